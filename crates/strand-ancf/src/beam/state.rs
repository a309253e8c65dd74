//! The per-point state that solvers commit on accepted steps.
//!
//! Every bending point holds, in one vector over the beam ([`Beam::state_len`] values, point
//! after point):
//! * the section law's state ([`strand_core::SectionLaw::state_len`]: for the hysteretic law
//!   the slip of each wire, the stored bending direction of the friction limits and the
//!   committed strain, and for several layers their closed-form states; none otherwise);
//! * for the spatial element, the point's reference section frame `(t0, e_z0)`
//!   ([`SectionFrame::STATE_LEN`] values): the section turns without spin about the tangent
//!   (see [`crate::spatial`]), so the frame carried to the accepted tangent is the next step's
//!   reference.
//!
//! [`Beam::internal`] reads the committed state and writes the trial state of the evaluated
//! configuration; a solver copies the trial state over the committed one when it accepts a
//! step. The planar element has no frame: its section frame is the global one.

use nalgebra::Vector3;

use super::{Beam, ElementKind};
use crate::spatial::SectionFrame;

impl Beam {
    /// Section-law state values per bending point (none for a law without state).
    pub(crate) fn law_state_per_point(&self) -> usize {
        self.law.state_len()
    }

    /// Section-frame state values per bending point (spatial element only).
    pub(crate) fn frame_state_per_point(&self) -> usize {
        match self.spec.element {
            ElementKind::Planar => 0,
            ElementKind::Spatial => SectionFrame::STATE_LEN,
        }
    }

    /// State values per bending point: the law's, then the frame's.
    pub(crate) fn state_per_point(&self) -> usize {
        self.law_state_per_point() + self.frame_state_per_point()
    }

    /// Length of the state vector for the whole beam.
    pub fn state_len(&self) -> usize {
        self.points() * self.state_per_point()
    }

    /// The state of the straight reference configuration: no slip, and every section frame the
    /// initial one (tangent along the strand, phase axis along the phase reference).
    pub fn initial_state(&self) -> Vec<f64> {
        let (ws, wl) = (self.state_per_point(), self.law_state_per_point());
        let mut s = vec![0.0; self.state_len()];
        if let Some(f) = &self.frame {
            for p in s.chunks_exact_mut(ws) {
                SectionFrame::write_state(&f.t0(), &f.e_z0(), &mut p[wl..]);
            }
        }
        s
    }

    /// The section-law state of bending point `i` (empty for a law without state).
    pub fn point_slip<'s>(&self, state: &'s [f64], i: usize) -> &'s [f64] {
        let ws = self.state_per_point();
        &state[i * ws..i * ws + self.law_state_per_point()]
    }

    /// The reference section frame of bending point `i` in `state`: (tangent, `e_y`, `e_z`);
    /// `None` for the planar element, whose section frame has `e_z` = Z.
    pub fn point_frame(&self, state: &[f64], i: usize) -> Option<[Vector3<f64>; 3]> {
        let ws = self.state_per_point();
        let wl = self.law_state_per_point();
        if self.frame_state_per_point() == 0 {
            return None;
        }
        let f = SectionFrame::from_state(&state[i * ws + wl..(i + 1) * ws]).ok()?;
        Some([f.t0(), f.e_y0(), f.e_z0()])
    }
}
