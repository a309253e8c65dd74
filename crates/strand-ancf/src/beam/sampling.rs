//! Position, slope, strain and curvature of a beam at any material coordinate, not only at
//! its integration points (for result files that run from one end of the strand to the other).

use super::strain_recovery::recovery_weights;
use super::{AXIAL_POINTS, Beam, BeamError, ElementKind};
use crate::planar::{self, PlanarPoint};
use crate::shape::{ShapeRow, gauss_legendre};
use crate::spatial::{self, SectionFrame, SpatialPoint};

/// The section state of a beam at one material coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionSample {
    /// Material coordinate (m).
    pub x: f64,
    /// Position (m).
    pub position: [f64; 3],
    /// Axial strain the section law reads there: the recovered field of module
    /// `strain_recovery` (the parabola through the element means of three neighbouring
    /// elements), as at the bending points, so that an end's tension is as accurate as theirs.
    pub eps: f64,
    /// Curvature `kappa_y` (1/m): zero for a planar element.
    pub kappa_y: f64,
    /// Curvature `kappa_z` (1/m): the signed curvature of a planar element.
    pub kappa_z: f64,
}

impl Beam {
    /// Position and slope `r'` at material coordinate `x` (m), as 3-vectors.
    pub fn sample(&self, q: &[f64], x: f64) -> ([f64; 3], [f64; 3]) {
        let e = ((x / self.element_length) as usize).min(self.spec.elements - 1);
        let row = ShapeRow::new(x - e as f64 * self.element_length, self.element_length);
        match self.spec.element {
            ElementKind::Planar => {
                let qe = self.planar_coords(q, e);
                let r = planar::position(&qe, &row);
                let p = PlanarPoint::at(&qe, &row);
                ([r.x, r.y, 0.0], [p.dr.x, p.dr.y, 0.0])
            }
            ElementKind::Spatial => {
                let qe = self.spatial_coords(q, e);
                let r = spatial::position(&qe, &row);
                let p = SpatialPoint::at(&qe, &row);
                (r.into(), p.dr.into())
            }
        }
    }

    /// The section state at material coordinate `x` (m, clamped to [0, L]) for the coordinates
    /// `q`, as the element there interpolates it (at a node, the element on its left, except
    /// at x = 0). The spatial element measures the curvature components in the section frame
    /// carried from bending point `point`'s committed frame in `state` (the per-point state,
    /// see `beam::state`; pass the bending point nearest to `x`); the planar element ignores
    /// both.
    pub fn section_at(
        &self,
        q: &[f64],
        state: &[f64],
        x: f64,
        point: usize,
    ) -> Result<SectionSample, BeamError> {
        let n = self.spec.elements;
        let l = self.element_length;
        let x = x.clamp(0.0, self.length);
        let e = ((x / l).ceil() as usize).clamp(1, n) - 1;
        let xl = (x - e as f64 * l).clamp(0.0, l);
        let kin = |source| BeamError::Kinematics { element: e, source };
        let xa: Vec<f64> = gauss_legendre(AXIAL_POINTS)
            .map_err(kin)?
            .on_interval(0.0, l)
            .map(|(x, _)| x)
            .collect();
        let row = ShapeRow::new(xl, l);
        let (position, strains, kappa_y, kappa_z) = match self.spec.element {
            ElementKind::Planar => {
                let qe = self.planar_coords(q, e);
                let r = planar::position(&qe, &row);
                let k = PlanarPoint::at(&qe, &row).curvature().map_err(kin)?;
                let strains = xa
                    .iter()
                    .map(|&xa| PlanarPoint::at(&qe, &ShapeRow::new(xa, l)).strain())
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(kin)?;
                ([r.x, r.y, 0.0], strains, 0.0, k)
            }
            ElementKind::Spatial => {
                let qe = self.spatial_coords(q, e);
                let (ws, wl) = (self.state_per_point(), self.law_state_per_point());
                let frame = state
                    .get(point * ws + wl..(point + 1) * ws)
                    .ok_or_else(|| {
                        BeamError::Setup(format!(
                            "no section frame of bending point {point} in a state of {} values",
                            state.len()
                        ))
                    })
                    .and_then(|fs| SectionFrame::from_state(fs).map_err(kin))?;
                let r = spatial::position(&qe, &row);
                let [ky, kz] = SpatialPoint::at(&qe, &row).curvature(&frame).map_err(kin)?;
                let strains = xa
                    .iter()
                    .map(|&xa| SpatialPoint::at(&qe, &ShapeRow::new(xa, l)).strain())
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(kin)?;
                (r.into(), strains, ky, kz)
            }
        };
        let (own, _, w) = recovery_weights(e, n, xl, l, &xa);
        let means = self.other_means(q, e)?;
        let eps = own.iter().zip(&strains).map(|(a, s)| a * s).sum::<f64>()
            + w[0] * means[0]
            + w[1] * means[1];
        Ok(SectionSample {
            x,
            position,
            eps,
            kappa_y,
            kappa_z,
        })
    }
}
