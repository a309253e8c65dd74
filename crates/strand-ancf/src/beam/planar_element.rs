//! Forces and tangent of one planar element (eq. (28)): axial points, hourglass
//! stabilization and bending points with the planar section law.

use nalgebra::{Vector2, Vector4};
use strand_core::{PlanarMoment, PlanarResponse};

use super::{
    AXIAL_POINTS, Beam, BeamError, BendPoint, ElementKind, ElementRule, Evaluation, HOURGLASS,
    PointState, Tangent, law_strain, strain_round_off,
};
use crate::error::check_stretch;
use crate::planar::{self, PlanarAxial, PlanarCoords, PlanarMatrix, PlanarPoint, PlanarVector};
use crate::scatter;

impl Beam {
    /// Forces (and tangent) of one planar element. The symmetric part of the tangent is built
    /// on and below the diagonal and mirrored; the coupling `d M / d eps` (the only
    /// non-symmetric term) is added after.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn element_planar(
        &self,
        e: usize,
        rule: &ElementRule,
        qe: &PlanarCoords,
        means: &[f64; 2],
        slip: &[f64],
        trial: &mut [f64],
        tangent: Option<(&mut PlanarMatrix, bool)>,
        mut points: Option<&mut [PointState]>,
    ) -> Result<(PlanarVector, Evaluation, bool), BeamError> {
        // `exact`: with the coupling `d M / d eps` (see [`Tangent`]).
        let (mut tangent, exact) = match tangent {
            Some((t, exact)) => (Some(t), exact),
            None => (None, true),
        };
        let kin = |source| BeamError::Kinematics { element: e, source };
        let ea = self.law.axial_stiffness();
        let mut f = PlanarVector::zeros();
        if let Some(t) = tangent.as_deref_mut() {
            t.fill(0.0);
        }
        let mut ev = Evaluation::default();
        // The non-symmetric part of the tangent, if any, as the element-size factors of its
        // rank-one terms per axial point (see the bending points).
        let mut coupling = [PlanarVector::zeros(); AXIAL_POINTS];
        let mut coupled = false;
        // Axial points: reduced quadrature.
        let mut eps_a = [0.0; AXIAL_POINTS];
        let mut eps_q = [PlanarVector::zeros(); AXIAL_POINTS];
        let mut axial = [PlanarAxial {
            eps: 0.0,
            tangent: Vector2::zeros(),
            stretch: 1.0,
        }; AXIAL_POINTS];
        for (j, ap) in rule.axial.iter().enumerate() {
            let a = PlanarPoint::at(qe, &ap.row).axial().map_err(kin)?;
            axial[j] = a;
            eps_a[j] = a.eps;
            let n = ea * a.eps;
            let ge = Vector4::new(a.tangent.x, a.tangent.y, 0.0, 0.0);
            planar::add_gradient(&mut f, ap.weight, &ap.row, &(ge * n));
            eps_q[j] = planar::scatter_gradient(&ap.row, &ge);
            if let Some(t) = tangent.as_deref_mut() {
                // N eps_yy + EA eps_y eps_y^T: only the r' block.
                let h = a.hessian() * n + a.tangent * a.tangent.transpose() * ea;
                planar::add_hessian_aa_lower(t, ap.weight, &ap.row, &h);
            }
            ev.energy += ap.weight * 0.5 * ea * eps_a[j] * eps_a[j];
        }
        // Hourglass stabilization at the midpoint (see [`HOURGLASS`]); the assumed field
        // there is the mean of the axial points.
        {
            let c = HOURGLASS * ea * self.element_length;
            let a = PlanarPoint::at(qe, &rule.mid).axial().map_err(kin)?;
            let mean = 1.0 / AXIAL_POINTS as f64;
            let d = a.eps - mean * eps_a.iter().sum::<f64>();
            let ge = Vector4::new(a.tangent.x, a.tangent.y, 0.0, 0.0);
            let mut g = planar::scatter_gradient(&rule.mid, &ge);
            for eq in &eps_q {
                g -= eq * mean;
            }
            f += g * (c * d);
            if let Some(t) = tangent.as_deref_mut() {
                t.ger(c, &g, &g, 1.0);
                planar::add_hessian_aa_lower(t, c * d, &rule.mid, &a.hessian());
                for (ap, aj) in rule.axial.iter().zip(&axial) {
                    planar::add_hessian_aa_lower(t, -c * d * mean, &ap.row, &aj.hessian());
                }
            }
            ev.energy += 0.5 * c * d * d;
        }
        // Bending points.
        let ws = self.state_per_point();
        let round = strain_round_off(rule, qe.as_slice(), 2);
        for (i, bp) in rule.bend.iter().enumerate() {
            let eps = law_strain(bp.strain(&eps_a, means), round);
            let pt = PlanarPoint::at(qe, &bp.qp.row);
            // Empty for a law without state (ws = 0).
            let (sl, tr) = (
                &slip[i * ws..(i + 1) * ws],
                &mut trial[i * ws..(i + 1) * ws],
            );
            let w = bp.qp.weight;
            let kappa;
            let r;
            if let Some(t) = tangent.as_deref_mut() {
                let b2 = pt.bending_second().map_err(kin)?;
                kappa = b2.kappa;
                r = self.law.planar(&bp.station, eps, kappa, sl, tr);
                planar::add_gradient(&mut f, w, &bp.qp.row, &(b2.grad * r.moment));
                // M kappa_yy + M_kappa kappa_y kappa_y^T (kappa_yy has no r'' r'' block).
                let mut h = b2.grad * b2.grad.transpose() * r.moment_curvature;
                for j in 0..2 {
                    for i in 0..2 {
                        h[(i, j)] += b2.hess_aa[(i, j)] * r.moment;
                        h[(i, 2 + j)] += b2.hess_ab[(i, j)] * r.moment;
                        h[(2 + j, i)] += b2.hess_ab[(i, j)] * r.moment;
                    }
                }
                planar::add_hessian_lower(t, w, &bp.qp.row, &h);
                if exact && r.moment_strain != 0.0 {
                    // d M / d eps_bar couples the curvature here to the axial points:
                    // w M_eps kappa_q eps_bar_q^T with eps_bar_q = sum_j interp_j eps_q[j] (the
                    // own element's part of the strain the law reads).
                    // Summed per axial point j over the bending points, then one rank-one
                    // update per axial point for the element.
                    let c = w * r.moment_strain;
                    for j in 0..AXIAL_POINTS {
                        planar::add_gradient(
                            &mut coupling[j],
                            c * bp.interp[j],
                            &bp.qp.row,
                            &b2.grad,
                        );
                    }
                    coupled = true;
                }
            } else {
                let (k, grad) = pt.bending_first().map_err(kin)?;
                kappa = k;
                r = self.law.planar(&bp.station, eps, kappa, sl, tr);
                planar::add_gradient(&mut f, w, &bp.qp.row, &(grad * r.moment));
            }
            let point = points.as_deref_mut().map(|p| &mut p[i]);
            book_planar_point(e, bp, eps, kappa, ea, &r, &mut ev, point)?;
        }
        if let Some(t) = tangent {
            planar::mirror_lower(t);
            if coupled {
                for j in 0..AXIAL_POINTS {
                    t.ger(1.0, &coupling[j], &eps_q[j], 1.0);
                }
            }
        }
        self.check_force(e, f.as_slice())?;
        Ok((f, ev, !coupled))
    }

    /// Forces of one planar element without the tangent: the quantities of
    /// [`Beam::element_planar`] with only what the forces need. Per point only `r'` (axial
    /// points) or `r'` and `r''` (bending points) are formed, and the hourglass term's strain
    /// gradients are folded into the scatter of each point's own force, so every point is
    /// mapped to the element coordinates once. This is the evaluation of every Newton
    /// iteration that keeps its matrix and of every explicit step. With `material`, it also
    /// builds the material part of the tangent ([`super::Tangent::Iteration`], with its share
    /// of the slipping wires' stick stiffness) from the same gradients: a rank-one term per
    /// point. Without `books` the bending points' books are left out (see
    /// [`Beam::internal_unbooked`]; `trial` is not written).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn planar_forces(
        &self,
        e: usize,
        rule: &ElementRule,
        qe: &PlanarCoords,
        means: &[f64; 2],
        slip: &[f64],
        trial: &mut [f64],
        material: Option<(&mut PlanarMatrix, Tangent)>,
        mut points: Option<&mut [PointState]>,
        books: bool,
    ) -> Result<(PlanarVector, Evaluation), BeamError> {
        let (mut material, kind) = match material {
            Some((m, kind)) => (Some(m), kind),
            None => (None, Tangent::FrozenMeans),
        };
        if let Some(m) = material.as_deref_mut() {
            m.as_mut_slice().fill(0.0);
        }
        let kin = |source| BeamError::Kinematics { element: e, source };
        let q = qe.as_slice();
        let ea = self.law.axial_stiffness();
        let mut f = [0.0; 8];
        let mut ev = Evaluation::default();
        // Axial points: strain and unit tangent from r' alone.
        let mut eps_a = [0.0; AXIAL_POINTS];
        let mut t_a = [[0.0; 2]; AXIAL_POINTS];
        for (j, ap) in rule.axial.iter().enumerate() {
            let dr = scatter::combine::<2>(&ap.row.ds, q);
            let n = check_stretch((dr[0] * dr[0] + dr[1] * dr[1]).sqrt()).map_err(kin)?;
            eps_a[j] = n - 1.0;
            t_a[j] = [dr[0] / n, dr[1] / n];
            ev.energy += ap.weight * 0.5 * ea * eps_a[j] * eps_a[j];
        }
        // Hourglass stabilization at the midpoint (see [`HOURGLASS`]): the force
        // `c d (d eps_mid/dq - mean sum_j d eps_j/dq)`.
        let c = HOURGLASS * ea * self.element_length;
        let mean = 1.0 / AXIAL_POINTS as f64;
        {
            let dr = scatter::combine::<2>(&rule.mid.ds, q);
            let n = check_stretch((dr[0] * dr[0] + dr[1] * dr[1]).sqrt()).map_err(kin)?;
            let d = (n - 1.0) - mean * eps_a.iter().sum::<f64>();
            let cd = c * d;
            add_slope_gradient(&mut f, cd / n, &rule.mid.ds, &dr);
            for (j, ap) in rule.axial.iter().enumerate() {
                // Axial force N = EA eps along the tangent, minus the hourglass share.
                let a = ap.weight * ea * eps_a[j] - cd * mean;
                add_slope_gradient(&mut f, a, &ap.row.ds, &t_a[j]);
            }
            ev.energy += 0.5 * c * d * d;
            if let Some(m) = material.as_deref_mut() {
                // EA on each axial strain's gradient; the penalty on the hourglass strain's.
                let mut g = [0.0; 8];
                add_slope_gradient(&mut g, 1.0 / n, &rule.mid.ds, &dr);
                for (j, ap) in rule.axial.iter().enumerate() {
                    let mut gj = [0.0; 8];
                    add_slope_gradient(&mut gj, 1.0, &ap.row.ds, &t_a[j]);
                    add_outer_lower(m, ap.weight * ea, &gj);
                    for (x, y) in g.iter_mut().zip(&gj) {
                        *x -= mean * y;
                    }
                }
                add_outer_lower(m, c, &g);
            }
        }
        let ws = self.state_per_point();
        let linear = self.law.is_linear();
        let round = strain_round_off(rule, q, 2);
        // The kinematics of the bending points, LANES at a time: the square roots and
        // divisions of independent points side by side (packed, with the same rounding as
        // one by one), not each waiting on the last.
        let mut kin_pts = [BendKinematics::default(); LANES];
        for (i, bp) in rule.bend.iter().enumerate() {
            let lane = i % LANES;
            if lane == 0 {
                let chunk = &rule.bend[i..(i + LANES).min(rule.bend.len())];
                bend_kinematics(chunk, q, &mut kin_pts);
                for k in &kin_pts[..chunk.len()] {
                    check_stretch(k.n).map_err(kin)?;
                }
            }
            let BendKinematics { kappa, ka, kb, .. } = kin_pts[lane];
            let eps = law_strain(bp.strain(&eps_a, means), round);
            // Empty for a law without state (ws = 0).
            let sl = &slip[i * ws..(i + 1) * ws];
            let point = points.as_deref_mut().map(|p| &mut p[i]);
            let r = if linear && books {
                let r = self.law.planar_linear(eps, kappa);
                book_planar_point(e, bp, eps, kappa, ea, &r, &mut ev, point)?;
                PlanarMoment {
                    moment: r.moment,
                    moment_curvature: r.moment_curvature,
                }
            } else if books {
                let tr = &mut trial[i * ws..(i + 1) * ws];
                let r = self.law.planar(&bp.station, eps, kappa, sl, tr);
                book_planar_point(e, bp, eps, kappa, ea, &r, &mut ev, point)?;
                PlanarMoment {
                    moment: r.moment,
                    moment_curvature: r.moment_curvature,
                }
            } else {
                let r = self.law.planar_moment(&bp.station, eps, kappa, sl);
                if !(r.moment.is_finite() && r.moment_curvature.is_finite()) {
                    return Err(non_finite_moment(e, bp));
                }
                // What `Beam::book_points` reads and the moment; it writes the rest.
                if let Some(p) = point {
                    p.eps = eps;
                    p.kappa = kappa;
                    p.moment = r.moment;
                }
                r
            };
            let wm = bp.qp.weight * r.moment;
            let row = &bp.qp.row;
            for k in 0..4 {
                let (c1, c2) = (wm * row.ds[k], wm * row.dds[k]);
                f[2 * k] += c1 * ka[0] + c2 * kb[0];
                f[2 * k + 1] += c1 * ka[1] + c2 * kb[1];
            }
            if let Some(m) = material.as_deref_mut() {
                // dM/dkappa on the curvature's gradient, slipping wires at `unloading` of
                // their stick stiffness.
                let mut g = [0.0; 8];
                for k in 0..4 {
                    g[2 * k] = row.ds[k] * ka[0] + row.dds[k] * kb[0];
                    g[2 * k + 1] = row.ds[k] * ka[1] + row.dds[k] * kb[1];
                }
                // Without tension the wires have no friction limit and never re-stick.
                let share = match kind {
                    Tangent::AllStick => 1.0,
                    Tangent::Iteration { unloading } if eps > 0.0 => unloading,
                    _ => 0.0,
                };
                let k = r.moment_curvature + share * (bp.stick - r.moment_curvature).max(0.0);
                add_outer_lower(m, bp.qp.weight * k, &g);
            }
        }
        if let Some(m) = material {
            mirror_lower(m);
        }
        self.check_force(e, f.as_slice())?;
        Ok((PlanarVector::from(f), ev))
    }
}

