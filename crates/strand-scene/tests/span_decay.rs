//! A plucked conductor span decays by interwire friction, and only by it: a Cardinal ACSR
//! 54/7 span (the geometry of `examples/cardinal-span.json`, shorter run, coarser mesh and
//! step), released straight under gravity between pins at its length apart (the tension is
//! the sag's own stretch), against its constant-stiffness twin (the traditional beam given
//! the equivalent's stick stiffness K_max and EA_eq, law `constant`).
//!
//! Independent of the law's code: the energy ledger's books (the mechanical energy and the
//! slip work booked by the law) are compared between successive cycles of the midspan probe;
//! the loss of mechanical energy over a cycle must be the slip work of that cycle to within
//! the run's energy balance error (the ledger's own closure, measured, not chosen), and that
//! slip work must stand far above the twin's loss of mechanical energy per cycle, which is
//! the integrator's numerical damping and is measured at h and h/2.

mod common;
#[path = "common/temp_path.rs"]
mod temp_path;

use std::path::Path;

use common::csv_columns;
use serde_json::json;
use strand_core::{LawKind, SectionLaw};
use strand_scene::decay::decay;
use strand_scene::{RunOptions, RunSummary, Scene, run_scene};
use temp_path::TempPath;

const LENGTH: f64 = 20.0;
/// After the first fall.
const FROM: f64 = 0.3;

fn cardinal(friction: f64) -> serde_json::Value {
    let steel = |wires: usize, pitch: f64, dir: &str| {
        json!({ "wires": wires, "diameter": 0.00334, "pitch": pitch, "lay_direction": dir,
                "youngs_modulus": 2.07e11, "poisson_ratio": 0.3, "density": 7780.0 })
    };
    let alu = |wires: usize, pitch: f64, dir: &str| {
        json!({ "wires": wires, "diameter": 0.00332, "pitch": pitch, "lay_direction": dir,
                "youngs_modulus": 6.8e10, "poisson_ratio": 0.33, "density": 2703.0 })
    };
    json!({
        "length": LENGTH,
        "core": { "diameter": 0.00334, "youngs_modulus": 2.07e11, "poisson_ratio": 0.3, "density": 7780.0 },
        "layers": [steel(6, 0.2104, "left"), alu(12, 0.2166, "right"), alu(18, 0.3029, "left"),
                   alu(24, 0.3593, "right")],
        "friction": friction
    })
}

fn span(friction: f64, step: f64, models: serde_json::Value) -> Scene {
    let scene = json!({
        "name": "cardinal-span-decay",
        "strand": cardinal(friction),
        "law": "hysteretic",
        "supports": [
            { "at": "start", "kind": "pinned" },
            { "at": "end", "kind": "pinned" }
        ],
        "loads": { "gravity": [0.0, -9.81, 0.0] },
        "analysis": { "kind": "dynamic", "duration": 3.5, "integrator": "generalized-alpha",
                      "time_step": step, "output_interval": step },
        "models": models,
        "output": { "probes": [LENGTH / 2.0] }
    });
    Scene::parse(&scene.to_string()).expect("valid scene")
}

fn run(scene: &Scene, tag: &str) -> (TempPath, RunSummary) {
    let out = TempPath::new(&format!("strand-span-decay-{tag}"));
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: false,
    };
    let mut summaries = run_scene(scene, &opts, &mut |_, _| {}).expect("run succeeds");
    assert_eq!(summaries.len(), 1);
    let s = summaries.remove(0);
    assert!(!s.failed(), "{:?}", s.failure());
    (out.into_sub(&s.model), s)
}

/// Per complete cycle of the midspan probe after `FROM`: (loss of mechanical energy, slip
/// work booked) between the cycle's start and the next's, and the run's balance error.
struct Cycles {
    loss: Vec<f64>,
    slip: Vec<f64>,
    balance: f64,
    decrement: f64,
}

