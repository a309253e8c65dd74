//! `cargo xtask pareto`: speed against error. A static and a dynamic scene, each run with the
//! equivalent model over element counts (and, in dynamics, integrators and time steps), the
//! traditional model and the fine model over segment counts; error against a converged
//! reference, median wall time of repeated runs, degrees of freedom; a table, a log-log plot
//! with the Pareto front, and the speed-up of the equivalent over the fine model at equal distance
//! to the reference (for the fine model mostly its modelling difference, not its error).
//!
//! References: statics, the elastica shooting solution with the scene's section law
//! (independent of every discretisation; SPEC 7); dynamics, the equivalent model with
//! [`REFERENCE_ELEMENTS`] elements and Stoermer-Verlet at its stable step (no independent
//! solution exists), whose own error is estimated by the run at half as many elements.

pub mod metrics;
mod report;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use indicatif::ProgressBar;
use strand_elastica::Solution;
use strand_scene::format::{BeamModelFile, FineModelFile, ModelsFile};
use strand_scene::{Analysis, Scene};

use crate::paper::{copy_to_docs, load_scene, run_into};
use crate::validate::checks::{self, BeamKind};
use crate::validate::machine::Provenance;
use crate::validate::report::worst;
use crate::validate::results::Centerline;
use crate::validate::{progress_bar, repo_root};
use metrics::{Tip, median};
use report::{CaseReport, ParetoReport};

/// A run longer than this (s) is timed once.
pub const LONG_RUN_S: f64 = 30.0;

fn s_wall(s: &Option<strand_scene::RunSummary>) -> f64 {
    s.as_ref().map_or(0.0, |s| s.wall_time_s)
}

/// Elements of the dynamic reference run.
pub const REFERENCE_ELEMENTS: usize = 128;

/// Options of `cargo xtask pareto`.
#[derive(Debug, Clone, clap::Args)]
pub struct ParetoArgs {
    /// Timed runs per configuration; the wall time is their median.
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// A few configurations, one run each (a smoke test, not a measurement).
    #[arg(long)]
    pub quick: bool,
    /// Folder of the table, the plots and the runs [default: target/pareto].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Segments per wire of the fine-model runs.
    #[arg(long, value_name = "N,N,...", value_delimiter = ',', default_values_t = [20, 40, 77])]
    pub fine_segments: Vec<usize>,
    /// Also copy the plots the README shows into docs/.
    #[arg(long)]
    pub update_docs: bool,
}

impl Default for ParetoArgs {
    fn default() -> Self {
        ParetoArgs {
            repeats: 3,
            quick: false,
            out: None,
            fine_segments: vec![20, 40, 77],
            update_docs: false,
        }
    }
}

/// Which model a configuration runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Model {
    /// The equivalent beam.
    Equivalent,
    /// The traditional beam.
    Traditional,
    /// The fine finite-segment model.
    Fine,
}

impl Model {
    /// Folder name of the model's results.
    pub fn name(self) -> &'static str {
        match self {
            Model::Equivalent => "equivalent",
            Model::Traditional => "traditional",
            Model::Fine => "fine",
        }
    }
}

/// One configuration to time.
#[derive(Debug, Clone)]
pub struct Config {
    /// Model.
    pub model: Model,
    /// Elements (beams) or segments per wire (fine).
    pub size: usize,
    /// `verlet` or `generalized-alpha` (dynamics).
    pub integrator: Option<String>,
    /// Time step (s); `None` is Verlet's estimated stable step.
    pub time_step: Option<f64>,
}

impl Config {
    /// Short label: model, size, integrator and step.
    pub fn label(&self) -> String {
        let unit = if self.model == Model::Fine {
            "seg/wire"
        } else {
            "el"
        };
        let mut s = format!("{} {} {unit}", self.model.name(), self.size);
        if self.model == Model::Fine {
            // The fine model integrates explicitly at its own stable step in dynamics.
            return s;
        }
        if let Some(i) = &self.integrator {
            s += &format!(", {i}");
            s += &match self.time_step {
                Some(h) => format!(" h={h:e}"),
                None => " stable h".into(),
            };
        }
        s
    }

    /// Family for the plot legend: model and integrator.
    pub fn family(&self) -> String {
        match &self.integrator {
            Some(i) if self.model == Model::Equivalent => format!("equivalent, {i}"),
            _ => self.model.name().into(),
        }
    }

