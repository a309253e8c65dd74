//! Position and slope of a beam at any material coordinate.

use super::{Beam, ElementKind};
use crate::planar::{self, PlanarPoint};
use crate::shape::ShapeRow;
use crate::spatial::{self, SpatialPoint};

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
}
