//! Frictionless bending stiffness of a strand stretched by an axial strain: the thin-rod
//! (Kirchhoff) energy of each helical wire laid on the bent, stretched layer beneath.
//!
//! # Model
//!
//! The strand's axis is stretched by the strain `eps` and bent to the curvature `kappa`
//! (per unit deformed length). A helical wire stays on the cylinder of its helix radius R
//! around the axis (the layer beneath is rigid) and, without friction, is free to slide
//! along its own length (one uniform wire strain `xi`, from its path length over a pitch),
//! to migrate around the axis, `theta = 2 pi x / P + a1 cos(phi) + a2 sin(phi)` with phi the
//! helix phase, and to spin about its own axis by `c1 cos(phi) + c2 sin(phi)` (rad). Its
//! energy per pitch is
//!
//! ```text
//! E A xi^2 L0 / 2 + int [ E I ((w1 (1 + xi))^2 + (w2 (1 + xi) - w2r)^2)
//!                         + G J (w3 (1 + xi) - w3r)^2 ] / 2 ds / (1 + xi)
//! ```
//!
//! with (w1, w2, w3) the material curvatures and twist of the wire's path (Darboux frame of
//! the cylinder: geodesic and normal curvature, geodesic torsion, turned by the spin), per unit
//! deformed length, and (w2r, w3r) = (-sin^2 alpha / R, -sin alpha cos alpha / R) those of
//! the unloaded helix. The migration and spin minimise it (one harmonic of the phase
//! suffices: a second changes the result below 1e-9). The layer's stiffness is the second
//! derivative of m times that energy per unit rest length in the rest-length curvature
//! `(1 + eps) kappa`, divided by `1 + eps` to refer it to the deformed curvature; the core
//! contributes `E_c I_c (1 + eps)` (its bending spring acts on the rotation per unit rest
//! length, as the fine model's joints do).
//!
//! At `eps = 0` the layer's value is Costello's `m E I cos(alpha) 2 / (2 + nu sin^2 alpha)`
//! ([`crate::BaseStiffness::Costello`]); under tension it falls: the wires' tension resists
//! the migration the bend drives, and the tension carried on the migrated path bends against
//! the strand (the frictionless fine strand's drop, see the Findings page of the manual).
//! Not in the model: the contact's compliance (the fine model's penalty sinks the wires), the
//! wires' shear, contact between neighbours or with a crossing layer above.

use std::f64::consts::PI;

use crate::geometry::{HelixLayer, Strand};

/// Quadrature points over a pitch (periodic trapezoid rule, exact to round-off for the
/// smooth integrand: 16 points already agree with 512 to 1e-6 of K_min).
const POINTS: usize = 32;

/// Curvature of the bend used for the second difference, as a fraction of 1 / R (-): the
/// energy is even in the curvature, so the central difference errs by the quartic term, the
/// wire's stretch `E A (kappa^2 R^2)^2` against its bending `E I kappa^2`, that is
/// O((kappa R)^2 (R / r_w)^2) = 1e-8 (R / r_w)^2 relative.
const BEND: f64 = 1e-4;

/// Material constants and rest geometry of one helical wire.
#[derive(Debug, Clone, Copy)]
struct Wire {
    radius: f64,
    lay_angle: f64,
    ea: f64,
    ei: f64,
    gj: f64,
}

impl Wire {
    fn of(layer: &HelixLayer) -> Wire {
        let w = &layer.spec.wire;
        let e = w.material.youngs_modulus;
        let g = e / (2.0 * (1.0 + w.material.poisson_ratio));
        Wire {
            radius: layer.radius,
            lay_angle: layer.lay_angle(),
            ea: e * w.area(),
            ei: e * w.inertia(),
            gj: g * 2.0 * w.inertia(),
        }
    }

