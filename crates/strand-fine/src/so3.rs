//! Rotation helpers on SO(3): rotation vectors, their exponential and logarithm, and the
//! transpose of the inverse right Jacobian that maps a rotational spring's moment in rotation
//! vector coordinates to a physical torque.
//!
//! Rotations are unit quaternions; a rotation vector `theta` (rad) has direction = axis and
//! length = angle.

use nalgebra::{UnitQuaternion, Vector3};

/// Rotation of angle `|theta|` (rad) about `theta / |theta|`; the identity for `theta = 0`.
pub fn exp(theta: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(*theta)
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
    let s = v.norm();
    if s < 1e-8 {
        // angle = 2 atan2(s, w) ~ 2 s / w (1 - s^2 / (3 w^2)); factor angle / s.
        let f = 2.0 / w * (1.0 - s * s / (3.0 * w * w));
        v * f
    } else {
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
    let c = if t2 < 1e-6 {
        // Series: 1/12 + theta^2/720 + theta^4/30240.
        1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0
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
