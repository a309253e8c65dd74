//! The pass criteria of the hard cases: `validation/hard/criteria.json`.
//!
//! One entry per case: what it checks (`what`), whether it belongs to the `--quick` subset,
//! and its named limits, each a `max` or a `min` with a one-line reason (`why`). The code of a
//! case looks its limits up by name, so a limit lives in one place.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, bail};
use serde::Deserialize;

use crate::validate::report::Bound;

/// One limit of a case.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limit {
    /// The measured value must not exceed this.
    #[serde(default)]
    pub max: Option<f64>,
    /// The measured value must reach this.
    #[serde(default)]
    pub min: Option<f64>,
    /// Why the limit is what it is.
    pub why: String,
    /// Set when the claim is not established (it holds at the case's discretisation but not
    /// under refinement): why. The row is then reported as open, neither pass nor fail.
    #[serde(default)]
    pub open: Option<String>,
}

impl Limit {
    /// The bound of the report row.
    pub fn bound(&self) -> Bound {
        match (self.max, self.min) {
            (Some(m), None) => Bound::AtMost(m),
            (None, Some(m)) => Bound::AtLeast(m),
            _ => Bound::None,
        }
    }
}

/// The criteria of one case.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseCriteria {
    /// What the case checks, in one or two sentences.
    pub what: String,
    /// Part of `cargo xtask hard --quick` (and of the test suite).
    pub quick: bool,
    /// The named limits.
    #[serde(default)]
    pub limits: BTreeMap<String, Limit>,
}

/// The whole criteria file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Criteria {
    /// What the file is.
    #[serde(rename = "_about")]
    pub about: String,
    /// Criteria by case name.
    pub cases: BTreeMap<String, CaseCriteria>,
}

impl Criteria {
    /// Reads `path` and checks that it names exactly the cases in `known`, each limit with
    /// exactly one of `max` and `min`.
    pub fn load(path: &Path, known: &[&str]) -> anyhow::Result<Criteria> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let c: Criteria =
            serde_json::from_str(&text).with_context(|| format!("parsing {}", path.display()))?;
        for k in known {
            if !c.cases.contains_key(*k) {
                bail!("{}: no entry for the case `{k}`", path.display());
            }
        }
        for (name, case) in &c.cases {
            if !known.contains(&name.as_str()) {
                bail!(
                    "{}: `{name}` is not a hard case (cases: {})",
                    path.display(),
                    known.join(", ")
                );
            }
            for (key, l) in &case.limits {
                let ok = match (l.max, l.min) {
                    (Some(v), None) | (None, Some(v)) => v.is_finite(),
                    _ => false,
                };
                if !ok {
                    bail!(
                        "{}: cases.{name}.limits.{key}: give exactly one finite `max` or `min`",
                        path.display()
                    );
                }
            }
        }
        Ok(c)
    }
}