    /// `base` running only this configuration.
    fn scene(&self, base: &Scene, output_interval: Option<f64>) -> anyhow::Result<Scene> {
        let mut file = base.file.clone();
        let beam = BeamModelFile {
            elements: self.size as i64,
            integration_points: None,
            mass_per_length: None,
        };
        file.models = match self.model {
            Model::Equivalent => ModelsFile {
                equivalent: Some(beam),
                ..Default::default()
            },
            Model::Traditional => ModelsFile {
                traditional: Some(beam),
                ..Default::default()
            },
            Model::Fine => {
                let mut fine = base.file.models.fine.clone().unwrap_or(FineModelFile {
                    segments_per_wire: 0,
                    penetration: None,
                    bind_free_end: None,
                });
                fine.segments_per_wire = self.size as i64;
                ModelsFile {
                    fine: Some(fine),
                    ..Default::default()
                }
            }
        };
        if let Some(i) = &self.integrator {
            file.analysis.integrator = Some(i.clone());
            file.analysis.time_step = self.time_step;
            if i != "generalized-alpha" {
                file.analysis.spectral_radius = None;
            }
            if output_interval.is_some() {
                file.analysis.output_interval = output_interval;
            }
        }
        Scene::from_file(file).with_context(|| format!("configuring {}", self.label()))
    }
}

/// The configurations of a scene.
fn plan(scene: &Scene, quick: bool, fine_sizes: &[usize]) -> Vec<Config> {
    let fine_sizes = if quick {
        &fine_sizes[..1.min(fine_sizes.len())]
    } else {
        fine_sizes
    };
    let beam = |model, size, integrator: Option<&str>, time_step| Config {
        model,
        size,
        integrator: integrator.map(String::from),
        time_step,
    };
    let mut out = Vec::new();
    match scene.analysis {
        Analysis::Static { .. } => {
            let els: &[usize] = if quick {
                &[4, 8]
            } else {
                &[4, 6, 8, 12, 16, 24, 32, 48, 64]
            };
            for &n in els {
                out.push(beam(Model::Equivalent, n, None, None));
            }
            for &n in if quick { &[8][..] } else { &[8, 16, 32] } {
                out.push(beam(Model::Traditional, n, None, None));
            }
            for &n in fine_sizes {
                out.push(beam(Model::Fine, n, None, None));
            }
        }
        Analysis::Dynamic(_) => {
            let els: &[usize] = if quick { &[8] } else { &[4, 8, 16, 32] };
            let steps: &[f64] = if quick {
                &[1e-3]
            } else {
                &[2e-3, 1e-3, 5e-4, 2.5e-4]
            };
            for &n in els {
                out.push(beam(Model::Equivalent, n, Some("verlet"), None));
                for &h in steps {
                    out.push(beam(
                        Model::Equivalent,
                        n,
                        Some("generalized-alpha"),
                        Some(h),
                    ));
                }
            }
            for &n in if quick { &[8][..] } else { &[8, 16, 32] } {
                out.push(beam(Model::Traditional, n, Some("verlet"), None));
            }
            let integrator = match scene.analysis {
                Analysis::Dynamic(d) => match d.integrator {
                    strand_scene::IntegratorKind::Verlet => "verlet",
                    strand_scene::IntegratorKind::GeneralizedAlpha => "generalized-alpha",
                },
                Analysis::Static { .. } => unreachable!(),
            };
            let h = match scene.analysis {
                Analysis::Dynamic(d) => d.time_step,
                Analysis::Static { .. } => None,
            };
            for &n in fine_sizes {
                out.push(beam(Model::Fine, n, Some(integrator), h));
            }
        }
    }
    out
}

/// The reference a scene's errors are measured against.
enum Reference {
    /// Statics: the elastica.
    Elastica(Box<Solution>),
    /// Dynamics: the tip trajectory of a converged run.
    Tip(Tip),
}

/// One timed configuration.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Point {
    /// Model.
    pub model: Model,
    /// Label.
    pub label: String,
    /// Legend family.
    pub family: String,
    /// Elements or segments per wire.
    pub size: usize,
    /// Degrees of freedom.
    pub dofs: usize,
    /// Load steps or time steps.
    pub steps: usize,
    /// Wall times of the solve, one per repeat (s).
    pub wall_times_s: Vec<f64>,
    /// Their median (s).
    pub wall_time_s: f64,
    /// Error against the reference (m); NaN when the run failed.
    pub error_m: f64,
    /// Whether the point is on the Pareto front.
    pub on_front: bool,
    /// Why the point has no error, if so.
    pub note: String,
}

