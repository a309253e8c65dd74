//! The Pareto report: table of both errors, the converged solutions, log-log plot with the
//! front, and the headline: the CPU time of each model to come within X.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::Serialize;
use strand_scene::{Analysis, Scene};

use super::reference::Grid;
use super::{Limit, Model, Point, metrics};
use crate::validate::machine::Provenance;
use strand_core::convergence::{Reach, cost_to_reach};
use strand_plot::{self as plot, Chart, Mark, Series};

/// How one model comes within a distance of the converged fine model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReachReport {
    /// CPU time (s) at which it comes within; `None` when no run does.
    pub cpu_time_s: Option<f64>,
    /// Wall time (s), by the same rule.
    pub wall_time_s: Option<f64>,
    /// `interpolated`, `at most` (the cheapest run is already within) or `never`.
    pub kind: String,
    /// Which runs bracket it, or the smallest error reached.
    pub how: String,
}

/// The times of both models to come within one distance, and their ratio.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reaching {
    /// The distance X (m).
    pub target_m: f64,
    /// The equivalent model, along its Pareto front, to X of the converged fine model.
    pub equivalent: ReachReport,
    /// The fine model, along its refinement, to X of itself converged.
    pub fine: ReachReport,
    /// Fine CPU time over equivalent CPU time; `None` when either never comes within.
    pub cpu_ratio: Option<f64>,
    /// The same with wall times.
    pub wall_ratio: Option<f64>,
    /// `estimate`, `at most` or `at least` (when one side is only bounded).
    pub ratio_kind: String,
}

/// Where `runs` (labels, CPU and wall times, errors, in order of refinement) come within
/// `target`.
fn reach(runs: &[&Point], target: f64) -> ReachReport {
    let of = |cost: fn(&Point) -> f64| {
        cost_to_reach(
            &runs
                .iter()
                .map(|p| (cost(p), p.error_fine_m))
                .collect::<Vec<_>>(),
            target,
        )
    };
    let (cpu, wall) = (of(|p| p.cpu_time_s), of(|p| p.wall_time_s));
    let (kind, how) = match cpu {
        Reach::AtFirst { .. } => (
            "at most",
            format!(
                "its cheapest run ({}, {:.2e} m) is already within",
                runs[0].label, runs[0].error_fine_m
            ),
        ),
        Reach::Between { index, .. } => (
            "interpolated",
            format!(
                "between {} ({:.2e} m) and {} ({:.2e} m), a power law in CPU time",
                runs[index - 1].label,
                runs[index - 1].error_fine_m,
                runs[index].label,
                runs[index].error_fine_m
            ),
        ),
        Reach::Never { best_error } => (
            "never",
            format!("no run comes within: its smallest distance is {best_error:.2e} m"),
        ),
    };
    ReachReport {
        cpu_time_s: cpu.cost(),
        wall_time_s: wall.cost(),
        kind: kind.into(),
        how,
    }
}

/// Both models' times to `target` and their ratio.
pub fn reaching(points: &[Point], target: f64) -> Reaching {
    let mut eq: Vec<&Point> = points
        .iter()
        .filter(|p| p.model == Model::Equivalent && p.on_front_equivalent())
        .collect();
    eq.sort_by(|a, b| a.cpu_time_s.total_cmp(&b.cpu_time_s));
    let fine: Vec<&Point> = points
        .iter()
        .filter(|p| p.model == Model::Fine && p.error_fine_m.is_finite())
        .collect();
    let (e, f) = (reach(&eq, target), reach(&fine, target));
    let ratio = |a: Option<f64>, b: Option<f64>| a.zip(b).map(|(f, e)| f / e);
    let ratio_kind = match (e.kind.as_str(), f.kind.as_str()) {
        ("never", _) => "none: the equivalent never comes within X",
        (_, "never") => "none: the fine model never comes within X",
        ("at most", "at most") => "unbounded: both cheapest runs are within",
        ("at most", _) => "at least",
        (_, "at most") => "at most",
        _ => "estimate",
    };
    Reaching {
        target_m: target,
        cpu_ratio: ratio(f.cpu_time_s, e.cpu_time_s),
        wall_ratio: ratio(f.wall_time_s, e.wall_time_s),
        ratio_kind: ratio_kind.into(),
        equivalent: e,
        fine: f,
    }
}

/// The smallest of 1, 2, 5 x 10^k at least `v`.
pub fn ladder_at_least(v: f64) -> f64 {
    let k = v.log10().floor();
    for m in [1.0, 2.0, 5.0, 10.0] {
        let x = m * 10f64.powf(k);
        if x >= v * (1.0 - 1e-12) {
            return x;
        }
    }
    10f64.powf(k + 1.0)
}

