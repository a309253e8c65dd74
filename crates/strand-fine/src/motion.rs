//! Imposed motion: moving supports and a rigid initial velocity field.
//!
//! A moving support translates the ground side of every anchor at its end (the rotation of a
//! clamp is kept); the anchors' springs then pull the strand along. The work the support does
//! on the strand over a step is minus the force the strand exerts on the ground through those
//! anchors times the ground's displacement (trapezoidal rule over the step; the anchors'
//! elastic energy is in the spring energy).

use nalgebra::Vector3;

use crate::model::{End, FineModel, ModelState};
use crate::segment::Pose;

impl FineModel {
    /// Whether anchor `segment` of a wire with `len` segments holds the end `end`.
    fn holds(segment: usize, len: usize, end: End) -> bool {
        match end {
            End::Start => segment == 0,
            End::End => segment + 1 == len,
        }
    }

    /// Moves the ground of every anchor at `end` to its rest place plus `displacement` (m).
    pub fn move_support(&mut self, end: End, displacement: Vector3<f64>) {
        for w in &mut self.wires {
            let c = &w.chain;
            let len = c.len();
            for a in &mut w.anchors {
                if !Self::holds(a.segment, len, end) {
                    continue;
                }
                let seg = c.segments[a.segment];
                let offset = match end {
                    End::Start => seg.start_offset(),
                    End::End => seg.end_offset(),
                };
                let rest = c.rest[a.segment];
                a.ground = Pose::new(rest.point(&offset) + displacement, rest.rotation);
            }
        }
    }

    /// Force (N) the strand at `state` exerts on the ground through the anchors at `end`.
    pub fn support_force(&self, state: &ModelState, end: End) -> Vector3<f64> {
        let mut f = Vector3::zeros();
        for (w, s) in self.wires.iter().zip(&state.wires) {
            let len = w.chain.len();
            for a in &w.anchors {
                if Self::holds(a.segment, len, end) {
                    f += a.joint.evaluate(&a.ground, &s.poses[a.segment]).force_a;
                }
            }
        }
        f
    }

    /// Gives every segment of `state` the rigid velocity field `velocity + w x r` (m/s) of a
    /// rotation at `angular_velocity` `w` (rad/s) about the origin: centre velocities and the
    /// angular momenta `I w` of the segments about their centres.
    pub fn set_rigid_velocity(
        &self,
        state: &mut ModelState,
        velocity: Vector3<f64>,
        angular_velocity: Vector3<f64>,
    ) {
        for (w, s) in self.wires.iter().zip(&mut state.wires) {
            for (k, seg) in w.chain.segments.iter().enumerate() {
                let p = &s.poses[k];
                s.velocities[k] = velocity + angular_velocity.cross(&p.position);
                s.angular_momenta[k] = seg.angular_momentum(p, &angular_velocity);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::tests::table1;
    use crate::model::{Discretisation, Support};

    /// A strand turning rigidly about a pin at the origin has the kinetic energy of a rigid
    /// body, `1/2 w^T I_O w`, and moving a support moves its anchors' ground only.
    #[test]
    fn rigid_rotation_has_the_rigid_kinetic_energy_and_supports_move() {
        let s = table1();
        let mut m = FineModel::from_strand(
            &s,
            Discretisation {
                core_segments: 20,
                wire_segments: 20,
            },
            Support::Pinned,
            Support::Free,
        );
        let mut state = m.rest_state();
        let w = Vector3::new(0.3, -1.2, 0.7);
        m.set_rigid_velocity(&mut state, Vector3::zeros(), w);
        let mut loads = m.load_buffers();
        let e = m.energies(&state, &mut loads);
        // Inertia about the origin of every segment: I_c + m (|r|^2 I - r r^T).
        let mut expect = 0.0;
        for (wire, ws) in m.wires.iter().zip(&state.wires) {
            for (k, seg) in wire.chain.segments.iter().enumerate() {
                let r = ws.poses[k].position;
                let h = seg.angular_momentum(&ws.poses[k], &w);
                expect += 0.5 * w.dot(&h)
                    + 0.5 * seg.mass * (r.norm_squared() * w.norm_squared() - r.dot(&w).powi(2));
            }
        }
        let total = e.kinetic_translation + e.kinetic_rotation;
        assert!((total - expect).abs() < 1e-12 * expect, "{total} {expect}");
        // Rotational energy from the angular momentum agrees with 1/2 w . I w.
        let rot: f64 = m
            .wires
            .iter()
            .zip(&state.wires)
            .flat_map(|(wire, ws)| {
                wire.chain
                    .segments
                    .iter()
                    .enumerate()
                    .map(move |(k, seg)| 0.5 * w.dot(&seg.angular_momentum(&ws.poses[k], &w)))
            })
            .sum();
        assert!((rot - e.kinetic_rotation).abs() < 1e-12 * rot);
        // The pin's anchor is at rest: no force; moved, it pulls the strand along.
        assert!(m.support_force(&state, End::Start).norm() < 1e-12);
        m.move_support(End::Start, Vector3::new(0.0, 1e-6, 0.0));
        let f = m.support_force(&state, End::Start);
        assert!(f.y < 0.0 && f.x.abs() < 1e-9 * f.y.abs(), "{f:?}");
        assert_eq!(m.support_force(&state, End::End), Vector3::zeros());
    }
}
