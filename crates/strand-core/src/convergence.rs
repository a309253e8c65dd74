//! Convergence of a discretisation: the observed order and the Richardson limit of results on
//! meshes refined by a constant ratio, and the cost at which a refinement sequence first comes
//! within a given error.
//!
//! A result computed with mesh size h behaves as u(h) = u + C h^p + ...; on meshes h, h/r,
//! h/r^2 the changes d1 = |u(h/r) - u(h)| and d2 = |u(h/r^2) - u(h/r)| give the observed order
//! p = ln(d1/d2) / ln(r), and the finest result's error is about d2 / (r^p - 1) (Richardson).
//! One order estimate does not show that the meshes are in the asymptotic range; a fourth
//! mesh gives a second, and the order counts only when the two agree ([`Richardson`]).
//! Results may be vectors (a centreline, a tip trajectory): the changes are then the caller's
//! norm of the difference, and the limit is extrapolated component by component with one order.

/// Observed order ln(d_coarse / d_fine) / ln(ratio) of two successive changes of a result on
/// meshes refined by `ratio` (> 1); not finite when a change is zero.
pub fn observed_order(d_coarse: f64, d_fine: f64, ratio: f64) -> f64 {
    (d_coarse / d_fine).ln() / ratio.ln()
}

/// Largest difference between the two order estimates of a four-level refinement for the
/// order to count as established: a quarter of an order. Two estimates closer than this
/// show the changes falling as one power law over three refinements; a wider spread (a
/// falling or rising order) shows the meshes outside the asymptotic range.
pub const ORDER_AGREEMENT: f64 = 0.25;

/// The Richardson extrapolation of a result from four meshes refined by a constant ratio.
///
/// The three changes d1, d2, d3 between successive meshes give two order estimates,
/// p1 = ln(d1/d2)/ln r and p2 = ln(d2/d3)/ln r. The order is established when both are
/// positive and finite and differ by at most [`ORDER_AGREEMENT`]; the order used is then the
/// smaller of the two, capped at the scheme's formal order (an observed order above the
/// formal one is a cancellation of error terms, not a faster convergence to count on). Only
/// an established order extrapolates: otherwise no order is used and the finest result
/// stands, its error not estimated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Richardson {
    /// The two orders measured from the changes, coarse pair first (not finite when a
    /// change is zero).
    pub observed_orders: [f64; 2],
    /// The scheme's formal order, the cap of the order used.
    pub formal_order: f64,
    /// The order used: the smaller observed order capped at the formal one; NaN when the
    /// order is not established.
    pub order: f64,
    /// Refinement ratio between successive meshes.
    pub ratio: f64,
    /// Estimated error of the finest result (in the changes' norm): d3 / (r^p - 1); NaN
    /// when the order is not established.
    pub finest_error: f64,
}

impl Richardson {
    /// From the changes `[d1, d2, d3]` between four meshes refined by `ratio` (> 1) each,
    /// coarse first, of a scheme of formal order `formal_order`.
    pub fn from_changes(changes: [f64; 3], ratio: f64, formal_order: f64) -> Self {
        let [d1, d2, d3] = changes;
        let observed = [observed_order(d1, d2, ratio), observed_order(d2, d3, ratio)];
        let established = observed.iter().all(|p| p.is_finite() && *p > 0.0)
            && (observed[0] - observed[1]).abs() <= ORDER_AGREEMENT;
        let order = if established {
            observed[0].min(observed[1]).min(formal_order)
        } else {
            f64::NAN
        };
        Richardson {
            observed_orders: observed,
            formal_order,
            order,
            ratio,
            finest_error: d3 / (ratio.powf(order) - 1.0),
        }
    }

    /// Whether the order is established (two estimates that agree): only then is
    /// [`Richardson::finest_error`] an estimate and [`Richardson::limit`] available.
    pub fn established(&self) -> bool {
        self.order.is_finite()
    }

