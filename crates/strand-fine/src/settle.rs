//! Static equilibrium with contacts: damped motion to rest ([`settle`]), then Newton
//! ([`crate::solve_static`]) from the settled state ([`solve_settled`]).
//!
//! Damped motion: the strand moves under its gravity, ramped up over a time, with a viscous
//! damping proportional to the masses and inertias, integrated by the explicit scheme of
//! [`crate::dynamics`] until the static residual meets a (loose) criterion of the form of
//! [`crate::solve_static`]'s.
//!
//! Why: with contacts and friction, Newton load stepping from the straight strand stalls. At
//! zero tension the contacts carry only the wires' weight, sit near zero gap and switch
//! open, stick and slip from one Newton iteration to the next; at a settled state most
//! contacts are stressed but still take turns between stick and slip in the first
//! iterations. The motion passes through those switches one small step at a time, with the
//! contact histories committed every step, so friction follows a physical load path (gravity
//! ramped with damping); Newton then converges from the settled state in a few iterations
//! (its line search accepting residual decrease only), to the tight tolerance.
//!
//! Mass-proportional damping at rate gamma makes every mode above gamma / 2 decay as
//! exp(-gamma t / 2) and modes below it as exp(-omega^2 t / gamma): gamma near twice the
//! lowest frequency settles fastest. Friction makes the static state depend on the load
//! path: settled states of the Table 1 strand under g = 8 with gamma = 4.5 and 10 1/s differ
//! by 3e-4 m at the tip.

use crate::dynamics::{Integrator, stable_time_step};
use crate::model::{FineModel, ModelState};
use crate::statics::{StaticOptions, StaticReport, residual_norms, scales, solve_static};

/// Controls of [`settle`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettleOptions {
    /// Damping rate gamma (1/s); `None`: 2 sqrt(|g| / L), about twice the lowest frequency
    /// of the hanging strand (near-critical damping of its swing).
    pub damping_rate: Option<f64>,
    /// Time over which gravity rises linearly to its full value (s); `None`: 2 / gamma; 0:
    /// full gravity from the start.
    pub ramp_time: Option<f64>,
    /// Time step (s); `None`: the stable step at `safety`.
    pub time_step: Option<f64>,
    /// Safety factor on the stable step (-).
    pub safety: f64,
    /// Simulated time allowed (s).
    pub max_time: f64,
    /// Tolerance on the scaled residual, as in [`StaticOptions`] (-).
    pub tolerance: f64,
    /// Steps between residual checks.
    pub check_every: usize,
}

impl Default for SettleOptions {
    fn default() -> Self {
        Self {
            damping_rate: None,
            ramp_time: None,
            time_step: None,
            safety: 0.9,
            max_time: 60.0,
            tolerance: 1e-4,
            check_every: 100,
        }
    }
}

/// Outcome of a settled run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettleReport {
    /// Steps taken.
    pub steps: u64,
    /// Simulated time (s).
    pub time: f64,
    /// Time step (s).
    pub time_step: f64,
    /// Damping rate (1/s).
    pub damping_rate: f64,
    /// Time over which gravity rose to its full value (s).
    pub ramp_time: f64,
    /// Final scaled residual `max(|F| / F_ref, |T| / (F_ref l_ref))` (-).
    pub residual: f64,
    /// Largest ratio of a segment's force or torque to its allowance (<= 1) (-).
    pub allowance_ratio: f64,
    /// Force scale F_ref (N).
    pub force_scale: f64,
    /// Round-off allowance added to `tolerance F_ref` (N).
    pub roundoff: f64,
}

/// Failure of [`settle`].
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum SettleError {
    /// The residual did not fall to its allowance in the allowed time.
    #[error(
        "not at rest after {time:.3} s of damped motion: force/torque {ratio:.3e} times the \
         allowance (scaled residual {residual:.3e})"
    )]
    NotSettled {
        /// Simulated time (s).
        time: f64,
        /// Scaled residual reached (-).
        residual: f64,
        /// Largest ratio to the allowance (-).
        ratio: f64,
    },
    /// A load or a position became NaN or infinite.
    #[error("non-finite residual after {time:.6} s of damped motion")]
    NonFinite {
        /// Simulated time (s).
        time: f64,
    },
}

