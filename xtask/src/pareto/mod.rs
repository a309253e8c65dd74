//! `cargo xtask pareto`: speed against error that means it. A static and a dynamic scene,
//! each run with the fine model refined in segments per wire (doubling), the equivalent model
//! refined in elements (and, in dynamics, time step) and the traditional model. Each run's
//! error is measured twice: against the converged fine model (the physics), and against its own
//! converged discretisation; a converged solution is the Richardson extrapolation of a
//! model's three finest runs (`strand_core::convergence`), shown with its estimated error.
//! The headline: the CPU time the equivalent model needs to come within a distance X of the
//! converged fine model, against the CPU time the fine model needs to come within the same X
//! of itself, with X stated and chosen above the equivalent's converged modelling difference.
//!
//! Scenes: statics, `vs-fine-12deg-friction` (a strand that is not the paper's, with friction,
//! 1.4 pitches long: the fine model converges in seconds to minutes per run); dynamics,
//! `paper-fig8-clamped` (the paper's pendulum, 0.5 s) with Costello's K_min, the default law.

pub mod metrics;
pub mod reference;
mod report;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use strand_scene::format::{BeamModelFile, FineModelFile, ModelsFile};
use strand_scene::{Analysis, Scene};

use crate::paper::{load_scene, run_into};
use crate::validate::machine::Provenance;
use crate::validate::{progress_bar, repo_root, with_base_stiffness};
use metrics::median;
use reference::{Converged, Grid, Sampled};
use report::{CaseReport, ParetoReport};

/// A run longer than this (s) is timed once.
pub const LONG_RUN_S: f64 = 10.0;

fn s_wall(s: &Option<strand_scene::RunSummary>) -> f64 {
    s.as_ref().map_or(0.0, |s| s.wall_time_s)
}

/// The static scene.
pub const STATIC_SCENE: &str = "vs-fine-12deg-friction";
/// The dynamic scene (run with Costello's K_min, the default; the file names the paper's).
pub const DYNAMIC_SCENE: &str = "paper-fig8-clamped";
/// Segments per pitch of the coarsest fine run, and the number of runs (each doubling), of
/// the static and the dynamic scene.
pub const FINE_LEVELS: [(f64, usize); 2] = [(5.0, 4), (2.5, 4)];
/// Stations along the strand of the static grid.
const STATIONS: usize = 400;

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
    /// The distance X (m) of the static headline [default: the smallest of 1, 2, 5 x 10^k
    /// at least twice the converged models' distance plus the fine reference's error].
    #[arg(long, value_name = "M")]
    pub target_static: Option<f64>,
    /// The distance X (m) of the dynamic headline [default: as for statics].
    #[arg(long, value_name = "M")]
    pub target_dynamic: Option<f64>,
    /// Also write the report into the manual (docs/book/src/performance.md, between the
    /// `pareto` markers) and copy its plots into docs/book/src/figures/.
    #[arg(long)]
    pub update_docs: bool,
}

impl Default for ParetoArgs {
    fn default() -> Self {
        ParetoArgs {
            repeats: 3,
            quick: false,
            out: None,
            target_static: None,
            target_dynamic: None,
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
            bending_stiffness: None,
            axial_stiffness: None,
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

/// The configurations of a scene: the fine model at `fine_sizes` segments per wire, the
/// equivalent model over elements (dynamics: generalized-alpha refined in elements and time
/// step together, Stoermer-Verlet at its stable step over elements), the traditional model.
fn plan(scene: &Scene, quick: bool, fine_sizes: &[usize]) -> Vec<Config> {
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
                &[4, 8, 16]
            } else {
                &[2, 4, 8, 16, 32, 64]
            };
            for &n in els {
                out.push(beam(Model::Equivalent, n, None, None));
            }
            for n in [4, 8, 16, 32] {
                out.push(beam(Model::Traditional, n, None, None));
            }
            for &n in fine_sizes {
                out.push(beam(Model::Fine, n, None, None));
            }
        }
        Analysis::Dynamic(_) => {
            let ga: &[(usize, f64)] = if quick {
                &[(4, 2e-3), (8, 1e-3), (16, 5e-4)]
            } else {
                &[
                    (4, 2e-3),
                    (8, 1e-3),
                    (16, 5e-4),
                    (32, 2.5e-4),
                    (64, 1.25e-4),
                ]
            };
            for &(n, h) in ga {
                out.push(beam(
                    Model::Equivalent,
                    n,
                    Some("generalized-alpha"),
                    Some(h),
                ));
            }
            for &n in if quick { &[8][..] } else { &[4, 8, 16, 32] } {
                out.push(beam(Model::Equivalent, n, Some("verlet"), None));
            }
            for n in [4, 8, 16, 32] {
                out.push(beam(Model::Traditional, n, Some("verlet"), None));
            }
            for &n in fine_sizes {
                // The fine model integrates explicitly at its own stable step.
                out.push(beam(Model::Fine, n, None, None));
            }
        }
    }
    out
}

