//! Static equilibrium `Q_e(q) = lambda Q_g` (SPEC 5) by continuation in the load factor
//! lambda from 0 to 1.
//!
//! The equilibrium path of a soft strand is far from linear in the load: the section-3
//! cantilever (q L^3 / K_min of about 120) drops most of its way under the first few per cent
//! of its weight and then hangs, stiffening as it straightens. Equal load steps are too large
//! at the start and too small at the end, and a step's Newton iteration from the last state
//! crosses the large rotations of the soft start with a linear tangent (it took 250 load steps,
//! 3882 iterations and 52 cut steps on the section-3 strand under g = 12). So the steps follow
//! the path instead:
//!
//! * step length: measured along the path as the largest displacement of the strand (slopes
//!   counted by the displacement they make across an element), adapted to the Newton
//!   iterations of the last step;
//! * predictor: along the secant through the last two equilibria (the tangent `K^-1 Q_g` at the
//!   start), so the load factor of a step follows from its displacement;
//! * corrector: Newton on the equilibrium and the pseudo arc-length condition that the
//!   correction is orthogonal (in length units) to the predictor's displacement (Keller), by
//!   bordering: two solves with one factorization. The load factor is an unknown, so a path
//!   that turns back in the load (a limit point) is followed through it. The last step ends at
//!   lambda = 1 exactly: Newton at fixed load from the predictor where it crosses 1.
//! * globalization: Deuflhard's natural monotonicity test as line search (affine invariant, so
//!   the large transient axial residuals of a thin beam do not stall it); a step whose Newton
//!   iteration fails is cut in half and retried.
//!
//! The `hysteretic` law's slip state is committed after every converged step, so its static
//! path follows the continuation steps: each step's return mapping starts from the last
//! step's slip. Under a load that only grows the wires load monotonically and the result
//! barely depends on the steps (measured in `tests/statics.rs`). The spatial element's section
//! frames are committed with it.
//!
//! Moving supports take the last row of their tables with the load factor. Their coordinates
//! follow the load factor, which the bordered corrector does not differentiate, so with moving
//! supports every step is corrected at the fixed load factor of its predictor (the secant
//! predictor still sets the steps along the path); the start's tangent includes the equivalent
//! load of the supports' displacement.

use strand_core::LawKind;

use crate::band::{BandMatrix, BandSolver};
use crate::beam::{Beam, BeamError, PointState};
use crate::measure::Lengths;

/// Newton corrections below this fraction of the tolerance times the strand's motion (its
/// largest displacement, at most its length; in the displacement they make) are taken in full
/// and end the iteration.
const CORRECTION: f64 = 1.0;

/// Settings of the static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// The first step's size: the load fraction `1 / load_steps`, or less, so that the strand
    /// moves by at most `1 / load_steps` of its length in it. Later steps adapt.
    pub load_steps: usize,
    /// Convergence: residual norm below `tolerance` times the norm of the full load (the dead
    /// load, or the equivalent load of a moving support's displacement if larger) plus the
    /// round-off the residual carries (the forces' sensitivity to the unit round-off of the
    /// coordinates, `eps |K| |q|`).
    pub tolerance: f64,
    /// Newton iterations per step before the step is cut.
    pub max_iterations: usize,
    /// Smallest step, as a fraction of the strand length, before giving up.
    pub min_step: f64,
    /// Most load steps tried (accepted or cut) beyond `load_steps` before giving up: a path
    /// of steps near `min_step` that converge and grow and are cut again would otherwise take
    /// up to `1 / min_step` steps of up to `max_iterations` Newton iterations each.
    pub max_attempts: usize,
    /// Largest step, as a fraction of the strand length.
    pub max_step: f64,
    /// Newton iterations a step aims at: the next step grows or shrinks by the square root of
    /// this over the iterations the last one took (within a factor of 2).
    pub target_iterations: usize,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions {
            load_steps: 20,
            tolerance: 1e-9,
            max_iterations: 30,
            min_step: 1e-9,
            max_attempts: 1000,
            max_step: 1.0,
            target_iterations: 5,
        }
    }
}

