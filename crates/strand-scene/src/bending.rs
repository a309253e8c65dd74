//! Virtual bending test of a scene's strand (SPEC 4): the fine model, pulled to a tension and
//! bent along circular arcs of growing curvature ([`strand_fine::BendingTest`]), measures its
//! moment-curvature curve; beside it, the equivalent section law of the scene (eq. (28)) at
//! the same strain and curvature, averaged over one pitch (the wires' phases turn once per
//! pitch, and the fine model's moment is measured over the middle pitches); on a strand of
//! several layers both are taken over whole pitches of every layer
//! ([`strand_fine::PitchWindow`]).

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;
use strand_core::{SectionLaw, Strand};
use strand_fine::{
    BendingError, BendingPoint, BendingTest, ContactOptions, NormalPenalty, PitchWindow,
};

use crate::output::Csv;
use crate::run::record::{RunError, io_err};
use crate::scene::{MEMORY_LIMIT, Scene, fine_memory};

/// Controls of a virtual bending test.
#[derive(Debug, Clone, PartialEq)]
pub struct BendingOptions {
    /// Axial tension T (N), applied first and held.
    pub tension: f64,
    /// Curvatures of the load steps (1/m), each reached from the one before (a sequence that
    /// turns back reverses the load); empty: 10 increasing values from 0.2 to 20 times the
    /// smallest critical curvature of the section law at `tension`.
    pub curvatures: Vec<f64>,
    /// Strand length in pitches (at least 3).
    pub pitches: usize,
    /// Segments per pitch of every wire.
    pub segments_per_pitch: usize,
    /// Output folder.
    pub out: PathBuf,
}

/// What a bending test wrote in `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BendingSummary {
    /// Scene name.
    pub scene: String,
    /// Section law the fine curve is compared with.
    pub law: String,
    /// The wires' stick stiffness of the law (`section.stick_stiffness`).
    pub stick_stiffness: String,
    /// Tension T (N).
    pub tension: f64,
    /// Axial strain of the tension, T / EA_eq (-).
    pub strain: f64,
    /// All-slip bending stiffness K_min (N m^2).
    pub k_min: f64,
    /// All-stick bending stiffness of the law, K_min plus the wires' stick stiffness in the
    /// form `section.stick_stiffness` (N m^2).
    pub k_max: f64,
    /// Smallest critical curvature of the law at this tension (1/m), over the stations of
    /// `law_moment` ([`first_slip_curvature`]).
    pub first_slip_curvature: Option<f64>,
    /// Strand length in pitches, segments per pitch.
    pub pitches: usize,
    /// Segments per pitch of every wire.
    pub segments_per_pitch: usize,
    /// The window along the strand the fine moment and curvature are taken over
    /// ([`BendingTest::window`]), in words.
    pub window: String,
    /// Its support: rest x from, to (m).
    pub window_support: [f64; 2],
    /// Wall time (s).
    pub wall_time: f64,
    /// Curvature, fine moment and law moment of every point (1/m, N m, N m).
    pub points: Vec<[f64; 3]>,
}

/// Most curvatures of one test: each is at least one Newton load step of the fine model.
const MAX_CURVATURES: usize = 1000;

/// Phase stations sampled over one pitch for the law's average.
const STATIONS: usize = 48;

/// The law's moment (N m) at strain `eps` and curvature `kappa` (1/m), bent from straight,
/// averaged over the stations of the law's path ([`LawPath::new`]: one pitch of a `1+m`
/// strand, the test's `window` of whole pitches of every layer on several layers); and the
/// smallest critical curvature there.
fn law_moment(
    law: &SectionLaw,
    strand: &Strand,
    window: &PitchWindow,
    eps: f64,
    kappa: f64,
) -> (f64, Option<f64>) {
    let stations = LawPath::new(law, strand, window).stations;
    let slip = vec![0.0; law.state_len()];
    let mut trial = slip.clone();
    let (mut sum, mut first) = (0.0, None::<f64>);
    for st in &stations {
        sum += law.planar(st, eps, kappa, &slip, &mut trial).moment;
        for w in law.planar_wires(st, eps, kappa, &slip) {
            if let Some(c) = w.critical_curvature {
                first = Some(first.map_or(c, |f| f.min(c)));
            }
        }
    }
    (sum / stations.len() as f64, first)
}

