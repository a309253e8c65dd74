//! `cargo xtask validate`: runs the scenes of `validation/` on the shared runner
//! (`strand_scene::run_scene`), applies the checks their entry in
//! `validation/tolerances.json` names, prints one table and writes
//! `target/validation/report.{md,json}`.

pub mod bending;
pub mod checks;
pub mod compare;
pub mod golden;
pub mod machine;
pub mod quotes;
pub mod report;
pub mod results;
pub mod tolerances;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use strand_scene::format::SceneFile;
use strand_scene::{Analysis, RunOptions, RunSummary, Scene, run_scene};

use crate::book::pages::Page;
use crate::pareto::metrics::Tip;
use checks::BeamKind;
use machine::Provenance;
use report::{Report, Row};
use tolerances::{
    CheckSpec, ConvergenceTol, EnergyTol, EquivalentVariant, TimeStepTol, Tolerances,
};

/// Options of `cargo xtask validate`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ValidateArgs {
    /// Only the quick subset (what CI runs).
    #[arg(long)]
    pub quick: bool,
    /// Only this scene (its file name in validation/ without `.json`).
    #[arg(long, value_name = "NAME")]
    pub scene: Option<String>,
    /// Rewrite golden/ from this run's results (after reviewing them).
    #[arg(long)]
    pub bless: bool,
    /// Folder of the report and the runs [default: target/validation].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Developer check that the harness can fail: multiply every Young's modulus of the strand
    /// by FACTOR in the model runs (the references keep the scene's values).
    #[arg(long, value_name = "FACTOR")]
    pub perturb_stiffness: Option<f64>,
    /// Developer check that the comparison with the fine model can fail: run every
    /// equivalent model with this `section.base_stiffness` (`costello`, `foti`, `papailiou`,
    /// `paper`), over the scene's and the tolerance file's choice.
    #[arg(long, value_name = "NAME")]
    pub base_stiffness: Option<String>,
    /// Round-off sensitivity study: scale the gravity of every model run by (1 + N eps), eps
    /// the machine epsilon, so that the golden rows show how far a change of the last bits of
    /// an input moves each stored result (the argument of the golden tolerances).
    #[arg(long, value_name = "N")]
    pub perturb_gravity_ulps: Option<u32>,
    /// Also write the table into its page of the manual (docs/book/src/validation.md, between the
    /// `validate` markers); only for a full run.
    #[arg(long)]
    pub update_docs: bool,
}

/// The repository root (the parent of `xtask/`).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask/ has a parent")
        .to_path_buf()
}

