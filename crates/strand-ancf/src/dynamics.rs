//! Dynamics of the strand beam, `M q'' + Q_e(q) = Q_g` (eq. (47) with the supports
//! eliminated), from rest in the reference configuration or from an [`InitialState`] (SPEC 5).
//!
//! * Stoermer-Verlet (the paper's integrator), explicit: the constant mass matrix is factored
//!   once; the stable step comes from the largest eigenvalue of the assembled system
//!   ([`stable_step`], Lanczos on `M^-1 K`).
//! * Generalized-alpha (Chung-Hulbert parameters in the Arnold-Bruels form), implicit: Newton
//!   on `S = beta' M + K` with the analytic tangent and a band LDL^T (LU when not symmetric).
//!   The factorized matrix is kept over iterations and steps (turned with the strand, module
//!   `corotation`: with a stick/slip law only while its nodes turn together) and rebuilt when
//!   Newton slows; with a stick/slip law the kept matrix's linear convergence is accelerated
//!   by the secant of its last two corrections. Spectral radius 1 gives the trapezoidal rule
//!   (no numerical damping).
//!
//! Energy accounting (SPEC 2): kinetic `1/2 v^T M v`, gravity `-Q_g . (q - q_0)`, elastic (the
//! section laws' stored energy), dissipated (the hysteretic law's slip work, never negative),
//! and the work the non-potential part of the `continuous` and `paper` laws has done on the
//! strand, `energy_strain d eps` at every bending point (midpoint rule over each accepted
//! step; positive when it puts energy in). Kinetic + gravity + elastic + dissipated - that
//! work stays at its initial value up to the integrator's own error, reported as the balance
//! error. The non-potential work is kept apart from the dissipation so that energy a law puts
//! in cannot pass for negative dissipation.
//! Moving supports (`beam::supports`) add the work they do on the strand, which the total
//! subtracts too. In 3D the non-potential work includes `energy_turn . d kappa`, the change of
//! the `continuous` and `paper` laws' slip energy as the friction limits turn with the bending
//! direction (zero in planar motion).

use crate::band::BandSolver;
use crate::beam::{Beam, BeamError, PointState};
use crate::initial::InitialState;
use crate::moving_support::Drive;
use crate::output_times::OutputTimes;
use crate::statics::{add_free, gather_free};
use strand_core::round_off::{BalanceFloor, OPERATIONS, Travel};

mod alpha;

pub use crate::stability::stable_step;

/// Time integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scheme {
    /// Stoermer-Verlet with the given step, or the estimated stable step times 0.9.
    Verlet {
        /// Time step (s); `None` for the estimate.
        step: Option<f64>,
    },
    /// Generalized-alpha.
    GeneralizedAlpha {
        /// Time step (s).
        step: f64,
        /// Spectral radius at infinite frequency, in [0, 1].
        spectral_radius: f64,
    },
}

