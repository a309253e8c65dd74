//! Charts: line and point series on linear or log axes, written as PNG and SVG with an
//! embedded font (DejaVu Sans), so text renders on a machine without system fonts; one chart
//! to a file ([`save`]) or several on a grid ([`save_grid`]).

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

/// Pixel size of a chart.
const SIZE: (u32, u32) = (900, 560);

/// What a chart's axes, labels and title take of its width and height (pixels): the plot
/// area is the chart's size less this.
pub const PLOT_MARGIN: (f64, f64) = (102.0, 92.0);

/// The plot area of one chart (pixels), width by height.
pub fn plot_area() -> (f64, f64) {
    (
        f64::from(SIZE.0) - PLOT_MARGIN.0,
        f64::from(SIZE.1) - PLOT_MARGIN.1,
    )
}

/// A chart that could not be drawn or written.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {message}")]
pub struct PlotError {
    /// The file.
    pub path: String,
    /// What failed.
    pub message: String,
}

/// A drawing error of plotters, as text (its error types borrow the backend).
fn draw_err<E: std::fmt::Debug>(e: E) -> String {
    format!("{e:?}")
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// Solid line.
    Line,
    /// Dashed line.
    Dashed,
    /// Filled circles.
    Points,
    /// Hollow circles.
    Rings,
    /// Small filled squares, for dense maps (many points side by side).
    Dots,
    /// Solid line with large hollow circles at the points (a Pareto front).
    Front,
    /// Thin solid line, for paths that turn back on themselves (hysteresis loops, orbits):
    /// the thick line's mitred joints would draw spikes past a reversal in the bitmap.
    Trace,
    /// A [`Mark::Trace`] in a pale tint of its colour: the background of a path (the whole
    /// run under its last cycle).
    Faint,
}

/// One curve or point set of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry; empty for none.
    pub label: String,
    /// (x, y) in the chart's units.
    pub points: Vec<(f64, f64)>,
    /// How to draw it.
    pub mark: Mark,
    /// Index into the palette.
    pub color: usize,
}

impl Series {
    /// A series from points.
    pub fn new(
        label: impl Into<String>,
        points: Vec<(f64, f64)>,
        mark: Mark,
        color: usize,
    ) -> Self {
        Series {
            label: label.into(),
            points,
            mark,
            color,
        }
    }

    /// A series from separate x and y columns.
    pub fn xy(label: impl Into<String>, x: &[f64], y: &[f64], mark: Mark, color: usize) -> Self {
        Series::new(
            label,
            x.iter().copied().zip(y.iter().copied()).collect(),
            mark,
            color,
        )
    }
}

/// A chart: title, axis labels, series, and an optional note printed under the title.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Chart {
    /// Title.
    pub title: String,
    /// Label of the x axis, with its unit.
    pub x_label: String,
    /// Label of the y axis, with its unit.
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Log-log axes (non-positive values are left out).
    pub log: bool,
    /// Log y axis on a linear x axis (ignored when `log` is set).
    pub log_y: bool,
    /// Same scale on both axes (shapes).
    pub equal_aspect: bool,
    /// With `equal_aspect`: a unit of y drawn this many times longer than a unit of x (a
    /// vertical exaggeration, which the y label should state); `None` for 1.
    pub vertical_exaggeration: Option<f64>,
    /// A line of text inside the plot area, e.g. what is not available.
    pub note: Option<String>,
    /// The y axis's range instead of the data's (linear axes).
    pub y_range: Option<(f64, f64)>,
}

/// The palette: colour-blind-safe (Okabe-Ito) plus black.
pub fn color(i: usize) -> RGBColor {
    const C: [RGBColor; 8] = [
        RGBColor(0, 114, 178),
        RGBColor(213, 94, 0),
        RGBColor(0, 158, 115),
        RGBColor(204, 121, 167),
        RGBColor(230, 159, 0),
        RGBColor(86, 180, 233),
        RGBColor(0, 0, 0),
        RGBColor(240, 228, 66),
    ];
    C[i % C.len()]
}

/// A pale tint of `c`: a quarter of it over white (opaque, so that overlapping pale paths do
/// not darken into a solid line).
pub fn pale(c: RGBColor) -> RGBColor {
    let tint = |v: u8| (0.25 * f64::from(v) + 0.75 * 255.0).round() as u8;
    RGBColor(tint(c.0), tint(c.1), tint(c.2))
}

/// Registers the embedded DejaVu Sans as plotters' `sans-serif` (once per process).
pub fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .unwrap_or_else(|_| panic!("the embedded DejaVu Sans is a valid font"));
    });
}

/// Writes `chart` as `dir/stem.png` and `dir/stem.svg`; returns both paths.
pub fn save(chart: &Chart, dir: &Path, stem: &str) -> Result<Vec<PathBuf>, PlotError> {
    save_grid(std::slice::from_ref(chart), 1, dir, stem)
}

