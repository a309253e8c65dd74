//! The friction limit of a layer's slipping wires from the contact pressure on them
//! (`section.slip_pressure`): their own tension's, or that plus what the layers outside press
//! down.
//!
//! A wire of layer j (j = 1..N outward) with tension T_j presses on the layer beneath with the
//! line load T_j sin^2(alpha_j) / R_j (its helix curvature times its tension). The layers
//! outside it press down too: layer k > j, with n_k wires on the radius R_k, puts the radial
//! load n_k T_k sin^2(alpha_k) / R_k per unit length on the cylinder beneath it, which layer j
//! carries to the layer beneath it, 1/n_j of it per wire. Along a wire length ds = R_j dtheta /
//! sin(alpha_j) friction changes the tension by at most mu times the line load, so the
//! friction-limited tension of a wire slipping from the neutral axis (theta = 0, T_j = F_j) obeys
//! the triangular linear system (Cardou's review, 2013; `../shared` references, "Multi-layer
//! strands")
//!
//! ```text
//! dT_j/dtheta = lambda_j T_j + sum_{k>j} a_jk T_k,   lambda_j = mu sin(alpha_j),
//! a_jk = mu (R_j / (n_j sin alpha_j)) n_k sin^2(alpha_k) / R_k        (accumulated)
//! a_jk = mu (r_wj / sin alpha_j) sin^2(alpha_k) / r_wk                 (sc5)
//! a_jk = 2 mu (R_j / (n_j sin alpha_j)) n_k sin^2(alpha_k) / R_k       (two_faces)
//! ```
//!
//! The SC5 form replaces the layer's n_k / R_k by its close-packing value pi / r_wk (and
//! R_j / n_j by r_wj / pi); the exact n_k / R_k is the better choice. The
//! layers' tensions at theta = 0 are the wires' tensions from the strand's strain, F_k = E_k A_k
//! cos^2(alpha_k) eps, so the solution is proportional to eps and its gain G_j(theta) =
//! (T_j(theta) - F_j) / F_j depends on theta alone: the section laws keep their form, with the
//! capstan gain exp(lambda_j theta) - 1 of the own-layer law (SC1, `own_layer`) replaced by
//! G_j. On the shortened side the tensions fall: the same system with every coefficient
//! negated. The outermost layer has nothing outside it and keeps the capstan gain exactly (its
//! row of the system is lambda_N T_N alone); so does the only layer of a `1+m` strand, whose law
//! is the same under every variant.
//!
//! Closed form: T(theta) = exp(theta A) F for the constant upper-triangular matrix A, each row
//! j a sum of the exponentials exp(lambda_k theta), k >= j (with powers of theta where two
//! lambdas coincide, as they do for layers at one lay angle). It is evaluated as the
//! exponential's series, T(theta) - F = sum_{n >= 1} (theta A)^n F / n!, which has no
//! cancellation at small theta and no division by lambda_k - lambda_j: for the capstan angles
//! of the law (theta <= pi) and friction coefficients up to 1, theta ||A|| is a few units and
//! the series reaches round-off in fewer than 40 terms; the loop stops when a term no longer
//! changes the sum. Beyond theta ||A|| = 8 (friction coefficients of several units, e.g. a
//! scene that sets a large mu to keep its wires stuck) the shortened side's alternating series
//! would lose every digit, and the exponential is scaled and squared instead. The property
//! tests compare both with a Runge-Kutta integration of the system built from the formulas
//! above.
//!
//! Both faces (`two_faces`): the layers outside press a wire of layer j down on its outer face
//! as well, with the same line load that its inner face passes on to the layer beneath. Where
//! layer j slips against the layer outside it too (it slips along its own helix, the layer
//! outside along another one, so their relative slip at a crossing has a component along the
//! wire), friction acts on both faces: mu times the own line load plus twice the load from
//! outside, the accumulated a_jk doubled. The fine 1+6+12 bending test measures this on the
//! inner layer (`multilayer.md`, "Which layer carries the excess"). The outermost layer has one
//! face in contact and keeps the capstan gain. It is the default: the fine model's converged
//! bending tests with friction (1+6+12 strand, ACSR section) follow it on loading where the
//! one-face `accumulated` limit lies 6-18 % low (`multilayer.md`, "Which layer
//! carries the excess").
//!
//! Where the contact type enters: the line load is the same total force whether a layer
//! touches the one beneath along lines or at crossing points, so the friction limit per unit
//! length is the same; what the crossing points change is the stick stiffness
//! ([`crate::bonded`], "Layers on layers").

use crate::geometry::Strand;

/// The largest number of layers the accumulated-pressure limits evaluate without allocating.
pub const MAX_LAYERS: usize = 16;

/// Upper bound on the series' terms; not reached (theta ||A|| <= [`SERIES_REACH`]).
const MAX_TERMS: usize = 400;

