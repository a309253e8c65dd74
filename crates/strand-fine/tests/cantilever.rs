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
