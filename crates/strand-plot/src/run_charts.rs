//! The charts of a run (`strand run --plot`), drawn from its result files so that they show
//! exactly what the files hold (a model that failed draws what it wrote): the shape (with a
//! stated vertical exaggeration where the sag or swing is small beside the length), the
//! curvature and the bending stiffness along s (with K_min and K_max, clipped to a stated
//! band), each wire's stick/slip state along s, and for dynamics the motion at each probe
//! (the tip's path without probes), the moment-curvature loop at each probe, the range
//! envelopes of moment, curvature and tension along s, and the energies; one chart to a file,
//! and an overview with all of them.

use std::path::{Path, PathBuf};

use strand_scene::{Analysis, RunSummary, Scene};

use crate::chart::{Chart, Mark, PlotError, Series, plot_area, save, save_grid};
use crate::table::{Table, TextTable};

/// Palette index of each model's curves.
fn model_color(model: &str) -> usize {
    match model {
        "equivalent" => 0,
        "traditional" => 1,
        _ => 2,
    }
}

/// A model's name in a legend, marked when its run failed.
fn label(s: &RunSummary) -> String {
    if s.failed() {
        format!("{} (failed: what it wrote)", s.model)
    } else {
        s.model.clone()
    }
}

/// Draws the charts of the run of `scene` whose model folders are in `out` and whose
/// summaries are `summaries`, into `out/plots/`; returns the files written.
pub fn plot_run(
    scene: &Scene,
    out: &Path,
    summaries: &[RunSummary],
) -> Result<Vec<PathBuf>, PlotError> {
    let dir = out.join("plots");
    let read = |s: &RunSummary, file: &str| Table::load(&out.join(&s.model).join(file)).ok();
    let lines: Vec<(&RunSummary, Table)> = summaries
        .iter()
        .filter_map(|s| read(s, "centerline.csv").map(|t| (s, t)))
        .collect();
    let name = &scene.name;
    let mut charts: Vec<(String, Chart)> = Vec::new();

    let shape = spread_view(format!("{name}: shape at the end"), &lines, Mark::Line);
    charts.push(("shape".into(), shape));

    let along = |column: &str, keep: &dyn Fn(&RunSummary, &Table, usize) -> bool| {
        lines
            .iter()
            .map(|(s, t)| {
                let (x, y) = (t.column("s"), t.column(column));
                let points = (0..x.len())
                    .filter(|&i| keep(s, t, i))
                    .map(|i| (x[i], y[i]))
                    .collect();
                Series::new(label(s), points, Mark::Line, model_color(&s.model))
            })
            .collect::<Vec<_>>()
    };
    let curvature = Chart {
        title: format!("{name}: curvature along the strand"),
        x_label: "s (m)".into(),
        y_label: if scene.is_planar() {
            "curvature kappa_z (1/m)".into()
        } else {
            "|curvature| (1/m)".into()
        },
        series: along("curvature", &|_, _, _| true),
        ..Chart::default()
    };
    charts.push(("curvature".into(), curvature));

    // Bending stiffness, with the section's bounds. The fine model's measured M / kappa is
    // drawn where its curvature is above 1 % of its largest (near zero curvature it is the
    // ratio of two small, noisy numbers).
    let strand = &scene.strand;
    let (k_min, k_max) = (
        strand.min_bending_stiffness(scene.section.base_stiffness),
        strand.max_bending_stiffness(scene.section.base_stiffness),
    );
    let bent = |s: &RunSummary, t: &Table, i: usize| {
        if s.model != "fine" {
            return true;
        }
        let k = t.column("curvature");
        let top = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        k[i].abs() > 1e-2 * top
    };
    let mut series = along("bending_stiffness", &bent);
    let band = stiffness_band(&series, k_max);
    let ends = (0.0, strand.length());
    if !strand.layers().is_empty() {
        for (k, what, color) in [(k_min, "K_min", 6), (k_max, "K_max", 3)] {
            series.push(Series::new(
                format!("{what} = {} N m^2", short(k)),
                vec![(ends.0, k), (ends.1, k)],
                Mark::Dashed,
                color,
            ));
        }
    }
    let stiffness = Chart {
        title: format!("{name}: bending stiffness M/kappa along the strand"),
        x_label: "s (m)".into(),
        y_label: "bending stiffness (N m^2)".into(),
        series,
        note: {
            let mut notes = Vec::new();
            if let Some((_, top)) = band {
                notes.push(format!(
                    "secant M/kappa clipped to 0..{} N m^2 (residual slip moments at small \
                     kappa send it far out)",
                    short(top)
                ));
            }
            if lines.iter().any(|(s, _)| s.model == "fine") {
                notes.push("fine model: where |kappa| > 1 % of its largest".to_string());
            }
            (!notes.is_empty()).then(|| notes.join("; "))
        },
        y_range: band,
        ..Chart::default()
    };
    charts.push(("stiffness".into(), stiffness));

    // Stick/slip maps: the beams' wires.csv, the fine model's contacts.csv; sticking points
    // drawn last, over the slipping ones (slip is the common state of a bent strand).
    for s in summaries {
        let (file, states): (&str, &[(&str, usize)]) = if s.model == "fine" {
            ("contacts.csv", &[("slip", 1), ("open", 4), ("stick", 0)])
        } else {
            ("wires.csv", &[("slip", 1), ("stick", 0)])
        };
        let Ok(rows) = TextTable::load(&out.join(&s.model).join(file)) else {
            continue;
        };
        if rows.is_empty() {
            continue;
        }
        // One map per layer of a strand of several (the beams' `layer` column; the fine
        // model's contacts and a one-layer strand's wires are one map).
        let layer_of = |r: &crate::table::TextRow<'_>| r.number("layer").unwrap_or(1.0);
        let layers = rows.rows().map(|r| layer_of(&r)).fold(1.0, f64::max) as usize;
        for layer in 1..=layers {
            let in_layer = |r: &crate::table::TextRow<'_>| layer_of(r) == layer as f64;
            let wires = rows
                .rows()
                .filter(in_layer)
                .filter_map(|r| r.number("wire"))
                .fold(1.0, f64::max);
            let series = states
                .iter()
                .map(|(state, color)| {
                    let points = rows
                        .rows()
                        .filter(in_layer)
                        .filter(|r| r.get("state") == Some(state))
                        .filter_map(|r| Some((r.number("s")?, r.number("wire")?)))
                        .collect();
                    Series::new(*state, points, Mark::Dots, *color)
                })
                .filter(|s| !s.points.is_empty())
                .collect();
            let (key, of_layer) = if layers > 1 {
                (
                    format!("stick-slip-{}-layer-{layer}", s.model),
                    format!(", layer {layer}"),
                )
            } else {
                (format!("stick-slip-{}", s.model), String::new())
            };
            charts.push((
                key,
                Chart {
                    title: format!(
                        "{name}: wire states along the strand, {}{of_layer}",
                        label(s)
                    ),
                    x_label: "s (m)".into(),
                    y_label: "wire".into(),
                    series,
                    // Room above the last wire for the legend.
                    y_range: Some((0.4, wires + 1.4)),
                    ..Chart::default()
                },
            ));
        }
    }

    if matches!(scene.analysis, Analysis::Dynamic(_)) {
        if scene.output.probes.is_empty() {
            let tips: Vec<(&RunSummary, Table)> = summaries
                .iter()
                .filter_map(|s| read(s, "tip.csv").map(|t| (s, t)))
                .collect();
            charts.push((
                "tip".into(),
                spread_view(format!("{name}: path of the tip"), &tips, Mark::Trace),
            ));
        }
        for &at in &scene.output.probes {
            let file = strand_scene::probe::file_name(at);
            let runs: Vec<(&RunSummary, Table)> = summaries
                .iter()
                .filter_map(|s| read(s, &file).map(|t| (s, t)))
                .collect();
            if runs.is_empty() {
                continue;
            }
            let stem = file.trim_end_matches(".csv").replace('_', "-");
            charts.push((
                format!("{stem}-motion"),
                probe_motion(format!("{name}: motion at s = {} m", short(at)), &runs),
            ));
            charts.push((
                format!("{stem}-loop"),
                probe_loop(
                    format!("{name}: moment-curvature at s = {} m", short(at)),
                    &runs,
                ),
            ));
        }
        let ranges: Vec<(&RunSummary, Table)> = summaries
            .iter()
            .filter_map(|s| read(s, "range.csv").map(|t| (s, t)))
            .collect();
        let window = scene
            .output
            .range_window
            .map_or("over the run".to_string(), |(a, b)| {
                format!("over t in [{}, {}] s", short(a), short(b))
            });
        for (q, what, unit) in [
            ("moment", "bending moment", "N m"),
            ("curvature", "curvature", "1/m"),
            ("tension", "tension", "N"),
        ] {
            if ranges.is_empty() {
                break;
            }
            charts.push((
                format!("range-{q}"),
                envelope(
                    format!("{name}: {what} range along the strand, {window}"),
                    &ranges,
                    q,
                    &format!("{what} ({unit})"),
                ),
            ));
        }
        for s in summaries {
            let Some(e) = read(s, "energy.csv") else {
                continue;
            };
            let t = e.column("t");
            let series = [
                ("kinetic", 0),
                ("gravity", 1),
                ("elastic", 2),
                ("dissipated", 3),
                ("total", 6),
            ]
            .iter()
            .map(|(c, color)| Series::xy(*c, &t, &e.column(c), Mark::Line, *color))
            .collect();
            charts.push((
                format!("energy-{}", s.model),
                Chart {
                    title: format!("{name}: energies, {}", label(s)),
                    x_label: "t (s)".into(),
                    y_label: "energy (J)".into(),
                    series,
                    ..Chart::default()
                },
            ));
        }
    }

    let mut files = Vec::new();
    for (stem, chart) in &charts {
        files.extend(save(chart, &dir, stem)?);
    }
    let all: Vec<Chart> = charts.into_iter().map(|(_, c)| c).collect();
    files.extend(save_grid(&all, 2, &dir, "overview")?);
    Ok(files)
}

