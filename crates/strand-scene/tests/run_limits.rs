//! The runner on input that used to crash, hang or be lost: step counts above
//! `analysis.max_steps` refused before the run starts, each model run on its own (one that
//! fails keeps its files and leaves the others to run), the fine model's step and frames, and
//! result files that run from s = 0 to s = L with no `NaN` or `inf`.

#[path = "common/temp_path.rs"]
mod temp_path;

use std::path::{Path, PathBuf};

use serde_json::{Value, json};
use strand_fine as fine;
use strand_scene::{Failure, RunOptions, RunSummary, Scene, run_scene};
use temp_path::TempPath;

fn out_dir(tag: &str) -> TempPath {
    TempPath::new(&format!("strand-limits-{tag}"))
}

/// The Table 1 strand, clamped at the start, under g = 8 along -y.
fn scene(analysis: Value, models: Value) -> Value {
    json!({
        "name": "limits",
        "strand": {
            "length": 0.4,
            "core": { "diameter": 3.0e-3, "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 },
            "layers": [ { "wires": 6, "diameter": 2.0e-3, "lay_angle_deg": 20.0,
                          "youngs_modulus": 2.0e8, "poisson_ratio": 0.3, "density": 7801.0 } ]
        },
        "law": "hysteretic",
        "supports": [ { "at": "start", "kind": "clamped" } ],
        "loads": { "gravity": [0.0, -8.0, 0.0] },
        "analysis": analysis,
        "models": models
    })
}

fn run(v: &Value, tag: &str) -> (Vec<RunSummary>, TempPath) {
    let scene = Scene::parse(&v.to_string()).expect("a valid scene");
    run_parsed(&scene, tag)
}

fn run_parsed(scene: &Scene, tag: &str) -> (Vec<RunSummary>, TempPath) {
    let out = out_dir(tag);
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: false,
    };
    let s = run_scene(scene, &opts, &mut |_, _| {}).expect("summaries are written");
    (s, out)
}

/// Every CSV file below `dir`: (path, header, rows of fields).
fn csv_files(dir: &Path) -> Vec<(PathBuf, Vec<String>, Vec<Vec<String>>)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(csv_files(&p));
        } else if p.extension().is_some_and(|x| x == "csv") {
            let text = std::fs::read_to_string(&p).unwrap();
            let mut lines = text.lines();
            let header = lines.next().unwrap().split(',').map(String::from).collect();
            let rows = lines
                .map(|l| l.split(',').map(String::from).collect())
                .collect();
            out.push((p, header, rows));
        }
    }
    out
}

/// No file below `dir` holds `NaN` or `inf`, and every CSV field is a number, except the
/// critical curvature of a wire that never slips (empty), the states, and a contact's kind
/// (one of the names `contacts.csv` documents).
fn assert_clean(dir: &Path) {
    for (p, header, rows) in csv_files(dir) {
        for r in &rows {
            for (h, f) in header.iter().zip(r) {
                if h == "state" || (h == "critical_curvature" && f.is_empty()) {
                    continue;
                }
                if h == "kind" {
                    assert!(
                        ["core", "crossing", "line", "neighbour"].contains(&f.as_str()),
                        "{}: kind = `{f}`",
                        p.display()
                    );
                    continue;
                }
                let v: f64 = f
                    .parse()
                    .unwrap_or_else(|_| panic!("{}: {h} = `{f}`", p.display()));
                assert!(v.is_finite(), "{}: {h} = {f}", p.display());
            }
        }
    }
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "json") {
            let t = std::fs::read_to_string(&p).unwrap();
            assert!(
                !t.contains("NaN") && !t.contains("inf"),
                "{}: {t}",
                p.display()
            );
        }
    }
}

fn ga(duration: f64, step: f64, max_steps: Option<u64>) -> Value {
    let mut a = json!({ "kind": "dynamic", "duration": duration, "integrator": "generalized-alpha",
                        "time_step": step, "output_interval": duration / 4.0 });
    if let Some(n) = max_steps {
        a["max_steps"] = json!(n);
    }
    a
}

