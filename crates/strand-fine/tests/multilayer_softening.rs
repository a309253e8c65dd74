//! The frictionless fine 1+6+12 strand under tension against the section law's K_min with
//! `section.base_tension` `thin_rod`: the sum of the layers' thin-rod stiffness of the
//! stretched helix (`strand_core::section::base_tension`), each layer on a rigid layer
//! beneath. The fine test is set up as the thin-rod cell, as `tension_softening.rs` sets up
//! the one-layer strand: lateral pressure on the core only, stiff shear springs, nearly rigid
//! contacts.

use strand_core::{
    BaseStiffness, BaseTension, LawKind, LayDirection, LayerSpec, Material, SectionLaw,
    SectionOptions, Strand, StrandSpec, WireSpec, stretched_min_bending_stiffness,
};
use strand_fine::{BendingTest, NormalPenalty};

mod common;

/// Soft material (E = 5e7 Pa, as `validation/vs-fine-30deg.json`): a few newtons are a
/// strain of 1e-3.
fn soft() -> Material {
    Material {
        youngs_modulus: 5e7,
        poisson_ratio: 0.3,
        density: 7800.0,
    }
}

fn layer(wires: usize, d: f64, deg: f64, direction: LayDirection) -> LayerSpec {
    LayerSpec {
        wires,
        wire: WireSpec {
            diameter: d,
            material: soft(),
        },
        lay_angle: deg.to_radians(),
        phase: 0.0,
        direction,
    }
}

/// The geometry of the 1+6+12 steel strand of `examples/steel-1x19-swing.json` in the soft
/// material, without friction, laid at `inner` and `outer` deg.
fn strand(inner: f64, outer: f64) -> Strand {
    Strand::new(StrandSpec {
        length: 1.0,
        core: WireSpec {
            diameter: 3.3e-3,
            material: soft(),
        },
        layers: vec![
            layer(6, 3.0e-3, inner, LayDirection::Right),
            layer(12, 3.0e-3, outer, LayDirection::Left),
        ],
        friction: 0.0,
    })
    .unwrap()
}

fn env(k: &str, d: f64) -> f64 {
    std::env::var(k)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(d)
}

/// The frictionless cell test at tension `t` (N): `pitches` outer pitches of `spp` segments,
/// allowed penetration `penetration` (fraction of the wire diameter), every load step solved
/// after `stages` softer penalties ([`strand_fine::StaticOptions::penalty_stages`]), bent to
/// `kappa` (1/m).
fn cell(
    t: f64,
    (pitches, spp): (usize, usize),
    penetration: f64,
    stages: usize,
    kappa: f64,
) -> BendingTest {
    let mut test = common::thin_rod_cell(pitches, spp, t, kappa, penetration);
    if env("RULE", 1.0) > 0.0 {
        test.contact.normal_penalty = NormalPenalty::Penetration;
    }
    test.statics.penalty_stages = stages;
    test
}

/// M / kappa (N m^2) of the frictionless cell test at tension `t` (N), [`cell`].
fn stiffness(s: &Strand, t: f64, pitches: usize, spp: usize, penetration: f64) -> f64 {
    let stages = env("STAGES", 2.0) as usize;
    common::secant_stiffness(
        &cell(t, (pitches, spp), penetration, stages, env("K", 0.1)),
        s,
    )
}

