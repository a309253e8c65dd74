//! Section laws of the equivalent beam (SPEC 2; paper sections 1.2, 1.3).
//!
//! A [`SectionLaw`] maps the axial strain `eps`, the bending curvature and the material
//! coordinate `x` to the axial force, the bending moment, their tangents and the stored energy
//! density. Four laws share one implementation ([`LawKind`]): the helical wires are friction
//! sliders (module `slider`) whose force laws differ; `constant` has no sliders.
//!
//! # Section frame, curvature vector and wire phases
//!
//! The cross-section carries a right-handed frame (t, y, z) with t the strand tangent. Wire
//! `i` sits at `(y, z) = R_w (sin phi_i, cos phi_i)` (eq. (1)), with `phi_i(x)` from eqs. (36),
//! (37). The curvature vector `kappa = (kappa_y, kappa_z)` holds the bending curvatures about
//! y and z, so the bending strain of a fibre at (y, z) is `z kappa_y - y kappa_z`, and wire `i`
//! has the lever `l_i = R_w (cos phi_i, -sin phi_i)`: its bending strain is `e_i = l_i . kappa`.
//! The wire's slider force `F_i` (module `slider`) acts through the lever vector, so the
//! section moment is `M = K_min kappa + sum_i F_i l_i`. A stuck wire adds `k l_i l_i^T` to the
//! tangent (symmetric, positive); a wire that has slipped keeps its force, and so its moment
//! `F_i l_i`, fixed in the section frame when the bending direction turns, as the wire on the
//! core does. Only the friction limits depend on the bending direction (through each wire's
//! angle from the neutral axis, below). For planar bending (`kappa_y = 0`) the z component is
//! the planar law bit for bit; the y component `sum_i F_i l_iy` is zero while every wire
//! sticks (m >= 3 wires evenly spaced) and otherwise a moment out of the plane of bending that
//! changes sign along the pitch (period pitch/m), with zero mean over a pitch for a strand bent
//! from straight: the planar element leaves it out.
//!
//! A planar scene moves in the global XY plane with z = global Z; the signed planar curvature
//! `kappa = (r' x r'')_Z / |r'|^2` (per reference length) is `kappa_z`. Bending with the convex side toward +y
//! (curvature centre toward -y, `kappa_z < 0`, the paper's hanging cantilever) uses the phases
//! of eq. (36) as they are; bending the other way mirrors them, phi -> -phi (SPEC 2).
//!
//! The friction limit of a wire grows with its angle from the neutral axis through the capstan
//! gain of eq. (20): `exp(mu theta_n sin(alpha)) - 1` for a stretched wire and `1 - exp(-mu
//! theta_n sin(alpha))` for a shortened one (eq. (20) with the sign of the wire's side). The
//! neutral axis is the line along `kappa` (where `e_i = 0`); `theta` is the wire's angle from
//! its reference half `b`, the half with a non-negative z component (the +y half when `kappa_z
//! = 0`), so `theta = |phi|` in planar bending (the SPEC 2 mirror convention). With the default
//! `section.slip_limit`, `papailiou`, `theta_n = min(theta, pi - theta)` is the angle from the
//! nearest neutral-axis crossing, where the slip starts, and the limit is symmetric about the
//! extreme fibre (module `slip_limit`). With `paper`, `theta_n = theta`: the limits of this
//! asymmetric law change sides, and jump, where `kappa_z` changes sign, while the symmetric
//! limit does not depend on the choice of half. When the bending direction turns, a slipping
//! wire's limit turns with it: the tangent holds `l_i (d cap_i / d theta_i) (d theta_i / d
//! kappa)`, and the `continuous` and `paper` laws, whose slip energy depends on the limit,
//! change their stored energy without work of the moment (`SectionResponse::energy_turn`). K_min
//! and the axial stiffness are isotropic.
//!
//! # Bending direction of the friction limits
//!
//! The friction limit of a wire builds up from the neutral axis of the bending that made it
//! slip. Near zero curvature the direction of `kappa` is ill-defined: a tiny out-of-plane
//! curvature turns the neutral axis a long way, and a wire with residual slip from an earlier
//! bending would meet a turned limit it never slipped against (after a layer slipped back, the
//! out-of-plane tangent of the Table 1 strand was -0.52 N m^2 at 0.001 1/m). A curvature too
//! small to slip a wire of a section without residual slip cannot re-orient its limits: below
//! the still curvature ([`SectionLaw::still_curvature`], a lower bound on the first slip in
//! every direction) the `hysteretic` law keeps the direction of the last committed bending
//! beyond it, stored per station after the wires' slips ([`SectionLaw::state_len`]; none
//! stored before the first, where the limits follow `kappa`); beyond it the limits follow
//! `kappa` as above. In planar bending both directions are the z axis, so the planar law is
//! met bit for bit. The laws without state (`continuous`, `paper`) keep turning their limits
//! with `kappa` at every curvature. Where `|kappa|` crosses the still curvature the limits
//! switch from the stored direction to that of `kappa`, a jump for a wire at its limit when the
//! two differ. The alternative of Masing's rule (the direction of the curvature change since the
//! last reversal) has no unique reversal in two dimensions: a rotating curvature reverses at
//! every step by the test `(kappa - kappa_c) . (kappa_c - kappa_r) < 0`.
//!
//! # The pitch-averaged law
//!
//! With `section.pitch_samples` `S >= 2` ([`SectionOptions::pitch_samples`]) a station stands
//! for the whole pitch around it: each wire of a layer of `m` wires and pitch `P` is a slider
//! at each of the `S` phases it takes at `x + (s - (S - 1)/2) P / (m S)`, `s = 0..S`, all at
//! the station's strain and curvature, each with `1 / S` of the wire's spring and friction
//! limit (a slider's force is homogeneous of degree one in both and its slip of degree zero,
//! so a sample is the wire's slider scaled). The layer's `m S` sliders sit at evenly spaced
//! phases, `2 pi / (m S)` apart, and carry their own slip history: under a curvature that does
//! not change along the pitch (every station has seen the same history) the section moment is
//! the resolved law's average over the stations that carry those phases, and tends to its
//! average over the pitch as `S` grows (the midpoint rule of a function of the phase with kinks
//! where wires switch). Where the curvature changes over a pitch every sample sees the
//! point's curvature rather than its own station's: the law is meant for curvatures that
//! change little over a pitch (measured in the manual, Performance). Each layer samples its own pitch; the closed-form layer states
//! of a strand of several layers and every report work on the samples as on wires (a
//! `wires.csv` row is then one phase sample with its share of the wire).