/// Writes `charts` on a grid of `columns` columns (each cell the size of one chart) as
/// `dir/stem.png` and `dir/stem.svg`; returns both paths.
pub fn save_grid(
    charts: &[Chart],
    columns: usize,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, PlotError> {
    register_fonts();
    let fail = |p: &Path| {
        let path = p.display().to_string();
        move |message: String| PlotError {
            path: path.clone(),
            message,
        }
    };
    std::fs::create_dir_all(dir).map_err(|e| fail(dir)(e.to_string()))?;
    let columns = columns.clamp(1, charts.len().max(1));
    let rows = charts.len().div_ceil(columns).max(1);
    let size = (SIZE.0 * columns as u32, SIZE.1 * rows as u32);
    let png = dir.join(format!("{stem}.png"));
    let svg = dir.join(format!("{stem}.svg"));
    {
        let root = BitMapBackend::new(&png, size).into_drawing_area();
        draw_grid(&root, charts, rows, columns).map_err(fail(&png))?;
        root.present().map_err(|e| fail(&png)(draw_err(e)))?;
    }
    {
        let root = SVGBackend::new(&svg, size).into_drawing_area();
        draw_grid(&root, charts, rows, columns).map_err(fail(&svg))?;
        root.present().map_err(|e| fail(&svg)(draw_err(e)))?;
    }
    Ok(vec![png, svg])
}

fn draw_grid<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    charts: &[Chart],
    rows: usize,
    columns: usize,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(draw_err)?;
    for (cell, chart) in root.split_evenly((rows, columns)).iter().zip(charts) {
        render(cell, chart)?;
    }
    Ok(())
}

/// The range of the finite values (positive ones only for log axes), padded by 5 %
/// (a factor on log axes); `(0, 1)` when there are none.
pub fn range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return if log { (0.1, 10.0) } else { (0.0, 1.0) };
    }
    if log {
        let f = (hi / lo).powf(0.05).max(1.2);
        (lo / f, hi * f)
    } else {
        let pad = if hi > lo {
            0.05 * (hi - lo)
        } else {
            0.05 * hi.abs().max(1e-12)
        };
        (lo - pad, hi + pad)
    }
}

/// Widens the shorter range so that one unit has the same length on both axes of a plot area
/// of `width` x `height` pixels.
fn equalize(x: (f64, f64), y: (f64, f64), width: f64, height: f64) -> ((f64, f64), (f64, f64)) {
    let (sx, sy) = ((x.1 - x.0) / width, (y.1 - y.0) / height);
    if sx > sy {
        let c = 0.5 * (y.0 + y.1);
        let h = 0.5 * sx * height;
        (x, (c - h, c + h))
    } else {
        let c = 0.5 * (x.0 + x.1);
        let w = 0.5 * sy * width;
        ((c - w, c + w), y)
    }
}

/// Tick labels for an axis spanning `range`: zero for values within 1e-9 of the span of
/// zero, plain decimals between 1e-2 and 1e4, else scientific notation with the digits that
/// tell ticks a twentieth of the span apart (1.5e-3 beside 1e-3, not both `2e-3`).
fn tick_label(range: (f64, f64)) -> impl Fn(&f64) -> String {
    let span = (range.1 - range.0).abs();
    move |v: &f64| {
        let a = v.abs();
        if a <= 1e-9 * span {
            "0".into()
        } else if (1e-2..1e4).contains(&a) {
            format!("{}", (v * 1e4).round() / 1e4)
        } else {
            let digits = (a / (span / 20.0)).log10().ceil().clamp(0.0, 6.0) as usize;
            let text = format!("{v:.digits$e}");
            // 1.0e-3 as 1e-3: trailing zeros of the mantissa dropped.
            match text.split_once('e') {
                Some((m, e)) if m.contains('.') => {
                    format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
                }
                _ => text,
            }
        }
    }
}