/// The band the bending stiffness chart is clipped to, `(0, top)` with `top` 1.5 times the
/// larger of K_max and each series' median (the traditional beam's constant EI may exceed
/// K_max); `None` when every point lies in the band already.
fn stiffness_band(series: &[Series], k_max: f64) -> Option<(f64, f64)> {
    let mut top = k_max;
    for s in series {
        let mut v: Vec<f64> = s
            .points
            .iter()
            .map(|p| p.1)
            .filter(|v| v.is_finite())
            .collect();
        if v.is_empty() {
            continue;
        }
        v.sort_by(f64::total_cmp);
        top = top.max(v[v.len() / 2]);
    }
    let top = 1.5 * top;
    let inside = series
        .iter()
        .flat_map(|s| &s.points)
        .all(|p| !p.1.is_finite() || (0.0..=top).contains(&p.1));
    (top > 0.0 && !inside).then_some((0.0, top))
}

/// The work of the moment along the path `(kappa, M)` (J/m): the trapezoidal sum of
/// M dkappa, the area of a closed loop (what the section dissipated over it, the slip work).
fn loop_work(kappa: &[f64], moment: &[f64]) -> f64 {
    kappa
        .windows(2)
        .zip(moment.windows(2))
        .map(|(k, m)| 0.5 * (m[0] + m[1]) * (k[1] - k[0]))
        .filter(|w| w.is_finite())
        .sum()
}

