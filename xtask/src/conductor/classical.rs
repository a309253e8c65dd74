//! The classical analytic moment-curvature models of a multi-layer strand, coded from their
//! published formulas and independent of `strand_core`'s section law (nothing here calls it):
//! the reference the Cardinal comparison sets the law beside.
//!
//! Geometry: a straight core and layers j = 1..N stacked wire on wire (R_1 = r_c + r_w1, R_j =
//! R_(j-1) + r_w(j-1) + r_wj), the lay angle from the pitch P on that radius, tan(alpha) = 2 pi
//! R / P. Under the strand strain eps a wire of layer j carries F_j = E_j A_j cos^2(alpha_j) eps
//! (EA = E_c A_c + sum n_j E_j A_j cos^3(alpha_j)).
//!
//! Stiffness bounds (Papailiou 1997): K_min = E_c I_c + sum_j n_j E_j I_j cos(alpha_j); K_max =
//! K_min + sum_j n_j E_j A_j cos^3(alpha_j) R_j^2 / 2 (the plane section).
//!
//! A wire of layer j at the angle phi from the neutral axis, stuck, gains the force k_j R_j
//! sin(phi) kappa (k_j = E_j A_j cos^2 alpha_j) on the stretched side (phi in (0, pi)) and loses
//! it on the shortened side. Friction limits that change to F_j G_j(theta), with theta =
//! min(phi, pi - phi) the angle from the nearest neutral-axis crossing and G_j from the wire
//! tensions T(theta) of the slip conditions (Cardou's review 2013, Cloutier's SC1-SC5):
//!
//! ```text
//! dT_j/dtheta = ± (lambda_j T_j + c_j sum_{k>j} b_k T_k),   T(0) = F,   lambda_j = mu sin(alpha_j)
//! ```
//!
//! (+ on the stretched side, G = T/F - 1; - on the shortened side, G = 1 - T/F). SC1
//! (Papailiou) has c = 0, the capstan law exp(lambda theta) - 1 of every layer; the others add
//! the layers outside with b_k = sin^2(alpha_k) / r_wk and c_j = (r_wj / sin alpha_j) m_j, m_j
//! = mu (SC5), 2 mu (SC2), mu (1 - cos(alpha_j + alpha_(j+1))) (SC3), 1.5 mu (Foti); the
//! `accumulated` form puts the exact line load of layer k on the cylinder beneath, n_k / R_k,
//! shared by the n_j wires of layer j: c_j b_k = mu R_j n_k sin^2(alpha_k) / (n_j sin(alpha_j)
//! R_k). The system is integrated by the classical Runge-Kutta method on the quadrature grid.
//!
//! The moment is the layer continuum (the wires' phases spread evenly, as a test over whole
//! pitches averages them): each wire's force change min(stick, limit), projected on the axis
//! by cos(alpha), times its lever arm R sin(phi):
//!
//! ```text
//! M = K_min kappa + sum_j (n_j / pi) cos(alpha_j) R_j int_0^{pi/2} sin(phi)
//!       [min(k_j R_j sin(phi) kappa, F_j G+_j(phi)) + min(k_j R_j sin(phi) kappa, F_j G-_j(phi))] dphi
//! ```
//!
//! by composite Simpson over `INTERVALS` intervals. All stick (kappa below the smallest
//! critical curvature) it is K_max kappa; all slip, K_min kappa plus a constant friction
//! moment, for SC1 in closed form (the tests).

use std::f64::consts::{FRAC_PI_2, PI};

use anyhow::{Context, bail};

/// Simpson intervals over [0, pi/2] (even).
pub const INTERVALS: usize = 1024;

/// One helical layer (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layer {
    /// Wire count n.
    pub wires: usize,
    /// Wire radius r_w (m).
    pub wire_radius: f64,
    /// Helix radius R (m).
    pub radius: f64,
    /// Lay angle alpha (rad).
    pub lay_angle: f64,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
}

impl Layer {
    fn area(&self) -> f64 {
        PI * self.wire_radius * self.wire_radius
    }
    /// k = E A cos^2(alpha) (N): a wire's axial force per unit strand strain.
    fn wire_stiffness(&self) -> f64 {
        self.youngs_modulus * self.area() * self.lay_angle.cos().powi(2)
    }
}

/// A strand as the classical models see it.
#[derive(Debug, Clone, PartialEq)]
pub struct Conductor {
    /// Core radius r_c (m).
    pub core_radius: f64,
    /// Core Young's modulus (Pa).
    pub core_youngs_modulus: f64,
    /// Layers from the core outward.
    pub layers: Vec<Layer>,
}

