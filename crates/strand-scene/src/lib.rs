//! Scene files of `strand` (SPEC 6): the JSON format ([`mod@format`]), its validation into a
//! [`Scene`] with errors that carry the JSON path of the fault, shared by the `strand` command
//! and the validation harness.

pub mod format;
mod scene;

pub use scene::{
    Analysis, BeamModel, Dynamic, End, FineModel, IntegratorKind, MEMORY_LIMIT, Models, Scene,
    SceneError, Support, SupportKind,
};
