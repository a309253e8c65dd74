//! One helical wire as a spring in series with a friction slider (paper eqs. (18)-(23)).
//!
//! The slider works on the wire's bending strain `e`: the strain, projected on the strand
//! axis, that strand bending imposes on the wire when it sticks to the core (eq. (18) divided
//! by cos^2(alpha) and projected back). With the wire's projected axial stiffness
//! `k = eta E_w A_w` the stick force is `F = k e` (eqs. (19), (22a)); friction caps it at
//! `cap_pos` when the wire is stretched and at `cap_neg` when it is shortened (eqs. (20),
//! (22b)). The moment of the wire about the strand axis is `F` times its lever arm, so the
//! per-wire laws of SPEC 2 follow from this one force law.

use super::LawKind;
use super::slip_work::trapezoid;

/// State of a wire's contact with the core.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum WireState {
    /// The wire moves with the core: it carries the full stick stiffness.
    Stick,
    /// The wire slides on the core: its force is the friction limit.
    Slip,
}

/// Force of one wire's slider for a given bending strain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SliderForce {
    /// Strand-axial force increment in the wire (N).
    pub force: f64,
    /// dF/de (N).
    pub d_strain: f64,
    /// dF/dcap_pos (-): 1 while slipping on the stretched side.
    pub d_cap_pos: f64,
    /// dF/dcap_neg (-): -1 while slipping on the shortened side.
    pub d_cap_neg: f64,
    /// Stored energy per unit strand length (J/m).
    pub energy: f64,
    /// d energy / d cap of the active side at fixed strain and slip (m/m): the slider's
    /// energy depends on the friction limit, which depends on the strand's axial strain.
    pub d_energy_cap: f64,
    /// Work dissipated by the slip of this trial step from the committed slip (J/m): the
    /// trapezoid of the friction limit over the step (module `slip_work`).
    pub slip_work: f64,
    /// Slip strain after the trial (hysteretic law; unchanged for the others).
    pub slip: f64,
    /// Stick or slip.
    pub state: WireState,
}

/// Evaluates the slider. `k` is eta E_w A_w (N), `e` the bending strain, `cap_pos >= 0` and
/// `cap_neg >= 0` the friction limits of the force (N), `paper_factor` = cos^2(alpha) (the
/// ratio of the slip force to the stick force at the `paper` law's switch, eq. (23)), `slip`
/// the committed slip strain and `cap_old(positive)` the friction limit of the stretched
/// (`true`) or shortened side at the step's start (N), which the slip work's trapezoid reads
/// (hysteretic law only, called only for a slipping wire; module `slip_work`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn slider(
    kind: LawKind,
    k: f64,
    e: f64,
    cap_pos: f64,
    cap_neg: f64,
    paper_factor: f64,
    slip: f64,
    cap_old: impl FnOnce(bool) -> f64,
) -> SliderForce {
    // Loop-invariant where the slider is inlined into a loop over wires: no division per wire.
    let inv_k = 1.0 / k;
    let stick = |f: f64, slip: f64| SliderForce {
        force: f,
        d_strain: k,
        d_cap_pos: 0.0,
        d_cap_neg: 0.0,
        energy: 0.5 * f * f * inv_k,
        d_energy_cap: 0.0,
        slip_work: 0.0,
        slip,
        state: WireState::Stick,
    };
    // Force held at the friction limit on the side of `e`.
    let sliding = |positive: bool,
                   (energy, d_energy_cap): (f64, f64),
                   slip: f64,
                   slip_work: f64| SliderForce {
        force: if positive { cap_pos } else { -cap_neg },
        d_strain: 0.0,
        d_cap_pos: if positive { 1.0 } else { 0.0 },
        d_cap_neg: if positive { 0.0 } else { -1.0 },
        energy,
        d_energy_cap,
        slip_work,
        slip,
        state: WireState::Slip,
    };
    // Without friction limits (no tension presses the wire on the core) the wire carries no
    // force at any strain: it slips, also at zero strain, where the stick branch would give
    // the tangent a stiffness the force never has.
    let free = cap_pos == 0.0 && cap_neg == 0.0;
    match kind {
        LawKind::Constant => stick(0.0, slip),
        LawKind::Continuous => {
            let cap = if e >= 0.0 { cap_pos } else { cap_neg };
            if k * e.abs() <= cap && !free {
                stick(k * e, slip)
            } else {
                // Energy: integral of the moment, 1/2 k e_c^2 + cap (|e| - e_c), e_c = cap / k,
                // i.e. cap |e| - cap^2 / (2 k).
                let ec = cap * inv_k;
                let energy = 0.5 * cap * ec + cap * (e.abs() - ec);
                sliding(e >= 0.0, (energy, e.abs() - ec), slip, 0.0)
            }
        }
        LawKind::Paper => {
            let cap = if e >= 0.0 { cap_pos } else { cap_neg };
            // eq. (23): the stick stress reaches the slip stress divided by cos^2(alpha).
            let ec = cap * inv_k / paper_factor;
            if e.abs() <= ec && !free {
                stick(k * e, slip)
            } else {
                // 1/2 k e_c^2 + cap (|e| - e_c) with e_c = cap / (k cos^2 alpha).
                let energy = 0.5 * k * ec * ec + cap * (e.abs() - ec);
                let d_cap = ec / paper_factor + e.abs() - 2.0 * ec;
                sliding(e >= 0.0, (energy, d_cap), slip, 0.0)
            }
        }
        LawKind::Hysteretic => {
            let trial = k * (e - slip);
            if trial > cap_pos || (free && trial >= 0.0) {
                let s = e - cap_pos * inv_k;
                // The slip work books the energy change of a moving limit: no cap term.
                sliding(
                    true,
                    (0.5 * cap_pos * cap_pos * inv_k, 0.0),
                    s,
                    trapezoid(cap_pos, cap_old(true), s - slip),
                )
            } else if trial < -cap_neg {
                let s = e + cap_neg * inv_k;
                sliding(
                    false,
                    (0.5 * cap_neg * cap_neg * inv_k, 0.0),
                    s,
                    trapezoid(cap_neg, cap_old(false), s - slip),
                )
            } else {
                stick(trial, slip)
            }
        }
    }
}
