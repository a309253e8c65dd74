//! The energy ledger of dynamic beam runs: the work the non-potential part of the `continuous`
//! and `paper` laws does is its own column of `energy.csv` and figure of `summary.json`, never
//! negative dissipation, and a run where it puts energy in warns; a dynamic scene that names
//! no law runs `hysteretic`.

mod common;
#[path = "common/temp_path.rs"]
mod temp_path;

use strand_core::LawKind;
use strand_scene::{RunOptions, Scene, run_scene};
use temp_path::TempPath;

fn fig14(law: Option<&str>) -> serde_json::Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/paper-fig14-pendulum.json"
    ))
    .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let obj = v.as_object_mut().unwrap();
    match law {
        Some(l) => obj.insert("law".into(), l.into()),
        None => obj.remove("law"),
    };
    let models = obj["models"]["equivalent"].clone();
    obj.insert("models".into(), serde_json::json!({ "equivalent": models }));
    v
}

/// The section-3 pendulum (Fig. 14, Stoermer-Verlet at its stable step, 1 s): with
/// `continuous` the law's non-potential part puts energy in (1.4e-4 J at the end, 3e-4 J at
/// 0.4 s; 22 J, booked as negative dissipation, before the law read the recovered tension);
/// the ledger shows it in `non_potential` and a warning, keeps `dissipated` (slip work) at
/// zero, and kinetic + gravity + elastic changes by exactly `non_potential - dissipated` up to
/// the integrator's error. With `hysteretic` the non-potential work is zero and the slip work
/// positive and growing.
#[test]
fn non_potential_work_is_booked_apart_from_dissipation() {
    for law in ["continuous", "hysteretic"] {
        let scene = Scene::parse(&fig14(Some(law)).to_string()).unwrap();
        let out = TempPath::new(&format!("strand-ledger-{law}"));
        let opts = RunOptions {
            out: out.to_path_buf(),
            vtk: false,
        };
        let summary = run_scene(&scene, &opts, &mut |_, _| {}).unwrap().remove(0);
        let e = common::csv_columns(&out.join("equivalent/energy.csv"));
        // Every field is a number: energy.csv has no blank (non-finite) value.
        assert!(
            e.values().flatten().all(|v| v.is_finite()),
            "{law}: a blank field in energy.csv"
        );
        let (d, w) = (&e["dissipated"], &e["non_potential"]);
        let k_max = e["kinetic"].iter().cloned().fold(0.0, f64::max);
        // Slip work can only grow (round-off of its sum aside).
        for (i, pair) in d.windows(2).enumerate() {
            assert!(
                d[i] >= 0.0 && pair[1] >= pair[0] - 1e-15,
                "{law}: dissipated {pair:?}"
            );
        }
        let mech = |i: usize| e["kinetic"][i] + e["gravity"][i] + e["elastic"][i];
        let mut worst: f64 = 0.0;
        for i in 0..d.len() {
            let gain = mech(i) - mech(0);
            worst = worst.max((gain - (w[i] - d[i])).abs());
        }
        let w_end = *w.last().unwrap();
        let w_max = w.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let warned = summary
            .warnings
            .iter()
            .any(|m| m.contains("into the strand"));
        println!(
            "{law}: non-potential work {w_end:.3e} J at the end ({w_max:.3e} J at most), \
             dissipated {:.3e} J; mechanical energy off its ledger by at most {worst:.2e} J \
             ({:.1e} of the largest kinetic energy); warned: {warned}",
            d.last().unwrap(),
            worst / k_max
        );
        // The Verlet balance of this scene is 1e-5 of the largest kinetic energy (validate).
        assert!(worst < 1e-4 * k_max, "{law}: ledger off by {worst} J");
        assert_eq!(summary.non_potential_work, Some(w_end));
        assert_eq!(summary.dissipated, Some(*d.last().unwrap()));
        match law {
            "continuous" => {
                assert!(w_max > 0.0, "the continuous law put no energy in");
                assert_eq!(*d.last().unwrap(), 0.0, "no slip work without slip state");
                assert_eq!(warned, w_end > 1e-9 * k_max, "{:?}", summary.warnings);
            }
            _ => {
                assert!(w.iter().all(|&x| x == 0.0), "hysteretic: {w_end}");
                assert!(*d.last().unwrap() > 0.0);
                assert!(!warned);
            }
        }
    }
}

#[test]
fn a_dynamic_scene_without_a_law_runs_hysteretic() {
    let scene = Scene::parse(&fig14(None).to_string()).unwrap();
    assert_eq!(scene.law, LawKind::Hysteretic);
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/paper-sec3-g12.json"
    ))
    .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.as_object_mut().unwrap().remove("law");
    assert_eq!(
        Scene::parse(&v.to_string()).unwrap().law,
        LawKind::Continuous
    );
}
