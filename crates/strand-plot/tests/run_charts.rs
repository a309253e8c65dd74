//! `plot_run` draws every chart of a run from its files: a static and a dynamic run of the
//! Table 1 strand (equivalent and traditional beams), PNG and SVG with their text.

#[path = "../../strand-scene/tests/common/temp_path.rs"]
mod temp_path;

use strand_scene::{RunOptions, Scene, run_scene};
use temp_path::TempPath;

fn scene(analysis: &str) -> Scene {
    scene_with(
        analysis,
        r#"[ { "at": "start", "kind": "clamped" } ]"#,
        "{}",
    )
}

fn scene_with(analysis: &str, supports: &str, output: &str) -> Scene {
    let text = format!(
        r#"{{
        "name": "plot-test",
        "strand": {{ "length": 0.4,
            "core": {{ "diameter": 3e-3, "youngs_modulus": 2e8, "poisson_ratio": 0.3, "density": 7801 }},
            "layers": [ {{ "wires": 6, "diameter": 2e-3, "lay_angle_deg": 20,
                           "youngs_modulus": 2e8, "poisson_ratio": 0.3, "density": 7801 }} ] }},
        "law": "hysteretic",
        "supports": {supports},
        "output": {output},
        "loads": {{ "gravity": [0, -8, 0] }},
        "analysis": {analysis},
        "models": {{ "equivalent": {{ "elements": 4 }}, "traditional": {{ "elements": 4 }} }}
    }}"#
    );
    Scene::parse(&text).unwrap()
}

#[test]
fn a_run_is_drawn_from_its_files() {
    for (tag, analysis, stems) in [
        (
            "static",
            r#"{ "kind": "static" }"#,
            &[
                "shape",
                "curvature",
                "stiffness",
                "stick-slip-equivalent",
                "overview",
            ][..],
        ),
        (
            "dynamic",
            r#"{ "kind": "dynamic", "duration": 0.02, "integrator": "generalized-alpha",
                 "time_step": 1e-3, "output_interval": 2e-3 }"#,
            &["tip", "energy-equivalent", "energy-traditional", "overview"][..],
        ),
    ] {
        let out = TempPath::new(&format!("strand-plot-{tag}"));
        let scene = scene(analysis);
        let opts = RunOptions {
            out: out.to_path_buf(),
            vtk: false,
        };
        let s = run_scene(&scene, &opts, &mut |_, _| {}).unwrap();
        let files = strand_plot::plot_run(&scene, &out, &s).unwrap();
        for stem in stems {
            let png = out.join("plots").join(format!("{stem}.png"));
            let svg = out.join("plots").join(format!("{stem}.svg"));
            assert!(files.contains(&png) && files.contains(&svg), "{stem}");
            assert!(std::fs::metadata(&png).unwrap().len() > 5000, "{stem}");
            let text = std::fs::read_to_string(&svg).unwrap();
            assert!(text.contains("plot-test"), "{stem}: the title is drawn");
        }
        let stiffness = std::fs::read_to_string(out.join("plots/stiffness.svg")).unwrap();
        assert!(stiffness.contains("K_min") && stiffness.contains("K_max"));
    }
}

/// A span pinned at both ends: its sag is drawn exaggerated, with the factor on the axis; in
/// dynamics the midspan probe (the default) takes the tip's place, with its moment-curvature
/// loop, and the range envelopes are drawn.
#[test]
fn a_span_shows_its_sag_midspan_and_ranges() {
    let supports = r#"[ { "at": "start", "kind": "pinned" }, { "at": "end", "kind": "pinned" } ]"#;
    let out = TempPath::new("strand-plot-span");
    let scene = scene_with(
        r#"{ "kind": "dynamic", "duration": 0.02, "integrator": "generalized-alpha",
             "time_step": 1e-3, "output_interval": 2e-3 }"#,
        supports,
        "{}",
    );
    assert_eq!(scene.output.probes, vec![0.2], "midspan by default");
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: false,
    };
    let s = run_scene(&scene, &opts, &mut |_, _| {}).unwrap();
    let files = strand_plot::plot_run(&scene, &out, &s).unwrap();
    let plots = out.join("plots");
    for stem in [
        "probe-0.2-motion",
        "probe-0.2-loop",
        "range-moment",
        "range-curvature",
        "range-tension",
    ] {
        assert!(files.contains(&plots.join(format!("{stem}.png"))), "{stem}");
    }
    assert!(
        !plots.join("tip.png").exists(),
        "the probe replaces the tip"
    );
    let shape = std::fs::read_to_string(plots.join("shape.svg")).unwrap();
    assert!(
        shape.contains("scale x"),
        "the sag is exaggerated and says so"
    );
    let loop_svg = std::fs::read_to_string(plots.join("probe-0.2-loop.svg")).unwrap();
    assert!(loop_svg.contains("work of M dkappa"));
}
