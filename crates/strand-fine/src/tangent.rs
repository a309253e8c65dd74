//! Tangent stiffness of the whole model as a list of element blocks.
//!
//! Generalized coordinates: per segment (global index `s`), six entries starting at `6 s`:
//! the translation of the centre (m) and a world-frame rotation increment (rad).

use nalgebra::SMatrix;
use rayon::prelude::*;

use crate::model::{FineModel, ModelState};

/// Stiffness of one element (joint or anchor) on its segments.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementTangent {
    /// Global segment index of body `a` (`None` for the ground) and of body `b`.
    pub segments: [Option<usize>; 2],
    /// `-d(loads)/d(coordinates)` over (a, b), 12 x 12.
    pub stiffness: SMatrix<f64, 12, 12>,
}

impl FineModel {
    /// Global index of each wire's first segment.
    pub fn segment_offsets(&self) -> Vec<usize> {
        let mut off = Vec::with_capacity(self.wires.len());
        let mut n = 0;
        for w in &self.wires {
            off.push(n);
            n += w.chain.len();
        }
        off
    }

    /// Element tangents at `state` (gravity is a constant load and adds no stiffness).
    pub fn element_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        let offsets = self.segment_offsets();
        let per_wire: Vec<Vec<ElementTangent>> = self
            .wires
            .par_iter()
            .zip(state.wires.par_iter())
            .zip(offsets.par_iter())
            .map(|((w, s), &off)| {
                let c = &w.chain;
                let mut out = Vec::with_capacity(c.joints.len() + w.anchors.len());
                for (k, j) in c.joints.iter().enumerate() {
                    out.push(ElementTangent {
                        segments: [Some(off + k), Some(off + k + 1)],
                        stiffness: j.stiffness(&s.poses[k], &s.poses[k + 1], c.segments[k].length),
                    });
                }
                for a in &w.anchors {
                    let l = c.segments[a.segment].length;
                    out.push(ElementTangent {
                        segments: [None, Some(off + a.segment)],
                        stiffness: a.joint.stiffness(&a.ground, &s.poses[a.segment], l),
                    });
                }
                out
            })
            .collect();
        per_wire.into_iter().flatten().collect()
    }
}
