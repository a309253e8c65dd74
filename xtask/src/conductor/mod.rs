//! `cargo xtask conductor`: the equivalent section law of a multi-layer conductor against the
//! one public measured moment-curvature curve, Cardinal ACSR 54/7 at 40 kN
//! (`validation/conductor/`, its README for the provenance of the curve and of the scene's
//! geometry, lay lengths and materials).
//!
//! The curve on first loading is computed at the measured curvatures, the strand bent from
//! straight and unslipped (`strand_scene::loading_moments`, the hysteretic law averaged over
//! stations that take every layer over its own whole pitch, as `strand bend --model
//! equivalent` draws it), for
//!
//! * (a) the project's law at the literature friction coefficient, each contact pressure
//!   (`section.slip_pressure`);
//! * (b) the classical analytic models (module [`classical`], coded independently of the law):
//!   Papailiou's SC1 and the accumulated-pressure forms;
//! * (c) each of them at the single friction coefficient that fits the curve best, labelled
//!   as a fit.
//!
//! Each row: RMS and largest error over the 18 points (of the largest measured moment), the
//! initial secant M(kappa_1) / kappa_1 against the measured one, and whether the targets (RMS
//! 5 %, secant 10 %) are met. The study prints the tables, writes `target/conductor/`
//! (report.md, curves.csv, conductor-cardinal.png/.svg) and with `--update-docs` the block
//! `conductor` of the Validation page and its figure. Missing a target is a finding, not a
//! failure: the command fails only when it cannot compute.

pub mod classical;
pub mod compare;
pub mod measured;

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::Context;
use strand_core::{SectionLaw, SlipPressure};
use strand_plot::{Chart, Mark, Series};
use strand_scene::{Scene, loading_moments};

use classical::{Conductor, Model, SlipCondition};
use compare::{Errors, RMS_TARGET, SECANT_TARGET, SecantWindow, best_friction};
use measured::Curve;

/// Options of `cargo xtask conductor`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ConductorArgs {
    /// Folder of the report, the curves and the figure [default: target/conductor].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Also write the tables into the manual (docs/book/src/validation.md, between the
    /// `conductor` markers) and the figure into its figures/.
    #[arg(long)]
    pub update_docs: bool,
}

/// The scene (geometry, materials, lay lengths) of the comparison.
const SCENE: &str = "validation/conductor/cardinal.json";
/// The measured curve.
const MEASURED: &str = "validation/conductor/FLEXION_CARDINAL_H40kN_mu0.7_FOTI.csv";
/// The test's tension (N): 40 kN, the file's name and its README.
pub const TENSION: f64 = 40e3;
/// The literature friction coefficient: 0.7, the value the public dataset's name and the
/// example that plots it give for this curve with Foti's slip condition (Foti & Martinelli
/// 2016); see the README in `validation/conductor/`.
pub const LITERATURE_FRICTION: f64 = 0.7;
/// Load steps from one measured curvature to the next (the hysteretic law's return mapping
/// from a committed state; the curve is checked against twice as many).
const SUBSTEPS: usize = 4;

/// One curve of the comparison.
struct Computed {
    /// Name in the tables.
    name: String,
    /// Friction coefficient.
    mu: f64,
    /// Whether `mu` was fitted to the curve.
    fitted: bool,
    /// Moments at the measured curvatures (N m).
    moments: Vec<f64>,
    errors: Errors,
}

/// A model of the comparison: moments at given curvatures for a friction coefficient.
type Moments<'a> = Box<dyn Fn(f64, &[f64]) -> anyhow::Result<Vec<f64>> + 'a>;

