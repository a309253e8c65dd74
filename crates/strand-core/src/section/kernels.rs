//! The planar law's inlined wire loops: the slider of `slider.rs` over a station's parallel
//! arrays, for the `continuous` and `hysteretic` laws, one layer at a time.

use super::PlanarResponse;
use super::layer_law::LayerLaw;
use super::slip_work::trapezoid;

/// The planar law's per-wire constants of a station, as parallel arrays.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct PlanarWires {
    pub lever: Vec<f64>,
    pub gain_pos: Vec<f64>,
    pub gain_neg: Vec<f64>,
    /// The smallest gain of either side over the wires (infinite without wires): where
    /// `scale * gain_min > 0` every wire has both friction limits, and the kernels skip the
    /// test for a wire without any ([`planar_continuous`]).
    pub gain_min: f64,
    /// sum_i l_i^2 (m^2): the layer's stick stiffness per unit spring `k`.
    pub lever_square: f64,
    /// The largest gain of either side per `k |l_i|` over the wires (1/(N m)); infinite where
    /// a wire has no lever (module `layer_state`).
    pub ratio_max: f64,
    /// 1 / |l_i| (1/m; infinite for a wire without lever).
    pub inv_lever: Vec<f64>,
}

/// What the wire loop of an accepted iterate tells of a layer's closed form (module
/// `layer_state`), summed alongside the books.
#[derive(Debug, Clone, Copy)]
pub(super) struct LayerTally {
    /// Wires that slipped.
    pub moved: usize,
    /// Slipping wires whose side sigma_i has the sign of their lever l_i.
    pub along: usize,
    /// The smallest distance of a sticking wire's elastic force from its friction limits per
    /// |l_i| (N/m).
    pub margin: f64,
    /// sum_i s_i l_i over the sticking wires (m).
    pub residual: f64,
    /// sum_i sigma_i g_i l_i over the slipping wires (m).
    pub per_scale: f64,
}

impl Default for LayerTally {
    fn default() -> Self {
        LayerTally {
            moved: 0,
            along: 0,
            margin: f64::INFINITY,
            residual: 0.0,
            per_scale: 0.0,
        }
    }
}

/// [`planar_continuous`] with the per-wire test for a wire without friction limits only where
/// the station's smallest gain times the friction scale leaves one possible.
#[inline(always)]
pub(super) fn continuous_wires<const BOOKS: bool>(
    law: &LayerLaw,
    p: &PlanarWires,
    kappa: f64,
    scale: f64,
    dscale: f64,
    r: &mut PlanarResponse,
) {
    let (k, ik) = (law.k, law.inv_k);
    if scale * p.gain_min > 0.0 {
        planar_continuous::<false, BOOKS>(k, ik, p, kappa, scale, dscale, r);
    } else {
        planar_continuous::<true, BOOKS>(k, ik, p, kappa, scale, dscale, r);
    }
}

/// [`planar_hysteretic`] with the free-wire test chosen as in [`continuous_wires`]; `TALLY`
/// (with `BOOKS`): sum the layer's closed-form data into `tally`. The scales are the
/// friction-limit scale at the strain, its strain derivative and the scale at the committed
/// strain (the slip work's trapezoid, module `slip_work`; read with `BOOKS` only).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn hysteretic_wires<const BOOKS: bool, const TALLY: bool>(
    law: &LayerLaw,
    p: &PlanarWires,
    kappa: f64,
    (scale, dscale, scale_old): (f64, f64, f64),
    slip: &[f64],
    trial: &mut [f64],
    r: &mut PlanarResponse,
    tally: &mut LayerTally,
) {
    let (k, ik) = (law.k, law.inv_k);
    let scales = (scale, dscale, scale_old);
    if scale * p.gain_min > 0.0 {
        planar_hysteretic::<false, BOOKS, TALLY>(k, ik, p, kappa, scales, slip, trial, r, tally);
    } else {
        planar_hysteretic::<true, BOOKS, TALLY>(k, ik, p, kappa, scales, slip, trial, r, tally);
    }
}