impl Beam {
    /// Completes `ev`, the evaluation [`Beam::internal_unbooked`] returned, with the books it
    /// left out, at the strains and curvatures it wrote to `points`: the section law at each
    /// bending point from the committed `slip`, its trial state into `trial`. The same values
    /// as a booked evaluation ([`Beam::internal_with`]).
    ///
    /// Planar elements: the bending points' energy is added to `ev`'s (the sum's rounding
    /// differs from the booked evaluation's by the order of its terms), their slip work and
    /// slipping wires replace `ev`'s, and `points` and `trial` are written. Spatial elements:
    /// the slip work alone replaces `ev`'s, summed as the booked evaluation sums it (bit for
    /// bit), from the trial state the unbooked evaluation wrote
    /// ([`SectionLaw::vector_slip_work`]: the friction limits of the wires whose slip changed
    /// alone).
    ///
    /// [`SectionLaw::vector_slip_work`]: strand_core::SectionLaw::vector_slip_work
    pub fn book_points(
        &self,
        slip: &[f64],
        trial: &mut [f64],
        points: &mut [PointState],
        ev: &mut Evaluation,
    ) {
        let ws = self.state_per_point();
        let wl = self.law_state_per_point();
        let ea = self.law.axial_stiffness();
        let spatial = self.spec.element == ElementKind::Spatial;
        let (sl, tl) = (slip.len(), trial.len());
        let mut sum = Evaluation::default();
        let mut p0 = 0;
        for rule in &self.rules {
            let np = rule.bend.len();
            let (s0, s1) = (p0 * ws, (p0 + np) * ws);
            let slip = &slip[s0.min(sl)..s1.min(sl)];
            let trial = &mut trial[s0.min(tl)..s1.min(tl)];
            let points = &mut points[p0..p0 + np];
            // Summed per element as in the element loop.
            let mut el = Evaluation::default();
            for (i, (bp, p)) in rule.bend.iter().zip(points.iter_mut()).enumerate() {
                let (sl, tr) = (
                    &slip[i * ws..(i + 1) * ws],
                    &mut trial[i * ws..(i + 1) * ws],
                );
                let (eps, kappa) = (p.eps, p.kappa);
                if spatial {
                    // From the law's part of the states (before the section frame's), which
                    // the unbooked evaluation wrote.
                    let (sl, tr) = (&sl[..wl], &tr[..wl]);
                    let w = self
                        .law
                        .vector_slip_work(&bp.station, eps, [p.kappa_y, kappa], sl, tr);
                    el.slip_work += bp.qp.weight * w;
                    continue;
                }
                let r = self.law.planar(&bp.station, eps, kappa, sl, tr);
                // Finite: the unbooked evaluation checked this moment at these arguments.
                record_planar_point(bp, eps, kappa, ea, &r, &mut el, Some(p));
            }
            p0 += np;
            sum.energy += el.energy;
            sum.slip_work += el.slip_work;
            sum.slipping += el.slipping;
        }
        ev.slip_work = sum.slip_work;
        if !spatial {
            ev.energy += sum.energy;
            ev.slipping = sum.slipping;
        }
    }
}

