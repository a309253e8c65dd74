//! Static equilibrium `Q_e(q) = lambda Q_g` by Newton-Raphson with load stepping (SPEC 5).
//!
//! The load factor lambda rises from 0 to 1 in steps; each step is solved by Newton on the
//! analytic tangent with a backtracking line search on the residual norm. A step that fails
//! (no convergence, a singular tangent, a degenerate element) is cut in half and retried from
//! the last converged state; a step that converged quickly lets the next one grow. The
//! `hysteretic` law's slip state (and the spatial element's section frames) is committed after
//! every converged step, so the static path follows the load steps. Moving supports take the
//! last row of their tables with the load factor.

use strand_core::LawKind;

use crate::band::{BandMatrix, BandSolver};
use crate::beam::{Beam, BeamError, PointState};

/// Settings of the static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// Initial number of equal load steps.
    pub load_steps: usize,
    /// Convergence: residual norm below `tolerance` times the norm of the full load (the dead
    /// load, or the equivalent load of a moving support's displacement if larger), or a full
    /// Newton correction below `increment` times the strand length (the residual of stiff
    /// axial springs has a round-off floor of about eps_mach EA) with the residual below 1e-6
    /// of the load.
    pub tolerance: f64,
    /// Newton increment criterion, relative to the strand length.
    pub increment: f64,
    /// Newton iterations per step before the step is cut.
    pub max_iterations: usize,
    /// Smallest load step, as a fraction of the full load, before giving up.
    pub min_step: f64,
    /// Most load steps tried (accepted or cut) beyond `load_steps` before giving up: a path
    /// of steps near `min_step` that converge and grow and are cut again would otherwise take
    /// up to `1 / min_step` steps of up to `max_iterations` Newton iterations each.
    pub max_attempts: usize,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions {
            load_steps: 20,
            tolerance: 1e-9,
            increment: 1e-9,
            max_iterations: 30,
            min_step: 1e-7,
            max_attempts: 1000,
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
    /// Accepted load steps.
    pub steps: usize,
    /// Newton iterations in total (accepted and rejected steps).
    pub iterations: usize,
    /// Load steps that were cut.
    pub cuts: usize,
    /// Final residual norm relative to the load.
    pub residual: f64,
}

/// Why a static solve failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticError {
    /// The load step shrank below the minimum.
    #[error(
        "no equilibrium found beyond load fraction {reached:.6} of the full load: the load step \
         fell below {min_step:e} ({law} law){detail}"
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
    trial: Vec<f64>,
    q_try: Vec<f64>,
    k: BandMatrix,
    solver: BandSolver,
}

