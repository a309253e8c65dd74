//! Property tests of the section laws (SPEC 2): continuity, monotonicity, the stick/slip
//! switch at the critical curvature, limits, symmetry, finite edge cases, analytic
//! derivatives against finite differences, and the hysteretic law's energy bounds.

mod common;

use proptest::prelude::*;
use std::f64::consts::PI;
use strand_core::{
    BaseStiffness, LawKind, LayDirection, LayerSpec, Material, SectionLaw, SectionOptions,
    SectionResponse, SlipLimit, Station, StickStiffness, Strand, StrandSpec, WireSpec, WireState,
};

/// A random valid 1+m strand: sizes, moduli, lay angle, phase, lay direction, friction.
fn strand() -> impl Strategy<Value = Strand> {
    (
        (0.5e-3..5e-3f64, 0.2..1.5f64, 1usize..=9, 5.0..40.0f64),
        (
            8.0..11.5f64,
            0.5..2.0f64,
            -PI..PI,
            any::<bool>(),
            0.0..1.0f64,
        ),
    )
        .prop_filter_map(
            "overlapping layer",
            |((dc, ratio, m, alpha), (loge, eratio, phase, left, mu))| {
                let e = 10f64.powf(loge);
                let mat = |e: f64| Material {
                    youngs_modulus: e,
                    poisson_ratio: 0.3,
                    density: 7800.0,
                };
                Strand::new(StrandSpec {
                    length: 1.0,
                    core: WireSpec {
                        diameter: dc,
                        material: mat(e),
                    },
                    layers: vec![LayerSpec {
                        wires: m,
                        wire: WireSpec {
                            diameter: dc * ratio,
                            material: mat(e * eratio),
                        },
                        lay_angle: alpha.to_radians(),
                        phase,
                        direction: if left {
                            LayDirection::Left
                        } else {
                            LayDirection::Right
                        },
                    }],
                    friction: mu,
                })
                .ok()
            },
        )
}

/// Typical first-slip curvature scale eps mu sin(alpha) / R_w of a strand (1/m).
fn curvature_scale(s: &Strand, eps: f64) -> f64 {
    let l = s.layers().first().unwrap();
    (eps.abs().max(1e-6) * s.friction().max(0.05) * l.lay_angle().sin() / l.radius).max(1e-6)
}

/// The vector law at the curvature `kappa` moved by `+h` and `-h` in component `c` (for
/// central differences), from the committed state `slip`.
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

fn planar(law: &SectionLaw, st: &Station, eps: f64, kappa: f64) -> strand_core::PlanarResponse {
    let mut trial = vec![0.0; law.state_len()];
    let slip = vec![0.0; law.state_len()];
    law.planar(st, eps, kappa, &slip, &mut trial)
}

