//! The measured moment-curvature curve (`validation/conductor/`, its README for provenance):
//! a CSV with the header `curvature [1/m],bending_moment [N.m]` and one point per line.

use anyhow::{Context, bail};

/// The header the file must have.
pub const HEADER: &str = "curvature [1/m],bending_moment [N.m]";

/// Points the Cardinal 40 kN file holds (its README).
pub const CARDINAL_POINTS: usize = 18;

/// A measured curve on first loading: curvature (1/m) and moment (N m), both rising.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Curvature kappa (1/m).
    pub curvature: Vec<f64>,
    /// Bending moment M (N m).
    pub moment: Vec<f64>,
}

impl Curve {
    /// Parses the file's text; fails on another header, a malformed line, a non-positive or
    /// non-finite value, or a curvature or moment that does not rise.
    pub fn parse(text: &str) -> anyhow::Result<Curve> {
        let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
        let header = lines.next().context("empty file")?;
        if header != HEADER {
            bail!("header `{header}`, expected `{HEADER}`");
        }
        let (mut curvature, mut moment) = (Vec::new(), Vec::new());
        for (i, line) in lines.enumerate() {
            let row = i + 2;
            let cols: Vec<&str> = line.split(',').collect();
            if cols.len() != 2 {
                bail!("line {row}: {} columns, expected 2", cols.len());
            }
            let v = |s: &str| -> anyhow::Result<f64> {
                let x: f64 = s
                    .trim()
                    .parse()
                    .with_context(|| format!("line {row}: `{s}` is not a number"))?;
                if !(x.is_finite() && x > 0.0) {
                    bail!("line {row}: {x} is not positive and finite");
                }
                Ok(x)
            };
            let (k, m) = (v(cols[0])?, v(cols[1])?);
            if curvature.last().is_some_and(|&p| k <= p) || moment.last().is_some_and(|&p| m <= p) {
                bail!(
                    "line {row}: the curve must rise in curvature and moment (monotonic loading)"
                );
            }
            curvature.push(k);
            moment.push(m);
        }
        Ok(Curve { curvature, moment })
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.curvature.len()
    }

    /// The largest measured moment (N m), the scale of the errors.
    pub fn largest_moment(&self) -> f64 {
        self.moment.iter().copied().fold(0.0, f64::max)
    }

    /// The initial secant stiffness M_1 / kappa_1 of the first point (N m^2).
    pub fn initial_secant(&self) -> f64 {
        self.moment[0] / self.curvature[0]
    }

    /// The least-squares slope through the origin of the first `n` points, sum kappa M / sum
    /// kappa^2 (N m^2): an initial stiffness less sensitive to one point's reading.
    pub fn origin_slope(&self, n: usize) -> f64 {
        let n = n.min(self.len());
        let km: f64 = (0..n).map(|i| self.curvature[i] * self.moment[i]).sum();
        let kk: f64 = (0..n).map(|i| self.curvature[i].powi(2)).sum();
        km / kk
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stored Cardinal file parses with the 18 points its README states, over the range
    /// it states.
    #[test]
    fn cardinal_file_has_its_18_points() {
        let path = crate::validate::repo_root()
            .join("validation/conductor/FLEXION_CARDINAL_H40kN_mu0.7_FOTI.csv");
        let c = Curve::parse(&std::fs::read_to_string(path).unwrap()).unwrap();
        assert_eq!(c.len(), CARDINAL_POINTS);
        assert!((c.curvature[0] - 0.0034717963716).abs() < 1e-15);
        assert!((c.largest_moment() - 84.8899497156).abs() < 1e-12);
        // Hand-computed from the first two points: (k1 M1 + k2 M2) / (k1^2 + k2^2).
        let (k1, m1, k2, m2) = (
            0.0034717963716,
            5.49543855015,
            0.0083313678689,
            13.0516901422,
        );
        let slope = (k1 * m1 + k2 * m2) / (k1 * k1 + k2 * k2);
        assert!((c.origin_slope(2) / slope - 1.0).abs() < 1e-14);
    }

    #[test]
    fn refuses_what_is_not_a_monotonic_curve() {
        let ok = format!("{HEADER}\n0.1,1\n0.2,2\n");
        assert_eq!(Curve::parse(&ok).unwrap().len(), 2);
        for bad in [
            "kappa,M\n0.1,1\n".to_string(),
            format!("{HEADER}\n0.1,1\n0.05,2\n"),
            format!("{HEADER}\n0.1,1\n0.2,0.5\n"),
            format!("{HEADER}\n0.1,x\n"),
            format!("{HEADER}\n0.1,1,3\n"),
            format!("{HEADER}\n-0.1,1\n"),
        ] {
            assert!(Curve::parse(&bad).is_err(), "{bad}");
        }
    }
}
