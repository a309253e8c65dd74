//! Spatial cable element: 2 nodes with `(r, r')` each (eq. (24)), 12 coordinates
//! `q = (r(0), r'(0), r(l), r'(l))`, position `r = S q` (eqs. (25)-(27)).
//!
//! # Kinematics
//!
//! At a point the element gives `a = r' = S' q` and `b = r'' = S'' q` ([`SpatialPoint`]):
//!
//! ```text
//! eps = |a| - 1                      axial strain (SPEC 3)
//! k   = a x b / |a|^2                curvature vector per reference length, k . t = 0
//! ```
//!
//! `|k|` is the rotation of the tangent per unit *reference* length (1/m), the geometrically
//! exact (Reissner) bending strain conjugate to the moment in eq. (28), not the paper's
//! curvature per deformed length `a x b / |a|^3 = k / (1 + eps)`. With it the force conjugate
//! to `eps` is the physical tension `EA eps = T` that the friction limits of the section law
//! need; see [`crate::planar`] for the derivation and the measured consequence.
//!
//! # Section frame
//!
//! The section law takes the curvature vector in a section frame `(t, e_y, e_z)` (see
//! `strand_core::section`): wire `i` sits at `R_w (sin phi_i e_y + cos phi_i e_z)`, so `e_z` is
//! the direction from which the wire phases are measured. A frame at a point is a reference
//! frame `(t0, e_y0, e_z0)` ([`SectionFrame`]) carried by the minimal rotation `R` that takes
//! `t0` to the current tangent `t = a / |a|` (Rodrigues' formula):
//!
//! ```text
//! R v = (t0 . t) v + (t0 x t) x v + ((t0 x t) . v) / (1 + t0 . t) (t0 x t).
//! ```
//!
//! For `v` orthogonal to `t0` this equals `v - (v . t) / (1 + t0 . t) (t0 + t)`, so with
//! `k . t = 0` the components `kappa_e = k . R e0` (e0 = e_y0 or e_z0) are the rational
//! functions
//!
//! ```text
//! kappa_e = [ (a x b) . e0 - (e0 . a) ((a x b) . t0) / (|a| + t0 . a) ] / |a|^2,
//! ```
//!
//! linear in `b`. Their gradients and Hessians with respect to `y = (a, b)` (6 values,
//! [`SpatialFirst`], [`SpatialSecond`]) include the frame's dependence on `a`. The minimal
//! rotation is undefined for `t = -t0`: below `1 + t0 . t =`
//! [`MIN_ALIGNMENT`](crate::MIN_ALIGNMENT) the evaluation returns
//! [`AncfError::AntiparallelTangent`]. No division by `|a x b|` occurs, so the straight state
//! is regular.
//!
//! ## What fixes the section's turn about its axis
//!
//! The cable element has no torsion: nothing in its kinematics says how a section turns about
//! the tangent. The beam ([`crate::beam`]) takes the section to turn *without spin about the
//! tangent*, as a rod without torsional load does: every bending point keeps its own reference
//! frame as state, and when a step (a time step, or a load step in statics) is accepted, the
//! frame carried to the accepted tangent becomes the reference of the next step, like the slip
//! state of the hysteretic law. Within a step the frame is a smooth function of the
//! coordinates (the formulas above, with the committed frame as `(t0, e_y0, e_z0)`), so the
//! forces have an exact analytic tangent; the committed frame is carried to the tangent it
//! was committed at, so committing does not move the frame of the configuration it belongs
//! to. The minimal rotation is singular only when the tangent at a point turns by half a turn
//! within one step, so no configuration of the strand is singular. Consequences:
//!
//! * Holonomy: a section whose tangent goes round a closed loop comes back turned about the
//!   tangent by the solid angle the loop encloses (parallel transport on the sphere of
//!   directions): the section of a conical pendulum of half-angle `beta` turns by
//!   `2 pi (1 - cos beta)` per revolution against the frame it started with. The wires' phases
//!   relative to the bending plane follow that turn.
//! * The frames of neighbouring points are carried independently, so in a general 3D motion
//!   neighbouring sections can turn relative to each other (a twist that the wires' torsional
//!   stiffness would resist in a real strand). It is neither resisted nor reported; motion in a
//!   fixed plane turns no section about its axis, so planar results are unaffected.
//! * The frame depends on the path of the tangent, and so, in 3D, slightly on the time or load
//!   steps: the composition of a step's minimal rotations is the parallel transport along the
//!   great-circle polygon through the accepted tangents, which differs from the transport along
//!   the true path by the solid angle between them, of second order in the step.
//! * Everything is covariant: a rigid rotation of the strand, its reference frames and its
//!   loads gives the rotated motion.
//!
//! The initial reference frame has `t0` along the straight strand and `e_z0` along the
//! scene's phase reference projected off `t0` ([`default_phase_reference`] when none is given).
//!
//! # Invariance
//!
//! `eps` and `|k| = |(kappa_y, kappa_z)|` are invariant under a rigid rotation of the nodal
//! coordinates. The components `(kappa_y, kappa_z)` are invariant only when the reference
//! frame is rotated with the strand; for a fixed reference frame they change with the
//! rotation (the frame is tied to `t0`, not to the material). A state in the XY plane with
//! `t0 = X`, `e_z0 = Z` has `kappa_z` equal to the planar signed curvature
//! ([`crate::planar`]) and `kappa_y = 0`.
//!
//! Element-size derivatives follow from [`scatter_gradient`], [`scatter_hessian`],
//! [`add_gradient`], [`add_hessian`], as in [`crate::planar`].

