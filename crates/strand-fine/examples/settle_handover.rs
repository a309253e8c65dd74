//! The Fig. 7 fine statics (Table 1 strand, 0.4 m, clamped, gravity G m/s^2 along -y, 77
//! segments a wire) with the damped motion handed over to a pseudo-transient continuation
//! when the residual falls to HANDOVER times the settle's allowance, first pseudo step H0
//! (s): `cargo run --release -p strand-fine --example settle_handover -- G HANDOVER [H0]`;
//! HANDOVER 0: the default settle (no continuation). With `FRICTION=0` the contacts are
//! frictionless; `LENGTH` (m) and `SEGMENTS` (a wire) change the strand; `PTC_STEPS` (60),
//! `GROWTH` (4), `COMMIT=1` and `ELASTIC=1` set the continuation's options. Prints the explicit steps, the continuation's steps, the Newton polish, the
//! tip and the CPU time of the process.

mod common;

use strand_fine::pseudo_transient::PseudoTransientOptions;
use strand_fine::{SettledOptions, solve_settled};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().unwrap());
    let (g, handover) = (arg(1, 8.0), arg(2, 100.0));
    // `LENGTH` (m) and `SEGMENTS` (a wire) change the strand (default 0.4 m, 77).
    let env = |k: &str, d: f64| std::env::var(k).map_or(d, |v| v.parse().unwrap());
    let segments = env("SEGMENTS", 77.0) as usize;
    let m = common::fig7_model_from_env(g, segments);
    let mut opts = SettledOptions::default();
    if handover > 0.0 {
        opts.pseudo_transient = Some(PseudoTransientOptions {
            handover,
            initial_step: args.get(3).map(|s| s.parse().unwrap()),
            commit: std::env::var("COMMIT").is_ok_and(|v| v == "1"),
            elastic_friction: std::env::var("ELASTIC").is_ok_and(|v| v == "1"),
            growth: std::env::var("GROWTH").map_or(4.0, |v| v.parse().unwrap()),
            max_steps: env("PTC_STEPS", 60.0) as usize,
        });
    }
    let mut state = m.rest_state();
    let r = solve_settled(&m, &mut state, &opts, &mut |_, _, _| {}).unwrap();
    let tip = *m.core_centreline(&state).last().unwrap();
    println!(
        "g {g} handover {handover}: {} steps of {:.4e} s, {:.3} s; continuation {:?}; Newton {} \
         it in {} attempts, residual {:.2e}, tip ({:.10}, {:.10}, {:.10}) [{:.1} s CPU]",
        r.settle.steps,
        r.settle.time_step,
        r.settle.time,
        r.pseudo_transient,
        r.iterations,
        r.attempts,
        r.residual,
        tip.x,
        tip.y,
        tip.z,
        common::cpu_seconds()
    );
}
