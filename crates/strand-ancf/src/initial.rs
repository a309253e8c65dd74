//! Initial conditions of a dynamic run: coordinates, velocities and the per-point state.

use nalgebra::Vector3;

use crate::beam::{Beam, BeamError, ElementKind};

/// Where a dynamic run starts.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialState {
    /// Coordinates, all of them.
    pub q: Vec<f64>,
    /// Velocities, all of them. Coordinates held by a fixed support are at rest; those of a
    /// moving support take their table's velocity at the first step (see `beam::supports`).
    pub v: Vec<f64>,
    /// Per-point state ([`Beam::initial_state`] for a straight start).
    pub state: Vec<f64>,
    /// Largest velocity component (m/s; 1/s for slopes) the rigid field gave a coordinate that
    /// a fixed support holds at rest: non-zero when the field and the supports disagree.
    pub discarded: f64,
}

impl InitialState {
    /// The straight reference configuration at rest.
    pub fn rest(beam: &Beam) -> InitialState {
        InitialState {
            q: beam.reference().to_vec(),
            v: vec![0.0; beam.coords()],
            state: beam.initial_state(),
            discarded: 0.0,
        }
    }

    /// The straight reference configuration moving rigidly: velocity `velocity + w x r` (m/s)
    /// at every point `r`, with `w = angular_velocity` (rad/s) about the origin, so the slope
    /// `r'` turns at `w x r'`. A planar beam needs a velocity in the XY plane and a rotation
    /// about Z.
    pub fn rigid(
        beam: &Beam,
        velocity: [f64; 3],
        angular_velocity: [f64; 3],
    ) -> Result<InitialState, BeamError> {
        let nd = beam.node_coords();
        let dim = nd / 2;
        let (v0, w) = (Vector3::from(velocity), Vector3::from(angular_velocity));
        if beam.spec().element == ElementKind::Planar && (v0.z != 0.0 || w.x != 0.0 || w.y != 0.0) {
            return Err(BeamError::Setup(
                "a planar beam moves in the XY plane: its initial velocity needs vz = 0 and its \
                 rotation the axis Z"
                    .into(),
            ));
        }
        let mut s = InitialState::rest(beam);
        let vec3 = |x: &[f64]| {
            let mut r = Vector3::zeros();
            r.as_mut_slice()[..dim].copy_from_slice(&x[..dim]);
            r
        };
        for node in s.q.chunks_exact(nd).zip(s.v.chunks_exact_mut(nd)) {
            let (q, v) = node;
            let (r, dr) = (vec3(&q[..dim]), vec3(&q[dim..]));
            let vr = v0 + w.cross(&r);
            let vd = w.cross(&dr);
            v[..dim].copy_from_slice(&vr.as_slice()[..dim]);
            v[dim..].copy_from_slice(&vd.as_slice()[..dim]);
        }
        // Coordinates a fixed support holds stay at rest.
        for (g, v) in s.v.iter_mut().enumerate() {
            let moving = (0..beam.moving_coords()).any(|k| beam.moving_coordinate(k) == g);
            if beam.free_index(g).is_none() && !moving {
                s.discarded = s.discarded.max(v.abs());
                *v = 0.0;
            }
        }
        Ok(s)
    }
}
