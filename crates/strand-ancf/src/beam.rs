//! The equivalent strand beam: a mesh of cable elements, planar (4 coordinates per node) or
//! spatial (6, eq. (24)), carrying a section law, with supports eliminated, its constant mass matrix (eq. (44)), gravity load (eq. (45)) and the
//! assembly of the generalized elastic forces (eq. (28)) and their analytic tangent.
//!
//! # Quadrature
//!
//! * Axial term: 2 Gauss points per element (reduced). A cubic cable element cannot bend into
//!   an arc without stretching; fully integrated, that parasitic strain stiffens thin strands
//!   (membrane locking: EA l^2 / EI is of order 10^3-10^7 here). With 3 points the tip error
//!   of the q L^3/EI = 5 elastica at 16 elements and EA L^2/EI = 1e7 is 3.9e-4 L (order 2.5);
//!   with 2 points it is 1.2e-6 L (order 3.5) (`tests/statics.rs`). The strain used by the
//!   section law for the wire tension is the assumed field `eps_bar`, linear through the two
//!   axial points, so the friction limits see the strand's tension, not the parasitic strain.
//!   The one zero-energy mode that two points leave is held by a weak penalty ([`HOURGLASS`]).
//! * Bending term: the wire phases turn once per pitch P, and each wire switches between stick
//!   and slip inside an element longer than P/2, so the default rule is composite: 3 Gauss points
//!   on each of `ceil(4 l / P)` equal sub-intervals (a sub-interval spans at most a quarter
//!   pitch). Laws without wires use 4 Gauss points. A scene can ask for n Gauss points instead.

use nalgebra::{DMatrix, Vector2, Vector3, Vector4};
use strand_core::{PlanarResponse, SectionLaw, Station};

use crate::band::BandMatrix;
use crate::error::{AncfError, check_stretch};
use crate::load::{planar_gravity, spatial_gravity};
use crate::mass::{VectorMass, planar_mass, spatial_mass};
use crate::planar::{self, PlanarAxial, PlanarCoords, PlanarMatrix, PlanarPoint, PlanarVector};
use crate::scatter;
use crate::shape::{QuadraturePoint, ShapeRow, element_quadrature, gauss_legendre};
use crate::spatial::{
    self, SectionFrame, SpatialCoords, SpatialMatrix, SpatialPoint, SpatialSection, SpatialVector,
};

/// Which cable element a beam uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementKind {
    /// Planar element in the XY plane: (r_x, r_y, r'_x, r'_y) per node.
    Planar,
    /// Spatial element: (r, r') per node (eq. (24)); curvature components in the section
    /// frame carried by the minimal rotation from the straight strand's frame.
    Spatial,
}

/// How an end of the beam is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Support {
    /// Position and slope fixed.
    Clamped,
    /// Position fixed.
    Pinned,
}

/// What a beam is built from (besides its section law).
#[derive(Debug, Clone, PartialEq)]
pub struct BeamSpec {
    /// Number of elements.
    pub elements: usize,
    /// Gauss points per element for the bending term; `None` for the pitch rule.
    pub bending_points: Option<usize>,
    /// Mass per length (kg/m).
    pub mass_per_length: f64,
    /// Element kind.
    pub element: ElementKind,
    /// Unit direction of the straight initial strand (in the XY plane for planar elements).
    pub direction: [f64; 3],
    /// Gravitational acceleration (m/s^2; in the XY plane for planar elements).
    pub gravity: [f64; 3],
    /// Support at x = 0.
    pub start: Option<Support>,
    /// Support at x = L.
    pub end: Option<Support>,
}

/// Errors of building or evaluating a beam.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BeamError {
    /// Kinematics failed in an element.
    #[error("element {element}: {source}")]
    Kinematics {
        /// 0-based element index.
        element: usize,
        /// What failed.
        source: AncfError,
    },
    /// A non-finite value appeared.
    #[error("non-finite {quantity} in element {element} at x = {x} m")]
    NonFinite {
        /// 0-based element index.
        element: usize,
        /// Material coordinate (m).
        x: f64,
        /// Which quantity.
        quantity: &'static str,
    },
    /// Invalid set-up.
    #[error("{0}")]
    Setup(String),
}