/// Distance (relative) of `kappa` from the nearest switch of any wire.
fn switch_distance(law: &SectionLaw, st: &Station, eps: f64, kappa: f64) -> f64 {
    law.planar_wires(st, eps, kappa, &[])
        .iter()
        .filter_map(|w| w.critical_curvature)
        .map(|c| (kappa.abs() - c).abs() / c.max(1e-300))
        .fold(f64::INFINITY, f64::min)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// `continuous`: M(k) is continuous and non-decreasing in the curvature magnitude, for
    /// bending in either sense.
    #[test]
    fn continuous_moment_is_monotone_and_continuous(
        s in strand(), eps in 1e-5..1e-2f64, x in 0.0..1.0f64,
        u in 0.0..20.0f64, du in 1e-9..1e-3f64, sense in prop::sample::select(vec![-1.0, 1.0]),
    ) {
        let law = SectionLaw::new(&s, LawKind::Continuous);
        let st = law.station(x);
        let k1 = u * curvature_scale(&s, eps);
        let k2 = k1 * (1.0 + du) + du * curvature_scale(&s, eps);
        let m1 = sense * planar(&law, &st, eps, sense * k1).moment;
        let m2 = sense * planar(&law, &st, eps, sense * k2).moment;
        prop_assert!(m2 >= m1 * (1.0 - 1e-14), "M decreased: {m1} -> {m2}");
        // Lipschitz with the all-stick tangent: no jump anywhere. The difference of two
        // moments carries their round-off, a few ulps of |M| (at du = 1e-9 that is 1e-7 of it).
        let kstick: f64 = law.planar_wires(&st, eps, sense * k1, &[]).iter().map(|w| w.k_stick).sum();
        let lip = (s.min_bending_stiffness(BaseStiffness::default()) + kstick) * (k2 - k1);
        let round_off = 16.0 * f64::EPSILON * (m1.abs() + m2.abs());
        prop_assert!(m2 - m1 <= lip * (1.0 + 1e-9) + round_off + 1e-300, "jump {} > {}", m2 - m1, lip);
    }

    /// A wire sticks exactly when its curvature is below its critical curvature.
    #[test]
    fn stick_exactly_below_critical_curvature(
        s in strand(), eps in -1e-3..1e-2f64, x in 0.0..1.0f64, u in 0.0..20.0f64,
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic]),
        sense in prop::sample::select(vec![-1.0, 1.0]),
    ) {
        let law = SectionLaw::new(&s, kind);
        let st = law.station(x);
        let k = u * curvature_scale(&s, eps);
        let slip = vec![0.0; law.state_len()];
        for w in law.planar_wires(&st, eps, sense * k, &slip) {
            match w.critical_curvature {
                None => prop_assert_eq!(w.state, WireState::Stick),
                Some(c) => {
                    if (k - c).abs() > 1e-9 * c.max(1e-12) {
                        let expect = if k < c { WireState::Stick } else { WireState::Slip };
                        prop_assert_eq!(w.state, expect, "k {} kappa_c {}", k, c);
                    }
                }
            }
        }
    }

    /// Zero or negative strain presses no wire on the core: M = K_min kappa.
    #[test]
    fn no_tension_gives_k_min(
        s in strand(), eps in -1e-2..=0.0f64, x in 0.0..1.0f64, k in -10.0..10.0f64,
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic]),
    ) {
        let law = SectionLaw::new(&s, kind);
        let st = law.station(x);
        let r = planar(&law, &st, eps, k);
        let expect = s.min_bending_stiffness(BaseStiffness::default()) * k;
        prop_assert!((r.moment - expect).abs() <= 1e-12 * expect.abs().max(1e-300));
    }

    /// Small curvature under high tension: every wire sticks and the secant stiffness is
    /// K_min + sum K_stick_i, which is the law's all-stick stiffness for m >= 3 (with the
    /// stick factor of `section.stick_stiffness`; `tests/bonded.rs` writes it out).
    #[test]
    fn small_curvature_high_tension_gives_all_stick(
        s in strand(), x in 0.0..1.0f64, sense in prop::sample::select(vec![-1.0, 1.0]),
    ) {
        let law = SectionLaw::new(&s, LawKind::Continuous);
        let st = law.station(x);
        let eps = 1e-2;
        let k = 1e-9 * curvature_scale(&s, eps);
        let secant = planar(&law, &st, eps, sense * k).moment / (sense * k);
        let sum: f64 = law.planar_wires(&st, eps, sense * k, &[]).iter().map(|w| w.k_stick).sum();
        // Wires within 1e-7 rad of the neutral axis have (almost) no friction limit.
        let near_axis = st.wires.iter().any(|w| w.phase.abs() < 1e-6 || (PI - w.phase.abs()) < 1e-6);
        if !near_axis {
            let want = s.min_bending_stiffness(BaseStiffness::default()) + sum;
            prop_assert!((secant - want).abs() <= 1e-9 * want);
            if s.layers().first().unwrap().wires() >= 3 {
                prop_assert!((secant - law.stick_bending_stiffness()).abs() <= 1e-9 * want);
            }
        }
    }

    /// `paper` with the paper's slip limit (eqs. (20), (22b) as printed): at a wire's switch
    /// its moment drops by exactly cos^2(alpha); with Papailiou's (axial projection
    /// cos(alpha)) eq. (23) is where eqs. (22a) and (22b) meet: no drop.
    #[test]
    fn paper_law_drops_by_cos2_alpha(
        s in strand(), eps in 1e-5..1e-2f64, x in 0.0..1.0f64,
        sense in prop::sample::select(vec![-1.0, 1.0]),
        limit in prop::sample::select(SlipLimit::ALL.to_vec()),
    ) {
        let options = SectionOptions { slip_limit: limit, ..Default::default() };
        let law = SectionLaw::with_options(&s, LawKind::Paper, &options);
        let st = law.station(x);
        let c2 = match limit {
            SlipLimit::Paper => s.layers().first().unwrap().lay_angle().cos().powi(2),
            SlipLimit::Papailiou => 1.0,
        };
        for w in law.planar_wires(&st, eps, sense, &[]) {
            if let Some(kc) = w.critical_curvature
                && w.k_stick * kc > 0.0
            {
                    // Stick moment at the switch K_stick kappa_c; slip moment M_slip.
                    let ratio = w.m_slip / (w.k_stick * kc);
                    prop_assert!((ratio - c2).abs() <= 1e-12, "ratio {ratio} vs {c2}");
                    // The total moment shows the same drop across the switch.
                    let d = 1e-9 * kc;
                    let below = sense * planar(&law, &st, eps, sense * (kc - d)).moment;
                    let above = sense * planar(&law, &st, eps, sense * (kc + d)).moment;
                    let others = (s.min_bending_stiffness(BaseStiffness::default()) + s.max_bending_stiffness(BaseStiffness::default())) * 4.0 * d;
                    let drop = w.k_stick * kc * (1.0 - c2);
                    prop_assert!(((below - above) - drop).abs() <= others + 1e-9 * w.k_stick * kc,
                        "drop {} vs {}", below - above, drop);
            }
        }
    }

    /// Mirror symmetry: mirroring the wire phases (phase -> -phase, lay reversed) mirrors the
    /// law: M(-kappa; -phi) = -M(kappa; phi).
    #[test]
    fn mirrored_strand_mirrors_the_moment(
        s in strand(), eps in -1e-3..1e-2f64, x in 0.0..1.0f64, u in 0.0..20.0f64,
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic]),
    ) {
        let mut spec = s.spec().clone();
        let l = &mut spec.layers[0];
        l.phase = -l.phase;
        l.direction = match l.direction { LayDirection::Right => LayDirection::Left, LayDirection::Left => LayDirection::Right };
        let mirrored = Strand::new(spec).unwrap();
        let (a, b) = (SectionLaw::new(&s, kind), SectionLaw::new(&mirrored, kind));
        let (sa, sb) = (a.station(x), b.station(x));
        let k = u * curvature_scale(&s, eps);
        let (ra, rb) = (planar(&a, &sa, eps, k), planar(&b, &sb, eps, -k));
        prop_assert!((ra.moment + rb.moment).abs() <= 1e-12 * ra.moment.abs().max(1e-300));
        prop_assert!((ra.energy - rb.energy).abs() <= 1e-12 * ra.energy.abs().max(1e-300));
    }

    /// Analytic tangents dM/dkappa and dM/deps of the planar law agree with central
    /// differences away from switch points.
    #[test]
    fn tangents_match_finite_differences(
        s in strand(), eps in 1e-4..1e-2f64, x in 0.0..1.0f64, u in 0.01..20.0f64,
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic, LawKind::Constant]),
    ) {
        let law = SectionLaw::new(&s, kind);
        let st = law.station(x);
        let k = u * curvature_scale(&s, eps);
        prop_assume!(switch_distance(&law, &st, eps, k) > 1e-3);
        let mut trial = vec![0.0; law.state_len()];
        let slip = vec![0.0; law.state_len()];
        let r = law.planar(&st, eps, -k, &slip, &mut trial);
        let hk = 1e-6 * k;
        let fd_k = (law.planar(&st, eps, -k + hk, &slip, &mut trial).moment
            - law.planar(&st, eps, -k - hk, &slip, &mut trial).moment) / (2.0 * hk);
        let scale = s.max_bending_stiffness(BaseStiffness::default()) * 2.0;
        prop_assert!((fd_k - r.moment_curvature).abs() <= 1e-6 * scale, "dM/dk {} fd {}", r.moment_curvature, fd_k);
        let he = 1e-6 * eps;
        let fd_e = (law.planar(&st, eps + he, -k, &slip, &mut trial).moment
            - law.planar(&st, eps - he, -k, &slip, &mut trial).moment) / (2.0 * he);
        prop_assert!((fd_e - r.moment_strain).abs() <= 1e-6 * (r.moment.abs() / eps + 1e-300),
            "dM/deps {} fd {}", r.moment_strain, fd_e);

    }

    /// The vector form's analytic tangents dM/dkappa (both directions, with the friction
    /// limits turning with the bending direction) and dM/deps agree with central
    /// differences away from switch points: both slip limits, and for the hysteretic law
    /// from a committed slip state left by bending in another direction.
    #[test]
    fn vector_tangents_match_finite_differences(
        s in strand(), eps in 1e-4..1e-2f64, x in 0.0..1.0f64, u in 0.01..20.0f64,
        dir in 0.0..(2.0 * PI), u0 in 0.0..20.0f64, dir0 in 0.0..(2.0 * PI),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic, LawKind::Constant]),
        limit in prop::sample::select(SlipLimit::ALL.to_vec()),
    ) {
        let options = SectionOptions { slip_limit: limit, ..Default::default() };
        let law = SectionLaw::with_options(&s, kind, &options);
        let st = law.station(x);
        let k = u * curvature_scale(&s, eps);
        // The paper's limit jumps where kappa_z changes sign (the neutral axis reference
        // changes side).
        prop_assume!(limit == SlipLimit::Papailiou || dir.sin().abs() > 1e-2);
        let mut trial = vec![0.0; law.state_len()];
        let k0 = u0 * curvature_scale(&s, eps);
        law.vector(&st, eps, [k0 * dir0.cos(), k0 * dir0.sin()], &vec![0.0; law.state_len()], &mut trial);
        let slip = trial.clone();
        let kv = [k * dir.cos(), k * dir.sin()];
        let hk = 1e-6 * k;
        let he = 1e-6 * eps;
        let scale = s.max_bending_stiffness(BaseStiffness::default()) * 2.0;
        let v = law.vector(&st, eps, kv, &slip, &mut trial);
        for c in 0..2 {
            let (p, m) = curvature_pair(&law, &st, eps, kv, c, hk, &slip, &mut trial);
            // Skip if the finite difference straddles a switch.
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

    /// The vector form's Newton evaluation without the slip work (`vector_unbooked`) is the
    /// full evaluation bit for bit but for the slip work, and the books of the accepted
    /// iterate (`vector_slip_work`, from the trial state it wrote) are the full evaluation's
    /// slip work bit for bit: from a committed state left by bending in another direction at
    /// another strain (the trapezoid's limit of the step's start), both slip limits, one
    /// layer or pitch samples.
    #[test]
    fn vector_books_apart_are_the_full_evaluations(
        s in strand(), eps in 1e-4..1e-2f64, eps0 in 0.0..1e-2f64, x in 0.0..1.0f64,
        u in 0.0..20.0f64, dir in 0.0..(2.0 * PI), u0 in 0.0..20.0f64,
        dir0 in 0.0..(2.0 * PI),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Hysteretic]),
        limit in prop::sample::select(SlipLimit::ALL.to_vec()),
        samples in prop::sample::select(vec![1usize, 3]),
    ) {
        let options = SectionOptions { slip_limit: limit, pitch_samples: samples, ..Default::default() };
        let law = SectionLaw::with_options(&s, kind, &options);
        let st = law.station(x);
        let n = law.state_len();
        let mut slip = vec![0.0; n];
        let k0 = u0 * curvature_scale(&s, eps0);
        law.vector(&st, eps0, [k0 * dir0.cos(), k0 * dir0.sin()], &vec![0.0; n], &mut slip);
        let k = u * curvature_scale(&s, eps);
        let kv = [k * dir.cos(), k * dir.sin()];
        let (mut t_full, mut t_iter) = (vec![0.0; n], vec![7.0; n]);
        let full = law.vector(&st, eps, kv, &slip, &mut t_full);
        let iter = law.vector_unbooked(&st, eps, kv, &slip, &mut t_iter);
        prop_assert_eq!(iter, SectionResponse { slip_work: 0.0, ..full });
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&t_iter), bits(&t_full));
        let books = law.vector_slip_work(&st, eps, kv, &slip, &t_iter);
        prop_assert_eq!(books.to_bits(), full.slip_work.to_bits(),
            "{} against {}", books, full.slip_work);
    }

    /// The vector form with kappa_y = 0: its z components (moment, dM_z/dkappa_z, dM_z/deps),
    /// energy, slip count and trial state are the planar law's bit for bit, also from a
    /// committed slip state; its y moment is the wires' forces times their y levers.
    #[test]
    fn vector_form_reduces_to_planar(
        s in strand(), eps in -1e-3..1e-2f64, x in 0.0..1.0f64, k in -20.0..20.0f64,
        k0 in -20.0..20.0f64,
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic, LawKind::Constant]),
        limit in prop::sample::select(SlipLimit::ALL.to_vec()),
    ) {
        let options = SectionOptions { slip_limit: limit, ..Default::default() };
        let law = SectionLaw::with_options(&s, kind, &options);
        let st = law.station(x);
        let scale = curvature_scale(&s, eps);
        let k = k * scale;
        let mut trial = vec![0.0; law.state_len()];
        law.planar(&st, eps, k0 * scale, &vec![0.0; law.state_len()], &mut trial);
        let slip = trial.clone();
        let mut tv = trial.clone();
        let p = law.planar(&st, eps, k, &slip, &mut trial);
        let v = law.vector(&st, eps, [0.0, k], &slip, &mut tv);
        prop_assert_eq!(p.moment, v.moment[1]);
        prop_assert_eq!(p.moment_curvature, v.moment_curvature[1][1]);
        prop_assert_eq!(p.moment_strain, v.moment_strain[1]);
        prop_assert_eq!(p.energy, v.energy);
        prop_assert_eq!(p.energy_strain, v.energy_strain);
        prop_assert_eq!(p.slip_work, v.slip_work);
        prop_assert_eq!(p.slipping, v.slipping);
        prop_assert_eq!(&trial, &tv);
        // In a fixed plane no energy turns.
        prop_assert_eq!(v.energy_turn[1], 0.0);
    }

    /// The moment vector, y component included, and `energy_turn` against the stored energy:
    /// at fixed strain and slip, d E/d kappa = M + energy_turn (central differences) for the
    /// `continuous` and `paper` laws, and d E/d kappa = M for the `hysteretic` law from a
    /// committed slip state while every wire sticks (its slip energy is booked as slip work).
    #[test]
    fn moment_and_energy_turn_are_the_energy_gradient(
        s in strand(), eps in 1e-4..1e-2f64, x in 0.0..1.0f64, u in 0.01..20.0f64,
        dir in 0.0..(2.0 * PI), u0 in 0.0..20.0f64, dir0 in 0.0..(2.0 * PI),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic]),
        limit in prop::sample::select(SlipLimit::ALL.to_vec()),
    ) {
        let options = SectionOptions { slip_limit: limit, ..Default::default() };
        let law = SectionLaw::with_options(&s, kind, &options);
        let st = law.station(x);
        prop_assume!(limit == SlipLimit::Papailiou || dir.sin().abs() > 1e-2);
        let (k, k0) = (u * curvature_scale(&s, eps), u0 * curvature_scale(&s, eps));
        let mut trial = vec![0.0; law.state_len()];
        law.vector(&st, eps, [k0 * dir0.cos(), k0 * dir0.sin()], &vec![0.0; law.state_len()], &mut trial);
        let slip = trial.clone();
        let kv = [k * dir.cos(), k * dir.sin()];
        let v = law.vector(&st, eps, kv, &slip, &mut trial);
        prop_assume!(kind != LawKind::Hysteretic || v.slipping == 0);
        let hk = 1e-6 * k;
        let scale = s.max_bending_stiffness(BaseStiffness::default()) * 2.0 * k;
        for c in 0..2 {
            let (p, m) = curvature_pair(&law, &st, eps, kv, c, hk, &slip, &mut trial);
            prop_assume!(p.slipping == v.slipping && m.slipping == v.slipping);
            let fd = (p.energy - m.energy) / (2.0 * hk);
            let want = v.moment[c] + v.energy_turn[c];
            // The difference of two energies loses their round-off.
            let round = 1e-15 * v.energy.abs() / hk;
            prop_assert!((fd - want).abs() <= 1e-6 * scale + round,
                "dE/dk{c} {fd} against M {} + turn {}", v.moment[c], v.energy_turn[c]);
        }
        // The turn term is normal to the bending direction.
        let along = v.energy_turn[0] * kv[0] + v.energy_turn[1] * kv[1];
        prop_assert!(along.abs() <= 1e-9 * scale * k);
        if kind == LawKind::Hysteretic {
            prop_assert_eq!(v.energy_turn, [0.0; 2]);
        }
    }

    /// `still_curvature` is a lower bound on the first slip: from no slip, a curvature below
    /// it slips no wire (by the wires' reports, which judge a wire without lever by its
    /// critical curvature) in any direction, for either slip limit and every law with wires.
    #[test]
    fn nothing_slips_below_the_still_curvature(
        s in strand(), eps in 1e-5..1e-2f64, x in 0.0..1.0f64, u in 0.0..0.999f64,
        dir in 0.0..(2.0 * PI),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic]),
        limit in prop::sample::select(SlipLimit::ALL.to_vec()),
    ) {
        let options = SectionOptions { slip_limit: limit, ..Default::default() };
        let law = SectionLaw::with_options(&s, kind, &options);
        let st = law.station(x);
        let k = u * law.still_curvature(eps);
        let kv = [k * dir.sin(), k * dir.cos()];
        let slip = vec![0.0; law.state_len()];
        let slipping: Vec<_> = law.vector_wires(&st, eps, kv, &slip).iter()
            .filter(|w| w.state == WireState::Slip).map(|w| (w.wire, w.critical_curvature)).collect();
        prop_assert!(slipping.is_empty(), "{} 1/m: {:?}", k, slipping);
    }

    /// With every wire sticking the vector tangent is symmetric and positive definite, at
    /// least K_min in every direction (`K_min I + sum_i k l_i l_i^T`), and for m >= 3 evenly
    /// spaced wires isotropic: the all-stick stiffness.
    #[test]
    fn stick_tangent_is_symmetric_positive_definite(
        s in strand(), eps in 1e-4..1e-2f64, x in 0.0..1.0f64, u in 0.0..1.0f64,
        dir in 0.0..(2.0 * PI),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic]),
    ) {
        let law = SectionLaw::new(&s, kind);
        let st = law.station(x);
        // Below every wire's critical curvature in this direction.
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
        let (tr, det) = (t[0][0] + t[1][1], t[0][0] * t[1][1] - t[0][1] * t[1][0]);
        // Smallest eigenvalue.
        let lmin = 0.5 * tr - (0.25 * (t[0][0] - t[1][1]).powi(2) + t[0][1] * t[1][0]).sqrt();
        prop_assert!(det > 0.0 && lmin >= kmin * (1.0 - 1e-12), "{t:?} K_min {kmin}");
        if s.layers().first().unwrap().wires() >= 3 {
            let want = law.stick_bending_stiffness();
            prop_assert!((t[0][0] - want).abs() <= 1e-12 * want && (t[1][1] - want).abs() <= 1e-12 * want);
            prop_assert!(t[0][1].abs() <= 1e-12 * want);
        }
        // The moment is the tangent times the curvature (linear while stuck from straight).
        for a in 0..2 {
            let m = t[a][0] * kv[0] + t[a][1] * kv[1];
            prop_assert!((r.moment[a] - m).abs() <= 1e-12 * (t[0][0] + t[1][1]) * k + 1e-300);
        }
    }

    /// Hysteretic law along a random curvature path: dissipation never negative, each wire's
    /// moment within its friction limit.
    #[test]
    fn hysteretic_dissipation_and_friction_limit(
        s in strand(), eps in 1e-4..1e-2f64, x in 0.0..1.0f64,
        path in prop::collection::vec(-20.0..20.0f64, 1..40),
    ) {
        let law = SectionLaw::new(&s, LawKind::Hysteretic);
        let st = law.station(x);
        let scale = curvature_scale(&s, eps);
        let mut slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        for u in path {
            let k = u * scale;
            let r = law.planar(&st, eps, k, &slip, &mut trial);
            prop_assert!(r.slip_work >= 0.0);
            // Friction limit: |M - K_min kappa| <= sum of the wires' slip moments.
            let limit: f64 = law.planar_wires(&st, eps, k, &slip).iter().map(|w| w.m_slip).sum();
            let excess = (r.moment - s.min_bending_stiffness(BaseStiffness::default()) * k).abs();
            // Rounding of the subtraction is relative to K_min kappa.
            let round = 1e-12 * (s.min_bending_stiffness(BaseStiffness::default()) * k).abs();
            prop_assert!(excess <= limit * (1.0 + 1e-12) + round, "{excess} > {limit}");
            slip.copy_from_slice(&trial);
        }
    }

    /// The moment alone (`planar_moment`, what a Newton iteration reads; the books are taken
    /// with `planar` at the accepted state) is that of `planar` bit for bit, along a random
    /// curvature path of every law (the hysteretic law committing each step), at any strain,
    /// tensionless included.
    #[test]
    fn moment_alone_is_planar_bit_for_bit(
        s in strand(), eps in -1e-3..1e-2f64, x in 0.0..1.0f64,
        kind in prop::sample::select(vec![
            LawKind::Constant, LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic,
        ]),
        path in prop::collection::vec(-20.0..20.0f64, 1..20),
    ) {
        let law = SectionLaw::new(&s, kind);
        let st = law.station(x);
        let scale = curvature_scale(&s, eps);
        let mut slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        for u in path {
            let k = u * scale;
            let r = law.planar(&st, eps, k, &slip, &mut trial);
            let m = law.planar_moment(&st, eps, k, &slip);
            prop_assert_eq!(m.moment.to_bits(), r.moment.to_bits());
            prop_assert_eq!(m.moment_curvature.to_bits(), r.moment_curvature.to_bits());
            slip.copy_from_slice(&trial);
        }
    }
}

