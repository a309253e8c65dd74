//! K_min under tension (`section.base_tension`): the helical layers' frictionless bending
//! stiffness following the axial strain at the bending point.
//!
//! The thin-rod energy of a helical wire laid on the stretched, bent layer beneath, free to
//! migrate around it and to spin ([`crate::stretched_bending`]), gives the layer's stiffness
//! `K_j(eps)` per unit deformed curvature; at zero strain it is Costello's. The equivalent
//! beam's curvature is per unit rest length (the rotation per unit reference length), with the
//! energy per unit rest length, so the law's stiffness is `K_j(eps) / (1 + eps)`: the moment
//! the thin-rod energy gives for the beam's curvature. With [`BaseTension::ThinRod`] each
//! layer's share of K_min (in the form `section.base_stiffness`) is scaled by
//!
//! ```text
//! s_j(eps) = K_j(eps) / ((1 + eps) K_j(0))
//! ```
//!
//! so that with Costello's form (the default) the layer carries the thin-rod value itself.
//! The core's `E_c I_c` is per unit rest curvature already and does not change.
//!
//! # Where it applies
//!
//! The fine model's frictionless bending test, set up as the thin-rod cell, agrees with the
//! thin-rod value on the one-layer `validation/vs-fine-30deg.json` strand up to 2 N (strain
//! 3.7e-3, where the layer keeps 0.927 of its tension-free stiffness) and parts from it at 3 N
//! (0.885), where the fine strand's stiffness also starts to depend on its length: a wire free to
//! migrate has slowly varying modes along the strand, and the value is no longer a section
//! property (Findings page of the manual). The thin-rod value itself falls without bound as the
//! strain grows, faster the lower the lay angle (six 1.5 mm wires on a 2.2 mm core: `s_j` is
//! -6.1 at 2 deg by a strain of 1e-3, -12 at 5 deg by 1e-2), and a negative K_min would make
//! the beam unstable. The law therefore follows `s_j` only while it
//! is at least [`RATIO_FLOOR`], and holds the value there beyond: the strain range the fine
//! model supports, not the thin-rod model's asymptote. Not in the model: contact between the
//! wires of a layer, which blocks their migration in a closed layer at finite curvature.
//!
//! # Table
//!
//! `s_j` is tabulated once per layer when the law is built ([`SofteningTable`]), on [`NODES`]
//! strains evenly spaced from 0 to the strain where it reaches [`RATIO_FLOOR`] (found by
//! bisection; [`STRAIN_MAX`] if it stays above), as a cubic Hermite interpolant whose node
//! slopes are fourth-order differences of the node values: the law reads a value and its
//! derivative `ds/deps` (the interpolant's own, so the tangent is exact for the forces), no
//! energy minimisation per point. Outside the table the ratio holds its end value with slope 0:
//! at `eps <= 0` the tension-free K_min (a wire under compression is not this model, and the
//! friction limits vanish there too), beyond the table's end the floor.

use crate::geometry::HelixLayer;
use crate::stretched_bending::layer_stiffness;

/// Largest strain a table covers (-): the issue's 10 N on the soft
/// `validation/vs-fine-30deg.json` strand (1.9e-2).
pub const STRAIN_MAX: f64 = 2e-2;

/// The smallest ratio `s_j` the law follows (-), module docs: the last ratio at which the fine
/// cell is checked to agree with the thin-rod value (0.927 at 2 N on `vs-fine-30deg`; it parts
/// at 0.885, 3 N), rounded down.
pub const RATIO_FLOOR: f64 = 0.92;

/// Strains tabulated (intervals + 1). The cubic Hermite interpolant errs by `h^4 / 384
/// max|s''''|`; measured against the thin-rod value evaluated directly, at the midpoints of
/// the intervals, it is at the direct value's own noise (a few 1e-9, its minimisation over
/// migration and spin by Newton on difference gradients) from 11 nodes on, 1e-7 at 6
/// (`tests/base_tension.rs`).
pub const NODES: usize = 21;

/// How K_min depends on the axial strain (`section.base_tension`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BaseTension {
    /// K_min does not depend on the strain (the paper's; the default).
    #[default]
    Fixed,
    /// Each layer's share of K_min follows the strain through the thin-rod energy of the
    /// stretched helix (module docs).
    ThinRod,
}

impl BaseTension {
    /// Every form, in the order of the documentation.
    pub const ALL: [BaseTension; 2] = [BaseTension::Fixed, BaseTension::ThinRod];

    /// Name as used in scene files (`section.base_tension`).
    pub fn name(self) -> &'static str {
        match self {
            BaseTension::Fixed => "fixed",
            BaseTension::ThinRod => "thin_rod",
        }
    }

    /// The form named `name` (as in scene files), if any.
    pub fn from_name(name: &str) -> Option<BaseTension> {
        Self::ALL.into_iter().find(|b| b.name() == name)
    }
}

