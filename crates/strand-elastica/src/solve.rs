//! The cantilever problem, the shooting with load continuation and the sampled solution.

use crate::ElasticaError;
use crate::law::{PlanarLaw, invert_moment};

/// A planar cantilever of length L clamped at s = 0 under a uniform load q per unit material
/// length acting in -Y (gravity for q = mass per length times g).
///
/// Unknowns along the material coordinate s: the centreline (x, y), the tangent angle theta
/// from +X (negative when the strand hangs down), the signed moment M (same sign as the
/// curvature kappa = d theta / ds; negative when hanging). Equilibrium of the free part
/// [s, L] gives
///
/// ```text
/// x' = (1 + eps) cos(theta)        y' = (1 + eps) sin(theta)       theta' = kappa
/// M  = -q  int_s^L (x(s') - x(s)) ds',   so   M' = q (L - s) (1 + eps) cos(theta),  M(L) = 0
/// T  = -q (L - s) sin(theta)       (axial tension: the free part's weight along the tangent)
/// ```
///
/// with `kappa` solving `M_law(kappa, T, s) = M`, `eps = 0` (inextensible) or `T / EA`
/// (extensible), and `theta(0)` the clamp angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cantilever {
    /// Length L (m, material).
    pub length: f64,
    /// Distributed load q (N per metre of material length), positive downward (-Y).
    pub load: f64,
    /// Tangent angle of the clamp from +X (rad); 0 for the horizontal cantilever.
    pub clamp_angle: f64,
    /// Axial stiffness EA (N) of extensible kinematics; `None` for an inextensible strand.
    pub axial_stiffness: Option<f64>,
}

impl Cantilever {
    /// Inextensible horizontal cantilever of length `length` (m) under load `load` (N/m).
    pub fn new(length: f64, load: f64) -> Self {
        Cantilever {
            length,
            load,
            clamp_angle: 0.0,
            axial_stiffness: None,
        }
    }

    /// Extensible horizontal cantilever: axial strain T / EA with `axial_stiffness` EA (N).
    pub fn extensible(length: f64, load: f64, axial_stiffness: f64) -> Self {
        Cantilever {
            axial_stiffness: Some(axial_stiffness),
            ..Cantilever::new(length, load)
        }
    }

    /// Axial strain of the kinematics under tension `tension` (N): T / EA or 0.
    pub fn strain(&self, tension: f64) -> f64 {
        self.axial_stiffness.map_or(0.0, |ea| tension / ea)
    }

    fn validate(&self) -> Result<(), ElasticaError> {
        let bad = |field, message: String| Err(ElasticaError::Input { field, message });
        if !(self.length.is_finite() && self.length > 0.0) {
            return bad("length", format!("must be positive, got {}", self.length));
        }
        if !(self.load.is_finite() && self.load >= 0.0) {
            return bad(
                "load",
                format!("must be zero or positive, got {}", self.load),
            );
        }
        if !self.clamp_angle.is_finite() {
            return bad("clamp_angle", "must be finite".into());
        }
        if let Some(ea) = self.axial_stiffness
            && !(ea.is_finite() && ea > 0.0)
        {
            return bad("axial_stiffness", format!("must be positive, got {ea}"));
        }
        Ok(())
    }
}

/// Solver options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// RK4 steps of the returned solution (a multiple of 4, at least 16). The error estimate
    /// solves again with 1/2 and 1/4 of them; the load continuation runs with 1/4.
    pub steps: usize,
    /// Load fraction of the first continuation step; `None` chooses it so that the first
    /// problem is nearly linear (q L^3 / K about 1, K the root's secant stiffness).
    pub initial_load_fraction: Option<f64>,
    /// Most continuation steps before giving up.
    pub max_continuation_steps: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            steps: 8000,
            initial_load_fraction: None,
            max_continuation_steps: 400,
        }
    }
}

/// Estimated discretisation error of a [`Solution`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorEstimate {
    /// Estimated largest position error over the grid (m): the difference between the
    /// solutions with `steps` and `steps / 2`, divided by 2^p - 1 (Richardson).
    pub position: f64,
    /// Observed convergence order p from the three resolutions (4 for a smooth law, lower
    /// where a piecewise smooth law has kinks), clamped to [1, 4].
    pub order: f64,
    /// Largest position difference between the solutions with `steps` and `steps / 2` (m).
    pub difference: f64,
    /// Residual moment at the free end M(L) of the returned solution (N m).
    pub end_moment: f64,
}

