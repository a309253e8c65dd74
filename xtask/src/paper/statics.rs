//! Figs. 9-13: the section-3 strand hanging under g = 8, 10, 12, equivalent against
//! traditional: shapes, bending stiffness, curvature, tension near the tip, and each wire's
//! critical curvature against the curvature.

use std::path::Path;

use anyhow::{Context, bail};

use super::fine::gravity;
use super::report::{Finding, Verdict, sci};
use super::{Figures, SceneRun};
use crate::validate::results::Table;
use strand_plot::{Chart, Mark, Series};

/// The paper's Fig. 12 tensions: (x in m, N).
const PAPER_TENSION: [(f64, f64); 3] = [(0.92, 0.149), (0.925, 0.14), (0.93, 0.13)];

/// `centerline.csv` of a model folder with every column.
struct Line {
    s: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    curvature: Vec<f64>,
    tension: Vec<f64>,
    stiffness: Vec<f64>,
}

impl Line {
    fn load(dir: &Path) -> anyhow::Result<Line> {
        let t = Table::load(&dir.join("centerline.csv"))?;
        Ok(Line {
            s: t.column("s")?,
            x: t.column("x")?,
            y: t.column("y")?,
            curvature: t.column("curvature")?,
            tension: t.column("tension")?,
            stiffness: t.column("bending_stiffness")?,
        })
    }

    /// Index of the point nearest to material coordinate `s`.
    fn nearest(&self, s: f64) -> usize {
        (0..self.s.len())
            .min_by(|&a, &b| (self.s[a] - s).abs().total_cmp(&(self.s[b] - s).abs()))
            .expect("non-empty")
    }

    /// Linear interpolation of `v` at `s`.
    fn at(&self, v: &[f64], s: f64) -> f64 {
        let n = self.s.len();
        let i = self.s.partition_point(|&a| a <= s).clamp(1, n - 1) - 1;
        let t = (s - self.s[i]) / (self.s[i + 1] - self.s[i]);
        v[i] + t * (v[i + 1] - v[i])
    }
}

/// One row of `wires.csv`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct WireRow {
    /// Material coordinate (m).
    pub s: f64,
    /// Wire number, from 1.
    pub wire: usize,
    /// Phase (rad).
    pub phase: f64,
    /// Critical curvature (1/m).
    pub critical: f64,
    /// Slipping.
    pub slip: bool,
}

/// Reads `wires.csv` of a model folder.
pub(crate) fn load_wires(dir: &Path) -> anyhow::Result<Vec<WireRow>> {
    let path = dir.join("wires.csv");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<&str> = lines.next().context("no header")?.split(',').collect();
    if header != ["s", "wire", "phase", "critical_curvature", "state", "layer"] {
        bail!("{}: unexpected header {header:?}", path.display());
    }
    lines
        .enumerate()
        .map(|(i, l)| {
            let f: Vec<&str> = l.split(',').map(str::trim).collect();
            let row = || -> anyhow::Result<WireRow> {
                if f.len() != 6 {
                    bail!("{} fields", f.len());
                }
                // The paper's strands have one layer.
                if f[5] != "1" {
                    bail!("layer `{}`: the paper's figures are of a 1+m strand", f[5]);
                }
                Ok(WireRow {
                    s: f[0].parse()?,
                    wire: f[1].parse()?,
                    phase: f[2].parse()?,
                    // Empty for a wire without lever: it never slips.
                    critical: match f[3] {
                        "" => f64::INFINITY,
                        c => c.parse()?,
                    },
                    slip: match f[4] {
                        "slip" => true,
                        "stick" => false,
                        o => bail!("state `{o}`"),
                    },
                })
            };
            row().with_context(|| format!("{} row {}", path.display(), i + 2))
        })
        .collect()
}

/// Along s: the number of slipping wires at each point, (s, count).
pub(crate) fn slipping_along(rows: &[WireRow]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    for r in rows {
        match out.last_mut() {
            Some(last) if last.0 == r.s => last.1 += f64::from(u8::from(r.slip)),
            _ => out.push((r.s, f64::from(u8::from(r.slip)))),
        }
    }
    out
}