/// The moment-curvature path at a probe, per model. Where the curvature cycles (at least two
/// upward crossings of the middle of its late range), the whole run is drawn pale and its last
/// full cycle in full colour, with that cycle's area (the work of M dkappa over it, J/m): a
/// long run's thousands of frames of a growing or decaying motion overlap into a tangle, and
/// the last cycle is the loop the motion settled to. Else the whole path, with its work.
fn probe_loop(title: String, runs: &[(&RunSummary, Table)]) -> Chart {
    let mut pale = Vec::new();
    let mut solid = Vec::new();
    let mut cycled = false;
    for (s, t) in runs {
        let (time, k, m) = (t.column("t"), t.column("curvature"), t.column("moment"));
        let color = model_color(&s.model);
        match crate::cycle::last_cycle(&k) {
            Some(c) => {
                cycled = true;
                pale.push(Series::xy(
                    format!("{}: the whole run", label(s)),
                    &k,
                    &m,
                    Mark::Faint,
                    color,
                ));
                solid.push(Series::xy(
                    format!(
                        "{}: t = {} to {} s, area {} J/m",
                        label(s),
                        short(time[*c.start()]),
                        short(time[*c.end()]),
                        short(loop_work(&k[c.clone()], &m[c.clone()]))
                    ),
                    &k[c.clone()],
                    &m[c],
                    Mark::Trace,
                    color,
                ));
            }
            None => solid.push(Series::xy(
                format!(
                    "{}: work of M dkappa {} J/m",
                    label(s),
                    short(loop_work(&k, &m))
                ),
                &k,
                &m,
                Mark::Trace,
                color,
            )),
        }
    }
    pale.extend(solid);
    Chart {
        title,
        x_label: "curvature (1/m)".into(),
        y_label: "bending moment (N m)".into(),
        series: pale,
        note: cycled.then(|| {
            "solid: the last full cycle of the curvature; its area (M dkappa) is the slip \
             work where the loop closes; pale: the whole run"
                .to_string()
        }),
        ..Chart::default()
    }
}

