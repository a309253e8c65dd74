//! The generalized-alpha integrator (Chung-Hulbert parameters in the Arnold-Bruels form): its
//! state, a step (the predictor, Newton's iteration in [`newton`] with its acceptance test in
//! [`convergence`], the accepted iterate's commit, halving on failure) and the run with its
//! output frames.

mod convergence;
mod newton;

use super::{
    DynamicError, DynamicOptions, DynamicSummary, Frame, Ledger, Rebuilds, SlipPredictor,
    non_potential_work, scatter_velocity, steps_for,
};
use crate::band::{BandMatrix, BandSolver};
use crate::beam::{Beam, ElementKind, Evaluation, PointState, Tangent};
use crate::corotation::Corotation;
use crate::initial::InitialState;
use crate::measure::{Lengths, dot};
use crate::moving_support::Drive;
use crate::output_times::OutputTimes;
use crate::statics::{add_free, gather_free};
use convergence::Limits;
use strand_core::round_off::BalanceFloor;

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
    /// Copies the motion of `o`, not its slip state: a step changes the slip state only when
    /// it commits, so a step that fails leaves it as it was, and a state saved to restore
    /// one ([`AlphaWork::saved`]) need not hold it (on the Cardinal span of the Performance
    /// page, the slip state of 400 bending points of 60 wires made the copy 4 % of the run's
    /// instructions).
    fn copy_motion_from(&mut self, o: &AlphaState) {
        self.q.copy_from_slice(&o.q);
        self.vf.copy_from_slice(&o.vf);
        self.acc.copy_from_slice(&o.acc);
        self.alg.copy_from_slice(&o.alg);
        self.acc_last.copy_from_slice(&o.acc_last);
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
    /// Why they were built.
    rebuilds: Rebuilds,
    /// Steps taken in halves because Newton failed at their size.
    cuts: usize,
    /// Motions to restore when a step is cut, one per level of cutting (their slip states
    /// empty: [`AlphaState::copy_motion_from`]).
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
    /// for the planar element with a stick/slip law, and for the spatial element with the
    /// `hysteretic` law, whose slip work alone it leaves out (the only book of the spatial
    /// element that costs more than the moment's own terms).
    unbooked: bool,
    /// Largest stiffness of a node of the step's exact iteration matrix, apart from the
    /// inertia term (N/m): Gershgorin row sums of the element matrices in length units over
    /// the two elements at a node, axially 2 x 2.6 EA / l for the stretch and as much again
    /// for the geometric stiffness of a tension up to EA, in bending 2 x 36 EI / l^3 with the
    /// law's largest (stick) bending stiffness ([`Limits`]).
    node_stiffness: f64,
    /// Gershgorin bound of the consistent mass at a node in length units (kg): 2 x 0.583 of
    /// an element's mass, rounded up to 2 m l.
    node_mass: f64,
    /// Round-off of a node's residual force (N): that of the internal force
    /// ([`BalanceFloor::node_force`]).
    force_floor: f64,
    /// The factor the iteration matrix is taken times (1: as built): a test's deliberately
    /// inexact matrix.
    matrix_scale: f64,
    /// Energy scale of the run so far (J): the largest ledger energy seen
    /// ([`Energies::largest`](crate::dynamics::Energies::largest)) or, if larger, the work of the strand's inertial force at a
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
            let trial = &mut self.trial;
            beam.internal_unbooked(&st.q, &st.slip, trial, &mut self.force, k, pts_new)
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

/// The generalized-alpha parameters of a step of `h` (s), with the factors `beta'` and
/// `gamma'` that turn a change of the coordinates into the changes of the acceleration and
/// the velocity.
#[derive(Debug, Clone, Copy)]
struct Parameters {
    am: f64,
    af: f64,
    gamma: f64,
    beta: f64,
    beta_p: f64,
    gamma_p: f64,
    h: f64,
}

impl Parameters {
    fn new(rho: f64, h: f64) -> Parameters {
        let (am, af, gamma, beta) = alpha_parameters(rho);
        Parameters {
            am,
            af,
            gamma,
            beta,
            beta_p: (1.0 - am) / (h * h * beta * (1.0 - af)),
            gamma_p: gamma / (h * beta),
            h,
        }
    }
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
    let p = Parameters::new(rho, h);
    let level = w.saved.len() - depth - 1;
    w.saved[level].copy_motion_from(st);
    predict(beam, opts, &p, t0, st, w);
    let limits = limits(beam, opts, &p, st, w);
    let (outcome, iterations) = newton::solve(beam, opts, &p, &limits, st, w, pts_new);
    match outcome {
        Some(ev) => Ok(commit(beam, &p, st, w, pts, pts_new, ev, iterations)),
        None if depth > 0 => {
            st.copy_motion_from(&w.saved[level]);
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

/// Moves `st` to the predicted end of the step that starts at `t0` (s).
fn predict(
    beam: &Beam,
    opts: &DynamicOptions,
    p: &Parameters,
    t0: f64,
    st: &mut AlphaState,
    w: &mut AlphaWork,
) {
    let Parameters {
        am,
        af,
        gamma,
        beta,
        h,
        ..
    } = *p;
    let nf = beam.dofs();
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
    //
    // A strand of several layers predicts with zero acceleration (`layers_predictor`): its
    // slipping layers give way at K_min, many times below K_max, so that wires starting or
    // stopping to slip kick its fast modes harder, as on the chattering strand above. On the
    // Cardinal span of the Performance page (with `keep_slow_fresh`), iterations (matrices)
    // with the mean and with zero acceleration over 0.5 s: 3015 (693) and 2709 (459); over
    // 2 s: 8359 (855) and 7568 (509); constant acceleration over 0.5 s: 3454 (813).
    let zero =
        !linear && beam.law().layer_count() > 1 && opts.layers_predictor == SlipPredictor::Zero;
    if linear {
        w.acc_pred.copy_from_slice(&st.acc);
    } else {
        for i in 0..nf {
            w.acc_pred[i] = if zero {
                0.0
            } else {
                0.5 * (st.acc[i] + st.acc_last[i])
            };
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
}

/// The convergence limits of the step predicted at `st`.
fn limits(
    beam: &Beam,
    opts: &DynamicOptions,
    p: &Parameters,
    st: &AlphaState,
    w: &mut AlphaWork,
) -> Limits {
    let Parameters { beta_p, h, .. } = *p;
    let linear = beam.law().is_linear();
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
    Limits {
        tol,
        energy_tol,
        ledger_tol,
        stiffness: beta_p * w.node_mass + w.node_stiffness,
        force_floor: w.force_floor,
    }
}

/// Commits the accepted iterate `ev` of a step that took `iterations`: its books (where the
/// iterations left them out, [`AlphaWork::unbooked`]), the algorithmic acceleration, the slip state and the
/// bending points, with the step's non-potential work.
#[allow(clippy::too_many_arguments)]
fn commit(
    beam: &Beam,
    p: &Parameters,
    st: &mut AlphaState,
    w: &mut AlphaWork,
    pts: &mut [PointState],
    pts_new: &mut [PointState],
    mut ev: Evaluation,
    iterations: usize,
) -> StepOutcome {
    let Parameters { am, af, .. } = *p;
    let nf = beam.dofs();
    if w.unbooked {
        // The books of the accepted iterate that the iterations left out.
        beam.book_points(&st.slip, &mut w.trial, pts_new, &mut ev);
    }
    for i in 0..nf {
        st.alg[i] += (1.0 - af) / (1.0 - am) * (st.acc[i] - w.acc_pred[i]);
    }
    st.slip.copy_from_slice(&w.trial);
    let non_potential = non_potential_work(pts, pts_new);
    pts.copy_from_slice(pts_new);
    StepOutcome {
        iterations,
        slip_work: ev.slip_work,
        non_potential,
        elastic: ev.energy,
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

/// Halvings of a generalized-alpha step before the run stops.
const MAX_CUTS: usize = 10;

/// Runs the generalized-alpha dynamics of `beam` from `init` at steps of about `h` (s) and
/// spectral radius `rho`, with the iteration matrix taken `matrix_scale` times (1: as built).
pub(super) fn generalized_alpha(
    beam: &Beam,
    opts: &DynamicOptions,
    init: &InitialState,
    h: f64,
    rho: f64,
    matrix_scale: f64,
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
        rebuilds: Rebuilds::default(),
        cuts: 0,
        saved: (0..=MAX_CUTS)
            .map(|_| AlphaState {
                slip: Vec::new(),
                ..new_state()
            })
            .collect(),
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
        unbooked: match beam.spec().element {
            ElementKind::Planar => !beam.law().is_linear(),
            ElementKind::Spatial => beam.law().kind().has_state(),
        },
        node_stiffness: {
            let l = beam.element_length();
            let law = beam.law();
            4.0 * 2.6 * law.axial_stiffness() / l + 72.0 * law.stick_bending_stiffness() / l.powi(3)
        },
        node_mass: 2.0 * beam.spec().mass_per_length * beam.element_length(),
        force_floor: BalanceFloor::new(
            beam.law().axial_stiffness(),
            beam.law().stick_bending_stiffness(),
            beam.length(),
            beam.spec().elements,
        )
        .node_force(),
        matrix_scale,
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
    let mut iteration_histogram = [0; 12];
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
        iteration_histogram[(out.iterations.max(1) - 1).min(11)] += 1;
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
        rebuilds: w.rebuilds,
        iteration_histogram,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{BeamSpec, Support};
    use crate::dynamics::Scheme;
    use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

    /// The section-3 pendulum (L = 1 m, E = 2e9 Pa) on 8 planar elements, released
    /// horizontal, 0.2 s at 1e-3 s steps, with the iteration matrix taken `scale` times.
    fn swing(scale: f64) -> Result<DynamicSummary, DynamicError> {
        let s = Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap();
        let beam = Beam::new(
            BeamSpec {
                elements: 8,
                bending_points: None,
                mass_per_length: s.mass_per_length(),
                element: ElementKind::Planar,
                direction: [1.0, 0.0, 0.0],
                gravity: [0.0, -9.8, 0.0],
                start: Some(Support::Pinned),
                end: None,
                ..Default::default()
            },
            SectionLaw::new(&s, LawKind::Constant),
        )
        .unwrap();
        let scheme = Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 0.9,
        };
        let opts = DynamicOptions::new(0.2, scheme, 0.1);
        let init = InitialState::rest(&beam);
        generalized_alpha(&beam, &opts, &init, 1e-3, 0.9, scale, &mut |_| {})
    }

    /// A deliberately stale matrix, 1e8 times stiffer than the tangent, makes corrections
    /// 1e8 times too small: the iteration stalls where it starts, each correction below the
    /// tolerance or within round-off. Accepted on the correction alone, the run ended `ok` on
    /// the predictor's trajectory, its tip 6.3 cm above the right one at 0.2 s (y = -0.1960
    /// against -0.2586 m). The residual test refuses a step once the error the stall leaves
    /// has built up to a residual above what the step's stiffness bound allows (step 75), and
    /// Newton reports that it did not converge. The matrix as built runs.
    #[test]
    fn a_stalled_iteration_is_not_accepted() {
        let ok = swing(1.0).unwrap();
        assert_eq!(ok.steps, 200);
        match swing(1e8) {
            Err(DynamicError::Newton { step, .. }) => assert!(step < 200, "{step}"),
            other => panic!("a stalled iteration was accepted: {other:?}"),
        }
    }
}