/// Runs the study; prints and writes its tables.
pub fn run(args: &ConductorArgs) -> anyhow::Result<()> {
    let root = crate::validate::repo_root();
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join("conductor"));
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    let measured_path = root.join(MEASURED);
    let measured = Curve::parse(
        &std::fs::read_to_string(&measured_path)
            .with_context(|| format!("reading {}", measured_path.display()))?,
    )
    .with_context(|| measured_path.display().to_string())?;
    if measured.len() != measured::CARDINAL_POINTS {
        anyhow::bail!(
            "{}: {} points, its README states {}",
            measured_path.display(),
            measured.len(),
            measured::CARDINAL_POINTS
        );
    }
    let scene_path = root.join(SCENE);
    let scene_text = std::fs::read_to_string(&scene_path)
        .with_context(|| format!("reading {}", scene_path.display()))?;
    let scene_json: serde_json::Value = serde_json::from_str(&scene_text)?;
    let conductor = Conductor::from_scene_json(&scene_json)?;

    // (a) the project's law, per contact pressure; (b) the classical models.
    let mut models: Vec<(String, Moments)> = Vec::new();
    for p in [
        SlipPressure::Accumulated,
        SlipPressure::Sc5,
        SlipPressure::OwnLayer,
        SlipPressure::TwoFaces,
    ] {
        let json = scene_json.clone();
        models.push((
            format!("law, {}", p.name()),
            Box::new(move |mu, kappa| {
                let law = law_at(&json, p, mu)?;
                Ok(loading_moments(&law, TENSION, kappa, SUBSTEPS))
            }),
        ));
    }
    for c in SlipCondition::ALL {
        let cond = conductor.clone();
        models.push((
            format!("classical, {}", c.name()),
            Box::new(move |mu, kappa| {
                let m = Model::new(&cond, c, mu, TENSION);
                Ok(kappa.iter().map(|&k| m.moment(k)).collect())
            }),
        ));
    }

    let mut rows = Vec::new();
    for (name, f) in &models {
        let moments = f(LITERATURE_FRICTION, &measured.curvature)?;
        rows.push(Computed {
            name: name.clone(),
            mu: LITERATURE_FRICTION,
            fitted: false,
            errors: Errors::of(&measured, &moments),
            moments,
        });
    }
    for (name, f) in &models {
        let (mu, errors) = best_friction(&measured, |mu| {
            f(mu, &measured.curvature).expect("the scene was built at the literature value")
        });
        rows.push(Computed {
            name: name.clone(),
            mu,
            fitted: true,
            moments: f(mu, &measured.curvature)?,
            errors,
        });
    }

    // Where the initial secant is within its target, and the best RMS there.
    let windows: Vec<(String, Option<SecantWindow>)> = models
        .iter()
        .map(|(name, f)| {
            let w = compare::secant_window(&measured, |mu| {
                f(mu, &measured.curvature).expect("the scene was built at the literature value")
            });
            (name.clone(), w)
        })
        .collect();

    // The law's curve at twice the load steps: the step's effect on the figures.
    let default = SlipPressure::default();
    let fine = loading_moments(
        &law_at(&scene_json, default, LITERATURE_FRICTION)?,
        TENSION,
        &measured.curvature,
        2 * SUBSTEPS,
    );
    let default_row = rows
        .iter()
        .find(|r| !r.fitted && r.name == format!("law, {default}"))
        .expect("the default pressure is among the law's rows");
    let step_effect = fine
        .iter()
        .zip(&default_row.moments)
        .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()));

    let law = law_at(&scene_json, default, LITERATURE_FRICTION)?;
    let text = report(
        &measured,
        &rows,
        &windows,
        &conductor,
        &law,
        step_effect,
        &scene_json,
    );
    print!("{text}");
    std::fs::write(out.join("report.md"), &text)?;
    write_curves(&out, &measured, &rows)?;
    draw(&out, &measured, &models, &rows, &law)?;
    println!("wrote {}", out.display());
    if args.update_docs {
        crate::book::pages::update(crate::book::pages::Page::Validation, "conductor", &text)?;
        crate::book::pages::copy_figures(&out, &["conductor-cardinal"])?;
    }
    Ok(())
}

/// The scene's law with friction `mu` and contact pressure `p`.
fn law_at(json: &serde_json::Value, p: SlipPressure, mu: f64) -> anyhow::Result<SectionLaw> {
    let mut json = json.clone();
    json["strand"]["friction"] = mu.into();
    json["section"]["slip_pressure"] = p.name().into();
    let scene = Scene::parse(&json.to_string()).map_err(|e| anyhow::anyhow!("{SCENE}: {e}"))?;
    Ok(SectionLaw::with_options(
        &scene.strand,
        scene.law,
        &scene.section,
    ))
}

fn pct(x: f64) -> String {
    format!("{:.1} %", 100.0 * x)
}

