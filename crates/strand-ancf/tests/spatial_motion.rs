//! Large 3D motion of the spatial beam: the section frames turn without spin about the tangent
//! (holonomy of the transport around a cone), a swing through the reversed tangent, the same
//! motion as the planar element in any plane, point forces, moving supports (statics and
//! dynamics) and the pretensioned span against closed forms.

use nalgebra::{Rotation3, Unit, Vector3};
use strand_ancf::beam::{Beam, BeamSpec, ElementKind, PointLoad, Support, SupportMotion};
use strand_ancf::dynamics::{
    DynamicOptions, DynamicSummary, Scheme, run_dynamic, run_dynamic_from,
};
use strand_ancf::initial::InitialState;
use strand_ancf::statics::{StaticOptions, solve_static};
use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

/// The paper's section-3 strand (L = 1 m, E = 2e9 Pa, rho = 5747 kg/m^3).
fn section3() -> Strand {
    Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap()
}

/// The paper's Table 1 strand (L = 0.4 m, E = 2e8 Pa).
fn table1() -> Strand {
    Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap()
}

fn spatial(s: &Strand, kind: LawKind, spec: BeamSpec) -> Beam {
    Beam::new(
        BeamSpec {
            mass_per_length: s.mass_per_length(),
            element: ElementKind::Spatial,
            ..spec
        },
        SectionLaw::new(s, kind),
    )
    .unwrap()
}

/// `q` turned rigidly by `r` about the origin (positions and slopes).
fn rotate(q: &[f64], r: &Rotation3<f64>) -> Vec<f64> {
    let mut out = q.to_vec();
    for c in out.chunks_exact_mut(3) {
        let v = r * Vector3::new(c[0], c[1], c[2]);
        c.copy_from_slice(v.as_slice());
    }
    out
}

/// Transports the section frames of a strand turned rigidly about `axis` through a full turn in
/// `n` accepted steps; returns the turn (rad) of every bending point's phase axis about the
/// tangent, against the start.
fn cone_holonomy(axis: Vector3<f64>, n: usize) -> Vec<f64> {
    let s = table1();
    let b = spatial(
        &s,
        LawKind::Constant,
        BeamSpec {
            elements: 2,
            ..Default::default()
        },
    );
    let mut state = b.initial_state();
    let mut trial = state.clone();
    let mut force = vec![0.0; b.coords()];
    let axis = Unit::new_normalize(axis);
    for k in 1..=n {
        let r = Rotation3::from_axis_angle(&axis, 2.0 * std::f64::consts::PI * k as f64 / n as f64);
        let q = rotate(b.reference(), &r);
        b.internal(&q, &state, &mut trial, &mut force, None, None)
            .unwrap();
        state.copy_from_slice(&trial);
    }
    (0..b.points())
        .map(|i| {
            let [t, _, ez] = b.point_frame(&state, i).unwrap();
            assert!((t - Vector3::x()).norm() < 1e-12);
            // Signed angle from Z to e_z about the tangent X.
            Vector3::z().cross(&ez).dot(&t).atan2(Vector3::z().dot(&ez))
        })
        .collect()
}

/// A strand turned round a cone (its tangent around a small circle of angular radius beta)
/// comes back with its sections turned about the tangent by the enclosed solid angle
/// 2 pi (1 - cos beta), the holonomy of transport without spin; the error of the polygon of
/// accepted tangents falls at second order in the step. A frame carried from the initial
/// tangent instead (no per-step transport) would come back unturned.
#[test]
fn sections_turn_without_spin_and_show_the_holonomy_of_a_cone() {
    for beta in [0.3f64, 45f64.to_radians(), 1.2] {
        let axis = Vector3::new(beta.cos(), beta.sin(), 0.0);
        let omega = 2.0 * std::f64::consts::PI * (1.0 - beta.cos());
        let expect = omega.sin().atan2(omega.cos());
        let errs: Vec<f64> = [100, 200]
            .iter()
            .map(|&n| {
                let turns = cone_holonomy(axis, n);
                // Every point of the rigid strand has the same tangent path, so the same turn.
                assert!(turns.iter().all(|t| (t - turns[0]).abs() < 1e-12));
                let d = turns[0] - expect;
                d.sin().atan2(d.cos()).abs()
            })
            .collect();
        println!(
            "cone beta {beta:.3}: holonomy errors {:.3e} and {:.3e} at 100 and 200 steps",
            errs[0], errs[1]
        );
        assert!(errs[1] < 1e-3, "beta {beta}: {errs:?}");
        assert!(
            errs[0] / errs[1] > 3.5 && errs[0] / errs[1] < 4.5,
            "{errs:?}"
        );
    }
}