/// The motion at a probe over time: each coordinate (of x, y, z) that moves at least a fifth
/// as far as the one that moves most (over all the runs), as its displacement from where it
/// starts; the one that moves most solid, the others dashed. A span pulled along its length
/// moves along x by the pull and across by its swing, and both show.
fn probe_motion(title: String, runs: &[(&RunSummary, Table)]) -> Chart {
    let spread = |c: &str| {
        runs.iter()
            .flat_map(|(_, t)| {
                let v = t.column(c);
                let first = v.first().copied().unwrap_or(0.0);
                v.into_iter().map(move |x| (x - first).abs())
            })
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::max)
    };
    let mut axes: Vec<(&str, f64)> = ["x", "y", "z"]
        .into_iter()
        .map(|a| (a, spread(a)))
        .collect();
    axes.sort_by(|a, b| b.1.total_cmp(&a.1));
    let top = axes[0].1;
    axes.retain(|(_, d)| *d >= 0.2 * top);
    let many = axes.len() > 1;
    let mut series = Vec::new();
    for (i, (axis, _)) in axes.iter().enumerate() {
        for (s, t) in runs {
            let v = t.column(axis);
            let first = v.first().copied().unwrap_or(0.0);
            let d: Vec<f64> = v.iter().map(|x| x - first).collect();
            let name = if many {
                format!("{}: {axis}", label(s))
            } else {
                label(s)
            };
            let mark = if i == 0 { Mark::Line } else { Mark::Dashed };
            series.push(Series::xy(
                name,
                &t.column("t"),
                &d,
                mark,
                model_color(&s.model),
            ));
        }
    }
    let names: Vec<&str> = axes.iter().map(|a| a.0).collect();
    Chart {
        title,
        x_label: "t (s)".into(),
        y_label: format!("displacement along {} (m)", names.join(", ")),
        series,
        ..Chart::default()
    }
}

/// The range envelope of quantity `q` along s from `range.csv`: each model's min and max
/// (solid) and mean (dashed).
fn envelope(title: String, runs: &[(&RunSummary, Table)], q: &str, y_label: &str) -> Chart {
    let mut series = Vec::new();
    for (s, t) in runs {
        let x = t.column("s");
        let c = model_color(&s.model);
        let name = label(s);
        series.push(Series::xy(
            format!("{name} min, max"),
            &x,
            &t.column(&format!("{q}_max")),
            Mark::Line,
            c,
        ));
        series.push(Series::xy(
            "",
            &x,
            &t.column(&format!("{q}_min")),
            Mark::Line,
            c,
        ));
        series.push(Series::xy(
            format!("{name} mean"),
            &x,
            &t.column(&format!("{q}_mean")),
            Mark::Dashed,
            c,
        ));
    }
    Chart {
        title,
        x_label: "s (m)".into(),
        y_label: y_label.into(),
        series,
        ..Chart::default()
    }
}

/// The vertical exaggeration that makes a shape spreading `dx` across and `dy` up fill about
/// half the plot's height: 1 where at equal scale it fills a quarter or more, else the
/// largest of 1, 2, 5 times a power of ten not above the factor that fills half.
fn exaggeration(dx: f64, dy: f64) -> f64 {
    let (w, h) = plot_area();
    let fill = if dx > 0.0 { (dy / dx) * (w / h) } else { 1.0 };
    if fill.is_nan() || fill <= 0.0 || fill >= 0.25 {
        return 1.0;
    }
    let target = 0.5 / fill;
    let decade = 10f64.powf(target.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&f| f <= target)
        .unwrap_or(decade)
        .max(1.0)
}

