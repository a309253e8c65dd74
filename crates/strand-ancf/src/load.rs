//! Generalized force of a uniform distributed load (eq. (45)).
//!
//! For a load `f` per unit length (N/m, e.g. `mu g` for gravity), the virtual work
//! `integral of f . delta r dx = Q . delta q` gives `Q = integral of S^T f dx = h (x) f` with
//! the Hermite load row
//!
//! ```text
//! h = (l/2, l^2/12, l/2, -l^2/12).
//! ```

use nalgebra::{Vector2, Vector3};

use crate::planar::PlanarVector;
use crate::spatial::SpatialVector;

/// `integral of S_k dx` over an element of length `l`.
pub fn hermite_load(l: f64) -> [f64; 4] {
    let m = l * l / 12.0;
    [0.5 * l, m, 0.5 * l, -m]
}

/// Generalized force (8) of the uniform load `f` (N/m) on a planar element of length `l`.
pub fn planar_uniform_load(f: &Vector2<f64>, l: f64) -> PlanarVector {
    let h = hermite_load(l);
    PlanarVector::from_fn(|i, _| h[i / 2] * f[i % 2])
}

/// Generalized force (12) of the uniform load `f` (N/m) on a spatial element of length `l`,
/// eq. (45).
pub fn spatial_uniform_load(f: &Vector3<f64>, l: f64) -> SpatialVector {
    let h = hermite_load(l);
    SpatialVector::from_fn(|i, _| h[i / 3] * f[i % 3])
}

/// Generalized gravity force (12): `spatial_uniform_load(mu g, l)` for mass per length `mu`
/// (kg/m) and gravity `g` (m/s^2), eq. (45).
pub fn spatial_gravity(mu: f64, g: &Vector3<f64>, l: f64) -> SpatialVector {
    spatial_uniform_load(&(g * mu), l)
}

/// Generalized gravity force (8) of a planar element.
pub fn planar_gravity(mu: f64, g: &Vector2<f64>, l: f64) -> PlanarVector {
    planar_uniform_load(&(g * mu), l)
}
