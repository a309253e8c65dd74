//! The `fine-bending` check: the frictionless virtual bending test of a scene's strand (any
//! number of layers) against the sum of the thin-rod K_min of its wires, and the section law
//! against the fine moment, at two meshes whose change is the finer one's mesh error.

use std::path::Path;

use strand_core::BaseStiffness;
use strand_fine::NormalPenalty;
use strand_scene::{BendingOptions, BendingSummary, Scene, run_bending_with_penalty};

use super::report::{Bound, Row};
use super::tolerances::FineBendingTol;

/// One mesh of the test: M / kappa of the fine model and the law's moment over the fine one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Segments per pitch.
    pub mesh: usize,
    /// Fine secant stiffness M / kappa at the measured curvature (N m^2).
    pub stiffness: f64,
    /// The section law's moment at the same strain and curvature over the fine moment (-).
    pub law_ratio: f64,
}

impl Measured {
    fn from_summary(mesh: usize, s: &BendingSummary) -> Option<Measured> {
        let [kappa, moment, law] = *s.points.last()?;
        Some(Measured {
            mesh,
            stiffness: moment / kappa,
            law_ratio: law / moment,
        })
    }
}

/// The rows `k-min`, `law` and `mesh` of the check on `model` (the scene the models run, a
/// perturbed one in a developer check), judged against the thin-rod K_min of `reference`'s
/// strand (Costello's wire stiffness, the closed form the one-layer test converges to). Each
/// mesh writes its `bending.csv` under `out`.
pub fn rows(reference: &Scene, model: &Scene, t: &FineBendingTol, out: &Path) -> Vec<Row> {
    let name = reference.name.as_str();
    let check = "fine-bending";
    let mut runs = Vec::new();
    for &mesh in &t.segments_per_pitch {
        let opts = BendingOptions {
            tension: t.tension,
            curvatures: vec![t.curvature],
            pitches: t.pitches,
            segments_per_pitch: mesh,
            out: out.join(format!("spp{mesh}")),
        };
        match run_bending_with_penalty(model, &opts, NormalPenalty::Penetration, &mut |_, _| {}) {
            Ok(s) => match Measured::from_summary(mesh, &s) {
                Some(m) => runs.push(m),
                None => {
                    return vec![Row::failed(
                        name,
                        check,
                        "-",
                        format!("{mesh} segments per pitch: no bending point"),
                    )];
                }
            },
            Err(e) => {
                return vec![Row::failed(
                    name,
                    check,
                    "-",
                    format!("{mesh} segments per pitch: {e}"),
                )];
            }
        }
    }
    let [coarse, fine] = runs[..] else {
        return vec![Row::failed(name, check, "-", "needs two meshes")];
    };
    let k_min = reference
        .strand
        .min_bending_stiffness(BaseStiffness::Costello);
    let mesh_error = (fine.stiffness - coarse.stiffness).abs() / fine.stiffness;
    let law_change = (fine.law_ratio - coarse.law_ratio).abs();
    let meshes = format!("{} and {} segments per pitch", coarse.mesh, fine.mesh);
    let mut k = Row::measured(
        name,
        check,
        "k-min",
        (fine.stiffness / k_min - 1.0).abs() + mesh_error,
        "-",
        Bound::AtMost(t.k_min),
    );
    k.note = format!(
        "M/kappa {:.5}, {:.5} K_min at {meshes} (K_min {k_min:.5e} N m^2); |K/K_min - 1| + mesh \
         change",
        coarse.stiffness / k_min,
        fine.stiffness / k_min
    );
    let mut law = Row::measured(
        name,
        check,
        "law",
        (fine.law_ratio - 1.0).abs() + law_change,
        "-",
        Bound::AtMost(t.law),
    );
    law.note = format!(
        "law / fine moment {:.5}, {:.5} at {meshes}; |ratio - 1| + its change",
        coarse.law_ratio, fine.law_ratio
    );
    let mut mesh = Row::measured(name, check, "mesh", mesh_error, "-", Bound::AtMost(t.mesh));
    mesh.note = format!("change of M/kappa from {meshes}, relative");
    vec![k, law, mesh]
}
