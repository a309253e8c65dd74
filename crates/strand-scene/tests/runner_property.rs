//! Random valid scenes through the whole runner: strands of 1 to 12 wires at lay angles of 1 to
//! 60 deg, friction 0 to 1, every support, law, analysis and integrator, all three models, the
//! 3D fields (initial direction, velocity and angular velocity, point forces, a moving
//! support). The time step, the duration, the output interval, gravity and the point forces
//! are drawn in decades over 1e-15 to 1e3 of their natural scale (the time an axial wave takes
//! along the strand; 9.81 m/s^2; the strand's weight), gravity and point forces also zero, and
//! the length over its valid range from 1e-6 m up to 1e3 m; each half the time, and over the
//! usual decades the other half. Each model's run ends `ok`, or `failed` with a named reason and a
//! message; it ends (a run that does not finish within a generous bound is a hang); no file it
//! writes holds `NaN` or `inf`; nothing panics.
//!
//! Runs of the scenes that must solve end `ok` ([`must_solve`]): a held, slender strand of a
//! beam model under a load that bends it by at most a tenth of its length, in statics, or in
//! dynamics from rest at or below the stable step the program estimates and within the step
//! limit. Of the other runs that start (not refused by the step limit), a share at least
//! [`OK_SHARE`] ends `ok`, so that a model that always fails is seen.
//! The scenes in `tests/scenes/` (runs that hung, panicked or failed where they must not) run
//! as regressions with their expected outcome (`tests/scenes/expected.json`).

#[path = "common/must_solve.rs"]
mod must_solve;
#[path = "common/temp_path.rs"]
mod temp_path;

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use must_solve::{must_solve, wire_fit};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestRunner};
use serde_json::{Value, json};
use strand_scene::{Failure, RunOptions, RunSummary, Scene, run_scene};
use temp_path::TempPath;

/// A run that takes longer than this is taken for a hang. The largest scene here (12 wires,
/// 16 elements, 24 fine segments per wire, a 2000-step limit) runs in about a second; the bound
/// only has to tell a finished run from one that never ends on a loaded machine.
/// `STRAND_PROP_HANG=S` sets another bound (s), e.g. to see a hang found sooner.
fn hang() -> Duration {
    let seconds = std::env::var("STRAND_PROP_HANG")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(300);
    Duration::from_secs(seconds)
}

/// Step limit of every generated scene, so that a run is short whatever the stable step.
const MAX_STEPS: u64 = 2000;

fn out_dir(tag: &str) -> TempPath {
    TempPath::new(&format!("strand-prop-{tag}"))
}

/// Decades over which the length, the times and the loads are drawn, relative to their
/// natural scale.
const DECADES: std::ops::Range<f64> = -15.0..3.0;

/// Decades of the strand length (m): its valid range (`strand.length` from 1e-6 m) up to the
/// top of [`DECADES`].
const LENGTH_DECADES: std::ops::Range<f64> = -6.0..3.0;

/// A value drawn in decades over [`DECADES`] (a factor of its natural scale), or, as often,
/// over the `usual` decades, where the scenes that must solve lie.
fn decades_or(usual: std::ops::Range<f64>) -> impl Strategy<Value = f64> {
    prop_oneof![DECADES, usual].prop_map(|e| 10f64.powf(e))
}

#[derive(Debug, Clone)]
struct Params {
    length: f64,
    core_d: f64,
    young: f64,
    density: f64,
    wires: u32,
    fit: f64,
    lay_deg: f64,
    friction: f64,
    gravity: [f64; 3],
    law: &'static str,
    supports: Vec<(&'static str, &'static str)>,
    analysis: Analysis,
    elements: u32,
    segments: u32,
    models: [bool; 3],
    motion: Motion,
}

/// The 3D fields: initial direction, initial velocity and angular velocity (dynamics only),
/// point forces (at fractions of the length, in units of the strand's weight) and a support
/// motion (one row `[t, dx, dy, dz]` with t as a fraction of the duration and dx.. as
/// fractions of the length).
#[derive(Debug, Clone)]
struct Motion {
    direction: Option<[f64; 3]>,
    velocity: Option<[f64; 3]>,
    angular_velocity: Option<[f64; 3]>,
    points: Vec<(f64, [f64; 3])>,
    support: Option<(f64, [f64; 3])>,
}

