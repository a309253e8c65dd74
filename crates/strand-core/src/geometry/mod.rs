//! Strand geometry and materials (SPEC 1; paper section 1.1).
//!
//! A strand is a straight core wire with layers of helical wires laid around it, layer j = 1..N
//! outward (a `1+m` strand has one, a 1x19 strand two, a Cardinal conductor four). Each layer
//! has its own wire count, wire diameter and material, lay angle, lay direction and phase
//! (module `layer`); the layers are stacked wire on wire from the core outward, closed layers
//! included (module `stack`). [`StrandSpec`] holds the inputs as a user gives them; [`Strand`]
//! is the validated strand with every derived quantity (helix radii, pitches, stiffness loss
//! factors, the interfaces between layers, mass per length, axial and bending stiffnesses).
//! All quantities are SI: metres, pascals, kg/m^3, radians.

mod layer;
mod stack;

use std::f64::consts::PI;

pub use layer::{HelixLayer, LayDirection, LayerSpec, wrap_angle};
pub use stack::{CLOSED_LAYER_TOLERANCE, Contact, Interface};

use crate::error::InputError;
pub use crate::wire::{Material, WireSpec};
use crate::wire_bending::BaseStiffness;

/// Inputs of a strand: length, core, helical layers and the friction between wires.
#[derive(Debug, Clone, PartialEq)]
pub struct StrandSpec {
    /// Strand length L (m).
    pub length: f64,
    /// Straight core wire.
    pub core: WireSpec,
    /// Helical layers from the core outward (none: a plain wire).
    pub layers: Vec<LayerSpec>,
    /// Coulomb friction coefficient mu between each layer's wires and the layer (or core)
    /// beneath (-).
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

/// The most helical layers a strand may have (the largest stranded conductors have five or
/// six); the section laws' accumulated-pressure limits evaluate this many without allocating.
pub const MAX_LAYERS: usize = crate::section::pressure::MAX_LAYERS;

/// Default friction coefficient when a scene gives none (SPEC 9: the paper does not state it).
pub const DEFAULT_FRICTION: f64 = 0.3;

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
    layers: Vec<HelixLayer>,
}

impl Strand {
    /// Validates the inputs and derives the strand. Errors name the offending field with the
    /// scene format's path below `strand` (e.g. `layers[0].lay_angle_deg`).
    pub fn new(spec: StrandSpec) -> Result<Self, InputError> {
        in_range("length", spec.length, LENGTH_RANGE, "m")?;
        check_wire("core", &spec.core)?;
        non_negative("friction", spec.friction)?;
        if spec.layers.len() > MAX_LAYERS {
            return Err(InputError::new(
                format!("layers[{MAX_LAYERS}]"),
                format!("at most {MAX_LAYERS} helical layers"),
            ));
        }
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
        }
        let layers = stack::stack(&spec.core, &spec.layers)?;
        Ok(Strand { spec, layers })
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
    /// The helical layers from the core outward (empty for a plain wire).
    pub fn layers(&self) -> &[HelixLayer] {
        &self.layers
    }
    /// The interface of `layers()[j]` with the layer beneath it (the core for `j = 0`):
    /// contact type and crossing angle. Panics if `j` is not a layer's index.
    pub fn interface(&self, j: usize) -> Interface {
        stack::interface(&self.layers, j)
    }
    /// Every layer's interface with the layer beneath, from the core outward.
    pub fn interfaces(&self) -> Vec<Interface> {
        (0..self.layers.len()).map(|j| self.interface(j)).collect()
    }
    /// The shortest of the layers' pitches (m), `None` for a plain wire: the length over which
    /// every layer's phases are resolved.
    pub fn shortest_pitch(&self) -> Option<f64> {
        self.layers.iter().map(|l| l.pitch).reduce(f64::min)
    }
    /// Total number of helical wires over the layers.
    pub fn helical_wires(&self) -> usize {
        self.layers.iter().map(|l| l.wires()).sum()
    }
    /// Friction coefficient mu between each layer and the layer beneath.
    pub fn friction(&self) -> f64 {
        self.spec.friction
    }

    /// Mass per unit strand length rho_c A_c + sum_j m_j rho_j A_j / cos(alpha_j) (kg/m), eq.
    /// (44) summed over the layers.
    pub fn mass_per_length(&self) -> f64 {
        let core = self.spec.core.material.density * self.spec.core.area();
        self.layers.iter().fold(core, |sum, l| {
            sum + l.wires() as f64 * l.spec.wire.material.density * l.spec.wire.area()
                / l.lay_angle().cos()
        })
    }

