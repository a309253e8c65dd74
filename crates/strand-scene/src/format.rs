//! The scene file as written (SPEC 6): serde types that reject unknown fields.
//!
//! These mirror the JSON one to one; [`crate::Scene`] is the validated form. Lengths in m,
//! moduli in Pa, densities in kg/m^3, angles in degrees, times in s, accelerations in m/s^2.

use serde::{Deserialize, Serialize};

/// A scene file.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Scene name, used in result files.
    pub name: String,
    /// The strand.
    pub strand: StrandFile,
    /// Section law of the equivalent model: `continuous`, `paper`, `hysteretic` (default
    /// `continuous` in statics, `hysteretic` in dynamics).
    #[serde(default)]
    pub law: Option<String>,
    /// Options of the section law.
    #[serde(default)]
    pub section: Option<SectionFile>,
    /// Supports, at most one per end.
    #[serde(default)]
    pub supports: Vec<SupportFile>,
    /// Initial state: the strand starts straight and at rest.
    #[serde(default)]
    pub initial: Option<InitialFile>,
    /// Loads.
    #[serde(default)]
    pub loads: Option<LoadsFile>,
    /// Static or dynamic analysis.
    pub analysis: AnalysisFile,
    /// Which models to run, with their discretisation.
    pub models: ModelsFile,
    /// Extra result files: probes and range envelopes.
    #[serde(default)]
    pub output: Option<OutputFile>,
}

/// `output`: extra result files of a run (the standard ones are always written).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    /// Probes: material coordinates s (m, in [0, L]) at which every model writes
    /// `probe_<s>.csv`, the time history of the strand there. Default: midspan for a strand
    /// supported at both ends, else none (`[]` for none).
    #[serde(default)]
    pub probes: Option<Vec<f64>>,
    /// Dynamic: the time window `[t0, t1]` (s) over which `range.csv` takes its minimum,
    /// maximum and mean (default the whole run).
    #[serde(default)]
    pub range_window: Option<[f64; 2]>,
}

/// `strand`: length, core, layers, friction (SPEC 1).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct StrandFile {
    /// Strand length L (m).
    pub length: f64,
    /// The straight core wire.
    pub core: WireFile,
    /// Helical layers from the core outward (none: a plain wire).
    #[serde(default)]
    pub layers: Vec<LayerFile>,
    /// Friction coefficient mu between each layer and the layer (or core) beneath (default
    /// 0.3).
    #[serde(default)]
    pub friction: Option<f64>,
}

/// `section`: options of the equivalent model's section law.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct SectionFile {
    /// The helical wires' frictionless bending stiffness in K_min: `costello` (default),
    /// `foti`, `papailiou` or `paper` (eta = cos^3(alpha), eqs. (10), (11)).
    #[serde(default)]
    pub base_stiffness: Option<String>,
    /// The helical wires' stick stiffness: `bonded` (default; the plane-section K_stick times
    /// the bonded strand's stick factor, `strand_core::bonded`) or `plane_section` (eq. (22a),
    /// the paper's).
    #[serde(default)]
    pub stick_stiffness: Option<String>,
    /// The slipping wires' friction limit: `papailiou` (default; the capstan gain from the
    /// nearest neutral-axis crossing, axial projection cos(alpha)) or `paper` (eqs. (20),
    /// (22b) as printed).
    #[serde(default)]
    pub slip_limit: Option<String>,
    /// The contact pressure that sets each layer's friction limit: `accumulated` (the wire's
    /// own tension plus what the layers outside press down, with their exact wire counts and
    /// radii), `sc5` (the same with close-packed layers), `two_faces` (default; friction on
    /// both faces of a layer under others: the load from outside counted twice) or
    /// `own_layer` (the wire's own tension only, the capstan law of every layer). A strand of
    /// one layer has the same law under every choice.
    #[serde(default)]
    pub slip_pressure: Option<String>,
    /// Whether K_min follows the axial strain: `fixed` (default; the tension-free value) or
    /// `thin_rod` (each layer's share scaled by the thin-rod stiffness of the stretched helix,
    /// `strand_core::section::base_tension`).
    #[serde(default)]
    pub base_tension: Option<String>,
    /// Phase samples per wire of the pitch-averaged law: 0 (default) is the resolved law;
    /// 2 to 256 make each bending point stand for the whole pitch around it, every wire's
    /// slider evaluated at that many phases (the elements then take the Gauss rule of
    /// `models.equivalent.integration_points`, default 4, instead of the pitch rule).
    #[serde(default)]
    pub pitch_samples: Option<usize>,
}

/// A core wire.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct WireFile {
    /// Diameter (m).
    pub diameter: f64,
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    /// Poisson ratio (-).
    pub poisson_ratio: f64,
    /// Density (kg/m^3).
    pub density: f64,
}