pub mod base_tension;
mod direction;
mod kernels;
mod layer_law;
mod layer_state;
mod options;
pub mod pressure;
mod report;
mod response;
mod slider;
mod slip_limit;
mod slip_work;
mod vector_law;

pub use base_tension::BaseTension;
use base_tension::SofteningTable;
use direction::DIRECTION_STATE;
use kernels::{LayerTally, PlanarWires, continuous_wires, hysteretic_wires};
use layer_law::{LayerLaw, still_per_scale};
use layer_state::LAYER_STATE;
pub use options::SectionOptions;
pub use pressure::{PressureSystem, SlipPressure};
pub use response::{PlanarMoment, PlanarResponse, SectionResponse, WireReport};
pub use slider::WireState;
use slider::{SliderForce, slider};
pub use slip_limit::SlipLimit;
use slip_work::STRAIN_STATE;

/// State values per station between the wires' slips and the layers' closed-form states: the
/// stored bending direction, then the committed strain.
const STATION_TAIL: usize = DIRECTION_STATE + STRAIN_STATE;

use crate::error::InputError;
use crate::geometry::Strand;

/// Which section law a beam uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LawKind {
    /// Stick/slip with the continuous critical curvature kappa_c = M_slip / K_stick (default).
    #[default]
    Continuous,
    /// The paper's eq. (23) critical curvature: the moment drops by cos^2(alpha) at a switch.
    Paper,
    /// Coulomb friction with committed slip state, return mapping and dissipated work.
    Hysteretic,
    /// Constant EI and EA of the envelope cylinder: the traditional beam.
    Constant,
}

impl LawKind {
    /// Name as used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            LawKind::Continuous => "continuous",
            LawKind::Paper => "paper",
            LawKind::Hysteretic => "hysteretic",
            LawKind::Constant => "constant",
        }
    }

    /// Whether the law carries slip state that a solver must commit on accepted steps.
    pub fn has_state(self) -> bool {
        self == LawKind::Hysteretic
    }
}

impl std::fmt::Display for LawKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A section law built for one strand.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionLaw {
    kind: LawKind,
    axial_stiffness: f64,
    base_bending: f64,
    /// K_min's strain dependence (`section.base_tension`); `None`: K_min is `base_bending`.
    softening: Option<Softening>,
    /// The layers' constants, from the core outward (none for `constant` and plain wires).
    layers: Vec<LayerLaw>,
    /// The accumulated-pressure system of the friction limits (`section.slip_pressure`);
    /// `None` where every layer keeps the capstan gain.
    pressure: Option<PressureSystem>,
    /// The layers' wires in all, kept for [`Self::state_len`], which element loops call per
    /// point.
    sliders: usize,
    /// Whether the state holds each layer's closed-form state after the wires' slips and the
    /// bending direction (module `layer_state`): the `hysteretic` law of a strand of several
    /// layers. A 1+m strand keeps the wire loop, and its results bit for bit.
    layer_states: bool,
    strand: Strand,
    options: SectionOptions,
}

/// K_min as a function of the strain (module `base_tension`): the core's part and each
/// layer's share with its tabulated ratio.
#[derive(Debug, Clone, PartialEq)]
struct Softening {
    /// The core's E_c I_c (N m^2).
    core: f64,
    /// Each layer's tension-free share of K_min (N m^2) and its ratio `s(eps)`.
    layers: Vec<(f64, SofteningTable)>,
}

impl Softening {
    fn new(strand: &Strand, options: &SectionOptions) -> Softening {
        let core = strand.core();
        Softening {
            core: core.material.youngs_modulus * core.inertia(),
            layers: strand
                .layers()
                .iter()
                .map(|l| {
                    (
                        strand.layer_min_bending(l, options.base_stiffness),
                        SofteningTable::new(l),
                    )
                })
                .collect(),
        }
    }

    /// K_min (N m^2) and dK_min/deps (N m^2) at the strain `eps`, summed as
    /// `Strand::min_bending_stiffness` sums it (the same bits where every ratio is 1).
    #[inline]
    fn at(&self, eps: f64) -> (f64, f64) {
        self.layers
            .iter()
            .fold((self.core, 0.0), |(k, dk), (kj, table)| {
                let (s, ds) = table.ratio(eps);
                (k + kj * s, dk + kj * ds)
            })
    }
}

