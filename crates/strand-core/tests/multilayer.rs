//! Property tests of the section laws of strands with several layers (1 to 4 helical layers of
//! random wire counts that fit, diameters, materials, lay angles, lay directions and phases):
//! analytic tangents against finite differences, the energy gradient, the stick tangent, the
//! monotone loading curve, a load cycle's dissipation against the slip work, and the
//! accumulated-pressure friction limit against an independent integration of its equations.

use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use strand_core::{
    LawKind, LayDirection, LayerSpec, Material, SectionLaw, SectionOptions, SectionResponse,
    SlipPressure, Station, StickStiffness, Strand, StrandSpec, WireSpec,
};

/// The most wires of diameter `d` that fit side by side on the helix radius `r` at lay angle
/// `a`: 2 r sin(pi/m) >= d / cos(a) (at least one).
fn most_wires(d: f64, r: f64, a: f64) -> usize {
    let s = d / (2.0 * r * a.cos());
    if s >= 1.0 {
        1
    } else {
        ((PI / s.asin()).floor() as usize).max(1)
    }
}

/// A random valid strand of 1 to 4 helical layers: per layer a diameter ratio to the core,
/// a share of the wires that fit, a lay angle, a lay direction, a phase and a modulus ratio
/// (steel on aluminium and the reverse); one friction coefficient.
fn multilayer() -> impl Strategy<Value = Strand> {
    strands(1..=4)
}

