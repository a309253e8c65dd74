//! Static equilibrium by Newton-Raphson with adaptive load stepping, a trust region on the
//! increment and a backtracking line search.
//!
//! The unknowns are the segment poses (6 per segment, see [`crate::tangent`]); the residual is
//! the resultant force and torque on every segment. Gravity is applied in load steps of at
//! most `1 / load_steps` (halved after a failed step, from the last converged state); every
//! Newton increment is scaled down so that no segment turns by more than `max_rotation` (and
//! moves by more than `max_translation`); each step iterates until every segment's force is below
//! `tolerance F_ref + F_round` and every torque below `(tolerance F_ref + F_round) l_ref`, where
//! `F_ref` is the largest segment weight, `l_ref` the largest segment length and `F_round = 100 eps
//! x_max k_max` the force that 100 ulps of the largest coordinate make on the stiffest joint spring
//! (the round-off floor of the residual: joint gaps are differences of absolute positions). The
//! tangent is the assembled element stiffness, factored by a sparse LU. Contact histories are
//! frozen during the iterations of a load step and committed when it converges, so friction follows
//! the load path step by step.
//!
//! Active sets of the contact states (a study option, [`StaticOptions::active_set`], off by
//! default; models with wire-to-wire links only). A stiff normal penalty makes a contact's
//! loads smooth only within nanometres of relative motion, and a Newton step of a bending
//! increment moves wires by micrometres: plain Newton carries contacts across zero gap and
//! across the stick/slip limit from one iterate to the next and stalls. Here a load step is
//! solved on held contact states instead ([`crate::contact::Hold`]), each held through a whole
//! Newton solve: open (no force), stuck (the normal spring also carries tension, the tangential
//! spring has no cap) or slipping (`mu N` along a held direction). The first set: contacts open
//! at the first iterate held open, contacts closed at the last commit slipping without friction,
//! others by their state there. At a held solution the law is evaluated; the step is accepted
//! when the law leaves every segment within the residual allowance `tolerance F_ref + F_round`.
//! Otherwise every contact whose held force differs from the law's by more than the bound `B`
//! (from the residual allowance, divided by 4 while no contact differs by more) takes the law's
//! state and friction direction, the largest differences first, at most twice as many as were
//! taken in the last round; while a closed contact changes its friction, none is released (its
//! tension may come from friction past the cap). A held solve that stalls goes back to the
//! last held solution with half the changes. The histories are committed from the law.
//!
//! Penalty continuation ([`StaticOptions::penalty_stages`], off by default). A contact that is
//! open at an iterate adds nothing to the tangent, so where a soft wire span rests on a few
//! stiff contacts, a Newton step that opens them moves the span by the wire's own compliance
//! (micrometres) through contacts whose allowed penetration is nanometres, and the line search
//! cuts every step to a few thousandths (the 1+6+12 strand under tension at 1e-5 of the
//! diameter: 60 iterations, scaled residual 0.48). Each load step is then solved first with the
//! normal penalties a hundred and ten times softer, each solve starting from the one before:
//! a softer penalty lets the contacts find their states over larger motions, and the stiffer
//! solve starts from nearly its own active set. The stages only give the last solve its first
//! iterate: the contact histories are committed from the model's own penalty.

use nalgebra::{SMatrix, Vector3};

use crate::contact::{ContactLoad, ContactState, Hold};
use crate::model::{FineModel, ModelState, WireLoads, WireState};
use crate::so3;
use crate::sparse_tangent::SparseTangent;

