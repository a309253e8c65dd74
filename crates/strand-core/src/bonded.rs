//! Bending stiffness of a bonded (all-stick) strand: the wires as rods bonded to the core.
//!
//! The plane-section bound K_max = K_min + (m/2) eta E_w A_w R_w^2 (eq. (22a)) takes every
//! helical wire's axial strain from the rigid rotation of the strand's cross-section. A real
//! wire is bonded to the core only along its contact line, r_w from its own axis and r_c from
//! the core's, and its axial force varies along it (as sin(phi)), so the bond carries a
//! tangential traction that varies as cos(phi). That traction is eccentric on both bodies:
//!
//! * it tilts the wire's section (against the wire's shear stiffness kappa G A_w and, as the
//!   tilt varies along the wire, its bending stiffness) and twists it (the circumferential
//!   part; with the helix's torsion a twisted wire rolls on its contact line, which again
//!   shifts its axis against the line), so the wire's axis need not follow the plane section;
//! * it loads the core with a constant distributed moment about the axis normal to the plane
//!   of bending, carried by a uniform shear force in the core and a uniform tilt of its
//!   sections against kappa G A_c, which moves the contact line (at r_c cos(phi) from that
//!   axis) in phase with the traction.
//!
//! Both are compliances in series with the wire's axial stiffness at the wavenumber
//! `k = dphi/ds = sin(alpha)/R_w` of its phase, so the bonded strand is softer than K_max.
//!
//! Model: the linear, periodic solution of the Cosserat (Timoshenko) rod equations of the
//! helical wires (axial E A, shear kappa G A, torsion G J, bending E I, kappa = 6 (1 + nu) /
//! (7 + 6 nu)), with the helix's curvature sin^2(alpha)/R_w and torsion sin(alpha) cos(alpha)/R_w
//! in the wire's frame (tangent t, outward normal e_r to the core, b = t x e_r), bonded to a
//! Timoshenko core with rigid sections. The displacement and rotation of each wire are the
//! rigid rotation of the strand's section (plane sections, bending curvature `kappa` about
//! z) plus a perturbation; the core's perturbation is a uniform rotation of its sections
//! (shear tilt) about the two transverse axes. The strains of a perturbation (v, theta) are
//! `Gamma = v' + t x theta`, `K = theta'`, with `(.)' = d/ds` of the frame components plus
//! `omega x (.)`, `omega = -tau t - kappa_w b` the frame's Darboux vector. Along a helix those
//! coefficients are constant and the plane-section loading is a first harmonic of the phase,
//! so the periodic solution is exactly a first harmonic of the phase in the frame components
//! (cos phi, sin phi for six fields), and for `m >= 3` evenly spaced wires the core sees only
//! constants. Minimising the energy per unit strand length (wires' energy per unit wire
//! length times m / cos(alpha), plus the core's shear energy) over these 14 amplitudes, with
//! the contact line bonded exactly or by springs, gives the stiffness `2 U / kappa^2`.
//!
//! # Layers on layers
//!
//! Each layer has its own stick factor, that of its interface with the layer beneath
//! ([`interface_bonded_stiffness`]): the same rod model with the layer beneath in the core's
//! place. For the first layer that is the core itself. For layer j > 1 the wires and core
//! beneath, all sticking, move as one body with plane sections: the model's rigid-section core,
//! of bond radius R_j - r_wj (the surface the layer lies on), with the shear stiffness kappa G A
//! summed over the core and the wires beneath (their sections normal to the strand, A / cos
//! alpha, taken as A: within cos(alpha) > 0.97 for lay angles below 14 deg) and the bending
//! stiffness E I summed likewise (it cancels in the stick factor). On a layer laid in the other
//! direction the contact is at crossing points, not along a line; they come every 9-18 mm along
//! a conductor's wire (`../shared` references), short against the wavelength of the bond's
//! traction, a pitch of wire length (0.2-0.4 m), so a bond smeared along the wire carries the
//! same traction. What the rigid bond leaves out there is the tangential compliance of each
//! crossing (Mindlin), which softens the interface: for a crossing interface this factor is an
//! upper bound.
//!
//! # The strand as one body
//!
//! The per-interface factor takes the layers beneath as one body with rigid sections. The
//! wires of a layer between two others are not: held on their crowns by the layer outside and
//! on their feet by the layer beneath (or the core), they roll (twist about their own axes,
//! their axes shifting by half the relative motion) and tilt their sections, like the
//! rollers of a bearing, against only their own torsion and shear stiffness, so the outer
//! layer's traction reaches the core through a compliant layer. [`strand_bonded_stiffness`]
//! solves every layer's rods at once: 12 amplitudes per layer and the core's two tilts, each
//! layer bonded to the one beneath where they touch (the bottom of its wire on the crown of
//! the wire beneath, both points' displacements including their section's rotation times
//! r_w), smeared along the wire as the single-layer model smears the line (crossings come
//! every 13.5 mm along the 1+6+12 strand's outer wire against the traction's wavelength of a
//! pitch, 182 mm). The bond's three components, in the strand's local axes (e_x, e_r,
//! e_theta) at the angle theta where the two wires touch, are first harmonics of theta, so
//! their cos and sin amplitudes vanish. A left-laid layer is the mirror image (z -> -z) of a
//! right-laid one at the phase pi - theta, which keeps the bending and reverses e_theta.
//! On the 1+6+12 steel strand the one-body value is 0.364 K_max where the per-interface
//! factors give 0.928; the fine model agrees with the former (`cargo xtask bonded
//! --multilayer`).
//!
//! Checks (tests): with the wires free to slide on the core the model gives Costello's
//! frictionless stiffness E_c I_c + m E_w I_w cos(alpha) 2 / (2 + nu sin^2(alpha)); with the
//! bond on the wires' axes and a shear-rigid core it gives that base plus the plane-section
//! stick stiffness exactly. The fine model (`strand bend`) converges to it: see
//! `cargo xtask bonded`.

