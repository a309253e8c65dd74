//! Checks of the elastica reference against closed forms, published values, independent
//! equilibrium and the paper's reported tensions.

use std::time::Instant;

use approx::assert_relative_eq;
use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};
use strand_elastica::{
    Cantilever, ConstantEi, ElasticaError, FnLaw, Options, PlanarLaw, Solution, StrandLaw,
    invert_moment, solve,
};

/// The paper's strand (Table 1; section 3 with `length` 1, `e` 2e9, `rho` 5747).
fn strand(length: f64, e: f64, rho: f64) -> Strand {
    Strand::new(StrandSpec::paper(length, e, rho)).expect("valid strand")
}

#[test]
fn constant_ei_matches_published_tip_displacements() {
    // (q L^3 / EI, u/L, v/L), 7 published digits.
    let cases = [
        (1.0, 0.0087536, 0.1234714),
        (5.0, 0.1533428, 0.4959050),
        (10.0, 0.3436462, 0.7001997),
    ];
    let (len, ei): (f64, f64) = (2.0, 3.0);
    for (p, u_ref, v_ref) in cases {
        let t0 = Instant::now();
        let q = p * ei / len.powi(3);
        let sol = solve(
            &Cantilever::new(len, q),
            &ConstantEi::new(ei),
            &Options::default(),
        )
        .unwrap();
        let [dx, dy] = sol.tip_displacement();
        let (u, v) = (-dx / len, -dy / len);
        println!(
            "qL^3/EI = {p}: u/L = {u:.10} ({:+.2e}), v/L = {v:.10} ({:+.2e}), error est {:.1e} m \
             order {:.2}, continuation {} steps, {:.1} ms",
            u - u_ref,
            v - v_ref,
            sol.error.position,
            sol.error.order,
            sol.continuation_steps,
            t0.elapsed().as_secs_f64() * 1e3
        );
        assert!((u - u_ref).abs() < 2e-7, "u/L = {u} vs {u_ref}");
        assert!((v - v_ref).abs() < 2e-7, "v/L = {v} vs {v_ref}");
        assert!(sol.error.position < 1e-8 * len, "{:?}", sol.error);
        assert!(sol.error.end_moment.abs() < 1e-12 * q * len * len);
    }
}

#[test]
fn small_load_matches_euler_bernoulli() {
    let (len, ei): (f64, f64) = (0.7, 2.5);
    let q = 1e-3 * ei / len.powi(3);
    let sol = solve(
        &Cantilever::new(len, q),
        &ConstantEi::new(ei),
        &Options::default(),
    )
    .unwrap();
    let drop = -sol.tip[1];
    let linear = q * len.powi(4) / (8.0 * ei);
    println!(
        "qL^3/EI = 1e-3: drop/linear - 1 = {:.3e}",
        drop / linear - 1.0
    );
    assert_relative_eq!(drop, linear, max_relative = 1e-3);
    // Root moment of the nearly straight beam: -q L^2 / 2.
    assert_relative_eq!(sol.root_moment, -0.5 * q * len * len, max_relative = 1e-3);
}

#[test]
fn errors_shrink_with_steps_and_interpolation_is_accurate() {
    let law = ConstantEi::new(1.0);
    let prob = Cantilever::new(1.0, 10.0);
    let coarse = solve(
        &prob,
        &law,
        &Options {
            steps: 400,
            ..Options::default()
        },
    )
    .unwrap();
    let fine = solve(
        &prob,
        &law,
        &Options {
            steps: 8000,
            ..Options::default()
        },
    )
    .unwrap();
    let true_err = (coarse.tip[0] - fine.tip[0]).hypot(coarse.tip[1] - fine.tip[1]);
    println!(
        "400 steps: tip error {true_err:.2e} m, estimate {:.2e} m (order {:.2})",
        coarse.error.position, coarse.error.order
    );
    assert!(coarse.error.order > 3.5);
    assert!(true_err < 3.0 * coarse.error.position && true_err > 0.2 * coarse.error.position);
    // Hermite interpolation of the coarse solution between its nodes.
    let mut worst: f64 = 0.0;
    for k in 0..997 {
        let s = (k as f64 + 0.37) / 997.0;
        let (a, b) = (coarse.position(s), fine.position(s));
        worst = worst.max((a[0] - b[0]).hypot(a[1] - b[1]));
    }
    println!("interpolation of the 400-step solution: max error {worst:.2e} m");
    assert!(worst < 1e-8, "{worst}");
}

/// -q int_s^L (x(s') - x(s)) ds' by composite Simpson on the interpolated shape.
fn moment_of_free_part(sol: &Solution, s: f64) -> f64 {
    let (len, q) = (sol.problem.length, sol.problem.load);
    let n = 4000;
    let h = (len - s) / n as f64;
    let x0 = sol.position(s)[0];
    let mut acc = 0.0;
    for i in 0..=n {
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        acc += w * (sol.position(s + i as f64 * h)[0] - x0);
    }
    -q * acc * h / 3.0
}

