//! The cost of a scene's equivalent beam against its traditional twin, for instruction counts
//! (the command-line runner reads the CPU clock through the vDSO, which valgrind does not
//! map; this runs the same beams and options without it):
//!
//! ```text
//! cargo build --release -p strand-scene --example span_cost
//! valgrind --tool=callgrind target/release/examples/span_cost SCENE equivalent
//! valgrind --tool=callgrind target/release/examples/span_cost SCENE traditional
//! target/release/examples/span_cost SCENE equivalent traditional equivalent traditional
//! SPAN_KEEP_SLOW_FRESH=0 SPAN_PREDICTOR=mean target/release/examples/span_cost SCENE equivalent
//! ```
//!
//! Each named model is built with `strand_scene::build_beam` and run with the scene's
//! `dynamic_options`, as `strand run` does, in the order given (interleaved rounds); per run
//! it prints steps, Newton iterations, matrices, cut steps, iterations per step, the balance
//! error and the solve's wall time (the beam's set-up apart), then why the matrices were
//! built, the steps counted by their Newton iterations, and the middle node's position and
//! the energies at the end.

use std::time::Instant;

use strand_ancf::dynamics::{SlipPredictor, run_dynamic_from};
use strand_ancf::initial::InitialState;
use strand_scene::{BeamModelKind, Scene, build_beam, dynamic_options};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    assert!(
        args.len() >= 2,
        "usage: span_cost SCENE (equivalent|traditional)..."
    );
    let text = std::fs::read_to_string(&args[0]).expect("scene file");
    let scene = Scene::parse(&text).expect("valid scene");
    let mut opts = dynamic_options(&scene).expect("a dynamic scene");
    // `SPAN_KEEP_SLOW_FRESH=0`: build a matrix at every iterate of a slow tail, as before
    // `DynamicOptions::keep_slow_fresh`.
    if std::env::var("SPAN_KEEP_SLOW_FRESH").is_ok_and(|v| v == "0") {
        opts.keep_slow_fresh = false;
    }
    // Newton's settings for studies: `SPAN_UNLOADING`, `SPAN_REFRESH`, `SPAN_BACKTRACK`.
    let setting = |name: &str| {
        std::env::var(name)
            .ok()
            .map(|v| v.parse::<f64>().expect(name))
    };
    if let Some(v) = setting("SPAN_UNLOADING") {
        opts.unloading = v;
    }
    if let Some(v) = setting("SPAN_REFRESH") {
        opts.refresh = v;
    }
    if let Some(v) = setting("SPAN_BACKTRACK") {
        opts.backtrack = v;
    }
    // `SPAN_PREDICTOR=mean`: predict a strand of several layers as a 1+m strand.
    if std::env::var("SPAN_PREDICTOR").is_ok_and(|v| v == "mean") {
        opts.layers_predictor = SlipPredictor::Mean;
    }
    for name in &args[1..] {
        let which = match name.as_str() {
            "equivalent" => BeamModelKind::Equivalent,
            "traditional" => BeamModelKind::Traditional,
            other => panic!("unknown model {other}"),
        };
        let beam = build_beam(&scene, which).expect("beam");
        let init = InitialState::rigid(&beam, scene.velocity, scene.angular_velocity)
            .expect("initial state");
        let start = Instant::now();
        let s = run_dynamic_from(&beam, &opts, &init, &mut |_| {}).expect("run");
        let wall = start.elapsed().as_secs_f64();
        println!(
            "{name:<12} law {:<10} steps {} newton {} matrices {} cut {} iterations/step {:.3} \
             balance {:.3e} J  solve {wall:.3} s",
            beam.law().kind(),
            s.steps,
            s.newton_iterations,
            s.factorizations,
            s.cut_steps,
            s.newton_iterations as f64 / s.steps as f64,
            s.balance_error
        );
        let r = s.rebuilds;
        println!(
            "{:<12} matrices built for the step size {}, after a slow step {}, after a slow \
             iteration {}; slow fresh matrices kept {}",
            "", r.step_size, r.slow_step, r.slow_iteration, r.kept_slow_fresh
        );
        println!(
            "{:<12} steps by Newton iterations (1, 2, ..., 12 or more): {:?}",
            "", s.iteration_histogram
        );
        let nodes = beam.spec().elements + 1;
        let mid = (nodes / 2) * (s.q.len() / nodes);
        println!(
            "{:<12} at the end: middle node at ({:.9e}, {:.9e}) m; energies {:?}",
            "",
            s.q[mid],
            s.q[mid + 1],
            s.last
        );
    }
}
