//! The bundled static scenes (issue 18.2): each beam model solves with no step cut, in at
//! most 60 steps and 600 Newton iterations, with no warning, to the equilibrium that small
//! steps of at most L / 400 reach at the same tolerance (tip within 1e-9 L).

#[path = "common/temp_path.rs"]
mod temp_path;

use strand_ancf::statics::{StaticOptions, solve_static};
use strand_scene::{BeamModelKind, RunOptions, Scene, build_beam, run_scene};
use temp_path::TempPath;

#[test]
fn bundled_static_scenes_solve_without_cut_steps() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../validation");
    for name in [
        "paper-sec3-g8",
        "paper-sec3-g10",
        "paper-sec3-g12",
        "paper-fig7-g8",
        "paper-fig7-g10",
        "paper-fig7-g12",
    ] {
        let text = std::fs::read_to_string(root.join(format!("{name}.json"))).unwrap();
        let mut scene = Scene::parse(&text).unwrap();
        // The beam models only: the fine model is not this test's subject.
        scene.models.fine = None;
        let out = TempPath::new(&format!("strand-static-{name}"));
        let opts = RunOptions {
            out: out.to_path_buf(),
            vtk: false,
        };
        let summaries = run_scene(&scene, &opts, &mut |_, _| {}).unwrap();
        assert_eq!(summaries.len(), 2, "{name}");
        for (summary, which) in summaries
            .iter()
            .zip([BeamModelKind::Equivalent, BeamModelKind::Traditional])
        {
            let beam = build_beam(&scene, which).unwrap();
            let length = beam.length();
            let small = StaticOptions {
                max_step: 1.0 / 400.0,
                ..StaticOptions::default()
            };
            let reference = solve_static(&beam, &small, &mut |_| {}).unwrap();
            let tip = beam.sample(&reference.q, length).0;
            let run_tip = summary.tip.expect("a converged run has a tip");
            let d = (0..3)
                .map(|c| (run_tip[c] - tip[c]).powi(2))
                .sum::<f64>()
                .sqrt();
            println!(
                "{name} {}: {} steps, {} Newton iterations, warnings {:?}; tip {:.2e} L from \
                 {} small steps",
                which.name(),
                summary.steps,
                summary.newton_iterations,
                summary.warnings,
                d / length,
                reference.steps
            );
            assert!(summary.error.is_none(), "{name}: {:?}", summary.error);
            assert!(
                summary.warnings.is_empty(),
                "{name}: {:?}",
                summary.warnings
            );
            assert!(summary.steps <= 60, "{name}: {} steps", summary.steps);
            assert!(
                summary.newton_iterations <= 600,
                "{name}: {} iterations",
                summary.newton_iterations
            );
            assert!(
                d <= 1e-9 * length,
                "{name}: tip {d} m from the small steps'"
            );
        }
    }
}
