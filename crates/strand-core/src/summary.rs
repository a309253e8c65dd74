//! What a strand calculator prints: the derived quantities of SPEC 1 and 2 and, for a given
//! strain and curvature, the section's response with a table per wire (`strand section`).

use serde::Serialize;

use crate::bonded::StickStiffness;
use crate::geometry::{Contact, Strand};
use crate::section::{LawKind, SectionLaw, SectionOptions, SlipLimit, SlipPressure, WireReport};
use crate::wire_bending::BaseStiffness;

/// Derived quantities of a strand (keys as in SPEC 6 `strand section --json`). The top-level
/// layer quantities are the first layer's (`None` for a plain wire); `layers` has every
/// layer's.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct StrandSummary {
    /// Helix radius R_w (m).
    #[serde(rename = "R_w")]
    pub r_w: Option<f64>,
    /// Pitch P (m).
    pub pitch: Option<f64>,
    /// Lay angle alpha (deg).
    pub lay_angle_deg: Option<f64>,
    /// Stiffness loss factor eta = cos^3(alpha).
    pub eta: Option<f64>,
    /// Gap between neighbouring helical wires (m).
    pub wire_gap: Option<f64>,
    /// Mass per length (kg/m), eq. (44).
    pub mass_per_length: f64,
    /// Equivalent axial stiffness EA_eq (N), eq. (32).
    #[serde(rename = "EA")]
    pub ea: f64,
    /// Which frictionless wire bending stiffness K_min uses (`section.base_stiffness`).
    pub base_stiffness: BaseStiffness,
    /// All-slip bending stiffness K_min the section laws use (N m^2): eq. (11) with the wire
    /// term in the form `base_stiffness`.
    #[serde(rename = "K_min")]
    pub k_min: f64,
    /// The paper's K_min, with eta = cos^3(alpha) (N m^2), eq. (11).
    #[serde(rename = "K_min_paper")]
    pub k_min_paper: f64,
    /// Which stick stiffness the helical wires have (`section.stick_stiffness`).
    pub stick_stiffness: StickStiffness,
    /// Factor on the plane-section stick stiffness of the first layer's wires (-): the rod
    /// model's for `bonded`, 1 for `plane_section`; `None` for a plain wire. Each layer's is
    /// [`LayerSummary::stick_factor`].
    pub stick_factor: Option<f64>,
    /// Which friction limit the slipping wires have (`section.slip_limit`).
    pub slip_limit: SlipLimit,
    /// All-stick bending stiffness the section laws use (N m^2): K_min plus eq. (22a) summed,
    /// times `stick_factor`.
    #[serde(rename = "K_max")]
    pub k_max: f64,
    /// The plane-section all-stick stiffness, K_min plus eq. (22a) summed (N m^2): the
    /// paper's K_max with this K_min.
    #[serde(rename = "K_max_plane_section")]
    pub k_max_plane_section: f64,
    /// Traditional beam bending stiffness EI (N m^2).
    #[serde(rename = "EI_traditional")]
    pub ei_traditional: f64,
    /// Traditional beam axial stiffness EA (N).
    #[serde(rename = "EA_traditional")]
    pub ea_traditional: f64,
    /// Which contact pressure sets the friction limits (`section.slip_pressure`).
    pub slip_pressure: SlipPressure,
    /// Every layer, from the core outward.
    pub layers: Vec<LayerSummary>,
}

/// One layer's derived quantities and its shares of the section's stiffnesses.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct LayerSummary {
    /// Layer number, 1-based from the core outward.
    pub layer: usize,
    /// Number of wires.
    pub wires: usize,
    /// Wire diameter (m).
    pub diameter: f64,
    /// Helix radius R_w (m).
    #[serde(rename = "R_w")]
    pub r_w: f64,
    /// How far the closed layer stands off the layer beneath (m).
    pub lift: f64,
    /// Pitch P (m).
    pub pitch: f64,
    /// Lay angle alpha (deg).
    pub lay_angle_deg: f64,
    /// Lay direction.
    pub lay_direction: String,
    /// Angle between this layer's wires and those beneath (deg).
    pub crossing_angle_deg: f64,
    /// Contact with the layer beneath: `line` or `crossing`.
    pub contact: Contact,
    /// Gap between neighbouring wires (m).
    pub wire_gap: Option<f64>,
    /// The layer's share of K_min, m K_w (N m^2).
    #[serde(rename = "K_min")]
    pub k_min: f64,
    /// The stick factor of the layer's interface (-).
    pub stick_factor: f64,
    /// The layer's stick stiffness, (m/2) f eta E_w A_w R_w^2 (N m^2).
    #[serde(rename = "K_stick")]
    pub k_stick: f64,
    /// Friction limit per unit strand strain of a wire at pi/2 from the neutral axis, the
    /// extreme fibre, on the stretched side (N).
    pub slip_force_per_strain: f64,
}