/// Edge cases give finite numbers: wires at phi = 0, phi -> 0, phi = +-pi, sin(phi) = 0,
/// zero curvature, zero and negative strain.
#[test]
fn edge_cases_are_finite() {
    for phase in [
        0.0,
        1e-300,
        1e-12,
        -1e-12,
        PI,
        -PI + 1e-15,
        PI - 1e-12,
        0.5 * PI,
    ] {
        let mut spec = common::table1();
        spec.layers[0].phase = phase;
        let s = Strand::new(spec).unwrap();
        for kind in [
            LawKind::Continuous,
            LawKind::Paper,
            LawKind::Hysteretic,
            LawKind::Constant,
        ] {
            let law = SectionLaw::new(&s, kind);
            let st = law.station(0.0);
            for eps in [-1e-3, 0.0, 1e-3] {
                for k in [0.0, 1e-300, 1e-12, -1e-12, 1.0, -1.0, 1e3] {
                    let mut trial = vec![0.0; law.state_len()];
                    let slip = vec![0.0; law.state_len()];
                    let r = law.planar(&st, eps, k, &slip, &mut trial);
                    for v in [r.moment, r.moment_curvature, r.moment_strain, r.energy] {
                        assert!(v.is_finite(), "{kind} phase {phase} eps {eps} k {k}: {r:?}");
                    }
                    let v = law.vector(&st, eps, [0.3 * k, k], &slip, &mut trial);
                    assert!(v.moment.iter().all(|m| m.is_finite()));
                    assert!(
                        v.moment_curvature.iter().flatten().all(|m| m.is_finite()),
                        "{kind} phase {phase} eps {eps} k {k}: {v:?}"
                    );
                    for w in law.planar_wires(&st, eps, k, &slip) {
                        assert!(w.k_stick.is_finite() && w.m_slip.is_finite());
                        if let Some(c) = w.critical_curvature {
                            assert!(c.is_finite() && c >= 0.0, "{w:?}");
                        }
                    }
                    assert!(law.planar_secant(&st, eps, k, &slip).is_finite());
                }
            }
        }
    }
}

