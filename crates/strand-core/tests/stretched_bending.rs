//! The thin-rod frictionless stiffness of a stretched strand (`strand_core::stretched_bending`)
//! against closed forms: Costello's K_min at zero strain, and the energy's own structure.

use strand_core::stretched_bending::layer_stiffness;
use strand_core::{BaseStiffness, Material, Strand, StrandSpec, WireSpec};

/// The `validation/vs-fine-30deg.json` strand (core 2.2 mm, six 1.5 mm wires at 30 deg,
/// E = 5e7 Pa, nu = 0.3) at lay angle `deg`.
fn strand(deg: f64) -> Strand {
    layer_on_core(deg, 1.5e-3, 0.3)
}

/// Core 2.2 mm and six wires of diameter `wire` (m) and Poisson ratio `nu` at lay angle `deg`,
/// E = 5e7 Pa.
fn layer_on_core(deg: f64, wire: f64, nu: f64) -> Strand {
    let material = Material {
        youngs_modulus: 5e7,
        poisson_ratio: 0.3,
        density: 7800.0,
    };
    let mut spec = StrandSpec::paper(0.05, 5e7, 7800.0);
    spec.core = WireSpec {
        diameter: 2.2e-3,
        material,
    };
    spec.layers[0].wire.diameter = wire;
    spec.layers[0].wire.material.poisson_ratio = nu;
    spec.layers[0].lay_angle = deg.to_radians();
    spec.friction = 0.0;
    Strand::new(spec).unwrap()
}

/// At zero strain the energy minimised over migration and spin is Costello's thin-rod value
/// E I cos(alpha) 2 / (2 + nu sin^2 alpha) per wire (an independent closed form: Costello
/// solves the wire's equilibrium, the module minimises its energy). Tolerance 1e-5: the
/// second difference in the curvature errs by 1e-8 (R / r_w)^2 (module `BEND`), under 1e-6
/// for these layers (R / r_w <= 5.4), and the Newton gradient's differences by less. With the spin held at zero the value is not Costello's
/// (the check fails: measured 1.0002 to 1.006 times it).
#[test]
fn at_zero_strain_the_layer_is_costellos() {
    for deg in [5.0, 20.0, 30.0, 35.0] {
        let s = strand(deg);
        let layer = &s.layers()[0];
        let costello = s.layer_min_bending(layer, BaseStiffness::Costello);
        let k = layer_stiffness(layer, 0.0);
        println!("{deg} deg: {:.8} Costello", k / costello);
        assert!(
            (k / costello - 1.0).abs() < 1e-5,
            "{deg} deg: {}",
            k / costello
        );
    }
}

/// Under tension the layer softens, and at small strain linearly: the stiffness at strains
/// e and 2 e (e = 1e-5) changes by the same step within 1 % (the second-order term
/// relative to the first is O(e) times a coefficient of order 10 here).
#[test]
fn small_strains_soften_the_layer_linearly() {
    let s = strand(30.0);
    let layer = &s.layers()[0];
    let k0 = layer_stiffness(layer, 0.0);
    let (k1, k2) = (layer_stiffness(layer, 1e-5), layer_stiffness(layer, 2e-5));
    let (d1, d2) = (k1 - k0, k2 - k1);
    println!(
        "steps {d1:.4e} {d2:.4e} N m^2; slope {:.3} K_layer per unit strain",
        d1 / 1e-5 / k0
    );
    assert!(d1 < 0.0, "tension must soften: {d1}");
    assert!((d2 / d1 - 1.0).abs() < 1e-2, "{d1} {d2}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    /// For any lay angle, Poisson ratio and wire size the zero-strain value is Costello's
    /// closed form, within 1e-5 (the second difference errs by 1e-8 (R / r_w)^2, R / r_w up
    /// to 5.4 here). With the curvature step at 1e-3 / R instead (error 1e-6 (R / r_w)^2) it
    /// fails: 1.0000285 at 7.7 deg, nu = 0, 0.5 mm wires.
    #[test]
    fn zero_strain_is_costello_for_any_layer(
        deg in 2.0f64..40.0,
        nu in 0.0f64..0.45,
        wire_mm in 0.5f64..1.2,
    ) {
        let s = layer_on_core(deg, wire_mm * 1e-3, nu);
        let layer = &s.layers()[0];
        let costello = s.layer_min_bending(layer, BaseStiffness::Costello);
        let r = layer_stiffness(layer, 0.0) / costello;
        proptest::prop_assert!((r - 1.0).abs() < 1e-5, "{} deg, nu {}: {}", deg, nu, r);
    }
}
