//! What every model's run shares: its options, its record (`summary.json`) and its errors.

use std::path::{Path, PathBuf};

use serde::Serialize;

/// Energy balance error, relative to the largest kinetic energy, above which a dynamic run
/// warns that its result is not to be trusted.
pub const BALANCE_WARNING: f64 = 0.05;

/// Whether a dynamic run's energy balance is open: its error is above [`BALANCE_WARNING`] of
/// the largest kinetic energy by more than `floor` (J), the error round-off alone can make
/// (`strand_core::round_off`). A strand at rest is moved by round-off alone, and its balance
/// error is then of the size of its kinetic energy: below the floor, the balance says nothing.
pub(crate) fn balance_open(error: f64, max_kinetic: f64, floor: f64) -> bool {
    error > BALANCE_WARNING * max_kinetic + floor
}

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
    /// `ok`, or `failed` with `reason` and `error` set (the files hold what was computed
    /// until then).
    pub status: String,
    /// Why the run failed, in one word ([`Failure`]).
    pub reason: Option<Failure>,
    /// Why the run failed: what, where and what to do.
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
    /// CPU time of the process over the same span, all threads (s); `None` where the platform
    /// has no process clock.
    pub cpu_time_s: Option<f64>,
    /// Tip position at the end, or where the run stopped (m); `None` if nothing was computed.
    pub tip: Option<[f64; 3]>,
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

/// Why a model's run failed: the `reason` of `summary.json`, one word a script can test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Failure {
    /// The model could not be built from the scene.
    Setup,
    /// The run would take more steps than `analysis.max_steps` allows: refused before it
    /// started, with the count and an estimate of its time.
    StepLimit,
    /// The solver did not converge (no static equilibrium, Newton failed in a time step, the
    /// damped motion did not come to rest).
    NoConvergence,
    /// A NaN or infinite value appeared.
    NonFinite,
    /// The explicit time step is above the estimated stable step.
    UnstableStep,
    /// A result file could not be written.
    Output,
}

impl Failure {
    /// The name `summary.json` gives it.
    pub fn name(self) -> &'static str {
        match self {
            Failure::Setup => "setup",
            Failure::StepLimit => "step-limit",
            Failure::NoConvergence => "no-convergence",
            Failure::NonFinite => "non-finite",
            Failure::UnstableStep => "unstable-step",
            Failure::Output => "output",
        }
    }
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A run that stopped: why, and the message that says where and what to do.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Stop {
    pub reason: Failure,
    pub message: String,
}

impl Stop {
    pub fn new(reason: Failure, message: impl Into<String>) -> Stop {
        Stop {
            reason,
            message: message.into(),
        }
    }

    /// A result file could not be written.
    pub fn output(message: impl Into<String>) -> Stop {
        Stop::new(Failure::Output, message)
    }
}

impl RunSummary {
    /// An empty record of `model`'s run of `scene` (status `ok`, nothing computed yet).
    pub(crate) fn start(scene: &str, model: &str, law: &str, analysis: &str) -> RunSummary {
        RunSummary {
            scene: scene.into(),
            model: model.into(),
            law: law.into(),
            analysis: analysis.into(),
            status: "ok".into(),
            reason: None,
            error: None,
            dofs: 0,
            elements: 0,
            integration_points: 0,
            steps: 0,
            newton_iterations: 0,
            wall_time_s: 0.0,
            cpu_time_s: None,
            tip: None,
            time_step: None,
            stable_time_step: None,
            energy_balance_error: None,
            energy_balance_relative: None,
            dissipated: None,
            non_potential_work: None,
            built: Vec::new(),
            warnings: Vec::new(),
        }
    }

    /// Whether the run failed (`status` is `failed`; `reason` and `error` say why).
    pub fn failed(&self) -> bool {
        self.status == "failed"
    }

    /// `model (reason): error` of a failed run; `None` for one that finished.
    pub fn failure(&self) -> Option<String> {
        self.failed().then(|| {
            format!(
                "{} ({}): {}",
                self.model,
                self.reason.map_or("failed", Failure::name),
                self.error.as_deref().unwrap_or("no reason given")
            )
        })
    }
}

/// Records the outcome `result` of a model's run in `summary` and writes `dir/summary.json`.
/// A failed run is recorded, not returned as an error (its files hold what was computed); the
/// error is only for a `summary.json` that cannot be written.
pub(crate) fn finish(
    mut summary: RunSummary,
    result: Result<(), Stop>,
    dir: &Path,
) -> Result<RunSummary, RunError> {
    if let Err(stop) = result {
        summary.status = "failed".into();
        summary.reason = Some(stop.reason);
        summary.error = Some(stop.message);
    }
    std::fs::create_dir_all(dir).map_err(io_err(dir))?;
    let path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(&summary).expect("summary serializes");
    std::fs::write(&path, text + "\n").map_err(io_err(&path))?;
    Ok(summary)
}
