//! The equivalent strand beam: a mesh of cable elements, planar (4 coordinates per node) or
//! spatial (6, eq. (24)), carrying a section law, with supports eliminated, its constant mass
//! matrix (eq. (44)), gravity load (eq. (45)) and the assembly of the generalized elastic
//! forces (eq. (28)) and their analytic tangent.
//!
//! Modules, one job each:
//! * `quadrature`: the axial, hourglass and bending integration points of an element;
//! * `supports`: which coordinates the supports hold, the free coordinates' numbering, and
//!   the prescribed motion of a supported end;
//! * `inertia`: the constant mass matrix (eq. (44)) of the free coordinates and its coupling
//!   to the coordinates a moving support holds;
//! * `loads`: the generalized force of gravity (eq. (45)) and of point forces;
//! * `state`: the per-point state solvers commit (slip state, section frames);
//! * `assembly`: the global elastic force and tangent from the element contributions;
//! * `strain_recovery`: the strain the section law reads, from the element means;
//! * `planar_element`, `spatial_element`: one element's forces and tangent;
//! * `sampling`: position, slope, strain and curvature at any material coordinate.
//!
//! # Quadrature
//!
//! * Axial term: 2 Gauss points per element (reduced). A cubic cable element cannot bend into
//!   an arc without stretching; fully integrated, that parasitic strain stiffens thin strands
//!   (membrane locking: EA l^2 / EI is of order 10^3-10^7 here). With 3 points the tip error
//!   of the q L^3/EI = 5 elastica at 16 elements and EA L^2/EI = 1e7 is 3.9e-4 L (order 2.5);
//!   with 2 points it is 1.2e-6 L (order 3.5) (`tests/statics.rs`). The one zero-energy mode
//!   that two points leave is held by a weak penalty ([`HOURGLASS`]). The strain the section
//!   law reads for the wires' friction limits is recovered from the element means (module
//!   `strain_recovery`): the line through the two points carries EA times the element's
//!   parasitic stretch.
//! * Bending term: the wire phases turn once per pitch P, and each wire switches between stick
//!   and slip inside an element longer than P/2, so the default rule follows the pitch: one
//!   Gauss point per quarter pitch, `max(4, ceil(4 l / P))` per element (elements longer than
//!   10 quarter pitches are split into equal parts of at most 10 points). Against a rule of 3
//!   points per quarter pitch (three times the points) it moves the static tip of the
//!   section-3 strand (g = 12, 30 elements) by 1.5e-7 m and that of the Table 1 strand (g = 8)
//!   by 5e-6 / 5e-6 / 4e-7 m at 4 / 8 / 16 elements, below 1 % of the elements' own error
//!   there (4.7e-3 / 7.3e-4 / 8.1e-5 m); 4 points at 4 elements (2.3 pitches each) were 1.6e-4
//!   m off. At most [`MAX_BENDING_POINTS`] per element. Laws without wires use 4 Gauss points.
//!   A scene can ask for n Gauss points instead.

mod assembly;
mod inertia;
mod loads;
mod planar_element;
mod quadrature;
mod sampling;
mod spatial_element;
mod state;
mod strain_recovery;
mod supports;

use nalgebra::{DMatrix, Vector3};
use strand_core::SectionLaw;

use crate::band::BandMatrix;
use crate::error::AncfError;
use crate::mass::VectorMass;
use crate::planar::PlanarCoords;
use crate::spatial::{SectionFrame, SpatialCoords, default_phase_reference};

pub use loads::PointLoad;
pub(crate) use quadrature::{BendPoint, ElementRule};
pub use quadrature::{MAX_BENDING_POINTS, pitch_rule_points, points_per_quarter_pitch};
pub use sampling::SectionSample;
pub use supports::SupportMotion;

