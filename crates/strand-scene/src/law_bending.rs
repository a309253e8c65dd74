//! The section law's moment-curvature curve at a given tension, with load reversals: what
//! `strand bend --model equivalent` draws, for a strand of any number of layers.
//!
//! The strand is held at the strain T / EA_eq and bent along the curvature path 0 ->
//! kappa_max -> -kappa_max -> kappa_max (a loading curve and one hysteresis loop). The
//! moment is averaged over stations that take every layer's wires evenly over its own whole
//! pitch (each station with its own slip state for the hysteretic law), as a bending test
//! over whole pitches of every layer measures it.

use std::path::{Path, PathBuf};

use serde::Serialize;
use strand_core::{SectionLaw, Station};

use crate::output::Csv;
use crate::run::record::{RunError, io_err};
use crate::scene::Scene;

/// Phase stations over the pitch of a `1+m` strand.
const STATIONS: usize = 48;

/// Phase stations over every layer's pitch on a strand of several layers. The moment along a
/// pitch has kinks where wires start to slip, and the midpoint rule over 48 stations per pitch
/// errs by up to 6e-4 of the moment on the 1+6+12 strand at 1e4 N, over 384 by 1e-5, over
/// 1536 by 1e-6 (`the_law_curve_of_two_layers_is_the_mean_along_the_strand`); 384 keeps
/// `cargo xtask conductor` (four layers) within a minute.
const LAYERED_STATIONS: usize = 384;

/// Options of the law's bending curve.
#[derive(Debug, Clone, PartialEq)]
pub struct LawBendingOptions {
    /// Axial tension T (N), held.
    pub tension: f64,
    /// Largest curvature of the loop (1/m); `None`: three times the largest critical curvature
    /// of the wires at the first station (every wire slips at the ends of the loop).
    pub amplitude: Option<f64>,
    /// Curvature steps from 0 to the amplitude (the loop takes four times as many).
    pub steps: usize,
    /// Output folder.
    pub out: PathBuf,
}

/// What the law's bending curve wrote in `law-summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawBendingSummary {
    /// Scene name.
    pub scene: String,
    /// Section law.
    pub law: String,
    /// Number of helical layers.
    pub layers: usize,
    /// Tension T (N).
    pub tension: f64,
    /// Strain T / EA_eq (-).
    pub strain: f64,
    /// All-slip stiffness K_min at the strain (N m^2): the tension-free value unless
    /// `section.base_tension` makes it follow the strain.
    pub k_min: f64,
    /// All-stick stiffness K_max at the strain (N m^2): K_min plus the wires' stick stiffness.
    pub k_max: f64,
    /// The loop's largest curvature (1/m).
    pub amplitude: f64,
    /// Slip work over the loop, averaged over the stations (J/m).
    pub dissipated: f64,
    /// The loop's area, the trapezoid sum of M d kappa around it (J/m): equal to the
    /// dissipated work for the hysteretic law (its stored energy returns), zero for an
    /// elastic law.
    pub loop_area: f64,
    /// (curvature 1/m, moment N m) along the path.
    pub points: Vec<[f64; 2]>,
}