fn scaled(lo: f64, hi: f64) -> impl Strategy<Value = [f64; 3]> {
    (unit_vector(), lo..hi).prop_map(|(u, e)| u.map(|x| x * 10f64.powf(e)))
}

fn motion() -> impl Strategy<Value = Motion> {
    (
        proptest::option::of(unit_vector()),
        proptest::option::weighted(0.3, scaled(-3.0, 1.0)),
        proptest::option::weighted(0.3, scaled(-2.0, 2.0)),
        prop_oneof![
            Just(vec![]),
            proptest::collection::vec(
                (
                    0.0f64..=1.0,
                    prop_oneof![scaled(DECADES.start, DECADES.end), scaled(-4.0, -1.0)],
                ),
                1..3,
            ),
        ],
        proptest::option::weighted(0.3, (0.1f64..=2.0, scaled(-4.0, -1.0))),
    )
        .prop_map(
            |(direction, velocity, angular_velocity, points, support)| Motion {
                direction,
                velocity,
                angular_velocity,
                points,
                support,
            },
        )
}

/// The analysis; times in units of the time an axial wave takes along the strand.
#[derive(Debug, Clone)]
enum Analysis {
    Static {
        load_steps: u32,
    },
    Verlet {
        duration: f64,
        time_step: Option<f64>,
        interval: f64,
    },
    GenAlpha {
        duration: f64,
        time_step: f64,
        interval: f64,
        rho: f64,
    },
}

fn unit_vector() -> impl Strategy<Value = [f64; 3]> {
    (-1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    })
}

/// Gravity in units of 9.81 m/s^2.
fn gravity() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        1 => Just([0.0, 0.0, 0.0]),
        5 => (unit_vector(), decades_or(-4.0..-1.0)).prop_map(|(u, g)| u.map(|x| x * g)),
    ]
}

fn supports() -> impl Strategy<Value = Vec<(&'static str, &'static str)>> {
    let kind = prop_oneof![Just("clamped"), Just("pinned")];
    prop_oneof![
        Just(vec![]),
        kind.clone().prop_map(|k| vec![("start", k)]),
        kind.clone().prop_map(|k| vec![("end", k)]),
        (kind.clone(), kind).prop_map(|(a, b)| vec![("start", a), ("end", b)]),
    ]
}

fn analysis() -> impl Strategy<Value = Analysis> {
    prop_oneof![
        1 => (1u32..8).prop_map(|load_steps| Analysis::Static { load_steps }),
        2 => (
            decades_or(-2.0..0.5),
            prop_oneof![2 => Just(None), 1 => decades_or(-3.0..-1.0).prop_map(Some)],
            decades_or(-2.0..0.0)
        )
            .prop_map(|(duration, time_step, interval)| Analysis::Verlet {
                duration,
                time_step,
                interval,
            }),
        1 => (
            decades_or(-2.0..0.5),
            decades_or(-4.0..-1.0),
            decades_or(-2.0..0.0),
            0.0f64..=1.0,
        )
            .prop_map(|(duration, time_step, interval, rho)| Analysis::GenAlpha {
                duration,
                time_step,
                interval,
                rho,
            }),
    ]
}

fn params() -> impl Strategy<Value = Params> {
    (
        (
            prop_oneof![LENGTH_DECADES, -1.3f64..0.7],
            -3.3f64..-2.3,
            8.0f64..11.3,
            900.0f64..8000.0,
        ),
        (1u32..=12, 0.05f64..1.0, 1.0f64..=60.0, 0.0f64..=1.0),
        gravity(),
        prop_oneof![Just("continuous"), Just("paper"), Just("hysteretic")],
        supports(),
        analysis(),
        (1u32..=16, 2u32..=24),
        any::<[bool; 3]>(),
        motion(),
    )
        .prop_map(
            |(
                (len, d, e, density),
                (wires, fit, lay_deg, friction),
                gravity,
                law,
                supports,
                analysis,
                (elements, segments),
                models,
                motion,
            )| Params {
                length: 10f64.powf(len),
                core_d: 10f64.powf(d),
                young: 10f64.powf(e),
                density,
                wires,
                fit,
                lay_deg,
                friction,
                gravity,
                law,
                supports,
                analysis,
                elements,
                segments,
                models,
                motion,
            },
        )
}