/// One bending integration point.
#[derive(Debug, Clone)]
pub(crate) struct BendPoint {
    pub qp: QuadraturePoint,
    pub station: Station,
    /// Lagrange weights of the axial points at this point (assumed strain).
    pub interp: [f64; AXIAL_POINTS],
}

/// Quadrature of one element (all elements have the same length but different stations).
#[derive(Debug, Clone)]
pub(crate) struct ElementRule {
    pub axial: Vec<QuadraturePoint>,
    /// Shape row at the element midpoint (hourglass stabilization).
    pub mid: ShapeRow,
    pub bend: Vec<BendPoint>,
}

/// State of the section at one bending point after an evaluation (for output and the
/// energy bookkeeping).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointState {
    /// Material coordinate (m).
    pub x: f64,
    /// Assumed axial strain.
    pub eps: f64,
    /// Curvature `kappa_z` (1/m): the signed curvature of a planar element.
    pub kappa: f64,
    /// Curvature `kappa_y` (1/m): zero for a planar element.
    pub kappa_y: f64,
    /// Bending moment (N m).
    pub moment: f64,
    /// d(stored energy)/d eps at fixed curvature (J/m), see `SectionResponse::energy_strain`.
    pub energy_strain: f64,
    /// Quadrature weight (m).
    pub weight: f64,
    /// Number of slipping wires.
    pub slipping: usize,
}

/// Sums of an evaluation of the internal forces.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Evaluation {
    /// Stored elastic energy (J).
    pub energy: f64,
    /// Work dissipated by slip from the committed state (J; hysteretic law).
    pub slip_work: f64,
    /// Slipping wire-points.
    pub slipping: usize,
}

/// A discretized planar strand beam.
#[derive(Debug, Clone)]
pub struct Beam {
    spec: BeamSpec,
    law: SectionLaw,
    length: f64,
    element_length: f64,
    /// Free-coordinate index of each global coordinate.
    free_index: Vec<Option<usize>>,
    n_free: usize,
    /// The global coordinates of the free ones when they are contiguous (no pinned end at
    /// x = L, whose fixed position sits between free coordinates).
    free_span: Option<std::ops::Range<usize>>,
    rules: Vec<ElementRule>,
    q_ref: Vec<f64>,
    gravity_force: Vec<f64>,
    mass: BandMatrix,
    vector_mass: VectorMass,
    wires: usize,
    /// Coordinates per node.
    nd: usize,
    /// Section frame of the straight strand (spatial element).
    frame: Option<SectionFrame>,
}

/// Gauss points of the reduced axial quadrature.
pub const AXIAL_POINTS: usize = 2;

/// Weight of the hourglass stabilization, relative to EA l. Two axial points leave one
/// zero-energy mode per beam: a uniform change of the nodal slope lengths makes a strain
/// shaped like the Legendre P2 that vanishes at both points (singular statics unless a clamp
/// fixes a slope). A penalty `1/2 HOURGLASS EA l (eps(l/2) - eps_bar(l/2))^2` on the
/// midpoint strain's departure from the assumed field gives it stiffness; it is small enough
/// not to bring membrane locking back (`tests/statics.rs`).
pub const HOURGLASS: f64 = 1e-6;

