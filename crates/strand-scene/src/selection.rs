//! Choosing which of a scene's models run (`strand run --model`, `strand.run(models=...)`).

use crate::scene::Models;

/// Names of the models a scene can hold, in the order they run.
pub const MODEL_NAMES: [&str; 3] = ["equivalent", "traditional", "fine"];

/// A model name that cannot be selected.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ModelSelectionError {
    /// Not one of [`MODEL_NAMES`].
    #[error("{0}: unknown model (expected equivalent, traditional or fine)")]
    Unknown(String),
    /// A model the scene does not name.
    #[error("the scene has no models.{0}")]
    Absent(String),
}

impl ModelSelectionError {
    /// The offending model name.
    pub fn model(&self) -> &str {
        match self {
            ModelSelectionError::Unknown(m) | ModelSelectionError::Absent(m) => m,
        }
    }
}

impl Models {
    /// Keeps only the models named in `only` (all of them when `only` is empty). Every name
    /// must be a model the scene has; nothing changes on an error.
    pub fn keep_only<S: AsRef<str>>(&mut self, only: &[S]) -> Result<(), ModelSelectionError> {
        if only.is_empty() {
            return Ok(());
        }
        for m in only.iter().map(AsRef::as_ref) {
            let named = match m {
                "equivalent" => self.equivalent.is_some(),
                "traditional" => self.traditional.is_some(),
                "fine" => self.fine.is_some(),
                other => return Err(ModelSelectionError::Unknown(other.to_string())),
            };
            if !named {
                return Err(ModelSelectionError::Absent(m.to_string()));
            }
        }
        let keep = |m: &str| only.iter().any(|o| o.as_ref() == m);
        if !keep("equivalent") {
            self.equivalent = None;
        }
        if !keep("traditional") {
            self.traditional = None;
        }
        if !keep("fine") {
            self.fine = None;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{BeamModel, FineModel};

    fn all() -> Models {
        let beam = BeamModel {
            elements: 4,
            integration_points: None,
            mass_per_length: None,
            bending_stiffness: None,
            axial_stiffness: None,
        };
        Models {
            equivalent: Some(beam),
            traditional: Some(beam),
            fine: Some(FineModel {
                segments_per_wire: 8,
                penetration: 1e-3,
                bind_free_end: false,
            }),
        }
    }

    #[test]
    fn keeps_the_named_models_only() {
        let mut m = all();
        m.keep_only(&["fine", "equivalent"]).unwrap();
        assert!(m.equivalent.is_some() && m.fine.is_some() && m.traditional.is_none());
        let mut m = all();
        m.keep_only::<&str>(&[]).unwrap();
        assert_eq!(m, all());
    }

    #[test]
    fn rejects_unknown_and_absent_models_unchanged() {
        let mut m = all();
        let e = m.keep_only(&["equivalent", "tradition"]).unwrap_err();
        assert_eq!(e, ModelSelectionError::Unknown("tradition".into()));
        assert_eq!(m, all());
        m.fine = None;
        let e = m.keep_only(&["fine"]).unwrap_err();
        assert_eq!(e.model(), "fine");
        assert!(m.equivalent.is_some());
    }
}
