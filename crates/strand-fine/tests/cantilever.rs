//! A single straight wire as a clamped cantilever under a uniform load (its own weight):
//! linear tip deflection q L^4 / 8 EI and the inextensible elastica (SPEC 7).

use nalgebra::Vector3;
use strand_core::{Material, WireSpec};
use strand_fine::{FineModel, StaticOptions, Support, WireSection, solve_static};

const LENGTH: f64 = 0.4;

fn section() -> WireSection {
    WireSection::from_spec(&WireSpec {
        diameter: 2.0e-3,
        material: Material {
            youngs_modulus: 2.0e8,
            poisson_ratio: 0.3,
            density: 7801.0,
        },
    })
}

/// Tip displacement (u/L, v/L) of an `n`-segment cantilever at load parameter q L^3 / EI.
fn tip(n: usize, load: f64) -> (f64, f64) {
    let s = section();
    let ei = s.youngs_modulus * s.inertia;
    let q = load * ei / LENGTH.powi(3);
    let mut m = FineModel::single_wire(s, LENGTH, n, Support::Clamped, Support::Free);
    m.gravity = Vector3::new(0.0, -q / (s.density * s.area), 0.0);
    let mut state = m.rest_state();
    let opts = StaticOptions {
        load_steps: if load > 1.0 { 5 } else { 1 },
        ..Default::default()
    };
    let rep = solve_static(&m, &mut state, &opts).expect("static solve");
    let line = m.core_centreline(&state);
    let t = line[n];
    println!(
        "n = {n:4}, qL^3/EI = {load}: {} Newton iterations, residual {:.2e} F_ref \
         (F_ref = {:.2e} N, round-off allowance {:.2e} N)",
        rep.iterations, rep.residual, rep.force_scale, rep.roundoff
    );
    ((LENGTH - t.x) / LENGTH, -t.y / LENGTH)
}

fn observed_order(e1: f64, e2: f64) -> f64 {
    (e1 / e2).log2()
}

#[test]
fn small_deflection_matches_beam_theory() {
    let load = 0.01;
    let exact = load / 8.0; // v/L = q L^3 / (8 EI)
    let mut errors = Vec::new();
    for n in [10, 20, 40, 80] {
        let (_, v) = tip(n, load);
        let err = (v - exact) / exact;
        println!("small deflection n = {n}: v/L = {v:.8e}, relative error {err:.3e}");
        errors.push(err.abs());
    }
    for w in errors.windows(2) {
        println!("observed order {:.2}", observed_order(w[0], w[1]));
        assert!(w[1] < w[0], "error must fall as segments are added");
    }
    assert!(errors[1] < 0.01, "n = 20 within 1 %");
}

#[test]
fn large_deflection_matches_the_elastica() {
    let (u_ref, v_ref) = (0.1533428, 0.4959050);
    let mut errors = Vec::new();
    for n in [10, 20, 40, 80] {
        let (u, v) = tip(n, 5.0);
        let err = ((u - u_ref).powi(2) + (v - v_ref).powi(2)).sqrt();
        println!("elastica n = {n}: (u/L, v/L) = ({u:.7}, {v:.7}), error {err:.3e} L");
        errors.push(err);
    }
    for w in errors.windows(2) {
        println!("observed order {:.2}", observed_order(w[0], w[1]));
        assert!(w[1] < w[0], "error must fall as segments are added");
    }
    assert!(errors[1] < 0.01, "n = 20 within 1 % L");
}

#[test]
fn dynamic_relaxation_agrees_with_newton() {
    let s = section();
    let ei = s.youngs_modulus * s.inertia;
    let q = 1.0 * ei / LENGTH.powi(3);
    let mut m = FineModel::single_wire(s, LENGTH, 10, Support::Clamped, Support::Free);
    m.gravity = Vector3::new(0.0, -q / (s.density * s.area), 0.0);
    let mut a = m.rest_state();
    solve_static(&m, &mut a, &StaticOptions::default()).expect("Newton");
    let mut b = m.rest_state();
    let rep = strand_fine::solve_relaxation(
        &m,
        &mut b,
        &strand_fine::RelaxationOptions {
            load_steps: 1,
            tolerance: 1e-7,
            ..Default::default()
        },
    )
    .expect("relaxation");
    let (ta, tb) = (m.core_centreline(&a)[10], m.core_centreline(&b)[10]);
    println!(
        "relaxation: {} pseudo-time steps, residual {:.2e} F_ref; tip difference to Newton \
         {:.2e} m",
        rep.iterations,
        rep.residual,
        (ta - tb).norm()
    );
    assert!((ta - tb).norm() < 1e-6 * LENGTH);
}

