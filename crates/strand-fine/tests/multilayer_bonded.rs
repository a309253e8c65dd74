//! The bonded (all-stick) bending stiffness of the 1+6+12 strand: the fine virtual bending
//! test with friction too high to slip, against the plane-section K_max and the rod model of
//! the bonded strand per interface (`strand_core::bonded`).

use strand_core::bonded::interface_bonded_stiffness;
use strand_core::{
    BaseStiffness, BondedOptions, LayDirection, LayerSpec, Material, Strand, StrandSpec, WireSpec,
};
use strand_fine::{BendingTest, NormalPenalty, SpringScale};

fn steel() -> Material {
    Material {
        youngs_modulus: 2.0e11,
        poisson_ratio: 0.3,
        density: 7850.0,
    }
}

fn layer(wires: usize, deg: f64, direction: LayDirection) -> LayerSpec {
    LayerSpec {
        wires,
        wire: WireSpec {
            diameter: 3.0e-3,
            material: steel(),
        },
        lay_angle: deg.to_radians(),
        phase: 0.0,
        direction,
    }
}

/// The 1+6+12 steel strand of `examples/steel-1x19-swing.json` (outer layer left-laid, or
/// right-laid with `same_lay`).
fn strand_1x19(same_lay: bool) -> Strand {
    let outer = if same_lay {
        LayDirection::Right
    } else {
        LayDirection::Left
    };
    Strand::new(StrandSpec {
        length: 1.0,
        core: WireSpec {
            diameter: 3.3e-3,
            material: steel(),
        },
        layers: vec![layer(6, 8.0, LayDirection::Right), layer(12, 12.0, outer)],
        friction: 0.3,
    })
    .unwrap()
}

fn env(k: &str, d: f64) -> f64 {
    std::env::var(k)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(d)
}

/// All-stick bending of the 1+6+12 strand with the idealisations from the environment:
/// MU, STRAIN (axial), BEND (kappa R_2), SPP, PITCHES, PEN (penetration rule at that
/// fraction of d), RELIEF (strain-relief rule), STICK_LOSS, POINTS, WSHEAR, WTORSION, WBEND, CSHEAR,
/// AXES (1: bond on the first layer's axes), SAME (1: outer layer right-laid), PSTAGES (penalty
/// continuation stages of every load step).
#[test]
#[ignore = "exploration: settings from the environment"]
fn probe_bonded_1x19() {
    let s = strand_1x19(env("SAME", 0.0) > 0.0);
    let ea = s.axial_stiffness();
    let tension = env("STRAIN", 2.2e-4) * ea;
    let outer = s.layers()[1];
    let kappa = env("BEND", 2.5e-5) / outer.radius;
    let mut test = BendingTest::frictionless(
        env("PITCHES", 3.0) as usize,
        env("SPP", 12.0) as usize,
        tension,
        kappa,
    );
    test.friction = env("MU", 1e3);
    test.max_halvings = env("HALVINGS", 3.0) as usize;
    test.statics.penalty_stages = env("PSTAGES", 0.0) as usize;
    let pen = env("PEN", 0.0);
    if pen > 0.0 {
        test.contact.normal_penalty = NormalPenalty::Penetration;
        test.contact.penetration = pen;
    }
    let relief = env("RELIEF", 0.0);
    if relief > 0.0 {
        test.contact.normal_penalty = NormalPenalty::StrainRelief(relief);
    }
    test.contact.stick_loss = env("STICK_LOSS", test.contact.stick_loss);
    test.contact.points_per_segment = Some(env("POINTS", 1.0) as usize);
    if env("AXES", 0.0) > 0.0 {
        test.contact.contact_radius = Some(s.layers()[0].radius);
    }
    test.wire_springs = SpringScale {
        shear: env("WSHEAR", 1.0),
        torsion: env("WTORSION", 1.0),
        bending: env("WBEND", 1.0),
        ..Default::default()
    };
    test.core_springs = SpringScale {
        shear: env("CSHEAR", 1.0),
        ..Default::default()
    };
    let start = std::time::Instant::now();
    let curve = test
        .run_with_progress(&s, &mut |p| {
            println!(
                "kappa {:.4e}: stick {} slip {} open {}, {} iterations, at {:.1} s",
                p.curvature,
                p.stick,
                p.slip,
                p.open,
                p.iterations,
                start.elapsed().as_secs_f64()
            )
        })
        .map(|(c, _, _)| c)
        .unwrap_or_else(|e| panic!("bending test: {e}"));
    let p = curve.last().unwrap();
    let k = p.secant_stiffness();
    let k_min = s.min_bending_stiffness(BaseStiffness::Costello);
    let k_max = s.max_bending_stiffness(BaseStiffness::Costello);
    let rigid = BondedOptions::default();
    let mut law = k_min;
    for j in 0..2 {
        let b = interface_bonded_stiffness(&s, j, &rigid).unwrap();
        law += b.stick_factor() * s.layer_plane_section_stick(&s.layers()[j]);
        println!("layer {}: stick factor {:.4}", j + 1, b.stick_factor());
    }
    println!(
        "RESULT K = {k:.6e} N m^2 = {:.5} K_max, {:.5} K_min; law (bonded) {:.5} K_max; \
         slip {} open {}; clamp/middle {:.4}; {:.1} s",
        k / k_max,
        k / k_min,
        law / k_max,
        p.slip,
        p.open,
        p.clamp_moment / p.moment,
        start.elapsed().as_secs_f64()
    );
}

