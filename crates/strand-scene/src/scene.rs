//! The validated scene (SPEC 6) and its parser.
//!
//! Parsing rejects unknown fields and wrong types with the JSON path of the fault
//! (`serde_path_to_error`); validation then checks values and names the field the same way,
//! e.g. `strand.layers[0].lay_angle_deg: must be in (0, 90), got 95`.

use std::path::Path;

use strand_ancf::beam::{
    ElementKind, MAX_BENDING_POINTS, pitch_rule_points, points_per_quarter_pitch,
};
use strand_core::{
    BaseStiffness, BaseTension, DEFAULT_FRICTION, InputError, LawKind, LayDirection, LayerSpec,
    Material, SectionLaw, SectionOptions, SlipLimit, SlipPressure, StickStiffness, Strand,
    StrandSpec, WireSpec,
};

use nalgebra::Vector3;
use strand_ancf::spatial::default_phase_reference;

use crate::format::{
    AnalysisFile, BeamModelFile, FineModelFile, LayerFile, OutputFile, SceneFile, SectionFile,
    WireFile,
};

/// A rejected scene: the JSON path of the fault and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}{message}", if path.is_empty() { String::new() } else { format!("{path}: ") })]
pub struct SceneError {
    /// JSON path of the offending value (empty for the whole file).
    pub path: String,
    /// What is wrong.
    pub message: String,
}

impl SceneError {
    fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        SceneError {
            path: path.into(),
            message: message.into(),
        }
    }
}

impl From<InputError> for SceneError {
    fn from(e: InputError) -> Self {
        SceneError::new(e.field, e.message)
    }
}

/// Default of `analysis.max_steps`: the most time steps a model's run may take unless the scene
/// (or `strand run --max-steps`) asks for more. The bundled scenes take at most about 1.1e6
/// (the fine model's settling of the Fig. 7 statics).
pub const DEFAULT_MAX_STEPS: usize = 10_000_000;

/// Largest memory a model may ask for before the scene is refused (bytes).
pub const MEMORY_LIMIT: f64 = 4.0 * (1u64 << 30) as f64;

/// Most rows a support's motion table (`supports[].motion`) may have: ample for a measured
/// history sampled every step of a long run, and far below what would weigh on memory (32 B a
/// row) or on the lookup (a binary search per step).
pub const MAX_MOTION_ROWS: usize = 1_000_000;

/// Most point forces (`loads.points`) a scene may apply: each is spread over the element (or
/// segments) around it once, before the run.
pub const MAX_POINT_FORCES: usize = 100_000;

/// Which end of the strand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    /// x = 0.
    Start,
    /// x = L.
    End,
}

/// How an end is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SupportKind {
    /// Position and tangent fixed.
    Clamped,
    /// Position fixed, free to rotate.
    Pinned,
}

/// A support.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// Where.
    pub at: End,
    /// How.
    pub kind: SupportKind,
    /// Prescribed displacement of the end, rows `[t, dx, dy, dz]` (s, m) with increasing
    /// times, linear between rows and from zero at t = 0; `None` for a fixed support.
    pub motion: Option<Vec<[f64; 4]>>,
}

/// A constant point force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointForce {
    /// Material coordinate from the start (m).
    pub s: f64,
    /// Force (N).
    pub force: [f64; 3],
}

/// Time integrator of a dynamic analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Stoermer-Verlet, explicit (the paper's).
    Verlet,
    /// Generalized-alpha, implicit.
    GeneralizedAlpha,
}

/// A dynamic analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dynamic {
    /// Simulated time (s).
    pub duration: f64,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Time step (s); `None` lets Verlet use its estimated stable step.
    pub time_step: Option<f64>,
    /// Interval between output frames (s).
    pub output_interval: f64,
    /// Generalized-alpha spectral radius at infinite frequency, in [0, 1].
    pub spectral_radius: f64,
}

/// The analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Analysis {
    /// Static equilibrium by load stepping.
    Static {
        /// Number of load steps.
        load_steps: usize,
    },
    /// Dynamics from rest.
    Dynamic(Dynamic),
}

/// Discretisation of a beam model (equivalent or traditional).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamModel {
    /// Number of elements.
    pub elements: usize,
    /// Gauss points per element; `None` chooses from the wire pitch.
    pub integration_points: Option<usize>,
    /// Mass per length (kg/m); `None` uses the strand's.
    pub mass_per_length: Option<f64>,
    /// Traditional model: EI (N m^2); `None` uses the envelope cylinder's.
    pub bending_stiffness: Option<f64>,
    /// Traditional model: EA (N); `None` uses the envelope cylinder's.
    pub axial_stiffness: Option<f64>,
}

/// Discretisation of the fine model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FineModel {
    /// Segments per helical wire.
    pub segments_per_wire: usize,
    /// Allowed contact penetration as a fraction of the wire diameter: sets the normal penalty
    /// of a `1+m` strand; on several layers only where a wire-to-wire contact turns from a
    /// crossing into a line (`strand_fine::penalty` sets the penalty there).
    pub penetration: f64,
    /// Whether the wires are bound together at the free end.
    pub bind_free_end: bool,
}

