//! The model's tangent as a block-sparse matrix, factored by sparse LU with its pattern
//! analysed once.
//!
//! Every coupling of two segments (a joint, an anchor, a tie, a contact) fills one 6 x 6 block
//! per ordered pair; the pattern is the set of those blocks plus the diagonal, stored column
//! by column (CSC) so that an element block scatters into precomputed slots. The fill-reducing
//! ordering and the symbolic LU are computed when the pattern is built; each Newton iteration
//! then redoes only the numeric factorization. A contact may pair with a neighbouring core
//! segment as the wires slide: the pattern then grows by the new blocks (with a new
//! analysis), and keeps them.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::PartialPivLuParams;
use faer::sparse::linalg::LuError;
use faer::sparse::linalg::lu::{
    LuRef, LuSymbolicParams, NumericLu, SymbolicLu, factorize_symbolic_lu,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Spec};
use nalgebra::SMatrix;

use crate::model::{FineModel, ModelState};
use crate::tangent::ElementTangent;

/// Failure to factor the tangent.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("sparse LU of the tangent failed: {0}")]
pub struct FactorError(pub String);

/// Block-sparse tangent with its symbolic and numeric LU.
pub struct SparseTangent {
    /// Number of segments (6 unknowns each).
    segments: usize,
    /// Row blocks (segments) of each column block, sorted.
    rows: Vec<Vec<usize>>,
    /// First value of each column block.
    block_start: Vec<usize>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factor_mem: MemBuffer,
    solve_mem: MemBuffer,
    factored: bool,
    /// Symbolic analyses done (1 unless the pattern grew).
    pub analyses: usize,
}

impl std::fmt::Debug for SparseTangent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseTangent")
            .field("segments", &self.segments)
            .field("nonzeros", &self.values.len())
            .field("analyses", &self.analyses)
            .finish()
    }
}

impl SparseTangent {
    /// Pattern of `model` at `state`: the diagonal, every joint, anchor and tie, and every
    /// contact point's wire segment with the core segment it is paired with (in the
    /// committed histories of `state`).
    pub fn new(model: &FineModel, state: &ModelState) -> Self {
        let n = model.segment_count();
        let mut pairs: Vec<(usize, usize)> = (0..n).map(|s| (s, s)).collect();
        let offsets = model.segment_offsets();
        for (w, off) in model.wires.iter().zip(&offsets) {
            for k in 0..w.chain.joints.len() {
                pairs.push((off + k, off + k + 1));
            }
        }
        for t in &model.ties {
            pairs.push((t.core_segment, offsets[t.wire] + t.segment));
        }
        let core_len = model.wires[0].chain.len();
        for ((w, hist), off) in model.wires.iter().zip(&state.contacts).zip(&offsets) {
            for (cp, h) in w.contacts.iter().zip(hist) {
                pairs.push((off + cp.segment, h.core_segment.min(core_len - 1)));
            }
        }
        let mut rows = vec![Vec::new(); n];
        for (a, b) in pairs {
            rows[b].push(a);
            rows[a].push(b);
        }
        Self::with_rows(n, rows)
    }

