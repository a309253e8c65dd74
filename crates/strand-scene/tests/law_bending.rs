//! The section law's bending curve (`strand bend --model equivalent`) of a 1x19 strand: the
//! loading curve between the all-slip and all-stick lines, and the hysteresis loop's area
//! equal to the slip work booked around it.

#[path = "common/temp_path.rs"]
mod temp_path;

use strand_scene::{LawBendingOptions, Scene, run_law_bending};
use temp_path::TempPath;

const SCENE: &str = r#"{
  "name": "steel-1x19",
  "strand": {
    "length": 1.0,
    "core": {"diameter": 0.0033, "youngs_modulus": 2.0e11, "poisson_ratio": 0.3, "density": 7850.0},
    "layers": [
      {"wires": 6, "diameter": 0.003, "lay_angle_deg": 8.0, "lay_direction": "right",
       "youngs_modulus": 2.0e11, "poisson_ratio": 0.3, "density": 7850.0},
      {"wires": 12, "diameter": 0.003, "lay_angle_deg": 12.0, "lay_direction": "left",
       "youngs_modulus": 2.0e11, "poisson_ratio": 0.3, "density": 7850.0}
    ],
    "friction": 0.3
  },
  "law": "hysteretic",
  "supports": [{"at": "start", "kind": "clamped"}],
  "analysis": {"kind": "static"},
  "models": {"equivalent": {"elements": 8}}
}"#;

/// The loading curve from straight lies between K_min kappa and K_max kappa (each wire's
/// force lies between zero and its stick force); around the loop the moment's work, by the
/// trapezoid rule, is the slip work: the moment is piecewise linear in kappa with at most
/// four kinks per wire, each costing the rule at most k_i arm_i^2 dk^2 / 8, so the difference
/// is at most (K_max - K_min) dk^2 / 2 (plus round-off).
#[test]
fn the_loop_area_is_the_slip_work() {
    let scene = Scene::parse(SCENE).unwrap();
    let out = TempPath::new("strand-law-bending");
    let steps = 200;
    let s = run_law_bending(
        &scene,
        &LawBendingOptions {
            tension: 1e4,
            amplitude: None,
            steps,
            out: out.to_path_buf(),
        },
    )
    .unwrap();
    assert!(out.join("law-bending.csv").exists());
    for p in &s.points[..=steps] {
        let (lo, hi) = (s.k_min * p[0], s.k_max * p[0]);
        assert!(
            p[1] >= lo * (1.0 - 1e-12) && p[1] <= hi * (1.0 + 1e-12),
            "{p:?}: [{lo}, {hi}]"
        );
    }
    let dk = s.amplitude / steps as f64;
    let bound = (s.k_max - s.k_min) * dk * dk / 2.0 + 1e-12 * s.dissipated;
    assert!(s.dissipated > 0.0);
    assert!(
        (s.loop_area - s.dissipated).abs() <= bound,
        "area {} against slip work {} (bound {bound})",
        s.loop_area,
        s.dissipated
    );
}

/// `loading_moments`, the first-loading curve at given curvatures: at the loading branch's
/// curvatures of `run_law_bending` it gives the same moments; on first loading every wire is
/// an elastic-perfectly-plastic slider with a fixed limit, whose force depends on the
/// curvature reached and not on the steps taken to it, so the load steps change nothing but
/// round-off; past the largest critical curvature every wire slips at its fixed limit and
/// the tangent is K_min.
#[test]
fn loading_moments_first_loading() {
    let scene = Scene::parse(SCENE).unwrap();
    let law = strand_core::SectionLaw::with_options(&scene.strand, scene.law, &scene.section);
    let out = TempPath::new("strand-law-loading");
    let (tension, steps) = (1e4, 40);
    let s = run_law_bending(
        &scene,
        &LawBendingOptions {
            tension,
            amplitude: None,
            steps,
            out: out.to_path_buf(),
        },
    )
    .unwrap();
    let kappa: Vec<f64> = s.points[1..=steps].iter().map(|p| p[0]).collect();
    let m1 = strand_scene::loading_moments(&law, tension, &kappa, 1);
    for (m, p) in m1.iter().zip(&s.points[1..=steps]) {
        assert_eq!(*m, p[1], "at kappa {}", p[0]);
    }
    let m7 = strand_scene::loading_moments(&law, tension, &kappa, 7);
    for (a, b) in m1.iter().zip(&m7) {
        assert!((a - b).abs() <= 1e-12 * a.abs(), "{a} vs {b}");
    }
    // The amplitude is three times the largest critical curvature: the last third slips.
    let (k1, k2) = (kappa[steps - 2], kappa[steps - 1]);
    let slope = (m1[steps - 1] - m1[steps - 2]) / (k2 - k1);
    let k_min = law.base_bending_stiffness();
    assert!((slope / k_min - 1.0).abs() < 1e-9, "{slope} vs {k_min}");
}

/// `section.stick_stiffness = one_body` along a curvature path (`law_path_moments`, what the
/// bending test's `law_moment` column follows): turned back by a little after full slip,
/// every wire sticks again, so the law's unloading tangent is its all-stick stiffness, and
/// with `one_body` that is the rod model of the strand as one body
/// (`strand_bonded_stiffness`: its free part is Costello's K_min, the law's default), not the
/// per-interface `bonded` value. The tangent is a difference of moments near 1 N m over a
/// step of 1e-6 1/m: round-off 1e-16 / 1e-4, far below the 1e-6 asked.
#[test]
fn one_body_unloads_with_the_strand_as_one_body() {
    let mut scene = Scene::parse(SCENE).unwrap();
    let one_body = strand_core::bonded::strand_bonded_stiffness(
        &scene.strand,
        &strand_core::BondedOptions::default(),
    )
    .unwrap()
    .bonded;
    let (k1, dk) = (0.05, 1e-6);
    let tangent = |scene: &Scene| {
        let m = strand_scene::law_path_moments(scene, 1e4, 3, &[k1, k1 - dk]);
        (m[0] - m[1]) / dk
    };
    scene.section.stick_stiffness = strand_core::StickStiffness::OneBody;
    let t = tangent(&scene);
    assert!((t / one_body - 1.0).abs() < 1e-6, "{t} vs {one_body}");
    scene.section.stick_stiffness = strand_core::StickStiffness::Bonded;
    let t = tangent(&scene);
    assert!(t / one_body > 2.0, "bonded: {t} vs one body {one_body}");
}