/// Figs. 9-13 from the three section-3 runs (g = 8, 10, 12).
pub fn figures(runs: &[&SceneRun], figs: &mut Figures) -> anyhow::Result<Vec<Finding>> {
    let mut findings = Vec::new();
    let strand = &runs[0].scene.strand;
    let law = strand_core::SectionLaw::with_options(
        strand,
        strand_core::LawKind::Continuous,
        &runs[0].scene.section,
    );
    let (k_min, k_max) = (law.base_bending_stiffness(), law.stick_bending_stiffness());
    let ei = strand.traditional().bending_stiffness;
    let mut eqs = Vec::new();
    let mut trads = Vec::new();
    for run in runs {
        let eq = Line::load(&run.model("equivalent").map_err(anyhow::Error::msg)?)?;
        let tr = Line::load(&run.model("traditional").map_err(anyhow::Error::msg)?)?;
        eqs.push(eq);
        trads.push(tr);
    }
    let gs: Vec<f64> = runs.iter().map(|r| gravity(&r.scene)).collect();

    // Fig. 9: shapes.
    let mut series = Vec::new();
    let mut tips = Vec::new();
    let mut sags_more = true;
    for (i, g) in gs.iter().enumerate() {
        let (e, t) = (&eqs[i], &trads[i]);
        series.push(Series::xy(
            format!("equivalent, g = {g}"),
            &e.x,
            &e.y,
            Mark::Line,
            i,
        ));
        series.push(Series::xy(
            format!("traditional, g = {g}"),
            &t.x,
            &t.y,
            Mark::Dashed,
            i,
        ));
        let (ne, nt) = (e.s.len() - 1, t.s.len() - 1);
        sags_more &= e.x[ne] < t.x[nt] && e.y[ne] < t.y[nt];
        tips.push(format!(
            "g = {g}: tip ({:.3}, {:.3}) m vs ({:.3}, {:.3}) m",
            e.x[ne], e.y[ne], t.x[nt], t.y[nt]
        ));
    }
    figs.save(
        "fig09-shapes",
        &Chart {
            title: "Fig. 9: static shapes, section-3 strand (30 elements)".into(),
            x_label: "x (m)".into(),
            y_label: "y (m)".into(),
            series,
            equal_aspect: true,
            ..Default::default()
        },
    )?;
    let root: Vec<String> = gs
        .iter()
        .enumerate()
        .map(|(i, g)| {
            format!(
                "g = {g}: {:.2} vs {:.2} 1/m",
                eqs[i].curvature[0].abs(),
                trads[i].curvature[0].abs()
            )
        })
        .collect();
    let bends_more = (0..gs.len()).all(|i| eqs[i].curvature[0].abs() > trads[i].curvature[0].abs());
    findings.push(Finding::new(
        "Fig. 9",
        "the equivalent strand sags further in X and Y than the traditional one",
        format!("equivalent vs traditional {}", tips.join("; ")),
        if sags_more {
            Verdict::Agrees
        } else {
            Verdict::Differs
        },
        "tip positions at the end of the load path",
    ));
    findings.push(Finding::new(
        "Fig. 9",
        "the equivalent strand bends more at the root",
        format!(
            "curvature at the root (s = {} m, the clamp), equivalent vs traditional: {}",
            eqs[0].s[0],
            root.join("; ")
        ),
        if bends_more {
            Verdict::Agrees
        } else {
            Verdict::Differs
        },
        "",
    ));

    // Fig. 10: bending stiffness.
    let l = strand.length();
    let mut series: Vec<Series> = gs
        .iter()
        .enumerate()
        .map(|(i, g)| {
            Series::xy(
                format!("equivalent, g = {g}"),
                &eqs[i].s,
                &eqs[i].stiffness,
                Mark::Line,
                i,
            )
        })
        .collect();
    for (label, v, c) in [
        ("K_min (all wires slip)", k_min, 6),
        ("K_max (all wires stick)", k_max, 3),
        ("traditional EI", ei, 4),
    ] {
        series.push(Series::new(label, vec![(0.0, v), (l, v)], Mark::Dashed, c));
    }
    figs.save(
        "fig10-stiffness",
        &Chart {
            title: "Fig. 10: bending stiffness (secant M/kappa) along the strand".into(),
            x_label: "s (m)".into(),
            y_label: "bending stiffness (N m^2)".into(),
            series,
            ..Default::default()
        },
    )?;
    let within = eqs.iter().all(|e| {
        e.stiffness
            .iter()
            .all(|&k| k >= k_min * (1.0 - 1e-9) && k <= k_max * (1.0 + 1e-9))
    });
    let ends: Vec<String> = gs
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let e = &eqs[i];
            let (j, peak) = e
                .stiffness
                .iter()
                .enumerate()
                .fold((0, 0.0), |m, (j, &k)| if k > m.1 { (j, k) } else { m });
            format!(
                "g = {g}: {:.3} K_min at the root, peak {:.3} K_max at s = {:.3} m, {:.3} K_max \
                 at the last point",
                e.stiffness[0] / k_min,
                peak / k_max,
                e.s[j],
                e.stiffness[e.s.len() - 1] / k_max
            )
        })
        .collect();
    findings.push(Finding::new(
        "Fig. 10",
        "stiffness between K_min (root: all wires slip) and the all-stick maximum (near the \
         tip); the traditional EI above both",
        format!(
            "K_min = {} N m^2, K_max = {} N m^2, traditional EI = {} N m^2; {}; all points \
             within [K_min, K_max]: {}",
            sci(k_min),
            sci(k_max),
            sci(ei),
            ends.join("; "),
            if within { "yes" } else { "no" }
        ),
        if within && ei > k_max {
            Verdict::Agrees
        } else {
            Verdict::Differs
        },
        "the secant M/kappa of the section law at every bending integration point",
    ));

    // Fig. 11: curvature.
    let mut series = Vec::new();
    for (i, g) in gs.iter().enumerate() {
        let abs = |v: &[f64]| v.iter().map(|k| k.abs()).collect::<Vec<_>>();
        series.push(Series::xy(
            format!("equivalent, g = {g}"),
            &eqs[i].s,
            &abs(&eqs[i].curvature),
            Mark::Line,
            i,
        ));
        series.push(Series::xy(
            format!("traditional, g = {g}"),
            &trads[i].s,
            &abs(&trads[i].curvature),
            Mark::Dashed,
            i,
        ));
    }
    figs.save(
        "fig11-curvature",
        &Chart {
            title: "Fig. 11: curvature along the strand".into(),
            x_label: "s (m)".into(),
            y_label: "|curvature| (1/m)".into(),
            series,
            ..Default::default()
        },
    )?;
    let curv: Vec<String> = gs
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let e = &eqs[i];
            format!(
                "g = {g}: {:.2} 1/m at the root, {} 1/m at the tip",
                e.curvature[0].abs(),
                sci(e.curvature[e.s.len() - 1].abs())
            )
        })
        .collect();
    let decays = eqs
        .iter()
        .all(|e| e.curvature[e.s.len() - 1].abs() < 1e-2 * e.curvature[0].abs());
    findings.push(Finding::new(
        "Fig. 11",
        "curvature large at the root (all wires slip), near zero at the tip",
        curv.join("; "),
        if decays {
            Verdict::Agrees
        } else {
            Verdict::Differs
        },
        "equivalent model; |curvature| at the clamp (s = 0) and the free end (s = L) of \
         centerline.csv",
    ));

    // Fig. 12: tension near the tip, g = 12.
    let i12 = gs.len() - 1;
    let (e, t) = (&eqs[i12], &trads[i12]);
    let near = |line: &Line| -> Vec<(f64, f64)> {
        line.s
            .iter()
            .zip(&line.tension)
            .filter(|p| *p.0 >= 0.85)
            .map(|(&s, &v)| (s, v))
            .collect()
    };
    let q = strand.mass_per_length() * gs[i12];
    let series = vec![
        Series::new("equivalent, g = 12", near(e), Mark::Line, 0),
        Series::new("traditional, g = 12", near(t), Mark::Dashed, 1),
        Series::new(
            "q (L - x)",
            vec![(0.85, q * (l - 0.85)), (l, 0.0)],
            Mark::Dashed,
            6,
        ),
        Series::new("paper", PAPER_TENSION.to_vec(), Mark::Points, 6),
    ];
    figs.save(
        "fig12-tension",
        &Chart {
            title: "Fig. 12: axial tension near the tip, g = 12".into(),
            x_label: "s (m)".into(),
            y_label: "tension (N)".into(),
            series,
            ..Default::default()
        },
    )?;
    let mut worst: f64 = 0.0;
    let vals: Vec<String> = PAPER_TENSION
        .iter()
        .map(|&(x, paper)| {
            let v = e.at(&e.tension, x);
            let rel = (v - paper) / paper;
            worst = worst.max(rel.abs());
            format!("{v:.4} N at {x} m ({:+.1} %)", 100.0 * rel)
        })
        .collect();
    findings.push(Finding::new(
        "Fig. 12",
        "tension 0.149, 0.14, 0.13 N at x = 0.92, 0.925, 0.93 m (g = 12)",
        vals.join("; "),
        if worst < 0.05 {
            Verdict::Agrees
        } else {
            Verdict::Differs
        },
        format!(
            "equivalent model, interpolated linearly in s between integration points; q (L - x) \
             = {:.4}, {:.4}, {:.4} N. The paper's values are read to 2-3 digits",
            q * (l - 0.92),
            q * (l - 0.925),
            q * (l - 0.93)
        ),
    ));

    // Fig. 13: critical curvature of each wire against the curvature, g = 12.
    let wires = load_wires(&runs[i12].dir.join("equivalent"))?;
    let mut series = Vec::new();
    let mut states = Vec::new();
    let mut mixed = false;
    for (c, &(x, _)) in PAPER_TENSION.iter().enumerate() {
        let j = e.nearest(x);
        let s = e.s[j];
        let k = e.curvature[j].abs();
        let at: Vec<&WireRow> = wires.iter().filter(|w| w.s == s).collect();
        if at.is_empty() {
            bail!("wires.csv has no rows at s = {s}");
        }
        let mut pts: Vec<(f64, f64)> = at
            .iter()
            .map(|w| (w.phase.to_degrees(), w.critical))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(Series::new(
            format!("critical, s = {s:.4} m"),
            pts,
            Mark::Points,
            c,
        ));
        series.push(Series::new(
            format!("|curvature| = {} 1/m", sci(k)),
            vec![(-180.0, k), (180.0, k)],
            Mark::Dashed,
            c,
        ));
        mixed |= at.iter().any(|w| w.slip) && at.iter().any(|w| !w.slip);
        let slip: Vec<String> = at
            .iter()
            .filter(|w| w.slip)
            .map(|w| w.wire.to_string())
            .collect();
        let stick: Vec<String> = at
            .iter()
            .filter(|w| !w.slip)
            .map(|w| format!("{} (phase {:.0} deg)", w.wire, w.phase.to_degrees()))
            .collect();
        states.push(format!(
            "s = {s:.4} m, |kappa| = {} 1/m: wires {} slip, {} stick",
            sci(k),
            if slip.is_empty() {
                "none".into()
            } else {
                slip.join(", ")
            },
            if stick.is_empty() {
                "none".into()
            } else {
                stick.join(", ")
            }
        ));
    }
    figs.save(
        "fig13-critical",
        &Chart {
            title: "Fig. 13: critical curvature of each wire vs curvature, g = 12".into(),
            x_label: "wire phase (deg)".into(),
            y_label: "curvature (1/m)".into(),
            series,
            log_y: true,
            ..Default::default()
        },
    )?;
    // Where the wires slip along the strand.
    let mut series = Vec::new();
    let mut spans = Vec::new();
    let mut root_slips_tip_sticks = true;
    let m = strand.layers().first().map_or(0, |l| l.wires()) as f64;
    for (i, g) in gs.iter().enumerate() {
        let w = load_wires(&runs[i].dir.join("equivalent"))?;
        let along = slipping_along(&w);
        let all_slip_to = along
            .iter()
            .take_while(|p| p.1 == m)
            .last()
            .map_or(0.0, |p| p.0);
        let first_stick = along.iter().find(|p| p.1 < m).map_or(f64::NAN, |p| p.0);
        let tail: Vec<f64> = along
            .iter()
            .filter(|p| p.0 >= 0.9 * l)
            .map(|p| p.1)
            .collect();
        let tail_mean = tail.iter().sum::<f64>() / tail.len().max(1) as f64;
        root_slips_tip_sticks &= along[0].1 == m && tail_mean < m;
        spans.push(format!(
            "g = {g}: all {m} wires slip from the root to s = {all_slip_to:.3} m (first sticking \
             wire at s = {first_stick:.3} m); over the last 10 % of the length {tail_mean:.1} \
             wires slip on average"
        ));
        series.push(Series::new(format!("g = {g}"), along, Mark::Line, i));
    }
    figs.save(
        "fig13-slipping",
        &Chart {
            title: "Where the wires slip: slipping wires along the strand".into(),
            x_label: "s (m)".into(),
            y_label: "slipping wires".into(),
            series,
            ..Default::default()
        },
    )?;
    findings.push(Finding::new(
        "Fig. 13",
        "at x = 0.92, 0.925, 0.93 m, where the stiffness rises toward the tip, comparing the \
         curvature with each wire's critical curvature gives its contact state (some stick, \
         some slip)",
        states.join("; "),
        if mixed {
            Verdict::Agrees
        } else {
            Verdict::Differs
        },
        "continuous law (kappa_c = M_slip / K_stick), not the paper's eq. (23); the critical \
         curvatures are the section law's at the integration point nearest each x",
    ));
    findings.push(Finding::new(
        "Figs. 10-13",
        "all wires slip at the root, wires stick toward the tip",
        spans.join("; "),
        if root_slips_tip_sticks {
            Verdict::Agrees
        } else {
            Verdict::Differs
        },
        "from wires.csv of the equivalent model. Between the root and the tip most points still \
         have all wires slipping; at the free end the tension, hence the friction limit, goes \
         to zero, so the last points slip again",
    ));
    Ok(findings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_slipping_wires_per_point() {
        let w = |s, slip| WireRow {
            s,
            wire: 1,
            phase: 0.0,
            critical: 1.0,
            slip,
        };
        let rows = [w(0.1, true), w(0.1, true), w(0.2, false), w(0.2, true)];
        assert_eq!(slipping_along(&rows), [(0.1, 2.0), (0.2, 1.0)]);
    }
}
