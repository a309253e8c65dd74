//! Random valid scenes through the whole runner: strands of 1 to 12 wires at lay angles of 1 to
//! 60 deg, friction 0 to 1, gravity of any direction from 0 to 1e3 m/s^2, every support, law,
//! analysis and integrator, all three models, the 3D fields (initial direction, velocity and
//! angular velocity, point forces, a moving support), short runs. Each model's run ends `ok`, or
//! `failed` with a named reason and a message; it ends (a run that does not finish within a
//! generous bound is a hang); no file it writes holds `NaN` or `inf`; nothing panics.
//! Scenes this test found failing are kept in `tests/scenes/` and run as regressions.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use proptest::prelude::*;
use serde_json::{Value, json};
use strand_scene::{RunOptions, RunSummary, Scene, run_scene};

/// A run that takes longer than this is taken for a hang. The largest scene here (12 wires,
/// 16 elements, 24 fine segments per wire, a 2000-step limit) runs in about a second; the bound
/// only has to tell a finished run from one that never ends on a loaded machine.
const HANG: Duration = Duration::from_secs(300);

/// Step limit of every generated scene, so that a run is short whatever the stable step.
const MAX_STEPS: u64 = 2000;

fn out_dir(tag: &str) -> PathBuf {
    let out = std::env::temp_dir().join(format!("strand-prop-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    out
}

/// Largest wire diameter (relative to the core's) at which `wires` wires at `lay_deg` fit
/// around the core without touching: adjacent wires' centres are `2 pi R / m` apart along the
/// circle, `2 R sin(pi / m)` in a cross-section, and a wire's cross-section across the lay is
/// its diameter over cos(alpha). For one wire, its own next turn (a pitch away) is the
/// neighbour, which the 2-wire bound covers with margin.
fn wire_fit(wires: u32, lay_deg: f64) -> f64 {
    let c = lay_deg.to_radians().cos();
    let s = if wires <= 2 {
        1.0
    } else {
        (std::f64::consts::PI / wires as f64).sin()
    };
    // (D/2 + d/2) s >= (d/2) / c  <=>  d/D <= s c / (1 - s c)
    let sc = (s * c).min(0.95);
    sc / (1.0 - sc)
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
/// point forces (as fractions of the length) and a support motion (one row `[t, dx, dy, dz]`
/// with t as a fraction of the duration and dx.. as fractions of the length).
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
        proptest::option::of(scaled(-3.0, 1.0)),
        proptest::option::of(scaled(-2.0, 2.0)),
        proptest::collection::vec((0.0f64..=1.0, scaled(-3.0, 2.0)), 0..3),
        proptest::option::of((0.1f64..=2.0, scaled(-4.0, -1.0))),
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

#[derive(Debug, Clone)]
enum Analysis {
    Static {
        load_steps: u32,
    },
    Verlet {
        steps: u32,
        time_step: Option<f64>,
    },
    GenAlpha {
        steps: u32,
        time_step: f64,
        rho: f64,
    },
}

fn unit_vector() -> impl Strategy<Value = [f64; 3]> {
    (-1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    })
}

fn gravity() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        1 => Just([0.0, 0.0, 0.0]),
        1 => unit_vector().prop_map(|u| u.map(|x| 1e3 * x)),
        6 => (unit_vector(), -3.0f64..3.0).prop_map(|(u, e)| u.map(|x| x * 10f64.powf(e))),
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
        (1u32..8).prop_map(|load_steps| Analysis::Static { load_steps }),
        (
            1u32..20,
            prop_oneof![
                Just(None),
                (-6.0f64..-3.0).prop_map(|e| Some(10f64.powf(e)))
            ]
        )
            .prop_map(|(steps, time_step)| Analysis::Verlet { steps, time_step }),
        (1u32..20, -5.0f64..-2.0, 0.0f64..=1.0).prop_map(|(steps, e, rho)| {
            Analysis::GenAlpha {
                steps,
                time_step: 10f64.powf(e),
                rho,
            }
        }),
    ]
}