/// Brings `state` to static equilibrium under the model's gravity by damped motion from rest
/// (see the module docs); `progress` receives the state, the simulated time (s) and the
/// residual's ratio to its allowance at every check.
pub fn settle(
    model: &FineModel,
    state: &mut ModelState,
    options: &SettleOptions,
    progress: &mut dyn FnMut(&ModelState, f64, f64),
) -> Result<SettleReport, SettleError> {
    let length = model.wires[0]
        .chain
        .segments
        .iter()
        .map(|s| s.length)
        .sum::<f64>()
        .max(f64::MIN_POSITIVE);
    let gamma = options
        .damping_rate
        .unwrap_or_else(|| 2.0 * (model.gravity.norm() / length).sqrt());
    let ramp = match options.ramp_time {
        Some(t) => t,
        None if gamma > 0.0 => 2.0 / gamma,
        None => 0.0,
    };
    let dt = options
        .time_step
        .unwrap_or_else(|| stable_time_step(model, state, options.safety));
    let sc = scales(
        model,
        &StaticOptions {
            tolerance: options.tolerance,
            ..Default::default()
        },
    );
    for w in &mut state.wires {
        w.velocities.iter_mut().for_each(|v| v.fill(0.0));
        w.angular_momenta.iter_mut().for_each(|v| v.fill(0.0));
    }
    let mut int = Integrator::new(model, state, dt);
    int.damping_rate = gamma;
    let factor = |t: f64| if ramp > 0.0 { (t / ramp).min(1.0) } else { 1.0 };
    int.load_factor = factor(0.0);
    int.reload(model, state);
    let check = options.check_every.max(1) as u64;
    let (mut ratio, mut residual) = (f64::INFINITY, f64::INFINITY);
    while int.time < options.max_time {
        int.load_factor = factor(int.time + dt);
        int.step(model, state);
        if int.steps.is_multiple_of(check) {
            (ratio, _, residual) = residual_norms(int.loads(), &sc);
            if !ratio.is_finite() {
                return Err(SettleError::NonFinite { time: int.time });
            }
            progress(state, int.time, ratio);
            if int.load_factor >= 1.0 && ratio <= 1.0 {
                return Ok(SettleReport {
                    steps: int.steps,
                    time: int.time,
                    time_step: dt,
                    damping_rate: gamma,
                    ramp_time: ramp,
                    residual,
                    allowance_ratio: ratio,
                    force_scale: sc.force,
                    roundoff: sc.roundoff,
                });
            }
        }
    }
    Err(SettleError::NotSettled {
        time: int.time,
        residual,
        ratio,
    })
}

/// Controls of [`solve_settled`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettledOptions {
    /// The damped motion to rest; its tolerance is the one the result meets if Newton
    /// stalls.
    pub settle: SettleOptions,
    /// The Newton polish from the settled state (one load step at full load; the line
    /// search should accept residual decrease only).
    pub polish: StaticOptions,
}

impl Default for SettledOptions {
    fn default() -> Self {
        Self {
            settle: SettleOptions::default(),
            polish: StaticOptions {
                load_steps: 1,
                min_increment: 1.0,
                potential_descent: false,
                ..StaticOptions::default()
            },
        }
    }
}

/// Outcome of [`solve_settled`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettledReport {
    /// The damped motion.
    pub settle: SettleReport,
    /// The Newton polish, if it converged.
    pub polish: Option<StaticReport>,
    /// Tolerance met by the result (scaled residual allowance, as in [`StaticOptions`]) (-).
    pub tolerance: f64,
    /// Final scaled residual `max(|F| / F_ref, |T| / (F_ref l_ref))` (-).
    pub residual: f64,
}

/// Static equilibrium under the model's gravity from the rest state in `state`: damped
/// motion to `options.settle.tolerance`, then Newton to `options.polish.tolerance`. If
/// Newton stalls (contacts switching between stick and slip, or open and closed, from one
/// iteration to the next), the settled state is the result, within the settle tolerance.
/// (On the Table 1 strand under g = 8, 20 segments per wire, Newton moved the tip of a state
/// settled to 1e-4 by 9e-6 m.) `progress` receives the state, the simulated time (s) and the
/// residual's ratio to the settle allowance during the motion.
pub fn solve_settled(
    model: &FineModel,
    state: &mut ModelState,
    options: &SettledOptions,
    progress: &mut dyn FnMut(&ModelState, f64, f64),
) -> Result<SettledReport, SettleError> {
    let settled = settle(model, state, &options.settle, progress)?;
    let saved = state.clone();
    match solve_static(model, state, &options.polish) {
        Ok(p) => Ok(SettledReport {
            settle: settled,
            polish: Some(p),
            tolerance: options.polish.tolerance,
            residual: p.residual,
        }),
        Err(_) => {
            *state = saved;
            Ok(SettledReport {
                settle: settled,
                polish: None,
                tolerance: options.settle.tolerance,
                residual: settled.residual,
            })
        }
    }
}
