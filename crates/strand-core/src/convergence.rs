//! Convergence of a discretisation: the observed order and the Richardson limit of results on
//! meshes refined by a constant ratio, and the cost at which a refinement sequence first comes
//! within a given error.
//!
//! A result computed with mesh size h behaves as u(h) = u + C h^p + ...; on meshes h, h/r,
//! h/r^2 the changes d1 = |u(h/r) - u(h)| and d2 = |u(h/r^2) - u(h/r)| give the observed order
//! p = ln(d1/d2) / ln(r), and the finest result's error is about d2 / (r^p - 1) (Richardson).
//! Results may be vectors (a centreline, a tip trajectory): the changes are then the caller's
//! norm of the difference, and the limit is extrapolated component by component with one order.

/// Observed order ln(d_coarse / d_fine) / ln(ratio) of two successive changes of a result on
/// meshes refined by `ratio` (> 1); not finite when a change is zero.
pub fn observed_order(d_coarse: f64, d_fine: f64, ratio: f64) -> f64 {
    (d_coarse / d_fine).ln() / ratio.ln()
}

/// The Richardson extrapolation of a result from its two finest meshes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Richardson {
    /// The order measured from the two changes (may be outside the accepted range, or not
    /// finite when a change is zero).
    pub observed_order: f64,
    /// The order used: the observed one clamped to the accepted range.
    pub order: f64,
    /// Refinement ratio between successive meshes.
    pub ratio: f64,
    /// Estimated error of the finest result (in the changes' norm): d2 / (r^p - 1).
    pub finest_error: f64,
}

impl Richardson {
    /// From the changes `d_coarse` (coarse to medium) and `d_fine` (medium to finest) on meshes
    /// refined by `ratio`, with the order clamped to `[min_order, max_order]` (a change that
    /// does not fall keeps `min_order`: the estimate is then conservative, not asymptotic).
    pub fn new(d_coarse: f64, d_fine: f64, ratio: f64, min_order: f64, max_order: f64) -> Self {
        let observed = observed_order(d_coarse, d_fine, ratio);
        let order = if observed.is_nan() {
            min_order
        } else {
            observed.clamp(min_order, max_order)
        };
        Richardson {
            observed_order: observed,
            order,
            ratio,
            finest_error: d_fine / (ratio.powf(order) - 1.0),
        }
    }

    /// Whether the observed order lies in the accepted range (the meshes are in the
    /// asymptotic range and the extrapolation is a small, trustworthy correction).
    pub fn asymptotic(&self) -> bool {
        (self.observed_order - self.order).abs() <= 1e-12 * self.order.abs().max(1.0)
    }

    /// The extrapolated limit of each component from the `medium` and `finest` results:
    /// finest + (finest - medium) / (r^p - 1).
    pub fn limit(&self, medium: &[f64], finest: &[f64]) -> Vec<f64> {
        assert_eq!(medium.len(), finest.len(), "results of different sizes");
        let f = 1.0 / (self.ratio.powf(self.order) - 1.0);
        medium
            .iter()
            .zip(finest)
            .map(|(m, u)| u + (u - m) * f)
            .collect()
    }
}

/// Where a refinement sequence first comes within a target error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reach {
    /// The first (cheapest) run is already within: the cost is at most its cost.
    AtFirst {
        /// The first run's cost.
        cost: f64,
    },
    /// Run `index` is the first within and run `index - 1` is not: the cost at which the
    /// error equals the target, interpolated as a power law (straight in log cost against
    /// log error) between the two.
    Between {
        /// The first run within.
        index: usize,
        /// Interpolated cost.
        cost: f64,
    },
    /// No run comes within.
    Never {
        /// The smallest error of the sequence.
        best_error: f64,
    },
}

impl Reach {
    /// The cost, when the target is reached.
    pub fn cost(&self) -> Option<f64> {
        match *self {
            Reach::AtFirst { cost } | Reach::Between { cost, .. } => Some(cost),
            Reach::Never { .. } => None,
        }
    }
}

