//! One timed generalized-alpha run of a dynamic scene's beam, printed as JSON: the strand side
//! of the side-by-side benchmarks (`cargo xtask bench-peers`, `benchmarks/exudyn/`).
//!
//! ```text
//! cargo run --release -p strand-scene --example peer_pendulum -- SCENE.json --law LAW
//!     --step H [--spectral-radius R] [--increment TOL] [--elements N] [--bending-points N]
//! ```
//!
//! LAW is `constant` (the scene's traditional beam: the envelope cylinder's EI and EA) or a
//! law of the equivalent beam (`continuous`, `hysteretic`, `paper`). The scene gives the strand,
//! supports, gravity, duration and output interval; its integrator is replaced by
//! generalized-alpha at step H (spectral radius R, default 0.9) with Newton converged to TOL
//! times the strand length (default: the solver's, 1e-8). `setup_s` is the beam's construction,
//! `solve_s` the integration (`run_dynamic`, which includes the integrator's own start: initial
//! accelerations, the first iteration matrix); both by the monotonic clock. `tip` holds
//! `[t, x, y]` (s, m) at every output time.

use std::path::PathBuf;
use std::time::Instant;

use strand_ancf::dynamics::{DynamicOptions, Scheme, run_dynamic};
use strand_core::LawKind;
use strand_scene::{Analysis, BeamModelKind, Scene, build_beam};

struct Args {
    scene: PathBuf,
    law: String,
    step: f64,
    spectral_radius: f64,
    increment: Option<f64>,
    elements: Option<usize>,
    bending_points: Option<usize>,
}

fn parse() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let mut scene = None;
    let (mut law, mut step, mut rho) = (None, None, 0.9);
    let (mut increment, mut elements, mut points) = (None, None, None);
    let number = |flag: &str, v: Option<String>| -> Result<f64, String> {
        v.ok_or(format!("{flag} needs a value"))?
            .parse::<f64>()
            .map_err(|e| format!("{flag}: {e}"))
            .and_then(|x| {
                if x.is_finite() && x > 0.0 {
                    Ok(x)
                } else {
                    Err(format!("{flag}: must be positive and finite"))
                }
            })
    };
    let count = |flag: &str, v: Option<String>| -> Result<usize, String> {
        v.ok_or(format!("{flag} needs a value"))?
            .parse::<usize>()
            .map_err(|e| format!("{flag}: {e} (a whole number of at least 1)"))
            .and_then(|n| {
                if n >= 1 {
                    Ok(n)
                } else {
                    Err(format!("{flag}: must be at least 1"))
                }
            })
    };
    while let Some(a) = it.next() {
        match a.as_str() {
            "--law" => law = it.next(),
            "--step" => step = Some(number("--step", it.next())?),
            "--spectral-radius" => rho = number("--spectral-radius", it.next())?,
            "--increment" => increment = Some(number("--increment", it.next())?),
            "--elements" => elements = Some(count("--elements", it.next())?),
            "--bending-points" => points = Some(count("--bending-points", it.next())?),
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s => scene = Some(PathBuf::from(s)),
        }
    }
    Ok(Args {
        scene: scene.ok_or("usage: peer_pendulum SCENE.json --law LAW --step H")?,
        law: law.ok_or("--law is required")?,
        step: step.ok_or("--step is required")?,
        spectral_radius: rho,
        increment,
        elements,
        bending_points: points,
    })
}

fn main() {
    if let Err(e) = run() {
        eprintln!("peer_pendulum: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let args = parse()?;
    let mut scene = Scene::load(&args.scene).map_err(|e| e.to_string())?;
    let Analysis::Dynamic(dynamic) = scene.analysis else {
        return Err("the scene is not dynamic".into());
    };
    let which = match args.law.as_str() {
        "constant" => BeamModelKind::Traditional,
        "continuous" | "hysteretic" | "paper" => {
            scene.law = match args.law.as_str() {
                "continuous" => LawKind::Continuous,
                "hysteretic" => LawKind::Hysteretic,
                _ => LawKind::Paper,
            };
            BeamModelKind::Equivalent
        }
        other => return Err(format!("unknown law `{other}`")),
    };
    let model = match which {
        BeamModelKind::Traditional => scene.models.traditional.as_mut(),
        BeamModelKind::Equivalent => scene.models.equivalent.as_mut(),
    }
    .ok_or(format!("the scene has no models.{}", which.name()))?;
    if let Some(n) = args.elements {
        model.elements = n;
    }
    let elements = model.elements;
    if args.bending_points.is_some() {
        model.integration_points = args.bending_points;
    }

    let start = Instant::now();
    let beam = build_beam(&scene, which).map_err(|e| e.to_string())?;
    let setup = start.elapsed().as_secs_f64();

    let scheme = Scheme::GeneralizedAlpha {
        step: args.step,
        spectral_radius: args.spectral_radius,
    };
    let mut opts = DynamicOptions::new(dynamic.duration, scheme, dynamic.output_interval);
    if let Some(tol) = args.increment {
        opts.increment = tol;
    }
    let mut tip = Vec::new();
    let start = Instant::now();
    let summary = run_dynamic(&beam, &opts, &mut |f| {
        let (p, _) = beam.sample(f.q, beam.length());
        tip.push([f.t, p[0], p[1]]);
    })
    .map_err(|e| e.to_string())?;
    let solve = start.elapsed().as_secs_f64();

    let out = serde_json::json!({
        "program": "strand",
        "version": env!("CARGO_PKG_VERSION"),
        "law": args.law,
        "elements": elements,
        "bending_points_per_element": beam.bending_points(),
        "dofs": beam.dofs(),
        "step": args.step,
        "spectral_radius": args.spectral_radius,
        "newton_increment": opts.increment,
        "modified_newton": true,
        "step_halving": true,
        "steps": summary.steps,
        "newton_iterations": summary.newton_iterations,
        "jacobians": summary.factorizations,
        "balance_error": summary.balance_error,
        "max_kinetic": summary.max_kinetic,
        "setup_s": setup,
        "solve_s": solve,
        "tip": tip,
    });
    println!("{out}");
    Ok(())
}
