//! Constant consistent mass matrix of the cable element (eq. (44)).
//!
//! `M = integral over [0, l] of mu S^T S dx` with `mu` the mass per unit length (for the
//! strand `rho_c A_c + m rho_w A_w / cos(alpha)`, eq. (44), SPEC 1). Because
//! `S = [S_1 I, ..., S_4 I]`, `M = mu m (x) I` with the scalar Hermite matrix
//!
//! ```text
//!               [ 156     22 l     54    -13 l  ]
//! m = l / 420   [ 22 l    4 l^2    13 l  -3 l^2 ]
//!               [ 54      13 l     156   -22 l  ]
//!               [ -13 l   -3 l^2  -22 l   4 l^2 ]
//! ```

use nalgebra::{Matrix4, SMatrix};

use crate::planar::PlanarMatrix;
use crate::spatial::SpatialMatrix;

/// Scalar Hermite mass matrix `m_ij = integral of S_i S_j dx` over an element of length `l`
/// (m; multiply by `mu` for kg).
pub fn hermite_mass(l: f64) -> Matrix4<f64> {
    let l2 = l * l;
    #[rustfmt::skip]
    let m = Matrix4::new(
        156.0,       22.0 * l,   54.0,       -13.0 * l,
        22.0 * l,    4.0 * l2,   13.0 * l,   -3.0 * l2,
        54.0,        13.0 * l,   156.0,      -22.0 * l,
        -13.0 * l,   -3.0 * l2,  -22.0 * l,  4.0 * l2,
    );
    m * (l / 420.0)
}

/// `mu m (x) I_D`.
fn kron<const N: usize, const D: usize>(mu: f64, l: f64) -> SMatrix<f64, N, N> {
    debug_assert_eq!(N, 4 * D);
    let m = hermite_mass(l) * mu;
    let mut out = SMatrix::<f64, N, N>::zeros();
    for j in 0..4 {
        for i in 0..4 {
            for d in 0..D {
                out[(i * D + d, j * D + d)] = m[(i, j)];
            }
        }
    }
    out
}

/// Mass matrix (8x8) of the planar element, mass per length `mu` (kg/m), length `l` (m).
pub fn planar_mass(mu: f64, l: f64) -> PlanarMatrix {
    kron::<8, 2>(mu, l)
}

/// Mass matrix (12x12) of the spatial element, mass per length `mu` (kg/m), length `l` (m),
/// eq. (44).
pub fn spatial_mass(mu: f64, l: f64) -> SpatialMatrix {
    kron::<12, 3>(mu, l)
}