/// phi -> 0: the critical curvature tends to sigma_a mu sin(alpha) / (E_w R_w cos^2(alpha)),
/// eq. (23)'s limit, for both laws with Papailiou's slip limit (hand computation: the slip
/// force cos(alpha) A_w sigma_a mu sin(alpha) theta meets the stick force eta E_w A_w R_w
/// kappa theta); with the paper's limit (22b) the continuous law's tends to cos^2(alpha) times
/// that (SPEC 2). phi -> pi: with Papailiou's limit the same finite limit (the slip starts
/// at both crossings); with the paper's it grows without bound. The stick stiffness vanishes.
#[test]
fn critical_curvature_limits() {
    let eps = 1e-3;
    let a = 20f64.to_radians();
    let (e, rw, mu) = (2.0e9, 2.5e-3, 0.3);
    let sigma = e * a.cos().powi(2) * eps;
    let limit = sigma * mu * a.sin() / (e * rw * a.cos().powi(2));
    let c2 = a.cos().powi(2);
    for (kind, slip_limit, want) in [
        (LawKind::Continuous, SlipLimit::Papailiou, limit),
        (LawKind::Paper, SlipLimit::Papailiou, limit),
        (LawKind::Continuous, SlipLimit::Paper, limit * c2),
        (LawKind::Paper, SlipLimit::Paper, limit),
    ] {
        let options = SectionOptions {
            slip_limit,
            ..Default::default()
        };
        // Phases toward the near crossing (0) and, with Papailiou's limit, the far one (pi).
        let toward_pi = slip_limit == SlipLimit::Papailiou;
        for far in [false, true].into_iter().filter(|f| !f || toward_pi) {
            let mut prev = f64::INFINITY;
            // Toward pi the phase's round-off (1e-16 rad) limits the approach.
            let steps: &[f64] = if far {
                &[1e-2, 1e-4, 1e-6]
            } else {
                &[1e-2, 1e-4, 1e-8, 1e-12]
            };
            for &d in steps {
                let mut spec = common::table1();
                spec.layers[0].phase = if far { PI - d } else { d };
                let s = Strand::new(spec).unwrap();
                let law = SectionLaw::with_options(&s, kind, &options);
                let w = law.planar_wires(&law.station(0.0), eps, -1.0, &[])[0];
                // The default stick stiffness is the bonded strand's, f K_stick: a wire slips
                // at 1/f times the plane section's critical curvature.
                let f = StickStiffness::default().factor(&s, 0);
                let err = (f * w.critical_curvature.unwrap() - want).abs() / want;
                assert!(
                    err <= prev.max(1e-9),
                    "{kind} {slip_limit}: error {err} at {d} from the crossing"
                );
                prev = err;
            }
            // The ratio gain / sin(theta) approaches its limit as 1 + c d / 2: 5e-8 at d = 1e-6.
            let tol = if far { 1e-7 } else { 1e-9 };
            assert!(
                prev < tol,
                "{kind} {slip_limit}: limit not reached ({prev})"
            );
        }
    }
    let paper = SectionOptions {
        slip_limit: SlipLimit::Paper,
        ..Default::default()
    };
    let mut last = 0.0;
    for d in [1e-1, 1e-3, 1e-6] {
        let mut spec = common::table1();
        spec.layers[0].phase = PI - d;
        let s = Strand::new(spec).unwrap();
        let law = SectionLaw::with_options(&s, LawKind::Continuous, &paper);
        let w = law.planar_wires(&law.station(0.0), eps, -1.0, &[])[0];
        let c = w.critical_curvature.unwrap();
        assert!(c > last);
        assert!(w.k_stick < 1e-3 * d * d * 1e3);
        last = c;
    }
}

