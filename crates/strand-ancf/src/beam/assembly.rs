//! The global elastic forces `Q_e` (eq. (28)) and their tangent: element contributions
//! summed over the mesh and scattered into the free coordinates' band matrix.

#[cfg(test)]
use nalgebra::DMatrix;

use super::{Beam, BeamError, ElementKind, Evaluation, PointState, Tangent};
use crate::band::BandMatrix;
use crate::planar::PlanarMatrix;
use crate::spatial::SpatialMatrix;

impl Beam {
    /// Evaluates the generalized elastic forces `Q_e` (eq. (28)) into `force` (all
    /// coordinates, overwritten) and, if given, the tangent `dQ_e/dq` of the free coordinates
    /// into `tangent` (overwritten). `slip`/`trial` are the committed and trial per-point state
    /// ([`Self::state_len`] values, see [`Self::initial_state`]; shorter slices stand for no
    /// slip with the planar element, whose state holds no section frames); `points`, if given,
    /// receives the state at every bending point.
    ///
    /// The tangent differentiates the forces with the neighbouring elements' mean strains, in
    /// the strain the section law reads (module `strain_recovery`), held fixed: that coupling
    /// would not fit in the band. [`Self::internal_frozen`] evaluates the forces with them held.
    pub fn internal(
        &self,
        q: &[f64],
        slip: &[f64],
        trial: &mut [f64],
        force: &mut [f64],
        tangent: Option<&mut BandMatrix>,
        points: Option<&mut [PointState]>,
    ) -> Result<Evaluation, BeamError> {
        let tangent = tangent.map(|t| (t, Tangent::FrozenMeans));
        self.assemble(q, q, slip, trial, force, tangent, points, true)
    }

    /// [`Self::internal`] at coordinates `q` with the mean strains that each element's section
    /// law reads of its neighbours taken at coordinates `means_at` instead: the forces whose
    /// derivative the tangent is (for finite-difference checks).
    #[allow(clippy::too_many_arguments)]
    pub fn internal_frozen(
        &self,
        q: &[f64],
        means_at: &[f64],
        slip: &[f64],
        trial: &mut [f64],
        force: &mut [f64],
        tangent: Option<&mut BandMatrix>,
        points: Option<&mut [PointState]>,
    ) -> Result<Evaluation, BeamError> {
        let tangent = tangent.map(|t| (t, Tangent::FrozenMeans));
        self.assemble(q, means_at, slip, trial, force, tangent, points, true)
    }

    /// [`Self::internal`] with a choice of tangent.
    pub fn internal_with(
        &self,
        q: &[f64],
        slip: &[f64],
        trial: &mut [f64],
        force: &mut [f64],
        tangent: Option<(&mut BandMatrix, Tangent)>,
        points: Option<&mut [PointState]>,
    ) -> Result<Evaluation, BeamError> {
        self.assemble(q, q, slip, trial, force, tangent, points, true)
    }

    /// [`Self::internal_with`] without the books of the bending points that a Newton
    /// iteration does not read; [`Self::book_points`] completes them at the iterate that is
    /// accepted. With a [`Tangent::Iteration`] or no matrix only (an error otherwise).
    ///
    /// * Planar elements leave out every book: the returned energy holds only the axial
    ///   points' and the hourglass term's, `trial` is not written, and `points` receive each
    ///   bending point's strain, curvature and moment. With the `continuous` and
    ///   `hysteretic` laws the books are about half the work per wire.
    /// * Spatial elements leave out the slip work alone (zero): it takes each slipping wire's
    ///   friction limit at the committed bending direction, its capstan gains evaluated a
    ///   second time ([`SectionLaw::vector_unbooked`]). The energy, the slipping wires, the
    ///   points and `trial` (the law's trial state and the carried section frames) are those
    ///   of [`Self::internal_with`] bit for bit: their per-wire terms come with the moment's,
    ///   and summed apart from the axial points' the energy would change its rounding.
    ///
    /// [`SectionLaw::vector_unbooked`]: strand_core::SectionLaw::vector_unbooked
    pub fn internal_unbooked(
        &self,
        q: &[f64],
        slip: &[f64],
        trial: &mut [f64],
        force: &mut [f64],
        tangent: Option<(&mut BandMatrix, Tangent)>,
        points: &mut [PointState],
    ) -> Result<Evaluation, BeamError> {
        if tangent
            .as_ref()
            .is_some_and(|(_, t)| *t == Tangent::FrozenMeans)
        {
            return Err(BeamError::Setup(
                "forces without books are for an iteration matrix".into(),
            ));
        }
        self.assemble(q, q, slip, trial, force, tangent, Some(points), false)
    }