/// One wire at one station: its phase and the quantities that depend only on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WireStation {
    /// Index of the wire's layer (0-based).
    pub layer: usize,
    /// Phase phi_i(x) wrapped to (-pi, pi] (rad).
    pub phase: f64,
    /// Unit position in the section (sin phi, cos phi).
    position: [f64; 2],
    /// Lever R_w (cos phi, -sin phi) (m).
    lever: [f64; 2],
    /// Planar capstan gains for theta = |phi| through the slip limit's angle: (stretched,
    /// shortened).
    gains: [f64; 2],
}

/// The section law's precomputed data at one material coordinate. Build stations once per
/// integration point; evaluating at a station is allocation-free.
#[derive(Debug, Clone, PartialEq)]
pub struct Station {
    /// Material coordinate x (m).
    pub x: f64,
    /// Helical wires at this station.
    pub wires: Vec<WireStation>,
    /// What the planar law reads of each wire, one set of arrays per layer, one array per
    /// quantity: the lever `R_w cos(phi)` (m) and the capstan gains (stretched, shortened), so
    /// that the per-wire loop of [`SectionLaw::planar`] reads contiguous values and has no
    /// branches.
    planar: Vec<PlanarWires>,
}

impl SectionLaw {
    /// Builds the law of `kind` for `strand` with the default [`SectionOptions`] (K_min from
    /// Costello's wire bending stiffness).
    pub fn new(strand: &Strand, kind: LawKind) -> Self {
        Self::with_options(strand, kind, &SectionOptions::default())
    }

    /// Builds the law of `kind` for `strand` with `options`. `constant` uses the traditional
    /// beam's EI and EA (and no options); the others use EA_eq, K_min in the form
    /// `options.base_stiffness` and the helical layer.
    pub fn with_options(strand: &Strand, kind: LawKind, options: &SectionOptions) -> Self {
        let (axial_stiffness, base_bending) = match kind {
            LawKind::Constant => {
                let t = strand.traditional();
                (t.axial_stiffness, t.bending_stiffness)
            }
            _ => (
                strand.axial_stiffness(),
                strand.min_bending_stiffness(options.base_stiffness),
            ),
        };
        let pressure = match kind {
            LawKind::Constant => None,
            _ => PressureSystem::new(strand, options.slip_pressure),
        };
        let layers = match kind {
            LawKind::Constant => Vec::new(),
            _ => strand
                .layers()
                .iter()
                .enumerate()
                .map(|(j, l)| {
                    let a = l.lay_angle();
                    let w = &l.spec.wire;
                    let c2 = a.cos().powi(2);
                    // The stick factor of the layer's interface is a compliance in series with
                    // the wire's axial stiffness: it scales the slider's spring, not its
                    // friction limit.
                    // The pitch-averaged law: each of the layer's m wires stands as `samples`
                    // sliders, each with 1 / samples of the wire's spring and friction limit
                    // (a slider's force is homogeneous of degree one in both, its slip not at
                    // all, so a sample is the wire's slider scaled by its weight).
                    let samples = options.pitch_samples.max(1);
                    let weight = |v: f64| if samples > 1 { v / samples as f64 } else { v };
                    let k = weight(
                        options.stick_stiffness.factor(strand, j) * l.wire_axial_stiffness(),
                    );
                    // The accumulated pressure changes the limits of the layers with others
                    // outside them; the outermost keeps the capstan gain (module `pressure`).
                    let accumulated = pressure.is_some() && j + 1 < strand.layers().len();
                    LayerLaw {
                        wires: l.wires() * samples,
                        samples,
                        radius: l.radius,
                        k,
                        inv_k: 1.0 / k,
                        cap_per_strain: weight(
                            options.slip_limit.projection(a)
                                * w.area()
                                * w.material.youngs_modulus
                                * c2,
                        ),
                        capstan: strand.friction() * a.sin(),
                        neutral_slope: match &pressure {
                            Some(p) if accumulated => p.neutral_slope(j),
                            _ => strand.friction() * a.sin(),
                        },
                        accumulated,
                        index: j,
                        first: strand.layers()[..j]
                            .iter()
                            .map(|l| l.wires())
                            .sum::<usize>()
                            * samples,
                        slip_limit: options.slip_limit,
                        paper_factor: match options.slip_limit {
                            SlipLimit::Paper => c2,
                            SlipLimit::Papailiou => 1.0,
                        },
                        still_per_scale: still_per_scale(
                            strand.friction() * a.sin(),
                            options.slip_limit,
                            k,
                            l.radius,
                        ),
                    }
                })
                .collect(),
        };
        let softening = match (kind, options.base_tension) {
            (LawKind::Constant, _) | (_, BaseTension::Fixed) => None,
            _ if strand.layers().is_empty() => None,
            _ => Some(Softening::new(strand, options)),
        };
        SectionLaw {
            kind,
            axial_stiffness,
            base_bending,
            softening,
            sliders: layers.iter().map(|l: &LayerLaw| l.wires).sum(),
            layer_states: kind == LawKind::Hysteretic && layers.len() > 1,
            layers,
            pressure,
            strand: strand.clone(),
            options: *options,
        }
    }

