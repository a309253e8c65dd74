//! `run_bending`: the virtual bending test through the scene runner writes the fine curve
//! beside the section law's, and rejects bad input naming the option.

#[path = "common/temp_path.rs"]
mod temp_path;

use std::path::PathBuf;

use strand_scene::{BendingOptions, RunError, Scene, run_bending};
use temp_path::TempPath;

fn scene() -> Scene {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../validation/paper-fig7-g8.json");
    Scene::load(&path).expect("bundled scene")
}

fn options(out: PathBuf) -> BendingOptions {
    BendingOptions {
        tension: 10.0,
        curvatures: vec![0.02, 2.0],
        pitches: 3,
        segments_per_pitch: 8,
        out,
    }
}

#[test]
fn bending_curve_sits_beside_the_law() {
    let out = TempPath::new("strand-bend");
    let s = scene();
    let mut seen = 0;
    let summary = run_bending(&s, &options(out.to_path_buf()), &mut |_, _| seen += 1).unwrap();
    assert_eq!(seen, 3, "the tension step and two curvatures");
    let [[k0, m0, law0], [k1, m1, law1]] = summary.points[..] else {
        panic!("two points: {:?}", summary.points)
    };
    // Below the first slip the law is the all-stick closed form K_max kappa (eq. (22a)).
    let first = summary.first_slip_curvature.unwrap();
    assert!(k0 < first, "{k0} below the first slip at {first}");
    assert!((law0 / (summary.k_max * k0) - 1.0).abs() < 1e-9, "{law0}");
    // Far past it the law tends to K_min; the fine strand is near all-stick at first and has
    // slipped toward K_min at the large curvature.
    assert!(law1 / k1 < 0.3 * summary.k_max);
    assert!(
        m0 / k0 > 0.7 * summary.k_max,
        "fine K = {} K_max",
        m0 / k0 / summary.k_max
    );
    assert!(
        m1 / k1 < 0.4 * summary.k_max,
        "fine K = {} K_max",
        m1 / k1 / summary.k_max
    );
    assert!(m1 / k1 > 0.9 * summary.k_min);
    let csv = std::fs::read_to_string(out.join("bending.csv")).unwrap();
    assert!(csv.starts_with("imposed_curvature,curvature,moment,law_moment,stiffness"));
    assert_eq!(csv.lines().count(), 3);
    assert!(out.join("summary.json").exists());
}

#[test]
fn bad_bending_input_names_the_option() {
    let s = scene();
    let out = TempPath::new("strand-bend-bad");
    for (opts, word) in [
        (
            BendingOptions {
                tension: -1.0,
                ..options(out.to_path_buf())
            },
            "--tension",
        ),
        // A repeated curvature and a zero one (a decreasing sequence reverses the load).
        (
            BendingOptions {
                curvatures: vec![0.5, 0.5],
                ..options(out.to_path_buf())
            },
            "--curvatures",
        ),
        (
            BendingOptions {
                curvatures: vec![0.5, 0.0],
                ..options(out.to_path_buf())
            },
            "--curvatures",
        ),
        (
            BendingOptions {
                pitches: 2,
                ..options(out.to_path_buf())
            },
            "--pitches",
        ),
    ] {
        let e = run_bending(&s, &opts, &mut |_, _| {}).unwrap_err();
        assert!(matches!(e, RunError::Setup { .. }));
        assert!(e.to_string().contains(word), "{e}");
    }
}
