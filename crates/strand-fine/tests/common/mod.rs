//! Fixtures of the fine model's tension-softening checks and studies: the `vs-fine-30deg`
//! strand and the frictionless bending test set up as the thin-rod cell.
#![allow(dead_code)]

use strand_core::{Material, Strand, StrandSpec, WireSpec};
use strand_fine::{BendingTest, Pressure};

/// The `validation/vs-fine-30deg.json` strand: core 2.2 mm, six 1.5 mm wires at 30 deg,
/// E = 5e7 Pa, nu = 0.3, no friction.
pub fn vs_fine_30deg() -> Strand {
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
    spec.layers[0].wire.diameter = 1.5e-3;
    spec.layers[0].lay_angle = 30f64.to_radians();
    spec.friction = 0.0;
    Strand::new(spec).unwrap()
}

/// The frictionless bending test at tension `t` (N) to curvature `kappa` (1/m), `pitches`
/// pitches of `spp` segments, set up as the thin-rod cell of `strand_core::stretched_bending`:
/// the lateral pressure on the core only ([`Pressure::Core`]: no load on the wires from
/// outside), shear springs 100 times stiffer (Kirchhoff wires) and the allowed penetration
/// `penetration` (fraction of the wire diameter: nearly rigid contacts).
pub fn thin_rod_cell(
    pitches: usize,
    spp: usize,
    t: f64,
    kappa: f64,
    penetration: f64,
) -> BendingTest {
    let mut test = BendingTest::frictionless(pitches, spp, t, kappa);
    test.pressure = Pressure::Core;
    test.contact.penetration = penetration;
    test.wire_springs.shear = 100.0;
    test.core_springs.shear = 100.0;
    test
}

/// M / kappa (N m^2) at the end of `test` on strand `s`.
pub fn secant_stiffness(test: &BendingTest, s: &Strand) -> f64 {
    test.run(s)
        .expect("bending test")
        .last()
        .unwrap()
        .secant_stiffness()
}
