//! Exploration (holds no claim; `--ignored`): the energy balance of issue 16's pendulum in its
//! own plane against the time step and the Newton tolerance. The planar copy of
//! `validation/hard/tilted-pendulum.json` (gravity turned onto -Y, no phase reference) runs on
//! the planar element at h = 1, 0.5, 0.25 and 0.125 ms with `DynamicOptions::increment` 1e-8
//! (the default) and 1e-10; it prints the balance error relative to the largest kinetic
//! energy, the slip work, the Newton iterations and the largest tip distance over the output
//! frames from the run at twice the step (the integrator's error at that step). The
//! trapezoidal rule closes the balance at second order in h; Newton's stopping test bounds
//! what it leaves in the ledger to `DynamicOptions::ledger` of the energy scale at every step.
//!
//! `cargo test --release -p strand-scene --test balance_step_study -- --ignored --nocapture`

use std::path::Path;

use strand_ancf::dynamics::{Scheme, run_dynamic};
use strand_scene::{BeamModelKind, Scene, build_beam, dynamic_options};

/// Largest distance between two runs' tips at the same output frames (m).
fn largest_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
}

#[test]
#[ignore = "exploration: a study of about 30 s that prints a table"]
fn tilted_pendulum_in_its_plane_balance_against_step_and_newton_tolerance() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../validation/hard/tilted-pendulum.json");
    let scene = Scene::load(&path).expect("the hard case's scene");
    let g = scene.gravity;
    let mut file = scene.file.clone();
    file.name = "tilted-pendulum-planar".into();
    if let Some(l) = file.loads.as_mut() {
        l.gravity = Some([0.0, -(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt(), 0.0]);
    }
    if let Some(i) = file.initial.as_mut() {
        i.phase_reference = None;
    }
    let planar = Scene::from_file(file).expect("the planar copy");
    assert!(planar.is_planar());
    let beam = build_beam(&planar, BeamModelKind::Equivalent).expect("the beam");
    println!(
        "increment  h (s)     balance / max kinetic  slip work (J)  Newton iterations  tip from 2h (m)"
    );
    for increment in [1e-8, 1e-10] {
        let mut coarser: Option<Vec<[f64; 3]>> = None;
        for step in [1e-3, 5e-4, 2.5e-4, 1.25e-4] {
            let mut opts = dynamic_options(&planar).expect("a dynamic scene");
            opts.increment = increment;
            let Scheme::GeneralizedAlpha {
                spectral_radius, ..
            } = opts.scheme
            else {
                panic!("the scene uses generalized-alpha");
            };
            opts.scheme = Scheme::GeneralizedAlpha {
                step,
                spectral_radius,
            };
            let mut tips = Vec::new();
            let s = run_dynamic(&beam, &opts, &mut |f| {
                tips.push(beam.sample(f.q, beam.length()).0);
            })
            .expect("the run");
            let apart = coarser
                .as_deref()
                .map_or(f64::NAN, |c| largest_distance(c, &tips));
            println!(
                "{increment:8.0e}  {step:8.3e}  {:21.3e}  {:13.5e}  {:17}  {apart:15.3e}",
                s.balance_error / s.max_kinetic,
                s.last.dissipated,
                s.newton_iterations
            );
            coarser = Some(tips);
        }
    }
}