fn params() -> impl Strategy<Value = Params> {
    (
        (-1.3f64..0.7, -3.3f64..-2.3, 8.0f64..11.3, 900.0f64..8000.0),
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
    let analysis = match p.analysis {
        Analysis::Static { load_steps } => {
            json!({ "kind": "static", "load_steps": load_steps, "max_steps": MAX_STEPS })
        }
        Analysis::Verlet { steps, time_step } => {
            // Without a step Verlet runs at its stable step: the duration is a few of a
            // millisecond step, and the step limit stops what needs more.
            let h = time_step.unwrap_or(1e-3);
            let mut a = json!({ "kind": "dynamic", "integrator": "verlet",
                                "duration": steps as f64 * h, "output_interval": 2.0 * h,
                                "max_steps": MAX_STEPS });
            if let Some(h) = time_step {
                a["time_step"] = json!(h);
            }
            a
        }
        Analysis::GenAlpha {
            steps,
            time_step,
            rho,
        } => json!({ "kind": "dynamic", "integrator": "generalized-alpha",
                     "duration": steps as f64 * time_step, "time_step": time_step,
                     "output_interval": 3.0 * time_step, "spectral_radius": rho,
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
        .map(|(s, f)| json!({ "s": s * p.length, "force": f }))
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
        "loads": { "gravity": p.gravity, "points": points },
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

/// The run's outcome is one a user can act on and its files are clean; a message when not.
fn check_run(scene: &Scene, tag: &str) -> Result<(), String> {
    let out = out_dir(tag);
    let opts = RunOptions {
        out: out.clone(),
        vtk: true,
    };
    let (tx, rx) = mpsc::channel();
    let run_scene_ = scene.clone();
    let worker = std::thread::spawn(move || {
        let r = run_scene(&run_scene_, &opts, &mut |_, _| {});
        let _ = tx.send(r);
    });
    let summaries: Vec<RunSummary> = match rx.recv_timeout(HANG) {
        Ok(Ok(s)) => s,
        Ok(Err(e)) => return Err(format!("the runner stopped without summaries: {e}")),
        Err(mpsc::RecvTimeoutError::Timeout) => {
            return Err(format!("no result after {HANG:?}: a hang"));
        }
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            return Err(format!("the run panicked: {:?}", worker.join().err()));
        }
    };
    let _ = worker.join();
    for s in &summaries {
        eprintln!("{tag} {}: {} {:?}", s.model, s.status, s.reason);
    }
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
    let _ = std::fs::remove_dir_all(&out);
    Ok(())
}

proptest! {
    // 48 cases by default (about 20 s); STRAND_PROP_CASES=N explores more.
    #![proptest_config(ProptestConfig {
        cases: std::env::var("STRAND_PROP_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(48),
        max_shrink_iters: 64,
        ..ProptestConfig::default()
    })]

    /// Random valid scenes run to an outcome with clean files.
    #[test]
    fn random_scenes_end_ok_or_failed_with_a_reason(p in params()) {
        let v = scene_json(&p);
        // The scene being run, for a run stopped from outside (e.g. one that takes too long).
        let _ = std::fs::write(
            std::env::temp_dir().join(format!("strand-prop-current-{}.json", std::process::id())),
            v.to_string(),
        );
        let scene = match Scene::parse(&v.to_string()) {
            Ok(s) => s,
            // A scene the validation refuses (e.g. a pitch rule past its cap) names the field.
            Err(e) => {
                prop_assert!(!e.path.is_empty() && !e.message.is_empty(), "{e}");
                return Ok(());
            }
        };
        if let Err(e) = check_run(&scene, "random") {
            return Err(TestCaseError::fail(format!("{e}\nscene: {v}")));
        }
    }
}

/// The scenes the property test found failing, each run again.
#[test]
fn regression_scenes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
    let mut n = 0;
    for f in files(&dir) {
        if f.extension().is_none_or(|x| x != "json") {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        let scene = Scene::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let tag = f.file_stem().unwrap().to_string_lossy().to_string();
        if let Err(e) = check_run(&scene, &tag) {
            panic!("{}: {e}", f.display());
        }
        n += 1;
    }
    assert!(n > 0 || !dir.exists());
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
    let _ = std::fs::remove_dir_all(dir);
}