/// Settings of a dynamic run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicOptions {
    /// Simulated time (s).
    pub duration: f64,
    /// Integrator.
    pub scheme: Scheme,
    /// Interval between output frames (s).
    pub output_interval: f64,
    /// Generalized-alpha: Newton converges when the correction, or the estimated error left
    /// after it (the correction times theta / (1 - theta) for a contraction rate theta), is
    /// below this times the strand length. The error estimate (not used by laws with slip
    /// state, whose committed state belongs to the forces before the last correction) lets a
    /// step stop after two iterations: on the section-3 pendulum at 1e-3 s steps it saves 16
    /// and 10 % of the iterations with the `constant` and `continuous` laws against accepting
    /// on the correction alone. With the default, 1e-8, the constant law's tip stays within
    /// 3.2e-5 m of a run converged to 1e-11 L over that swing, a quarter of the integrator's
    /// own error there (1.2e-4 m); 1e-9 brings that to 6.3e-6 m for 4.5 % more iterations at
    /// 1e-3 s steps, but 23 % more at 2.5e-3 s and 12-14 % more with the stick/slip laws.
    pub increment: f64,
    /// Generalized-alpha: the share of the run's energy scale that Newton's stopping test may
    /// leave in the energy balance over the whole run, at any step size. A step is accepted
    /// only when its last correction changed the ledger's total energy by at most this times
    /// the energy scale times `h / duration`, so the run's `T / h` steps add at most this share
    /// (none cancelling): a fixed energy, where a tolerance on the correction alone admits an
    /// error that grows as the step shrinks (see the acceptance test in the step). With the
    /// default, 1e-5, issue 16's tilted pendulum in its plane (hysteretic law, 5 s) closes its
    /// balance to 4.96e-4, 1.08e-4, 2.26e-5 and 3.69e-6 of the largest kinetic energy at 1,
    /// 0.5, 0.25 and 0.125 ms (second order; 4.95e-4, 1.06e-4, 2.05e-5 and 3.02e-6 with
    /// `increment` 1e-10), against 4.97e-4, 1.23e-4, 9.94e-5 and 3.97e-4 with the former test,
    /// and takes fewer iterations at 1 ms (30,663 against 32,924).
    pub ledger: f64,
    /// Generalized-alpha: Newton iterations per step before the step is cut.
    pub max_iterations: usize,
    /// Generalized-alpha: line search. Where the step's incremental potential rises again at
    /// a full Newton correction (its slope along the correction changes sign: a stick/slip
    /// kink was overshot), the iterate steps back to the secant root of that slope if it lies
    /// below this fraction of the correction (1: always; 0: never).
    pub backtrack: f64,
    /// Generalized-alpha, `hysteretic` law: the share of their stick stiffness the iteration
    /// matrix gives to slipping wires (see
    /// [`Tangent::Iteration`](crate::beam::Tangent::Iteration)). On the section-3 pendulum
    /// at 1e-3 s steps (`pendulum_speed`, `PENDULUM_UNLOADING`), Newton iterations (matrices)
    /// 0: 5610 (895), 0.1: 4612 (671), 0.2: 4314 (551), 0.25: 4209 (602), 0.3: 4177 (647),
    /// 0.5: 4464 (1238). Before the two-step predictor, the coherent co-rotation and the
    /// secant acceleration of the generalized-alpha step: 0: 6721 (968), 0.05: 5795 (753),
    /// 0.1: 5284 (636), 0.2: 4894 (587), 0.25: 4705 (668), 0.3: 4656 (810), 0.5: 4854
    /// (1238), 1: 5050 (1507); the fewest instructions at 0.25 (callgrind: 771 M against
    /// 847 M at 0.1), its tip 4.8e-6 m from the run converged to `increment` 1e-12 (3.2e-6 m
    /// at 0.1), the same energy balance (1.8e-5 J).
    pub unloading: f64,
    /// Generalized-alpha: the iteration matrix is rebuilt within a step when a Newton
    /// correction shrinks by less than this factor (0: full Newton; 1: rebuilt only when
    /// Newton stalls).
    pub refresh: f64,
    /// Generalized-alpha, linear section law: the next step starts with a fresh iteration
    /// matrix when the last correction of a step shrank by less than this factor with a
    /// kept (co-rotated) matrix. A kept matrix contracts more slowly as it ages (by about
    /// 2e-3 per step on the section-3 pendulum at 1e-3 s steps with the zero-acceleration
    /// predictor), and at a rate theta a step's second iterate is left with about theta^2
    /// times the predictor's error: steps converge in two iterations while theta stays
    /// below about 0.02. On that pendulum (constant law) at 2.5e-3 s steps, 0.02 takes 944
    /// iterations and 55 matrices, against 1430 and 9 without rebuilds between steps
    /// (`f64::INFINITY`): 28 % less time.
    pub rebuild_rate: f64,
    /// Generalized-alpha, a strand of several layers with a stick/slip law: keep a matrix
    /// built at the last iterate whose correction still shrank by less than `refresh`,
    /// rather than build one at every iterate of a slow tail (see the generalized-alpha
    /// Newton). A 1+m strand and a linear law are not affected.
    pub keep_slow_fresh: bool,
    /// Generalized-alpha, a strand of several layers with a stick/slip law: the acceleration
    /// a step is predicted with (a 1+m strand keeps the two steps' mean).
    pub layers_predictor: SlipPredictor,
}