/// Books the section response `r` of planar bending point `bp` (element `e`): checks that
/// it is finite, then [`record_planar_point`]. Shared by both planar element paths.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn book_planar_point(
    e: usize,
    bp: &BendPoint,
    eps: f64,
    kappa: f64,
    ea: f64,
    r: &PlanarResponse,
    ev: &mut Evaluation,
    point: Option<&mut PointState>,
) -> Result<(), BeamError> {
    if !(r.moment.is_finite() && r.moment_curvature.is_finite()) {
        return Err(non_finite_moment(e, bp));
    }
    record_planar_point(bp, eps, kappa, ea, r, ev, point);
    Ok(())
}

/// Adds the stored energy beyond the axial part, slip work and slipping wires of the section
/// response `r` at planar bending point `bp` to `ev`, and records its state in `point`, if
/// given.
#[inline(always)]
fn record_planar_point(
    bp: &BendPoint,
    eps: f64,
    kappa: f64,
    ea: f64,
    r: &PlanarResponse,
    ev: &mut Evaluation,
    point: Option<&mut PointState>,
) {
    let w = bp.qp.weight;
    ev.energy += w * (r.energy - 0.5 * ea * eps * eps);
    ev.slip_work += w * r.slip_work;
    ev.slipping += r.slipping;
    if let Some(p) = point {
        *p = PointState {
            x: bp.station.x,
            eps,
            kappa,
            kappa_y: 0.0,
            moment: r.moment,
            energy_strain: r.energy_strain,
            energy_turn: [0.0; 2],
            weight: w,
            slipping: r.slipping,
        };
    }
}