/// Segments per wire of the fine runs: `per_pitch` segments per pitch rounded, doubled
/// `levels - 1` times.
pub fn fine_sizes(scene: &Scene, per_pitch: f64, levels: usize) -> Vec<usize> {
    let pitches = scene
        .strand
        .layers()
        .first()
        .map_or(1.0, |l| scene.strand.length() / l.pitch);
    let first = (per_pitch * pitches).round().max(2.0) as usize;
    (0..levels).map(|k| first << k).collect()
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
    /// Time step (s; dynamics of the beams with a fixed step).
    pub time_step: Option<f64>,
    /// Degrees of freedom.
    pub dofs: usize,
    /// Load steps or time steps.
    pub steps: usize,
    /// Wall times of the solve, one per repeat (s).
    pub wall_times_s: Vec<f64>,
    /// Their median (s).
    pub wall_time_s: f64,
    /// CPU times of the solve (process, all threads), one per repeat (s).
    pub cpu_times_s: Vec<f64>,
    /// Their median (s).
    pub cpu_time_s: f64,
    /// Largest distance to the converged fine model (m); NaN when not available.
    pub error_fine_m: f64,
    /// Largest distance to the model's own converged discretisation (m); NaN when not
    /// available.
    pub error_own_m: f64,
    /// Whether the point is on the Pareto front of CPU time against `error_fine_m`.
    pub on_front: bool,
    /// Why the point has no error, if so.
    pub note: String,
}