/// The models a scene runs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Models {
    /// Equivalent ANCF beam.
    pub equivalent: Option<BeamModel>,
    /// Traditional ANCF beam.
    pub traditional: Option<BeamModel>,
    /// Fine finite-segment model.
    pub fine: Option<FineModel>,
}

/// Most probes (`output.probes`) a scene may name: each is a file written at every output
/// frame of every model.
pub const MAX_PROBES: usize = 1000;

/// Extra result files (`output`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Output {
    /// Material coordinates s (m, in [0, L]) of the probes, in the scene's order; without
    /// `output.probes`, midspan for a strand supported at both ends, else none.
    pub probes: Vec<f64>,
    /// Time window `(t0, t1)` (s) of the range envelopes; `None` for the whole run.
    pub range_window: Option<(f64, f64)>,
}

/// A validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Scene name.
    pub name: String,
    /// The strand.
    pub strand: Strand,
    /// Section law of the equivalent model.
    pub law: LawKind,
    /// Options of the section law (`section`).
    pub section: SectionOptions,
    /// Supports.
    pub supports: Vec<Support>,
    /// Unit direction of the initially straight strand.
    pub direction: [f64; 3],
    /// The direction at x = 0 from which wire phases are measured (unit, orthogonal to the
    /// direction): the scene's `initial.phase_reference` projected off the direction, or the
    /// default ([`strand_ancf::spatial::default_phase_reference`]).
    pub phase_reference: [f64; 3],
    /// Uniform initial velocity (m/s).
    pub velocity: [f64; 3],
    /// Initial angular velocity about the origin (rad/s): `v = w x r`.
    pub angular_velocity: [f64; 3],
    /// Gravitational acceleration (m/s^2).
    pub gravity: [f64; 3],
    /// Constant point forces.
    pub point_forces: Vec<PointForce>,
    /// Analysis.
    pub analysis: Analysis,
    /// Most time steps a model's run may take (`analysis.max_steps`).
    pub max_steps: usize,
    /// Models to run.
    pub models: Models,
    /// Extra result files.
    pub output: Output,
    /// The file as parsed (for provenance in result files).
    pub file: SceneFile,
}

