//! The energy balance of a hysteretic beam run falls at the integrator's second order under
//! step refinement: the law books a slipping wire's work by the trapezoid of its moving
//! friction limit (module `slip_work` of the section laws), so the books add no first-order
//! term of their own.
//!
//! ```text
//! cargo test --release -p strand-scene --test balance_order -- --nocapture
//! ```

use std::path::Path;

use strand_ancf::dynamics::{Scheme, run_dynamic_from};
use strand_ancf::initial::InitialState;
use strand_scene::{BeamModelKind, Scene, build_beam, dynamic_options};

/// The equivalent model's balance of the validation scene `name` (largest |total - initial|
/// over every step, of the largest kinetic energy) at its time step divided by `divisor`,
/// with Newton converged far below the step error (`increment` 1e-11, `ledger` 1e-8, as the
/// balance limits of `validation/tolerances.json` are measured).
fn balance(name: &str, divisor: f64) -> f64 {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../validation/{name}.json"));
    let scene = Scene::parse(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut opts = dynamic_options(&scene).unwrap();
    (opts.increment, opts.ledger) = (1e-11, 1e-8);
    match &mut opts.scheme {
        Scheme::GeneralizedAlpha { step, .. } => *step /= divisor,
        Scheme::Verlet { .. } => panic!("{name}: a generalized-alpha scene"),
    }
    let beam = build_beam(&scene, BeamModelKind::Equivalent).unwrap();
    let init = InitialState::rigid(&beam, scene.velocity, scene.angular_velocity).unwrap();
    let s = run_dynamic_from(&beam, &opts, &init, &mut |_| {}).unwrap();
    s.balance_error / s.max_kinetic
}

/// Fig. 8 clamped (planar element) at h, h/2, h/4, h/8 and the spin pendulum (spatial
/// element, the friction limits turning with the bending direction too) at h, h/2, h/4:
/// generalized-alpha at spectral radius 1 is the trapezoidal rule, second order, and each
/// doubling's observed order must exceed 1.5, midway between it and the first order of an
/// end-point booking. Measured: clamped 1.372e-5, 3.399e-6, 8.544e-7, 2.135e-7 (orders 2.01,
/// 1.99, 2.00); spin 1.413e-5, 3.278e-6, 8.385e-7 (2.11, 1.97). With the slip work booked at
/// the limit of the step's end (the mutation `cap |ds|` in `slip_work::trapezoid`) the
/// clamped balance stalls, 6.011e-6, 1.170e-6, 1.076e-6, 7.502e-7 (orders 2.36, 0.12, 0.52):
/// the test fails.
#[test]
fn hysteretic_balance_falls_at_second_order() {
    for (name, divisors) in [
        ("paper-fig8-clamped", &[1.0, 2.0, 4.0, 8.0][..]),
        ("spin-pendulum", &[1.0, 2.0, 4.0][..]),
    ] {
        let b: Vec<f64> = divisors.iter().map(|&d| balance(name, d)).collect();
        let orders: Vec<f64> = b.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        let shown: Vec<String> = b.iter().map(|v| format!("{v:.3e}")).collect();
        println!("{name}: balance {shown:?} of the largest kinetic energy, orders {orders:.2?}");
        assert!(
            orders.iter().all(|&p| p > 1.5),
            "{name}: balance {b:?}, orders {orders:?}"
        );
    }
}