/// Response of a section to a given strain and curvature.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SectionPoint {
    /// Section law.
    pub law: LawKind,
    /// Axial strain eps (-).
    pub strain: f64,
    /// Signed planar curvature `kappa_z` (1/m): positive when the strand turns
    /// counter-clockwise seen from +Z (convex side toward -y for a strand along +x), negative
    /// for the paper's hanging cantilever (convex side toward +y); the convention of the
    /// result files.
    pub curvature: f64,
    /// Material coordinate x (m).
    pub at: f64,
    /// Axial force (N).
    pub axial_force: f64,
    /// Bending moment `M_z`, signed like `curvature` (N m).
    pub moment: f64,
    /// Secant bending stiffness M / kappa (N m^2).
    pub secant_stiffness: f64,
    /// Tangent bending stiffness dM/dkappa (N m^2).
    pub tangent_stiffness: f64,
    /// Smallest critical curvature of the wires: where slip starts (1/m).
    pub first_slip_curvature: Option<f64>,
    /// Largest finite critical curvature: beyond it every wire with a lever slips (1/m).
    pub full_slip_curvature: Option<f64>,
    /// Per-wire table.
    pub wires: Vec<WireReport>,
}

impl StrandSummary {
    /// Summarises `strand` with the section `options`.
    pub fn new(strand: &Strand, options: &SectionOptions) -> Self {
        let base = options.base_stiffness;
        let l = strand.layers().first();
        let t = strand.traditional();
        let law = SectionLaw::with_options(strand, LawKind::Continuous, options);
        StrandSummary {
            r_w: l.map(|l| l.radius),
            pitch: l.map(|l| l.pitch),
            lay_angle_deg: l.map(|l| l.lay_angle().to_degrees()),
            eta: l.map(|l| l.eta),
            wire_gap: l.map(|l| l.wire_gap()).filter(|g| g.is_finite()),
            mass_per_length: strand.mass_per_length(),
            ea: strand.axial_stiffness(),
            base_stiffness: base,
            k_min: strand.min_bending_stiffness(base),
            k_min_paper: strand.min_bending_stiffness(BaseStiffness::Paper),
            stick_stiffness: options.stick_stiffness,
            stick_factor: l.map(|_| options.stick_stiffness.factor(strand, 0)),
            slip_limit: options.slip_limit,
            k_max: law.stick_bending_stiffness(),
            k_max_plane_section: strand.max_bending_stiffness(base),
            ei_traditional: t.bending_stiffness,
            ea_traditional: t.axial_stiffness,
            slip_pressure: options.slip_pressure,
            layers: strand
                .layers()
                .iter()
                .zip(strand.interfaces())
                .enumerate()
                .map(|(j, (h, i))| LayerSummary {
                    layer: j + 1,
                    wires: h.wires(),
                    diameter: h.spec.wire.diameter,
                    r_w: h.radius,
                    lift: h.lift,
                    pitch: h.pitch,
                    lay_angle_deg: h.lay_angle().to_degrees(),
                    lay_direction: h.direction().name().to_string(),
                    crossing_angle_deg: i.crossing_angle.to_degrees(),
                    contact: i.contact,
                    wire_gap: Some(h.wire_gap()).filter(|g| g.is_finite()),
                    k_min: strand.layer_min_bending(h, base),
                    stick_factor: options.stick_stiffness.factor(strand, j),
                    k_stick: law.layer_stick_stiffness(j),
                    slip_force_per_strain: law.friction_limit(j, 1.0, 0.5 * std::f64::consts::PI)
                        [0],
                })
                .collect(),
        }
    }
}

impl SectionPoint {
    /// Evaluates `law` of `strand` (with the section `options`) at strain `eps`, signed planar
    /// curvature `curvature` (`kappa_z`, see the field) and material coordinate `at`, from a
    /// state without slip.
    pub fn new(
        strand: &Strand,
        law: LawKind,
        options: &SectionOptions,
        eps: f64,
        curvature: f64,
        at: f64,
    ) -> Self {
        let law_ = SectionLaw::with_options(strand, law, options);
        let st = law_.station(at);
        let kappa = curvature;
        let slip = vec![0.0; law_.state_len()];
        let mut trial = slip.clone();
        let r = law_.planar(&st, eps, kappa, &slip, &mut trial);
        let wires = law_.planar_wires(&st, eps, kappa, &slip);
        let crit = wires.iter().filter_map(|w| w.critical_curvature);
        SectionPoint {
            law,
            strain: eps,
            curvature,
            at,
            axial_force: r.axial_force,
            moment: r.moment,
            secant_stiffness: law_.planar_secant(&st, eps, kappa, &slip),
            tangent_stiffness: r.moment_curvature,
            first_slip_curvature: crit.clone().reduce(f64::min),
            full_slip_curvature: crit.reduce(f64::max),
            wires,
        }
    }
}
