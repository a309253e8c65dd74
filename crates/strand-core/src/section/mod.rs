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

mod options;
mod slider;
mod slip_limit;

pub use options::SectionOptions;
pub use slider::WireState;
use slider::{SliderForce, slider};
pub use slip_limit::SlipLimit;

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

/// The helical layer's constants as the section law uses them.
#[derive(Debug, Clone, Copy, PartialEq)]
struct LayerLaw {
    wires: usize,
    radius: f64,
    /// The slider's spring: eta E_w A_w times the stick factor of `section.stick_stiffness`
    /// (N).
    k: f64,
    /// 1 / k (1/N).
    inv_k: f64,
    /// Projection times A_w E_w cos^2(alpha) (N): friction limit per unit strand strain and
    /// unit gain; the projection is cos(alpha) or the paper's eta ([`SlipLimit::projection`]).
    cap_per_strain: f64,
    /// mu sin(alpha).
    capstan: f64,
    /// Where the capstan angle starts (`section.slip_limit`).
    slip_limit: SlipLimit,
    /// Ratio of the slip force to the stick force at the `paper` law's switch, eq. (23):
    /// cos^2(alpha) with the paper's slip limit, whose eq. (22b) projects the slip stress by
    /// eta; 1 with the `papailiou` limit, whose cos(alpha) makes eq. (23) the point where
    /// eqs. (22a) and (22b) meet.
    paper_factor: f64,
    /// A lower bound on the curvature at which a wire of a section without residual slip
    /// first slips, in any bending direction, per unit friction-limit scale (1/(m N)): the
    /// hysteretic law turns the friction limits only with a bending larger than this
    /// (module docs, "Bending direction of the friction limits").
    still_per_scale: f64,
}

impl LayerLaw {
    /// The curvature magnitude (1/m) below which the hysteretic law keeps the stored bending
    /// direction, at friction-limit scale `scale` (N): no wire of a section without residual
    /// slip slips below it, in any direction.
    #[inline(always)]
    fn still_curvature(&self, scale: f64) -> f64 {
        scale * self.still_per_scale
    }

    /// The critical curvature (1/m) a wire report gives for a wire at angle `theta` (rad,
    /// `sin_t` its sine) from the reference half of the neutral axis, with friction limit
    /// `scale gain` on the loaded side of its slider: `scale gain / (k factor R_w sin(theta))`.
    /// The ratio gain/sin(theta) has the limit mu sin(alpha) on the neutral axis (theta -> 0);
    /// as theta -> pi it has the same limit with Papailiou's slip limit and grows without
    /// bound with the paper's (none).
    fn critical_curvature(
        &self,
        scale: f64,
        factor: f64,
        gain: f64,
        theta: f64,
        sin_t: f64,
    ) -> Option<f64> {
        let ratio = if sin_t > 1e-12 {
            Some(gain / sin_t)
        } else if self.slip_limit.angle(theta).0 < 0.5 * std::f64::consts::PI {
            Some(self.capstan)
        } else {
            None
        };
        ratio.map(|r| scale * r / (self.k * factor * self.radius))
    }

    /// The state a wire report gives: the slider's, except for a wire without lever (`arm`,
    /// m), which carries no force: its state follows `critical` against the curvature
    /// magnitude `kappa` (1/m).
    fn reported_state(
        &self,
        slider: WireState,
        arm: f64,
        critical: Option<f64>,
        kappa: f64,
    ) -> WireState {
        if arm > 1e-12 * self.radius {
            slider
        } else if critical.is_some_and(|c| kappa > c) {
            WireState::Slip
        } else {
            WireState::Stick
        }
    }

    /// Capstan gains (stretched, shortened) at the angle `theta` in `[0, pi]` from the
    /// reference half of the neutral axis, and d theta_n / d theta of the slip limit's angle.
    #[inline(always)]
    fn gains(&self, theta: f64) -> ([f64; 2], f64) {
        let (t, dt) = self.slip_limit.angle(theta);
        (
            [(self.capstan * t).exp_m1(), -(-self.capstan * t).exp_m1()],
            dt,
        )
    }
}

/// A section law built for one strand.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionLaw {
    kind: LawKind,
    axial_stiffness: f64,
    base_bending: f64,
    layer: Option<LayerLaw>,
    strand: Strand,
    options: SectionOptions,
}

/// One wire at one station: its phase and the quantities that depend only on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WireStation {
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
    /// What the planar law reads of each wire, one array per quantity: the lever
    /// `R_w cos(phi)` (m) and the capstan gains (stretched, shortened), so that the per-wire
    /// loop of [`SectionLaw::planar`] reads contiguous values and has no branches.
    planar: PlanarWires,
}

/// The planar law's per-wire constants of a station, as parallel arrays.
#[derive(Debug, Clone, PartialEq, Default)]
struct PlanarWires {
    lever: Vec<f64>,
    gain_pos: Vec<f64>,
    gain_neg: Vec<f64>,
    /// The smallest gain of either side over the wires (infinite without wires): where
    /// `scale * gain_min > 0` every wire has both friction limits, and the kernels skip the
    /// test for a wire without any ([`planar_continuous`]).
    gain_min: f64,
}