    /// Whether the order used is the formal one, both observed orders above it.
    pub fn capped(&self) -> bool {
        self.established() && self.observed_orders.iter().all(|p| *p > self.formal_order)
    }

    /// The extrapolated limit of each component from the `medium` and `finest` results
    /// (the two finest meshes): finest + (finest - medium) / (r^p - 1); `None` when the
    /// order is not established.
    pub fn limit(&self, medium: &[f64], finest: &[f64]) -> Option<Vec<f64>> {
        assert_eq!(medium.len(), finest.len(), "results of different sizes");
        if !self.established() {
            return None;
        }
        let f = 1.0 / (self.ratio.powf(self.order) - 1.0);
        Some(
            medium
                .iter()
                .zip(finest)
                .map(|(m, u)| u + (u - m) * f)
                .collect(),
        )
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

    /// A sequence u(h) = 1 + 3 h^2 (+ nothing else): both orders are 2 and the limit exact.
    #[test]
    fn richardson_recovers_a_power_law() {
        let u = |h: f64| [1.0 + 3.0 * h * h, -2.0 + 0.5 * h * h];
        let d = |x: [f64; 2], y: [f64; 2]| (x[0] - y[0]).hypot(x[1] - y[1]);
        let h = [0.8, 0.4, 0.2, 0.1].map(u);
        let changes = [d(h[0], h[1]), d(h[1], h[2]), d(h[2], h[3])];
        let r = Richardson::from_changes(changes, 2.0, 2.0);
        assert!(r.observed_orders.iter().all(|p| (p - 2.0).abs() < 1e-12));
        assert!(r.established() && (r.order - 2.0).abs() < 1e-12);
        let l = r.limit(&h[2], &h[3]).unwrap();
        assert!((l[0] - 1.0).abs() < 1e-12 && (l[1] + 2.0).abs() < 1e-12);
        assert!((r.finest_error - d(h[3], [1.0, -2.0])).abs() < 1e-12);
        // Ratio 3: the same order.
        let h = [2.7, 0.9, 0.3, 0.1].map(u);
        let r3 = Richardson::from_changes([d(h[0], h[1]), d(h[1], h[2]), d(h[2], h[3])], 3.0, 4.0);
        assert!((r3.order - 2.0).abs() < 1e-12 && !r3.capped());
    }

    /// An observed order above the formal one is capped: the estimated error is then larger
    /// than the observed order would make it (a fourth-order cancellation in a second-order
    /// scheme is not counted on).
    #[test]
    fn richardson_caps_the_order_at_the_formal_one() {
        let r = Richardson::from_changes([16.0, 1.0, 1.0 / 16.0], 2.0, 2.0);
        assert!((r.observed_orders[0] - 4.0).abs() < 1e-12);
        assert_eq!(r.order, 2.0);
        assert!(r.capped());
        assert!((r.finest_error - 1.0 / 48.0).abs() < 1e-15);
    }

    /// Orders that do not agree (falling 1.57 -> 1.33 is within a quarter; 2 -> 1 is not),
    /// changes that grow, or a zero change: no order is established, nothing extrapolates.
    #[test]
    fn richardson_needs_two_orders_that_agree() {
        let falling = [2f64.powf(1.57) * 2f64.powf(1.33), 2f64.powf(1.33), 1.0];
        let r = Richardson::from_changes(falling, 2.0, 2.0);
        assert!(r.established());
        assert!((r.order - 1.33).abs() < 1e-12, "the smaller order: {r:?}");
        for changes in [
            [4.0, 1.0, 0.5],
            [1.0, 1.5, 2.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.5, 0.0],
        ] {
            let r = Richardson::from_changes(changes, 2.0, 2.0);
            assert!(!r.established(), "{changes:?}: {r:?}");
            assert!(r.finest_error.is_nan());
            assert_eq!(r.limit(&[0.0], &[1.0]), None);
        }
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
