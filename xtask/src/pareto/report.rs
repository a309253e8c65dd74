//! The Pareto report: table, log-log plot with the front, and the headline speed-up.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::Serialize;
use strand_scene::{Analysis, Scene};

use super::metrics::cheapest_within;
use super::{Model, Point};
use crate::validate::machine::Provenance;
use strand_plot::{self as plot, Chart, Mark, Series};

/// The speed-up of the equivalent over the fine model at one fine-model run's error.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedUp {
    /// The fine-model run.
    pub fine: String,
    /// Its error (m) and median wall time (s).
    pub fine_error_m: f64,
    /// Median wall time of the fine run (s).
    pub fine_time_s: f64,
    /// The cheapest equivalent run at most as wrong.
    pub equivalent: String,
    /// Its median wall time (s).
    pub equivalent_time_s: f64,
    /// fine time / equivalent time.
    pub speed_up: f64,
}

/// One scene's points and headline.
#[derive(Debug, Clone, Serialize)]
pub struct CaseReport {
    /// Scene name.
    pub scene: String,
    /// `static` or `dynamic`.
    pub analysis: String,
    /// What the errors are measured against.
    pub reference: String,
    /// The timed configurations.
    pub points: Vec<Point>,
    /// Speed-ups at equal error, one per fine-model run that is matched; empty when none.
    pub speed_ups: Vec<SpeedUp>,
    /// The headline sentence.
    pub headline: String,
}

/// The speed-ups of the equivalent model over each fine-model run at equal error.
pub fn speed_ups(points: &[Point]) -> Vec<SpeedUp> {
    let eq: Vec<&Point> = points
        .iter()
        .filter(|p| p.model == Model::Equivalent && p.error_m.is_finite())
        .collect();
    let cand: Vec<(f64, f64)> = eq.iter().map(|p| (p.wall_time_s, p.error_m)).collect();
    points
        .iter()
        .filter(|p| p.model == Model::Fine && p.error_m.is_finite() && p.wall_time_s > 0.0)
        .filter_map(|f| {
            cheapest_within(&cand, f.error_m).map(|i| SpeedUp {
                fine: f.label.clone(),
                fine_error_m: f.error_m,
                fine_time_s: f.wall_time_s,
                equivalent: eq[i].label.clone(),
                equivalent_time_s: eq[i].wall_time_s,
                speed_up: f.wall_time_s / eq[i].wall_time_s,
            })
        })
        .collect()
}

impl CaseReport {
    /// The report of `scene` from its points.
    pub fn new(scene: &Scene, reference: String, points: Vec<Point>) -> CaseReport {
        let analysis = match scene.analysis {
            Analysis::Static { .. } => "static",
            Analysis::Dynamic(_) => "dynamic",
        };
        let speed_ups = speed_ups(&points);
        let fine_ran = points
            .iter()
            .any(|p| p.model == Model::Fine && p.error_m.is_finite());
        let best_eq = points
            .iter()
            .filter(|p| p.model == Model::Equivalent && p.error_m.is_finite())
            .min_by(|a, b| a.error_m.total_cmp(&b.error_m));
        let eq_part = best_eq.map_or(String::new(), |p| {
            format!(
                " The equivalent model's smallest error is {:.2e} m ({}, {:.3} s).",
                p.error_m, p.label, p.wall_time_s
            )
        });
        let headline = if let Some(best) = speed_ups
            .iter()
            .min_by(|a, b| a.fine_error_m.total_cmp(&b.fine_error_m))
        {
            format!(
                "{} ({analysis}): at the distance to this reference of the most accurate fine \
                 run ({}, {:.2e} m, {:.3} s) the equivalent model ({}) is {:.0}x faster; that \
                 distance is mostly the fine model's modelling difference from the equivalent \
                 law, so this is not a speed-up at equal error against the fine model.{eq_part}",
                scene.name,
                best.fine,
                best.fine_error_m,
                best.fine_time_s,
                best.equivalent,
                best.speed_up
            )
        } else if fine_ran {
            format!(
                "{} ({analysis}): no equivalent run is as accurate as a fine run against this \
                 reference, so there is no speed-up at equal error.{eq_part}",
                scene.name
            )
        } else {
            format!(
                "{} ({analysis}): speed-up over the fine model at equal error: not available \
                 (no fine-model run finished).{eq_part}",
                scene.name
            )
        };
        CaseReport {
            scene: scene.name.clone(),
            analysis: analysis.into(),
            reference,
            points,
            speed_ups,
            headline,
        }
    }