    /// Whether `kind` can run `strand`: the `paper` law is the paper's one-layer law and
    /// refuses a second layer (the error names `layers[1]` below `strand`); the others run any
    /// number of layers.
    pub fn check(strand: &Strand, kind: LawKind) -> Result<(), InputError> {
        if kind == LawKind::Paper && strand.layers().len() > 1 {
            return Err(InputError::new(
                "layers[1]",
                "the `paper` section law is the paper's law of a 1+m strand: use `continuous`, \
                 `hysteretic` or `constant` for a strand of several layers",
            ));
        }
        Ok(())
    }

    /// Builds a `constant` law with given stiffnesses (a traditional beam of any EI, EA).
    pub fn constant(strand: &Strand, bending_stiffness: f64, axial_stiffness: f64) -> Self {
        SectionLaw {
            kind: LawKind::Constant,
            axial_stiffness,
            base_bending: bending_stiffness,
            softening: None,
            layers: Vec::new(),
            pressure: None,
            sliders: 0,
            layer_states: false,
            strand: strand.clone(),
            options: SectionOptions::default(),
        }
    }

    /// The law's kind.
    pub fn kind(&self) -> LawKind {
        self.kind
    }
    /// The strand the law was built for.
    pub fn strand(&self) -> &Strand {
        &self.strand
    }
    /// The options the law was built with.
    pub fn options(&self) -> &SectionOptions {
        &self.options
    }
    /// Axial stiffness EA (N).
    pub fn axial_stiffness(&self) -> f64 {
        self.axial_stiffness
    }
    /// Bending stiffness with every wire slipping: K_min, or EI for `constant` (N m^2); at
    /// zero strain where K_min follows the strain ([`Self::base_bending_at`]).
    pub fn base_bending_stiffness(&self) -> f64 {
        self.base_bending
    }
    /// K_min (N m^2) and dK_min/deps (N m^2) at the strain `eps`: [`Self::base_bending_stiffness`]
    /// and 0 unless `section.base_tension` makes it follow the strain (module `base_tension`;
    /// the moment is `K_min(eps) kappa` with kappa per unit rest length).
    pub fn base_bending_at(&self, eps: f64) -> (f64, f64) {
        match &self.softening {
            None => (self.base_bending, 0.0),
            Some(s) => s.at(eps),
        }
    }
    /// Bending stiffness with every wire sticking: K_min plus the layers' stick stiffness
    /// ([`Self::layer_stick_stiffness`]); EI for `constant` (N m^2).
    pub fn stick_bending_stiffness(&self) -> f64 {
        (0..self.layers.len()).fold(self.base_bending, |sum, j| {
            sum + self.layer_stick_stiffness(j)
        })
    }
    /// Layer `j`'s stick stiffness (m/2) f eta E_w A_w R_w^2 with the stick factor f of its
    /// interface (`section.stick_stiffness`) (N m^2); 0 for a layer the law does not have.
    pub fn layer_stick_stiffness(&self, j: usize) -> f64 {
        self.layers
            .get(j)
            .map_or(0.0, |l| 0.5 * l.wires as f64 * l.k * l.radius * l.radius)
    }
    /// Friction limits (stretched, shortened) of a slipping wire of layer `j` at strain `eps`
    /// and capstan angle `theta_n` (rad) from the neutral axis (N, the strand-axial force
    /// increment; module `slip_limit` for the angle, module `pressure` for the gain); zero
    /// for a layer the law does not have.
    pub fn friction_limit(&self, j: usize, eps: f64, theta_n: f64) -> [f64; 2] {
        let Some(law) = self.layers.get(j) else {
            return [0.0; 2];
        };
        let scale = law.cap_scale(eps).0;
        let gains = self.capstan_gains(law, theta_n).0;
        [scale * gains[0], scale * gains[1]]
    }
    /// The gains (stretched, shortened) of layer `law` at capstan angle `t` (rad) and their
    /// derivatives with respect to `t`: the capstan law's, or the accumulated pressure's.
    #[inline(always)]
    fn capstan_gains(&self, law: &LayerLaw, t: f64) -> ([f64; 2], [f64; 2]) {
        match &self.pressure {
            Some(p) if law.accumulated => p.gains(law.index, t),
            _ => {
                let g = law.capstan_gains(t);
                (g, [law.capstan * (g[0] + 1.0), law.capstan * (1.0 - g[1])])
            }
        }
    }
    /// The gains of [`LayerLaw::gains`] for a wire at angle `theta` in `[0, pi]` from the
    /// reference half of the neutral axis, through the slip limit's angle, with the
    /// accumulated pressure where the layer has it; and d theta_n / d theta.
    #[inline(always)]
    fn gains(&self, law: &LayerLaw, theta: f64) -> ([f64; 2], f64) {
        if law.accumulated {
            let (t, dt) = law.slip_limit.angle(theta);
            (self.capstan_gains(law, t).0, dt)
        } else {
            law.gains(theta)
        }
    }
    /// The curvature magnitude (1/m) below which no wire of a section without residual slip
    /// slips, in any bending direction, at strain `eps` (a lower bound on the first-slip
    /// curvature; 0 without tension or wires). Below it the hysteretic law keeps the stored
    /// bending direction of its friction limits (module docs).
    pub fn still_curvature(&self, eps: f64) -> f64 {
        if self.layers.is_empty() {
            return 0.0;
        }
        self.still(eps)
    }
    /// The smallest of the layers' still curvatures at strain `eps` (1/m): no wire of any
    /// layer slips below it (infinite without layers).
    #[inline(always)]
    fn still(&self, eps: f64) -> f64 {
        if let [law] = self.layers.as_slice() {
            return law.still_curvature(law.cap_scale(eps).0);
        }
        self.layers
            .iter()
            .map(|l| l.still_curvature(l.cap_scale(eps).0))
            .fold(f64::INFINITY, f64::min)
    }
    /// Number of friction sliders per station, over every layer (0 for `constant` and plain
    /// wires).
    #[inline]
    pub fn sliders(&self) -> usize {
        self.sliders
    }
    /// Phase samples per wire: 1 for the resolved law, `section.pitch_samples` for the
    /// pitch-averaged law, whose bending point stands for a whole pitch (module docs).
    pub fn pitch_samples(&self) -> usize {
        self.layers.first().map_or(1, |l| l.samples)
    }
    /// Whether each bending point stands for a whole pitch (`section.pitch_samples` >= 2 and
    /// a law with sliders): the element's quadrature is then set by its curvature, not by the
    /// pitch.
    pub fn is_pitch_averaged(&self) -> bool {
        self.pitch_samples() > 1
    }
    /// Number of layers the law has sliders for (0 for `constant` and plain wires).
    pub fn layer_count(&self) -> usize {
        self.layers.len()
    }
    /// Length of the state slice a station needs: for the hysteretic law the slip strain of
    /// each wire, then the stored bending direction of the friction limits (the unit vector
    /// (y, z) of the neutral axis's reference half, (0, 0) before any; module docs), then the
    /// committed axial strain (the slip work's trapezoid, module `slip_work`), then for a
    /// strand of several layers each layer's closed-form state (module `layer_state`,
    /// written by [`Self::planar`] at the accepted iterate; zeros: none); 0 for the other laws
    /// and for a strand without wires. Zeros are the straight, unslipped state.
    #[inline]
    pub fn state_len(&self) -> usize {
        if self.kind.has_state() && self.sliders() > 0 {
            self.sliders() + STATION_TAIL + self.layer_state_len()
        } else {
            0
        }
    }
    /// The committed axial strain in a station's state `slip` of `n` wires: the strain of the
    /// step's start, at which the slip work's trapezoid takes the friction limits (module
    /// `slip_work`); `eps` itself (the limit of the step's end) for a state without it.
    #[inline(always)]
    fn committed_strain(&self, n: usize, slip: &[f64], eps: f64) -> f64 {
        if slip.len() == self.state_len() && slip.len() > n {
            slip[n + DIRECTION_STATE]
        } else {
            eps
        }
    }
    /// The layers' closed-form state values at the end of a station's state (0 for a 1+m
    /// strand and the laws without state).
    #[inline]
    fn layer_state_len(&self) -> usize {
        if self.layer_states {
            LAYER_STATE * self.layers.len()
        } else {
            0
        }
    }

