//! What the section laws return: the section's response and the per-wire reports.

use super::WireState;

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
    /// Work dissipated by slip from the committed state to this trial (J/m; hysteretic law):
    /// the trapezoid of each slipping wire's friction limit over the step (module `slip_work`).
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
    /// Work dissipated by slip from the committed state to this trial (J/m; hysteretic law):
    /// the trapezoid of each slipping wire's friction limit over the step (module `slip_work`).
    pub slip_work: f64,
    /// Number of slipping wires.
    pub slipping: usize,
}

/// The bending moment of [`super::SectionLaw::planar_moment`] and its curvature tangent, without
/// the books (energy, slip work, slipping wires) that [`super::SectionLaw::planar`] keeps.
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
    /// Wire number within its layer, 1-based as in the paper.
    pub wire: usize,
    /// Layer number, 1-based from the core outward.
    pub layer: usize,
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