impl Scene {
    /// Reads and validates a scene file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SceneError::new("", format!("cannot read {}: {e}", path.display())))?;
        Scene::parse(&text)
    }

    /// Parses and validates scene JSON.
    pub fn parse(text: &str) -> Result<Scene, SceneError> {
        if text.trim().is_empty() {
            return Err(SceneError::new("", "the scene file is empty"));
        }
        let de = &mut serde_json::Deserializer::from_str(text);
        let file: SceneFile = serde_path_to_error::deserialize(de).map_err(|e| {
            let path = e.path().to_string();
            let path = if path == "." { String::new() } else { path };
            SceneError::new(path, e.into_inner().to_string())
        })?;
        Scene::from_file(file)
    }

    /// Validates a parsed scene file.
    pub fn from_file(file: SceneFile) -> Result<Scene, SceneError> {
        if file.name.trim().is_empty() {
            return Err(SceneError::new("name", "must not be empty"));
        }
        let strand = strand(&file)?;
        let section = section(file.section.as_ref())?;
        let law = match file.law.as_deref() {
            // Decided below from the analysis: `continuous` in statics, `hysteretic` in dynamics.
            None => None,
            Some("continuous") => Some(LawKind::Continuous),
            Some("paper") => Some(LawKind::Paper),
            Some("hysteretic") => Some(LawKind::Hysteretic),
            Some("constant") => {
                return Err(SceneError::new(
                    "law",
                    "`constant` is the traditional model's law: add models.traditional instead",
                ));
            }
            Some(other) => {
                return Err(SceneError::new(
                    "law",
                    format!("unknown law `{other}`: expected continuous, paper or hysteretic"),
                ));
            }
        };
        if let Some(kind) = law {
            SectionLaw::check(&strand, kind).map_err(|e| SceneError::from(e.within("strand")))?;
        }

        let mut supports: Vec<Support> = Vec::new();
        for (i, s) in file.supports.iter().enumerate() {
            let at = match s.at.as_str() {
                "start" => End::Start,
                "end" => End::End,
                o => {
                    return Err(SceneError::new(
                        format!("supports[{i}].at"),
                        format!("unknown end `{o}`: expected start or end"),
                    ));
                }
            };
            let kind = match s.kind.as_str() {
                "clamped" => SupportKind::Clamped,
                "pinned" => SupportKind::Pinned,
                o => {
                    return Err(SceneError::new(
                        format!("supports[{i}].kind"),
                        format!("unknown support `{o}`: expected clamped or pinned"),
                    ));
                }
            };
            if supports.iter().any(|p| p.at == at) {
                return Err(SceneError::new(
                    format!("supports[{i}].at"),
                    "this end already has a support",
                ));
            }
            let motion = match &s.motion {
                None => None,
                Some(rows) => Some(motion(&format!("supports[{i}].motion"), rows)?),
            };
            supports.push(Support { at, kind, motion });
        }

        let direction = match file.initial.as_ref().and_then(|i| i.direction) {
            None => [1.0, 0.0, 0.0],
            Some(d) => {
                let p = "initial.direction";
                finite_vec(p, &d)?;
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                if n == 0.0 {
                    return Err(SceneError::new(p, "must not be the zero vector"));
                }
                [d[0] / n, d[1] / n, d[2] / n]
            }
        };
        let initial = file.initial.as_ref();
        let phase_reference = match initial.and_then(|i| i.phase_reference) {
            None => default_phase_reference(&Vector3::from(direction)).normalize(),
            Some(r) => {
                let p = "initial.phase_reference";
                finite_vec(p, &r)?;
                let (d, r) = (Vector3::from(direction), Vector3::from(r));
                let off = r - d * d.dot(&r);
                if off.norm() <= 1e-9 * r.norm() {
                    return Err(SceneError::new(
                        p,
                        "must have a part off initial.direction (it is zero or parallel to it)",
                    ));
                }
                off.normalize()
            }
        }
        .into();
        let velocity = initial.and_then(|i| i.velocity).unwrap_or([0.0; 3]);
        finite_vec("initial.velocity", &velocity)?;
        let angular_velocity = initial.and_then(|i| i.angular_velocity).unwrap_or([0.0; 3]);
        finite_vec("initial.angular_velocity", &angular_velocity)?;
        let gravity = match file.loads.as_ref().and_then(|l| l.gravity) {
            None => [0.0; 3],
            Some(g) => {
                finite_vec("loads.gravity", &g)?;
                g
            }
        };
        let points = file.loads.as_ref().and_then(|l| l.points.as_deref());
        let points = points.unwrap_or_default();
        if points.len() > MAX_POINT_FORCES {
            return Err(SceneError::new(
                "loads.points",
                format!(
                    "{} point forces, more than the {MAX_POINT_FORCES} a scene may apply: add \
                     the forces that act at one place, or use gravity for a distributed load",
                    points.len()
                ),
            ));
        }
        let mut point_forces = Vec::with_capacity(points.len());
        for (k, p) in points.iter().enumerate() {
            let path = format!("loads.points[{k}]");
            let s = finite(&format!("{path}.s"), p.s)?;
            let length = strand.length();
            if !(0.0..=length).contains(&s) {
                return Err(SceneError::new(
                    format!("{path}.s"),
                    format!("must be in [0, {length}] (metres from the start), got {s}"),
                ));
            }
            finite_vec(&format!("{path}.force"), &p.force)?;
            point_forces.push(PointForce { s, force: p.force });
        }
        let analysis = analysis(&file.analysis)?;
        // A dynamic run defaults to the only energetically consistent stick/slip law: the
        // moment of `continuous` and `paper` depends on the tension without a potential, so
        // their non-potential work can feed energy in (the manual, docs/book/src/findings.md).
        let law = law.unwrap_or(match analysis {
            Analysis::Static { .. } => LawKind::Continuous,
            Analysis::Dynamic(_) => LawKind::Hysteretic,
        });
        if matches!(analysis, Analysis::Static { .. }) {
            for (field, v) in [
                ("velocity", velocity),
                ("angular_velocity", angular_velocity),
            ] {
                if v != [0.0; 3] {
                    return Err(SceneError::new(
                        format!("initial.{field}"),
                        "only for a dynamic analysis (a static one has no velocity)",
                    ));
                }
            }
        }
        let max_steps = count(
            "analysis.max_steps",
            file.analysis.max_steps.unwrap_or(DEFAULT_MAX_STEPS as i64),
            1,
            i64::MAX,
        )?;
        if matches!(analysis, Analysis::Static { .. }) && supports.is_empty() {
            return Err(SceneError::new(
                "supports",
                "a static analysis needs at least one support",
            ));
        }
        let element = Motion {
            direction,
            gravity,
            velocity,
            angular_velocity,
            phase_reference,
            point_forces: &point_forces,
            supports: &supports,
        }
        .element();
        let models = models(&file, &strand, element)?;
        if models.fine.is_some()
            && matches!(analysis, Analysis::Static { .. })
            && supports.iter().any(|s| s.motion.is_some())
        {
            return Err(SceneError::new(
                "models.fine",
                "the fine model cannot run a static analysis with a moving support \
                 (supports[].motion): its static solvers step gravity and forces, not the \
                 supports; run the fine model in a dynamic analysis",
            ));
        }
        let both_ends = supports.len() == 2;
        let output = output(file.output.as_ref(), strand.length(), &analysis, both_ends)?;
        Ok(Scene {
            name: file.name.clone(),
            strand,
            law,
            section,
            supports,
            direction,
            phase_reference,
            velocity,
            angular_velocity,
            gravity,
            point_forces,
            analysis,
            max_steps,
            models,
            output,
            file,
        })
    }

    /// Whether the scene stays in the global XY plane, so the planar element can be used: the
    /// direction, gravity, initial velocity, point forces and support motions have no Z
    /// component, the initial rotation is about Z, and the wire phases are measured from +Z
    /// (the planar element's convention).
    pub fn is_planar(&self) -> bool {
        self.element() == ElementKind::Planar
    }

    /// The element the beams of this scene are built with: planar if the scene stays in the
    /// XY plane ([`Scene::is_planar`]), else spatial.
    pub fn element(&self) -> ElementKind {
        Motion {
            direction: self.direction,
            gravity: self.gravity,
            velocity: self.velocity,
            angular_velocity: self.angular_velocity,
            phase_reference: self.phase_reference,
            point_forces: &self.point_forces,
            supports: &self.supports,
        }
        .element()
    }

    /// Whether the strand starts moving: a non-zero initial velocity or angular velocity.
    pub fn starts_moving(&self) -> bool {
        self.velocity != [0.0; 3] || self.angular_velocity != [0.0; 3]
    }
}

