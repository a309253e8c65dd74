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

use crate::band::BandMatrix;
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

/// The assembled mass matrix of a beam's free coordinates as `M = M_s (x) I_D`: a scalar band
/// `M_s` (half-bandwidth 3) over the free position and slope vectors, each of `D = 2` or 3
/// components. Supports fix whole vectors, so the free matrix keeps the Kronecker form of the
/// element's (eq. (44)), and `M x` costs a third of the band product's multiplications.
#[derive(Debug, Clone, PartialEq)]
pub struct VectorMass {
    /// `M_s` by rows: row `a` holds columns `a - 3 ..= a + 3` at offsets `0..7`.
    rows: Vec<[f64; 7]>,
    dim: usize,
}

impl VectorMass {
    /// The Kronecker form of the assembled free mass matrix `m` of vectors of `dim`
    /// components: `M_s` is read from the first component of each vector.
    pub fn from_band(m: &BandMatrix, dim: usize) -> Self {
        let n = m.n() / dim;
        let rows = (0..n)
            .map(|a| {
                std::array::from_fn(|o| match (a + o).checked_sub(3) {
                    Some(b) if b < n => m.get(dim * a, dim * b),
                    _ => 0.0,
                })
            })
            .collect();
        VectorMass { rows, dim }
    }

    /// Number of free coordinates.
    pub fn n(&self) -> usize {
        self.rows.len() * self.dim
    }

    /// `y = M x`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        match self.dim {
            2 => self.mul_fixed::<2>(x, y),
            _ => self.mul_fixed::<3>(x, y),
        }
    }

    fn mul_fixed<const D: usize>(&self, x: &[f64], y: &mut [f64]) {
        let n = self.rows.len();
        let xs: &[[f64; D]] = x.as_chunks::<D>().0;
        let ys: &mut [[f64; D]] = y.as_chunks_mut::<D>().0;
        for (a, (row, ya)) in self.rows.iter().zip(ys.iter_mut()).enumerate() {
            let mut s = [0.0; D];
            if a >= 3 && a + 3 < n {
                for (m, xb) in row.iter().zip(&xs[a - 3..=a + 3]) {
                    for c in 0..D {
                        s[c] += m * xb[c];
                    }
                }
            } else {
                for b in a.saturating_sub(3)..=(a + 3).min(n - 1) {
                    for c in 0..D {
                        s[c] += row[b + 3 - a] * xs[b][c];
                    }
                }
            }
            *ya = s;
        }
    }
}