/// Deep slip: as the curvature grows every wire slips and the pitch-mean moment tends to
/// K_min kappa plus the friction moments, by hand: each wire's limit is cos(alpha) A_w sigma_a
/// times the capstan gain of the angle theta_n from the nearest neutral-axis crossing, so over
/// a pitch its moment averages (I+ + I-) cos(alpha) A_w sigma_a R_w / pi with
/// I+ = int_0^{pi/2} (exp(c t) - 1) sin(t) dt = (c exp(c pi/2) + 1) / (1 + c^2) - 1 and
/// I- = int_0^{pi/2} (1 - exp(-c t)) sin(t) dt = 1 - (1 - c exp(-c pi/2)) / (1 + c^2),
/// c = mu sin(alpha). The paper's limit (the angle from one half of the neutral axis, over
/// [0, pi], and eta for cos(alpha)) averages (J+ + J-) eta A_w sigma_a R_w / (2 pi) with the
/// integrals over [0, pi], J+ = (exp(c pi) + 1) / (1 + c^2) - 2 and
/// J- = 2 - (exp(-c pi) + 1) / (1 + c^2).
#[test]
fn deep_slip_moment_is_the_friction_limits_by_hand() {
    let s = Strand::new(common::table1()).unwrap();
    let l = s.layers().first().unwrap();
    let (a, rw, m) = (l.lay_angle(), l.radius, l.wires() as f64);
    let w = &l.spec.wire;
    let eps = 2e-3;
    let sigma = w.material.youngs_modulus * a.cos().powi(2) * eps;
    let c = s.friction() * a.sin();
    let k_min = s.min_bending_stiffness(BaseStiffness::default());
    let half = 0.5 * PI;
    let papailiou = (((c * (c * half).exp() + 1.0) / (1.0 + c * c) - 1.0)
        + (1.0 - (1.0 - c * (-c * half).exp()) / (1.0 + c * c)))
        / PI;
    let paper = (((c * PI).exp() + 1.0) / (1.0 + c * c) - 2.0
        + (2.0 - ((-c * PI).exp() + 1.0) / (1.0 + c * c)))
        / (2.0 * PI);
    for (limit, mean, projection) in [
        (SlipLimit::Papailiou, papailiou, a.cos()),
        (SlipLimit::Paper, paper, a.cos().powi(3)),
    ] {
        let options = SectionOptions {
            slip_limit: limit,
            ..Default::default()
        };
        let law = SectionLaw::with_options(&s, LawKind::Continuous, &options);
        let friction = m * mean * projection * w.area() * sigma * rw;
        // 1e5 times the first-slip curvature: the stick zones are 1e-5 of a pitch.
        let kappa = 1e5 * sigma * c / (w.material.youngs_modulus * rw);
        let got = law.pitch_mean_moment(eps, kappa, 4096) - k_min * kappa;
        let err = (got / friction - 1.0).abs();
        // The stick zones (1e-5 of the wire) and the 4096-station midpoint rule (1e-6).
        assert!(
            err < 1e-4,
            "{limit}: friction moment {got} vs {friction} ({err})"
        );
    }
}

/// Hysteretic: after a preload to kappa_max, a closed cycle kappa_max -> -kappa_max ->
/// kappa_max at fixed strain returns the stored energy to its start, and the dissipated work
/// equals the area of the moment-curvature loop.
#[test]
fn hysteretic_cycle_energy_and_loop_area() {
    let s = Strand::new(common::table1()).unwrap();
    let law = SectionLaw::new(&s, LawKind::Hysteretic);
    let eps = 2e-3;
    for x in [0.0, 0.01, 0.0257] {
        let st = law.station(x);
        let kmax = 20.0 * curvature_scale(&s, eps);
        let n = 20000;
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
        let start = step(kmax, &mut slip);
        let (mut area, mut dissipated) = (0.0, 0.0);
        let mut prev = start;
        let mut k_prev = kmax;
        for i in 1..=4 * n {
            let t = i as f64 / (4 * n) as f64;
            let k = kmax * (2.0 * PI * t).cos();
            let r = step(k, &mut slip);
            area += 0.5 * (r.moment + prev.moment) * (k - k_prev);
            dissipated += r.slip_work;
            prev = r;
            k_prev = k;
        }
        assert!(
            (prev.energy - start.energy).abs() <= 1e-12 * start.energy,
            "stored energy {} -> {}",
            start.energy,
            prev.energy
        );
        assert!(dissipated > 0.0);
        // The loop is closed, so its area is the work done on the section, all dissipated.
        let rel = (area - dissipated).abs() / dissipated;
        assert!(
            rel < 1e-3,
            "loop area {area} vs dissipated {dissipated} ({rel})"
        );
    }
}

