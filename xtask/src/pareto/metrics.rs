//! Error metrics and the Pareto front: tip trajectories compared at the run's own output
//! times (the reference interpolated by cubic Hermite on its positions and velocities), the
//! median of repeated timings, and the non-dominated set.

use std::path::Path;

use anyhow::bail;

use crate::validate::results::Table;

/// The tip trajectory of a dynamic run (`tip.csv`).
#[derive(Debug, Clone, PartialEq)]
pub struct Tip {
    /// Time (s), increasing.
    pub t: Vec<f64>,
    /// Position x, y (m).
    pub x: Vec<f64>,
    /// Position y (m).
    pub y: Vec<f64>,
    /// Velocity x (m/s).
    pub vx: Vec<f64>,
    /// Velocity y (m/s).
    pub vy: Vec<f64>,
}

impl Tip {
    /// Reads `tip.csv` in the model folder `dir`.
    pub fn load(dir: &Path) -> anyhow::Result<Tip> {
        let t = Table::load(&dir.join("tip.csv"))?;
        let tip = Tip {
            t: t.column("t")?,
            x: t.column("x")?,
            y: t.column("y")?,
            vx: t.column("vx")?,
            vy: t.column("vy")?,
        };
        if tip.t.len() < 2 || tip.t.windows(2).any(|w| w[1] <= w[0]) {
            bail!(
                "{}: needs two or more rows with increasing t",
                dir.join("tip.csv").display()
            );
        }
        Ok(tip)
    }

    /// Speed |v| at every frame (m/s).
    pub fn speed(&self) -> Vec<f64> {
        self.vx
            .iter()
            .zip(&self.vy)
            .map(|(a, b)| a.hypot(*b))
            .collect()
    }

    /// Position at time `t` by cubic Hermite interpolation on positions and velocities
    /// (fourth-order accurate between frames); `None` outside the sampled times.
    pub fn at(&self, t: f64) -> Option<(f64, f64)> {
        let n = self.t.len();
        let tol = 1e-9 * self.t[n - 1].abs().max(1e-12);
        if t < self.t[0] - tol || t > self.t[n - 1] + tol {
            return None;
        }
        let i = self.t.partition_point(|&v| v <= t).clamp(1, n - 1) - 1;
        let h = self.t[i + 1] - self.t[i];
        let u = ((t - self.t[i]) / h).clamp(0.0, 1.0);
        let (h00, h10) = (
            2.0 * u.powi(3) - 3.0 * u * u + 1.0,
            u.powi(3) - 2.0 * u * u + u,
        );
        let (h01, h11) = (-2.0 * u.powi(3) + 3.0 * u * u, u.powi(3) - u * u);
        let f = |p: &[f64], v: &[f64]| {
            h00 * p[i] + h10 * h * v[i] + h01 * p[i + 1] + h11 * h * v[i + 1]
        };
        Some((f(&self.x, &self.vx), f(&self.y, &self.vy)))
    }

    /// Tip distance to `reference` at each of this run's output times inside the reference's
    /// time span: (t, distance in m).
    pub fn distance_to(&self, reference: &Tip) -> Vec<(f64, f64)> {
        self.t
            .iter()
            .enumerate()
            .filter_map(|(i, &t)| {
                reference
                    .at(t)
                    .map(|(x, y)| (t, (self.x[i] - x).hypot(self.y[i] - y)))
            })
            .collect()
    }
}

/// Median of `v` (mean of the middle pair for an even count); NaN for none.
pub fn median(v: &[f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

/// Indices of the non-dominated points of (time, error): no other point is at most as slow
/// and at most as wrong and strictly better in one of them. Sorted by time. Non-finite points
/// are never on the front.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    idx.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in idx {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(&[]).is_nan());
    }

    #[test]
    fn front_keeps_only_non_dominated_points() {
        let p = [
            (1.0, 1.0),
            (2.0, 0.5),
            (2.0, 0.8),
            (3.0, 0.6),
            (0.5, 2.0),
            (4.0, 0.1),
            (f64::NAN, 0.0),
        ];
        assert_eq!(pareto_front(&p), [4, 0, 1, 5]);
        assert!(pareto_front(&[]).is_empty());
    }

    /// Hermite interpolation is exact for a cubic trajectory with exact velocities.
    #[test]
    fn hermite_tip_is_exact_for_cubics() {
        let t: Vec<f64> = (0..5).map(|k| 0.1 * k as f64).collect();
        let x: Vec<f64> = t.iter().map(|t| t.powi(3) - t).collect();
        let vx: Vec<f64> = t.iter().map(|t| 3.0 * t * t - 1.0).collect();
        let y: Vec<f64> = t.iter().map(|t| -4.9 * t * t).collect();
        let vy: Vec<f64> = t.iter().map(|t| -9.8 * t).collect();
        let tip = Tip { t, x, y, vx, vy };
        let (px, py) = tip.at(0.237).unwrap();
        assert!((px - (0.237f64.powi(3) - 0.237)).abs() < 1e-14);
        assert!((py + 4.9 * 0.237 * 0.237).abs() < 1e-14);
        assert!(tip.at(0.5).is_none());
        let shifted = Tip {
            y: tip.y.iter().map(|y| y + 1e-3).collect(),
            ..tip.clone()
        };
        let d = shifted.distance_to(&tip);
        assert_eq!(d.len(), 5);
        assert!(d.iter().all(|(_, d)| (d - 1e-3).abs() < 1e-12));
    }
}
