//! A layer whose wires all stick, or all slip, in closed form (planar `hysteretic` law of a
//! strand of several layers).
//!
//! At the accepted iterate of a step the planar law writes, after each layer's slips, what
//! the next step's Newton iterations need to evaluate the layer without visiting its wires
//! (summed by the wire loop of the books, `kernels::LayerTally`):
//! the curvature `kappa_r` (1/m) and friction-limit scale `c_r` (N) it was committed at, and
//!
//! * for a layer whose wires all stuck (no slip changed): the smallest distance `D` (1/m) of
//!   any wire's elastic force from its friction limits, in curvature per wire lever, and the
//!   residual moment `P = k sum_i s_i l_i` (N m) of the committed slips. With `dk = kappa -
//!   kappa_r`, `dc = c - c_r` and `rho` the station's largest gain per `k |l_i|` (1/(N m)), a
//!   wire's elastic force moves by at most `k |l_i| (|dk| + rho |dc|)` towards a limit that
//!   moves by `g_i |dc|`, so while `|dk| + rho |dc| < D` every wire still sticks and the
//!   layer adds `k kappa sum_i l_i^2 - P` to the moment and `k sum_i l_i^2` to its tangent;
//! * for a layer whose wires all slipped, each on the side `sigma_i` with `sigma_i sign(l_i)`
//!   the same `sigma` for all: each wire was on its limit, and it slips on while its elastic
//!   force grows faster than its limit, `sigma_i k l_i dk > g_i dc`, which holds for every
//!   wire while `sigma dk > 0` and `sigma dk > rho dc`; the layer then adds `c C` to the
//!   moment, `C = sum_i sigma_i g_i l_i` (m), and nothing to its tangent.
//!
//! Otherwise the layer's wires are visited (module `kernels`). The tests are sufficient
//! conditions, so the closed form gives the wire loop's moment and tangent up to the
//! rounding of the sums. The books (energy, slip work, trial slips) of the accepted iterate
//! always come from the wire loop.

use super::kernels::{LayerTally, PlanarWires};
use super::layer_law::LayerLaw;

/// Values per layer: kind, `kappa_r`, `c_r`, then `D` and `P` (stick) or `sigma` and `C`
/// (slip).
pub(super) const LAYER_STATE: usize = 5;

const NONE: f64 = 0.0;
const STICK: f64 = 1.0;
const SLIP: f64 = 2.0;

/// Writes the layer's closed-form state into `out` ([`LAYER_STATE`] values) at the accepted
/// curvature `kappa` and scale `scale`, from what the wire loop summed into `tally` while it
/// wrote the trial slips.
pub(super) fn commit(
    law: &LayerLaw,
    p: &PlanarWires,
    kappa: f64,
    scale: f64,
    tally: &LayerTally,
    out: &mut [f64],
) {
    out.fill(NONE);
    let limited = scale * p.gain_min > 0.0 && p.ratio_max.is_finite();
    let n = p.lever.len();
    if !limited || n == 0 {
        return;
    }
    let k = law.k;
    if tally.moved == 0 {
        let d = tally.margin / k;
        if d > 0.0 {
            out.copy_from_slice(&[STICK, kappa, scale, d, k * tally.residual]);
        }
    } else if tally.moved == n && (tally.along == n || tally.along == 0) {
        let sigma = if tally.along == n { 1.0 } else { -1.0 };
        out.copy_from_slice(&[SLIP, kappa, scale, sigma, tally.per_scale]);
    }
}