    /// Energy of the wire per unit rest strand length (J/m) at strain `eps`, curvature
    /// `kappa` (1/m, per deformed length), migration `(a1, a2)` and spin `(c1, c2)` (rad).
    fn energy(&self, eps: f64, kappa: f64, p: &[f64; 4]) -> f64 {
        let r = self.radius;
        let (sa, ca) = self.lay_angle.sin_cos();
        let k = sa / (ca * r); // 2 pi / P
        let a = 1.0 + eps;
        let (w2r, w3r) = (-sa * sa / r, -sa * ca / r);
        let mut path = 0.0;
        let mut terms = [0.0; 3]; // int of w1^2 s, (w2, w3) with their weights, by moment
        let mut samples = [(0.0, 0.0, 0.0, 0.0); POINTS];
        for (i, sample) in samples.iter_mut().enumerate() {
            let phi = 2.0 * PI * i as f64 / POINTS as f64;
            let (sp, cp) = phi.sin_cos();
            let d = p[0] * cp + p[1] * sp;
            let dx = k * (-p[0] * sp + p[1] * cp);
            let dxx = -k * k * d;
            let psi = p[2] * cp + p[3] * sp;
            let psix = k * (-p[2] * sp + p[3] * cp);
            let (th, thx) = (phi + d, k + dx);
            let (s, c) = th.sin_cos();
            // Tangent r_x = u T + v e_theta and r_xx in the frame (T, e_theta, e_r).
            let u = a * (1.0 - kappa * r * s);
            let v = r * thx;
            let ux = -a * kappa * r * c * thx;
            let vx = r * dxx;
            let b = [
                ux - v * a * kappa * c,
                u * a * kappa * c + vx,
                u * a * kappa * s - v * thx,
            ];
            let n = u.hypot(v);
            let t = [u / n, v / n];
            let bt = b[0] * t[0] + b[1] * t[1];
            // Curvature vector (r_xx minus its tangential part) / |r_x|^2.
            let kv = [
                (b[0] - bt * t[0]) / (n * n),
                (b[1] - bt * t[1]) / (n * n),
                b[2] / (n * n),
            ];
            let kn = kv[2]; // along e_r
            let kg = kv[0] * t[1] - kv[1] * t[0]; // along t x e_r = (t1, -t0, 0)
            // Geodesic torsion: d e_r / ds . (t x e_r), d e_r / dx = (-a kappa s, thx, 0).
            let tg = (-a * kappa * s * t[1] - thx * t[0]) / n;
            let (sp2, cp2) = psi.sin_cos();
            let w1 = -kg * cp2 + kn * sp2;
            let w2 = kg * sp2 + kn * cp2;
            let w3 = tg + psix / n;
            path += n;
            *sample = (w1, w2, w3, n);
        }
        let length = path / POINTS as f64; // deformed wire length per unit rest strand length
        let xi = length * ca - 1.0;
        let f = 1.0 + xi;
        for (w1, w2, w3, n) in samples {
            terms[0] += (w1 * f).powi(2) * n / f;
            terms[1] += (w2 * f - w2r).powi(2) * n / f;
            terms[2] += (w3 * f - w3r).powi(2) * n / f;
        }
        let mean = |x: f64| x / POINTS as f64;
        0.5 * self.ea * xi * xi / ca
            + 0.5 * self.ei * (mean(terms[0]) + mean(terms[1]))
            + 0.5 * self.gj * mean(terms[2])
    }

    /// The energy minimised over migration and spin (Newton on a central-difference
    /// gradient and Hessian; the energy is quadratic in them to the bend's order).
    fn relaxed_energy(&self, eps: f64, kappa: f64) -> f64 {
        let mut p = [0.0; 4];
        let h = 1e-6;
        for _ in 0..3 {
            let e = |q: &[f64; 4]| self.energy(eps, kappa, q);
            let shifted = |i: usize, di: f64, j: usize, dj: f64| {
                let mut q = p;
                q[i] += di;
                q[j] += dj;
                e(&q)
            };
            let mut g = [0.0; 4];
            let mut hm = [[0.0; 4]; 4];
            for i in 0..4 {
                g[i] = (shifted(i, h, i, 0.0) - shifted(i, -h, i, 0.0)) / (2.0 * h);
                for j in i..4 {
                    hm[i][j] = (shifted(i, h, j, h) - shifted(i, h, j, -h) - shifted(i, -h, j, h)
                        + shifted(i, -h, j, -h))
                        / (4.0 * h * h);
                    hm[j][i] = hm[i][j];
                }
            }
            let Some(step) = solve4(hm, g) else { break };
            for i in 0..4 {
                p[i] -= step[i];
            }
        }
        self.energy(eps, kappa, &p)
    }

    /// Bending stiffness of `m` such wires (N m^2) at strain `eps`, per deformed curvature.
    fn stiffness(&self, wires: usize, eps: f64) -> f64 {
        let kappa = BEND / self.radius;
        let w0 = self.relaxed_energy(eps, 0.0);
        let second = (self.relaxed_energy(eps, kappa) + self.relaxed_energy(eps, -kappa)
            - 2.0 * w0)
            / (kappa * kappa);
        wires as f64 * second / (1.0 + eps)
    }
}

/// Solves the 4 x 4 system `a x = b` by Gaussian elimination with partial pivoting; `None`
/// when singular.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c] == 0.0 {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..4 {
            let f = a[r][c] / a[c][c];
            for k in c..4 {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        let s: f64 = (r + 1..4).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
}

/// Frictionless bending stiffness of the wires of `layer` at the axial strain `eps` (-), per
/// unit deformed curvature (N m^2): the thin-rod energy of the module docs.
pub fn layer_stiffness(layer: &HelixLayer, eps: f64) -> f64 {
    Wire::of(layer).stiffness(layer.wires(), eps)
}

/// Frictionless bending stiffness of `strand` at the axial strain `eps` (-), per unit deformed
/// curvature (N m^2): the core's `E_c I_c (1 + eps)` plus [`layer_stiffness`] of every layer,
/// each on a rigid layer beneath (no contact between layers is modelled).
pub fn stretched_min_bending_stiffness(strand: &Strand, eps: f64) -> f64 {
    let core = strand.core();
    core.material.youngs_modulus * core.inertia() * (1.0 + eps)
        + strand
            .layers()
            .iter()
            .map(|l| layer_stiffness(l, eps))
            .sum::<f64>()
}