/// 20 steps run under a limit of 20 and are refused under 19, before the first step, with the
/// count and a time estimate; 2e15 steps (a typo in the duration) are refused at once.
#[test]
fn a_run_above_the_step_limit_is_refused_before_it_starts() {
    let models = json!({ "equivalent": { "elements": 4 } });
    let (s, _) = run(&scene(ga(0.02, 1e-3, Some(20)), models.clone()), "at-limit");
    assert_eq!(s[0].status, "ok", "{:?}", s[0].error);
    assert_eq!(s[0].steps, 20);
    let (s, out) = run(&scene(ga(0.02, 1e-3, Some(19)), models.clone()), "over");
    assert_eq!(s[0].reason, Some(Failure::StepLimit));
    let e = s[0].error.as_deref().unwrap();
    assert!(
        e.contains("2.0000e1 time steps") && e.contains("analysis.max_steps = 19"),
        "{e}"
    );
    assert!(e.contains("would take about"), "{e}");
    assert_eq!(s[0].steps, 0);
    assert!(!out.join("equivalent/tip.csv").exists(), "nothing ran");
    let t = std::time::Instant::now();
    let (s, _) = run(&scene(ga(1e12, 5e-4, None), models), "typo");
    assert_eq!(s[0].reason, Some(Failure::StepLimit));
    let e = s[0].error.as_deref().unwrap();
    assert!(
        e.contains("2.0000e15 time steps") && e.contains("years"),
        "{e}"
    );
    assert!(t.elapsed().as_secs_f64() < 10.0);
}

/// Verlet without a step runs at 0.9 of the estimated stable step: the count uses it.
#[test]
fn the_explicit_step_count_follows_the_stable_step() {
    let a = json!({ "kind": "dynamic", "duration": 1.0, "integrator": "verlet",
                    "output_interval": 0.1, "max_steps": 1000 });
    let (s, _) = run(
        &scene(a, json!({ "equivalent": { "elements": 8 } })),
        "verlet",
    );
    assert_eq!(s[0].reason, Some(Failure::StepLimit));
    let stable = s[0].stable_time_step.expect("the estimate is recorded");
    let want = (1.0 / (0.9 * stable)).ceil();
    let e = s[0].error.as_deref().unwrap();
    assert!(
        e.contains(&format!("{want:.4e} time steps")),
        "{e} ({want})"
    );
}

/// One model failing (the equivalent: a Verlet step above its stable step) leaves the next
/// (the traditional, made heavy enough that the step is stable for it) to run and write its
/// files; the failed one keeps its summary with the reason.
#[test]
fn a_failing_model_leaves_the_others_to_run() {
    let a = json!({ "kind": "dynamic", "duration": 0.01, "integrator": "verlet",
                    "time_step": 3e-4, "output_interval": 0.005 });
    let models = json!({ "equivalent": { "elements": 8 },
                         "traditional": { "elements": 8, "mass_per_length": 21.16 } });
    let (s, out) = run(&scene(a, models), "isolated");
    assert_eq!(s.len(), 2);
    assert_eq!(s[0].reason, Some(Failure::UnstableStep), "{:?}", s[0]);
    assert_eq!(s[1].status, "ok", "{:?}", s[1].error);
    for f in ["summary.json", "centerline.csv", "tip.csv", "energy.csv"] {
        assert!(out.join("traditional").join(f).exists(), "{f}");
    }
    let text = std::fs::read_to_string(out.join("equivalent/summary.json")).unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["status"], "failed");
    assert_eq!(v["reason"], "unstable-step");
    assert_clean(&out);
}

/// An explicit run that goes unstable after its start fails instead of ending `ok`: the Table 1
/// clamped pendulum (Fig. 8) on 4 elements at 0.9 of the stable step estimated at the straight
/// reference swings stably for 0.36 s, then its energy jumps by more than the strand was ever
/// given (about 1 J against 0.15 J of gravity work); the run stops there with `unstable-step`,
/// keeping the frames before it.
#[test]
fn an_explicit_run_that_creates_energy_fails() {
    let mut v: Value =
        serde_json::from_str(include_str!("../../../validation/paper-fig8-clamped.json")).unwrap();
    v["name"] = json!("verlet-4-elements");
    v["analysis"] = json!({ "kind": "dynamic", "duration": 0.5, "integrator": "verlet",
                            "output_interval": 0.01 });
    v["models"] = json!({ "equivalent": { "elements": 4 } });
    v["section"] = json!({ "base_stiffness": "costello" });
    let (s, out) = run(&v, "diverged");
    assert_eq!(s[0].reason, Some(Failure::UnstableStep), "{:?}", s[0]);
    let error = s[0].error.as_deref().unwrap();
    assert!(error.contains("more than the"), "{error}");
    let tip = std::fs::read_to_string(out.join("equivalent/tip.csv")).unwrap();
    assert!(tip.lines().count() > 30, "frames before the jump are kept");
    assert_clean(&out);
}