/// The next value of the 1, 2, 5 ladder above `x`.
fn ladder_next(x: f64) -> f64 {
    ladder_at_least(x * 1.01)
}

/// One scene's points, converged solutions and headline.
#[derive(Debug, Clone, Serialize)]
pub struct CaseReport {
    /// Scene name.
    pub scene: String,
    /// `static` or `dynamic`.
    pub analysis: String,
    /// What the errors measure.
    pub metric: String,
    /// The converged solution of each model.
    pub limits: Vec<Limit>,
    /// The timed configurations.
    pub points: Vec<Point>,
    /// The headline distance X (m) and why.
    pub target_m: f64,
    /// Why X is what it is.
    pub target_why: String,
    /// The times to X and, for scale, to the next distances of the 1, 2, 5 ladder.
    pub reaching: Vec<Reaching>,
    /// The headline sentence.
    pub headline: String,
}

impl Point {
    /// Whether the point is on the equivalent model's own front (of CPU time against error to
    /// the converged fine model); set by [`CaseReport::new`].
    fn on_front_equivalent(&self) -> bool {
        self.note.contains(EQ_FRONT)
    }
}

const EQ_FRONT: &str = "[equivalent front]";

/// A time in seconds with about three significant digits.
fn secs(t: f64) -> String {
    if t >= 10.0 {
        format!("{t:.1}")
    } else if t >= 0.1 {
        format!("{t:.3}")
    } else {
        format!("{t:.2e}")
    }
}

fn fmt_reach(r: &ReachReport) -> String {
    match r.cpu_time_s {
        Some(t) if r.kind == "at most" => format!("at most {} s", secs(t)),
        Some(t) => format!("{} s", secs(t)),
        None => "never".into(),
    }
}

impl CaseReport {
    /// The report of `scene` from its points and converged solutions; `target` overrides X.
    pub fn new(
        scene: &Scene,
        grid: &Grid,
        mut points: Vec<Point>,
        limits: Vec<Limit>,
        target: Option<f64>,
    ) -> CaseReport {
        let analysis = match scene.analysis {
            Analysis::Static { .. } => "static",
            Analysis::Dynamic(_) => "dynamic",
        };
        let metric = match grid {
            Grid::Stations(s) => format!(
                "largest centreline distance over the run's own points (the converged \
                 solutions sampled at {} stations along the strand, interpolated linearly)",
                s.len()
            ),
            Grid::Times(t) => format!(
                "largest tip distance over the {} output times (each run's tip interpolated by \
                 cubic Hermite at them)",
                t.len()
            ),
        };
        // The equivalent model's own front.
        let eq_idx: Vec<usize> = (0..points.len())
            .filter(|&i| points[i].model == Model::Equivalent)
            .collect();
        let front = metrics::pareto_front(
            &eq_idx
                .iter()
                .map(|&i| (points[i].cpu_time_s, points[i].error_fine_m))
                .collect::<Vec<_>>(),
        );
        for k in front {
            points[eq_idx[k]].note += EQ_FRONT;
        }
        let fine_limit = limits.iter().find(|l| l.model == "fine");
        let eq_limit = limits.iter().find(|l| l.model == "equivalent");
        let (target_m, target_why) = match (target, fine_limit, eq_limit) {
            (Some(x), _, _) => (x, "given on the command line".to_string()),
            (None, Some(f), Some(e)) => {
                let floor = e.distance_to_fine_m + f.finest_error_m;
                (
                    ladder_at_least(2.0 * floor),
                    format!(
                        "the smallest of 1, 2, 5 x 10^k at least twice the converged equivalent \
                         model's distance to the converged fine model ({:.2e} m, the modelling \
                         difference no refinement removes) plus the fine reference's estimated \
                         error ({:.1e} m): the equivalent's discretisation has at least half \
                         of X to spend",
                        e.distance_to_fine_m, f.finest_error_m
                    ),
                )
            }
            _ => (
                f64::NAN,
                "not available: a converged solution is missing".into(),
            ),
        };
        // X and, for scale, every distance of the 1, 2, 5 ladder from twice the fine
        // reference's error up to the coarsest fine run's error.
        let mut reaching_rows = Vec::new();
        if target_m.is_finite() {
            let largest = points
                .iter()
                .filter(|p| p.model == Model::Fine)
                .map(|p| p.error_fine_m)
                .filter(|e| e.is_finite())
                .fold(0.0, f64::max);
            let floor = fine_limit.map_or(target_m, |f| 2.0 * f.finest_error_m);
            let mut xs = vec![target_m];
            let mut x = ladder_at_least(floor.min(target_m));
            while xs.len() < 10 && x < 2.0 * largest.max(target_m) {
                if (x / target_m - 1.0).abs() > 1e-9 {
                    xs.push(x);
                }
                x = ladder_next(x);
            }
            xs.sort_by(f64::total_cmp);
            reaching_rows = xs.into_iter().map(|x| reaching(&points, x)).collect();
        }
        let headline = match reaching_rows.iter().find(|r| r.target_m == target_m) {
            Some(r) => {
                let ratio = match (r.cpu_ratio, r.ratio_kind.as_str()) {
                    (Some(q), "estimate") => format!("the equivalent model is {q:.0}x faster"),
                    (Some(q), "at most") => format!("the equivalent model is at most {q:.0}x faster (the fine model's cheapest run is already within X)"),
                    (Some(q), "at least") => format!("the equivalent model is at least {q:.0}x faster (its cheapest run is already within X)"),
                    (Some(_), k) => format!("no ratio: {k}"),
                    (None, _) if r.equivalent.cpu_time_s.is_none() => "the equivalent model cannot come within X of the converged fine model: its modelling difference is larger".into(),
                    (None, _) => "the fine model does not come within X of itself in the runs made".into(),
                };
                format!(
                    "{} ({analysis}): X = {:.0e} m. CPU time of the equivalent model to come \
                     within X of the converged fine model: {} ({}); of the fine model to come \
                     within X of itself: {} ({}); {ratio}.",
                    scene.name,
                    target_m,
                    fmt_reach(&r.equivalent),
                    r.equivalent.how,
                    fmt_reach(&r.fine),
                    r.fine.how,
                )
            }
            None => format!("{} ({analysis}): no headline: {target_why}", scene.name),
        };
        for p in &mut points {
            p.note = p.note.replace(EQ_FRONT, "").trim().to_string();
        }
        CaseReport {
            scene: scene.name.clone(),
            analysis: analysis.into(),
            metric,
            limits,
            points,
            target_m,
            target_why,
            reaching: reaching_rows,
            headline,
        }
    }

