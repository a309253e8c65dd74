//! Rotation helpers on SO(3): rotation vectors, their exponential and logarithm, and the
//! transpose of the inverse right Jacobian that maps a rotational spring's moment in rotation
//! vector coordinates to a physical torque.
//!
//! Rotations are unit quaternions; a rotation vector `theta` (rad) has direction = axis and
//! length = angle.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Rotation of angle `|theta|` (rad) about `theta / |theta|`; the identity for `theta = 0`.
/// Below 0.01 rad (the rotations of a time step) the half-angle sine and cosine are their
/// Taylor series to the eighth order, exact to round-off and without trigonometric calls.
pub fn exp(theta: &Vector3<f64>) -> UnitQuaternion<f64> {
    let t2 = theta.norm_squared();
    if t2 < 1e-4 {
        // cos(a/2) and sin(a/2)/a in a^2; the next terms are below 1e-19.
        let w = 1.0 - t2 / 8.0 + t2 * t2 / 384.0 - t2 * t2 * t2 / 46080.0;
        let s = 0.5 - t2 / 48.0 + t2 * t2 / 3840.0 - t2 * t2 * t2 / 645120.0;
        UnitQuaternion::new_unchecked(Quaternion::new(w, s * theta.x, s * theta.y, s * theta.z))
    } else {
        UnitQuaternion::from_scaled_axis(*theta)
    }
}

/// Rotation vector (rad) of `q`, with the angle in [0, pi]; exact near the identity (no
/// division by a vanishing angle).
pub fn log(q: &UnitQuaternion<f64>) -> Vector3<f64> {
    // Take the representative with non-negative scalar part so the angle is in [0, pi].
    let (w, v) = if q.w < 0.0 {
        (-q.w, -q.imag())
    } else {
        (q.w, q.imag())
    };
    let s2 = v.norm_squared();
    if s2 < 0.0025 * w * w {
        // angle = 2 atan(x) with x = |v| / w < 0.05: factor angle / |v| = (2 / w) atan(x) / x
        // as its series to x^12 (the next term is below 1e-19).
        let x2 = s2 / (w * w);
        let series = 1.0
            - x2 * (1.0 / 3.0
                - x2 * (1.0 / 5.0
                    - x2 * (1.0 / 7.0 - x2 * (1.0 / 9.0 - x2 * (1.0 / 11.0 - x2 / 13.0)))));
        v * (2.0 / w * series)
    } else {
        let s = s2.sqrt();
        v * (2.0 * s.atan2(w) / s)
    }
}

/// Applies the transpose of the inverse right Jacobian of SO(3) at `theta` to `m`:
/// `J_r^{-T}(theta) m = m - 1/2 theta x m + c(theta) theta x (theta x m)` with
/// `c = 1/theta^2 - (1 + cos theta) / (2 theta sin theta)`.
///
/// If a rotation `Q = exp(theta)` is perturbed on the right by a small body rotation `dphi`,
/// `d theta = J_r^{-1}(theta) dphi`; a spring with energy `U(theta)` and moment
/// `m = dU/dtheta` therefore exerts the body torque `J_r^{-T} m`.
pub fn right_jacobian_inv_t(theta: &Vector3<f64>, m: &Vector3<f64>) -> Vector3<f64> {
    let t2 = theta.norm_squared();
    let c = if t2 < 1e-2 {
        // Series (Bernoulli numbers) to theta^8; the next term is below 1e-19.
        1.0 / 12.0
            + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 * (1.0 / 1209600.0 + t2 / 47900160.0)))
    } else {
        let t = t2.sqrt();
        1.0 / t2 - (1.0 + t.cos()) / (2.0 * t * t.sin())
    };
    let txm = theta.cross(m);
    m - 0.5 * txm + c * theta.cross(&txm)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn log_inverts_exp() {
        for th in [
            Vector3::new(0.3, -0.2, 1.1),
            Vector3::new(1e-10, 2e-10, -3e-10),
            Vector3::new(0.0, 0.0, 3.0),
            Vector3::zeros(),
        ] {
            let back = log(&exp(&th));
            assert_relative_eq!(back, th, epsilon = 1e-14, max_relative = 1e-12);
        }
    }

    /// The series branches agree with the closed forms on both sides of their switches.
    #[test]
    fn series_branches_match_the_closed_forms() {
        let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
        for a in [
            1e-9, 1e-5, 3e-3, 9.99e-3, 1.001e-2, 0.09, 0.0999, 0.1001, 0.2,
        ] {
            let th = axis * a;
            let q = exp(&th);
            let closed = UnitQuaternion::from_scaled_axis(th);
            assert!(q.angle_to(&closed) < 1e-16 + 1e-15 * a, "exp at {a}");
            assert!((q.norm() - 1.0).abs() < 1e-15);
            let back = log(&closed);
            assert_relative_eq!(back, th, max_relative = 1e-15);
            // c(theta) against its closed form.
            let m = Vector3::new(1.0, -2.0, 0.5);
            let series = right_jacobian_inv_t(&th, &m);
            let c = 1.0 / (a * a) - (1.0 + a.cos()) / (2.0 * a * a.sin());
            let txm = th.cross(&m);
            let closed = m - 0.5 * txm + c * th.cross(&txm);
            // The closed form itself loses digits to cancellation below 1e-2 rad.
            let tol = if a < 0.05 { 1e-16 / (a * a) } else { 1e-14 };
            assert!((series - closed).norm() < tol * m.norm(), "c at {a}");
        }
    }

    #[test]
    fn jacobian_matches_finite_difference() {
        // d theta = J_r^{-1} dphi  <=>  <J_r^{-T} m, dphi> = <m, d theta>.
        let th = Vector3::new(0.4, -0.7, 0.9);
        let m = Vector3::new(1.0, 2.0, -0.5);
        let q = exp(&th);
        let jtm = right_jacobian_inv_t(&th, &m);
        let h = 1e-6;
        for k in 0..3 {
            let mut dphi = Vector3::zeros();
            dphi[k] = h;
            let tp = log(&(q * exp(&dphi)));
            let tm = log(&(q * exp(&(-dphi))));
            let dtheta = (tp - tm) / (2.0 * h);
            assert_relative_eq!(m.dot(&dtheta), jtm[k], epsilon = 1e-8);
        }
        // Small-angle branch agrees with the closed form across the switch.
        let a = Vector3::new(5e-4, 3e-4, -6e-4);
        let b = a * 1.01;
        let ra = right_jacobian_inv_t(&a, &m);
        let rb = right_jacobian_inv_t(&b, &m);
        assert_relative_eq!(ra, rb, epsilon = 1e-5);
    }
}