/// Runs the comparison, writes the report and prints the headlines and the report's path.
pub fn run(args: &ParetoArgs) -> anyhow::Result<()> {
    let t0 = Instant::now();
    let root = repo_root();
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join("pareto"));
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    let provenance = Provenance::detect(&root);
    let repeats = if args.quick { 1 } else { args.repeats.max(1) };
    let scenes = [
        load_scene("paper-fig7-g8")?,
        load_scene("paper-fig8-clamped")?,
    ];
    let plans: Vec<Vec<Config>> = scenes
        .iter()
        .map(|s| plan(s, args.quick, &args.fine_segments))
        .collect();
    let total: usize = plans.iter().map(|p| p.len() * repeats + 2).sum();
    let bar = progress_bar(total);
    let mut tick = 0u64;
    let mut cases = Vec::new();
    for (scene, plan) in scenes.iter().zip(&plans) {
        let dir = out.join("runs").join(&scene.name);
        bar.set_message(format!("{} reference", scene.name));
        let (reference, reference_note) = reference(scene, &dir, &bar, &mut tick, args.quick)?;
        let mut points = Vec::new();
        let mut fine_missing: Option<String> = None;
        for c in plan {
            if c.model == Model::Fine
                && let Some(why) = &fine_missing
            {
                points.push(unavailable(c, why));
                tick += repeats as u64;
                continue;
            }
            let cfg_scene = c.scene(scene, None)?;
            let run_dir = dir.join(c.label().replace([' ', ',', '=', '/'], "_"));
            let mut times = Vec::new();
            let mut last = None;
            let mut failure = None;
            for r in 0..repeats {
                let label = format!("{} {} ({}/{repeats})", scene.name, c.label(), r + 1);
                let o = run_into(&cfg_scene, &run_dir, &bar, tick * 1000, &label)?;
                tick += 1;
                let o = o.into_iter().find(|o| o.model == c.model.name());
                match o.as_ref().and_then(|o| o.ok()) {
                    Some(s) => {
                        times.push(s.wall_time_s);
                        last = Some(s.clone());
                    }
                    None => {
                        failure = Some(o.map_or("the runner produced no result".into(), |o| {
                            o.error
                                .or(o.summary.and_then(|s| s.error))
                                .unwrap_or_else(|| "no reason given".into())
                        }));
                        break;
                    }
                }
                // A long run is timed once: its spread is small and the command stays short.
                if s_wall(&last) > LONG_RUN_S {
                    tick += (repeats - r - 1) as u64;
                    break;
                }
            }
            let Some(summary) = last else {
                let why = format!("failed: {}", failure.unwrap_or_default());
                if c.model == Model::Fine {
                    fine_missing = Some(format!(
                        "not available: not attempted after the {} run failed",
                        c.label()
                    ));
                }
                points.push(unavailable(c, &why));
                continue;
            };
            let model_dir = run_dir.join(c.model.name());
            let (error, mut note) =
                match measure(&reference, &model_dir, summary.tip.unwrap_or([f64::NAN; 3])) {
                    Ok(e) => (e, String::new()),
                    Err(e) => (f64::NAN, format!("{e:#}")),
                };
            if times.len() < repeats {
                note = format!("timed once (longer than {LONG_RUN_S} s) {note}");
            }
            points.push(Point {
                model: c.model,
                label: c.label(),
                family: c.family(),
                size: c.size,
                dofs: summary.dofs,
                steps: summary.steps,
                wall_time_s: median(&times),
                wall_times_s: times,
                error_m: error,
                on_front: false,
                note,
            });
        }
        let front = metrics::pareto_front(
            &points
                .iter()
                .map(|p| (p.wall_time_s, p.error_m))
                .collect::<Vec<_>>(),
        );
        for i in front {
            points[i].on_front = true;
        }
        cases.push(CaseReport::new(scene, reference_note, points));
    }
    bar.finish_and_clear();
    let report = ParetoReport {
        provenance,
        repeats,
        quick: args.quick,
        wall_time_s: t0.elapsed().as_secs_f64(),
        cases,
    };
    let path = report.write(&out)?;
    println!("{}", report.headlines().join("\n"));
    if args.update_docs {
        copy_to_docs(&out, &["pareto-static", "pareto-dynamic"])?;
    }
    println!("report: {}", path.display());
    Ok(())
}

fn unavailable(c: &Config, why: &str) -> Point {
    Point {
        model: c.model,
        label: c.label(),
        family: c.family(),
        size: c.size,
        dofs: 0,
        steps: 0,
        wall_times_s: Vec::new(),
        wall_time_s: f64::NAN,
        error_m: f64::NAN,
        on_front: false,
        note: why.to_string(),
    }
}