/// A support's motion table at JSON path `path`: finite values, times non-negative and
/// increasing, zero displacement at t = 0.
fn motion(path: &str, rows: &[[f64; 4]]) -> Result<Vec<[f64; 4]>, SceneError> {
    if rows.is_empty() {
        return Err(SceneError::new(
            path,
            "needs at least one row [t, dx, dy, dz]",
        ));
    }
    if rows.len() > MAX_MOTION_ROWS {
        return Err(SceneError::new(
            path,
            format!(
                "{} rows, more than the {MAX_MOTION_ROWS} a table may have: sample the motion \
                 more coarsely (it is interpolated linearly between rows)",
                rows.len()
            ),
        ));
    }
    let mut last = None;
    let mut prev = [0.0; 3];
    for (r, row) in rows.iter().enumerate() {
        finite_vec(&format!("{path}[{r}]"), row)?;
        let t = row[0];
        let p = format!("{path}[{r}][0]");
        if t < 0.0 {
            return Err(SceneError::new(
                p,
                format!("time must not be negative, got {t}"),
            ));
        }
        if let Some(l) = last
            && t <= l
        {
            return Err(SceneError::new(
                p,
                format!("times must increase: {t} s after {l} s"),
            ));
        }
        if t == 0.0 && row[1..] != [0.0; 3] {
            return Err(SceneError::new(
                format!("{path}[{r}]"),
                "the displacement at t = 0 must be zero (the strand starts straight at its \
                 supports)",
            ));
        }
        // The speed between rows (from rest at t = 0 to the first) must be a number.
        let (t0, d0) = last.map_or((0.0, [0.0; 3]), |l| (l, prev));
        if t > t0 && (0..3).any(|c| !((row[c + 1] - d0[c]) / (t - t0)).is_finite()) {
            return Err(SceneError::new(
                format!("{path}[{r}]"),
                format!(
                    "moves the support at a speed that is not a finite number ({:?} m in \
                     {:e} s)",
                    [row[1] - d0[0], row[2] - d0[1], row[3] - d0[2]],
                    t - t0
                ),
            ));
        }
        last = Some(t);
        prev = [row[1], row[2], row[3]];
    }
    Ok(rows.to_vec())
}

/// The `output` section: probes in [0, L] (by default midspan for a strand supported at both
/// ends, `both_ends`, else none), a range window inside a dynamic run.
fn output(
    file: Option<&OutputFile>,
    length: f64,
    analysis: &Analysis,
    both_ends: bool,
) -> Result<Output, SceneError> {
    let default = OutputFile::default();
    let file = file.unwrap_or(&default);
    let probes = match &file.probes {
        Some(p) => p.clone(),
        None if both_ends => vec![0.5 * length],
        None => Vec::new(),
    };
    if probes.len() > MAX_PROBES {
        return Err(SceneError::new(
            "output.probes",
            format!(
                "{} probes, more than the {MAX_PROBES} a scene may name (each is a file)",
                probes.len()
            ),
        ));
    }
    for (k, &s) in probes.iter().enumerate() {
        let path = format!("output.probes[{k}]");
        finite(&path, s)?;
        if !(0.0..=length).contains(&s) {
            return Err(SceneError::new(
                path,
                format!("must be in [0, {length}] (metres from the start), got {s}"),
            ));
        }
        if probes[..k].contains(&s) {
            return Err(SceneError::new(path, format!("s = {s} is named twice")));
        }
    }
    let range_window = match file.range_window {
        None => None,
        Some([t0, t1]) => {
            let path = "output.range_window";
            finite_vec(path, &[t0, t1])?;
            let Analysis::Dynamic(dy) = analysis else {
                return Err(SceneError::new(
                    path,
                    "only for a dynamic analysis (range.csv is written by dynamic runs)",
                ));
            };
            if !(0.0 <= t0 && t0 <= t1 && t0 <= dy.duration) {
                return Err(SceneError::new(
                    path,
                    format!(
                        "must be [t0, t1] with 0 <= t0 <= t1 and t0 <= analysis.duration = {} \
                         s, got [{t0}, {t1}]",
                        dy.duration
                    ),
                ));
            }
            Some((t0, t1))
        }
    };
    Ok(Output {
        probes,
        range_window,
    })
}

