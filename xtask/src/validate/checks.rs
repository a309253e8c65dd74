//! The checks: each turns the files of a run (and, where needed, an independent reference)
//! into rows of the table.

use std::path::Path;

use strand_core::SectionLaw;
use strand_elastica::{Cantilever, ConstantEi, Options, Solution, StrandLaw, solve};
use strand_scene::{Analysis, BeamModel, End, Scene, SupportKind};

use super::report::{Bound, Row};
use super::results::{Centerline, Energy};
use super::tolerances::{DistanceTol, EnergyTol, TensionTol};

/// The two beam models of the runner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BeamKind {
    /// The equivalent beam with the scene's section law.
    Equivalent,
    /// The traditional beam with constant EI.
    Traditional,
}

impl BeamKind {
    /// The model's folder name.
    pub fn name(self) -> &'static str {
        match self {
            BeamKind::Equivalent => "equivalent",
            BeamKind::Traditional => "traditional",
        }
    }

    fn model(self, scene: &Scene) -> Option<&BeamModel> {
        match self {
            BeamKind::Equivalent => scene.models.equivalent.as_ref(),
            BeamKind::Traditional => scene.models.traditional.as_ref(),
        }
    }
}

/// Configuration distance between a run's centreline and a reference at equal material
/// coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distance {
    /// Largest distance over the integration points (m).
    pub max: f64,
    /// RMS distance over the integration points (m).
    pub rms: f64,
    /// Tip distance (m).
    pub tip: f64,
    /// Material coordinate of the largest distance (m).
    pub at: f64,
}

/// Distance of the centreline `c` with tip `tip` from the elastica solution `r`.
pub fn distance(c: &Centerline, tip: [f64; 3], r: &Solution) -> Distance {
    let mut max: f64 = 0.0;
    let mut at = 0.0;
    let mut sum = 0.0;
    for i in 0..c.s.len() {
        let p = r.position(c.s[i]);
        // The elastica is planar: a point off the XY plane is off by its z too.
        let d = (c.x[i] - p[0]).hypot(c.y[i] - p[1]).hypot(c.z[i]);
        if d.is_nan() || d > max {
            (max, at) = (d, c.s[i]);
        }
        sum += d * d;
    }
    let tip = (tip[0] - r.tip[0]).hypot(tip[1] - r.tip[1]).hypot(tip[2]);
    if tip.is_nan() || tip > max {
        (max, at) = (tip, r.problem.length);
    }
    Distance {
        max,
        rms: (sum / c.s.len() as f64).sqrt(),
        tip,
        at,
    }
}

/// The elastica reference of `kind` for a static scene: the clamped horizontal cantilever
/// under q = mass per length * |g| with the same section law (equivalent) or the traditional
/// beam's constant EI, extensible with the model's EA like the ANCF beam.
pub fn elastica(scene: &Scene, kind: BeamKind) -> Result<Solution, String> {
    let model = kind
        .model(scene)
        .ok_or_else(|| format!("the scene has no `{}` model", kind.name()))?;
    if !matches!(scene.analysis, Analysis::Static { .. }) {
        return Err("the elastica reference is for static scenes".into());
    }
    let clamped_start = scene
        .supports
        .iter()
        .any(|s| s.at == End::Start && s.kind == SupportKind::Clamped);
    let [dx, dy, dz] = scene.direction;
    let [gx, gy, gz] = scene.gravity;
    let horizontal = (dx - 1.0).abs() < 1e-12 && dy.abs() < 1e-12 && dz.abs() < 1e-12;
    if !clamped_start || scene.supports.len() != 1 || !horizontal || gx != 0.0 || gz != 0.0 {
        return Err(
            "the elastica reference needs a cantilever clamped at the start, along +X, under \
             gravity in -Y"
                .into(),
        );
    }
    let strand = &scene.strand;
    let q = model.mass_per_length.unwrap_or(strand.mass_per_length()) * (-gy);
    let opts = Options::default();
    let cantilever = |ea: f64| Cantilever::extensible(strand.length(), q, ea);
    let solution = match kind {
        BeamKind::Equivalent => {
            // The hysteretic law from a virgin state on a monotone load path is `continuous`.
            let law = StrandLaw::new(SectionLaw::with_options(strand, scene.law, &scene.section));
            solve(&cantilever(law.axial_stiffness()), &law, &opts)
        }
        BeamKind::Traditional => {
            let t = strand.traditional();
            let law = ConstantEi::new(t.bending_stiffness);
            solve(&cantilever(t.axial_stiffness), &law, &opts)
        }
    };
    solution.map_err(|e| e.to_string())
}

/// The three rows (max, rms, tip) of a distance check.
pub fn distance_rows(scene: &str, check: &str, d: &Distance, tol: &DistanceTol) -> Vec<Row> {
    vec![
        Row::measured(scene, check, "max", d.max, "m", Bound::AtMost(tol.max)),
        Row::measured(scene, check, "rms", d.rms, "m", Bound::AtMost(tol.rms)),
        Row::measured(scene, check, "tip", d.tip, "m", Bound::AtMost(tol.tip)),
    ]
}

/// A model's statics against its elastica reference.
pub fn against_elastica(
    scene: &Scene,
    kind: BeamKind,
    dir: &Path,
    tip: [f64; 3],
    reference: &Result<Solution, String>,
    tol: &DistanceTol,
) -> Vec<Row> {
    let check = format!("{}-vs-elastica", kind.name());
    let name = &scene.name;
    let r = match reference {
        Ok(r) => r,
        Err(e) => return vec![Row::failed(name, &check, "-", format!("reference: {e}"))],
    };
    match Centerline::load(dir) {
        Ok(c) => {
            let d = distance(&c, tip, r);
            let mut rows = distance_rows(name, &check, &d, tol);
            rows[0].note = format!(
                "largest at s = {:.3} m; elastica error estimate {:.1e} m, {} continuation steps",
                d.at, r.error.position, r.continuation_steps
            );
            rows
        }
        Err(e) => vec![Row::failed(name, &check, "-", format!("{e:#}"))],
    }
}