impl Beam {
    /// Builds the beam of `spec` with section law `law` (its strand gives the length).
    pub fn new(spec: BeamSpec, law: SectionLaw) -> Result<Beam, BeamError> {
        let n = spec.elements;
        if n == 0 {
            return Err(BeamError::Setup("a beam needs at least one element".into()));
        }
        let length = law.strand().length();
        let l = length / n as f64;
        let d = Vector3::from(spec.direction);
        if (d.norm() - 1.0).abs() > 1e-12 {
            return Err(BeamError::Setup("direction must be a unit vector".into()));
        }
        let (nd, frame) = match spec.element {
            ElementKind::Planar => {
                if d.z != 0.0 || spec.gravity[2] != 0.0 {
                    return Err(BeamError::Setup(
                        "a planar beam needs its direction and gravity in the XY plane".into(),
                    ));
                }
                (4, None)
            }
            ElementKind::Spatial => (
                6,
                Some(
                    SectionFrame::along(d)
                        .map_err(|source| BeamError::Kinematics { element: 0, source })?,
                ),
            ),
        };
        let dim = nd / 2;
        let n_glob = (n + 1) * nd;
        let mut q_ref = vec![0.0; n_glob];
        for j in 0..=n {
            let x = j as f64 * l;
            for c in 0..dim {
                q_ref[j * nd + c] = x * d[c];
                q_ref[j * nd + dim + c] = d[c];
            }
        }
        let mut fixed = vec![false; n_glob];
        for (node, s) in [(0, spec.start), (n, spec.end)] {
            let count = match s {
                None => 0,
                Some(Support::Pinned) => dim,
                Some(Support::Clamped) => nd,
            };
            for k in 0..count {
                fixed[node * nd + k] = true;
            }
        }
        let mut free_index = vec![None; n_glob];
        let mut n_free = 0;
        for (g, f) in fixed.iter().enumerate() {
            if !f {
                free_index[g] = Some(n_free);
                n_free += 1;
            }
        }
        let wires = law.sliders();
        let rules = (0..n)
            .map(|e| element_rule(&law, &spec, e, l))
            .collect::<Result<Vec<_>, _>>()?;

        // Mass (free block) and gravity.
        let band = 2 * nd - 1;
        let mut mass = BandMatrix::zeros(n_free, band, band);
        let me = element_mass(spec.element, spec.mass_per_length, l);
        let fe: Vec<f64> = match spec.element {
            ElementKind::Planar => {
                let g = Vector2::new(spec.gravity[0], spec.gravity[1]);
                planar_gravity(spec.mass_per_length, &g, l)
                    .as_slice()
                    .to_vec()
            }
            ElementKind::Spatial => {
                let g = Vector3::from(spec.gravity);
                spatial_gravity(spec.mass_per_length, &g, l)
                    .as_slice()
                    .to_vec()
            }
        };
        let mut gravity_force = vec![0.0; n_glob];
        for e in 0..n {
            for a in 0..2 * nd {
                let ga = e * nd + a;
                gravity_force[ga] += fe[a];
                let Some(ia) = free_index[ga] else { continue };
                for b in 0..2 * nd {
                    if let Some(ib) = free_index[e * nd + b] {
                        mass.add(ia, ib, me[(a, b)]);
                    }
                }
            }
        }
        let vector_mass = VectorMass::from_band(&mass, dim);
        Ok(Beam {
            spec,
            law,
            length,
            element_length: l,
            vector_mass,
            free_span: free_span(&free_index, n_free),
            free_index,
            n_free,
            rules,
            q_ref,
            gravity_force,
            mass,
            wires,
            nd,
            frame,
        })
    }

