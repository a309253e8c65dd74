//! What the section law reports beyond its response: each wire's state, stick stiffness,
//! friction-limited moment and critical curvature (`wires.csv`, `strand section`), the secant
//! stiffness and the moment averaged over a pitch.

use super::direction::{BendingDirection, DIRECTION_STATE};
use super::{LawKind, SectionLaw, Station, WireReport};

impl SectionLaw {
    /// Per-wire report for a signed planar curvature (see [`Self::planar`]). At zero
    /// curvature the report is for bending with the convex side toward +y (`kappa_z < 0`).
    pub fn planar_wires(
        &self,
        st: &Station,
        eps: f64,
        kappa: f64,
        slip: &[f64],
    ) -> Vec<WireReport> {
        let dir = if kappa > 0.0 { 1.0 } else { -1.0 };
        st.wires
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let law = self.layers[w.layer];
                let (scale, _) = law.cap_scale(eps);
                let lever = w.lever[1] * dir; // strain per unit |kappa|
                let arm = lever.abs();
                // A report reads no slip work: the step's start is left out.
                let e = w.lever[1] * kappa;
                let f = self.slide(law, i, e, scale, w.gains, slip, &mut [], |_| 0.0);
                // The side of the slider the force loads (the strain's side when it is zero).
                let stretched = if f.force != 0.0 {
                    f.force > 0.0
                } else {
                    lever >= 0.0
                };
                let cap = scale * w.gains[if stretched { 0 } else { 1 }];
                let factor = if self.kind == LawKind::Paper {
                    law.paper_factor
                } else {
                    1.0
                };
                // kappa_c = cap / (k_factor arm), arm = R_w sin(theta), theta = |phi|.
                let theta = w.phase.abs();
                let gain = w.gains[if stretched { 0 } else { 1 }];
                let critical = law.critical_curvature(scale, factor, gain, theta, theta.sin());
                let state = law.reported_state(f.state, arm, critical, kappa.abs());
                WireReport {
                    wire: (i - law.first) % (law.wires / law.samples) + 1,
                    layer: law.index + 1,
                    phase: w.phase,
                    k_stick: law.k * arm * arm,
                    m_slip: cap * arm,
                    critical_curvature: critical,
                    state,
                }
            })
            .collect()
    }

    /// Per-wire report for a curvature vector `kappa = (kappa_y, kappa_z)` in the section frame
    /// (see [`Self::vector`]): each wire's phase is measured from the reference half `b` of
    /// the neutral axis of the current bending direction (the law's convention, module docs),
    /// in the sense from z toward y, wrapped to (-pi, pi]; its critical curvature is the
    /// curvature magnitude at which it slips in this bending direction, with its lever
    /// `R_w sin(theta)` and the capstan gain of its angle `theta` from `b`. With
    /// `kappa_y = 0` this is [`Self::planar_wires`] up to round-off. At zero curvature the
    /// report is for bending with the convex side toward +y.
    pub fn vector_wires(
        &self,
        st: &Station,
        eps: f64,
        kappa: [f64; 2],
        slip: &[f64],
    ) -> Vec<WireReport> {
        if self.layers.is_empty() {
            return Vec::new();
        }
        let knorm = kappa[0].hypot(kappa[1]);
        let n = st.wires.len();
        let still = self.still(eps);
        let tail = slip
            .get(n..)
            .filter(|t| t.len() + n == self.state_len())
            .map(|t| &t[..DIRECTION_STATE]);
        let dir = match tail {
            Some(t) => BendingDirection::select(kappa, still, t, None),
            None => BendingDirection::of(kappa),
        };
        let kh = if let Some(b) = tail.filter(|t| knorm <= still && t != &[0.0; 2]) {
            // The stored direction: its neutral axis's half on the side of the curvature.
            let s = if b[0] * kappa[0] + b[1] * kappa[1] > 0.0 {
                1.0
            } else {
                -1.0
            };
            [s * b[0], s * b[1]]
        } else if knorm == 0.0 {
            // At zero curvature: bending with the convex side toward +y (kappa_z < 0).
            [0.0, -1.0]
        } else {
            [kappa[0] / knorm, kappa[1] / knorm]
        };
        st.wires
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let law = self.layers[w.layer];
                let (scale, _) = law.cap_scale(eps);
                let factor = if self.kind == LawKind::Paper {
                    law.paper_factor
                } else {
                    1.0
                };
                let l = w.lever;
                let lambda = l[0] * kh[0] + l[1] * kh[1];
                let arm = lambda.abs();
                let phase = dir.wire_angle(w.phase);
                let theta = phase.abs();
                let gains = self.gains(&law, theta).0;
                let e = l[0] * kappa[0] + l[1] * kappa[1];
                let f = self.slide(law, i, e, scale, gains, slip, &mut [], |_| 0.0);
                let stretched = if f.force != 0.0 {
                    f.force > 0.0
                } else {
                    lambda >= 0.0
                };
                let gain = gains[if stretched { 0 } else { 1 }];
                let critical = law.critical_curvature(scale, factor, gain, theta, theta.sin());
                let state = law.reported_state(f.state, arm, critical, knorm);
                WireReport {
                    wire: (i - law.first) % (law.wires / law.samples) + 1,
                    layer: law.index + 1,
                    phase,
                    k_stick: law.k * arm * arm,
                    m_slip: scale * gain * arm,
                    critical_curvature: critical,
                    state,
                }
            })
            .collect()
    }

    /// Planar moment (N m) at strain `eps` and signed curvature `kappa` (1/m), bent from
    /// straight (no committed slip), averaged over `stations` evenly spaced stations of one
    /// pitch (the strand's length without a helical layer): what a bending test measures over
    /// whole pitches. With several layers the pitch is the longest of them, over which the
    /// others' wires pass through their phases more than once (their own pitches need not
    /// divide it: the mean then carries a remainder of order 1/stations).
    pub fn pitch_mean_moment(&self, eps: f64, kappa: f64, stations: usize) -> f64 {
        let pitch = self
            .strand
            .layers()
            .iter()
            .map(|l| l.pitch)
            .reduce(f64::max)
            .unwrap_or(self.strand.length());
        let slip = vec![0.0; self.state_len()];
        let mut trial = slip.clone();
        let sum: f64 = (0..stations)
            .map(|i| {
                let st = self.station(pitch * (i as f64 + 0.5) / stations as f64);
                self.planar(&st, eps, kappa, &slip, &mut trial).moment
            })
            .sum();
        sum / stations as f64
    }

    /// Secant bending stiffness |M| / |kappa| for a signed planar curvature (N m^2); at zero
    /// curvature its limit from the +y-convex side.
    pub fn planar_secant(&self, st: &Station, eps: f64, kappa: f64, slip: &[f64]) -> f64 {
        if kappa != 0.0 {
            let mut trial = vec![0.0; self.state_len()];
            return self.planar(st, eps, kappa, slip, &mut trial).moment / kappa;
        }
        self.base_bending
            + self
                .planar_wires(st, eps, kappa, slip)
                .iter()
                .filter(|w| w.critical_curvature.is_none_or(|c| c > 0.0))
                .map(|w| w.k_stick)
                .sum::<f64>()
    }
}