/// Hysteretic: unloading from full slip re-sticks every wire: the tangent is
/// K_min + sum K_stick_i.
#[test]
fn hysteretic_unloading_slope_is_all_stick() {
    let s = Strand::new(common::table1()).unwrap();
    let law = SectionLaw::new(&s, LawKind::Hysteretic);
    let eps = 2e-3;
    for x in [0.0, 0.0031, 0.02] {
        let st = law.station(x);
        let mut slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        let kmax = 1e4 * curvature_scale(&s, eps);
        let mut loaded = Default::default();
        for i in 1..=100 {
            loaded = law.planar(&st, eps, -kmax * i as f64 / 100.0, &slip, &mut trial);
            slip.copy_from_slice(&trial);
        }
        let loaded: strand_core::PlanarResponse = loaded;
        // Every wire with a lever slips at kmax; a wire on the neutral axis (phase 0) has no
        // friction limit and slips too.
        let wires = law.planar_wires(&st, eps, -kmax, &slip);
        let levered = wires
            .iter()
            .filter(|w| w.k_stick > 1e-12 * s.max_bending_stiffness(BaseStiffness::default()))
            .count();
        let free = wires
            .iter()
            .filter(|w| {
                w.m_slip == 0.0
                    && w.k_stick <= 1e-12 * s.max_bending_stiffness(BaseStiffness::default())
            })
            .count();
        assert_eq!(loaded.slipping, levered + free);
        let dk = 1e-6 * kmax;
        let un = law.planar(&st, eps, -kmax + dk, &slip, &mut trial);
        let slope = (un.moment - loaded.moment) / dk;
        let kstick: f64 = law
            .planar_wires(&st, eps, -kmax, &slip)
            .iter()
            .map(|w| w.k_stick)
            .sum();
        let want = s.min_bending_stiffness(BaseStiffness::default()) + kstick;
        assert!(
            (slope - want).abs() <= 1e-8 * want,
            "slope {slope} vs {want}"
        );
        assert_eq!(un.slipping, free);
        assert!((un.moment_curvature - want).abs() <= 1e-12 * want);
    }
}

/// The traditional (`constant`) law is linear with the envelope cylinder's EI and EA.
#[test]
fn constant_law_is_the_traditional_beam() {
    let s = Strand::new(common::table1()).unwrap();
    let law = SectionLaw::new(&s, LawKind::Constant);
    let t = s.traditional();
    let st = law.station(0.1);
    let r = law.planar(&st, 1e-3, -2.0, &[], &mut []);
    assert!((r.moment + 2.0 * t.bending_stiffness).abs() < 1e-15);
    assert!((r.axial_force - 1e-3 * t.axial_stiffness).abs() < 1e-12);
    assert_eq!(law.planar_wires(&st, 1e-3, -2.0, &[]).len(), 0);
}

/// The energy bookkeeping closes: along a path in (eps, kappa) at fixed slip, the work of the
/// section forces equals the change of stored energy minus the non-potential work
/// `energy_strain d eps` (SPEC 2). Checked against the trapezoidal work on a fine path.
#[test]
fn non_potential_work_closes_the_energy_balance() {
    let s = Strand::new(common::table1()).unwrap();
    for kind in [LawKind::Continuous, LawKind::Paper, LawKind::Constant] {
        let law = SectionLaw::new(&s, kind);
        for x in [0.0, 0.007, 0.02] {
            let st = law.station(x);
            let n = 20000;
            let path = |t: f64| {
                let eps = 1e-3 * (1.0 + 0.8 * (3.0 * t).sin());
                let k = -2.0 * (2.0 * PI * t).sin() + 0.5 * t;
                (eps, k)
            };
            let (e0, k0) = path(0.0);
            let mut prev = law.planar(&st, e0, k0, &[], &mut []);
            let (mut work, mut non_potential) = (0.0, 0.0);
            let (mut ep, mut kp) = (e0, k0);
            let start = prev.energy;
            for i in 1..=n {
                let (e, k) = path(i as f64 / n as f64);
                let r = law.planar(&st, e, k, &[], &mut []);
                work += 0.5 * (r.axial_force + prev.axial_force) * (e - ep)
                    + 0.5 * (r.moment + prev.moment) * (k - kp);
                non_potential += 0.5 * (r.energy_strain + prev.energy_strain) * (e - ep);
                prev = r;
                ep = e;
                kp = k;
            }
            let stored = prev.energy - start;
            let err = (work - (stored - non_potential)).abs();
            // The paper law's moment jumps at each switch; the trapezoidal work then errs by
            // half the jump times the step at every crossing (O(1/n), not O(1/n^2)).
            let tol = if kind == LawKind::Paper { 1e-4 } else { 1e-6 };
            assert!(
                err <= tol * prev.energy.abs().max(start),
                "{kind} x {x}: work {work} stored {stored} non-potential {non_potential}"
            );
            if kind == LawKind::Constant {
                assert_eq!(non_potential, 0.0);
            }
        }
    }
}

/// In 3D the bending direction turns: along a path in (eps, kappa_y, kappa_z) the work of the
/// section forces equals the change of stored energy plus the slip work (hysteretic law,
/// committed at every step) minus the non-potential work `energy_strain d eps + energy_turn .
/// d kappa`. Without the last term the balance of the `continuous` law is off by the change of
/// its slip energy when the friction limits turn with the bending direction (checked too), so
/// the test fails if `energy_turn` is wrong or missing; the `hysteretic` law books that change
/// as slip work and has no turn term. Both
/// slip limits: the paper's (smooth in the bending direction) and Papailiou's, whose limit
/// has a kink where a wire passes the extreme fibre.
#[test]
fn non_potential_work_closes_the_energy_balance_in_3d() {
    let s = Strand::new(common::table1()).unwrap();
    for (kind, limit) in [
        LawKind::Continuous,
        LawKind::Paper,
        LawKind::Hysteretic,
        LawKind::Constant,
    ]
    .into_iter()
    .flat_map(|k| SlipLimit::ALL.map(|l| (k, l)))
    {
        let options = SectionOptions {
            slip_limit: limit,
            ..Default::default()
        };
        let law = SectionLaw::with_options(&s, kind, &options);
        for x in [0.0, 0.007, 0.02] {
            let st = law.station(x);
            let mut slip = vec![0.0; law.state_len()];
            let mut trial = slip.clone();
            let n = 20000;
            // The bending direction swings by about 84 degrees and back with a varying
            // magnitude and strain, keeping kappa_z > 0 (where kappa_z changes sign the
            // friction limits jump, see `SectionLaw::vector`).
            let path = |t: f64| {
                let eps = 1e-3 * (1.0 + 0.8 * (3.0 * t).sin());
                let a = 2.0 * PI * t;
                let m = 2.0 * (1.0 + 0.5 * (5.0 * t).cos());
                (eps, [m * a.cos(), m * (a.sin() + 1.5)])
            };
            let (e0, k0) = path(0.0);
            let mut prev = law.vector(&st, e0, k0, &slip, &mut trial);
            slip.copy_from_slice(&trial);
            let (mut work, mut non_potential, mut turn, mut slip_work) = (0.0, 0.0, 0.0, 0.0);
            let (mut ep, mut kp) = (e0, k0);
            let start = prev.energy;
            for i in 1..=n {
                let (e, k) = path(i as f64 / n as f64);
                let r = law.vector(&st, e, k, &slip, &mut trial);
                slip.copy_from_slice(&trial);
                work += 0.5 * (r.axial_force + prev.axial_force) * (e - ep);
                for j in 0..2 {
                    work += 0.5 * (r.moment[j] + prev.moment[j]) * (k[j] - kp[j]);
                    turn += 0.5 * (r.energy_turn[j] + prev.energy_turn[j]) * (k[j] - kp[j]);
                }
                non_potential += 0.5 * (r.energy_strain + prev.energy_strain) * (e - ep);
                slip_work += r.slip_work;
                prev = r;
                ep = e;
                kp = k;
            }
            let stored = prev.energy - start;
            let scale = prev.energy.abs().max(start);
            let err = (work - (stored + slip_work - non_potential - turn)).abs();
            // The paper law's moment jumps at each switch: against the trapezoidal work it errs
            // at first order in the step at every switch. The hysteretic law books the
            // trapezoid of its moving limits, second order (the order is held by
            // tests/slip_work.rs); its limit here is the paper law's.
            // Papailiou's limit is continuous but has a kink at the extreme fibre (theta_n =
            // min(theta, pi - theta)): there `energy_turn` of a slipping wire changes sign, and
            // the trapezoid errs at first order in the step at each such crossing (measured
            // 0.8e-6 to 6.4e-6 of the energy at 20000 steps, 0.1e-6 to 1.5e-6 at 80000; with the
            // paper's limit 0.5e-9 to 2.7e-9, second order).
            let tol = match (kind, limit) {
                (LawKind::Paper | LawKind::Hysteretic, _) => 1e-4,
                (_, SlipLimit::Papailiou) => 2e-5,
                _ => 1e-6,
            };
            assert!(
                err <= tol * scale,
                "{kind} {limit} x {x}: work {work} stored {stored} slip {slip_work} \
                 non-potential {non_potential} turn {turn}"
            );
            if matches!(kind, LawKind::Constant | LawKind::Hysteretic) {
                // No stored energy that depends on a friction limit.
                assert_eq!(turn, 0.0);
            } else if kind != LawKind::Paper {
                // The turn term is far above the tolerance on this path: the balance needs it.
                assert!(
                    turn.abs() > 10.0 * tol * scale,
                    "{kind} {limit} x {x}: turn {turn}"
                );
            }
            if kind == LawKind::Hysteretic {
                assert!(slip_work > 0.0);
            }
        }
    }
}