fn cycles(dir: &Path, summary: &RunSummary) -> Cycles {
    let probe = csv_columns(&dir.join(format!("probe_{}.csv", LENGTH / 2.0)));
    let energy = csv_columns(&dir.join("energy.csv"));
    let (t, y) = (&probe["t"], &probe["y"]);
    assert_eq!(t.len(), energy["t"].len(), "one probe row per energy row");
    let d = decay(t, y, FROM);
    assert!(d.cycles.len() >= 3, "{} cycles", d.cycles.len());
    let mech = |i: usize| energy["kinetic"][i] + energy["gravity"][i] + energy["elastic"][i];
    let mut loss = Vec::new();
    let mut slip = Vec::new();
    for w in d.cycles.windows(2) {
        let (a, b) = (w[0].start_index, w[1].start_index);
        loss.push(mech(a) - mech(b));
        slip.push(energy["dissipated"][b] - energy["dissipated"][a]);
    }
    Cycles {
        loss,
        slip,
        balance: summary.energy_balance_error.expect("dynamic run"),
        decrement: d.decrement.expect("cycles"),
    }
}

#[test]
fn plucked_span_decays_by_the_slip_work_the_twin_does_not() {
    let step = 2e-3;
    let equivalent = json!({ "equivalent": { "elements": 40 } });
    let (dir, summary) = run(&span(0.5, step, equivalent), "hysteretic");
    let hyst = cycles(&dir, &summary);

    // The twin: the same beam with the equivalent's all-stick stiffness and EA, no sliders.
    let strand = span(0.5, step, json!({ "equivalent": { "elements": 1 } })).strand;
    let law = SectionLaw::new(&strand, LawKind::Hysteretic);
    let twin = |h: f64, tag: &str| {
        let models = json!({ "traditional": { "elements": 40,
            "bending_stiffness": law.stick_bending_stiffness(),
            "axial_stiffness": law.axial_stiffness() } });
        let (dir, summary) = run(&span(0.5, h, models), tag);
        cycles(&dir, &summary)
    };
    let twin_h = twin(step, "twin-h");
    let twin_h2 = twin(step / 2.0, "twin-h2");

    // 1. The ledger: each cycle's loss of mechanical energy is its slip work, within the
    //    balance error (the drift of the balance over a cycle is at most twice its largest
    //    excursion).
    for (k, (l, s)) in hyst.loss.iter().zip(&hyst.slip).enumerate() {
        assert!(
            (l - s).abs() <= 2.0 * hyst.balance,
            "cycle {k}: mechanical energy lost {l:.4e} J, slip work {s:.4e} J, balance {:.3e} J",
            hyst.balance
        );
    }
    // 2. Numerical damping of the twin (law `constant`, nothing to dissipate): its loss of
    //    mechanical energy per cycle, measured at h and h/2.
    let worst = |c: &Cycles| c.loss.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    let numerical = worst(&twin_h).max(worst(&twin_h2));
    let slip_per_cycle = hyst.slip.iter().sum::<f64>() / hyst.slip.len() as f64;
    eprintln!(
        "slip work per cycle {slip_per_cycle:.4e} J (balance {:.2e} J); twin's largest loss per \
         cycle {:.3e} J at h, {:.3e} J at h/2; decrements: hysteretic {:.4}, twin {:.4} (h), {:.4} (h/2)",
        hyst.balance,
        worst(&twin_h),
        worst(&twin_h2),
        hyst.decrement,
        twin_h.decrement,
        twin_h2.decrement
    );
    // The friction's work per cycle stands at least ten times above both the numerical loss
    // and the ledger's balance error: the decay is physical, not the integrator's.
    assert!(
        slip_per_cycle > 10.0 * numerical.max(hyst.balance),
        "slip work per cycle {slip_per_cycle:.3e} J against numerical loss {numerical:.3e} J and \
         balance {:.3e} J",
        hyst.balance
    );
    // 3. The probe: the midspan amplitude decays beyond the cycle-to-cycle modulation a strand
    //    without dissipation shows (the sag-tension coupling trades energy between the
    //    fundamental, its harmonics and the axial stretch), measured as the twin's fitted
    //    decrement at h and h/2: three times that noise, a margin on a fitted slope.
    let noise = twin_h.decrement.abs().max(twin_h2.decrement.abs());
    assert!(
        hyst.decrement > 3.0 * noise,
        "decrement {:.4} against the twin's {noise:.4}",
        hyst.decrement
    );
}