/// A model that cannot be built (here an equivalent beam edited past the pitch rule's cap
/// after validation) fails with the reason `setup`; the traditional and fine models run.
#[test]
fn a_model_that_cannot_be_built_fails_alone() {
    let a = json!({ "kind": "dynamic", "duration": 2e-3, "integrator": "verlet",
                    "output_interval": 1e-3 });
    let models = json!({ "equivalent": { "elements": 4 }, "traditional": { "elements": 4 },
                         "fine": { "segments_per_wire": 4 } });
    let mut scene = Scene::parse(&scene(a, models).to_string()).unwrap();
    // 1e5 m in one element: 2.8e7 bending points by the pitch rule.
    let mut spec = scene.strand.spec().clone();
    spec.length = 1e5;
    let long = strand_core::Strand::new(spec).unwrap();
    let mut long_scene = scene.clone();
    long_scene.strand = long;
    long_scene.models.equivalent.as_mut().unwrap().elements = 1;
    long_scene.models.traditional = None;
    long_scene.models.fine = None;
    let (s, _) = run_parsed(&long_scene, "setup-long");
    assert_eq!(s[0].reason, Some(Failure::Setup), "{:?}", s[0]);
    assert!(
        s[0].error.as_deref().unwrap().contains("use at least"),
        "{:?}",
        s[0].error
    );
    // A setup failure (zero bending points, edited in after validation) first in a scene with
    // the other two models.
    scene.models.equivalent.as_mut().unwrap().integration_points = Some(0);
    let (s, out) = run_parsed(&scene, "setup");
    assert_eq!(s.len(), 3);
    assert_eq!(s[0].reason, Some(Failure::Setup), "{:?}", s[0]);
    assert!(s[1..].iter().all(|s| s.status == "ok"), "{s:?}");
    assert_clean(&out);
}

/// The fine model: a dynamic run above the limit is refused before it starts; an output
/// interval shorter than its step writes a frame every step (and says so); one a little
/// longer shortens the step so that frames fall on steps (and says so).
#[test]
fn the_fine_model_counts_its_steps_and_says_what_it_changed() {
    let models = json!({ "fine": { "segments_per_wire": 4 } });
    let a = |duration: f64, interval: f64, max: u64| {
        json!({ "kind": "dynamic", "duration": duration, "integrator": "verlet",
                "output_interval": interval, "max_steps": max })
    };
    let (s, _) = run(&scene(a(1.0, 0.1, 100), models.clone()), "fine-limit");
    assert_eq!(s[0].reason, Some(Failure::StepLimit), "{:?}", s[0]);
    let stable = s[0].stable_time_step.unwrap();
    // An interval of half the step: a frame at every step, at the stable step.
    let (s, out) = run(
        &scene(a(10.0 * stable, 0.5 * stable, 1000), models.clone()),
        "fine-dense",
    );
    assert_eq!(s[0].status, "ok", "{:?}", s[0].error);
    assert!(
        s[0].warnings
            .iter()
            .any(|w| w.contains("a frame is written at every step")),
        "{:?}",
        s[0].warnings
    );
    assert_eq!(s[0].time_step, Some(stable));
    let frames = csv_files(&out.join("fine"))
        .into_iter()
        .find(|f| f.0.ends_with("tip.csv"))
        .unwrap()
        .2
        .len();
    assert_eq!(frames, s[0].steps + 1);
    assert_clean(&out);
    // An interval of 1.5 steps: two steps of 0.75 per frame, with a warning.
    let (s, _) = run(
        &scene(a(6.0 * stable, 1.5 * stable, 1000), models),
        "fine-short",
    );
    assert!((s[0].time_step.unwrap() / (0.75 * stable) - 1.0).abs() < 1e-12);
    assert!(
        s[0].warnings.iter().any(|w| w.contains("was shortened")),
        "{:?}",
        s[0].warnings
    );
}

/// The fine model's static settling stops at the step limit: the run fails naming it and
/// keeps the state it reached along the strand, with no empty or non-finite value.
#[test]
fn the_fine_settling_stops_at_the_step_limit_and_keeps_its_state() {
    let a = json!({ "kind": "static", "max_steps": 300 });
    let (s, out) = run(
        &scene(a, json!({ "fine": { "segments_per_wire": 4 } })),
        "settle",
    );
    assert_eq!(s[0].reason, Some(Failure::StepLimit), "{:?}", s[0]);
    assert!(
        s[0].error
            .as_deref()
            .unwrap()
            .contains("analysis.max_steps = 300"),
        "{:?}",
        s[0].error
    );
    let files = csv_files(&out.join("fine"));
    let centre = files
        .iter()
        .find(|f| f.0.ends_with("centerline.csv"))
        .unwrap();
    assert_eq!(centre.2.len(), 5, "the core's 4 segments: 5 nodes");
    let num = |r: &Vec<String>, i: usize| r[i].parse::<f64>().unwrap();
    assert_eq!(num(&centre.2[0], 0), 0.0);
    assert!((num(&centre.2[4], 0) - 0.4).abs() < 1e-12);
    assert!(s[0].tip.is_some());
    assert_clean(&out);
}

