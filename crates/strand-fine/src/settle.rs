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
//! ramped with damping); Newton then finishes from the settled state, to the tight tolerance.
//! Implicit steps of the same damped motion (backward Euler on the assembled tangent plus the
//! inertia, Newton per step, the histories committed after each) do not pay here. With
//! friction, on the Table 1 strand at 20 segments per wire, their Newton iterations cycle
//! between the stick and slip states and slip directions of hundreds of contacts for steps
//! above 1e-4 s (15 explicit steps), while a factorization of the tangent costs about 100
//! explicit steps at 77 segments per wire. Without friction, where the static state is
//! unique, a continuation with a doubling step reached the settle's equilibrium (within
//! 5e-10 m at the tip, 0.1 m strand, 12 segments per wire) in 306 steps and 1993 Newton
//! iterations, eight times the settle's time.
//!
//! Mass-proportional damping at rate gamma makes every mode above gamma / 2 decay as
//! exp(-gamma t / 2) and modes below it as exp(-omega^2 t / gamma): gamma near twice the
//! lowest frequency settles fastest. The residual the settle waits on is that of the stiff
//! modes, all above gamma / 2: on the Fig. 7 strand under g = 8 it is 1.57e4 times its
//! allowance at the end of the ramp and the settle ends 2.17 s later, when exp(-gamma t / 2)
//! has taken 1.65e4 off it; fewer steps need another damping, i.e. another load path.
//! Friction makes the static state depend on the load
//! path, and strongly on the damping: on the Table 1 strand under g = 8 (20 segments per
//! wire) states settled with gamma 5 % apart differ by 1.7e-4 m at the tip, while a ramp 5 %
//! longer moves it by 1e-6 m, a time step 0.67 or 2.2 times as long by less than 2e-6 m and
//! four times the segments' axial inertia by 2e-6 m: the motion of the strand as a whole sets
//! the result, not the fast motions of its contacts.
//!
//! The motion need not be the strand's own: the static state does not depend on the masses
//! and inertias, only the load path does. The settle gives every segment its transverse
//! moment of inertia about its own axis too ([`SettleOptions::isotropic_inertia`]): the spin
//! of a segment about its axis under the contacts' tangential springs at the wire's surface
//! is otherwise the fastest motion, and with it gone the stable step of the Fig. 7 strand
//! (77 segments per wire) grows 1.32 times; at 0.9 of it instead of 0.75 the settle takes
//! 1.56-1.58 times fewer steps at g = 8, 10, 12 (276,300, 244,600, 225,400). The tip lands
//! 2.2e-6, 2.2e-6, 1.7e-6 m from that of the strand's own inertia at 0.75, every state
//! polished by Newton to its tolerance: the friction's path dependence, up to about twice
//! what a change of the step alone gives (0.75 to 0.7: 6.5e-7, 4.9e-7 m at g = 8, 10; 1.73
//! to 5.46 us: up to 1.3e-6 m).
//!
//! Newton cannot take over much earlier: on the Fig. 7 strand under g = 8, from the states
//! where the residual had fallen to 945, 297, 97, 29, 9.3 and 2.9 times the settle's
//! allowance, Newton with the histories frozen stalled every time (40 iterations, scaled
//! residual 0.03-7); it converges from the settled state or after the retries' motion.
//!
//! Newton from the settled state (the contact histories of the settled state frozen) most
//! often converges, but it can stall where most closed contacts sit at the slip limit, as
//! they do at rest. The settled state is then about 1e-5 m from the equilibrium the motion
//! reaches at the tip; the motion goes on in short stretches and Newton is tried again from
//! each, which on the Fig. 7 strand lands within 1e-6 m of the limit the motion itself
//! reaches after another 0.9 s.
//!
//! Nor can an implicit continuation with friction ([`SettledOptions::pseudo_transient`], off
//! by default; [`crate::pseudo_transient`]): without friction it takes over from the motion
//! at 100 or 1000 times the allowance and lands on the motion's equilibrium, with friction it
//! stalls and the motion goes on from the handover state as without it (the same result, bit
//! for bit).
//!
//! Nor, on the Fig. 7 strand, a quasi-static load continuation from the straight strand
//! ([`SettledOptions::load_continuation`], off by default; [`crate::load_continuation`]): it
//! reaches full load on a short strand and replaces the motion there, but on the Fig. 7 strand it
//! stalls or crawls short of full load at a higher cost than the whole settle; the motion then
//! runs from the straight strand as without it.