/// Response of the section to a strain and a curvature vector (units: N, N m, J/m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SectionResponse {
    /// Axial force N = EA eps (N).
    pub axial_force: f64,
    /// dN/deps (N).
    pub axial_stiffness: f64,
    /// Bending moment vector (M_y, M_z) (N m).
    pub moment: [f64; 2],
    /// dM_a / dkappa_b (N m^2).
    pub moment_curvature: [[f64; 2]; 2],
    /// dM / deps (N m).
    pub moment_strain: [f64; 2],
    /// Stored energy density (J/m).
    pub energy: f64,
    /// Derivative of the wires' stored energy with respect to the strain at fixed curvature
    /// and slip (J/m): the part of the energy that the forces N, M do not derive from. Over a
    /// strain increment d eps the section dissipates `-energy_strain d eps` (SPEC 2: the
    /// non-potential work is reported as dissipation).
    pub energy_strain: f64,
    /// The gradient of the stored energy with respect to the curvature vector at fixed strain
    /// and slip, minus the moment (N m, section frame): normal to the bending direction. The
    /// friction limit of a slipping wire depends on its angle from the neutral axis, which
    /// turns with the bending direction; the `continuous` and `paper` laws store an energy
    /// that depends on the limit, so when the direction turns their stored energy changes by
    /// `energy_turn . d kappa` without work of the moment. Over a curvature increment the
    /// section dissipates `-energy_turn . d kappa` (non-potential work, like
    /// `energy_strain`). Zero for bending in a fixed plane, where `d kappa` is along the
    /// bending direction, for a section whose wires all stick, and for the `hysteretic` law,
    /// which books the energy change of a moving limit as slip work.
    pub energy_turn: [f64; 2],
    /// Work dissipated by slip from the committed state to this trial (J/m; hysteretic law).
    pub slip_work: f64,
    /// Number of slipping wires.
    pub slipping: usize,
}

/// Response of the section to a strain and a signed planar curvature (units: N, N m, J/m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarResponse {
    /// Axial force N = EA eps (N).
    pub axial_force: f64,
    /// dN/deps (N).
    pub axial_stiffness: f64,
    /// Bending moment M_z, same sign as the curvature (N m).
    pub moment: f64,
    /// dM/dkappa (N m^2).
    pub moment_curvature: f64,
    /// dM/deps (N m).
    pub moment_strain: f64,
    /// Stored energy density (J/m).
    pub energy: f64,
    /// Derivative of the wires' stored energy with respect to the strain at fixed curvature
    /// and slip (J/m): the part of the energy that the forces N, M do not derive from. Over a
    /// strain increment d eps the section dissipates `-energy_strain d eps` (SPEC 2: the
    /// non-potential work is reported as dissipation).
    pub energy_strain: f64,
    /// Work dissipated by slip from the committed state to this trial (J/m; hysteretic law).
    pub slip_work: f64,
    /// Number of slipping wires.
    pub slipping: usize,
}

/// The bending moment of [`SectionLaw::planar_moment`] and its curvature tangent, without
/// the books (energy, slip work, slipping wires) that [`SectionLaw::planar`] keeps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarMoment {
    /// Bending moment M_z, same sign as the curvature (N m).
    pub moment: f64,
    /// dM/dkappa (N m^2).
    pub moment_curvature: f64,
}