    /// Precomputes the station at material coordinate `x` (m): every layer's wires, from the
    /// core outward.
    pub fn station(&self, x: f64) -> Station {
        self.station_at(x, |_| x)
    }

    /// A station whose layer `j` (0 the first helical layer) has its wires at the phases of
    /// material coordinate `xs[j]` (m; the station's `x` is `xs[0]`, 0 with no layer). Every
    /// wire's slider reads only its own phase (its lever and gains), so stations `i` with
    /// `xs[j] = P_j (i + 1/2) / n` take each layer's mean over its own pitch `P_j` at once, in
    /// `n` stations, for any number of layers and any ratio of their pitches.
    ///
    /// # Panics
    ///
    /// If `xs` has fewer entries than the strand has layers.
    pub fn station_by_layer(&self, xs: &[f64]) -> Station {
        assert!(
            xs.len() >= self.layers.len(),
            "one coordinate per layer: {} for {} layers",
            xs.len(),
            self.layers.len()
        );
        self.station_at(xs.first().copied().unwrap_or(0.0), |j| xs[j])
    }

    /// The `n` stations [`Self::station_by_layer`] describes: station `i` has layer `j`'s wires
    /// at `P_j (i + 1/2) / n` along that layer's own pitch `P_j` (m), so that a mean over them
    /// is every layer's mean over its whole pitch at once.
    pub fn stations_by_layer(&self, n: usize) -> Vec<Station> {
        (0..n)
            .map(|i| {
                let xs: Vec<f64> = self
                    .strand
                    .layers()
                    .iter()
                    .map(|l| l.pitch * (i as f64 + 0.5) / n as f64)
                    .collect();
                self.station_by_layer(&xs)
            })
            .collect()
    }