impl std::fmt::Display for BaseTension {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A layer's softening ratio `s(eps)` (module docs) tabulated in the strain.
#[derive(Debug, Clone, PartialEq)]
pub struct SofteningTable {
    /// Strain step between nodes (-).
    step: f64,
    /// `s` at the nodes (-).
    values: Vec<f64>,
    /// `ds/deps` at the nodes (-).
    slopes: Vec<f64>,
}

impl SofteningTable {
    /// The table of `layer` on [`NODES`] strains in `[0, STRAIN_MAX]`.
    pub fn new(layer: &HelixLayer) -> SofteningTable {
        Self::with_nodes(layer, NODES)
    }

    /// The table of `layer` on `nodes` (at least 5) strains from 0 to [`Self::end_strain`].
    pub fn with_nodes(layer: &HelixLayer, nodes: usize) -> SofteningTable {
        assert!(nodes >= 5, "a table needs at least 5 nodes");
        let k0 = layer_stiffness(layer, 0.0);
        let ratio = |eps: f64| layer_stiffness(layer, eps) / ((1.0 + eps) * k0);
        let end = if ratio(STRAIN_MAX) >= RATIO_FLOOR {
            STRAIN_MAX
        } else {
            // Bisection for the first strain where the ratio reaches the floor, to 1e-6 of
            // the strain (the ratio falls monotonically in the strain on every layer tried).
            let (mut lo, mut hi) = (0.0, STRAIN_MAX);
            while hi - lo > 1e-6 * hi {
                let mid = 0.5 * (lo + hi);
                if ratio(mid) >= RATIO_FLOOR {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        let step = end / (nodes - 1) as f64;
        let values: Vec<f64> = (0..nodes)
            .map(|i| if i == 0 { 1.0 } else { ratio(i as f64 * step) })
            .collect();
        let v = &values;
        let n = nodes - 1;
        let slopes = (0..nodes)
            .map(|i| {
                // Fourth-order differences: central inside, one-sided at the two ends.
                let d = match i {
                    0 => -25.0 * v[0] + 48.0 * v[1] - 36.0 * v[2] + 16.0 * v[3] - 3.0 * v[4],
                    1 => -3.0 * v[0] - 10.0 * v[1] + 18.0 * v[2] - 6.0 * v[3] + v[4],
                    _ if i == n - 1 => {
                        3.0 * v[n] + 10.0 * v[n - 1] - 18.0 * v[n - 2] + 6.0 * v[n - 3] - v[n - 4]
                    }
                    _ if i == n => {
                        25.0 * v[n] - 48.0 * v[n - 1] + 36.0 * v[n - 2] - 16.0 * v[n - 3]
                            + 3.0 * v[n - 4]
                    }
                    _ => v[i - 2] - 8.0 * v[i - 1] + 8.0 * v[i + 1] - v[i + 2],
                };
                d / (12.0 * step)
            })
            .collect();
        SofteningTable {
            step,
            values,
            slopes,
        }
    }

    /// The largest strain the table follows the thin-rod ratio to (-): [`STRAIN_MAX`], or
    /// the strain where the ratio reaches [`RATIO_FLOOR`].
    pub fn end_strain(&self) -> f64 {
        self.step * (self.values.len() - 1) as f64
    }

    /// `s(eps)` and `ds/deps` (-): the cubic Hermite interpolant and its derivative inside
    /// the table, the end values (slope 0) outside.
    #[inline]
    pub fn ratio(&self, eps: f64) -> (f64, f64) {
        let n = self.values.len() - 1;
        if eps <= 0.0 {
            return (self.values[0], 0.0);
        }
        let x = eps / self.step;
        if x >= n as f64 {
            return (self.values[n], 0.0);
        }
        let i = (x as usize).min(n - 1);
        let t = x - i as f64;
        let (p0, p1) = (self.values[i], self.values[i + 1]);
        let (m0, m1) = (self.slopes[i] * self.step, self.slopes[i + 1] * self.step);
        let (t2, t3) = (t * t, t * t * t);
        let value = (2.0 * t3 - 3.0 * t2 + 1.0) * p0
            + (t3 - 2.0 * t2 + t) * m0
            + (-2.0 * t3 + 3.0 * t2) * p1
            + (t3 - t2) * m1;
        let slope = (6.0 * t2 - 6.0 * t) * p0
            + (3.0 * t2 - 4.0 * t + 1.0) * m0
            + (-6.0 * t2 + 6.0 * t) * p1
            + (3.0 * t2 - 2.0 * t) * m1;
        (value, slope / self.step)
    }
}