/// The largest theta ||A|| summed as the plain series (-): on the shortened side the series
/// alternates, and its largest term, at most exp(theta ||A||) of the sum's scale, costs that
/// many units of round-off, 3e3 u = 7e-13 at 8. Friction coefficients up to 1 stay below it
/// (theta <= pi); beyond it [`PressureSystem::side`] scales and squares.
const SERIES_REACH: f64 = 8.0;

/// Which contact pressure sets a layer's friction limit (`section.slip_pressure`; module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SlipPressure {
    /// Each wire's own tension only: the capstan gain exp(mu theta sin(alpha)) - 1 of every
    /// layer (SC1).
    OwnLayer,
    /// Own tension plus the layers outside, with their exact n_k / R_k, on one face: a layer
    /// under others is pressed by them (without it an inner layer of a conductor slips at the
    /// curvature of a lone layer), and this is the line load of the strand as built.
    Accumulated,
    /// Own tension plus the layers outside with the close-packing n_k / R_k = pi / r_wk (SC5).
    Sc5,
    /// Own tension plus twice the layers outside (exact n_k / R_k): friction on the inner face
    /// (own tension plus the load from outside) and on the outer face (the load from outside),
    /// for a layer that slips against both its neighbours (module docs). The default.
    #[default]
    TwoFaces,
}

impl SlipPressure {
    /// Every form, in the order of the documentation.
    pub const ALL: [SlipPressure; 4] = [
        SlipPressure::OwnLayer,
        SlipPressure::Accumulated,
        SlipPressure::Sc5,
        SlipPressure::TwoFaces,
    ];

    /// Name as used in scene files (`section.slip_pressure`).
    pub fn name(self) -> &'static str {
        match self {
            SlipPressure::OwnLayer => "own_layer",
            SlipPressure::Accumulated => "accumulated",
            SlipPressure::Sc5 => "sc5",
            SlipPressure::TwoFaces => "two_faces",
        }
    }

    /// The form named `name` (as in scene files), if any.
    pub fn from_name(name: &str) -> Option<SlipPressure> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

impl std::fmt::Display for SlipPressure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The pressure system of a strand's layers (module docs): the upper-triangular matrix A and
/// the wires' tensions per unit strand strain F (N).
#[derive(Debug, Clone, PartialEq)]
pub struct PressureSystem {
    /// Row-major N x N, zero below the diagonal (1/rad).
    matrix: Vec<f64>,
    /// F_k / eps = E_k A_k cos^2(alpha_k) (N).
    tension: Vec<f64>,
    layers: usize,
}

impl PressureSystem {
    /// The system of `strand` under `variant`; `None` for the own-layer variant, or for a
    /// strand with fewer than two layers (where every variant is the capstan law).
    pub fn new(strand: &Strand, variant: SlipPressure) -> Option<Self> {
        let l = strand.layers();
        let n = l.len();
        if variant == SlipPressure::OwnLayer || n < 2 {
            return None;
        }
        let mu = strand.friction();
        let mut matrix = vec![0.0; n * n];
        for j in 0..n {
            let sj = l[j].lay_angle().sin();
            matrix[j * n + j] = mu * sj;
            for k in j + 1..n {
                let sk2 = l[k].lay_angle().sin().powi(2);
                matrix[j * n + k] = match variant {
                    SlipPressure::Sc5 => {
                        mu * (l[j].spec.wire.radius() / sj) * sk2 / l[k].spec.wire.radius()
                    }
                    _ => {
                        let faces = if variant == SlipPressure::TwoFaces {
                            2.0
                        } else {
                            1.0
                        };
                        faces
                            * mu
                            * (l[j].radius / (l[j].wires() as f64 * sj))
                            * l[k].wires() as f64
                            * sk2
                            / l[k].radius
                    }
                };
            }
        }
        let tension = l
            .iter()
            .map(|h| {
                let w = &h.spec.wire;
                w.material.youngs_modulus * w.area() * h.lay_angle().cos().powi(2)
            })
            .collect();
        Some(PressureSystem {
            matrix,
            tension,
            layers: n,
        })
    }

    /// Number of layers N.
    pub fn layers(&self) -> usize {
        self.layers
    }

    /// The coefficient a_jk of the system (1/rad; the diagonal is lambda_j).
    pub fn coefficient(&self, j: usize, k: usize) -> f64 {
        self.matrix[j * self.layers + k]
    }

    /// Gains (stretched, shortened) of layer `j`'s friction limit at capstan angle `theta`
    /// (rad): (T_j(theta) - F_j) / F_j on the stretched side and (F_j - T_j(theta)) / F_j on
    /// the shortened side, and their derivatives with respect to `theta` (1/rad).
    pub fn gains(&self, j: usize, theta: f64) -> ([f64; 2], [f64; 2]) {
        let (g_pos, d_pos) = self.side(j, theta, 1.0);
        let (g_neg, d_neg) = self.side(j, theta, -1.0);
        ([g_pos, -g_neg], [d_pos, -d_neg])
    }