/// One wire's state for reports (SPEC 6 `wires.csv`, `strand section`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WireReport {
    /// Wire number, 1-based as in the paper.
    pub wire: usize,
    /// Phase phi_i(x) in (-pi, pi] (rad).
    pub phase: f64,
    /// Stick stiffness K_stick_i = f eta E_w A_w (R_w sin theta)^2 for this bending direction
    /// (N m^2): eq. (22a) times the stick factor f of `section.stick_stiffness`.
    pub k_stick: f64,
    /// Friction-limited moment M_slip_i (N m), eq. (22b) times kappa.
    pub m_slip: f64,
    /// Critical curvature kappa_c_i (1/m); `None` where the wire has no lever (it never slips).
    pub critical_curvature: Option<f64>,
    /// Stick or slip at the given curvature.
    pub state: WireState,
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
        let layer = match kind {
            LawKind::Constant => None,
            _ => strand.layer().map(|l| {
                let a = l.lay_angle();
                let w = &l.spec.wire;
                let c2 = a.cos().powi(2);
                // The stick factor is a compliance in series with the wire's axial
                // stiffness: it scales the slider's spring, not its friction limit.
                let k = options.stick_stiffness.factor(strand) * l.wire_axial_stiffness();
                LayerLaw {
                    wires: l.wires(),
                    radius: l.radius,
                    k,
                    inv_k: 1.0 / k,
                    cap_per_strain: options.slip_limit.projection(a)
                        * w.area()
                        * w.material.youngs_modulus
                        * c2,
                    capstan: strand.friction() * a.sin(),
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
            }),
        };
        SectionLaw {
            kind,
            axial_stiffness,
            base_bending,
            layer,
            strand: strand.clone(),
            options: *options,
        }
    }

    /// Builds a `constant` law with given stiffnesses (a traditional beam of any EI, EA).
    pub fn constant(strand: &Strand, bending_stiffness: f64, axial_stiffness: f64) -> Self {
        SectionLaw {
            kind: LawKind::Constant,
            axial_stiffness,
            base_bending: bending_stiffness,
            layer: None,
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
    /// Bending stiffness with every wire slipping: K_min, or EI for `constant` (N m^2).
    pub fn base_bending_stiffness(&self) -> f64 {
        self.base_bending
    }
    /// Bending stiffness with every wire sticking: K_min plus the wires' stick stiffness,
    /// (m/2) f eta E_w A_w R_w^2 with the stick factor f of `section.stick_stiffness`; EI for
    /// `constant` (N m^2).
    pub fn stick_bending_stiffness(&self) -> f64 {
        self.base_bending
            + self
                .layer
                .map_or(0.0, |l| 0.5 * l.wires as f64 * l.k * l.radius * l.radius)
    }
    /// The curvature magnitude (1/m) below which no wire of a section without residual slip
    /// slips, in any bending direction, at strain `eps` (a lower bound on the first-slip
    /// curvature; 0 without tension or wires). Below it the hysteretic law keeps the stored
    /// bending direction of its friction limits (module docs).
    pub fn still_curvature(&self, eps: f64) -> f64 {
        self.layer
            .map_or(0.0, |l| l.still_curvature(self.cap_scale(eps).0))
    }
    /// Number of friction sliders per station (0 for `constant` and plain wires).
    pub fn sliders(&self) -> usize {
        self.layer.map_or(0, |l| l.wires)
    }
    /// Length of the state slice a station needs: for the hysteretic law the slip strain of
    /// each wire, then the stored bending direction of the friction limits (the unit vector
    /// (y, z) of the neutral axis's reference half, (0, 0) before any; module docs); 0 for the
    /// other laws and for a strand without wires. Zeros are the straight, unslipped state.
    pub fn state_len(&self) -> usize {
        if self.kind.has_state() && self.sliders() > 0 {
            self.sliders() + DIRECTION_STATE
        } else {
            0
        }
    }

    /// Precomputes the station at material coordinate `x` (m).
    pub fn station(&self, x: f64) -> Station {
        let wires = match (self.layer, self.strand.layer()) {
            (Some(law), Some(h)) => (0..law.wires)
                .map(|i| {
                    let phase = h.phase(i, x);
                    let (s, c) = phase.sin_cos();
                    WireStation {
                        phase,
                        position: [s, c],
                        lever: [law.radius * c, -law.radius * s],
                        gains: law.gains(phase.abs()).0,
                    }
                })
                .collect(),
            _ => Vec::new(),
        };
        let planar = PlanarWires {
            lever: wires.iter().map(|w| w.lever[1]).collect(),
            gain_pos: wires.iter().map(|w| w.gains[0]).collect(),
            gain_neg: wires.iter().map(|w| w.gains[1]).collect(),
            gain_min: wires
                .iter()
                .map(|w| w.gains[0].min(w.gains[1]))
                .fold(f64::INFINITY, f64::min),
        };
        Station { x, wires, planar }
    }

    /// Friction limits (stretched, shortened) per unit gain: eta A_w sigma_a (N), with
    /// sigma_a = E_w cos^2(alpha) eps for eps > 0 and 0 otherwise (SPEC 2), and d/deps.
    fn cap_scale(&self, eps: f64) -> (f64, f64) {
        match self.layer {
            Some(l) if eps > 0.0 => (l.cap_per_strain * eps, l.cap_per_strain),
            _ => (0.0, 0.0),
        }
    }

    /// Bending stiffness for a planar curvature with every wire sticking, `K_min + sum_i
    /// K_stick_i` (N m^2): the largest tangent [`Self::planar`] gives at `st`.
    pub fn planar_stick_stiffness(&self, st: &Station) -> f64 {
        let k = self.layer.map_or(0.0, |l| l.k);
        self.base_bending + st.planar.lever.iter().map(|a| k * a * a).sum::<f64>()
    }

    /// Whether the law is linear: no wire layer, so [`Self::planar_linear`] is the whole of
    /// [`Self::planar`] (the `constant` law, plain wires).
    #[inline]
    pub fn is_linear(&self) -> bool {
        self.layer.is_none()
    }

    /// The part of [`Self::planar`] without the wires, `N = EA eps` and `M = K kappa` with the
    /// base bending stiffness: all of it for a linear law ([`Self::is_linear`]), which element
    /// loops can then evaluate inline.
    #[inline(always)]
    pub fn planar_linear(&self, eps: f64, kappa: f64) -> PlanarResponse {
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
        let Some(law) = self.layer else { return r };
        let (scale, dscale) = self.cap_scale(eps);
        let n = st.wires.len();
        match self.kind {
            LawKind::Continuous => {
                continuous_wires::<true>(law, &st.planar, kappa, scale, dscale, &mut r)
            }
            LawKind::Hysteretic if slip.len() > n && trial.len() == slip.len() => {
                let (sl, tr) = (&slip[..n], &mut trial[..n]);
                hysteretic_wires::<true>(law, &st.planar, kappa, scale, dscale, sl, tr, &mut r);
            }
            _ => {
                // Through a copy: `r` itself never has its address taken, so the inlined
                // loops above keep its sums in registers (through memory each wire's additions
                // wait on a store and a reload of the last wire's).
                let mut g = r;
                self.planar_wires_generic(law, st, kappa, (scale, dscale), slip, trial, &mut g);
                r = g;
            }
        }
        // The stored bending direction (hysteretic law), as `vector` writes it with kappa_y = 0
        // (`BendingDirection::select` without its angles): beyond the still curvature the
        // neutral axis of (0, kappa), (+-0, 1), else the stored one.
        if slip.len() == n + DIRECTION_STATE && trial.len() == slip.len() {
            let tail = if kappa.abs() > law.still_curvature(scale) {
                [if kappa < 0.0 { -0.0 } else { 0.0 }, 1.0]
            } else {
                [slip[n], slip[n + 1]]
            };
            trial[n..].copy_from_slice(&tail);
        }
        r
    }

    /// The moment of [`Self::planar`] and its curvature tangent alone, the same values bit for
    /// bit: what a Newton iteration reads. The books (stored energy, slip work, slipping
    /// wires, `dM/deps`) and the trial state are left out; [`Self::planar`] at the accepted
    /// strain and curvature gives them. For the `continuous` and `hysteretic` laws this skips
    /// about half the work per wire.
    #[inline(always)]
    pub fn planar_moment(&self, st: &Station, eps: f64, kappa: f64, slip: &[f64]) -> PlanarMoment {
        let base = self.planar_linear(eps, kappa);
        let mut r = PlanarResponse {
            moment: base.moment,
            moment_curvature: base.moment_curvature,
            ..PlanarResponse::default()
        };
        let Some(law) = self.layer else {
            return PlanarMoment {
                moment: r.moment,
                moment_curvature: r.moment_curvature,
            };
        };
        let (scale, dscale) = self.cap_scale(eps);
        let n = st.wires.len();
        let p = &st.planar;
        match self.kind {
            LawKind::Continuous => continuous_wires::<false>(law, p, kappa, scale, dscale, &mut r),
            LawKind::Hysteretic if slip.len() > n => {
                let sl = &slip[..n];
                hysteretic_wires::<false>(law, p, kappa, scale, dscale, sl, &mut [], &mut r);
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
        law: LayerLaw,
        st: &Station,
        kappa: f64,
        (scale, dscale): (f64, f64),
        slip: &[f64],
        trial: &mut [f64],
        r: &mut PlanarResponse,
    ) {
        for (i, w) in st.wires.iter().enumerate() {
            let lever = w.lever[1];
            let f = self.slide(law, i, lever * kappa, scale, w.gains, slip, trial);
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

    /// Evaluates the law for a curvature vector `kappa = (kappa_y, kappa_z)` (1/m) in the
    /// section frame at strain `eps`; `slip` and `trial` as for [`Self::planar`].
    ///
    /// Each wire's slider works on its bending strain `e_i = l_i . kappa` and its force acts
    /// through its lever vector: `M = K_min kappa + sum_i F_i l_i` (module docs). The tangent
    /// is `K_min I + sum_i l_i (dF_i/de_i l_i + dF_i/dcap_i dcap_i/dkappa)`: the stick part
    /// is symmetric and positive definite, the second term is the friction limit of a
    /// slipping wire turning with the bending direction (for the `hysteretic` law beyond the
    /// still curvature only; below it the limits keep the stored direction, module docs).
    /// With `kappa_y = 0` the z components of the moment, its tangent `dM_z/dkappa_z` and
    /// `dM_z/deps`, and the energy are those of [`Self::planar`] bit for bit.
    pub fn vector(
        &self,
        st: &Station,
        eps: f64,
        kappa: [f64; 2],
        slip: &[f64],
        trial: &mut [f64],
    ) -> SectionResponse {
        let kb = self.base_bending;
        let mut r = SectionResponse {
            axial_force: self.axial_stiffness * eps,
            axial_stiffness: self.axial_stiffness,
            moment: [kb * kappa[0], kb * kappa[1]],
            moment_curvature: [[kb, 0.0], [0.0, kb]],
            moment_strain: [0.0; 2],
            // Summed as in `planar_linear`, the out-of-plane term last.
            energy: 0.5 * self.axial_stiffness * eps * eps
                + 0.5 * kb * kappa[1] * kappa[1]
                + 0.5 * kb * kappa[0] * kappa[0],
            energy_strain: 0.0,
            energy_turn: [0.0; 2],
            slip_work: 0.0,
            slipping: 0,
        };
        let Some(law) = self.layer else { return r };
        let (scale, dscale) = self.cap_scale(eps);
        let n = st.wires.len();
        let still = law.still_curvature(scale);
        let dir = if slip.len() == n + DIRECTION_STATE && trial.len() == slip.len() {
            BendingDirection::select(kappa, still, &slip[n..], Some(&mut trial[n..]))
        } else {
            BendingDirection::of(kappa)
        };
        for (i, w) in st.wires.iter().enumerate() {
            let l = w.lever;
            let theta = dir.wire_angle(w.phase);
            let (gains, dtheta_n) = law.gains(theta.abs());
            let f = self.slide(
                law,
                i,
                l[0] * kappa[0] + l[1] * kappa[1],
                scale,
                gains,
                slip,
                trial,
            );
            // The friction limit of the active side turns with the bending direction:
            // d cap/d theta through the slip limit's angle theta_n(theta) (non-zero only while
            // slipping) ...
            let dgain = scale * law.capstan * dtheta_n;
            let (dg_pos, dg_neg) = (dgain * (gains[0] + 1.0), dgain * (1.0 - gains[1]));
            let cap_theta = f.d_cap_pos * dg_pos + f.d_cap_neg * dg_neg;
            // ... times d theta/d kappa: theta = phi - beta (wrapped), so d|theta|/d kappa =
            // -sign(theta) d beta/d kappa.
            let sign = if theta < 0.0 { -1.0 } else { 1.0 };
            let dtheta = [-sign * dir.dbeta[0], -sign * dir.dbeta[1]];
            // The stored energy's dependence on the active limit, d E/d cap d cap/d kappa.
            let cap_energy = f.d_energy_cap * (f.d_cap_pos * dg_pos - f.d_cap_neg * dg_neg);
            let ms = (f.d_cap_pos * gains[0] + f.d_cap_neg * gains[1]) * dscale;
            for a in 0..2 {
                r.moment[a] += f.force * l[a];
                r.moment_strain[a] += ms * l[a];
                r.energy_turn[a] += cap_energy * dtheta[a];
                for j in 0..2 {
                    // The stick part summed symmetrically (and as in `planar` for a = j = z).
                    let stick = if a == j {
                        f.d_strain * l[a] * l[a]
                    } else {
                        f.d_strain * (l[0] * l[1])
                    };
                    r.moment_curvature[a][j] += stick + l[a] * (cap_theta * dtheta[j]);
                }
            }
            let cap_strain = (f.d_cap_pos * gains[0] - f.d_cap_neg * gains[1]) * dscale;
            r.energy += f.energy;
            r.energy_strain += f.d_energy_cap * cap_strain;
            r.slip_work += f.slip_work;
            r.slipping += usize::from(f.state == WireState::Slip);
        }
        r
    }

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
        );
        if let Some(t) = trial.get_mut(i) {
            *t = f.slip;
        }
        f
    }

    /// Per-wire report for a signed planar curvature (see [`Self::planar`]). At zero
    /// curvature the report is for bending with the convex side toward +y (`kappa_z < 0`).
    pub fn planar_wires(
        &self,
        st: &Station,
        eps: f64,
        kappa: f64,
        slip: &[f64],
    ) -> Vec<WireReport> {
        let Some(law) = self.layer else {
            return Vec::new();
        };
        let (scale, _) = self.cap_scale(eps);
        let dir = if kappa > 0.0 { 1.0 } else { -1.0 };
        st.wires
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let lever = w.lever[1] * dir; // strain per unit |kappa|
                let arm = lever.abs();
                let f = self.slide(law, i, w.lever[1] * kappa, scale, w.gains, slip, &mut []);
                // The side of the slider the force loads (the strain's side when it is zero).
                let stretched = if f.force != 0.0 {
                    f.force > 0.0
                } else {
                    lever >= 0.0
                };
                let cap = scale * w.gains[if stretched { 0 } else { 1 }];
                let factor = if self.kind == LawKind::Paper {
                    law.paper_factor
                } else {
                    1.0
                };
                // kappa_c = cap / (k_factor arm), arm = R_w sin(theta), theta = |phi|.
                let theta = w.phase.abs();
                let gain = w.gains[if stretched { 0 } else { 1 }];
                let critical = law.critical_curvature(scale, factor, gain, theta, theta.sin());
                let state = law.reported_state(f.state, arm, critical, kappa.abs());
                WireReport {
                    wire: i + 1,
                    phase: w.phase,
                    k_stick: law.k * arm * arm,
                    m_slip: cap * arm,
                    critical_curvature: critical,
                    state,
                }
            })
            .collect()
    }

    /// Per-wire report for a curvature vector `kappa = (kappa_y, kappa_z)` in the section frame
    /// (see [`Self::vector`]): each wire's phase is measured from the reference half `b` of
    /// the neutral axis of the current bending direction (the law's convention, module docs),
    /// in the sense from z toward y, wrapped to (-pi, pi]; its critical curvature is the
    /// curvature magnitude at which it slips in this bending direction, with its lever
    /// `R_w sin(theta)` and the capstan gain of its angle `theta` from `b`. With
    /// `kappa_y = 0` this is [`Self::planar_wires`] up to round-off. At zero curvature the
    /// report is for bending with the convex side toward +y.
    pub fn vector_wires(
        &self,
        st: &Station,
        eps: f64,
        kappa: [f64; 2],
        slip: &[f64],
    ) -> Vec<WireReport> {
        let Some(law) = self.layer else {
            return Vec::new();
        };
        let (scale, _) = self.cap_scale(eps);
        let knorm = kappa[0].hypot(kappa[1]);
        let n = st.wires.len();
        let still = law.still_curvature(scale);
        let tail = slip.get(n..).filter(|t| t.len() == DIRECTION_STATE);
        let dir = match tail {
            Some(t) => BendingDirection::select(kappa, still, t, None),
            None => BendingDirection::of(kappa),
        };
        let kh = if let Some(b) = tail.filter(|t| knorm <= still && t != &[0.0; 2]) {
            // The stored direction: its neutral axis's half on the side of the curvature.
            let s = if b[0] * kappa[0] + b[1] * kappa[1] > 0.0 {
                1.0
            } else {
                -1.0
            };
            [s * b[0], s * b[1]]
        } else if knorm == 0.0 {
            // At zero curvature: bending with the convex side toward +y (kappa_z < 0).
            [0.0, -1.0]
        } else {
            [kappa[0] / knorm, kappa[1] / knorm]
        };
        let factor = if self.kind == LawKind::Paper {
            law.paper_factor
        } else {
            1.0
        };
        st.wires
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let l = w.lever;
                let lambda = l[0] * kh[0] + l[1] * kh[1];
                let arm = lambda.abs();
                let phase = dir.wire_angle(w.phase);
                let theta = phase.abs();
                let gains = law.gains(theta).0;
                let e = l[0] * kappa[0] + l[1] * kappa[1];
                let f = self.slide(law, i, e, scale, gains, slip, &mut []);
                let stretched = if f.force != 0.0 {
                    f.force > 0.0
                } else {
                    lambda >= 0.0
                };
                let gain = gains[if stretched { 0 } else { 1 }];
                let critical = law.critical_curvature(scale, factor, gain, theta, theta.sin());
                let state = law.reported_state(f.state, arm, critical, knorm);
                WireReport {
                    wire: i + 1,
                    phase,
                    k_stick: law.k * arm * arm,
                    m_slip: scale * gain * arm,
                    critical_curvature: critical,
                    state,
                }
            })
            .collect()
    }

    /// Planar moment (N m) at strain `eps` and signed curvature `kappa` (1/m), bent from
    /// straight (no committed slip), averaged over `stations` evenly spaced stations of one
    /// pitch (the strand's length without a helical layer): what a bending test measures over
    /// whole pitches.
    pub fn pitch_mean_moment(&self, eps: f64, kappa: f64, stations: usize) -> f64 {
        let pitch = self
            .strand
            .layer()
            .map_or(self.strand.length(), |l| l.pitch);
        let slip = vec![0.0; self.state_len()];
        let mut trial = slip.clone();
        let sum: f64 = (0..stations)
            .map(|i| {
                let st = self.station(pitch * (i as f64 + 0.5) / stations as f64);
                self.planar(&st, eps, kappa, &slip, &mut trial).moment
            })
            .sum();
        sum / stations as f64
    }

    /// Secant bending stiffness |M| / |kappa| for a signed planar curvature (N m^2); at zero
    /// curvature its limit from the +y-convex side.
    pub fn planar_secant(&self, st: &Station, eps: f64, kappa: f64, slip: &[f64]) -> f64 {
        if kappa != 0.0 {
            let mut trial = vec![0.0; self.state_len()];
            return self.planar(st, eps, kappa, slip, &mut trial).moment / kappa;
        }
        self.base_bending
            + self
                .planar_wires(st, eps, kappa, slip)
                .iter()
                .filter(|w| w.critical_curvature.is_none_or(|c| c > 0.0))
                .map(|w| w.k_stick)
                .sum::<f64>()
    }
}