/// Runs the validation and writes the report; the caller decides the exit status from
/// [`Report::failed`].
pub fn run(args: &ValidateArgs) -> anyhow::Result<Report> {
    if args.update_docs
        && (args.quick
            || args.scene.is_some()
            || args.perturb_stiffness.is_some()
            || args.perturb_gravity_ulps.is_some()
            || args.base_stiffness.is_some())
    {
        bail!(
            "--update-docs writes the manual's table from a full run: drop --quick, --scene, --perturb-stiffness, --perturb-gravity-ulps and --base-stiffness"
        );
    }
    let t0 = Instant::now();
    let root = repo_root();
    if let Some(f) = args.perturb_stiffness {
        if !(f.is_finite() && f > 0.0) {
            bail!("--perturb-stiffness: must be a positive factor, got {f}");
        }
        if args.bless {
            bail!("--bless with --perturb-stiffness would store a broken model; refused");
        }
    }
    if let Some(b) = &args.base_stiffness {
        if strand_core::BaseStiffness::from_name(b).is_none() {
            bail!(
                "--base-stiffness: unknown base stiffness `{b}` (costello, foti, papailiou, paper)"
            );
        }
        if args.bless {
            bail!("--bless with --base-stiffness would store another model; refused");
        }
    }
    if args.perturb_gravity_ulps.is_some() && args.bless {
        bail!("--bless with --perturb-gravity-ulps would store a perturbed scene; refused");
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join("validation"));
    let scenes = load_scenes(&root.join("validation"))?;
    let names: Vec<String> = scenes.keys().cloned().collect();
    let tolerances = Tolerances::load(&root.join("validation/tolerances.json"), &names)?;
    if let Some(s) = &args.scene
        && !scenes.contains_key(s)
    {
        bail!(
            "--scene {s}: no such scene in validation/ (scenes: {})",
            names.join(", ")
        );
    }
    let plan: Vec<(&Scene, Vec<&CheckSpec>)> = scenes
        .iter()
        .filter(|(name, _)| args.scene.as_ref().is_none_or(|s| s == *name))
        .map(|(name, scene)| (scene, tolerances.scenes[name].selected(args.quick)))
        .filter(|(_, checks)| !checks.is_empty())
        .collect();
    if plan.is_empty() {
        bail!("no checks selected (is the scene's entry marked quick?)");
    }
    let provenance = Provenance::detect(&root);
    let bar = progress_bar(plan.len());
    let mut rows = Vec::new();
    for (i, (scene, specs)) in plan.iter().enumerate() {
        let ctx = SceneRun {
            scene,
            args,
            out: out.join("runs").join(&scene.name),
            golden_dir: root.join("golden"),
            provenance: &provenance,
            bar: &bar,
            base: i as u64 * 1000,
            tag: format!("[{}/{}]", i + 1, plan.len()),
            balance: tolerances.scenes[&scene.name]
                .checks
                .iter()
                .find_map(|c| match c {
                    CheckSpec::EnergyBalance(t) => Some(compare::TotalLimit {
                        limit: t.relative + t.fine.unwrap_or(t.relative),
                        open: t
                            .open
                            .as_ref()
                            .filter(|o| o.models.iter().any(|m| m == "equivalent" || m == "fine"))
                            .map(|o| o.why.clone()),
                    }),
                    _ => None,
                }),
        };
        let r = ctx.validate(specs);
        for row in r.iter().filter(|r| r.status == report::Status::Fail) {
            bar.println(format!(
                "FAIL {} {} {}: {}",
                row.scene, row.check, row.metric, row.note
            ));
        }
        rows.extend(r);
    }
    bar.finish_and_clear();
    // Figures the `why` texts quote from this run's rows (not in a perturbed run: they quote
    // the unperturbed one).
    let perturbed = args.perturb_stiffness.is_some()
        || args.perturb_gravity_ulps.is_some()
        || args.base_stiffness.is_some();
    if !perturbed {
        let complete = !args.quick && args.scene.is_none();
        let stale = quotes::stale(&rows, complete);
        for row in &stale {
            eprintln!(
                "FAIL {} {} {}: {}",
                row.scene, row.check, row.metric, row.note
            );
        }
        rows.extend(stale);
    }
    let report = Report::new(provenance, args.quick, t0.elapsed().as_secs_f64(), rows);
    report.write(&out)?;
    if args.update_docs {
        crate::book::pages::update(Page::Validation, "validate", &report.docs())?;
    }
    Ok(report)
}

/// The scenes of `dir` (every `*.json` but `tolerances.json`), by file stem. A scene whose
/// `name` differs from its file name is an error.
fn load_scenes(dir: &Path) -> anyhow::Result<BTreeMap<String, Scene>> {
    let mut scenes = BTreeMap::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("listing {}", dir.display()))? {
        let path = entry?.path();
        if path.extension().is_none_or(|e| e != "json")
            || path.file_name().is_some_and(|n| n == "tolerances.json")
        {
            continue;
        }
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .context("scene file name is not UTF-8")?
            .to_string();
        let scene = Scene::load(&path).with_context(|| format!("{}", path.display()))?;
        if scene.name != stem {
            bail!(
                "{}: the scene is named `{}`; name it after its file",
                path.display(),
                scene.name
            );
        }
        scenes.insert(stem, scene);
    }
    Ok(scenes)
}

