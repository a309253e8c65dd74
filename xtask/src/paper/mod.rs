//! `cargo xtask paper`: runs the paper's scenes (SPEC 8) on the shared runner
//! (`strand_scene::run_scene`), draws Figs. 7-15 as PNG and SVG and writes
//! `target/paper/report.{md,json}` with our numbers beside the paper's statements.

mod dynamics;
mod fine;
pub mod report;
mod statics;

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use indicatif::ProgressBar;
use strand_scene::{RunOptions, RunSummary, Scene, run_scene};

use crate::validate::machine::Provenance;
use crate::validate::{progress_bar, repo_root};
use report::{Finding, PaperReport};
use strand_plot::{self as plot, Chart};

/// Options of `cargo xtask paper`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct PaperArgs {
    /// Folder of the figures, the report and the runs [default: target/paper].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Also write the findings table into the manual (docs/book/src/validation.md, between
    /// the `paper` markers) and copy the figures it shows into docs/book/src/figures/.
    #[arg(long)]
    pub update_docs: bool,
}

/// The figures the manual shows (file stems in the output folder).
const DOCS_FIGURES: [&str; 3] = ["fig09-shapes", "fig10-stiffness", "fig14-tip"];

/// What became of one model of a scene.
#[derive(Debug, Clone)]
pub(crate) struct Outcome {
    /// Model name (its folder).
    pub model: String,
    /// The run's summary when the runner returned one.
    pub summary: Option<RunSummary>,
    /// Why the model has no result: the runner's error.
    pub error: Option<String>,
}

impl Outcome {
    /// The summary of a run that finished.
    pub fn ok(&self) -> Option<&RunSummary> {
        self.summary.as_ref().filter(|s| s.status == "ok")
    }
}

/// A scene's run: its folder and what became of each model it names.
pub(crate) struct SceneRun {
    /// The scene.
    pub scene: Scene,
    /// Folder with one sub-folder per model.
    pub dir: PathBuf,
    /// One outcome per model the scene names.
    pub outcomes: Vec<Outcome>,
}

impl SceneRun {
    /// The folder of `model` if it ran and finished, else why not.
    pub fn model(&self, model: &str) -> Result<PathBuf, String> {
        match self.outcomes.iter().find(|o| o.model == model) {
            Some(o) if o.ok().is_some() => Ok(self.dir.join(model)),
            Some(o) => Err(format!(
                "the {model} model did not finish: {}",
                o.error
                    .as_deref()
                    .or(o.summary.as_ref().and_then(|s| s.error.as_deref()))
                    .unwrap_or("no reason given")
            )),
            None => Err(format!("the scene does not run the {model} model")),
        }
    }
}

/// The models `scene` names, in the runner's order.
fn named_models(scene: &Scene) -> Vec<&'static str> {
    let m = &scene.file.models;
    [
        ("equivalent", m.equivalent.is_some()),
        ("traditional", m.traditional.is_some()),
        ("fine", m.fine.is_some()),
    ]
    .into_iter()
    .filter_map(|(n, on)| on.then_some(n))
    .collect()
}

/// Runs each model of `scene` on its own into `dir` (cleared first, so that no earlier result
/// stands in for a model this run skips), so that one model's failure keeps the others'
/// results; reports progress on `bar` from `base` to `base + 999`.
pub(crate) fn run_into(
    scene: &Scene,
    dir: &Path,
    bar: &ProgressBar,
    base: u64,
    label: &str,
) -> anyhow::Result<Vec<Outcome>> {
    match std::fs::remove_dir_all(dir) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            return Err(e).with_context(|| format!("clearing {}", dir.display()));
        }
        _ => {}
    }
    let opts = RunOptions {
        out: dir.to_path_buf(),
        vtk: false,
    };
    let models = named_models(scene);
    let mut out = Vec::new();
    for (k, model) in models.iter().enumerate() {
        let mut file = scene.file.clone();
        if *model != "equivalent" {
            file.models.equivalent = None;
        }
        if *model != "traditional" {
            file.models.traditional = None;
        }
        if *model != "fine" {
            file.models.fine = None;
        }
        let single = Scene::from_file(file).with_context(|| format!("{label}: {model}"))?;
        let n = models.len() as f64;
        let mut progress = |m: &str, f: f64| {
            bar.set_message(format!("{label} {m}"));
            let done = (k as f64 + f.clamp(0.0, 1.0)) / n;
            bar.set_position(base + (done * 999.0) as u64);
        };
        out.push(match run_scene(&single, &opts, &mut progress) {
            Ok(mut s) => {
                let summary = s.pop();
                let error = summary
                    .as_ref()
                    .and_then(|s| s.failure())
                    .map(|e| format!("{e} (results so far in {})", dir.join(model).display()));
                Outcome {
                    model: model.to_string(),
                    summary,
                    error,
                }
            }
            Err(e) => Outcome {
                model: model.to_string(),
                summary: None,
                error: Some(e.to_string()),
            },
        });
    }
    Ok(out)
}