use std::f64::consts::PI;

use crate::geometry::Strand;
use crate::wire::WireSpec;

/// Which stick stiffness the helical wires have in the stick/slip section laws
/// (`section.stick_stiffness`).
///
/// The default is [`StickStiffness::Bonded`]: the plane-section K_stick of eq. (22a) assumes
/// that each wire's axial strain follows the rigid rotation of the strand's section, which a
/// wire held to the core only along its contact line cannot do (module docs). The rod model
/// of the bonded strand gives the share of K_stick that the bond delivers from the strand's
/// geometry and materials alone (no fitted constant), and the fine model converges to that
/// model (`cargo xtask bonded`); the plane section's K_max is an upper bound the strand does
/// not reach (Table 1: stick factor 0.76). [`StickStiffness::PlaneSection`] keeps the
/// paper's law, for the scenes that reproduce it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StickStiffness {
    /// The plane-section K_stick_i = eta E_w A_w (R_w sin phi_i)^2 of eq. (22a) times the rod
    /// model's stick factor ([`BondedStiffness::stick_factor`], rigid bond on the touching
    /// surfaces). The default.
    #[default]
    Bonded,
    /// The plane-section K_stick_i of eq. (22a), as the paper (all-stick stiffness K_max).
    PlaneSection,
    /// Each layer's share of the stick stiffness of the strand as one body
    /// ([`strand_layer_stick_stiffness`], rigid bonds), over its plane-section value: the
    /// layers' stick stiffnesses sum to the one-body `bonded - free`. For one layer, or a
    /// layer of fewer than 3 wires (which the one-body model does not carry), `bonded`.
    OneBody,
}

impl StickStiffness {
    /// Every form, in the order of the documentation.
    pub const ALL: [StickStiffness; 3] = [
        StickStiffness::Bonded,
        StickStiffness::PlaneSection,
        StickStiffness::OneBody,
    ];

    /// Name as used in scene files (`section.stick_stiffness`).
    pub fn name(self) -> &'static str {
        match self {
            StickStiffness::Bonded => "bonded",
            StickStiffness::PlaneSection => "plane_section",
            StickStiffness::OneBody => "one_body",
        }
    }

    /// The form named `name` (as in scene files), if any.
    pub fn from_name(name: &str) -> Option<StickStiffness> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Factor on the plane-section stick stiffness of the wires of `strand`'s layer `layer`
    /// (0-based) (-): 1 for `plane_section`; for `bonded` the rod model's
    /// [`BondedStiffness::stick_factor`] of the layer's interface with the layer beneath
    /// ([`interface_bonded_stiffness`]), with a rigid bond on the touching surfaces (1 for a
    /// layer the strand does not have). With one or two wires
    /// the model cannot carry the core's tilt, which then varies along the strand, so their
    /// factor takes the core rigid in shear and keeps only the wires' own compliance (an
    /// upper bound on the factor). For `one_body` on strands of two or more layers of at
    /// least 3 wires each, the layer's share of the one-body stick stiffness over its
    /// plane-section value (`one_body_factors`); otherwise as `bonded`.
    pub fn factor(self, strand: &Strand, layer: usize) -> f64 {
        match self {
            StickStiffness::PlaneSection => 1.0,
            StickStiffness::OneBody
                if strand.layers().len() > 1 && strand.layers().get(layer).is_some() =>
            {
                match one_body_factors(strand) {
                    Some(f) => f[layer],
                    None => StickStiffness::Bonded.factor(strand, layer),
                }
            }
            StickStiffness::OneBody => StickStiffness::Bonded.factor(strand, layer),
            StickStiffness::Bonded => {
                let Some(h) = strand.layers().get(layer) else {
                    return 1.0;
                };
                let options = BondedOptions {
                    core_shear: if h.wires() < 3 { f64::INFINITY } else { 1.0 },
                    ..Default::default()
                };
                interface_bonded_stiffness(strand, layer, &options)
                    .map_or(1.0, |b| b.stick_factor())
            }
        }
    }
}