use nalgebra::{Matrix3, Matrix6, SMatrix, SVector, Vector3, Vector6};

use crate::error::{AncfError, check_alignment, check_stretch};
use crate::scatter;
use crate::shape::ShapeRow;

/// Element coordinates of the spatial element (12).
pub type SpatialCoords = SVector<f64, 12>;
/// Element-size gradient (12).
pub type SpatialVector = SVector<f64, 12>;
/// Element-size matrix (12x12).
pub type SpatialMatrix = SMatrix<f64, 12, 12>;

/// Reference section frame `(t0, e_y0, e_z0)` at a point: orthonormal and right-handed
/// (`e_z0 = t0 x e_y0`); `e_z0` is the direction of phase zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionFrame {
    t0: Vector3<f64>,
    e_y0: Vector3<f64>,
    e_z0: Vector3<f64>,
}

impl SectionFrame {
    /// Frame with tangent along `t0` and `e_z0` along the part of `z_hint` orthogonal to
    /// `t0` (both normalized; `e_y0 = e_z0 x t0`). Errors if either is zero or they are
    /// parallel.
    pub fn new(t0: Vector3<f64>, z_hint: Vector3<f64>) -> Result<Self, AncfError> {
        let tn = t0.norm();
        if !(tn > 0.0 && tn.is_finite()) {
            return Err(AncfError::InvalidFrame {
                reason: "zero or non-finite tangent",
            });
        }
        let t0 = t0 / tn;
        let z = z_hint - t0 * t0.dot(&z_hint);
        let zn = z.norm();
        if !(zn > 1e-12 * z_hint.norm() && zn.is_finite()) {
            return Err(AncfError::InvalidFrame {
                reason: "z direction zero or parallel to the tangent",
            });
        }
        let e_z0 = z / zn;
        let e_y0 = e_z0.cross(&t0);
        Ok(Self { t0, e_y0, e_z0 })
    }

    /// Frame for a strand along `t0` with the default phase reference
    /// ([`default_phase_reference`]).
    pub fn along(t0: Vector3<f64>) -> Result<Self, AncfError> {
        Self::new(t0, default_phase_reference(&t0))
    }

    /// Values of a frame kept as state: `t0` and `e_z0` ([`Self::STATE_LEN`] values).
    pub const STATE_LEN: usize = 6;

    /// The frame kept as state `(t0, e_z0)` (see [`Self::write_state`]); the pair is
    /// orthonormalized again, so round-off does not accumulate over steps.
    #[inline]
    pub fn from_state(state: &[f64]) -> Result<Self, AncfError> {
        Self::new(
            Vector3::new(state[0], state[1], state[2]),
            Vector3::new(state[3], state[4], state[5]),
        )
    }

    /// Writes the frame with tangent `t` and phase axis `e_z` as state (6 values).
    #[inline]
    pub fn write_state(t: &Vector3<f64>, e_z: &Vector3<f64>, out: &mut [f64]) {
        out[..3].copy_from_slice(t.as_slice());
        out[3..6].copy_from_slice(e_z.as_slice());
    }

