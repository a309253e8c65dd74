//! Planar cable element: 2 nodes with `(r_x, r_y, r'_x, r'_y)` each, 8 coordinates
//! `q = (r(0), r'(0), r(l), r'(l))` (eqs. (24)-(26) restricted to the XY plane).
//!
//! At a point the element gives `r' = S' q`, `r'' = S'' q` ([`PlanarPoint`]); from them
//!
//! ```text
//! eps   = |r'| - 1                                  axial strain (SPEC 3)
//! kappa = (r' x r'')_z / |r'|^2                     signed curvature, kappa_z of the section
//! ```
//!
//! # Curvature per reference length
//!
//! `kappa` is the rotation of the tangent per unit *reference* (material) length `x`, in 1/m:
//! with `t = (cos theta, sin theta)`, `r' = |r'| t` and `r'' = |r'|' t + |r'| theta' n`, so
//! `(r' x r'')_z = |r'|^2 d theta/dx`. This is the geometrically exact (Reissner) bending
//! strain, conjugate to the moment in the virtual work per reference length of eq. (28); the
//! paper's (and SPEC 3's) `(r' x r'')_z / |r'|^3` is the curvature per *deformed* length,
//! `kappa_def = kappa / (1 + eps)`. The two differ only at order `eps`, but the choice decides
//! which force is conjugate to `eps`: with `W(eps, kappa)` per reference length the axial
//! resultant is `dW/deps` at fixed `kappa`. With the Reissner measure that is `EA eps = T`,
//! the physical tension (equilibrium of a cut), which the section law's friction limits need
//! (wire axial stress `sigma_a = E_w cos^2(alpha) eps`, eqs. (22b), (23)). With the deformed
//! length measure equilibrium gives `EA eps = T + M kappa`, and near the root of the paper's
//! soft hanging strands `M kappa` (about 1.5 N) dwarfs `T` (about 0.4 N): the friction saw far
//! too much tension and the statics stalled at 1.2e-4 m from the elastica shooting reference
//! (which uses `T = -q (L - s) sin(theta)`) as elements were added (`tests/statics.rs`).
//!
//! with analytic first and second derivatives with respect to the local variables
//! `y = (r'_x, r'_y, r''_x, r''_y)` ([`PlanarFirst`], [`PlanarSecond`]). Element-size
//! derivatives (8-vectors, 8x8 matrices) follow from [`scatter_gradient`] and
//! [`scatter_hessian`], or their accumulating forms [`add_gradient`] and [`add_hessian`]: an
//! element combines the local derivatives of all section quantities at a Gauss point first
//! (4 values, 4x4) and maps them to `q` once.
//!
//! The signed curvature is a polynomial in `(r', r'')` divided by `|r'|^2`: it is smooth
//! through the straight state (`r' x r'' = 0`), and the only division is by `|r'|`, which must
//! be positive: below [`MIN_STRETCH`](crate::MIN_STRETCH) the evaluation returns
//! [`AncfError::DegenerateTangent`].

use nalgebra::{Matrix2, Matrix4, SMatrix, SVector, Vector2, Vector4};

use crate::error::{AncfError, check_stretch};
use crate::scatter;
use crate::shape::ShapeRow;

/// Element coordinates of the planar element (8).
pub type PlanarCoords = SVector<f64, 8>;
/// Element-size gradient (8).
pub type PlanarVector = SVector<f64, 8>;
/// Element-size matrix (8x8).
pub type PlanarMatrix = SMatrix<f64, 8, 8>;

/// Position `r(x) = S(x) q` (eq. (26)).
#[inline]
pub fn position(q: &PlanarCoords, row: &ShapeRow) -> Vector2<f64> {
    Vector2::from(scatter::combine::<2>(&row.s, q.as_slice()))
}

/// Local kinematic variables at one point: `r'` and `r''`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarPoint {
    /// Position gradient `r' = dr/dx`.
    pub dr: Vector2<f64>,
    /// Second derivative `r'' = d^2 r/dx^2`.
    pub ddr: Vector2<f64>,
}

/// Strain, curvature and their gradients with respect to `y = (r', r'')`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarFirst {
    /// Axial strain `eps = |r'| - 1`.
    pub eps: f64,
    /// Signed curvature per reference length `kappa = (r' x r'')_z / |r'|^2` (1/m); the
    /// section's `kappa_z`.
    pub kappa: f64,
    /// Unit tangent `t = r' / |r'|`.
    pub tangent: Vector2<f64>,
    /// `d eps / dy` (the last two entries are zero).
    pub eps_grad: Vector4<f64>,
    /// `d kappa / dy`.
    pub kappa_grad: Vector4<f64>,
}