use crate::dynamics::Integrator;
use crate::load_continuation::{LoadContinuationReport, load_continuation};
use crate::model::{FineModel, ModelState};
use crate::pseudo_transient::{PseudoTransientOptions, PseudoTransientReport, pseudo_transient};
use crate::spectrum::lanczos_highest_frequency;
use crate::statics::{
    Scales, StaticError, StaticOptions, StaticReport, residual_norms, scales, solve_static,
};

/// Controls of [`settle`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettleOptions {
    /// Damping rate gamma (1/s); `None`: twice the larger of sqrt(|g| / L), the frequency of
    /// the hanging strand's swing, and the first bending frequency of the straight strand as a
    /// cantilever (near-critical damping of the slowest motion; the second keeps the settle's
    /// duration bounded under loads far below the paper's).
    pub damping_rate: Option<f64>,
    /// Time over which gravity rises linearly to its full value (s); `None`: 2 / gamma; 0:
    /// full gravity from the start.
    pub ramp_time: Option<f64>,
    /// Time step (s); `None`: `safety` x 2 / omega_max, with omega_max the Lanczos estimate
    /// of the highest frequency ([`crate::spectrum`]).
    pub time_step: Option<f64>,
    /// Fraction of the linear stability limit `omega_max dt = 2` (-). The pendulum's
    /// [`crate::dynamics::MOTION_FACTOR`] does not apply: omega_max is that of contacts closed
    /// at their stiffer (tangential) spring in every direction, above the strand's, and the
    /// damped settle of the Table 1 strand ran stable to 1.0 (20 and 77 segments per wire);
    /// default 0.9. At 1.0 the fastest mode is barely damped: the Fig. 7 strand under g = 8
    /// (77 segments per wire) took 3.57 s of motion to rest instead of 2.36 s at 0.75, and
    /// 2.31 s at 0.9 (with the axial inertia four times its value: 4.14 s at 1.0). A settle
    /// that turns non-finite is run again from rest at 0.54 (the dynamic runs' 0.9 x 0.6).
    pub safety: f64,
    /// Simulated time allowed (s).
    pub max_time: f64,
    /// Steps allowed, those of a motion run again at the fallback step included; `None`: no
    /// limit but `max_time`. The motion stops at whichever limit comes first. (The motion of
    /// [`solve_settled`]'s Newton retries after the settle is not counted.)
    pub max_steps: Option<u64>,
    /// Tolerance on the scaled residual, as in [`StaticOptions`] (-).
    pub tolerance: f64,
    /// Steps between residual checks.
    pub check_every: usize,
    /// The motion gives every segment its transverse moment of inertia about its own axis
    /// too (isotropic rotational inertia) instead of `m r^2 / 2`: the static state does not
    /// depend on the inertia, and the spin of a segment about its axis under the contacts'
    /// tangential springs at the wire's surface is the model's fastest motion (on the Fig. 7
    /// strand, 77 segments per wire, the settle's stable step grows from 7.28e-6 to about
    /// 9.6e-6 s; the axial inertia four or eight times its value gives 9.62e-6 and
    /// 9.65e-6 s, so the spin no longer sets it). Default true.
    pub isotropic_inertia: bool,
    /// Damping rate (1/s) from the end of the gravity ramp on (the motion to rest at full
    /// load), switched at the first residual check at or after the ramp's end; `None`:
    /// `damping_rate` throughout (default). A study option: a larger rate takes the stiff
    /// modes out faster once the load is applied, but the modes below half of it then
    /// decay slower, and with friction the state reached depends on the motion.
    pub rest_damping_rate: Option<f64>,
}