    /// The forces and the chosen tangent with the neighbours' mean strains taken at `means_at`;
    /// with `books`, the bending points' books too (see [`Self::internal_unbooked`]).
    #[allow(clippy::too_many_arguments)]
    fn assemble(
        &self,
        q: &[f64],
        means_at: &[f64],
        slip: &[f64],
        trial: &mut [f64],
        force: &mut [f64],
        tangent: Option<(&mut BandMatrix, Tangent)>,
        mut points: Option<&mut [PointState]>,
        books: bool,
    ) -> Result<Evaluation, BeamError> {
        if self.frame_state_per_point() > 0
            && (slip.len() != self.state_len() || trial.len() != self.state_len())
        {
            return Err(BeamError::Setup(format!(
                "state vectors of {} and {} values for a beam whose state has {} (section \
                 frames of the spatial element included)",
                slip.len(),
                trial.len(),
                self.state_len()
            )));
        }
        let (mut tangent, kind) = match tangent {
            Some((t, kind)) => (Some(t), kind),
            None => (None, Tangent::FrozenMeans),
        };
        let exact = kind == Tangent::FrozenMeans;
        force.fill(0.0);
        if let Some(t) = tangent.as_deref_mut() {
            t.fill_zero();
        }
        let nd = self.nd;
        let ws = self.state_per_point();
        let mut sum = Evaluation::default();
        let mut kp = PlanarMatrix::zeros();
        let mut ks = SpatialMatrix::zeros();
        let mut p0 = 0;
        for (e, rule) in self.rules.iter().enumerate() {
            let np = rule.bend.len();
            let (s0, s1) = (p0 * ws, (p0 + np) * ws);
            let (sl, tl) = (slip.len(), trial.len());
            let sl = &slip[s0.min(sl)..s1.min(sl)];
            let tr = &mut trial[s0.min(tl)..s1.min(tl)];
            let pts = points.as_deref_mut().map(|p| &mut p[p0..p0 + np]);
            let want_k = tangent.is_some();
            let means = self.other_means(means_at, e)?;
            let (ke, ev, sym): (&[f64], Evaluation, bool) = match self.spec.element {
                ElementKind::Planar => {
                    let qe = self.planar_coords(q, e);
                    let (f, ev, sym) = if want_k && exact {
                        let k = Some((&mut kp, true));
                        self.element_planar(e, rule, &qe, &means, sl, tr, k, pts)?
                    } else {
                        let k = want_k.then_some((&mut kp, kind));
                        let (f, ev) =
                            self.planar_forces(e, rule, &qe, &means, sl, tr, k, pts, books)?;
                        (f, ev, true)
                    };
                    for a in 0..8 {
                        force[e * nd + a] += f[a];
                    }
                    (kp.as_slice(), ev, sym)
                }
                ElementKind::Spatial => {
                    let qe = self.spatial_coords(q, e);
                    let k = want_k.then_some((&mut ks, kind));
                    let (f, ev, sym) =
                        self.element_spatial(e, rule, &qe, &means, sl, tr, k, pts, books)?;
                    for a in 0..12 {
                        force[e * nd + a] += f[a];
                    }
                    (ks.as_slice(), ev, sym)
                }
            };
            p0 += np;
            sum.energy += ev.energy;
            sum.slip_work += ev.slip_work;
            sum.slipping += ev.slipping;
            if let Some(t) = tangent.as_deref_mut() {
                // Element matrices are column-major, 2 nd x 2 nd.
                let m = 2 * nd;
                if let (Some(i0), Some(i1)) =
                    (self.free_index[e * nd], self.free_index[e * nd + m - 1])
                    && i1 == i0 + m - 1
                {
                    // Every coordinate of the element is free: one dense block.
                    t.add_block(i0, m, ke, sym);
                    continue;
                }
                if sym {
                    // Mirror the lower triangle: the global matrix is then exactly symmetric
                    // (each mirrored pair sums the same values in the same order), which lets
                    // the solver use LDL^T.
                    for b in 0..m {
                        let Some(ib) = self.free_index[e * nd + b] else {
                            continue;
                        };
                        for a in b..m {
                            if let Some(ia) = self.free_index[e * nd + a] {
                                let v = ke[a + b * m];
                                t.add(ia, ib, v);
                                if a != b {
                                    t.add(ib, ia, v);
                                }
                            }
                        }
                    }
                    continue;
                }
                for b in 0..m {
                    let Some(ib) = self.free_index[e * nd + b] else {
                        continue;
                    };
                    for a in 0..m {
                        if let Some(ia) = self.free_index[e * nd + a] {
                            t.add(ia, ib, ke[a + b * m]);
                        }
                    }
                }
            }
        }
        Ok(sum)
    }

    /// `Ok` if the element force `f` of element `e` is finite.
    pub(super) fn check_force(&self, e: usize, f: &[f64]) -> Result<(), BeamError> {
        if f.iter().all(|v| v.is_finite()) {
            return Ok(());
        }
        Err(BeamError::NonFinite {
            element: e,
            x: (e as f64 + 0.5) * self.element_length,
            quantity: "elastic force",
        })
    }

    /// Tangent of element `e` alone at coordinates `q` from the initial state with every wire
    /// sticking ([`Tangent::AllStick`], as the stable step reads it; for the stable-step bound).
    #[cfg(test)]
    pub(crate) fn element_tangent(&self, e: usize, q: &[f64]) -> Result<DMatrix<f64>, BeamError> {
        let rule = &self.rules[e];
        let ws = self.state_per_point();
        let p0: usize = self.rules[..e].iter().map(|r| r.bend.len()).sum();
        let slip = self.initial_state()[p0 * ws..(p0 + rule.bend.len()) * ws].to_vec();
        let mut trial = slip.clone();
        let means = self.other_means(q, e)?;
        let m = &means;
        Ok(match self.spec.element {
            ElementKind::Planar => {
                let mut k = PlanarMatrix::zeros();
                let qe = self.planar_coords(q, e);
                let tangent = Some((&mut k, Tangent::AllStick));
                self.planar_forces(e, rule, &qe, m, &slip, &mut trial, tangent, None, true)?;
                DMatrix::from_column_slice(8, 8, k.as_slice())
            }
            ElementKind::Spatial => {
                let mut k = SpatialMatrix::zeros();
                let qe = self.spatial_coords(q, e);
                let tangent = Some((&mut k, Tangent::AllStick));
                self.element_spatial(e, rule, &qe, m, &slip, &mut trial, tangent, None, true)?;
                DMatrix::from_column_slice(12, 12, k.as_slice())
            }
        })
    }
}