    /// The spec the beam was built from.
    pub fn spec(&self) -> &BeamSpec {
        &self.spec
    }
    /// The section law.
    pub fn law(&self) -> &SectionLaw {
        &self.law
    }
    /// Strand length (m).
    pub fn length(&self) -> f64 {
        self.length
    }
    /// Element length (m).
    pub fn element_length(&self) -> f64 {
        self.element_length
    }
    /// Number of global coordinates.
    pub fn coords(&self) -> usize {
        self.q_ref.len()
    }
    /// Number of free coordinates (degrees of freedom).
    pub fn dofs(&self) -> usize {
        self.n_free
    }
    /// The global coordinates of the free ones, `g0..g0 + dofs()`, when they are contiguous:
    /// free index `i` is then global coordinate `g0 + i`.
    pub fn free_span(&self) -> Option<std::ops::Range<usize>> {
        self.free_span.clone()
    }
    /// Free index of global coordinate `g`, if free.
    pub fn free_index(&self, g: usize) -> Option<usize> {
        self.free_index[g]
    }
    /// The straight reference configuration.
    pub fn reference(&self) -> &[f64] {
        &self.q_ref
    }
    /// Generalized gravity force, all coordinates (N).
    pub fn gravity_force(&self) -> &[f64] {
        &self.gravity_force
    }
    /// Mass matrix of the free coordinates (kg).
    pub fn mass(&self) -> &BandMatrix {
        &self.mass
    }
    /// The same mass matrix in Kronecker form, for fast products.
    pub fn vector_mass(&self) -> &VectorMass {
        &self.vector_mass
    }
    /// Half-bandwidth of the free system.
    pub fn bandwidth(&self) -> usize {
        2 * self.nd - 1
    }
    /// Coordinates per node: 4 (planar) or 6 (spatial).
    pub fn node_coords(&self) -> usize {
        self.nd
    }
    /// Consistent mass matrix of one element (eq. (44)).
    pub fn element_mass(&self) -> DMatrix<f64> {
        element_mass(
            self.spec.element,
            self.spec.mass_per_length,
            self.element_length,
        )
    }
    /// Bending points per element.
    pub fn bending_points(&self) -> usize {
        self.rules[0].bend.len()
    }
    /// Total bending points.
    pub fn points(&self) -> usize {
        self.rules.iter().map(|r| r.bend.len()).sum()
    }
    /// Slip state values per bending point: one per wire for a law with state, else none.
    fn state_per_point(&self) -> usize {
        if self.law.kind().has_state() {
            self.wires
        } else {
            0
        }
    }
    /// Length of the law's state vector for the whole beam.
    pub fn state_len(&self) -> usize {
        self.points() * self.state_per_point()
    }

    fn planar_coords(&self, q: &[f64], e: usize) -> PlanarCoords {
        PlanarCoords::from_column_slice(&q[e * 4..e * 4 + 8])
    }

    fn spatial_coords(&self, q: &[f64], e: usize) -> SpatialCoords {
        SpatialCoords::from_column_slice(&q[e * 6..e * 6 + 12])
    }

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

