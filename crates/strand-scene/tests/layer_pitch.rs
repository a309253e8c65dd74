//! A layer given by its lay length keeps it: the helix radius the strand is built on, lifted
//! for a closed layer and stacked on the lifted layers beneath, is the radius of
//! `P = 2 pi R_w / tan(alpha)`.

use std::f64::consts::PI;

use strand_scene::Scene;

/// Cardinal ACSR 54/7 by lay lengths: a closed 6-wire steel layer (lifted by about 17 um)
/// under three aluminium layers laid in alternate directions.
#[test]
fn given_pitches_hold_on_lifted_and_stacked_radii() {
    let text = r#"{
      "name": "cardinal-by-pitch",
      "strand": {
        "length": 1.0,
        "core": { "diameter": 0.00334, "youngs_modulus": 2.07e11, "poisson_ratio": 0.3, "density": 7780 },
        "layers": [
          { "wires": 6, "diameter": 0.00334, "pitch": 0.2104, "lay_direction": "left",
            "youngs_modulus": 2.07e11, "poisson_ratio": 0.3, "density": 7780 },
          { "wires": 12, "diameter": 0.00332, "pitch": 0.2166, "lay_direction": "right",
            "youngs_modulus": 6.8e10, "poisson_ratio": 0.33, "density": 2703 },
          { "wires": 18, "diameter": 0.00332, "pitch": 0.3029, "lay_direction": "left",
            "youngs_modulus": 6.8e10, "poisson_ratio": 0.33, "density": 2703 },
          { "wires": 24, "diameter": 0.00332, "pitch": 0.3593, "lay_direction": "right",
            "youngs_modulus": 6.8e10, "poisson_ratio": 0.33, "density": 2703 }
        ],
        "friction": 0.5
      },
      "supports": [{ "at": "start", "kind": "clamped" }],
      "analysis": { "kind": "static" },
      "models": { "equivalent": { "elements": 4 } }
    }"#;
    let scene = Scene::parse(text).unwrap();
    let layers = scene.strand.layers();
    assert!(
        layers[0].lift > 1e-5,
        "the steel layer is closed and lifted"
    );
    for (l, want) in layers.iter().zip([0.2104, 0.2166, 0.3029, 0.3593]) {
        let pitch = 2.0 * PI * l.radius / l.lay_angle().tan();
        assert!(
            (pitch - want).abs() <= 1e-12 * want,
            "pitch {pitch} m on radius {} m, want {want} m",
            l.radius
        );
        assert!((l.pitch - want).abs() <= 1e-12 * want);
    }
}