    /// The log-log chart of error against wall time with the front.
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
                    .filter(|p| &p.family == f && p.error_m.is_finite())
                    .map(|p| (p.wall_time_s, p.error_m))
                    .collect();
                Series::new(f.clone(), pts, Mark::Points, i)
            })
            .filter(|s| !s.points.is_empty())
            .collect();
        let mut front: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter(|p| p.on_front)
            .map(|p| (p.wall_time_s, p.error_m))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(Series::new("Pareto front", front, Mark::Front, 6));
        let fine_missing = self
            .points
            .iter()
            .any(|p| p.model == Model::Fine && !p.error_m.is_finite());
        Chart {
            title: format!("Speed against error: {} ({})", self.scene, self.analysis),
            x_label: "wall time, median (s)".into(),
            y_label: "error (m)".into(),
            series,
            log: true,
            note: fine_missing
                .then(|| "fine model: some runs not available (see the table)".into()),
            ..Default::default()
        }
    }
}

/// The whole report.
#[derive(Debug, Clone, Serialize)]
pub struct ParetoReport {
    /// Machine, commit, build profile, command, date.
    pub provenance: Provenance,
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

    /// The report as Markdown.
    pub fn markdown(&self) -> String {
        let p = &self.provenance;
        let mut m = String::new();
        let _ = writeln!(m, "# Speed against error\n");
        let _ = writeln!(
            m,
            "`{}` on {}; commit `{}`, {} build, {}; {:.1} s. Wall time: the solve time the \
             runner measures, median of {} run(s) per configuration{}.\n",
            p.command,
            p.machine.description(),
            p.commit,
            p.profile,
            p.date,
            self.wall_time_s,
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
            let _ = writeln!(m, "Reference: {}.\n", c.reference);
            let _ = writeln!(m, "![{}](pareto-{}.png)\n", c.scene, c.analysis);
            let _ = writeln!(
                m,
                "| configuration | dofs | steps | wall time (s) | error (m) | front | note |"
            );
            let _ = writeln!(m, "|---|---:|---:|---:|---:|:-:|---|");
            for pt in &c.points {
                let _ = writeln!(
                    m,
                    "| {} | {} | {} | {} | {} | {} | {} |",
                    pt.label,
                    pt.dofs,
                    pt.steps,
                    num(pt.wall_time_s, 2),
                    num(pt.error_m, 2),
                    if pt.on_front { "x" } else { "" },
                    pt.note.replace('|', "\\|")
                );
            }
            if !c.speed_ups.is_empty() {
                let _ = writeln!(
                    m,
                    "\n| fine run | its error (m) | its time (s) | cheapest equivalent as \
                     accurate | its time (s) | speed-up |"
                );
                let _ = writeln!(m, "|---|---:|---:|---|---:|---:|");
                for s in &c.speed_ups {
                    let _ = writeln!(
                        m,
                        "| {} | {:.2e} | {:.3} | {} | {:.3} | {:.0}x |",
                        s.fine,
                        s.fine_error_m,
                        s.fine_time_s,
                        s.equivalent,
                        s.equivalent_time_s,
                        s.speed_up
                    );
                }
            }
        }
        m
    }

    /// Writes `report.md`, `report.json` and the plots into `dir`; returns the Markdown's path.
    pub fn write(&self, dir: &Path) -> anyhow::Result<PathBuf> {
        for c in &self.cases {
            plot::save(&c.chart(), dir, &format!("pareto-{}", c.analysis))?;
        }
        let md = dir.join("report.md");
        let json = dir.join("report.json");
        std::fs::write(&md, self.markdown())
            .with_context(|| format!("writing {}", md.display()))?;
        std::fs::write(&json, serde_json::to_string_pretty(self)? + "\n")
            .with_context(|| format!("writing {}", json.display()))?;
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
            dofs: 1,
            steps: 1,
            wall_times_s: vec![t],
            wall_time_s: t,
            error_m: e,
            on_front: false,
            note: String::new(),
        }
    }

    #[test]
    fn speed_up_at_equal_error() {
        let pts = [
            point(Model::Equivalent, "e4", 0.01, 1e-2),
            point(Model::Equivalent, "e8", 0.02, 1e-3),
            point(Model::Equivalent, "e16", 0.08, 2e-4),
            point(Model::Fine, "f20", 2.0, 1.5e-3),
            point(Model::Fine, "f77", 10.0, 1e-4),
            point(Model::Fine, "f-missing", f64::NAN, f64::NAN),
        ];
        let s = speed_ups(&pts);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].equivalent, "e8");
        assert!((s[0].speed_up - 100.0).abs() < 1e-9);
    }
}
