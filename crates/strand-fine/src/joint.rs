//! Joint springs of the finite segment method (Hamper, Recuero, Escalona, Shabana 2012).
//!
//! Two bodies `a` and `b` (neighbouring segments of a wire, or the ground and a wire's end
//! segment) are joined at attachment points fixed in each body. The joint stores the relative
//! pose at rest, so a wire laid along a helix is stress-free in its helical shape.
//!
//! * Gap: `e = R_a^T (p_b - p_a) - e_0` in body `a`'s axes (m), with a diagonal spring
//!   `(k_axial, k_shear, k_shear) = (E A, kappa G A, kappa G A) / l` (N/m).
//! * Relative rotation: `Q = Q_0^T R_a^T R_b`, rotation vector `theta = log Q` (rad) in body
//!   `b`'s axes, with a diagonal spring `(k_torsion, k_bend, k_bend) = (G J, E I, E I) / l`
//!   (N m/rad).
//!
//! Energy `U = (e^T K_t e + theta^T K_r theta) / 2` (J). Forces and torques are the exact
//! negative gradient of `U` with respect to translations and world-frame rotation increments
//! (`R <- exp(dw) R`), so they conserve linear and angular momentum and are invariant under a
//! rigid motion of both bodies.

use nalgebra::{SMatrix, UnitQuaternion, Vector3};

use crate::segment::{Frame, Pose, rotate_offset};
use crate::so3;

/// Spring constants of one joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointStiffness {
    /// Translational springs on the gap along body `a`'s axes: axial, shear, shear (N/m).
    pub translational: Vector3<f64>,
    /// Rotational springs about body `b`'s axes: torsion, bending, bending (N m/rad).
    pub rotational: Vector3<f64>,
}

impl JointStiffness {
    /// Doubles every spring: used for a half-length joint (e.g. a support, which represents
    /// the half segment between the support and the first segment's centre).
    pub fn scaled(&self, factor: f64) -> Self {
        Self {
            translational: self.translational * factor,
            rotational: self.rotational * factor,
        }
    }
}

/// Loads a joint exerts on its two bodies (world axes) and its stored energy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointLoad {
    /// Force on body `a` (N).
    pub force_a: Vector3<f64>,
    /// Torque on body `a` about its centre (N m).
    pub torque_a: Vector3<f64>,
    /// Force on body `b` (N).
    pub force_b: Vector3<f64>,
    /// Torque on body `b` about its centre (N m).
    pub torque_b: Vector3<f64>,
    /// Elastic energy stored in the joint (J).
    pub energy: f64,
}

/// A spring joint between two rigid bodies, relaxed at a stored rest pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointSpring {
    /// Attachment point in body `a`'s axes, relative to its centre (m).
    pub offset_a: Vector3<f64>,
    /// Attachment point in body `b`'s axes, relative to its centre (m).
    pub offset_b: Vector3<f64>,
    /// Gap `R_a^T (p_b - p_a)` at rest (m), in `a`'s axes.
    pub rest_gap: Vector3<f64>,
    /// Relative rotation `R_a^T R_b` at rest.
    pub rest_rotation: UnitQuaternion<f64>,
    /// Spring constants.
    pub stiffness: JointStiffness,
}

impl JointSpring {
    /// Joint relaxed at the rest poses `a`, `b` with attachment offsets `offset_a`, `offset_b`.
    pub fn at_rest(
        a: &Pose,
        offset_a: Vector3<f64>,
        b: &Pose,
        offset_b: Vector3<f64>,
        stiffness: JointStiffness,
    ) -> Self {
        let mut j = Self {
            offset_a,
            offset_b,
            rest_gap: Vector3::zeros(),
            rest_rotation: a.rotation.inverse() * b.rotation,
            stiffness,
        };
        j.rest_gap = j.gap(a, b);
        j
    }

    /// Gap vector `R_a^T (p_b - p_a)` in `a`'s axes (m).
    fn gap(&self, a: &Pose, b: &Pose) -> Vector3<f64> {
        // The arithmetic of `evaluate_in`, so that the rest pose is exactly relaxed.
        let (fa, fb) = (Frame::of(a), Frame::of(b));
        let d = (b.position + rotate_offset(&fb.matrix, &self.offset_b))
            - (a.position + rotate_offset(&fa.matrix, &self.offset_a));
        fa.matrix.tr_mul(&d)
    }

