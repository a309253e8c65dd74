//! Rigid cylindrical segments and their poses.
//!
//! A segment is a solid circular cylinder of length `l` and radius `r` whose body axis 1 is
//! the cylinder axis (the wire's tangent), axis 2 the material normal (toward the strand axis
//! for a helical wire) and axis 3 the binormal. Its pose is the position of its centre of mass
//! and the rotation from body to world axes.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Position of a segment's centre (m) and rotation body -> world (unit quaternion).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Centre of mass in world coordinates (m).
    pub position: Vector3<f64>,
    /// Rotation from body axes (1 = tangent, 2 = normal, 3 = binormal) to world axes.
    pub rotation: UnitQuaternion<f64>,
}

impl Pose {
    /// Pose at `position` with rotation `rotation`.
    pub fn new(position: Vector3<f64>, rotation: UnitQuaternion<f64>) -> Self {
        Self { position, rotation }
    }

    /// World position (m) of the body-frame point `offset` (m).
    pub fn point(&self, offset: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.rotation * offset
    }

    /// World direction of body axis 1 (the segment's tangent).
    pub fn tangent(&self) -> Vector3<f64> {
        self.rotation * Vector3::x()
    }

    /// Rotation matrix body -> world.
    pub fn matrix(&self) -> Matrix3<f64> {
        self.rotation.to_rotation_matrix().into_inner()
    }
}

/// Where a rigid segment is: its centre and the map of body vectors to world axes. Two
/// forms: a [`Pose`] (rotation as a unit quaternion, what the state stores) and a [`Frame`]
/// (rotation as a matrix, for a body whose many points and directions are evaluated in one
/// load evaluation: a matrix turns a vector in about half the operations of a quaternion).
pub trait Placement {
    /// Centre of mass in world coordinates (m).
    fn centre(&self) -> Vector3<f64>;
    /// World position (m) of the body-frame point `offset` (m).
    fn point(&self, offset: &Vector3<f64>) -> Vector3<f64>;
    /// World direction of body axis 1 (the segment's tangent).
    fn tangent(&self) -> Vector3<f64>;
    /// Body-frame components of the world vector `v`.
    fn to_body(&self, v: &Vector3<f64>) -> Vector3<f64>;
}

impl Placement for Pose {
    fn centre(&self) -> Vector3<f64> {
        self.position
    }
    fn point(&self, offset: &Vector3<f64>) -> Vector3<f64> {
        Pose::point(self, offset)
    }
    fn tangent(&self) -> Vector3<f64> {
        Pose::tangent(self)
    }
    fn to_body(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.rotation.inverse_transform_vector(v)
    }
}

/// A pose with its rotation as a matrix (see [`Placement`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Centre of mass in world coordinates (m).
    pub position: Vector3<f64>,
    /// Rotation matrix body -> world.
    pub matrix: Matrix3<f64>,
}

impl Frame {
    /// The frame of `pose`.
    pub fn of(pose: &Pose) -> Self {
        Self {
            position: pose.position,
            matrix: pose.matrix(),
        }
    }
}

impl Default for Frame {
    fn default() -> Self {
        Self {
            position: Vector3::zeros(),
            matrix: Matrix3::identity(),
        }
    }
}

/// `matrix * offset`: a body-frame offset (m) turned into world axes. For an offset on the
/// body axis 1 (every joint arm and contact point of a chain) the first column times the
/// offset's length, without the six products with the zero components: the same value,
/// up to the sign of an exactly zero component.
#[inline]
pub(crate) fn rotate_offset(matrix: &Matrix3<f64>, offset: &Vector3<f64>) -> Vector3<f64> {
    if offset.y == 0.0 && offset.z == 0.0 {
        matrix.column(0) * offset.x
    } else {
        matrix * offset
    }
}

impl Placement for Frame {
    fn centre(&self) -> Vector3<f64> {
        self.position
    }
    fn point(&self, offset: &Vector3<f64>) -> Vector3<f64> {
        self.position + rotate_offset(&self.matrix, offset)
    }
    fn tangent(&self) -> Vector3<f64> {
        self.matrix.column(0).into_owned()
    }
    fn to_body(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.matrix.tr_mul(v)
    }
}

/// Mass properties of a rigid solid cylinder.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Length l along body axis 1 (m).
    pub length: f64,
    /// Radius r (m).
    pub radius: f64,
    /// Mass m = rho pi r^2 l (kg).
    pub mass: f64,
    /// Moment of inertia about the cylinder axis, m r^2 / 2 (kg m^2).
    pub axial_inertia: f64,
    /// Moment of inertia about a transverse axis through the centre, m (3 r^2 + l^2) / 12
    /// (kg m^2).
    pub transverse_inertia: f64,
}

impl Segment {
    /// Solid cylinder of length `length` (m), radius `radius` (m) and density `density`
    /// (kg/m^3).
    pub fn cylinder(length: f64, radius: f64, density: f64) -> Self {
        let mass = density * std::f64::consts::PI * radius * radius * length;
        Self {
            length,
            radius,
            mass,
            axial_inertia: 0.5 * mass * radius * radius,
            transverse_inertia: mass * (3.0 * radius * radius + length * length) / 12.0,
        }
    }

    /// The same cylinder with mass and inertias multiplied by `factor` (a density change).
    pub fn with_mass_scaled(&self, factor: f64) -> Self {
        Self {
            mass: self.mass * factor,
            axial_inertia: self.axial_inertia * factor,
            transverse_inertia: self.transverse_inertia * factor,
            ..*self
        }
    }