/// [`PlanarFirst`] plus the Hessians with respect to `y = (r', r'')`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarSecond {
    /// Values and gradients.
    pub first: PlanarFirst,
    /// `d^2 eps / dy^2`: only the `r'` block `(I - t t^T) / |r'|` is non-zero.
    pub eps_hess: Matrix4<f64>,
    /// `d^2 kappa / dy^2`: the `r''` block is zero (kappa is linear in `r''`).
    pub kappa_hess: Matrix4<f64>,
}

/// Intermediate quantities shared by the evaluations.
struct Core {
    n: f64,
    t: Vector2<f64>,
    /// `1 / |r'|^2`.
    g: f64,
    /// `(r' x r'')_z`.
    c: f64,
    /// `d c / d r'` = `(r''_y, -r''_x)`.
    c_a: Vector2<f64>,
    /// `d c / d r''` = `(-r'_y, r'_x)`.
    c_b: Vector2<f64>,
    /// `d g / d r'` = `-2 r' / |r'|^4`.
    g_a: Vector2<f64>,
}

impl PlanarPoint {
    /// Local variables from raw vectors.
    #[inline]
    pub fn new(dr: Vector2<f64>, ddr: Vector2<f64>) -> Self {
        Self { dr, ddr }
    }

    /// `r'` and `r''` of the element with coordinates `q` at the point of `row`.
    #[inline]
    pub fn at(q: &PlanarCoords, row: &ShapeRow) -> Self {
        Self {
            dr: Vector2::from(scatter::combine::<2>(&row.ds, q.as_slice())),
            ddr: Vector2::from(scatter::combine::<2>(&row.dds, q.as_slice())),
        }
    }

    /// `|r'|`, checked against [`MIN_STRETCH`](crate::MIN_STRETCH).
    #[inline]
    fn stretch(&self) -> Result<f64, AncfError> {
        check_stretch(self.dr.norm())
    }

    /// Axial strain `eps = |r'| - 1`.
    #[inline]
    pub fn strain(&self) -> Result<f64, AncfError> {
        Ok(self.stretch()? - 1.0)
    }

    /// Signed curvature per reference length `(r' x r'')_z / |r'|^2` (1/m).
    #[inline]
    pub fn curvature(&self) -> Result<f64, AncfError> {
        let n = self.stretch()?;
        Ok(cross(&self.dr, &self.ddr) / (n * n))
    }

    #[inline]
    fn core(&self) -> Result<Core, AncfError> {
        let n = self.stretch()?;
        let (a, b) = (&self.dr, &self.ddr);
        let t = a / n;
        let g = 1.0 / (n * n);
        Ok(Core {
            n,
            t,
            g,
            c: cross(a, b),
            c_a: Vector2::new(b.y, -b.x),
            c_b: Vector2::new(-a.y, a.x),
            g_a: t * (-2.0 * g / n),
        })
    }

    /// Strain, curvature and their gradients with respect to `(r', r'')`.
    #[inline]
    pub fn first(&self) -> Result<PlanarFirst, AncfError> {
        let k = self.core()?;
        Ok(first_from(&k))
    }

    /// Strain, curvature, gradients and Hessians with respect to `(r', r'')`.
    pub fn second(&self) -> Result<PlanarSecond, AncfError> {
        let k = self.core()?;
        let first = first_from(&k);
        let (n, t, g, c) = (k.n, k.t, k.g, k.c);

        let mut eps_hess = Matrix4::zeros();
        let p = (Matrix2::identity() - t * t.transpose()) / n;
        eps_hess.fixed_view_mut::<2, 2>(0, 0).copy_from(&p);

        // g_aa = -2 I / n^4 + 8 a a^T / n^6 = (g / n^2) (8 t t^T - 2 I).
        let g_aa = (t * t.transpose() * 8.0 - Matrix2::identity() * 2.0) * (g / (n * n));
        let k_aa = k.c_a * k.g_a.transpose() + k.g_a * k.c_a.transpose() + g_aa * c;
        // d^2 c / da db = [[0, 1], [-1, 0]] (rows r', columns r'').
        let c_ab = Matrix2::new(0.0, 1.0, -1.0, 0.0);
        let k_ab = c_ab * g + k.g_a * k.c_b.transpose();
        let mut kappa_hess = Matrix4::zeros();
        kappa_hess.fixed_view_mut::<2, 2>(0, 0).copy_from(&k_aa);
        kappa_hess.fixed_view_mut::<2, 2>(0, 2).copy_from(&k_ab);
        kappa_hess
            .fixed_view_mut::<2, 2>(2, 0)
            .copy_from(&k_ab.transpose());
        Ok(PlanarSecond {
            first,
            eps_hess,
            kappa_hess,
        })
    }
}