/// The smallest critical curvature (1/m) of the section law `law` at the strain of tension
/// `tension` (N), straight, over the stations the bending test's `law_moment` takes: one pitch
/// of a `1+m` strand, the test's `window` of whole pitches of every layer on several layers
/// ([`BendingTest::window_of`]); `None` where no wire has one (no friction).
pub fn first_slip_curvature(law: &SectionLaw, window: &PitchWindow, tension: f64) -> Option<f64> {
    let strand = law.strand();
    law_moment(
        law,
        strand,
        window,
        tension / strand.axial_stiffness(),
        1e-9,
    )
    .1
}

/// The section law followed along a curvature path at `STATIONS` stations of one pitch, each
/// with its committed slip state (a load reversal unloads the sliders).
struct LawPath {
    stations: Vec<strand_core::Station>,
    slip: Vec<Vec<f64>>,
    trial: Vec<f64>,
}

impl LawPath {
    /// One pitch of a `1+m` strand; on several layers the stations of `window`, whole
    /// pitches of every layer (`STATIONS` in each of its shifted boxes).
    fn new(law: &SectionLaw, strand: &Strand, window: &PitchWindow) -> Self {
        let stations: Vec<strand_core::Station> = if let [layer] = strand.layers() {
            (0..STATIONS)
                .map(|i| law.station(layer.pitch * (i as f64 + 0.5) / STATIONS as f64))
                .collect()
        } else {
            window
                .stations(STATIONS)
                .into_iter()
                .map(|x| law.station(x))
                .collect()
        };
        Self {
            slip: vec![vec![0.0; law.state_len()]; stations.len()],
            stations,
            trial: vec![0.0; law.state_len()],
        }
    }

    /// The law's moment (N m) at strain `eps` and curvature `kappa` (1/m) reached from the
    /// last point, averaged over the stations; commits the slip.
    fn moment(&mut self, law: &SectionLaw, eps: f64, kappa: f64) -> f64 {
        let mut sum = 0.0;
        for (st, slip) in self.stations.iter().zip(&mut self.slip) {
            sum += law.planar(st, eps, kappa, slip, &mut self.trial).moment;
            slip.copy_from_slice(&self.trial);
        }
        sum / self.stations.len() as f64
    }
}

/// The section law of `scene` followed along the curvature path `curvatures` (1/m, from
/// straight) at the strain of tension `tension` (N), as the bending test's `law_moment`
/// column takes it: the moment (N m) at each point, averaged over the stations of one pitch
/// (one layer) or of the window of a test `pitches` longest pitches long (several layers,
/// [`BendingTest::window`]). Evaluates other laws or options at a fine test's measured
/// curvatures.
pub fn law_path_moments(
    scene: &Scene,
    tension: f64,
    pitches: usize,
    curvatures: &[f64],
) -> Vec<f64> {
    let strand = &scene.strand;
    let law = SectionLaw::with_options(strand, scene.law, &scene.section);
    let eps = tension / strand.axial_stiffness();
    let window = PitchWindow::for_strand(strand, pitches);
    let mut path = LawPath::new(&law, strand, &window);
    curvatures
        .iter()
        .map(|&k| path.moment(&law, eps, k))
        .collect()
}

/// Runs the virtual bending test on `scene`'s strand and writes `DIR/bending.csv` and
/// `DIR/summary.json`; `progress` receives each measured point. The contacts' normal penalty
/// follows the number of layers ([`NormalPenalty::ByLayers`]).
pub fn run_bending(
    scene: &Scene,
    opts: &BendingOptions,
    progress: &mut dyn FnMut(&BendingPoint, f64),
) -> Result<BendingSummary, RunError> {
    run_bending_with_penalty(scene, opts, NormalPenalty::ByLayers, progress)
}

