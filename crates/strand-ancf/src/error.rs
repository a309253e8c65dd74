//! Errors of the element kinematics.

/// Smallest admissible stretch `|r'|`: below it the tangent is undefined and the kinematics
/// return [`AncfError::DegenerateTangent`].
pub const MIN_STRETCH: f64 = 1e-8;

/// Smallest admissible `1 + t0 . t` for the spatial section frame: closer to zero the current
/// tangent `t` is (nearly) opposite to the reference tangent `t0`, where the minimal rotation
/// is undefined, and the kinematics return [`AncfError::AntiparallelTangent`].
pub const MIN_ALIGNMENT: f64 = 1e-8;

/// Failure of an element evaluation.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum AncfError {
    /// The position gradient `r'` has (almost) vanished: `|r'| < MIN_STRETCH`.
    #[error("position gradient |r'| = {norm:e} is below {MIN_STRETCH:e}: tangent undefined")]
    DegenerateTangent {
        /// The offending `|r'|`.
        norm: f64,
    },
    /// The current tangent is (almost) opposite to the reference tangent of the section frame:
    /// `1 + t0 . t < MIN_ALIGNMENT`.
    #[error(
        "tangent opposite to the reference tangent (1 + t0.t = {alignment:e}): section frame undefined"
    )]
    AntiparallelTangent {
        /// The offending `1 + t0 . t`.
        alignment: f64,
    },
    /// No Gauss-Legendre rule with this number of points.
    #[error("Gauss-Legendre rule with {n} points not available (1..=10)")]
    QuadratureOrder {
        /// Requested number of points.
        n: usize,
    },
    /// A reference section frame that is not a proper frame (zero or parallel vectors).
    #[error("invalid reference section frame: {reason}")]
    InvalidFrame {
        /// What is wrong.
        reason: &'static str,
    },
    /// A non-positive or non-finite element length.
    #[error("element length {length} must be positive and finite")]
    InvalidLength {
        /// The offending length.
        length: f64,
    },
}

/// `n` if it is an admissible stretch `|r'| >= MIN_STRETCH` (NaN is not).
#[inline]
pub(crate) fn check_stretch(n: f64) -> Result<f64, AncfError> {
    if n.is_nan() || n < MIN_STRETCH {
        return Err(AncfError::DegenerateTangent { norm: n });
    }
    Ok(n)
}

/// `alignment = 1 + t0 . t` if the minimal rotation is defined there (NaN is not).
#[inline]
pub(crate) fn check_alignment(alignment: f64) -> Result<f64, AncfError> {
    if alignment.is_nan() || alignment < MIN_ALIGNMENT {
        return Err(AncfError::AntiparallelTangent { alignment });
    }
    Ok(alignment)
}