/// The per-wire report of a curvature vector: with kappa_y = 0 it is the planar report; turning
/// the bending direction and the wires together by an angle leaves every wire's phase from the
/// neutral axis, critical curvature and state unchanged.
#[test]
fn vector_wire_report_follows_the_bending_direction() {
    let s = Strand::new(common::table1()).unwrap();
    for kind in [LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic] {
        let law = SectionLaw::new(&s, kind);
        let slip = vec![0.0; law.state_len()];
        for x in [0.0, 0.011, 0.03] {
            let st = law.station(x);
            for k in [-3.0, -0.05, 0.0, 0.05, 3.0] {
                let p = law.planar_wires(&st, 2e-3, k, &slip);
                let v = law.vector_wires(&st, 2e-3, [0.0, k], &slip);
                for (a, b) in p.iter().zip(&v) {
                    assert!((a.phase - b.phase).abs() < 1e-12, "{kind} {x} {k}");
                    assert_eq!(a.state, b.state, "{kind} {x} {k}");
                    match (a.critical_curvature, b.critical_curvature) {
                        (Some(c), Some(d)) => assert!((c - d).abs() <= 1e-10 * c),
                        (c, d) => assert_eq!(c, d),
                    }
                    assert!((a.k_stick - b.k_stick).abs() <= 1e-12 * a.k_stick.max(1e-30));
                }
            }
        }
        // A strand whose phases are shifted by psi, bent in the direction turned by psi
        // (kappa_z < 0 keeps the neutral-axis half), reports the same table.
        let psi = 0.4;
        let mut spec = common::table1();
        spec.layers[0].phase += psi;
        let turned = SectionLaw::new(&Strand::new(spec).unwrap(), kind);
        let st = law.station(0.011);
        let st2 = turned.station(0.011);
        let k = 2.0;
        // (kappa_y, kappa_z) = k (-sin(psi), -cos(psi)) turned from (0, -k).
        let a = law.vector_wires(&st, 2e-3, [0.0, -k], &slip);
        let b = turned.vector_wires(&st2, 2e-3, [-k * psi.sin(), -k * psi.cos()], &slip);
        for (a, b) in a.iter().zip(&b) {
            assert!((a.phase - b.phase).abs() < 1e-12, "{kind}: {a:?} {b:?}");
            assert_eq!(a.state, b.state);
            assert!((a.critical_curvature.unwrap() - b.critical_curvature.unwrap()).abs() < 1e-9);
        }
    }
}

/// After slip in one plane a small curvature out of that plane meets a non-negative
/// stiffness: the Table 1 strand (x = 0.013 m, strain 1e-3) bent in the z plane to 4 1/m,
/// where its wires slip, then (hysteretic law) unloaded to 0.001 1/m, where they slip back,
/// and bent again to 0.002 and 0.003 1/m, where they stick with residual forces that oppose
/// the curvature. A stuck wire keeps its force in the section frame, so `dM_y/dkappa_y` is
/// `K_min` plus the stuck wires' `k l_iy^2`; while the wires slip forward their friction
/// limits turn with the bending direction and add a positive stiffness. Checked on the
/// analytic tangent and on the secant over an out-of-plane curvature small enough to leave
/// every wire's state as it is. A moment kept parallel to the curvature turns the residual
/// moment `m` of the stuck wires with the bending direction, `dM_y/dkappa_y = K_min +
/// m/|kappa|`, negative at these states. (While the wires slip back beyond the still
/// curvature, at 0.2 1/m, their limits turn with the bending direction, against the
/// curvature: printed, not asserted; the README's finding. Below it, at 0.01 and 0.001 1/m,
/// the hysteretic law keeps the stored direction: `stored_bending_direction_near_zero_curvature`.)
#[test]
fn out_of_plane_stiffness_after_slip_is_not_negative() {
    let s = Strand::new(common::table1()).unwrap();
    for kind in [LawKind::Continuous, LawKind::Paper, LawKind::Hysteretic] {
        let law = SectionLaw::new(&s, kind);
        let kmin = law.base_bending_stiffness();
        let st = law.station(0.013);
        let eps = 1e-3;
        let mut slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        // Loaded to 4 1/m in steps of 0.01 1/m, back to 0.001 and up to 0.003 in steps of
        // 0.001 1/m, the state committed at every step.
        let n = |a: f64, b: f64, h: f64| ((b - a) / h).abs().round() as usize;
        let path: Vec<f64> = (1..=400)
            .map(|i| 0.01 * i as f64)
            .chain((1..=n(4.0, 0.001, 0.001)).map(|i| 4.0 - 0.001 * i as f64))
            .chain([0.002, 0.003])
            .collect();
        let mut checked = 0;
        for (i, &k) in path.iter().enumerate() {
            // The step from the state committed at the last curvature: perturbed below.
            let r = law.vector(&st, eps, [0.0, k], &slip, &mut trial);
            let committed = slip.clone();
            slip.copy_from_slice(&trial);
            let slip = &committed;
            let t = r.moment_curvature[0][0];
            // Loaded (every law); bent again after slipping back (the hysteretic law's
            // history).
            let loaded = i == 399;
            let again = i + 2 >= path.len();
            let back = i > 399 && [0.2, 0.01, 0.001].iter().any(|a| (k - a).abs() < 1e-9);
            if kind == LawKind::Hysteretic && back && !again {
                println!(
                    "slipping back at {k:.3} 1/m: {} wires slip, dM_y/dkappa_y {t:.3e} N m^2, \
                     M_z {:.3e} N m",
                    r.slipping, r.moment[1]
                );
            }
            if !(loaded || (again && kind == LawKind::Hysteretic)) {
                continue;
            }
            if loaded {
                assert_eq!(r.slipping, 6, "{kind}: not every wire slips at 4 1/m");
            } else {
                // Stuck, with the layer's residual moment against the curvature.
                assert_eq!(r.slipping, 0, "{kind} at {k}");
                assert!(r.moment[1] < 0.0, "{kind} at {k}: {:?}", r.moment);
                assert!(t >= kmin, "{kind} at {k}: {t}");
            }
            assert!(t >= 0.0, "{kind} at {k} 1/m: dM_y/dkappa_y {t}");
            let states = |kv| -> Vec<WireState> {
                law.vector_wires(&st, eps, kv, slip)
                    .iter()
                    .map(|w| w.state)
                    .collect()
            };
            let before = states([0.0, k]);
            // The secant over kappa_y = d, halved until no wire changes state.
            let mut d = 1e-3 * k;
            let secant = loop {
                let mut tp = slip.clone();
                let p = law.vector(&st, eps, [d, k], slip, &mut tp);
                if states([d, k]) == before {
                    break (p.moment[0] - r.moment[0]) / d;
                }
                d *= 0.5;
                assert!(
                    d > 1e-12 * k,
                    "{kind} at {k} 1/m: every kappa_y changes a state"
                );
            };
            println!("{kind} at {k:.3} 1/m: dM_y/dkappa_y {t:.3e}, secant {secant:.3e} N m^2");
            assert!(
                secant >= 0.0 && (secant - t).abs() <= 1e-3 * (t + kmin),
                "{kind} at {k} 1/m: secant {secant} tangent {t}"
            );
            checked += 1;
        }
        let want = if kind == LawKind::Hysteretic { 3 } else { 1 };
        assert_eq!(checked, want, "{kind}");
    }
}