/// Tension of the equivalent model (`centerline.csv` in `dir`) against the elastica's
/// -q (L - s) sin(theta) of the same law: one row per point, relative to the elastica's
/// tension there, and one for the largest difference along the strand from `tol.from` on,
/// relative to q L.
/// The row of the largest |T - T_elastica| / (q L) of the centreline `c` from `from` (m) on,
/// against `limit`, named `metric`.
pub fn tension_along(
    scene: &str,
    c: &Centerline,
    r: &Solution,
    from: f64,
    limit: f64,
    metric: &str,
) -> Row {
    let ql = r.problem.load * r.problem.length;
    let (mut worst, mut at) = (0.0f64, f64::NAN);
    for (s, t) in c.s.iter().zip(&c.tension) {
        let d = (t - r.sample(*s).tension).abs();
        if *s >= from && d > worst {
            (worst, at) = (d, *s);
        }
    }
    Row::measured(
        scene,
        "tension-vs-elastica",
        metric,
        worst / ql,
        "",
        Bound::AtMost(limit),
    )
    .with_note(format!(
        "largest |T - T_elastica| {worst:.3e} N at s = {at:.3} m (from s = {from} m on), q L = \
         {ql:.4} N"
    ))
}

pub fn tension_vs_elastica(
    scene: &str,
    dir: &Path,
    reference: &Result<Solution, String>,
    tol: &TensionTol,
) -> Vec<Row> {
    const CHECK: &str = "tension-vs-elastica";
    let r = match reference {
        Ok(r) => r,
        Err(e) => return vec![Row::failed(scene, CHECK, "-", format!("reference: {e}"))],
    };
    let c = match Centerline::load(dir) {
        Ok(c) => c,
        Err(e) => return vec![Row::failed(scene, CHECK, "-", format!("{e:#}"))],
    };
    let mut rows: Vec<Row> = tol
        .points
        .iter()
        .map(|p| {
            let t = c.interpolate(&c.tension, p.x);
            let el = r.sample(p.x).tension;
            Row::measured(
                scene,
                CHECK,
                &format!("x={}", p.x),
                (t - el).abs() / el.abs(),
                "",
                Bound::AtMost(tol.relative),
            )
            .with_note(format!(
                "tension {t:.5} N at s = {} m, elastica {el:.5} N (paper {} N)",
                p.x, p.paper
            ))
        })
        .collect();
    rows.push(tension_along(scene, &c, r, tol.from, tol.along, "along"));
    rows
}

/// Energy balance error of a dynamic run relative to its largest kinetic energy: the larger
/// of the figure from the output frames of `energy.csv` and the runner's own over every step
/// (`summary`, from `summary.json`).
pub fn energy_balance(
    scene: &str,
    model: &str,
    dir: &Path,
    summary: Option<f64>,
    tol: &EnergyTol,
) -> Row {
    const CHECK: &str = "energy-balance";
    match Energy::load(dir) {
        Ok(e) => {
            let frames = e.balance_relative();
            let every_step = summary.unwrap_or(f64::NAN);
            let rel = if every_step.is_nan() {
                frames
            } else {
                frames.max(every_step)
            };
            let limit = match (model, tol.fine, tol.traditional) {
                ("fine", Some(f), _) => f,
                ("traditional", _, Some(t)) => t,
                _ => tol.relative,
            };
            let row = Row::measured(scene, CHECK, model, rel, "", Bound::AtMost(limit)).with_note(
                format!(
                    "{frames:.2e} over the output frames, {every_step:.2e} over every step; \
                     dissipated {:.3e} J",
                    e.last()[3]
                ),
            );
            match &tol.open {
                Some(o) if o.models.iter().any(|m| m == model) => row.opened(&o.why),
                _ => row,
            }
        }
        Err(e) => Row::failed(scene, CHECK, model, format!("{e:#}")),
    }
}

/// Observed order log2(e1 / e2) of two errors at h and h/2.
pub fn observed_order(coarse: f64, fine: f64) -> f64 {
    (coarse / fine).log2()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_of_halving_errors() {
        assert!((observed_order(4.0, 1.0) - 2.0).abs() < 1e-15);
    }

    #[test]
    fn distance_to_the_elastica_of_itself_is_small() {
        let sol = solve(
            &Cantilever::new(1.0, 1.0),
            &ConstantEi::new(1.0),
            &Options::default(),
        )
        .unwrap();
        let s: Vec<f64> = (0..=10).map(|i| i as f64 / 10.0).collect();
        let p: Vec<[f64; 2]> = s.iter().map(|&v| sol.position(v)).collect();
        let c = Centerline {
            x: p.iter().map(|q| q[0]).collect(),
            y: p.iter().map(|q| q[1] + 1e-3).collect(),
            z: vec![0.0; s.len()],
            tension: vec![0.0; s.len()],
            s,
        };
        let d = distance(&c, [sol.tip[0], sol.tip[1], 0.0], &sol);
        assert!((d.rms - 1e-3).abs() < 1e-12 && (d.max - 1e-3).abs() < 1e-12);
        assert_eq!(d.tip, 0.0);
    }
}