/// The `one_body` stick factors of every layer of `strand` (-): each layer's share
/// ([`strand_layer_stick_stiffness`], rigid bonds) over its plane-section stick stiffness.
/// A share can be negative (a stiff layer laid on a compliant one drags the wires beneath
/// against their plane-section strain), which no slider spring can carry; then every layer
/// takes the same factor, the one-body stick stiffness over the plane-section one, which keeps
/// the all-stick total. `None` where the one-body model is `None`.
fn one_body_factors(strand: &Strand) -> Option<Vec<f64>> {
    let shares = strand_layer_stick_stiffness(strand, &BondedOptions::default())?;
    let plane: Vec<f64> = strand
        .layers()
        .iter()
        .map(|l| strand.layer_plane_section_stick(l))
        .collect();
    if shares.iter().all(|&k| k > 0.0) {
        Some(shares.iter().zip(&plane).map(|(k, p)| k / p).collect())
    } else {
        let even = shares.iter().sum::<f64>() / plane.iter().sum::<f64>();
        Some(vec![even; plane.len()])
    }
}

impl std::fmt::Display for StickStiffness {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Idealisations of the bonded-strand model, to separate its compliances (all `1.0` and
/// `None`: the physical strand with a rigid bond on the touching surfaces).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BondedOptions {
    /// Factor on the helical wires' shear stiffness kappa G A_w (-).
    pub wire_shear: f64,
    /// Factor on the helical wires' torsion stiffness G J_w (-).
    pub wire_torsion: f64,
    /// Factor on the helical wires' bending stiffness E I_w (-).
    pub wire_bending: f64,
    /// Factor on the core's shear stiffness kappa G A_c (-); infinite: the core's sections
    /// do not tilt.
    pub core_shear: f64,
    /// Tangential stiffness of the bond per unit wire length (N/m^2), along the wire and
    /// across it; `None`: rigid. Zero: the wires slide freely on the core.
    pub tangential_stiffness: Option<f64>,
    /// Normal stiffness of the contact per unit wire length (N/m^2); `None`: rigid.
    pub normal_stiffness: Option<f64>,
    /// Distance of the bond line from the core's axis (m); `None`: r_c, the touching
    /// surfaces. `Some(R_w)` puts it on the wires' axes (no eccentricity on the wires).
    pub contact_radius: Option<f64>,
}

impl Default for BondedOptions {
    fn default() -> Self {
        Self {
            wire_shear: 1.0,
            wire_torsion: 1.0,
            wire_bending: 1.0,
            core_shear: 1.0,
            tangential_stiffness: None,
            normal_stiffness: None,
            contact_radius: None,
        }
    }
}

/// Bending stiffnesses of a strand from the rod model (N m^2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BondedStiffness {
    /// Every wire bonded to the core: the initial (all-stick) stiffness.
    pub bonded: f64,
    /// Every wire free to slide along and around the core (normal contact kept): the
    /// frictionless stiffness (Costello's).
    pub free: f64,
    /// The plane-section stick stiffness sum_i eta E_w A_w (R_w sin phi_i)^2 =
    /// (m/2) eta E_w A_w R_w^2 (eq. (22a)).
    pub plane_section_stick: f64,
}

impl BondedStiffness {
    /// Share of the plane-section stick stiffness that the bond delivers,
    /// (bonded - free) / plane_section_stick (-): the factor on each wire's K_stick.
    pub fn stick_factor(&self) -> f64 {
        (self.bonded - self.free) / self.plane_section_stick
    }
}

/// Bonded and free bending stiffness of `strand`'s first layer on the core under `options`
/// ([`interface_bonded_stiffness`] of layer 0).
pub fn bonded_stiffness(strand: &Strand, options: &BondedOptions) -> Option<BondedStiffness> {
    interface_bonded_stiffness(strand, 0, options)
}

