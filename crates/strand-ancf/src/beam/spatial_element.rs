//! Forces and tangent of one spatial element (eq. (28)): as the planar element, with the
//! curvature vector in each bending point's carried section frame and the vector form of the
//! section law.

use nalgebra::Matrix6;
use strand_core::Station;

use super::{
    AXIAL_POINTS, Beam, BeamError, ElementRule, Evaluation, HOURGLASS, PointState, Tangent,
    law_strain, strain_round_off,
};
use crate::spatial::{
    self, SectionFrame, SpatialCoords, SpatialMatrix, SpatialPoint, SpatialSection, SpatialVector,
};

impl Beam {
    /// Forces (and tangent) of one spatial element: as [`Beam::element_planar`] with the
    /// curvature vector `(kappa_y, kappa_z)` in the section frame of every bending point and
    /// the vector form of the section law. `state` holds each bending point's committed slip
    /// state and section frame (see `beam::state`); the frame carried to the current tangent
    /// is written to `trial` with the law's trial state. Without `books` the slip work is left
    /// out (zero; see [`Beam::internal_unbooked`]), every other value the same.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn element_spatial(
        &self,
        e: usize,
        rule: &ElementRule,
        qe: &SpatialCoords,
        means: &[f64; 2],
        state: &[f64],
        trial: &mut [f64],
        tangent: Option<(&mut SpatialMatrix, Tangent)>,
        mut points: Option<&mut [PointState]>,
        books: bool,
    ) -> Result<(SpatialVector, Evaluation, bool), BeamError> {
        let law = |st: &Station, eps, kappa, sl: &[f64], tr: &mut [f64]| {
            if books {
                self.law.vector(st, eps, kappa, sl, tr)
            } else {
                self.law.vector_unbooked(st, eps, kappa, sl, tr)
            }
        };
        let (mut tangent, kind) = match tangent {
            Some((t, kind)) => (Some(t), kind),
            None => (None, Tangent::FrozenMeans),
        };
        // With the coupling `d M / d eps` and the law's coupling of the two bending directions.
        let exact = kind == Tangent::FrozenMeans;
        let kin = |source| BeamError::Kinematics { element: e, source };
        let ea = self.law.axial_stiffness();
        let mut f = SpatialVector::zeros();
        if let Some(t) = tangent.as_deref_mut() {
            t.fill(0.0);
        }
        let mut ev = Evaluation::default();
        // Whether the tangent is symmetric: d M / d eps and a non-symmetric d M / d kappa break
        // the symmetry.
        let mut symmetric = true;
        let mut eps_a = [0.0; AXIAL_POINTS];
        let mut eps_q = [SpatialVector::zeros(); AXIAL_POINTS];
        let mut eps_h = [Matrix6::<f64>::zeros(); AXIAL_POINTS];
        for (j, ap) in rule.axial.iter().enumerate() {
            let a = SpatialPoint::at(qe, &ap.row).axial().map_err(kin)?;
            eps_a[j] = a.eps;
            let g = a.gradient();
            let n = ea * a.eps;
            spatial::add_gradient(&mut f, ap.weight, &ap.row, &(g * n));
            if let Some(t) = tangent.as_deref_mut() {
                // N eps_yy + EA eps_y eps_y^T.
                let h = a.hessian6();
                spatial::add_hessian(t, ap.weight, &ap.row, &(h * n + g * g.transpose() * ea));
                eps_q[j] = spatial::scatter_gradient(&ap.row, &g);
                eps_h[j] = h;
            }
            ev.energy += ap.weight * 0.5 * ea * eps_a[j] * eps_a[j];
        }
        // Hourglass stabilization at the midpoint (see [`HOURGLASS`]); the assumed field
        // there is the mean of the axial points.
        {
            let c = HOURGLASS * ea * self.element_length;
            let a = SpatialPoint::at(qe, &rule.mid).axial().map_err(kin)?;
            let mean = 1.0 / AXIAL_POINTS as f64;
            let d = a.eps - mean * eps_a.iter().sum::<f64>();
            if let Some(t) = tangent.as_deref_mut() {
                let mut g = spatial::scatter_gradient(&rule.mid, &a.gradient());
                for eq in &eps_q {
                    g -= eq * mean;
                }
                f += g * (c * d);
                t.ger(c, &g, &g, 1.0);
                spatial::add_hessian(t, c * d, &rule.mid, &a.hessian6());
                for (ap, hq) in rule.axial.iter().zip(&eps_h) {
                    spatial::add_hessian(t, -c * d * mean, &ap.row, hq);
                }
            } else {
                spatial::add_gradient(&mut f, c * d, &rule.mid, &a.gradient());
                for ap in &rule.axial {
                    let aj = SpatialPoint::at(qe, &ap.row).axial().map_err(kin)?;
                    spatial::add_gradient(&mut f, -c * d * mean, &ap.row, &aj.gradient());
                }
            }
            ev.energy += 0.5 * c * d * d;
        }
        let ws = self.state_per_point();
        let wl = self.law_state_per_point();
        let round = strain_round_off(rule, qe.as_slice(), 3);
        for (i, bp) in rule.bend.iter().enumerate() {
            let eps = law_strain(bp.strain(&eps_a, means), round);
            let pt = SpatialPoint::at(qe, &bp.qp.row);
            // The point's state: the law's slip state (empty for a law without state), then
            // its committed section frame.
            let (sl, fs) = state[i * ws..(i + 1) * ws].split_at(wl);
            let (tr, ft) = trial[i * ws..(i + 1) * ws].split_at_mut(wl);
            let frame = SectionFrame::from_state(fs).map_err(kin)?;
            let w = bp.qp.weight;
            let kappa;
            let r;
            if let Some(t) = tangent.as_deref_mut() {
                let s2 = pt.second(&frame).map_err(kin)?;
                SectionFrame::write_state(&s2.first.tangent, &s2.first.axes[1], ft);
                kappa = s2.first.kappa;
                r = law(&bp.station, eps, kappa, sl, tr);
                let mut dm_dkappa = r.moment_curvature;
                if kind == Tangent::AllStick {
                    dm_dkappa = [[bp.stick, 0.0], [0.0, bp.stick]];
                } else if !exact {
                    // Without the coupling of the two bending directions through the law (the
                    // friction limits turning with the bending direction, not symmetric, and
                    // the stuck wires' k l_y l_z, which cancel for three or more wires).
                    (dm_dkappa[0][1], dm_dkappa[1][0]) = (0.0, 0.0);
                }
                let sec = SpatialSection {
                    m: r.moment,
                    dm_dkappa,
                    ..Default::default()
                };
                spatial::add_gradient(&mut f, w, &bp.qp.row, &s2.force(&sec));
                spatial::add_hessian(t, w, &bp.qp.row, &s2.tangent(&sec));
                symmetric &= dm_dkappa[0][1] == dm_dkappa[1][0];
                if exact && r.moment_strain != [0.0; 2] {
                    symmetric = false;
                    let mut ge = SpatialVector::zeros();
                    for j in 0..AXIAL_POINTS {
                        ge += eps_q[j] * bp.interp[j];
                    }
                    for a in 0..2 {
                        let gk = spatial::scatter_gradient(&bp.qp.row, &s2.first.kappa_grad[a]);
                        t.ger(w * r.moment_strain[a], &gk, &ge, 1.0);
                    }
                }
            } else {
                let s1 = pt.first(&frame).map_err(kin)?;
                SectionFrame::write_state(&s1.tangent, &s1.axes[1], ft);
                kappa = s1.kappa;
                r = law(&bp.station, eps, kappa, sl, tr);
                let local = s1.kappa_grad[0] * r.moment[0] + s1.kappa_grad[1] * r.moment[1];
                spatial::add_gradient(&mut f, w, &bp.qp.row, &local);
            }
            if !(r.moment.iter().all(|m| m.is_finite())
                && r.moment_curvature.iter().flatten().all(|m| m.is_finite()))
            {
                return Err(BeamError::NonFinite {
                    element: e,
                    x: bp.station.x,
                    quantity: "bending moment",
                });
            }
            ev.energy += w * (r.energy - 0.5 * ea * eps * eps);
            ev.slip_work += w * r.slip_work;
            ev.slipping += r.slipping;
            if let Some(p) = points.as_deref_mut() {
                p[i] = PointState {
                    x: bp.station.x,
                    eps,
                    kappa: kappa[1],
                    kappa_y: kappa[0],
                    moment: r.moment[1],
                    energy_strain: r.energy_strain,
                    energy_turn: r.energy_turn,
                    weight: w,
                    slipping: r.slipping,
                };
            }
        }
        self.check_force(e, f.as_slice())?;
        Ok((f, ev, symmetric))
    }
}