fn finite(path: &str, v: f64) -> Result<f64, SceneError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(SceneError::new(
            path,
            format!("must be a finite number, got {v}"),
        ))
    }
}

fn finite_vec(path: &str, v: &[f64]) -> Result<(), SceneError> {
    for (i, x) in v.iter().enumerate() {
        finite(&format!("{path}[{i}]"), *x)?;
    }
    Ok(())
}

fn positive(path: &str, v: f64) -> Result<f64, SceneError> {
    finite(path, v)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(SceneError::new(path, format!("must be positive, got {v}")))
    }
}

fn count(path: &str, v: i64, min: i64, max: i64) -> Result<usize, SceneError> {
    if v < min || v > max {
        Err(SceneError::new(
            path,
            format!("must be a whole number from {min} to {max}, got {v}"),
        ))
    } else {
        Ok(v as usize)
    }
}

/// Most phase samples per wire `section.pitch_samples` accepts.
const MAX_PITCH_SAMPLES: usize = 256;

fn section(file: Option<&SectionFile>) -> Result<SectionOptions, SceneError> {
    let mut options = SectionOptions::default();
    let Some(file) = file else {
        return Ok(options);
    };
    if let Some(name) = file.base_stiffness.as_deref() {
        options.base_stiffness = BaseStiffness::from_name(name).ok_or_else(|| {
            let names: Vec<&str> = BaseStiffness::ALL.iter().map(|b| b.name()).collect();
            SceneError::new(
                "section.base_stiffness",
                format!(
                    "unknown base stiffness `{name}`: expected {}",
                    names.join(", ")
                ),
            )
        })?;
    }
    if let Some(name) = file.stick_stiffness.as_deref() {
        options.stick_stiffness = StickStiffness::from_name(name).ok_or_else(|| {
            let names: Vec<&str> = StickStiffness::ALL.iter().map(|b| b.name()).collect();
            SceneError::new(
                "section.stick_stiffness",
                format!(
                    "unknown stick stiffness `{name}`: expected {}",
                    names.join(", ")
                ),
            )
        })?;
    }
    if let Some(name) = file.slip_pressure.as_deref() {
        options.slip_pressure = SlipPressure::from_name(name).ok_or_else(|| {
            let names: Vec<&str> = SlipPressure::ALL.iter().map(|b| b.name()).collect();
            SceneError::new(
                "section.slip_pressure",
                format!(
                    "unknown slip pressure `{name}`: expected {}",
                    names.join(", ")
                ),
            )
        })?;
    }
    if let Some(name) = file.base_tension.as_deref() {
        options.base_tension = BaseTension::from_name(name).ok_or_else(|| {
            let names: Vec<&str> = BaseTension::ALL.iter().map(|b| b.name()).collect();
            SceneError::new(
                "section.base_tension",
                format!(
                    "unknown base tension `{name}`: expected {}",
                    names.join(", ")
                ),
            )
        })?;
    }
    if let Some(samples) = file.pitch_samples {
        if samples == 1 || samples > MAX_PITCH_SAMPLES {
            return Err(SceneError::new(
                "section.pitch_samples",
                format!(
                    "{samples} phase samples: expected 0 (the resolved law) or 2 to \
                     {MAX_PITCH_SAMPLES}"
                ),
            ));
        }
        options.pitch_samples = samples;
    }
    if let Some(name) = file.slip_limit.as_deref() {
        options.slip_limit = SlipLimit::from_name(name).ok_or_else(|| {
            let names: Vec<&str> = SlipLimit::ALL.iter().map(|b| b.name()).collect();
            SceneError::new(
                "section.slip_limit",
                format!("unknown slip limit `{name}`: expected {}", names.join(", ")),
            )
        })?;
    }
    Ok(options)
}

fn material(w: &WireFile) -> Material {
    Material {
        youngs_modulus: w.youngs_modulus,
        poisson_ratio: w.poisson_ratio,
        density: w.density,
    }
}

fn strand(file: &SceneFile) -> Result<Strand, SceneError> {
    let s = &file.strand;
    let core = WireSpec {
        diameter: s.core.diameter,
        material: material(&s.core),
    };
    let mut layers = Vec::new();
    // The diameter of what each layer lies on (the core, then the layers beneath), for a
    // pitch given instead of a lay angle.
    let mut beneath = core.diameter;
    for (k, l) in s.layers.iter().enumerate() {
        layers.push(layer(k, l, beneath)?);
        beneath += 2.0 * l.diameter;
    }
    let mut spec = StrandSpec {
        length: s.length,
        core,
        layers,
        friction: s.friction.unwrap_or(DEFAULT_FRICTION),
    };
    let mut strand = Strand::new(spec.clone()).map_err(|e| e.within("strand"))?;
    // A layer given by its pitch keeps it on the radius the stacking gives: a closed layer's
    // lift (and the lifts beneath an outer layer) move the helix radius off the stacked one
    // the angle was taken on (Cardinal's steel layer: 16.6 um, which made its 0.2104 m pitch
    // 0.2114 m). The lift depends on the angle only weakly (through d_w / cos alpha), so
    // taking the angle again on the new radius converges in a few rounds.
    for _ in 0..MAX_PITCH_ROUNDS {
        let mut moved = false;
        for ((l, built), lay) in s.layers.iter().zip(strand.layers()).zip(&mut spec.layers) {
            if let Some(pitch) = l.pitch
                && (built.pitch - pitch).abs() > PITCH_TOLERANCE * pitch
            {
                lay.lay_angle = (2.0 * std::f64::consts::PI * built.radius / pitch).atan();
                moved = true;
            }
        }
        if !moved {
            break;
        }
        strand = Strand::new(spec.clone()).map_err(|e| e.within("strand"))?;
    }
    Ok(strand)
}