/// The solved cantilever sampled at the `steps + 1` RK4 nodes s_i = i L / steps.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// The problem solved.
    pub problem: Cantilever,
    /// Material coordinate s (m).
    pub s: Vec<f64>,
    /// Centreline x (m).
    pub x: Vec<f64>,
    /// Centreline y (m).
    pub y: Vec<f64>,
    /// Tangent angle theta (rad).
    pub theta: Vec<f64>,
    /// Signed curvature kappa = d theta / ds (1/m).
    pub kappa: Vec<f64>,
    /// Signed bending moment M (N m).
    pub moment: Vec<f64>,
    /// Axial tension T (N).
    pub tension: Vec<f64>,
    /// Axial strain of the kinematics (0 when inextensible).
    pub strain: Vec<f64>,
    /// Root moment M(0) (N m).
    pub root_moment: f64,
    /// Tip position (x(L), y(L)) (m).
    pub tip: [f64; 2],
    /// Discretisation error estimate.
    pub error: ErrorEstimate,
    /// Load continuation steps taken (1 when the full load was solved directly).
    pub continuation_steps: usize,
}

/// The solution interpolated at one material coordinate (see [`Solution::sample`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Centreline x (m).
    pub x: f64,
    /// Centreline y (m).
    pub y: f64,
    /// Tangent angle (rad).
    pub theta: f64,
    /// Curvature (1/m), linear between nodes.
    pub kappa: f64,
    /// Bending moment (N m).
    pub moment: f64,
    /// Axial tension -q (L - s) sin(theta) (N).
    pub tension: f64,
}

impl Solution {
    /// Tip displacement from the undeformed tip L (cos theta_0, sin theta_0) (m). For the
    /// horizontal cantilever (-u, -v): u the horizontal shortening, v the drop.
    pub fn tip_displacement(&self) -> [f64; 2] {
        let p = &self.problem;
        let (sn, cs) = p.clamp_angle.sin_cos();
        [self.tip[0] - p.length * cs, self.tip[1] - p.length * sn]
    }

    /// Centreline position at material coordinate `s` (m), clamped to [0, L]: cubic Hermite
    /// between nodes using the exact tangents (1 + eps)(cos theta, sin theta), so the
    /// interpolation error is O(h^4) like the integration's.
    pub fn position(&self, s: f64) -> [f64; 2] {
        let v = self.sample(s);
        [v.x, v.y]
    }

    /// The solution at material coordinate `s` (m), clamped to [0, L]: x, y, theta and M by
    /// cubic Hermite interpolation with their exact derivatives, kappa linearly, T from theta.
    pub fn sample(&self, s: f64) -> Sample {
        let p = &self.problem;
        let n = self.s.len() - 1;
        let h = p.length / n as f64;
        let s = s.clamp(0.0, p.length);
        let i = ((s / h).floor() as usize).min(n - 1);
        let t = (s - self.s[i]) / h;
        let (h00, h10, h01, h11) = (
            (1.0 + 2.0 * t) * (1.0 - t) * (1.0 - t),
            t * (1.0 - t) * (1.0 - t),
            t * t * (3.0 - 2.0 * t),
            t * t * (t - 1.0),
        );
        let q = p.load;
        let node = |j: usize| {
            let stretch = 1.0 + self.strain[j];
            let (sn, cs) = self.theta[j].sin_cos();
            let dm = q * (p.length - self.s[j]) * stretch * cs;
            [stretch * cs, stretch * sn, self.kappa[j], dm]
        };
        let (d0, d1) = (node(i), node(i + 1));
        let herm =
            |v: &[f64], k: usize| h00 * v[i] + h10 * h * d0[k] + h01 * v[i + 1] + h11 * h * d1[k];
        let theta = herm(&self.theta, 2);
        Sample {
            x: herm(&self.x, 0),
            y: herm(&self.y, 1),
            theta,
            kappa: (1.0 - t) * self.kappa[i] + t * self.kappa[i + 1],
            moment: herm(&self.moment, 3),
            tension: -q * (p.length - s) * theta.sin(),
        }
    }
}