/// The acceleration at a step's end that generalized-alpha predicts the step with, for the
/// stick/slip laws (see the step's predictor).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlipPredictor {
    /// The mean of the last two steps' accelerations, `(q''_n + q''_{n-1}) / 2`.
    Mean,
    /// Zero acceleration.
    Zero,
}

impl DynamicOptions {
    /// Options with default Newton settings.
    pub fn new(duration: f64, scheme: Scheme, output_interval: f64) -> Self {
        DynamicOptions {
            duration,
            scheme,
            output_interval,
            increment: 1e-8,
            ledger: 1e-5,
            max_iterations: 25,
            backtrack: 0.8,
            unloading: 0.25,
            refresh: 0.5,
            rebuild_rate: 0.02,
            keep_slow_fresh: true,
            layers_predictor: SlipPredictor::Zero,
        }
    }
}

/// Energies at one instant (J).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energies {
    /// Time (s).
    pub t: f64,
    /// Kinetic energy.
    pub kinetic: f64,
    /// Gravity potential relative to the initial configuration.
    pub gravity: f64,
    /// Stored elastic energy.
    pub elastic: f64,
    /// Work dissipated so far by slip (hysteretic law; never negative).
    pub dissipated: f64,
    /// Work done on the strand so far by the non-potential part of the section laws (the
    /// `continuous` and `paper` laws' `energy_strain d eps` and, in 3D, their turn term;
    /// positive: energy put in).
    pub non_potential: f64,
    /// Work done on the strand by moving supports so far.
    pub supports: f64,
}

impl Energies {
    /// The largest of the energies in absolute value (J): a scale for errors in their sum.
    pub fn largest(&self) -> f64 {
        [
            self.kinetic,
            self.gravity,
            self.elastic,
            self.dissipated,
            self.non_potential,
            self.supports,
        ]
        .into_iter()
        .fold(0.0, |a, e| a.max(e.abs()))
    }

    /// Kinetic + gravity + elastic + dissipated - non-potential work - support work: constant
    /// up to the integrator's error.
    pub fn total(&self) -> f64 {
        self.kinetic + self.gravity + self.elastic + self.dissipated
            - self.non_potential
            - self.supports
    }
}

/// What an observer sees at an output time.
#[derive(Debug, Clone, Copy)]
pub struct Frame<'a> {
    /// Time (s).
    pub t: f64,
    /// Coordinates, all of them.
    pub q: &'a [f64],
    /// Velocities, all of them (zero for coordinates a fixed support holds).
    pub v: &'a [f64],
    /// Energies.
    pub energies: Energies,
    /// State at every bending point.
    pub points: &'a [PointState],
    /// Committed slip state of the section law ([`Beam::state_len`] values).
    pub slip: &'a [f64],
}

/// Summary of a dynamic run.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicSummary {
    /// Time step used (s).
    pub time_step: f64,
    /// Estimated stable step of the explicit scheme (s): Verlet runs only; the implicit
    /// integrator does not need it, and its Lanczos estimate costs as much as tens of
    /// generalized-alpha steps ([`stable_step`] gives it on demand).
    pub stable_step: Option<f64>,
    /// Steps taken.
    pub steps: usize,
    /// Newton iterations in total (generalized-alpha).
    pub newton_iterations: usize,
    /// Iteration matrices built and factorized (generalized-alpha).
    pub factorizations: usize,
    /// Why each iteration matrix was built, and the slow fresh matrices kept
    /// (generalized-alpha).
    pub rebuilds: Rebuilds,
    /// Steps by their Newton iterations: `iteration_histogram[k]` steps took `k + 1`
    /// (cut steps counted with the iterations of their halves; the last entry holds every
    /// step of at least its count) (generalized-alpha).
    pub iteration_histogram: [usize; 12],
    /// Steps of the scheme's step size that Newton could not take and that were taken in
    /// halves instead (generalized-alpha).
    pub cut_steps: usize,
    /// Largest |total energy - initial total energy| over the run (J).
    pub balance_error: f64,
    /// Largest kinetic energy over the run (J): a scale for the balance error.
    pub max_kinetic: f64,
    /// The balance error that round-off alone can make over the run (J): the work the
    /// round-off of the internal forces can do over the distance the strand travelled
    /// ([`BalanceFloor`]). A balance error below it says nothing about the integrator.
    pub balance_floor: f64,
    /// Energies at the end.
    pub last: Energies,
    /// Final coordinates.
    pub q: Vec<f64>,
    /// Final velocities.
    pub v: Vec<f64>,
    /// Final committed per-point state (the law's slip state and the section frames).
    pub slip: Vec<f64>,
}