/// A converged static state.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticSolution {
    /// Coordinates, all of them.
    pub q: Vec<f64>,
    /// Committed per-point state (the law's slip state and the section frames).
    pub slip: Vec<f64>,
    /// State at every bending point.
    pub points: Vec<PointState>,
    /// Stored elastic energy (J).
    pub energy: f64,
    /// Accepted steps.
    pub steps: usize,
    /// Newton iterations in total (accepted and rejected steps).
    pub iterations: usize,
    /// Steps that were cut.
    pub cuts: usize,
    /// Final residual norm relative to the load.
    pub residual: f64,
}

/// Why a static solve failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticError {
    /// The step shrank below the minimum.
    #[error(
        "no equilibrium found beyond load fraction {reached:.6} of the full load: the step \
         fell below {min_step:e} of the strand length ({law} law){detail}"
    )]
    Stalled {
        /// Load fraction of the last converged state.
        reached: f64,
        /// The minimum step.
        min_step: f64,
        /// The section law's name.
        law: &'static str,
        /// What the last attempt reported.
        detail: String,
        /// The last converged state (at load fraction `reached`), for the result files;
        /// `None` if it could not be evaluated.
        last: Option<Box<StaticSolution>>,
    },
    /// The solver tried more load steps than its budget allows.
    #[error(
        "no equilibrium found beyond load fraction {reached:.6} of the full load: the solver \
         tried {tried} load steps ({cuts} of them cut, the last of {step:.3e} of the load), its \
         budget ({law} law)"
    )]
    Budget {
        /// Load fraction of the last converged state.
        reached: f64,
        /// Load steps tried, accepted or cut.
        tried: usize,
        /// Load steps cut.
        cuts: usize,
        /// The load step when the solver stopped (fraction of the full load).
        step: f64,
        /// The section law's name.
        law: &'static str,
        /// The last converged state (at load fraction `reached`), for the result files;
        /// `None` if it could not be evaluated.
        last: Option<Box<StaticSolution>>,
    },
    /// Evaluation failed at the start.
    #[error(transparent)]
    Beam(#[from] BeamError),
}

/// Free part of `v` into `out`.
pub(crate) fn gather_free(beam: &Beam, v: &[f64], out: &mut [f64]) {
    if let Some(span) = beam.free_span() {
        out.copy_from_slice(&v[span]);
        return;
    }
    for (g, x) in v.iter().enumerate() {
        if let Some(i) = beam.free_index(g) {
            out[i] = *x;
        }
    }
}

