//! Times a 1,000-point sweep of the section law in Rust, the reference for the same sweep
//! called from Python (the manual's Python page, speed):
//!
//! ```text
//! cargo run --release -p strand-scene --example section_sweep -- examples/nylon-1x8-hanging.json
//! ```
//!
//! Curvatures from -20 to 20 1/m at strain 1e-3, x = 0, through
//! [`strand_scene::section_batch::evaluate_planar`] with the law built once; prints the median
//! wall time of one sweep over 2,000 repetitions for each law.

use std::time::Instant;

use strand_core::{LawKind, SectionLaw};
use strand_scene::Scene;
use strand_scene::section_batch::{PlanarOutputs, evaluate_planar};

const POINTS: usize = 1000;
const REPEATS: usize = 2000;

fn main() {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "examples/nylon-1x8-hanging.json".into());
    let scene = Scene::load(path.as_ref()).unwrap_or_else(|e| panic!("{path}: {e}"));
    let curvature: Vec<f64> = (0..POINTS)
        .map(|i| -20.0 + 40.0 * i as f64 / (POINTS - 1) as f64)
        .collect();
    let strain = vec![1e-3; POINTS];
    let x = vec![0.0; POINTS];
    for kind in [LawKind::Continuous, LawKind::Hysteretic] {
        let law = SectionLaw::with_options(&scene.strand, kind, &scene.section);
        let n = law.state_len();
        let state = vec![0.0; POINTS * n];
        let mut out = PlanarOutputs::zeros(POINTS, n);
        let mut times = Vec::with_capacity(REPEATS);
        let mut check = 0.0;
        for _ in 0..REPEATS {
            let t = Instant::now();
            evaluate_planar(&law, &strain, &curvature, &x, &state, out.arrays())
                .expect("consistent arrays");
            times.push(t.elapsed().as_secs_f64());
            check += out.moment[POINTS / 3];
        }
        times.sort_by(f64::total_cmp);
        println!(
            "{kind:<11} {POINTS} points: median {:.1} us per sweep (min {:.1} us; checksum {check:.6e})",
            times[REPEATS / 2] * 1e6,
            times[0] * 1e6
        );
    }
}