/// Draws the series of `chart` on an already built chart context (linear or log axes).
macro_rules! draw_series {
    ($ctx:expr, $chart:expr, $keep:expr, $corner:expr) => {{
        let err = draw_err;
        for s in &$chart.series {
            let c = color(s.color);
            let pts: Vec<(f64, f64)> = s.points.iter().copied().filter($keep).collect();
            let anno = match s.mark {
                Mark::Line => $ctx
                    .draw_series(LineSeries::new(pts, c.stroke_width(2)))
                    .map_err(err)?,
                Mark::Trace => $ctx
                    .draw_series(LineSeries::new(pts, c.stroke_width(1)))
                    .map_err(err)?,
                Mark::Faint => $ctx
                    .draw_series(LineSeries::new(pts, pale(c).stroke_width(1)))
                    .map_err(err)?,
                Mark::Dashed => $ctx
                    .draw_series(DashedLineSeries::new(pts, 8, 5, c.stroke_width(2)))
                    .map_err(err)?,
                Mark::Points => $ctx
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.filled())))
                    .map_err(err)?,
                Mark::Rings => $ctx
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 5, c.stroke_width(2))))
                    .map_err(err)?,
                Mark::Dots => $ctx
                    .draw_series(pts.iter().map(|&p| {
                        EmptyElement::at(p) + Rectangle::new([(-2, -3), (2, 3)], c.filled())
                    }))
                    .map_err(err)?,
                Mark::Front => {
                    $ctx.draw_series(pts.iter().map(|&p| Circle::new(p, 9, c.stroke_width(2))))
                        .map_err(err)?;
                    $ctx.draw_series(LineSeries::new(pts, c.stroke_width(2)))
                        .map_err(err)?
                }
            };
            if !s.label.is_empty() {
                let mark = s.mark;
                let c = if mark == Mark::Faint { pale(c) } else { c };
                // Two segments: contiguous for lines, apart for dashes, one thick dot for
                // points.
                let (a, b, w) = match mark {
                    Mark::Dashed => ((0, 7), (13, 20), 2),
                    Mark::Points | Mark::Rings | Mark::Dots => ((7, 10), (10, 13), 7),
                    _ => ((0, 10), (10, 20), 2),
                };
                anno.label(s.label.clone()).legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(a.0, 0), (a.1, 0)], c.stroke_width(w))
                        + PathElement::new(vec![(b.0, 0), (b.1, 0)], c.stroke_width(w))
                });
            }
        }
        if $chart.series.iter().any(|s| !s.label.is_empty()) {
            $ctx.configure_series_labels()
                .position($corner)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.5))
                .label_font(("sans-serif", 14))
                .draw()
                .map_err(err)?;
        }
    }};
}

fn render<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, chart: &Chart) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let err = draw_err;
    root.fill(&WHITE).map_err(err)?;
    let all = || chart.series.iter().flat_map(|s| s.points.iter());
    let xr = range(all().map(|p| p.0), chart.log);
    let yr = match chart.y_range {
        Some(r) if !(chart.log || chart.log_y) => r,
        _ => range(all().map(|p| p.1), chart.log || chart.log_y),
    };
    // Room at the bottom of a linear range for the note's lines (18 px each, 20 px up from
    // the bottom of a plot area of about PLOT_MARGIN less than the chart), so that the note
    // covers no curve.
    let yr = match &chart.note {
        Some(text) if !(chart.log || chart.log_y || chart.equal_aspect) => {
            let (_, h) = root.dim_in_pixel();
            let rows = text.lines().count() as f64;
            let share = (20.0 + 18.0 * rows) / (f64::from(h) - PLOT_MARGIN.1).max(1.0);
            (yr.0 - share * (yr.1 - yr.0), yr.1)
        }
        _ => yr,
    };
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(&chart.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(78);
    let (fx, fy) = (tick_label(xr), tick_label(yr));
    macro_rules! mesh_and_series {
        ($ctx:expr, $keep:expr, $corner:expr) => {{
            let mut ctx = $ctx;
            ctx.configure_mesh()
                .x_desc(&chart.x_label)
                .y_desc(&chart.y_label)
                .x_label_formatter(&fx)
                .y_label_formatter(&fy)
                .label_style(("sans-serif", 14))
                .axis_desc_style(("sans-serif", 16))
                .draw()
                .map_err(err)?;
            draw_series!(ctx, chart, $keep, $corner);
            note(&ctx.plotting_area().strip_coord_spec(), chart)?;
        }};
    }
    if chart.log {
        mesh_and_series!(
            builder
                .build_cartesian_2d((xr.0..xr.1).log_scale(), (yr.0..yr.1).log_scale())
                .map_err(err)?,
            |p: &(f64, f64)| p.0 > 0.0 && p.1 > 0.0,
            legend_corner(chart, xr, yr, (true, true))
        );
    } else if chart.log_y {
        mesh_and_series!(
            builder
                .build_cartesian_2d(xr.0..xr.1, (yr.0..yr.1).log_scale())
                .map_err(err)?,
            |p: &(f64, f64)| p.0.is_finite() && p.1 > 0.0,
            legend_corner(chart, xr, yr, (false, true))
        );
    } else {
        let (xr, yr) = if chart.equal_aspect {
            let (w, h) = root.dim_in_pixel();
            let e = chart.vertical_exaggeration.unwrap_or(1.0);
            let (w, h) = (f64::from(w) - PLOT_MARGIN.0, f64::from(h) - PLOT_MARGIN.1);
            let (xr, (y0, y1)) = equalize(xr, (yr.0 * e, yr.1 * e), w, h);
            (xr, (y0 / e, y1 / e))
        } else {
            (xr, yr)
        };
        mesh_and_series!(
            builder
                .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
                .map_err(err)?,
            |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite(),
            legend_corner(chart, xr, yr, (false, false))
        );
    }
    Ok(())
}

