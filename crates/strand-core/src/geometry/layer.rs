//! One helical layer: its inputs ([`LayerSpec`]) and the derived helix ([`HelixLayer`]).

use std::f64::consts::PI;

use crate::wire::WireSpec;

/// Sense in which the helical wires wind along the strand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LayDirection {
    /// Phase grows with the material coordinate: phi = phi_0 + 2 pi x / P (eq. 36).
    #[default]
    Right,
    /// Phase falls with the material coordinate: phi = phi_0 - 2 pi x / P.
    Left,
}

impl LayDirection {
    /// +1 for right lay, -1 for left lay.
    pub fn sign(self) -> f64 {
        match self {
            LayDirection::Right => 1.0,
            LayDirection::Left => -1.0,
        }
    }

    /// Name as used in scene files (`lay_direction`).
    pub fn name(self) -> &'static str {
        match self {
            LayDirection::Right => "right",
            LayDirection::Left => "left",
        }
    }
}

impl std::fmt::Display for LayDirection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Inputs of one helical layer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerSpec {
    /// Number of helical wires m (at least 1).
    pub wires: usize,
    /// The helical wires' cross-section and material.
    pub wire: WireSpec,
    /// Lay angle alpha between a wire's axis and the strand axis (rad), in (0, pi/2).
    pub lay_angle: f64,
    /// Phase phi_0 of wire 1 at x = 0 (rad).
    pub phase: f64,
    /// Lay direction.
    pub direction: LayDirection,
}

/// A helical layer with its derived quantities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelixLayer {
    /// The inputs this layer was built from.
    pub spec: LayerSpec,
    /// Helix radius R_w (m): stacked wire on wire from the core (module `stack`), lifted by
    /// `lift` where the layer is closed.
    pub radius: f64,
    /// Pitch (lay length) P = 2 pi R_w / tan(alpha) (m).
    pub pitch: f64,
    /// Stiffness loss factor eta = cos^3(alpha) (eq. 10).
    pub eta: f64,
    /// How far the closed layer's wires stand off the layer beneath so that neighbours touch
    /// (m); 0 for a layer with room between its wires (module `stack`).
    pub lift: f64,
}

impl HelixLayer {
    /// Number of wires m.
    pub fn wires(&self) -> usize {
        self.spec.wires
    }
    /// Lay angle alpha (rad).
    pub fn lay_angle(&self) -> f64 {
        self.spec.lay_angle
    }
    /// Lay direction.
    pub fn direction(&self) -> LayDirection {
        self.spec.direction
    }
    /// Helix curvature kappa_w = sin^2(alpha) / R_w (1/m), eq. (5).
    pub fn helix_curvature(&self) -> f64 {
        self.spec.lay_angle.sin().powi(2) / self.radius
    }
    /// Helix torsion tau_w = sin(alpha) cos(alpha) / R_w (1/m), signed by the lay direction.
    pub fn helix_torsion(&self) -> f64 {
        let a = self.spec.lay_angle;
        self.spec.direction.sign() * a.sin() * a.cos() / self.radius
    }
    /// Axial stiffness of one wire projected on the strand axis, eta E_w A_w (N), eq. (31).
    pub fn wire_axial_stiffness(&self) -> f64 {
        self.eta * self.spec.wire.material.youngs_modulus * self.spec.wire.area()
    }
    /// Phase of wire `i` (0-based) at material coordinate `x`, wrapped to (-pi, pi],
    /// eqs. (36), (37).
    pub fn phase(&self, i: usize, x: f64) -> f64 {
        let m = self.spec.wires as f64;
        let raw = self.spec.phase
            + 2.0 * PI * i as f64 / m
            + self.spec.direction.sign() * 2.0 * PI * x / self.pitch;
        wrap_angle(raw)
    }
    /// Length of one wire per unit strand length, 1 / cos(alpha).
    pub fn wire_length_ratio(&self) -> f64 {
        1.0 / self.spec.lay_angle.cos()
    }
    /// Gap between neighbouring wires of the layer measured across the wires (m); negative
    /// when they overlap. Uses the SPEC 1 criterion 2 R_w sin(pi/m) - d_w / cos(alpha): the
    /// chord between neighbouring wire centres in a cross-section against the width of a
    /// wire's section along the circle. A single wire's neighbour is its own next turn, a whole
    /// circle away: 2 pi R_w - d_w / cos(alpha) (equivalently, its turns P apart along the
    /// strand overlap when P sin(alpha) < d_w), so that a wire laid near 90 deg is refused too.
    pub fn wire_gap(&self) -> f64 {
        wire_gap(&self.spec, self.radius)
    }
}

/// [`HelixLayer::wire_gap`] of the layer `spec` on the helix radius `radius` (m).
pub(crate) fn wire_gap(spec: &LayerSpec, radius: f64) -> f64 {
    let width = spec.wire.diameter / spec.lay_angle.cos();
    if spec.wires < 2 {
        return 2.0 * PI * radius - width;
    }
    2.0 * radius * (PI / spec.wires as f64).sin() - width
}

/// The chord between neighbouring wire centres per unit helix radius and per 2: sin(pi/m),
/// or pi for a single wire (its own next turn, a whole circle away).
pub(crate) fn neighbour_chord(wires: usize) -> f64 {
    if wires < 2 {
        PI
    } else {
        (PI / wires as f64).sin()
    }
}

/// Wraps an angle to (-pi, pi].
pub fn wrap_angle(phi: f64) -> f64 {
    let w = phi.rem_euclid(2.0 * PI);
    if w > PI { w - 2.0 * PI } else { w }
}