    /// Rotation vector `log(Q_0^T R_a^T R_b)` (rad), in `b`'s axes.
    #[inline(always)]
    pub fn rotation_strain(&self, a: &Pose, b: &Pose) -> Vector3<f64> {
        so3::log(&(self.rest_rotation.inverse() * (a.rotation.inverse() * b.rotation)))
    }

    /// Gap deformation `e` (m) in `a`'s axes.
    pub fn gap_strain(&self, a: &Pose, b: &Pose) -> Vector3<f64> {
        self.gap(a, b) - self.rest_gap
    }

    /// Forces, torques and energy for bodies at poses `a` and `b`.
    pub fn evaluate(&self, a: &Pose, b: &Pose) -> JointLoad {
        self.evaluate_in(a, &Frame::of(a), b, &Frame::of(b))
    }

    /// [`JointSpring::evaluate`] with the bodies' frames `fa`, `fb` (their poses' rotation
    /// matrices) at hand: a wire's segments share theirs between two joints and contacts.
    #[inline(always)]
    pub fn evaluate_in(&self, a: &Pose, fa: &Frame, b: &Pose, fb: &Frame) -> JointLoad {
        let arm_a = rotate_offset(&fa.matrix, &self.offset_a);
        let arm_b = rotate_offset(&fb.matrix, &self.offset_b);
        let d = (b.position + arm_b) - (a.position + arm_a);
        let e = fa.matrix.tr_mul(&d) - self.rest_gap;
        let fe = self.stiffness.translational.component_mul(&e);
        // f = dU/dp_b; the spring pulls b by -f and a by +f.
        let f = fa.matrix * fe;
        let theta = self.rotation_strain(a, b);
        let m = self.stiffness.rotational.component_mul(&theta);
        let t = fb.matrix * so3::right_jacobian_inv_t(&theta, &m);
        JointLoad {
            force_a: f,
            torque_a: (arm_a + d).cross(&f) + t,
            force_b: -f,
            torque_b: -arm_b.cross(&f) - t,
            energy: 0.5 * (e.dot(&fe) + theta.dot(&m)),
        }
    }

    /// Elastic energy (J) only.
    pub fn energy(&self, a: &Pose, b: &Pose) -> f64 {
        let e = self.gap_strain(a, b);
        let theta = self.rotation_strain(a, b);
        0.5 * (e.dot(&self.stiffness.translational.component_mul(&e))
            + theta.dot(&self.stiffness.rotational.component_mul(&theta)))
    }

    /// Tangent stiffness `K = -d(F_a, T_a, F_b, T_b) / d(dx_a, dw_a, dx_b, dw_b)` (12 x 12;
    /// N/m, N, N m/rad blocks), with `dw` world-frame rotation increments. Computed by central
    /// differences of the exact loads; `length` (m) sets the translation step.
    pub fn stiffness(&self, a: &Pose, b: &Pose, length: f64) -> SMatrix<f64, 12, 12> {
        let step_x = 1e-6 * length;
        let step_w = 1e-6;
        let mut k = SMatrix::<f64, 12, 12>::zeros();
        for col in 0..12 {
            let h = if col % 6 < 3 { step_x } else { step_w };
            let lp = self.evaluate_perturbed(a, b, col, h);
            let lm = self.evaluate_perturbed(a, b, col, -h);
            for (blk, (p, m)) in [
                (lp.force_a, lm.force_a),
                (lp.torque_a, lm.torque_a),
                (lp.force_b, lm.force_b),
                (lp.torque_b, lm.torque_b),
            ]
            .iter()
            .enumerate()
            {
                for r in 0..3 {
                    k[(3 * blk + r, col)] = -(p[r] - m[r]) / (2.0 * h);
                }
            }
        }
        k
    }

    fn evaluate_perturbed(&self, a: &Pose, b: &Pose, col: usize, h: f64) -> JointLoad {
        let (mut a, mut b) = (*a, *b);
        let body = if col < 6 { &mut a } else { &mut b };
        perturb(body, col % 6, h);
        self.evaluate(&a, &b)
    }
}

