//! `validation/tolerances.json`: for every scene, the checks it runs, their tolerances and a
//! one-line justification of each.
//!
//! The file maps scene names to entries:
//!
//! ```json
//! { "paper-fig7-g8": { "quick": true,
//!     "checks": { "equivalent-vs-elastica": { "max": 2e-3, "rms": 1e-3, "tip": 2e-3,
//!                                             "why": "..." } } } }
//! ```
//!
//! Scene names must be files of `validation/`, check names must be known (see [`CheckSpec`]),
//! and every check must say `why`; anything else is an error that names the fault.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, bail};
use serde::{Deserialize, Serialize, de::DeserializeOwned};

/// Names of the checks a tolerance entry may list.
pub const CHECK_NAMES: [&str; 9] = [
    "equivalent-vs-elastica",
    "traditional-vs-elastica",
    "tension-vs-elastica",
    "energy-balance",
    "convergence-order",
    "time-step-order",
    "golden",
    "equivalent-vs-fine",
    "fine-bending",
];

/// Configuration distance limits (m) between two centrelines at equal material coordinate.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DistanceTol {
    /// Largest distance over s.
    pub max: f64,
    /// Root mean square distance over the integration points.
    pub rms: f64,
    /// Tip distance.
    pub tip: f64,
    /// Model against model in dynamics: largest difference of gravity's potential energy over
    /// the output times, relative to the largest kinetic energy (`equivalent-vs-fine` only):
    /// the weight times the position limit. The total is held to the two balances' limits,
    /// the other components are reported.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy: Option<f64>,
    /// Why these limits.
    pub why: String,
    /// Run this check in `--quick` (default: the scene's setting).
    #[serde(default)]
    pub quick: Option<bool>,
    /// `equivalent-vs-fine` only: the equivalent model of this comparison where it differs
    /// from the scene's (the paper scenes name the paper's base stiffness to reproduce its
    /// figures; the comparison with the fine model uses the corrected law).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub equivalent: Option<EquivalentVariant>,
}

/// The equivalent model of a comparison, changed from the scene's.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct EquivalentVariant {
    /// Number of elements.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    /// `section.base_stiffness` (`costello`, `foti`, `papailiou`, `paper`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_stiffness: Option<String>,
    /// Drop the scene's `section` options: the equivalent runs the project's default section
    /// law (Costello's K_min, the bonded stick stiffness, Papailiou's slip limit), where the
    /// scene names the paper's to reproduce its figures. `base_stiffness` still applies.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub default_section: bool,
}

impl EquivalentVariant {
    /// Changes the equivalent model of `file` as the variant says (the other models are left).
    pub fn apply(&self, file: &mut strand_scene::format::SceneFile) {
        if let (Some(eq), Some(n)) = (file.models.equivalent.as_mut(), self.elements) {
            eq.elements = n as i64;
        }
        if self.default_section {
            file.section = None;
        }
        if let Some(b) = &self.base_stiffness {
            file.section
                .get_or_insert_with(Default::default)
                .base_stiffness = Some(b.clone());
        }
    }
}

/// One tension value the paper reports.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TensionPoint {
    /// Material coordinate (m).
    pub x: f64,
    /// The paper's tension there (N).
    pub paper: f64,
}

/// The equivalent model's tension against the elastica's -q (L - s) sin(theta) of the same
/// section law: at points (the paper's Fig. 12, its values shown beside) and along the strand.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TensionTol {
    /// Largest relative error |T - T_elastica| / T_elastica at the points.
    pub relative: f64,
    /// Largest |T - T_elastica| / (q L) along the strand from `from` on.
    pub along: f64,
    /// Material coordinate from which the comparison along the strand runs (m).
    pub from: f64,
    /// The whole strand, root included, compared with the same `along` limit on a run of the
    /// equivalent model at this many elements: where the scene's mesh is too coarse at the
    /// strongly curved root for the limit, the mesh at which it holds there.
    #[serde(default)]
    pub root_elements: Option<usize>,
    /// The points, with the paper's values.
    pub points: Vec<TensionPoint>,
    /// Why this limit.
    pub why: String,
    /// Run this check in `--quick`.
    #[serde(default)]
    pub quick: Option<bool>,
}

