//! Converged references and the distances to them. A run is sampled on the scene's common
//! grid (statics: stations along the strand; dynamics: the output times), the last of a refinement sequence are extrapolated to their limit (Richardson,
//! [`strand_core::convergence`]: two order estimates that agree, capped at the formal order),
//! and a run's error is its largest distance to a limit: in
//! statics at the run's own centreline points (the limit interpolated between its dense
//! stations), in dynamics the tip at the output times.

use std::path::Path;

use strand_core::convergence::Richardson;

use super::metrics::Tip;
use crate::validate::results::Centerline;

/// Where runs are sampled.
#[derive(Debug, Clone, PartialEq)]
pub enum Grid {
    /// Statics: material coordinates along the strand (m).
    Stations(Vec<f64>),
    /// Dynamics: output times (s); the tip at each.
    Times(Vec<f64>),
}

impl Grid {
    /// `n + 1` stations evenly over a strand of length `l` (m).
    pub fn stations(l: f64, n: usize) -> Grid {
        Grid::Stations((0..=n).map(|i| l * i as f64 / n as f64).collect())
    }

    /// The times k `interval` up to `duration` (s).
    pub fn times(duration: f64, interval: f64) -> Grid {
        let n = (duration / interval + 1e-9).floor() as usize;
        Grid::Times((0..=n).map(|k| k as f64 * interval).collect())
    }
}

/// A run's result: its positions on the grid and, in statics, its own centreline.
#[derive(Debug, Clone)]
pub struct Sampled {
    /// Positions at the grid's stations or times (m).
    pub grid: Vec<[f64; 3]>,
    /// The run's centreline (statics).
    pub centerline: Option<Centerline>,
}

impl Sampled {
    /// Reads the run in the model folder `dir` and samples it on `grid`: the centreline
    /// interpolated linearly between its points, the tip by cubic Hermite between its frames.
    pub fn load(grid: &Grid, dir: &Path) -> anyhow::Result<Sampled> {
        match grid {
            Grid::Stations(s) => {
                let c = Centerline::load(dir)?;
                Ok(Sampled {
                    grid: s.iter().map(|&s| c.position(s)).collect(),
                    centerline: Some(c),
                })
            }
            Grid::Times(t) => {
                let tip = Tip::load(dir)?;
                let grid = t
                    .iter()
                    .map(|&t| {
                        tip.at(t).map(|(x, y)| [x, y, 0.0]).ok_or_else(|| {
                            anyhow::anyhow!(
                                "{}: no tip at t = {t} s (the run stopped early)",
                                dir.display()
                            )
                        })
                    })
                    .collect::<anyhow::Result<_>>()?;
                Ok(Sampled {
                    grid,
                    centerline: None,
                })
            }
        }
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Largest distance between two samplings of the same grid (m).
pub fn max_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| dist(*p, *q))
        .fold(0.0, f64::max)
}

/// The limit of a refinement sequence.
#[derive(Debug, Clone)]
pub struct Converged {
    /// The limit on the grid (m): extrapolated when the order is established, else the
    /// finest run.
    pub grid: Vec<[f64; 3]>,
    /// The extrapolation: the two observed orders and the order used.
    pub richardson: Richardson,
    /// The finest run's error (m): Richardson's estimate when the order is established,
    /// else its last change (an estimate only if the sequence converges at order 1 or more).
    pub finest_error: f64,
    /// Largest changes between successive runs, coarse first (m).
    pub changes: [f64; 3],
    /// The four runs it comes from, coarse to finest.
    pub runs: [String; 4],
}

impl Converged {
    /// The limit of four runs refined by `ratio` each, coarse to finest, of a scheme of
    /// formal order `formal_order`.
    pub fn new(runs: [(&str, &Sampled); 4], ratio: f64, formal_order: f64) -> Converged {
        let [a, b, c, d] = runs.map(|r| r.1);
        let changes = [
            max_distance(&a.grid, &b.grid),
            max_distance(&b.grid, &c.grid),
            max_distance(&c.grid, &d.grid),
        ];
        let richardson = Richardson::from_changes(changes, ratio, formal_order);
        let flat = |s: &Sampled| s.grid.iter().flatten().copied().collect::<Vec<f64>>();
        let (grid, finest_error) = match richardson.limit(&flat(c), &flat(d)) {
            Some(limit) => (
                limit.chunks(3).map(|p| [p[0], p[1], p[2]]).collect(),
                richardson.finest_error,
            ),
            // Orders that do not agree are not a power law: the finest run stands.
            None => (d.grid.clone(), changes[2]),
        };
        Converged {
            grid,
            richardson,
            finest_error,
            changes,
            runs: runs.map(|r| r.0.to_string()),
        }
    }