/// The Markdown report: the setting, the table of figures, the points.
fn report(
    measured: &Curve,
    rows: &[Computed],
    windows: &[(String, Option<SecantWindow>)],
    conductor: &Conductor,
    law: &SectionLaw,
    step_effect: f64,
    scene: &serde_json::Value,
) -> String {
    let mut s = String::new();
    let lays: Vec<String> = conductor
        .layers
        .iter()
        .zip(scene["strand"]["layers"].as_array().into_iter().flatten())
        .map(|(l, j)| {
            format!(
                "{} x {:.2} mm, lay {} m ({:.2} deg)",
                l.wires,
                2e3 * l.wire_radius,
                j["pitch"],
                l.lay_angle.to_degrees()
            )
        })
        .collect();
    let _ = writeln!(
        s,
        "Cardinal ACSR 54/7 (`{SCENE}`: core {:.2} mm; layers {}) at T = {} kN, the {} measured \
         points of `{MEASURED}` (largest moment {:.2} N m, initial secant M_1 / kappa_1 = {:.0} N m^2). \
         The law (`hysteretic`, default section options, `{}`): K_min = {:.1} N m^2, stick stiffness \
         {:.0} N m^2. The classical models: K_min = {:.1} N m^2 (Papailiou), K_max = {:.0} N m^2 \
         (plane section), strain T / EA = {:.3e}. Targets: RMS within {:.0} % of the largest measured moment and the \
         initial secant within {:.0} % of the measured one, with one friction coefficient. The \
         law's largest change at {} load steps per interval instead of {SUBSTEPS}: {:.1e} N m. \
         The measured initial stiffness rests on one small moment read off a curve: the \
         least-squares slope through the origin of the first three points is {:.0} N m^2 \
         (the law's stick stiffness {:+.1} % from it, the plane section's {:+.1} %).\n",
        2e3 * conductor.core_radius,
        lays.join("; "),
        TENSION / 1e3,
        measured.len(),
        measured.largest_moment(),
        measured.initial_secant(),
        SlipPressure::default(),
        law.base_bending_stiffness(),
        law.stick_bending_stiffness(),
        conductor.k_min(),
        conductor.k_max(),
        TENSION / conductor.axial_stiffness(),
        100.0 * RMS_TARGET,
        100.0 * SECANT_TARGET,
        2 * SUBSTEPS,
        step_effect,
        measured.origin_slope(3),
        100.0 * (law.stick_bending_stiffness() / measured.origin_slope(3) - 1.0),
        100.0 * (conductor.k_max() / measured.origin_slope(3) - 1.0),
    );
    let _ = writeln!(
        s,
        "| model | mu | RMS error | largest error | initial secant (N m^2) | vs measured | targets |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for r in rows {
        let e = &r.errors;
        let _ = writeln!(
            s,
            "| {}{} | {:.3}{} | {} | {} | {:.0} | {:+.1} % | {} |",
            r.name,
            if r.fitted { " (fit)" } else { "" },
            r.mu,
            if r.fitted { " (fit)" } else { " (literature)" },
            pct(e.rms),
            pct(e.largest),
            e.secant,
            100.0 * e.secant_error,
            if e.meets_targets() { "met" } else { "missed" },
        );
    }
    let _ = writeln!(
        s,
        "\nThe friction coefficients (scan 0.01 to 2.0 in steps of 0.01) at which the initial \
         secant is within {:.0} %, and the least RMS error among them:\n",
        100.0 * SECANT_TARGET
    );
    let _ = writeln!(
        s,
        "| model | mu with the secant within target | least RMS error there |"
    );
    let _ = writeln!(s, "|---|---|---|");
    for (name, w) in windows {
        let _ = match w {
            Some((lo, hi, best, e)) => writeln!(
                s,
                "| {name} | {lo:.2} to {hi:.2} | {} (mu {best:.2}, secant {:+.1} %) |",
                pct(e.rms),
                100.0 * e.secant_error
            ),
            None => writeln!(s, "| {name} | none | - |"),
        };
    }
    let _ = writeln!(
        s,
        "\nMoments (N m) at the measured curvatures, mu = {LITERATURE_FRICTION} unless marked:\n"
    );
    let shown: Vec<&Computed> = rows
        .iter()
        .filter(|r| {
            (r.name.starts_with("law") || r.name.contains("SC1") || r.name.contains("accumulated"))
                && (!r.fitted || r.name == format!("law, {}", SlipPressure::default()))
        })
        .collect();
    let head: Vec<String> = shown
        .iter()
        .map(|r| {
            if r.fitted {
                format!("{} (fit, mu {:.3})", r.name, r.mu)
            } else {
                r.name.clone()
            }
        })
        .collect();
    let _ = writeln!(s, "| kappa (1/m) | measured | {} |", head.join(" | "));
    let _ = writeln!(s, "|---|---|{}", "---|".repeat(shown.len()));
    for i in 0..measured.len() {
        let cells: Vec<String> = shown
            .iter()
            .map(|r| format!("{:.2}", r.moments[i]))
            .collect();
        let _ = writeln!(
            s,
            "| {:.4} | {:.2} | {} |",
            measured.curvature[i],
            measured.moment[i],
            cells.join(" | ")
        );
    }
    s
}

