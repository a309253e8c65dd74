//! The constant consistent mass matrix (eq. (44)) of the free coordinates, and its entries
//! that couple any coordinate to one a moving support holds.

use nalgebra::DMatrix;

use super::{BeamSpec, ElementKind};
use crate::band::BandMatrix;
use crate::mass::{planar_mass, spatial_mass};

/// Mass matrix of the free coordinates (band), assembled from the element matrices.
pub(super) fn free_mass(
    spec: &BeamSpec,
    nd: usize,
    l: f64,
    free_index: &[Option<usize>],
    n_free: usize,
) -> BandMatrix {
    let band = 2 * nd - 1;
    let mut mass = BandMatrix::zeros(n_free, band, band);
    let me = element_mass(spec.element, spec.mass_per_length, l);
    for e in 0..spec.elements {
        for a in 0..2 * nd {
            let Some(ia) = free_index[e * nd + a] else {
                continue;
            };
            for b in 0..2 * nd {
                if let Some(ib) = free_index[e * nd + b] {
                    mass.add(ia, ib, me[(a, b)]);
                }
            }
        }
    }
    mass
}

/// Mass entries `(row, k, m)` of the columns that moving supports hold: `row` a global
/// coordinate, `k` the index into `moving` (see `supports::moving_coordinates`).
pub(super) fn held_mass(
    spec: &BeamSpec,
    nd: usize,
    l: f64,
    moving: &[(usize, usize, usize)],
) -> Vec<(usize, usize, f64)> {
    let mut out = Vec::new();
    if moving.is_empty() {
        return out;
    }
    let me = element_mass(spec.element, spec.mass_per_length, l);
    for e in 0..spec.elements {
        for b in 0..2 * nd {
            let Some(k) = moving.iter().position(|m| m.0 == e * nd + b) else {
                continue;
            };
            for a in 0..2 * nd {
                if me[(a, b)] != 0.0 {
                    out.push((e * nd + a, k, me[(a, b)]));
                }
            }
        }
    }
    out
}

/// Consistent mass matrix of one element of `kind` (eq. (44)).
pub(super) fn element_mass(kind: ElementKind, mu: f64, l: f64) -> DMatrix<f64> {
    match kind {
        ElementKind::Planar => DMatrix::from_column_slice(8, 8, planar_mass(mu, l).as_slice()),
        ElementKind::Spatial => DMatrix::from_column_slice(12, 12, spatial_mass(mu, l).as_slice()),
    }
}
