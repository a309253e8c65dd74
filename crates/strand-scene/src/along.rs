//! The strand's state along s at one time, as every model measures it: the common input of
//! the probes (`probe_<s>.csv`) and the range envelopes (`range.csv`).

/// One measured point along the strand.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Station {
    /// Material coordinate (m).
    pub s: f64,
    /// Position (m).
    pub position: [f64; 3],
    /// Curvature (1/m): signed about Z in a planar scene, the magnitude in 3D.
    pub curvature: f64,
    /// Bending moment (N m): same sign convention as the curvature.
    pub moment: f64,
    /// Tension (N).
    pub tension: f64,
    /// Secant bending stiffness M / kappa (N m^2); `None` where it is undefined.
    pub stiffness: Option<f64>,
}

/// The bracket of `s` in the increasing coordinates `at`: `(i, w)` with `s` between `at[i]`
/// and `at[i + 1]` at the fraction `w` in [0, 1] (`w = 0` at `at[i]`). Outside the range the
/// nearest end (`w` 0 or 1). `at` must not be empty.
pub fn bracket(at: &[f64], s: f64) -> (usize, f64) {
    let n = at.len();
    if n < 2 {
        return (0, 0.0);
    }
    // First index with at[j] > s, so at[j - 1] <= s < at[j].
    let j = at.partition_point(|&x| x <= s).clamp(1, n - 1);
    let (a, b) = (at[j - 1], at[j]);
    let w = if b > a {
        ((s - a) / (b - a)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (j - 1, w)
}

/// Linear interpolation between `values[i]` and `values[i + 1]` at the fraction `w`; exactly
/// `values[i]` at `w = 0` and `values[i + 1]` at `w = 1`.
pub fn lerp(values: &[f64], (i, w): (usize, f64)) -> f64 {
    if w == 0.0 || i + 1 >= values.len() {
        values[i]
    } else if w == 1.0 {
        values[i + 1]
    } else {
        values[i] + w * (values[i + 1] - values[i])
    }
}

/// The stations' curvature, moment, tension and position interpolated linearly in s at `s`.
pub fn interpolate(stations: &[Station], s: f64) -> Station {
    let at: Vec<f64> = stations.iter().map(|p| p.s).collect();
    let b = bracket(&at, s);
    let col = |f: fn(&Station) -> f64| lerp(&stations.iter().map(f).collect::<Vec<_>>(), b);
    Station {
        s,
        position: [
            col(|p| p.position[0]),
            col(|p| p.position[1]),
            col(|p| p.position[2]),
        ],
        curvature: col(|p| p.curvature),
        moment: col(|p| p.moment),
        tension: col(|p| p.tension),
        stiffness: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Linear interpolation reproduces a linear field exactly (to round-off) anywhere in
        /// the range, and the end values beyond it.
        #[test]
        fn a_linear_field_is_reproduced(
            steps in prop::collection::vec(1e-3f64..1.0, 1..20),
            a in -10.0f64..10.0, b in -10.0f64..10.0, u in -0.2f64..1.2,
        ) {
            let mut at = vec![0.0];
            for d in &steps {
                at.push(at.last().unwrap() + d);
            }
            let len = *at.last().unwrap();
            let values: Vec<f64> = at.iter().map(|x| a + b * x).collect();
            let s = u * len;
            let got = lerp(&values, bracket(&at, s));
            let expect = a + b * s.clamp(0.0, len);
            // Round-off of a few operations on values up to |a| + |b| len.
            prop_assert!((got - expect).abs() <= 1e-12 * (a.abs() + b.abs() * len + 1.0));
        }
    }

    #[test]
    fn a_node_gives_its_own_value() {
        let at = [0.0, 0.5, 1.5, 2.0];
        let v = [1.0, -3.0, 7.0, 2.0];
        for (x, y) in at.iter().zip(&v) {
            assert_eq!(lerp(&v, bracket(&at, *x)), *y);
        }
        assert_eq!(lerp(&[4.0], bracket(&[1.0], 3.0)), 4.0);
    }
}