/// Bonded and free bending stiffness of `strand`'s layer `layer` (0-based) on the layer
/// beneath under `options` (module docs, "Layers on layers"); `None` for a layer the strand
/// does not have, and for one or two wires unless the core's shear is rigid (`core_shear`
/// infinite): their tractions then load the core with a tilt that varies along the strand
/// (the second harmonic of the phase), which this model leaves out.
pub fn interface_bonded_stiffness(
    strand: &Strand,
    layer: usize,
    options: &BondedOptions,
) -> Option<BondedStiffness> {
    let index = layer;
    let layer = *strand.layers().get(index)?;
    if layer.wires() < 3 && options.core_shear.is_finite() {
        return None;
    }
    let rod = Rods::new(strand, index, options);
    let free = rod.stiffness(Some(0.0), options.normal_stiffness);
    let bonded = rod.stiffness(options.tangential_stiffness, options.normal_stiffness);
    Some(BondedStiffness {
        bonded,
        free,
        plane_section_stick: 0.5
            * layer.wires() as f64
            * layer.wire_axial_stiffness()
            * layer.radius.powi(2),
    })
}

/// The rod model's constants (SI).
struct Rods {
    wires: f64,
    alpha: f64,
    helix_radius: f64,
    contact_radius: f64,
    /// Phase wavenumber along the wire sin(alpha)/R_w (1/m).
    k: f64,
    /// Helix curvature and torsion (1/m).
    curvature: f64,
    torsion: f64,
    /// E A, kappa G A, kappa G A, G J, E I, E I of a helical wire.
    wire: [f64; 6],
    core_shear: f64,
    core_bending: f64,
}

/// Unknown amplitudes: (cos, sin) of v_t, v_r, v_b, theta_t, theta_r, theta_b, then the
/// core's section rotations about y and z.
const N: usize = 14;
/// Quadrature stations over the phase: exact for the products of first harmonics.
const STATIONS: usize = 8;

/// A linear form in the unknowns plus a constant per unit curvature.
#[derive(Clone, Copy)]
struct Form {
    q: [f64; N],
    c: f64,
}

impl Form {
    fn zero() -> Self {
        Self {
            q: [0.0; N],
            c: 0.0,
        }
    }

    fn add(mut self, f: f64, o: &Form) -> Self {
        for (a, b) in self.q.iter_mut().zip(&o.q) {
            *a += f * b;
        }
        self.c += f * o.c;
        self
    }
}