    fn with_rows(n: usize, mut rows: Vec<Vec<usize>>) -> Self {
        for r in &mut rows {
            r.sort_unstable();
            r.dedup();
        }
        let mut block_start = Vec::with_capacity(n + 1);
        let mut col_ptr = Vec::with_capacity(6 * n + 1);
        let mut row_idx = Vec::new();
        let mut at = 0;
        for r in &rows {
            block_start.push(at);
            for _ in 0..6 {
                col_ptr.push(row_idx.len());
                for &rb in r {
                    row_idx.extend(6 * rb..6 * rb + 6);
                }
            }
            at += 36 * r.len();
        }
        block_start.push(at);
        col_ptr.push(row_idx.len());
        let nnz = row_idx.len();
        let pattern = SymbolicSparseColMatRef::new_checked(6 * n, 6 * n, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_lu(pattern, LuSymbolicParams::default())
            .expect("symbolic LU of a valid pattern");
        let factor_mem = MemBuffer::new(symbolic.factorize_numeric_lu_scratch::<f64>(
            Par::Seq,
            Spec::<PartialPivLuParams, f64>::default(),
        ));
        let solve_mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        Self {
            segments: n,
            rows,
            block_start,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
            symbolic,
            numeric: NumericLu::new(),
            factor_mem,
            solve_mem,
            factored: false,
            analyses: 1,
        }
    }

    /// Number of unknowns (6 per segment).
    pub fn dimension(&self) -> usize {
        6 * self.segments
    }

    /// Stored values (the pattern's nonzeros).
    pub fn nonzeros(&self) -> usize {
        self.values.len()
    }

    /// Index of the first value of block (row segment `r`, column segment `c`), if stored.
    fn slot(&self, r: usize, c: usize) -> Option<usize> {
        let rows = &self.rows[c];
        rows.binary_search(&r)
            .ok()
            .map(|p| self.block_start[c] + 6 * p)
    }

    /// Adds `k` (6 x 6) to block (`r`, `c`); the slot of entry (i, j) is
    /// `base + j * 6 len(rows[c]) + i`.
    fn add_block(&mut self, r: usize, c: usize, k: impl Fn(usize, usize) -> f64) -> bool {
        let Some(base) = self.slot(r, c) else {
            return false;
        };
        let stride = 6 * self.rows[c].len();
        for j in 0..6 {
            let col = &mut self.values[base + j * stride..base + j * stride + 6];
            for (i, v) in col.iter_mut().enumerate() {
                *v += k(i, j);
            }
        }
        true
    }

    /// Assembles the element tangents `elements` plus the diagonal blocks `diagonal(s)` of
    /// every segment `s` (e.g. a mass term); grows the pattern (and analyses it again) if an
    /// element couples segments it does not hold.
    pub fn assemble(
        &mut self,
        elements: &[ElementTangent],
        diagonal: impl Fn(usize) -> SMatrix<f64, 6, 6>,
    ) {
        self.factored = false;
        loop {
            self.values.fill(0.0);
            let mut missing = Vec::new();
            for e in elements {
                for (bi, si) in e.segments.iter().enumerate() {
                    let Some(si) = *si else { continue };
                    for (bj, sj) in e.segments.iter().enumerate() {
                        let Some(sj) = *sj else { continue };
                        let ok =
                            self.add_block(si, sj, |i, j| e.stiffness[(6 * bi + i, 6 * bj + j)]);
                        if !ok {
                            missing.push((si, sj));
                        }
                    }
                }
            }
            if missing.is_empty() {
                break;
            }
            let mut rows = std::mem::take(&mut self.rows);
            for (a, b) in missing {
                rows[b].push(a);
                rows[a].push(b);
            }
            let analyses = self.analyses + 1;
            *self = Self::with_rows(self.segments, rows);
            self.analyses = analyses;
        }
        for s in 0..self.segments {
            let d = diagonal(s);
            self.add_block(s, s, |i, j| d[(i, j)]);
        }
    }

    /// Numeric LU of the assembled values.
    pub fn factor(&mut self) -> Result<(), FactorError> {
        let n = 6 * self.segments;
        let pattern =
            SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx);
        let mat = SparseColMatRef::new(pattern, &self.values);
        let stack = MemStack::new(&mut self.factor_mem);
        self.symbolic
            .factorize_numeric_lu(&mut self.numeric, mat, Par::Seq, stack, Default::default())
            .map_err(|e: LuError| FactorError(format!("{e:?}")))?;
        self.factored = true;
        Ok(())
    }

