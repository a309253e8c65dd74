//! `strand run` writes the SPEC 6 files: a static scene (the paper's section-3 strand under
//! g = 12) and a dynamic one (the Fig. 8 pinned pendulum).

#[path = "../../strand-scene/tests/common/temp_path.rs"]
mod temp_path;

use std::path::Path;
use std::process::Command;

use temp_path::TempPath;

fn run(scene: &str, tag: &str, extra: &[&str]) -> TempPath {
    let out = TempPath::new(&format!("strand-run-{tag}"));
    let o = Command::new(env!("CARGO_BIN_EXE_strand"))
        .args(["run", scene, "--out", out.to_str().unwrap()])
        .args(extra)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

fn csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

fn summary(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn static_scene_writes_centerline_wires_and_summary() {
    let out = run("validation/paper-sec3-g12.json", "static", &[]);
    for model in ["equivalent", "traditional"] {
        let dir = out.join(model);
        let s = summary(&dir.join("summary.json"));
        assert_eq!(s["status"], "ok");
        assert_eq!(s["model"], model);
        let (h, rows) = csv(&dir.join("centerline.csv"));
        assert_eq!(
            h,
            [
                "s",
                "x",
                "y",
                "z",
                "curvature",
                "tension",
                "bending_stiffness",
                "moment"
            ]
        );
        assert!(rows.len() > 100);
        // The moment is the one the secant stiffness divides: M = (M / kappa) kappa, signed
        // like the curvature (round-off of one division and one product).
        for r in &rows {
            let (kappa, k, m) = (r[4], r[6], r[7]);
            assert!(
                (m - k * kappa).abs() <= 1e-12 * m.abs().max(1e-300),
                "{r:?}"
            );
        }
        assert!(rows.iter().flatten().all(|v| v.is_finite()));
        // The strand hangs: the last point is far below the clamp.
        assert!(rows.last().unwrap()[2] < -0.5);
        let wires = std::fs::read_to_string(dir.join("wires.csv")).unwrap();
        assert!(wires.starts_with("s,wire,phase,critical_curvature,state,layer\n"));
    }
    // Equivalent: bending stiffness between K_min and K_max everywhere (SPEC 8 Fig. 10).
    let (_, rows) = csv(&out.join("equivalent/centerline.csv"));
    for r in &rows {
        assert!(
            r[6] >= 1.57725e-2 * (1.0 - 1e-5) && r[6] <= 1.135275e-1 * (1.0 + 1e-5),
            "{r:?}"
        );
    }
}

#[test]
fn dynamic_scene_writes_tip_energy_and_vtk() {
    let out = run(
        "validation/paper-fig8-pinned.json",
        "dynamic",
        &["--vtk", "--model", "equivalent", "--model", "traditional"],
    );
    assert!(
        !out.join("fine").exists(),
        "--model leaves the fine model out"
    );
    let dir = out.join("equivalent");
    let s = summary(&dir.join("summary.json"));
    assert_eq!(s["analysis"], "dynamic");
    let (h, tip) = csv(&dir.join("tip.csv"));
    assert_eq!(h, ["t", "x", "y", "z", "vx", "vy", "vz"]);
    assert_eq!(tip.len(), 51); // t = 0 and every 10 ms to 0.5 s
    let (h, en) = csv(&dir.join("energy.csv"));
    assert_eq!(
        h,
        [
            "t",
            "kinetic",
            "gravity",
            "elastic",
            "dissipated",
            "total",
            "non_potential"
        ]
    );
    // The hysteretic law has no non-potential part.
    assert!(en.iter().all(|r| r[6] == 0.0));
    // Energy balance: total stays at its initial value (zero) to a small fraction of the
    // kinetic energy reached.
    let kmax = en.iter().map(|r| r[1]).fold(0.0, f64::max);
    let worst = en.iter().map(|r| r[5].abs()).fold(0.0, f64::max);
    assert!(
        kmax > 0.05 && worst < 1e-4 * kmax,
        "kinetic {kmax}, balance {worst}"
    );
    // Dissipation of the hysteretic law never decreases.
    assert!(en.windows(2).all(|w| w[1][4] >= w[0][4] - 1e-15));
    let frames = std::fs::read_dir(dir.join("vtk")).unwrap().count();
    assert_eq!(frames, 51);
}

/// A model that fails does not stop the others: the equivalent beam of this scene cannot take
/// the Verlet step (above its stable step) while the traditional beam, made heavy, can. The
/// command says which model failed and why, exits with a failure, and both folders hold their
/// files.
#[test]
fn a_failing_model_leaves_the_others_and_exits_with_failure() {
    let out = TempPath::new("strand-run-iso");
    std::fs::create_dir_all(&out).unwrap();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/paper-fig8-pinned.json"
    ))
    .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["analysis"] = serde_json::json!({ "kind": "dynamic", "duration": 0.01,
        "integrator": "verlet", "time_step": 3e-4, "output_interval": 0.005 });
    v["models"] = serde_json::json!({ "equivalent": { "elements": 8 },
        "traditional": { "elements": 8, "mass_per_length": 21.16 } });
    let scene = out.join("scene.json");
    std::fs::write(&scene, v.to_string()).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_strand"))
        .args([
            "run",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stdout.contains("FAILED (unstable-step)"), "{stdout}");
    assert!(
        stderr.contains("1 of 2 models failed: equivalent"),
        "{stderr}"
    );
    assert_eq!(
        summary(&out.join("equivalent/summary.json"))["status"],
        "failed"
    );
    assert_eq!(
        summary(&out.join("traditional/summary.json"))["status"],
        "ok"
    );
    let (_, tip) = csv(&out.join("traditional/tip.csv"));
    assert_eq!(tip.len(), 3);
}

/// `strand bend` on counts too large for the machine stops with a message naming the flags,
/// not a panic: 3e10 pitches (a strand beyond the plausible length, which panicked), a pitch
/// count whose product with the segments overflows, and 1e5 pitches (64 GiB, which hung).
#[test]
fn bend_refuses_counts_it_cannot_build() {
    for (pitches, segments, says) in [
        ("30000000000", "12", "GiB"),
        ("1152921504606846976", "16", "overflows"),
        ("100000", "12", "64.1 GiB"),
    ] {
        let refused = TempPath::new("strand-bend-refused");
        let o = Command::new(env!("CARGO_BIN_EXE_strand"))
            .args([
                "bend",
                "validation/paper-fig7-g8.json",
                "--tension",
                "10",
                "--pitches",
                pitches,
                "--segments-per-pitch",
                segments,
                "--out",
                refused.to_str().unwrap(),
            ])
            .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{pitches}: {err}");
        assert!(err.contains("--pitches") && err.contains(says), "{err}");
    }
}

/// `strand bend` draws the fine and the law's moment against curvature beside `bending.csv`
/// (a one-layer strand, short: 3 pitches of 8 segments, one load reversal).
#[test]
fn bend_draws_its_curve() {
    let out = TempPath::new("strand-bend-plot");
    let o = Command::new(env!("CARGO_BIN_EXE_strand"))
        .args([
            "bend",
            "validation/vs-fine-30deg.json",
            "--tension",
            "0.1",
            "--curvatures",
            "0.5,-0.5",
            "--pitches",
            "3",
            "--segments-per-pitch",
            "8",
            "--out",
            out.to_str().unwrap(),
        ])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (header, rows) = csv(&out.join("bending.csv"));
    assert!(header.iter().any(|h| h == "law_moment") && rows.len() == 2);
    for f in ["bending.png", "bending.svg"] {
        let len = std::fs::metadata(out.join(f)).unwrap().len();
        assert!(len > 1000, "{f}: {len} bytes");
    }
}