impl Default for SettleOptions {
    fn default() -> Self {
        Self {
            damping_rate: None,
            ramp_time: None,
            time_step: None,
            safety: 0.9,
            max_time: 60.0,
            max_steps: None,
            tolerance: 1e-4,
            check_every: 100,
            isotropic_inertia: true,
            rest_damping_rate: None,
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
    /// Steps of a motion at the default step that turned non-finite and was run again from
    /// the start at the fallback step (0: none) (not in `steps`).
    pub discarded_steps: u64,
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
        /// Steps taken (-).
        steps: u64,
        /// Time step (s).
        time_step: f64,
        /// Simulated time (s).
        time: f64,
        /// Scaled residual reached (-).
        residual: f64,
        /// Largest ratio to the allowance (-).
        ratio: f64,
    },
    /// The motion took `options.max_steps` steps without coming to rest.
    #[error(
        "not at rest after {steps} steps of {time_step:.3e} s ({time:.3} s of damped \
         motion): force/torque {ratio:.3e} times the allowance (scaled residual {residual:.3e})"
    )]
    StepLimit {
        /// Steps taken (-).
        steps: u64,
        /// Time step (s).
        time_step: f64,
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

/// Damping rate and ramp time of the settle for `model` under `options` (1/s, s): the
/// options' own, or the defaults of [`SettleOptions::damping_rate`] and
/// [`SettleOptions::ramp_time`].
pub fn damping_and_ramp(model: &FineModel, options: &SettleOptions) -> (f64, f64) {
    let core = &model.wires[0].chain;
    let length = core
        .segments
        .iter()
        .map(|s| s.length)
        .sum::<f64>()
        .max(f64::MIN_POSITIVE);
    let gamma = options.damping_rate.unwrap_or_else(|| {
        // First bending frequency of a clamped-free beam with the wires' summed bending
        // stiffness (a lower bound of the strand's) and the strand's mass per length.
        let ei: f64 = model
            .wires
            .iter()
            .map(|w| w.chain.section.youngs_modulus * w.chain.section.inertia)
            .sum();
        let mass: f64 = model.wires.iter().map(|w| w.chain.mass()).sum::<f64>() / length;
        let bending = 3.516 * (ei / (mass * length.powi(4))).sqrt();
        2.0 * (model.gravity.norm() / length).sqrt().max(bending)
    });
    let ramp = match options.ramp_time {
        Some(t) => t,
        None if gamma > 0.0 => 2.0 / gamma,
        None => 0.0,
    };
    (gamma, ramp)
}

/// The damped motion of a settle, resumable after it has met its tolerance.
struct DampedMotion {
    int: Integrator,
    gamma: f64,
    ramp: f64,
    /// Damping rate from the ramp's end on ([`SettleOptions::rest_damping_rate`]).
    rest_gamma: Option<f64>,
    sc: Scales,
    check: u64,
    /// The motion is at rest when the residual's largest ratio to the allowance falls to
    /// this (1, or the continuation's handover ratio).
    at_rest: f64,
}

impl DampedMotion {
    /// Motion from rest at `state` (velocities zeroed) with the step `dt` (s).
    fn start(model: &FineModel, state: &mut ModelState, options: &SettleOptions, dt: f64) -> Self {
        let (gamma, ramp) = damping_and_ramp(model, options);
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
        int.load_factor = if ramp > 0.0 { 0.0 } else { 1.0 };
        int.reload(model, state);
        Self {
            int,
            gamma,
            ramp,
            rest_gamma: options.rest_damping_rate,
            sc,
            check: options.check_every.max(1) as u64,
            at_rest: 1.0,
        }
    }

    /// Moves until the residual is within the allowance at full load, or until the time
    /// `until` (s) or `max_steps` steps in all; returns (within the allowance, largest ratio
    /// to it, scaled residual).
    fn run(
        &mut self,
        model: &FineModel,
        state: &mut ModelState,
        until: f64,
        max_steps: u64,
        progress: &mut dyn FnMut(&ModelState, f64, f64),
    ) -> Result<(bool, f64, f64), SettleError> {
        let ramp = self.ramp;
        let factor = move |t: f64| if ramp > 0.0 { (t / ramp).min(1.0) } else { 1.0 };
        let (mut ratio, mut residual) = (f64::INFINITY, f64::INFINITY);
        while self.int.time < until && self.int.steps < max_steps {
            let steps = self.check.min(max_steps - self.int.steps);
            if let Some(rate) = self.rest_gamma.filter(|_| self.int.time >= ramp) {
                self.int.damping_rate = rate;
            }
            self.int.advance(model, state, steps, &factor);
            (ratio, _, residual) = residual_norms(self.int.loads(), &self.sc);
            if !ratio.is_finite() {
                return Err(SettleError::NonFinite {
                    time: self.int.time,
                });
            }
            progress(state, self.int.time, ratio);
            if self.int.load_factor >= 1.0 && ratio <= self.at_rest {
                return Ok((true, ratio, residual));
            }
        }
        Ok((false, ratio, residual))
    }

    fn report(&self, ratio: f64, residual: f64) -> SettleReport {
        SettleReport {
            steps: self.int.steps,
            time: self.int.time,
            time_step: self.int.dt,
            discarded_steps: 0,
            damping_rate: self.gamma,
            ramp_time: self.ramp,
            residual,
            allowance_ratio: ratio,
            force_scale: self.sc.force,
            roundoff: self.sc.roundoff,
        }
    }
}

/// The settle's default time step at `state` (s): `safety` x 2 / omega_max, with omega_max
/// the Lanczos estimate of [`lanczos_highest_frequency`] (every contact closed and stuck).
/// [`settle`] and [`solve_settled`] take it (at [`SettleOptions::safety`]) unless
/// `SettleOptions::time_step` is given.
pub fn settle_time_step(model: &FineModel, state: &ModelState, safety: f64) -> f64 {
    let omega = lanczos_highest_frequency(model, state, LANCZOS_STEPS).omega;
    safety * 2.0 / omega
}

/// Lanczos steps of the settle's frequency estimate.
const LANCZOS_STEPS: usize = 100;

/// Fraction of the linear stability limit for a settle run again after turning non-finite.
const FALLBACK_SAFETY: f64 = 0.9 * crate::dynamics::MOTION_FACTOR;

/// The model the settle's motion moves: `model`, with every segment's axial moment of
/// inertia raised to its transverse one if `options.isotropic_inertia` (loads, masses and
/// the static state are the model's own). The settle's default step is
/// [`settle_time_step`] of this model.
pub fn motion_model<'a>(
    model: &'a FineModel,
    options: &SettleOptions,
) -> std::borrow::Cow<'a, FineModel> {
    if !options.isotropic_inertia {
        return std::borrow::Cow::Borrowed(model);
    }
    let mut m = model.clone();
    for seg in m.wires.iter_mut().flat_map(|w| w.chain.segments.iter_mut()) {
        seg.axial_inertia = seg.transverse_inertia;
    }
    std::borrow::Cow::Owned(m)
}

