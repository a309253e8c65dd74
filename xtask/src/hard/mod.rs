//! `cargo xtask hard`: the hard cases of SPEC 10 (numerical stability, clear failure, bad
//! input). Each case runs its scenes of `validation/hard/` on the shared runner
//! (`strand_scene::run_scene`) or, where it needs finer access (stable-step bisection,
//! curvature history, kinematic states), on the strand-ancf API with the beam the runner
//! builds (`strand_scene::build_beam`); it judges what it measured against the limits of
//! `validation/hard/criteria.json`, prints one table and writes `target/hard/report.{md,json}`.
//!
//! The `--quick` cases also run as tests of this crate (`cargo test --release -p xtask`), from
//! the same code and criteria.

mod cases;
pub mod criteria;
pub mod probe;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use strand_scene::Scene;

use crate::validate::machine::Provenance;
use crate::validate::repo_root;
use crate::validate::report::{Bound, Report, Row};
use criteria::{CaseCriteria, Criteria};

/// Options of `cargo xtask hard`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct HardArgs {
    /// Only the quick cases (those the test suite also runs).
    #[arg(long)]
    pub quick: bool,
    /// Only this case (see validation/hard/criteria.json).
    #[arg(long, value_name = "NAME")]
    pub case: Option<String>,
    /// Folder of the report and the runs [default: target/hard].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Also write the table into its page of the manual (docs/book/src/validation.md, between the
    /// `hard` markers); only for a full run.
    #[arg(long)]
    pub update_docs: bool,
}

/// A case: it measures and returns its rows (judged with [`Ctx::check`]).
type CaseFn = fn(&Ctx) -> anyhow::Result<Vec<Row>>;

/// Every hard case, in the order of the table.
pub const CASES: &[(&str, CaseFn)] = &[
    ("steel-generalized-alpha", cases::steel_generalized_alpha),
    ("steel-verlet-forced-step", cases::steel_verlet_forced_step),
    ("steel-verlet-stable-step", cases::steel_verlet_stable_step),
    ("stable-step-bisection-64", cases::stable_step_bisection_64),
    ("fine-mesh-64", cases::fine_mesh_64),
    ("fine-mesh-128", cases::fine_mesh_128),
    ("fine-mesh-256", cases::fine_mesh_256),
    ("whip-pendulum", cases::whip_pendulum),
    ("stick-slip-chatter", cases::stick_slip_chatter),
    ("hysteretic-loop-area", cases::hysteretic_loop_area),
    ("compression-zero-tension", cases::compression_zero_tension),
    ("near-straight", cases::near_straight),
    ("rigid-rotation", cases::rigid_rotation),
    ("sudden-gravity", cases::sudden_gravity),
    ("long-run-100s", cases::long_run_100s),
    ("paper-law-statics", cases::paper_law_statics),
    ("non-finite-stop", cases::non_finite_stop),
    ("bad-input", cases::bad_input),
    ("spinning-whip", cases::spinning_whip),
    ("folded-strand", cases::folded_strand),
    ("tilted-pendulum", cases::tilted_pendulum),
];

fn names() -> Vec<&'static str> {
    CASES.iter().map(|(n, _)| *n).collect()
}

/// What a case sees: its criteria, its output folder, the scenes and the progress bar.
pub struct Ctx<'a> {
    /// Case name.
    pub name: &'static str,
    /// Its criteria.
    pub criteria: &'a CaseCriteria,
    /// Folder for its runs.
    pub out: PathBuf,
    scenes: &'a BTreeMap<String, Scene>,
    bar: &'a ProgressBar,
    base: u64,
    tag: String,
}