    /// Evaluates the generalized elastic forces `Q_e` (eq. (28)) into `force` (all
    /// coordinates, overwritten) and, if given, the tangent `dQ_e/dq` of the free coordinates
    /// into `tangent` (overwritten). `slip`/`trial` are the law's committed and trial state
    /// ([`Self::state_len`]); `points`, if given, receives the state at every bending point.
    pub fn internal(
        &self,
        q: &[f64],
        slip: &[f64],
        trial: &mut [f64],
        force: &mut [f64],
        mut tangent: Option<&mut BandMatrix>,
        mut points: Option<&mut [PointState]>,
    ) -> Result<Evaluation, BeamError> {
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
            let (ke, ev, sym): (&[f64], Evaluation, bool) = match self.spec.element {
                ElementKind::Planar => {
                    let qe = self.planar_coords(q, e);
                    let (f, ev, sym) = if want_k {
                        self.element_planar(e, rule, &qe, sl, tr, Some(&mut kp), pts)?
                    } else {
                        let (f, ev) = self.planar_forces(e, rule, &qe, sl, tr, pts)?;
                        (f, ev, true)
                    };
                    for a in 0..8 {
                        force[e * nd + a] += f[a];
                    }
                    (kp.as_slice(), ev, sym)
                }
                ElementKind::Spatial => {
                    let qe = self.spatial_coords(q, e);
                    let (f, ev, sym) =
                        self.element_spatial(e, rule, &qe, sl, tr, want_k.then_some(&mut ks), pts)?;
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
    fn check_force(&self, e: usize, f: &[f64]) -> Result<(), BeamError> {
        if f.iter().all(|v| v.is_finite()) {
            return Ok(());
        }
        Err(BeamError::NonFinite {
            element: e,
            x: (e as f64 + 0.5) * self.element_length,
            quantity: "elastic force",
        })
    }

    /// Tangent of element `e` alone at coordinates `q`, from a state without slip (for the
    /// stable-step bound).
    #[cfg(test)]
    pub(crate) fn element_tangent(&self, e: usize, q: &[f64]) -> Result<DMatrix<f64>, BeamError> {
        let rule = &self.rules[e];
        let ws = self.state_per_point();
        let slip = vec![0.0; rule.bend.len() * ws];
        let mut trial = slip.clone();
        Ok(match self.spec.element {
            ElementKind::Planar => {
                let mut k = PlanarMatrix::zeros();
                let qe = self.planar_coords(q, e);
                self.element_planar(e, rule, &qe, &slip, &mut trial, Some(&mut k), None)?;
                DMatrix::from_column_slice(8, 8, k.as_slice())
            }
            ElementKind::Spatial => {
                let mut k = SpatialMatrix::zeros();
                let qe = self.spatial_coords(q, e);
                self.element_spatial(e, rule, &qe, &slip, &mut trial, Some(&mut k), None)?;
                DMatrix::from_column_slice(12, 12, k.as_slice())
            }
        })
    }

    /// Forces (and tangent) of one planar element. The symmetric part of the tangent is built
    /// on and below the diagonal and mirrored; the coupling `d M / d eps` (the only
    /// non-symmetric term) is added after.
    #[allow(clippy::too_many_arguments)]
    fn element_planar(
        &self,
        e: usize,
        rule: &ElementRule,
        qe: &PlanarCoords,
        slip: &[f64],
        trial: &mut [f64],
        mut tangent: Option<&mut PlanarMatrix>,
        mut points: Option<&mut [PointState]>,
    ) -> Result<(PlanarVector, Evaluation, bool), BeamError> {
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
        for (i, bp) in rule.bend.iter().enumerate() {
            let eps: f64 = (0..AXIAL_POINTS).map(|j| bp.interp[j] * eps_a[j]).sum();
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
                if r.moment_strain != 0.0 {
                    // d M / d eps_bar couples the curvature here to the axial points:
                    // w M_eps kappa_q eps_bar_q^T with eps_bar_q = sum_j interp_j eps_q[j].
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
}

impl Beam {
    /// Forces of one planar element without the tangent: the quantities of
    /// [`Beam::element_planar`] with only what the forces need. Per point only `r'` (axial
    /// points) or `r'` and `r''` (bending points) are formed, and the hourglass term's strain
    /// gradients are folded into the scatter of each point's own force, so every point is
    /// mapped to the element coordinates once. This is the evaluation of every Newton
    /// iteration that keeps its matrix and of every explicit step.
    fn planar_forces(
        &self,
        e: usize,
        rule: &ElementRule,
        qe: &PlanarCoords,
        slip: &[f64],
        trial: &mut [f64],
        mut points: Option<&mut [PointState]>,
    ) -> Result<(PlanarVector, Evaluation), BeamError> {
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
        }
        let ws = self.state_per_point();
        let linear = self.law.is_linear();
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
            let eps: f64 = (0..AXIAL_POINTS).map(|j| bp.interp[j] * eps_a[j]).sum();
            // Empty for a law without state (ws = 0).
            let (sl, tr) = (
                &slip[i * ws..(i + 1) * ws],
                &mut trial[i * ws..(i + 1) * ws],
            );
            let r = if linear {
                self.law.planar_linear(eps, kappa)
            } else {
                self.law.planar(&bp.station, eps, kappa, sl, tr)
            };
            let point = points.as_deref_mut().map(|p| &mut p[i]);
            book_planar_point(e, bp, eps, kappa, ea, &r, &mut ev, point)?;
            let wm = bp.qp.weight * r.moment;
            let row = &bp.qp.row;
            for k in 0..4 {
                let (c1, c2) = (wm * row.ds[k], wm * row.dds[k]);
                f[2 * k] += c1 * ka[0] + c2 * kb[0];
                f[2 * k + 1] += c1 * ka[1] + c2 * kb[1];
            }
        }
        self.check_force(e, f.as_slice())?;
        Ok((PlanarVector::from(f), ev))
    }
}

/// Books the section response `r` of planar bending point `bp` (element `e`): checks that
/// it is finite, adds its stored energy beyond the axial part, slip work and slipping wires to
/// `ev`, and records its state in `point`, if given. Shared by both planar element paths.
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
        return Err(BeamError::NonFinite {
            element: e,
            x: bp.station.x,
            quantity: "bending moment",
        });
    }
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
            weight: w,
            slipping: r.slipping,
        };
    }
    Ok(())
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

impl Beam {
    /// Forces (and tangent) of one spatial element: as [`Beam::element_planar`] with the
    /// curvature vector `(kappa_y, kappa_z)` in the carried section frame and the vector form
    /// of the section law.
    #[allow(clippy::too_many_arguments)]
    fn element_spatial(
        &self,
        e: usize,
        rule: &ElementRule,
        qe: &SpatialCoords,
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
            let eps: f64 = (0..AXIAL_POINTS).map(|j| bp.interp[j] * eps_a[j]).sum();
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

/// `g0..g0 + n_free` if the free coordinates are exactly those (see [`Beam::free_span`]).
fn free_span(free_index: &[Option<usize>], n_free: usize) -> Option<std::ops::Range<usize>> {
    let g0 = free_index.iter().position(|f| f.is_some())?;
    let span = g0..g0 + n_free;
    free_index
        .iter()
        .enumerate()
        .all(|(g, f)| *f == span.contains(&g).then(|| g - g0))
        .then_some(span)
}

/// Consistent mass matrix of one element of `kind` (eq. (44)).
fn element_mass(kind: ElementKind, mu: f64, l: f64) -> DMatrix<f64> {
    match kind {
        ElementKind::Planar => DMatrix::from_column_slice(8, 8, planar_mass(mu, l).as_slice()),
        ElementKind::Spatial => DMatrix::from_column_slice(12, 12, spatial_mass(mu, l).as_slice()),
    }
}

/// Bending integration points of element `e`: the pitch rule or the scene's Gauss rule.
fn element_rule(
    law: &SectionLaw,
    spec: &BeamSpec,
    e: usize,
    l: f64,
) -> Result<ElementRule, BeamError> {
    let setup = |source| BeamError::Kinematics { element: e, source };
    let axial = element_quadrature(l, AXIAL_POINTS).map_err(setup)?;
    let x0 = e as f64 * l;
    let mut pts: Vec<(f64, f64)> = Vec::new();
    match (spec.bending_points, law.strand().layer()) {
        (Some(n), _) => {
            let rule = gauss_legendre(n).map_err(setup)?;
            pts.extend(rule.on_interval(0.0, l));
        }
        (None, Some(layer)) if law.sliders() > 0 => {
            let sub = ((4.0 * l / layer.pitch).ceil() as usize).max(1);
            let rule = gauss_legendre(3).map_err(setup)?;
            let h = l / sub as f64;
            for k in 0..sub {
                pts.extend(rule.on_interval(k as f64 * h, (k + 1) as f64 * h));
            }
        }
        _ => {
            let rule = gauss_legendre(4).map_err(setup)?;
            pts.extend(rule.on_interval(0.0, l));
        }
    }
    let xa: Vec<f64> = axial.iter().map(|a| a.row.x).collect();
    let bend = pts
        .into_iter()
        .map(|(x, weight)| {
            // Lagrange polynomial through the axial points.
            let interp = std::array::from_fn(|j| {
                (0..AXIAL_POINTS)
                    .filter(|&k| k != j)
                    .map(|k| (x - xa[k]) / (xa[j] - xa[k]))
                    .product()
            });
            BendPoint {
                qp: QuadraturePoint {
                    weight,
                    row: ShapeRow::new(x, l),
                },
                station: law.station(x0 + x),
                interp,
            }
        })
        .collect();
    Ok(ElementRule {
        axial,
        mid: ShapeRow::new(0.5 * l, l),
        bend,
    })
}
