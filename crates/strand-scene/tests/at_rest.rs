//! A strand at rest with no load stays at rest: every model, law and integrator ends `ok` with
//! no energy warning. Its motion is round-off alone (energies of 1e-27 to 1e-24 J), and the
//! balance checks compare it against their round-off floor (`strand_core::round_off`), not
//! against the kinetic energy of that motion, which is round-off too.

#[path = "common/temp_path.rs"]
mod temp_path;

use serde_json::{Value, json};
use strand_scene::{RunOptions, Scene, run_scene};
use temp_path::TempPath;

/// The section-3 strand (L = 1 m, E = 2e9 Pa), clamped at its start, without gravity, at rest.
fn at_rest(law: &str, integrator: &str, direction: [f64; 3]) -> Value {
    let wire = |d: f64| json!({ "diameter": d, "youngs_modulus": 2e9, "poisson_ratio": 0.3, "density": 5747.0 });
    let mut layer = wire(0.002);
    layer["wires"] = json!(6);
    layer["lay_angle_deg"] = json!(20.0);
    let mut analysis = json!({ "kind": "dynamic", "duration": 0.005, "integrator": integrator,
                               "output_interval": 0.001 });
    if integrator == "generalized-alpha" {
        analysis["time_step"] = json!(1e-4);
    }
    json!({
        "name": format!("rest-{law}-{integrator}"),
        "strand": { "length": 1.0, "core": wire(0.003), "layers": [layer], "friction": 0.3 },
        "law": law,
        "initial": { "direction": direction },
        "supports": [ { "at": "start", "kind": "clamped" } ],
        "loads": { "gravity": [0.0, 0.0, 0.0] },
        "analysis": analysis,
        "models": { "equivalent": { "elements": 8 }, "traditional": { "elements": 8 },
                    "fine": { "segments_per_wire": 12 } }
    })
}

#[test]
fn a_strand_at_rest_without_load_runs_ok_without_energy_warnings() {
    let out = TempPath::new("strand-rest");
    let mut runs = 0;
    for law in ["continuous", "paper", "hysteretic"] {
        for integrator in ["verlet", "generalized-alpha"] {
            // Planar, and along a direction out of every coordinate plane (3D elements).
            for direction in [[1.0, 0.0, 0.0], [0.48, 0.6, 0.64]] {
                let v = at_rest(law, integrator, direction);
                let scene = Scene::parse(&v.to_string()).unwrap();
                let opts = RunOptions {
                    out: out.to_path_buf(),
                    vtk: false,
                };
                let summaries = run_scene(&scene, &opts, &mut |_, _| {}).unwrap();
                assert_eq!(summaries.len(), 3);
                for s in &summaries {
                    let tag = format!("{law} {integrator} {direction:?} {}", s.model);
                    println!(
                        "{tag}: {} balance {:.3e} J",
                        s.status,
                        s.energy_balance_error.unwrap_or(f64::NAN)
                    );
                    assert_eq!(s.status, "ok", "{tag}: {:?}", s.error);
                    let energy = s
                        .warnings
                        .iter()
                        .find(|w| w.contains("energy balance") || w.contains("J into the strand"));
                    assert!(energy.is_none(), "{tag}: {energy:?}");
                    runs += 1;
                }
            }
        }
    }
    assert_eq!(runs, 36);
}