/// [`planar_continuous`] with the per-wire test for a wire without friction limits only where
/// the station's smallest gain times the friction scale leaves one possible.
#[inline(always)]
fn continuous_wires<const BOOKS: bool>(
    law: LayerLaw,
    p: &PlanarWires,
    kappa: f64,
    scale: f64,
    dscale: f64,
    r: &mut PlanarResponse,
) {
    let (k, ik) = (law.k, law.inv_k);
    if scale * p.gain_min > 0.0 {
        planar_continuous::<false, BOOKS>(k, ik, p, kappa, scale, dscale, r);
    } else {
        planar_continuous::<true, BOOKS>(k, ik, p, kappa, scale, dscale, r);
    }
}

/// [`planar_hysteretic`] with the free-wire test chosen as in [`continuous_wires`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn hysteretic_wires<const BOOKS: bool>(
    law: LayerLaw,
    p: &PlanarWires,
    kappa: f64,
    scale: f64,
    dscale: f64,
    slip: &[f64],
    trial: &mut [f64],
    r: &mut PlanarResponse,
) {
    let (k, ik) = (law.k, law.inv_k);
    if scale * p.gain_min > 0.0 {
        planar_hysteretic::<false, BOOKS>(k, ik, p, kappa, scale, dscale, slip, trial, r);
    } else {
        planar_hysteretic::<true, BOOKS>(k, ik, p, kappa, scale, dscale, slip, trial, r);
    }
}