/// The wires' part of [`super::SectionLaw::planar`] for the `continuous` law, added to `r`: the
/// slider of `slider.rs` inlined over parallel arrays (the same values, summed in the same
/// order), without the per-wire law dispatch and optional slip state of the generic loop.
/// `FREE`: whether a wire may have no friction limit on either side (otherwise the caller
/// has checked that none has, and the test per wire is left out). `BOOKS`: whether the
/// energy, `dE/deps`, `dM/deps` and the slipping wires are summed (else only the moment and
/// its curvature tangent, the same values).
#[inline(always)]
fn planar_continuous<const FREE: bool, const BOOKS: bool>(
    k: f64,
    inv_k: f64,
    w: &PlanarWires,
    kappa: f64,
    scale: f64,
    dscale: f64,
    r: &mut PlanarResponse,
) {
    let n = w.lever.len();
    let (lev, gp, gn) = (&w.lever[..n], &w.gain_pos[..n], &w.gain_neg[..n]);
    for i in 0..n {
        let lever = lev[i];
        let e = lever * kappa;
        let (cap_pos, cap_neg) = (scale * gp[i], scale * gn[i]);
        let stick_force = k * e;
        // Slipping on the stretched (k e > cap_pos) or the shortened (k e < -cap_neg) side;
        // without friction limits at any strain (see `slider`).
        let free = FREE && cap_pos == 0.0 && cap_neg == 0.0;
        let pos = stick_force > cap_pos || (free && stick_force >= 0.0);
        let neg = stick_force < -cap_neg;
        if !(pos || neg) {
            r.moment += stick_force * lever;
            r.moment_curvature += k * lever * lever;
            if BOOKS {
                r.energy += 0.5 * stick_force * stick_force * inv_k;
            }
            continue;
        }
        // Held at the limit: energy 1/2 k e_c^2 + cap (|e| - e_c), e_c = cap / k.
        let (cap, gain, sign) = if pos {
            (cap_pos, gp[i], 1.0)
        } else {
            (cap_neg, gn[i], -1.0)
        };
        r.moment += sign * cap * lever;
        if BOOKS {
            let ec = cap * inv_k;
            r.moment_strain += sign * gain * dscale * lever;
            r.energy += 0.5 * cap * ec + cap * (e.abs() - ec);
            r.energy_strain += (e.abs() - ec) * (gain * dscale);
            r.slipping += 1;
        }
    }
}

/// The wires' part of [`super::SectionLaw::planar`] for the `hysteretic` law (return mapping from the
/// committed `slip` into `trial`), added to `r`: the slider of `slider.rs` inlined over
/// parallel arrays (the same values, summed in the same order). `FREE` and `BOOKS` as for
/// [`planar_continuous`]; without the books `trial` is not written (it may be empty).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn planar_hysteretic<const FREE: bool, const BOOKS: bool, const TALLY: bool>(
    k: f64,
    inv_k: f64,
    w: &PlanarWires,
    kappa: f64,
    (scale, dscale, scale_old): (f64, f64, f64),
    slip: &[f64],
    trial: &mut [f64],
    r: &mut PlanarResponse,
    tally: &mut LayerTally,
) {
    let n = w.lever.len();
    let (lev, gp, gn) = (&w.lever[..n], &w.gain_pos[..n], &w.gain_neg[..n]);
    let slip = &slip[..n];
    let trial = if BOOKS { &mut trial[..n] } else { &mut [][..] };
    for i in 0..n {
        let lever = lev[i];
        let e = lever * kappa;
        let (cap_pos, cap_neg) = (scale * gp[i], scale * gn[i]);
        let committed = slip[i];
        let elastic = k * (e - committed);
        let free = FREE && cap_pos == 0.0 && cap_neg == 0.0;
        let pos = elastic > cap_pos || (free && elastic >= 0.0);
        let neg = elastic < -cap_neg;
        if !(pos || neg) {
            r.moment += elastic * lever;
            r.moment_curvature += k * lever * lever;
            if BOOKS {
                trial[i] = committed;
                r.energy += 0.5 * elastic * elastic * inv_k;
            }
            if TALLY {
                let (a, b) = (cap_pos - elastic, elastic + cap_neg);
                let margin = (if a < b { a } else { b }) * w.inv_lever[i];
                tally.margin = if margin < tally.margin {
                    margin
                } else {
                    tally.margin
                };
                tally.residual += committed * lever;
            }
            continue;
        }
        // Return mapping: the slip puts the wire on its friction limit. The stored energy is
        // 1/2 F^2 / k; the slip work books the energy change of a moving limit (no
        // energy_strain term), by the trapezoid of the limit over the step.
        let (cap, gain, force) = if pos {
            (cap_pos, gp[i], cap_pos)
        } else {
            (cap_neg, -gn[i], -cap_neg)
        };
        r.moment += force * lever;
        if BOOKS {
            let cap_old = scale_old * if pos { gp[i] } else { gn[i] };
            let s = e - force * inv_k;
            trial[i] = s;
            r.moment_strain += gain * dscale * lever;
            r.energy += 0.5 * cap * cap * inv_k;
            r.slip_work += trapezoid(cap, cap_old, s - committed);
            r.slipping += 1;
        }
        if TALLY {
            tally.moved += 1;
            tally.along += usize::from(pos == (lever > 0.0));
            tally.per_scale += gain * lever;
        }
    }
}