    /// The station recorded at `x` (m) with layer `j`'s wires at `at(j)` (m).
    fn station_at(&self, x: f64, at: impl Fn(usize) -> f64) -> Station {
        let mut wires = Vec::with_capacity(self.sliders());
        let mut planar = Vec::with_capacity(self.layers.len());
        for (j, (law, h)) in self.layers.iter().zip(self.strand.layers()).enumerate() {
            let x = at(j);
            let m = h.wires();
            // The pitch-averaged law's samples: wire i % m at the offset of sample i / m, the
            // samples centred on x and spaced by P / (m S), so that the layer's m S phases
            // are evenly spaced by 2 pi / (m S).
            let spacing = h.pitch / (m * law.samples) as f64;
            let centre = 0.5 * (law.samples as f64 - 1.0);
            let layer: Vec<WireStation> = (0..law.wires)
                .map(|i| {
                    let phase = if law.samples > 1 {
                        h.phase(i % m, x + ((i / m) as f64 - centre) * spacing)
                    } else {
                        h.phase(i, x)
                    };
                    let (s, c) = phase.sin_cos();
                    WireStation {
                        layer: law.index,
                        phase,
                        position: [s, c],
                        lever: [law.radius * c, -law.radius * s],
                        gains: self.gains(law, phase.abs()).0,
                    }
                })
                .collect();
            let k = law.k;
            planar.push(PlanarWires {
                lever_square: layer.iter().map(|w| w.lever[1] * w.lever[1]).sum(),
                ratio_max: layer
                    .iter()
                    .map(|w| {
                        if w.lever[1] == 0.0 {
                            f64::INFINITY
                        } else {
                            w.gains[0].max(w.gains[1]) / (k * w.lever[1].abs())
                        }
                    })
                    .fold(0.0, f64::max),
                inv_lever: layer.iter().map(|w| 1.0 / w.lever[1].abs()).collect(),
                lever: layer.iter().map(|w| w.lever[1]).collect(),
                gain_pos: layer.iter().map(|w| w.gains[0]).collect(),
                gain_neg: layer.iter().map(|w| w.gains[1]).collect(),
                gain_min: layer
                    .iter()
                    .map(|w| w.gains[0].min(w.gains[1]))
                    .fold(f64::INFINITY, f64::min),
            });
            wires.extend(layer);
        }
        Station { x, wires, planar }
    }

    /// Bending stiffness for a planar curvature with every wire sticking, `K_min + sum_i
    /// K_stick_i` over every layer's wires (N m^2): the largest tangent [`Self::planar`] gives
    /// at `st`.
    pub fn planar_stick_stiffness(&self, st: &Station) -> f64 {
        self.layers
            .iter()
            .zip(&st.planar)
            .fold(self.base_bending, |sum, (l, p)| {
                let k = l.k;
                sum + p.lever.iter().map(|a| k * a * a).sum::<f64>()
            })
    }

    /// Whether the law is linear: no wire layer, so [`Self::planar_linear`] is the whole of
    /// [`Self::planar`] (the `constant` law, plain wires).
    #[inline]
    pub fn is_linear(&self) -> bool {
        self.layers.is_empty()
    }

    /// The part of [`Self::planar`] without the wires, `N = EA eps` and `M = K kappa` with the
    /// base bending stiffness: all of it for a linear law ([`Self::is_linear`]), which element
    /// loops can then evaluate inline.
    /// Where K_min follows the strain (`section.base_tension`) the moment is `K_min(eps)
    /// kappa`, with `dM/deps = K_min'(eps) kappa`; the axial force stays `EA eps`, so the
    /// energy's `K_min'(eps) kappa^2 / 2` is booked in `energy_strain`.
    #[inline(always)]
    pub fn planar_linear(&self, eps: f64, kappa: f64) -> PlanarResponse {
        if let Some(s) = &self.softening {
            let (kb, dkb) = s.at(eps);
            return PlanarResponse {
                axial_force: self.axial_stiffness * eps,
                axial_stiffness: self.axial_stiffness,
                moment: kb * kappa,
                moment_curvature: kb,
                moment_strain: dkb * kappa,
                energy: 0.5 * self.axial_stiffness * eps * eps + 0.5 * kb * kappa * kappa,
                energy_strain: 0.5 * dkb * kappa * kappa,
                slip_work: 0.0,
                slipping: 0,
            };
        }
        PlanarResponse {
            axial_force: self.axial_stiffness * eps,
            axial_stiffness: self.axial_stiffness,
            moment: self.base_bending * kappa,
            moment_curvature: self.base_bending,
            moment_strain: 0.0,
            energy: 0.5 * self.axial_stiffness * eps * eps
                + 0.5 * self.base_bending * kappa * kappa,
            energy_strain: 0.0,
            slip_work: 0.0,
            slipping: 0,
        }
    }