/// Relative tolerance of a layer's pitch against the scene's `pitch` (module docs of
/// [`strand`]): far below any lay length's manufacturing tolerance, far above round-off.
const PITCH_TOLERANCE: f64 = 1e-12;

/// Rounds of taking a given pitch's lay angle again on the lifted radius; each shrinks the
/// pitch's error by the lift's sensitivity to the angle (about tan(alpha)^2 d R / R), so two
/// or three reach [`PITCH_TOLERANCE`].
const MAX_PITCH_ROUNDS: usize = 20;

/// Layer `k` of the scene, lying on a cylinder of diameter `beneath` (m): a pitch converts to
/// the lay angle on the stacked helix radius (beneath + d_w) / 2, taken again on the lifted
/// radius of a closed layer by [`strand`].
fn layer(k: usize, l: &LayerFile, beneath: f64) -> Result<LayerSpec, SceneError> {
    let p = |f: &str| format!("strand.layers[{k}].{f}");
    let wires = count(&p("wires"), l.wires, 1, 1000)?;
    let lay_angle = match (l.lay_angle_deg, l.pitch) {
        (Some(_), Some(_)) => {
            return Err(SceneError::new(
                p("pitch"),
                "give either lay_angle_deg or pitch, not both",
            ));
        }
        (None, None) => {
            return Err(SceneError::new(
                format!("strand.layers[{k}]"),
                "needs lay_angle_deg or pitch",
            ));
        }
        (Some(a), None) => finite(&p("lay_angle_deg"), a)?.to_radians(),
        (None, Some(pitch)) => {
            let pitch = positive(&p("pitch"), pitch)?;
            let rw = 0.5 * (beneath + l.diameter);
            (2.0 * std::f64::consts::PI * rw / pitch).atan()
        }
    };
    let direction = match l.lay_direction.as_deref() {
        None | Some("right") => LayDirection::Right,
        Some("left") => LayDirection::Left,
        Some(o) => {
            return Err(SceneError::new(
                p("lay_direction"),
                format!("unknown lay direction `{o}`: expected right or left"),
            ));
        }
    };
    Ok(LayerSpec {
        wires,
        wire: WireSpec {
            diameter: l.diameter,
            material: Material {
                youngs_modulus: l.youngs_modulus,
                poisson_ratio: l.poisson_ratio,
                density: l.density,
            },
        },
        lay_angle,
        phase: finite(&p("phase_deg"), l.phase_deg.unwrap_or(0.0))?.to_radians(),
        direction,
    })
}

fn analysis(a: &AnalysisFile) -> Result<Analysis, SceneError> {
    let only = |field: &str, present: bool, kind: &str| {
        if present {
            Err(SceneError::new(
                format!("analysis.{field}"),
                format!("only for a {kind} analysis"),
            ))
        } else {
            Ok(())
        }
    };
    match a.kind.as_str() {
        "static" => {
            only("duration", a.duration.is_some(), "dynamic")?;
            only("integrator", a.integrator.is_some(), "dynamic")?;
            only("time_step", a.time_step.is_some(), "dynamic")?;
            only("output_interval", a.output_interval.is_some(), "dynamic")?;
            only("spectral_radius", a.spectral_radius.is_some(), "dynamic")?;
            let load_steps = count(
                "analysis.load_steps",
                a.load_steps.unwrap_or(20),
                1,
                1_000_000,
            )?;
            Ok(Analysis::Static { load_steps })
        }
        "dynamic" => {
            only("load_steps", a.load_steps.is_some(), "static")?;
            let duration = positive(
                "analysis.duration",
                a.duration.ok_or_else(|| {
                    SceneError::new("analysis.duration", "a dynamic analysis needs a duration")
                })?,
            )?;
            let integrator = match a.integrator.as_deref() {
                Some("verlet") => IntegratorKind::Verlet,
                Some("generalized-alpha") => IntegratorKind::GeneralizedAlpha,
                Some(o) => {
                    return Err(SceneError::new(
                        "analysis.integrator",
                        format!("unknown integrator `{o}`: expected verlet or generalized-alpha"),
                    ));
                }
                None => {
                    return Err(SceneError::new(
                        "analysis.integrator",
                        "a dynamic analysis needs an integrator: verlet or generalized-alpha",
                    ));
                }
            };
            let time_step = match a.time_step {
                Some(h) => {
                    let h = positive("analysis.time_step", h)?;
                    if h > duration {
                        return Err(SceneError::new(
                            "analysis.time_step",
                            format!("{h} s is longer than the duration {duration} s"),
                        ));
                    }
                    Some(h)
                }
                None if integrator == IntegratorKind::GeneralizedAlpha => {
                    return Err(SceneError::new(
                        "analysis.time_step",
                        "generalized-alpha needs a time step",
                    ));
                }
                None => None,
            };
            let output_interval = match a.output_interval {
                Some(o) => positive("analysis.output_interval", o)?,
                None => duration / 100.0,
            };
            if integrator != IntegratorKind::GeneralizedAlpha {
                only(
                    "spectral_radius",
                    a.spectral_radius.is_some(),
                    "generalized-alpha",
                )?;
            }
            let rho = finite("analysis.spectral_radius", a.spectral_radius.unwrap_or(0.9))?;
            if !(0.0..=1.0).contains(&rho) {
                return Err(SceneError::new(
                    "analysis.spectral_radius",
                    format!("must be in [0, 1], got {rho}"),
                ));
            }
            Ok(Analysis::Dynamic(Dynamic {
                duration,
                integrator,
                time_step,
                output_interval,
                spectral_radius: rho,
            }))
        }
        o => Err(SceneError::new(
            "analysis.kind",
            format!("unknown analysis `{o}`: expected static or dynamic"),
        )),
    }
}