    /// Body-frame offset of the segment's start (-l/2 along axis 1) (m).
    pub fn start_offset(&self) -> Vector3<f64> {
        Vector3::new(-0.5 * self.length, 0.0, 0.0)
    }

    /// Body-frame offset of the segment's end (+l/2 along axis 1) (m).
    pub fn end_offset(&self) -> Vector3<f64> {
        Vector3::new(0.5 * self.length, 0.0, 0.0)
    }

    /// Rotational kinetic energy (J) for the world-frame angular momentum `h` (kg m^2/s) at
    /// pose `pose`: (h_1^2 / I_1 + (|h|^2 - h_1^2) / I_2) / 2 with h_1 along the axis.
    pub fn rotational_energy(&self, pose: &Pose, h: &Vector3<f64>) -> f64 {
        let h1 = pose.tangent().dot(h);
        0.5 * (h1 * h1 / self.axial_inertia
            + (h.norm_squared() - h1 * h1) / self.transverse_inertia)
    }

    /// World-frame angular velocity (rad/s) for the world-frame angular momentum `h`.
    pub fn angular_velocity(&self, pose: &Pose, h: &Vector3<f64>) -> Vector3<f64> {
        let n = pose.tangent();
        let h1 = n.dot(h);
        h / self.transverse_inertia
            + n * (h1 * (1.0 / self.axial_inertia - 1.0 / self.transverse_inertia))
    }

    /// World-frame angular momentum (kg m^2/s) for the world-frame angular velocity `omega`
    /// (the inverse of [`Self::angular_velocity`]): `I_2 omega + (I_1 - I_2) n (n . omega)`.
    pub fn angular_momentum(&self, pose: &Pose, omega: &Vector3<f64>) -> Vector3<f64> {
        let n = pose.tangent();
        omega * self.transverse_inertia
            + n * (n.dot(omega) * (self.axial_inertia - self.transverse_inertia))
    }

    /// Exact torque-free motion of the axisymmetric body over `dt` (s) with constant
    /// world-frame angular momentum `h`: the rotation becomes
    /// `exp(dt h / I_2) R exp(dt h_1 (1/I_1 - 1/I_2) e_1)`.
    #[inline(always)]
    pub fn free_rotation(
        &self,
        rotation: &UnitQuaternion<f64>,
        h: &Vector3<f64>,
        dt: f64,
    ) -> UnitQuaternion<f64> {
        let world = crate::so3::exp(&(h * (dt / self.transverse_inertia)));
        // An isotropic body (equal inertias) does not spin relative to the world turn: skip
        // the identity (the same result bit for bit), and the spin's arithmetic with it
        // (its factor 1/I_1 - 1/I_2 is exactly 0).
        let spin = if self.axial_inertia == self.transverse_inertia {
            0.0
        } else {
            let h1 = (rotation * Vector3::x()).dot(h);
            dt * h1 * (1.0 / self.axial_inertia - 1.0 / self.transverse_inertia)
        };
        let mut q = if spin == 0.0 {
            world * rotation
        } else {
            world * rotation * crate::so3::exp(&Vector3::new(spin, 0.0, 0.0))
        };
        q.renormalize();
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn cylinder_inertia() {
        let s = Segment::cylinder(0.01, 0.001, 7801.0);
        let m = 7801.0 * std::f64::consts::PI * 1e-6 * 0.01;
        assert_relative_eq!(s.mass, m, max_relative = 1e-14);
        assert_relative_eq!(s.axial_inertia, m * 1e-6 / 2.0, max_relative = 1e-14);
        assert_relative_eq!(
            s.transverse_inertia,
            m * (3e-6 + 1e-4) / 12.0,
            max_relative = 1e-14
        );
    }

    #[test]
    fn free_rotation_is_exact_torque_free_motion() {
        // Integrate dR/dt = [omega] R with a fine explicit scheme and compare, for the
        // cylinder and for the isotropic body the settle moves (axial inertia raised to the
        // transverse one: its own arithmetic, without the spin about the axis). Over the
        // 1.2 rad the isotropic body turns, the bound 1e-7 rad is the one of the cylinder.
        let cylinder = Segment::cylinder(0.05, 0.01, 1000.0);
        let isotropic = Segment {
            axial_inertia: cylinder.transverse_inertia,
            ..cylinder
        };
        for s in [cylinder, isotropic] {
            let q0 = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.4, 0.2));
            let h = Vector3::new(1e-5, 3e-6, -2e-5);
            let t = 0.2;
            let exact = s.free_rotation(&q0, &h, t);
            let n = 200_000;
            let dt = t / n as f64;
            let mut q = q0;
            for _ in 0..n {
                let w = s.angular_velocity(&Pose::new(Vector3::zeros(), q), &h);
                let half = UnitQuaternion::from_scaled_axis(w * (0.5 * dt));
                let w2 = s.angular_velocity(&Pose::new(Vector3::zeros(), half * q), &h);
                q = UnitQuaternion::from_scaled_axis(w2 * dt) * q;
            }
            assert!(exact.angle_to(&q) < 1e-7, "angle {}", exact.angle_to(&q));
            // Energy is a constant of the free motion.
            let e0 = s.rotational_energy(&Pose::new(Vector3::zeros(), q0), &h);
            let e1 = s.rotational_energy(&Pose::new(Vector3::zeros(), exact), &h);
            assert_relative_eq!(e0, e1, max_relative = 1e-12);
        }
    }
}