    /// Reference tangent `t0`.
    pub fn t0(&self) -> Vector3<f64> {
        self.t0
    }

    /// Reference `e_y0`.
    pub fn e_y0(&self) -> Vector3<f64> {
        self.e_y0
    }

    /// Reference `e_z0`.
    pub fn e_z0(&self) -> Vector3<f64> {
        self.e_z0
    }

    /// The section frame `(e_y, e_z)` carried to the unit tangent `t` by the minimal
    /// rotation taking `t0` to `t`.
    pub fn carried(&self, t: &Vector3<f64>) -> Result<[Vector3<f64>; 2], AncfError> {
        let alignment = check_alignment(1.0 + self.t0.dot(t))?;
        let s = self.t0 + t;
        let carry = |e: &Vector3<f64>| e - s * (e.dot(t) / alignment);
        Ok([carry(&self.e_y0), carry(&self.e_z0)])
    }
}

/// The direction of phase zero at x = 0 when a scene gives none, for a strand along `t0`: the
/// global Z axis projected off `t0`. For a strand in the XY plane that is Z itself, the
/// convention of the planar element (phases of eq. (36) measured from the out-of-plane axis,
/// SPEC 2). For a strand along Z, where Z has no part off the direction, it is the global X
/// axis; close to Z the projection turns quickly with the direction, so such scenes should
/// give their phase reference.
pub fn default_phase_reference(t0: &Vector3<f64>) -> Vector3<f64> {
    let n = t0.norm();
    if n.is_nan() || n <= 0.0 {
        return Vector3::z();
    }
    let t = t0 / n;
    let z = Vector3::z() - t * t.z;
    if z.norm() > 1e-12 {
        z
    } else {
        Vector3::x() - t * t.x
    }
}

/// Local kinematic variables at one point: `r'` and `r''`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialPoint {
    /// Position gradient `r' = dr/dx`.
    pub dr: Vector3<f64>,
    /// Second derivative `r'' = d^2 r/dx^2`.
    pub ddr: Vector3<f64>,
}

/// The axial strain at a point: `eps = |r'| - 1` with gradient `t` with respect to `r'`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialAxial {
    /// Axial strain.
    pub eps: f64,
    /// Unit tangent `t = r' / |r'|`, the gradient of `eps` with respect to `r'`.
    pub tangent: Vector3<f64>,
    /// `|r'|`.
    pub stretch: f64,
}

impl SpatialAxial {
    /// `d^2 eps / dr'^2 = (I - t t^T) / |r'|`.
    #[inline]
    pub fn hessian(&self) -> Matrix3<f64> {
        (Matrix3::identity() - self.tangent * self.tangent.transpose()) / self.stretch
    }

    /// `d eps / dy` with respect to `y = (r', r'')` (the last three entries are zero).
    #[inline]
    pub fn gradient(&self) -> Vector6<f64> {
        let t = &self.tangent;
        Vector6::new(t.x, t.y, t.z, 0.0, 0.0, 0.0)
    }

    /// `d^2 eps / dy^2` (only the `r'` block is non-zero).
    #[inline]
    pub fn hessian6(&self) -> Matrix6<f64> {
        let mut h = Matrix6::zeros();
        h.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.hessian());
        h
    }
}

/// Strain, curvature components and their gradients with respect to `y = (r', r'')`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialFirst {
    /// Axial strain `eps = |r'| - 1`.
    pub eps: f64,
    /// Curvature vector in the section frame `(kappa_y, kappa_z) = (k . e_y, k . e_z)` (1/m).
    pub kappa: [f64; 2],
    /// Global curvature vector per reference length `k = r' x r'' / |r'|^2` (1/m).
    pub curvature: Vector3<f64>,
    /// Unit tangent `t = r' / |r'|`.
    pub tangent: Vector3<f64>,
    /// Current section axes `(e_y, e_z)`.
    pub axes: [Vector3<f64>; 2],
    /// `d eps / dy` (the last three entries are zero).
    pub eps_grad: Vector6<f64>,
    /// `(d kappa_y / dy, d kappa_z / dy)`.
    pub kappa_grad: [Vector6<f64>; 2],
}