    /// Evaluates the law for a signed planar curvature `kappa` (1/m, `kappa_z`) at strain
    /// `eps`. `slip` is the station's committed slip state and `trial` receives the trial state
    /// (both of length [`Self::state_len`]; empty slices for laws without state).
    #[inline(always)]
    pub fn planar(
        &self,
        st: &Station,
        eps: f64,
        kappa: f64,
        slip: &[f64],
        trial: &mut [f64],
    ) -> PlanarResponse {
        let mut r = self.planar_linear(eps, kappa);
        if self.layers.is_empty() {
            return r;
        }
        let n = st.wires.len();
        let stateful = slip.len() > n && trial.len() == slip.len();
        match (self.kind, self.layers.as_slice(), st.planar.as_slice()) {
            (LawKind::Continuous, layers, planar) => {
                for (law, p) in layers.iter().zip(planar) {
                    let (scale, dscale) = law.cap_scale(eps);
                    continuous_wires::<true>(law, p, kappa, scale, dscale, &mut r);
                }
            }
            (LawKind::Hysteretic, layers, planar) if stateful => {
                // Each layer's wires, one after another in the state; then, where the state
                // holds them, each layer's closed-form state for the next step's iterations.
                let eps_old = self.committed_strain(n, slip, eps);
                let (wires, tail) = trial.split_at_mut(n);
                let tally = self.layer_states && slip.len() == self.state_len();
                let mut states = if tally {
                    tail[STATION_TAIL..].chunks_exact_mut(LAYER_STATE)
                } else {
                    [].chunks_exact_mut(LAYER_STATE)
                };
                let (mut sl, mut tr) = (&slip[..n], wires);
                for (law, p) in layers.iter().zip(planar) {
                    let (scale, dscale) = law.cap_scale(eps);
                    let scales = (scale, dscale, law.cap_scale(eps_old).0);
                    let m = p.lever.len();
                    let (s_here, s_rest) = sl.split_at(m);
                    let (t_here, t_rest) = tr.split_at_mut(m);
                    let mut t = LayerTally::default();
                    if tally {
                        hysteretic_wires::<true, true>(
                            law, p, kappa, scales, s_here, t_here, &mut r, &mut t,
                        );
                        if let Some(out) = states.next() {
                            layer_state::commit(law, p, kappa, scale, &t, out);
                        }
                    } else {
                        hysteretic_wires::<true, false>(
                            law, p, kappa, scales, s_here, t_here, &mut r, &mut t,
                        );
                    }
                    (sl, tr) = (s_rest, t_rest);
                }
            }
            _ => {
                // Through a copy: `r` itself never has its address taken, so the inlined
                // loops above keep its sums in registers (through memory each wire's additions
                // wait on a store and a reload of the last wire's).
                let mut g = r;
                self.planar_wires_generic(st, eps, kappa, slip, trial, &mut g);
                r = g;
            }
        }
        // The stored bending direction (hysteretic law), as `vector` writes it with kappa_y = 0
        // (`BendingDirection::select` without its angles): beyond the still curvature the
        // neutral axis of (0, kappa), (+-0, 1), else the stored one; then the strain, the
        // next step's committed strain.
        if slip.len() == self.state_len() && slip.len() > n && trial.len() == slip.len() {
            let tail = if kappa.abs() > self.still(eps) {
                [if kappa < 0.0 { -0.0 } else { 0.0 }, 1.0]
            } else {
                [slip[n], slip[n + 1]]
            };
            trial[n..n + DIRECTION_STATE].copy_from_slice(&tail);
            trial[n + DIRECTION_STATE] = eps;
        }
        r
    }

    /// The moment of [`Self::planar`] and its curvature tangent alone, the same values bit for
    /// bit: what a Newton iteration reads. The books (stored energy, slip work, slipping
    /// wires, `dM/deps`) and the trial state are left out; [`Self::planar`] at the accepted
    /// strain and curvature gives them. For the `continuous` and `hysteretic` laws this skips
    /// about half the work per wire. The `hysteretic` law of a strand of several layers
    /// evaluates a layer whose wires all stick, or all slip, in closed form from the state
    /// the accepted iterate left (module `layer_state`): the wire loop's values up to the
    /// rounding of the sums.
    #[inline(always)]
    pub fn planar_moment(&self, st: &Station, eps: f64, kappa: f64, slip: &[f64]) -> PlanarMoment {
        let base = self.planar_linear(eps, kappa);
        let mut r = PlanarResponse {
            moment: base.moment,
            moment_curvature: base.moment_curvature,
            ..PlanarResponse::default()
        };
        if self.layers.is_empty() {
            return PlanarMoment {
                moment: r.moment,
                moment_curvature: r.moment_curvature,
            };
        }
        let n = st.wires.len();
        match (self.kind, self.layers.as_slice(), st.planar.as_slice()) {
            // One layer on its own: the loop over layers left out, as the element loops that
            // inline this keep their sums in registers (measured: 2 % of the section-3
            // pendulum's instructions with the loop).
            (LawKind::Continuous, [law], [p]) => {
                let (scale, dscale) = law.cap_scale(eps);
                continuous_wires::<false>(law, p, kappa, scale, dscale, &mut r);
            }
            (LawKind::Hysteretic, [law], [p]) if slip.len() > n => {
                let (scale, dscale) = law.cap_scale(eps);
                let sl = &slip[..n];
                let t = &mut LayerTally::default();
                hysteretic_wires::<false, false>(
                    law,
                    p,
                    kappa,
                    (scale, dscale, scale),
                    sl,
                    &mut [],
                    &mut r,
                    t,
                );
            }
            (LawKind::Continuous, layers, planar) => {
                for (law, p) in layers.iter().zip(planar) {
                    let (scale, dscale) = law.cap_scale(eps);
                    continuous_wires::<false>(law, p, kappa, scale, dscale, &mut r);
                }
            }
            (LawKind::Hysteretic, layers, planar) if slip.len() > n => {
                let mut sl = &slip[..n];
                // Each layer's closed-form state, where the state holds them.
                let states = if self.layer_states && slip.len() == self.state_len() {
                    &slip[n + STATION_TAIL..]
                } else {
                    &[]
                };
                let mut states = states.chunks_exact(LAYER_STATE);
                for (law, p) in layers.iter().zip(planar) {
                    let (scale, dscale) = law.cap_scale(eps);
                    let (here, rest) = sl.split_at(p.lever.len());
                    sl = rest;
                    let closed = states
                        .next()
                        .and_then(|s| layer_state::closed_form(law, p, kappa, scale, s));
                    if let Some((moment, tangent)) = closed {
                        r.moment += moment;
                        r.moment_curvature += tangent;
                        continue;
                    }
                    let t = &mut LayerTally::default();
                    hysteretic_wires::<false, false>(
                        law,
                        p,
                        kappa,
                        (scale, dscale, scale),
                        here,
                        &mut [],
                        &mut r,
                        t,
                    );
                }
            }
            _ => {
                let full = self.planar(st, eps, kappa, slip, &mut []);
                r.moment = full.moment;
                r.moment_curvature = full.moment_curvature;
            }
        }
        PlanarMoment {
            moment: r.moment,
            moment_curvature: r.moment_curvature,
        }
    }

