//! One round wire: its material and cross-section (plain data, SI units).

use std::f64::consts::PI;

/// Linear elastic isotropic material of one wire.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson ratio nu (-), in (-1, 0.5].
    pub poisson_ratio: f64,
    /// Density rho (kg/m^3).
    pub density: f64,
}

impl Material {
    /// Shear modulus G = E / (2 (1 + nu)) (Pa).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }
}

/// Round wire cross-section of a given material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WireSpec {
    /// Wire diameter d (m).
    pub diameter: f64,
    /// Wire material.
    pub material: Material,
}

impl WireSpec {
    /// Radius d/2 (m).
    pub fn radius(&self) -> f64 {
        0.5 * self.diameter
    }
    /// Cross-section area A = pi d^2 / 4 (m^2).
    pub fn area(&self) -> f64 {
        PI * self.diameter * self.diameter / 4.0
    }
    /// Second moment of area I = pi d^4 / 64 (m^4).
    pub fn inertia(&self) -> f64 {
        PI * self.diameter.powi(4) / 64.0
    }
    /// Polar moment of area J = 2 I (m^4).
    pub fn polar_inertia(&self) -> f64 {
        2.0 * self.inertia()
    }
}
