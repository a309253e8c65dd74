//! Study of the quasi-static load continuation ([`strand_fine::load_continuation`]): the Fig. 7
//! fine statics (Table 1 strand, 0.4 m, clamped, gravity G m/s^2 along -y, 77 segments a wire)
//! by Newton load stepping from the straight strand, STEPS load steps at most of the load,
//! STAGES penalty stages: `cargo run --release -p strand-fine --example load_continuation -- G
//! STEPS STAGES`. `FRICTION=0`: frictionless contacts; `LENGTH` (m) and `SEGMENTS` (a wire)
//! another strand; `MAXIT` Newton iterations a load step (40), `MININC` the smallest load
//! increment (1e-4), `POT=0` residual descent only in the line search. Prints the load factor
//! after every converged step with the CPU time of the process, then the report (or the
//! failure) and the tip at the last converged step.

mod common;

use strand_fine::{StaticOptions, solve_static_with_progress};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().unwrap());
    let env = |k: &str, d: f64| std::env::var(k).map_or(d, |v| v.parse().unwrap());
    let (g, steps, stages) = (arg(1, 8.0), arg(2, 20.0) as usize, arg(3, 0.0) as usize);
    let m = common::fig7_model_from_env(g, env("SEGMENTS", 77.0) as usize);
    let opts = StaticOptions {
        load_steps: steps,
        penalty_stages: stages,
        potential_descent: std::env::var("POT").map_or(true, |v| v == "1"),
        max_iterations: env("MAXIT", 40.0) as usize,
        min_increment: env("MININC", 1e-4),
        ..StaticOptions::default()
    };
    let mut state = m.rest_state();
    let r = solve_static_with_progress(&m, &mut state, &opts, &mut |l| {
        eprintln!("  lambda {l:.5} [{:.1} s CPU]", common::cpu_seconds())
    });
    let tip = *m.core_centreline(&state).last().unwrap();
    println!(
        "g {g} steps {steps} stages {stages}: {r:?}; tip ({:.10}, {:.10}, {:.10}) [{:.1} s CPU]",
        tip.x,
        tip.y,
        tip.z,
        common::cpu_seconds()
    );
}
