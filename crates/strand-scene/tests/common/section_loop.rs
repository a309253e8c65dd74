//! The moment-curvature path a probe records at a bending point against the section law's
//! own: the law driven through the probe's frames from the unslipped state, and the work
//! balance of the section over an interval of frames.

use std::collections::HashMap;

use strand_core::{PlanarResponse, SectionLaw, Station};
use strand_scene::{RunOptions, Scene, run_scene};

use crate::temp_path::TempPath;

/// Gauss-Legendre 3-point nodes and weights on [0, 1].
const GAUSS3: [(f64, f64); 3] = [
    (0.112_701_665_379_258_3, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.887_298_334_620_741_7, 5.0 / 18.0),
];

/// The bending points of the first `elements` elements of length `h` (m) of three Gauss
/// points each: material coordinate and quadrature weight (m).
pub fn gauss_points(elements: usize, h: f64) -> Vec<(f64, f64)> {
    (0..elements)
        .flat_map(|e| GAUSS3.map(|(x, w)| ((e as f64 + x) * h, w * h)))
        .collect()
}

/// Runs `scene` into a fresh folder `<temp>/<name>-<process id>` and checks that its first
/// model did not fail and that no step was cut: a step cut in halves commits a state between
/// two frames, and with slip limits that change with the tension the law's path would then
/// differ from the frames'. Returns the folder.
pub fn run_uncut(scene: &Scene, name: &str) -> TempPath {
    let out = TempPath::new(name);
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: false,
    };
    let s = run_scene(scene, &opts, &mut |_, _| {}).unwrap();
    assert!(!s[0].failed(), "{:?}", s[0].failure());
    assert!(
        s[0].warnings.iter().all(|w| !w.contains("cut")),
        "no step was cut (each committed step is a frame): {:?}",
        s[0].warnings
    );
    out
}

/// The law's all-stick tangent at `st` (N m^2), its largest, at strain `eps`: the slope of
/// M(kappa) lies in [K_min, K_stick] along any path.
pub fn stick_tangent(law: &SectionLaw, st: &Station, eps: f64) -> f64 {
    let mut scratch = vec![0.0; law.state_len()];
    let zero = vec![0.0; law.state_len()];
    law.planar(st, eps, 1e-9, &zero, &mut scratch)
        .moment_curvature
}

/// The law's path through a probe's frames: stored energy and accumulated slip work (J/m) at
/// each frame, from zero at the first.
pub struct LawPath {
    pub energy: Vec<f64>,
    pub work: Vec<f64>,
}

/// The law at `st` driven through the frames of `probe` (columns `t`, `curvature`, `moment`,
/// `tension`), from the unslipped state at the first frame: at every frame the probe's moment
/// must be the law's at the same strain (read back from the tension, N / EA), curvature and
/// slip state, to round-off. Needs a frame every committed step (the law's state moves at
/// every step).
pub fn drive(law: &SectionLaw, st: &Station, probe: &HashMap<String, Vec<f64>>) -> LawPath {
    let ea = law.axial_stiffness();
    let (t, kappa, moment, tension) = (
        &probe["t"],
        &probe["curvature"],
        &probe["moment"],
        &probe["tension"],
    );
    let scale = moment.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut slip = vec![0.0; law.state_len()];
    let mut trial = slip.clone();
    let mut path = LawPath {
        energy: vec![0.0],
        work: vec![0.0],
    };
    for k in 1..t.len() {
        let r: PlanarResponse = law.planar(st, tension[k] / ea, kappa[k], &slip, &mut trial);
        assert!(
            (r.moment - moment[k]).abs() <= 1e-9 * scale.max(1e-12),
            "x = {}, t = {}: the probe's moment {} vs the law's {}",
            st.x,
            t[k],
            moment[k],
            r.moment
        );
        slip.copy_from_slice(&trial);
        path.energy.push(r.energy);
        path.work.push(path.work[k - 1] + r.slip_work);
    }
    path
}

/// The section's work balance over frames `a..=b`.
#[derive(Debug)]
pub struct Balance {
    /// Trapezoidal sum of M dkappa (J/m): the loop's area on a closed loop.
    pub area: f64,
    /// Trapezoidal sum of N deps (J/m).
    pub axial: f64,
    /// Change of the law's stored energy (J/m).
    pub stored: f64,
    /// The law's slip work (J/m).
    pub slip_work: f64,
    /// The trapezoidal rule's error bound: on a step where the slope of M(kappa) stays in
    /// [K_min, K_stick], sum of (K_stick - K_min) dkappa^2 / 8.
    pub bound: f64,
}

impl Balance {
    /// M dkappa + N deps - dE - slip work: zero but for the trapezoidal rule's error.
    pub fn residual(&self) -> f64 {
        self.area + self.axial - self.stored - self.slip_work
    }

    /// Asserts `|residual| <= bound` plus round-off.
    pub fn check(&self, what: &str) {
        let roundoff =
            1e-9 * (self.area.abs() + self.axial.abs() + self.stored.abs() + self.slip_work);
        assert!(
            self.residual().abs() <= self.bound + roundoff,
            "{what}: loop area {:e} + axial work {:e} - stored {:e} vs slip work {:e} \
             (off by {:e}, bound {:e})",
            self.area,
            self.axial,
            self.stored,
            self.slip_work,
            self.residual(),
            self.bound
        );
    }
}

/// The work balance of the section at a probe over frames `a..=b`, with `path` the law's path
/// through its frames ([`drive`]); `k_stick` and `k_min` bound the slope of M(kappa) along any
/// path (the all-stick tangent and the all-slip stiffness).
pub fn balance(
    probe: &HashMap<String, Vec<f64>>,
    path: &LawPath,
    ea: f64,
    (k_min, k_stick): (f64, f64),
    a: usize,
    b: usize,
) -> Balance {
    let (kappa, moment, tension) = (&probe["curvature"], &probe["moment"], &probe["tension"]);
    let mut out = Balance {
        area: 0.0,
        axial: 0.0,
        stored: path.energy[b] - path.energy[a],
        slip_work: path.work[b] - path.work[a],
        bound: 0.0,
    };
    for k in a + 1..=b {
        let dk = kappa[k] - kappa[k - 1];
        out.area += 0.5 * (moment[k] + moment[k - 1]) * dk;
        out.axial += 0.5 * (tension[k] + tension[k - 1]) * (tension[k] - tension[k - 1]) / ea;
        out.bound += (k_stick - k_min) * dk * dk / 8.0;
    }
    out
}