/// Energy balance error relative to the largest kinetic energy.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EnergyTol {
    /// Largest relative balance error.
    pub relative: f64,
    /// Largest relative balance error of the fine model (its explicit integrator at its
    /// stable step); default `relative`.
    #[serde(default)]
    pub fine: Option<f64>,
    /// Largest relative balance error of the traditional beam (its constant law has no
    /// slip to book, so its bound is the step's error alone); default `relative`.
    #[serde(default)]
    pub traditional: Option<f64>,
    /// Models whose balance is an open claim (it holds at the scene's step and mesh but not
    /// under refinement): their rows are reported as open, neither pass nor fail.
    #[serde(default)]
    pub open: Option<OpenClaim>,
    /// Also run the equivalent model at half the scene's time step: its balance there must
    /// not exceed its balance at the scene's step (a balance that holds under refinement
    /// shows no growth), a row of its own.
    #[serde(default)]
    pub refined: Option<bool>,
    /// Why this limit.
    pub why: String,
    /// Run this check in `--quick`.
    #[serde(default)]
    pub quick: Option<bool>,
}

/// A check's claim that is not established for some models, and why.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OpenClaim {
    /// The models (`equivalent`, `traditional`, `fine`) whose rows are open.
    pub models: Vec<String>,
    /// Why the claim is open (what refinement shows).
    pub why: String,
}

/// Observed convergence order of the equivalent model's statics in elements.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ConvergenceTol {
    /// Element counts n, 2n, 4n (three, each doubling the previous).
    pub elements: Vec<usize>,
    /// Smallest acceptable observed order log2(e(2n) / e(4n)) of the largest distance.
    pub order: f64,
    /// Why this limit.
    pub why: String,
    /// Run this check in `--quick`.
    #[serde(default)]
    pub quick: Option<bool>,
}

/// Observed convergence order of the equivalent model's dynamics in the time step.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TimeStepTol {
    /// Time steps h, h/2, h/4 (s), each half the previous.
    pub time_steps: Vec<f64>,
    /// Smallest acceptable observed order log2(d(h, h/2) / d(h/2, h/4)), with d the largest
    /// tip distance over the output times between two runs.
    pub order: f64,
    /// Why this limit.
    pub why: String,
    /// Run this check in `--quick`.
    #[serde(default)]
    pub quick: Option<bool>,
}

/// Regression against the stored golden results.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GoldenTol {
    /// Largest position difference (m).
    pub position: f64,
    /// Largest energy difference (J, dynamics).
    pub energy: f64,
    /// Why these limits.
    pub why: String,
    /// Run this check in `--quick`.
    #[serde(default)]
    pub quick: Option<bool>,
}

/// The frictionless virtual bending test of the scene's strand (`strand_scene::run_bending`
/// with the penetration rule) at two meshes: the fine model's M / kappa against the sum of the
/// thin-rod K_min of the core and every wire (Costello's wire stiffness), and the section
/// law's moment at the same strain and curvature against the fine one.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FineBendingTol {
    /// Axial tension of the test (N).
    pub tension: f64,
    /// The one imposed curvature (1/m).
    pub curvature: f64,
    /// Strand length in pitches (at least 3).
    pub pitches: usize,
    /// Two meshes in segments per pitch, coarse then fine; the change between them is the
    /// finer one's mesh error.
    pub segments_per_pitch: Vec<usize>,
    /// Largest |K / K_min - 1| at the finer mesh plus the mesh error.
    pub k_min: f64,
    /// Largest |M_law / M - 1| at the finer mesh plus the change of that ratio between the
    /// meshes.
    pub law: f64,
    /// Largest change of M / kappa between the meshes, relative to the finer one.
    pub mesh: f64,
    /// Why these limits.
    pub why: String,
    /// Run this check in `--quick`.
    #[serde(default)]
    pub quick: Option<bool>,
}