    /// The wires' part of [`Self::planar`] through the generic slider (any law, optional slip
    /// state), added to `r`.
    fn planar_wires_generic(
        &self,
        st: &Station,
        eps: f64,
        kappa: f64,
        slip: &[f64],
        trial: &mut [f64],
        r: &mut PlanarResponse,
    ) {
        let eps_old = self.committed_strain(st.wires.len(), slip, eps);
        for (i, w) in st.wires.iter().enumerate() {
            let law = self.layers[w.layer];
            let (scale, dscale) = law.cap_scale(eps);
            let lever = w.lever[1];
            let gains = w.gains;
            let old = |pos: bool| law.cap_scale(eps_old).0 * gains[usize::from(!pos)];
            let f = self.slide(law, i, lever * kappa, scale, gains, slip, trial, old);
            r.moment += f.force * lever;
            r.moment_curvature += f.d_strain * lever * lever;
            let cap_strain = (f.d_cap_pos * w.gains[0] - f.d_cap_neg * w.gains[1]) * dscale;
            r.moment_strain +=
                (f.d_cap_pos * w.gains[0] + f.d_cap_neg * w.gains[1]) * dscale * lever;
            r.energy += f.energy;
            r.energy_strain += f.d_energy_cap * cap_strain;
            r.slip_work += f.slip_work;
            r.slipping += usize::from(f.state == WireState::Slip);
        }
    }

    /// The slider of wire `i` of layer `law` at bending strain `e`, with its committed slip
    /// from `slip` and its trial slip written into `trial`; `cap_old` as for `slider`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn slide(
        &self,
        law: LayerLaw,
        i: usize,
        e: f64,
        scale: f64,
        gains: [f64; 2],
        slip: &[f64],
        trial: &mut [f64],
        cap_old: impl FnOnce(bool) -> f64,
    ) -> SliderForce {
        let committed = slip.get(i).copied().unwrap_or(0.0);
        let f = slider(
            self.kind,
            law.k,
            e,
            scale * gains[0],
            scale * gains[1],
            law.paper_factor,
            committed,
            cap_old,
        );
        if let Some(t) = trial.get_mut(i) {
            *t = f.slip;
        }
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::StrandSpec;

    /// The paper's strand with a second layer of twelve wires laid the other way, a third
    /// of its modulus (R_2 = 4.5 mm).
    fn two_layers() -> Strand {
        let mut spec = StrandSpec::paper(1.0, 2.0e9, 5747.0);
        let mut outer = spec.layers[0];
        outer.wires = 12;
        outer.lay_angle = 15f64.to_radians();
        outer.direction = crate::LayDirection::Left;
        outer.wire.material.youngs_modulus /= 3.0;
        spec.layers.push(outer);
        Strand::new(spec).unwrap()
    }

    /// The inlined planar loops of the `continuous` and `hysteretic` laws give exactly the
    /// generic slider's values, sticking and slipping on both sides, for one layer and for
    /// two (each layer's wires with its own spring and friction limits).
    #[test]
    fn inlined_planar_loops_match_the_slider() {
        let strands = [
            Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap(),
            two_layers(),
        ];
        for (strand, kind) in strands
            .iter()
            .flat_map(|s| [(s, LawKind::Continuous), (s, LawKind::Hysteretic)])
        {
            let law = SectionLaw::new(strand, kind);
            let n = law.sliders();
            let (mut count, mut paths) = ([0usize; 2], [0usize; 2]);
            for j in 0..400 {
                let st = law.station(0.0137 * j as f64);
                let eps = 1e-4 * ((j % 7) as f64 - 2.0);
                let kappa = 1e-3 * ((j * 37 % 101) as f64 - 50.0);
                let slip: Vec<f64> = (0..n)
                    .map(|i| 1e-5 * (((i * 13 + j * 7) % 11) as f64 - 5.0))
                    .collect();
                let slip = if kind.has_state() { slip } else { Vec::new() };
                let (mut t_fast, mut t_gen) = (vec![0.0; slip.len()], vec![0.0; slip.len()]);
                let fast = law.planar(&st, eps, kappa, &slip, &mut t_fast);
                let mut generic = PlanarResponse {
                    moment_curvature: law.base_bending,
                    moment: law.base_bending * kappa,
                    ..fast
                };
                (
                    generic.moment_strain,
                    generic.energy_strain,
                    generic.slip_work,
                    generic.slipping,
                ) = (0.0, 0.0, 0.0, 0);
                generic.energy =
                    0.5 * law.axial_stiffness * eps * eps + 0.5 * law.base_bending * kappa * kappa;
                let sd = law.layers[0].cap_scale(eps);
                law.planar_wires_generic(&st, eps, kappa, &slip, &mut t_gen, &mut generic);
                assert_eq!(fast, generic, "{kind} at station {j}");
                assert_eq!(t_fast, t_gen);
                count[usize::from(fast.slipping > 0 && fast.slipping < n)] += 1;
                // Both kernels: with the test for wires without friction limits and without.
                paths[usize::from(sd.0 * st.planar[0].gain_min > 0.0)] += 1;
            }
            assert!(count[0] > 0 && count[1] > 0, "{kind}: {count:?}");
            assert!(paths[0] > 0 && paths[1] > 0, "{kind}: {paths:?}");
        }
    }
}