impl Rods {
    /// The rod model of `strand`'s layer `index` on what lies beneath it (module docs).
    fn new(strand: &Strand, index: usize, o: &BondedOptions) -> Self {
        let layer = &strand.layers()[index];
        let w = &layer.spec.wire;
        let c = strand.core();
        let alpha = layer.lay_angle();
        let r = layer.radius;
        let ks = |nu: f64| 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);
        let (e, g, nu) = (
            w.material.youngs_modulus,
            w.material.shear_modulus(),
            w.material.poisson_ratio,
        );
        let k = alpha.sin() / r;
        // The core, or the core and the layers beneath as one rigid-section body.
        let shear =
            |w: &WireSpec| ks(w.material.poisson_ratio) * w.material.shear_modulus() * w.area();
        let bending = |w: &WireSpec| w.material.youngs_modulus * w.inertia();
        let (bond, core_shear, core_bending) = if index == 0 {
            (
                c.radius(),
                o.core_shear * ks(c.material.poisson_ratio) * c.material.shear_modulus() * c.area(),
                bending(c),
            )
        } else {
            let inner = &strand.layers()[..index];
            let sum = |f: &dyn Fn(&WireSpec) -> f64| {
                inner
                    .iter()
                    .fold(f(c), |s, l| s + l.wires() as f64 * f(&l.spec.wire))
            };
            (
                layer.radius - w.radius(),
                o.core_shear * sum(&shear),
                sum(&bending),
            )
        };
        Self {
            wires: layer.wires() as f64,
            alpha,
            helix_radius: r,
            contact_radius: o.contact_radius.unwrap_or(bond),
            k,
            curvature: k * alpha.sin(),
            torsion: k * alpha.cos(),
            wire: [
                e * w.area(),
                o.wire_shear * ks(nu) * g * w.area(),
                o.wire_shear * ks(nu) * g * w.area(),
                o.wire_torsion * g * w.polar_inertia(),
                o.wire_bending * e * w.inertia(),
                o.wire_bending * e * w.inertia(),
            ],
            core_shear,
            core_bending,
        }
    }

    /// Strains (axial, two shears, twist, two bendings) and bond gaps (along t, e_r, b)
    /// at phase `phi` per unit curvature, as linear forms in the unknowns.
    fn fields(&self, phi: f64) -> ([Form; 6], [Form; 3]) {
        let (c, s) = (phi.cos(), phi.sin());
        let (ca, sa) = (self.alpha.cos(), self.alpha.sin());
        // Value and s-derivative of field f (0..6).
        let val = |f: usize| {
            let mut x = Form::zero();
            x.q[2 * f] = c;
            x.q[2 * f + 1] = s;
            x
        };
        let der = |f: usize| {
            let mut x = Form::zero();
            x.q[2 * f] = -self.k * s;
            x.q[2 * f + 1] = self.k * c;
            x
        };
        let base = |v: f64| Form { q: [0.0; N], c: v };
        let (kw, tw) = (self.curvature, self.torsion);
        let r = self.helix_radius;
        let (vt, vr, vb, tt, tr, tb) = (0, 1, 2, 3, 4, 5);
        // Gamma = v' + t x theta and K = theta' of the perturbation, plus the rigid
        // rotation of the strand's section (Gamma0 = -kappa cos(alpha) y x_hat,
        // K0 = kappa cos(alpha) z_hat, y = R_w sin(phi)).
        let strains = [
            der(vt).add(kw, &val(vr)).add(1.0, &base(-r * ca * ca * s)),
            der(vr)
                .add(-kw, &val(vt))
                .add(tw, &val(vb))
                .add(-1.0, &val(tb)),
            der(vb)
                .add(-tw, &val(vr))
                .add(1.0, &val(tr))
                .add(1.0, &base(-r * ca * sa * s)),
            der(tt).add(kw, &val(tr)).add(1.0, &base(-ca * sa * s)),
            der(tr)
                .add(-kw, &val(tt))
                .add(tw, &val(tb))
                .add(1.0, &base(ca * c)),
            der(tb).add(-tw, &val(tr)).add(1.0, &base(ca * ca * s)),
        ];
        // The bond line, rho from the core's axis: the wire's point R_w - rho inward of its
        // axis against the core's point, moved axially by the core's tilt (theta_y z -
        // theta_z y at (y, z) = rho (sin phi, cos phi)).
        let arm = self.helix_radius - self.contact_radius;
        let mut tilt = Form::zero();
        tilt.q[12] = self.contact_radius * c;
        tilt.q[13] = -self.contact_radius * s;
        let gaps = [
            val(vt).add(arm, &val(tb)).add(-ca, &tilt),
            val(vr),
            val(vb).add(-arm, &val(tt)).add(-sa, &tilt),
        ];
        (strains, gaps)
    }

    /// Bending stiffness (N m^2) with the bond's tangential and normal stiffness per unit
    /// wire length (`None`: rigid).
    fn stiffness(&self, tangential: Option<f64>, normal: Option<f64>) -> f64 {
        // Energy per unit strand length at unit curvature: 1/2 q^T A q + b^T q + c0.
        let mut a = [[0.0; N]; N];
        let mut b = [0.0; N];
        let mut c0 = 0.0;
        let weight = self.wires / self.alpha.cos() / STATIONS as f64;
        let springs = [tangential, normal, tangential];
        // Rigid bonds: the cos and sin amplitudes of each rigid gap vanish.
        let mut constraints: Vec<[f64; N]> = Vec::new();
        let mut amplitudes = [[[0.0; N]; 2]; 3];
        for j in 0..STATIONS {
            let phi = 2.0 * PI * (j as f64 + 0.5) / STATIONS as f64;
            let (strains, gaps) = self.fields(phi);
            let mut add = |f: &Form, stiffness: f64| {
                for (r, row) in a.iter_mut().enumerate() {
                    for (c, v) in row.iter_mut().enumerate() {
                        *v += weight * stiffness * f.q[r] * f.q[c];
                    }
                    b[r] += weight * stiffness * f.q[r] * f.c;
                }
                c0 += 0.5 * weight * stiffness * f.c * f.c;
            };
            for (f, &k) in strains.iter().zip(&self.wire) {
                add(f, k);
            }
            for (g, (spring, amp)) in gaps.iter().zip(springs.iter().zip(&mut amplitudes)) {
                match spring {
                    Some(k) => add(g, *k),
                    None => {
                        for (h, trig) in [phi.cos(), phi.sin()].into_iter().enumerate() {
                            for (x, y) in amp[h].iter_mut().zip(&g.q) {
                                *x += trig * y;
                            }
                        }
                    }
                }
            }
        }
        for (g, spring) in amplitudes.iter().zip(&springs) {
            if spring.is_none() {
                constraints.extend(g.iter().copied());
            }
        }
        if self.core_shear.is_finite() {
            a[12][12] += self.core_shear;
            a[13][13] += self.core_shear;
        } else {
            for i in [12, 13] {
                let mut row = [0.0; N];
                row[i] = 1.0;
                constraints.push(row);
            }
        }
        // Stationarity with the constraints' multipliers: [A G^T; G 0] [q; l] = [-b; 0].
        let n = N + constraints.len();
        let mut m = vec![vec![0.0; n + 1]; n];
        for r in 0..N {
            m[r][..N].copy_from_slice(&a[r]);
            m[r][n] = -b[r];
        }
        for (i, g) in constraints.iter().enumerate() {
            for c in 0..N {
                m[N + i][c] = g[c];
                m[c][N + i] = g[c];
            }
        }
        let x = solve(m);
        // At the minimum q^T A q = -b^T q, so U = c0 + b^T q / 2.
        let u = c0 + 0.5 * b.iter().zip(&x).map(|(b, q)| b * q).sum::<f64>();
        2.0 * u + self.core_bending
    }
}