/// Equilibrium of the solved shape checked independently of the shooting's own moment.
fn check_equilibrium(sol: &Solution, law: &StrandLaw) -> f64 {
    let (len, q) = (sol.problem.length, sol.problem.load);
    let scale = 0.5 * q * len * len;
    let n = sol.s.len() - 1;
    assert!(
        sol.moment[n].abs() < 1e-12 * scale,
        "M(L) = {}",
        sol.moment[n]
    );
    let mut worst: f64 = 0.0;
    for frac in [0.0, 0.05, 0.125, 0.25, 0.5, 0.75, 0.9] {
        let i = (frac * n as f64).round() as usize;
        let s = sol.s[i];
        let direct = moment_of_free_part(sol, s);
        let point = law.point(s);
        let (m_law, _) = law.moment(&point, sol.kappa[i], sol.tension[i]);
        worst = worst.max((direct - m_law).abs() / scale);
        // Tension of the hanging branch: the free part's weight along the tangent.
        let t = q * (len - s) * sol.theta[i].sin().abs();
        assert!((sol.tension[i] - t).abs() <= 1e-12 * q * len);
        assert!(sol.tension[i] >= 0.0);
    }
    worst
}

#[test]
fn table1_strand_continuous_law_by_continuation() {
    let st = strand(0.4, 2.0e8, 7801.0);
    let law = StrandLaw::new(SectionLaw::new(&st, LawKind::Continuous));
    let mut drops = Vec::new();
    for g in [8.0, 10.0, 12.0] {
        let t0 = Instant::now();
        let q = st.mass_per_length() * g;
        let prob = Cantilever::new(st.length(), q);
        let sol = solve(&prob, &law, &Options::default()).unwrap();
        let eq = check_equilibrium(&sol, &law);
        let param = q * st.length().powi(3) / law.section_law().base_bending_stiffness();
        println!(
            "Table 1, g = {g}: q L^3/K_min = {param:.1}, tip ({:.6}, {:.6}) m, root kappa \
             {:.3} 1/m, theta(L) = {:.2} deg, equilibrium error {eq:.1e} (of q L^2/2), error \
             est {:.1e} m (order {:.2}), {} continuation steps, {:.0} ms",
            sol.tip[0],
            sol.tip[1],
            sol.kappa[0],
            sol.theta.last().unwrap().to_degrees(),
            sol.error.position,
            sol.error.order,
            sol.continuation_steps,
            t0.elapsed().as_secs_f64() * 1e3
        );
        assert!(eq < 1e-6, "equilibrium error {eq}");
        assert!(sol.error.position < 1e-6 * st.length(), "{:?}", sol.error);
        // The hanging branch: the angle falls monotonically from the clamp and stays above
        // the vertical.
        assert!(sol.theta.windows(2).all(|w| w[1] <= w[0] + 1e-12));
        assert!(
            sol.theta
                .iter()
                .all(|&t| t > -0.5 * std::f64::consts::PI - 1e-9)
        );
        assert!(sol.tip[1] < -0.5 * st.length());
        drops.push(-sol.tip[1]);
    }
    assert!(drops.windows(2).all(|w| w[1] > w[0]), "{drops:?}");
}

#[test]
fn section3_strand_tension_near_tip_matches_fig12() {
    let st = strand(1.0, 2.0e9, 5747.0);
    let law = StrandLaw::new(SectionLaw::new(&st, LawKind::Continuous));
    let q = st.mass_per_length() * 12.0;
    let t0 = Instant::now();
    let sol = solve(&Cantilever::new(1.0, q), &law, &Options::default()).unwrap();
    let eq = check_equilibrium(&sol, &law);
    println!(
        "section 3, g = 12: tip ({:.6}, {:.6}) m, equilibrium error {eq:.1e}, error est {:.1e} m \
         (order {:.2}), {} continuation steps, {:.0} ms",
        sol.tip[0],
        sol.tip[1],
        sol.error.position,
        sol.error.order,
        sol.continuation_steps,
        t0.elapsed().as_secs_f64() * 1e3
    );
    for (s, t_paper) in [(0.92, 0.149), (0.925, 0.14), (0.93, 0.13)] {
        let v = sol.sample(s);
        println!(
            "  s = {s}: T = {:.4} N (paper {t_paper}), q (L - s) = {:.4} N, theta = {:.2} deg",
            v.tension,
            q * (1.0 - s),
            v.theta.to_degrees()
        );
        assert!(
            (v.tension - t_paper).abs() <= 0.05 * t_paper,
            "T({s}) = {} vs {t_paper}",
            v.tension
        );
    }
}