/// The wires' part of [`SectionLaw::planar`] for the `continuous` law, added to `r`: the
/// slider of `slider.rs` inlined over parallel arrays (the same values, summed in the same
/// order), without the per-wire law dispatch and optional slip state of the generic loop.
/// `FREE`: whether a wire may have no friction limit on either side (otherwise the caller
/// has checked that none has, and the test per wire is left out). `BOOKS`: whether the
/// energy, `dE/deps`, `dM/deps` and the slipping wires are summed (else only the moment and
/// its curvature tangent, the same values).
#[inline(always)]
fn planar_continuous<const FREE: bool, const BOOKS: bool>(
    k: f64,
    inv_k: f64,
    w: &PlanarWires,
    kappa: f64,
    scale: f64,
    dscale: f64,
    r: &mut PlanarResponse,
) {
    let n = w.lever.len();
    let (lev, gp, gn) = (&w.lever[..n], &w.gain_pos[..n], &w.gain_neg[..n]);
    for i in 0..n {
        let lever = lev[i];
        let e = lever * kappa;
        let (cap_pos, cap_neg) = (scale * gp[i], scale * gn[i]);
        let stick_force = k * e;
        // Slipping on the stretched (k e > cap_pos) or the shortened (k e < -cap_neg) side;
        // without friction limits at any strain (see `slider`).
        let free = FREE && cap_pos == 0.0 && cap_neg == 0.0;
        let pos = stick_force > cap_pos || (free && stick_force >= 0.0);
        let neg = stick_force < -cap_neg;
        if !(pos || neg) {
            r.moment += stick_force * lever;
            r.moment_curvature += k * lever * lever;
            if BOOKS {
                r.energy += 0.5 * stick_force * stick_force * inv_k;
            }
            continue;
        }
        // Held at the limit: energy 1/2 k e_c^2 + cap (|e| - e_c), e_c = cap / k.
        let (cap, gain, sign) = if pos {
            (cap_pos, gp[i], 1.0)
        } else {
            (cap_neg, gn[i], -1.0)
        };
        r.moment += sign * cap * lever;
        if BOOKS {
            let ec = cap * inv_k;
            r.moment_strain += sign * gain * dscale * lever;
            r.energy += 0.5 * cap * ec + cap * (e.abs() - ec);
            r.energy_strain += (e.abs() - ec) * (gain * dscale);
            r.slipping += 1;
        }
    }
}