/// Output folder, progress and the figures written so far.
pub(crate) struct Figures {
    /// Output folder.
    pub out: PathBuf,
    /// (title, files relative to `out`).
    pub written: Vec<(String, Vec<String>)>,
}

impl Figures {
    /// Draws `chart` as `out/stem.{png,svg}`.
    pub fn save(&mut self, stem: &str, chart: &Chart) -> anyhow::Result<()> {
        let files = plot::save(chart, &self.out, stem)?;
        self.written.push((
            chart.title.clone(),
            files
                .iter()
                .filter_map(|f| f.file_name().map(|n| n.to_string_lossy().into_owned()))
                .collect(),
        ));
        Ok(())
    }
}

/// The scene `validation/NAME.json`.
pub(crate) fn load_scene(name: &str) -> anyhow::Result<Scene> {
    let path = repo_root().join("validation").join(format!("{name}.json"));
    Scene::load(&path).with_context(|| format!("{}", path.display()))
}

/// Runs the paper's scenes, draws the figures, writes the report and prints its path.
pub fn run(args: &PaperArgs) -> anyhow::Result<()> {
    let t0 = Instant::now();
    let root = repo_root();
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join("paper"));
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    let provenance = Provenance::detect(&root);
    let names = [
        "paper-sec3-g8",
        "paper-sec3-g10",
        "paper-sec3-g12",
        "paper-fig14-pendulum",
        "paper-fig7-g8",
        "paper-fig7-g10",
        "paper-fig7-g12",
        "paper-fig8-clamped",
        "paper-fig8-pinned",
    ];
    let bar = progress_bar(names.len());
    let mut runs = Vec::new();
    for (i, name) in names.iter().enumerate() {
        let scene = load_scene(name)?;
        let dir = out.join("runs").join(name);
        let label = format!("[{}/{}] {name}", i + 1, names.len());
        let outcomes = run_into(&scene, &dir, &bar, i as u64 * 1000, &label)?;
        runs.push(SceneRun {
            scene,
            dir,
            outcomes,
        });
        for o in &runs[i].outcomes {
            if let Err(why) = runs[i].model(&o.model) {
                bar.println(format!("{name}: {why}"));
            }
        }
    }
    bar.set_message("figures");
    let mut figs = Figures {
        out: out.clone(),
        written: Vec::new(),
    };
    let mut findings: Vec<Finding> = Vec::new();
    let by_name = |n: &str| runs.iter().find(|r| r.scene.name == n).expect("ran");
    let fig7: Vec<&SceneRun> = ["paper-fig7-g8", "paper-fig7-g10", "paper-fig7-g12"]
        .iter()
        .map(|n| by_name(n))
        .collect();
    let fig8: Vec<&SceneRun> = ["paper-fig8-clamped", "paper-fig8-pinned"]
        .iter()
        .map(|n| by_name(n))
        .collect();
    let sec3: Vec<&SceneRun> = ["paper-sec3-g8", "paper-sec3-g10", "paper-sec3-g12"]
        .iter()
        .map(|n| by_name(n))
        .collect();
    findings.extend(fine::fig7(&fig7, &mut figs)?);
    findings.extend(fine::fig8(&fig8, &mut figs)?);
    findings.extend(statics::figures(&sec3, &mut figs)?);
    findings.extend(dynamics::figures(
        by_name("paper-fig14-pendulum"),
        &mut figs,
    )?);
    bar.finish_and_clear();
    let report = PaperReport {
        provenance,
        wall_time_s: t0.elapsed().as_secs_f64(),
        findings,
        figures: figs.written,
    };
    let files = report.write(&out)?;
    if args.update_docs {
        crate::book::pages::copy_figures(&out, &DOCS_FIGURES)?;
        crate::book::pages::update(
            crate::book::pages::Page::Validation,
            "paper",
            &report.docs(),
        )?;
    }
    println!("report: {}", files[0].display());
    Ok(())
}