/// Solves the static problem of `beam` under its gravity load. `progress` receives the
/// converged load fraction after each step.
pub fn solve_static(
    beam: &Beam,
    opts: &StaticOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<StaticSolution, StaticError> {
    let n = beam.dofs();
    let b = beam.bandwidth();
    let mut w = Work {
        force: vec![0.0; beam.coords()],
        r: vec![0.0; n],
        dq: vec![0.0; n],
        s: vec![0.0; n],
        trial: beam.initial_state(),
        q_try: beam.reference().to_vec(),
        k: BandMatrix::zeros(n, b, b),
        solver: BandSolver::default(),
    };
    let mut g_free = vec![0.0; n];
    gather_free(beam, beam.gravity_force(), &mut g_free);
    let mut load_norm = norm(&g_free);
    if beam.has_moving_supports() {
        // A moving support loads the strand too: the elastic force of its displacement with
        // the rest of the strand straight, the equivalent load of the displacement (taken at
        // a small fraction of it, where the strand responds linearly, and scaled up).
        let fraction = 1e-6;
        beam.move_supports_static(&mut w.q_try, fraction);
        let slip = beam.initial_state();
        let r = residual(beam, &mut w, &slip, &g_free, 0.0, false)?;
        load_norm = load_norm.max(r / fraction);
        w.q_try.copy_from_slice(beam.reference());
    }
    let load_norm = load_norm.max(f64::MIN_POSITIVE);

    let mut q = beam.reference().to_vec();
    let mut slip = beam.initial_state();
    let mut lambda = 0.0;
    let mut step = 1.0 / opts.load_steps.max(1) as f64;
    let (mut steps, mut iterations, mut cuts) = (0, 0, 0);
    let mut residual = 0.0;
    let budget = opts.load_steps.saturating_add(opts.max_attempts);
    while lambda < 1.0 {
        if steps + cuts >= budget {
            let last = solution(beam, &mut w, q, slip, (steps, iterations, cuts))
                .ok()
                .map(|mut s| {
                    s.residual = residual;
                    Box::new(s)
                });
            return Err(StaticError::Budget {
                reached: lambda,
                tried: steps + cuts,
                cuts,
                step,
                law: beam.law().kind().name(),
                last,
            });
        }
        let target = (lambda + step).min(1.0);
        w.q_try.copy_from_slice(&q);
        beam.move_supports_static(&mut w.q_try, target);
        match newton(beam, opts, &mut w, &slip, &g_free, target, load_norm) {
            Ok((its, res)) => {
                iterations += its;
                residual = res;
                q.copy_from_slice(&w.q_try);
                slip.copy_from_slice(&w.trial);
                lambda = target;
                steps += 1;
                progress(lambda);
                if its <= opts.max_iterations / 4 {
                    step = (step * 1.5).min(1.0);
                }
            }
            Err((its, detail)) => {
                iterations += its;
                cuts += 1;
                step *= 0.5;
                if step < opts.min_step {
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
                            s.residual = residual;
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
    sol.residual = residual;
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

/// Newton iterations at load fraction `lambda` from `w.q_try`; Ok(iterations, relative
/// residual) or Err(iterations, reason).
///
/// Globalised by Deuflhard's natural monotonicity test: a trial step `alpha dq` is accepted
/// when the simplified Newton correction at the trial point, `K^-1 r(q - alpha dq)` with the
/// current factorization, is shorter than `(1 - alpha/4) |dq|`. Unlike a test on the residual
/// norm it is affine invariant, so the large transient axial residual that a good step of a
/// thin beam (EA l^2 >> EI) creates does not cause rejections.
fn newton(
    beam: &Beam,
    opts: &StaticOptions,
    w: &mut Work,
    slip: &[f64],
    g_free: &[f64],
    lambda: f64,
    load_norm: f64,
) -> Result<(usize, f64), (usize, String)> {
    let tol = opts.tolerance * load_norm;
    let small_step = opts.increment * beam.length();
    let mut r0 = residual(beam, w, slip, g_free, lambda, true).map_err(|e| (0, e.to_string()))?;
    for it in 1..=opts.max_iterations {
        if r0 <= tol {
            return Ok((it - 1, r0 / load_norm));
        }
        if !w.solver.factorize(&w.k) {
            return Err((it, "singular tangent".into()));
        }
        w.dq.copy_from_slice(&w.r);
        w.solver.solve(&mut w.dq);
        let dn = norm(&w.dq);
        if !dn.is_finite() {
            return Err((it, "non-finite Newton step".into()));
        }
        let mut alpha = 1.0;
        loop {
            add_free(beam, &mut w.q_try, -alpha, &w.dq);
            let trial = residual(beam, w, slip, g_free, lambda, true);
            let simplified = trial.as_ref().ok().map(|_| {
                w.s.copy_from_slice(&w.r);
                w.solver.solve(&mut w.s);
                norm(&w.s)
            });
            match (trial, simplified) {
                (Ok(r), Some(sn)) if sn <= (1.0 - 0.25 * alpha) * dn || alpha <= 1.0 / 64.0 => {
                    r0 = r;
                    break;
                }
                (Err(e), _) if alpha <= 1.0 / 64.0 => return Err((it, e.to_string())),
                _ => {
                    add_free(beam, &mut w.q_try, alpha, &w.dq);
                    alpha *= 0.5;
                }
            }
        }
        if alpha == 1.0 && dn <= small_step && r0 <= 1e-6 * load_norm {
            return Ok((it, r0 / load_norm));
        }
    }
    if r0 <= tol {
        Ok((opts.max_iterations, r0 / load_norm))
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