/// The cell at 1 N, 12 segments per pitch, 3 outer pitches, penetration 1e-5 of the diameter
/// (0.1 1/m): with two penalty stages (1e-3 and 1e-4 of the diameter, then 1e-5) the tension
/// step and the bend converge by Newton, and M / kappa is the law's sum of the layers'
/// thin-rod stiffness within the 1 % the frictionless multi-layer K_min is asked to meet
/// (issue of the multi-layer fine model; measured 0.52 % above, the Strands of several layers
/// page). Without the stages (`penalty_stages` 0) the tension step stalls: 60 Newton
/// iterations, scaled residual 0.48, line-search steps of 2e-4 to 1e-1.
#[test]
fn tension_step_of_the_1x19_cell_converges_with_penalty_stages() {
    let s = strand(8.0, 12.0);
    let t = 1.0;
    let eps = t / s.axial_stiffness();
    let theory = stretched_min_bending_stiffness(&s, eps);
    let curve = cell(t, (3, 12), 1e-5, 2, 0.1)
        .run(&s)
        .expect("bending test");
    let point = curve.last().unwrap();
    let k = point.secant_stiffness();
    println!(
        "M/kappa {:.6} of the thin-rod sum; {} Newton iterations; tension {:.4} N",
        k / theory,
        point.iterations,
        point.tension
    );
    assert!((k / theory - 1.0).abs() < 1e-2, "{} of the sum", k / theory);
}

/// The cell's M / kappa is the same at 3 and 4 outer pitches, both as the test measures it
/// (over whole pitches of every layer, [`strand_fine::PitchWindow`]) and over two whole
/// pitches of the inner layer (the layer on the core), centred; over whole outer pitches alone
/// (1.29 and 2.58 inner pitches, the test's window before) it alternated with the length
/// (1.0040 and 0.9975 K_min at 0.01 N): the core's curvature oscillates with the inner pitch
/// (about 2.5 %), and a window of a fractional number of inner pitches takes its mean at a
/// phase that depends on the length. Allowance: the two figures' own discretisation errors,
/// measured as their change from 12 to 24 segments per pitch, added (the test's figure:
/// 4.33e-4 at 3 outer pitches, 4.11e-4 at 4; two inner pitches: 4.2e-4 and 3.8e-4; the
/// Strands of several layers page). The test's figure measured over whole outer pitches
/// instead fails the same check (6.5e-3 apart).
#[test]
fn the_1x19_cell_over_whole_pitches_does_not_depend_on_the_length() {
    let s = strand(8.0, 12.0);
    let (inner, outer) = (s.layers()[0].pitch, s.layers()[1].pitch);
    let figures = |pitches: usize| {
        let (curve, model, state) = cell(0.01, (pitches, 12), 1e-5, 2, 0.1)
            .run_with_state(&s)
            .expect("bending test");
        let window = BendingTest::centred_window(pitches as f64 * outer, inner, 2);
        (
            curve.last().unwrap().secant_stiffness(),
            BendingTest::window_stiffness(&model, &state, window),
        )
    };
    let ((t3, k3), (t4, k4)) = (figures(3), figures(4));
    let k_min = s.min_bending_stiffness(BaseStiffness::Costello);
    println!(
        "M/kappa, the test's figure: {:.6} K_min at 3 outer pitches, {:.6} at 4; over two inner \
         pitches: {:.6}, {:.6}",
        t3 / k_min,
        t4 / k_min,
        k3 / k_min,
        k4 / k_min
    );
    assert!(
        ((t3 - t4) / k_min).abs() < 4.33e-4 + 4.11e-4,
        "the test's figure {:.3e} K_min apart",
        (t3 - t4) / k_min
    );
    assert!(
        ((k3 - k4) / k_min).abs() < 4.2e-4 + 3.8e-4,
        "two inner pitches {:.3e} K_min apart",
        (k3 - k4) / k_min
    );
}

