//! The scene runner shared by `strand run` and the validation harness: builds the models a
//! scene names, runs its analysis, and writes `DIR/<model>/` with the files of SPEC 6.
//!
//! Modules: [`record`] holds what every run shares (options, `summary.json`, errors);
//! `beam` runs the equivalent and traditional beams, `fine` the fine model.

pub(crate) mod beam;
mod beam_state;
mod budget;
pub(crate) mod fine;
pub(crate) mod record;
mod stopwatch;

use strand_core::LawKind;

use crate::scene::{BeamModel, Scene};
pub use beam::{BeamModelKind, build_beam, dynamic_options};
pub use record::{Failure, RunError, RunOptions, RunSummary};

/// Runs every model `scene` names and writes their results below `opts.out`. `progress`
/// receives (model, fraction done). Returns one summary per model: each model runs on its own,
/// and one that fails (`status` `failed`, with `reason` and `error`) keeps the files it wrote
/// and leaves the others to run. The error is for a `summary.json` that cannot be written.
pub fn run_scene(
    scene: &Scene,
    opts: &RunOptions,
    progress: &mut dyn FnMut(&str, f64),
) -> Result<Vec<RunSummary>, RunError> {
    let mut out = Vec::new();
    let models: [(&str, Option<&BeamModel>, LawKind); 2] = [
        ("equivalent", scene.models.equivalent.as_ref(), scene.law),
        (
            "traditional",
            scene.models.traditional.as_ref(),
            LawKind::Constant,
        ),
    ];
    for (name, model, law) in models {
        if let Some(m) = model {
            out.push(beam::run_beam(scene, name, m, law, opts, progress)?);
        }
    }
    if let Some(m) = &scene.models.fine {
        out.push(fine::run_fine(scene, m, opts, progress)?);
    }
    Ok(out)
}
