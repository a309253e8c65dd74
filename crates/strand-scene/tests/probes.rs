//! Probes (`probe_<s>.csv`) and range envelopes (`range.csv`) against the files they summarise:
//! each probe row equals the centreline of the same output frame (the VTK frame, with its
//! point data, and at the end `centerline.csv`) interpolated at s by this test's own linear
//! interpolation, for the beams (planar and spatial) and the fine model; the probe at s = L
//! equals `tip.csv`; every envelope bounds every frame in its window and its mean is the
//! frames' mean.

mod common;
#[path = "common/temp_path.rs"]
mod temp_path;

use std::collections::HashMap;
use std::path::Path;

use common::csv_columns;
use serde_json::json;
use strand_scene::{RunOptions, Scene, run_scene};
use temp_path::TempPath;

fn run(scene: &serde_json::Value, tag: &str) -> TempPath {
    let scene = Scene::parse(&scene.to_string()).expect("valid scene");
    let out = TempPath::new(&format!("strand-probes-{tag}"));
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: true,
    };
    let summaries = run_scene(&scene, &opts, &mut |_, _| {}).expect("run succeeds");
    for s in &summaries {
        assert!(!s.failed(), "{:?}", s.failure());
        assert!(
            s.warnings.iter().all(|w| !w.contains("left empty")),
            "{:?}",
            s.warnings
        );
    }
    out
}

