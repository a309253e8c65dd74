//! One wire as a chain of rigid cylindrical segments laid along its undeformed centreline.
//!
//! The centreline is sampled at `n + 1` nodes; segment `k` is the chord from node `k` to node
//! `k + 1`, with its centre at the chord midpoint and body axis 1 along the chord. Joint `k`
//! joins the end of segment `k` to the start of segment `k + 1` (the shared node) with the
//! springs of the wire length between the two segment centres.

use std::f64::consts::PI;

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use strand_core::{HelixLayer, WireSpec};

use crate::joint::{JointSpring, JointStiffness};
use crate::segment::{Frame, Pose, Segment};

/// Elastic and inertial properties of a round wire's cross-section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WireSection {
    /// Wire radius r (m).
    pub radius: f64,
    /// Area A (m^2).
    pub area: f64,
    /// Second moment of area I (m^4).
    pub inertia: f64,
    /// Polar moment J = 2 I (m^4).
    pub polar_inertia: f64,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Shear modulus G (Pa).
    pub shear_modulus: f64,
    /// Timoshenko shear coefficient of a solid circle, 6 (1 + nu) / (7 + 6 nu) (-).
    pub shear_coefficient: f64,
    /// Density rho (kg/m^3).
    pub density: f64,
}

impl WireSection {
    /// Section of the wire `spec`.
    pub fn from_spec(spec: &WireSpec) -> Self {
        let nu = spec.material.poisson_ratio;
        Self {
            radius: spec.radius(),
            area: spec.area(),
            inertia: spec.inertia(),
            polar_inertia: spec.polar_inertia(),
            youngs_modulus: spec.material.youngs_modulus,
            shear_modulus: spec.material.shear_modulus(),
            shear_coefficient: 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu),
            density: spec.material.density,
        }
    }

    /// Joint springs for a wire piece of length `length` (m): axial E A / l, shear
    /// kappa G A / l, torsion G J / l, bending E I / l.
    pub fn joint_stiffness(&self, length: f64) -> JointStiffness {
        let ga = self.shear_coefficient * self.shear_modulus * self.area / length;
        let ei = self.youngs_modulus * self.inertia / length;
        JointStiffness {
            translational: Vector3::new(self.youngs_modulus * self.area / length, ga, ga),
            rotational: Vector3::new(self.shear_modulus * self.polar_inertia / length, ei, ei),
        }
    }
}

/// A wire as a chain of rigid segments with joint springs, at its rest configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// Cross-section of the wire.
    pub section: WireSection,
    /// Mass properties of each segment.
    pub segments: Vec<Segment>,
    /// Rest (undeformed) pose of each segment.
    pub rest: Vec<Pose>,
    /// Joint `k` joins segment `k` (body a) and segment `k + 1` (body b).
    pub joints: Vec<JointSpring>,
}