/// `v` with 4 significant digits: plain between 1e-3 and 1e4, with an exponent outside.
fn short(v: f64) -> String {
    let a = v.abs();
    if (1e-3..1e4).contains(&a) {
        let digits = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

/// Each run's points (columns x, y, z, m) drawn in the plane of the two axes along which they
/// spread most, at equal scale, or with the vertical scale exaggerated by a factor the y label
/// states where the vertical spread is small beside the horizontal one (a sag on a span).
fn spread_view(title: String, runs: &[(&RunSummary, Table)], mark: Mark) -> Chart {
    let axes = spread_axes(runs.iter().map(|(_, t)| t));
    let axis_name = ["x", "y", "z"];
    let extent = |a: usize| {
        let v: Vec<f64> = runs
            .iter()
            .flat_map(|(_, t)| t.column(axis_name[a]))
            .filter(|v| v.is_finite())
            .collect();
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (hi - lo).max(0.0)
    };
    let e = exaggeration(extent(axes.0), extent(axes.1));
    let y_label = if e > 1.0 {
        format!("{} (m, scale x {})", axis_name[axes.1], e)
    } else {
        format!("{} (m)", axis_name[axes.1])
    };
    Chart {
        title,
        x_label: format!("{} (m)", axis_name[axes.0]),
        y_label,
        vertical_exaggeration: (e > 1.0).then_some(e),
        series: runs
            .iter()
            .map(|(s, t)| {
                Series::xy(
                    label(s),
                    &t.column(axis_name[axes.0]),
                    &t.column(axis_name[axes.1]),
                    mark,
                    model_color(&s.model),
                )
            })
            .collect(),
        equal_aspect: true,
        ..Chart::default()
    }
}

/// The two coordinates (0 = x, 1 = y, 2 = z), in order, along which the points of the `x`,
/// `y`, `z` columns spread most: the plane of a planar scene, the main plane of motion else.
fn spread_axes<'a>(tables: impl Iterator<Item = &'a Table>) -> (usize, usize) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for t in tables {
        for (a, c) in ["x", "y", "z"].iter().enumerate() {
            for v in t.column(c).into_iter().filter(|v| v.is_finite()) {
                lo[a] = lo[a].min(v);
                hi[a] = hi[a].max(v);
            }
        }
    }
    let spread = |a: usize| (hi[a] - lo[a]).max(0.0);
    // The axis with the least spread is left out (z on a tie: the planar convention).
    let out = (0..3)
        .rev()
        .min_by(|&a, &b| spread(a).total_cmp(&spread(b)))
        .unwrap_or(2);
    match out {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_axes_leave_out_the_flattest() {
        let t = |rows: &str| {
            let p = std::env::temp_dir().join(format!(
                "strand-plot-axes-{}-{}.csv",
                std::process::id(),
                rows.len()
            ));
            std::fs::write(&p, format!("x,y,z\n{rows}")).unwrap();
            let t = Table::load(&p).unwrap();
            std::fs::remove_file(p).unwrap();
            t
        };
        assert_eq!(spread_axes([t("0,0,0\n1,-2,0\n")].iter()), (0, 1));
        assert_eq!(spread_axes([t("0,0,0\n1,0,-2\n")].iter()), (0, 2));
        assert_eq!(spread_axes([t("0,0,0\n0,1,-2\n")].iter()), (1, 2));
        assert_eq!(spread_axes(std::iter::empty()), (0, 1));
        assert_eq!(short(0.05334), "0.05334");
        assert_eq!(short(1.94), "1.940");
        assert_eq!(short(2.5e-5), "2.500e-5");
    }

    /// A flat shape is exaggerated by a round factor that makes it fill between a quarter
    /// and about half of the height; one that fills a quarter at equal scale is not.
    #[test]
    fn exaggeration_fills_the_height_with_a_round_factor() {
        let (w, h) = plot_area();
        for (dx, dy) in [(50.0, 0.43), (50.0, 0.05), (2.0, 0.01), (1.0, 1e-6)] {
            let e = exaggeration(dx, dy);
            let fill = dy * e / dx * w / h;
            assert!(
                (0.2..=0.5 + 1e-12).contains(&fill),
                "{dx} {dy}: x {e} fills {fill}"
            );
            let m = e / 10f64.powf(e.log10().floor());
            assert!([1.0, 2.0, 5.0].iter().any(|r| (m - r).abs() < 1e-9), "{e}");
        }
        assert_eq!(exaggeration(2.0, 1.0), 1.0);
        assert_eq!(exaggeration(2.0, 0.0), 1.0);
        assert_eq!(exaggeration(0.0, 1.0), 1.0);
    }
}