/// A check of a scene with its tolerance.
#[derive(Debug, Clone, PartialEq)]
pub enum CheckSpec {
    /// Equivalent model statics against the elastica with the same section law.
    EquivalentVsElastica(DistanceTol),
    /// Traditional model statics against the elastica with constant EI.
    TraditionalVsElastica(DistanceTol),
    /// Equivalent model tension against the elastica's.
    TensionVsElastica(TensionTol),
    /// Energy balance of every model's dynamics.
    EnergyBalance(EnergyTol),
    /// Convergence order in elements of the equivalent model's statics.
    ConvergenceOrder(ConvergenceTol),
    /// Convergence order in the time step of the equivalent model's dynamics.
    TimeStepOrder(TimeStepTol),
    /// Regression against `golden/`.
    Golden(GoldenTol),
    /// Equivalent model against the fine model.
    EquivalentVsFine(DistanceTol),
    /// Frictionless fine bending against the thin-rod K_min and the section law.
    FineBending(FineBendingTol),
}

impl CheckSpec {
    /// The check's name in the tolerance file and the report.
    pub fn name(&self) -> &'static str {
        match self {
            CheckSpec::EquivalentVsElastica(_) => "equivalent-vs-elastica",
            CheckSpec::TraditionalVsElastica(_) => "traditional-vs-elastica",
            CheckSpec::TensionVsElastica(_) => "tension-vs-elastica",
            CheckSpec::EnergyBalance(_) => "energy-balance",
            CheckSpec::ConvergenceOrder(_) => "convergence-order",
            CheckSpec::TimeStepOrder(_) => "time-step-order",
            CheckSpec::Golden(_) => "golden",
            CheckSpec::EquivalentVsFine(_) => "equivalent-vs-fine",
            CheckSpec::FineBending(_) => "fine-bending",
        }
    }

    fn quick(&self) -> Option<bool> {
        match self {
            CheckSpec::EquivalentVsElastica(t)
            | CheckSpec::TraditionalVsElastica(t)
            | CheckSpec::EquivalentVsFine(t) => t.quick,
            CheckSpec::TensionVsElastica(t) => t.quick,
            CheckSpec::EnergyBalance(t) => t.quick,
            CheckSpec::ConvergenceOrder(t) => t.quick,
            CheckSpec::TimeStepOrder(t) => t.quick,
            CheckSpec::Golden(t) => t.quick,
            CheckSpec::FineBending(t) => t.quick,
        }
    }

    /// The one-line justification of the tolerance.
    pub fn why(&self) -> &str {
        match self {
            CheckSpec::EquivalentVsElastica(t)
            | CheckSpec::TraditionalVsElastica(t)
            | CheckSpec::EquivalentVsFine(t) => &t.why,
            CheckSpec::TensionVsElastica(t) => &t.why,
            CheckSpec::EnergyBalance(t) => &t.why,
            CheckSpec::ConvergenceOrder(t) => &t.why,
            CheckSpec::TimeStepOrder(t) => &t.why,
            CheckSpec::Golden(t) => &t.why,
            CheckSpec::FineBending(t) => &t.why,
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneEntryFile {
    #[serde(default)]
    quick: bool,
    checks: BTreeMap<String, serde_json::Value>,
}

/// The checks of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneEntry {
    /// Whether the scene belongs to the `--quick` subset.
    pub quick: bool,
    /// Its checks, in the order of [`CHECK_NAMES`].
    pub checks: Vec<CheckSpec>,
}

impl SceneEntry {
    /// The checks to run: all, or in `--quick` those of a quick scene not marked
    /// `"quick": false`.
    pub fn selected(&self, quick: bool) -> Vec<&CheckSpec> {
        self.checks
            .iter()
            .filter(|c| !quick || c.quick().unwrap_or(self.quick))
            .collect()
    }
}

/// The parsed tolerance file: scene name to its checks.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerances {
    /// Entries by scene name.
    pub scenes: BTreeMap<String, SceneEntry>,
}

fn typed<T: DeserializeOwned>(scene: &str, check: &str, v: serde_json::Value) -> anyhow::Result<T> {
    serde_json::from_value(v).with_context(|| format!("{scene}.checks.{check}"))
}

fn positive(value: f64, at: &str) -> anyhow::Result<()> {
    if !(value.is_finite() && value > 0.0) {
        bail!("{at}: must be a positive number, got {value}");
    }
    Ok(())
}