/// Round-off of the axial strains of an element with coordinates `q` (`dim` components per
/// position or slope): `|r'| - 1` from `r' = sum_k S_k' q_k` carries about `eps_mach sum_k
/// |S_k'| |q_k|`, far more than `eps_mach` where the positions are far from the origin. In
/// space `|q_k|` is the Euclidean length of the position or slope, which a rotation of the
/// axes leaves unchanged (the strain is read as zero below a multiple of this, so a scene and
/// its rotation must agree on it); the planar element, whose plane is fixed, sums the
/// components' magnitudes.
pub(crate) fn strain_round_off(rule: &ElementRule, q: &[f64], dim: usize) -> f64 {
    let size = |v: &[f64]| -> f64 {
        if dim == 3 {
            v.iter().map(|x| x * x).sum::<f64>().sqrt()
        } else {
            v.iter().map(|x| x.abs()).sum::<f64>()
        }
    };
    let largest = rule
        .axial
        .iter()
        .map(|ap| {
            ap.row
                .ds
                .iter()
                .zip(q.chunks_exact(dim))
                .map(|(d, v)| d.abs() * size(v))
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    f64::EPSILON * largest
}

/// Strains within this many times their round-off ([`strain_round_off`]) are zero to the
/// section law.
const STRAIN_ROUND_OFF: f64 = 64.0;

/// The strain the section law reads at a bending point: the assumed strain `eps`, or zero
/// within [`STRAIN_ROUND_OFF`] times its round-off `round_off`. Only tension presses the wires
/// on the core, so the friction limits follow the strain; a strand under a tiny transverse
/// load has a tension of the order of the load squared, below that round-off, and friction
/// limits taken from round-off would make its wires stick or slip at random (Newton then
/// stalls; the stiffness without tension is `K_min`). The axial force keeps the strain as
/// computed.
pub(crate) fn law_strain(eps: f64, round_off: f64) -> f64 {
    if eps.abs() <= STRAIN_ROUND_OFF * round_off {
        0.0
    } else {
        eps
    }
}

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
    /// Bending points per element (one Gauss rule, or equal Gauss rules on equal parts of the
    /// element beyond [`crate::shape::MAX_GAUSS_POINTS`]); `None` for the pitch rule.
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
    /// Direction of phase zero at x = 0 (projected off `direction`); `None` for
    /// [`default_phase_reference`]. A planar beam measures phases from Z.
    pub phase_reference: Option<[f64; 3]>,
    /// Constant point forces.
    pub point_loads: Vec<PointLoad>,
    /// Prescribed displacement of the support at x = 0 (which must exist).
    pub start_motion: Option<SupportMotion>,
    /// Prescribed displacement of the support at x = L (which must exist).
    pub end_motion: Option<SupportMotion>,
}

impl Default for BeamSpec {
    /// One planar element of 1 kg/m along +X, no bending-point override, no loads, no
    /// supports: fill in what a beam needs with `..BeamSpec::default()`.
    fn default() -> Self {
        BeamSpec {
            elements: 1,
            bending_points: None,
            mass_per_length: 1.0,
            element: ElementKind::Planar,
            direction: [1.0, 0.0, 0.0],
            gravity: [0.0; 3],
            start: None,
            end: None,
            phase_reference: None,
            point_loads: Vec::new(),
            start_motion: None,
            end_motion: None,
        }
    }
}

/// Which tangent [`Beam::internal_with`] assembles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tangent {
    /// `dQ_e/dq` of each element with the neighbouring elements' mean strains, which enter the
    /// strain the section law reads (module `strain_recovery`), held fixed: that coupling would
    /// not fit in the band. Exact where the moment does not depend on the strain (the
    /// `constant` law, a strand without tension); otherwise the Jacobian of the forces the
    /// solvers balance differs from it by that coupling alone (`tests/tangent.rs` bounds the
    /// modified Newton contraction it costs). Not symmetric where the moment depends on the
    /// axial strain (the friction limits of the stick/slip laws) or, in space, on the
    /// curvature's direction.
    FrozenMeans,
    /// An iteration matrix for modified Newton, symmetric (factorized as LDL^T, a third
    /// cheaper than LU to factorize and half to solve with): [`Tangent::FrozenMeans`] without the
    /// moment's dependence on the strain and, in space, without the law's coupling of the two
    /// bending directions; for the planar element only its material part, each section
    /// stiffness on the outer product of its strain's gradient (`EA` at the axial points,
    /// `dM/dkappa` at the bending points, the hourglass penalty), which the force evaluation
    /// builds at a few flops per point. The geometric terms it leaves out (the resultants
    /// times the strains' second derivatives) are of the relative size of the strain and of
    /// the curvature times the element length. The forces are exact, so a Newton iteration on
    /// it converges to the same state.
    Iteration {
        /// Planar element: the share of their stick stiffness given to slipping wires, in
        /// [0, 1] (0: the law's tangent). A wire of the `hysteretic` law that slips re-sticks
        /// with its full stick stiffness when its strain turns back, so a share of it keeps
        /// Newton from overshooting where that happens.
        unloading: f64,
    },
    /// The tangent with every wire sticking, whatever its state (and, in space, with the
    /// planar stick stiffness in both bending directions): at the straight, unstrained
    /// reference the stiffest the strand can be, for the explicit scheme's stable step.
    AllStick,
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

/// State of the section at one bending point after an evaluation (for output and the
/// energy bookkeeping).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointState {
    /// Material coordinate (m).
    pub x: f64,
    /// Axial strain the section law reads (module `strain_recovery`): EA times it is the
    /// tension of `centerline.csv`.
    pub eps: f64,
    /// Curvature `kappa_z` (1/m): the signed curvature of a planar element.
    pub kappa: f64,
    /// Curvature `kappa_y` (1/m): zero for a planar element.
    pub kappa_y: f64,
    /// Bending moment (N m).
    pub moment: f64,
    /// d(stored energy)/d eps at fixed curvature (J/m), see `SectionResponse::energy_strain`.
    pub energy_strain: f64,
    /// The stored energy's change with the bending direction through the friction limits
    /// `(y, z)` (N m), see `SectionResponse::energy_turn`; zero for the planar element.
    pub energy_turn: [f64; 2],
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

/// A discretized strand beam (planar or spatial elements).
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
    /// Gravity and point forces (see [`Beam::gravity_force`]).
    gravity_force: Vec<f64>,
    mass: BandMatrix,
    /// Moving supports: the global position coordinates they hold, with the motion and the
    /// component each follows.
    moving: Vec<(usize, usize, usize)>,
    /// The motions of the start and end supports.
    motions: [Option<SupportMotion>; 2],
    /// Mass entries `(row, column, m)` coupling any coordinate (row) to a coordinate a moving
    /// support holds (column).
    held_mass: Vec<(usize, usize, f64)>,
    vector_mass: VectorMass,
    /// Coordinates per node.
    nd: usize,
    /// Initial section frame of every bending point (spatial element).
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
        let setup = |source| BeamError::Kinematics { element: 0, source };
        let reference = spec.phase_reference.map(Vector3::from);
        let (nd, frame) = match spec.element {
            ElementKind::Planar => {
                if d.z != 0.0 || spec.gravity[2] != 0.0 {
                    return Err(BeamError::Setup(
                        "a planar beam needs its direction and gravity in the XY plane".into(),
                    ));
                }
                if let Some(r) = reference {
                    let f = SectionFrame::new(d, r).map_err(setup)?;
                    if (f.e_z0() - Vector3::z()).norm() > 1e-12 {
                        return Err(BeamError::Setup(
                            "a planar beam measures the wire phases from Z: its phase \
                             reference must project onto +Z"
                                .into(),
                        ));
                    }
                }
                (4, None)
            }
            ElementKind::Spatial => {
                let r = reference.unwrap_or_else(|| default_phase_reference(&d));
                (6, Some(SectionFrame::new(d, r).map_err(setup)?))
            }
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
        let (free_index, n_free) = supports::free_coordinates(&spec, nd);
        let rules = (0..n)
            .map(|e| quadrature::element_rule(&law, &spec, e, l))
            .collect::<Result<Vec<_>, _>>()?;
        let mass = inertia::free_mass(&spec, nd, l, &free_index, n_free);
        let gravity_force = loads::dead_load(&spec, nd, l)?;
        let motions = [spec.start_motion.clone(), spec.end_motion.clone()];
        let moving = supports::moving_coordinates(&spec, nd)?;
        let held_mass = inertia::held_mass(&spec, nd, l, &moving);
        let vector_mass = VectorMass::from_band(&mass, dim);
        Ok(Beam {
            spec,
            law,
            length,
            element_length: l,
            vector_mass,
            free_span: supports::free_span(&free_index, n_free),
            free_index,
            n_free,
            rules,
            q_ref,
            gravity_force,
            mass,
            moving,
            motions,
            held_mass,
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
    /// Generalized dead load, all coordinates (N): gravity and the point forces, whose
    /// potential `-Q . (q - q_0)` the energy ledger books as gravity.
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
        inertia::element_mass(
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
    pub(crate) fn planar_coords(&self, q: &[f64], e: usize) -> PlanarCoords {
        PlanarCoords::from_column_slice(&q[e * 4..e * 4 + 8])
    }

    pub(crate) fn spatial_coords(&self, q: &[f64], e: usize) -> SpatialCoords {
        SpatialCoords::from_column_slice(&q[e * 6..e * 6 + 12])
    }
}