impl Conductor {
    /// The strand of a scene file (`strand.core`, `strand.layers[]` with `wires`, `diameter`,
    /// `youngs_modulus` and `pitch` or `lay_angle_deg`), read from its JSON and stacked as in
    /// the module docs.
    pub fn from_scene_json(scene: &serde_json::Value) -> anyhow::Result<Self> {
        let num = |v: &serde_json::Value, f: &str| {
            v[f].as_f64()
                .with_context(|| format!("strand field `{f}` missing or not a number"))
        };
        let strand = &scene["strand"];
        let core = &strand["core"];
        let core_radius = 0.5 * num(core, "diameter")?;
        let mut layers = Vec::new();
        let mut below = (0.0, core_radius); // (helix radius, wire radius) of the layer beneath
        for l in strand["layers"].as_array().context("strand.layers")? {
            let wire_radius = 0.5 * num(l, "diameter")?;
            let radius = below.0 + below.1 + wire_radius;
            let lay_angle = match (l["pitch"].as_f64(), l["lay_angle_deg"].as_f64()) {
                (Some(p), None) => (2.0 * PI * radius / p).atan(),
                (None, Some(a)) => a.to_radians(),
                _ => bail!("a layer needs one of `pitch` and `lay_angle_deg`"),
            };
            layers.push(Layer {
                wires: l["wires"].as_u64().context("layer `wires`")? as usize,
                wire_radius,
                radius,
                lay_angle,
                youngs_modulus: num(l, "youngs_modulus")?,
            });
            below = (radius, wire_radius);
        }
        Ok(Conductor {
            core_radius,
            core_youngs_modulus: num(core, "youngs_modulus")?,
            layers,
        })
    }

    /// EA = E_c A_c + sum n E A cos^3(alpha) (N).
    pub fn axial_stiffness(&self) -> f64 {
        let core = self.core_youngs_modulus * PI * self.core_radius.powi(2);
        core + self
            .layers
            .iter()
            .map(|l| l.wires as f64 * l.wire_stiffness() * l.lay_angle.cos())
            .sum::<f64>()
    }

    /// K_min = E_c I_c + sum n E I cos(alpha) (N m^2), Papailiou's.
    pub fn k_min(&self) -> f64 {
        let inertia = |r: f64| PI * r.powi(4) / 4.0;
        self.core_youngs_modulus * inertia(self.core_radius)
            + self
                .layers
                .iter()
                .map(|l| {
                    l.wires as f64 * l.youngs_modulus * inertia(l.wire_radius) * l.lay_angle.cos()
                })
                .sum::<f64>()
    }

    /// K_max = K_min + sum n E A cos^3(alpha) R^2 / 2 (N m^2), the plane section.
    pub fn k_max(&self) -> f64 {
        self.k_min()
            + self
                .layers
                .iter()
                .map(|l| {
                    0.5 * l.wires as f64 * l.wire_stiffness() * l.lay_angle.cos() * l.radius.powi(2)
                })
                .sum::<f64>()
    }
}

/// The slip condition: which contact pressure sets a layer's friction limit (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlipCondition {
    /// Own tension only: the capstan law (Papailiou; Cardou's SC1).
    Sc1,
    /// The layers outside with their exact line load n_k / R_k.
    Accumulated,
    /// Cardou's SC5: close packing, m_j = mu.
    Sc5,
    /// Cardou's SC2: m_j = mu_j + mu_(j+1).
    Sc2,
    /// Cardou's SC3: m_j = mu_j - mu_(j+1) cos(alpha_j + alpha_(j+1)).
    Sc3,
    /// Foti's: m_j = mu_j (1 + mu_(j+1) / (mu_j + mu_(j+1))).
    Foti,
}

impl SlipCondition {
    /// Every condition, in the order of the tables.
    pub const ALL: [SlipCondition; 6] = [
        SlipCondition::Sc1,
        SlipCondition::Accumulated,
        SlipCondition::Sc5,
        SlipCondition::Sc2,
        SlipCondition::Sc3,
        SlipCondition::Foti,
    ];

    /// Short name for the tables.
    pub fn name(self) -> &'static str {
        match self {
            SlipCondition::Sc1 => "SC1 (Papailiou)",
            SlipCondition::Accumulated => "accumulated",
            SlipCondition::Sc5 => "SC5",
            SlipCondition::Sc2 => "SC2",
            SlipCondition::Sc3 => "SC3",
            SlipCondition::Foti => "Foti",
        }
    }
}

/// A classical model of one strand at one tension and friction coefficient, its friction
/// limits tabulated on the quadrature grid.
#[derive(Debug, Clone)]
pub struct Model {
    conductor: Conductor,
    k_min: f64,
    /// Per layer, per grid node theta_i = i pi / (2 INTERVALS): F_j G+_j and F_j G-_j (N).
    limit: Vec<[Vec<f64>; 2]>,
}