impl Tolerances {
    /// Parses `text`; `known_scenes` are the scene names found in `validation/`. Every known
    /// scene needs an entry, and every entry a known scene.
    pub fn parse(text: &str, known_scenes: &[String]) -> anyhow::Result<Tolerances> {
        let raw: BTreeMap<String, SceneEntryFile> =
            serde_json::from_str(text).context("parsing the tolerance file")?;
        let unknown: Vec<&String> = raw.keys().filter(|k| !known_scenes.contains(k)).collect();
        if !unknown.is_empty() {
            bail!(
                "unknown scene(s) in the tolerance file: {} (the scenes of validation/ are: {})",
                join(&unknown),
                known_scenes.join(", ")
            );
        }
        let missing: Vec<&String> = known_scenes
            .iter()
            .filter(|k| !raw.contains_key(*k))
            .collect();
        if !missing.is_empty() {
            bail!(
                "scene(s) without an entry in the tolerance file: {}",
                join(&missing)
            );
        }
        let mut scenes = BTreeMap::new();
        for (scene, entry) in raw {
            let mut checks = Vec::new();
            let bad: Vec<&String> = entry
                .checks
                .keys()
                .filter(|k| !CHECK_NAMES.contains(&k.as_str()))
                .collect();
            if !bad.is_empty() {
                bail!(
                    "{scene}: unknown check(s) {} (known: {})",
                    join(&bad),
                    CHECK_NAMES.join(", ")
                );
            }
            let mut by_name = entry.checks;
            for name in CHECK_NAMES {
                let Some(v) = by_name.remove(name) else {
                    continue;
                };
                let spec = match name {
                    "equivalent-vs-elastica" => {
                        CheckSpec::EquivalentVsElastica(typed(&scene, name, v)?)
                    }
                    "traditional-vs-elastica" => {
                        CheckSpec::TraditionalVsElastica(typed(&scene, name, v)?)
                    }
                    "tension-vs-elastica" => CheckSpec::TensionVsElastica(typed(&scene, name, v)?),
                    "energy-balance" => CheckSpec::EnergyBalance(typed(&scene, name, v)?),
                    "convergence-order" => CheckSpec::ConvergenceOrder(typed(&scene, name, v)?),
                    "time-step-order" => CheckSpec::TimeStepOrder(typed(&scene, name, v)?),
                    "golden" => CheckSpec::Golden(typed(&scene, name, v)?),
                    "equivalent-vs-fine" => CheckSpec::EquivalentVsFine(typed(&scene, name, v)?),
                    "fine-bending" => CheckSpec::FineBending(typed(&scene, name, v)?),
                    _ => unreachable!("names checked above"),
                };
                validate_spec(&scene, &spec)?;
                checks.push(spec);
            }
            scenes.insert(
                scene,
                SceneEntry {
                    quick: entry.quick,
                    checks,
                },
            );
        }
        Ok(Tolerances { scenes })
    }

    /// Reads and parses `path`.
    pub fn load(path: &Path, known_scenes: &[String]) -> anyhow::Result<Tolerances> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        Tolerances::parse(&text, known_scenes).with_context(|| format!("in {}", path.display()))
    }
}

