//! Solve time of the paper's section-3 pendulum (scene `validation/paper-fig14-pendulum.json`:
//! L = 1 m, E = 2e9 Pa, rho = 5747 kg/m^3, 30 planar elements, pinned at x = 0, gravity 9.8
//! m/s^2, 1 s) for each integrator and law, with the tip error against a converged run
//! (generalized-alpha at 1e-4 s, no numerical damping).
//!
//! ```text
//! cargo run --release -p strand-ancf --example pendulum_speed [-- LAW...]
//! ```
//!
//! LAW is `constant`, `continuous` or `hysteretic` (default: constant and hysteretic). Only
//! the solve is timed (`run_dynamic`, after the beam is built); each configuration runs
//! `REPEAT` times and the fastest is reported, with the median (timings on a shared machine vary
//! by up to a factor of two from minute to minute: compare builds in interleaved runs).

use std::time::Instant;

use strand_ancf::beam::{Beam, BeamSpec, ElementKind, Support};
use strand_ancf::dynamics::{DynamicOptions, DynamicSummary, Scheme, run_dynamic};
use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

const REPEAT: usize = 3;
const DURATION: f64 = 1.0;
/// Spectral radius of the scenes' default generalized-alpha.
const RHO: f64 = 0.9;
/// Newton tolerance of the reference run (times the strand length).
const REFERENCE_INCREMENT: f64 = 1e-12;

/// The pendulum with `points` Gauss points per element for bending (`None`: the pitch rule).
fn beam(kind: LawKind, points: Option<usize>) -> Beam {
    let s = Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap();
    Beam::new(
        BeamSpec {
            elements: 30,
            bending_points: points,
            mass_per_length: s.mass_per_length(),
            element: ElementKind::Planar,
            direction: [1.0, 0.0, 0.0],
            gravity: [0.0, -9.8, 0.0],
            start: Some(Support::Pinned),
            end: None,
            ..Default::default()
        },
        SectionLaw::new(&s, kind),
    )
    .unwrap()
}

fn tip(beam: &Beam, q: &[f64]) -> [f64; 2] {
    let (p, _) = beam.sample(q, beam.length());
    [p[0], p[1]]
}