    /// Equivalent axial stiffness EA_eq = E_c A_c + sum_j m_j eta_j E_j A_j (N), eqs.
    /// (29)-(32) summed over the layers.
    pub fn axial_stiffness(&self) -> f64 {
        let core = self.spec.core.material.youngs_modulus * self.spec.core.area();
        self.layers.iter().fold(core, |sum, l| {
            sum + l.wires() as f64 * l.wire_axial_stiffness()
        })
    }

    /// Minimum (all-slip) bending stiffness K_min = E_c I_c + sum_j m_j K_wj (N m^2), with
    /// K_wj the frictionless bending stiffness of one wire of layer j in the form `base`
    /// ([`crate::wire_bending`]). With [`BaseStiffness::Paper`] and one layer this is the
    /// paper's E_c I_c + m eta E_w I_w, eqs. (10), (11) (not (33), which misprints the areas;
    /// SPEC 9).
    pub fn min_bending_stiffness(&self, base: BaseStiffness) -> f64 {
        let core = self.spec.core.material.youngs_modulus * self.spec.core.inertia();
        self.layers
            .iter()
            .fold(core, |sum, l| sum + self.layer_min_bending(l, base))
    }

    /// Layer `l`'s share of K_min: m K_w (N m^2), see [`Self::min_bending_stiffness`].
    pub fn layer_min_bending(&self, l: &HelixLayer, base: BaseStiffness) -> f64 {
        l.wires() as f64 * base.wire_stiffness(&l.spec.wire, l.lay_angle())
    }

    /// Layer `l`'s plane-section stick stiffness sum_i eta E_w A_w (R_w sin phi_i)^2 =
    /// (m/2) eta E_w A_w R_w^2 (N m^2), eq. (22a), averaged over the phases: the sum of sin^2
    /// over m evenly spaced wires is m/2 (exact at every x for m >= 3; the mean over a pitch
    /// for m = 1, 2).
    pub fn layer_plane_section_stick(&self, l: &HelixLayer) -> f64 {
        0.5 * l.wires() as f64 * l.wire_axial_stiffness() * l.radius * l.radius
    }

    /// All-stick bending stiffness K_max = K_min + the layers' plane-section stick stiffness
    /// (N m^2), eq. (22a), with K_min in the form `base`.
    pub fn max_bending_stiffness(&self, base: BaseStiffness) -> f64 {
        self.layers
            .iter()
            .fold(self.min_bending_stiffness(base), |sum, l| {
                sum + self.layer_plane_section_stick(l)
            })
    }

    /// The traditional constant-stiffness beam (envelope cylinder of the core's material, of
    /// the strand's outer diameter).
    pub fn traditional(&self) -> TraditionalBeam {
        // The layers' wire diameters, and the lifts of closed layers, summed outward.
        let layers = self
            .layers
            .iter()
            .fold(0.0, |sum, l| sum + (l.spec.wire.diameter + l.lift));
        let d = self.spec.core.diameter + 2.0 * layers;
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

    /// Outer diameter of the strand d_c + 2 sum_j d_wj, with the lifts of closed layers (m).
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
        let l = &s.layers()[0];
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
    /// turns touch at arccos(d_w / (2 pi R_w)), 82.685 deg for Table 1 (R_w = 2.5 mm, d_w = 2
    /// mm): below it the wire lies on the core; up to where a wire thinner by the closed-layer
    /// tolerance would touch, arccos(0.99 d_w / (2 pi R_w)), it is lifted so that its turns
    /// touch; beyond that it is refused.
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
        let l = &ok.layers()[0];
        // The turns' distance across the wire, P sin(alpha) - d_w, has the sign of the gap.
        assert!(l.wire_gap() > 0.0 && l.pitch * l.lay_angle().sin() > 2e-3);
        assert_eq!(l.lift, 0.0);
        let lifted = one(limit + 1e-3).unwrap();
        let l = &lifted.layers()[0];
        assert!(l.lift > 0.0 && l.radius > 2.5e-3);
        // Lifted to where the turns touch: the gap closes to round-off of R_w.
        assert!(l.wire_gap().abs() < 1e-15, "{}", l.wire_gap());
        let tolerance = (0.99 * 2e-3 / (2.0 * PI * 2.5e-3)).acos().to_degrees();
        assert!(one(tolerance - 1e-3).is_ok());
        assert!(one(tolerance + 1e-3).is_err());
    }