/// The corner of the plot area where the legend hides the fewest points: of the four boxes of
/// 40 % of the width and 30 % of the height at the corners (on the axes' scales, `log` for a
/// log axis), the one holding the fewest; the upper right on a tie; one of the upper two when
/// the chart has a note (printed at the bottom).
fn legend_corner(
    chart: &Chart,
    x: (f64, f64),
    y: (f64, f64),
    log: (bool, bool),
) -> SeriesLabelPosition {
    let unit = |v: f64, (lo, hi): (f64, f64), log: bool| {
        if log {
            (v.ln() - lo.ln()) / (hi.ln() - lo.ln())
        } else {
            (v - lo) / (hi - lo)
        }
    };
    let mut counts = [0usize; 4];
    for p in chart.series.iter().flat_map(|s| s.points.iter()) {
        let (u, v) = (unit(p.0, x, log.0), unit(p.1, y, log.1));
        if !(u.is_finite() && v.is_finite()) {
            continue;
        }
        let (left, right, low, high) = (u < 0.4, u > 0.6, v < 0.3, v > 0.7);
        for (i, inside) in [high && right, high && left, low && right, low && left]
            .into_iter()
            .enumerate()
        {
            counts[i] += usize::from(inside);
        }
    }
    // A note is printed along the bottom of the plot area: the legend keeps to the top.
    let corners = if chart.note.is_some() { 0..2 } else { 0..4 };
    match corners.min_by_key(|&i| counts[i]).unwrap_or(0) {
        0 => SeriesLabelPosition::UpperRight,
        1 => SeriesLabelPosition::UpperLeft,
        2 => SeriesLabelPosition::LowerRight,
        _ => SeriesLabelPosition::LowerLeft,
    }
}

/// Prints the chart's note at the lower left of the plot area.
fn note<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, chart: &Chart) -> Result<(), String> {
    if let Some(text) = &chart.note {
        let (_, h) = area.dim_in_pixel();
        for (i, line) in text.lines().rev().enumerate() {
            area.draw_text(
                line,
                &("sans-serif", 14).into_font().color(&RGBColor(150, 0, 0)),
                (8, h as i32 - 20 - 18 * i as i32),
            )
            .map_err(draw_err)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_padded_and_log_ranges_positive() {
        let (lo, hi) = range([1.0, 3.0, f64::NAN].into_iter(), false);
        assert!((lo - 0.9).abs() < 1e-12 && (hi - 3.1).abs() < 1e-12);
        let (lo, hi) = range([-1.0, 1e-3, 1e2].into_iter(), true);
        assert!(lo > 0.0 && lo < 1e-3 && hi > 1e2);
        assert_eq!(range(std::iter::empty(), false), (0.0, 1.0));
    }

    /// Ticks a twentieth of the span apart read differently: 1.5e-3 is not rounded to 2e-3.
    #[test]
    fn small_tick_labels_keep_the_digits_that_tell_them_apart() {
        let f = tick_label((-3e-3, 7e-3));
        assert_eq!(f(&1.5e-3), "1.5e-3");
        assert_eq!(f(&1e-3), "1e-3");
        assert_eq!(f(&-2.5e-3), "-2.5e-3");
        assert_eq!(f(&1e-12), "0");
        assert_eq!(tick_label((0.0, 5e5))(&2e5), "2e5");
    }

    #[test]
    fn equal_aspect_widens_the_short_range() {
        let (x, y) = equalize((0.0, 1.0), (0.0, 0.1), 100.0, 100.0);
        assert_eq!(x, (0.0, 1.0));
        assert!((y.1 - y.0 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn writes_png_and_svg_with_text() {
        let dir = std::env::temp_dir().join(format!("strand-plot-{}", std::process::id()));
        let chart = Chart {
            title: "test".into(),
            x_label: "x (m)".into(),
            y_label: "y (m)".into(),
            series: vec![Series::new(
                "a",
                vec![(1.0, 1.0), (2.0, 4.0)],
                Mark::Front,
                0,
            )],
            log: true,
            note: Some("note".into()),
            ..Default::default()
        };
        let files = save(&chart, &dir, "t").unwrap();
        let svg = std::fs::read_to_string(&files[1]).unwrap();
        assert!(svg.contains("x (m)") && svg.contains("note"));
        assert!(std::fs::metadata(&files[0]).unwrap().len() > 1000);
        std::fs::remove_dir_all(dir).unwrap();
    }
}