/// The wires' part of [`SectionLaw::planar`] for the `hysteretic` law (return mapping from the
/// committed `slip` into `trial`), added to `r`: the slider of `slider.rs` inlined over
/// parallel arrays (the same values, summed in the same order). `FREE` and `BOOKS` as for
/// [`planar_continuous`]; without the books `trial` is not written (it may be empty).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn planar_hysteretic<const FREE: bool, const BOOKS: bool>(
    k: f64,
    inv_k: f64,
    w: &PlanarWires,
    kappa: f64,
    scale: f64,
    dscale: f64,
    slip: &[f64],
    trial: &mut [f64],
    r: &mut PlanarResponse,
) {
    let n = w.lever.len();
    let (lev, gp, gn) = (&w.lever[..n], &w.gain_pos[..n], &w.gain_neg[..n]);
    let slip = &slip[..n];
    let trial = if BOOKS { &mut trial[..n] } else { &mut [][..] };
    for i in 0..n {
        let lever = lev[i];
        let e = lever * kappa;
        let (cap_pos, cap_neg) = (scale * gp[i], scale * gn[i]);
        let committed = slip[i];
        let elastic = k * (e - committed);
        let free = FREE && cap_pos == 0.0 && cap_neg == 0.0;
        let pos = elastic > cap_pos || (free && elastic >= 0.0);
        let neg = elastic < -cap_neg;
        if !(pos || neg) {
            r.moment += elastic * lever;
            r.moment_curvature += k * lever * lever;
            if BOOKS {
                trial[i] = committed;
                r.energy += 0.5 * elastic * elastic * inv_k;
            }
            continue;
        }
        // Return mapping: the slip puts the wire on its friction limit. The stored energy is
        // 1/2 F^2 / k; the slip work books the energy change of a moving limit (no
        // energy_strain term).
        let (cap, gain, force) = if pos {
            (cap_pos, gp[i], cap_pos)
        } else {
            (cap_neg, -gn[i], -cap_neg)
        };
        r.moment += force * lever;
        if BOOKS {
            let s = e - force * inv_k;
            trial[i] = s;
            r.moment_strain += gain * dscale * lever;
            r.energy += 0.5 * cap * cap * inv_k;
            r.slip_work += cap * (s - committed).abs();
            r.slipping += 1;
        }
    }
}

