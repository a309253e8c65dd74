//! The moment-curvature path a probe records at a bending point against the section law's
//! own: the law driven through the probe's frames from the unslipped state, and the work
//! balance of the section over an interval of frames.

use std::collections::HashMap;

use strand_core::{PlanarResponse, SectionLaw, Station};

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
