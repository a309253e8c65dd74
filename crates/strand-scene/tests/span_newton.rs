//! Newton on a strand of several layers: the kept slow fresh matrix
//! (`DynamicOptions::keep_slow_fresh`) and the zero-acceleration predictor
//! (`DynamicOptions::layers_predictor`), on the Cardinal span of the Performance page
//! (`benchmarks/conductor-span/cardinal-span-cost.json`, the first 0.2 s of its fall), with
//! them and without them.
//!
//! Both change only where Newton starts and which matrix it iterates with, never the residual
//! or the acceptance test, so the accepted states differ by what Newton's tolerance leaves.
//! The references are independent of them: the run without them, and the integrator's own
//! error, measured by halving the step (generalized-alpha is second order: the error of the
//! run at h is about 4/3 of its distance to the run at h/2). A 1+m strand is left as it was,
//! bit for bit.

use std::path::Path;

use strand_ancf::dynamics::{DynamicOptions, DynamicSummary, SlipPredictor, run_dynamic_from};
use strand_ancf::initial::InitialState;
use strand_scene::{BeamModelKind, Scene, build_beam, dynamic_options};

/// The bundled span's scene as JSON, run for `duration` (s) at `step` (s), with the first
/// `layers` of its four layers.
fn span(duration: f64, step: f64, layers: usize) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../benchmarks/conductor-span/cardinal-span-cost.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    v["analysis"]["duration"] = duration.into();
    v["analysis"]["time_step"] = step.into();
    v["strand"]["layers"]
        .as_array_mut()
        .unwrap()
        .truncate(layers);
    Scene::parse(&v.to_string()).unwrap()
}

/// The equivalent beam's run of `scene`, with the two changes (`new`) or without, and the
/// middle node's height at the end (m).
fn run(scene: &Scene, new: bool) -> (DynamicSummary, f64) {
    let beam = build_beam(scene, BeamModelKind::Equivalent).unwrap();
    let opts = DynamicOptions {
        keep_slow_fresh: new,
        layers_predictor: if new {
            SlipPredictor::Zero
        } else {
            SlipPredictor::Mean
        },
        ..dynamic_options(scene).unwrap()
    };
    let init = InitialState::rigid(&beam, scene.velocity, scene.angular_velocity).unwrap();
    let s = run_dynamic_from(&beam, &opts, &init, &mut |_| {}).unwrap();
    let nodes = beam.spec().elements + 1;
    let mid = (nodes / 2) * (s.q.len() / nodes) + 1;
    let y = s.q[mid];
    (s, y)
}

/// The counters' law: every matrix is counted once, under one reason.
fn counted(s: &DynamicSummary) {
    let r = s.rebuilds;
    assert_eq!(
        r.step_size + r.slow_step + r.slow_iteration,
        s.factorizations
    );
    assert_eq!(s.iteration_histogram.iter().sum::<usize>(), s.steps);
}

/// With the changes, the run takes fewer iterations and builds fewer matrices, and its middle
/// node and energy balance stay within the integrator's own error of the run without them.
#[test]
fn kept_matrices_leave_the_span_within_the_integrators_error() {
    let (h, duration) = (1e-3, 0.2);
    let (new, y_new) = run(&span(duration, h, 4), true);
    let (old, y_old) = run(&span(duration, h, 4), false);
    let (_, y_half) = run(&span(duration, 0.5 * h, 4), false);
    counted(&new);
    counted(&old);
    assert_eq!(old.rebuilds.kept_slow_fresh, 0);
    assert!(new.rebuilds.kept_slow_fresh > 0, "the rule never applied");
    println!(
        "iterations {} -> {}, matrices {} -> {}; middle node {y_old:.9e} -> {y_new:.9e} m \
         (h/2: {y_half:.9e}); balance {:.4e} -> {:.4e} J",
        old.newton_iterations,
        new.newton_iterations,
        old.factorizations,
        new.factorizations,
        old.balance_error,
        new.balance_error
    );
    assert!(new.factorizations < old.factorizations);
    assert!(new.newton_iterations < old.newton_iterations);
    // The integrator's error of the middle node at h (Richardson, second order).
    let integrator = 4.0 / 3.0 * (y_old - y_half).abs();
    assert!(
        (y_new - y_old).abs() <= integrator,
        "middle node moved by {:.3e} m, the integrator's error is {integrator:.3e} m",
        (y_new - y_old).abs()
    );
    // The balance error at h is the integrator's own (Newton's share is bounded to
    // `ledger` = 1e-5 of the energy scale); the rule may move it by no more than itself.
    assert!((new.balance_error - old.balance_error).abs() <= old.balance_error);
}

/// A 1+m strand (the span with its steel layer alone) runs bit for bit as without the
/// changes.
#[test]
fn a_one_layer_strand_is_unchanged() {
    let scene = span(0.05, 1e-3, 1);
    let (new, y_new) = run(&scene, true);
    let (old, y_old) = run(&scene, false);
    assert_eq!(new.rebuilds, old.rebuilds);
    assert_eq!(new.rebuilds.kept_slow_fresh, 0);
    assert_eq!(y_new.to_bits(), y_old.to_bits());
    assert_eq!(new.q, old.q);
    assert_eq!(new.slip, old.slip);
}