fn run(b: &Beam, duration: f64, h: f64, increment: f64) -> (Vec<[f64; 3]>, DynamicSummary) {
    let mut o = DynamicOptions::new(
        duration,
        Scheme::GeneralizedAlpha {
            step: h,
            spectral_radius: 0.9,
        },
        0.01,
    );
    o.increment = increment;
    let mut tips = Vec::new();
    let s = run_dynamic(b, &o, &mut |f| tips.push(b.sample(f.q, b.length()).0)).unwrap();
    (tips, s)
}

/// The section-3 pendulum (pinned, generalized-alpha 1 ms) swings through the opposite of its
/// initial tangent at t = 0.77 s, where a frame carried from the initial tangent is singular.
/// Released in the XY plane and in the tilted plane of gravity (0, -9.8, -4) (with the phase
/// reference turned into that plane), the spatial beam follows the planar beam's motion
/// rotated into the plane, for 1 s: within 1e-6 L with Newton converged to 1e-11 L (the
/// difference of two converged runs shrinks with the Newton tolerance: 8.7e-7 m at the default
/// 1e-8 L, 4.4e-8 m at 1e-11 L, measured for the tilted plane).
#[test]
fn pendulum_in_any_plane_is_the_planar_pendulum() {
    let s = section3();
    let g = 9.8f64.hypot(4.0);
    let down = Vector3::new(0.0, -9.8, -4.0) / g;
    // The rotation taking the planar run's (X, -Y) to (X, down).
    let rot = Rotation3::from_basis_unchecked(&[Vector3::x(), -down, Vector3::x().cross(&-down)]);
    let pendulum = |element, gravity: Vector3<f64>, reference: Vector3<f64>| {
        Beam::new(
            BeamSpec {
                elements: 30,
                mass_per_length: s.mass_per_length(),
                element,
                gravity: gravity.into(),
                start: Some(Support::Pinned),
                phase_reference: Some(reference.into()),
                ..Default::default()
            },
            SectionLaw::new(&s, LawKind::Constant),
        )
        .unwrap()
    };
    let planar = pendulum(ElementKind::Planar, -g * Vector3::y(), Vector3::z());
    let (p, _) = run(&planar, 1.0, 1e-3, 1e-11);
    for (name, b, r) in [
        (
            "XY plane",
            pendulum(ElementKind::Spatial, -g * Vector3::y(), Vector3::z()),
            Rotation3::identity(),
        ),
        (
            "tilted plane",
            pendulum(ElementKind::Spatial, g * down, rot * Vector3::z()),
            rot,
        ),
    ] {
        let (t, sum) = run(&b, 1.0, 1e-3, 1e-11);
        let d = p
            .iter()
            .zip(&t)
            .map(|(a, b)| (r * Vector3::from(*a) - Vector3::from(*b)).norm())
            .fold(0.0, f64::max);
        // The tip passes below the pin (x < 0) and comes back: the tangent reversed.
        let reversed = t.iter().any(|x| x[0] < -0.5);
        println!(
            "{name}: tip within {d:.3e} m of the planar run, balance {:.2e}",
            sum.balance_error
        );
        assert!(reversed, "{name}: the tip never passed behind the pin");
        assert!(d < 1e-6 * s.length(), "{name}: {d}");
    }
}

