//! Strand geometry and materials (SPEC 1; paper section 1.1).
//!
//! A `1+m` strand is a straight core wire with one layer of `m` helical wires laid around it.
//! [`StrandSpec`] holds the inputs as a user gives them; [`Strand`] is the validated strand with
//! every derived quantity (helix radius, pitch, stiffness loss factor, areas, inertias, mass per
//! length, axial and bending stiffnesses). All quantities are SI: metres, pascals, kg/m^3,
//! radians.

use std::f64::consts::PI;

use crate::error::InputError;
use crate::wire_bending::BaseStiffness;

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
}

/// Inputs of the helical layer.
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

/// Inputs of a strand: length, core, at most one helical layer and the wire-core friction.
#[derive(Debug, Clone, PartialEq)]
pub struct StrandSpec {
    /// Strand length L (m).
    pub length: f64,
    /// Straight core wire.
    pub core: WireSpec,
    /// Helical layers; this version supports zero (a plain wire) or one.
    pub layers: Vec<LayerSpec>,
    /// Coulomb friction coefficient mu between the helical wires and the core (-).
    pub friction: f64,
}

impl StrandSpec {
    /// The paper's 1+6 strand (Table 1 geometry: core 3 mm, six 2 mm wires at 20 deg, phase 0,
    /// right lay, friction 0.3) with the given length (m), Young's modulus (Pa) and density
    /// (kg/m^3), the same for every wire: Table 1 is (0.4, 2e8, 7801), section 3 is
    /// (1.0, 2e9, 5747).
    pub fn paper(length: f64, youngs_modulus: f64, density: f64) -> StrandSpec {
        let material = Material {
            youngs_modulus,
            poisson_ratio: 0.3,
            density,
        };
        StrandSpec {
            length,
            core: WireSpec {
                diameter: 3.0e-3,
                material,
            },
            layers: vec![LayerSpec {
                wires: 6,
                wire: WireSpec {
                    diameter: 2.0e-3,
                    material,
                },
                lay_angle: 20f64.to_radians(),
                phase: 0.0,
                direction: LayDirection::Right,
            }],
            friction: DEFAULT_FRICTION,
        }
    }
}

/// Default friction coefficient when a scene gives none (SPEC 9: the paper does not state it).
pub const DEFAULT_FRICTION: f64 = 0.3;

/// The helical layer with its derived quantities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelixLayer {
    /// The inputs this layer was built from.
    pub spec: LayerSpec,
    /// Helix radius R_w = r_c + r_w (m): the wires touch the core.
    pub radius: f64,
    /// Pitch (lay length) P = 2 pi R_w / tan(alpha) (m).
    pub pitch: f64,
    /// Stiffness loss factor eta = cos^3(alpha) (eq. 10).
    pub eta: f64,
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
        let width = self.spec.wire.diameter / self.spec.lay_angle.cos();
        if self.spec.wires < 2 {
            return 2.0 * PI * self.radius - width;
        }
        2.0 * self.radius * (PI / self.spec.wires as f64).sin() - width
    }
}

/// Wraps an angle to (-pi, pi].
pub fn wrap_angle(phi: f64) -> f64 {
    let w = phi.rem_euclid(2.0 * PI);
    if w > PI { w - 2.0 * PI } else { w }
}

/// Constant-stiffness beam of the traditional model: the envelope cylinder of diameter
/// d_c + 2 d_w made of the core's material (SPEC 2, `constant` law).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraditionalBeam {
    /// Envelope diameter (m).
    pub diameter: f64,
    /// Bending stiffness EI (N m^2).
    pub bending_stiffness: f64,
    /// Axial stiffness EA (N).
    pub axial_stiffness: f64,
}

/// A validated strand with its derived quantities (SPEC 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Strand {
    spec: StrandSpec,
    layer: Option<HelixLayer>,
}

impl Strand {
    /// Validates the inputs and derives the strand. Errors name the offending field with the
    /// scene format's path below `strand` (e.g. `layers[0].lay_angle_deg`).
    pub fn new(spec: StrandSpec) -> Result<Self, InputError> {
        in_range("length", spec.length, LENGTH_RANGE, "m")?;
        check_wire("core", &spec.core)?;
        non_negative("friction", spec.friction)?;
        if spec.layers.len() > 1 {
            return Err(InputError::new(
                "layers[1]",
                "only one helical layer is supported (a 1+m strand)",
            ));
        }
        let mut layer = None;
        for (k, l) in spec.layers.iter().enumerate() {
            let p = |f: &str| format!("layers[{k}].{f}");
            if l.wires < 1 {
                return Err(InputError::new(p("wires"), "must be at least 1"));
            }
            check_wire(&format!("layers[{k}]"), &l.wire)?;
            if !l.lay_angle.is_finite() || l.lay_angle <= 0.0 || l.lay_angle >= 0.5 * PI {
                return Err(InputError::new(
                    p("lay_angle_deg"),
                    format!("must be in (0, 90), got {}", l.lay_angle.to_degrees()),
                ));
            }
            finite(&p("phase_deg"), l.phase)?;
            let radius = spec.core.radius() + l.wire.radius();
            let h = HelixLayer {
                spec: *l,
                radius,
                pitch: 2.0 * PI * radius / l.lay_angle.tan(),
                eta: l.lay_angle.cos().powi(3),
            };
            let gap = h.wire_gap();
            if gap.is_nan() || gap < 0.0 {
                let rule = if l.wires == 1 {
                    "a single wire's neighbouring turns need 2 pi R_w >= d_w / cos(alpha)"
                } else {
                    "neighbouring wires need 2 R_w sin(pi/m) >= d_w / cos(alpha)"
                };
                return Err(InputError::new(
                    p("wires"),
                    format!(
                        "{} wires of diameter {} m at lay angle {:.4} deg overlap: {rule} (short \
                         by {:.3e} m)",
                        l.wires,
                        l.wire.diameter,
                        l.lay_angle.to_degrees(),
                        -gap
                    ),
                ));
            }
            layer = Some(h);
        }
        Ok(Strand { spec, layer })
    }

