//! Scene files of `strand` (SPEC 6): the JSON format ([`mod@format`]), its validation into a
//! [`Scene`] with errors that carry the JSON path of the fault, and the runner ([`run_scene`])
//! that builds and runs the models and writes the result files ([`output`]); shared by the
//! `strand` command and the validation harness.

pub mod along;
mod bending;
pub mod decay;
pub mod format;
mod law_bending;
pub mod output;
pub mod probe;
pub mod range;
mod run;
mod scene;
pub mod section_batch;
mod selection;

pub use bending::{
    BendingOptions, BendingSummary, first_slip_curvature, law_path_moments, run_bending,
    run_bending_with_penalty,
};
pub use law_bending::{LawBendingOptions, LawBendingSummary, loading_moments, run_law_bending};
pub use run::{
    BeamModelKind, Failure, RunError, RunOptions, RunSummary, build_beam, dynamic_options,
    run_scene,
};
pub use scene::{
    Analysis, BeamModel, DEFAULT_MAX_STEPS, Dynamic, End, FineModel, IntegratorKind,
    MAX_MOTION_ROWS, MAX_POINT_FORCES, MAX_PROBES, MEMORY_LIMIT, Models, Output, Scene, SceneError,
    Support, SupportKind, beam_memory, fine_memory,
};
pub use selection::{MODEL_NAMES, ModelSelectionError};
