//! The emulation the Multilayer page's unloading diagnosis uses (example `layer_moments`,
//! `LAW_ONLY` with `STICK_SCALE`): for the hysteretic slider a stick stiffness f k is the same
//! as the bending strain f e at stiffness k, so a layer's friction moment under stick
//! stiffness f k along a curvature path equals the one under k along the path f kappa. Checked
//! against the law's own two stick stiffnesses: `bonded` (per-interface factor f_j) along
//! kappa against `plane_section` along f_j kappa, per layer, for random paths with reversals.

#[path = "common/pitch_law.rs"]
mod pitch_law;

use pitch_law::PitchLaw;
use proptest::prelude::*;
use strand_core::{SectionLaw, SectionOptions, StickStiffness, Strand};
use strand_scene::Scene;

/// A two-layer, two-material section with the layers laid in alternate directions.
const SCENE: &str = r#"{
  "name": "acsr-section",
  "strand": {
    "length": 1.0,
    "core": {"diameter": 0.00334, "youngs_modulus": 2.07e11, "poisson_ratio": 0.3, "density": 7780.0},
    "layers": [
      {"wires": 6, "diameter": 0.00334, "pitch": 0.2104, "lay_direction": "left",
       "youngs_modulus": 2.07e11, "poisson_ratio": 0.3, "density": 7780.0},
      {"wires": 12, "diameter": 0.00332, "pitch": 0.2166, "lay_direction": "right",
       "youngs_modulus": 6.8e10, "poisson_ratio": 0.33, "density": 2703.0}
    ],
    "friction": 0.5
  },
  "law": "hysteretic",
  "supports": [{"at": "start", "kind": "clamped"}],
  "analysis": {"kind": "static"},
  "models": {"equivalent": {"elements": 8}}
}"#;

/// Stations over a pitch.
const STATIONS: usize = 12;

/// Per layer, the friction moment sum_i k (l_i kappa - s_i) l_i averaged over the stations
/// along `path` (N m), the law's slip state committed at each point; asserts that K_min kappa
/// plus it is the law's moment.
fn layer_friction(law: &SectionLaw, strand: &Strand, eps: f64, path: &[f64]) -> Vec<Vec<f64>> {
    let mut pitch_law = PitchLaw::new(law.clone(), strand, STATIONS);
    let layers = pitch_law.layers();
    path.iter()
        .map(|&kappa| {
            let mut friction = vec![0.0; layers];
            pitch_law.step(
                eps,
                kappa,
                (1e-10, 1e-6),
                |layer, m| friction[layer] += m / STATIONS as f64,
                |_, _, _, _| {},
            );
            friction
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn scaled_stick_stiffness_is_scaled_curvature(
        steps in proptest::collection::vec(-0.012f64..0.012, 1..8),
        tension in 100.0f64..3000.0,
    ) {
        let scene = Scene::parse(SCENE).unwrap();
        let strand = &scene.strand;
        let eps = tension / strand.axial_stiffness();
        let law_with = |stick| {
            let options = SectionOptions { stick_stiffness: stick, ..scene.section };
            SectionLaw::with_options(strand, scene.law, &options)
        };
        let bonded = law_with(StickStiffness::Bonded);
        let plane = law_with(StickStiffness::PlaneSection);
        // A path through the slip thresholds with reversals (cumulative steps).
        let path: Vec<f64> = steps
            .iter()
            .scan(0.0, |k, d| {
                *k += d;
                Some(*k)
            })
            .collect();
        let reference = layer_friction(&bonded, strand, eps, &path);
        for j in 0..strand.layers().len() {
            let f = bonded.layer_stick_stiffness(j) / plane.layer_stick_stiffness(j);
            prop_assert!(f > 0.0 && f < 1.0, "layer {j}: bonded factor {f}");
            let scaled: Vec<f64> = path.iter().map(|k| f * k).collect();
            let emulated = layer_friction(&plane, strand, eps, &scaled);
            for (a, b) in reference.iter().zip(&emulated) {
                // Round-off only: a few products and 12-station sums of moments of order
                // 0.3 N m, about 1e-15 each (the allowance 1e-12 is far above, far below the
                // 1.6e-3 N m a 1 % error in the factor makes).
                prop_assert!((a[j] - b[j]).abs() <= 1e-12, "layer {j}: {} against {}", a[j], b[j]);
            }
        }
    }
}