/// [`SpatialFirst`] plus the Hessians with respect to `y = (r', r'')`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialSecond {
    /// Values and gradients.
    pub first: SpatialFirst,
    /// `d^2 eps / dy^2`: only the `r'` block `(I - t t^T) / |r'|` is non-zero.
    pub eps_hess: Matrix6<f64>,
    /// `(d^2 kappa_y / dy^2, d^2 kappa_z / dy^2)`; their `r''` blocks are zero.
    pub kappa_hess: [Matrix6<f64>; 2],
}

/// Quantities shared by both curvature components.
struct Shared {
    n: f64,
    t: Vector3<f64>,
    /// `1 / n^2`.
    g: f64,
    /// `d g / da = -2 t g / n`.
    g_a: Vector3<f64>,
    /// `a x b`.
    w: Vector3<f64>,
    /// `d = n + t0 . a`.
    d: f64,
    /// `d d / da = t + t0`.
    d_a: Vector3<f64>,
    /// `c_u = (a x b) . t0`.
    c_u: f64,
    /// `d c_u / da = b x t0`.
    c_u_a: Vector3<f64>,
    /// `d c_u / db = t0 x a`.
    c_u_b: Vector3<f64>,
    alignment: f64,
}

/// One curvature component `kappa_e = N g` with `N = c_e - h`, `h = p c_u / d`: value and
/// first derivatives of `N` (kept for the Hessian).
struct Component {
    p: f64,
    big_n: f64,
    n_a: Vector3<f64>,
    n_b: Vector3<f64>,
    h: f64,
    /// `d (p c_u) / da`.
    f_a: Vector3<f64>,
}

impl SpatialPoint {
    /// Local variables from raw vectors.
    #[inline]
    pub fn new(dr: Vector3<f64>, ddr: Vector3<f64>) -> Self {
        Self { dr, ddr }
    }

    /// `r'` and `r''` of the element with coordinates `q` at the point of `row`.
    #[inline]
    pub fn at(q: &SpatialCoords, row: &ShapeRow) -> Self {
        Self {
            dr: Vector3::from(scatter::combine::<3>(&row.ds, q.as_slice())),
            ddr: Vector3::from(scatter::combine::<3>(&row.dds, q.as_slice())),
        }
    }

    #[inline]
    fn stretch(&self) -> Result<f64, AncfError> {
        check_stretch(self.dr.norm())
    }

    /// Axial strain `eps = |r'| - 1`.
    #[inline]
    pub fn strain(&self) -> Result<f64, AncfError> {
        Ok(self.stretch()? - 1.0)
    }

    /// Axial strain, unit tangent and stretch (no section frame needed).
    #[inline]
    pub fn axial(&self) -> Result<SpatialAxial, AncfError> {
        let n = self.stretch()?;
        Ok(SpatialAxial {
            eps: n - 1.0,
            tangent: self.dr / n,
            stretch: n,
        })
    }

    /// Global curvature vector per reference length `k = r' x r'' / |r'|^2`; its norm is the
    /// curvature (1/m).
    #[inline]
    pub fn curvature_vector(&self) -> Result<Vector3<f64>, AncfError> {
        let n = self.stretch()?;
        Ok(self.dr.cross(&self.ddr) / (n * n))
    }

    /// Curvature components `(kappa_y, kappa_z)` in the section frame carried from `frame`.
    pub fn curvature(&self, frame: &SectionFrame) -> Result<[f64; 2], AncfError> {
        let s = self.shared(frame)?;
        let e = [frame.e_y0, frame.e_z0];
        Ok(e.map(|e0| (s.w.dot(&e0) - e0.dot(&self.dr) * s.c_u / s.d) * s.g))
    }

    #[inline]
    fn shared(&self, frame: &SectionFrame) -> Result<Shared, AncfError> {
        let n = self.stretch()?;
        let (a, b, u) = (&self.dr, &self.ddr, &frame.t0);
        let t = a / n;
        let alignment = check_alignment(1.0 + u.dot(&t))?;
        let g = 1.0 / (n * n);
        let w = a.cross(b);
        Ok(Shared {
            n,
            t,
            g,
            g_a: t * (-2.0 * g / n),
            w,
            d: n * alignment,
            d_a: t + u,
            c_u: w.dot(u),
            c_u_a: b.cross(u),
            c_u_b: u.cross(a),
            alignment,
        })
    }

