//! The runner's fine model: the measured moment, curvature and stiffness along a cantilever
//! against beam theory, and a short dynamic run of the paper's strand with contacts (files,
//! energy balance, the scene's axes).

mod common;
#[path = "common/temp_path.rs"]
mod temp_path;

use serde_json::json;
use strand_scene::{RunOptions, Scene, run_scene};
use temp_path::TempPath;

fn out_dir(tag: &str) -> TempPath {
    TempPath::new(&format!("strand-fine-{tag}"))
}

fn run(scene: serde_json::Value, tag: &str) -> TempPath {
    let scene = Scene::parse(&scene.to_string()).expect("valid scene");
    let out = out_dir(tag);
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: false,
    };
    run_scene(&scene, &opts, &mut |_, _| {}).expect("run succeeds");
    out.into_sub("fine")
}

/// A steel core wire without a layer, clamped, under gravity: small deflection.
#[test]
fn measured_moment_curvature_and_stiffness_follow_beam_theory() {
    let (d, e, rho, g, l): (f64, f64, f64, f64, f64) = (3.0e-3, 2.0e11, 7801.0, 9.81, 0.4);
    let scene = json!({
        "name": "fine-core-cantilever",
        "strand": {
            "length": l,
            "core": { "diameter": d, "youngs_modulus": e, "poisson_ratio": 0.3, "density": rho },
            "layers": []
        },
        "supports": [ { "at": "start", "kind": "clamped" } ],
        "initial": { "direction": [1.0, 0.0, 0.0] },
        "loads": { "gravity": [0.0, -g, 0.0] },
        "analysis": { "kind": "static", "load_steps": 2 },
        "models": { "fine": { "segments_per_wire": 40 } }
    });
    let dir = run(scene, "core");
    let c = common::csv_columns(&dir.join("centerline.csv"));
    let pi = std::f64::consts::PI;
    let q = rho * pi * d * d / 4.0 * g;
    let ei = e * pi * d.powi(4) / 64.0;
    let tip = q * l.powi(4) / (8.0 * ei);
    let y = c["y"].last().unwrap();
    assert!(
        (-y / tip - 1.0).abs() < 0.01,
        "tip {y:e} m against q L^4 / 8 EI = {tip:e} m"
    );
    // Root moment: the weight's moment about the clamp, q L^2 / 2, signed like the curvature
    // (the hanging cantilever bends with its convex side toward +y: both negative, as in the
    // beams' files).
    let m0 = c["moment"][0];
    assert!(
        (m0 / (-0.5 * q * l * l) - 1.0).abs() < 1e-3,
        "root moment {m0:e} against {:e}",
        -0.5 * q * l * l
    );
    for (i, s) in c["s"].iter().enumerate() {
        let m = -q * (l - s).powi(2) / 2.0;
        assert!(c["curvature"][i] <= 0.0, "curvature at s = {s}");
        // Moment from the far part's weight, exact up to the small deflection.
        assert!(
            (c["moment"][i] - m).abs() < 2e-3 * 0.5 * q * l * l,
            "moment at s = {s}: {} against {m}",
            c["moment"][i]
        );
        // Measured stiffness M / kappa: the wire's E I where the moment is not small.
        if *s < 0.5 * l {
            let k = c["bending_stiffness"][i];
            assert!(
                (k / ei - 1.0).abs() < 0.02,
                "M/kappa at s = {s}: {k} vs {ei}"
            );
        }
        // Horizontal cantilever: the tension is the far weight times the small slope.
        assert!(c["tension"][i].abs() < 0.02 * q * l, "tension at {s}");
    }
}

fn pendulum(direction: [f64; 3], duration: f64) -> serde_json::Value {
    json!({
        "name": "fine-pendulum",
        "strand": {
            "length": 0.4,
            "core": { "diameter": 3.0e-3, "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 },
            "layers": [ { "wires": 6, "diameter": 2.0e-3, "lay_angle_deg": 20.0, "phase_deg": 0.0,
                          "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 } ],
            "friction": 0.3
        },
        "law": "hysteretic",
        "supports": [ { "at": "start", "kind": "pinned" } ],
        "initial": { "direction": direction },
        "loads": { "gravity": [0.0, -9.8065, 0.0] },
        "analysis": { "kind": "dynamic", "duration": duration, "integrator": "verlet",
                      "output_interval": 0.005 },
        "models": { "fine": { "segments_per_wire": 10 } }
    })
}

#[test]
fn dynamic_run_writes_the_files_and_balances_energy() {
    let dir = run(pendulum([1.0, 0.0, 0.0], 0.03), "dyn-x");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["status"], "ok");
    assert_eq!(s["model"], "fine");
    assert_eq!(s["dofs"], 6 * 70);
    let rel = s["energy_balance_relative"].as_f64().unwrap();
    assert!(
        rel < 1e-3,
        "energy balance error {rel:e} of the kinetic energy"
    );
    let tip = common::csv_columns(&dir.join("tip.csv"));
    assert_eq!(tip["t"].len(), 7, "frames at 0, 5, ..., 30 ms");
    // Free fall at first: the tip drops by about g t^2 / 2 (slightly less: it is pinned).
    let drop = -tip["y"].last().unwrap();
    let free = 0.5 * 9.8065 * 0.03f64.powi(2);
    assert!(
        drop > 0.5 * free && drop < 1.6 * free,
        "tip drop {drop:e} vs {free:e}"
    );
    let e = common::csv_columns(&dir.join("energy.csv"));
    for k in ["kinetic", "gravity", "elastic", "dissipated", "total"] {
        assert!(e[k].iter().all(|v| v.is_finite()), "{k}");
    }
    assert!(e["dissipated"].iter().all(|&w| w >= 0.0));
    let contacts = std::fs::read_to_string(dir.join("contacts.csv")).unwrap();
    assert_eq!(contacts.lines().count(), 1 + 6 * 10 * 2);
    assert!(
        contacts
            .lines()
            .skip(1)
            .all(|l| ["open", "stick", "slip"].iter().any(|st| l.contains(st)))
    );
    // The same scene laid along +Z (gravity unchanged, a rotation about Y, which takes the
    // phase reference +Z to -X) gives the rotated results.
    let mut along_z = pendulum([0.0, 0.0, 1.0], 0.03);
    along_z["initial"]["phase_reference"] = json!([-1.0, 0.0, 0.0]);
    let dz = run(along_z, "dyn-z");
    let tz = common::csv_columns(&dz.join("tip.csv"));
    for i in 0..tip["t"].len() {
        let (x, y, z) = (tip["x"][i], tip["y"][i], tip["z"][i]);
        // R_y(-90 deg): (x, y, z) -> (-z, y, x).
        for (a, b) in [(tz["x"][i], -z), (tz["y"][i], y), (tz["z"][i], x)] {
            assert!((a - b).abs() < 1e-9, "frame {i}: {a} vs {b}");
        }
    }
}