/// [`run_bending`] with the contacts' normal penalty `penalty`: e.g. the penetration rule on
/// a strand of several layers, whose frictionless test at a low tension (0.1 N) converges
/// under that rule and not under the strain-relief penalty (Multilayer page).
pub fn run_bending_with_penalty(
    scene: &Scene,
    opts: &BendingOptions,
    penalty: NormalPenalty,
    progress: &mut dyn FnMut(&BendingPoint, f64),
) -> Result<BendingSummary, RunError> {
    let strand = &scene.strand;
    if strand.layers().is_empty() {
        return Err(invalid(
            "strand.layers: the bending test needs a helical layer",
        ));
    }
    if !(opts.tension.is_finite() && opts.tension > 0.0) {
        return Err(invalid(format!(
            "--tension must be positive and finite, got {}",
            opts.tension
        )));
    }
    if opts.pitches < 3 || opts.segments_per_pitch < 4 {
        return Err(invalid(format!(
            "--pitches must be at least 3 and --segments-per-pitch at least 4, got {} and {}",
            opts.pitches, opts.segments_per_pitch
        )));
    }
    let wires = 1 + strand.helical_wires();
    let need = match opts.pitches.checked_mul(opts.segments_per_pitch) {
        Some(n) => fine_memory(n, wires),
        None => f64::INFINITY,
    };
    if need.is_infinite() {
        return Err(invalid(format!(
            "--pitches {} x --segments-per-pitch {}: the segment count overflows",
            opts.pitches, opts.segments_per_pitch
        )));
    }
    if need > MEMORY_LIMIT {
        return Err(invalid(format!(
            "--pitches {} x --segments-per-pitch {} = {:.4e} segments per wire ({wires} wires) \
             would need about {:.1} GiB of memory (limit {:.0} GiB)",
            opts.pitches,
            opts.segments_per_pitch,
            opts.pitches as f64 * opts.segments_per_pitch as f64,
            need / (1u64 << 30) as f64,
            MEMORY_LIMIT / (1u64 << 30) as f64
        )));
    }
    if opts.curvatures.len() > MAX_CURVATURES {
        return Err(invalid(format!(
            "--curvatures: {} values, at most {MAX_CURVATURES} (each is a load step of the fine \
             model)",
            opts.curvatures.len()
        )));
    }
    let law = SectionLaw::with_options(strand, scene.law, &scene.section);
    let eps = opts.tension / strand.axial_stiffness();
    let window = BendingTest::window_of(strand, opts.pitches)
        .map_err(|e| invalid(format!("bending test: {e}")))?;
    let first = first_slip_curvature(&law, &window, opts.tension);
    let curvatures = if opts.curvatures.is_empty() {
        let k0 = first.unwrap_or(1.0 / strand.length());
        (0..10)
            .map(|i| 0.2 * k0 * 100f64.powf(i as f64 / 9.0))
            .collect()
    } else {
        opts.curvatures.clone()
    };
    if curvatures.iter().any(|k| !k.is_finite() || *k == 0.0)
        || curvatures.windows(2).any(|w| w[1] == w[0])
    {
        return Err(invalid(format!(
            "--curvatures must be finite and non-zero, each different from the one before, got \
             {curvatures:?}"
        )));
    }
    let contact = ContactOptions {
        penetration: scene.models.fine.map_or(1e-3, |f| f.penetration),
        normal_penalty: penalty,
        ..ContactOptions::default()
    };
    let test = BendingTest {
        pitches: opts.pitches,
        segments_per_pitch: opts.segments_per_pitch,
        tension: opts.tension,
        curvatures: curvatures.clone(),
        contact,
        friction: strand.friction(),
        statics: BendingTest::load_step_statics(opts.tension),
        max_halvings: 6,
        core_springs: Default::default(),
        wire_springs: Default::default(),
        pressure: Default::default(),
    };
    let last = *curvatures.last().expect("at least one curvature");
    let start = Instant::now();
    let (curve, _, _) = test
        .run_with_progress(strand, &mut |p| progress(p, p.imposed_curvature / last))
        .map_err(|e| match e {
            BendingError::Setup(m) => invalid(format!("bending test: {m}")),
            e => RunError::Solve {
                model: "fine".into(),
                message: format!("bending test: {e}"),
                dir: opts.out.display().to_string(),
            },
        })?;
    let wall_time = start.elapsed().as_secs_f64();

    std::fs::create_dir_all(&opts.out).map_err(io_err(&opts.out))?;
    let path = opts.out.join("bending.csv");
    let mut csv = Csv::create(
        &path,
        &[
            "imposed_curvature",
            "curvature",
            "moment",
            "law_moment",
            "stiffness",
            "law_stiffness",
            "clamp_moment",
            "tension",
            "stick",
            "slip",
            "open",
            "axial_force",
            "law_moment_at_axial_force",
        ],
    )
    .map_err(io_err(&path))?;
    let mut points = Vec::new();
    let mut law_path = LawPath::new(&law, strand, &window);
    let mut measured_path = LawPath::new(&law, strand, &window);
    // The tension step (curvature zero) first, then the load steps.
    for p in curve.iter().skip(1) {
        let m_law = law_path.moment(&law, eps, p.curvature);
        let m_measured =
            measured_path.moment(&law, p.axial_force / strand.axial_stiffness(), p.curvature);
        csv.row(&[
            p.imposed_curvature,
            p.curvature,
            p.moment,
            m_law,
            p.secant_stiffness(),
            m_law / p.curvature,
            p.clamp_moment,
            p.tension,
            p.stick as f64,
            p.slip as f64,
            p.open as f64,
            p.axial_force,
            m_measured,
        ])
        .map_err(io_err(&path))?;
        points.push([p.curvature, p.moment, m_law]);
    }
    csv.finish().map_err(io_err(&path))?;
    let summary = BendingSummary {
        scene: scene.name.clone(),
        law: scene.law.to_string(),
        stick_stiffness: scene.section.stick_stiffness.to_string(),
        tension: opts.tension,
        strain: eps,
        k_min: strand.min_bending_stiffness(scene.section.base_stiffness),
        k_max: law.stick_bending_stiffness(),
        first_slip_curvature: first,
        pitches: opts.pitches,
        segments_per_pitch: opts.segments_per_pitch,
        window: window.describe(),
        window_support: window.support().into(),
        wall_time,
        points,
    };
    write_json(&opts.out.join("summary.json"), &summary)?;
    Ok(summary)
}