    /// The inputs.
    pub fn spec(&self) -> &StrandSpec {
        &self.spec
    }
    /// Strand length L (m).
    pub fn length(&self) -> f64 {
        self.spec.length
    }
    /// The core wire.
    pub fn core(&self) -> &WireSpec {
        &self.spec.core
    }
    /// The helical layer, if any.
    pub fn layer(&self) -> Option<&HelixLayer> {
        self.layer.as_ref()
    }
    /// Wire-core friction coefficient mu.
    pub fn friction(&self) -> f64 {
        self.spec.friction
    }

    /// Mass per unit strand length rho_c A_c + m rho_w A_w / cos(alpha) (kg/m), eq. (44).
    pub fn mass_per_length(&self) -> f64 {
        let core = self.spec.core.material.density * self.spec.core.area();
        core + self.layer.as_ref().map_or(0.0, |l| {
            l.wires() as f64 * l.spec.wire.material.density * l.spec.wire.area()
                / l.lay_angle().cos()
        })
    }

    /// Equivalent axial stiffness EA_eq = E_c A_c + m eta E_w A_w (N), eqs. (29)-(32).
    pub fn axial_stiffness(&self) -> f64 {
        let core = self.spec.core.material.youngs_modulus * self.spec.core.area();
        core + self
            .layer
            .as_ref()
            .map_or(0.0, |l| l.wires() as f64 * l.wire_axial_stiffness())
    }

    /// Minimum (all-slip) bending stiffness K_min = E_c I_c + m K_w (N m^2), with K_w the
    /// frictionless bending stiffness of one helical wire in the form `base`
    /// ([`crate::wire_bending`]). With [`BaseStiffness::Paper`] this is the paper's
    /// E_c I_c + m eta E_w I_w, eqs. (10), (11) (not (33), which misprints the areas; SPEC 9).
    pub fn min_bending_stiffness(&self, base: BaseStiffness) -> f64 {
        let core = self.spec.core.material.youngs_modulus * self.spec.core.inertia();
        core + self.layer.as_ref().map_or(0.0, |l| {
            l.wires() as f64 * base.wire_stiffness(&l.spec.wire, l.lay_angle())
        })
    }

    /// All-stick bending stiffness K_max = K_min + sum_i eta E_w A_w (R_w sin phi_i)^2
    /// (N m^2), eq. (22a), with K_min in the form `base`, averaged over the phases: the sum of
    /// sin^2 over m evenly spaced wires is m/2 (exact at every x for m >= 3; the mean over a
    /// pitch for m = 1, 2).
    pub fn max_bending_stiffness(&self, base: BaseStiffness) -> f64 {
        self.min_bending_stiffness(base)
            + self.layer.as_ref().map_or(0.0, |l| {
                0.5 * l.wires() as f64 * l.wire_axial_stiffness() * l.radius * l.radius
            })
    }

    /// The traditional constant-stiffness beam (envelope cylinder of the core's material).
    pub fn traditional(&self) -> TraditionalBeam {
        let d = self.spec.core.diameter
            + 2.0 * self.layer.as_ref().map_or(0.0, |l| l.spec.wire.diameter);
        let env = WireSpec {
            diameter: d,
            material: self.spec.core.material,
        };
        TraditionalBeam {
            diameter: d,
            bending_stiffness: env.material.youngs_modulus * env.inertia(),
            axial_stiffness: env.material.youngs_modulus * env.area(),
        }
    }

    /// Outer diameter of the strand d_c + 2 d_w (m).
    pub fn outer_diameter(&self) -> f64 {
        self.traditional().diameter
    }
}

fn finite(field: &str, v: f64) -> Result<(), InputError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(InputError::new(
            field,
            format!("must be a finite number, got {v}"),
        ))
    }
}

fn positive(field: &str, v: f64) -> Result<(), InputError> {
    finite(field, v)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(InputError::new(field, format!("must be positive, got {v}")))
    }
}