    #[inline]
    fn component(&self, s: &Shared, e0: &Vector3<f64>) -> Component {
        let (a, b) = (&self.dr, &self.ddr);
        let c_e = s.w.dot(e0);
        let p = e0.dot(a);
        let h = p * s.c_u / s.d;
        let f_a = e0 * s.c_u + s.c_u_a * p;
        let h_a = (f_a - s.d_a * h) / s.d;
        let h_b = s.c_u_b * (p / s.d);
        Component {
            p,
            big_n: c_e - h,
            n_a: b.cross(e0) - h_a,
            n_b: e0.cross(a) - h_b,
            h,
            f_a,
        }
    }

    /// Strain, curvature components and their gradients with respect to `(r', r'')`.
    pub fn first(&self, frame: &SectionFrame) -> Result<SpatialFirst, AncfError> {
        let s = self.shared(frame)?;
        let cy = self.component(&s, &frame.e_y0);
        let cz = self.component(&s, &frame.e_z0);
        Ok(self.first_from(frame, &s, &cy, &cz))
    }

    fn first_from(
        &self,
        frame: &SectionFrame,
        s: &Shared,
        cy: &Component,
        cz: &Component,
    ) -> SpatialFirst {
        let grad = |c: &Component| {
            let ka = c.n_a * s.g + s.g_a * c.big_n;
            let kb = c.n_b * s.g;
            Vector6::new(ka.x, ka.y, ka.z, kb.x, kb.y, kb.z)
        };
        let sum = frame.t0 + s.t;
        let carry = |e: &Vector3<f64>| e - sum * (e.dot(&s.t) / s.alignment);
        SpatialFirst {
            eps: s.n - 1.0,
            kappa: [cy.big_n * s.g, cz.big_n * s.g],
            curvature: s.w * s.g,
            tangent: s.t,
            axes: [carry(&frame.e_y0), carry(&frame.e_z0)],
            eps_grad: Vector6::new(s.t.x, s.t.y, s.t.z, 0.0, 0.0, 0.0),
            kappa_grad: [grad(cy), grad(cz)],
        }
    }

    /// Strain, curvature components, gradients and Hessians with respect to `(r', r'')`.
    pub fn second(&self, frame: &SectionFrame) -> Result<SpatialSecond, AncfError> {
        let s = self.shared(frame)?;
        let cy = self.component(&s, &frame.e_y0);
        let cz = self.component(&s, &frame.e_z0);
        let first = self.first_from(frame, &s, &cy, &cz);

        let id = Matrix3::identity();
        let tt = s.t * s.t.transpose();
        let d_aa = (id - tt) / s.n;
        let mut eps_hess = Matrix6::zeros();
        eps_hess.fixed_view_mut::<3, 3>(0, 0).copy_from(&d_aa);

        // g_aa = -2 I / n^4 + 8 a a^T / n^6.
        let g_aa = (tt * 8.0 - id * 2.0) * (s.g / (s.n * s.n));
        // d^2 c_u / da db = -[t0]x (rows a, columns b).
        let cu_ab = -frame.t0.cross_matrix();
        let hess = |c: &Component, e0: &Vector3<f64>| {
            let d = s.d;
            let d2 = d * d;
            // f = p c_u; h = f / d.
            let f_aa = e0 * s.c_u_a.transpose() + s.c_u_a * e0.transpose();
            let h_aa = f_aa / d
                - (c.f_a * s.d_a.transpose() + s.d_a * c.f_a.transpose()) / d2
                - d_aa * (c.h / d)
                + s.d_a * s.d_a.transpose() * (2.0 * c.h / d2);
            let f_b = s.c_u_b * c.p;
            let f_ab = e0 * s.c_u_b.transpose() + cu_ab * c.p;
            let h_ab = f_ab / d - s.d_a * f_b.transpose() / d2;
            let n_aa = -h_aa;
            // d^2 c_e / da db = -[e0]x.
            let n_ab = -e0.cross_matrix() - h_ab;
            let k_aa =
                n_aa * s.g + c.n_a * s.g_a.transpose() + s.g_a * c.n_a.transpose() + g_aa * c.big_n;
            let k_ab = n_ab * s.g + s.g_a * c.n_b.transpose();
            let mut m = Matrix6::zeros();
            m.fixed_view_mut::<3, 3>(0, 0).copy_from(&k_aa);
            m.fixed_view_mut::<3, 3>(0, 3).copy_from(&k_ab);
            m.fixed_view_mut::<3, 3>(3, 0).copy_from(&k_ab.transpose());
            m
        };
        let kappa_hess = [hess(&cy, &frame.e_y0), hess(&cz, &frame.e_z0)];
        Ok(SpatialSecond {
            first,
            eps_hess,
            kappa_hess,
        })
    }
}

