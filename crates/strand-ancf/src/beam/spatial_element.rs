//! Forces and tangent of one spatial element (eq. (28)): as the planar element, with the
//! curvature vector in the carried section frame and the vector form of the section law.

use super::{AXIAL_POINTS, Beam, BeamError, ElementRule, Evaluation, HOURGLASS, PointState};
use crate::spatial::{
    self, SpatialCoords, SpatialMatrix, SpatialPoint, SpatialSection, SpatialVector,
};

impl Beam {
    /// Forces (and tangent) of one spatial element: as [`Beam::element_planar`] with the
    /// curvature vector `(kappa_y, kappa_z)` in the carried section frame and the vector form
    /// of the section law.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn element_spatial(
        &self,
        e: usize,
        rule: &ElementRule,
        qe: &SpatialCoords,
        means: &[f64; 2],
        slip: &[f64],
        trial: &mut [f64],
        mut tangent: Option<&mut SpatialMatrix>,
        mut points: Option<&mut [PointState]>,
    ) -> Result<(SpatialVector, Evaluation, bool), BeamError> {
        let kin = |source| BeamError::Kinematics { element: e, source };
        let frame = self.frame.as_ref().expect("spatial beams have a frame");
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
        let mut eps_h = [nalgebra::Matrix6::<f64>::zeros(); AXIAL_POINTS];
        for (j, ap) in rule.axial.iter().enumerate() {
            let pt = SpatialPoint::at(qe, &ap.row);
            let sec = |eps: f64| SpatialSection {
                n: ea * eps,
                dn_deps: ea,
                ..Default::default()
            };
            if let Some(t) = tangent.as_deref_mut() {
                let s2 = pt.second(frame).map_err(kin)?;
                let s = sec(s2.first.eps);
                eps_a[j] = s2.first.eps;
                spatial::add_gradient(&mut f, ap.weight, &ap.row, &s2.force(&s));
                spatial::add_hessian(t, ap.weight, &ap.row, &s2.tangent(&s));
                eps_q[j] = spatial::scatter_gradient(&ap.row, &s2.first.eps_grad);
                eps_h[j] = s2.eps_hess;
            } else {
                let s1 = pt.first(frame).map_err(kin)?;
                eps_a[j] = s1.eps;
                spatial::add_gradient(&mut f, ap.weight, &ap.row, &s1.force(&sec(s1.eps)));
            }
            ev.energy += ap.weight * 0.5 * ea * eps_a[j] * eps_a[j];
        }
        // Hourglass stabilization at the midpoint (see [`HOURGLASS`]); the assumed field
        // there is the mean of the axial points.
        {
            let c = HOURGLASS * ea * self.element_length;
            let pt = SpatialPoint::at(qe, &rule.mid);
            let mean = 1.0 / AXIAL_POINTS as f64;
            if let Some(t) = tangent.as_deref_mut() {
                let s2 = pt.second(frame).map_err(kin)?;
                let d = s2.first.eps - mean * eps_a.iter().sum::<f64>();
                let mut g = spatial::scatter_gradient(&rule.mid, &s2.first.eps_grad);
                for eq in &eps_q {
                    g -= eq * mean;
                }
                f += g * (c * d);
                t.ger(c, &g, &g, 1.0);
                spatial::add_hessian(t, c * d, &rule.mid, &s2.eps_hess);
                for (ap, hq) in rule.axial.iter().zip(&eps_h) {
                    spatial::add_hessian(t, -c * d * mean, &ap.row, hq);
                }
                ev.energy += 0.5 * c * d * d;
            } else {
                let s1 = pt.first(frame).map_err(kin)?;
                let d = s1.eps - mean * eps_a.iter().sum::<f64>();
                spatial::add_gradient(&mut f, c * d, &rule.mid, &s1.eps_grad);
                for ap in &rule.axial {
                    let e1 = SpatialPoint::at(qe, &ap.row).first(frame).map_err(kin)?;
                    spatial::add_gradient(&mut f, -c * d * mean, &ap.row, &e1.eps_grad);
                }
                ev.energy += 0.5 * c * d * d;
            }
        }
        let ws = self.state_per_point();
        for (i, bp) in rule.bend.iter().enumerate() {
            let eps = bp.strain(&eps_a, means);
            let pt = SpatialPoint::at(qe, &bp.qp.row);
            // Empty for a law without state (ws = 0).
            let (sl, tr) = (
                &slip[i * ws..(i + 1) * ws],
                &mut trial[i * ws..(i + 1) * ws],
            );
            let w = bp.qp.weight;
            let kappa;
            let r;
            if let Some(t) = tangent.as_deref_mut() {
                let s2 = pt.second(frame).map_err(kin)?;
                kappa = s2.first.kappa;
                r = self.law.vector(&bp.station, eps, kappa, sl, tr);
                let sec = SpatialSection {
                    m: r.moment,
                    dm_dkappa: r.moment_curvature,
                    ..Default::default()
                };
                spatial::add_gradient(&mut f, w, &bp.qp.row, &s2.force(&sec));
                spatial::add_hessian(t, w, &bp.qp.row, &s2.tangent(&sec));
                symmetric &= r.moment_curvature[0][1] == r.moment_curvature[1][0];
                if r.moment_strain != [0.0; 2] {
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
                let s1 = pt.first(frame).map_err(kin)?;
                kappa = s1.kappa;
                r = self.law.vector(&bp.station, eps, kappa, sl, tr);
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
                    weight: w,
                    slipping: r.slipping,
                };
            }
        }
        self.check_force(e, f.as_slice())?;
        Ok((f, ev, symmetric))
    }
}