/// Runs the law's bending curve of `scene`'s strand and writes `DIR/law-bending.csv`
/// (curvature, moment, tangent) and `DIR/law-summary.json`.
pub fn run_law_bending(
    scene: &Scene,
    opts: &LawBendingOptions,
) -> Result<LawBendingSummary, RunError> {
    let strand = &scene.strand;
    let invalid = |message: String| RunError::Setup {
        model: "equivalent".into(),
        message,
    };
    SectionLaw::check(strand, scene.law).map_err(|e| invalid(e.within("strand").to_string()))?;
    if !(opts.tension.is_finite() && opts.tension >= 0.0) {
        return Err(invalid(format!(
            "--tension must be zero or positive and finite, got {}",
            opts.tension
        )));
    }
    if opts.steps < 2 {
        return Err(invalid(format!(
            "--steps must be at least 2, got {}",
            opts.steps
        )));
    }
    let law = SectionLaw::with_options(strand, scene.law, &scene.section);
    let eps = opts.tension / law.axial_stiffness();
    let stations = stations(&law);
    let amplitude = match opts.amplitude {
        Some(a) if a.is_finite() && a > 0.0 => a,
        Some(a) => return Err(invalid(format!("--amplitude must be positive, got {a}"))),
        None => {
            let largest = law
                .planar_wires(&stations[0], eps, -1.0, &[])
                .iter()
                .filter_map(|w| w.critical_curvature)
                .fold(0.0, f64::max);
            if largest > 0.0 { 3.0 * largest } else { 1.0 }
        }
    };
    // 0 -> a, a -> -a, -a -> a.
    let n = opts.steps;
    let path: Vec<f64> = (1..=n)
        .map(|i| amplitude * i as f64 / n as f64)
        .chain((1..=2 * n).map(|i| amplitude * (1.0 - i as f64 / n as f64)))
        .chain((1..=2 * n).map(|i| amplitude * (-1.0 + i as f64 / n as f64)))
        .collect();
    let mut slips: Vec<Vec<f64>> = vec![vec![0.0; law.state_len()]; stations.len()];
    let count = stations.len() as f64;
    let mut trial = vec![0.0; law.state_len()];
    let mut rows = Vec::with_capacity(path.len() + 1);
    rows.push([0.0, 0.0, law.planar_stick_stiffness(&stations[0])]);
    let (mut dissipated, mut loop_area) = (0.0, 0.0);
    for (i, &k) in path.iter().enumerate() {
        let (mut m, mut t, mut w) = (0.0, 0.0, 0.0);
        for (st, slip) in stations.iter().zip(&mut slips) {
            let r = law.planar(st, eps, k, slip, &mut trial);
            slip.copy_from_slice(&trial);
            m += r.moment;
            t += r.moment_curvature;
            w += r.slip_work;
        }
        let (m, t) = (m / count, t / count);
        if i >= n {
            let prev = rows[rows.len() - 1];
            loop_area += 0.5 * (m + prev[1]) * (k - prev[0]);
            dissipated += w / count;
        }
        rows.push([k, m, t]);
    }
    std::fs::create_dir_all(&opts.out).map_err(io_err(&opts.out))?;
    let csv_path = opts.out.join("law-bending.csv");
    let mut csv =
        Csv::create(&csv_path, &["curvature", "moment", "tangent"]).map_err(io_err(&csv_path))?;
    for r in &rows {
        csv.row(r).map_err(io_err(&csv_path))?;
    }
    csv.finish().map_err(io_err(&csv_path))?;
    // K_min at the held strain (`section.base_tension`; the tension-free value by default).
    let k_min = law.base_bending_at(eps).0;
    let summary = LawBendingSummary {
        scene: scene.name.clone(),
        law: scene.law.to_string(),
        layers: strand.layers().len(),
        tension: opts.tension,
        strain: eps,
        k_min,
        k_max: law.stick_bending_stiffness() + (k_min - law.base_bending_stiffness()),
        amplitude,
        dissipated,
        loop_area,
        points: rows.iter().map(|r| [r[0], r[1]]).collect(),
    };
    write_json(&opts.out.join("law-summary.json"), &summary)?;
    Ok(summary)
}

/// The law's stations: station `i` of `n` ([`STATIONS`] on a `1+m` strand,
/// [`LAYERED_STATIONS`] on several layers) has every layer's wires at the phases of
/// `P_j (i + 1/2) / n` along that layer's own pitch `P_j`
/// ([`SectionLaw::station_by_layer`]), so that every layer is averaged over its whole pitch
/// whatever the ratio of the pitches (over the strand's length for a plain wire). On a `1+m`
/// strand these are the stations evenly spaced over its pitch.
fn stations(law: &SectionLaw) -> Vec<Station> {
    let strand = law.strand();
    let pitches: Vec<f64> = strand.layers().iter().map(|l| l.pitch).collect();
    if pitches.is_empty() {
        let length = strand.length();
        return (0..STATIONS)
            .map(|i| law.station(length * (i as f64 + 0.5) / STATIONS as f64))
            .collect();
    }
    let n = if pitches.len() > 1 {
        LAYERED_STATIONS
    } else {
        STATIONS
    };
    law.stations_by_layer(n)
}

/// The section law's moment on first loading (N m) at each of `curvatures` (1/m, positive and
/// rising) under the tension `tension` (N): the strand is bent from straight and unslipped
/// through the points, in `substeps` equal steps up to each, and the moment averaged over the
/// law's stations (every layer over its own pitch), as [`run_law_bending`] averages it. What a bending test of a
/// measured curve compares with.
pub fn loading_moments(
    law: &SectionLaw,
    tension: f64,
    curvatures: &[f64],
    substeps: usize,
) -> Vec<f64> {
    let eps = tension / law.axial_stiffness();
    let stations = stations(law);
    let mut slips: Vec<Vec<f64>> = vec![vec![0.0; law.state_len()]; stations.len()];
    let mut trial = vec![0.0; law.state_len()];
    let substeps = substeps.max(1);
    let mut last = 0.0;
    let mut out = Vec::with_capacity(curvatures.len());
    for &k in curvatures {
        let mut m = 0.0;
        for s in 1..=substeps {
            let at = last + (k - last) * s as f64 / substeps as f64;
            m = 0.0;
            for (st, slip) in stations.iter().zip(&mut slips) {
                let r = law.planar(st, eps, at, slip, &mut trial);
                slip.copy_from_slice(&trial);
                m += r.moment;
            }
        }
        out.push(m / stations.len() as f64);
        last = k;
    }
    out
}

fn write_json(path: &Path, value: &impl Serialize) -> Result<(), RunError> {
    let text = serde_json::to_string_pretty(value).expect("summary serializes");
    std::fs::write(path, text + "\n").map_err(io_err(path))
}