    /// The log-log chart of error to the converged fine model against CPU time, with the
    /// front and X.
    pub fn chart(&self) -> Chart {
        let mut families: Vec<String> = Vec::new();
        for p in &self.points {
            if !families.contains(&p.family) {
                families.push(p.family.clone());
            }
        }
        let mut series: Vec<Series> = families
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let pts = self
                    .points
                    .iter()
                    .filter(|p| &p.family == f && p.error_fine_m.is_finite())
                    .map(|p| (p.cpu_time_s, p.error_fine_m))
                    .collect();
                Series::new(f.clone(), pts, Mark::Points, i)
            })
            .filter(|s| !s.points.is_empty())
            .collect();
        let mut front: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter(|p| p.on_front)
            .map(|p| (p.cpu_time_s, p.error_fine_m))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(Series::new("Pareto front", front, Mark::Front, 6));
        let times: Vec<f64> = self
            .points
            .iter()
            .map(|p| p.cpu_time_s)
            .filter(|t| t.is_finite() && *t > 0.0)
            .collect();
        if self.target_m.is_finite() && !times.is_empty() {
            let lo = times.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = times.iter().copied().fold(0.0, f64::max);
            series.push(Series::new(
                format!("X = {:.0e} m", self.target_m),
                vec![(lo, self.target_m), (hi, self.target_m)],
                Mark::Dashed,
                7,
            ));
        }
        let missing = self.points.iter().any(|p| !p.error_fine_m.is_finite());
        Chart {
            title: format!("Speed against error: {} ({})", self.scene, self.analysis),
            x_label: "CPU time of the solve, median (s)".into(),
            y_label: "distance to the converged fine model (m)".into(),
            series,
            log: true,
            note: missing.then(|| "some runs not available (see the table)".into()),
            ..Default::default()
        }
    }
}

/// The whole report.
#[derive(Debug, Clone, Serialize)]
pub struct ParetoReport {
    /// Machine, commit, build profile, command, date.
    pub provenance: Provenance,
    /// Load averages over 1, 5, 15 minutes at the end (the machine may be shared).
    pub load_average: Option<[f64; 3]>,
    /// Timed runs per configuration.
    pub repeats: usize,
    /// Whether this was the quick smoke run.
    pub quick: bool,
    /// Wall time of the whole command (s).
    pub wall_time_s: f64,
    /// One per scene.
    pub cases: Vec<CaseReport>,
}

