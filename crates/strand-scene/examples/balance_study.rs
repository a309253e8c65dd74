//! What a beam run's energy balance is made of: the integrator's step error, the books of the
//! hysteretic law's slip work under a moving friction limit, and Newton's stopping test.
//!
//! ```text
//! cargo build --release -p strand-scene --example balance_study
//! target/release/examples/balance_study SCENE MODEL DIVISOR [INCREMENT LEDGER]
//! ```
//!
//! Runs `MODEL` (`equivalent` or `traditional`) of the planar dynamic `SCENE` at its time step
//! divided by `DIVISOR` (Verlet without a step: 0.9 of the estimated stable step, divided),
//! with Newton's `increment` and `ledger` tolerances (`DynamicOptions`; defaults 1e-8, 1e-5),
//! and prints, relative to the largest kinetic energy:
//!
//! * `balance`: the largest |total - initial| over every step (the runner's figure);
//! * `booking`: the largest |D(t)|, where D sums over the steps and bending points the slip
//!   work the law books less the trapezoid of the friction limit over the step. The
//!   `hysteretic` law books a slipping wire's work at the limit of the step's end,
//!   `cap_new |ds|`; the limit scales with the strain the section reads (`cap = c eps`), so
//!   the trapezoid `(cap_old + cap_new) / 2 |ds|` is the booked work times
//!   `(1 + eps_old / eps_new) / 2`, and the end-point rule's excess is
//!   `W (1 - eps_old / eps_new) / 2` per point: a first-order quadrature, O(h) over the run;
//! * `balance less booking`: the largest |total - initial - D(t)|, the integrator's own error;
//! * the run's round-off floor (`DynamicSummary::balance_floor`).
//!
//! The slip work is recomputed point by point from the committed states (the law at the step's
//! strain and curvature from the state before it) and printed beside the ledger's as a check.

use strand_ancf::beam::PointState;
use strand_ancf::dynamics::{Scheme, run_dynamic_from, stable_step};
use strand_ancf::initial::InitialState;
use strand_scene::{BeamModelKind, Scene, build_beam, dynamic_options};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    assert!(
        args.len() >= 3,
        "usage: balance_study SCENE (equivalent|traditional) DIVISOR [INCREMENT LEDGER]"
    );
    let text = std::fs::read_to_string(&args[0]).expect("scene file");
    let scene = Scene::parse(&text).expect("valid scene");
    let which = match args[1].as_str() {
        "equivalent" => BeamModelKind::Equivalent,
        "traditional" => BeamModelKind::Traditional,
        other => panic!("unknown model {other}"),
    };
    let divisor: f64 = args[2].parse().expect("divisor");
    let mut opts = dynamic_options(&scene).expect("a dynamic scene");
    if let Some(v) = args.get(3) {
        opts.increment = v.parse().expect("increment");
    }
    if let Some(v) = args.get(4) {
        opts.ledger = v.parse().expect("ledger");
    }
    let beam = build_beam(&scene, which).expect("beam");
    let h = match &mut opts.scheme {
        Scheme::GeneralizedAlpha { step, .. } => {
            *step /= divisor;
            *step
        }
        Scheme::Verlet { step } => {
            let stable = stable_step(&beam).expect("stable step");
            let h = step.unwrap_or(0.9 * stable) / divisor;
            *step = Some(h);
            h
        }
    };
    // A frame at every step: the booking is summed step by step.
    opts.output_interval = h;
    let init =
        InitialState::rigid(&beam, scene.velocity, scene.angular_velocity).expect("initial state");
    let law = beam.law().clone();
    let ws = law.state_len();
    let mut stations = Vec::new();
    let mut trial = vec![0.0; ws];
    let mut before: Option<(Vec<f64>, Vec<PointState>)> = None;
    let mut e0 = None;
    let (mut booking, mut booking_max, mut corrected_max, mut recomputed, mut dissipated) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let s = run_dynamic_from(&beam, &opts, &init, &mut |f| {
        if let Some((slip, points)) = &before {
            if stations.is_empty() {
                stations = f.points.iter().map(|p| law.station(p.x)).collect();
            }
            for (j, (p, old)) in f.points.iter().zip(points).enumerate() {
                let r = law.planar(
                    &stations[j],
                    p.eps,
                    p.kappa,
                    &slip[j * ws..(j + 1) * ws],
                    &mut trial,
                );
                let w = r.slip_work * p.weight;
                recomputed += w;
                if w != 0.0 && p.eps > 0.0 {
                    booking += 0.5 * w * (1.0 - old.eps.max(0.0) / p.eps);
                }
            }
        }
        let e = f.energies;
        let z = *e0.get_or_insert(e.total());
        booking_max = booking_max.max(booking.abs());
        corrected_max = corrected_max.max((e.total() - z - booking).abs());
        dissipated = e.dissipated;
        before = Some((f.slip.to_vec(), f.points.to_vec()));
    })
    .expect("run");
    let k = s.max_kinetic;
    println!(
        "{} {} h = {h:.4e} s (increment {:.0e}, ledger {:.0e}): balance {:.3e}, booking {:.3e}, \
         balance less booking {:.3e}, round-off floor {:.2e} of the largest kinetic energy \
         {k:.4e} J; slip work {dissipated:.6e} J (recomputed {recomputed:.6e} J); {} Newton \
         iterations, {} cut steps",
        args[0],
        args[1],
        opts.increment,
        opts.ledger,
        s.balance_error / k,
        booking_max / k,
        corrected_max / k,
        s.balance_floor / k,
        s.newton_iterations,
        s.cut_steps
    );
}