/// Bonded and free bending stiffness of the whole strand with every layer bonded to the
/// layer beneath it and the first to the core, all layers' wires as rods at once (module
/// docs, "The strand as one body"); `None` for a strand with no layer or a layer of fewer
/// than 3 wires. `options` apply to every layer (wire factors) and interface (contact
/// stiffnesses per unit length of the outer wire); `contact_radius` applies to the first
/// layer's bond on the core only. For a `1+m` strand this is [`bonded_stiffness`].
pub fn strand_bonded_stiffness(
    strand: &Strand,
    options: &BondedOptions,
) -> Option<BondedStiffness> {
    let layers = strand.layers();
    if layers.is_empty() || layers.iter().any(|l| l.wires() < 3) {
        return None;
    }
    let rods: Vec<Rods> = (0..layers.len())
        .map(|j| Rods::new(strand, j, options))
        .collect();
    let stack = Stack {
        rods,
        directions: layers.iter().map(|l| l.direction().sign()).collect(),
        radii: layers.iter().map(|l| l.spec.wire.radius()).collect(),
    };
    let free = stack.stiffness(Some(0.0), options.normal_stiffness).0;
    let bonded = stack
        .stiffness(options.tangential_stiffness, options.normal_stiffness)
        .0;
    Some(BondedStiffness {
        bonded,
        free,
        plane_section_stick: layers
            .iter()
            .map(|l| strand.layer_plane_section_stick(l))
            .sum(),
    })
}

/// Each layer's stick stiffness in the strand as one body (N m^2, one per layer, inner
/// first): the bending moment per unit curvature that the layer's wires carry with every
/// interface bonded, less the one they carry with every wire free to slide
/// ([`strand_bonded_stiffness`] under `options`; `None` where that is `None`).
///
/// The moment of the strand is `dU/dkappa`; with the perturbation at its minimum, only the
/// explicit dependence counts (the envelope theorem), and that lies in the wires' strains
/// alone (the plane section's field: axial, shear, twist and bending of each wire; the bond
/// and the core's tilt carry none). So the moment splits exactly into the layers' shares
/// `sum_i k_i gamma_i gamma0_i` (`gamma_i` a wire strain, `gamma0_i` its plane-section part,
/// both per unit curvature, `k_i` its stiffness) plus the core's E I, and the shares of the
/// bonded strand less those of the free one sum to its stick stiffness `bonded - free`. A
/// layer's share is mostly its wires' axial forces times their arm (for rigid-section wires,
/// bonded on their axes, exactly the plane-section `(m/2) eta E_w A_w R_w^2`); the change of
/// the wires' own bending and twisting moments between bond and free sliding is the rest. For
/// one layer it is `bonded - free` of [`bonded_stiffness`].
pub fn strand_layer_stick_stiffness(strand: &Strand, options: &BondedOptions) -> Option<Vec<f64>> {
    let layers = strand.layers();
    if layers.is_empty() || layers.iter().any(|l| l.wires() < 3) {
        return None;
    }
    let stack = Stack {
        rods: (0..layers.len())
            .map(|j| Rods::new(strand, j, options))
            .collect(),
        directions: layers.iter().map(|l| l.direction().sign()).collect(),
        radii: layers.iter().map(|l| l.spec.wire.radius()).collect(),
    };
    let free = stack.stiffness(Some(0.0), options.normal_stiffness).1;
    let bonded = stack
        .stiffness(options.tangential_stiffness, options.normal_stiffness)
        .1;
    Some(bonded.iter().zip(&free).map(|(b, f)| b - f).collect())
}