fn validate_spec(scene: &str, spec: &CheckSpec) -> anyhow::Result<()> {
    let at = |f: &str| format!("{scene}.checks.{}.{f}", spec.name());
    if spec.why().trim().is_empty() {
        bail!("{}: must say why the tolerance is what it is", at("why"));
    }
    match spec {
        CheckSpec::EquivalentVsElastica(t)
        | CheckSpec::TraditionalVsElastica(t)
        | CheckSpec::EquivalentVsFine(t) => {
            positive(t.max, &at("max"))?;
            positive(t.rms, &at("rms"))?;
            positive(t.tip, &at("tip"))?;
            match (t.energy, spec) {
                (Some(e), CheckSpec::EquivalentVsFine(_)) => positive(e, &at("energy"))?,
                (Some(_), _) => bail!(
                    "{}: only equivalent-vs-fine compares energies",
                    at("energy")
                ),
                (None, _) => {}
            }
            match (&t.equivalent, spec) {
                (Some(v), CheckSpec::EquivalentVsFine(_)) => {
                    if v.elements == Some(0) {
                        bail!("{}: must be at least 1", at("equivalent.elements"));
                    }
                    if let Some(b) = &v.base_stiffness
                        && strand_core::BaseStiffness::from_name(b).is_none()
                    {
                        bail!(
                            "{}: unknown base stiffness `{b}`",
                            at("equivalent.base_stiffness")
                        );
                    }
                }
                (Some(_), _) => bail!(
                    "{}: only equivalent-vs-fine runs a variant of the equivalent model",
                    at("equivalent")
                ),
                (None, _) => {}
            }
        }
        CheckSpec::TensionVsElastica(t) => {
            positive(t.relative, &at("relative"))?;
            positive(t.along, &at("along"))?;
            if t.from.is_nan() || t.from < 0.0 {
                bail!("{}: must be zero or positive, got {}", at("from"), t.from);
            }
            if t.points.is_empty() {
                bail!("{}: needs at least one point", at("points"));
            }
            for (i, p) in t.points.iter().enumerate() {
                positive(p.paper, &at(&format!("points[{i}].paper")))?;
            }
        }
        CheckSpec::EnergyBalance(t) => positive(t.relative, &at("relative"))?,
        CheckSpec::ConvergenceOrder(t) => {
            positive(t.order, &at("order"))?;
            let e = &t.elements;
            if e.len() != 3 || e[0] == 0 || e[1] != 2 * e[0] || e[2] != 2 * e[1] {
                bail!(
                    "{}: must be three element counts n, 2n, 4n, got {e:?}",
                    at("elements")
                );
            }
        }
        CheckSpec::TimeStepOrder(t) => {
            positive(t.order, &at("order"))?;
            let h = &t.time_steps;
            let halves = |a: f64, b: f64| (a - 2.0 * b).abs() <= 1e-9 * a;
            if h.len() != 3
                || h[0].is_nan()
                || h[0] <= 0.0
                || !halves(h[0], h[1])
                || !halves(h[1], h[2])
            {
                bail!(
                    "{}: must be three time steps h, h/2, h/4 (s), got {h:?}",
                    at("time_steps")
                );
            }
        }
        CheckSpec::Golden(t) => {
            positive(t.position, &at("position"))?;
            positive(t.energy, &at("energy"))?;
        }
        CheckSpec::FineBending(t) => {
            positive(t.tension, &at("tension"))?;
            positive(t.curvature, &at("curvature"))?;
            positive(t.k_min, &at("k_min"))?;
            positive(t.law, &at("law"))?;
            positive(t.mesh, &at("mesh"))?;
            if t.pitches < 3 {
                bail!("{}: must be at least 3, got {}", at("pitches"), t.pitches);
            }
            let n = &t.segments_per_pitch;
            if n.len() != 2 || n[0] < 4 || n[1] <= n[0] {
                bail!(
                    "{}: must be two meshes, coarse then fine, each at least 4, got {n:?}",
                    at("segments_per_pitch")
                );
            }
        }
    }
    Ok(())
}