/// State values per station that hold the stored bending direction of the hysteretic law
/// (after the wires' slips): the unit vector `b` (y, z) of the neutral axis's reference half of
/// the last committed bending beyond the still curvature, (0, 0) before any.
const DIRECTION_STATE: usize = 2;

/// The bending direction of a curvature vector as the section law reads it: the angle `beta`
/// of the reference half `b` of the neutral axis (module docs), measured from z toward y as
/// the wire phases are, and d beta / d kappa (m).
struct BendingDirection {
    beta: f64,
    dbeta: [f64; 2],
}

impl BendingDirection {
    /// The direction of `kappa`; for zero curvature `b = +z` with no derivative.
    #[inline(always)]
    fn of(kappa: [f64; 2]) -> Self {
        let n = kappa[0].hypot(kappa[1]);
        if n == 0.0 {
            return BendingDirection {
                beta: 0.0,
                dbeta: [0.0; 2],
            };
        }
        let b = neutral_axis(kappa);
        // beta = atan2(kappa_y, kappa_z) up to a constant (0 or pi).
        BendingDirection {
            beta: b[0].atan2(b[1]),
            dbeta: [kappa[1] / n / n, -kappa[0] / n / n],
        }
    }

    /// The direction the hysteretic law reads at curvature `kappa` with the stored direction
    /// `tail` ([`DIRECTION_STATE`] values): `kappa`'s own beyond the still curvature `still`
    /// (1/m), else the stored one (`kappa`'s own if none is stored yet); writes the trial
    /// tail, the direction of `kappa` beyond `still`, else the stored one (module docs).
    #[inline(always)]
    fn select(kappa: [f64; 2], still: f64, tail: &[f64], trial: Option<&mut [f64]>) -> Self {
        let stored = [tail[0], tail[1]];
        let (dir, axis) = if kappa[0].hypot(kappa[1]) > still {
            (Self::of(kappa), neutral_axis(kappa))
        } else if stored != [0.0; 2] {
            let dir = BendingDirection {
                beta: stored[0].atan2(stored[1]),
                dbeta: [0.0; 2],
            };
            (dir, stored)
        } else {
            (Self::of(kappa), stored)
        };
        if let Some(t) = trial {
            t[..DIRECTION_STATE].copy_from_slice(&axis);
        }
        dir
    }

