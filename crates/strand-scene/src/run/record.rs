//! What every model's run shares: its options, its record (`summary.json`) and its errors.

use std::path::{Path, PathBuf};

use serde::Serialize;

/// Energy balance error, relative to the largest kinetic energy, above which a dynamic run
/// warns that its result is not to be trusted.
pub const BALANCE_WARNING: f64 = 0.05;

/// Options of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// Output folder; each model writes into a sub-folder named after it.
    pub out: PathBuf,
    /// Also write the centreline of every output frame as VTK polylines.
    pub vtk: bool,
}

/// What `summary.json` holds.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct RunSummary {
    /// Scene name.
    pub scene: String,
    /// Model: `equivalent`, `traditional` or `fine`.
    pub model: String,
    /// Section law.
    pub law: String,
    /// `static` or `dynamic`.
    pub analysis: String,
    /// `ok`, or `failed` with `error` set (the files hold what was computed until then).
    pub status: String,
    /// Why the run failed.
    pub error: Option<String>,
    /// Degrees of freedom.
    pub dofs: usize,
    /// Elements.
    pub elements: usize,
    /// Bending integration points per element.
    pub integration_points: usize,
    /// Load steps (statics) or time steps (dynamics).
    pub steps: usize,
    /// Newton iterations in total.
    pub newton_iterations: usize,
    /// Wall time of the solve (s).
    pub wall_time_s: f64,
    /// Tip position at the end (m).
    pub tip: [f64; 3],
    /// Time step (s, dynamics).
    pub time_step: Option<f64>,
    /// Estimated stable step of the explicit integrator (s, runs of the explicit integrator).
    pub stable_time_step: Option<f64>,
    /// Largest |kinetic + gravity + elastic + dissipated - non-potential work - initial| (J,
    /// dynamics).
    pub energy_balance_error: Option<f64>,
    /// The balance error relative to the largest kinetic energy (dynamics).
    pub energy_balance_relative: Option<f64>,
    /// Work dissipated at the end (J, dynamics): slip (beam models) or friction (fine model).
    pub dissipated: Option<f64>,
    /// Work done on the strand by the non-potential part of the `continuous` and `paper` laws
    /// at the end (J, beam dynamics; positive: energy put in, not part of `dissipated`).
    pub non_potential_work: Option<f64>,
    /// What was built for this run.
    pub built: Vec<String>,
    /// Warnings.
    pub warnings: Vec<String>,
}

/// Why a run could not start or write its results.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The scene asks for something this version cannot build.
    #[error("{0}")]
    Unsupported(String),
    /// A model could not be built.
    #[error("{model}: {message}")]
    Setup {
        /// Model name.
        model: String,
        /// What failed.
        message: String,
    },
    /// The solver stopped; the files hold what was computed.
    #[error("{model}: {message} (results so far in {dir})")]
    Solve {
        /// Model name.
        model: String,
        /// What failed.
        message: String,
        /// Where the partial results are.
        dir: String,
    },
    /// Writing results failed.
    #[error("writing {path}: {source}")]
    Io {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
}

pub(crate) fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> RunError + '_ {
    move |source| RunError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Records the outcome `result` of a model's run in `summary`, writes `dir/summary.json` and
/// returns the summary, or the solver's failure (the files hold what was computed).
pub(crate) fn finish(
    mut summary: RunSummary,
    result: Result<(), String>,
    dir: &Path,
) -> Result<RunSummary, RunError> {
    if let Err(message) = &result {
        summary.status = "failed".into();
        summary.error = Some(message.clone());
    }
    let path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(&summary).expect("summary serializes");
    std::fs::write(&path, text + "\n").map_err(io_err(&path))?;
    match result {
        Ok(()) => Ok(summary),
        Err(message) => Err(RunError::Solve {
            model: summary.model,
            message,
            dir: dir.display().to_string(),
        }),
    }
}