/// Strain, unit tangent and stretch at an axial point: what the axial term needs (its
/// gradient with respect to `r'` is the tangent, its Hessian [`PlanarAxial::hessian`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarAxial {
    /// Axial strain `eps = |r'| - 1`.
    pub eps: f64,
    /// Unit tangent `t = r' / |r'|` = `d eps / d r'`.
    pub tangent: Vector2<f64>,
    /// `|r'|`.
    pub stretch: f64,
}

/// Curvature and its derivatives at a bending point: what the bending term needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarBending {
    /// Signed curvature per reference length (1/m).
    pub kappa: f64,
    /// `d kappa / dy`.
    pub grad: Vector4<f64>,
    /// `d^2 kappa / d r'^2` (symmetric).
    pub hess_aa: Matrix2<f64>,
    /// `d^2 kappa / d r' d r''` (rows `r'`); the `r''` block is zero.
    pub hess_ab: Matrix2<f64>,
}

impl PlanarPoint {
    /// Strain and tangent only (as [`Self::first`], without the curvature).
    #[inline]
    pub fn axial(&self) -> Result<PlanarAxial, AncfError> {
        let n = self.stretch()?;
        Ok(PlanarAxial {
            eps: n - 1.0,
            tangent: self.dr / n,
            stretch: n,
        })
    }

    /// Curvature and its gradient only (as [`Self::first`], without the strain).
    ///
    /// (The curvature could skip the square root, with `1 / |r'|^2` from `r' . r'`; that
    /// rounding made Newton stall at 3e-9 of the load, above its 1e-9 tolerance, on the
    /// EA L^2 / EI = 1e7 elastica of `tests/statics.rs`.)
    #[inline]
    pub fn bending_first(&self) -> Result<(f64, Vector4<f64>), AncfError> {
        let k = self.core()?;
        let ka = k.c_a * k.g + k.g_a * k.c;
        let kb = k.c_b * k.g;
        Ok((k.c * k.g, Vector4::new(ka.x, ka.y, kb.x, kb.y)))
    }

    /// Curvature, gradient and the non-zero blocks of the Hessian (as [`Self::second`],
    /// without the strain).
    #[inline]
    pub fn bending_second(&self) -> Result<PlanarBending, AncfError> {
        let k = self.core()?;
        let ka = k.c_a * k.g + k.g_a * k.c;
        let kb = k.c_b * k.g;
        let (n, t, g, c) = (k.n, k.t, k.g, k.c);
        let g_aa = (t * t.transpose() * 8.0 - Matrix2::identity() * 2.0) * (g / (n * n));
        let hess_aa = k.c_a * k.g_a.transpose() + k.g_a * k.c_a.transpose() + g_aa * c;
        let c_ab = Matrix2::new(0.0, 1.0, -1.0, 0.0);
        let hess_ab = c_ab * g + k.g_a * k.c_b.transpose();
        Ok(PlanarBending {
            kappa: c * g,
            grad: Vector4::new(ka.x, ka.y, kb.x, kb.y),
            hess_aa,
            hess_ab,
        })
    }
}

impl PlanarAxial {
    /// `d^2 eps / d r'^2` = `(I - t t^T) / |r'|` (the only non-zero block).
    #[inline]
    pub fn hessian(&self) -> Matrix2<f64> {
        (Matrix2::identity() - self.tangent * self.tangent.transpose()) / self.stretch
    }
}

/// `out += w d^2 f/dq^2` for a local Hessian whose only non-zero block is `d^2 f / d r'^2`
/// (`haa`, symmetric), lower triangle only (see [`add_hessian_lower`]).
#[inline]
pub fn add_hessian_aa_lower(out: &mut PlanarMatrix, w: f64, row: &ShapeRow, haa: &Matrix2<f64>) {
    for m in 0..4 {
        let am = w * row.ds[m];
        for k in m..4 {
            let c = am * row.ds[k];
            for j in 0..2 {
                for i in 0..2 {
                    out[(2 * k + i, 2 * m + j)] += c * haa[(i, j)];
                }
            }
        }
    }
}

/// `out += w d^2 f/dq^2` for a symmetric local Hessian `h`, on and below the diagonal blocks
/// only: entries above the diagonal are partial (complete them with [`mirror_lower`]).
#[inline]
pub fn add_hessian_lower(out: &mut PlanarMatrix, w: f64, row: &ShapeRow, h: &Matrix4<f64>) {
    // t = h B for the columns of node block m (weight included), then the blocks k >= m.
    for m in 0..4 {
        let (am, bm) = (w * row.ds[m], w * row.dds[m]);
        let mut t = nalgebra::Matrix4x2::<f64>::zeros();
        for j in 0..2 {
            for r in 0..4 {
                t[(r, j)] = h[(r, j)] * am + h[(r, 2 + j)] * bm;
            }
        }
        for k in m..4 {
            let (ak, bk) = (row.ds[k], row.dds[k]);
            for j in 0..2 {
                for i in 0..2 {
                    out[(2 * k + i, 2 * m + j)] += ak * t[(i, j)] + bk * t[(2 + i, j)];
                }
            }
        }
    }
}