/// Solves the cantilever with law `law`: load continuation from a nearly linear load up to
/// the full load on the coarse grid (steps / 4), then the shooting on steps / 2 and steps for
/// the Richardson error estimate. See [`Cantilever`] for the equations.
pub fn solve<L: PlanarLaw>(
    problem: &Cantilever,
    law: &L,
    options: &Options,
) -> Result<Solution, ElasticaError> {
    problem.validate()?;
    let n = options.steps;
    if n < 16 || !n.is_multiple_of(4) {
        return Err(ElasticaError::Input {
            field: "steps",
            message: format!("must be a multiple of 4 and at least 16, got {n}"),
        });
    }
    let len = problem.length;
    let q = problem.load;
    // Load parameter q L^3 / K with K the secant stiffness of the unloaded root.
    let k_probe = 1e-3 / len;
    let root = law.point(0.0);
    let k0 = law.moment(&root, -k_probe, 0.0).0 / -k_probe;
    let k0 = if k0.is_finite() && k0 > 0.0 { k0 } else { 1.0 };
    let param = q * len.powi(3) / k0;
    let scale = 0.5 * q * len * len;

    let coarse = Grid::new(law, len, n / 4);
    let (m0, cont_steps) = continuation(problem, law, &coarse, param, scale, options)?;
    let mut runs = Vec::with_capacity(3);
    let mut guess = m0;
    for level in [n / 4, n / 2, n] {
        let grid = if level == n / 4 {
            None
        } else {
            Some(Grid::new(law, len, level))
        };
        let g = grid.as_ref().unwrap_or(&coarse);
        let f = |m: f64| integrate(problem, law, g, q, m, None);
        let m = if level == n / 4 {
            guess
        } else {
            let dx = 1e-8 * guess.abs().max(1e-6 * scale);
            find_root(
                f,
                guess,
                dx,
                1e-3 * scale.max(guess.abs()),
                1e-14 * scale,
                60,
            )
            .map_err(|r| ElasticaError::Shooting {
                load_fraction: 1.0,
                residual: r,
            })?
        };
        guess = m;
        let mut tr = Trajectory::with_capacity(level + 1);
        let end = integrate(problem, law, g, q, m, Some(&mut tr))?;
        runs.push((m, end, tr));
    }
    let (fine_m, fine_end, fine) = runs.pop().expect("three runs");
    let (_, _, mid) = runs.pop().expect("three runs");
    let (_, _, low) = runs.pop().expect("three runs");
    let d_fine = max_distance(&fine, &mid, 2);
    let d_mid = max_distance(&mid, &low, 2);
    let tiny = 1e-14 * len;
    let order = if d_fine > tiny && d_mid > tiny {
        (d_mid / d_fine).log2().clamp(1.0, 4.0)
    } else {
        4.0
    };
    let error = ErrorEstimate {
        position: d_fine / (2f64.powf(order) - 1.0),
        order,
        difference: d_fine,
        end_moment: fine_end,
    };
    let tip = [fine.x[n], fine.y[n]];
    Ok(Solution {
        problem: *problem,
        s: (0..=n).map(|i| len * i as f64 / n as f64).collect(),
        x: fine.x,
        y: fine.y,
        theta: fine.theta,
        kappa: fine.kappa,
        moment: fine.moment,
        tension: fine.tension,
        strain: fine.strain,
        root_moment: fine_m,
        tip,
        error,
        continuation_steps: cont_steps,
    })
}

/// Largest distance between the nodes of a fine trajectory and a coarse one (`ratio` fine
/// steps per coarse step).
fn max_distance(fine: &Trajectory, coarse: &Trajectory, ratio: usize) -> f64 {
    (0..coarse.x.len())
        .map(|i| {
            let j = ratio * i;
            (fine.x[j] - coarse.x[i]).hypot(fine.y[j] - coarse.y[i])
        })
        .fold(0.0, f64::max)
}

/// The law's points on the half-step grid s_k = k L / (2 n) of an n-step RK4 integration.
struct Grid<P> {
    steps: usize,
    length: f64,
    points: Vec<P>,
}

impl<P> Grid<P> {
    fn new<L: PlanarLaw<Point = P>>(law: &L, length: f64, steps: usize) -> Self {
        let points = (0..=2 * steps)
            .map(|k| law.point(half_node(length, steps, k)))
            .collect();
        Grid {
            steps,
            length,
            points,
        }
    }
}

/// Material coordinate of half-step node k of an n-step grid.
fn half_node(length: f64, steps: usize, k: usize) -> f64 {
    length * k as f64 / (2 * steps) as f64
}

/// Node values recorded by [`integrate`].
#[derive(Default)]
struct Trajectory {
    x: Vec<f64>,
    y: Vec<f64>,
    theta: Vec<f64>,
    kappa: Vec<f64>,
    moment: Vec<f64>,
    tension: Vec<f64>,
    strain: Vec<f64>,
}

