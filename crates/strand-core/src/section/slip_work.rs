//! The slip work a step books (`hysteretic` law): the trapezoid of the friction limit over
//! the step.
//!
//! A wire slipping from slip `s_old` to `s` dissipates `int cap |ds|` (SPEC 2), and its
//! friction limit `cap` moves with the tension the section reads (and, in 3D, with the bending
//! direction) over the step. Booked at the limit of the step's end, `cap |s - s_old|`, the
//! books differ from that integral by `(cap - cap_old) |ds| / 2` per step: O(h^2) per step,
//! O(h) over a run, a first-order term in the energy balance of every hysteretic run whose
//! tension moves. The trapezoid `(cap_old + cap) / 2 |s - s_old|` is the quadrature that
//! makes the books consistent with the work the slider's force does over the step: for a wire
//! on its limit at both ends (`F_old = cap_old`, `F = cap`, `F = k (e - s)`) the stored energy
//! `F^2 / (2 k)` changes by `(F_old + F) / 2 (de - ds)`, so the trapezoid of the force over the
//! strain increment, `(F_old + F) / 2 de`, is the stored energy's change plus this booking
//! exactly; for a wire that starts to slip within the step the two differ by `(F_old -
//! cap_old) |ds| / 2`, O(h^2) once per switch. The balance of a run is then the integrator's
//! second-order error alone.
//!
//! The limit of the step's start is the law's at the committed strain (stored in the state
//! after the bending direction, [`STRAIN_STATE`]) and, in 3D, at the committed bending
//! direction; the wire's side is the side it slips on at the step's end.

/// State values per station that hold the committed axial strain (after the stored bending
/// direction): the strain of the step's start, at which the slip work's trapezoid takes the
/// friction limit. Zero (the straight reference's strain) before the first step.
pub(super) const STRAIN_STATE: usize = 1;

/// The slip work (J/m) of a slip `ds` under a friction limit that moves from `cap_old` to
/// `cap` (N) over the step: the trapezoid `(cap_old + cap) / 2 |ds|` (module docs).
#[inline(always)]
pub(super) fn trapezoid(cap: f64, cap_old: f64, ds: f64) -> f64 {
    0.5 * (cap + cap_old) * ds.abs()
}