/// A pendulum of the paper's strand, pinned at the start, falling under gravity from along
/// `direction` (the XY plane: the planar element; else the spatial one).
fn pendulum(
    direction: [f64; 3],
    models: serde_json::Value,
    output: serde_json::Value,
) -> serde_json::Value {
    json!({
        "name": "probe-pendulum",
        "strand": {
            "length": 0.4,
            "core": { "diameter": 3.0e-3, "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 },
            "layers": [ { "wires": 6, "diameter": 2.0e-3, "lay_angle_deg": 20.0,
                          "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 } ],
            "friction": 0.3
        },
        "law": "hysteretic",
        "supports": [ { "at": "start", "kind": "pinned" } ],
        "initial": { "direction": direction },
        "loads": { "gravity": [0.0, -9.8065, 0.0] },
        "analysis": { "kind": "dynamic", "duration": 0.08, "integrator": "generalized-alpha",
                      "time_step": 1e-3, "output_interval": 0.004 },
        "models": models,
        "output": output
    })
}

/// A legacy VTK polyline frame: points and named point data.
struct Frame {
    points: Vec<[f64; 3]>,
    data: HashMap<String, Vec<f64>>,
}

fn read_vtk(path: &Path) -> Frame {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut points = Vec::new();
    let mut data = HashMap::new();
    while let Some(l) = lines.next() {
        if let Some(n) = l.strip_prefix("POINTS ") {
            let n: usize = n.split(' ').next().unwrap().parse().unwrap();
            for _ in 0..n {
                let v: Vec<f64> = lines
                    .next()
                    .unwrap()
                    .split(' ')
                    .map(|x| x.parse().unwrap())
                    .collect();
                points.push([v[0], v[1], v[2]]);
            }
        } else if let Some(name) = l.strip_prefix("SCALARS ") {
            let name = name.split(' ').next().unwrap().to_string();
            lines.next(); // LOOKUP_TABLE
            let v = (0..points.len())
                .map(|_| lines.next().unwrap().parse().unwrap())
                .collect();
            data.insert(name, v);
        }
    }
    Frame { points, data }
}

/// Linear interpolation in the increasing `at` at `s` (this test's own).
fn interp(at: &[f64], v: &[f64], s: f64) -> f64 {
    let j = (1..at.len()).find(|&j| at[j] >= s).unwrap_or(at.len() - 1);
    let w = (s - at[j - 1]) / (at[j] - at[j - 1]);
    (1.0 - w) * v[j - 1] + w * v[j]
}

/// The s of each point of a frame: the arc lengths of the rows of `centerline.csv`, whose
/// points the VTK frames follow in the same order.
fn stations(dir: &Path) -> Vec<f64> {
    csv_columns(&dir.join("centerline.csv"))["s"].clone()
}

fn scale(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Every probe row against the VTK frame of the same time: curvature, moment and tension to
/// round-off; the position within the error of linear interpolation between the frame's
/// points, h^2/8 max|r''| (`exact_position`: the beams take the position from the elements'
/// shape functions at s; the fine model interpolates its nodes, so there to round-off).
fn probes_follow_the_frames(dir: &Path, probes: &[f64], exact_position: bool) {
    let s_at = stations(dir);
    let t = csv_columns(&dir.join("tip.csv"))["t"].clone();
    let frames: Vec<Frame> = (0..t.len())
        .map(|k| read_vtk(&dir.join(format!("vtk/centerline_{k:05}.vtk"))))
        .collect();
    for &s in probes {
        let name = format!("probe_{s}.csv");
        let p = csv_columns(&dir.join(&name));
        assert_eq!(p["t"], t, "{name}: one row per output frame");
        for (k, f) in frames.iter().enumerate() {
            assert_eq!(f.points.len(), s_at.len());
            for q in ["curvature", "moment", "tension"] {
                let col = &f.data[q];
                let expect = interp(&s_at, col, s);
                // The same linear interpolation: round-off of a few operations.
                let tol = 1e-12 * scale(col).max(1e-300);
                assert!(
                    (p[q][k] - expect).abs() <= tol,
                    "{name} t = {}: {q} {} vs the frame's {expect}",
                    t[k],
                    p[q][k]
                );
            }
            // Spacing of the points around s and the largest curvature of the frame: a
            // chord of length h departs from a curve with |r''| <= kappa (strain below 1 %:
            // |r''| = kappa |r'|^2 < 1.03 kappa, taken as 2 kappa for the curvature between
            // points) by at most h^2/8 |r''|.
            let j = (1..s_at.len()).find(|&j| s_at[j] >= s).unwrap();
            let h = s_at[j] - s_at[j - 1];
            let kappa = scale(&f.data["curvature"]);
            let tol = if exact_position {
                h * h / 8.0 * 2.0 * kappa + 1e-12
            } else {
                1e-12
            };
            for (a, c) in ["x", "y", "z"].iter().enumerate() {
                let col: Vec<f64> = f.points.iter().map(|x| x[a]).collect();
                let expect = interp(&s_at, &col, s);
                assert!(
                    (p[*c][k] - expect).abs() <= tol,
                    "{name} t = {}: {c} {} vs {expect} (tolerance {tol:e})",
                    t[k],
                    p[*c][k]
                );
            }
            let wires = p["sticking"][k] + p["slipping"][k];
            assert!(
                wires <= 6.0 && p["sticking"][k] >= 0.0,
                "{name}: {wires} wires"
            );
        }
        // The last frame is the final state of centerline.csv.
        let c = csv_columns(&dir.join("centerline.csv"));
        let last = t.len() - 1;
        for q in ["curvature", "moment", "tension"] {
            let expect = interp(&s_at, &c[q], s);
            assert!(
                (p[q][last] - expect).abs() <= 1e-12 * scale(&c[q]).max(1e-300),
                "{name}: final {q} {} vs centerline.csv {expect}",
                p[q][last]
            );
        }
    }
}

/// The probe at s = L is the tip of `tip.csv`, position and velocity (to round-off).
fn probe_at_the_end_is_the_tip(dir: &Path, name: &str) {
    let p = csv_columns(&dir.join(name));
    let tip = csv_columns(&dir.join("tip.csv"));
    for c in ["x", "y", "z", "vx", "vy", "vz"] {
        let tol = 1e-12 * scale(&tip[c]).max(1e-12);
        for (a, b) in p[c].iter().zip(&tip[c]) {
            assert!((a - b).abs() <= tol, "{name} {c}: {a} vs tip {b}");
        }
    }
}

/// Envelopes over the frames in `window` from the VTK frames, against `range.csv`.
fn envelopes_bound_the_frames(dir: &Path, window: Option<(f64, f64)>, quantities: &[&str]) {
    let t = csv_columns(&dir.join("tip.csv"))["t"].clone();
    let r = csv_columns(&dir.join("range.csv"));
    let s_at = stations(dir);
    assert_eq!(r["s"], s_at, "range.csv at the points of centerline.csv");
    let mut taken = 0;
    let mut sums = vec![vec![0.0; s_at.len()]; quantities.len()];
    for (k, &tk) in t.iter().enumerate() {
        if window.is_some_and(|(a, b)| tk < a || tk > b) {
            continue;
        }
        taken += 1;
        let f = read_vtk(&dir.join(format!("vtk/centerline_{k:05}.vtk")));
        for (qi, q) in quantities.iter().enumerate() {
            let (lo, hi) = (&r[&format!("{q}_min")], &r[&format!("{q}_max")]);
            for (i, v) in f.data[*q].iter().enumerate() {
                assert!(
                    lo[i] <= *v && *v <= hi[i],
                    "{q} at s = {}: {v} outside [{}, {}]",
                    s_at[i],
                    lo[i],
                    hi[i]
                );
                sums[qi][i] += v;
            }
        }
    }
    assert!(taken > 2, "{taken} frames in the window");
    for (qi, q) in quantities.iter().enumerate() {
        let (lo, hi, mean) = (
            &r[&format!("{q}_min")],
            &r[&format!("{q}_max")],
            &r[&format!("{q}_mean")],
        );
        let sc = scale(hi).max(scale(lo)).max(1e-300);
        for i in 0..s_at.len() {
            assert!(
                lo[i] <= mean[i] && mean[i] <= hi[i],
                "{q} mean outside its range"
            );
            let expect = sums[qi][i] / taken as f64;
            // A sum of `taken` values: round-off of that many additions.
            assert!(
                (mean[i] - expect).abs() <= 1e-13 * taken as f64 * sc,
                "{q} mean at s = {}: {} vs the frames' {expect}",
                s_at[i],
                mean[i]
            );
        }
        // The bounds are attained (a min or max from no frame would be loose).
        assert!(lo.iter().chain(hi).all(|v| v.is_finite()));
    }
}

#[test]
fn beam_probes_equal_the_centreline_at_every_output_time() {
    let probes = [0.0, 0.13, 0.25, 0.4];
    for (direction, tag) in [([1.0, 0.0, 0.0], "planar"), ([0.6, 0.0, 0.8], "spatial")] {
        let scene = pendulum(
            direction,
            json!({ "equivalent": { "elements": 6 }, "traditional": { "elements": 6 } }),
            json!({ "probes": probes }),
        );
        let out = run(&scene, tag);
        for model in ["equivalent", "traditional"] {
            let dir = out.join(model);
            probes_follow_the_frames(&dir, &probes, true);
            probe_at_the_end_is_the_tip(&dir, "probe_0.4.csv");
            let q = ["curvature", "moment", "tension", "bending_stiffness"];
            envelopes_bound_the_frames(&dir, None, &q);
        }
    }
}

#[test]
fn fine_probes_equal_the_measured_centreline_at_every_output_time() {
    let probes = [0.0, 0.13, 0.4];
    let mut scene = pendulum(
        [1.0, 0.0, 0.0],
        json!({ "fine": { "segments_per_wire": 10 } }),
        json!({ "probes": probes }),
    );
    scene["analysis"] = json!({ "kind": "dynamic", "duration": 0.02, "integrator": "verlet",
                               "output_interval": 0.002 });
    let out = run(&scene, "fine");
    let dir = out.join("fine");
    probes_follow_the_frames(&dir, &probes, false);
    envelopes_bound_the_frames(&dir, None, &["curvature", "moment", "tension"]);
}

#[test]
fn the_range_window_takes_only_its_frames() {
    let window = (0.02, 0.05);
    let scene = pendulum(
        [1.0, 0.0, 0.0],
        json!({ "equivalent": { "elements": 6 } }),
        json!({ "range_window": [window.0, window.1] }),
    );
    let out = run(&scene, "window");
    let dir = out.join("equivalent");
    let q = ["curvature", "moment", "tension", "bending_stiffness"];
    envelopes_bound_the_frames(&dir, Some(window), &q);
    // The pendulum falls: the last frames bend it more than any in the window, so the window
    // excluded them (or the test above would hold for the whole run too).
    let r = csv_columns(&dir.join("range.csv"));
    let last = read_vtk(&dir.join("vtk/centerline_00020.vtk"));
    let beyond = last.data["tension"]
        .iter()
        .zip(&r["tension_max"])
        .any(|(v, hi)| v > hi);
    assert!(
        beyond,
        "the frame at t = 0.08 s lies outside the window's envelope"
    );
}

/// Statics: each probe file holds one row, the equilibrium at t = 0 at rest, equal to
/// `centerline.csv` interpolated at s (beams with a layer, the fine model on a core wire).
#[test]
fn static_probes_equal_the_centreline() {
    let probes = [0.0, 0.1, 0.23, 0.4];
    let mut checked = 0;
    let layer = json!([ { "wires": 6, "diameter": 2.0e-3, "lay_angle_deg": 20.0,
                          "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 } ]);
    for (layers, models, tag) in [
        (
            layer,
            json!({ "equivalent": { "elements": 6 }, "traditional": { "elements": 6 } }),
            "static-beams",
        ),
        (
            json!([]),
            json!({ "fine": { "segments_per_wire": 20 } }),
            "static-fine",
        ),
    ] {
        let scene = json!({
            "name": "probe-cantilever",
            "strand": {
                "length": 0.4,
                "core": { "diameter": 3.0e-3, "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 },
                "layers": layers
            },
            "supports": [ { "at": "start", "kind": "clamped" } ],
            "loads": { "gravity": [0.0, -9.8065, 0.0] },
            "analysis": { "kind": "static", "load_steps": 4 },
            "models": models,
            "output": { "probes": probes }
        });
        let out = run(&scene, tag);
        for model in ["equivalent", "traditional", "fine"] {
            let dir = out.join(model);
            if !dir.exists() {
                continue;
            }
            checked += 1;
            let c = csv_columns(&dir.join("centerline.csv"));
            let kappa = scale(&c["curvature"]);
            for s in probes {
                let p = csv_columns(&dir.join(format!("probe_{s}.csv")));
                assert_eq!(p["t"], vec![0.0], "{model} {s}: one row at t = 0");
                for v in ["vx", "vy", "vz"] {
                    assert_eq!(p[v], vec![0.0]);
                }
                for q in ["curvature", "moment", "tension"] {
                    let expect = interp(&c["s"], &c[q], s);
                    let tol = 1e-12 * scale(&c[q]).max(1e-300);
                    assert!((p[q][0] - expect).abs() <= tol, "{model} {s} {q}");
                }
                // Position: exact at s for the beams, within the chord error h^2/8 |r''|
                // of the rows' interpolation (module docs of the dynamic check).
                let j = (1..c["s"].len()).find(|&j| c["s"][j] >= s).unwrap();
                let h = c["s"][j] - c["s"][j - 1];
                for a in ["x", "y", "z"] {
                    let expect = interp(&c["s"], &c[a], s);
                    let tol = h * h / 8.0 * 2.0 * kappa + 1e-12;
                    assert!((p[a][0] - expect).abs() <= tol, "{model} {s} {a}");
                }
            }
        }
    }
    assert_eq!(checked, 3, "the three models were checked");
}