impl Trajectory {
    fn with_capacity(n: usize) -> Self {
        let v = || Vec::with_capacity(n);
        Trajectory {
            x: v(),
            y: v(),
            theta: v(),
            kappa: v(),
            moment: v(),
            tension: v(),
            strain: v(),
        }
    }
}

/// State (x, y, theta, M) and its derivative in s.
type State = [f64; 4];

/// Right-hand side at half-step node `k`; `kappa` carries the previous curvature in (Newton
/// start) and this node's out. Returns the derivative and the tension.
fn rhs<L: PlanarLaw>(
    problem: &Cantilever,
    law: &L,
    grid: &Grid<L::Point>,
    q: f64,
    k: usize,
    y: &State,
    kappa: &mut f64,
) -> Result<(State, f64), ElasticaError> {
    let s = half_node(grid.length, grid.steps, k);
    let (sn, cs) = y[2].sin_cos();
    let arm = q * (grid.length - s);
    let tension = -arm * sn;
    let point = &grid.points[k];
    *kappa =
        invert_moment(|c| law.moment(point, c, tension), y[3], *kappa).map_err(|e| match e {
            ElasticaError::Inversion { moment, reason, .. } => {
                ElasticaError::Inversion { s, moment, reason }
            }
            other => other,
        })?;
    let stretch = 1.0 + problem.strain(tension);
    Ok((
        [stretch * cs, stretch * sn, *kappa, arm * stretch * cs],
        tension,
    ))
}

/// Integrates from the clamp with root moment `m0` (N m) under load `q` (N/m) with classical
/// RK4 on `grid`; returns the free-end moment M(L) and records the nodes into `record`.
fn integrate<L: PlanarLaw>(
    problem: &Cantilever,
    law: &L,
    grid: &Grid<L::Point>,
    q: f64,
    m0: f64,
    mut record: Option<&mut Trajectory>,
) -> Result<f64, ElasticaError> {
    let n = grid.steps;
    let h = grid.length / n as f64;
    let mut y: State = [0.0, 0.0, problem.clamp_angle, m0];
    let mut kappa = 0.0;
    let axpy = |y: &State, a: f64, d: &State| {
        [
            y[0] + a * d[0],
            y[1] + a * d[1],
            y[2] + a * d[2],
            y[3] + a * d[3],
        ]
    };
    for i in 0..n {
        let (d1, t1) = rhs(problem, law, grid, q, 2 * i, &y, &mut kappa)?;
        if let Some(r) = record.as_deref_mut() {
            push(r, problem, &y, kappa, t1);
        }
        let (d2, _) = rhs(
            problem,
            law,
            grid,
            q,
            2 * i + 1,
            &axpy(&y, 0.5 * h, &d1),
            &mut kappa,
        )?;
        let (d3, _) = rhs(
            problem,
            law,
            grid,
            q,
            2 * i + 1,
            &axpy(&y, 0.5 * h, &d2),
            &mut kappa,
        )?;
        let (d4, _) = rhs(
            problem,
            law,
            grid,
            q,
            2 * i + 2,
            &axpy(&y, h, &d3),
            &mut kappa,
        )?;
        for c in 0..4 {
            y[c] += h / 6.0 * (d1[c] + 2.0 * (d2[c] + d3[c]) + d4[c]);
        }
        if !y.iter().all(|v| v.is_finite()) {
            return Err(ElasticaError::Inversion {
                s: half_node(grid.length, n, 2 * i + 2),
                moment: y[3],
                reason: "the integration diverged".into(),
            });
        }
    }
    if let Some(r) = record {
        let (_, t) = rhs(problem, law, grid, q, 2 * n, &y, &mut kappa)?;
        push(r, problem, &y, kappa, t);
    }
    Ok(y[3])
}

fn push(r: &mut Trajectory, problem: &Cantilever, y: &State, kappa: f64, tension: f64) {
    r.x.push(y[0]);
    r.y.push(y[1]);
    r.theta.push(y[2]);
    r.moment.push(y[3]);
    r.kappa.push(kappa);
    r.tension.push(tension);
    r.strain.push(problem.strain(tension));
}