/// Controls of the static solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// Number of equal load steps from zero to full gravity.
    pub load_steps: usize,
    /// Tolerance on the scaled residual (-).
    pub tolerance: f64,
    /// Newton iterations allowed per load step.
    pub max_iterations: usize,
    /// Step halvings allowed in the line search.
    pub max_backtracks: usize,
    /// Reference force F_ref (N) of the residual; `None`: the largest segment weight (or,
    /// without gravity, E A 1e-9 of the stiffest wire).
    pub force_scale: Option<f64>,
    /// Smallest load increment (fraction of the full load) tried after failed load steps
    /// before giving up (-).
    pub min_increment: f64,
    /// Largest rotation of a segment in one Newton iteration (rad).
    pub max_rotation: f64,
    /// Largest translation of a segment in one Newton iteration (m); `None`: no cap.
    pub max_translation: Option<f64>,
    /// The line search also accepts a step that lowers the total potential (Armijo). Right
    /// far from equilibrium on conservative loads; a slipping contact's force has no
    /// potential, so the potential is a merit function only while no contact slips: at a
    /// trial state with a slipping contact the line search accepts residual decrease only,
    /// whatever this flag. (With the potential it accepted steps that raise the residual and
    /// stalled: the Table 1 bending test at 10 N, 24 segments per pitch, took 780 Newton
    /// iterations to kappa = 0.59 1/m and failed at 1.21 1/m; with residual descent it takes
    /// 15 and 38.) The polish of a settled state ([`mod@crate::settle`]) turns it off.
    pub potential_descent: bool,
    /// Solve a load step of a model with wire-to-wire links on active sets of its contacts'
    /// states (module docs; a study option, off by default: on the 1+6+12 bending test with
    /// friction the sets do not settle). One-layer models, which have no links, are solved by
    /// plain Newton whatever this flag.
    pub active_set: bool,
    /// Penalty continuation (module docs; a study option for models with wire-to-wire
    /// links): each load step is first solved with every contact's normal penalty at
    /// `10^-k` of its own for `k` = this number down to 1, each
    /// solve from the equilibrium of the one before, without committing the contact
    /// histories; then with the model's own penalty. 0 (the default): the model's penalty
    /// only.
    pub penalty_stages: usize,
    /// A load step that has not converged after `max_iterations` is given another
    /// `max_iterations`, again and again, as long as the block just run at least halved the
    /// scaled residual (`false`, the default: `max_iterations` in all). The polish of a
    /// stalled multi-layer settle ([`crate::SettledOptions::polish_stalled`]) turns it on:
    /// there Newton crosses contacts at their kinks, where the line search stalls for a few
    /// iterations before the contact states settle and the convergence turns quadratic (the
    /// 1+6+12 cantilever at 48 segments a wire, 800,000 steps: 45 iterations, the residual
    /// falling from 7.7 to 2e-2 segment weights over the first 40).
    pub extend_while_falling: bool,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            load_steps: 5,
            tolerance: 1e-9,
            max_iterations: 40,
            max_backtracks: 20,
            force_scale: None,
            min_increment: 1e-4,
            max_rotation: 0.1,
            max_translation: None,
            potential_descent: true,
            active_set: false,
            penalty_stages: 0,
            extend_while_falling: false,
        }
    }
}

/// Outcome of a converged static solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticReport {
    /// Converged load steps (more than requested when increments were halved).
    pub load_steps: usize,
    /// Newton iterations over all load steps.
    pub iterations: usize,
    /// Final scaled residual `max(|F| / F_ref, |T| / (F_ref l_ref))` (-).
    pub residual: f64,
    /// Round-off allowance added to `tolerance F_ref` in the convergence test (N).
    pub roundoff: f64,
    /// Force scale F_ref of the residual (N).
    pub force_scale: f64,
    /// Moment scale F_ref l_ref of the residual (N m).
    pub moment_scale: f64,
}

/// Failure of the static solve.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticError {
    /// Newton did not reach the tolerance, even with the smallest load increment.
    #[error(
        "static solve did not converge at load step {step}: scaled residual {residual:.3e} \
         beyond load factor {load_factor:.6}"
    )]
    NotConverged {
        /// Load step (1-based).
        step: usize,
        /// Load factor of the last converged step (-).
        load_factor: f64,
        /// Scaled residual reached.
        residual: f64,
    },
    /// The tangent could not be factored (e.g. an unsupported rigid-body mode).
    #[error("singular tangent at load step {step} beyond load factor {load_factor:.6}: {message}")]
    Singular {
        /// Load step (1-based).
        step: usize,
        /// Load factor of the last converged step (-).
        load_factor: f64,
        /// Solver message.
        message: String,
    },
    /// A residual became NaN or infinite.
    #[error("non-finite residual at load step {step} beyond load factor {load_factor:.6}")]
    NonFinite {
        /// Load step (1-based).
        step: usize,
        /// Load factor of the last converged step (-).
        load_factor: f64,
    },
}

pub(crate) struct Scales {
    pub(crate) force: f64,
    pub(crate) moment: f64,
    pub(crate) force_allowance: f64,
    pub(crate) moment_allowance: f64,
    pub(crate) roundoff: f64,
    /// Tolerance on the scaled residual (-).
    pub(crate) tolerance: f64,
    /// Round-off of a position, 100 ulps of the largest coordinate (m).
    pub(crate) position_roundoff: f64,
}