/// Fastest of `repeat` runs: (summary, seconds, largest tip distance to `reference` over the
/// output frames every 10 ms that fall on the same times, always including the end, t = 1 s).
fn timed(
    beam: &Beam,
    scheme: Scheme,
    repeat: usize,
    reference: Option<&[[f64; 2]]>,
    increment: Option<f64>,
) -> (DynamicSummary, Timing, f64, Vec<[f64; 2]>) {
    let mut times = Vec::with_capacity(repeat);
    let mut out = None;
    for _ in 0..repeat {
        let mut opts = DynamicOptions::new(DURATION, scheme, 0.01);
        if let Ok(v) = std::env::var("PENDULUM_REFRESH") {
            opts.refresh = v.parse().expect("PENDULUM_REFRESH is a number");
        }
        if let Ok(v) = std::env::var("PENDULUM_REBUILD") {
            opts.rebuild_rate = v.parse().expect("PENDULUM_REBUILD is a number");
        }
        if let Ok(v) = std::env::var("PENDULUM_INCREMENT") {
            opts.increment = v.parse().expect("PENDULUM_INCREMENT is a number");
        }
        if let Ok(v) = std::env::var("PENDULUM_UNLOADING") {
            opts.unloading = v.parse().expect("PENDULUM_UNLOADING is a number");
        }
        if let Ok(v) = std::env::var("PENDULUM_LEDGER") {
            opts.ledger = v.parse().expect("PENDULUM_LEDGER is a number");
        }
        if let Some(v) = increment {
            opts.increment = v;
        }
        let mut tips = Vec::new();
        let start = Instant::now();
        let s = run_dynamic(beam, &opts, &mut |f| {
            // Frames off the 10 ms grid (a step that does not divide it) are marked NaN.
            let on_grid = ((f.t / 0.01).round() * 0.01 - f.t).abs() < 1e-9;
            tips.push(if on_grid {
                tip(beam, f.q)
            } else {
                [f64::NAN; 2]
            });
        })
        .unwrap();
        times.push(start.elapsed().as_secs_f64());
        out = Some((s, tips));
    }
    let (s, tips) = out.unwrap();
    let err = reference.map_or(0.0, |r| {
        r.iter()
            .zip(&tips)
            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
            .filter(|d| d.is_finite())
            .fold(0.0, f64::max)
            .max({
                let (a, b) = (r.last().unwrap(), tips.last().unwrap());
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
    });
    times.sort_by(f64::total_cmp);
    let n = times.len();
    let timing = Timing {
        fastest: times[0],
        median: 0.5 * (times[(n - 1) / 2] + times[n / 2]),
        runs: n,
    };
    (s, timing, err, tips)
}

/// Solve times of repeated runs (s): on a shared machine the fastest is the most repeatable,
/// the median shows the spread.
struct Timing {
    fastest: f64,
    median: f64,
    runs: usize,
}

fn report(name: &str, s: &DynamicSummary, t: &Timing, err: f64) {
    println!(
        "{name:<34} {:>9.2} ms {:>6} steps {:>7} iter {:>6} fact  RTF {:>7.1}  tip err {:.2e} m  \
         balance {:.1e} J  median {:.2} ms of {}",
        1e3 * t.fastest,
        s.steps,
        s.newton_iterations,
        s.factorizations,
        DURATION / t.fastest,
        err,
        s.balance_error,
        1e3 * t.median,
        t.runs
    );
}

fn main() {
    let laws: Vec<String> = std::env::args().skip(1).collect();
    let laws = if laws.is_empty() {
        vec!["constant".to_string(), "hysteretic".to_string()]
    } else {
        laws
    };
    for law in laws {
        let kind = match law.as_str() {
            "constant" => LawKind::Constant,
            "continuous" => LawKind::Continuous,
            "hysteretic" => LawKind::Hysteretic,
            other => panic!("unknown law {other}"),
        };
        // PENDULUM_POINTS=N: N Gauss points per element for bending instead of the pitch rule.
        let points = std::env::var("PENDULUM_POINTS")
            .ok()
            .map(|v| v.parse().expect("PENDULUM_POINTS is a count"));
        let b = beam(kind, points);
        println!(
            "law {law}: {} dofs, {} bending points",
            b.dofs(),
            b.points()
        );
        let alpha = |step: f64, rho: f64| Scheme::GeneralizedAlpha {
            step,
            spectral_radius: rho,
        };
        // PENDULUM_ONLY=STEP: one generalized-alpha run of that step, untimed against a
        // reference (for profiling).
        // PENDULUM_REPEAT=N: best of N runs there; PENDULUM_TIPS=FILE: the tip every 10 ms
        // and the final coordinates written to FILE (to compare trajectories between builds).
        if let Ok(only) = std::env::var("PENDULUM_ONLY") {
            let step: f64 = only.parse().expect("PENDULUM_ONLY is a step in seconds");
            let repeat = std::env::var("PENDULUM_REPEAT")
                .map_or(1, |v| v.parse().expect("PENDULUM_REPEAT is a count"));
            let (s, t, e, tips) = timed(&b, alpha(step, RHO), repeat, None, None);
            report(&format!("gen-alpha {step:.1e} s rho {RHO}"), &s, &t, e);
            if let Ok(path) = std::env::var("PENDULUM_TIPS") {
                let mut out = String::new();
                for p in &tips {
                    out += &format!("tip {:e} {:e}\n", p[0], p[1]);
                }
                for v in &s.q {
                    out += &format!("q {v:e}\n");
                }
                std::fs::write(format!("{path}.{law}"), out).expect("PENDULUM_TIPS is writable");
            }
            continue;
        }
        // The reference always uses the default quadrature, and Newton converged far below
        // the default tolerance (whose error could add up over its 10,000 steps).
        let reference_beam = beam(kind, None);
        let (rs, rt, _, reference) = timed(
            &reference_beam,
            alpha(1e-4, 1.0),
            1,
            None,
            Some(REFERENCE_INCREMENT),
        );
        report("gen-alpha 1e-4 s rho 1 (reference)", &rs, &rt, 0.0);
        if kind == LawKind::Continuous {
            // Its tension-dependent moment is not a potential: its work can put energy in
            // (README, "Finding"; since the law reads the recovered tension the flutter of the
            // 2 kHz axial-bending mode is gone, but the work is not zero).
            println!(
                "note: the continuous law's non-potential work is not zero (balance below); the \
                 reference is the same law at 0.1 ms"
            );
        }
        let r = Some(reference.as_slice());
        let (s, t, e, _) = timed(&b, Scheme::Verlet { step: None }, 1, r, None);
        report(&format!("verlet {:.2e} s", s.time_step), &s, &t, e);
        // Steps that divide the 10 ms output interval, so that frames fall on the same times.
        for step in [1e-3, 2e-3, 2.5e-3, 5e-3, 1e-2] {
            let (s, t, e, _) = timed(&b, alpha(step, RHO), REPEAT, r, None);
            report(&format!("gen-alpha {step:.1e} s rho {RHO}"), &s, &t, e);
        }
    }
}