/// A point force on a clamped cantilever (traditional law, small load): the deflection at the
/// tip of a force P at a is P a^2 (3 L - a) / (6 EI), in any direction; its generalized force
/// is the shape functions' row at its place, so a force at a node equals a nodal force.
#[test]
fn point_force_bends_a_cantilever_by_the_closed_form() {
    let s = table1();
    let law = SectionLaw::new(&s, LawKind::Constant);
    let ei = law.base_bending_stiffness();
    let l = s.length();
    let dir = Vector3::new(0.3, -0.5, 0.8).normalize();
    let side = Vector3::new(0.0, 1.0, 0.4).normalize();
    let side = (side - dir * dir.dot(&side)).normalize();
    for a in [0.4 * l, 0.73 * l, l] {
        let p = 1e-4 * ei / (l * l);
        let b = Beam::new(
            BeamSpec {
                elements: 8,
                mass_per_length: s.mass_per_length(),
                element: ElementKind::Spatial,
                direction: dir.into(),
                start: Some(Support::Clamped),
                point_loads: vec![PointLoad {
                    s: a,
                    force: (side * p).into(),
                }],
                ..Default::default()
            },
            law.clone(),
        )
        .unwrap();
        let sol = solve_static(&b, &StaticOptions::default(), &mut |_| {}).unwrap();
        let tip = Vector3::from(b.sample(&sol.q, l).0);
        let w = (tip - dir * l).dot(&side);
        let expect = p * a * a * (3.0 * l - a) / (6.0 * ei);
        println!("point force at {a}: tip {w:.6e} against {expect:.6e}");
        // Small deflection (w / L about 1e-4): the geometric nonlinearity is of order
        // (w / L)^2 and the cubic elements are exact for a point load at a node.
        assert!((w - expect).abs() < 1e-3 * expect, "{w} {expect}");
    }
}

/// Pulling one end of a straight strand pinned at both ends (statics, the motion's last row
/// with the load steps) stretches it uniformly: every point at x (1 + d / L), to 1e-9 L.
#[test]
fn moving_support_pulls_a_span_uniformly_in_statics() {
    let s = section3();
    let d = 2e-3;
    let dir = Vector3::new(1.0, 2.0, -2.0).normalize();
    let disp = dir * d;
    let b = spatial(
        &s,
        LawKind::Hysteretic,
        BeamSpec {
            elements: 10,
            direction: dir.into(),
            start: Some(Support::Pinned),
            end: Some(Support::Pinned),
            end_motion: Some(SupportMotion::new(&[[1.0, disp.x, disp.y, disp.z]]).unwrap()),
            ..Default::default()
        },
    );
    let sol = solve_static(&b, &StaticOptions::default(), &mut |_| {}).unwrap();
    let worst = (0..=20)
        .map(|i| {
            let x = i as f64 / 20.0;
            (Vector3::from(b.sample(&sol.q, x).0) - dir * x * (1.0 + d)).norm()
        })
        .fold(0.0, f64::max);
    assert!(worst < 1e-9 * s.length(), "{worst}");
}

/// A strand translating at velocity V whose pinned end is carried along at V: it moves
/// rigidly, with no strain, no support work and a closed balance.
#[test]
fn moving_support_carries_a_translating_strand_rigidly() {
    let s = table1();
    let v = Vector3::new(0.4, -0.3, 0.5);
    let b = spatial(
        &s,
        LawKind::Continuous,
        BeamSpec {
            elements: 6,
            start: Some(Support::Pinned),
            start_motion: Some(SupportMotion::new(&[[1.0, v.x, v.y, v.z]]).unwrap()),
            ..Default::default()
        },
    );
    let init = InitialState::rigid(&b, v.into(), [0.0; 3]).unwrap();
    let opts = DynamicOptions::new(
        0.5,
        Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 0.9,
        },
        0.1,
    );
    let sum = run_dynamic_from(&b, &opts, &init, &mut |_| {}).unwrap();
    let tip = Vector3::from(b.sample(&sum.q, s.length()).0);
    let expect = Vector3::x() * s.length() + v * 0.5;
    println!(
        "translation: tip off by {:.2e} m, support work {:.2e} J, balance {:.2e} J",
        (tip - expect).norm(),
        sum.last.supports,
        sum.balance_error
    );
    assert!((tip - expect).norm() < 1e-12, "{tip:?}");
    // Round-off of the kinetic energy, 1/2 m |V|^2 = 0.021 J.
    let round = 1e-12 * sum.max_kinetic;
    assert!(sum.last.supports.abs() < round && sum.balance_error < round);
}