/// The fine strand's M / kappa (per deformed curvature) against the law's: K_min(eps) of the
/// `thin_rod` law is per unit rest curvature, so the fine test's figure is `(1 + eps)` times
/// it. Prints the law's, the thin-rod sum evaluated directly
/// (`stretched_min_bending_stiffness`) and the fine figure, in units of the tension-free
/// K_min. A study (the Strands of several layers page of the manual): STAGES penalty stages
/// (default 2).
#[test]
#[ignore = "study: T, SPP, PITCHES, PEN, K, RULE, STAGES, INNER, OUTER, PROFILE, PITCHES_ONLY from the environment"]
fn probe() {
    let s = strand(env("INNER", 8.0), env("OUTER", 12.0));
    let t = env("T", 1.0);
    let eps = t / s.axial_stiffness();
    let k_min = s.min_bending_stiffness(BaseStiffness::Costello);
    let theory = stretched_min_bending_stiffness(&s, eps);
    let options = SectionOptions {
        base_tension: BaseTension::ThinRod,
        ..Default::default()
    };
    let law = SectionLaw::with_options(&s, LawKind::Continuous, &options);
    let k_law = (1.0 + eps) * law.base_bending_at(eps).0;
    println!(
        "strain {eps:.3e}; law {:.6}, thin-rod {:.6} K_min",
        k_law / k_min,
        theory / k_min
    );
    let (p1, p2) = (s.layers()[0].pitch, s.layers()[1].pitch);
    println!(
        "pitches: inner {p1:.6} m, outer {p2:.6} m, ratio {:.6}",
        p2 / p1
    );
    if env("PITCHES_ONLY", 0.0) > 0.0 {
        return;
    }
    if env("PROFILE", 0.0) > 0.0 {
        profile(&s, t, k_min, k_law);
        return;
    }
    let start = std::time::Instant::now();
    let k = stiffness(
        &s,
        t,
        env("PITCHES", 3.0) as usize,
        env("SPP", 12.0) as usize,
        env("PEN", 1e-5),
    );
    println!(
        "fine {:.6} K_min; law {:.6}; {:.1} s",
        k / k_min,
        k_law / k_min,
        start.elapsed().as_secs_f64()
    );
}

/// Prints the moment at every core cut of the cell (PITCHES, SPP, PEN, STAGES, K), in units of
/// K_min times the measured curvature, with the cut's position in outer and inner pitches, and
/// the mean over windows: the test's own, and whole numbers of inner pitches centred in the
/// strand.
fn profile(s: &Strand, t: f64, k_min: f64, k_law: f64) {
    let pitches = env("PITCHES", 3.0) as usize;
    let test = cell(
        t,
        (pitches, env("SPP", 12.0) as usize),
        env("PEN", 1e-5),
        env("STAGES", 2.0) as usize,
        env("K", 0.1),
    );
    let (curve, model, state) = test.run_with_state(s).expect("bending test");
    let point = curve.last().unwrap();
    let unit = point.curvature * k_min;
    let (p1, p2) = (s.layers()[0].pitch, s.layers()[1].pitch);
    let m = BendingTest::moment_profile(&model, &state);
    println!(
        "test: {:.6} K_min; law {:.6}",
        point.secant_stiffness() / k_min,
        k_law / k_min
    );
    let poses = &state.wires[0].poses;
    let angle = |k: usize| {
        let t = poses[k].tangent();
        t.y.atan2(t.x)
    };
    for (k, &(x, mx)) in m.iter().enumerate() {
        // Local curvature at the joint k (between the core segments k - 1 and k).
        let local = if k == 0 || k == poses.len() {
            f64::NAN
        } else {
            (angle(k) - angle(k - 1)) / (poses[k].position - poses[k - 1].position).norm()
        };
        println!(
            "cut {:.4} {:.4} M {:.6} kappa {:.6} M/kappa {:.6}",
            x / p2,
            x / p1,
            mx / unit,
            local / point.curvature,
            mx / (local * k_min)
        );
    }
    let len = pitches as f64 * p2;
    for (name, p) in [("inner", p1), ("outer", p2)] {
        for n in 1..=((len / p - 1.0).max(1.0) as usize) {
            let (lo, hi) = BendingTest::centred_window(len, p, n);
            println!(
                "window {n} {name} pitches [{:.3}, {:.3}] outer: M/kappa {:.6} K_min",
                lo / p2,
                hi / p2,
                BendingTest::window_stiffness(&model, &state, (lo, hi)) / k_min
            );
        }
    }
}
