//! Errors of the elastica solver.

use std::fmt;

/// Why the elastica solver gave no solution.
#[derive(Debug, Clone, PartialEq)]
pub enum ElasticaError {
    /// The problem or the options are invalid; `field` names the offending value.
    Input {
        /// Offending field, e.g. `length` or `steps`.
        field: &'static str,
        /// What is wrong with it.
        message: String,
    },
    /// The section law could not be inverted: no curvature has this moment.
    Inversion {
        /// Material coordinate (m); NaN when not known.
        s: f64,
        /// The moment to be reached (N m).
        moment: f64,
        /// Why it failed.
        reason: String,
    },
    /// The shooting did not find M(L) = 0 from the given start.
    Shooting {
        /// Load fraction of the continuation step that failed (-).
        load_fraction: f64,
        /// Residual moment at the free end at the best iterate (N m).
        residual: f64,
    },
    /// The load continuation stalled (its step fell below the minimum or it took too many
    /// steps) before reaching the full load.
    Continuation {
        /// Last load fraction reached (-).
        load_fraction: f64,
        /// Continuation steps taken.
        steps: usize,
    },
}

impl fmt::Display for ElasticaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ElasticaError::Input { field, message } => write!(f, "{field}: {message}"),
            ElasticaError::Inversion { s, moment, reason } => write!(
                f,
                "cannot invert the section law at s = {s} m for M = {moment:e} N m: {reason}"
            ),
            ElasticaError::Shooting {
                load_fraction,
                residual,
            } => write!(
                f,
                "shooting did not converge at load fraction {load_fraction}: best residual \
                 M(L) = {residual:e} N m"
            ),
            ElasticaError::Continuation {
                load_fraction,
                steps,
            } => write!(
                f,
                "load continuation stalled at load fraction {load_fraction} after {steps} steps"
            ),
        }
    }
}

impl std::error::Error for ElasticaError {}