/// Why generalized-alpha built its iteration matrices (their sum is
/// [`DynamicSummary::factorizations`]), and how often it kept a slow one.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Rebuilds {
    /// At a step's start, for want of a matrix of the step's size: the first step, a step
    /// cut in halves or the one after, or after a diverged or singular iteration.
    pub step_size: usize,
    /// At a step's start, because the last step's final contraction with the kept matrix
    /// of a linear law was slower than `rebuild_rate`.
    pub slow_step: usize,
    /// Within a step, because a correction shrank by less than `refresh`.
    pub slow_iteration: usize,
    /// Within a step of a strand of several layers with a stick/slip law, the matrices
    /// built at the last iterate whose correction still shrank by less than `refresh`, and
    /// which were kept rather than built again (see the generalized-alpha Newton).
    pub kept_slow_fresh: usize,
}

/// Why a dynamic run stopped.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DynamicError {
    /// An evaluation failed (non-finite value, degenerate element).
    #[error("at t = {t:.6} s (step {step}): {source}")]
    Beam {
        /// Time (s).
        t: f64,
        /// Step number.
        step: usize,
        /// What failed.
        source: BeamError,
    },
    /// Newton did not converge in a step.
    #[error(
        "generalized-alpha: Newton did not converge at t = {t:.6} s (step {step}) within {iterations} \
         iterations ({law} law); try a smaller time step"
    )]
    Newton {
        /// Time (s).
        t: f64,
        /// Step number.
        step: usize,
        /// Iterations made.
        iterations: usize,
        /// Section law.
        law: &'static str,
    },
    /// The explicit step exceeds the stability limit.
    #[error(
        "Verlet time step {step:e} s exceeds the estimated stable step {stable:e} s; use a step of at \
         most {stable:e} s or the implicit generalized-alpha integrator"
    )]
    Unstable {
        /// Requested step (s).
        step: f64,
        /// Estimated stable step (s).
        stable: f64,
    },
    /// The explicit run created energy: its balance is off by more than all the energy the
    /// strand was ever given, which no stable step does (the stable step is estimated at the
    /// straight reference and does not bound every deformed state).
    #[error(
        "Verlet run unstable at t = {t:.4e} s: the energy balance is off by {error:.3e} J, more \
         than the {supplied:.3e} J the strand was ever given (initial state, gravity, supports); \
         the step {step:.4e} s is above the stable step of the deformed strand (the estimate \
         {stable:.4e} s is taken at the straight reference): use a smaller analysis.time_step or \
         the generalized-alpha integrator"
    )]
    Diverged {
        /// Time of the step that found it (s).
        t: f64,
        /// Energy balance error (J).
        error: f64,
        /// Largest energy given to the strand so far (J).
        supplied: f64,
        /// Step (s).
        step: f64,
        /// Estimated stable step (s).
        stable: f64,
    },
    /// A matrix could not be factorized.
    #[error("singular {0} matrix")]
    Singular(&'static str),
    /// Invalid settings.
    #[error("{0}")]
    Setup(String),
}

/// Work done on the strand over a step by the non-potential part of the stick/slip laws (J,
/// positive when it puts energy in): `energy_strain d eps + energy_turn . d kappa` at every
/// bending point between the states `old` and `new` (trapezoidal rule, SPEC 2). The second
/// term, the change of the slip energy as the friction limits turn with the bending
/// direction, is zero in planar motion.
pub fn non_potential_work(old: &[PointState], new: &[PointState]) -> f64 {
    old.iter()
        .zip(new)
        .map(|(a, b)| {
            let [ny, nz] = [0, 1].map(|j| a.energy_turn[j] + b.energy_turn[j]);
            let turn = ny * (b.kappa_y - a.kappa_y) + nz * (b.kappa - a.kappa);
            0.5 * a.weight * (a.energy_strain + b.energy_strain) * (b.eps - a.eps)
                + 0.5 * a.weight * turn
        })
        .sum()
}