impl Ctx<'_> {
    /// The scene `validation/hard/<name>.json`.
    pub fn scene(&self, name: &str) -> anyhow::Result<Scene> {
        self.scenes
            .get(name)
            .cloned()
            .with_context(|| format!("no scene validation/hard/{name}.json"))
    }

    /// A row judged against the limit `key` of this case.
    pub fn check(&self, key: &str, value: f64, unit: &'static str) -> anyhow::Result<Row> {
        let limit = self.criteria.limits.get(key).with_context(|| {
            format!(
                "validation/hard/criteria.json: the case `{}` has no limit `{key}`",
                self.name
            )
        })?;
        let mut row = Row::measured(self.name, key, "-", value, unit, limit.bound());
        if let Some(open) = &limit.open {
            row = row.opened(open);
        }
        row.why = limit.why.clone();
        Ok(row)
    }

    /// A reported value without a limit.
    pub fn report(&self, key: &str, value: f64, unit: &'static str) -> Row {
        Row::measured(self.name, key, "-", value, unit, Bound::None)
    }

    /// Shows `what` and the fraction `f` done of this case on the progress bar.
    pub fn progress(&self, what: &str, f: f64) {
        self.bar
            .set_message(format!("{} {} {what}", self.tag, self.name));
        self.bar
            .set_position(self.base + (f.clamp(0.0, 1.0) * 999.0) as u64);
    }
}

/// The scenes of `validation/hard/`, by file stem (each named after its file).
fn load_scenes(dir: &Path) -> anyhow::Result<BTreeMap<String, Scene>> {
    let mut scenes = BTreeMap::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("listing {}", dir.display()))? {
        let path = entry?.path();
        if path.extension().is_none_or(|e| e != "json")
            || path.file_name().is_some_and(|n| n == "criteria.json")
        {
            continue;
        }
        let scene = Scene::load(&path).with_context(|| format!("{}", path.display()))?;
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        if scene.name != stem {
            bail!(
                "{}: the scene is named `{}`; name it after its file",
                path.display(),
                scene.name
            );
        }
        scenes.insert(stem.to_string(), scene);
    }
    Ok(scenes)
}