/// Starts the damped motion of `options` at `state` and runs it until settled; a motion
/// at the default step that turns non-finite is run again from the start state at the
/// fallback step.
fn settle_motion(
    model: &FineModel,
    state: &mut ModelState,
    options: &SettleOptions,
    at_rest: f64,
    progress: &mut dyn FnMut(&ModelState, f64, f64),
) -> Result<(DampedMotion, SettleReport), SettleError> {
    let start = state.clone();
    let mut safety = options.safety;
    let mut discarded = 0;
    loop {
        let dt = options
            .time_step
            .unwrap_or_else(|| settle_time_step(model, state, safety));
        let mut motion = DampedMotion::start(model, state, options, dt);
        motion.at_rest = at_rest;
        let max_steps = options
            .max_steps
            .map_or(u64::MAX, |n| n.saturating_sub(discarded));
        match motion.run(model, state, options.max_time, max_steps, progress) {
            Ok((true, ratio, residual)) => {
                let report = SettleReport {
                    discarded_steps: discarded,
                    ..motion.report(ratio, residual)
                };
                return Ok((motion, report));
            }
            Ok((false, ratio, residual)) if motion.int.steps >= max_steps => {
                return Err(SettleError::StepLimit {
                    steps: motion.int.steps + discarded,
                    time_step: dt,
                    time: motion.int.time,
                    residual,
                    ratio,
                });
            }
            Ok((false, ratio, residual)) => {
                return Err(SettleError::NotSettled {
                    steps: motion.int.steps + discarded,
                    time_step: dt,
                    time: motion.int.time,
                    residual,
                    ratio,
                });
            }
            Err(e) => {
                discarded += motion.int.steps;
                if options.time_step.is_some()
                    || safety <= FALLBACK_SAFETY
                    || options.max_steps.is_some_and(|n| discarded >= n)
                {
                    return Err(e);
                }
                safety = FALLBACK_SAFETY;
                state.clone_from(&start);
            }
        }
    }
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
    let model = motion_model(model, options);
    settle_motion(&model, state, options, 1.0, progress).map(|(_, report)| report)
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
    /// Simulated time the motion goes on between two Newton attempts after Newton stalled
    /// (s).
    pub retry_interval: f64,
    /// Simulated time the motion may go on after the settle before the settled state is
    /// taken as the result (s).
    pub retry_time: f64,
    /// Hand the motion over to a pseudo-transient continuation
    /// ([`crate::pseudo_transient`]) at the options' handover ratio, then polish; `None`
    /// (default): the motion goes on to the settle's tolerance. If the continuation or the
    /// polish after it fails, the motion goes on from the handover state as without it.
    pub pseudo_transient: Option<PseudoTransientOptions>,
    /// Quasi-static load continuation first ([`load_continuation`]): Newton load stepping
    /// ([`solve_static`] with these options) from the state given, the straight strand; if it
    /// reaches full load, its state is the result and no motion runs; if it fails, the state
    /// given is restored and the settle runs from it as without the option (the same result,
    /// bit for bit). `None` (default): no continuation. A study option (module docs of
    /// [`load_continuation`]: it does not reach full load on the Fig. 7 strand).
    pub load_continuation: Option<StaticOptions>,
    /// On a model with wire-to-wire links, Newton is tried from the state where the motion
    /// stopped without coming to rest (step or time limit), and its converged state is the
    /// result (default true; models without links are not affected). On the 1+6+12
    /// cantilever the motion stands still (tip moving 2.4e-7 m in 0.08 s) while a few
    /// segments keep vibrating against contacts that open and close (largest speed 5e-4
    /// m/s, force residual 1-2 segment weights), which the rest criterion of 1e-4 of a
    /// segment weight never passes; Newton with the histories frozen converges from there,
    /// given further blocks of iterations while each halves the residual
    /// ([`StaticOptions::extend_while_falling`]: at 48 segments a wire it takes 45).
    pub polish_stalled: bool,
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
            retry_interval: 0.02,
            retry_time: 0.5,
            pseudo_transient: None,
            load_continuation: None,
            polish_stalled: true,
        }
    }
}