/// The rod models of every layer of a strand, coupled at their interfaces.
struct Stack {
    rods: Vec<Rods>,
    /// Lay direction of each layer (+1 right, -1 left).
    directions: Vec<f64>,
    /// Wire radius r_w of each layer (m).
    radii: Vec<f64>,
}

impl Stack {
    /// Unknowns: 12 amplitudes per layer, then the core's two section rotations.
    fn unknowns(&self) -> usize {
        12 * self.rods.len() + 2
    }

    /// A layer's form in the stack's unknowns.
    fn place(&self, layer: usize, f: &Form) -> Vec<f64> {
        let mut q = vec![0.0; self.unknowns()];
        q[12 * layer..12 * layer + 12].copy_from_slice(&f.q[..12]);
        let core = 12 * self.rods.len();
        q[core] = f.q[12];
        q[core + 1] = f.q[13];
        q
    }

    /// Displacement of the surface point of layer `layer`'s wire at the strand angle `theta`,
    /// `offset` (m) outward along e_r from its axis, per unit curvature, in the strand's local
    /// components (e_x, e_r, e_theta). A left-laid layer is the mirror image (z -> -z) of a
    /// right-laid one at the phase pi - theta: its rod model runs there and the e_theta
    /// component changes sign.
    fn surface(&self, layer: usize, theta: f64, offset: f64) -> [Vec<f64>; 3] {
        let rod = &self.rods[layer];
        let mirrored = self.directions[layer] < 0.0;
        let phi = if mirrored { PI - theta } else { theta };
        let (c, s) = (phi.cos(), phi.sin());
        let val = |f: usize| {
            let mut x = Form::zero();
            x.q[2 * f] = c;
            x.q[2 * f + 1] = s;
            x
        };
        let (ca, sa) = (rod.alpha.cos(), rod.alpha.sin());
        // Along t and b: v_t - offset theta_b, v_b + offset theta_t.
        let along_t = val(0).add(-offset, &val(5));
        let along_b = val(2).add(offset, &val(3));
        // t = cos(alpha) e_x + sin(alpha) e_theta, b = sin(alpha) e_x - cos(alpha) e_theta.
        let x = Form::zero().add(ca, &along_t).add(sa, &along_b);
        let r = val(1);
        let sign = if mirrored { -1.0 } else { 1.0 };
        let th = Form::zero()
            .add(sign * sa, &along_t)
            .add(-sign * ca, &along_b);
        [
            self.place(layer, &x),
            self.place(layer, &r),
            self.place(layer, &th),
        ]
    }