fn non_negative(field: &str, v: f64) -> Result<(), InputError> {
    finite(field, v)?;
    if v >= 0.0 {
        Ok(())
    } else {
        Err(InputError::new(
            field,
            format!("must be zero or positive, got {v}"),
        ))
    }
}

/// Plausible strand lengths (m).
const LENGTH_RANGE: (f64, f64) = (1e-6, 1e9);
/// Plausible wire diameters (m).
const DIAMETER_RANGE: (f64, f64) = (1e-9, 10.0);
/// Plausible Young's moduli (Pa).
const MODULUS_RANGE: (f64, f64) = (1e-3, 1e15);
/// Plausible densities (kg/m^3).
const DENSITY_RANGE: (f64, f64) = (1e-6, 1e6);

/// A positive value within a plausibility range that keeps every derived quantity (areas,
/// inertias ~ d^4, stiffnesses) finite and non-zero.
fn in_range(field: &str, v: f64, (lo, hi): (f64, f64), unit: &str) -> Result<(), InputError> {
    positive(field, v)?;
    if v < lo || v > hi {
        return Err(InputError::new(
            field,
            format!("{v} {unit} lies outside the plausible range [{lo:e}, {hi:e}] {unit}"),
        ));
    }
    Ok(())
}

fn check_wire(prefix: &str, w: &WireSpec) -> Result<(), InputError> {
    let p = |f: &str| format!("{prefix}.{f}");
    in_range(&p("diameter"), w.diameter, DIAMETER_RANGE, "m")?;
    in_range(
        &p("youngs_modulus"),
        w.material.youngs_modulus,
        MODULUS_RANGE,
        "Pa",
    )?;
    in_range(&p("density"), w.material.density, DENSITY_RANGE, "kg/m^3")?;
    let nu = w.material.poisson_ratio;
    finite(&p("poisson_ratio"), nu)?;
    if nu <= -1.0 || nu > 0.5 {
        return Err(InputError::new(
            p("poisson_ratio"),
            format!("must be in (-1, 0.5], got {nu}"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// The paper's Table 1 strand.
    pub(crate) fn table1() -> StrandSpec {
        StrandSpec::paper(0.4, 2.0e8, 7801.0)
    }

    #[test]
    fn table1_sanity_values() {
        // SPEC 8 sanity values, closed forms to the digits SPEC prints.
        let s = Strand::new(table1()).unwrap();
        let l = s.layer().unwrap();
        assert_relative_eq!(l.radius, 2.5e-3, max_relative = 1e-12);
        assert_relative_eq!(l.pitch, 0.043157, max_relative = 1e-5);
        assert_relative_eq!(l.eta, 0.829769, max_relative = 1e-6);
        assert_relative_eq!(s.mass_per_length(), 0.211624, max_relative = 1e-5);
        assert_relative_eq!(s.axial_stiffness(), 4541.87, max_relative = 1e-5);
        let paper = BaseStiffness::Paper;
        assert_relative_eq!(
            s.min_bending_stiffness(paper),
            1.57725e-3,
            max_relative = 1e-5
        );
        assert_relative_eq!(
            s.max_bending_stiffness(paper),
            1.135275e-2,
            max_relative = 1e-6
        );
        assert_relative_eq!(
            s.traditional().bending_stiffness,
            2.357176e-2,
            max_relative = 1e-6
        );
    }

    /// A single helical wire overlaps its own next turn when its pitch along the strand,
    /// times sin(alpha), is below its diameter: laid at 89.9999 deg its turns are 2.7e-8 m
    /// apart, far below 2 mm, and the strand is refused (the gap was infinite before). The
    /// limit angle is arccos(d_w / (2 pi R_w)), 82.685 deg for Table 1 (R_w = 2.5 mm, d_w = 2
    /// mm): accepted just below, refused just above.
    #[test]
    fn a_single_wire_overlaps_its_next_turn() {
        let one = |deg: f64| {
            let mut spec = table1();
            spec.layers[0].wires = 1;
            spec.layers[0].lay_angle = deg.to_radians();
            Strand::new(spec)
        };
        let e = one(89.9999).unwrap_err();
        assert_eq!(e.field, "layers[0].wires");
        assert!(e.message.contains("single wire"), "{}", e.message);
        let limit = (2e-3 / (2.0 * PI * 2.5e-3)).acos().to_degrees();
        assert_relative_eq!(limit, 82.685, epsilon = 1e-3);
        let ok = one(limit - 1e-3).unwrap();
        let l = ok.layer().unwrap();
        // The turns' distance across the wire, P sin(alpha) - d_w, has the sign of the gap.
        assert!(l.wire_gap() > 0.0 && l.pitch * l.lay_angle().sin() > 2e-3);
        assert!(one(limit + 1e-3).is_err());
    }

    #[test]
    fn wrap_angle_range() {
        assert_relative_eq!(wrap_angle(PI), PI);
        assert_relative_eq!(wrap_angle(-PI), PI);
        assert_relative_eq!(wrap_angle(3.0 * PI / 2.0), -PI / 2.0, epsilon = 1e-15);
        assert_relative_eq!(wrap_angle(0.1), 0.1);
    }
}