/// Bookkeeping shared by both integrators.
struct Ledger {
    q0_gravity: f64,
    dissipated: f64,
    non_potential: f64,
    e0: f64,
    balance_error: f64,
    max_kinetic: f64,
    /// The round-off of the internal forces ([`Ledger::floor`]).
    floor: BalanceFloor,
    /// The distance the strand has travelled at its root mean square speed.
    path: Travel,
    /// Mass of the strand (kg).
    mass: f64,
    /// Largest elastic energy so far (J).
    max_elastic: f64,
    /// Largest sum of the gravity potential's terms in absolute value, `|Q_g| . |q|` (J):
    /// the potential is their sum less the initial one, and keeps their round-off.
    gravity_terms: f64,
}

impl Ledger {
    /// A ledger starting from coordinates `q0` with stored and kinetic energy `e0`.
    fn new(beam: &Beam, q0: &[f64], e0: f64) -> Ledger {
        let potential = -q0
            .iter()
            .zip(beam.gravity_force())
            .map(|(a, b)| a * b)
            .sum::<f64>();
        Ledger {
            q0_gravity: potential,
            dissipated: 0.0,
            non_potential: 0.0,
            e0,
            balance_error: 0.0,
            max_kinetic: 0.0,
            floor: BalanceFloor::new(
                beam.law().axial_stiffness(),
                beam.law().stick_bending_stiffness(),
                beam.length(),
                beam.spec().elements,
            ),
            path: Travel::default(),
            mass: beam.spec().mass_per_length * beam.length(),
            max_elastic: 0.0,
            gravity_terms: 0.0,
        }
    }

    /// The balance error round-off alone can make so far (J): the work of the round-off
    /// forces over the path, and the round-off of evaluating the elastic energy.
    fn floor(&self) -> f64 {
        self.floor.work(self.path.distance)
            + self.floor.evaluation(self.max_elastic)
            + OPERATIONS * f64::EPSILON * self.gravity_terms
    }

    fn gravity(&self, beam: &Beam, q: &[f64]) -> f64 {
        -q.iter()
            .zip(beam.gravity_force())
            .map(|(a, b)| a * b)
            .sum::<f64>()
            - self.q0_gravity
    }

    /// Adds the slip work and the non-potential work of an accepted step (from the
    /// bending-point states).
    fn dissipate(&mut self, slip_work: f64, old: &[PointState], new: &[PointState]) {
        self.dissipated += slip_work;
        self.non_potential += non_potential_work(old, new);
    }

    /// Energy given to the strand so far as of energies `en` (J): the initial state's,
    /// gravity's and the supports' work and the law's non-potential work (each in absolute
    /// value, a bound).
    fn supplied(&self, en: &Energies) -> f64 {
        self.e0.abs() + en.gravity.abs() + en.supports.abs() + en.non_potential.abs()
    }