/// Outcome of [`solve_settled`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettledReport {
    /// The damped motion (up to the state Newton finished from, or to the result if it
    /// never did).
    pub settle: SettleReport,
    /// The Newton polish, if it converged.
    pub polish: Option<StaticReport>,
    /// Newton attempts (1 if the first converged).
    pub attempts: usize,
    /// Newton iterations of all attempts.
    pub iterations: usize,
    /// Tolerance met by the result (scaled residual allowance, as in [`StaticOptions`]) (-).
    pub tolerance: f64,
    /// Final scaled residual `max(|F| / F_ref, |T| / (F_ref l_ref))` (-).
    pub residual: f64,
    /// The pseudo-transient continuation, if one ran.
    pub pseudo_transient: Option<PseudoTransientReport>,
    /// The quasi-static load continuation, if one ran. If it reached full load, no motion
    /// ran: `settle` has no steps, its residual and scales are Newton's and its allowance ratio
    /// is 0.
    pub load_continuation: Option<LoadContinuationReport>,
}

/// Static equilibrium under the model's gravity from the rest state in `state`: damped
/// motion to `options.settle.tolerance`, then Newton to `options.polish.tolerance`. If
/// Newton stalls (contacts at the slip limit switching between stick and slip from one
/// iteration to the next), the motion goes on for `retry_interval` and Newton starts again
/// from there, for up to `retry_time`; if it never converges, the settled state where the
/// motion stopped is the result, within the settle tolerance. `progress` receives the state,
/// the simulated time (s) and the residual's ratio to the settle allowance during the motion.
pub fn solve_settled(
    model: &FineModel,
    state: &mut ModelState,
    options: &SettledOptions,
    progress: &mut dyn FnMut(&ModelState, f64, f64),
) -> Result<SettledReport, SettleError> {
    let mut loaded = None;
    if let Some(lc) = &options.load_continuation {
        let (report, converged) = load_continuation(model, state, lc);
        loaded = Some(report);
        if let Some(p) = converged {
            let (damping_rate, ramp_time) = damping_and_ramp(model, &options.settle);
            return Ok(SettledReport {
                settle: SettleReport {
                    steps: 0,
                    time: 0.0,
                    time_step: 0.0,
                    discarded_steps: 0,
                    damping_rate,
                    ramp_time,
                    residual: p.residual,
                    allowance_ratio: 0.0,
                    force_scale: p.force_scale,
                    roundoff: p.roundoff,
                },
                polish: Some(p),
                attempts: 1,
                iterations: p.iterations,
                tolerance: lc.tolerance,
                residual: p.residual,
                pseudo_transient: None,
                load_continuation: loaded,
            });
        }
    }
    let moving = motion_model(model, &options.settle);
    let handover = options
        .pseudo_transient
        .map_or(1.0, |p| p.handover.max(1.0));
    let (mut motion, mut settled) =
        match settle_motion(&moving, state, &options.settle, handover, progress) {
            Ok(m) => m,
            Err(e) => return polish_stalled(model, state, options, e),
        };
    let mut continuation = None;
    if let Some(pt) = &options.pseudo_transient {
        let handed = state.clone();
        let masses: Vec<(f64, f64)> = moving
            .wires
            .iter()
            .flat_map(|w| w.chain.segments.iter())
            .map(|seg| (seg.mass, seg.transverse_inertia.max(seg.axial_inertia)))
            .collect();
        let h0 = 1.0 / motion.gamma.max(f64::MIN_POSITIVE);
        let report = pseudo_transient(model, state, pt, &motion.sc, &masses, h0);
        continuation = Some(report);
        if report.converged
            && let Ok(p) = solve_static(model, state, &options.polish)
        {
            return Ok(SettledReport {
                settle: settled,
                polish: Some(p),
                attempts: 1,
                iterations: p.iterations,
                tolerance: options.polish.tolerance,
                residual: p.residual,
                pseudo_transient: continuation,
                load_continuation: loaded,
            });
        }
        // The motion goes on from the handover state to the settle's tolerance.
        state.clone_from(&handed);
        motion.at_rest = 1.0;
        let budget = options.settle.max_steps.unwrap_or(u64::MAX);
        let (rest, ratio, residual) =
            motion.run(&moving, state, options.settle.max_time, budget, progress)?;
        if !rest {
            return Err(if motion.int.steps >= budget {
                SettleError::StepLimit {
                    steps: motion.int.steps + settled.discarded_steps,
                    time_step: motion.int.dt,
                    time: motion.int.time,
                    residual,
                    ratio,
                }
            } else {
                SettleError::NotSettled {
                    steps: motion.int.steps + settled.discarded_steps,
                    time_step: motion.int.dt,
                    time: motion.int.time,
                    residual,
                    ratio,
                }
            });
        }
        settled = SettleReport {
            discarded_steps: settled.discarded_steps,
            ..motion.report(ratio, residual)
        };
    }
    let give_up = settled.time + options.retry_time;
    let mut saved = state.clone();
    let (mut attempts, mut iterations) = (0, 0);
    loop {
        attempts += 1;
        match solve_static(model, state, &options.polish) {
            Ok(p) => {
                return Ok(SettledReport {
                    settle: settled,
                    polish: Some(p),
                    attempts,
                    iterations: iterations + p.iterations,
                    tolerance: options.polish.tolerance,
                    residual: p.residual,
                    pseudo_transient: continuation,
                    load_continuation: loaded,
                });
            }
            Err(e) => {
                iterations += match e {
                    StaticError::NotConverged { .. } => options.polish.max_iterations,
                    _ => 0,
                };
                state.clone_from(&saved);
            }
        }
        // The retries' motion counts against the same step budget as the settling: without it a
        // strand whose stable step is tiny (a strand shorter than its wires are thick) moved on
        // for `retry_time` at that step, for ever in effect.
        let budget = options.settle.max_steps.unwrap_or(u64::MAX);
        if motion.int.time + options.retry_interval > give_up + 1e-12 || motion.int.steps >= budget
        {
            return Ok(SettledReport {
                settle: settled,
                polish: None,
                attempts,
                iterations,
                tolerance: options.settle.tolerance,
                residual: settled.residual,
                pseudo_transient: continuation,
                load_continuation: loaded,
            });
        }
        // The motion goes on from the state it stopped at (momenta included).
        let until = motion.int.time + options.retry_interval;
        let (_, ratio, residual) = motion.run(&moving, state, until, budget, progress)?;
        settled = SettleReport {
            discarded_steps: settled.discarded_steps,
            ..motion.report(ratio, residual)
        };
        saved.clone_from(state);
    }
}

