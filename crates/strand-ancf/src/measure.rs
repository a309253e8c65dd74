//! Length measures of vectors of free coordinates, for the solvers' step sizes and
//! convergence tests: a position coordinate is a length (m); a slope coordinate is
//! dimensionless, and is measured by the displacement it makes across an element (times the
//! element length), so that a correction of the slopes near a free end counts as much as the
//! positions it moves, not as if a slope of 1e-8 were a displacement of 1e-8 m.
//!
//! With the spatial element a node's position or slope change is measured by its Euclidean
//! length, which a rotation of the axes leaves unchanged, so that a solver stopping on these
//! measures takes the same decisions for a scene and its rotation (supports hold whole
//! position or slope vectors, so the free coordinates are a sequence of whole 3-vectors). The
//! planar element, whose plane is fixed, measures each coordinate on its own.

use crate::beam::{Beam, ElementKind};

/// The length scales of a beam's free coordinates and how they group into vectors.
#[derive(Debug, Clone)]
pub(crate) struct Lengths {
    /// Length scale of each free coordinate: 1 for a position, the element length for a slope.
    scale: Vec<f64>,
    /// Coordinates measured together: 3 (a position or slope vector) for the spatial
    /// element, 1 for the planar one.
    vector: usize,
}

impl Lengths {
    /// The measures of `beam`'s free coordinates.
    pub(crate) fn of(beam: &Beam) -> Lengths {
        let nd = beam.node_coords();
        let mut scale = vec![0.0; beam.dofs()];
        for g in 0..beam.coords() {
            if let Some(i) = beam.free_index(g) {
                scale[i] = if g % nd < nd / 2 {
                    1.0
                } else {
                    beam.element_length()
                };
            }
        }
        let vector = match beam.spec().element {
            ElementKind::Planar => 1,
            ElementKind::Spatial => 3,
        };
        Lengths { scale, vector }
    }

    /// The largest displacement a change `dq` of the free coordinates makes (m).
    pub(crate) fn displacement(&self, dq: &[f64]) -> f64 {
        let v = self.vector;
        dq.chunks_exact(v)
            .zip(self.scale.chunks_exact(v))
            .fold(0.0f64, |a, (d, s)| a.max(norm(d) * s[0]))
    }

    /// The largest node force of a vector `r` of generalized forces of the free coordinates
    /// (N): a position's force as it is, a slope's moment (N m) over the element length, the
    /// force conjugate to the displacement [`Self::displacement`] measures.
    pub(crate) fn force(&self, r: &[f64]) -> f64 {
        let v = self.vector;
        r.chunks_exact(v)
            .zip(self.scale.chunks_exact(v))
            .fold(0.0f64, |a, (f, s)| a.max(norm(f) / s[0]))
    }

    /// `sum_i s_i^2 a_i b_i`: the inner product of two changes of the free coordinates in
    /// length units (m^2).
    pub(crate) fn dot(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .zip(&self.scale)
            .map(|((x, y), s)| s * s * x * y)
            .sum()
    }

    /// The largest displacement from `q0` to `q` (all coordinates) over the free coordinates
    /// (m).
    pub(crate) fn distance(&self, beam: &Beam, q: &[f64], q0: &[f64]) -> f64 {
        let v = self.vector;
        let mut largest = 0.0f64;
        for (g0, (x, x0)) in q.chunks_exact(v).zip(q0.chunks_exact(v)).enumerate() {
            if let Some(i) = beam.free_index(g0 * v) {
                let d2: f64 = x.iter().zip(x0).map(|(a, b)| (a - b) * (a - b)).sum();
                largest = largest.max(d2.sqrt() * self.scale[i]);
            }
        }
        largest
    }

    /// Whether every position or slope change of the correction `dq` (free coordinates) is
    /// within `tol` (m) or within the round-off of the positions it moves, both in length
    /// units (`q` all coordinates): a correction of a node's position or slope moves points
    /// near the node, whose positions are known only to the unit round-off of their size, so
    /// a position far from the origin cannot be corrected by less than its last bits, while a
    /// transverse coordinate near zero can.
    pub(crate) fn within_round_off(&self, beam: &Beam, dq: &[f64], q: &[f64], tol: f64) -> bool {
        let nd = beam.node_coords();
        let dim = nd / 2;
        let v = self.vector;
        q.chunks_exact(nd).enumerate().all(|(node, c)| {
            (0..nd).step_by(v).all(|k| {
                let g = node * nd + k;
                beam.free_index(g).is_none_or(|i| {
                    let s = self.scale[i];
                    let size = (norm(&c[k..k + v]) * s).max(norm(&c[k % dim..k % dim + v]));
                    norm(&dq[i..i + v]) * s <= tol + ROUND_OFF * f64::EPSILON * size
                })
            })
        })
    }
}

/// Euclidean length of `x` (its absolute value for one component).
fn norm(x: &[f64]) -> f64 {
    match x {
        [a] => a.abs(),
        _ => x.iter().map(|a| a * a).sum::<f64>().sqrt(),
    }
}

/// `sum_i a_i b_i`.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Unit round-offs of a coordinate that a Newton correction of it may be lost in.
pub(crate) const ROUND_OFF: f64 = 16.0;