    /// Bending stiffness (N m^2) with the bonds' tangential and normal stiffness per unit
    /// length of the outer wire of each interface (`None`: rigid), and each layer's share of
    /// it ([`strand_layer_stick_stiffness`]; the shares and the core's E I sum to it).
    fn stiffness(&self, tangential: Option<f64>, normal: Option<f64>) -> (f64, Vec<f64>) {
        let n = self.unknowns();
        let mut a = vec![vec![0.0; n]; n];
        let mut b = vec![0.0; n];
        let mut c0 = 0.0;
        let mut add = |q: &[f64], constant: f64, k: f64| {
            for (r, row) in a.iter_mut().enumerate() {
                if q[r] == 0.0 {
                    continue;
                }
                for (c, v) in row.iter_mut().enumerate() {
                    *v += k * q[r] * q[c];
                }
                b[r] += k * q[r] * constant;
            }
            c0 += 0.5 * k * constant * constant;
        };
        let springs = [tangential, normal, tangential];
        let mut constraints: Vec<Vec<f64>> = Vec::new();
        for (j, rod) in self.rods.iter().enumerate() {
            let weight = rod.wires / rod.alpha.cos() / STATIONS as f64;
            // Amplitudes of the rigid gaps of this layer's interface: (component, cos/sin).
            let mut amplitudes = vec![[vec![0.0; n], vec![0.0; n]]; 3];
            for i in 0..STATIONS {
                let theta = 2.0 * PI * (i as f64 + 0.5) / STATIONS as f64;
                let (strains, core_gaps) = rod.fields(theta);
                for (f, &k) in strains.iter().zip(&rod.wire) {
                    add(&self.place(j, f), f.c, weight * k);
                }
                // Layer 0 on the core (its own gaps, wire frame); layer j on layer j - 1
                // (the bottom of its wire against the top of the wire beneath).
                let gaps: Vec<Vec<f64>> = if j == 0 {
                    core_gaps.iter().map(|g| self.place(0, g)).collect()
                } else {
                    let outer = self.surface(j, theta, -self.radii[j]);
                    let inner = self.surface(j - 1, theta, self.radii[j - 1]);
                    outer
                        .iter()
                        .zip(&inner)
                        .map(|(o, i)| o.iter().zip(i).map(|(o, i)| o - i).collect())
                        .collect()
                };
                for ((g, spring), amp) in gaps.iter().zip(&springs).zip(&mut amplitudes) {
                    match spring {
                        Some(k) => add(g, 0.0, weight * k),
                        None => {
                            for (h, trig) in [theta.cos(), theta.sin()].into_iter().enumerate() {
                                for (x, y) in amp[h].iter_mut().zip(g) {
                                    *x += trig * y;
                                }
                            }
                        }
                    }
                }
            }
            for (amp, spring) in amplitudes.into_iter().zip(&springs) {
                if spring.is_none() {
                    constraints.extend(amp);
                }
            }
        }
        let core = 12 * self.rods.len();
        let rod = &self.rods[0];
        if rod.core_shear.is_finite() {
            a[core][core] += rod.core_shear;
            a[core + 1][core + 1] += rod.core_shear;
        } else {
            for i in [core, core + 1] {
                let mut row = vec![0.0; n];
                row[i] = 1.0;
                constraints.push(row);
            }
        }
        // Drop constraint rows that repeat others (a left-laid layer's mirrored phases make
        // some of the sampled amplitudes identical up to sign).
        let constraints = independent(constraints);
        let size = n + constraints.len();
        let mut m = vec![vec![0.0; size + 1]; size];
        for r in 0..n {
            m[r][..n].copy_from_slice(&a[r]);
            m[r][size] = -b[r];
        }
        for (i, g) in constraints.iter().enumerate() {
            for c in 0..n {
                m[n + i][c] = g[c];
                m[c][n + i] = g[c];
            }
        }
        let x = solve(m);
        let u = c0 + 0.5 * b.iter().zip(&x).map(|(b, q)| b * q).sum::<f64>();
        let shares = self
            .rods
            .iter()
            .enumerate()
            .map(|(j, rod)| {
                let weight = rod.wires / rod.alpha.cos() / STATIONS as f64;
                (0..STATIONS)
                    .map(|i| {
                        let theta = 2.0 * PI * (i as f64 + 0.5) / STATIONS as f64;
                        let (strains, _) = rod.fields(theta);
                        strains
                            .iter()
                            .zip(&rod.wire)
                            .map(|(f, &k)| {
                                let q = self.place(j, f);
                                let strain =
                                    f.c + q.iter().zip(&x).map(|(a, b)| a * b).sum::<f64>();
                                weight * k * strain * f.c
                            })
                            .sum::<f64>()
                    })
                    .sum()
            })
            .collect();
        (2.0 * u + rod.core_bending, shares)
    }
}

/// The rows of `rows` that are linearly independent of the ones kept before them (Gram-
/// Schmidt with a relative tolerance of 1e-10).
fn independent(rows: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut kept = Vec::new();
    for row in rows {
        let norm = row.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm == 0.0 {
            continue;
        }
        let mut r = row.clone();
        for e in &basis {
            let d: f64 = r.iter().zip(e).map(|(a, b)| a * b).sum();
            for (x, y) in r.iter_mut().zip(e) {
                *x -= d * y;
            }
        }
        let rest = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        if rest > 1e-10 * norm {
            basis.push(r.iter().map(|x| x / rest).collect());
            kept.push(row);
        }
    }
    kept
}

/// Solves the augmented system `m = [M | r]` by Gaussian elimination with partial pivoting.
fn solve(mut m: Vec<Vec<f64>>) -> Vec<f64> {
    let n = m.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
            .expect("a row");
        m.swap(c, p);
        let pivot = m[c][c];
        assert!(pivot != 0.0, "singular bonded-strand system");
        for r in c + 1..n {
            let f = m[r][c] / pivot;
            if f != 0.0 {
                for k in c..=n {
                    m[r][k] -= f * m[c][k];
                }
            }
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| m[r][k] * x[k]).sum();
        x[r] = (m[r][n] - s) / m[r][r];
    }
    x
}