/// Follows the equilibrium branch from a small load to the full load on `grid`; returns the
/// full-load root moment and the number of continuation steps.
fn continuation<L: PlanarLaw>(
    problem: &Cantilever,
    law: &L,
    grid: &Grid<L::Point>,
    param: f64,
    scale: f64,
    options: &Options,
) -> Result<(f64, usize), ElasticaError> {
    let q = problem.load;
    if q == 0.0 {
        return Ok((0.0, 0));
    }
    let linear = |lam: f64| -lam * scale * problem.clamp_angle.cos();
    let solve_at = |lam: f64, pred: f64, max_step: f64| {
        let f = |m: f64| integrate(problem, law, grid, lam * q, m, None);
        let dx = 1e-6 * pred.abs().max(1e-3 * lam * scale);
        find_root(f, pred, dx, max_step, 1e-14 * lam * scale, 40)
    };
    // First step: a nearly linear problem, predicted by the small-deflection root moment.
    let mut lam = options
        .initial_load_fraction
        .unwrap_or(1.0 / param.max(1.0))
        .clamp(1e-12, 1.0);
    let mut m = loop {
        match solve_at(lam, linear(lam), 0.5 * lam * scale) {
            Ok(m) => break m,
            Err(r) if lam < 1e-9 => {
                return Err(ElasticaError::Shooting {
                    load_fraction: lam,
                    residual: r,
                });
            }
            Err(_) => lam *= 0.1,
        }
    };
    let mut hist = vec![(lam, m)];
    let mut dl = lam;
    let mut steps = 1;
    while lam < 1.0 {
        if steps >= options.max_continuation_steps || dl < 1e-9 {
            return Err(ElasticaError::Continuation {
                load_fraction: lam,
                steps,
            });
        }
        let next = (lam + dl).min(1.0);
        let pred = match hist.as_slice() {
            [.., (l0, m0), (l1, m1)] => m1 + (m1 - m0) * (next - l1) / (l1 - l0),
            _ => m * next / lam,
        };
        let step = (pred - m).abs();
        steps += 1;
        match solve_at(next, pred, 2.0 * step + 1e-3 * next * scale) {
            // Accept only a root near the predictor: a root far from it is another branch.
            Ok(mn) if (mn - pred).abs() <= 0.5 * (mn - m).abs() + 0.01 * m.abs() => {
                let err = (mn - pred).abs() / (0.05 * (mn - m).abs() + 1e-3 * m.abs());
                lam = next;
                m = mn;
                hist.push((lam, m));
                dl *= (1.0 / err.max(1e-12)).sqrt().clamp(0.5, 2.0);
            }
            _ => dl *= 0.25,
        }
    }
    Ok((m, steps))
}

/// Root of `f` from `x0`: secant steps (at most `max_step` long) until the root is bracketed,
/// then Brent's method. Returns the best residual on failure.
fn find_root(
    mut f: impl FnMut(f64) -> Result<f64, ElasticaError>,
    x0: f64,
    dx0: f64,
    max_step: f64,
    ftol: f64,
    max_evals: usize,
) -> Result<f64, f64> {
    let mut best = f64::INFINITY;
    let mut eval = |x: f64, best: &mut f64| -> Result<f64, f64> {
        let v = f(x).map_err(|_| *best)?;
        if v.abs() < best.abs() {
            *best = v;
        }
        Ok(v)
    };
    let mut a = x0;
    let mut fa = eval(a, &mut best)?;
    if fa.abs() <= ftol {
        return Ok(a);
    }
    let mut b = x0 + dx0;
    let mut fb = eval(b, &mut best)?;
    let mut evals = 2;
    while evals < max_evals {
        if fb.abs() <= ftol {
            return Ok(b);
        }
        if fa * fb < 0.0 {
            return brent(
                |x| eval(x, &mut best),
                a,
                fa,
                b,
                fb,
                ftol,
                max_evals - evals,
            );
        }
        let mut d = -fb * (b - a) / (fb - fa);
        if !d.is_finite() {
            d = dx0;
        }
        if d.abs() > max_step {
            d = max_step.copysign(d);
        }
        a = b;
        fa = fb;
        b += d;
        fb = eval(b, &mut best)?;
        evals += 1;
    }
    Err(best)
}

/// Brent's method on a bracket [a, b] with f(a) f(b) < 0.
fn brent(
    mut f: impl FnMut(f64) -> Result<f64, f64>,
    mut a: f64,
    mut fa: f64,
    mut b: f64,
    mut fb: f64,
    ftol: f64,
    max_evals: usize,
) -> Result<f64, f64> {
    let mut c = a;
    let mut fc = fa;
    let mut d = b - a;
    let mut e = d;
    for _ in 0..max_evals.max(100) {
        if fb * fc > 0.0 {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 1e-300;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol || fb.abs() <= ftol {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            if 2.0 * p < (3.0 * xm * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(xm) };
        fb = f(b)?;
    }
    Err(fb)
}