fn scene_json(p: &Params) -> Value {
    let layer_d = p.core_d * p.fit * wire_fit(p.wires, p.lay_deg);
    // Natural scales: the time an axial wave takes along the strand (s), gravity (m/s^2) and
    // the strand's weight (N, from the core's density and the wires' cross-sections).
    let time = p.length * (p.density / p.young).sqrt();
    let g = 9.81;
    let area = std::f64::consts::FRAC_PI_4 * (p.core_d.powi(2) + p.wires as f64 * layer_d.powi(2));
    let weight = p.density * area * p.length * g;
    let analysis = match p.analysis {
        Analysis::Static { load_steps } => {
            json!({ "kind": "static", "load_steps": load_steps, "max_steps": MAX_STEPS })
        }
        Analysis::Verlet {
            duration,
            time_step,
            interval,
        } => {
            let mut a = json!({ "kind": "dynamic", "integrator": "verlet",
                                "duration": duration * time, "output_interval": interval * time,
                                "max_steps": MAX_STEPS });
            if let Some(h) = time_step {
                a["time_step"] = json!(h * time);
            }
            a
        }
        Analysis::GenAlpha {
            duration,
            time_step,
            interval,
            rho,
        } => json!({ "kind": "dynamic", "integrator": "generalized-alpha",
                     "duration": duration * time, "time_step": time_step * time,
                     "output_interval": interval * time, "spectral_radius": rho,
                     "max_steps": MAX_STEPS }),
    };
    let mut models = json!({});
    let [eq, tr, fine] = p.models;
    // At least one model: the equivalent when none is drawn.
    if eq || !(tr || fine) {
        models["equivalent"] = json!({ "elements": p.elements });
    }
    if tr {
        models["traditional"] = json!({ "elements": p.elements });
    }
    if fine {
        models["fine"] = json!({ "segments_per_wire": p.segments });
    }
    let wire = |d: f64| {
        json!({ "diameter": d, "youngs_modulus": p.young, "poisson_ratio": 0.3,
                "density": p.density })
    };
    let mut layer = wire(layer_d);
    layer["wires"] = json!(p.wires);
    layer["lay_angle_deg"] = json!(p.lay_deg);
    let m = &p.motion;
    let dynamic = !matches!(p.analysis, Analysis::Static { .. });
    let mut initial = json!({});
    if let Some(d) = m.direction {
        initial["direction"] = json!(d);
    }
    if dynamic {
        if let Some(v) = m.velocity {
            initial["velocity"] = json!(v);
        }
        if let Some(w) = m.angular_velocity {
            initial["angular_velocity"] = json!(w);
        }
    }
    let points: Vec<Value> = m
        .points
        .iter()
        .map(|(s, f)| json!({ "s": s * p.length, "force": f.map(|x| x * weight) }))
        .collect();
    // A moving support in a dynamic run, or in statics without the fine model (which refuses
    // it there by name).
    let duration = analysis["duration"].as_f64().unwrap_or(1.0);
    let moving = m.support.filter(|_| dynamic || !fine);
    let supports: Vec<Value> = p
        .supports
        .iter()
        .enumerate()
        .map(|(i, (at, kind))| {
            let mut s = json!({ "at": at, "kind": kind });
            if let (0, Some((t, d))) = (i, moving) {
                s["motion"] = json!([[
                    t * duration,
                    d[0] * p.length,
                    d[1] * p.length,
                    d[2] * p.length
                ]]);
            }
            s
        })
        .collect();
    json!({
        "name": "random",
        "strand": { "length": p.length, "core": wire(p.core_d), "layers": [layer],
                    "friction": p.friction },
        "law": p.law,
        "initial": initial,
        "supports": supports,
        "loads": { "gravity": p.gravity.map(|x| x * g), "points": points },
        "analysis": analysis,
        "models": models
    })
}

/// Every file below `dir`.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return out;
    };
    for e in entries {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(files(&p));
        } else {
            out.push(p);
        }
    }
    out
}