    fn wire(d: f64, e: f64) -> WireSpec {
        WireSpec {
            diameter: d,
            material: Material {
                youngs_modulus: e,
                poisson_ratio: 0.3,
                density: 7800.0,
            },
        }
    }

    fn layer(m: usize, d: f64, deg: f64, direction: LayDirection) -> LayerSpec {
        LayerSpec {
            wires: m,
            wire: wire(d, 2e11),
            lay_angle: deg.to_radians(),
            phase: 0.0,
            direction,
        }
    }

    /// Cardinal's steel core, six wires of the core's diameter at 5.696 deg, is a closed layer:
    /// short by 1.657e-5 m on the stacked radius, within the 1 % tolerance (3.36e-5 m), it is
    /// lifted by the shortfall over 2 sin(pi/6) = 1 and the neighbours touch; the aluminium
    /// layers stack on the lifted radius. Seven such wires overlap by far more and are
    /// refused naming the layer's field.
    #[test]
    fn closed_layers_are_lifted_and_overlap_is_refused() {
        let d = 3.34e-3;
        let spec = |m: usize| StrandSpec {
            length: 1.0,
            core: wire(d, 2.07e11),
            layers: vec![
                layer(m, d, 5.696, LayDirection::Right),
                layer(12, 3.32e-3, 11.0, LayDirection::Left),
            ],
            friction: 0.5,
        };
        let s = Strand::new(spec(6)).unwrap();
        let (l0, l1) = (&s.layers()[0], &s.layers()[1]);
        let short = d / 5.696f64.to_radians().cos() - d;
        assert_relative_eq!(short, 1.657e-5, max_relative = 1e-3);
        assert_relative_eq!(l0.lift, short, max_relative = 1e-9);
        assert_relative_eq!(l0.radius, d + short, max_relative = 1e-12);
        assert!(l0.wire_gap().abs() < 1e-15);
        assert_eq!(l1.lift, 0.0);
        assert_relative_eq!(
            l1.radius,
            l0.radius + 0.5 * d + 1.66e-3,
            max_relative = 1e-12
        );
        let e = Strand::new(spec(7)).unwrap_err();
        assert_eq!(e.field, "layers[0].wires");
        assert!(e.message.contains("overlap"), "{}", e.message);
    }

    /// The interfaces: the first layer touches the straight core along lines at its lay
    /// angle; alternate lay crosses at the sum of the lay angles, the same lay touches along
    /// lines at their difference.
    #[test]
    fn interfaces_follow_the_lay_directions() {
        let spec = StrandSpec {
            length: 1.0,
            core: wire(2.2e-3, 2e11),
            layers: vec![
                layer(6, 2e-3, 10.0, LayDirection::Right),
                layer(12, 2e-3, 14.0, LayDirection::Left),
                layer(18, 2e-3, 15.0, LayDirection::Left),
            ],
            friction: 0.3,
        };
        let s = Strand::new(spec).unwrap();
        let i = s.interfaces();
        assert_eq!(i[0].contact, Contact::Line);
        assert_relative_eq!(i[0].crossing_angle.to_degrees(), 10.0, epsilon = 1e-12);
        assert_eq!(i[1].contact, Contact::Crossing);
        assert_relative_eq!(i[1].crossing_angle.to_degrees(), 24.0, epsilon = 1e-12);
        assert_eq!(i[2].contact, Contact::Line);
        assert_relative_eq!(i[2].crossing_angle.to_degrees(), 1.0, epsilon = 1e-12);
        // Radii stacked wire on wire (2 mm wires on a 2.2 mm core: 2.1, 4.1, 6.1 mm), none
        // of the layers closed.
        for (j, l) in s.layers().iter().enumerate() {
            assert_eq!(l.lift, 0.0);
            assert_relative_eq!(
                l.radius,
                1.1e-3 + 2e-3 * j as f64 + 1e-3,
                max_relative = 1e-12
            );
        }
        let mut bad = s.spec().clone();
        bad.layers[2].lay_angle = 95f64.to_radians();
        assert_eq!(
            Strand::new(bad).unwrap_err().field,
            "layers[2].lay_angle_deg"
        );
    }

    #[test]
    fn wrap_angle_range() {
        assert_relative_eq!(wrap_angle(PI), PI);
        assert_relative_eq!(wrap_angle(-PI), PI);
        assert_relative_eq!(wrap_angle(3.0 * PI / 2.0), -PI / 2.0, epsilon = 1e-15);
        assert_relative_eq!(wrap_angle(0.1), 0.1);
    }
}
