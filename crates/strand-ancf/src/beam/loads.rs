//! External loads: the generalized force of gravity (eq. (45)) and of constant point forces,
//! the beam's dead load (scaled by the load factor in statics).

use nalgebra::{Vector2, Vector3};

use super::{BeamError, BeamSpec, ElementKind};
use crate::load::{planar_gravity, spatial_gravity};
use crate::shape::shape;

/// A constant point force on the strand.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLoad {
    /// Material coordinate from the start (m), in [0, L].
    pub s: f64,
    /// Force (N); in the XY plane for planar elements.
    pub force: [f64; 3],
}

/// Generalized force of gravity and the point loads on all coordinates (N), `nd` coordinates
/// per node, elements of length `l`. A point force `F` at `s` adds `S(s)^T F` to the element
/// holding `s` (virtual work `F . delta r(s)`); its potential `-F . r(s)` is linear in the
/// coordinates like that of gravity.
pub(super) fn dead_load(spec: &BeamSpec, nd: usize, l: f64) -> Result<Vec<f64>, BeamError> {
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
    let n = spec.elements;
    let mut load = vec![0.0; (n + 1) * nd];
    for e in 0..n {
        for a in 0..2 * nd {
            load[e * nd + a] += fe[a];
        }
    }
    let dim = nd / 2;
    let length = l * n as f64;
    for (k, p) in spec.point_loads.iter().enumerate() {
        if !(p.s.is_finite() && (0.0..=length).contains(&p.s)) {
            return Err(BeamError::Setup(format!(
                "point load {k}: s = {} m is outside the strand [0, {length}] m",
                p.s
            )));
        }
        if !p.force.iter().all(|f| f.is_finite()) {
            return Err(BeamError::Setup(format!(
                "point load {k}: non-finite force"
            )));
        }
        if dim == 2 && p.force[2] != 0.0 {
            return Err(BeamError::Setup(format!(
                "point load {k}: a planar beam takes forces in the XY plane"
            )));
        }
        let e = ((p.s / l) as usize).min(n - 1);
        let row = shape(p.s - e as f64 * l, l);
        for (i, h) in row.iter().enumerate() {
            for c in 0..dim {
                load[e * nd + i * dim + c] += h * p.force[c];
            }
        }
    }
    Ok(load)
}
