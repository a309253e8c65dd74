//! The bundled shaken span (`examples/steel-1x7-span-50m-shaken.json`: a 50 m 1+6 steel span
//! pretensioned to 26 kN, its clamped start shaken vertically at 9.675 Hz, 6 mm) cycles the
//! sections near the clamp through stick and slip, and its loops are the section law's own:
//!
//! * the example's scene as written (strand, supports and their motion tables, integrator,
//!   step, a frame every step) on a coarser mesh, 400 elements of three Gauss points, with
//!   probes at the bending points of the first metre: the laws checked here are those of the
//!   section and of the energy books, which hold on any mesh (the example's own mesh takes
//!   about 20 s of CPU; the refinement of its loop is on the manual's page "Probes, envelopes
//!   and loops");
//! * at every probe the moment is the law's, driven by this test through the frames;
//! * over the last period of the shaking, the loop's area (trapezoidal M dkappa) plus the
//!   axial work less the change of stored energy is the law's slip work, within the
//!   trapezoidal rule's error bound;
//! * the slip work of the probed bending points, weighted by their quadrature weights, is
//!   the `dissipated` of `energy.csv` (no section beyond the first metre slips);
//! * no file of the run holds `NaN` or `inf`.

mod common;
#[path = "common/section_loop.rs"]
mod section_loop;
#[path = "common/temp_path.rs"]
mod temp_path;

use std::path::Path;

use common::csv_columns;
use strand_core::{LawKind, SectionLaw};
use strand_scene::Scene;

const ELEMENTS: usize = 400;
/// Elements probed from the clamp (the first metre).
const PROBED: usize = 8;
/// The clamp's shaking frequency (Hz), as the example's motion table is written.
const FREQUENCY: f64 = 9.675;

#[test]
fn the_shaken_spans_loops_near_the_clamp_are_the_laws_and_their_area_is_the_slip_work() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = std::fs::read_to_string(root.join("examples/steel-1x7-span-50m-shaken.json"))
        .expect("the bundled example");
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let length = value["strand"]["length"].as_f64().unwrap();
    let points = section_loop::gauss_points(PROBED, length / ELEMENTS as f64);
    value["models"] = serde_json::json!({
        "equivalent": { "elements": ELEMENTS, "integration_points": 3 }
    });
    value["output"]["probes"] = points.iter().map(|p| p.0).collect();
    let step = value["analysis"]["time_step"].as_f64().unwrap();
    assert_eq!(
        value["analysis"]["output_interval"].as_f64(),
        Some(step),
        "the example writes a frame every step"
    );
    let scene = Scene::parse(&value.to_string()).unwrap();
    let out = section_loop::run_uncut(&scene, "strand-shaken");
    let dir = out.join("equivalent");
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let bad = text
            .split([',', '\n', ' ', ':', '[', ']'])
            .any(|f| matches!(f.trim_matches('"'), "NaN" | "nan" | "inf" | "-inf"));
        assert!(!bad, "{}: a NaN or inf", path.display());
    }

    let law = SectionLaw::with_options(&scene.strand, LawKind::Hysteretic, &scene.section);
    let ea = law.axial_stiffness();
    let k_min = scene
        .strand
        .min_bending_stiffness(scene.section.base_stiffness);
    let mut total_slip_work = 0.0;
    let mut first_loop = None;
    for &(s, weight) in &points {
        let c = csv_columns(&dir.join(strand_scene::probe::file_name(s)));
        let t = &c["t"];
        let st = law.station(s);
        let k_stick = section_loop::stick_tangent(&law, &st, c["tension"][t.len() - 1] / ea);
        let path = section_loop::drive(&law, &st, &c);
        total_slip_work += weight * path.work[t.len() - 1];
        // The last period of the shaking: from the frame nearest one period before the end.
        let b = t.len() - 1;
        let a = t
            .iter()
            .position(|&x| x >= t[b] - 1.0 / FREQUENCY - 0.5 * step)
            .unwrap();
        let cycle = section_loop::balance(&c, &path, ea, (k_min, k_stick), a, b);
        cycle.check(&format!("s = {s}"));
        eprintln!("s = {s:.4}: {cycle:?}");
        first_loop.get_or_insert(cycle);
    }
    // The section nearest the clamp slips over the period: a loop with area.
    let first = first_loop.unwrap();
    assert!(first.slip_work > 0.0 && first.area > 0.0, "{first:?}");
    let dissipated = *csv_columns(&dir.join("energy.csv"))["dissipated"]
        .last()
        .unwrap();
    assert!(
        dissipated > 0.0 && (total_slip_work - dissipated).abs() <= 1e-9 * dissipated,
        "the first metre's slip work {total_slip_work:e} J vs energy.csv {dissipated:e} J"
    );
    let _ = std::fs::remove_dir_all(out);
}