    /// (T_j(theta) - F_j) / F_j and its theta-derivative for the system `sign A`.
    fn side(&self, j: usize, theta: f64, sign: f64) -> (f64, f64) {
        let n = self.layers;
        let m = n - j;
        debug_assert!(n <= MAX_LAYERS);
        // theta ||A|| (rows j.., maximum row sum): beyond SERIES_REACH the shortened side's
        // alternating series loses every digit (its largest term grows as
        // exp(theta ||A||) while the sum stays below one), so it is scaled and squared.
        let norm = (j..n)
            .map(|r| (r..n).map(|c| self.matrix[r * n + c].abs()).sum::<f64>())
            .fold(0.0, f64::max);
        if theta * norm > SERIES_REACH {
            return self.side_squared(j, theta * norm, theta, sign);
        }
        // Rows j.. only: the system is upper triangular.
        let mut term = [0.0; MAX_LAYERS];
        let mut sum = [0.0; MAX_LAYERS];
        term[..m].copy_from_slice(&self.tension[j..]);
        let a = |r: usize, c: usize| sign * self.matrix[(j + r) * n + j + c];
        for order in 1..MAX_TERMS {
            let mut next = [0.0; MAX_LAYERS];
            for (r, x) in next[..m].iter_mut().enumerate() {
                let s: f64 = (r..m).map(|c| a(r, c) * term[c]).sum();
                *x = s * theta / order as f64;
            }
            for r in 0..m {
                sum[r] += next[r];
            }
            term = next;
            // Past the largest term the terms fall factorially: stop once none moves its sum
            // by more than 1e-17 of it (the sum at theta = 0 is exactly zero).
            if (0..m).all(|r| next[r].abs() <= 1e-17 * sum[r].abs()) {
                break;
            }
        }
        // dT_j/dtheta = (A T)_j with T = F + sum.
        let slope: f64 = (0..m)
            .map(|c| a(0, c) * (self.tension[j + c] + sum[c]))
            .sum();
        (sum[0] / self.tension[j], slope / self.tension[j])
    }

    /// [`Self::side`] by scaling and squaring, for `reach` = theta ||A|| beyond
    /// [`SERIES_REACH`]: B = exp(theta A / 2^s) - I by its series, with ||theta A / 2^s|| <= 1
    /// (no cancellation: the largest term is the first), then s times (I + B)^2 - I = 2 B +
    /// B^2, which keeps the difference from I without forming I + B. The matrices are upper
    /// triangular; the products run over r <= k <= c only, so an infinite entry of the
    /// stretched side (exp overflows past theta ||A|| of about 700: a limit no wire reaches,
    /// the wires stick) never meets a structural zero.
    fn side_squared(&self, j: usize, reach: f64, theta: f64, sign: f64) -> (f64, f64) {
        let n = self.layers;
        let m = n - j;
        let squarings = reach.log2().ceil().max(0.0) as i32;
        let h = theta * 0.5f64.powi(squarings);
        let a = |r: usize, c: usize| sign * self.matrix[(j + r) * n + j + c];
        let mut b = [[0.0; MAX_LAYERS]; MAX_LAYERS];
        let mut term = [[0.0; MAX_LAYERS]; MAX_LAYERS];
        for r in 0..m {
            for c in r..m {
                term[r][c] = h * a(r, c);
                b[r][c] = term[r][c];
            }
        }
        for order in 2..MAX_TERMS {
            let mut next = [[0.0; MAX_LAYERS]; MAX_LAYERS];
            for r in 0..m {
                for c in r..m {
                    let s: f64 = (r..=c).map(|k| term[r][k] * a(k, c)).sum();
                    next[r][c] = s * h / order as f64;
                }
            }
            let mut moved = false;
            for r in 0..m {
                for c in r..m {
                    b[r][c] += next[r][c];
                    moved |= next[r][c].abs() > 1e-17 * b[r][c].abs();
                }
            }
            term = next;
            if !moved {
                break;
            }
        }
        for _ in 0..squarings {
            let mut sq = [[0.0; MAX_LAYERS]; MAX_LAYERS];
            for r in 0..m {
                for c in r..m {
                    let p: f64 = (r..=c).map(|k| b[r][k] * b[k][c]).sum();
                    sq[r][c] = 2.0 * b[r][c] + p;
                }
            }
            b = sq;
        }
        let f = &self.tension[j..n];
        let sum: Vec<f64> = (0..m)
            .map(|r| (r..m).map(|c| b[r][c] * f[c]).sum())
            .collect();
        let slope: f64 = (0..m).map(|c| a(0, c) * (f[c] + sum[c])).sum();
        (sum[0] / self.tension[j], slope / self.tension[j])
    }

    /// d G_j / d theta at theta = 0 (1/rad), the same on both sides: the ratio of a wire's
    /// friction-limited force to its angle from the neutral axis as the angle goes to zero.
    pub fn neutral_slope(&self, j: usize) -> f64 {
        let n = self.layers;
        (j..n)
            .map(|k| self.matrix[j * n + k] * self.tension[k])
            .sum::<f64>()
            / self.tension[j]
    }
}