/// Copies the lower triangle of `out` onto the upper one.
#[inline]
pub fn mirror_lower(out: &mut PlanarMatrix) {
    for c in 1..8 {
        for r in 0..c {
            out[(r, c)] = out[(c, r)];
        }
    }
}

#[inline]
fn first_from(k: &Core) -> PlanarFirst {
    let ka = k.c_a * k.g + k.g_a * k.c;
    let kb = k.c_b * k.g;
    PlanarFirst {
        eps: k.n - 1.0,
        kappa: k.c * k.g,
        tangent: k.t,
        eps_grad: Vector4::new(k.t.x, k.t.y, 0.0, 0.0),
        kappa_grad: Vector4::new(ka.x, ka.y, kb.x, kb.y),
    }
}

/// `(a x b)_z`.
#[inline]
fn cross(a: &Vector2<f64>, b: &Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Section resultants at a point and their tangents, as a section law returns them
/// (planar: `strand_core::PlanarResponse`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarSection {
    /// Axial force `N` (N).
    pub n: f64,
    /// `dN/deps` (N).
    pub dn_deps: f64,
    /// Bending moment `M` conjugate to the signed curvature (N m).
    pub m: f64,
    /// `dM/dkappa` (N m^2).
    pub dm_dkappa: f64,
    /// `dM/deps` (N m); makes the tangent non-symmetric.
    pub dm_deps: f64,
}

impl PlanarFirst {
    /// Local generalized force `N d eps/dy + M d kappa/dy` (the integrand of eq. (28) in the
    /// variables `y = (r', r'')`); map with [`add_gradient`].
    #[inline]
    pub fn force(&self, s: &PlanarSection) -> Vector4<f64> {
        self.eps_grad * s.n + self.kappa_grad * s.m
    }
}

impl PlanarSecond {
    /// Local generalized force, as [`PlanarFirst::force`].
    #[inline]
    pub fn force(&self, s: &PlanarSection) -> Vector4<f64> {
        self.first.force(s)
    }

    /// Local tangent `d force / dy` (rows: force component, columns: variable):
    ///
    /// ```text
    /// N eps_yy + M kappa_yy + N_eps eps_y eps_y^T + M_kappa kappa_y kappa_y^T
    ///   + M_eps kappa_y eps_y^T
    /// ```
    ///
    /// Map with [`add_hessian`].
    #[inline]
    pub fn tangent(&self, s: &PlanarSection) -> Matrix4<f64> {
        let (ge, gk) = (&self.first.eps_grad, &self.first.kappa_grad);
        self.eps_hess * s.n
            + self.kappa_hess * s.m
            + ge * ge.transpose() * s.dn_deps
            + gk * gk.transpose() * s.dm_dkappa
            + gk * ge.transpose() * s.dm_deps
    }
}

/// Element gradient `df/dq` (8) from the local gradient `(df/dr', df/dr'')` (4).
#[inline]
pub fn scatter_gradient(row: &ShapeRow, g: &Vector4<f64>) -> PlanarVector {
    let mut out = PlanarVector::zeros();
    add_gradient(&mut out, 1.0, row, g);
    out
}

/// `out += w df/dq` for the local gradient `g = (df/dr', df/dr'')`.
#[inline]
pub fn add_gradient(out: &mut PlanarVector, w: f64, row: &ShapeRow, g: &Vector4<f64>) {
    scatter::add_gradient::<2>(out.as_mut_slice(), w, row, g.as_slice());
}

/// Element Hessian `d^2 f/dq^2` (8x8) from the local Hessian with respect to `(r', r'')`
/// (4x4). Also maps non-symmetric local tangents (rows: derivative of the force, columns:
/// variable).
#[inline]
pub fn scatter_hessian(row: &ShapeRow, h: &Matrix4<f64>) -> PlanarMatrix {
    let mut out = PlanarMatrix::zeros();
    add_hessian(&mut out, 1.0, row, h);
    out
}

/// `out += w d^2 f/dq^2` for the local Hessian `h` with respect to `(r', r'')`.
#[inline]
pub fn add_hessian(out: &mut PlanarMatrix, w: f64, row: &ShapeRow, h: &Matrix4<f64>) {
    scatter::add_hessian::<2, 4, 8>(out, w, row, h);
}