    /// Largest distance of `run` to the limit (m): in statics at the run's own centreline
    /// points, the limit interpolated linearly along `grid`'s stations; in dynamics at the
    /// output times.
    pub fn distance(&self, grid: &Grid, run: &Sampled) -> f64 {
        match (grid, &run.centerline) {
            (Grid::Stations(s), Some(c)) => {
                let limit = Centerline {
                    s: s.clone(),
                    x: self.grid.iter().map(|p| p[0]).collect(),
                    y: self.grid.iter().map(|p| p[1]).collect(),
                    z: self.grid.iter().map(|p| p[2]).collect(),
                    tension: vec![0.0; s.len()],
                };
                (0..c.s.len())
                    .map(|i| dist(c.point(i), limit.position(c.s[i])))
                    .fold(0.0, f64::max)
            }
            _ => max_distance(&run.grid, &self.grid),
        }
    }

    /// Whether the limit is extrapolated (the order is established); otherwise it is the
    /// finest run.
    pub fn extrapolated(&self) -> bool {
        self.richardson.established()
    }

    /// One sentence: where the limit comes from and how good the finest run is.
    pub fn describe(&self) -> String {
        let r = &self.richardson;
        let [p1, p2] = r.observed_orders;
        let [d1, d2, d3] = self.changes;
        let runs = self.runs.join(", ");
        if !self.extrapolated() {
            return format!(
                "the finest of {runs} (largest changes {d1:.2e}, {d2:.2e}, {d3:.2e} m, observed \
                 orders {p1:.2}, {p2:.2}: they do not agree, not extrapolated); its error taken \
                 as the last change, {:.1e} m",
                self.finest_error
            );
        }
        format!(
            "Richardson extrapolation of {runs} (largest changes {d1:.2e}, {d2:.2e}, {d3:.2e} m, \
             observed orders {p1:.2}, {p2:.2}, used {:.2}{}); the finest run's estimated error \
             {:.1e} m",
            r.order,
            if r.capped() { ", the formal order" } else { "" },
            self.finest_error
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sampled(grid: &Grid, f: impl Fn(f64) -> [f64; 3]) -> Sampled {
        let Grid::Stations(s) = grid else {
            panic!("stations")
        };
        let pts: Vec<[f64; 3]> = s.iter().map(|&s| f(s)).collect();
        Sampled {
            grid: pts.clone(),
            centerline: Some(Centerline {
                s: s.clone(),
                x: pts.iter().map(|p| p[0]).collect(),
                y: pts.iter().map(|p| p[1]).collect(),
                z: pts.iter().map(|p| p[2]).collect(),
                tension: vec![0.0; s.len()],
            }),
        }
    }

    /// Runs whose shape error falls as h^2 extrapolate to the exact shape, and each run's
    /// distance to the limit is its own error.
    #[test]
    fn limit_of_a_second_order_sequence() {
        let grid = Grid::stations(1.0, 40);
        let exact = |s: f64| [s, -0.1 * s * s, 0.0];
        let run = |h: f64| sampled(&grid, move |s| [s, -0.1 * s * s + h * h * s, 0.0]);
        let (z, a, b, c) = (run(0.4), run(0.2), run(0.1), run(0.05));
        let conv = Converged::new([("z", &z), ("a", &a), ("b", &b), ("c", &c)], 2.0, 2.0);
        assert!((conv.richardson.order - 2.0).abs() < 1e-9);
        let e = sampled(&grid, exact);
        assert!(max_distance(&conv.grid, &e.grid) < 1e-12);
        assert!((conv.distance(&grid, &a) - 0.04).abs() < 1e-12);
        assert!((conv.finest_error - 0.05f64.powi(2)).abs() < 1e-12);
        assert!(conv.describe().contains("observed orders 2.00, 2.00"));
    }

    /// Changes that grow, or fall at orders that do not agree, are not extrapolated: the
    /// finest run stands, its error the last change.
    #[test]
    fn no_extrapolation_without_an_established_order() {
        let grid = Grid::stations(1.0, 10);
        let run = |e: f64| sampled(&grid, move |s| [s, e * s, 0.0]);
        // Growing changes, then changes falling at orders 3 and 1.
        for es in [[0.0, 1e-3, 3e-3, 7e-3], [0.0, 8e-3, 9e-3, 9.5e-3]] {
            let [z, a, b, c] = es.map(run);
            let conv = Converged::new([("z", &z), ("a", &a), ("b", &b), ("c", &c)], 2.0, 2.0);
            assert!(!conv.extrapolated());
            assert_eq!(conv.grid, c.grid);
            assert!((conv.finest_error - (es[3] - es[2])).abs() < 1e-15);
            assert!(conv.describe().contains("not extrapolated"));
        }
    }

    #[test]
    fn grids() {
        let Grid::Times(t) = Grid::times(0.5, 0.1) else {
            panic!("times")
        };
        assert_eq!(t.len(), 6);
        assert!((t[5] - 0.5).abs() < 1e-12);
        assert_eq!(Grid::stations(2.0, 2), Grid::Stations(vec![0.0, 1.0, 2.0]));
    }
}