pub(crate) fn progress_bar(scenes: usize) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(
        Some(scenes as u64 * 1000),
        ProgressDrawTarget::stderr_with_hz(4),
    );
    bar.set_style(
        ProgressStyle::with_template("{elapsed:>4} [{bar:30}] {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar
}

/// `scene` with every Young's modulus multiplied by `factor`.
pub fn perturbed(scene: &Scene, factor: f64) -> anyhow::Result<Scene> {
    let mut file = scene.file.clone();
    file.strand.core.youngs_modulus *= factor;
    for l in &mut file.strand.layers {
        l.youngs_modulus *= factor;
    }
    Scene::from_file(file).context("perturbing the scene")
}

/// `scene` with its gravity scaled by (1 + `ulps` eps), eps the machine epsilon.
pub fn with_gravity_ulps(scene: &Scene, ulps: u32) -> anyhow::Result<Scene> {
    let mut file = scene.file.clone();
    let scale = 1.0 + f64::from(ulps) * f64::EPSILON;
    if let Some(g) = file.loads.as_mut().and_then(|l| l.gravity.as_mut()) {
        for v in g.iter_mut() {
            *v *= scale;
        }
    }
    Scene::from_file(file).context("perturbing the gravity")
}

/// `scene` with `section.base_stiffness` set to `name`.
pub fn with_base_stiffness(scene: &Scene, name: &str) -> anyhow::Result<Scene> {
    let mut file = scene.file.clone();
    file.section
        .get_or_insert_with(Default::default)
        .base_stiffness = Some(name.into());
    Scene::from_file(file).context("setting the base stiffness")
}

/// The validation of one scene.
struct SceneRun<'a> {
    scene: &'a Scene,
    args: &'a ValidateArgs,
    out: PathBuf,
    golden_dir: PathBuf,
    provenance: &'a Provenance,
    bar: &'a ProgressBar,
    base: u64,
    /// `[i/N]`: which scene of the plan this is.
    tag: String,
    /// The limit of a total-energy difference against the fine model: the equivalent's
    /// plus the fine model's energy-balance limit (relative to the largest kinetic energy),
    /// open when either is.
    balance: Option<compare::TotalLimit>,
}