/// The hysteretic law's stored bending direction (module docs of `section`), Table 1 strand,
/// strain 1e-3, both slip limits. (1) `still_curvature` is a lower bound on the first slip:
/// from no slip, a curvature of 0.999 times it slips no wire at any station of a pitch in any
/// direction, and twice it slips some (the bound is not vacuous). (2) Bent in the z plane to
/// 4 1/m, where every wire slips, and unloaded to 0.001 1/m (x = 0.013 m), where the layer
/// slips back, an out-of-plane curvature meets `dM_y/dkappa_y >= K_min`: the friction limits
/// keep the direction of the bending that made the wires slip (turned with the direction of
/// `kappa`, they gave -0.52 N m^2 here). (3) Bent again to 0.003 1/m, where every wire
/// sticks with a residual force, out-of-plane curvatures of 0.1 to 0.9 times the still
/// curvature slip no wire and meet a secant stiffness of at least `K_min`.
#[test]
fn stored_bending_direction_near_zero_curvature() {
    let s = Strand::new(common::table1()).unwrap();
    let eps = 1e-3;
    let pitch = s.layers().first().unwrap().pitch;
    for limit in SlipLimit::ALL {
        let options = SectionOptions {
            slip_limit: limit,
            ..Default::default()
        };
        let law = SectionLaw::with_options(&s, LawKind::Hysteretic, &options);
        let still = law.still_curvature(eps);
        assert!(still > 0.0);
        let zero = vec![0.0; law.state_len()];
        let mut trial = zero.clone();
        let mut above = 0;
        for j in 0..40 {
            let st = law.station(pitch * j as f64 / 40.0);
            for a in 0..48 {
                let d = PI * a as f64 / 24.0;
                let kv = |m: f64| [m * still * d.sin(), m * still * d.cos()];
                // No slip and no stored direction: the limits of the curvature's direction.
                let state = &zero;
                // The wires' reported states: a wire on the neutral axis has no friction
                // limit and no force, and is reported by its critical curvature.
                let slipping = |m: f64| {
                    law.vector_wires(&st, eps, kv(m), state)
                        .iter()
                        .filter(|w| w.state == WireState::Slip)
                        .count()
                };
                assert_eq!(slipping(0.999), 0, "{limit} station {j} direction {a}");
                above += slipping(2.0);
            }
        }
        assert!(
            above > 0,
            "{limit}: nothing slips at twice the still curvature"
        );

        let kmin = law.base_bending_stiffness();
        let st = law.station(0.013);
        let mut slip = zero.clone();
        let path: Vec<f64> = (1..=400)
            .map(|i| 0.01 * i as f64)
            .chain((1..=3998).map(|i| 4.0 - 0.001 * i as f64))
            .collect();
        // Committed at every step down to 0.002 1/m; slipping back at 0.001 1/m.
        for &k in &path {
            law.vector(&st, eps, [0.0, k], &slip, &mut trial);
            slip.copy_from_slice(&trial);
        }
        let k = 0.001;
        assert!(still > 10.0 * k, "{limit}: still curvature {still}");
        let prev = slip.clone();
        let r = law.vector(&st, eps, [0.0, k], &prev, &mut trial);
        assert!(r.slipping > 0, "{limit}: the layer does not slip back");
        let t = r.moment_curvature[0][0];
        let h = 1e-3 * k;
        let p = law.vector(&st, eps, [h, k], &prev, &mut trial);
        let secant = (p.moment[0] - r.moment[0]) / h;
        println!("{limit} slipping back at {k} 1/m: dM_y/dkappa_y {t:.4e}, secant {secant:.4e}");
        assert!(
            t >= kmin && secant >= kmin * (1.0 - 1e-6),
            "{limit}: {t} {secant}"
        );

        // Bent again to 0.003 1/m: every wire sticks.
        for k in [0.001, 0.002, 0.003] {
            law.vector(&st, eps, [0.0, k], &slip, &mut trial);
            slip.copy_from_slice(&trial);
        }
        // Bent again by 0.002 1/m from the slip back, each wire's force has left its limit
        // by k R_w sin(theta) 0.002 (theta = |phi|, the limits those of the bending in z); an
        // out-of-plane curvature d changes it by at most k R_w |cos(theta)| d, so no wire
        // slips while d < 0.002 |tan(theta)| for every wire (half of it here).
        let safe = 0.5
            * 0.002
            * law
                .planar_wires(&st, eps, 0.003, &slip)
                .iter()
                .map(|w| w.phase.tan().abs())
                .fold(f64::INFINITY, f64::min);
        let r = law.vector(&st, eps, [0.0, 0.003], &slip, &mut trial);
        assert_eq!(r.slipping, 0, "{limit}");
        for d in [
            0.1 * safe,
            safe,
            0.1 * still,
            0.3 * still,
            0.6 * still,
            0.9 * still,
        ] {
            let p = law.vector(&st, eps, [d, 0.003], &slip, &mut trial);
            let secant = (p.moment[0] - r.moment[0]) / d;
            let t = p.moment_curvature[0][0];
            println!(
                "{limit} at (kappa_y {d:.3e}, 0.003) 1/m: {} slip, dM_y/dkappa_y {t:.4e}, \
                 secant {secant:.4e} N m^2",
                p.slipping
            );
            if d <= safe {
                assert_eq!(p.slipping, 0, "{limit} at kappa_y {d}");
            }
            // A wire that slips holds its limit of the bending in z, which the out-of-plane
            // curvature does not turn: its force changes with the sign of its strain change.
            assert!(
                t >= kmin && secant >= kmin * (1.0 - 1e-9),
                "{limit} at kappa_y {d}: {t} {secant}"
            );
        }
    }
}