/// `curves.csv`: the measured points and every computed curve at them.
fn write_curves(dir: &std::path::Path, measured: &Curve, rows: &[Computed]) -> anyhow::Result<()> {
    let mut s = String::from("curvature,measured");
    for r in rows {
        let _ = write!(
            s,
            ",{} mu {:.4}{}",
            r.name.replace(',', ""),
            r.mu,
            if r.fitted { " fit" } else { "" }
        );
    }
    s.push('\n');
    for i in 0..measured.len() {
        let _ = write!(s, "{:e},{:e}", measured.curvature[i], measured.moment[i]);
        for r in rows {
            let _ = write!(s, ",{:e}", r.moments[i]);
        }
        s.push('\n');
    }
    std::fs::write(dir.join("curves.csv"), s)?;
    Ok(())
}

/// `conductor-cardinal.png/.svg`: the measured points and the curves, over the whole range
/// and over the first curvatures (with the law's stick line).
fn draw(
    dir: &std::path::Path,
    measured: &Curve,
    models: &[(String, Moments)],
    rows: &[Computed],
    law: &SectionLaw,
) -> anyhow::Result<()> {
    let top = *measured.curvature.last().expect("points");
    let panel = |kmax: f64, title: &str, stick: bool| -> anyhow::Result<Chart> {
        let kappa: Vec<f64> = (1..=200).map(|i| kmax * i as f64 / 200.0).collect();
        let mut series = Vec::new();
        // The fitted curve is the default law's, named from the default.
        let default = format!("law, {}", SlipPressure::default());
        let picks = [
            ("law, accumulated", false, Mark::Line, 0),
            ("law, two_faces", false, Mark::Line, 5),
            ("law, own_layer", false, Mark::Line, 1),
            ("classical, SC1 (Papailiou)", false, Mark::Dashed, 3),
            ("classical, accumulated", false, Mark::Dashed, 2),
            ("classical, Foti", false, Mark::Dashed, 6),
            (default.as_str(), true, Mark::Dashed, 4),
        ];
        for (name, fitted, mark, color) in picks {
            let r = rows
                .iter()
                .find(|r| r.name == name && r.fitted == fitted)
                .expect("row");
            let f = &models.iter().find(|(n, _)| n == name).expect("model").1;
            let mut m = vec![0.0];
            m.extend(f(r.mu, &kappa)?);
            let mut k = vec![0.0];
            k.extend(&kappa);
            let label = if fitted {
                format!("{name}, mu {:.2} (fit)", r.mu)
            } else {
                format!("{name}, mu {}", r.mu)
            };
            series.push(Series::xy(label, &k, &m, mark, color));
        }
        let ymax = measured
            .moment
            .iter()
            .zip(&measured.curvature)
            .filter(|(_, k)| **k <= kmax * 1.0001)
            .fold(0.0_f64, |a, (m, _)| a.max(*m));
        if stick {
            // Ended inside the axes (a line past the range is drawn clamped, not clipped).
            let k = law.stick_bending_stiffness();
            let end = kmax.min(1.2 * ymax / k);
            series.push(Series::new(
                "law stick stiffness",
                vec![(0.0, 0.0), (end, k * end)],
                Mark::Trace,
                0,
            ));
            let s = measured.initial_secant();
            let end = kmax.min(1.2 * ymax / s);
            series.push(Series::new(
                "measured initial secant",
                vec![(0.0, 0.0), (end, s * end)],
                Mark::Trace,
                1,
            ));
        }
        let pts: Vec<(f64, f64)> = measured
            .curvature
            .iter()
            .zip(&measured.moment)
            .filter(|(k, _)| **k <= kmax * 1.0001)
            .map(|(k, m)| (*k, *m))
            .collect();
        series.push(Series::new("measured (40 kN)", pts, Mark::Points, 6));
        Ok(Chart {
            title: title.into(),
            x_label: "curvature (1/m)".into(),
            y_label: "bending moment (N m)".into(),
            series,
            y_range: Some((0.0, 1.25 * ymax)),
            ..Default::default()
        })
    };
    let charts = [
        panel(top, "Cardinal ACSR 54/7 at 40 kN: first loading", false)?,
        panel(0.02, "the first four points", true)?,
    ];
    strand_plot::save_grid(&charts, 2, dir, "conductor-cardinal")
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok(())
}