impl SceneRun<'_> {
    /// `scene` perturbed as the developer options ask (itself without them).
    fn prepared(&self, scene: &Scene) -> anyhow::Result<Scene> {
        let scene = match self.args.perturb_stiffness {
            Some(f) => perturbed(scene, f)?,
            None => scene.clone(),
        };
        let scene = match &self.args.base_stiffness {
            Some(b) => with_base_stiffness(&scene, b)?,
            None => scene,
        };
        let scene = match self.args.perturb_gravity_ulps {
            Some(n) => with_gravity_ulps(&scene, n)?,
            None => scene,
        };
        Ok(scene)
    }

    /// Runs `scene` (perturbed if asked) into `dir` on the shared runner.
    fn run(&self, scene: &Scene, dir: &Path, label: &str) -> anyhow::Result<Vec<RunSummary>> {
        let scene = self.prepared(scene)?;
        let opts = RunOptions {
            out: dir.to_path_buf(),
            vtk: false,
        };
        let (bar, base, tag) = (self.bar, self.base, &self.tag);
        let mut progress = |model: &str, f: f64| {
            bar.set_message(format!("{tag} {label} {model}"));
            bar.set_position(base + (f.clamp(0.0, 1.0) * 999.0) as u64);
        };
        let summaries =
            run_scene(&scene, &opts, &mut progress).map_err(|e| anyhow::anyhow!("{e}"))?;
        // A model that failed fails the scene's checks, with the runner's reason.
        if let Some(e) = summaries.iter().find_map(|s| s.failure()) {
            anyhow::bail!("{e} (results so far in {})", dir.display());
        }
        Ok(summaries)
    }

    fn validate(&self, specs: &[&CheckSpec]) -> Vec<Row> {
        let name = self.scene.name.clone();
        // Results of an earlier validation must not stand in for a model this run skips.
        let run = match std::fs::remove_dir_all(&self.out) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                Err(anyhow::anyhow!("clearing {}: {e}", self.out.display()))
            }
            // The bending test builds its own fine model: a scene with only that check runs
            // no model of the runner.
            _ if specs.iter().all(|c| matches!(c, CheckSpec::FineBending(_))) => Ok(Vec::new()),
            _ => self.run(&self.models(false), &self.out, &name),
        };
        let mut summaries = match run {
            Ok(s) => s,
            Err(e) => {
                return specs
                    .iter()
                    .map(|c| Row::failed(&name, c.name(), "-", format!("run failed: {e:#}")))
                    .collect();
            }
        };
        // The fine model runs on its own, only for a comparison with it (the tolerance file
        // keeps the comparisons that take minutes out of the quick set); its failure fails
        // that comparison, not the beam checks.
        let wants_fine = specs
            .iter()
            .any(|c| matches!(c, CheckSpec::EquivalentVsFine(_)));
        let mut fine_error = None;
        if wants_fine && self.scene.models.fine.is_some() {
            match self.run(&self.models(true), &self.out, &name) {
                Ok(s) => summaries.extend(s),
                Err(e) => fine_error = Some(format!("{e:#}")),
            }
        }
        let fine_error = fine_error.as_deref();
        let mut rows = Vec::new();
        for spec in specs {
            let mut r = self.apply(spec, &summaries, fine_error);
            for row in &mut r {
                row.why = spec.why().to_string();
            }
            rows.extend(r);
        }
        rows
    }

    /// The rows of one check on the scene's run.
    fn apply(
        &self,
        spec: &CheckSpec,
        summaries: &[RunSummary],
        fine_error: Option<&str>,
    ) -> Vec<Row> {
        let name = self.scene.name.clone();
        let summary = |m: &str| summaries.iter().find(|s| s.model == m);
        let mut rows = Vec::new();
        match spec {
            CheckSpec::EquivalentVsElastica(t) | CheckSpec::TraditionalVsElastica(t) => {
                let kind = if matches!(spec, CheckSpec::EquivalentVsElastica(_)) {
                    BeamKind::Equivalent
                } else {
                    BeamKind::Traditional
                };
                let Some(s) = summary(kind.name()) else {
                    rows.push(Row::failed(
                        &name,
                        spec.name(),
                        "-",
                        format!("the scene does not run the {} model", kind.name()),
                    ));
                    return rows;
                };
                self.bar
                    .set_message(format!("{} {name} elastica reference", self.tag));
                let reference = checks::elastica(self.scene, kind);
                rows.extend(checks::against_elastica(
                    self.scene,
                    kind,
                    &self.out.join(kind.name()),
                    s.tip.unwrap_or([f64::NAN; 3]),
                    &reference,
                    t,
                ));
            }
            CheckSpec::TensionVsElastica(t) => {
                let reference = checks::elastica(self.scene, BeamKind::Equivalent);
                rows.extend(checks::tension_vs_elastica(
                    &name,
                    &self.out.join("equivalent"),
                    &reference,
                    t,
                ));
                if let Some(n) = t.root_elements {
                    rows.push(self.tension_at_the_root(&reference, t, n));
                }
            }
            CheckSpec::EnergyBalance(t) => {
                let dynamic: Vec<&RunSummary> = summaries
                    .iter()
                    .filter(|s| s.analysis == "dynamic")
                    .collect();
                if dynamic.is_empty() {
                    rows.push(Row::failed(
                        &name,
                        spec.name(),
                        "-",
                        "the scene runs no dynamic model",
                    ));
                }
                for s in dynamic {
                    let row = checks::energy_balance(
                        &name,
                        &s.model,
                        &self.out.join(&s.model),
                        s.energy_balance_relative,
                        t,
                    );
                    let half = (t.refined == Some(true) && s.model == "equivalent")
                        .then(|| self.balance_at_half_step(&row, t));
                    rows.push(row);
                    rows.extend(half);
                }
            }
            CheckSpec::ConvergenceOrder(t) => rows.extend(self.convergence(t)),
            CheckSpec::TimeStepOrder(t) => rows.extend(self.time_step_order(t)),
            CheckSpec::Golden(t) => {
                let length = self.scene.strand.length();
                let dynamic = matches!(self.scene.analysis, Analysis::Dynamic(_));
                let mut snaps = BTreeMap::new();
                let mut failed = Vec::new();
                // Golden files hold the beam models (the fine model runs in the full set only).
                for s in summaries.iter().filter(|s| s.model != "fine") {
                    match golden::ModelSnapshot::take(
                        &self.out.join(&s.model),
                        s.tip.unwrap_or([f64::NAN; 3]),
                        length,
                        dynamic,
                    ) {
                        Ok(snap) => {
                            snaps.insert(s.model.clone(), snap);
                        }
                        Err(e) => {
                            failed.push(Row::failed(&name, spec.name(), &s.model, format!("{e:#}")))
                        }
                    }
                }
                if !failed.is_empty() {
                    rows.extend(failed);
                    return rows;
                }
                if self.args.bless {
                    match golden::bless(&self.golden_dir, &name, self.provenance, t, snaps) {
                        Ok(p) => rows.push(Row::done(
                            &name,
                            spec.name(),
                            format!("blessed: wrote {}", p.display()),
                        )),
                        Err(e) => rows.push(Row::failed(&name, spec.name(), "-", format!("{e:#}"))),
                    }
                } else {
                    rows.extend(golden::compare(&self.golden_dir, &name, t, &snaps));
                }
            }
            CheckSpec::FineBending(t) => {
                self.bar
                    .set_message(format!("{} {name} fine bending", self.tag));
                match self.prepared(self.scene) {
                    Ok(model) => rows.extend(bending::rows(
                        self.scene,
                        &model,
                        t,
                        &self.out.join("fine-bending"),
                    )),
                    Err(e) => rows.push(Row::failed(&name, spec.name(), "-", format!("{e:#}"))),
                }
            }
            CheckSpec::EquivalentVsFine(t) => {
                if summary("equivalent").is_some() && summary("fine").is_some() {
                    let dynamic = matches!(self.scene.analysis, Analysis::Dynamic(_));
                    let equivalent = match &t.equivalent {
                        None => Ok(self.out.join("equivalent")),
                        Some(v) => self.equivalent_variant_for_fine(v),
                    };
                    match equivalent {
                        Ok(dir) => rows.extend(compare::rows(
                            &name,
                            spec.name(),
                            &dir,
                            &self.out.join("fine"),
                            dynamic,
                            t,
                            self.balance.as_ref(),
                        )),
                        Err(e) => rows.push(Row::failed(
                            &name,
                            spec.name(),
                            "-",
                            format!("equivalent variant: {e:#}"),
                        )),
                    }
                } else if let Some(e) = fine_error {
                    rows.push(Row::failed(
                        &name,
                        spec.name(),
                        "-",
                        format!("fine model: {e}"),
                    ));
                } else {
                    rows.push(Row::not_available(
                        &name,
                        spec.name(),
                        "the fine model runs in the full validation only (minutes per scene); \
                         this row is not a pass",
                    ));
                }
            }
        }
        rows
    }

    /// The scene with only its beam models (`fine` false) or only its fine model.
    fn models(&self, fine: bool) -> Scene {
        let mut scene = self.scene.clone();
        if fine {
            scene.models.equivalent = None;
            scene.models.traditional = None;
            scene.file.models.equivalent = None;
            scene.file.models.traditional = None;
        } else {
            scene.models.fine = None;
            scene.file.models.fine = None;
        }
        scene
    }

    /// Runs the scene with only its equivalent model, its file changed by `edit`, into `dir`:
    /// the variants of the convergence checks.
    fn run_equivalent_variant(
        &self,
        edit: impl FnOnce(&mut SceneFile),
        dir: &Path,
        label: &str,
    ) -> anyhow::Result<Vec<RunSummary>> {
        let mut file = self.scene.file.clone();
        if file.models.equivalent.is_none() {
            bail!("the scene has no equivalent model");
        }
        file.models.traditional = None;
        file.models.fine = None;
        edit(&mut file);
        let scene = Scene::from_file(file)?;
        self.run(&scene, dir, label)
    }

    /// The tension of the equivalent model at `n` elements against the elastica along the
    /// whole strand, root included (`TensionTol::root_elements`).
    fn tension_at_the_root(
        &self,
        reference: &Result<strand_elastica::Solution, String>,
        t: &tolerances::TensionTol,
        n: usize,
    ) -> Row {
        let name = &self.scene.name;
        let metric = format!("along from 0 at {n} elements");
        let fail = |why: String| Row::failed(name, "tension-vs-elastica", &metric, why);
        let r = match reference {
            Ok(r) => r,
            Err(e) => return fail(format!("reference: {e}")),
        };
        let dir = self.out.join("tension-root");
        let label = format!("{name} tension at {n} elements");
        let edit = |f: &mut SceneFile| {
            if let Some(eq) = f.models.equivalent.as_mut() {
                eq.elements = n as i64;
            }
        };
        if let Err(e) = self.run_equivalent_variant(edit, &dir, &label) {
            return fail(format!("{e:#}"));
        }
        match results::Centerline::load(&dir.join("equivalent")) {
            Ok(c) => checks::tension_along(name, &c, r, 0.0, t.along, &metric),
            Err(e) => fail(format!("{e:#}")),
        }
    }

    /// Runs the equivalent model of a comparison with the fine model, changed from the
    /// scene's as `v` says, into `vs-fine/`; returns its folder.
    fn equivalent_variant_for_fine(&self, v: &EquivalentVariant) -> anyhow::Result<PathBuf> {
        let dir = self.out.join("vs-fine");
        let label = format!("{} equivalent for the fine comparison", self.scene.name);
        self.run_equivalent_variant(|f: &mut SceneFile| v.apply(f), &dir, &label)?;
        Ok(dir.join("equivalent"))
    }

    /// Statics of the equivalent model with n, 2n, 4n elements against the elastica: the
    /// observed order of the largest distance between 2n and 4n.
    fn convergence(&self, t: &ConvergenceTol) -> Vec<Row> {
        const CHECK: &str = "convergence-order";
        let name = self.scene.name.clone();
        let fail = |why: String| vec![Row::failed(&name, CHECK, "order", why)];
        let reference = match checks::elastica(self.scene, BeamKind::Equivalent) {
            Ok(r) => r,
            Err(e) => return fail(format!("reference: {e}")),
        };
        let mut errors = Vec::new();
        for &n in &t.elements {
            let dir = self.out.join("convergence").join(format!("n{n}"));
            let label = format!("{name} convergence n={n}");
            let edit = |f: &mut SceneFile| {
                if let Some(eq) = f.models.equivalent.as_mut() {
                    eq.elements = n as i64;
                }
            };
            let summary = match self.run_equivalent_variant(edit, &dir, &label) {
                Ok(s) => s,
                Err(e) => return fail(format!("{n} elements: {e:#}")),
            };
            let c = match results::Centerline::load(&dir.join("equivalent")) {
                Ok(c) => c,
                Err(e) => return fail(format!("{e:#}")),
            };
            errors.push(checks::distance(
                &c,
                summary[0].tip.unwrap_or([f64::NAN; 3]),
                &reference,
            ));
        }
        let order = checks::observed_order(errors[1].max, errors[2].max);
        let e = &t.elements;
        vec![
            Row::measured(
                &name,
                CHECK,
                "order",
                order,
                "",
                report::Bound::AtLeast(t.order),
            )
            .with_note(format!(
                "largest distance to the elastica {:.2e}, {:.2e}, {:.2e} m (at s = {:.3}, \
                 {:.3}, {:.3} m) with {}, {}, {} elements; order {:.2} from the first pair",
                errors[0].max,
                errors[1].max,
                errors[2].max,
                errors[0].at,
                errors[1].at,
                errors[2].at,
                e[0],
                e[1],
                e[2],
                checks::observed_order(errors[0].max, errors[1].max)
            )),
        ]
    }

    /// The equivalent model's energy balance at half the scene's time step against its
    /// balance at the scene's step, `at_h` (`EnergyTol::refined`): no growth.
    fn balance_at_half_step(&self, at_h: &Row, t: &EnergyTol) -> Row {
        const CHECK: &str = "energy-balance";
        let name = self.scene.name.clone();
        let metric = "equivalent at h/2";
        let Some(h) = self.scene.file.analysis.time_step else {
            return Row::failed(&name, CHECK, metric, "the scene sets no time step to halve");
        };
        let Some(limit) = at_h.value else {
            return Row::failed(&name, CHECK, metric, "no balance at the scene's step");
        };
        let dir = self.out.join("energy-balance").join("half-step");
        let label = format!("{name} balance at time step {:e} s", 0.5 * h);
        let edit = |f: &mut SceneFile| f.analysis.time_step = Some(0.5 * h);
        let summaries = match self.run_equivalent_variant(edit, &dir, &label) {
            Ok(s) => s,
            Err(e) => return Row::failed(&name, CHECK, metric, format!("{e:#}")),
        };
        let every_step = summaries.first().and_then(|s| s.energy_balance_relative);
        let half =
            checks::energy_balance(&name, "equivalent", &dir.join("equivalent"), every_step, t);
        match half.value {
            Some(v) => Row::measured(&name, CHECK, metric, v, "", report::Bound::AtMost(limit))
                .with_note(format!(
                    "time step {:e} s: at most the balance at the scene's step {h:e} s, {limit:.3e} \
                     (no growth under refinement)",
                    0.5 * h
                )),
            None => Row::failed(&name, CHECK, metric, "no balance at h/2"),
        }
    }

    /// Dynamics of the equivalent model with time steps h, h/2, h/4: the observed order of
    /// the largest tip distance over the output times between successive runs (the finer
    /// run's tip interpolated at the coarser run's output times).
    fn time_step_order(&self, t: &TimeStepTol) -> Vec<Row> {
        const CHECK: &str = "time-step-order";
        let name = self.scene.name.clone();
        let fail = |why: String| vec![Row::failed(&name, CHECK, "order", why)];
        let mut tips = Vec::new();
        for &h in &t.time_steps {
            let dir = self.out.join("time-step-order").join(format!("h{h:e}"));
            let label = format!("{name} time step {h:e} s");
            let edit = |f: &mut SceneFile| f.analysis.time_step = Some(h);
            if let Err(e) = self.run_equivalent_variant(edit, &dir, &label) {
                return fail(format!("time step {h:e} s: {e:#}"));
            }
            match Tip::load(&dir.join("equivalent")) {
                Ok(tip) => tips.push(tip),
                Err(e) => return fail(format!("{e:#}")),
            }
        }
        let largest = |a: &Tip, b: &Tip| report::worst(a.distance_to(b).iter().map(|&(_, d)| d));
        let (d1, d2) = (largest(&tips[0], &tips[1]), largest(&tips[1], &tips[2]));
        let order = checks::observed_order(d1, d2);
        let h = &t.time_steps;
        vec![
            Row::measured(
                &name,
                CHECK,
                "order",
                order,
                "",
                report::Bound::AtLeast(t.order),
            )
            .with_note(format!(
                "largest tip distance over the output times {d1:.2e} m between time steps \
                 {:e} and {:e} s, {d2:.2e} m between {:e} and {:e} s",
                h[0], h[1], h[1], h[2]
            )),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(out: &str, perturb: Option<f64>) -> ValidateArgs {
        ValidateArgs {
            quick: true,
            scene: Some("paper-fig7-g10".into()),
            bless: false,
            out: Some(std::env::temp_dir().join(format!("xtask-{out}-{}", std::process::id()))),
            perturb_stiffness: perturb,
            base_stiffness: None,
            perturb_gravity_ulps: None,
            update_docs: false,
        }
    }

    fn failing_checks(report: &Report) -> Vec<&str> {
        report.failures().map(|r| r.check.as_str()).collect()
    }

    /// The harness can fail: 5 % stiffer wires in the model runs (not in the references) make
    /// the elastica checks fail by name, while the unperturbed scene passes them.
    #[test]
    fn a_five_percent_stiffness_error_is_caught_by_name() {
        let a = args("perturbed", Some(1.05));
        let report = run(&a).unwrap();
        let failed = failing_checks(&report);
        assert!(report.failed());
        assert!(
            failed.contains(&"equivalent-vs-elastica")
                && failed.contains(&"traditional-vs-elastica"),
            "{failed:?}"
        );
        let md = std::fs::read_to_string(a.out.as_ref().unwrap().join("report.md")).unwrap();
        assert!(md.contains("equivalent-vs-elastica max") && md.contains("FAIL"));

        let b = args("control", None);
        let report = run(&b).unwrap();
        let failed = failing_checks(&report);
        assert!(
            !failed.iter().any(|c| c.ends_with("-vs-elastica")),
            "unperturbed: {failed:?}"
        );
        for d in [a.out, b.out].into_iter().flatten() {
            std::fs::remove_dir_all(d).unwrap();
        }
    }

    /// The elastica limits are the beam's own discretisation error bounded by refinement (the
    /// sum of the changes over four meshes plus the finest one's Richardson error), so a
    /// 0.1 % stiffness error in the model runs fails `equivalent-vs-elastica` on each of the
    /// Fig. 7 and section-3 scenes (the unperturbed scenes pass in `validate --quick`).
    #[test]
    fn a_tenth_of_a_percent_stiffness_error_fails_the_elastica_limits() {
        // The rows each scene's `why` names: where the slip limit bounds the moment (g = 10,
        // 12) the stiffness matters less.
        let all: &[&str] = &["max", "rms", "tip"];
        for (scene, rows) in [
            ("paper-fig7-g8", all),
            ("paper-fig7-g10", &["rms", "tip"][..]),
            ("paper-fig7-g12", &["tip"][..]),
            ("paper-sec3-g8", all),
            ("paper-sec3-g10", all),
            ("paper-sec3-g12", all),
        ] {
            let mut a = args(&format!("tenth-percent-{scene}"), Some(1.001));
            a.scene = Some(scene.into());
            let report = run(&a).unwrap();
            let failed: Vec<&str> = report
                .failures()
                .filter(|r| r.check == "equivalent-vs-elastica")
                .map(|r| r.metric.as_str())
                .collect();
            for row in rows {
                assert!(failed.contains(row), "{scene}: {row} passes ({failed:?})");
            }
            std::fs::remove_dir_all(a.out.unwrap()).unwrap();
        }
    }

    /// The frictionless fine bending check of the 1+6+12 strand fails where its references
    /// are missed: a 2 % stiffness error in the models (the thin-rod K_min keeps the scene's
    /// moduli) fails the `k-min` row and only it; the paper's base stiffness in the law
    /// (2.9 % below the thin-rod sum on this strand) fails the `law` row and only it.
    #[test]
    fn the_fine_bending_check_fails_a_stiffness_error_and_the_paper_law() {
        for (tag, perturb, base, metric) in [
            ("bend-stiffer", Some(1.02), None, "k-min"),
            ("bend-paper", None, Some("paper"), "law"),
        ] {
            let mut a = args(tag, perturb);
            a.scene = Some("multilayer-1x19-frictionless".into());
            a.base_stiffness = base.map(String::from);
            let report = run(&a).unwrap();
            let failed: Vec<(&str, &str)> = report
                .failures()
                .map(|r| (r.check.as_str(), r.metric.as_str()))
                .collect();
            assert_eq!(failed, [("fine-bending", metric)], "{tag}");
            std::fs::remove_dir_all(a.out.unwrap()).unwrap();
        }
    }

    /// The comparisons with the fine model can fail: on the 30 deg strand, planar and bent out
    /// of its plane by a tip force (3D), the paper's base stiffness (K_min 12 % below
    /// Costello's) puts the equivalent's tip about 1e-3 m from the fine model's, ten times the
    /// tolerance (the unperturbed scenes pass in `validate --quick`).
    #[test]
    fn the_paper_base_stiffness_fails_the_comparison_with_the_fine_model() {
        for scene in ["vs-fine-30deg", "vs-fine-30deg-3d"] {
            let mut a = args(&format!("paper-base-{scene}"), None);
            a.scene = Some(scene.into());
            a.base_stiffness = Some("paper".into());
            let report = run(&a).unwrap();
            let failed: Vec<&str> = report.failures().map(|r| r.metric.as_str()).collect();
            assert!(
                report
                    .failures()
                    .all(|r| r.check == "equivalent-vs-fine" && r.value.is_some()),
                "{scene}: {failed:?}"
            );
            assert_eq!(failed, ["max", "rms", "tip"], "{scene}");
            std::fs::remove_dir_all(a.out.unwrap()).unwrap();
        }
    }

    #[test]
    fn unknown_scene_is_named() {
        let mut a = args("unknown", None);
        a.scene = Some("no-such-scene".into());
        let e = run(&a).unwrap_err().to_string();
        assert!(
            e.contains("no-such-scene") && e.contains("paper-fig7-g8"),
            "{e}"
        );
    }

    #[test]
    fn perturbation_scales_every_youngs_modulus() {
        let scenes = load_scenes(&repo_root().join("validation")).unwrap();
        let s = &scenes["paper-fig7-g8"];
        let p = perturbed(s, 1.05).unwrap();
        let (a, b) = (&s.file.strand, &p.file.strand);
        assert_eq!(b.core.youngs_modulus, a.core.youngs_modulus * 1.05);
        assert_eq!(
            b.layers[0].youngs_modulus,
            a.layers[0].youngs_modulus * 1.05
        );
        assert_eq!(b.core.density, a.core.density);
    }
}