/// No file below `dir` holds a non-finite number. Rust parses `NaN`, `inf` and `infinity` in
/// any case as floats: a token that parses to a non-finite number is one.
fn clean(dir: &Path) -> Result<(), String> {
    for f in files(dir) {
        let Ok(text) = std::fs::read_to_string(&f) else {
            continue;
        };
        for (i, line) in text.lines().enumerate() {
            let bad = line
                .split(|c: char| c.is_whitespace() || ",:[]{}\"".contains(c))
                .any(|t| t.parse::<f64>().is_ok_and(|x| !x.is_finite()));
            if bad {
                return Err(format!("{} line {}: {line}", f.display(), i + 1));
            }
        }
    }
    Ok(())
}

/// The run's outcome is one a user can act on and its files are clean: the summaries, or a
/// message when not.
fn check_run(scene: &Scene, tag: &str) -> Result<Vec<RunSummary>, String> {
    let out = out_dir(tag);
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: true,
    };
    let (tx, rx) = mpsc::channel();
    let run_scene_ = scene.clone();
    let worker = std::thread::spawn(move || {
        let r = run_scene(&run_scene_, &opts, &mut |_, _| {});
        let _ = tx.send(r);
    });
    let summaries: Vec<RunSummary> = match rx.recv_timeout(hang()) {
        Ok(Ok(s)) => s,
        Ok(Err(e)) => return Err(format!("the runner stopped without summaries: {e}")),
        Err(mpsc::RecvTimeoutError::Timeout) => {
            return Err(format!("no result after {:?}: a hang", hang()));
        }
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            return Err(format!("the run panicked: {:?}", worker.join().err()));
        }
    };
    let _ = worker.join();
    if summaries.is_empty() {
        return Err("no model ran".into());
    }
    for s in &summaries {
        match (s.status.as_str(), s.reason, &s.error) {
            ("ok", None, None) => {}
            ("failed", Some(_), Some(e)) if !e.is_empty() => {}
            _ => {
                return Err(format!(
                    "{}: status {} reason {:?} error {:?}",
                    s.model, s.status, s.reason, s.error
                ));
            }
        }
        if !out.join(&s.model).join("summary.json").exists() {
            return Err(format!("{}: no summary.json", s.model));
        }
    }
    clean(&out)?;
    Ok(summaries)
}

/// Outcomes of the runs of a property test.
#[derive(Debug, Default)]
struct Tally {
    /// Runs that must end `ok`: statics, dynamics.
    must: [usize; 2],
    /// Other runs not refused by the step limit.
    started: usize,
    /// Of these, the ones that ended `ok`.
    ok: usize,
    /// Scenes the validation refused.
    refused: usize,
    /// Why runs were not required to end `ok`.
    why_not: std::collections::BTreeMap<&'static str, usize>,
    /// Runs the step limit refused.
    limited: usize,
}

/// Runs `v` (a scene) and checks every model's outcome, counting it in `tally`; the scene is
/// written to `current` first, for a run stopped from outside (e.g. one that takes too long).
fn check_scene(v: &Value, current: &Path, tally: &RefCell<Tally>) -> Result<(), TestCaseError> {
    let _ = std::fs::write(current, v.to_string());
    let scene = match Scene::parse(&v.to_string()) {
        Ok(s) => s,
        // A scene the validation refuses (e.g. a pitch rule past its cap) names the field.
        Err(e) => {
            prop_assert!(!e.path.is_empty() && !e.message.is_empty(), "{e}");
            tally.borrow_mut().refused += 1;
            return Ok(());
        }
    };
    let summaries =
        check_run(&scene, "random").map_err(|e| TestCaseError::fail(format!("{e}\nscene: {v}")))?;
    let mut tally = tally.borrow_mut();
    for s in &summaries {
        let must = must_solve(&scene, &s.model);
        if let Err(why_not) = &must {
            *tally.why_not.entry(why_not).or_default() += 1;
        }
        if let Ok(why) = must {
            prop_assert!(
                s.status == "ok",
                "{}: {:?} {:?}, but it must solve ({why})\nscene: {v}",
                s.model,
                s.reason,
                s.error
            );
            tally.must[usize::from(why.starts_with("dynamics"))] += 1;
        } else if s.reason == Some(Failure::StepLimit) {
            tally.limited += 1;
        } else {
            tally.started += 1;
            tally.ok += usize::from(s.status == "ok");
        }
    }
    Ok(())
}