/// The fine model's static settling steps at the settle's own step, safety x 2 / omega_max
/// with omega_max the Lanczos estimate at rest (every contact closed and stuck) of the
/// settle's motion model (isotropic rotational inertia), as
/// `strand_fine::settle` does, not at the dynamic runs' step from the Gershgorin bound (which
/// the runner took from 24 Nov 2026 to turn the step limit into a time, a step 3.2 times
/// shorter on the Fig. 7 strand); and the motion at that step stays finite (no rerun at the
/// fallback step).
#[test]
fn the_fine_settling_steps_at_the_lanczos_step() {
    let v = scene(
        json!({ "kind": "static" }),
        json!({ "fine": { "segments_per_wire": 4 } }),
    );
    let parsed = Scene::parse(&v.to_string()).expect("a valid scene");
    let (s, _) = run_parsed(&parsed, "settle-step");
    assert_eq!(s[0].status, "ok", "{:?}", s[0].error);
    // The scene's model, built here (the scene is in the model's axes: along +X, phases
    // from +Z).
    let n = 4;
    let mut model = fine::FineModel::from_strand(
        &parsed.strand,
        fine::Discretisation {
            core_segments: n,
            wire_segments: n,
        },
        fine::Support::Clamped,
        fine::Support::Free,
    );
    let contact = fine::ContactOptions {
        penetration: parsed.models.fine.as_ref().unwrap().penetration,
        ..fine::ContactOptions::default()
    };
    model.add_contacts(&parsed.strand, &contact);
    let settle = fine::SettleOptions::default();
    let moving = fine::settle::motion_model(&model, &settle);
    let omega = fine::spectrum::lanczos_highest_frequency(&moving, &model.rest_state(), 100).omega;
    let dt = s[0].time_step.unwrap();
    assert!(
        (dt * omega / (settle.safety * 2.0) - 1.0).abs() < 1e-12,
        "step {dt:.4e} s, {} x 2 / omega_max = {:.4e} s",
        settle.safety,
        settle.safety * 2.0 / omega
    );
    assert!(
        !s[0].warnings.iter().any(|w| w.contains("fallback")),
        "{:?}",
        s[0].warnings
    );
}

/// `centerline.csv` runs from the clamp (s = 0, at the origin) to the tip (s = L, where the
/// summary puts it), in statics and dynamics, for the beams and the fine model.
#[test]
fn the_centreline_runs_from_end_to_end() {
    let statics = json!({ "kind": "static" });
    let dynamics = json!({ "kind": "dynamic", "duration": 5e-3, "integrator": "verlet",
                           "output_interval": 1e-3 });
    let beams = json!({ "equivalent": { "elements": 4 }, "traditional": { "elements": 4 } });
    let all = json!({ "equivalent": { "elements": 4 }, "traditional": { "elements": 4 },
                      "fine": { "segments_per_wire": 4 } });
    // (The fine model's statics: `the_fine_settling_stops_at_the_step_limit...`.)
    for (tag, a, models) in [
        ("ends-static", statics, beams),
        ("ends-dynamic", dynamics, all),
    ] {
        let (s, out) = run(&scene(a, models), tag);
        for m in &s {
            assert_eq!(m.status, "ok", "{}: {:?}", m.model, m.error);
            let f = csv_files(&out.join(&m.model))
                .into_iter()
                .find(|f| f.0.ends_with("centerline.csv"))
                .unwrap();
            let num = |r: &Vec<String>, i: usize| r[i].parse::<f64>().unwrap();
            let (first, last) = (&f.2[0], &f.2[f.2.len() - 1]);
            // The beams hold a clamped node exactly; the fine model's clamp is a stiff spring.
            let held = if m.model == "fine" { 1e-4 } else { 0.0 };
            assert_eq!(num(first, 0), 0.0, "{}", m.model);
            assert!((num(last, 0) - 0.4).abs() < 1e-12, "{}: {last:?}", m.model);
            assert!(
                (1..4).all(|i| num(first, i).abs() <= held),
                "{}: {first:?}",
                m.model
            );
            let tip = m.tip.unwrap();
            let d = (0..3)
                .map(|i| (num(last, i + 1) - tip[i]).abs())
                .fold(0.0, f64::max);
            assert!(d < 1e-12, "{}: {last:?} vs {tip:?}", m.model);
            // s increases along the file.
            assert!(f.2.windows(2).all(|w| num(&w[1], 0) >= num(&w[0], 0)));
        }
        assert_clean(&out);
    }
}
