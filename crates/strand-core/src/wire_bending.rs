//! Frictionless bending stiffness of one helical wire: its share of the strand's all-slip
//! bending stiffness K_min (N m^2, per unit strand length, about the strand's bending axis).
//!
//! # The thin-rod picture
//!
//! When the strand bends with curvature kappa (1/m) and the helical wires slide freely on the
//! core, each wire bends and twists with the strand's cross-section. A wire at lay angle alpha
//! turns with the section by kappa per unit strand length, that is kappa cos(alpha) per unit
//! wire length. Resolved in the wire's frame at its angular position theta around the core,
//! that rotation rate has a component kappa cos(alpha) cos(theta) about the radial direction
//! (bending), kappa cos^2(alpha) sin(theta) about the wire's binormal (bending) and
//! kappa cos(alpha) sin(alpha) sin(theta) about its tangent (twist). With the wire's bending
//! stiffness E I and torsional stiffness G J = E I / (1 + nu) (round wire, J = 2 I), the
//! energy per unit strand length, averaged over theta, is
//!
//! ```text
//! 1/2 kappa^2 E I cos(alpha) [ (1 + cos^2 alpha) / 2 + sin^2(alpha) / (2 (1 + nu)) ]
//! ```
//!
//! The bracket averages the bending and torsional stiffnesses with the weights
//! (1 + cos^2 alpha)/2 and sin^2(alpha)/2: this is the [`BaseStiffness::Foti`] form, the
//! energy of a wire made to follow the section's rotation exactly (a wire free to relax
//! stores less). Costello's thin-rod (Love) result for a strand bent without friction,
//! [`BaseStiffness::Costello`], averages the compliances with the same weights instead:
//! `1 / [ (1 + cos^2 alpha)/2 + (1 + nu) sin^2(alpha)/2 ] = 2 / (2 + nu sin^2 alpha)`, and lies
//! below Foti's by cos(alpha) nu^2 sin^2(alpha) / (2 (1 + nu)) E I to leading order. With
//! nu = 0 (torsional and bending stiffness equal) both reduce to E I cos(alpha),
//! [`BaseStiffness::Papailiou`]; the paper's E I cos^3(alpha) ([`BaseStiffness::Paper`])
//! applies the axial loss factor eta = cos^3(alpha) of eq. (10) to the wire's bending and
//! leaves out the torsion. At alpha -> 0 every form is E I, the straight wire; they differ at
//! second order in alpha:
//!
//! | form | E I times | at 20 deg, nu = 0.3 |
//! |---|---|---:|
//! | `costello` | cos(alpha) 2 / (2 + nu sin^2 alpha) | 0.9235 |
//! | `foti` | cos(alpha) [1 + cos^2 alpha + sin^2(alpha) / (1 + nu)] / 2 | 0.9270 |
//! | `papailiou` | cos(alpha) | 0.9397 |
//! | `paper` | cos^3(alpha) | 0.8298 |
//!
//! Sources: G. A. Costello, *Theory of Wire Rope* (2nd ed., Springer 1997), the bending of a
//! strand with frictionless wires; F. Foti and L. Martinelli (2016), "An analytical approach to
//! model the hysteretic bending behavior of spiral strands" and "Mechanical modeling of
//! metallic strands subjected to tension, torsion and bending" (Int. J. Solids Struct.), the
//! all-slip (minimum) bending stiffness, which equals Lehanneur's (1949) E I cos(alpha)
//! (1 - nu sin^2(alpha) / (2 (1 + nu))); K. O. Papailiou (1997), "On the bending stiffness of
//! transmission line conductors", IEEE Trans. Power Delivery 12(4), the minimum stiffness
//! EI_min = sum E I cos(alpha); the three are collected side by side in A. Cloutier (2013),
//! *Stick-slip mechanical models for overhead electrical conductors in bending*, M.Sc. thesis,
//! Universite Laval, section 2.3. Equation numbers inside those texts are not quoted here: the
//! derivation above is what each form is checked against (`tests/wire_bending.rs`), and the
//! fine model's frictionless virtual bending test measures it (`cargo xtask stiffness`).

use crate::wire::WireSpec;

/// Which frictionless bending stiffness of a helical wire the section laws use as the base of
/// K_min (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BaseStiffness {
    /// E I cos(alpha) 2 / (2 + nu sin^2 alpha): thin-rod equilibrium with the wire's torsion
    /// (Costello). The default.
    #[default]
    Costello,
    /// E I cos(alpha) [1 + cos^2 alpha + sin^2(alpha) / (1 + nu)] / 2: the wire turning with
    /// the section (Foti and Martinelli; Lehanneur).
    Foti,
    /// E I cos(alpha): torsion as stiff as bending (Papailiou).
    Papailiou,
    /// E I cos^3(alpha): the paper's loss factor eta applied to bending (eqs. (10), (11)).
    Paper,
}

impl BaseStiffness {
    /// Every form, in the order of the module docs.
    pub const ALL: [BaseStiffness; 4] = [
        BaseStiffness::Costello,
        BaseStiffness::Foti,
        BaseStiffness::Papailiou,
        BaseStiffness::Paper,
    ];

    /// Name as used in scene files (`section.base_stiffness`).
    pub fn name(self) -> &'static str {
        match self {
            BaseStiffness::Costello => "costello",
            BaseStiffness::Foti => "foti",
            BaseStiffness::Papailiou => "papailiou",
            BaseStiffness::Paper => "paper",
        }
    }

    /// The form named `name` (as in scene files), if any.
    pub fn from_name(name: &str) -> Option<BaseStiffness> {
        Self::ALL.into_iter().find(|b| b.name() == name)
    }

    /// The factor f of the wire's own bending stiffness: the wire contributes f E I to K_min
    /// (-), for lay angle `lay_angle` (rad) and Poisson ratio `poisson_ratio` (-).
    pub fn factor(self, lay_angle: f64, poisson_ratio: f64) -> f64 {
        let (s, c) = lay_angle.sin_cos();
        let (s2, c2) = (s * s, c * c);
        match self {
            BaseStiffness::Costello => c * 2.0 / (2.0 + poisson_ratio * s2),
            BaseStiffness::Foti => 0.5 * c * (1.0 + c2 + s2 / (1.0 + poisson_ratio)),
            BaseStiffness::Papailiou => c,
            BaseStiffness::Paper => c * c2,
        }
    }

    /// Frictionless bending stiffness of one helical wire `wire` laid at `lay_angle` (rad), per
    /// unit strand length (N m^2): [`Self::factor`] times E I of the wire.
    pub fn wire_stiffness(self, wire: &WireSpec, lay_angle: f64) -> f64 {
        self.factor(lay_angle, wire.material.poisson_ratio)
            * wire.material.youngs_modulus
            * wire.inertia()
    }
}

impl std::fmt::Display for BaseStiffness {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