fn num(v: f64, digits: usize) -> String {
    if v.is_finite() {
        format!("{v:.digits$e}")
    } else {
        "-".into()
    }
}

impl ParetoReport {
    /// One headline per scene.
    pub fn headlines(&self) -> Vec<String> {
        self.cases.iter().map(|c| c.headline.clone()).collect()
    }

    /// The report for the manual (`--update-docs`): its Markdown without the title, each
    /// scene's heading two levels down (the page's own headings stay above it).
    pub fn docs(&self) -> String {
        self.markdown()
            .lines()
            .skip(1)
            .map(|l| {
                if l.starts_with("## ") {
                    format!("##{l}")
                } else {
                    // The figures sit in the manual's figures/ folder (copy_figures).
                    l.replace("](pareto-", "](figures/pareto-")
                }
            })
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The report as Markdown.
    pub fn markdown(&self) -> String {
        let p = &self.provenance;
        let mut m = String::new();
        let _ = writeln!(m, "# Speed against error\n");
        let _ = writeln!(
            m,
            "`{}` on {}; commit `{}`, {} build, {}; {:.1} s; load average at the end {}. \
             Times: the solve as the runner measures it (CPU time of the process, all threads, \
             and wall time), median of {} run(s) per configuration{}.\n",
            p.command,
            p.machine.description(),
            p.commit,
            p.profile,
            p.date,
            self.wall_time_s,
            self.load_average
                .map_or("not available".into(), |l| format!(
                    "{:.1}, {:.1}, {:.1}",
                    l[0], l[1], l[2]
                )),
            self.repeats,
            if self.quick {
                " (quick smoke run: not a measurement)"
            } else {
                ""
            }
        );
        for h in self.headlines() {
            let _ = writeln!(m, "* {h}");
        }
        for c in &self.cases {
            let _ = writeln!(m, "\n## {} ({})\n", c.scene, c.analysis);
            let _ = writeln!(m, "Error: {}.\n", c.metric);
            let _ = writeln!(m, "Converged solutions:\n");
            for l in &c.limits {
                let _ = writeln!(
                    m,
                    "* {}: {}; distance to the converged fine model {:.2e} m",
                    l.model, l.description, l.distance_to_fine_m
                );
            }
            let _ = writeln!(m, "\nX = {:.0e} m: {}.\n", c.target_m, c.target_why);
            let _ = writeln!(m, "![{}](pareto-{}.png)\n", c.scene, c.analysis);
            let _ = writeln!(
                m,
                "| configuration | dofs | steps | CPU time (s) | wall time (s) | error vs \
                 converged fine (m) | error vs own converged (m) | front | note |"
            );
            let _ = writeln!(m, "|---|---:|---:|---:|---:|---:|---:|:-:|---|");
            for pt in &c.points {
                let _ = writeln!(
                    m,
                    "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                    pt.label,
                    pt.dofs,
                    pt.steps,
                    num(pt.cpu_time_s, 2),
                    num(pt.wall_time_s, 2),
                    num(pt.error_fine_m, 2),
                    num(pt.error_own_m, 2),
                    if pt.on_front { "x" } else { "" },
                    pt.note.replace('|', "\\|")
                );
            }
            let _ = writeln!(
                m,
                "\n| X (m) | equivalent to X of converged fine: CPU (s) | fine to X of itself: \
                 CPU (s) | ratio (CPU) | ratio (wall) | kind |"
            );
            let _ = writeln!(m, "|---:|---:|---:|---:|---:|---|");
            for r in &c.reaching {
                let q = |v: Option<f64>| v.map_or("-".into(), |v| format!("{v:.0}"));
                let _ = writeln!(
                    m,
                    "| {:.0e} | {} | {} | {} | {} | {} |",
                    r.target_m,
                    fmt_reach(&r.equivalent),
                    fmt_reach(&r.fine),
                    q(r.cpu_ratio),
                    q(r.wall_ratio),
                    r.ratio_kind
                );
            }
        }
        m
    }

    /// One row per run of every scene, as CSV.
    pub fn csv(&self) -> String {
        let mut m = String::from(
            "scene,analysis,model,configuration,size,time_step,dofs,steps,cpu_time_s,\
             wall_time_s,error_fine_m,error_own_m,on_front\n",
        );
        let f = |v: f64| {
            if v.is_finite() {
                format!("{v:e}")
            } else {
                String::new()
            }
        };
        for c in &self.cases {
            for p in &c.points {
                let _ = writeln!(
                    m,
                    "{},{},{},\"{}\",{},{},{},{},{},{},{},{},{}",
                    c.scene,
                    c.analysis,
                    p.model.name(),
                    p.label,
                    p.size,
                    p.time_step.map_or(String::new(), |h| format!("{h:e}")),
                    p.dofs,
                    p.steps,
                    f(p.cpu_time_s),
                    f(p.wall_time_s),
                    f(p.error_fine_m),
                    f(p.error_own_m),
                    p.on_front
                );
            }
        }
        m
    }

    /// Writes `report.md`, `report.json`, `runs.csv` and the plots into `dir`; returns the
    /// Markdown's path.
    pub fn write(&self, dir: &Path) -> anyhow::Result<PathBuf> {
        for c in &self.cases {
            plot::save(&c.chart(), dir, &format!("pareto-{}", c.analysis))?;
        }
        let md = dir.join("report.md");
        let json = dir.join("report.json");
        let csv = dir.join("runs.csv");
        std::fs::write(&md, self.markdown())
            .with_context(|| format!("writing {}", md.display()))?;
        std::fs::write(&json, serde_json::to_string_pretty(self)? + "\n")
            .with_context(|| format!("writing {}", json.display()))?;
        std::fs::write(&csv, self.csv()).with_context(|| format!("writing {}", csv.display()))?;
        Ok(md)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(model: Model, label: &str, t: f64, e: f64) -> Point {
        Point {
            model,
            label: label.into(),
            family: model.name().into(),
            size: 1,
            time_step: None,
            dofs: 1,
            steps: 1,
            wall_times_s: vec![2.0 * t],
            wall_time_s: 2.0 * t,
            cpu_times_s: vec![t],
            cpu_time_s: t,
            error_fine_m: e,
            error_own_m: e,
            on_front: false,
            note: String::new(),
        }
    }

    #[test]
    fn ladder() {
        assert_eq!(ladder_at_least(3e-5), 5e-5);
        assert_eq!(ladder_at_least(1e-4), 1e-4);
        assert!((ladder_at_least(1.1e-4) - 2e-4).abs() < 1e-18);
        assert!((ladder_at_least(6e-3) - 1e-2).abs() < 1e-15);
        assert!((ladder_next(2e-4) - 5e-4).abs() < 1e-18);
        assert!((ladder_at_least(1e-4 / 2.5) - 5e-5).abs() < 1e-18);
    }

    /// The equivalent along its front, the fine model along its refinement; the ratio is of
    /// the interpolated CPU times, and bounds are named as such.
    #[test]
    fn times_to_reach_a_distance() {
        let mut pts = vec![
            point(Model::Equivalent, "e4", 0.01, 1e-2),
            point(Model::Equivalent, "e8", 0.02, 1e-3),
            point(Model::Equivalent, "e8-slow", 0.05, 2e-3),
            point(Model::Equivalent, "e16", 0.08, 2e-4),
            point(Model::Fine, "f10", 1.0, 4e-3),
            point(Model::Fine, "f20", 4.0, 1e-3),
            point(Model::Fine, "f40", 16.0, 2.5e-4),
        ];
        for p in &mut pts[..4] {
            if p.label != "e8-slow" {
                p.note = EQ_FRONT.into();
            }
        }
        let r = reaching(&pts, 1e-3);
        assert!((r.equivalent.cpu_time_s.unwrap() - 0.02).abs() < 1e-12);
        assert!((r.fine.cpu_time_s.unwrap() - 4.0).abs() < 1e-12);
        assert!((r.cpu_ratio.unwrap() - 200.0).abs() < 1e-9);
        assert!((r.wall_ratio.unwrap() - 200.0).abs() < 1e-9);
        assert_eq!(r.ratio_kind, "estimate");
        // Error falls as cost^-1 on the fine runs: 2e-3 m at 2 s.
        let r = reaching(&pts, 2e-3);
        assert!((r.fine.cpu_time_s.unwrap() - 2.0).abs() < 1e-9);
        // Below the equivalent's best: never, and no ratio.
        let r = reaching(&pts, 1e-4);
        assert_eq!(r.equivalent.kind, "never");
        assert_eq!(r.cpu_ratio, None);
        assert!(r.ratio_kind.starts_with("none"));
        // Above the coarsest fine run: the fine time is an upper bound.
        let r = reaching(&pts, 5e-3);
        assert_eq!(r.fine.kind, "at most");
        assert_eq!(r.ratio_kind, "at most");
    }
}