/// The coupled rod model's values on the 1+6+12 strand (prints; no assertion).
#[test]
#[ignore = "exploration: prints the rod models"]
fn probe_rod_models() {
    use strand_core::bonded::strand_bonded_stiffness;
    for same in [false, true] {
        let s = strand_1x19(same);
        let k_max = s.max_bending_stiffness(BaseStiffness::Costello);
        let k_min = s.min_bending_stiffness(BaseStiffness::Costello);
        let r1 = s.layers()[0].radius;
        for (name, o) in [
            ("physical", BondedOptions::default()),
            (
                "torsion x100",
                BondedOptions {
                    wire_torsion: 100.0,
                    ..Default::default()
                },
            ),
            (
                "shear x10",
                BondedOptions {
                    wire_shear: 10.0,
                    ..Default::default()
                },
            ),
            (
                "axes",
                BondedOptions {
                    contact_radius: Some(r1),
                    ..Default::default()
                },
            ),
            (
                "core shear x100",
                BondedOptions {
                    core_shear: 100.0,
                    ..Default::default()
                },
            ),
            (
                "env",
                BondedOptions {
                    wire_torsion: env("WTORSION", 1.0),
                    wire_shear: env("WSHEAR", 1.0),
                    core_shear: env("CSHEAR", 1.0),
                    contact_radius: (env("AXES", 0.0) > 0.0).then_some(r1),
                    // KT, KN: the bond's tangential and normal stiffness per unit wire
                    // length (N/m^2) on every interface; unset: rigid.
                    tangential_stiffness: std::env::var("KT").ok().and_then(|v| v.parse().ok()),
                    normal_stiffness: std::env::var("KN").ok().and_then(|v| v.parse().ok()),
                    ..Default::default()
                },
            ),
        ] {
            let b = strand_bonded_stiffness(&s, &o).unwrap();
            println!(
                "same {same} {name}: bonded {:.5} K_max, free {:.6} K_min, bonded / (free + stick) {:.5}",
                b.bonded / k_max,
                b.free / k_min,
                b.bonded / (b.free + b.plane_section_stick)
            );
        }
    }
}

/// All stick on the 1+6+12 strand (mu = 1e3, axial strain 2.2e-4, bending strain 2.5e-5 at
/// the outer axes, stiff penalties, 16 segments per pitch over 3 pitches): no contact slips,
/// the contacts closed under the tension alone stay closed, and M / kappa meets the rod model
/// of the strand as one body (`strand_bonded_stiffness`, rigid bonds) within the 5 % asked of
/// the closed form plus the mesh error of 16 segments per pitch: 1.5 %, measured by `cargo
/// xtask bonded --multilayer`'s `stiff-penalties` (0.3747 K_max at 16 against 0.3703 at 32
/// and 0.3701 at 40). The
/// per-interface stick factors of the law (0.928 K_max) are printed beside it. With the
/// mirror's sign left out of the one-body model (a left-laid layer's e_theta not reversed)
/// the model gives 0.669 K_max and this check fails.
#[test]
fn bonded_1x19_bends_with_the_strand_as_one_body() {
    use strand_core::bonded::strand_bonded_stiffness;
    let s = strand_1x19(false);
    let tension = 2.2e-4 * s.axial_stiffness();
    let mut test = BendingTest::frictionless(3, 16, tension, 2.5e-5 / s.layers()[1].radius);
    test.friction = 1e3;
    test.max_halvings = 0;
    test.contact.normal_penalty = NormalPenalty::StrainRelief(1e-4);
    test.contact.stick_loss = 5e-4;
    test.contact.points_per_segment = Some(1);
    let curve = test.run(&s).expect("all-stick bending");
    let (first, p) = (curve[0], curve[1]);
    assert_eq!(p.slip, 0);
    assert_eq!(p.stick, first.stick);
    let k = p.secant_stiffness();
    let rod = strand_bonded_stiffness(&s, &BondedOptions::default())
        .unwrap()
        .bonded;
    let k_max = s.max_bending_stiffness(BaseStiffness::Costello);
    let mut law = s.min_bending_stiffness(BaseStiffness::Costello);
    for (j, l) in s.layers().iter().enumerate() {
        let b = interface_bonded_stiffness(&s, j, &BondedOptions::default()).unwrap();
        law += b.stick_factor() * s.layer_plane_section_stick(l);
    }
    println!(
        "fine {:.4} K_max, one body {:.4}, per interface {:.4}",
        k / k_max,
        rod / k_max,
        law / k_max
    );
    assert!((k / rod - 1.0).abs() < 0.05 + 0.015, "{k} against {rod}");
}