    /// Fails where the balance error exceeds all the energy the strand was given so far,
    /// `supplied` (J), above the round-off floor too: a strand at rest is moved by round-off
    /// alone, and its balance error is then of the size of all it was given. `t` (s) is the
    /// time of the step, `h` (s) the step and `stable` (s) the estimated stable step.
    fn check_stable(&self, supplied: f64, t: f64, h: f64, stable: f64) -> Result<(), DynamicError> {
        if self.balance_error > supplied + self.floor() {
            return Err(DynamicError::Diverged {
                t,
                error: self.balance_error,
                supplied,
                step: h,
                stable,
            });
        }
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    fn energies(
        &mut self,
        beam: &Beam,
        t: f64,
        q: &[f64],
        vf: &[f64],
        drive: &Drive,
        mv: &mut [f64],
        elastic: f64,
    ) -> Energies {
        let kinetic = beam.kinetic_energy(vf, drive.velocity(), mv);
        let e = Energies {
            t,
            kinetic,
            gravity: self.gravity(beam, q),
            elastic,
            dissipated: self.dissipated,
            non_potential: self.non_potential,
            supports: drive.work,
        };
        self.balance_error = self.balance_error.max((e.total() - self.e0).abs());
        self.max_kinetic = self.max_kinetic.max(kinetic);
        self.max_elastic = self.max_elastic.max(elastic.abs());
        let terms: f64 = q
            .iter()
            .zip(beam.gravity_force())
            .map(|(a, b)| (a * b).abs())
            .sum();
        self.gravity_terms = self.gravity_terms.max(terms);
        if t == 0.0 {
            self.path = Travel::start(t, kinetic, self.mass);
        } else {
            self.path.advance(t, kinetic, self.mass);
        }
        e
    }
}

/// Runs the dynamics of `beam` from rest; `observer` sees the state at t = 0 and every
/// output interval (and the last step).
pub fn run_dynamic(
    beam: &Beam,
    opts: &DynamicOptions,
    observer: &mut dyn FnMut(Frame<'_>),
) -> Result<DynamicSummary, DynamicError> {
    run_dynamic_from(beam, opts, &InitialState::rest(beam), observer)
}

/// Runs the dynamics of `beam` from `init`; `observer` sees the state at t = 0 and every
/// output interval (and the last step).
pub fn run_dynamic_from(
    beam: &Beam,
    opts: &DynamicOptions,
    init: &InitialState,
    observer: &mut dyn FnMut(Frame<'_>),
) -> Result<DynamicSummary, DynamicError> {
    let n = beam.coords();
    if init.q.len() != n || init.v.len() != n || init.state.len() != beam.state_len() {
        return Err(DynamicError::Setup(
            "the initial state does not fit the beam".into(),
        ));
    }
    if !(opts.duration > 0.0 && opts.output_interval > 0.0) {
        return Err(DynamicError::Setup(
            "duration and output interval must be positive".into(),
        ));
    }
    match opts.scheme {
        Scheme::Verlet { step } => {
            let stable = stable_step(beam).map_err(|source| DynamicError::Beam {
                t: 0.0,
                step: 0,
                source,
            })?;
            let h = step.unwrap_or(0.9 * stable);
            if h > stable {
                return Err(DynamicError::Unstable { step: h, stable });
            }
            verlet(beam, opts, init, h, stable, observer)
        }
        Scheme::GeneralizedAlpha {
            step,
            spectral_radius,
        } => {
            if !(step > 0.0 && (0.0..=1.0).contains(&spectral_radius)) {
                return Err(DynamicError::Setup(
                    "generalized-alpha needs a positive step and a spectral radius in [0, 1]"
                        .into(),
                ));
            }
            alpha::generalized_alpha(beam, opts, init, step, spectral_radius, 1.0, observer)
        }
    }
}

/// Full-length velocity vector from the free velocities and the moving supports'.
fn scatter_velocity(beam: &Beam, vf: &[f64], drive: &Drive, v: &mut [f64]) {
    for (g, x) in v.iter_mut().enumerate() {
        *x = beam.free_index(g).map_or(0.0, |i| vf[i]);
    }
    for (k, x) in drive.velocity().iter().enumerate() {
        v[beam.moving_coordinate(k)] = *x;
    }
}

/// Number of steps of size about `h` that fit the duration, and the step that makes them fit.
fn steps_for(duration: f64, h: f64) -> (usize, f64) {
    let n = (duration / h).ceil().max(1.0) as usize;
    (n, duration / n as f64)
}

/// Half a Verlet kick of the free velocities `vf` by the free accelerations `af` over the
/// step `h` (s): v += h/2 a.
fn half_kick(vf: &mut [f64], af: &[f64], h: f64) {
    for (v, a) in vf.iter_mut().zip(af) {
        *v += 0.5 * h * a;
    }
}

/// Fails where a free velocity of the step `step` at time `t` (s) is not finite.
fn finite_velocity(vf: &[f64], t: f64, step: usize) -> Result<(), DynamicError> {
    if !vf.iter().all(|x| x.is_finite()) {
        return Err(DynamicError::Beam {
            t,
            step,
            source: BeamError::NonFinite {
                element: 0,
                x: f64::NAN,
                quantity: "velocity",
            },
        });
    }
    Ok(())
}

/// The explicit scheme's run: half kick, drift (and the supports' motion), the internal force
/// at the new coordinates, half kick; then the step is committed (slip state, ledger, support
/// work) and its energy balance checked against all the strand was given.
fn verlet(
    beam: &Beam,
    opts: &DynamicOptions,
    init: &InitialState,
    h: f64,
    stable: f64,
    observer: &mut dyn FnMut(Frame<'_>),
) -> Result<DynamicSummary, DynamicError> {
    let (n_steps, h) = steps_for(opts.duration, h);
    let nf = beam.dofs();
    let mut mass = BandSolver::default();
    if !mass.factorize(beam.mass()) {
        return Err(DynamicError::Singular("mass"));
    }
    let mut q = init.q.clone();
    let mut vf = vec![0.0; nf];
    gather_free(beam, &init.v, &mut vf);
    let mut v = vec![0.0; q.len()];

    let mut af = vec![0.0; nf];
    let mut force = vec![0.0; q.len()];
    let mut mv = vec![0.0; nf];
    let mut slip = init.state.clone();
    let mut trial = slip.clone();
    let mut pts = vec![PointState::default(); beam.points()];
    let mut pts_new = pts.clone();
    let mut g_free = vec![0.0; nf];
    gather_free(beam, beam.gravity_force(), &mut g_free);

    let fail = |t: f64, step: usize| move |source| DynamicError::Beam { t, step, source };
    // Acceleration a = M^-1 (Q_g - Q_e) of the free coordinates.
    let accel = |force: &[f64], af: &mut [f64]| {
        gather_free(beam, force, af);
        for (a, g) in af.iter_mut().zip(&g_free) {
            *a = g - *a;
        }
        mass.solve(af);
    };
    let ev = beam
        .internal(&q, &slip, &mut trial, &mut force, None, Some(&mut pts))
        .map_err(fail(0.0, 0))?;
    accel(&force, &mut af);
    let mut drive = Drive::new(beam, &q, &init.v, &force);
    let kinetic = beam.kinetic_energy(&vf, drive.velocity(), &mut mv);
    let mut ledger = Ledger::new(beam, &q, ev.energy + kinetic);
    let mut en = ledger.energies(beam, 0.0, &q, &vf, &drive, &mut mv, ev.energy);
    scatter_velocity(beam, &vf, &drive, &mut v);
    observer(Frame {
        t: 0.0,
        q: &q,
        v: &v,
        energies: en,
        points: &pts,
        slip: &slip,
    });
    let mut supplied = 0.0f64;
    let mut output = OutputTimes::new(opts.output_interval, h);
    for step in 1..=n_steps {
        let t = step as f64 * h;
        drive.kick(beam, t - h, &mut vf, &mass, &mut mv);
        half_kick(&mut vf, &af, h);
        add_free(beam, &mut q, h, &vf);
        beam.move_supports(&mut q, t);
        let ev = beam
            .internal(&q, &slip, &mut trial, &mut force, None, Some(&mut pts_new))
            .map_err(fail(t, step))?;
        accel(&force, &mut af);
        half_kick(&mut vf, &af, h);
        finite_velocity(&vf, t, step)?;
        slip.copy_from_slice(&trial);
        ledger.dissipate(ev.slip_work, &pts, &pts_new);
        drive.end_step(beam, &q, &vf, &force);
        std::mem::swap(&mut pts, &mut pts_new);
        en = ledger.energies(beam, t, &q, &vf, &drive, &mut mv, ev.energy);
        supplied = supplied.max(ledger.supplied(&en));
        ledger.check_stable(supplied, t, h, stable)?;
        if output.due(t, step == n_steps) {
            scatter_velocity(beam, &vf, &drive, &mut v);
            observer(Frame {
                t,
                q: &q,
                v: &v,
                energies: en,
                points: &pts,
                slip: &slip,
            });
        }
    }
    scatter_velocity(beam, &vf, &drive, &mut v);
    Ok(DynamicSummary {
        time_step: h,
        stable_step: Some(stable),
        steps: n_steps,
        newton_iterations: 0,
        factorizations: 1,
        rebuilds: Rebuilds::default(),
        iteration_histogram: [0; 12],
        cut_steps: 0,
        balance_error: ledger.balance_error,
        max_kinetic: ledger.max_kinetic,
        balance_floor: ledger.floor(),
        last: en,
        q,
        v,
        slip,
    })
}
