//! Cubic Hermite shape functions of the cable element (eq. (27)) and Gauss-Legendre rules.
//!
//! An element of length `l` has the material coordinate `x` in `[0, l]` and `xi = x / l`.
//! Its position field is `r(x) = S(x) q = sum_k S_k(x) q_k` (eq. (26)) with the nodal blocks
//! `q_1 = r(0)`, `q_2 = r'(0)`, `q_3 = r(l)`, `q_4 = r'(l)` (each of the space's dimension)
//! and
//!
//! ```text
//! S_1 = 1 - 3 xi^2 + 2 xi^3      S_2 = l (xi - 2 xi^2 + xi^3)
//! S_3 = 3 xi^2 - 2 xi^3          S_4 = l (-xi^2 + xi^3)            (27)
//! ```
//!
//! The shape matrix is the Kronecker product `S = [S_1 I, S_2 I, S_3 I, S_4 I]`, so every
//! element quantity is a combination of nodal blocks with the four scalars of a [`ShapeRow`].

use std::sync::OnceLock;

use crate::error::AncfError;

/// The four Hermite shape functions (eq. (27)) at `x` for an element of length `l`.
#[inline]
pub fn shape(x: f64, l: f64) -> [f64; 4] {
    let xi = x / l;
    let xi2 = xi * xi;
    let xi3 = xi2 * xi;
    [
        1.0 - 3.0 * xi2 + 2.0 * xi3,
        l * (xi - 2.0 * xi2 + xi3),
        3.0 * xi2 - 2.0 * xi3,
        l * (xi3 - xi2),
    ]
}

/// First derivatives `dS_k/dx` of the shape functions at `x` for an element of length `l`.
#[inline]
pub fn shape_dx(x: f64, l: f64) -> [f64; 4] {
    let xi = x / l;
    let xi2 = xi * xi;
    let b = 6.0 * (xi2 - xi) / l;
    [b, 1.0 - 4.0 * xi + 3.0 * xi2, -b, 3.0 * xi2 - 2.0 * xi]
}

/// Second derivatives `d^2 S_k/dx^2` of the shape functions at `x` for an element of length
/// `l`.
#[inline]
pub fn shape_dxx(x: f64, l: f64) -> [f64; 4] {
    let xi = x / l;
    let c = (12.0 * xi - 6.0) / (l * l);
    [c, (6.0 * xi - 4.0) / l, -c, (6.0 * xi - 2.0) / l]
}

/// Shape functions and their first two `x`-derivatives at one point of an element.
///
/// Element kinematics need only `ds` (for `r'`) and `dds` (for `r''`); `s` gives the position
/// and enters the mass matrix and loads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeRow {
    /// Material coordinate `x` in the element (m).
    pub x: f64,
    /// `S_k(x)`, eq. (27).
    pub s: [f64; 4],
    /// `dS_k/dx`.
    pub ds: [f64; 4],
    /// `d^2 S_k/dx^2`.
    pub dds: [f64; 4],
}

impl ShapeRow {
    /// Shape row at material coordinate `x` of an element of length `l`.
    #[inline]
    pub fn new(x: f64, l: f64) -> Self {
        Self {
            x,
            s: shape(x, l),
            ds: shape_dx(x, l),
            dds: shape_dxx(x, l),
        }
    }
}

/// Largest number of points of the Gauss-Legendre rules provided.
pub const MAX_GAUSS_POINTS: usize = 10;

/// A Gauss-Legendre rule on `[-1, 1]`, exact for polynomials of degree `2 n - 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussRule {
    n: usize,
    points: [f64; MAX_GAUSS_POINTS],
    weights: [f64; MAX_GAUSS_POINTS],
}

impl GaussRule {
    /// Number of points.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Abscissae on `[-1, 1]`, ascending.
    pub fn points(&self) -> &[f64] {
        &self.points[..self.n]
    }

    /// Weights (they sum to 2).
    pub fn weights(&self) -> &[f64] {
        &self.weights[..self.n]
    }

    /// Points and weights mapped to `[a, b]`: `(x_i, w_i)` with `sum w_i f(x_i)` approximating
    /// the integral of `f` over `[a, b]`.
    pub fn on_interval(&self, a: f64, b: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        self.points()
            .iter()
            .zip(self.weights())
            .map(move |(&p, &w)| (mid + half * p, half * w))
    }

    /// Computes the `n`-point rule by Newton's method on the Legendre polynomial `P_n`, with
    /// symmetric points and weights `2 / ((1 - x^2) P_n'(x)^2)`.
    fn compute(n: usize) -> Self {
        let mut points = [0.0; MAX_GAUSS_POINTS];
        let mut weights = [0.0; MAX_GAUSS_POINTS];
        let half = n.div_ceil(2);
        for i in 0..half {
            // i-th largest root; Tricomi's initial guess.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (p, d) = legendre(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() <= 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre(n, x);
            if d != 0.0 {
                dp = d;
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            // Ascending order: the i-th largest root goes to n - 1 - i, its mirror to i.
            points[n - 1 - i] = x;
            points[i] = -x;
            weights[n - 1 - i] = w;
            weights[i] = w;
        }
        if n % 2 == 1 {
            points[n / 2] = 0.0;
        }
        Self { n, points, weights }
    }
}

/// `(P_n(x), P_n'(x))` by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let mut p0 = 1.0;
    let mut p1 = x;
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

/// The `n`-point Gauss-Legendre rule on `[-1, 1]`, `n` in `1..=10` (computed once, then
/// shared).
pub fn gauss_legendre(n: usize) -> Result<&'static GaussRule, AncfError> {
    static RULES: OnceLock<[GaussRule; MAX_GAUSS_POINTS]> = OnceLock::new();
    if !(1..=MAX_GAUSS_POINTS).contains(&n) {
        return Err(AncfError::QuadratureOrder { n });
    }
    let rules = RULES.get_or_init(|| std::array::from_fn(|i| GaussRule::compute(i + 1)));
    Ok(&rules[n - 1])
}

/// One integration point of an element: its shape row and its weight for integrals over
/// `x` in `[0, l]` (the Jacobian `l / 2` is included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraturePoint {
    /// Weight `w_i l / 2` (m).
    pub weight: f64,
    /// Shape functions and derivatives at the point.
    pub row: ShapeRow,
}

/// The `n` Gauss points of an element of length `l`, with their shape rows: build once per
/// element (the rows depend only on `l` and `n`), reuse in every evaluation.
pub fn element_quadrature(l: f64, n: usize) -> Result<Vec<QuadraturePoint>, AncfError> {
    if !(l.is_finite() && l > 0.0) {
        return Err(AncfError::InvalidLength { length: l });
    }
    let rule = gauss_legendre(n)?;
    Ok(rule
        .on_interval(0.0, l)
        .map(|(x, weight)| QuadraturePoint {
            weight,
            row: ShapeRow::new(x, l),
        })
        .collect())
}
