//! The free-vibration decay of a run's probe, beside the energy ledger, for each model folder
//! of a results directory:
//!
//! ```text
//! cargo run --release -p strand-scene --example span_decay -- RESULTS PROBE_S FROM
//! ```
//!
//! `RESULTS` is `strand run --out` (its `equivalent/`, `traditional/` folders), `PROBE_S` the
//! probe's material coordinate as in `probe_<s>.csv`, `FROM` the time (s) from which cycles
//! are counted (after the pretensioning ramp). Prints per model: the cycles of the probe's y
//! (mean-crossing to mean-crossing), their amplitudes, the logarithmic decrement per cycle,
//! and per cycle the loss of mechanical energy and the slip work booked by the ledger.

use std::collections::HashMap;
use std::path::Path;

use strand_scene::decay::decay;

fn columns(path: &Path) -> HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let names: Vec<String> = lines
        .next()
        .expect("header")
        .split(',')
        .map(str::to_string)
        .collect();
    let mut cols: HashMap<String, Vec<f64>> = names.iter().map(|n| (n.clone(), vec![])).collect();
    for line in lines {
        for (n, v) in names.iter().zip(line.split(',')) {
            cols.get_mut(n).unwrap().push(v.parse().unwrap_or(f64::NAN));
        }
    }
    cols
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    assert!(args.len() == 3, "usage: span_decay RESULTS PROBE_S FROM");
    let from: f64 = args[2].parse().expect("FROM in s");
    for model in ["equivalent", "traditional"] {
        let dir = Path::new(&args[0]).join(model);
        let probe = dir.join(format!("probe_{}.csv", args[1]));
        if !probe.exists() {
            continue;
        }
        let p = columns(&probe);
        let e = columns(&dir.join("energy.csv"));
        let d = decay(&p["t"], &p["y"], from);
        let mech = |i: usize| e["kinetic"][i] + e["gravity"][i] + e["elastic"][i];
        println!(
            "{model}: {} cycles from t = {from} s, mean y {:.4} m, period {:.4} s, logarithmic \
             decrement {:.4} per cycle",
            d.cycles.len(),
            d.mean,
            d.period.unwrap_or(f64::NAN),
            d.decrement.unwrap_or(f64::NAN)
        );
        println!("  cycle  start/s  amplitude/m  mech. energy lost/J  slip work/J");
        for (k, c) in d.cycles.iter().enumerate() {
            let (lost, slip) = match d.cycles.get(k + 1) {
                Some(n) if e["t"].len() == p["t"].len() => (
                    mech(c.start_index) - mech(n.start_index),
                    e["dissipated"][n.start_index] - e["dissipated"][c.start_index],
                ),
                _ => (f64::NAN, f64::NAN),
            };
            println!(
                "  {k:>5}  {:>7.3}  {:>11.4e}  {lost:>19.4e}  {slip:>11.4e}",
                c.start, c.amplitude
            );
        }
    }
}
