//! The Fig. 7 fine statics (Table 1 strand, 0.4 m, clamped, gravity G m/s^2 along -y, 77
//! segments a wire, the settle's default motion and polish) with the settle's damping rate
//! FACTOR times its default and the gravity ramp kept at its default length:
//! `cargo run --release -p strand-fine --example settle_damping -- G FACTOR`.
//! Prints the steps, the Newton polish, the tip and the CPU time of the process. The
//! mass-proportional damping makes every mode above gamma / 2 decay as exp(-gamma t / 2),
//! whatever its frequency, and the residual is the stiff modes' (settle module docs): the
//! study measures how much of the settle's length that sets, and how far a faster path lands
//! from the default one with friction.

mod common;

use strand_fine::{SettledOptions, damping_and_ramp, solve_settled};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().unwrap());
    let (g, factor) = (arg(1, 8.0), arg(2, 1.0));
    // Optional: the damping rate from the ramp's end on, as a factor on the default rate.
    let rest_factor = args.get(3).map(|s| s.parse::<f64>().unwrap());
    let m = common::fig7_model(g, 77);
    let mut opts = SettledOptions::default();
    let (gamma, ramp) = damping_and_ramp(&m, &opts.settle);
    opts.settle.damping_rate = Some(factor * gamma);
    opts.settle.ramp_time = Some(ramp);
    opts.settle.rest_damping_rate = rest_factor.map(|f| f * gamma);
    let mut state = m.rest_state();
    let r = solve_settled(&m, &mut state, &opts, &mut |_, _, _| {}).unwrap();
    let tip = *m.core_centreline(&state).last().unwrap();
    println!(
        "g {g} gamma {:.4} 1/s ({factor} x {gamma:.4}; after the ramp {rest_factor:?} x), ramp \
         {ramp:.4} s: {}, tip ({:.10}, {:.10}, {:.10}) [{:.1} s CPU]",
        factor * gamma,
        common::settled_line(&r),
        tip.x,
        tip.y,
        tip.z,
        common::cpu_seconds()
    );
}