/// Memory of a beam model (bytes) with `n` elements, `points` bending points in all and `wires`
/// helical wires: nodal vectors, band matrices and element data per element; per bending point
/// its quadrature row, section station (per wire: phase, levers, gains) and the run's copies
/// of the point states and of the slip state (generalized-alpha keeps one per level of step
/// cutting). Measured as the largest resident set of `strand run` (`/usr/bin/time -v`) on
/// generalized-alpha runs with the `hysteretic` law, the most state, of the Table 1 strand
/// lengthened to 40-800 m: 6.3 KB per element (with one point), and per point 614 B with one
/// wire, 792 B with 3, 1159 B with 6; the constants below are those plus a quarter.
pub fn beam_memory(n: usize, points: f64, wires: usize) -> f64 {
    n as f64 * MEMORY_PER_ELEMENT
        + points * (MEMORY_PER_POINT + MEMORY_PER_POINT_WIRE * wires as f64)
}

/// Memory per beam element (bytes).
const MEMORY_PER_ELEMENT: f64 = 7680.0;
/// Memory per bending point without wires (bytes).
const MEMORY_PER_POINT: f64 = 640.0;
/// Memory per bending point and helical wire (bytes).
const MEMORY_PER_POINT_WIRE: f64 = 136.0;

/// Memory of a fine model (bytes) with `segments` segments per wire and `wires` wires (core
/// included): poses, velocities, joints, contacts and the run's copies of the state. Measured
/// like [`beam_memory`] on the Table 1 strand with 2000 and 8000 segments per wire: 6.2 KB per
/// segment with one helical wire, 7.1 KB with six; 8 KB is used.
pub fn fine_memory(segments: usize, wires: usize) -> f64 {
    segments as f64 * wires as f64 * 8192.0
}

fn gib(bytes: f64) -> f64 {
    bytes / (1u64 << 30) as f64
}

/// The vectors of a scene that decide whether it stays in the XY plane.
struct Motion<'a> {
    direction: [f64; 3],
    gravity: [f64; 3],
    velocity: [f64; 3],
    angular_velocity: [f64; 3],
    phase_reference: [f64; 3],
    point_forces: &'a [PointForce],
    supports: &'a [Support],
}

impl Motion<'_> {
    fn element(&self) -> ElementKind {
        let w = self.angular_velocity;
        let planar = self.direction[2] == 0.0
            && self.gravity[2] == 0.0
            && self.velocity[2] == 0.0
            && w[0] == 0.0
            && w[1] == 0.0
            && self.phase_reference == [0.0, 0.0, 1.0]
            && self.point_forces.iter().all(|p| p.force[2] == 0.0)
            && self
                .supports
                .iter()
                .flat_map(|s| s.motion.iter().flatten())
                .all(|r| r[3] == 0.0);
        if planar {
            ElementKind::Planar
        } else {
            ElementKind::Spatial
        }
    }
}

