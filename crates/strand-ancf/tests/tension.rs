//! The tension the section laws read, against statics: in a hanging cantilever the tension at
//! s is the weight below projected on the tangent, -q (L - s) sin(theta), and never more than
//! q (L - s).

use strand_ancf::beam::{Beam, BeamSpec, ElementKind, Support};
use strand_ancf::statics::{StaticOptions, solve_static};
use strand_core::{LawKind, SectionLaw, SectionOptions, Strand, StrandSpec};
use strand_elastica::{Cantilever, Options, StrandLaw, solve};

/// The strand of `law` clamped at x = 0 under gravity `g` (m/s^2), straight along +X (or
/// hanging along -Y with `DOWN=1`).
fn cantilever(law: SectionLaw, elements: usize, g: f64) -> Beam {
    let mu = law.strand().mass_per_length();
    let bp = env("BP", 0.0) as usize;
    Beam::new(
        BeamSpec {
            elements,
            bending_points: (bp > 0).then_some(bp),
            mass_per_length: mu,
            element: ElementKind::Planar,
            direction: if env("DOWN", 0.0) > 0.0 {
                [0.0, -1.0, 0.0]
            } else {
                [1.0, 0.0, 0.0]
            },
            gravity: [0.0, -g, 0.0],
            start: Some(Support::Clamped),
            end: None,
            ..Default::default()
        },
        law,
    )
    .unwrap()
}

fn env(k: &str, d: f64) -> f64 {
    std::env::var(k)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(d)
}

/// Largest (T - q (L - x)) and |T - T_elastica| over the bending points of the hanging
/// section-3 strand (g = 12, `elements` elements) with `law`, relative to q L, the largest
/// tension; and the tension at x = 0.92, 0.925, 0.93 m (Fig. 12).
fn section3_tension(kind: LawKind, elements: usize) -> (f64, f64, [f64; 3]) {
    let s = Strand::new(StrandSpec::paper(1.0, 2.0e9, 5747.0)).unwrap();
    let g = 12.0;
    let law = SectionLaw::new(&s, kind);
    let beam = cantilever(law.clone(), elements, g);
    let sol = solve_static(&beam, &StaticOptions::default(), &mut |_| {}).unwrap();
    let q = s.mass_per_length() * g;
    let reference = match kind {
        LawKind::Constant => {
            let t = s.traditional();
            let c = Cantilever::extensible(s.length(), q, t.axial_stiffness);
            solve(
                &c,
                &strand_elastica::ConstantEi::new(t.bending_stiffness),
                &Options::default(),
            )
        }
        _ => {
            let el = StrandLaw::new(law.clone());
            let c = Cantilever::extensible(s.length(), q, law.axial_stiffness());
            solve(&c, &el, &Options::default())
        }
    }
    .unwrap();
    let (mut over, mut off) = (f64::NEG_INFINITY, 0.0f64);
    let ea = law.axial_stiffness();
    for p in &sol.points {
        let t = ea * p.eps;
        over = over.max(t - q * (s.length() - p.x));
        off = off.max((t - reference.sample(p.x).tension).abs());
    }
    let at = |x: f64| {
        let i = sol.points.iter().position(|p| p.x > x).unwrap();
        let (a, b) = (&sol.points[i - 1], &sol.points[i]);
        ea * (a.eps + (b.eps - a.eps) * (x - a.x) / (b.x - a.x))
    };
    let ql = q * s.length();
    (over / ql, off / ql, [at(0.92), at(0.925), at(0.93)])
}

/// The tension the section laws read along the hanging section-3 strand (g = 12) never exceeds
/// the weight below (no static state can hold more), and converges at second order in the
/// element length to the elastica's -q (L - s) sin(theta) of the same law: largest distance
/// 1.39e-2, 4.44e-3, 1.23e-3, 3.07e-4 q L at 30, 60, 120, 240 elements with the `continuous`
/// law (the strongly curved root, kappa l = 0.5 at 30 elements, holds the largest error),
/// 2.6e-4, 6.3e-5, 1.7e-5, 4.3e-6 q L with `constant` (`STUDY=1`). The checks: 120 elements
/// (continuous) and 30 (constant) within 2e-3 q L, below the 5e-3 q L of a 0.5 % tension
/// error, and the order from the halving above 1.5. Before the law read the tension recovered
/// from the element means, the linear field through each element's two axial points was off at
/// first order (0.12, 0.061, 0.028 q (L - x) at 30, 60, 120 elements) and above the weight
/// below near the tip.
#[test]
fn hanging_tension_obeys_statics_and_matches_the_elastica() {
    if env("STUDY", 0.0) > 0.0 {
        for kind in [LawKind::Continuous, LawKind::Constant] {
            for n in [30, 60, 120, 240] {
                let (over, off, fig12) = section3_tension(kind, n);
                println!("{kind} {n}: over {over:+.2e} off {off:.2e} Fig. 12 {fig12:?}");
            }
        }
    }
    for (kind, n) in [(LawKind::Continuous, 60), (LawKind::Constant, 30)] {
        let (over, off, fig12) = section3_tension(kind, n);
        let (over2, off2, _) = section3_tension(kind, 2 * n);
        let order = (off / off2).log2();
        println!(
            "{kind}: T - q (L - x) at most {over:+.2e}, {over2:+.2e} q L; |T - T_elastica| at \
             most {off:.2e}, {off2:.2e} q L at {n}, {} elements (order {order:.2}); Fig. 12 at \
             {n}: {:.4}, {:.4}, {:.4} N",
            2 * n,
            fig12[0],
            fig12[1],
            fig12[2]
        );
        // Round-off of EA eps relative to q L: far below 1e-9.
        assert!(
            over.max(over2) <= 1e-9,
            "{kind}: above the weight below by {over} q L"
        );
        assert!(off2 < 2e-3, "{kind}: {off2} q L from the elastica");
        assert!(order > 1.5, "{kind}: order {order}");
    }
}

#[test]
#[ignore = "exploration: N (elements), G, LAW (0 continuous, 1 constant), MU, EI and EAF (a constant \
            law of that EI and EA_eq times EAF), BP (bending points), DOWN (hanging straight) from \
            the environment"]
fn probe() {
    let mut spec = StrandSpec::paper(1.0, 2.0e9, 5747.0);
    spec.friction = env("MU", 0.3);
    let s = Strand::new(spec).unwrap();
    let g = env("G", 12.0);
    let kind = if env("LAW", 0.0) == 0.0 {
        LawKind::Continuous
    } else {
        LawKind::Constant
    };
    let law = if env("EI", 0.0) > 0.0 {
        SectionLaw::constant(&s, env("EI", 0.0), s.axial_stiffness() * env("EAF", 1.0))
    } else {
        SectionLaw::with_options(&s, kind, &SectionOptions::paper())
    };
    let beam = cantilever(law.clone(), env("N", 30.0) as usize, g);
    let sol = solve_static(&beam, &StaticOptions::default(), &mut |_| {}).unwrap();
    let q = s.mass_per_length() * g;
    let ea = law.axial_stiffness();
    let mut worst: f64 = 0.0;
    for p in &sol.points {
        let (_, d) = beam.sample(&sol.q, p.x);
        let below = q * (s.length() - p.x);
        let eq = -below * d[1] / d[0].hypot(d[1]);
        let t = ea * p.eps;
        worst = worst.max((t - eq).abs() / below);
        println!(
            "x {:.5} T {t:.6e} eq {eq:.6e} below {below:.6e} (T - eq)/below {:+.3e}",
            p.x,
            (t - eq) / below
        );
    }
    println!("largest |T - eq| / (q (L - x)) {worst:.3e}");
}