/// The reference of `scene` and a sentence on what it is and how good it is.
fn reference(
    scene: &Scene,
    dir: &std::path::Path,
    bar: &ProgressBar,
    tick: &mut u64,
    quick: bool,
) -> anyhow::Result<(Reference, String)> {
    match scene.analysis {
        Analysis::Static { .. } => {
            let r = checks::elastica(scene, BeamKind::Equivalent)
                .map_err(|e| anyhow::anyhow!("{}: elastica reference: {e}", scene.name))?;
            *tick += 2;
            let note = format!(
                "the elastica shooting solution with the scene's section law (SPEC 7; \
                 independent of every discretisation, its own position error estimate {:.1e} \
                 m), which the equivalent beam converges to as elements are added; the \
                 traditional and fine models differ from it by their modelling as well",
                r.error.position
            );
            Ok((Reference::Elastica(Box::new(r)), note))
        }
        Analysis::Dynamic(d) => {
            let n = if quick { 16 } else { REFERENCE_ELEMENTS };
            let config = |size| Config {
                model: Model::Equivalent,
                size,
                integrator: Some("verlet".into()),
                time_step: None,
            };
            // Frames 10x denser than the scene's for the interpolation of the reference.
            let interval = Some(d.output_interval / 10.0);
            let mut tips = Vec::new();
            for size in [n, n / 2] {
                let c = config(size);
                let sub = dir.join(format!("reference-{size}"));
                let label = format!("{} reference {}", scene.name, c.label());
                let o = run_into(&c.scene(scene, interval)?, &sub, bar, *tick * 1000, &label)?;
                *tick += 1;
                if o.iter().any(|o| o.ok().is_none()) {
                    anyhow::bail!("{label}: the reference run failed: {:?}", o[0].error);
                }
                tips.push(Tip::load(&sub.join("equivalent"))?);
            }
            let self_error = worst(tips[1].distance_to(&tips[0]).iter().map(|p| p.1));
            let note = format!(
                "the equivalent model with {n} elements, Stoermer-Verlet at its estimated stable \
                 step, frames every {:.0e} s, interpolated by cubic Hermite at each run's output \
                 times. Error = largest tip distance over the output times. Its own error, \
                 estimated by the {} element run: {self_error:.1e} m. The traditional and fine \
                 models differ from it by their modelling as well",
                d.output_interval / 10.0,
                n / 2
            );
            Ok((Reference::Tip(tips.swap_remove(0)), note))
        }
    }
}

/// Error of the run in `dir` against the reference (m).
fn measure(reference: &Reference, dir: &std::path::Path, tip: [f64; 3]) -> anyhow::Result<f64> {
    match reference {
        Reference::Elastica(r) => Ok(checks::distance(&Centerline::load(dir)?, tip, r).max),
        Reference::Tip(r) => {
            let d = Tip::load(dir)?.distance_to(r);
            if d.is_empty() {
                anyhow::bail!("no output time inside the reference's span");
            }
            Ok(worst(d.iter().map(|p| p.1)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each configuration runs only its model, with its size, integrator and step.
    #[test]
    fn configurations_run_one_model_each() {
        let scene = load_scene("paper-fig8-clamped").unwrap();
        let plan = plan(&scene, false, &[20, 40, 77]);
        assert!(plan.iter().any(|c| c.model == Model::Fine && c.size == 77));
        let ga = plan
            .iter()
            .find(|c| c.integrator.as_deref() == Some("generalized-alpha"))
            .unwrap();
        let s = ga.scene(&scene, None).unwrap();
        assert!(s.models.traditional.is_none() && s.models.fine.is_none());
        assert_eq!(s.models.equivalent.unwrap().elements, ga.size);
        let Analysis::Dynamic(d) = s.analysis else {
            panic!("dynamic")
        };
        assert_eq!(d.time_step, ga.time_step);
        let verlet = plan
            .iter()
            .find(|c| c.integrator.as_deref() == Some("verlet"))
            .unwrap();
        let Analysis::Dynamic(d) = verlet.scene(&scene, Some(1e-3)).unwrap().analysis else {
            panic!("dynamic")
        };
        assert_eq!(
            (d.integrator, d.time_step, d.output_interval),
            (strand_scene::IntegratorKind::Verlet, None, 1e-3)
        );
        let fine = plan.iter().find(|c| c.model == Model::Fine).unwrap();
        let s = fine.scene(&scene, None).unwrap();
        assert_eq!(s.models.fine.unwrap().segments_per_wire, fine.size);
        assert!(s.models.equivalent.is_none());
        assert_eq!(fine.label(), "fine 20 seg/wire");
    }
}
