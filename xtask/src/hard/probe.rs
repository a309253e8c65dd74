//! Test support: the observed stability limit of Stoermer-Verlet, found by bisection.
//!
//! The solver refuses a step above its estimate, so this probe integrates with its own
//! minimal Verlet loop (same beam, same mass matrix, same forces, no step check): from given
//! start states under the beam's gravity, a step is stable when the velocities stay bounded
//! over a fixed number of steps from every start. The start states matter with the stick/slip
//! laws: released from rest the strand has no tension, every wire slips and the beam is at
//! its softest; hanging straight at rest (where a damped pendulum ends) the tension makes
//! every wire stick, and the beam is at its stiffest. Above the limit h omega_max > 2 the highest mode grows by a factor of at
//! least 1 + 2 sqrt(2 delta) per step (delta the relative excess), so a few thousand steps
//! separate stable from unstable steps to well under 1 %.

use strand_ancf::band::BandSolver;
use strand_ancf::beam::{Beam, Evaluation, PointState};
use strand_ancf::dynamics::non_potential_work;

/// Velocity (m/s, or 1/s for slope coordinates) beyond which a run counts as blown up: far
/// above anything a strand released from rest reaches in the few milliseconds of a probe.
const BLOW_UP_SPEED: f64 = 1e3;

/// Largest energy balance error of a stable probe, relative to the potential drop of the
/// strand from its reference to hanging. Measured on the 128-element section-3 pendulum over
/// 3000 steps: below the limit 1e-11 to 1e-9 from every start; 1 % above it 5e-6 to 1e-4
/// (the churning mode), so the limit sits well inside the gap.
const BALANCE: f64 = 1e-6;

/// Velocity perturbation of every free coordinate at the start (m/s, or 1/s for slopes).
const SEED: f64 = 1e-6;

/// A start state of the probe: all coordinates and all velocities (supported ones ignored).
#[derive(Debug, Clone)]
pub struct Start {
    /// Coordinates (m, and - for slopes).
    pub q: Vec<f64>,
    /// Velocities (m/s, and 1/s for slopes).
    pub v: Vec<f64>,
}

impl Start {
    /// At rest in the reference configuration.
    pub fn rest(beam: &Beam) -> Start {
        Start {
            q: beam.reference().to_vec(),
            v: vec![0.0; beam.coords()],
        }
    }

    /// At rest hanging straight from the first node along gravity: the reference
    /// configuration turned about the first node (positions and slopes alike).
    pub fn hanging(beam: &Beam) -> Start {
        let dim = beam.node_coords() / 2;
        let d = beam.spec().direction;
        let g = beam.spec().gravity;
        let gn = g.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut q = beam.reference().to_vec();
        if gn > 0.0 {
            let g = g.map(|x| x / gn);
            let rotate = rotation(d, g);
            let pin: Vec<f64> = q[..dim].to_vec();
            for node in q.chunks_mut(2 * dim) {
                let mut p = [0.0; 3];
                let mut t = [0.0; 3];
                for i in 0..dim {
                    p[i] = node[i] - pin[i];
                    t[i] = node[dim + i];
                }
                let (p, t) = (rotate(p), rotate(t));
                for i in 0..dim {
                    node[i] = pin[i] + p[i];
                    node[dim + i] = t[i];
                }
            }
        }
        Start {
            q,
            v: vec![0.0; beam.coords()],
        }
    }
}

/// The rotation taking unit vector `a` to unit vector `b` (Rodrigues; a half turn about an
/// axis normal to `a` in the xy-plane when they are opposite).
fn rotation(a: [f64; 3], b: [f64; 3]) -> impl Fn([f64; 3]) -> [f64; 3] {
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let c: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
    let mut k = cross(a, b);
    let s = k.iter().map(|x| x * x).sum::<f64>().sqrt();
    if s > 1e-12 {
        k = k.map(|x| x / s);
    } else {
        // Parallel (no turn) or opposite (half turn about z, which keeps planar beams planar).
        k = [0.0, 0.0, 1.0];
    }
    let (s, c) = if s > 1e-12 { (s, c) } else { (0.0, c.signum()) };
    move |v: [f64; 3]| {
        let kv = cross(k, v);
        let kdv: f64 = k.iter().zip(&v).map(|(x, y)| x * y).sum();
        std::array::from_fn(|i| v[i] * c + kv[i] * s + k[i] * kdv * (1.0 - c))
    }
}