/// Convergence with a scale: the same cantilever under its weight times 1e-12 to 1e3 (the
/// load parameter q L^3 / EI from 8e-11 to 8e4), 20 segments. Up to 1e-6 the deflection is
/// the linear one, q L^4 / (8 EI), within the chain's discretisation error (0.25 %, from the
/// refinement of `small_deflection_matches_beam_theory`); at 1e-3 and 1 the inextensible
/// elastica (the shooting solution), within 5e-3 L (the chain's error at q L^3 / EI = 80,
/// 9.4e-4 and 2.9e-4 L at 40 and 80 segments, is second order: 3.8e-3 L at 20); at 1e3 the
/// wire hangs as a string, its tip at L + q L^2 / (2 E A) below the clamp (12 % strain at
/// the root on the paper's modulus of 2e8 Pa), within one segment (the bending boundary layer
/// at the clamp, sqrt(EI / T) = 1.4 mm long, lies inside the first segment). With the
/// residual measured against the load alone, the round-off of the joint forces (E A / l times
/// an ulp of the coordinates, about 1e-9 N) exceeds the weight of 1e-15 N at 1e-12 and the
/// straight wire passes as converged.
#[test]
fn loads_from_1e_minus_12_to_1e3_times_the_weight_converge() {
    let s = section();
    let ei = s.youngs_modulus * s.inertia;
    let ea = s.youngs_modulus * s.area;
    let weight_q = s.density * s.area * 8.0;
    let n = 20;
    for factor in [1e-12, 1e-9, 1e-6, 1e-3, 1.0, 1e3] {
        let q = weight_q * factor;
        let load = q * LENGTH.powi(3) / ei;
        let mut m = FineModel::single_wire(s, LENGTH, n, Support::Clamped, Support::Free);
        m.gravity = Vector3::new(0.0, -8.0 * factor, 0.0);
        let mut state = m.rest_state();
        let opts = StaticOptions {
            load_steps: 5,
            max_iterations: 60,
            ..Default::default()
        };
        let rep = solve_static(&m, &mut state, &opts).expect("static solve");
        let t = m.core_centreline(&state)[n];
        let (u, v) = ((LENGTH - t.x) / LENGTH, -t.y / LENGTH);
        println!(
            "weight x {factor:e} (q L^3/EI = {load:.3e}): {} iterations in {} load steps, \
             residual {:.2e} F_ref, tip (u, v)/L = ({u:.6e}, {v:.6e})",
            rep.iterations, rep.load_steps, rep.residual
        );
        if factor <= 1e-6 {
            let linear = load / 8.0;
            assert!(
                ((v - linear) / linear).abs() < 3e-3,
                "weight x {factor:e}: v/L = {v:e}, linear {linear:e}"
            );
        } else if factor <= 1.0 {
            let e = strand_elastica::solve(
                &strand_elastica::Cantilever::new(LENGTH, q),
                &strand_elastica::ConstantEi::new(ei),
                &strand_elastica::Options::default(),
            )
            .expect("elastica");
            let [dx, dy] = e.tip_displacement();
            let err = ((u + dx / LENGTH).powi(2) + (v + dy / LENGTH).powi(2)).sqrt();
            println!("  {err:.2e} L from the elastica");
            assert!(
                err < 5e-3,
                "weight x {factor:e}: {err:e} L from the elastica"
            );
        } else {
            let string = 1.0 + q * LENGTH / (2.0 * ea);
            let segment = 1.0 / n as f64;
            println!("  string: drop {string:.6e} L");
            assert!((v - string).abs() < segment && t.x.abs() < segment * LENGTH);
        }
    }
}