/// Moves `pose` by `h` along generalized coordinate `dof` (0-2: translation in m, 3-5:
/// world-frame rotation in rad).
pub fn perturb(pose: &mut Pose, dof: usize, h: f64) {
    if dof < 3 {
        pose.position[dof] += h;
    } else {
        let mut w = Vector3::zeros();
        w[dof - 3] = h;
        pose.rotation = so3::exp(&w) * pose.rotation;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn sample() -> (JointSpring, Pose, Pose) {
        let a = Pose::new(
            Vector3::new(0.1, 0.02, -0.01),
            UnitQuaternion::from_scaled_axis(Vector3::new(0.2, 0.5, -0.3)),
        );
        let b = Pose::new(
            Vector3::new(0.11, 0.023, -0.012),
            UnitQuaternion::from_scaled_axis(Vector3::new(0.25, 0.45, -0.2)),
        );
        let k = JointStiffness {
            translational: Vector3::new(1e5, 4e4, 4e4),
            rotational: Vector3::new(0.02, 0.03, 0.03),
        };
        let j = JointSpring::at_rest(
            &a,
            Vector3::new(0.005, 0.0, 0.0),
            &b,
            Vector3::new(-0.005, 0.0, 0.0),
            k,
        );
        (j, a, b)
    }

    fn deform(a: &Pose, b: &Pose) -> (Pose, Pose) {
        let mut a2 = *a;
        let mut b2 = *b;
        a2.position += Vector3::new(1e-4, -2e-4, 5e-5);
        a2.rotation = so3::exp(&Vector3::new(0.1, -0.05, 0.2)) * a2.rotation;
        b2.rotation = so3::exp(&Vector3::new(-0.3, 0.2, 0.1)) * b2.rotation;
        (a2, b2)
    }

    #[test]
    fn relaxed_at_rest_and_under_rigid_motion() {
        let (j, a, b) = sample();
        let l = j.evaluate(&a, &b);
        assert!(l.energy < 1e-30);
        assert!(l.force_a.norm() < 1e-14 && l.torque_a.norm() < 1e-16);
        let g = UnitQuaternion::from_scaled_axis(Vector3::new(1.0, -2.0, 0.5));
        let shift = Vector3::new(0.3, -0.1, 2.0);
        let moved = |p: &Pose| Pose::new(g * p.position + shift, g * p.rotation);
        let l = j.evaluate(&moved(&a), &moved(&b));
        // Round-off of positions of order 1 m on springs of 1e5 N/m.
        assert!(l.force_a.norm() < 1e-9, "{}", l.force_a.norm());
        assert!(l.torque_a.norm() < 1e-12, "{}", l.torque_a.norm());
        assert!(l.energy < 1e-25);
    }

    #[test]
    fn loads_are_the_energy_gradient() {
        let (j, a, b) = sample();
        let (a, b) = deform(&a, &b);
        let l = j.evaluate(&a, &b);
        let loads = [l.force_a, l.torque_a, l.force_b, l.torque_b];
        for col in 0..12 {
            let h = if col % 6 < 3 { 1e-7 } else { 1e-6 };
            let mut ap = a;
            let mut bp = b;
            let mut am = a;
            let mut bm = b;
            if col < 6 {
                perturb(&mut ap, col, h);
                perturb(&mut am, col, -h);
            } else {
                perturb(&mut bp, col - 6, h);
                perturb(&mut bm, col - 6, -h);
            }
            let de = (j.energy(&ap, &bp) - j.energy(&am, &bm)) / (2.0 * h);
            let expected = -loads[col / 3][col % 3];
            assert_relative_eq!(
                de,
                expected,
                epsilon = 1e-7 * loads[col / 3].norm().max(1e-3)
            );
        }
    }

    #[test]
    fn momentum_balance() {
        let (j, a, b) = sample();
        let (a, b) = deform(&a, &b);
        let l = j.evaluate(&a, &b);
        assert!((l.force_a + l.force_b).norm() < 1e-12 * l.force_a.norm());
        let moment =
            a.position.cross(&l.force_a) + b.position.cross(&l.force_b) + l.torque_a + l.torque_b;
        assert!(moment.norm() < 1e-12 * l.force_a.norm());
    }

    #[test]
    fn stiffness_is_symmetric_at_rest() {
        let (j, a, b) = sample();
        let k = j.stiffness(&a, &b, 0.01);
        let scale = k.abs().max();
        assert!((k - k.transpose()).abs().max() < 1e-7 * scale);
        // The axial spring appears on the diagonal (a's axis 1 in world axes).
        let t = a.tangent();
        let kx = t.transpose() * k.fixed_view::<3, 3>(0, 0) * t;
        assert_relative_eq!(kx[0], 1e5, max_relative = 1e-6);
    }
}