/// `q[g] += s * dq[free(g)]` for the free coordinates.
pub(crate) fn add_free(beam: &Beam, q: &mut [f64], s: f64, dq: &[f64]) {
    if let Some(span) = beam.free_span() {
        for (x, d) in q[span].iter_mut().zip(dq) {
            *x += s * d;
        }
        return;
    }
    for (g, x) in q.iter_mut().enumerate() {
        if let Some(i) = beam.free_index(g) {
            *x += s * dq[i];
        }
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Workspace of one Newton solve.
struct Work {
    force: Vec<f64>,
    r: Vec<f64>,
    dq: Vec<f64>,
    s: Vec<f64>,
    /// `K^-1 Q_g` (free coordinates): the correction's response to the load factor.
    b: Vec<f64>,
    trial: Vec<f64>,
    q_try: Vec<f64>,
    k: BandMatrix,
    solver: BandSolver,
    /// Length measures of the free coordinates.
    lengths: Lengths,
    /// Workspace of [`converged`].
    round_off: [Vec<f64>; 2],
    /// Workspace of [`within_measured_round_off`]: coordinates, forces, trial state.
    probe: Probe,
}

impl Work {
    /// The workspace of a solve of `beam`, the iterate at its reference.
    fn new(beam: &Beam) -> Self {
        let n = beam.dofs();
        let b = beam.bandwidth();
        Work {
            force: vec![0.0; beam.coords()],
            r: vec![0.0; n],
            dq: vec![0.0; n],
            s: vec![0.0; n],
            b: vec![0.0; n],
            trial: beam.initial_state(),
            q_try: beam.reference().to_vec(),
            k: BandMatrix::zeros(n, b, b),
            solver: BandSolver::default(),
            lengths: Lengths::of(beam),
            round_off: [vec![0.0; n], vec![0.0; n]],
            probe: Probe {
                q: vec![0.0; beam.coords()],
                force: vec![0.0; beam.coords()],
                trial: beam.initial_state(),
                spread: vec![0.0; n],
            },
        }
    }
}

/// Buffers of [`within_measured_round_off`], apart from the iteration's own so that the
/// iterate's trial state, residual and tangent are left as they are.
struct Probe {
    q: Vec<f64>,
    force: Vec<f64>,
    trial: Vec<f64>,
    /// The largest change of each free residual component over the perturbations (N).
    spread: Vec<f64>,
}

/// Where a continuation step's corrector may move: along the pseudo arc-length hyperplane
/// orthogonal to `direction` (the predictor's displacement, free coordinates), the load
/// factor with it; or at the fixed load factor of the predictor.
enum Constraint<'a> {
    ArcLength { direction: &'a [f64] },
    FixedLoad,
}

/// Solves the static problem of `beam` under its gravity load. `progress` receives the
/// converged load fraction after each step.
pub fn solve_static(
    beam: &Beam,
    opts: &StaticOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<StaticSolution, StaticError> {
    let n = beam.dofs();
    let mut w = Work::new(beam);
    let mut g_free = vec![0.0; n];
    gather_free(beam, beam.gravity_force(), &mut g_free);
    // A moving support loads the strand too: the elastic force of its displacement with the
    // rest of the strand straight, the equivalent load of the displacement (taken at a small
    // fraction of it, where the strand responds linearly, and scaled up).
    let mut support_load = vec![0.0; n];
    if beam.has_moving_supports() {
        let fraction = 1e-6;
        beam.move_supports_static(&mut w.q_try, fraction);
        let slip = beam.initial_state();
        residual(beam, &mut w, &slip, &g_free, 0.0, false)?;
        for (p, r) in support_load.iter_mut().zip(&w.r) {
            *p = -r / fraction;
        }
        w.q_try.copy_from_slice(beam.reference());
    }
    let load_norm = norm(&g_free)
        .max(norm(&support_load))
        .max(f64::MIN_POSITIVE);
    let length = beam.length();
    let steps_hint = opts.load_steps.max(1) as f64;

    let mut q = beam.reference().to_vec();
    let mut slip = beam.initial_state();
    let mut lambda = 0.0;
    // The path's direction in (free coordinates, load factor), scaled to a unit largest
    // displacement: from the tangent at the start, then from the secant of the last step.
    let mut dir_q = vec![0.0; n];
    let mut dir_l;
    // The start's tangent: d q / d lambda = K^-1 (Q_g + the supports' equivalent load).
    residual(beam, &mut w, &slip, &g_free, 0.0, true)?;
    if !w.solver.factorize(&w.k) {
        return Err(StaticError::Stalled {
            reached: 0.0,
            min_step: opts.min_step,
            law: beam.law().kind().name(),
            detail: ": singular tangent at the start".into(),
            last: None,
        });
    }
    for ((d, g), p) in dir_q.iter_mut().zip(&g_free).zip(&support_load) {
        *d = g + p;
    }
    w.solver.solve(&mut dir_q);
    let first = w.lengths.displacement(&dir_q);
    // Step length (m): the first step's load fraction 1 / load_steps, or less so that the
    // strand moves by at most L / load_steps.
    let mut ds = if first > 0.0 && first.is_finite() {
        (first / steps_hint).min(length / steps_hint)
    } else {
        length / steps_hint
    }
    .min(opts.max_step * length);
    if first > 0.0 && first.is_finite() {
        dir_q.iter_mut().for_each(|x| *x /= first);
        dir_l = 1.0 / first;
    } else {
        // No load, or none the tangent resolves: one step at the full load.
        dir_q.fill(0.0);
        dir_l = f64::INFINITY;
    }
    let (mut steps, mut iterations, mut cuts) = (0, 0, 0);
    let mut residual_left = 0.0;
    let mut step_q = vec![0.0; n];
    // Set when a step's corrector carried the load factor past 1: the step is taken again to
    // end at lambda = 1.
    let mut finish = false;
    let budget = opts.load_steps.saturating_add(opts.max_attempts);
    while lambda < 1.0 {
        if steps + cuts >= budget {
            let last = solution(beam, &mut w, q, slip, (steps, iterations, cuts))
                .ok()
                .map(|mut s| {
                    s.residual = residual_left;
                    Box::new(s)
                });
            // The step length as a load fraction, along the last direction.
            let step = ds * dir_l;
            return Err(StaticError::Budget {
                reached: lambda,
                tried: steps + cuts,
                cuts,
                step: if step.is_finite() { step } else { 1.0 - lambda },
                law: beam.law().kind().name(),
                last,
            });
        }
        // Predictor along the direction; the step that would pass lambda = 1 ends there.
        let to_end = (1.0 - lambda) / dir_l;
        let last = finish || !(to_end > ds && dir_l > 0.0);
        let h = if last { to_end.min(ds).max(0.0) } else { ds };
        let h = if h.is_finite() { h } else { 0.0 };
        let target = if last { 1.0 } else { lambda + h * dir_l };
        w.q_try.copy_from_slice(&q);
        add_free(beam, &mut w.q_try, h, &dir_q);
        beam.move_supports_static(&mut w.q_try, target);
        let constraint = if last || beam.has_moving_supports() {
            Constraint::FixedLoad
        } else {
            Constraint::ArcLength { direction: &dir_q }
        };
        match newton(
            beam, opts, &mut w, &slip, &g_free, target, load_norm, constraint,
        ) {
            Ok((its, _, reached)) if reached > 1.0 => {
                iterations += its;
                finish = true;
            }
            Ok((its, res, reached)) => {
                iterations += its;
                residual_left = res;
                // The secant of this step is the next direction.
                for (g, x) in q.iter().enumerate() {
                    if let Some(i) = beam.free_index(g) {
                        step_q[i] = w.q_try[g] - x;
                    }
                }
                let moved = w.lengths.displacement(&step_q);
                if moved > 0.0 && reached != lambda {
                    for (d, x) in dir_q.iter_mut().zip(&step_q) {
                        *d = x / moved;
                    }
                    dir_l = (reached - lambda) / moved;
                }
                q.copy_from_slice(&w.q_try);
                slip.copy_from_slice(&w.trial);
                lambda = reached;
                steps += 1;
                progress(lambda);
                let target_its = opts.target_iterations.max(1) as f64;
                let factor = (target_its / its.max(1) as f64).sqrt().clamp(0.5, 2.0);
                ds = (ds * factor).min(opts.max_step * length);
            }
            Err((its, detail)) => {
                iterations += its;
                cuts += 1;
                // Retried along the path with half the step, not at the full load again.
                finish = false;
                ds *= 0.5;
                if ds < opts.min_step * length {
                    let law = beam.law().kind();
                    let why = if law == LawKind::Paper {
                        "; the `paper` law is non-monotone (the moment drops when a wire starts \
                         to slip, eq. (23)), so an equilibrium beyond the drop may not exist; \
                         the `continuous` law is its monotone counterpart"
                    } else {
                        ""
                    };
                    let last = solution(beam, &mut w, q, slip, (steps, iterations, cuts))
                        .ok()
                        .map(|mut s| {
                            s.residual = residual_left;
                            Box::new(s)
                        });
                    return Err(StaticError::Stalled {
                        reached: lambda,
                        min_step: opts.min_step,
                        law: law.name(),
                        detail: format!(": {detail}{why}"),
                        last,
                    });
                }
            }
        }
    }
    let mut sol = solution(beam, &mut w, q, slip, (steps, iterations, cuts))?;
    sol.residual = residual_left;
    Ok(sol)
}

/// The solution at the converged state `(q, slip)` with its bending-point states and energy;
/// `counts` are the accepted steps, the Newton iterations and the cut steps.
fn solution(
    beam: &Beam,
    w: &mut Work,
    q: Vec<f64>,
    slip: Vec<f64>,
    (steps, iterations, cuts): (usize, usize, usize),
) -> Result<StaticSolution, BeamError> {
    let mut points = vec![PointState::default(); beam.points()];
    let ev = beam.internal(
        &q,
        &slip,
        &mut w.trial,
        &mut w.force,
        None,
        Some(&mut points),
    )?;
    Ok(StaticSolution {
        q,
        slip,
        points,
        energy: ev.energy,
        steps,
        iterations,
        cuts,
        residual: 0.0,
    })
}

/// Residual `Q_e - lambda Q_g` of the free coordinates at `w.q_try`; its norm.
fn residual(
    beam: &Beam,
    w: &mut Work,
    slip: &[f64],
    g_free: &[f64],
    lambda: f64,
    with_tangent: bool,
) -> Result<f64, BeamError> {
    let k = with_tangent.then_some(&mut w.k);
    beam.internal(&w.q_try, slip, &mut w.trial, &mut w.force, k, None)?;
    for (g, f) in w.force.iter().enumerate() {
        if let Some(i) = beam.free_index(g) {
            w.r[i] = f - lambda * g_free[i];
        }
    }
    let r = norm(&w.r);
    if r.is_finite() {
        Ok(r)
    } else {
        let i = w.r.iter().position(|v| !v.is_finite()).unwrap_or(0);
        let (element, x) = locate(beam, i);
        Err(BeamError::NonFinite {
            element,
            x,
            quantity: "residual",
        })
    }
}

/// The unit round-offs a computed residual component may carry per unit of its sensitivity
/// `(|K| |q|)_i` (the sums and products of the force evaluation; at Newton's stall on the
/// section-3 strand the largest ratio was 11).
const ROUND_OFF: f64 = 16.0;

/// Whether the residual `w.r` at `w.q_try` is converged: every component within `tol` (N) or
/// within the round-off it carries, estimated from the forces' sensitivity to the unit
/// round-off `eps` of the coordinates, [`ROUND_OFF`] `eps (|K| |q|)_i` with the tangent `w.k`
/// there. The stiff axial springs of a thin strand make that far larger than `eps` times the
/// load along the strand (Newton stalls at 1.3e-9 of the section-3 strand's weight), and
/// nothing across a straight strand, so that a tiny transverse load is still resolved.
///
/// A force is computed from differences of node positions, whose round-off is that of the
/// larger of the two: a position coordinate therefore counts with the extent of the strand
/// in its direction ([`position_extents`]), held nodes included, not with its own value. (A
/// strand held at `x = L` and pulled along x by 1e-6 N: its free node at the origin has
/// `|q| = 0`, yet its axial force carries `eps EA` from the held node's `x = L`; Newton left
/// 1.4e-5 of that load, all round-off, and the step was cut to nothing.)
fn converged(beam: &Beam, w: &mut Work, tol: f64) -> bool {
    let extents = position_extents(beam, &w.q_try);
    let nd = beam.node_coords();
    let [q, kq] = &mut w.round_off;
    for (g, x) in w.q_try.iter().enumerate() {
        if let Some(i) = beam.free_index(g) {
            let c = g % nd;
            q[i] = if c < nd / 2 {
                x.abs().max(extents[c])
            } else {
                x.abs()
            };
        }
    }
    w.k.abs_mul_vec(q, kq);
    w.r.iter()
        .zip(kq.iter())
        .all(|(r, f)| r.abs() <= tol + ROUND_OFF * f64::EPSILON * f)
}

/// The multiple of the residual's change under a one-unit-round-off move of the coordinates
/// that [`within_measured_round_off`] allows. The residual of the floating-point equilibrium
/// is itself one sample of that change; a few samples' worth allows for the spread between
/// samples.
const MEASURED_ROUND_OFF: f64 = 4.0;

/// Whether every component of the residual `w.r` at `w.q_try` is within `tol` (N) or within
/// [`MEASURED_ROUND_OFF`] times the change the residual shows when every coordinate moves by
/// its own unit round-off (two moves, with the signs of a fixed pattern and their opposite):
/// the round-off the residual carries, measured rather than estimated from the tangent as
/// [`converged`] does.
///
/// The estimate `eps (|K| |q|)_i` misses what the tangent leaves out: the law's strain is
/// recovered from the neighbouring elements' mean strains too (module `strain_recovery`),
/// and where the strand's tension is of the order of its round-off, the friction limits,
/// which follow the strain, move with that round-off. On a strand held at both ends under a
/// transverse load of 5e-5 N (strain 1e-12) the transverse residual changes under a one-ulp
/// move by up to 79 times the estimate, and Newton, whose corrections are then 1e-14 m,
/// cannot bring it below. Read only where Newton no longer makes progress (its line search
/// damped to [`STALLED_STEP`], a step that did not halve the residual norm, or its
/// iterations spent): a Newton iteration that still converges is left to meet
/// [`converged`]. Costs two force evaluations without tangent.
fn within_measured_round_off(
    beam: &Beam,
    w: &mut Work,
    slip: &[f64],
    tol: f64,
) -> Result<bool, BeamError> {
    let p = &mut w.probe;
    p.spread.fill(0.0);
    for sign in [1.0, -1.0] {
        for (g, (x, y)) in w.q_try.iter().zip(p.q.iter_mut()).enumerate() {
            // A fixed pattern of signs that looks random over the coordinates (the top bit of
            // a multiplicative hash): a pattern that moved every position alike would be a
            // rigid motion or a uniform stretch, which most forces do not feel.
            let s = if (g as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 63 == 0 {
                sign
            } else {
                -sign
            };
            *y = x + s * f64::EPSILON * x.abs();
        }
        beam.internal(&p.q, slip, &mut p.trial, &mut p.force, None, None)?;
        for (g, (f, f0)) in p.force.iter().zip(&w.force).enumerate() {
            if let Some(i) = beam.free_index(g) {
                p.spread[i] = p.spread[i].max((f - f0).abs());
            }
        }
    }
    Ok(w.r
        .iter()
        .zip(&p.spread)
        .all(|(r, d)| r.abs() <= tol + MEASURED_ROUND_OFF * d))
}

/// A line search that accepts no more than this fraction of Newton's correction marks an
/// iteration that no longer makes progress (see [`within_measured_round_off`]), as does a
/// step that leaves more than half the residual norm.
const STALLED_STEP: f64 = 1.0 / 16.0;

/// The largest absolute position coordinate of any node, held or free, per direction (m):
/// the size of the numbers whose differences make the strains.
fn position_extents(beam: &Beam, q: &[f64]) -> [f64; 3] {
    let nd = beam.node_coords();
    let mut extents = [0.0_f64; 3];
    for node in q.chunks_exact(nd) {
        for (e, x) in extents.iter_mut().zip(&node[..nd / 2]) {
            *e = e.max(x.abs());
        }
    }
    extents
}

/// The element (0-based) and material coordinate (m) of the node that free coordinate `i`
/// belongs to (the last element holds the end node).
fn locate(beam: &Beam, i: usize) -> (usize, f64) {
    let g = (0..beam.coords())
        .find(|&g| beam.free_index(g) == Some(i))
        .unwrap_or(0);
    let node = g / beam.node_coords();
    (
        node.min(beam.spec().elements - 1),
        node as f64 * beam.element_length(),
    )
}

/// `: the residual is largest at x = ... m (element e)`, where Newton left it.
fn largest_residual(beam: &Beam, r: &[f64]) -> String {
    let i = (0..r.len())
        .max_by(|&a, &b| r[a].abs().total_cmp(&r[b].abs()))
        .unwrap_or(0);
    let (element, x) = locate(beam, i);
    format!("; the residual is largest at x = {x:.4} m (node of element {element})")
}

/// Newton iterations from `w.q_try` at load fraction `lambda`, which `constraint` may let
/// move; Ok(iterations, relative residual, load fraction reached) or Err(iterations, reason).
///
/// Globalised by Deuflhard's natural monotonicity test: a trial step `alpha dq` is accepted
/// when the simplified Newton correction at the trial point, `K^-1 r(q - alpha dq)` with the
/// current factorization, is shorter than `(1 - alpha/4) |dq|`. Unlike a test on the residual
/// norm it is affine invariant, so the large transient axial residual that a good step of a
/// thin beam (EA l^2 >> EI) creates does not cause rejections. A step that reduces the
/// residual norm as much is accepted too: the tangent leaves out the neighbours' strains that
/// the section law reads (`Beam::internal`), and on coarse meshes its simplified correction
/// can grow along a soft direction while the full step cuts the residual a hundredfold (Table 1
/// strand, 8 elements, g = 8: the test alone damped every step to 1/64 and stalled).
#[allow(clippy::too_many_arguments)]
fn newton(
    beam: &Beam,
    opts: &StaticOptions,
    w: &mut Work,
    slip: &[f64],
    g_free: &[f64],
    mut lambda: f64,
    load_norm: f64,
    constraint: Constraint<'_>,
) -> Result<(usize, f64, f64), (usize, String)> {
    let tol = opts.tolerance * load_norm;
    let mut r0 = residual(beam, w, slip, g_free, lambda, true).map_err(|e| (0, e.to_string()))?;
    // Whether the last accepted step made no progress: damped to `STALLED_STEP` or below,
    // or leaving more than half the residual norm.
    let mut stalled = false;
    let at_round_off =
        |w: &mut Work| within_measured_round_off(beam, w, slip, tol).unwrap_or(false);
    for it in 1..=opts.max_iterations {
        if converged(beam, w, tol) || (stalled && at_round_off(w)) {
            return Ok((it - 1, r0 / load_norm, lambda));
        }
        if !w.solver.factorize(&w.k) {
            return Err((it, "singular tangent".into()));
        }
        // The correction q -= dq, lambda += dl: K dq = r - dl Q_g; with the arc-length
        // condition direction . dq = 0 (in length units), dl = (t . K^-1 r) / (t . K^-1 Q_g).
        w.dq.copy_from_slice(&w.r);
        w.solver.solve(&mut w.dq);
        let mut dl = 0.0;
        if let Constraint::ArcLength { direction } = constraint {
            w.b.copy_from_slice(g_free);
            w.solver.solve(&mut w.b);
            let tb = w.lengths.dot(direction, &w.b);
            if tb != 0.0 && tb.is_finite() {
                dl = w.lengths.dot(direction, &w.dq) / tb;
                for (d, bi) in w.dq.iter_mut().zip(&w.b) {
                    *d -= dl * bi;
                }
            }
        }
        let dn = norm(&w.dq);
        if !dn.is_finite() {
            return Err((it, "non-finite Newton step".into()));
        }
        // The strand's largest displacement from the reference (into `w.s`, free before the
        // line search).
        for (g, (x, x0)) in w.q_try.iter().zip(beam.reference()).enumerate() {
            if let Some(i) = beam.free_index(g) {
                w.s[i] = x - x0;
            }
        }
        let motion = w.lengths.displacement(&w.s).min(beam.length());
        if w.lengths.displacement(&w.dq) <= CORRECTION * opts.tolerance * motion {
            // Newton's correction, its estimate of the distance to the equilibrium, moves no
            // point of the strand by more than the tolerance times the strand's motion: taken
            // in full, the state is converged. Near it the monotonicity test compares
            // corrections in the residual's round-off, which the soft directions of the
            // tangent magnify, and would damp the steps that converge.
            add_free(beam, &mut w.q_try, -1.0, &w.dq);
            lambda += dl;
            r0 = residual(beam, w, slip, g_free, lambda, false).map_err(|e| (it, e.to_string()))?;
            return Ok((it, r0 / load_norm, lambda));
        }
        let mut alpha = 1.0;
        loop {
            add_free(beam, &mut w.q_try, -alpha, &w.dq);
            let trial = residual(beam, w, slip, g_free, lambda + alpha * dl, true);
            let simplified = trial.as_ref().ok().map(|_| {
                w.s.copy_from_slice(&w.r);
                w.solver.solve(&mut w.s);
                if let Constraint::ArcLength { direction } = constraint {
                    let tb = w.lengths.dot(direction, &w.b);
                    if tb != 0.0 && tb.is_finite() {
                        let dl = w.lengths.dot(direction, &w.s) / tb;
                        for (d, bi) in w.s.iter_mut().zip(&w.b) {
                            *d -= dl * bi;
                        }
                    }
                }
                norm(&w.s)
            });
            match (trial, simplified) {
                (Ok(r), Some(sn))
                    if sn <= (1.0 - 0.25 * alpha) * dn
                        || r <= (1.0 - 0.25 * alpha) * r0
                        || alpha <= 1.0 / 64.0 =>
                {
                    stalled = alpha <= STALLED_STEP || r > 0.5 * r0;
                    r0 = r;
                    lambda += alpha * dl;
                    break;
                }
                (Err(e), _) if alpha <= 1.0 / 64.0 => return Err((it, e.to_string())),
                _ => {
                    add_free(beam, &mut w.q_try, alpha, &w.dq);
                    alpha *= 0.5;
                }
            }
        }
    }
    if converged(beam, w, tol) || at_round_off(w) {
        Ok((opts.max_iterations, r0 / load_norm, lambda))
    } else {
        Err((
            opts.max_iterations,
            format!(
                "Newton left a residual of {:.3e} of the load after {} iterations{}",
                r0 / load_norm,
                opts.max_iterations,
                largest_residual(beam, &w.r)
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{BeamSpec, ElementKind, Support};
    use strand_core::{SectionLaw, Strand, StrandSpec};

    /// The paper's strand, 1 m, held at both ends (clamped and pinned) under a small
    /// transverse load, with the `continuous` law at friction 1: the family whose continuation
    /// stalled at the round-off of its residual.
    fn held_strand(gravity: f64) -> Beam {
        let mut spec = StrandSpec::paper(1.0, 2.0e8, 7801.0);
        spec.friction = 1.0;
        let s = Strand::new(spec).unwrap();
        Beam::new(
            BeamSpec {
                elements: 8,
                bending_points: None,
                mass_per_length: s.mass_per_length(),
                element: ElementKind::Planar,
                direction: [1.0, 0.0, 0.0],
                gravity: [0.0, -gravity, 0.0],
                start: Some(Support::Clamped),
                end: Some(Support::Pinned),
                ..Default::default()
            },
            SectionLaw::new(&s, LawKind::Continuous),
        )
        .unwrap()
    }

    /// The measured round-off accepts the solver's equilibrium and rejects it moved by
    /// 1e-12 of the strand's length at one node: a move of a thousand times the unit
    /// round-off of the coordinates it changes, which the forces resolve. It fails with the
    /// allowance a million times larger.
    #[test]
    fn measured_round_off_accepts_the_equilibrium_and_rejects_a_moved_one() {
        let beam = held_strand(1e-3);
        let sol = solve_static(&beam, &StaticOptions::default(), &mut |_| {}).unwrap();
        let mut w = Work::new(&beam);
        let mut g_free = vec![0.0; beam.dofs()];
        gather_free(&beam, beam.gravity_force(), &mut g_free);
        let tol = StaticOptions::default().tolerance * norm(&g_free);
        w.q_try.copy_from_slice(&sol.q);
        residual(&beam, &mut w, &sol.slip, &g_free, 1.0, true).unwrap();
        // The solve ends once Newton's correction is below the tolerance times the motion;
        // full Newton steps from there take the residual down to its round-off.
        for _ in 0..3 {
            assert!(w.solver.factorize(&w.k));
            w.dq.copy_from_slice(&w.r);
            w.solver.solve(&mut w.dq);
            add_free(&beam, &mut w.q_try, -1.0, &w.dq);
            residual(&beam, &mut w, &sol.slip, &g_free, 1.0, true).unwrap();
        }
        assert!(within_measured_round_off(&beam, &mut w, &sol.slip, tol).unwrap());
        // The transverse position of the middle node.
        let g = (beam.spec().elements / 2) * beam.node_coords() + 1;
        assert!(beam.free_index(g).is_some());
        w.q_try[g] += 1e-12 * beam.length();
        residual(&beam, &mut w, &sol.slip, &g_free, 1.0, true).unwrap();
        assert!(!converged(&beam, &mut w, tol));
        assert!(!within_measured_round_off(&beam, &mut w, &sol.slip, tol).unwrap());
    }
}
