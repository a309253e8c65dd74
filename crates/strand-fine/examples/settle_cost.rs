//! The cost of the settle's steps on the Fig. 7 strand (Table 1 strand, 0.4 m, clamped,
//! gravity G m/s^2 along -y, 77 segments a wire, the settle's default motion): the first
//! STEPS steps of [`strand_fine::settle`], for instruction counts per step under callgrind,
//! where the CLI's CPU clock does not run:
//! `valgrind --tool=callgrind target/release/examples/settle_cost G STEPS`
//! (`RAYON_NUM_THREADS` sets the threads). Prints the steps, the step and a fingerprint of
//! the state (the sum of the positions' bits, equal for equal states).

mod common;

use strand_fine::{SettleOptions, settle};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().unwrap());
    let (g, steps) = (arg(1, 8.0), arg(2, 2000.0) as u64);
    let m = common::fig7_model(g, 77);
    let mut state = m.rest_state();
    let opts = SettleOptions {
        max_steps: Some(steps),
        ..SettleOptions::default()
    };
    let r = settle(&m, &mut state, &opts, &mut |_, _, _| {});
    let fingerprint = state
        .wires
        .iter()
        .flat_map(|w| w.poses.iter())
        .map(|p| {
            p.position
                .iter()
                .map(|x| x.to_bits())
                .fold(0u64, u64::wrapping_add)
        })
        .fold(0u64, u64::wrapping_add);
    println!(
        "g {g}: {steps} steps on {} thread(s): {}; fingerprint {fingerprint:016x}",
        rayon::current_num_threads(),
        match r {
            Ok(r) => format!("settled in {} steps", r.steps),
            Err(e) => e.to_string(),
        }
    );
}
