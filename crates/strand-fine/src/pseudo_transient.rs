//! Pseudo-transient continuation (PTC) to static equilibrium with the contact histories
//! frozen: implicit Euler steps of a motion without momentum, `(M / h^2 + K) dx = F`, with
//! `M` the segments' masses and (isotropic) moments of inertia, `K` the assembled tangent
//! ([`crate::sparse_tangent`]) and `F` the residual loads, the pseudo step `h` growing by a
//! fixed factor after every accepted step and cut by it after a refused one.
//!
//! A mode of frequency omega keeps the factor `1 / (1 + omega^2 h^2)` of its residual in one
//! step: the stiff modes, which the damped motion of the settle takes out only at the rate
//! gamma / 2, go in the first step, and as `h` grows the steps become Newton's. Each step
//! takes the backtracking line search of [`crate::solve_static`]'s Newton on the scaled
//! 2-norm of the residual: a full step grows `h`, a shortened one keeps it, and a step
//! that no fraction down to 2^-10 makes lower is refused and cuts `h`.
//!
//! With friction the histories stay those of the state the continuation starts from (as in
//! the Newton polish, [`crate::settle::solve_settled`]; [`PseudoTransientOptions::commit`]
//! commits them after every accepted step instead): the continuation does not follow a load
//! path, it solves the static problem of that state's anchors.
//!
//! What it gives ([`crate::settle::SettledOptions::pseudo_transient`]; the manual's
//! Performance page has the figures): without friction, where the static state is unique,
//! it takes over from the damped motion at 100 or 1000 times the settle's allowance and
//! converges in about ten steps, on the same equilibrium. With friction it stalls: a step
//! carries contacts that sit at the slip limit across it, the residual of the full step is
//! many times the one it started from and grows about linearly with the step's length (the
//! tangent of the branch a contact is on is not the one the step lands on), and neither the
//! elastic tangent of friction ([`PseudoTransientOptions::elastic_friction`]) nor
//! committing the histories changes that; the settle then moves on from the handover state
//! as without the continuation.

use nalgebra::{SMatrix, SVector};

use crate::contact::ContactState;
use crate::model::{FineModel, ModelState};
use crate::sparse_tangent::SparseTangent;
use crate::statics::{Scales, apply_step, residual_norms};

/// Controls of the continuation ([`crate::settle::SettledOptions::pseudo_transient`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PseudoTransientOptions {
    /// The damped motion hands over to the continuation when the residual's largest ratio to
    /// the settle's allowance falls to this (-).
    pub handover: f64,
    /// First pseudo step `h` (s); `None`: 1 / gamma, the settle's damping rate (the
    /// slowest mode then keeps about 0.8 of its residual, every mode ten times faster less
    /// than 4 %).
    pub initial_step: Option<f64>,
    /// Growth of `h` after an accepted step, and its cut after a refused one (-).
    pub growth: f64,
    /// Pseudo steps allowed (refused ones included).
    pub max_steps: usize,
    /// Commit the contact histories after every accepted step (the frictional state follows
    /// the continuation's path); `false`: frozen at the start state's.
    pub commit: bool,
    /// Build the steps on the elastic tangent of friction
    /// ([`FineModel::elastic_tangents`]: every closed contact stuck); `false`: the
    /// consistent tangent of each contact's branch ([`FineModel::element_tangents`]).
    pub elastic_friction: bool,
}

impl Default for PseudoTransientOptions {
    fn default() -> Self {
        Self {
            handover: 100.0,
            initial_step: None,
            growth: 4.0,
            max_steps: 60,
            commit: false,
            elastic_friction: false,
        }
    }
}

/// Outcome of the continuation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PseudoTransientReport {
    /// Pseudo steps taken (accepted and refused; one factorization each).
    pub steps: usize,
    /// Refused steps.
    pub refused: usize,
    /// Last pseudo step (s).
    pub last_step: f64,
    /// Largest ratio of a segment's force or torque to its allowance at the end (-).
    pub allowance_ratio: f64,
    /// Whether the ratio reached 1.
    pub converged: bool,
}

/// Runs the continuation from `state` at full load until every segment's residual is within
/// the allowance of `sc` or `options.max_steps` steps; leaves the last accepted state in
/// `state` (histories untouched). `mass[s]` holds the translational mass (kg) and the
/// (isotropic) moment of inertia (kg m^2) of segment `s`; `initial_step` is `h` when
/// `options.initial_step` is `None` (s).
pub(crate) fn pseudo_transient(
    model: &FineModel,
    state: &mut ModelState,
    options: &PseudoTransientOptions,
    sc: &Scales,
    mass: &[(f64, f64)],
    initial_step: f64,
) -> PseudoTransientReport {
    faer::set_global_parallelism(faer::Par::Seq);
    let n = 6 * model.segment_count();
    let mut loads = model.load_buffers();
    let mut trial = state.clone();
    let mut delta = vec![0.0; n];
    let mut tangent = SparseTangent::new(model, state);
    model.compute_loads(state, 1.0, &mut loads);
    let (mut ratio, mut r2, _) = residual_norms(&loads, sc);
    let mut h = options.initial_step.unwrap_or(initial_step);
    let (mut steps, mut refused) = (0, 0);
    while ratio > 1.0 && steps < options.max_steps && ratio.is_finite() {
        steps += 1;
        let mut s = 0;
        for l in &loads {
            for (f, t) in l.forces.iter().zip(&l.torques) {
                delta[6 * s..6 * s + 3].copy_from_slice(f.as_slice());
                delta[6 * s + 3..6 * s + 6].copy_from_slice(t.as_slice());
                s += 1;
            }
        }
        let inv_h2 = 1.0 / (h * h);
        let elements = if options.elastic_friction {
            model.elastic_tangents(state, |i, k| {
                loads[i].contacts[k].state != ContactState::Open
            })
        } else {
            model.element_tangents(state)
        };
        tangent.assemble(&elements, |s| {
            let (m, i) = mass[s];
            SMatrix::from_diagonal(&SVector::<f64, 6>::from([m, m, m, i, i, i])) * inv_h2
        });
        if tangent.factor().is_err() {
            h /= options.growth;
            refused += 1;
            continue;
        }
        tangent.solve_in_place(&mut delta);
        let mut accepted = None;
        let mut alpha = 1.0;
        for _ in 0..=BACKTRACKS {
            apply_step(state, &delta, alpha, &mut trial);
            model.compute_loads(&trial, 1.0, &mut loads);
            let (t_ratio, t2, _) = residual_norms(&loads, sc);
            if t2.is_finite() && t2 < (1.0 - 1e-4 * alpha) * r2 {
                accepted = Some((t_ratio, t2));
                break;
            }
            alpha *= 0.5;
        }
        match accepted {
            Some((t_ratio, t2)) => {
                if alpha == 1.0 {
                    h *= options.growth;
                }
                (ratio, r2) = (t_ratio, t2);
                for (ws, wt) in state.wires.iter_mut().zip(&trial.wires) {
                    ws.poses.copy_from_slice(&wt.poses);
                }
                if options.commit {
                    model.commit_contacts(state, &loads);
                    trial.contacts.clone_from(&state.contacts);
                }
            }
            None => {
                h /= options.growth;
                refused += 1;
                model.compute_loads(state, 1.0, &mut loads);
            }
        }
    }
    PseudoTransientReport {
        steps,
        refused,
        last_step: h,
        allowance_ratio: ratio,
        converged: ratio <= 1.0,
    }
}

/// Halvings of a step in the line search.
const BACKTRACKS: usize = 10;