#[test]
fn extensible_strand_drops_further() {
    let (len, ei) = (1.0, 1.0);
    let q = 10.0;
    let law = ConstantEi::new(ei);
    let rigid = solve(&Cantilever::new(len, q), &law, &Options::default()).unwrap();
    let mut extra = Vec::new();
    for ea in [2e4, 1e4] {
        let sol = solve(
            &Cantilever::extensible(len, q, ea),
            &law,
            &Options::default(),
        )
        .unwrap();
        let dv = rigid.tip[1] - sol.tip[1];
        // First-order estimate: stretch of the inextensible shape along its tangent.
        let n = rigid.s.len() - 1;
        let h = len / n as f64;
        let stretch: f64 = (0..=n)
            .map(|i| {
                let w = if i == 0 || i == n { 0.5 } else { 1.0 };
                w * h * rigid.tension[i] / ea * (-rigid.theta[i].sin())
            })
            .sum();
        println!("EA = {ea}: extra drop {dv:.4e} m, stretch along the shape {stretch:.4e} m");
        assert!(dv > 0.0);
        // Stretching also lengthens the lever arms, which bends the strand further.
        assert!(dv > stretch && dv < 3.0 * stretch, "{dv} vs {stretch}");
        extra.push(dv);
    }
    // Small strains: the extra drop is linear in the compliance 1 / EA.
    assert_relative_eq!(extra[1], 2.0 * extra[0], max_relative = 1e-3);

    // Clamped pointing down the strand stays straight and stretches by q L^2 / (2 EA).
    let ea = 50.0;
    let down = Cantilever {
        clamp_angle: -0.5 * std::f64::consts::PI,
        ..Cantilever::extensible(len, q, ea)
    };
    let sol = solve(&down, &law, &Options::default()).unwrap();
    assert_relative_eq!(
        -sol.tip[1],
        len + q * len * len / (2.0 * ea),
        max_relative = 1e-12
    );
    assert!(sol.tip[0].abs() < 1e-12);
}

#[test]
fn inversion_handles_kinks_zero_and_jumps() {
    // Piecewise linear softening law with kinks at |kappa| = 1 and 3.
    let m = |k: f64| {
        let a = k.abs();
        let (v, d) = if a <= 1.0 {
            (10.0 * a, 10.0)
        } else if a <= 3.0 {
            (10.0 + 2.0 * (a - 1.0), 2.0)
        } else {
            (14.0 + 0.5 * (a - 3.0), 0.5)
        };
        (v.copysign(k), d)
    };
    for target in [-20.0, -12.0, -5.0, 0.0, 3.0, 10.0, 11.0, 14.0, 1e6] {
        for guess in [0.0, -7.0, 0.5, 2.0, 100.0] {
            let k = invert_moment(m, target, guess).unwrap();
            assert!((m(k).0 - target).abs() <= 1e-12 * (1.0 + target.abs()));
        }
    }
    // A law that jumps up over the target cannot be inverted: a clean error, no hang.
    let jump = |k: f64| (if k < 1.0 { k } else { k + 5.0 }, 1.0);
    assert!(matches!(
        invert_moment(jump, 3.0, 0.5),
        Err(ElasticaError::Inversion { .. })
    ));
    // A saturating law neither.
    let sat = |k: f64| (k.tanh(), 1.0 - k.tanh().powi(2));
    assert!(invert_moment(sat, 2.0, 0.0).is_err());
}

#[test]
fn closure_law_and_paper_law_finish() {
    // A closure law equal to constant EI gives the same solution.
    let prob = Cantilever::new(1.0, 5.0);
    let opts = Options {
        steps: 2000,
        ..Options::default()
    };
    let a = solve(&prob, &ConstantEi::new(1.0), &opts).unwrap();
    let b = solve(&prob, &FnLaw(|_s: f64, k: f64, _t: f64| (k, 1.0)), &opts).unwrap();
    assert_eq!(a.tip, b.tip);

    // The non-monotone `paper` law must end with an answer or a clean error.
    let st = strand(0.4, 2.0e8, 7801.0);
    let law = StrandLaw::new(SectionLaw::new(&st, LawKind::Paper));
    let t0 = Instant::now();
    let r = solve(
        &Cantilever::new(0.4, st.mass_per_length() * 10.0),
        &law,
        &opts,
    );
    match &r {
        Ok(sol) => println!(
            "paper law: tip ({:.6}, {:.6}), error est {:.1e} (order {:.2})",
            sol.tip[0], sol.tip[1], sol.error.position, sol.error.order
        ),
        Err(e) => println!("paper law: {e}"),
    }
    assert!(t0.elapsed().as_secs_f64() < 60.0);

    // On the monotone loading of statics the hysteretic law from a virgin state is the
    // continuous law.
    let q = st.mass_per_length() * 10.0;
    let tip = |kind| {
        let law = StrandLaw::new(SectionLaw::new(&st, kind));
        solve(&Cantilever::new(0.4, q), &law, &opts).unwrap().tip
    };
    assert_eq!(tip(LawKind::Hysteretic), tip(LawKind::Continuous));
}

#[test]
fn bad_input_is_rejected() {
    let law = ConstantEi::new(1.0);
    let o = Options::default();
    assert!(matches!(
        solve(&Cantilever::new(-1.0, 1.0), &law, &o),
        Err(ElasticaError::Input {
            field: "length",
            ..
        })
    ));
    assert!(matches!(
        solve(
            &Cantilever::new(1.0, 1.0),
            &law,
            &Options { steps: 10, ..o }
        ),
        Err(ElasticaError::Input { field: "steps", .. })
    ));
    let zero = solve(&Cantilever::new(1.0, 0.0), &law, &o).unwrap();
    assert!((zero.tip[0] - 1.0).abs() < 1e-12 && zero.tip[1] == 0.0);
}