/// Share of the runs outside [`must_solve`] that start (not refused by the step limit) and
/// must end `ok`, at least. These include runs that may fail for cause (a given Verlet step
/// above the stable one, loads that fold the strand, mechanisms, the fine model's contacts);
/// 269 of 314 ended `ok` in 400 cases (0.857, `STRAND_PROP_CASES=400`). The default 192 cases
/// give about 150 such runs, whose share spreads by sqrt(0.857 x 0.143 / 150) = 0.029
/// (binomial), the measured rate itself by 0.020: the floor is 0.857 less four times their
/// combined 0.035, rounded down, which the code as it is misses with a chance of about 3e-5,
/// and a model that always fails (share 0) cannot pass.
const OK_SHARE: f64 = 0.7;

/// Random valid scenes run to an outcome with clean files; those that must solve end `ok`, and
/// at least [`OK_SHARE`] of the others that start.
#[test]
fn random_scenes_end_ok_or_failed_with_a_reason() {
    // 192 cases by default; STRAND_PROP_CASES=N explores more, STRAND_PROP_SHRINK=N shrinks a
    // failure N times at most (each a run: 0 to report a hang without waiting for more).
    let env = |name: &str, default: u32| {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let cases = env("STRAND_PROP_CASES", 192);
    let config = Config {
        cases,
        max_shrink_iters: env("STRAND_PROP_SHRINK", 64),
        source_file: Some(file!()),
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..Config::default()
    };
    let tally = RefCell::new(Tally::default());
    let current = TempPath::new("strand-prop-current");
    let result = TestRunner::new(config).run(&params(), |p| {
        check_scene(&scene_json(&p), &current, &tally)
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    let t = tally.into_inner();
    let share = t.ok as f64 / t.started.max(1) as f64;
    println!(
        "{:?} runs (statics, dynamics) that must solve, all ok; {} of {} other runs that started ended ok ({share:.3}); \
         {} refused by the step limit; {} scenes refused by the validation",
        t.must, t.ok, t.started, t.limited, t.refused
    );
    println!("not required to solve: {:?}", t.why_not);
    assert!(
        share >= OK_SHARE,
        "{} of {} runs ended ok: below {OK_SHARE}",
        t.ok,
        t.started
    );
}

/// The regression scenes of `tests/scenes/`, each run with the outcome its entry in
/// `expected.json` names for every model (`ok`, or the failure reason).
#[test]
fn regression_scenes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
    let expected: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let expected = expected.as_object().unwrap();
    let mut n = 0;
    for f in files(&dir) {
        let tag = f.file_stem().unwrap().to_string_lossy().to_string();
        if f.extension().is_none_or(|x| x != "json") || tag == "expected" {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        let scene = Scene::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let want = expected
            .get(&tag)
            .unwrap_or_else(|| panic!("{tag}: no entry in expected.json"))
            .as_object()
            .unwrap();
        let summaries = check_run(&scene, &tag).unwrap_or_else(|e| panic!("{tag}: {e}"));
        assert_eq!(summaries.len(), want.len(), "{tag}: models");
        for s in &summaries {
            let outcome = s.reason.map_or("ok", Failure::name);
            assert_eq!(
                Some(outcome),
                want[&s.model].as_str(),
                "{tag} {}: {:?}",
                s.model,
                s.error
            );
        }
        n += 1;
    }
    assert_eq!(
        n,
        expected.len(),
        "every entry of expected.json has its scene"
    );
}

/// The file check finds non-finite numbers in CSV, JSON and VTK text, and not words.
#[test]
fn the_file_check_finds_non_finite_numbers() {
    let dir = out_dir("check");
    std::fs::create_dir_all(dir.join("m")).unwrap();
    let f = dir.join("m/centerline.csv");
    std::fs::write(&f, "s,x\n0,1e-3\n").unwrap();
    std::fs::write(
        dir.join("m/summary.json"),
        r#"{"note": "information: infinite"}"#,
    )
    .unwrap();
    assert!(clean(&dir).is_ok());
    for bad in ["0.5,NaN", "0.5,inf", "0.5,-inf", "0.5 Infinity 1"] {
        std::fs::write(&f, format!("s,x\n{bad}\n")).unwrap();
        assert!(clean(&dir).is_err(), "{bad}");
    }
    std::fs::write(&f, "s,x\n0,1\n").unwrap();
    std::fs::write(dir.join("m/summary.json"), r#"{"tip": [NaN, 0]}"#).unwrap();
    assert!(clean(&dir).is_err());
}
