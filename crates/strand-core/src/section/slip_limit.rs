//! The friction limit of a slipping helical wire: how far the capstan law lets its axial force
//! grow from the neutral axis (`section.slip_limit`).
//!
//! A wire of tension `T_w` presses on the core with the line load `T_w sin^2(alpha) / R_w`
//! (the helix curvature times the tension), and along a wire length `ds = R_w d theta /
//! sin(alpha)` friction changes its tension by at most `mu T_w sin(alpha) d theta` (eq. (13)):
//! the capstan law, `T_w (exp(mu theta sin(alpha)) - 1)` after an angle `theta` of slip.
//!
//! Where does the slip start? The bending strain of a stuck wire, `kappa R_w sin(phi)`, is
//! zero at both neutral-axis crossings of every half pitch (`phi = 0` and `phi = pi`) and
//! steepest there, so a wire slips first at both crossings. Along the wire its axial force
//! increment `F` obeys `F = k (e + u')` (`u` the slip, `e` the imposed strain) and `|F'| <=`
//! the friction line load; mirrored about a crossing, where `e` is odd, these equations map
//! onto themselves with `F -> -F`, so the response to a monotone bending is odd about every
//! crossing: `F = 0` there, and friction builds it up from the nearest one. The
//! friction-limited force at phase `phi` is the capstan gain of `theta_n = min(|phi|, pi -
//! |phi|)` in `[0, pi/2]`, the same at both ends of a half pitch, as in Papailiou's model
//! (1997). The paper's eq. (20) measures the angle from one half of the neutral axis only,
//! `theta = |phi|` in `[0, pi]`: past the extreme fibre it lets the limit keep growing to
//! `exp(mu pi sin(alpha)) - 1` while the stick force falls to zero at the far crossing, with
//! a slope `k kappa R_w` that friction cannot supply once the near crossing slips; so the
//! slipped wire carries more than friction allows (Table 1, 40 N, deep slip: the moment 20 %
//! above the fine model's, `cargo xtask bonded --variant curve`).
//!
//! The strand-axial component of the tension increment is `cos(alpha)` times it, the
//! projection eq. (22a) applies to the stick stress of eq. (19) (`eta / cos^2(alpha)`); eq.
//! (22b) applies `eta` itself to the slip stress of eq. (20), `cos^2(alpha)` less. With
//! `cos(alpha)` the paper's own eq. (23) is where the stick moment (22a) meets the slip
//! moment: the moment no longer drops by `cos^2(alpha)` at the switch.

use std::f64::consts::FRAC_PI_2;

/// Which friction limit the slipping wires have (`section.slip_limit`; module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SlipLimit {
    /// The capstan gain from the nearest neutral-axis crossing, `theta_n = min(|phi|, pi -
    /// |phi|)`, on the axial projection `cos(alpha)` of the tension increment:
    /// `cos(alpha) A_w sigma_a (exp(mu theta_n sin(alpha)) - 1)`. The default.
    #[default]
    Papailiou,
    /// Eqs. (20), (22b) as printed: `theta = |phi|` from the reference half of the neutral axis
    /// and the projection `eta = cos^3(alpha)`: `eta A_w sigma_a (exp(mu theta sin(alpha)) - 1)`.
    Paper,
}

impl SlipLimit {
    /// Every form, in the order of the documentation.
    pub const ALL: [SlipLimit; 2] = [SlipLimit::Papailiou, SlipLimit::Paper];

    /// Name as used in scene files (`section.slip_limit`).
    pub fn name(self) -> &'static str {
        match self {
            SlipLimit::Papailiou => "papailiou",
            SlipLimit::Paper => "paper",
        }
    }

    /// The form named `name` (as in scene files), if any.
    pub fn from_name(name: &str) -> Option<SlipLimit> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The capstan angle of a wire at angle `theta` in `[0, pi]` from the reference half of
    /// the neutral axis (rad), and its derivative with respect to `theta` (-).
    #[inline(always)]
    pub fn angle(self, theta: f64) -> (f64, f64) {
        match self {
            SlipLimit::Paper => (theta, 1.0),
            SlipLimit::Papailiou if theta > FRAC_PI_2 => (std::f64::consts::PI - theta, -1.0),
            SlipLimit::Papailiou => (theta, 1.0),
        }
    }

    /// The factor that projects the wire's tension increment on the strand axis (-):
    /// `cos(alpha)`, or the paper's `eta = cos^3(alpha)`.
    pub fn projection(self, lay_angle: f64) -> f64 {
        match self {
            SlipLimit::Papailiou => lay_angle.cos(),
            SlipLimit::Paper => lay_angle.cos().powi(3),
        }
    }
}

impl std::fmt::Display for SlipLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