/// Section resultants at a point and their tangents, as a section law returns them
/// (`strand_core::SectionResponse`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpatialSection {
    /// Axial force `N` (N).
    pub n: f64,
    /// `dN/deps` (N).
    pub dn_deps: f64,
    /// Bending moments `(M_y, M_z)` conjugate to `(kappa_y, kappa_z)` (N m).
    pub m: [f64; 2],
    /// `dM_a / dkappa_b` (N m^2).
    pub dm_dkappa: [[f64; 2]; 2],
    /// `dM_a / deps` (N m); makes the tangent non-symmetric.
    pub dm_deps: [f64; 2],
}

impl SpatialFirst {
    /// Local generalized force `N d eps/dy + sum_a M_a d kappa_a/dy` (the integrand of eq.
    /// (28) in the variables `y = (r', r'')`); map with [`add_gradient`].
    #[inline]
    pub fn force(&self, s: &SpatialSection) -> Vector6<f64> {
        self.eps_grad * s.n + self.kappa_grad[0] * s.m[0] + self.kappa_grad[1] * s.m[1]
    }
}

impl SpatialSecond {
    /// Local generalized force, as [`SpatialFirst::force`].
    #[inline]
    pub fn force(&self, s: &SpatialSection) -> Vector6<f64> {
        self.first.force(s)
    }

    /// Local tangent `d force / dy` (rows: force component, columns: variable):
    ///
    /// ```text
    /// N eps_yy + sum_a M_a kappa_a,yy + N_eps eps_y eps_y^T
    ///   + sum_ab (dM_a/dkappa_b) kappa_a,y kappa_b,y^T + sum_a (dM_a/deps) kappa_a,y eps_y^T
    /// ```
    ///
    /// Map with [`add_hessian`].
    #[inline]
    pub fn tangent(&self, s: &SpatialSection) -> Matrix6<f64> {
        let ge = &self.first.eps_grad;
        let gk = &self.first.kappa_grad;
        let mut k = self.eps_hess * s.n
            + self.kappa_hess[0] * s.m[0]
            + self.kappa_hess[1] * s.m[1]
            + ge * ge.transpose() * s.dn_deps;
        for a in 0..2 {
            let row = s.dm_dkappa[a][0] * gk[0] + s.dm_dkappa[a][1] * gk[1] + ge * s.dm_deps[a];
            k += gk[a] * row.transpose();
        }
        k
    }
}

/// Position `r(x) = S(x) q` (eq. (26)).
#[inline]
pub fn position(q: &SpatialCoords, row: &ShapeRow) -> Vector3<f64> {
    Vector3::from(scatter::combine::<3>(&row.s, q.as_slice()))
}

/// Element gradient `df/dq` (12) from the local gradient `(df/dr', df/dr'')` (6).
#[inline]
pub fn scatter_gradient(row: &ShapeRow, g: &Vector6<f64>) -> SpatialVector {
    let mut out = SpatialVector::zeros();
    add_gradient(&mut out, 1.0, row, g);
    out
}

/// `out += w df/dq` for the local gradient `g = (df/dr', df/dr'')`.
#[inline]
pub fn add_gradient(out: &mut SpatialVector, w: f64, row: &ShapeRow, g: &Vector6<f64>) {
    scatter::add_gradient::<3>(out.as_mut_slice(), w, row, g.as_slice());
}

/// Element Hessian `d^2 f/dq^2` (12x12) from the local Hessian with respect to `(r', r'')`
/// (6x6). Also maps non-symmetric local tangents.
#[inline]
pub fn scatter_hessian(row: &ShapeRow, h: &Matrix6<f64>) -> SpatialMatrix {
    let mut out = SpatialMatrix::zeros();
    add_hessian(&mut out, 1.0, row, h);
    out
}

/// `out += w d^2 f/dq^2` for the local Hessian `h` with respect to `(r', r'')`.
#[inline]
pub fn add_hessian(out: &mut SpatialMatrix, w: f64, row: &ShapeRow, h: &Matrix6<f64>) {
    scatter::add_hessian::<3, 6, 12>(out, w, row, h);
}