/// The cost at which `runs`, (cost, error) pairs in order of refinement, first come within
/// `target`. Runs with a non-finite cost or error are skipped.
pub fn cost_to_reach(runs: &[(f64, f64)], target: f64) -> Reach {
    let ok: Vec<(f64, f64)> = runs
        .iter()
        .copied()
        .filter(|(c, e)| c.is_finite() && e.is_finite())
        .collect();
    let Some(i) = ok.iter().position(|&(_, e)| e <= target) else {
        return Reach::Never {
            best_error: ok.iter().map(|r| r.1).fold(f64::INFINITY, f64::min),
        };
    };
    if i == 0 {
        return Reach::AtFirst { cost: ok[0].0 };
    }
    let ((c0, e0), (c1, e1)) = (ok[i - 1], ok[i]);
    let cost = if c0 > 0.0 && c1 > 0.0 && e1 > 0.0 && target > 0.0 {
        let u = (target / e0).ln() / (e1 / e0).ln();
        (c0.ln() + u * (c1 / c0).ln()).exp()
    } else {
        c1
    };
    let index = runs
        .iter()
        .position(|r| *r == ok[i])
        .expect("the run comes from the list");
    Reach::Between { index, cost }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sequence u(h) = 1 + 3 h^2 (+ nothing else): the order is 2 and the limit exact.
    #[test]
    fn richardson_recovers_a_power_law() {
        let u = |h: f64| [1.0 + 3.0 * h * h, -2.0 + 0.5 * h * h];
        let (a, b, c) = (u(0.4), u(0.2), u(0.1));
        let d = |x: [f64; 2], y: [f64; 2]| (x[0] - y[0]).hypot(x[1] - y[1]);
        let r = Richardson::new(d(a, b), d(b, c), 2.0, 1.0, 4.0);
        assert!((r.observed_order - 2.0).abs() < 1e-12);
        assert!(r.asymptotic());
        let l = r.limit(&b, &c);
        assert!((l[0] - 1.0).abs() < 1e-12 && (l[1] + 2.0).abs() < 1e-12);
        assert!((r.finest_error - d(c, [1.0, -2.0])).abs() < 1e-12);
        // Ratio 3: the same order.
        let r3 = Richardson::new(d(u(0.9), u(0.3)), d(u(0.3), u(0.1)), 3.0, 1.0, 4.0);
        assert!((r3.observed_order - 2.0).abs() < 1e-12);
    }

    /// An order outside the range is clamped and flagged; a change that does not fall keeps
    /// the smallest order.
    #[test]
    fn richardson_clamps_the_order() {
        let r = Richardson::new(1.0, 0.01, 2.0, 1.0, 4.0);
        assert_eq!(r.order, 4.0);
        assert!(!r.asymptotic());
        let r = Richardson::new(1.0, 1.5, 2.0, 1.0, 4.0);
        assert_eq!(r.order, 1.0);
        assert!((r.finest_error - 1.5).abs() < 1e-15);
        assert_eq!(Richardson::new(0.0, 0.0, 2.0, 1.0, 4.0).order, 1.0);
    }

    /// Error e = cost^-2 on every run: the interpolated cost to reach a target is exact.
    #[test]
    fn cost_to_reach_interpolates_a_power_law() {
        let runs: Vec<(f64, f64)> = [1.0, 2.0, 4.0, 8.0]
            .iter()
            .map(|&c: &f64| (c, c.powi(-2)))
            .collect();
        let Reach::Between { index, cost } = cost_to_reach(&runs, 0.1) else {
            panic!("between")
        };
        assert_eq!(index, 2);
        assert!((cost - 0.1f64.powf(-0.5)).abs() < 1e-12);
        assert_eq!(cost_to_reach(&runs, 2.0), Reach::AtFirst { cost: 1.0 });
        assert_eq!(
            cost_to_reach(&runs, 1e-3),
            Reach::Never {
                best_error: 1.0 / 64.0
            }
        );
        assert_eq!(cost_to_reach(&runs, 1e-3).cost(), None);
    }

    /// Failed runs (NaN) are skipped; the index is that of the input list.
    #[test]
    fn cost_to_reach_skips_failed_runs() {
        let runs = [(1.0, 1.0), (f64::NAN, f64::NAN), (4.0, 0.25)];
        let Reach::Between { index, cost } = cost_to_reach(&runs, 0.5) else {
            panic!("between")
        };
        assert_eq!(index, 2);
        assert!((cost - 2.0).abs() < 1e-12);
        // A target met exactly at a run costs that run.
        assert_eq!(cost_to_reach(&runs, 0.25).cost(), Some(4.0));
    }
}