/// Runs the selected cases and writes the report; the caller decides the exit status.
pub fn run(args: &HardArgs) -> anyhow::Result<Report> {
    if args.update_docs && (args.quick || args.case.is_some()) {
        anyhow::bail!(
            "--update-docs writes the manual's table from a full run: drop --quick and --case"
        );
    }
    let t0 = Instant::now();
    let root = repo_root();
    let dir = root.join("validation").join("hard");
    let criteria = Criteria::load(&dir.join("criteria.json"), &names())?;
    let scenes = load_scenes(&dir)?;
    if let Some(c) = &args.case
        && !criteria.cases.contains_key(c)
    {
        bail!("--case {c}: no such case (cases: {})", names().join(", "));
    }
    let plan: Vec<&(&str, CaseFn)> = CASES
        .iter()
        .filter(|(n, _)| args.case.as_ref().is_none_or(|c| c == n))
        .filter(|(n, _)| args.case.is_some() || !args.quick || criteria.cases[*n].quick)
        .collect();
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join("hard"));
    let bar = ProgressBar::with_draw_target(
        Some(plan.len() as u64 * 1000),
        ProgressDrawTarget::stderr_with_hz(4),
    );
    bar.set_style(
        ProgressStyle::with_template("{elapsed:>4} [{bar:30}] {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    let mut rows = Vec::new();
    for (i, (name, case)) in plan.iter().enumerate() {
        let ctx = Ctx {
            name,
            criteria: &criteria.cases[*name],
            out: out.join("runs").join(name),
            scenes: &scenes,
            bar: &bar,
            base: i as u64 * 1000,
            tag: format!("[{}/{}]", i + 1, plan.len()),
        };
        ctx.progress("", 0.0);
        let t = Instant::now();
        let r = run_case(&ctx, *case);
        let line = format!(
            "{:<26} {:>7.1} s  {}",
            name,
            t.elapsed().as_secs_f64(),
            if r.iter()
                .any(|r| r.status == crate::validate::report::Status::Fail)
            {
                "FAIL"
            } else {
                "pass"
            }
        );
        // Without a terminal the bar is hidden, and so is its println: print the line itself.
        if bar.is_hidden() {
            eprintln!("{line}");
        } else {
            bar.println(line);
        }
        rows.extend(r);
    }
    bar.finish_and_clear();
    let report = Report::new(
        Provenance::detect(&root),
        args.quick,
        t0.elapsed().as_secs_f64(),
        rows,
    )
    .titled("Hard cases report", "case", "validation/hard/criteria.json");
    report.write(&out)?;
    if args.update_docs {
        crate::book::pages::update(crate::book::pages::Page::Validation, "hard", &report.docs())?;
    }
    Ok(report)
}

/// One case; an error or a panic becomes a failed row that says why.
fn run_case(ctx: &Ctx, case: CaseFn) -> Vec<Row> {
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| case(ctx)));
    match result {
        Ok(Ok(rows)) if !rows.is_empty() => rows,
        Ok(Ok(_)) => vec![Row::failed(ctx.name, "-", "-", "the case measured nothing")],
        Ok(Err(e)) => vec![Row::failed(ctx.name, "-", "-", format!("{e:#}"))],
        Err(p) => {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            vec![Row::failed(ctx.name, "-", "-", format!("panicked: {msg}"))]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validate::report::Status;

    /// Runs one case as `cargo xtask hard --case NAME` would and fails on any failed row.
    fn case(name: &str) {
        let args = HardArgs {
            quick: true,
            case: Some(name.into()),
            out: Some(
                std::env::temp_dir().join(format!("xtask-hard-{name}-{}", std::process::id())),
            ),
            update_docs: false,
        };
        let report = run(&args).unwrap();
        let failed: Vec<String> = report
            .rows
            .iter()
            .filter(|r| r.status == Status::Fail)
            .map(|r| format!("{} {}: {:?} {}", r.scene, r.check, r.value, r.note))
            .collect();
        assert!(failed.is_empty(), "{failed:#?}\n{}", report.table());
        std::fs::remove_dir_all(args.out.unwrap()).ok();
    }

    #[test]
    fn every_case_has_criteria_and_the_quick_ones_have_tests() {
        let c =
            Criteria::load(&repo_root().join("validation/hard/criteria.json"), &names()).unwrap();
        let quick: Vec<&String> = c
            .cases
            .iter()
            .filter(|(_, v)| v.quick)
            .map(|(k, _)| k)
            .collect();
        // Keep this list in step with the tests below.
        let tested = [
            "steel-generalized-alpha",
            "steel-verlet-forced-step",
            "stable-step-bisection-64",
            "whip-pendulum",
            "stick-slip-chatter",
            "hysteretic-loop-area",
            "compression-zero-tension",
            "near-straight",
            "rigid-rotation",
            "sudden-gravity",
            "paper-law-statics",
            "non-finite-stop",
            "bad-input",
            "spinning-whip",
            "folded-strand",
            "tilted-pendulum",
        ];
        for q in &quick {
            assert!(tested.contains(&q.as_str()), "quick case {q} has no test");
        }
        assert_eq!(quick.len(), tested.len());
    }

    #[test]
    fn steel_generalized_alpha() {
        case("steel-generalized-alpha");
    }
    #[test]
    fn steel_verlet_forced_step() {
        case("steel-verlet-forced-step");
    }
    #[test]
    fn stable_step_bisection_64() {
        case("stable-step-bisection-64");
    }
    #[test]
    fn whip_pendulum() {
        case("whip-pendulum");
    }
    #[test]
    fn stick_slip_chatter() {
        case("stick-slip-chatter");
    }
    #[test]
    fn hysteretic_loop_area() {
        case("hysteretic-loop-area");
    }
    #[test]
    fn compression_zero_tension() {
        case("compression-zero-tension");
    }
    #[test]
    fn near_straight() {
        case("near-straight");
    }
    #[test]
    fn rigid_rotation() {
        case("rigid-rotation");
    }
    #[test]
    fn sudden_gravity() {
        case("sudden-gravity");
    }
    #[test]
    fn paper_law_statics() {
        case("paper-law-statics");
    }
    #[test]
    fn non_finite_stop() {
        case("non-finite-stop");
    }
    #[test]
    fn bad_input() {
        case("bad-input");
    }
    /// The 3D cases (8, 3 and 26 s of wall time on the loaded 2-core machine).
    #[test]
    fn spinning_whip() {
        case("spinning-whip");
    }
    #[test]
    fn folded_strand() {
        case("folded-strand");
    }
    #[test]
    fn tilted_pendulum() {
        case("tilted-pendulum");
    }
}
