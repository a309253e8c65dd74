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

use crate::band::{BandMatrix, BandSolver};
use crate::beam::{Beam, BeamError, ElementKind, Evaluation, PointState, Tangent};
use crate::corotation::Corotation;
use crate::initial::InitialState;
use crate::measure::{Lengths, dot};
use crate::moving_support::Drive;
use crate::output_times::OutputTimes;
use crate::statics::{add_free, gather_free};
use strand_core::round_off::{BalanceFloor, Travel};

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
    /// matrix gives to slipping wires (see [`Tangent::Iteration`]). On the section-3 pendulum
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
        }
    }

    /// The balance error round-off alone can make so far (J).
    fn floor(&self) -> f64 {
        self.floor.work(self.path.distance)
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
            generalized_alpha(beam, opts, init, step, spectral_radius, observer)
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
        for i in 0..nf {
            vf[i] += 0.5 * h * af[i];
        }
        add_free(beam, &mut q, h, &vf);
        beam.move_supports(&mut q, t);
        let ev = beam
            .internal(&q, &slip, &mut trial, &mut force, None, Some(&mut pts_new))
            .map_err(fail(t, step))?;
        accel(&force, &mut af);
        for i in 0..nf {
            vf[i] += 0.5 * h * af[i];
        }
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
        slip.copy_from_slice(&trial);
        ledger.dissipate(ev.slip_work, &pts, &pts_new);
        drive.end_step(beam, &q, &vf, &force);
        std::mem::swap(&mut pts, &mut pts_new);
        en = ledger.energies(beam, t, &q, &vf, &drive, &mut mv, ev.energy);
        // Energy given to the strand so far: the initial state's, gravity's and the supports'
        // work and the law's non-potential work (each in absolute value, a bound).
        supplied = supplied
            .max(ledger.e0.abs() + en.gravity.abs() + en.supports.abs() + en.non_potential.abs());
        // Above the round-off floor too: a strand at rest is moved by round-off alone, and its
        // balance error is then of the size of all it was given.
        if ledger.balance_error > supplied + ledger.floor() {
            return Err(DynamicError::Diverged {
                t,
                error: ledger.balance_error,
                supplied,
                step: h,
                stable,
            });
        }
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

/// State of the generalized-alpha integrator (free coordinates) and its workspace.
struct AlphaState {
    q: Vec<f64>,
    vf: Vec<f64>,
    /// True acceleration q''.
    acc: Vec<f64>,
    /// Algorithmic acceleration a.
    alg: Vec<f64>,
    /// True acceleration at the start of the last step, q''_{n-1} (the predictor of the
    /// stick/slip laws).
    acc_last: Vec<f64>,
    slip: Vec<f64>,
}

impl AlphaState {
    fn copy_from(&mut self, o: &AlphaState) {
        self.q.copy_from_slice(&o.q);
        self.vf.copy_from_slice(&o.vf);
        self.acc.copy_from_slice(&o.acc);
        self.alg.copy_from_slice(&o.alg);
        self.acc_last.copy_from_slice(&o.acc_last);
        self.slip.copy_from_slice(&o.slip);
    }
}

struct AlphaWork {
    force: Vec<f64>,
    r: Vec<f64>,
    dq: Vec<f64>,
    mv: Vec<f64>,
    trial: Vec<f64>,
    g_free: Vec<f64>,
    k: BandMatrix,
    solver: BandSolver,
    /// Step size the factorized iteration matrix belongs to (0: none).
    factor_h: f64,
    /// Iteration matrices built and factorized.
    factorizations: usize,
    /// Steps taken in halves because Newton failed at their size.
    cuts: usize,
    /// States to restore when a step is cut, one per level of cutting.
    saved: Vec<AlphaState>,
    /// Turns the kept iteration matrix with the strand.
    rot: Corotation,
    /// Whether the next step starts with a fresh iteration matrix.
    stale: bool,
    /// The predicted q'' of the step: the algorithmic acceleration takes up the Newton
    /// corrections from there when the step is accepted.
    acc_pred: Vec<f64>,
    /// The last iteration's Newton correction (secant acceleration, in the step).
    last_correction: Vec<f64>,
    /// What the last iteration moved the coordinates by, negated.
    last_move: Vec<f64>,
    /// The secant direction u of the acceleration.
    secant: Vec<f64>,
    /// The algorithmic acceleration the step's tolerances are scaled with ([`Self::tolerance`]).
    alg_scale: Vec<f64>,
    /// Length measures of the free coordinates.
    lengths: Lengths,
    /// Mass of the strand (kg).
    mass: f64,
    /// Largest displacement from the reference configuration so far (m).
    motion: f64,
    /// Whether the Newton iterations evaluate the forces without the bending points' books
    /// ([`Beam::internal_unbooked`]), which the accepted iterate's are then completed with:
    /// for the planar element with a stick/slip law.
    unbooked: bool,
    /// Energy scale of the run so far (J): the largest ledger energy seen
    /// ([`Energies::largest`]) or, if larger, the work of the strand's inertial force at a
    /// step's prediction over the tolerance's motion scale (mass times the root mean square of
    /// the acceleration times that length), which gives a strand released from rest a scale at
    /// its first step.
    energy: f64,
}

impl AlphaWork {
    /// Evaluates the forces (and, if asked, the tangent into `k`) at `st` and the Newton
    /// residual into `r`; `None` if the evaluation fails.
    fn evaluate(
        &mut self,
        beam: &Beam,
        st: &AlphaState,
        pts_new: &mut [PointState],
        tangent: Option<Tangent>,
    ) -> Option<Evaluation> {
        let k = tangent.map(|t| (&mut self.k, t));
        let ev = if self.unbooked {
            beam.internal_unbooked(&st.q, &st.slip, &mut self.force, k, pts_new)
        } else {
            beam.internal_with(
                &st.q,
                &st.slip,
                &mut self.trial,
                &mut self.force,
                k,
                Some(pts_new),
            )
        }
        .ok()?;
        beam.vector_mass().mul_vec(&st.acc, &mut self.mv);
        residual(beam, &self.mv, &self.force, &self.g_free, &mut self.r);
        Some(ev)
    }

    /// Newton tolerance of a step predicted at `st` (m): `increment` times the scale of the
    /// motion, the strand length or, if smaller, the largest of the displacement from the
    /// reference so far and of the distance the strand's current velocity and the algorithmic
    /// acceleration `alg` (their root mean square over the mass) carry it over the run's
    /// duration (a strand under a tiny load moves by tiny amounts, and an absolute tolerance
    /// would accept its predictor). Corrections within the round-off of their coordinates are
    /// converged too ([`Lengths::within_round_off`]).
    fn tolerance(
        &mut self,
        beam: &Beam,
        opts: &DynamicOptions,
        st: &AlphaState,
        alg: &[f64],
    ) -> f64 {
        let moved = self.lengths.distance(beam, &st.q, beam.reference());
        self.motion = self.motion.max(moved);
        let mut rms = |x: &[f64]| {
            beam.vector_mass().mul_vec(x, &mut self.mv);
            (dot(x, &self.mv) / self.mass).max(0.0).sqrt()
        };
        let t = opts.duration;
        let acceleration = rms(alg);
        let coming = rms(&st.vf) * t + 0.5 * acceleration * t * t;
        let scale = self.motion.max(coming).min(beam.length());
        self.energy = self.energy.max(self.mass * acceleration * scale);
        opts.increment * scale
    }
}

/// Generalized-alpha parameters for spectral radius `rho`: (alpha_m, alpha_f, gamma, beta).
fn alpha_parameters(rho: f64) -> (f64, f64, f64, f64) {
    let am = (2.0 * rho - 1.0) / (rho + 1.0);
    let af = rho / (rho + 1.0);
    let gamma = 0.5 + af - am;
    (am, af, gamma, 0.25 * (gamma + 0.5) * (gamma + 0.5))
}

/// Result of one accepted (possibly subdivided) step: Newton iterations, slip work and the
/// elastic energy at its end; `points` holds the bending-point states at its end.
struct StepOutcome {
    iterations: usize,
    slip_work: f64,
    non_potential: f64,
    elastic: f64,
}

/// Advances `st` by `h`; on Newton failure restores it and takes two half steps, down to
/// `depth` halvings.
#[allow(clippy::too_many_arguments)]
fn alpha_step(
    beam: &Beam,
    opts: &DynamicOptions,
    rho: f64,
    t0: f64,
    h: f64,
    depth: usize,
    st: &mut AlphaState,
    w: &mut AlphaWork,
    pts: &mut [PointState],
    pts_new: &mut [PointState],
) -> Result<StepOutcome, usize> {
    let (am, af, gamma, beta) = alpha_parameters(rho);
    let beta_p = (1.0 - am) / (h * h * beta * (1.0 - af));
    let gamma_p = gamma / (h * beta);
    let nf = beam.dofs();
    let level = w.saved.len() - depth - 1;
    w.saved[level].copy_from(st);
    let linear = beam.law().is_linear();
    // Predictor: constant acceleration, q''_{n+1} = q''_n, for a linear section law; for the
    // stick/slip laws the mean of the last two steps' accelerations, (q''_n + q''_{n-1}) / 2.
    // On the section-3 pendulum at 1e-3 s steps the constant acceleration leaves the constant
    // law's first correction about ten times smaller than zero acceleration does, so the
    // co-rotated matrix of the first step serves the whole run (2012 iterations and 2
    // matrices against 2287 and 51). With the stick/slip laws q''_n also carries the strand's
    // fast modes, which every wire that starts or stops slipping kicks and which, near the
    // step's own frequency, change sign from step to step: extrapolated, they make the
    // hysteretic law's Newton slower than zero acceleration does; the mean of two steps
    // cancels them and keeps the slow motion (on a strand hanging still and chattering,
    // `stick-slip-chatter` of `cargo xtask hard`, it mispredicts: 3.12 iterations a step
    // against 2.54 with zero acceleration). On that pendulum (with the matrix and the acceleration
    // below) Newton iterations (matrices) with zero acceleration, constant acceleration and
    // the mean: continuous 5068 (421), 4643 (535), 4250 (474); hysteretic 4807 (612), 5263
    // (1102), 4209 (602).
    if linear {
        w.acc_pred.copy_from_slice(&st.acc);
    } else {
        for i in 0..nf {
            w.acc_pred[i] = 0.5 * (st.acc[i] + st.acc_last[i]);
            // The algorithmic acceleration of a zero-acceleration prediction (below).
            w.alg_scale[i] = (af * st.acc[i] - am * st.alg[i]) / (1.0 - am);
        }
        st.acc_last.copy_from_slice(&st.acc);
    }
    for i in 0..nf {
        let pa = w.acc_pred[i];
        let a_new = (af * st.acc[i] + (1.0 - af) * pa - am * st.alg[i]) / (1.0 - am);
        w.dq[i] = h * st.vf[i] + h * h * ((0.5 - beta) * st.alg[i] + beta * a_new);
        st.vf[i] += h * ((1.0 - gamma) * st.alg[i] + gamma * a_new);
        st.alg[i] = a_new;
        st.acc[i] = pa;
    }
    add_free(beam, &mut st.q, 1.0, &w.dq);
    beam.move_supports(&mut st.q, t0 + h);
    // The tolerances scale with the predicted algorithmic acceleration (`AlphaWork::tolerance`)
    // and, for the stick/slip laws, with that of a zero-acceleration prediction, as before
    // their predictor extrapolated: the two-step mean's larger acceleration raises the energy
    // scale, which would loosen the ledger test below by about four times on the section-3
    // pendulum (4.8e-9 to 2.0e-8 J per step at t = 0.3 s).
    let tol = if linear {
        w.tolerance(beam, opts, st, &st.alg)
    } else {
        let alg = std::mem::take(&mut w.alg_scale);
        let tol = w.tolerance(beam, opts, st, &alg);
        w.alg_scale = alg;
        tol
    };
    // The energy of a rigid translation of the whole strand by `tol` in the metric of the
    // inertia term (J): `tol` for the root mean square of a correction over the mass.
    let energy_tol = beta_p * w.mass * tol * tol;
    // What the step may leave in the energy ledger (J): its share, h / T, of `opts.ledger`
    // times the energy scale (the acceptance test below).
    let ledger_tol = opts.ledger * w.energy * h / opts.duration;
    // Modified Newton: the factorized iteration matrix S = beta' M + K is kept across
    // iterations and steps and rebuilt when the step size changes or a correction shrinks by
    // less than `opts.refresh`; every force evaluation is exact, so the converged state is the
    // same as with full Newton. With a linear law the kept matrix is the exact tangent, also
    // turned node by node with the strand since it was built (`dq = R S^-1 R^T r`, module
    // `corotation`), and rebuilt at a step's start when the last step's final contraction was
    // slower than `opts.rebuild_rate`. With the stick/slip laws the matrix is the symmetric
    // one of [`Tangent::Iteration`] (LDL^T; no slower to converge than the exact tangent on
    // the section-3 pendulum), turned only while the nodes turn together
    // ([`Corotation::turns_together`]): where the strand bends or chatters under the kept
    // matrix (`long-run-100s` of `cargo xtask hard`, the soft Fig. 8 pendulum on 8 elements)
    // turning every node by its own slope took 60 % more iterations and twice the matrices
    // (2,100,007 and 475,770 against 1,313,426 and 222,357; one turn for the whole strand,
    // that of its mean slope, 1,768,053 and 374,359), and turning only coherent turns
    // 1,336,599 and 231,069 (all without the secant acceleration below). On the section-3
    // pendulum the turned matrix saves the `continuous` law iterations and matrices (no turn,
    // every node, coherent turns: 4727 (612), 4210 (380), 4489 (467), again without the
    // acceleration) and the hysteretic law next to none (4320 (770), 4304 (695), 4292 (698)).
    let tangent = if linear {
        Tangent::Exact
    } else {
        let unloading = if beam.law().kind().has_state() {
            opts.unloading
        } else {
            0.0
        };
        Tangent::Iteration { unloading }
    };
    let estimate = !beam.law().kind().has_state();
    let mut iterations = 0;
    let mut outcome = None;
    let mut fresh = w.factor_h != h || w.stale;
    w.stale = false;
    let mut prev = f64::INFINITY;
    let mut full_step = true;
    let mut history = false;
    let mut ev = w.evaluate(beam, st, pts_new, fresh.then_some(tangent));
    iterations += 1;
    while let Some(e) = ev {
        if fresh {
            w.k.add_scaled(beta_p, beam.mass());
            w.factorizations += 1;
            if !w.solver.factorize(&w.k) {
                w.factor_h = 0.0;
                break;
            }
            w.factor_h = h;
            w.rot.reset(&st.q);
        } else {
            w.rot.update(&st.q);
            if !linear && !w.rot.turns_together() {
                w.rot.clear();
            }
        }
        w.dq.copy_from_slice(&w.r);
        w.rot.apply(&mut w.dq, true);
        w.solver.solve(&mut w.dq);
        w.rot.apply(&mut w.dq, false);
        let dn = w.lengths.displacement(&w.dq);
        if !dn.is_finite() || dn > beam.length() {
            // Diverged: the step is retried in halves, with a fresh matrix.
            w.factor_h = 0.0;
            break;
        }
        // The Newton decrement r . dq (J): the drop of the step's incremental potential the
        // correction promises (for a linear problem, twice its distance to the minimum), and
        // the slope of that potential along -dq.
        let decrement = dot(&w.r, &w.dq);
        // The same correction in the inertia term's metric alone, beta' dq^T M dq (J).
        let inertial = {
            beam.vector_mass().mul_vec(&w.dq, &mut w.mv);
            beta_p * dot(&w.dq, &w.mv)
        };
        // Converged when the trajectory and the energy ledger both are.
        //
        // The trajectory: this correction, or the error left after it, is below `tol`. With
        // full steps contracting at the rate theta = dn / prev, the corrections still to come
        // add up to about dn theta / (1 - theta) (the estimate of Hairer and Wanner, IV.8),
        // which accepts a fast-converging iterate one iteration earlier. Not for a law with
        // slip state: the committed trial state belongs to the forces before this correction,
        // so the correction itself is the error (and its Newton path, which decides where the
        // slip is committed, is left as it was). Or the correction's root mean square over the
        // mass is below `tol` (`inertial <= energy_tol`): the displacement is a largest value,
        // and a correction of one wire's slip state near the free end, carrying almost no
        // mass, would hold it up.
        //
        // The ledger: the error left in the step's state, delta (the correction itself, or
        // theta / (1 - theta) of it), changes the total energy by about that share of
        // `ledger()` (below), and the later steps carry the changed total on: the integrator
        // conserves the energy it is given, so each step's error stays in the balance. With
        // gamma' ~ 1/h the same delta costs more energy the smaller the step, and the steps
        // are more: a tolerance on the correction's size (or its Newton decrement against
        // beta' m tol^2 ~ 1/h^2, the former test) leaves a balance error that grows as h
        // shrinks (on issue 16's tilted pendulum in its plane, 9.9e-5 and 4.0e-4 of the
        // largest kinetic energy at 0.25 and 0.125 ms, where the integrator's own is 2.0e-5
        // and 3.0e-6). Bounding each step's by `ledger_tol` = `opts.ledger` E h / T bounds
        // the run's, T / h steps of it, by `opts.ledger` E at every step size (a fixed share,
        // not one falling with h as the integrator's error does: below the step where that
        // error is `opts.ledger`, only the errors' partial cancelling keeps Newton's share
        // small). A correction within the round-off of its coordinates is accepted whatever
        // it changes: no iteration can make it smaller.
        //
        // The ledger uses the forces before this last correction, which moved q by about
        // `tol` and the elastic energy by O(tol |Q|): an error of that step's report alone,
        // not carried on.
        let theta = dn / prev;
        let contracting = estimate && full_step && prev.is_finite() && theta < 1.0;
        let (left, share) = if contracting {
            let share = theta / (1.0 - theta);
            (dn * share, share)
        } else {
            (f64::INFINITY, 1.0)
        };
        let trajectory = dn <= tol || left <= tol || inertial <= energy_tol;
        // The change of the ledger's total energy that the correction makes (J). The iterate's
        // velocity and acceleration follow q (v = v* + gamma' (q - q*), q'' likewise with
        // beta'), so the total, 1/2 v^T M v - Q_g . q + elastic, has the gradient
        // gamma' M v - Q_g + Q_e = gamma' M v - M q'' + r, and the correction -dq changes it by
        // (gamma' v - q'') . M dq + r . dq to first order; beta' dq^T M dq bounds the second
        // order (the kinetic part, gamma'^2/2 dq^T M dq, is half of it at spectral radius 0.9)
        // and guards a matrix that is not positive definite (a strand in compression, a matrix
        // kept from another state), whose decrement can be small for a large correction.
        let ledger = || {
            let first: f64 = st
                .vf
                .iter()
                .zip(&st.acc)
                .zip(&w.mv)
                .map(|((v, a), m)| (gamma_p * v - a) * m)
                .sum();
            (first + decrement).abs() + inertial
        };
        let converged = trajectory && share * ledger() <= ledger_tol;
        step_by(beam, st, &w.dq, 1.0, gamma_p, beta_p);
        if converged || w.lengths.within_round_off(beam, &w.dq, &st.q, 0.0) {
            if linear && !fresh && theta.is_finite() && theta > opts.rebuild_rate {
                w.stale = true;
            }
            outcome = Some(e);
            break;
        }
        if iterations >= opts.max_iterations {
            break;
        }
        // Secant acceleration of a slow kept matrix (Anderson mixing of depth one, Walker and
        // Ni 2011), for the stick/slip laws. Their matrix is stiffer than their tangent where
        // wires slip (the hysteretic law's `unloading` share: on the section-3 pendulum, with
        // no wire changing state, the corrections after a fresh matrix shrink by 0.48 per
        // iteration at 0.25, 0.24 at 0.1, 0.004 at 0), so modified Newton contracts linearly,
        // by theta per iteration.
        // Two corrections of the same matrix, c_k and c_{k-1}, with the move between their
        // iterates, d_{k-1}, give the secant estimate of the step to the root: the iterate
        // moves by -(c_k - g u), u = d_{k-1} + c_k - c_{k-1}, with g minimizing
        // |c_k - g (c_k - c_{k-1})|, when theta > 0.1 and the incremental potential still
        // falls along it (r . (c_k - g u) > 0). On the section-3 pendulum at 1e-3 s steps:
        // continuous 4489 (467) -> 4250 (474) iterations (matrices), hysteretic 4292 (698) ->
        // 4209 (602); on `long-run-100s`'s pendulum with either law, 20 s: 8.5 and 7.1 %
        // fewer iterations. The convergence tests above always judge the plain correction.
        let mut secant = None;
        if !linear && history && !fresh && theta.is_finite() && theta > 0.1 {
            let (mut dd, mut cd) = (0.0, 0.0);
            for i in 0..nf {
                let d = w.dq[i] - w.last_correction[i];
                dd += d * d;
                cd += w.dq[i] * d;
                w.secant[i] = w.last_move[i] + d;
            }
            let g = cd / dd;
            if g.is_finite() && g.abs() < MAX_SECANT {
                let falls = decrement - g * dot(&w.r, &w.secant);
                secant = (falls > 0.0).then_some((g, falls));
            }
        }
        if !linear {
            // The plain correction, before any secant step changes `dq`.
            w.last_correction.copy_from_slice(&w.dq);
        }
        let mut slope = decrement;
        if let Some((g, falls)) = secant {
            step_by(beam, st, &w.secant, -g, gamma_p, beta_p);
            for (d, u) in w.dq.iter_mut().zip(&w.secant) {
                *d -= g * u;
            }
            slope = falls;
        }
        let accelerated = secant.is_some();
        history = !linear;
        // Rebuild the iteration matrix when the last correction shrank by less than
        // `opts.refresh`: a stale tangent converges linearly at about that rate.
        fresh = dn > opts.refresh * prev;
        prev = dn;
        ev = w.evaluate(beam, st, pts_new, fresh.then_some(tangent));
        iterations += 1;
        // After a secant step the next correction's ratio to this one is no contraction rate.
        full_step = !accelerated;
        if history {
            w.last_move.copy_from_slice(&w.dq);
        }
        if fresh {
            history = false;
        }
        // Line search: where the potential rises again at the full correction (a stick/slip
        // kink was overshot: the slope -r . dq changed sign), step back to the root of the
        // slope's secant.
        let rises = dot(&w.r, &w.dq);
        if ev.is_some() && slope > 0.0 && rises < 0.0 {
            let alpha = slope / (slope - rises);
            if alpha < opts.backtrack && iterations < opts.max_iterations {
                step_by(beam, st, &w.dq, alpha - 1.0, gamma_p, beta_p);
                for d in &mut w.last_move {
                    *d *= alpha;
                }
                ev = w.evaluate(beam, st, pts_new, fresh.then_some(tangent));
                iterations += 1;
                full_step = false;
            }
        }
    }
    match outcome {
        Some(mut ev) => {
            if w.unbooked {
                // The books of the accepted iterate: its trial state, energy and slip work.
                let books = beam.book_points(&st.slip, &mut w.trial, pts_new);
                ev.energy += books.energy;
                ev.slip_work = books.slip_work;
                ev.slipping = books.slipping;
            }
            for i in 0..nf {
                st.alg[i] += (1.0 - af) / (1.0 - am) * (st.acc[i] - w.acc_pred[i]);
            }
            st.slip.copy_from_slice(&w.trial);
            let non_potential = non_potential_work(pts, pts_new);
            pts.copy_from_slice(pts_new);
            Ok(StepOutcome {
                iterations,
                slip_work: ev.slip_work,
                non_potential,
                elastic: ev.energy,
            })
        }
        None if depth > 0 => {
            st.copy_from(&w.saved[level]);
            w.cuts += 1;
            let a = alpha_step(beam, opts, rho, t0, 0.5 * h, depth - 1, st, w, pts, pts_new)?;
            let b = alpha_step(
                beam,
                opts,
                rho,
                t0 + 0.5 * h,
                0.5 * h,
                depth - 1,
                st,
                w,
                pts,
                pts_new,
            )?;
            Ok(StepOutcome {
                iterations: iterations + a.iterations + b.iterations,
                slip_work: a.slip_work + b.slip_work,
                non_potential: a.non_potential + b.non_potential,
                elastic: b.elastic,
            })
        }
        None => Err(iterations),
    }
}

/// Moves the generalized-alpha iterate by `-alpha dq`: coordinates, and velocities and
/// accelerations with them.
fn step_by(beam: &Beam, st: &mut AlphaState, dq: &[f64], alpha: f64, gamma_p: f64, beta_p: f64) {
    add_free(beam, &mut st.q, -alpha, dq);
    for ((v, a), d) in st.vf.iter_mut().zip(st.acc.iter_mut()).zip(dq) {
        *v -= alpha * gamma_p * d;
        *a -= alpha * beta_p * d;
    }
}

/// Newton residual of the free coordinates, `r = M q'' + Q_e - Q_g`, from `mv = M q''`,
/// the elastic forces of all coordinates and the free gravity forces.
fn residual(beam: &Beam, mv: &[f64], force: &[f64], g_free: &[f64], r: &mut [f64]) {
    gather_free(beam, force, r);
    for ((ri, m), g) in r.iter_mut().zip(mv).zip(g_free) {
        *ri = m + *ri - g;
    }
}

/// Largest secant factor g of the Newton acceleration in a generalized-alpha step (a larger
/// one extrapolates from two nearly equal corrections, where the iteration is not contracting).
const MAX_SECANT: f64 = 10.0;

/// Halvings of a generalized-alpha step before the run stops.
const MAX_CUTS: usize = 10;

fn generalized_alpha(
    beam: &Beam,
    opts: &DynamicOptions,
    init: &InitialState,
    h: f64,
    rho: f64,
    observer: &mut dyn FnMut(Frame<'_>),
) -> Result<DynamicSummary, DynamicError> {
    let (n_steps, h) = steps_for(opts.duration, h);
    let nf = beam.dofs();
    let b = beam.bandwidth();
    let zeros = vec![0.0; nf];
    let new_state = || AlphaState {
        q: init.q.clone(),
        vf: zeros.clone(),
        acc: zeros.clone(),
        alg: zeros.clone(),
        acc_last: zeros.clone(),
        slip: init.state.clone(),
    };
    let mut st = new_state();
    gather_free(beam, &init.v, &mut st.vf);
    let mut w = AlphaWork {
        force: vec![0.0; beam.coords()],
        r: zeros.clone(),
        dq: zeros.clone(),
        mv: zeros.clone(),
        trial: beam.initial_state(),
        g_free: zeros.clone(),
        k: BandMatrix::zeros(nf, b, b),
        solver: BandSolver::default(),
        factor_h: 0.0,
        factorizations: 0,
        cuts: 0,
        saved: (0..=MAX_CUTS).map(|_| new_state()).collect(),
        rot: Corotation::new(beam, beam.reference()),
        stale: false,
        acc_pred: zeros.clone(),
        alg_scale: zeros.clone(),
        last_correction: zeros.clone(),
        last_move: zeros.clone(),
        secant: zeros.clone(),
        lengths: Lengths::of(beam),
        mass: beam.spec().mass_per_length * beam.length(),
        motion: 0.0,
        energy: 0.0,
        unbooked: !beam.law().is_linear() && beam.spec().element == ElementKind::Planar,
    };
    gather_free(beam, beam.gravity_force(), &mut w.g_free);
    let mut v = vec![0.0; beam.coords()];
    let mut pts = vec![PointState::default(); beam.points()];
    let mut pts_new = pts.clone();
    let fail = |t: f64, step: usize| move |source| DynamicError::Beam { t, step, source };

    let ev = beam
        .internal(
            &st.q,
            &st.slip,
            &mut w.trial,
            &mut w.force,
            None,
            Some(&mut pts),
        )
        .map_err(fail(0.0, 0))?;
    let mut m = BandSolver::default();
    if !m.factorize(beam.mass()) {
        return Err(DynamicError::Singular("mass"));
    }
    for (g, f) in w.force.iter().enumerate() {
        if let Some(i) = beam.free_index(g) {
            st.acc[i] = w.g_free[i] - f;
        }
    }
    m.solve(&mut st.acc);
    st.alg.copy_from_slice(&st.acc);
    st.acc_last.copy_from_slice(&st.acc);
    let mut drive = Drive::new(beam, &st.q, &init.v, &w.force);
    let kinetic = beam.kinetic_energy(&st.vf, drive.velocity(), &mut w.mv);
    let mut ledger = Ledger::new(beam, &st.q, ev.energy + kinetic);
    let mut en = ledger.energies(beam, 0.0, &st.q, &st.vf, &drive, &mut w.mv, ev.energy);
    w.energy = en.largest();
    scatter_velocity(beam, &st.vf, &drive, &mut v);
    observer(Frame {
        t: 0.0,
        q: &st.q,
        v: &v,
        energies: en,
        points: &pts,
        slip: &st.slip,
    });
    let mut newton_iterations = 0;
    let mut output = OutputTimes::new(opts.output_interval, h);
    for step in 1..=n_steps {
        let t = step as f64 * h;
        drive.kick(beam, t - h, &mut st.vf, &m, &mut w.mv);
        let out = alpha_step(
            beam,
            opts,
            rho,
            t - h,
            h,
            MAX_CUTS,
            &mut st,
            &mut w,
            &mut pts,
            &mut pts_new,
        )
        .map_err(|iterations| DynamicError::Newton {
            t,
            step,
            iterations,
            law: beam.law().kind().name(),
        })?;
        newton_iterations += out.iterations;
        ledger.dissipated += out.slip_work;
        ledger.non_potential += out.non_potential;
        drive.end_step(beam, &st.q, &st.vf, &w.force);
        en = ledger.energies(beam, t, &st.q, &st.vf, &drive, &mut w.mv, out.elastic);
        w.energy = w.energy.max(en.largest());
        if output.due(t, step == n_steps) {
            scatter_velocity(beam, &st.vf, &drive, &mut v);
            observer(Frame {
                t,
                q: &st.q,
                v: &v,
                energies: en,
                points: &pts,
                slip: &st.slip,
            });
        }
    }
    scatter_velocity(beam, &st.vf, &drive, &mut v);
    Ok(DynamicSummary {
        time_step: h,
        stable_step: None,
        steps: n_steps,
        newton_iterations,
        factorizations: w.factorizations,
        cut_steps: w.cuts,
        balance_error: ledger.balance_error,
        max_kinetic: ledger.max_kinetic,
        balance_floor: ledger.floor(),
        last: en,
        q: st.q,
        v,
        slip: st.slip,
    })
}