    /// Signed angle (rad, in (-pi, pi]) of the wire at `phase` from `b`: the phase itself
    /// when `b = +z` (planar bending), so that the planar law's values are met bit for bit.
    #[inline(always)]
    fn wire_angle(&self, phase: f64) -> f64 {
        if self.beta == 0.0 {
            phase
        } else {
            crate::geometry::wrap_angle(phase - self.beta)
        }
    }
}

/// [`LayerLaw::still_per_scale`]. A wire at angle `theta` from the neutral axis slips when `k
/// R_w |kappa| sin(theta)` exceeds its friction limit `scale gain`, so no wire without residual
/// slip slips below `scale min(gain / sin(theta)) / (k R_w)`. The smaller gain, the shortened
/// side's `1 - exp(-c theta_n)` (`c = mu sin(alpha)`), over `sin(theta) <= theta_n` is at least
/// `(1 - exp(-c theta_n)) / theta_n`, which falls with `theta_n`: at least its value at the
/// largest capstan angle `theta_max`, pi/2 from the nearest crossing (Papailiou), pi from the
/// reference half (the paper's limit).
fn still_per_scale(capstan: f64, limit: SlipLimit, k: f64, radius: f64) -> f64 {
    let theta_max = match limit {
        SlipLimit::Papailiou => 0.5 * std::f64::consts::PI,
        SlipLimit::Paper => std::f64::consts::PI,
    };
    -(-capstan * theta_max).exp_m1() / theta_max / (k * radius)
}

/// Reference half of the neutral axis for a curvature vector: the unit vector along `kappa`
/// with a non-negative z component (+y when `kappa_z = 0`); +z for zero curvature.
fn neutral_axis(kappa: [f64; 2]) -> [f64; 2] {
    let n = kappa[0].hypot(kappa[1]);
    if n == 0.0 {
        return [0.0, 1.0];
    }
    let s = if kappa[1] > 0.0 || (kappa[1] == 0.0 && kappa[0] >= 0.0) {
        1.0
    } else {
        -1.0
    };
    [s * kappa[0] / n, s * kappa[1] / n]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::StrandSpec;

    /// The inlined planar loops of the `continuous` and `hysteretic` laws give exactly the
    /// generic slider's values, sticking and slipping on both sides.
    #[test]
    fn inlined_planar_loops_match_the_slider() {
        let strand = Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap();
        for kind in [LawKind::Continuous, LawKind::Hysteretic] {
            let law = SectionLaw::new(&strand, kind);
            let layer = law.layer.unwrap();
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
                let sd = law.cap_scale(eps);
                law.planar_wires_generic(layer, &st, kappa, sd, &slip, &mut t_gen, &mut generic);
                assert_eq!(fast, generic, "{kind} at station {j}");
                assert_eq!(t_fast, t_gen);
                count[usize::from(fast.slipping > 0 && fast.slipping < n)] += 1;
                // Both kernels: with the test for wires without friction limits and without.
                paths[usize::from(sd.0 * st.planar.gain_min > 0.0)] += 1;
            }
            assert!(count[0] > 0 && count[1] > 0, "{kind}: {count:?}");
            assert!(paths[0] > 0 && paths[1] > 0, "{kind}: {paths:?}");
        }
    }
}
