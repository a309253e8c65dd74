//! One layer's constants as the section law uses them.

use super::{SlipLimit, WireState};

/// A helical layer's constants as the section law uses them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct LayerLaw {
    /// The layer's index in the strand (0-based, from the core outward).
    pub index: usize,
    /// Index of the layer's first wire among every layer's wires (the station's and the slip
    /// state's order).
    pub first: usize,
    /// Sliders of the layer per station: its wire count times [`Self::samples`].
    pub wires: usize,
    /// Phase samples per wire: 1 for the resolved law, `section.pitch_samples` for the
    /// pitch-averaged law (each sample's spring and friction limit carry 1 / samples of the
    /// wire's).
    pub samples: usize,
    pub radius: f64,
    /// The slider's spring: eta E_w A_w times the stick factor of `section.stick_stiffness`
    /// (N).
    pub k: f64,
    /// 1 / k (1/N).
    pub inv_k: f64,
    /// Projection times A_w E_w cos^2(alpha) (N): friction limit per unit strand strain and
    /// unit gain; the projection is cos(alpha) or the paper's eta ([`SlipLimit::projection`]).
    pub cap_per_strain: f64,
    /// mu sin(alpha).
    pub capstan: f64,
    /// Whether the friction limit has the accumulated pressure of layers outside (module
    /// `pressure`); else the capstan gain of `capstan`.
    pub accumulated: bool,
    /// d gain / d theta_n on the neutral axis (1/rad): `capstan`, or the accumulated
    /// pressure's [`super::PressureSystem::neutral_slope`].
    pub neutral_slope: f64,
    /// Where the capstan angle starts (`section.slip_limit`).
    pub slip_limit: SlipLimit,
    /// Ratio of the slip force to the stick force at the `paper` law's switch, eq. (23):
    /// cos^2(alpha) with the paper's slip limit, whose eq. (22b) projects the slip stress by
    /// eta; 1 with the `papailiou` limit, whose cos(alpha) makes eq. (23) the point where
    /// eqs. (22a) and (22b) meet.
    pub paper_factor: f64,
    /// A lower bound on the curvature at which a wire of a section without residual slip
    /// first slips, in any bending direction, per unit friction-limit scale (1/(m N)): the
    /// hysteretic law turns the friction limits only with a bending larger than this
    /// (module docs, "Bending direction of the friction limits").
    pub still_per_scale: f64,
}

impl LayerLaw {
    /// The curvature magnitude (1/m) below which the hysteretic law keeps the stored bending
    /// direction, at friction-limit scale `scale` (N): no wire of a section without residual
    /// slip slips below it, in any direction.
    #[inline(always)]
    pub fn still_curvature(&self, scale: f64) -> f64 {
        scale * self.still_per_scale
    }

    /// The critical curvature (1/m) a wire report gives for a wire at angle `theta` (rad,
    /// `sin_t` its sine) from the reference half of the neutral axis, with friction limit
    /// `scale gain` on the loaded side of its slider: `scale gain / (k factor R_w sin(theta))`.
    /// The ratio gain/sin(theta) has the limit `neutral_slope` on the neutral axis (theta -> 0);
    /// as theta -> pi it has the same limit with Papailiou's slip limit and grows without
    /// bound with the paper's (none).
    pub fn critical_curvature(
        &self,
        scale: f64,
        factor: f64,
        gain: f64,
        theta: f64,
        sin_t: f64,
    ) -> Option<f64> {
        let ratio = if sin_t > 1e-12 {
            Some(gain / sin_t)
        } else if self.slip_limit.angle(theta).0 < 0.5 * std::f64::consts::PI {
            Some(self.neutral_slope)
        } else {
            None
        };
        ratio.map(|r| scale * r / (self.k * factor * self.radius))
    }

    /// The state a wire report gives: the slider's, except for a wire without lever (`arm`,
    /// m), which carries no force: its state follows `critical` against the curvature
    /// magnitude `kappa` (1/m).
    pub fn reported_state(
        &self,
        slider: WireState,
        arm: f64,
        critical: Option<f64>,
        kappa: f64,
    ) -> WireState {
        if arm > 1e-12 * self.radius {
            slider
        } else if critical.is_some_and(|c| kappa > c) {
            WireState::Slip
        } else {
            WireState::Stick
        }
    }

    /// Capstan gains (stretched, shortened) at the angle `theta` in `[0, pi]` from the
    /// reference half of the neutral axis, and d theta_n / d theta of the slip limit's angle.
    /// Own-layer only: the accumulated pressure's gains come from
    /// [`super::PressureSystem::gains`].
    #[inline(always)]
    pub fn gains(&self, theta: f64) -> ([f64; 2], f64) {
        let (t, dt) = self.slip_limit.angle(theta);
        (self.capstan_gains(t), dt)
    }

    /// Capstan gains (stretched, shortened) at the capstan angle `t` (rad): exp(mu sin(alpha)
    /// t) - 1 and 1 - exp(-mu sin(alpha) t).
    #[inline(always)]
    pub fn capstan_gains(&self, t: f64) -> [f64; 2] {
        [(self.capstan * t).exp_m1(), -(-self.capstan * t).exp_m1()]
    }

    /// Friction limits (stretched, shortened) per unit gain: the projection times A_w
    /// sigma_a (N), with sigma_a = E_w cos^2(alpha) eps for eps > 0 and 0 otherwise (SPEC 2),
    /// and d/deps.
    #[inline(always)]
    pub fn cap_scale(&self, eps: f64) -> (f64, f64) {
        if eps > 0.0 {
            (self.cap_per_strain * eps, self.cap_per_strain)
        } else {
            (0.0, 0.0)
        }
    }
}

/// [`LayerLaw::still_per_scale`]. A wire at angle `theta` from the neutral axis slips when `k
/// R_w |kappa| sin(theta)` exceeds its friction limit `scale gain`, so no wire without residual
/// slip slips below `scale min(gain / sin(theta)) / (k R_w)`. The smaller gain, the shortened
/// side's `1 - exp(-c theta_n)` (`c = mu sin(alpha)`), over `sin(theta) <= theta_n` is at least
/// `(1 - exp(-c theta_n)) / theta_n`, which falls with `theta_n`: at least its value at the
/// largest capstan angle `theta_max`, pi/2 from the nearest crossing (Papailiou), pi from the
/// reference half (the paper's limit). The accumulated pressure of layers outside only adds
/// friction on either side (module `pressure`: the outer tensions stay positive over the
/// capstan angles), so its gains are at least the capstan gains and the bound holds for them.
pub(super) fn still_per_scale(capstan: f64, limit: SlipLimit, k: f64, radius: f64) -> f64 {
    let theta_max = match limit {
        SlipLimit::Papailiou => 0.5 * std::f64::consts::PI,
        SlipLimit::Paper => std::f64::consts::PI,
    };
    -(-capstan * theta_max).exp_m1() / theta_max / (k * radius)
}