fn invalid(message: impl Into<String>) -> RunError {
    RunError::Setup {
        model: "fine".into(),
        message: message.into(),
    }
}

fn write_json(path: &Path, value: &impl Serialize) -> Result<(), RunError> {
    let text = serde_json::to_string_pretty(value).expect("summary serializes");
    std::fs::write(path, text + "\n").map_err(io_err(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On the 1+6+12 strand with friction (`examples/steel-1x19-swing.json`, 1000 N, loaded
    /// to 0.0125 then 0.05 1/m) the law's moment over the window of whole pitches of every
    /// layer is its mean along the strand, the mean over 200 outer pitches. That reference
    /// spans whole pitches of the outer layer and 258.18 of the inner one: a layer's moment
    /// varies along its pitch by less than the whole moment, so the leftover 0.18 inner pitch
    /// bounds its error by 0.18 / 258.18 = 7e-4 of the moment (the allowance). Measured 4.6e-6
    /// (one inner pitch, the stations before: 2.2e-5, within it too); one station instead of
    /// the window's fails (2.45e-3 off, checked once).
    #[test]
    fn the_laws_mean_over_the_window_is_its_mean_along_the_strand() {
        let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/steel-1x19-swing.json");
        let scene = Scene::load(&path).expect("bundled scene");
        let strand = &scene.strand;
        let law = SectionLaw::with_options(strand, scene.law, &scene.section);
        let eps = 1000.0 / strand.axial_stiffness();
        let pitches: Vec<f64> = strand.layers().iter().map(|l| l.pitch).collect();
        let outer = pitches.iter().copied().fold(0.0, f64::max);
        let window = PitchWindow::for_layers(&pitches, 3.0 * outer);
        let path_mean = |xs: &[f64]| {
            let mut lp = LawPath {
                stations: xs.iter().map(|&x| law.station(x)).collect(),
                slip: vec![vec![0.0; law.state_len()]; xs.len()],
                trial: vec![0.0; law.state_len()],
            };
            lp.moment(&law, eps, 0.0125);
            lp.moment(&law, eps, 0.05)
        };
        let n = 200 * 97;
        let long: Vec<f64> = (0..n)
            .map(|i| 200.0 * outer * (i as f64 + 0.5) / n as f64)
            .collect();
        let reference = path_mean(&long);
        let ours = path_mean(&window.stations(STATIONS));
        let inner: Vec<f64> = (0..STATIONS)
            .map(|i| pitches[0] * (i as f64 + 0.5) / STATIONS as f64)
            .collect();
        let before = path_mean(&inner);
        println!(
            "law moment: window {ours:.6e}, one inner pitch {before:.6e}, 200 outer pitches \
             {reference:.6e} N m"
        );
        let span = 200.0 * outer / pitches[0];
        let allowance = (span - span.floor()) / span;
        assert!(
            (ours / reference - 1.0).abs() < allowance,
            "window {:.3e} off",
            ours / reference - 1.0
        );
    }
}