impl Chain {
    /// Chain through the centreline nodes `nodes` (m); `normal(k, t)` gives an approximate
    /// material normal for segment `k` with unit tangent `t` (it is made orthogonal to `t`).
    pub fn through_nodes(
        section: WireSection,
        nodes: &[Vector3<f64>],
        normal: impl Fn(usize, &Vector3<f64>) -> Vector3<f64>,
    ) -> Self {
        assert!(nodes.len() >= 2, "a chain needs at least one segment");
        let n = nodes.len() - 1;
        let mut segments = Vec::with_capacity(n);
        let mut rest = Vec::with_capacity(n);
        for k in 0..n {
            let chord = nodes[k + 1] - nodes[k];
            let l = chord.norm();
            let t = chord / l;
            let guess = normal(k, &t);
            let e2 = (guess - t * t.dot(&guess)).normalize();
            let e3 = t.cross(&e2);
            let rot = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[t, e2, e3]));
            segments.push(Segment::cylinder(l, section.radius, section.density));
            rest.push(Pose::new(
                0.5 * (nodes[k] + nodes[k + 1]),
                UnitQuaternion::from_rotation_matrix(&rot),
            ));
        }
        let joints = (0..n.saturating_sub(1))
            .map(|k| {
                let (a, b) = (&segments[k], &segments[k + 1]);
                let spacing = 0.5 * (a.length + b.length);
                JointSpring::at_rest(
                    &rest[k],
                    a.end_offset(),
                    &rest[k + 1],
                    b.start_offset(),
                    section.joint_stiffness(spacing),
                )
            })
            .collect();
        Self {
            section,
            segments,
            rest,
            joints,
        }
    }

    /// Straight wire from `origin` along +X of length `length` (m) in `n` segments; material
    /// normal +Y.
    pub fn straight(section: WireSection, origin: Vector3<f64>, length: f64, n: usize) -> Self {
        let nodes: Vec<_> = (0..=n)
            .map(|k| origin + Vector3::new(length * k as f64 / n as f64, 0.0, 0.0))
            .collect();
        Self::through_nodes(section, &nodes, |_, _| Vector3::y())
    }

    /// Helical wire `wire` (0-based) of `layer` over the strand length `length` (m) in `n`
    /// segments: r(x) = (x, R_w sin phi(x), R_w cos phi(x)) (SPEC 1 eq. (1)) with equal steps
    /// in x; material normal toward the strand axis.
    pub fn helix(layer: &HelixLayer, wire: usize, length: f64, n: usize) -> Self {
        let section = WireSection::from_spec(&layer.spec.wire);
        let r = layer.radius;
        let point = |x: f64| {
            let phi = layer.phase(wire, x);
            Vector3::new(x, r * phi.sin(), r * phi.cos())
        };
        let dx = length / n as f64;
        let nodes: Vec<_> = (0..=n).map(|k| point(k as f64 * dx)).collect();
        let mut chain = Self::through_nodes(section, &nodes, |k, _| {
            let phi = layer.phase(wire, (k as f64 + 0.5) * dx);
            -Vector3::new(0.0, phi.sin(), phi.cos())
        });
        // A chord is shorter than its helical arc (by (kappa l)^2 / 24, 0.3 % for the paper's
        // 77 segments): give each segment the mass of its arc so the wire keeps its mass.
        let arc = helix_length(r, layer.pitch, dx);
        for s in &mut chain.segments {
            *s = s.with_mass_scaled(arc / s.length);
        }
        chain
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.segments.len()
    }

    /// True when the chain has no segment.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// Total mass (kg).
    pub fn mass(&self) -> f64 {
        self.segments.iter().map(|s| s.mass).sum()
    }

    /// Centreline nodes (m) of the chain at poses `poses`: the start of segment 0, the
    /// midpoints of the joint gaps, and the end of the last segment.
    pub fn centreline(&self, poses: &[Pose]) -> Vec<Vector3<f64>> {
        let n = self.len();
        let mut out = Vec::with_capacity(n + 1);
        out.push(poses[0].point(&self.segments[0].start_offset()));
        for k in 0..n.saturating_sub(1) {
            let a = poses[k].point(&self.segments[k].end_offset());
            let b = poses[k + 1].point(&self.segments[k + 1].start_offset());
            out.push(0.5 * (a + b));
        }
        out.push(poses[n - 1].point(&self.segments[n - 1].end_offset()));
        out
    }

    /// Adds the joint loads at poses `poses` (with their frames `frames`) to `forces` and
    /// `torques` (world axes, N and N m) and returns the joints' elastic energy (J).
    pub fn add_joint_loads(
        &self,
        poses: &[Pose],
        frames: &[Frame],
        forces: &mut [Vector3<f64>],
        torques: &mut [Vector3<f64>],
    ) -> f64 {
        self.add_joint_loads_in(&SegmentRun::whole(poses, frames), forces, torques)
    }

    /// [`Chain::add_joint_loads`] on a run of segments only: the loads of every joint
    /// touching them (the joints at the run's ends included, evaluated with the neighbours
    /// outside it), added to `forces` and `torques` of the run's segments; returns the
    /// energy of the joints whose first segment is in the run (J). Each segment receives the
    /// same sums, in the same order, as from [`Chain::add_joint_loads`]: runs that cut the
    /// chain split its loads exactly.
    #[inline(always)]
    pub fn add_joint_loads_in(
        &self,
        run: &SegmentRun<'_>,
        forces: &mut [Vector3<f64>],
        torques: &mut [Vector3<f64>],
    ) -> f64 {
        let (a, n) = (run.first, run.poses.len());
        let (poses, frames) = (run.poses, run.frames);
        let mut energy = 0.0;
        if n == 0 {
            return energy;
        }
        if a > 0 {
            let (p, f) = run
                .before
                .expect("a run inside a chain has its neighbour before");
            let l = self.joints[a - 1].evaluate_in(p, f, &poses[0], &frames[0]);
            forces[0] += l.force_b;
            torques[0] += l.torque_b;
        }
        for (k, j) in self.joints[a..a + n - 1].iter().enumerate() {
            let l = j.evaluate_in(&poses[k], &frames[k], &poses[k + 1], &frames[k + 1]);
            forces[k] += l.force_a;
            torques[k] += l.torque_a;
            forces[k + 1] += l.force_b;
            torques[k + 1] += l.torque_b;
            energy += l.energy;
        }
        if a + n < self.len() {
            let (p, f) = run
                .after
                .expect("a run inside a chain has its neighbour after");
            let l = self.joints[a + n - 1].evaluate_in(&poses[n - 1], &frames[n - 1], p, f);
            forces[n - 1] += l.force_a;
            torques[n - 1] += l.torque_a;
            energy += l.energy;
        }
        energy
    }
}