/// A converged solution of one model, for the report.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Limit {
    /// `fine`, `equivalent` or `traditional`.
    pub model: String,
    /// Where it comes from and its estimated error.
    pub description: String,
    /// The two observed orders of the extrapolation, coarse pair first.
    pub observed_orders: [f64; 2],
    /// The order used (NaN when the two observed orders do not agree: not extrapolated).
    pub order: f64,
    /// Estimated error of the finest run (m).
    pub finest_error_m: f64,
    /// Largest distance to the converged fine model (m): the modelling difference.
    pub distance_to_fine_m: f64,
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
        load_scene(STATIC_SCENE)?,
        with_base_stiffness(&load_scene(DYNAMIC_SCENE)?, "costello")?,
    ];
    let targets = [args.target_static, args.target_dynamic];
    let plans: Vec<Vec<Config>> = scenes
        .iter()
        .zip(FINE_LEVELS)
        .map(|(s, (per_pitch, levels))| {
            let levels = if args.quick { 3 } else { levels };
            plan(s, args.quick, &fine_sizes(s, per_pitch, levels))
        })
        .collect();
    let total: usize = plans.iter().map(|p| p.len() * repeats).sum();
    let bar = progress_bar(total);
    let mut tick = 0u64;
    let mut cases = Vec::new();
    for ((scene, plan), target) in scenes.iter().zip(&plans).zip(targets) {
        let dir = out.join("runs").join(&scene.name);
        let grid = match scene.analysis {
            Analysis::Static { .. } => Grid::stations(scene.strand.length(), STATIONS),
            Analysis::Dynamic(d) => Grid::times(d.duration, d.output_interval),
        };
        let mut points = Vec::new();
        let mut results: Vec<Option<Sampled>> = Vec::new();
        for c in plan {
            let cfg_scene = c.scene(scene, None)?;
            let run_dir = dir.join(c.label().replace([' ', ',', '=', '/'], "_"));
            let mut times = Vec::new();
            let mut cpu = Vec::new();
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
                        cpu.push(s.cpu_time_s.unwrap_or(f64::NAN));
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
                points.push(unavailable(c, &why));
                results.push(None);
                continue;
            };
            let mut note = String::new();
            match Sampled::load(&grid, &run_dir.join(c.model.name())) {
                Ok(r) => results.push(Some(r)),
                Err(e) => {
                    note = format!("{e:#}");
                    results.push(None);
                }
            }
            if times.len() < repeats {
                note = format!("timed once (longer than {LONG_RUN_S} s) {note}");
            }
            points.push(Point {
                model: c.model,
                label: c.label(),
                family: c.family(),
                size: c.size,
                time_step: c.time_step,
                dofs: summary.dofs,
                steps: summary.steps,
                wall_time_s: median(&times),
                wall_times_s: times,
                cpu_time_s: median(&cpu),
                cpu_times_s: cpu,
                error_fine_m: f64::NAN,
                error_own_m: f64::NAN,
                on_front: false,
                note,
            });
        }
        let limits = measure(&grid, plan, &mut points, &results);
        let front = metrics::pareto_front(
            &points
                .iter()
                .map(|p| (p.cpu_time_s, p.error_fine_m))
                .collect::<Vec<_>>(),
        );
        for i in front {
            points[i].on_front = true;
        }
        cases.push(CaseReport::new(scene, &grid, points, limits, target));
    }
    bar.finish_and_clear();
    let report = ParetoReport {
        provenance,
        load_average: load_average(),
        repeats,
        quick: args.quick,
        wall_time_s: t0.elapsed().as_secs_f64(),
        cases,
    };
    let path = report.write(&out)?;
    println!("{}", report.headlines().join("\n"));
    if args.update_docs {
        crate::book::pages::copy_figures(&out, &["pareto-static", "pareto-dynamic"])?;
        crate::book::pages::update(
            crate::book::pages::Page::Performance,
            "pareto",
            &report.docs(),
        )?;
    }
    println!("report: {}", path.display());
    Ok(())
}

/// The load averages over 1, 5 and 15 minutes (`/proc/loadavg`), if readable.
fn load_average() -> Option<[f64; 3]> {
    let s = std::fs::read_to_string("/proc/loadavg").ok()?;
    let v: Vec<f64> = s
        .split_whitespace()
        .take(3)
        .filter_map(|w| w.parse().ok())
        .collect();
    (v.len() == 3).then(|| [v[0], v[1], v[2]])
}

/// The indices of the sequence of `model` (and, for the equivalent in dynamics, the
/// generalized-alpha family that refines elements and step together) that ran, in plan order.
fn sequence(plan: &[Config], model: Model) -> Vec<usize> {
    (0..plan.len())
        .filter(|&i| {
            plan[i].model == model
                && (model != Model::Equivalent || plan[i].integrator.as_deref() != Some("verlet"))
        })
        .collect()
}