/// The bending test's default contacts converge in the stick regime (the 1+6+12 strand with
/// mu = 1e3 at T = 1000 N, kappa = 5e-4 1/m, 3 pitches, the scene runner's `strand bend`
/// settings): no contact slips, M / kappa changes by under 1 % from 16 to 32 segments per
/// pitch (a fifth of the 5 % to which the law is compared; measured 0.65 %, then 0.16 % to
/// 64, order 2), and both lie within the 5 % asked of the closed form of the physical value,
/// the rod model of the strand as one body. Before the crossings stood for their spacing
/// whatever the segment length and before the strands of several layers took one contact
/// point per segment on the core, the same test gave 0.458 and 0.404 K_max (12 % apart, the
/// finer 11 % above the rod model) and kept falling, to 0.342 at 128.
#[test]
fn default_contacts_converge_in_the_stick_regime() {
    use strand_core::bonded::strand_bonded_stiffness;
    let s = strand_1x19(false);
    let rod = strand_bonded_stiffness(&s, &BondedOptions::default())
        .unwrap()
        .bonded;
    let k_max = s.max_bending_stiffness(BaseStiffness::Costello);
    let k = |spp: usize| {
        let mut test = BendingTest::frictionless(3, spp, 1000.0, 5e-4);
        test.friction = 1e3;
        let curve = test.run(&s).expect("all-stick bending");
        let (first, p) = (curve[0], curve[1]);
        assert_eq!(p.slip, 0, "{spp} segments per pitch");
        assert_eq!(p.stick, first.stick, "{spp} segments per pitch");
        p.secant_stiffness()
    };
    let (coarse, fine) = (k(16), k(32));
    println!(
        "default contacts: {:.4}, {:.4} K_max at 16, 32 segments per pitch; one body {:.4}",
        coarse / k_max,
        fine / k_max,
        rod / k_max
    );
    assert!((fine / coarse - 1.0).abs() < 1e-2, "{coarse} then {fine}");
    for k in [coarse, fine] {
        assert!((k / rod - 1.0).abs() < 0.05, "{k} against {rod}");
    }
}

/// The 1+6+12 strand with the compliances the plane-section K_max ignores removed (wires'
/// G J x100 and kappa G A x10, core's kappa G A x100, the first layer's bond on its axes, stiff
/// penalties; `cargo xtask bonded --multilayer`'s `removed`) at `spp` segments per pitch.
fn removed_1x19(spp: usize) -> (Strand, BendingTest) {
    let s = strand_1x19(false);
    let tension = 2.2e-4 * s.axial_stiffness();
    let mut test = BendingTest::frictionless(3, spp, tension, 2.5e-5 / s.layers()[1].radius);
    test.friction = 1e3;
    test.contact.normal_penalty = NormalPenalty::StrainRelief(1e-4);
    test.contact.stick_loss = 5e-4;
    test.contact.contact_radius = Some(s.layers()[0].radius);
    test.wire_springs = SpringScale {
        torsion: 100.0,
        shear: 10.0,
        ..Default::default()
    };
    test.core_springs = SpringScale {
        shear: 100.0,
        ..Default::default()
    };
    (s, test)
}

/// A tension step that plain Newton does not solve is retried with penalty continuation,
/// which changes only the first iterate: on the compliance-free 1+6+12 strand at 20 segments
/// per pitch the tension step fails without a retry (Newton's iterates cross the stiff
/// contacts' kinks: scaled residual 2.0 after 60 iterations) and passes with it, every
/// contact sticking; at 16 segments per pitch, where plain Newton converges, two stages of
/// continuation on every step give the same stiffness within 1e-6 (the steps' residual
/// tolerance is 1e-8 of the tension). With a failed tension step retried as before (the
/// same solve again, its zero curvature increment halved) the first check fails.
#[test]
fn a_failed_tension_step_is_retried_with_penalty_continuation() {
    let (s, mut test) = removed_1x19(20);
    test.max_halvings = 0;
    match test.run(&s) {
        Err(strand_fine::BendingError::Static { curvature, .. }) => assert_eq!(curvature, 0.0),
        other => panic!("plain Newton solved the tension step: {other:?}"),
    }
    test.max_halvings = 3;
    let curve = test.run(&s).expect("retried tension step");
    assert_eq!(curve[1].slip, 0);
    assert_eq!(curve[1].stick, curve[0].stick);
    let (s, mut test) = removed_1x19(16);
    test.max_halvings = 0;
    let plain = test.run(&s).expect("plain Newton")[1].secant_stiffness();
    test.statics.penalty_stages = 2;
    let staged = test.run(&s).expect("penalty continuation")[1].secant_stiffness();
    assert!(
        (staged / plain - 1.0).abs() < 1e-6,
        "{staged} against {plain}"
    );
}
