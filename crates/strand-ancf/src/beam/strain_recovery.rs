//! The strain the section law reads (the tension of its friction limits): recovered from the
//! element means of the axial strain, not taken from each element's two axial points.
//!
//! The cubic element cannot follow an inextensible curve whose curvature varies: with exact
//! nodal positions and unit nodal slopes its stretch at the two axial points differs by about
//! kappa kappa' l^3 / 20 (kappa l = 0.1, kappa' l^2 = 0.02: 1e-4). EA times that antisymmetric
//! part, far above the tension of a thin strand, stays in the slope of the line through the
//! two points: on the hanging section-3 strand (g = 12) that line was off by up to 0.12,
//! 0.061, 0.028 q (L - x) at 30, 60, 120 elements (first order; ten times worse with EA ten
//! times larger) and above the weight below near the tip. The element means are
//! second-order accurate, so the law reads the parabola whose means over three neighbouring
//! elements are theirs: within 1.4e-2, 4.4e-3, 1.2e-3 q L of the elastica at 30, 60, 120
//! elements, the largest at the strongly curved root (`tests/tension.rs`). The tangent leaves
//! out the dependence on the neighbours' strains (it would not fit in the band): Newton
//! converged in fewer iterations on the bundled stick/slip scenes than with the line
//! (section-3, g = 12: 1751 against 3882).

use super::quadrature::BendPoint;
use super::{AXIAL_POINTS, Beam, BeamError};
use crate::error::check_stretch;
use crate::scatter;

impl BendPoint {
    /// The strain the section law reads at this point, from the element's axial-point strains
    /// `eps_a` and the mean strains `means` of [`super::quadrature::ElementRule::others`].
    #[inline(always)]
    pub(super) fn strain(&self, eps_a: &[f64; AXIAL_POINTS], means: &[f64; 2]) -> f64 {
        let own: f64 = (0..AXIAL_POINTS).map(|j| self.interp[j] * eps_a[j]).sum();
        own + self.others[0] * means[0] + self.others[1] * means[1]
    }
}

impl Beam {
    /// Mean of element `e`'s axial-point strains at coordinates `q` (all coordinates).
    fn mean_strain(&self, q: &[f64], e: usize) -> Result<f64, BeamError> {
        let nd = self.nd;
        let qe = &q[e * nd..e * nd + 2 * nd];
        let mut sum = 0.0;
        for ap in &self.rules[e].axial {
            let n2: f64 = if nd == 4 {
                scatter::combine::<2>(&ap.row.ds, qe)
                    .iter()
                    .map(|v| v * v)
                    .sum()
            } else {
                scatter::combine::<3>(&ap.row.ds, qe)
                    .iter()
                    .map(|v| v * v)
                    .sum()
            };
            let n = check_stretch(n2.sqrt())
                .map_err(|source| BeamError::Kinematics { element: e, source })?;
            sum += n - 1.0;
        }
        Ok(sum / AXIAL_POINTS as f64)
    }

    /// Mean strains at coordinates `q` of the two other elements whose means enter the strain
    /// element `e`'s section law reads.
    pub(super) fn other_means(&self, q: &[f64], e: usize) -> Result<[f64; 2], BeamError> {
        if self.spec.elements == 1 {
            return Ok([0.0; 2]);
        }
        let o = self.rules[e].others;
        Ok([self.mean_strain(q, o[0])?, self.mean_strain(q, o[1])?])
    }
}

/// Weights of the strain the section law reads at local coordinate `x` of element `e` (of
/// `n`, length `l`, axial points at `xa`): on the element's own axial-point strains, and on
/// the mean strains of two other elements (returned with their indices).
///
/// The law reads the parabola whose means over three neighbouring elements (`c - 1, c,
/// c + 1`, with `c = e` inside and the nearest interior element at the ends) are their
/// measured mean strains: exact for a tension varying quadratically along the strand. Two
/// elements use the line through their means, one element the line through its axial points.
pub(super) fn recovery_weights(
    e: usize,
    n: usize,
    x: f64,
    l: f64,
    xa: &[f64],
) -> ([f64; AXIAL_POINTS], [usize; 2], [f64; 2]) {
    // Weight w on the element's own mean: w / AXIAL_POINTS on each of its axial points.
    let own = |w: f64| [w / AXIAL_POINTS as f64; AXIAL_POINTS];
    match n {
        1 => {
            // Lagrange polynomial through the axial points.
            let interp = std::array::from_fn(|j| {
                (0..AXIAL_POINTS)
                    .filter(|&k| k != j)
                    .map(|k| (x - xa[k]) / (xa[j] - xa[k]))
                    .product()
            });
            (interp, [0, 0], [0.0, 0.0])
        }
        2 => {
            // The line through the two means, u from the first element's midpoint.
            let u = (e as f64 * l + x - 0.5 * l) / l;
            let (w0, w1) = (1.0 - u, u);
            let (mine, other) = if e == 0 { (w0, w1) } else { (w1, w0) };
            (own(mine), [1 - e, 1 - e], [other, 0.0])
        }
        _ => {
            let c = e.clamp(1, n - 2);
            // u / l from the midpoint of element c; the weights of the means of c - 1, c, c + 1.
            let u = ((e as f64 - c as f64) * l + x - 0.5 * l) / l;
            let w = [
                -1.0 / 24.0 - 0.5 * u + 0.5 * u * u,
                13.0 / 12.0 - u * u,
                -1.0 / 24.0 + 0.5 * u + 0.5 * u * u,
            ];
            let mine = e + 1 - c;
            let (a, b) = match mine {
                0 => (1, 2),
                1 => (0, 2),
                _ => (0, 1),
            };
            (own(w[mine]), [c - 1 + a, c - 1 + b], [w[a], w[b]])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The recovered strain reproduces any quadratic field from its element means, whatever
    /// the element (inside or at either end).
    #[test]
    fn recovery_is_exact_for_quadratic_fields() {
        let (n, l) = (5, 0.2);
        let g = 1.0 / 3f64.sqrt();
        let xa = [0.5 * l * (1.0 - g), 0.5 * l * (1.0 + g)];
        let f = |x: f64| 0.3 - 1.7 * x + 2.9 * x * x;
        // Element means of f (exact: two-point Gauss integrates the quadratic).
        let mean = |e: usize| 0.5 * (f(e as f64 * l + xa[0]) + f(e as f64 * l + xa[1]));
        for e in 0..n {
            for x in [0.0, 0.031, 0.1, 0.17, 0.2] {
                let (own, idx, w) = recovery_weights(e, n, x, l, &xa);
                let eps_a = [f(e as f64 * l + xa[0]), f(e as f64 * l + xa[1])];
                let got = own[0] * eps_a[0]
                    + own[1] * eps_a[1]
                    + w[0] * mean(idx[0])
                    + w[1] * mean(idx[1]);
                let want = f(e as f64 * l + x);
                assert!(
                    (got - want).abs() < 1e-13,
                    "element {e}, x {x}: {got} vs {want}"
                );
            }
        }
    }
}