/// The support work books the energy a moving support puts in: with the pinned end of a
/// hanging strand driven round a circle (smooth start), kinetic + gravity + elastic +
/// dissipated - support work stays constant up to the integrator's error, which falls with the
/// step at second order for the linear law and at first order for the hysteretic law (whose
/// return mapping books a step's slip at its end); a booking error would not fall.
#[test]
fn moving_support_work_closes_the_energy_balance() {
    let s = table1();
    for kind in [LawKind::Constant, LawKind::Hysteretic] {
        let (a, w, ramp) = (0.03, 2.0 * std::f64::consts::PI * 3.0, 0.1);
        let rows: Vec<[f64; 4]> = (1..=400)
            .map(|i| {
                let t = i as f64 * 5e-4;
                let x = (t / ramp).min(1.0);
                let r = a * x * x * (3.0 - 2.0 * x);
                [t, r * ((w * t).cos() - 1.0), 0.0, r * (w * t).sin()]
            })
            .collect();
        let b = spatial(
            &s,
            kind,
            BeamSpec {
                elements: 8,
                gravity: [0.0, -9.8, 0.0],
                start: Some(Support::Pinned),
                start_motion: Some(SupportMotion::new(&rows).unwrap()),
                ..Default::default()
            },
        );
        let errs: Vec<f64> = [1e-3, 5e-4]
            .iter()
            .map(|&h| {
                let o = DynamicOptions::new(
                    0.2,
                    Scheme::GeneralizedAlpha {
                        step: h,
                        spectral_radius: 1.0,
                    },
                    0.01,
                );
                let sum = run_dynamic(&b, &o, &mut |_| {}).unwrap();
                assert!(sum.last.supports.abs() > 1e-3 * sum.max_kinetic);
                sum.balance_error / sum.max_kinetic
            })
            .collect();
        println!(
            "{kind}: balance {:.2e} and {:.2e} of the largest kinetic energy at 1 and 0.5 ms",
            errs[0], errs[1]
        );
        let order = if kind == LawKind::Constant { 3.0 } else { 1.6 };
        assert!(errs[0] / errs[1] > order, "{kind}: {errs:?}");
    }
}

/// A span of `length` (m) of the section-3 strand, pinned at both ends, its end pulled along
/// the strand by `pull` (m, negative: pushed in; zero: a fixed end), under gravity `g`
/// (m/s^2) across it.
fn span(length: f64, kind: LawKind, elements: usize, pull: f64, g: [f64; 3]) -> Beam {
    let s = Strand::new(StrandSpec::paper(length, 2.0e9, 5747.0)).unwrap();
    Beam::new(
        BeamSpec {
            elements,
            mass_per_length: s.mass_per_length(),
            element: ElementKind::Spatial,
            gravity: g,
            start: Some(Support::Pinned),
            end: Some(Support::Pinned),
            end_motion: (pull != 0.0)
                .then(|| SupportMotion::new(&[[1.0, pull, 0.0, 0.0]]).unwrap()),
            ..Default::default()
        },
        SectionLaw::new(&s, kind),
    )
    .unwrap()
}

/// Bending stiffness of the small-curvature state: the envelope EI for the constant law, the
/// all-stick K_max for a stick/slip law under tension.
fn small_curvature_ei(b: &Beam) -> f64 {
    let law = b.law();
    if law.kind() == LawKind::Constant {
        law.base_bending_stiffness()
    } else {
        law.stick_bending_stiffness()
    }
}

