//! Fixtures of the fine model's tension-softening checks and studies: the `vs-fine-30deg`
//! strand and the frictionless bending test set up as the thin-rod cell.
#![allow(dead_code)]

use nalgebra::Vector3;
use strand_core::{LayDirection, LayerSpec, Material, Strand, StrandSpec, WireSpec};
use strand_fine::{BendingTest, ContactOptions, Discretisation, FineModel, Pressure, Support};

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

/// The fine model of `validation/vs-fine-1x19-cantilever.json`: 0.08 m, core
/// 2.2 mm, 6 + 12 wires of 1.5 mm at 20 deg right / left (the first `layers` of the two),
/// E = 5e7 Pa, friction `friction`, `segments` a wire, clamped at its start and free at its
/// end, g = 10 m/s^2 along -y, the default contacts.
pub fn cantilever_1x19(friction: f64, layers: usize, segments: usize) -> FineModel {
    cantilever_1x19_with(friction, layers, segments, &ContactOptions::default())
}

/// [`cantilever_1x19`] with the contacts `contact`.
pub fn cantilever_1x19_with(
    friction: f64,
    layers: usize,
    segments: usize,
    contact: &ContactOptions,
) -> FineModel {
    let mat = Material {
        youngs_modulus: 5.0e7,
        poisson_ratio: 0.3,
        density: 7800.0,
    };
    let layer = |wires, direction| LayerSpec {
        wires,
        wire: WireSpec {
            diameter: 1.5e-3,
            material: mat,
        },
        lay_angle: 20f64.to_radians(),
        phase: 0.0,
        direction,
    };
    let strand = Strand::new(StrandSpec {
        length: 0.08,
        core: WireSpec {
            diameter: 2.2e-3,
            material: mat,
        },
        layers: vec![layer(6, LayDirection::Right), layer(12, LayDirection::Left)][..layers]
            .to_vec(),
        friction,
    })
    .unwrap();
    let mut m = FineModel::from_strand(
        &strand,
        Discretisation {
            core_segments: segments,
            wire_segments: segments,
        },
        Support::Clamped,
        Support::Free,
    );
    m.gravity = Vector3::new(0.0, -10.0, 0.0);
    m.add_contacts(&strand, contact);
    m
}