/// Residual measures: (largest ratio to the allowance, 2-norm scaled by the reference
/// loads, largest scaled load).
pub(crate) fn residual_norms(loads: &[WireLoads], sc: &Scales) -> (f64, f64, f64) {
    let mut ratio: f64 = 0.0;
    let mut max: f64 = 0.0;
    let mut sq = 0.0;
    for l in loads {
        for (f, t) in l.forces.iter().zip(&l.torques) {
            let (f, t) = (f.norm(), t.norm());
            ratio = ratio
                .max(f / sc.force_allowance)
                .max(t / sc.moment_allowance);
            let (rf, rt) = (f / sc.force, t / sc.moment);
            max = max.max(rf).max(rt);
            sq += rf * rf + rt * rt;
        }
    }
    if !sq.is_finite() {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    (ratio, sq.sqrt(), max)
}

/// Total potential: spring and contact energies plus the potential of the (scaled) loads
/// (J).
fn potential(loads: &[WireLoads]) -> f64 {
    loads
        .iter()
        .map(|l| l.spring_energy + l.gravity_energy + l.contact_energy + l.friction_energy)
        .sum()
}

/// Whether a contact slips at the state the loads were computed at: its friction force is
/// then not the gradient of [`potential`].
fn slipping(loads: &[WireLoads]) -> bool {
    loads
        .iter()
        .flat_map(|l| l.contacts.iter())
        .any(|c| c.state == ContactState::Slip)
}

/// Virtual work of the loads on the increment `delta` (J).
fn dot_loads(loads: &[WireLoads], delta: &[f64]) -> f64 {
    let mut w = 0.0;
    let mut s = 0;
    for l in loads {
        for (f, t) in l.forces.iter().zip(&l.torques) {
            for i in 0..3 {
                w += f[i] * delta[6 * s + i] + t[i] * delta[6 * s + 3 + i];
            }
            s += 1;
        }
    }
    w
}

pub(crate) fn apply_step(base: &ModelState, delta: &[f64], alpha: f64, out: &mut ModelState) {
    let mut s = 0;
    for (wb, wo) in base.wires.iter().zip(out.wires.iter_mut()) {
        for (pb, po) in wb.poses.iter().zip(wo.poses.iter_mut()) {
            let d = &delta[6 * s..6 * s + 6];
            po.position = pb.position + alpha * Vector3::new(d[0], d[1], d[2]);
            let mut q = so3::exp(&(alpha * Vector3::new(d[3], d[4], d[5]))) * pb.rotation;
            q.renormalize();
            po.rotation = q;
            s += 1;
        }
    }
}

/// Residual scales and allowances of `options` for `model`.
pub(crate) fn scales(model: &FineModel, options: &StaticOptions) -> Scales {
    let l_ref = model
        .wires
        .iter()
        .flat_map(|w| w.chain.segments.iter())
        .map(|s| s.length)
        .fold(0.0, f64::max);
    // The largest load on a segment at full load: its weight plus its external force.
    let mut load: f64 = 0.0;
    for w in &model.wires {
        for (k, seg) in w.chain.segments.iter().enumerate() {
            let f = model.gravity * seg.mass + w.external.get(k).copied().unwrap_or_default();
            load = load.max(f.norm());
        }
    }
    let force = if let Some(f) = options.force_scale {
        f
    } else if load > 0.0 {
        load
    } else {
        // No load: scale by a small force of the stiffest wire.
        model
            .wires
            .iter()
            .map(|w| w.chain.section.youngs_modulus * w.chain.section.area * 1e-9)
            .fold(0.0, f64::max)
    };
    // Round-off allowance: 100 ulps of the largest coordinate on the stiffest spring.
    let x_max = model
        .wires
        .iter()
        .flat_map(|w| w.chain.rest.iter())
        .map(|p| p.position.amax())
        .fold(0.0, f64::max)
        + l_ref;
    let k_max = model
        .wires
        .iter()
        .flat_map(|w| {
            w.chain
                .joints
                .iter()
                .chain(w.anchors.iter().map(|a| &a.joint))
        })
        .map(|j| j.stiffness.translational.max())
        .fold(0.0, f64::max);
    let position_roundoff = 100.0 * f64::EPSILON * x_max;
    let roundoff = position_roundoff * k_max;
    Scales {
        force,
        moment: force * l_ref,
        force_allowance: options.tolerance * force + roundoff,
        moment_allowance: (options.tolerance * force + roundoff) * l_ref,
        roundoff,
        tolerance: options.tolerance,
        position_roundoff,
    }
}

/// Solves for static equilibrium under the model's gravity, starting from `state` (poses
/// only; velocities are left untouched) and leaving the equilibrium in `state`.
pub fn solve_static(
    model: &FineModel,
    state: &mut ModelState,
    options: &StaticOptions,
) -> Result<StaticReport, StaticError> {
    solve_static_with_progress(model, state, options, &mut |_| {})
}

/// Why a Newton attempt at one load factor failed.
enum Failure {
    /// Iterations exhausted; the scaled residual reached.
    Stalled(f64),
    /// Non-finite residual.
    NonFinite,
    /// The tangent could not be factored.
    Singular(String),
}

/// Work buffers of the Newton iterations.
struct Newton {
    loads: Vec<WireLoads>,
    trial: ModelState,
    delta: Vec<f64>,
    tangent: SparseTangent,
}

impl Newton {
    fn new(model: &FineModel, state: &ModelState) -> Self {
        let n = 6 * model.segment_count();
        Self {
            loads: model.load_buffers(),
            trial: state.clone(),
            delta: vec![0.0; n],
            tangent: SparseTangent::new(model, state),
        }
    }

    /// Newton iterations at load factor `lambda` from `state` (histories frozen) until
    /// converged (module docs); returns (iterations, scaled residual).
    fn solve(
        &mut self,
        model: &FineModel,
        state: &mut ModelState,
        lambda: f64,
        options: &StaticOptions,
        sc: &Scales,
    ) -> Result<(usize, f64), (usize, Failure)> {
        let Self {
            loads,
            trial,
            delta,
            tangent,
        } = self;
        model.compute_loads(state, lambda, loads);
        let (mut rmax, mut r2, mut rel) = residual_norms(loads, sc);
        let mut it = 0;
        let mut limit = options.max_iterations;
        let mut block_start = rel;
        loop {
            if rmax.is_nan() {
                return Err((it, Failure::NonFinite));
            }
            // Small against the loads in play, whatever the round-off.
            if rel <= sc.tolerance {
                break;
            }
            if it == limit {
                // Another block of iterations while the last one at least halved the
                // residual (if asked).
                if !(options.extend_while_falling && rel <= 0.5 * block_start) {
                    return Err((it, Failure::Stalled(rel)));
                }
                limit += options.max_iterations;
                block_start = rel;
            }
            it += 1;
            // Right-hand side: the residual loads (K delta = r).
            let mut s = 0;
            for l in loads.iter() {
                for (f, t) in l.forces.iter().zip(&l.torques) {
                    delta[6 * s..6 * s + 3].copy_from_slice(f.as_slice());
                    delta[6 * s + 3..6 * s + 6].copy_from_slice(t.as_slice());
                    s += 1;
                }
            }
            tangent.assemble(&model.element_tangents(state), |_| SMatrix::zeros());
            tangent
                .factor()
                .map_err(|e| (it, Failure::Singular(e.to_string())))?;
            tangent.solve_in_place(delta);
            if delta.iter().any(|d| !d.is_finite()) {
                return Err((
                    it,
                    Failure::Singular("non-finite Newton increment".to_string()),
                ));
            }
            // Within the round-off allowance: converged if the correction this residual
            // asks for is also within the round-off of the positions or small against the
            // displacements (the residual is round-off, not an error of the solution).
            if rmax <= 1.0 && correction_is_small(model, state, delta, sc) {
                break;
            }
            // Trust region: the largest rotation and translation of a segment in one
            // iteration are capped (the contact gaps are nonlinear in the rotations).
            let (mut dx, mut dw) = (0.0f64, 0.0f64);
            for d in delta.chunks_exact(6) {
                dx = dx.max(Vector3::new(d[0], d[1], d[2]).norm());
                dw = dw.max(Vector3::new(d[3], d[4], d[5]).norm());
            }
            let cap = 1.0f64
                .min(options.max_rotation / dw)
                .min(options.max_translation.map_or(1.0, |t| t / dx));
            if cap < 1.0 {
                delta.iter_mut().for_each(|d| *d *= cap);
            }
            // Backtracking line search: accept a step that lowers the total potential
            // (Armijo, if `potential_descent`) or the scaled residual. The potential is the
            // merit function far from equilibrium: the residual of stiff axial springs grows
            // with the second-order gaps of a rotation step even when the step is good.
            let potential0 = potential(loads);
            let slope: f64 = -dot_loads(loads, delta);
            let mut alpha = 1.0;
            let mut accepted = false;
            for _ in 0..=options.max_backtracks {
                apply_step(state, delta, alpha, trial);
                model.compute_loads(trial, lambda, loads);
                let (tmax, t2, trel) = residual_norms(loads, sc);
                let armijo = options.potential_descent
                    && !slipping(loads)
                    && potential(loads) <= potential0 + 1e-4 * alpha * slope;
                if armijo || t2 < (1.0 - 1e-4 * alpha) * r2 || trel <= sc.tolerance {
                    rmax = tmax;
                    rel = trel;
                    r2 = t2;
                    accepted = true;
                    break;
                }
                alpha *= 0.5;
            }
            if !accepted {
                // Take the (capped) full step: near round-off the residual no longer
                // decreases.
                apply_step(state, delta, 1.0, trial);
                model.compute_loads(trial, lambda, loads);
                (rmax, r2, rel) = residual_norms(loads, sc);
            }
            for (ws, wt) in state.wires.iter_mut().zip(&trial.wires) {
                ws.poses.copy_from_slice(&wt.poses);
            }
        }
        Ok((it, rel))
    }
}

/// Most solves of one load step on active sets of the links' states.
const ACTIVE_SET_ROUNDS: usize = 30;

/// The held state of a link whose contact law gives `state`.
fn hold_of(state: ContactState) -> Hold {
    match state {
        ContactState::Open => Hold::Open,
        ContactState::Stick => Hold::Stick,
        ContactState::Slip => Hold::Slip,
    }
}

/// Sets the hold and held slip direction of every contact in `state` to `hold(wire,
/// contact)`.
fn set_holds(state: &mut ModelState, hold: impl Fn(usize, usize) -> (Hold, Vector3<f64>)) {
    for (i, h) in state.contacts.iter_mut().enumerate() {
        for (k, hk) in h.iter_mut().enumerate() {
            (hk.hold, hk.slip_direction) = hold(i, k);
        }
    }
}

/// The hold a contact takes from the law's evaluation `c`: its state, and the direction of
/// its friction force where it slips.
fn held(c: &ContactLoad) -> (Hold, Vector3<f64>) {
    (hold_of(c.state), c.tangential_force)
}

/// The contacts' loads in `loads`, per wire in contact order.
fn contact_loads(loads: &[WireLoads]) -> Vec<Vec<ContactLoad>> {
    loads.iter().map(|l| l.contacts.clone()).collect()
}

impl Newton {
    /// [`Newton::solve`] of one load step on active sets of the links' contact states (module
    /// docs). Leaves every hold `Free` in `state` and in the trial state.
    fn solve_active_set(
        &mut self,
        model: &FineModel,
        state: &mut ModelState,
        lambda: f64,
        options: &StaticOptions,
        sc: &Scales,
    ) -> Result<(usize, f64), (usize, Failure)> {
        let result = self.active_set_rounds(model, state, lambda, options, sc);
        let free = |_, _| (Hold::Free, Vector3::zeros());
        set_holds(state, free);
        set_holds(&mut self.trial, free);
        result
    }

    fn active_set_rounds(
        &mut self,
        model: &FineModel,
        state: &mut ModelState,
        lambda: f64,
        options: &StaticOptions,
        sc: &Scales,
    ) -> Result<(usize, f64), (usize, Failure)> {
        type Held = (Hold, Vector3<f64>);
        type Holds = Vec<Vec<Held>>;
        // The first active set: the law's states at the first iterate, with the contacts
        // closed at the last commit slipping without friction (the friction forces of a
        // step that slides the wires are not known before it is solved).
        model.compute_loads(state, lambda, &mut self.loads);
        let mut holds: Holds = contact_loads(&self.loads)
            .iter()
            .map(|l| {
                l.iter()
                    .map(|c| match c.state {
                        ContactState::Open => (Hold::Open, Vector3::zeros()),
                        // Closed at the last commit: frictionless for the first solve.
                        _ if c.history.closed => (Hold::Slip, Vector3::zeros()),
                        _ => held(c),
                    })
                    .collect()
            })
            .collect();
        let mut good: Option<(Vec<WireState>, Holds)> = None;
        // Changes asked at the last converged active set: (difference of the held and the
        // law's force (N), wire, contact, the law's hold), largest first.
        let mut changes: Vec<(f64, usize, usize, Held)> = Vec::new();
        let mut limit = usize::MAX;
        let mut bound = sc.force_allowance;
        let mut iterations = 0;
        let mut rel = f64::NAN;
        for _ in 0..ACTIVE_SET_ROUNDS {
            set_holds(state, |i, k| holds[i][k]);
            set_holds(&mut self.trial, |i, k| holds[i][k]);
            let res = self.solve(model, state, lambda, options, sc);
            match res {
                Ok((it, _)) => iterations += it,
                Err((it, Failure::Stalled(r))) => {
                    iterations += it;
                    rel = r;
                    // Back to the last converged active set with half its changes.
                    let Some((poses, last)) = &good else {
                        return Err((iterations, Failure::Stalled(r)));
                    };
                    limit = limit.min(changes.len()) / 2;
                    if limit == 0 {
                        return Err((iterations, Failure::Stalled(r)));
                    }
                    for (ws, p) in state.wires.iter_mut().zip(poses) {
                        ws.poses.copy_from_slice(&p.poses);
                    }
                    holds.clone_from(last);
                    for &(_, i, k, h) in &changes[..limit] {
                        holds[i][k] = h;
                    }
                    continue;
                }
                Err((it, f)) => return Err((iterations + it, f)),
            }
            model.compute_loads(state, lambda, &mut self.loads);
            let at_held = contact_loads(&self.loads);
            // The law at the held solution.
            set_holds(state, |_, _| (Hold::Free, Vector3::zeros()));
            model.compute_loads(state, lambda, &mut self.loads);
            let (rmax, _, r) = residual_norms(&self.loads, sc);
            rel = r;
            if rmax.is_nan() {
                return Err((iterations, Failure::NonFinite));
            }
            if rmax <= 1.0 || rel <= sc.tolerance {
                return Ok((iterations, rel));
            }
            let free = contact_loads(&self.loads);
            good = Some((state.wires.clone(), holds.clone()));
            loop {
                changes.clear();
                for (i, (a, b)) in at_held.iter().zip(&free).enumerate() {
                    for (k, (a, b)) in a.iter().zip(b).enumerate() {
                        let d = (a.force_wire - b.force_wire).norm();
                        if d > bound {
                            changes.push((d, i, k, held(b)));
                        }
                    }
                }
                if !changes.is_empty() || bound < 1e-6 * sc.force_allowance {
                    break;
                }
                bound *= 0.25;
            }
            if changes.is_empty() {
                return Err((iterations, Failure::Stalled(rel)));
            }
            // Friction first: while a closed contact changes between stick and slip (or its
            // slip direction), none is released (its tension may come from friction forces
            // past the cap).
            let friction = changes
                .iter()
                .any(|&(_, i, k, h)| holds[i][k].0 != Hold::Open && h.0 != Hold::Open);
            if friction {
                changes.retain(|&(_, i, k, h)| !(holds[i][k].0 != Hold::Open && h.0 == Hold::Open));
            }
            changes.sort_by(|a, b| b.0.total_cmp(&a.0));
            limit = limit.saturating_mul(2).min(changes.len());
            for &(_, i, k, h) in &changes[..limit] {
                holds[i][k] = h;
            }
        }
        Err((iterations, Failure::Stalled(rel)))
    }
}

/// True when the Newton correction `delta` at `state` moves no segment by more than the
/// larger of the position round-off and `tolerance` times the largest displacement from
/// rest, and turns none by more than the larger of 100 eps and `tolerance` times the
/// largest rotation from rest.
fn correction_is_small(model: &FineModel, state: &ModelState, delta: &[f64], sc: &Scales) -> bool {
    let (mut u_max, mut theta_max) = (0.0f64, 0.0f64);
    for (w, ws) in model.wires.iter().zip(&state.wires) {
        for (rest, p) in w.chain.rest.iter().zip(&ws.poses) {
            u_max = u_max.max((p.position - rest.position).norm());
            theta_max = theta_max.max(p.rotation.angle_to(&rest.rotation));
        }
    }
    let dx_allowed = sc.position_roundoff.max(sc.tolerance * u_max);
    let dw_allowed = (100.0 * f64::EPSILON).max(sc.tolerance * theta_max);
    delta.chunks_exact(6).all(|d| {
        Vector3::new(d[0], d[1], d[2]).norm() <= dx_allowed
            && Vector3::new(d[3], d[4], d[5]).norm() <= dw_allowed
    })
}

/// [`solve_static`] reporting the load factor reached after every load step to `progress`.
///
/// Load stepping is adaptive: the load factor advances by `1 / load_steps` at most; when
/// Newton fails at a load factor, the last converged state is restored and the increment
/// halved (down to `min_increment`); after a load step converged in at most a quarter of
/// `max_iterations` the increment doubles again (up to `1 / load_steps`).
pub fn solve_static_with_progress(
    model: &FineModel,
    state: &mut ModelState,
    options: &StaticOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<StaticReport, StaticError> {
    faer::set_global_parallelism(faer::Par::Seq);
    let sc = scales(model, options);
    let mut newton = Newton::new(model, state);
    // The softer models of the penalty continuation, softest first.
    let softened: Vec<FineModel> = (1..=options.penalty_stages)
        .rev()
        .map(|k| model.with_normal_penalty_scaled(10f64.powi(-(k as i32))))
        .collect();
    let full = 1.0 / options.load_steps.max(1) as f64;
    let min_increment = options.min_increment.min(full);
    let mut increment = full;
    let mut reached = 0.0;
    let mut saved = state.wires.clone();
    let (mut steps, mut iterations, mut residual) = (0, 0, 0.0);
    while reached < 1.0 {
        let lambda = if reached + increment > 1.0 - 1e-12 {
            1.0
        } else {
            reached + increment
        };
        let step = steps + 1;
        // Penalty continuation: each softer model's equilibrium is the next solve's first
        // iterate; a stage that fails leaves the iterate it started from.
        let mut stage_iterations = 0;
        for soft in &softened {
            let start = state.wires.clone();
            match newton.solve(soft, state, lambda, options, &sc) {
                Ok((it, _)) => stage_iterations += it,
                Err((it, _)) => {
                    stage_iterations += it;
                    state.wires.clone_from(&start);
                }
            }
        }
        iterations += stage_iterations;
        let attempt = if options.active_set && model.link_count() > 0 {
            newton.solve_active_set(model, state, lambda, options, &sc)
        } else {
            newton.solve(model, state, lambda, options, &sc)
        };
        match attempt {
            Ok((it, rel)) => {
                iterations += it;
                residual = rel;
                steps = step;
                reached = lambda;
                progress(lambda);
                // The load step is accepted: commit the contact histories.
                model.compute_loads(state, lambda, &mut newton.loads);
                model.commit_contacts(state, &newton.loads);
                newton.trial.contacts.clone_from(&state.contacts);
                newton.trial.friction_work = state.friction_work;
                saved.clone_from(&state.wires);
                if 4 * it <= options.max_iterations {
                    increment = (2.0 * increment).min(full);
                }
            }
            Err((it, failure)) => {
                iterations += it;
                // Back to the last converged state with half the increment.
                for (ws, s) in state.wires.iter_mut().zip(&saved) {
                    ws.poses.copy_from_slice(&s.poses);
                }
                increment *= 0.5;
                if increment >= min_increment {
                    continue;
                }
                return Err(match failure {
                    Failure::Stalled(residual) => StaticError::NotConverged {
                        step,
                        load_factor: reached,
                        residual,
                    },
                    Failure::NonFinite => StaticError::NonFinite {
                        step,
                        load_factor: reached,
                    },
                    Failure::Singular(message) => StaticError::Singular {
                        step,
                        load_factor: reached,
                        message,
                    },
                });
            }
        }
    }
    Ok(StaticReport {
        load_steps: steps,
        iterations,
        residual,
        roundoff: sc.roundoff,
        force_scale: sc.force,
        moment_scale: sc.moment,
    })
}

/// Controls of the dynamic relaxation ([`solve_relaxation`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxationOptions {
    /// Number of equal load steps from zero to full load.
    pub load_steps: usize,
    /// Tolerance on the scaled residual (-), as in [`StaticOptions`].
    pub tolerance: f64,
    /// Pseudo-time steps allowed per load step.
    pub max_iterations: usize,
    /// Reference force F_ref (N) of the residual, as in [`StaticOptions`].
    pub force_scale: Option<f64>,
    /// Pseudo-time steps between updates of the fictitious masses.
    pub mass_update: usize,
}

impl Default for RelaxationOptions {
    fn default() -> Self {
        Self {
            load_steps: 10,
            tolerance: 1e-9,
            max_iterations: 1_000_000,
            force_scale: None,
            mass_update: 200,
        }
    }
}

/// Fictitious masses of dynamic relaxation: 0.6 times the Gershgorin row sums of the tangent
/// (contacts entered closed), so that a unit pseudo-time step is stable.
fn fictitious_masses(model: &FineModel, state: &ModelState, mass: &mut [f64]) {
    mass.iter_mut().for_each(|m| *m = 0.0);
    let mut elements = model.joint_tangents(state);
    elements.extend(model.contact_bound_tangents(state));
    for e in elements {
        for (bi, si) in e.segments.iter().enumerate() {
            let Some(si) = si else { continue };
            for bj in 0..2 {
                if e.segments[bj].is_none() {
                    continue;
                }
                for r in 0..6 {
                    for c in 0..6 {
                        mass[6 * si + r] += 0.6 * e.stiffness[(6 * bi + r, 6 * bj + c)].abs();
                    }
                }
            }
        }
    }
    let floor = mass.iter().fold(0.0f64, |a, &b| a.max(b)) * 1e-12;
    mass.iter_mut().for_each(|m| *m = m.max(floor));
}

/// Static equilibrium by dynamic relaxation with kinetic damping: pseudo-time steps of the
/// undamped motion with fictitious masses (0.6 times the Gershgorin row sums of the tangent,
/// contacts entered closed, so that a unit step is stable), the velocities zeroed at every
/// peak of the kinetic energy. Slow but robust where Newton stalls (wires held only
/// by contacts at zero gap). Contact histories are frozen within a load step and committed
/// when it converges on the residual criterion of [`solve_static`].
pub fn solve_relaxation(
    model: &FineModel,
    state: &mut ModelState,
    options: &RelaxationOptions,
) -> Result<StaticReport, StaticError> {
    let so = StaticOptions {
        load_steps: options.load_steps,
        tolerance: options.tolerance,
        max_iterations: options.max_iterations,
        force_scale: options.force_scale,
        ..Default::default()
    };
    let sc = scales(model, &so);
    let n = 6 * model.segment_count();
    let mut loads = model.load_buffers();
    let mut vel = vec![0.0; n];
    let mut mass = vec![0.0; n];
    let mut iterations = 0;
    let mut residual = 0.0;
    let steps = options.load_steps.max(1);
    for step in 1..=steps {
        let lambda = step as f64 / steps as f64;
        vel.iter_mut().for_each(|v| *v = 0.0);
        let mut ke_prev = 0.0;
        let mut it = 0;
        loop {
            if it % options.mass_update.max(1) == 0 {
                fictitious_masses(model, state, &mut mass);
            }
            model.compute_loads(state, lambda, &mut loads);
            let (rmax, _, rel) = residual_norms(&loads, &sc);
            if rmax.is_nan() {
                return Err(StaticError::NonFinite {
                    step,
                    load_factor: (step - 1) as f64 / steps as f64,
                });
            }
            residual = rel;
            if rmax <= 1.0 {
                break;
            }
            if it == options.max_iterations {
                return Err(StaticError::NotConverged {
                    step,
                    load_factor: (step - 1) as f64 / steps as f64,
                    residual: rel,
                });
            }
            it += 1;
            let mut s = 0;
            let mut ke = 0.0;
            for l in &loads {
                for (f, t) in l.forces.iter().zip(&l.torques) {
                    for i in 0..3 {
                        let (a, b) = (6 * s + i, 6 * s + 3 + i);
                        vel[a] += f[i] / mass[a];
                        vel[b] += t[i] / mass[b];
                        ke += mass[a] * vel[a] * vel[a] + mass[b] * vel[b] * vel[b];
                    }
                    s += 1;
                }
            }
            if ke < ke_prev {
                // Kinetic energy peaked: restart from rest.
                vel.iter_mut().for_each(|v| *v = 0.0);
                ke_prev = 0.0;
                continue;
            }
            ke_prev = ke;
            let mut s = 0;
            for ws in &mut state.wires {
                for p in &mut ws.poses {
                    let d = &vel[6 * s..6 * s + 6];
                    p.position += Vector3::new(d[0], d[1], d[2]);
                    let mut q = so3::exp(&Vector3::new(d[3], d[4], d[5])) * p.rotation;
                    q.renormalize();
                    p.rotation = q;
                    s += 1;
                }
            }
        }
        iterations += it;
        model.compute_loads(state, lambda, &mut loads);
        model.commit_contacts(state, &loads);
    }
    Ok(StaticReport {
        load_steps: steps,
        iterations,
        residual,
        roundoff: sc.roundoff,
        force_scale: sc.force,
        moment_scale: sc.moment,
    })
}