/// The layer's moment and curvature tangent (N m, N m^2) at `kappa` and `scale` from its
/// committed closed-form state `state`, if the state's test holds (module docs); `None` when
/// the wires must be visited.
#[inline(always)]
pub(super) fn closed_form(
    law: &LayerLaw,
    p: &PlanarWires,
    kappa: f64,
    scale: f64,
    state: &[f64],
) -> Option<(f64, f64)> {
    let kind = state[0];
    // Every wire has both friction limits (false for NaN too).
    let limited = scale * p.gain_min > 0.0;
    if kind == NONE || !limited {
        return None;
    }
    let (dk, dc) = (kappa - state[1], scale - state[2]);
    if kind == STICK {
        let k_stick = law.k * p.lever_square;
        (dk.abs() + p.ratio_max * dc.abs() < state[3])
            .then(|| (k_stick * kappa - state[4], k_stick))
    } else if kind == SLIP {
        let turn = state[3] * dk;
        (turn > 0.0 && turn > p.ratio_max * dc).then(|| (scale * state[4], 0.0))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::section::{LawKind, SectionLaw, Station};
    use crate::{LayDirection, Strand, StrandSpec};
    use proptest::prelude::*;

    /// The paper's strand (core 3 mm, six 2 mm wires at 20 deg) with a layer of twelve 2 mm
    /// wires laid the other way at 15 deg and one of eighteen laid as the first at 12 deg.
    fn three_layers() -> Strand {
        let mut spec = StrandSpec::paper(1.0, 2.0e9, 5747.0);
        let mut second = spec.layers[0];
        second.wires = 12;
        second.lay_angle = 15f64.to_radians();
        second.direction = LayDirection::Left;
        let mut third = spec.layers[0];
        third.wires = 18;
        third.lay_angle = 12f64.to_radians();
        spec.layers.extend([second, third]);
        Strand::new(spec).unwrap()
    }

    /// The moment and tangent of [`SectionLaw::planar_moment`] (closed form where a layer's
    /// state allows) against the wire loop of [`SectionLaw::planar`] at the same point, with
    /// a bound on the rounding of two orders of summation: 4 n eps_machine times the sum of
    /// the magnitudes of the terms. Returns the closed-form layers' kinds counted.
    fn agree(law: &SectionLaw, st: &Station, eps: f64, kappa: f64, slip: &[f64]) -> [usize; 2] {
        let mut scratch = vec![0.0; slip.len()];
        let fast = law.planar_moment(st, eps, kappa, slip);
        let full = law.planar(st, eps, kappa, slip, &mut scratch);
        let n = law.sliders();
        let (mut magnitude, mut first, mut hits) = (law.base_bending * kappa.abs(), 0, [0; 2]);
        let states = slip[n + crate::section::STATION_TAIL..].chunks_exact(LAYER_STATE);
        for ((l, p), s) in law.layers.iter().zip(&st.planar).zip(states) {
            let scale = l.cap_scale(eps).0;
            for (i, lever) in p.lever.iter().enumerate() {
                let caps = scale * (p.gain_pos[i] + p.gain_neg[i]);
                let stick = l.k * (lever * kappa).abs() + l.k * slip[first + i].abs();
                magnitude += (caps + stick) * lever.abs();
            }
            first += p.lever.len();
            if closed_form(l, p, kappa, scale, s).is_some() {
                hits[usize::from(s[0] == SLIP)] += 1;
            }
        }
        let bound = 4.0 * n as f64 * f64::EPSILON * magnitude;
        assert!(
            (fast.moment - full.moment).abs() <= bound,
            "moment {} against the wire loop's {} (bound {bound:e})",
            fast.moment,
            full.moment
        );
        let k_bound = 4.0 * n as f64 * f64::EPSILON * law.stick_bending_stiffness();
        assert!(
            (fast.moment_curvature - full.moment_curvature).abs() <= k_bound,
            "tangent {} against the wire loop's {}",
            fast.moment_curvature,
            full.moment_curvature
        );
        hits
    }

    /// A loading path of accepted steps (the state committed at each) with iterates around
    /// each: every iterate's moment and tangent are the wire loop's.
    fn walk(law: &SectionLaw, x: f64, path: &[(f64, f64, f64, f64)]) -> [usize; 2] {
        let st = law.station(x);
        let mut slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        let mut hits = [0; 2];
        let (mut eps, mut kappa) = (3e-4, 0.0);
        for &(dk, de, pk, pe) in path {
            eps = (eps + de).clamp(-1e-4, 6e-4);
            kappa += dk;
            law.planar(&st, eps, kappa, &slip, &mut trial);
            slip.copy_from_slice(&trial);
            for f in [0.01, 0.1, 1.0] {
                let h = agree(law, &st, eps + f * pe, kappa + f * pk, &slip);
                hits = [hits[0] + h[0], hits[1] + h[1]];
            }
        }
        hits
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]
        /// Any path of bending (curvature steps of up to 0.05 1/m, strain steps of up to
        /// 3e-5): the closed-form layers give the wire loop's moment and tangent.
        #[test]
        fn closed_form_layers_give_the_wire_loop(
            x in 0.0..0.3f64,
            path in prop::collection::vec(
                (-0.05..0.05f64, -3e-5..3e-5f64, -0.01..0.01f64, -1e-5..1e-5f64),
                1..40,
            ),
        ) {
            let law = SectionLaw::new(&three_layers(), LawKind::Hysteretic);
            walk(&law, x, &path);
        }
    }

    /// A bending cycle with small iterates: both closed forms are taken (all wires of a layer
    /// sticking after a reversal, all slipping on loading), and agree with the wire loop;
    /// the tangent is the moment's finite difference where the closed form holds on both
    /// sides.
    #[test]
    fn a_bending_cycle_takes_both_closed_forms() {
        let law = SectionLaw::new(&three_layers(), LawKind::Hysteretic);
        let path: Vec<_> = (0..240)
            .map(|j| {
                let dk = if (j / 60) % 2 == 0 { 2e-3 } else { -2e-3 };
                (dk, 1e-7, 0.3 * dk, 1e-8)
            })
            .collect();
        let hits = walk(&law, 0.137, &path);
        assert!(hits[0] > 50 && hits[1] > 50, "closed forms taken: {hits:?}");
        // The tangent against the moment's central difference in a stuck state.
        let st = law.station(0.137);
        let mut slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        law.planar(&st, 3e-4, 0.01, &slip, &mut trial);
        slip.copy_from_slice(&trial);
        law.planar(&st, 3e-4, 0.009, &slip, &mut trial);
        slip.copy_from_slice(&trial);
        let h = 1e-6;
        let m = |k: f64| law.planar_moment(&st, 3e-4, k, &slip).moment;
        let t = law.planar_moment(&st, 3e-4, 0.009, &slip).moment_curvature;
        let fd = (m(0.009 + h) - m(0.009 - h)) / (2.0 * h);
        assert!((fd - t).abs() <= 1e-6 * t, "tangent {t} against {fd}");
    }
}