fn join(names: &[&String]) -> String {
    names
        .iter()
        .map(|s| format!("`{s}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenes() -> Vec<String> {
        vec!["a".into(), "b".into()]
    }

    const GOOD: &str = r#"{
        "a": { "quick": true, "checks": {
            "golden": { "position": 1e-6, "energy": 1e-6, "why": "round-off" },
            "equivalent-vs-fine": { "max": 1e-3, "rms": 1e-3, "tip": 1e-3, "why": "paper",
                                    "quick": false } } },
        "b": { "checks": { "energy-balance": { "relative": 1e-3, "why": "integrator" } } }
    }"#;

    #[test]
    fn parses_and_selects_the_quick_subset() {
        let t = Tolerances::parse(GOOD, &scenes()).unwrap();
        let a = &t.scenes["a"];
        assert_eq!(a.checks.len(), 2);
        let quick: Vec<_> = a.selected(true).iter().map(|c| c.name()).collect();
        assert_eq!(quick, ["golden"]);
        assert_eq!(a.selected(false).len(), 2);
        assert!(t.scenes["b"].selected(true).is_empty());
    }

    #[test]
    fn unknown_scene_and_check_names_are_named() {
        let more = vec!["a".into()];
        let e = Tolerances::parse(GOOD, &more).unwrap_err().to_string();
        assert!(e.contains("unknown scene(s)") && e.contains("`b`"), "{e}");
        let e = Tolerances::parse(GOOD, &["a".into(), "b".into(), "c".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("without an entry") && e.contains("`c`"), "{e}");
        let bad = GOOD.replace("energy-balance", "energy-balanse");
        let e = Tolerances::parse(&bad, &scenes()).unwrap_err().to_string();
        assert!(e.contains("b: unknown check(s) `energy-balanse`"), "{e}");
    }

    #[test]
    fn fields_are_checked_with_their_path() {
        let bad = GOOD.replace("\"relative\": 1e-3", "\"relativ\": 1e-3");
        let e = format!("{:#}", Tolerances::parse(&bad, &scenes()).unwrap_err());
        assert!(
            e.contains("b.checks.energy-balance") && e.contains("relativ"),
            "{e}"
        );
        let bad = GOOD.replace("\"why\": \"integrator\"", "\"why\": \" \"");
        let e = Tolerances::parse(&bad, &scenes()).unwrap_err().to_string();
        assert!(e.contains("b.checks.energy-balance.why"), "{e}");
    }

    /// The fine bending check needs two meshes, coarse then fine.
    #[test]
    fn fine_bending_meshes_are_checked() {
        let entry = |meshes: &str| {
            format!(
                r#"{{ "a": {{ "checks": {{ "fine-bending": {{ "tension": 0.1, "curvature": 0.1,
                "pitches": 3, "segments_per_pitch": {meshes}, "k_min": 1e-2, "law": 1e-2,
                "mesh": 2e-3, "why": "issue" }} }} }}, "b": {{ "checks": {{}} }} }}"#
            )
        };
        let t = Tolerances::parse(&entry("[8, 16]"), &scenes()).unwrap();
        assert_eq!(t.scenes["a"].checks[0].name(), "fine-bending");
        for bad in ["[16, 8]", "[8]", "[2, 8]"] {
            let e = Tolerances::parse(&entry(bad), &scenes())
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("a.checks.fine-bending.segments_per_pitch"),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn a_variant_of_the_equivalent_model_is_checked() {
        let with =
            |v: &str| GOOD.replace("\"why\": \"paper\",", &format!("\"why\": \"paper\", {v},"));
        let t = Tolerances::parse(
            &with(r#""equivalent": {"elements": 16, "base_stiffness": "costello"}"#),
            &scenes(),
        )
        .unwrap();
        let CheckSpec::EquivalentVsFine(f) = &t.scenes["a"].checks[1] else {
            panic!("{:?}", t.scenes["a"].checks);
        };
        let v = f.equivalent.as_ref().unwrap();
        assert_eq!(
            (v.elements, v.base_stiffness.as_deref(), v.default_section),
            (Some(16), Some("costello"), false)
        );
        let t = Tolerances::parse(
            &with(r#""equivalent": {"default_section": true}"#),
            &scenes(),
        )
        .unwrap();
        let CheckSpec::EquivalentVsFine(f) = &t.scenes["a"].checks[1] else {
            panic!("{:?}", t.scenes["a"].checks);
        };
        assert!(f.equivalent.as_ref().unwrap().default_section);
        let bad = with(r#""equivalent": {"base_stiffness": "cosine"}"#);
        let e = Tolerances::parse(&bad, &scenes()).unwrap_err().to_string();
        assert!(
            e.contains("a.checks.equivalent-vs-fine.equivalent.base_stiffness")
                && e.contains("cosine"),
            "{e}"
        );
        let bad = with(r#""equivalent": {"elements": 0}"#);
        let e = Tolerances::parse(&bad, &scenes()).unwrap_err().to_string();
        assert!(e.contains("equivalent.elements"), "{e}");
    }
}