impl Model {
    /// The model of `conductor` under the axial tension `tension` (N) with friction `mu`.
    pub fn new(conductor: &Conductor, condition: SlipCondition, mu: f64, tension: f64) -> Self {
        let eps = tension / conductor.axial_stiffness();
        let l = &conductor.layers;
        let n = l.len();
        let force: Vec<f64> = l.iter().map(|x| x.wire_stiffness() * eps).collect();
        // The coupling matrix a (row j: lambda_j on the diagonal, c_j b_k beyond).
        let mut a = vec![vec![0.0; n]; n];
        for j in 0..n {
            let sj = l[j].lay_angle.sin();
            a[j][j] = mu * sj;
            if condition == SlipCondition::Sc1 {
                continue;
            }
            let m = match condition {
                SlipCondition::Sc2 if j + 1 < n => 2.0 * mu,
                SlipCondition::Sc3 if j + 1 < n => {
                    mu * (1.0 - (l[j].lay_angle + l[j + 1].lay_angle).cos())
                }
                SlipCondition::Foti if j + 1 < n => 1.5 * mu,
                _ => mu,
            };
            for k in j + 1..n {
                let sk2 = l[k].lay_angle.sin().powi(2);
                a[j][k] = match condition {
                    SlipCondition::Accumulated => {
                        mu * l[j].radius * l[k].wires as f64 * sk2
                            / (l[j].wires as f64 * sj * l[k].radius)
                    }
                    _ => m * l[j].wire_radius / sj * sk2 / l[k].wire_radius,
                };
            }
        }
        let h = FRAC_PI_2 / INTERVALS as f64;
        let mut limit: Vec<[Vec<f64>; 2]> = (0..n)
            .map(|_| {
                [
                    Vec::with_capacity(INTERVALS + 1),
                    Vec::with_capacity(INTERVALS + 1),
                ]
            })
            .collect();
        for (side, sign) in [(0, 1.0), (1, -1.0)] {
            let rate = |t: &[f64]| -> Vec<f64> {
                (0..n)
                    .map(|j| sign * (j..n).map(|k| a[j][k] * t[k]).sum::<f64>())
                    .collect()
            };
            let mut t = force.clone();
            for i in 0..=INTERVALS {
                for j in 0..n {
                    limit[j][side].push(sign * (t[j] - force[j]));
                }
                if i == INTERVALS {
                    break;
                }
                let k1 = rate(&t);
                let y2: Vec<f64> = (0..n).map(|j| t[j] + 0.5 * h * k1[j]).collect();
                let k2 = rate(&y2);
                let y3: Vec<f64> = (0..n).map(|j| t[j] + 0.5 * h * k2[j]).collect();
                let k3 = rate(&y3);
                let y4: Vec<f64> = (0..n).map(|j| t[j] + h * k3[j]).collect();
                let k4 = rate(&y4);
                for j in 0..n {
                    t[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
                }
            }
        }
        Model {
            conductor: conductor.clone(),
            k_min: conductor.k_min(),
            limit,
        }
    }

    /// Wire force F_j = k_j T / EA of layer `j` under the tension `tension` (N).
    #[cfg(test)]
    fn wire_force(&self, j: usize, tension: f64) -> f64 {
        self.conductor.layers[j].wire_stiffness() * tension / self.conductor.axial_stiffness()
    }

    /// The friction-limited force change F_j G_j of layer `j` at grid node `i` (N), stretched
    /// side (`side` 0) or shortened side (1).
    #[cfg(test)]
    fn limit(&self, j: usize, side: usize, i: usize) -> f64 {
        self.limit[j][side][i]
    }

    /// Bending moment on first loading to the curvature `kappa` >= 0 (N m).
    pub fn moment(&self, kappa: f64) -> f64 {
        let h = FRAC_PI_2 / INTERVALS as f64;
        let mut m = self.k_min * kappa;
        for (j, l) in self.conductor.layers.iter().enumerate() {
            let stick = l.wire_stiffness() * l.radius * kappa;
            let mut sum = 0.0;
            for i in 0..=INTERVALS {
                let s = (i as f64 * h).sin();
                let f = (stick * s).min(self.limit[j][0][i]) + (stick * s).min(self.limit[j][1][i]);
                let w = if i == 0 || i == INTERVALS {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                sum += w * s * f;
            }
            m += l.wires as f64 / PI * l.lay_angle.cos() * l.radius * sum * h / 3.0;
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cardinal-like: steel 1+6 x 3.34 mm, aluminium 12+18+24 x 3.32 mm.
    fn cardinal() -> Conductor {
        let scene = serde_json::json!({"strand": {
        "core": {"diameter": 0.00334, "youngs_modulus": 2.07e11},
        "layers": [
            {"wires": 6, "diameter": 0.00334, "pitch": 0.21, "youngs_modulus": 2.07e11},
            {"wires": 12, "diameter": 0.00332, "pitch": 0.22, "youngs_modulus": 6.8e10},
            {"wires": 18, "diameter": 0.00332, "pitch": 0.30, "youngs_modulus": 6.8e10},
            {"wires": 24, "diameter": 0.00332, "lay_angle_deg": 13.0, "youngs_modulus": 6.8e10}
        ]}});
        Conductor::from_scene_json(&scene).unwrap()
    }

    #[test]
    fn stacks_radii_and_converts_pitch() {
        let c = cardinal();
        // R_1 = 1.67 + 1.67, R_2 = R_1 + 1.67 + 1.66, then + 3.32 mm per layer.
        let r = [3.34e-3, 6.67e-3, 9.99e-3, 13.31e-3];
        for (l, r) in c.layers.iter().zip(r) {
            assert!((l.radius - r).abs() < 1e-12, "{} vs {r}", l.radius);
        }
        // P = 2 pi R / tan(alpha) back from the angle.
        let p = 2.0 * PI * c.layers[0].radius / c.layers[0].lay_angle.tan();
        assert!((p - 0.21).abs() < 1e-12);
        assert!((c.layers[3].lay_angle.to_degrees() - 13.0).abs() < 1e-12);
    }

    /// Below the smallest critical curvature every wire sticks: M = K_max kappa (Simpson's error
    /// on sin^2 at 1024 intervals is below 1e-12 of it).
    #[test]
    fn all_stick_is_k_max() {
        let c = cardinal();
        for cond in SlipCondition::ALL {
            let m = Model::new(&c, cond, 0.7, 40e3);
            let kappa = 1e-6;
            let k = m.moment(kappa) / kappa;
            assert!(
                (k / c.k_max() - 1.0).abs() < 1e-10,
                "{}: {k} vs {}",
                cond.name(),
                c.k_max()
            );
        }
    }

    /// Past the largest critical curvature every wire slips: the tangent is K_min, and for SC1
    /// the intercept is the closed-form friction moment sum_j (n_j / pi) cos(alpha_j) R_j F_j
    /// 2 lambda_j cosh(lambda_j pi / 2) / (1 + lambda_j^2) (int_0^{pi/2} sin(phi) (exp(lambda
    /// phi) - exp(-lambda phi)) dphi).
    #[test]
    fn all_slip_is_k_min_and_the_sc1_friction_moment() {
        let c = cardinal();
        let (mu, tension) = (0.7, 40e3);
        let m = Model::new(&c, SlipCondition::Sc1, mu, tension);
        let (k1, k2) = (50.0, 60.0);
        let slope = (m.moment(k2) - m.moment(k1)) / (k2 - k1);
        assert!(
            (slope / c.k_min() - 1.0).abs() < 1e-9,
            "{slope} vs {}",
            c.k_min()
        );
        let closed: f64 = c
            .layers
            .iter()
            .enumerate()
            .map(|(j, l)| {
                let lam = mu * l.lay_angle.sin();
                l.wires as f64 / PI
                    * l.lay_angle.cos()
                    * l.radius
                    * m.wire_force(j, tension)
                    * 2.0
                    * lam
                    * (lam * FRAC_PI_2).cosh()
                    / (1.0 + lam * lam)
            })
            .sum();
        let intercept = m.moment(k1) - c.k_min() * k1;
        // Simpson on a smooth integrand at 1024 intervals: error far below 1e-9.
        assert!(
            (intercept / closed - 1.0).abs() < 1e-9,
            "{intercept} vs {closed}"
        );
    }

    /// The outermost layer has nothing outside it: its limit is the capstan law under every
    /// condition; the steel layer is pressed harder by the accumulated forms than by SC1 (by half
    /// as much again at least, Cardinal's three aluminium layers pressing it).
    #[test]
    fn outer_layer_is_capstan_inner_layers_gain() {
        let c = cardinal();
        let sc1 = Model::new(&c, SlipCondition::Sc1, 0.7, 40e3);
        let i = INTERVALS;
        for cond in SlipCondition::ALL {
            let m = Model::new(&c, cond, 0.7, 40e3);
            let lam = 0.7 * c.layers[3].lay_angle.sin();
            let f = m.wire_force(3, 40e3);
            let exact = f * ((lam * FRAC_PI_2).exp() - 1.0);
            assert!((m.limit(3, 0, i) / exact - 1.0).abs() < 1e-12);
            let exact = f * (1.0 - (-lam * FRAC_PI_2).exp());
            assert!((m.limit(3, 1, i) / exact - 1.0).abs() < 1e-12);
            // SC3's coupling carries 1 - cos(alpha_j + alpha_(j+1)), a few percent of mu.
            let gain = match cond {
                SlipCondition::Sc1 => continue,
                SlipCondition::Sc3 => 1.0,
                _ => 1.5,
            };
            assert!(
                m.limit(0, 0, i) > gain * sc1.limit(0, 0, i),
                "{}",
                cond.name()
            );
        }
    }
}
