//! `section.pitch_samples`: the scene reader's range, and the pitch rule's cap lifted for the
//! pitch-averaged law (a bending point standing for a whole pitch).

use serde_json::{Value, json};
use strand_scene::Scene;

fn span() -> Value {
    let text = include_str!("../../../examples/cardinal-span-400m.json");
    serde_json::from_str(text).unwrap()
}

/// 0 and 2 to 256 samples are read; 1 (a single phase, no average) and more than 256 are
/// refused naming the field.
#[test]
fn samples_outside_the_range_are_refused_by_name() {
    for (samples, ok) in [(0, true), (1, false), (2, true), (256, true), (257, false)] {
        let mut s = span();
        s["section"] = json!({ "pitch_samples": samples });
        match Scene::parse(&s.to_string()) {
            Ok(_) => assert!(ok, "{samples} samples read"),
            Err(e) => {
                assert!(!ok, "{samples} samples refused: {e}");
                assert_eq!(e.path, "section.pitch_samples", "{e}");
            }
        }
    }
}

/// Five elements of 80 m (380 pitches of 0.2104 m each, 1521 points per element by the pitch
/// rule, above the cap of 1024) are refused for the resolved law, and the message names the
/// option; the pitch-averaged law takes them, as it takes any number of pitches per element.
#[test]
fn the_pitch_averaged_law_lifts_the_pitch_rule_cap() {
    let mut s = span();
    s["models"]["equivalent"]["elements"] = json!(5);
    Scene::parse(&s.to_string()).expect("pitch-averaged: 5 elements of 80 m");
    s.as_object_mut().unwrap().remove("section");
    let e = Scene::parse(&s.to_string()).unwrap_err();
    assert_eq!(e.path, "models.equivalent.elements");
    assert!(
        e.message.contains("1.5210e3 per element") && e.message.contains("section.pitch_samples"),
        "{e}"
    );
}