/// A taut span (section-3 strand, 1 m, pulled to T0 = 100 N, then gravity, statics): the
/// midspan sag against the closed form of a pretensioned pinned beam-string,
/// `q X^2 / (8 H) + (q EI / H^2) (sech(k X / 2) - 1)` with `k = sqrt(H / EI)`, the span
/// `X = L (1 + T0 / EA)`, the weight `q` per span length and the tension `H` raised by the
/// stretch of the deflection `w`, `H = T0 + EA / (2 L) int w'^2 dx` (Irvine's cable equation
/// with the beam-string's shape); within 2e-4 of the sag (what is left out: (sag / L)^2 = 4e-6
/// of geometric nonlinearity, the tension's change along the span, of order (w')^2 = 6e-5). The taut-cable value
/// `q L^2 / (8 T0)` is the first term with the pretension: the sag differs from it by the
/// tension rise and the bending term, both stated. (The hysteretic law follows the load path:
/// with the pull and gravity stepped together the wires slip while the tension is still low,
/// and the span ends 3.4e-3 softer than the all-stick closed form.)
#[test]
fn pretensioned_span_sags_as_a_taut_beam_string() {
    for kind in [LawKind::Constant, LawKind::Continuous] {
        let probe = span(1.0, kind, 20, 0.0, [0.0; 3]);
        let (ea, l) = (probe.law().axial_stiffness(), 1.0);
        let t0 = 100.0;
        let b = span(1.0, kind, 20, t0 * l / ea, [0.0, -9.8, 0.0]);
        let q = b.spec().mass_per_length * 9.8;
        let ei = small_curvature_ei(&b);
        let sol = solve_static(&b, &StaticOptions::default(), &mut |_| {}).unwrap();
        let sag = -b.sample(&sol.q, 0.5 * l).0[1];
        // The span is X = L (1 + T0 / EA) and the weight per span length q L / X.
        let x = l * (1.0 + t0 / ea);
        let qx = q * l / x;
        // The beam-string's deflection and its stretch: H = T0 + EA / (2 L) int w'^2 dx, by
        // fixed-point iteration (contracting: dH/dH is about 1e-2) with Simpson's rule.
        let slope = |h: f64, s: f64| {
            let k = (h / ei).sqrt();
            qx / (2.0 * h) * (x - 2.0 * s)
                + qx * ei / (h * h) * k * (k * (s - 0.5 * x)).sinh() / (0.5 * k * x).cosh()
        };
        let mut h = t0;
        for _ in 0..50 {
            let n = 2000;
            let d = x / n as f64;
            let int: f64 = (0..=n)
                .map(|i| {
                    let c = if i == 0 || i == n {
                        1.0
                    } else {
                        2.0 + 2.0 * (i % 2) as f64
                    };
                    c * slope(h, i as f64 * d).powi(2)
                })
                .sum::<f64>()
                * d
                / 3.0;
            h = t0 + ea * int / (2.0 * l);
        }
        let k = (h / ei).sqrt();
        let bending = qx * ei / (h * h) * (1.0 / (0.5 * k * x).cosh() - 1.0);
        let closed = qx * x * x / (8.0 * h) + bending;
        let taut = q * l * l / (8.0 * t0);
        println!(
            "{kind}: sag {sag:.6e} m, beam-string {closed:.6e} ({:+.1e}), q L^2/(8 T0) {taut:.6e} \
             ({:+.1e}; tension rise {:+.1e}, bending {:+.1e})",
            sag / closed - 1.0,
            sag / taut - 1.0,
            t0 / h - 1.0,
            bending / closed
        );
        assert!(
            (sag - closed).abs() < 2e-4 * closed,
            "{kind}: {sag} {closed}"
        );
    }
}

/// A slack span (the section-3 strand, 10 m, its end pushed in to a 9 m span, then gravity,
/// statics) hangs as the elastic catenary (Irvine): for the horizontal tension H that fits the
/// span, `X = H L0 / EA + (2 H / q) asinh(q L0 / (2 H))`, the sag is
/// `(sqrt(H^2 + (q L0 / 2)^2) - H) / q + q L0^2 / (8 EA)`. The cable leaves out bending; its
/// effect on the sag is of order `q EI / H^2` (3e-4 of the sag here), so the tolerance is
/// three times that.
#[test]
fn slack_span_hangs_as_the_elastic_catenary() {
    for kind in [LawKind::Constant, LawKind::Hysteretic] {
        let (l0, x) = (10.0, 9.0);
        let b = span(l0, kind, 40, x - l0, [0.0, -9.8, 0.0]);
        let ea = b.law().axial_stiffness();
        let q = b.spec().mass_per_length * 9.8;
        let opts = StaticOptions {
            load_steps: 50,
            ..StaticOptions::default()
        };
        let sol = solve_static(&b, &opts, &mut |_| {}).unwrap();
        let mid = (0..=200)
            .map(|i| b.sample(&sol.q, l0 * i as f64 / 200.0).0)
            .fold(0.0f64, |a, p| a.max(-p[1]));
        let span_of = |h: f64| h * l0 / ea + 2.0 * h / q * (q * l0 / (2.0 * h)).asinh();
        let (mut lo, mut hi) = (1e-3, 1e4);
        for _ in 0..200 {
            let h = 0.5 * (lo + hi);
            if span_of(h) < x {
                lo = h;
            } else {
                hi = h;
            }
        }
        let h = 0.5 * (lo + hi);
        let v = 0.5 * q * l0;
        let sag = ((h * h + v * v).sqrt() - h) / q + q * l0 * l0 / (8.0 * ea);
        let ei = small_curvature_ei(&b);
        let tol = 3.0 * q * ei / (h * h);
        println!(
            "{kind}: sag {mid:.6} m, catenary {sag:.6} m ({:+.1e}), H {h:.3} N, q EI / H^2 {:.1e} \
             of the sag, {} load steps",
            mid / sag - 1.0,
            q * ei / (h * h) / sag,
            sol.steps
        );
        assert!((mid - sag).abs() < tol, "{kind}: {mid} {sag}");
    }
}