/// The result of a motion that stopped with `error` without coming to rest: on a model with
/// wire-to-wire links and [`SettledOptions::polish_stalled`], Newton from the state the
/// motion stopped in (the polish's options with [`StaticOptions::extend_while_falling`]);
/// its converged state, or `error` (with `state` where the motion stopped)
/// if it does not converge.
fn polish_stalled(
    model: &FineModel,
    state: &mut ModelState,
    options: &SettledOptions,
    error: SettleError,
) -> Result<SettledReport, SettleError> {
    let (steps, time_step, time, residual, ratio) = match error {
        SettleError::StepLimit {
            steps,
            time_step,
            time,
            residual,
            ratio,
        }
        | SettleError::NotSettled {
            steps,
            time_step,
            time,
            residual,
            ratio,
        } => (steps, time_step, time, residual, ratio),
        SettleError::NonFinite { .. } => return Err(error),
    };
    if !options.polish_stalled || model.link_count() == 0 {
        return Err(error);
    }
    let stopped = state.clone();
    let polish = StaticOptions {
        extend_while_falling: true,
        ..options.polish
    };
    match solve_static(model, state, &polish) {
        Ok(p) => {
            let (damping_rate, ramp_time) = damping_and_ramp(model, &options.settle);
            let sc = scales(
                model,
                &StaticOptions {
                    tolerance: options.settle.tolerance,
                    ..Default::default()
                },
            );
            Ok(SettledReport {
                settle: SettleReport {
                    steps,
                    time,
                    time_step,
                    discarded_steps: 0,
                    damping_rate,
                    ramp_time,
                    residual,
                    allowance_ratio: ratio,
                    force_scale: sc.force,
                    roundoff: sc.roundoff,
                },
                polish: Some(p),
                attempts: 1,
                iterations: p.iterations,
                tolerance: options.polish.tolerance,
                residual: p.residual,
                pseudo_transient: None,
                load_continuation: None,
            })
        }
        Err(_) => {
            state.clone_from(&stopped);
            Err(error)
        }
    }
}
