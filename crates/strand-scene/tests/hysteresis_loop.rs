//! The moment-curvature loop a probe records, against the section law's own: a steel strand,
//! clamped at the start and pulled axially at the pinned end, whose end is then swung up and
//! down twice, so that the sections near the root cycle through stick and slip. Probes at every
//! bending point (two elements of three Gauss points), a frame every time step.
//!
//! * The probe's moment is the law's at the probe's strain and curvature, driven by this test
//!   from the unslipped state through the same frames (the loop closes on the law's loop).
//! * Over one full cycle, the area the probe's loop encloses (trapezoidal sum of M dkappa)
//!   equals the slip work the law dissipates over it, plus the change of its stored energy
//!   less the axial work (both small on a closed cycle), within the trapezoidal rule's error.
//! * The slip work of every bending point, weighted by its quadrature weight, sums to the
//!   `dissipated` of `energy.csv`.

mod common;
#[path = "common/section_loop.rs"]
mod section_loop;
#[path = "common/temp_path.rs"]
mod temp_path;

use common::csv_columns;
use serde_json::json;
use strand_core::{LawKind, SectionLaw};
use strand_scene::Scene;

const L: f64 = 0.5;
const ELEMENTS: usize = 2;

fn scene(probes: &[f64]) -> serde_json::Value {
    // Axial pull 5e-4 m (strain 1e-3, about 27 kN) over 0.1 s, held; then the end swings
    // between y = +A and -A with period 0.4 s (quasi-static: the strand's lowest transverse mode under
    // that tension is near 150 Hz).
    let (dx, a) = (5e-4, 4e-3);
    json!({
        "name": "cycled-section",
        "strand": {
            "length": L,
            "core": { "diameter": 0.0052, "youngs_modulus": 1.95e11, "poisson_ratio": 0.3, "density": 7850.0 },
            "layers": [ { "wires": 6, "diameter": 0.005, "pitch": 0.22,
                          "youngs_modulus": 1.95e11, "poisson_ratio": 0.3, "density": 7850.0 } ],
            "friction": 0.4
        },
        "law": "hysteretic",
        "supports": [
            { "at": "start", "kind": "clamped" },
            { "at": "end", "kind": "pinned", "motion": [
                [0.1, dx, 0.0, 0.0], [0.2, dx, a, 0.0], [0.4, dx, -a, 0.0],
                [0.6, dx, a, 0.0], [0.8, dx, -a, 0.0], [1.0, dx, a, 0.0] ] }
        ],
        "analysis": { "kind": "dynamic", "duration": 1.0, "integrator": "generalized-alpha",
                      "time_step": 2.5e-4, "output_interval": 2.5e-4, "spectral_radius": 0.8 },
        "models": { "equivalent": { "elements": ELEMENTS, "integration_points": 3 } },
        "output": { "probes": probes }
    })
}

#[test]
fn a_cycled_section_closes_on_the_laws_loop_and_its_area_is_the_slip_work() {
    let points = section_loop::gauss_points(ELEMENTS, L / ELEMENTS as f64);
    let probes: Vec<f64> = points.iter().map(|p| p.0).collect();
    let text = scene(&probes).to_string();
    let scene = Scene::parse(&text).unwrap();
    let out = section_loop::run_uncut(&scene, "strand-loop");
    let dir = out.join("equivalent");
    // The probes sit on the bending points (the rows of centerline.csv).
    let rows = csv_columns(&dir.join("centerline.csv"))["s"].clone();
    for p in &probes {
        assert!(
            rows.iter().any(|r| (r - p).abs() < 1e-12),
            "{p} is a bending point"
        );
    }

    let law = SectionLaw::with_options(&scene.strand, LawKind::Hysteretic, &scene.section);
    let ea = law.axial_stiffness();
    let k_min = scene
        .strand
        .min_bending_stiffness(scene.section.base_stiffness);
    let mut total_slip_work = 0.0;
    let mut largest_loop = 0.0f64;
    for (&(s, weight), p) in points.iter().zip(&probes) {
        let c = csv_columns(&dir.join(format!("probe_{p}.csv")));
        let (t, tension) = (&c["t"], &c["tension"]);
        let st = law.station(s);
        let k_stick = section_loop::stick_tangent(&law, &st, tension[1] / ea);
        // Drive the law through the probe's frames: the same moments, to round-off.
        let path = section_loop::drive(&law, &st, &c);
        total_slip_work += weight * path.work[t.len() - 1];
        // One full cycle, between the end's visits of +A at t = 0.6 s and 1 s.
        let at = |time: f64| t.iter().position(|x| (x - time).abs() < 1e-9).unwrap();
        let cycle = section_loop::balance(&c, &path, ea, (k_min, k_stick), at(0.6), at(1.0));
        cycle.check(&format!("s = {s}"));
        largest_loop = largest_loop.max(cycle.area);
        eprintln!("s = {s:.4}: {cycle:?}");
    }
    // The cycle slips: a loop with area, not a line.
    assert!(largest_loop > 0.0, "no loop: {largest_loop}");
    let dissipated = *csv_columns(&dir.join("energy.csv"))["dissipated"]
        .last()
        .unwrap();
    assert!(
        (total_slip_work - dissipated).abs() <= 1e-9 * dissipated.abs().max(1e-12),
        "the bending points' slip work {total_slip_work:e} J vs energy.csv {dissipated:e} J"
    );
    let _ = std::fs::remove_dir_all(out);
}