/// Whether Verlet with step `h` (s) stays stable for `steps` steps from `start` (the slip
/// state starts at zero: wires stick until their friction limit): the velocities stay
/// bounded and the energy balance (kinetic + gravity + elastic + dissipated) stays within
/// [`BALANCE`] of `scale` (J). With the stick/slip laws an unstable mode does not always
/// blow up: it grows until its wires slip, which softens it, and then churns at that
/// amplitude, feeding slip; the balance catches it.
pub fn verlet_stable(beam: &Beam, h: f64, steps: usize, start: &Start, scale: f64) -> bool {
    let nf = beam.dofs();
    let free: Vec<(usize, usize)> = (0..beam.coords())
        .filter_map(|g| beam.free_index(g).map(|i| (g, i)))
        .collect();
    let mut mass = BandSolver::default();
    if !mass.factorize(beam.mass()) {
        return false;
    }
    let mut q = start.q.clone();
    let mut slip = beam.initial_state();
    let mut trial = slip.clone();
    let mut force = vec![0.0; beam.coords()];
    let mut v = vec![0.0; nf];
    // A seed of 1e-6 m/s with alternating signs puts every mode, the highest included, in
    // motion: a straight hanging strand would otherwise never leave its plane of symmetry.
    for (k, &(gi, i)) in free.iter().enumerate() {
        v[i] = start.v[gi] + if k % 2 == 0 { SEED } else { -SEED };
    }
    let mut a = vec![0.0; nf];
    let mut mv = vec![0.0; nf];
    let mut pts = vec![PointState::default(); beam.points()];
    let mut pts_new = pts.clone();
    let g = beam.gravity_force().to_vec();
    let mut accel = |q: &[f64],
                     slip: &[f64],
                     trial: &mut [f64],
                     a: &mut [f64],
                     pts: &mut [PointState]|
     -> Option<Evaluation> {
        let ev = beam
            .internal(q, slip, trial, &mut force, None, Some(pts))
            .ok()?;
        for &(gi, i) in &free {
            a[i] = g[gi] - force[gi];
        }
        mass.solve(a);
        a.iter().all(|x| x.is_finite()).then_some(ev)
    };
    let total = |q: &[f64], v: &[f64], mv: &mut [f64], elastic: f64, dissipated: f64| {
        beam.mass().mul_vec(v, mv);
        let kinetic: f64 = 0.5 * v.iter().zip(mv.iter()).map(|(a, b)| a * b).sum::<f64>();
        let gravity: f64 = -q.iter().zip(&g).map(|(a, b)| a * b).sum::<f64>();
        kinetic + gravity + elastic + dissipated
    };
    let Some(ev) = accel(&q, &slip, &mut trial, &mut a, &mut pts) else {
        return false;
    };
    // The start's slip state is the friction limit reached from zero slip (a bent start
    // slips into place): committed before the clock starts.
    slip.copy_from_slice(&trial);
    let mut dissipated = 0.0;
    let e0 = total(&q, &v, &mut mv, ev.energy, dissipated);
    for _ in 0..steps {
        for i in 0..nf {
            v[i] += 0.5 * h * a[i];
        }
        for &(gi, i) in &free {
            q[gi] += h * v[i];
        }
        let Some(ev) = accel(&q, &slip, &mut trial, &mut a, &mut pts_new) else {
            return false;
        };
        slip.copy_from_slice(&trial);
        // Slip work and the non-potential work of the law (midpoint rule), as the solver
        // books them.
        dissipated += ev.slip_work + non_potential_work(&pts, &pts_new);
        std::mem::swap(&mut pts, &mut pts_new);
        for i in 0..nf {
            v[i] += 0.5 * h * a[i];
        }
        if !v.iter().all(|x| x.is_finite() && x.abs() < BLOW_UP_SPEED) {
            return false;
        }
        let e = total(&q, &v, &mut mv, ev.energy, dissipated);
        if (e - e0).is_nan() || (e - e0).abs() > BALANCE * scale {
            return false;
        }
    }
    true
}

/// The observed stability limit (s): the largest step found stable from every start by
/// bisection between
/// `estimate / 4` and the first unstable multiple of `estimate` (up to 64), to a relative
/// width `rel`. `None` when no bracket is found.
pub fn observed_limit(
    beam: &Beam,
    starts: &[Start],
    estimate: f64,
    steps: usize,
    rel: f64,
) -> Option<f64> {
    let scale = drop(beam);
    let verlet_bounded = |beam: &Beam, h: f64, steps: usize| {
        starts
            .iter()
            .all(|s| verlet_stable(beam, h, steps, s, scale))
    };
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

/// Potential drop of the strand from its reference configuration to hanging (J): the energy
/// scale of the probe.
pub fn drop(beam: &Beam) -> f64 {
    let hanging = Start::hanging(beam);
    hanging
        .q
        .iter()
        .zip(beam.reference())
        .zip(beam.gravity_force())
        .map(|((a, b), g)| (a - b) * g)
        .sum::<f64>()
        .abs()
}