/// The equivalent or traditional beam of `models`. `samples` is the pitch-averaged law's
/// phase samples per wire (`section.pitch_samples`; 0 or 1: the resolved law), under which the
/// equivalent beam takes the Gauss rule instead of the pitch rule and carries `samples`
/// sliders per wire.
fn beam(
    path: &str,
    m: &BeamModelFile,
    strand: &Strand,
    traditional: bool,
    element: ElementKind,
    samples: usize,
) -> Result<BeamModel, SceneError> {
    let field = format!("{path}.elements");
    let elements = count(&field, m.elements, 1, i64::MAX)?;
    let integration_points = match m.integration_points {
        Some(n) => Some(count(&format!("{path}.integration_points"), n, 1, 10)?),
        None => None,
    };
    let l = strand.length() / elements as f64;
    // Bending points per element: the scene's Gauss rule, the pitch rule of the stick/slip
    // laws (the traditional beam has no wires: 4 points), as `strand_ancf::beam` builds them.
    // The shortest of the layers' pitches sets the rule: it resolves every layer's phases. A
    // pitch-averaged law's bending point stands for a whole pitch: 4 points.
    let averaged = samples > 1 && !traditional;
    let per_element = match (integration_points, strand.shortest_pitch()) {
        (Some(n), _) => n as f64,
        (None, Some(pitch)) if !traditional && !averaged => pitch_rule_points(l, pitch, element),
        _ => 4.0,
    };
    if integration_points.is_none() && per_element > MAX_BENDING_POINTS as f64 {
        let pitch = strand.shortest_pitch().unwrap_or(f64::NAN);
        return Err(SceneError::new(
            field,
            format!(
                "{elements} element(s) of {l:.4e} m each span {:.4e} wire pitches (P = {pitch:.4e} \
                 m); the pitch rule puts {} bending point(s) on every quarter pitch, {per_element:.4e} \
                 per element, above the cap of {MAX_BENDING_POINTS}: use at least {:.0} elements \
                 (or the pitch-averaged law, `section.pitch_samples`)",
                l / pitch,
                points_per_quarter_pitch(element),
                (elements as f64 * per_element / MAX_BENDING_POINTS as f64).ceil()
            ),
        ));
    }
    let wires = if traditional {
        0
    } else {
        strand.helical_wires() * samples.max(1)
    };
    let points = elements as f64 * per_element;
    let need = beam_memory(elements, points, wires);
    if need > MEMORY_LIMIT {
        return Err(SceneError::new(
            field,
            format!(
                "{elements} elements with {per_element} bending points each ({points:.4e} in all, \
                 {wires} wires) would need about {:.1} GiB of memory (limit {:.0} GiB)",
                gib(need),
                gib(MEMORY_LIMIT)
            ),
        ));
    }
    let mass_per_length = match m.mass_per_length {
        Some(_) if !traditional => {
            return Err(SceneError::new(
                format!("{path}.mass_per_length"),
                "only for the traditional model (the equivalent model uses the strand's, eq. (44))",
            ));
        }
        Some(v) => Some(positive(&format!("{path}.mass_per_length"), v)?),
        None => None,
    };
    let traditional_only = |name: &str, value: Option<f64>| match value {
        Some(_) if !traditional => Err(SceneError::new(
            format!("{path}.{name}"),
            "only for the traditional model (the equivalent model's stiffness is its section law)",
        )),
        Some(v) => Ok(Some(positive(&format!("{path}.{name}"), v)?)),
        None => Ok(None),
    };
    let bending_stiffness = traditional_only("bending_stiffness", m.bending_stiffness)?;
    let axial_stiffness = traditional_only("axial_stiffness", m.axial_stiffness)?;
    Ok(BeamModel {
        elements,
        integration_points,
        mass_per_length,
        bending_stiffness,
        axial_stiffness,
    })
}

fn fine(m: &FineModelFile, strand: &Strand) -> Result<FineModel, SceneError> {
    let p = "models.fine.segments_per_wire";
    let segments_per_wire = count(p, m.segments_per_wire, 2, i64::MAX)?;
    let wires = 1 + strand.helical_wires();
    let need = fine_memory(segments_per_wire, wires);
    if need > MEMORY_LIMIT {
        return Err(SceneError::new(
            p,
            format!(
                "{segments_per_wire} segments per wire ({wires} wires) would need about {:.1} GiB \
                 of memory (limit {:.0} GiB)",
                gib(need),
                gib(MEMORY_LIMIT)
            ),
        ));
    }
    let penetration = finite("models.fine.penetration", m.penetration.unwrap_or(1e-3))?;
    if !(penetration > 0.0 && penetration < 0.5) {
        return Err(SceneError::new(
            "models.fine.penetration",
            format!("must be in (0, 0.5) (a fraction of the wire diameter), got {penetration}"),
        ));
    }
    Ok(FineModel {
        segments_per_wire,
        penetration,
        bind_free_end: m.bind_free_end.unwrap_or(false),
    })
}

fn models(file: &SceneFile, strand: &Strand, element: ElementKind) -> Result<Models, SceneError> {
    let m = &file.models;
    let samples = file
        .section
        .as_ref()
        .and_then(|s| s.pitch_samples)
        .unwrap_or(0);
    if m.equivalent.is_none() && m.traditional.is_none() && m.fine.is_none() {
        return Err(SceneError::new(
            "models",
            "name at least one model: equivalent, traditional or fine",
        ));
    }
    Ok(Models {
        equivalent: m
            .equivalent
            .as_ref()
            .map(|b| beam("models.equivalent", b, strand, false, element, samples))
            .transpose()?,
        traditional: m
            .traditional
            .as_ref()
            .map(|b| beam("models.traditional", b, strand, true, element, 0))
            .transpose()?,
        fine: m.fine.as_ref().map(|f| fine(f, strand)).transpose()?,
    })
}