/// A helical layer: give either `lay_angle_deg` or `pitch`.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LayerFile {
    /// Number of wires m.
    pub wires: i64,
    /// Wire diameter (m).
    pub diameter: f64,
    /// Lay angle alpha (deg), in (0, 90).
    #[serde(default)]
    pub lay_angle_deg: Option<f64>,
    /// Pitch P = 2 pi R_w / tan(alpha) (m), instead of the lay angle; R_w is the stacked
    /// helix radius (the diameter beneath plus this layer's wire diameter, halved).
    #[serde(default)]
    pub pitch: Option<f64>,
    /// Phase of wire 1 at x = 0 (deg), default 0.
    #[serde(default)]
    pub phase_deg: Option<f64>,
    /// `right` (default: phase grows with x) or `left`.
    #[serde(default)]
    pub lay_direction: Option<String>,
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    /// Poisson ratio (-).
    pub poisson_ratio: f64,
    /// Density (kg/m^3).
    pub density: f64,
}

/// A support at one end.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SupportFile {
    /// `start` (x = 0) or `end` (x = L).
    pub at: String,
    /// `clamped` (position and tangent fixed) or `pinned` (position fixed).
    pub kind: String,
    /// Prescribed displacement of the supported end: rows `[t, dx, dy, dz]` (s, m), linear
    /// between rows, from zero at t = 0; in statics the last row is applied with the load
    /// steps.
    #[serde(default)]
    pub motion: Option<Vec<[f64; 4]>>,
}

/// Initial state: the strand starts straight from the origin.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct InitialFile {
    /// Direction of the straight strand from the origin (normalised), default +X.
    #[serde(default)]
    pub direction: Option<[f64; 3]>,
    /// The direction at x = 0 from which wire phases are measured (phi = 0), projected off
    /// the direction; default the global Z projected off the direction (X for a strand along
    /// Z).
    #[serde(default)]
    pub phase_reference: Option<[f64; 3]>,
    /// Uniform initial velocity (m/s), dynamics only.
    #[serde(default)]
    pub velocity: Option<[f64; 3]>,
    /// Initial angular velocity (rad/s) of a rigid rotation about the origin, `v = w x r`,
    /// dynamics only.
    #[serde(default)]
    pub angular_velocity: Option<[f64; 3]>,
}

/// Loads.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LoadsFile {
    /// Gravitational acceleration (m/s^2); the load per length is the mass per length times it.
    #[serde(default)]
    pub gravity: Option<[f64; 3]>,
    /// Constant point forces (load-stepped in statics).
    #[serde(default)]
    pub points: Option<Vec<PointLoadFile>>,
}

/// A constant point force on the strand.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PointLoadFile {
    /// Material coordinate from the start (m), in [0, L].
    pub s: f64,
    /// Force (N).
    pub force: [f64; 3],
}

/// Analysis: `kind` is `static` or `dynamic`; the other fields belong to one of them.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AnalysisFile {
    /// `static` or `dynamic`.
    pub kind: String,
    /// Static: number of load steps (default 20).
    #[serde(default)]
    pub load_steps: Option<i64>,
    /// Dynamic: simulated time (s).
    #[serde(default)]
    pub duration: Option<f64>,
    /// Dynamic: `verlet` or `generalized-alpha`.
    #[serde(default)]
    pub integrator: Option<String>,
    /// Dynamic: time step (s); optional for `verlet` (the stable step is estimated).
    #[serde(default)]
    pub time_step: Option<f64>,
    /// Dynamic: interval between output frames (s).
    #[serde(default)]
    pub output_interval: Option<f64>,
    /// Dynamic, generalized-alpha: spectral radius at infinite frequency in [0, 1].
    #[serde(default)]
    pub spectral_radius: Option<f64>,
    /// Most time steps a model's run may take (default 10,000,000): a dynamic run that needs
    /// more is refused before it starts, with the count and an estimate of its time, and the
    /// fine model's static settling stops after this many. Raise it to run a longer analysis.
    #[serde(default)]
    pub max_steps: Option<i64>,
}

/// Models to run.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct ModelsFile {
    /// The equivalent ANCF beam with the scene's section law.
    #[serde(default)]
    pub equivalent: Option<BeamModelFile>,
    /// The traditional ANCF beam (constant EI of the envelope cylinder).
    #[serde(default)]
    pub traditional: Option<BeamModelFile>,
    /// The fine finite-segment model.
    #[serde(default)]
    pub fine: Option<FineModelFile>,
}

/// Discretisation of a beam model.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BeamModelFile {
    /// Number of elements.
    pub elements: i64,
    /// Gauss points per element for the bending term (default: from the wire pitch).
    #[serde(default)]
    pub integration_points: Option<i64>,
    /// Traditional model: mass per length (kg/m); default the strand's.
    #[serde(default)]
    pub mass_per_length: Option<f64>,
    /// Traditional model: bending stiffness EI (N m^2); default the envelope cylinder's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bending_stiffness: Option<f64>,
    /// Traditional model: axial stiffness EA (N); default the envelope cylinder's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_stiffness: Option<f64>,
}

/// Discretisation of the fine model.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FineModelFile {
    /// Segments per helical wire (the core gets as many over its shorter length).
    pub segments_per_wire: i64,
    /// Allowed contact penetration as a fraction of the wire diameter (default 1e-3): the
    /// normal penalty of a `1+m` strand; on several layers only where a wire-to-wire contact
    /// turns from a crossing into a line (the penalty follows from the strain relief).
    #[serde(default)]
    pub penetration: Option<f64>,
    /// Bind the wires together at the free end (default false).
    #[serde(default)]
    pub bind_free_end: Option<bool>,
}
