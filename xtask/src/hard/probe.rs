//! Test support: the observed stability limit of Stoermer-Verlet, found by bisection.
//!
//! The solver refuses a step above its estimate, so this probe integrates with its own
//! minimal Verlet loop (same beam, same mass matrix, same forces, no step check): from rest
//! under the beam's gravity, a step is stable when the velocities stay bounded over a fixed
//! number of steps. Above the limit h omega_max > 2 the highest mode grows by a factor of at
//! least 1 + 2 sqrt(2 delta) per step (delta the relative excess), so a few thousand steps
//! separate stable from unstable steps to well under 1 %.

use strand_ancf::band::BandSolver;
use strand_ancf::beam::Beam;

/// Velocity (m/s, or 1/s for slope coordinates) beyond which a run counts as blown up: far
/// above anything a strand released from rest reaches in the few milliseconds of a probe.
const BLOW_UP_SPEED: f64 = 1e3;

/// Whether Verlet with step `h` (s) stays bounded for `steps` steps from rest.
pub fn verlet_bounded(beam: &Beam, h: f64, steps: usize) -> bool {
    let nf = beam.dofs();
    let free: Vec<(usize, usize)> = (0..beam.coords())
        .filter_map(|g| beam.free_index(g).map(|i| (g, i)))
        .collect();
    let mut mass = BandSolver::default();
    if !mass.factorize(beam.mass()) {
        return false;
    }
    let mut q = beam.reference().to_vec();
    let mut slip = vec![0.0; beam.state_len()];
    let mut trial = slip.clone();
    let mut force = vec![0.0; beam.coords()];
    let mut v = vec![0.0; nf];
    let mut a = vec![0.0; nf];
    let g = beam.gravity_force().to_vec();
    let mut accel = |q: &[f64], slip: &[f64], trial: &mut [f64], a: &mut [f64]| -> bool {
        if beam
            .internal(q, slip, trial, &mut force, None, None)
            .is_err()
        {
            return false;
        }
        for &(gi, i) in &free {
            a[i] = g[gi] - force[gi];
        }
        mass.solve(a);
        a.iter().all(|x| x.is_finite())
    };
    if !accel(&q, &slip, &mut trial, &mut a) {
        return false;
    }
    for _ in 0..steps {
        for i in 0..nf {
            v[i] += 0.5 * h * a[i];
        }
        for &(gi, i) in &free {
            q[gi] += h * v[i];
        }
        if !accel(&q, &slip, &mut trial, &mut a) {
            return false;
        }
        slip.copy_from_slice(&trial);
        for i in 0..nf {
            v[i] += 0.5 * h * a[i];
        }
        if !v.iter().all(|x| x.is_finite() && x.abs() < BLOW_UP_SPEED) {
            return false;
        }
    }
    true
}

/// The observed stability limit (s): the largest step found stable by bisection between
/// `estimate / 4` and the first unstable multiple of `estimate` (up to 64), to a relative
/// width `rel`. `None` when no bracket is found.
pub fn observed_limit(beam: &Beam, estimate: f64, steps: usize, rel: f64) -> Option<f64> {
    let mut lo = 0.25 * estimate;
    if !verlet_bounded(beam, lo, steps) {
        return None;
    }
    let mut hi = estimate;
    while verlet_bounded(beam, hi, steps) {
        lo = hi;
        hi *= 2.0;
        if hi > 64.0 * estimate {
            return None;
        }
    }
    while hi - lo > rel * lo {
        let mid = 0.5 * (lo + hi);
        if verlet_bounded(beam, mid, steps) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}