/// The poses and frames of a run of a chain's segments `first..first + poses.len()`, and
/// the neighbours' on either side (for the joints at the run's ends; `None` at the chain's
/// ends).
#[derive(Debug, Clone, Copy)]
pub struct SegmentRun<'a> {
    /// The run's first segment.
    pub first: usize,
    /// The run's poses.
    pub poses: &'a [Pose],
    /// The run's frames.
    pub frames: &'a [Frame],
    /// Pose and frame of the segment before the run.
    pub before: Option<(&'a Pose, &'a Frame)>,
    /// Pose and frame of the segment after the run.
    pub after: Option<(&'a Pose, &'a Frame)>,
}

impl<'a> SegmentRun<'a> {
    /// The run of a whole chain at poses `poses` with frames `frames`.
    pub fn whole(poses: &'a [Pose], frames: &'a [Frame]) -> Self {
        Self {
            first: 0,
            poses,
            frames,
            before: None,
            after: None,
        }
    }
}

/// Length of a helix of radius `radius` and pitch `pitch` over the axial length `length` (m).
pub fn helix_length(radius: f64, pitch: f64, length: f64) -> f64 {
    length * (1.0 + (2.0 * PI * radius / pitch).powi(2)).sqrt()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use strand_core::{Strand, StrandSpec};

    pub(crate) fn table1() -> Strand {
        Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap()
    }

    #[test]
    fn helix_segments_follow_the_helix() {
        let s = table1();
        let layer = s.layers().first().unwrap();
        let c = Chain::helix(layer, 2, s.length(), 77);
        assert_eq!(c.len(), 77);
        // Chord length sum approaches the helix length from below (chords of an arc).
        let total: f64 = c.segments.iter().map(|g| g.length).sum();
        let exact = helix_length(layer.radius, layer.pitch, s.length());
        assert_relative_eq!(
            exact,
            s.length() / layer.lay_angle().cos(),
            max_relative = 1e-12
        );
        assert!(total < exact && total > exact * (1.0 - 5e-3));
        // Segment masses follow the arc length.
        let wire_mass = layer.spec.wire.material.density * layer.spec.wire.area() * exact;
        assert_relative_eq!(c.mass(), wire_mass, max_relative = 1e-12);
        // Frames are orthonormal; the normal points toward the strand axis.
        for p in &c.rest {
            let m = p.matrix();
            assert_relative_eq!(m.transpose() * m, Matrix3::identity(), epsilon = 1e-14);
            let radial = Vector3::new(0.0, p.position.y, p.position.z).normalize();
            assert!(m.column(1).dot(&radial) < -0.99);
            // Tangent at the lay angle to the strand axis.
            assert_relative_eq!(m[(0, 0)], layer.lay_angle().cos(), max_relative = 5e-3);
        }
        // Joints close: the centreline passes through the helix nodes.
        let nodes = c.centreline(&c.rest);
        for (k, p) in nodes.iter().enumerate() {
            let xk = s.length() * k as f64 / 77.0;
            let phi = layer.phase(2, xk);
            let exact = Vector3::new(xk, layer.radius * phi.sin(), layer.radius * phi.cos());
            assert!((p - exact).norm() < 1e-15);
        }
    }

    #[test]
    fn segment_mass_adds_to_wire_mass() {
        let s = table1();
        let core = Chain::straight(
            WireSection::from_spec(s.core()),
            Vector3::zeros(),
            s.length(),
            50,
        );
        let m = s.core().material.density * s.core().area() * s.length();
        assert_relative_eq!(core.mass(), m, max_relative = 1e-12);
        assert_eq!(core.joints.len(), 49);
    }
}
