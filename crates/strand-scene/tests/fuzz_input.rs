//! Bad input never panics: random and mutated scene files are either accepted as valid scenes
//! or rejected with an error that names the JSON path of the fault (or the whole file for
//! syntax errors).

use proptest::prelude::*;
use serde_json::{Value, json};
use strand_scene::Scene;

fn good() -> Value {
    serde_json::from_str(include_str!("../../../validation/paper-fig7-g8.json")).unwrap()
}

/// Every JSON pointer to a leaf or object in `v`.
fn pointers(v: &Value, prefix: String, out: &mut Vec<String>) {
    out.push(prefix.clone());
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                pointers(x, format!("{prefix}/{k}"), out);
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                pointers(x, format!("{prefix}/{i}"), out);
            }
        }
        _ => {}
    }
}

fn replacement() -> impl Strategy<Value = Value> {
    prop_oneof![
        Just(json!(null)),
        Just(json!(0)),
        Just(json!(-1.0)),
        Just(json!(1e308)),
        Just(json!(-1e-300)),
        Just(json!(1_000_000_000_000i64)),
        Just(json!("text")),
        Just(json!([])),
        Just(json!({})),
        Just(json!([1.0, 2.0])),
        Just(json!(true)),
        any::<f64>().prop_map(|x| if x.is_finite() { json!(x) } else { json!(null) }),
        any::<i64>().prop_map(|x| json!(x)),
    ]
}

fn check(text: &str) -> Result<(), TestCaseError> {
    match Scene::parse(text) {
        Ok(scene) => {
            // An accepted scene is usable: its strand quantities are finite.
            prop_assert!(scene.strand.mass_per_length().is_finite());
            prop_assert!(
                scene
                    .strand
                    .min_bending_stiffness(scene.section.base_stiffness)
                    .is_finite()
            );
        }
        Err(e) => {
            prop_assert!(!e.message.is_empty());
            // Value errors name a path; syntax errors of the whole file may not.
            let whole_file = e.path.is_empty();
            prop_assert!(
                !whole_file || e.message.contains("line") || e.message.contains("empty"),
                "no path and no position: {e}"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Replace any value in a valid scene by a value of another type or range.
    #[test]
    fn mutated_values(which in any::<prop::sample::Index>(), v in replacement()) {
        let mut s = good();
        let mut ptrs = Vec::new();
        pointers(&s, String::new(), &mut ptrs);
        let p = which.get(&ptrs).clone();
        if p.is_empty() {
            s = v;
        } else {
            *s.pointer_mut(&p).unwrap() = v;
        }
        check(&s.to_string())?;
    }

    /// Remove any field of a valid scene.
    #[test]
    fn removed_fields(which in any::<prop::sample::Index>()) {
        let mut s = good();
        let mut ptrs = Vec::new();
        pointers(&s, String::new(), &mut ptrs);
        let p = which.get(&ptrs).clone();
        if let Some((parent, key)) = p.rsplit_once('/')
            && let Some(Value::Object(m)) = s.pointer_mut(parent)
        {
            m.remove(key);
        }
        check(&s.to_string())?;
    }

    /// Truncated files and random bytes.
    #[test]
    fn truncated_and_random_text(cut in 0usize..2000, noise in "\\PC{0,200}") {
        let text = good().to_string();
        let cut = cut.min(text.len());
        check(&text[..cut])?;
        check(&noise)?;
    }
}

/// A strand value: typical, scaled by up to 1e4 either way, or one of the hostile values.
fn strand_value(typical: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => (-4.0f64..4.0).prop_map(move |e| typical * 10f64.powf(e)),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(-typical),
        1 => Just(0.0),
        1 => Just(f64::MAX),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random strand parameters (NaN and infinity included, which JSON cannot carry) through
    /// the validation and the runner's set-up: a rejection names the JSON path; an accepted
    /// scene builds a beam whose stable step and forces at rest are finite, or the set-up
    /// refuses it with an error. Never a panic.
    #[test]
    fn random_strands_through_the_runner_setup(
        length in strand_value(0.4),
        core in (strand_value(3e-3), strand_value(2e8), strand_value(7801.0)),
        layer in (strand_value(2e-3), strand_value(2e8), strand_value(7801.0), strand_value(20.0)),
        wires in -1i64..12,
        friction in strand_value(0.3),
        elements in 0i64..40,
    ) {
        let mut f: strand_scene::format::SceneFile = serde_json::from_value(good()).unwrap();
        f.strand.length = length;
        (f.strand.core.diameter, f.strand.core.youngs_modulus, f.strand.core.density) = core;
        let l = &mut f.strand.layers[0];
        (l.diameter, l.youngs_modulus, l.density) = (layer.0, layer.1, layer.2);
        l.lay_angle_deg = Some(layer.3);
        l.wires = wires;
        f.strand.friction = Some(friction);
        f.models.equivalent.as_mut().unwrap().elements = elements;
        f.models.traditional = None;
        match Scene::from_file(f) {
            Err(e) => prop_assert!(!e.path.is_empty() && !e.message.is_empty(), "{e}"),
            Ok(scene) => {
                if let Ok(beam) =
                    strand_scene::build_beam(&scene, strand_scene::BeamModelKind::Equivalent)
                {
                    let h = strand_ancf::dynamics::stable_step(&beam);
                    prop_assert!(h.as_ref().map_or(true, |h| h.is_finite() && *h > 0.0), "{h:?}");
                    let slip = beam.initial_state();
                    let mut trial = slip.clone();
                    let mut force = vec![0.0; beam.coords()];
                    if beam
                        .internal(beam.reference(), &slip, &mut trial, &mut force, None, None)
                        .is_ok()
                    {
                        prop_assert!(force.iter().all(|x| x.is_finite()));
                    }
                }
            }
        }
    }
}