/// The converged solution of each model from its four finest runs (refined by 2 each), and
/// every run's two errors.
fn measure(
    grid: &Grid,
    plan: &[Config],
    points: &mut [Point],
    results: &[Option<Sampled>],
) -> Vec<Limit> {
    let mut limits = Vec::new();
    let mut converged: Vec<(Model, Converged)> = Vec::new();
    for model in [Model::Fine, Model::Equivalent, Model::Traditional] {
        let seq = sequence(plan, model);
        if seq.len() < 4 {
            for &i in &seq {
                points[i].note += &format!(
                    " no converged {} solution: fewer than four runs refine it",
                    model.name()
                );
            }
            continue;
        }
        let last = &seq[seq.len() - 4..];
        let runs: Vec<(&str, &Sampled)> = last
            .iter()
            .filter_map(|&i| results[i].as_ref().map(|r| (points[i].label.as_str(), r)))
            .collect();
        if runs.len() < 4 {
            for &i in &seq {
                points[i].note += &format!(
                    " no converged {} solution: one of its four finest runs failed",
                    model.name()
                );
            }
            continue;
        }
        let ratio = plan[last[3]].size as f64 / plan[last[2]].size as f64;
        let c = Converged::new(
            [runs[0], runs[1], runs[2], runs[3]],
            ratio,
            formal_order(model, grid),
        );
        converged.push((model, c));
    }
    let fine = converged
        .iter()
        .find(|c| c.0 == Model::Fine)
        .map(|c| c.1.clone());
    for (model, c) in &converged {
        for i in 0..points.len() {
            if points[i].model != *model {
                continue;
            }
            if let Some(r) = &results[i] {
                points[i].error_own_m = c.distance(grid, r);
                if let Some(f) = &fine {
                    points[i].error_fine_m = f.distance(grid, r);
                }
            }
        }
        limits.push(Limit {
            model: model.name().into(),
            description: c.describe(),
            observed_orders: c.richardson.observed_orders,
            order: c.richardson.order,
            finest_error_m: c.finest_error,
            distance_to_fine_m: fine
                .as_ref()
                .map_or(f64::NAN, |f| reference::max_distance(&c.grid, &f.grid)),
        });
    }
    // A run whose model has no converged solution is still measured against the fine one.
    if let Some(f) = &fine {
        for i in 0..points.len() {
            if points[i].error_fine_m.is_nan()
                && let Some(r) = &results[i]
            {
                points[i].error_fine_m = f.distance(grid, r);
            }
        }
    }
    limits
}

/// The formal order of a model's refinement sequence, the cap of its Richardson order: the
/// fine model's straight segments are second order; the beams' cubic elements fourth order
/// in statics, and in dynamics the generalized-alpha family, refined in elements and step
/// together, the step's second order (Stoermer-Verlet at the stable step, which falls with
/// the square of the element length, keeps the elements' fourth).
fn formal_order(model: Model, grid: &Grid) -> f64 {
    match (model, grid) {
        (Model::Fine, _) => 2.0,
        (Model::Equivalent, Grid::Times(_)) => 2.0,
        _ => 4.0,
    }
}

fn unavailable(c: &Config, why: &str) -> Point {
    Point {
        model: c.model,
        label: c.label(),
        family: c.family(),
        size: c.size,
        time_step: c.time_step,
        dofs: 0,
        steps: 0,
        wall_times_s: Vec::new(),
        wall_time_s: f64::NAN,
        cpu_times_s: Vec::new(),
        cpu_time_s: f64::NAN,
        error_fine_m: f64::NAN,
        error_own_m: f64::NAN,
        on_front: false,
        note: why.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each configuration runs only its model, with its size, integrator and step; the fine
    /// runs double from the stated segments per pitch.
    #[test]
    fn configurations_run_one_model_each() {
        let scene = load_scene(DYNAMIC_SCENE).unwrap();
        let sizes = fine_sizes(&scene, 2.5, 4);
        // 0.4 m of a 20 deg lay with the layer at radius 2.5 mm: 9.26 pitches.
        assert_eq!(sizes, [23, 46, 92, 184]);
        let plan = plan(&scene, false, &sizes);
        assert!(plan.iter().any(|c| c.model == Model::Fine && c.size == 184));
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
        assert_eq!(fine.label(), "fine 23 seg/wire");
        // The converged equivalent comes from the generalized-alpha sequence only.
        let seq = sequence(&plan, Model::Equivalent);
        assert!(
            seq.iter()
                .all(|&i| plan[i].integrator.as_deref() == Some("generalized-alpha"))
        );
        let stat = load_scene(STATIC_SCENE).unwrap();
        assert_eq!(fine_sizes(&stat, 5.0, 4), [7, 14, 28, 56]);
    }
}
