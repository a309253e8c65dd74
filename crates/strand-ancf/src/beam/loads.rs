//! External loads: the generalized force of gravity (eq. (45)).

use nalgebra::{Vector2, Vector3};

use super::{BeamSpec, ElementKind};
use crate::load::{planar_gravity, spatial_gravity};

/// Generalized gravity force on all coordinates (N), `nd` coordinates per node, elements of
/// length `l`.
pub(super) fn gravity_force(spec: &BeamSpec, nd: usize, l: f64) -> Vec<f64> {
    let fe: Vec<f64> = match spec.element {
        ElementKind::Planar => {
            let g = Vector2::new(spec.gravity[0], spec.gravity[1]);
            planar_gravity(spec.mass_per_length, &g, l)
                .as_slice()
                .to_vec()
        }
        ElementKind::Spatial => {
            let g = Vector3::from(spec.gravity);
            spatial_gravity(spec.mass_per_length, &g, l)
                .as_slice()
                .to_vec()
        }
    };
    let mut gravity_force = vec![0.0; (spec.elements + 1) * nd];
    for e in 0..spec.elements {
        for a in 0..2 * nd {
            gravity_force[e * nd + a] += fe[a];
        }
    }
    gravity_force
}