/// The error of a bending moment (or its tangent) that is not finite at point `bp` of
/// element `e`.
#[cold]
fn non_finite_moment(e: usize, bp: &BendPoint) -> BeamError {
    BeamError::NonFinite {
        element: e,
        x: bp.station.x,
        quantity: "bending moment",
    }
}

/// Bending points evaluated side by side in [`Beam::planar_forces`].
const LANES: usize = 4;

/// Curvature and its gradient at a bending point (as `PlanarPoint::bending_first`).
#[derive(Debug, Clone, Copy, Default)]
struct BendKinematics {
    /// `|r'|`.
    n: f64,
    /// `(r' x r'')_z / |r'|^2` (1/m).
    kappa: f64,
    /// `d kappa / d r'`.
    ka: [f64; 2],
    /// `d kappa / d r''`.
    kb: [f64; 2],
}

/// [`BendKinematics`] of up to [`LANES`] bending points with element coordinates `q`, each
/// step over all points at once; lanes past `points` are left with `n = 1`.
#[inline(always)]
fn bend_kinematics(points: &[BendPoint], q: &[f64], out: &mut [BendKinematics; LANES]) {
    let (mut a, mut b) = ([[0.0; 2]; LANES], [[0.0; 2]; LANES]);
    let mut n = [1.0; LANES];
    for (l, bp) in points.iter().enumerate() {
        a[l] = scatter::combine::<2>(&bp.qp.row.ds, q);
        b[l] = scatter::combine::<2>(&bp.qp.row.dds, q);
        n[l] = a[l][0] * a[l][0] + a[l][1] * a[l][1];
    }
    for x in &mut n {
        *x = x.sqrt();
    }
    let mut g = [0.0; LANES];
    let mut ga = [0.0; LANES];
    let mut t = [[0.0; 2]; LANES];
    for l in 0..LANES {
        g[l] = 1.0 / (n[l] * n[l]);
        ga[l] = -2.0 * g[l] / n[l];
        t[l] = [a[l][0] / n[l], a[l][1] / n[l]];
    }
    for l in 0..LANES {
        let cr = a[l][0] * b[l][1] - a[l][1] * b[l][0];
        out[l] = BendKinematics {
            n: n[l],
            kappa: cr * g[l],
            ka: [
                b[l][1] * g[l] + t[l][0] * ga[l] * cr,
                -b[l][0] * g[l] + t[l][1] * ga[l] * cr,
            ],
            kb: [-a[l][1] * g[l], a[l][0] * g[l]],
        };
    }
}

/// Copies the lower triangle of the column-major `m` onto the upper one.
#[inline(always)]
fn mirror_lower(m: &mut PlanarMatrix) {
    let d = m.as_mut_slice();
    for col in 1..8 {
        for row in 0..col {
            d[8 * col + row] = d[8 * row + col];
        }
    }
}

/// `m += c g g^T`, on and below the diagonal only.
#[inline(always)]
fn add_outer_lower(m: &mut PlanarMatrix, c: f64, g: &[f64; 8]) {
    // Column-major: column `col` is `data[8 col..8 col + 8]`.
    for (col, column) in m.as_mut_slice().chunks_exact_mut(8).enumerate() {
        let gc = c * g[col];
        for (x, y) in column[col..].iter_mut().zip(&g[col..]) {
            *x += gc * y;
        }
    }
}

/// `f += a S_k' v` for the four nodal slope blocks: the element force of a local force `a v`
/// acting on `r'` alone.
#[inline(always)]
fn add_slope_gradient(f: &mut [f64; 8], a: f64, ds: &[f64; 4], v: &[f64; 2]) {
    for k in 0..4 {
        let c = a * ds[k];
        f[2 * k] += c * v[0];
        f[2 * k + 1] += c * v[1];
    }
}