/// A random valid strand with `layers` helical layers, drawn as [`multilayer`] draws them.
fn strands(layers: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Strand> {
    (
        (0.5e-3..4e-3f64, 9.5..11.5f64, 0.05..1.0f64),
        prop::collection::vec(
            (
                0.5..1.3f64,
                0.3..1.0f64,
                3.0..25.0f64,
                any::<bool>(),
                -PI..PI,
                0.3..3.0f64,
            ),
            layers,
        ),
    )
        .prop_filter_map("layers that do not fit", |((dc, loge, mu), raw)| {
            let e = 10f64.powf(loge);
            let mat = |e: f64| Material {
                youngs_modulus: e,
                poisson_ratio: 0.3,
                density: 7800.0,
            };
            let mut layers = Vec::new();
            let mut beneath = dc;
            for (ratio, fill, alpha, left, phase, eratio) in raw {
                let d = dc * ratio;
                let a = alpha.to_radians();
                let m_max = most_wires(d, 0.5 * (beneath + d), a).min(40);
                let m = ((fill * m_max as f64).ceil() as usize).clamp(1, m_max);
                layers.push(LayerSpec {
                    wires: m,
                    wire: WireSpec {
                        diameter: d,
                        material: mat(e * eratio),
                    },
                    lay_angle: a,
                    phase,
                    direction: if left {
                        LayDirection::Left
                    } else {
                        LayDirection::Right
                    },
                });
                beneath += 2.0 * d;
            }
            Strand::new(StrandSpec {
                length: 1.0,
                core: WireSpec {
                    diameter: dc,
                    material: mat(e),
                },
                layers,
                friction: mu,
            })
            .ok()
        })
}

/// The smallest first-slip curvature scale eps mu sin(alpha_j) / R_j over the layers (1/m).
fn curvature_scale(s: &Strand, eps: f64) -> f64 {
    s.layers()
        .iter()
        .map(|l| eps.abs().max(1e-6) * s.friction().max(0.05) * l.lay_angle().sin() / l.radius)
        .fold(f64::INFINITY, f64::min)
        .max(1e-6)
}

fn law(s: &Strand, kind: LawKind, pressure: SlipPressure) -> SectionLaw {
    let options = SectionOptions {
        slip_pressure: pressure,
        ..Default::default()
    };
    SectionLaw::with_options(s, kind, &options)
}

fn kinds() -> impl Strategy<Value = LawKind> {
    prop::sample::select(vec![
        LawKind::Continuous,
        LawKind::Hysteretic,
        LawKind::Constant,
    ])
}

fn pressures() -> impl Strategy<Value = SlipPressure> {
    prop::sample::select(SlipPressure::ALL.to_vec())
}

/// The vector law at `kappa` moved by `+h` and `-h` in component `c`.
#[allow(clippy::too_many_arguments)]
fn curvature_pair(
    law: &SectionLaw,
    st: &Station,
    eps: f64,
    kappa: [f64; 2],
    c: usize,
    h: f64,
    slip: &[f64],
    trial: &mut [f64],
) -> (SectionResponse, SectionResponse) {
    let (mut kp, mut km) = (kappa, kappa);
    kp[c] += h;
    km[c] -= h;
    (
        law.vector(st, eps, kp, slip, trial),
        law.vector(st, eps, km, slip, trial),
    )
}

/// Layer `j`'s friction-limited tension gain (T_j(theta) - F_j) / F_j by the classical
/// fourth-order Runge-Kutta method on `steps` steps, for the system written out from its
/// definition (`../shared` references, "Multi-layer strands"): dT_j/dtheta = sign (lambda_j
/// T_j + c_j sum_{k>j} b_k T_k), T_k(0) = F_k = E_k A_k cos^2(alpha_k), with lambda_j = mu
/// sin(alpha_j) and, for the exact line load, c_j = mu R_j / (n_j sin alpha_j), b_k = n_k
/// sin^2(alpha_k) / R_k; for SC5, c_j = mu r_wj / sin(alpha_j), b_k = sin^2(alpha_k) / r_wk;
/// for the own layer alone, c_j = 0; with friction on both faces, c_j twice the exact one.
fn rk4_gain(
    s: &Strand,
    pressure: SlipPressure,
    j: usize,
    theta: f64,
    sign: f64,
    steps: usize,
) -> f64 {
    let l = s.layers();
    let n = l.len();
    let mu = s.friction();
    let lambda: Vec<f64> = l.iter().map(|h| mu * h.lay_angle().sin()).collect();
    let (c, b): (Vec<f64>, Vec<f64>) = l
        .iter()
        .map(|h| {
            let (sa, r) = (h.lay_angle().sin(), h.spec.wire.diameter / 2.0);
            match pressure {
                SlipPressure::OwnLayer => (0.0, 0.0),
                SlipPressure::Sc5 => (mu * r / sa, sa * sa / r),
                SlipPressure::TwoFaces => (
                    2.0 * mu * h.radius / (h.wires() as f64 * sa),
                    h.wires() as f64 * sa * sa / h.radius,
                ),
                _ => (
                    mu * h.radius / (h.wires() as f64 * sa),
                    h.wires() as f64 * sa * sa / h.radius,
                ),
            }
        })
        .unzip();
    let rate = |t: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let outside: f64 = (i + 1..n).map(|k| b[k] * t[k]).sum();
                sign * (lambda[i] * t[i] + c[i] * outside)
            })
            .collect()
    };
    let f: Vec<f64> = l
        .iter()
        .map(|h| {
            let w = &h.spec.wire;
            w.material.youngs_modulus * w.area() * h.lay_angle().cos().powi(2)
        })
        .collect();
    let mut t = f.clone();
    let h = theta / steps as f64;
    let axpy = |t: &[f64], k: &[f64], a: f64| -> Vec<f64> {
        t.iter().zip(k).map(|(x, y)| x + a * y).collect()
    };
    for _ in 0..steps {
        let k1 = rate(&t);
        let k2 = rate(&axpy(&t, &k1, 0.5 * h));
        let k3 = rate(&axpy(&t, &k2, 0.5 * h));
        let k4 = rate(&axpy(&t, &k3, h));
        for i in 0..n {
            t[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    (t[j] - f[j]) / f[j]
}

/// Every layer's friction limit of the `continuous` law on `s`, both sides, at capstan angle
/// `theta` and strain `eps`, against [`rk4_gain`] on `steps` and `2 steps` steps: within ten
/// times their difference (fourth order: the finer run is 16 times closer), 1e-12 of the gain
/// for the round-off of both sums, and the reference's own round-off (RK4 rounds each tension
/// by a few u in each step, so (T_j - F_j) / F_j carries up to 2 steps x 2u x (1 + |gain|)
/// however small the gain: a gain of 1.8e-3 once came out 4e-14 off).
fn limits_match_rk4(
    s: &Strand,
    pressure: SlipPressure,
    theta: f64,
    eps: f64,
    steps: usize,
) -> Result<(), TestCaseError> {
    let law = law(s, LawKind::Continuous, pressure);
    for (j, h) in s.layers().iter().enumerate() {
        let w = &h.spec.wire;
        let a = h.lay_angle();
        // Papailiou's projection cos(alpha) of the tension increment (the default limit).
        let per_gain = a.cos() * w.material.youngs_modulus * w.area() * a.cos().powi(2) * eps;
        let cap = law.friction_limit(j, eps, theta);
        for (side, sign) in [(0, 1.0), (1, -1.0)] {
            let got = cap[side] / per_gain;
            let coarse = sign * rk4_gain(s, pressure, j, theta, sign, steps);
            let fine = sign * rk4_gain(s, pressure, j, theta, sign, 2 * steps);
            let rk4_round = 2.0 * steps as f64 * f64::EPSILON * (1.0 + fine.abs());
            let tol = 10.0 * (fine - coarse).abs() + 1e-12 * fine.abs() + rk4_round;
            prop_assert!(
                got.is_finite() && (got - fine).abs() <= tol,
                "layer {j} side {side}: {got} against RK4 {fine} (tolerance {tol})"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// The accumulated-pressure friction limit of every layer, on both sides, against a
    /// Runge-Kutta integration of the pressure system written out independently. The RK4
    /// error at 400 steps is estimated by the difference to 800 steps (fourth order: the
    /// finer run is 16 times closer); the tolerance is ten times that estimate plus 1e-12 of
    /// the gain for the round-off of both sums (the series sums some 40 terms of one sign on
    /// the stretched side, RK4 800 steps), and at least RK4's accumulated round-off. The
    /// outermost layer and the own-layer variant have the capstan gain, which the same
    /// integration gives.
    #[test]
    fn friction_limit_solves_the_pressure_system(
        s in multilayer(), pressure in pressures(), theta in 0.0..FRAC_PI_2, eps in 1e-4..1e-2f64,
    ) {
        limits_match_rk4(&s, pressure, theta, eps, 400)?;
    }

    /// The same at friction coefficients of 3 to 100, where theta ||A|| passes the plain
    /// series' reach and the exponential is scaled and squared (the series summed as before
    /// gave -2e81 for a law moment at mu = 1000). RK4 takes 40 steps per unit of mu theta
    /// (mu theta sin(alpha) h <= 0.025, stable and accurate on both sides) and twice that; the
    /// tolerance as above, with the round-off of the longer integration.
    #[test]
    fn friction_limit_at_large_friction_solves_the_pressure_system(
        s in multilayer(), pressure in pressures(), theta in 0.1..FRAC_PI_2, mu in 3.0..100.0f64,
    ) {
        let s = Strand::new(StrandSpec { friction: mu, ..s.spec().clone() }).unwrap();
        limits_match_rk4(&s, pressure, theta, 1e-3, (40.0 * mu * theta).ceil() as usize)?;
    }

    /// Planar tangents dM/dkappa and dM/deps against central differences, away from the
    /// switches (the moment is linear in kappa between them, and in eps through the friction
    /// limits, so a central difference is exact but for round-off: 1e-16 |M| / h with
    /// h = 1e-6 kappa, below 1e-9 of the all-stick stiffness; the tolerance 1e-6 of it).
    #[test]
    fn planar_tangents_match_finite_differences(
        s in multilayer(), kind in kinds(), pressure in pressures(),
        eps in 1e-4..1e-2f64, x in 0.0..1.0f64, logu in -1.0..2.5f64,
    ) {
        let law = law(&s, kind, pressure);
        let st = law.station(x);
        let k = 10f64.powf(logu) * curvature_scale(&s, eps);
        let slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        let r = law.planar(&st, eps, -k, &slip, &mut trial);
        let (hk, he) = (1e-6 * k, 1e-6 * eps);
        let p = law.planar(&st, eps, -k + hk, &slip, &mut trial);
        let m = law.planar(&st, eps, -k - hk, &slip, &mut trial);
        prop_assume!(p.slipping == r.slipping && m.slipping == r.slipping);
        let scale = law.stick_bending_stiffness() * 2.0;
        let fd = (p.moment - m.moment) / (2.0 * hk);
        prop_assert!((fd - r.moment_curvature).abs() <= 1e-6 * scale,
            "dM/dk {} fd {}", r.moment_curvature, fd);
        let p = law.planar(&st, eps + he, -k, &slip, &mut trial);
        let m = law.planar(&st, eps - he, -k, &slip, &mut trial);
        prop_assume!(p.slipping == r.slipping && m.slipping == r.slipping);
        let fd = (p.moment - m.moment) / (2.0 * he);
        prop_assert!((fd - r.moment_strain).abs() <= 1e-6 * (k * scale / eps),
            "dM/deps {} fd {}", r.moment_strain, fd);
    }

    /// Vector tangents (both directions, the friction limits turning with the bending
    /// direction through the accumulated-pressure gains' own derivative) against central
    /// differences, from a committed state left by bending in another direction. The limits
    /// are smooth in the direction, so the central difference has a truncation error of
    /// order h^2 = 1e-12 of the curvature's scale: the tolerance 1e-5 of the all-stick
    /// stiffness covers it and the round-off.
    #[test]
    fn vector_tangents_match_finite_differences(
        s in multilayer(), kind in kinds(), pressure in pressures(),
        eps in 1e-4..1e-2f64, x in 0.0..1.0f64, logu in -1.0..2.5f64,
        dir in 0.0..(2.0 * PI), u0 in 0.0..50.0f64, dir0 in 0.0..(2.0 * PI),
    ) {
        let law = law(&s, kind, pressure);
        let st = law.station(x);
        let k = 10f64.powf(logu) * curvature_scale(&s, eps);
        let k0 = u0 * curvature_scale(&s, eps);
        let mut trial = vec![0.0; law.state_len()];
        law.vector(&st, eps, [k0 * dir0.cos(), k0 * dir0.sin()], &vec![0.0; law.state_len()], &mut trial);
        let slip = trial.clone();
        let kv = [k * dir.cos(), k * dir.sin()];
        let (hk, he) = (1e-6 * k, 1e-6 * eps);
        let scale = law.stick_bending_stiffness() * 2.0;
        let v = law.vector(&st, eps, kv, &slip, &mut trial);
        for c in 0..2 {
            let (p, m) = curvature_pair(&law, &st, eps, kv, c, hk, &slip, &mut trial);
            prop_assume!(p.slipping == v.slipping && m.slipping == v.slipping);
            for a in 0..2 {
                let fd = (p.moment[a] - m.moment[a]) / (2.0 * hk);
                prop_assert!((fd - v.moment_curvature[a][c]).abs() <= 1e-5 * scale,
                    "dM{a}/dk{c} {} fd {}", v.moment_curvature[a][c], fd);
            }
        }
        let p = law.vector(&st, eps + he, kv, &slip, &mut trial);
        let m = law.vector(&st, eps - he, kv, &slip, &mut trial);
        prop_assume!(p.slipping == v.slipping && m.slipping == v.slipping);
        for a in 0..2 {
            let fd = (p.moment[a] - m.moment[a]) / (2.0 * he);
            prop_assert!((fd - v.moment_strain[a]).abs() <= 1e-6 * (k * scale / eps),
                "dM{a}/deps {} fd {}", v.moment_strain[a], fd);
        }
    }

    /// The stored energy's gradient: at fixed strain and slip, dE/dkappa = M + energy_turn for
    /// the continuous law, and dE/dkappa = M for the hysteretic law from a committed slip
    /// state while every wire sticks (its slip energy is booked as slip work). The energy is
    /// quadratic between switches: central differences are exact but for the round-off of two
    /// energies (below, a bound from the number of summed terms).
    #[test]
    fn moment_is_the_energy_gradient(
        s in multilayer(), pressure in pressures(),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Hysteretic]),
        eps in 1e-4..1e-2f64, x in 0.0..1.0f64, logu in -1.0..2.0f64,
        dir in 0.0..(2.0 * PI), u0 in 0.0..50.0f64, dir0 in 0.0..(2.0 * PI),
    ) {
        let law = law(&s, kind, pressure);
        let st = law.station(x);
        let (k, k0) = (10f64.powf(logu) * curvature_scale(&s, eps), u0 * curvature_scale(&s, eps));
        let mut trial = vec![0.0; law.state_len()];
        law.vector(&st, eps, [k0 * dir0.cos(), k0 * dir0.sin()], &vec![0.0; law.state_len()], &mut trial);
        let slip = trial.clone();
        let kv = [k * dir.cos(), k * dir.sin()];
        let v = law.vector(&st, eps, kv, &slip, &mut trial);
        prop_assume!(kind != LawKind::Hysteretic || v.slipping == 0);
        let hk = 1e-6 * k;
        let scale = law.stick_bending_stiffness() * 2.0 * k;
        for c in 0..2 {
            let (p, m) = curvature_pair(&law, &st, eps, kv, c, hk, &slip, &mut trial);
            prop_assume!(p.slipping == v.slipping && m.slipping == v.slipping);
            let fd = (p.energy - m.energy) / (2.0 * hk);
            let want = v.moment[c] + v.energy_turn[c];
            // Each energy sums the axial, two bending and one term per wire, all positive:
            // recursive summation errs by at most (terms - 1) u E, and each term's own
            // products by a few u of it (Higham, Accuracy and Stability, 4.2), so at most
            // terms x 2u x E per energy, terms x 2u x E / h in the difference quotient.
            let terms = (st.wires.len() + 3) as f64;
            let round = terms * f64::EPSILON * v.energy.abs() / hk;
            prop_assert!((fd - want).abs() <= 1e-6 * scale + round,
                "dE/dk{c} {fd} against M {} + turn {}", v.moment[c], v.energy_turn[c]);
        }
    }

    /// With every wire of every layer sticking (below the smallest critical curvature in this
    /// direction, from no slip) the vector tangent is symmetric positive definite, its
    /// smallest eigenvalue at least K_min, and the moment is the tangent times the curvature.
    #[test]
    fn stick_tangent_is_symmetric_positive_definite(
        s in multilayer(), pressure in pressures(),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Hysteretic]),
        eps in 1e-4..1e-2f64, x in 0.0..1.0f64, u in 0.0..1.0f64, dir in 0.0..(2.0 * PI),
    ) {
        let law = law(&s, kind, pressure);
        let st = law.station(x);
        let kv0 = [dir.cos(), dir.sin()];
        let kc = law.vector_wires(&st, eps, kv0, &[]).iter()
            .filter_map(|w| w.critical_curvature).fold(f64::INFINITY, f64::min);
        let k = u * kc.min(1e3);
        let kv = [k * kv0[0], k * kv0[1]];
        let slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        let r = law.vector(&st, eps, kv, &slip, &mut trial);
        prop_assume!(r.slipping == 0);
        let t = r.moment_curvature;
        let kmin = law.base_bending_stiffness();
        prop_assert_eq!(t[0][1], t[1][0]);
        let tr = t[0][0] + t[1][1];
        let lmin = 0.5 * tr - (0.25 * (t[0][0] - t[1][1]).powi(2) + t[0][1] * t[1][0]).sqrt();
        // The eigenvalue's round-off is relative to the trace.
        prop_assert!(lmin >= kmin - 1e-12 * tr, "{t:?} K_min {kmin}");
        for a in 0..2 {
            let m = t[a][0] * kv[0] + t[a][1] * kv[1];
            prop_assert!((r.moment[a] - m).abs() <= 1e-12 * tr * k + 1e-300);
        }
    }

    /// The loading curve from straight: the continuous law's moment never falls as the
    /// curvature grows (every wire's force is non-decreasing in its strain), and the
    /// hysteretic law along the same monotone path, committing each step, gives the same
    /// moment (on a monotone path from no slip its return mapping holds each wire at the
    /// limit the continuous law caps it at) up to the round-off of its slip updates.
    #[test]
    fn monotone_loading_curve(
        s in multilayer(), pressure in pressures(), eps in 1e-5..1e-2f64, x in 0.0..1.0f64,
        sense in prop::sample::select(vec![-1.0, 1.0]), steps in 5usize..60,
    ) {
        let cont = law(&s, LawKind::Continuous, pressure);
        let hyst = law(&s, LawKind::Hysteretic, pressure);
        let st = cont.station(x);
        let kmax = 300.0 * curvature_scale(&s, eps);
        let mut slip = vec![0.0; hyst.state_len()];
        let mut trial = slip.clone();
        let mut last = 0.0;
        for i in 1..=steps {
            let k = sense * kmax * (i as f64 / steps as f64).powi(2);
            let c = cont.planar(&st, eps, k, &[], &mut []);
            let h = hyst.planar(&st, eps, k, &slip, &mut trial);
            slip.copy_from_slice(&trial);
            let m = sense * c.moment;
            prop_assert!(m >= last * (1.0 - 1e-14), "M fell: {last} -> {m}");
            last = m;
            let round = 1e-12 * cont.stick_bending_stiffness() * k.abs();
            prop_assert!((h.moment - c.moment).abs() <= round, "{} against {}", h.moment, c.moment);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Load cycles of the hysteretic law at fixed strain: after a preload to kappa_max, each
    /// cycle kappa_max -> -kappa_max -> kappa_max does work (the loop's area) equal to the
    /// slip work booked plus the change of stored energy; the first cycle may leave a wire
    /// that slipped on one side only with a new slip, the second is the stable loop (each
    /// slider's limits are fixed), whose stored energy returns to its start, so that all its
    /// work is dissipated. The moment is piecewise linear in kappa with at most four kinks
    /// per wire and cycle (a switch to slip and back on each side), and the trapezoid rule
    /// errs by at most k_i arm_i^2 dk^2 / 8 at each kink: the tolerance sums that bound over
    /// the wires.
    #[test]
    fn cycle_dissipation_is_the_slip_work(
        s in multilayer(), pressure in pressures(), eps in 1e-4..1e-2f64, x in 0.0..1.0f64,
        logu in 0.5..2.5f64,
    ) {
        let law = law(&s, LawKind::Hysteretic, pressure);
        let st = law.station(x);
        let kmax = 10f64.powf(logu) * curvature_scale(&s, eps);
        let n = 2000;
        let mut slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        let mut step = |k: f64, slip: &mut Vec<f64>| {
            let r = law.planar(&st, eps, k, slip, &mut trial);
            slip.copy_from_slice(&trial);
            r
        };
        for i in 1..=n {
            step(kmax * i as f64 / n as f64, &mut slip);
        }
        let stick: f64 = law.planar_wires(&st, eps, kmax, &[]).iter().map(|w| w.k_stick).sum();
        let dk_max = 2.0 * PI * kmax / (4 * n) as f64;
        let kinks = 4.0 * stick * dk_max * dk_max / 8.0;
        for cycle in 0..2 {
            let start = step(kmax, &mut slip);
            let (mut area, mut dissipated, mut prev, mut k_prev) = (0.0, 0.0, start, kmax);
            for i in 1..=4 * n {
                let k = kmax * (2.0 * PI * i as f64 / (4 * n) as f64).cos();
                let r = step(k, &mut slip);
                area += 0.5 * (r.moment + prev.moment) * (k - k_prev);
                dissipated += r.slip_work;
                prev = r;
                k_prev = k;
            }
            let stored = prev.energy - start.energy;
            let round = 1e-12 * (start.energy + dissipated + area.abs());
            prop_assert!((area - stored - dissipated).abs() <= kinks + round + 1e-9 * dissipated,
                "cycle {cycle}: loop area {area} against slip work {dissipated} + stored {stored} \
                 (kinks {kinks})");
            if cycle == 1 {
                prop_assert!(stored.abs() <= round,
                    "stored energy {} -> {}", start.energy, prev.energy);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// On a strand of one layer (1+m) every `section.slip_pressure` and the stick stiffnesses
    /// `bonded` and `one_body` give the same law, bit for bit, so that the defaults of the two
    /// options cannot move a 1+m result: nothing lies outside the layer to press it, and the
    /// one-body share of a lone layer is its interface's factor. Checked on both the planar and
    /// the vector law along a path that loads past full slip (up to 30 times the smallest
    /// first-slip scale), reverses and reloads, committing each step's slip state.
    #[test]
    fn one_layer_law_is_the_same_under_every_pressure_and_stick_stiffness(
        s in strands(1..=1), kind in kinds(), eps in 0.0..2e-3f64, x in 0.0..1.0f64,
        logu in -0.5..1.5f64, turn in 0.0..PI,
    ) {
        let laws: Vec<SectionLaw> = SlipPressure::ALL
            .iter()
            .flat_map(|&slip_pressure| {
                [StickStiffness::Bonded, StickStiffness::OneBody].map(|stick_stiffness| {
                    let options = SectionOptions {
                        slip_pressure,
                        stick_stiffness,
                        ..Default::default()
                    };
                    SectionLaw::with_options(&s, kind, &options)
                })
            })
            .collect();
        let amplitude = 10f64.powf(logu) * curvature_scale(&s, eps);
        let n = 24;
        let path = |law: &SectionLaw| {
            let st = law.station(x);
            let (mut planar, mut vector) = (vec![0.0; law.state_len()], vec![0.0; law.state_len()]);
            let mut trial = planar.clone();
            let mut out = Vec::with_capacity(2 * n);
            for i in 1..=2 * n {
                let k = amplitude * (PI * i as f64 / n as f64).sin();
                let r = law.planar(&st, eps, k, &planar, &mut trial);
                planar.copy_from_slice(&trial);
                let kv = [k * turn.cos(), k * turn.sin()];
                let v = law.vector(&st, eps, kv, &vector, &mut trial);
                vector.copy_from_slice(&trial);
                out.push((r, v));
            }
            (law.stick_bending_stiffness(), law.state_len(), out)
        };
        let first = path(&laws[0]);
        for (i, law) in laws.iter().enumerate().skip(1) {
            prop_assert!(path(law) == first, "{kind}: variant {i} differs");
        }
    }
}

/// A strand of one layer has the same law under every slip pressure, bit for bit: nothing
/// lies outside its layer.
#[test]
fn one_layer_law_is_the_same_under_every_pressure() {
    let s = Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap();
    for kind in [LawKind::Continuous, LawKind::Hysteretic] {
        let laws: Vec<SectionLaw> = SlipPressure::ALL
            .iter()
            .map(|p| law(&s, kind, *p))
            .collect();
        for i in 0..200 {
            let x = 0.0173 * i as f64;
            let (eps, k) = (1e-4 * (i % 9) as f64, 1e-2 * ((i * 37 % 101) as f64 - 50.0));
            let kv = [0.3 * k, k];
            let rs: Vec<_> = laws
                .iter()
                .map(|l| {
                    let st = l.station(x);
                    let slip = vec![0.0; l.state_len()];
                    let mut trial = slip.clone();
                    (
                        l.planar(&st, eps, k, &slip, &mut trial),
                        l.vector(&st, eps, kv, &slip, &mut trial),
                    )
                })
                .collect();
            assert!(rs.iter().all(|r| *r == rs[0]), "{kind} at {i}");
        }
    }
}

/// The 1+6+12 steel strand of `examples/steel-1x19-swing.json` (core 3.3 mm, 6 and 12 wires
/// of 3 mm at 8 deg right and 12 deg left, E = 2e11 Pa), mu = 0.3.
fn steel_1x19() -> Strand {
    let wire = |d: f64| WireSpec {
        diameter: d,
        material: Material {
            youngs_modulus: 2e11,
            poisson_ratio: 0.3,
            density: 7850.0,
        },
    };
    let layer = |m: usize, deg: f64, direction| LayerSpec {
        wires: m,
        wire: wire(3e-3),
        lay_angle: f64::to_radians(deg),
        phase: 0.0,
        direction,
    };
    Strand::new(StrandSpec {
        length: 1.0,
        core: wire(3.3e-3),
        layers: vec![
            layer(6, 8.0, LayDirection::Right),
            layer(12, 12.0, LayDirection::Left),
        ],
        friction: 0.3,
    })
    .unwrap()
}

/// A 1+6+12 strand: the inner layer's friction limit with the outer layer pressing down is
/// larger than its own-layer capstan limit, on both sides and at every angle; the outer
/// layer's is the capstan one under every variant.
#[test]
fn outer_layers_raise_the_inner_friction_limit() {
    let s = steel_1x19();
    let own = law(&s, LawKind::Continuous, SlipPressure::OwnLayer);
    for p in [
        SlipPressure::Accumulated,
        SlipPressure::Sc5,
        SlipPressure::TwoFaces,
    ] {
        let acc = law(&s, LawKind::Continuous, p);
        for t in [0.1, 0.5, 1.0, FRAC_PI_2] {
            let (a, o) = (
                acc.friction_limit(0, 1e-3, t),
                own.friction_limit(0, 1e-3, t),
            );
            assert!(
                a[0] > o[0] && a[1] > o[1],
                "{p} at {t}: {a:?} against {o:?}"
            );
            assert_eq!(
                acc.friction_limit(1, 1e-3, t),
                own.friction_limit(1, 1e-3, t)
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Each interface's stick factor (the rod model of the layer bonded to what lies beneath
    /// it, `strand_core::bonded`): the bond adds stiffness (factor above 0) and cannot add more
    /// than the plane section, whose rigid rotation of every section is the stiffest the
    /// wires' axial strains can follow (factor at most 1). For the first layer it is the rod
    /// model on the core, whatever lies outside.
    #[test]
    fn interface_stick_factors_lie_in_the_plane_section_bound(s in multilayer()) {
        for (j, h) in s.layers().iter().enumerate() {
            let f = strand_core::StickStiffness::Bonded.factor(&s, j);
            prop_assert!(f > 0.0 && f <= 1.0 + 1e-12, "layer {j} ({} wires): {f}", h.wires());
        }
        let mut inner = s.spec().clone();
        inner.layers.truncate(1);
        let one = Strand::new(inner).unwrap();
        prop_assert_eq!(
            strand_core::StickStiffness::Bonded.factor(&s, 0),
            strand_core::StickStiffness::Bonded.factor(&one, 0)
        );
    }
}

/// Friction on both faces (`two_faces`) on the 1+6+12 strand: the inner layer's limit against
/// the closed form of its two-layer system, dT_1/dtheta = +-(lambda_1 T_1 + 2 a T_2), T_2 =
/// F_2 exp(+-lambda_2 theta), a = mu (R_1 / (n_1 sin alpha_1)) n_2 sin^2(alpha_2) / R_2:
/// T_1 - F_1 = F_1 (exp(s lambda_1 theta) - 1) + 2 a F_2 (exp(s lambda_2 theta) - exp(s
/// lambda_1 theta)) / (lambda_2 - lambda_1) with s = +-1, compared through its ratio to the
/// own-layer limit (the force scale cancels). The closed form loses at most
/// log10(1 / (theta |lambda_2 - lambda_1|)) < 4 digits to the difference of exponentials at
/// theta >= 0.1: tolerance 1e-10 relative.
#[test]
fn two_faces_inner_limit_matches_its_closed_form() {
    let s = steel_1x19();
    let two = law(&s, LawKind::Continuous, SlipPressure::TwoFaces);
    let own = law(&s, LawKind::Continuous, SlipPressure::OwnLayer);
    let (l1, l2) = (&s.layers()[0], &s.layers()[1]);
    let mu = 0.3;
    let (s1, s2) = (l1.lay_angle().sin(), l2.lay_angle().sin());
    let (lam1, lam2) = (mu * s1, mu * s2);
    let a = mu * (l1.radius / (6.0 * s1)) * 12.0 * s2 * s2 / l2.radius;
    // F_k per unit strain: E A_w cos^2(alpha_k); the wires are alike, so E A_w cancels.
    let (f1, f2) = (l1.lay_angle().cos().powi(2), l2.lay_angle().cos().powi(2));
    for theta in [0.1, 0.4, 1.0, FRAC_PI_2] {
        let lim = two.friction_limit(0, 1e-3, theta);
        let base = own.friction_limit(0, 1e-3, theta);
        for (side, sign) in [(0, 1.0), (1, -1.0)] {
            let (e1, e2) = ((sign * lam1 * theta).exp(), (sign * lam2 * theta).exp());
            let t1 = f1 * e1 + 2.0 * a * f2 * (e2 - e1) / (lam2 - lam1);
            let gain = sign * (t1 - f1) / f1;
            let capstan = sign * (e1 - 1.0);
            let expected = gain / capstan;
            let got = lim[side] / base[side];
            assert!(
                (got / expected - 1.0).abs() <= 1e-10,
                "side {side}, theta {theta}: {got} against {expected}"
            );
        }
        // The outer layer has one face in contact: the capstan limit.
        assert_eq!(
            two.friction_limit(1, 1e-3, theta),
            own.friction_limit(1, 1e-3, theta)
        );
    }
}
