//! What a beam run's energy balance is made of: the integrator's step error, the books of the
//! hysteretic law's slip work under a moving friction limit, and Newton's stopping test.
//!
//! ```text
//! cargo build --release -p strand-scene --example balance_study
//! target/release/examples/balance_study SCENE MODEL DIVISOR [INCREMENT LEDGER]
//! ```
//!
//! Runs `MODEL` (`equivalent` or `traditional`) of the dynamic `SCENE` (planar or spatial
//! element) at its time step divided by `DIVISOR` (Verlet without a step: 0.9 of the
//! estimated stable step, divided), with Newton's `increment` and `ledger` tolerances
//! (`DynamicOptions`; defaults 1e-8, 1e-5), and prints, relative to the largest kinetic
//! energy:
//!
//! * `balance`: the largest |total - initial| over every step (the runner's figure);
//! * `end-point excess`: the largest |D(t)|, where D sums over the steps and bending points
//!   what booking a slipping wire's work at the friction limit of the step's end, `cap_new
//!   |ds|`, adds to the books of the `hysteretic` law, which take the trapezoid of the limit
//!   over the step, `(cap_old + cap_new) / 2 |ds|` (module `slip_work` of the section laws).
//!   In planar bending the limit scales with the strain the section reads (`cap = c eps`),
//!   so the end-point rule's excess over the trapezoid is `W (1 - r) / (1 + r)` per point for
//!   the booked work `W` and `r = eps_old / eps_new`: a first-order quadrature error, O(h)
//!   over the run, that the end-point booking left in the balance (printed for planar runs;
//!   in 3D the limits also turn with the bending direction and the ratio is per wire);
//! * `balance with the end-point booking`: the largest |total - initial + D(t)|;
//! * the run's round-off floor (`DynamicSummary::balance_floor`).
//!
//! The slip work is recomputed point by point from the committed states (the law at the step's
//! strain and curvature from the state before it) and printed beside the ledger's as a check.

use strand_ancf::beam::{ElementKind, PointState};
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
    let planar = beam.spec().element == ElementKind::Planar;
    let ws = law.state_len();
    let mut stations = Vec::new();
    let mut trial = vec![0.0; ws];
    let mut before: Option<(Vec<f64>, Vec<PointState>)> = None;
    let mut e0 = None;
    let (mut excess, mut excess_max, mut end_point_max, mut recomputed, mut dissipated) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let s = run_dynamic_from(&beam, &opts, &init, &mut |f| {
        if let Some((state, points)) = &before {
            if stations.is_empty() {
                stations = f.points.iter().map(|p| law.station(p.x)).collect();
            }
            for (j, (p, old)) in f.points.iter().zip(points).enumerate() {
                let slip = beam.point_slip(state, j);
                let w = if planar {
                    law.planar(&stations[j], p.eps, p.kappa, slip, &mut trial)
                        .slip_work
                } else {
                    law.vector(&stations[j], p.eps, [p.kappa_y, p.kappa], slip, &mut trial)
                        .slip_work
                } * p.weight;
                recomputed += w;
                if planar && w != 0.0 && p.eps > 0.0 {
                    let r = old.eps.max(0.0) / p.eps;
                    excess += w * (1.0 - r) / (1.0 + r);
                }
            }
        }
        let e = f.energies;
        let z = *e0.get_or_insert(e.total());
        excess_max = excess_max.max(excess.abs());
        end_point_max = end_point_max.max((e.total() - z + excess).abs());
        dissipated = e.dissipated;
        before = Some((f.slip.to_vec(), f.points.to_vec()));
    })
    .expect("run");
    let k = s.max_kinetic;
    println!(
        "{} {} h = {h:.4e} s (increment {:.0e}, ledger {:.0e}): balance {:.3e}, end-point excess \
         {:.3e}, balance with the end-point booking {:.3e}, round-off floor {:.2e} of the \
         largest kinetic energy \
         {k:.4e} J; slip work {dissipated:.6e} J (recomputed {recomputed:.6e} J); {} Newton \
         iterations, {} cut steps",
        args[0],
        args[1],
        opts.increment,
        opts.ledger,
        s.balance_error / k,
        excess_max / k,
        end_point_max / k,
        s.balance_floor / k,
        s.newton_iterations,
        s.cut_steps
    );
}