    /// Solves `K x = rhs` in place with the last factorization.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        assert!(self.factored, "solve before factor");
        let n = rhs.len();
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let stack = MemStack::new(&mut self.solve_mem);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            Par::Seq,
            stack,
        );
    }

    /// `y = K^T x` with the assembled values.
    pub fn multiply_transpose(&self, x: &[f64], y: &mut [f64]) {
        for (c, yc) in y.iter_mut().enumerate() {
            let mut s = 0.0;
            for p in self.col_ptr[c]..self.col_ptr[c + 1] {
                s += self.values[p] * x[self.row_idx[p]];
            }
            *yc = s;
        }
    }

    /// `y = K x` with the assembled values (for tests and residual checks).
    pub fn multiply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for (c, xc) in x.iter().enumerate() {
            for p in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[p]] += self.values[p] * xc;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::tests::table1;
    use crate::contact::ContactOptions;
    use crate::model::{Discretisation, Support};
    use nalgebra::{DMatrix, DVector};

    /// A Table 1 strand with contacts, bent a little so that the tangent is not symmetric.
    fn bent() -> (FineModel, ModelState) {
        let s = table1();
        let mut m = FineModel::from_strand(
            &s,
            Discretisation {
                core_segments: 8,
                wire_segments: 8,
            },
            Support::Clamped,
            Support::Free,
        );
        m.add_contacts(&s, &ContactOptions::default());
        let mut state = m.rest_state();
        for w in &mut state.wires {
            for p in &mut w.poses {
                p.position.y -= 1e-3 * p.position.x * p.position.x;
            }
        }
        (m, state)
    }

    /// A diagonal block that is not symmetric.
    fn block(shift: f64) -> SMatrix<f64, 6, 6> {
        let mut b = SMatrix::<f64, 6, 6>::identity() * shift;
        b[(0, 4)] = 0.3 * shift;
        b[(5, 1)] = -0.2 * shift;
        b
    }

    fn dense(model: &FineModel, elements: &[ElementTangent], shift: f64) -> DMatrix<f64> {
        let n = 6 * model.segment_count();
        let mut k = DMatrix::<f64>::zeros(n, n);
        for s in 0..model.segment_count() {
            k.view_mut((6 * s, 6 * s), (6, 6)).copy_from(&block(shift));
        }
        for e in elements {
            e.add_to_dense(&mut k);
        }
        k
    }

    #[test]
    fn assembles_and_solves_like_the_dense_matrix() {
        let (m, state) = bent();
        let elements = m.element_tangents(&state);
        let shift = 10.0;
        let mut k = SparseTangent::new(&m, &state);
        k.assemble(&elements, |_| block(shift));
        let d = dense(&m, &elements, shift);
        let n = k.dimension();
        let x: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
        let (mut y, mut yt) = (vec![0.0; n], vec![0.0; n]);
        k.multiply(&x, &mut y);
        k.multiply_transpose(&x, &mut yt);
        let xv = DVector::from_column_slice(&x);
        let (yd, ytd) = (&d * &xv, d.transpose() * &xv);
        let scale = yd.amax();
        for i in 0..n {
            assert!((y[i] - yd[i]).abs() <= 1e-12 * scale);
            assert!((yt[i] - ytd[i]).abs() <= 1e-12 * scale);
        }
        k.factor().unwrap();
        let mut sol = yd.as_slice().to_vec();
        k.solve_in_place(&mut sol);
        let err = sol
            .iter()
            .zip(&x)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        println!("solve error {err:.2e}, {} nonzeros", k.nonzeros());
        assert!(err < 1e-8, "solve error {err:e}");
    }

    #[test]
    fn pattern_grows_to_a_new_contact_pairing() {
        let (m, state) = bent();
        // A pattern built with every contact paired with the first core segment.
        let mut first = state.clone();
        for h in first.contacts.iter_mut().flatten() {
            h.core_segment = 0;
        }
        let mut k = SparseTangent::new(&m, &first);
        let elements = m.element_tangents(&state);
        k.assemble(&elements, |_| block(1.0));
        assert_eq!(k.analyses, 2);
        let d = dense(&m, &elements, 1.0);
        let n = k.dimension();
        let x: Vec<f64> = (0..n).map(|i| (i % 7) as f64).collect();
        let mut y = vec![0.0; n];
        k.multiply(&x, &mut y);
        let yd = &d * DVector::from_column_slice(&x);
        for i in 0..n {
            assert!((y[i] - yd[i]).abs() <= 1e-12 * yd.amax());
        }
    }
}