/// The pretensioned span (1 m, T = 100 N, no gravity) plucked out of plane with the velocity
/// of its first mode: it swings at the first frequency of a pinned beam-string,
/// `f = (1 / 2X) sqrt(T / m_X) sqrt(1 + pi^2 EI / (T X^2))` (sin(pi x / X) is its exact mode;
/// the span X = L (1 + T / EA) and the mass per span length m_X = m L / X),
/// measured from the zero crossings of the midspan over 0.5 s: within 3e-4 (generalized-alpha
/// without damping lengthens the period by (omega h)^2 / 12 = 1.3e-4 at 0.5 ms). The taut-string
/// value `(1 / 2L) sqrt(T / m)` leaves out the bending term, stated.
#[test]
fn plucked_span_swings_at_the_beam_string_frequency() {
    for kind in [LawKind::Constant, LawKind::Hysteretic] {
        let probe = span(1.0, kind, 16, 0.0, [0.0; 3]);
        let (ea, l) = (probe.law().axial_stiffness(), 1.0);
        let t = 100.0;
        let pulled = span(1.0, kind, 16, t * l / ea, [0.0; 3]);
        let sol = solve_static(&pulled, &StaticOptions::default(), &mut |_| {}).unwrap();
        // The dynamics holds the end where the statics left it (a fixed support keeps its
        // coordinates of the initial state).
        let b = span(1.0, kind, 16, 0.0, [0.0; 3]);
        let m = b.spec().mass_per_length;
        let ei = small_curvature_ei(&b);
        // The first mode's velocity, out of the plane of the span, 1 mm/s at midspan.
        let mut init = InitialState {
            q: sol.q.clone(),
            v: vec![0.0; b.coords()],
            state: sol.slip.clone(),
            discarded: 0.0,
        };
        let (v0, nd) = (1e-3, b.node_coords());
        let pi = std::f64::consts::PI;
        for (j, node) in init.v.chunks_exact_mut(nd).enumerate() {
            let x = j as f64 * b.element_length();
            node[2] = v0 * (pi * x / l).sin();
            node[5] = v0 * pi / l * (pi * x / l).cos();
        }
        for (g, v) in init.v.iter_mut().enumerate() {
            if b.free_index(g).is_none() {
                *v = 0.0;
            }
        }
        let o = DynamicOptions::new(
            0.5,
            Scheme::GeneralizedAlpha {
                step: 5e-4,
                spectral_radius: 1.0,
            },
            5e-4,
        );
        let mut z = Vec::new();
        run_dynamic_from(&b, &o, &init, &mut |f| {
            z.push((f.t, b.sample(f.q, 0.5 * l).0[2]));
        })
        .unwrap();
        let crossings: Vec<f64> = z
            .windows(2)
            .filter(|w| w[0].1 * w[1].1 < 0.0)
            .map(|w| w[0].0 - w[0].1 * (w[1].0 - w[0].0) / (w[1].1 - w[0].1))
            .collect();
        let n = crossings.len() - 1;
        let f = 0.5 * n as f64 / (crossings[n] - crossings[0]);
        let string = (t / m).sqrt() / (2.0 * l);
        let x = l * (1.0 + t / ea);
        let beam_string =
            (t * x / (m * l)).sqrt() / (2.0 * x) * (1.0 + pi * pi * ei / (t * x * x)).sqrt();
        println!(
            "{kind}: f {f:.5} Hz from {n} half periods, beam-string {beam_string:.5} Hz ({:+.1e}), \
             string (1/2L) sqrt(T/m) {string:.5} Hz ({:+.1e})",
            f / beam_string - 1.0,
            f / string - 1.0
        );
        assert!(
            (f / beam_string - 1.0).abs() < 3e-4,
            "{kind}: {f} {beam_string}"
        );
    }
}
