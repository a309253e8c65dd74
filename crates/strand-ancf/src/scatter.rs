//! Maps derivatives with respect to the local kinematic variables `y = (r', r'')` (2 D
//! values, D = 2 or 3) to derivatives with respect to the element coordinates `q` (4 D
//! values), using `r' = sum_k S_k' q_k` and `r'' = sum_k S_k'' q_k`:
//!
//! ```text
//! df/dq_k           = S_k' df/dr' + S_k'' df/dr''                         (D-vector)
//! d2f/dq_k dq_m     = S_k' S_m' f_aa + S_k' S_m'' f_ab + S_k'' S_m' f_ba + S_k'' S_m'' f_bb
//! ```
//!
//! with `a = r'`, `b = r''` (D x D blocks). Slices are nalgebra's column-major storage.

use nalgebra::SMatrix;

use crate::shape::ShapeRow;

/// `out += w * dq(g)`: `g` holds `(df/dr', df/dr'')` (2 D values), `out` 4 D values.
#[inline]
pub(crate) fn add_gradient<const D: usize>(out: &mut [f64], w: f64, row: &ShapeRow, g: &[f64]) {
    debug_assert_eq!(g.len(), 2 * D);
    debug_assert_eq!(out.len(), 4 * D);
    for k in 0..4 {
        let c1 = w * row.ds[k];
        let c2 = w * row.dds[k];
        for i in 0..D {
            out[k * D + i] += c1 * g[i] + c2 * g[D + i];
        }
    }
}

/// `out += w * dq dq(h)`: `h` is the `2D x 2D` matrix of second derivatives with respect to
/// `(r', r'')` (rows: first variable), `out` the `4D x 4D` element matrix (`NL = 2 D`,
/// `NE = 4 D`). No symmetry is assumed. Two stages: `T = H B` (the local matrix times the
/// shape rows), then `out += B^T T`, with `B` the 2 x 4 rows `(S', S'')` (Kronecker with I).
#[inline]
pub(crate) fn add_hessian<const D: usize, const NL: usize, const NE: usize>(
    out: &mut SMatrix<f64, NE, NE>,
    w: f64,
    row: &ShapeRow,
    h: &SMatrix<f64, NL, NL>,
) {
    debug_assert!(NL == 2 * D && NE == 4 * D);
    // t[(r, m * D + j)] = sum_beta h[(r, beta * D + j)] * B[beta][m] (weight included).
    let mut t = SMatrix::<f64, NL, NE>::zeros();
    for m in 0..4 {
        let (am, bm) = (w * row.ds[m], w * row.dds[m]);
        for j in 0..D {
            for r in 0..NL {
                t[(r, m * D + j)] = h[(r, j)] * am + h[(r, D + j)] * bm;
            }
        }
    }
    // out[(k * D + i, c)] += sum_alpha B[alpha][k] t[(alpha * D + i, c)].
    for c in 0..NE {
        for k in 0..4 {
            let (ak, bk) = (row.ds[k], row.dds[k]);
            for i in 0..D {
                out[(k * D + i, c)] += ak * t[(i, c)] + bk * t[(D + i, c)];
            }
        }
    }
}

/// `sum_k c_k q_k` for the four nodal D-blocks of `q` (4 D values).
#[inline]
pub(crate) fn combine<const D: usize>(c: &[f64; 4], q: &[f64]) -> [f64; D] {
    debug_assert_eq!(q.len(), 4 * D);
    let mut v = [0.0; D];
    for k in 0..4 {
        for i in 0..D {
            v[i] += c[k] * q[k * D + i];
        }
    }
    v
}
