//! Dynamics: energy conservation of the pinned pendulum with the constant law (Verlet bounded
//! and second order; generalized-alpha without numerical damping), and the energy balance of
//! the stick/slip laws (kinetic + gravity + elastic + dissipated constant up to the
//! integrator's error, which falls with the step), and the cost of Newton with the kept,
//! co-rotated iteration matrix; Newton's stopping test leaves the balance to the integrator.

use strand_ancf::beam::{Beam, BeamSpec, ElementKind, Support};
use strand_ancf::dynamics::{DynamicOptions, DynamicSummary, Scheme, run_dynamic, stable_step};
use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

/// The paper's Table 1 strand (L = 0.4 m, E = 2e8 Pa).
fn strand() -> Strand {
    strand_of(0.4, 2.0e8, 7801.0)
}

/// The paper's section-3 strand (L = 1 m, E = 2e9 Pa, rho = 5747 kg/m^3).
fn section3() -> Strand {
    strand_of(1.0, 2.0e9, 5747.0)
}

fn strand_of(length: f64, e: f64, rho: f64) -> Strand {
    Strand::new(StrandSpec::paper(length, e, rho)).unwrap()
}

fn pendulum(kind: LawKind, elements: usize) -> Beam {
    pendulum_of(&strand(), kind, elements)
}

fn pendulum_of(s: &Strand, kind: LawKind, elements: usize) -> Beam {
    horizontal(s, kind, elements, Support::Pinned, 9.8065)
}

/// `s` laid along +x on the planar element, held at x = 0 by `support`, under gravity `g`
/// (m/s^2) along -y.
fn horizontal(s: &Strand, kind: LawKind, elements: usize, support: Support, g: f64) -> Beam {
    Beam::new(
        BeamSpec {
            elements,
            bending_points: None,
            mass_per_length: s.mass_per_length(),
            element: ElementKind::Planar,
            direction: [1.0, 0.0, 0.0],
            gravity: [0.0, -g, 0.0],
            start: Some(support),
            end: None,
            ..Default::default()
        },
        SectionLaw::new(s, kind),
    )
    .unwrap()
}

/// Potential drop of the strand falling from horizontal to vertical, m g L / 2 (J): the scale
/// of the energies in the run.
fn drop_scale() -> f64 {
    drop_of(&strand())
}

fn drop_of(s: &Strand) -> f64 {
    s.mass_per_length() * s.length() * 9.8065 * s.length() / 2.0
}

fn run(beam: &Beam, duration: f64, scheme: Scheme) -> DynamicSummary {
    let opts = DynamicOptions::new(duration, scheme, duration / 10.0);
    run_dynamic(beam, &opts, &mut |_| {}).unwrap()
}

#[test]
fn verlet_conserves_energy_to_second_order() {
    let beam = pendulum(LawKind::Constant, 8);
    let hs = stable_step(&beam).unwrap();
    let a = run(
        &beam,
        0.3,
        Scheme::Verlet {
            step: Some(0.5 * hs),
        },
    );
    let b = run(
        &beam,
        0.3,
        Scheme::Verlet {
            step: Some(0.25 * hs),
        },
    );
    let (ea, eb) = (
        a.balance_error / drop_scale(),
        b.balance_error / drop_scale(),
    );
    println!(
        "Verlet: stable step {hs:.3e} s; energy error {ea:.3e} at h = {:.3e}, {eb:.3e} at h = {:.3e}; ratio {:.2}",
        a.time_step,
        b.time_step,
        ea / eb
    );
    assert!(ea < 1e-3, "energy error {ea} of the potential drop");
    // The strand has fallen: the kinetic energy is a sizeable part of the potential drop.
    assert!(a.max_kinetic > 0.2 * drop_scale());
    let ratio = ea / eb;
    assert!(
        (3.0..5.5).contains(&ratio),
        "halving the step divides the error by {ratio}"
    );
}

#[test]
fn verlet_refuses_a_step_above_the_stable_one() {
    let beam = pendulum(LawKind::Constant, 8);
    let hs = stable_step(&beam).unwrap();
    let opts = DynamicOptions::new(
        0.01,
        Scheme::Verlet {
            step: Some(2.0 * hs),
        },
        0.01,
    );
    let err = run_dynamic(&beam, &opts, &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(err.contains("stable step"), "{err}");
}

/// The paper's section-3 pendulum (30 elements) with the constant law over 1 s: undamped
/// generalized-alpha (the trapezoidal rule) keeps the energy error below 1e-4 of the
/// potential drop at a 1 ms step.
#[test]
fn generalized_alpha_without_damping_conserves_energy() {
    let s3 = section3();
    let beam = pendulum_of(&s3, LawKind::Constant, 30);
    let s = run(
        &beam,
        1.0,
        Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 1.0,
        },
    );
    let e = s.balance_error / drop_of(&s3);
    println!(
        "generalized-alpha rho = 1, h = 1e-3: energy error {e:.3e} of the potential drop, {} steps, {} Newton iterations",
        s.steps, s.newton_iterations
    );
    assert!(e < 1e-4, "energy error {e}");
    assert!(s.max_kinetic > 0.5 * drop_of(&s3));
}

/// The kept iteration matrix turns with the strand: on the section-3 pendulum at 1e-3 s
/// steps (constant law), modified Newton converges in two iterations a step with the
/// matrix of the first step or two. A matrix that stays put contracts at 0.3-0.5 per
/// iteration there (its stiff axial part points along the old tangent): more than three
/// iterations a step, or a fresh matrix every few steps.
#[test]
fn a_turned_iteration_matrix_serves_the_swing() {
    let s3 = section3();
    let beam = pendulum_of(&s3, LawKind::Constant, 30);
    let s = run(
        &beam,
        0.5,
        Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 0.9,
        },
    );
    println!(
        "{} steps: {} Newton iterations, {} matrices",
        s.steps, s.newton_iterations, s.factorizations
    );
    assert!(s.newton_iterations <= 2 * s.steps + s.steps / 20);
    assert!(s.factorizations <= 5);
}

/// Coulomb friction only removes energy: with the `hysteretic` law the paper's section-3
/// pendulum (Verlet at its stable step, 1 s) never holds more mechanical energy than it
/// started with, beyond the integrator's error, and the dissipated work is positive.
/// (The `continuous` and `paper` laws are not potentials: their moment depends on the
/// tension, so an (eps, kappa) cycle can do net work; with the strand's axial vibrations
/// resolved, as at Verlet's step, that work feeds energy in. That is why dynamic scenes
/// should use `hysteretic`.)
#[test]
fn hysteretic_law_never_creates_energy() {
    let s3 = section3();
    let beam = pendulum_of(&s3, LawKind::Hysteretic, 30);
    let drop = drop_of(&s3);
    let mut worst: f64 = 0.0;
    let opts = DynamicOptions::new(1.0, Scheme::Verlet { step: None }, 1e-3);
    let s = run_dynamic(&beam, &opts, &mut |f| {
        let e = &f.energies;
        worst = worst.max(e.kinetic + e.gravity + e.elastic);
    })
    .unwrap();
    println!(
        "hysteretic, Verlet h {:.3e}: largest mechanical energy {:.3e} of the drop, dissipated {:.4e} J, balance error {:.3e}",
        s.time_step,
        worst / drop,
        s.last.dissipated,
        s.balance_error / drop
    );
    assert!(worst <= 1e-5 * drop, "energy was created: {worst} J");
    assert!(s.last.dissipated > 0.0);
    assert!(s.balance_error < 1e-4 * drop);
}

#[test]
fn stick_slip_laws_close_the_energy_balance() {
    for kind in [LawKind::Continuous, LawKind::Hysteretic] {
        let beam = pendulum(kind, 8);
        let mut errors = Vec::new();
        for h in [2e-3, 1e-3, 5e-4] {
            let s = run(
                &beam,
                0.4,
                Scheme::GeneralizedAlpha {
                    step: h,
                    spectral_radius: 1.0,
                },
            );
            let e = s.balance_error / drop_scale();
            println!(
                "{kind}: h {h:.1e}: balance error {e:.3e} of the potential drop, dissipated {:.4e} J, kinetic at end {:.4e} J",
                s.last.dissipated, s.last.kinetic
            );
            if kind == LawKind::Hysteretic {
                assert!(s.last.dissipated > 0.0, "the hysteretic law dissipates");
            }
            errors.push(e);
        }
        assert!(errors[2] < 1e-3, "{kind}: {errors:?}");
        assert!(
            errors[2] < errors[0],
            "{kind}: the error does not fall with the step: {errors:?}"
        );
    }
}

/// Newton's tolerance in dynamics knows the scale of the motion (issue 17.1): the section-3
/// strand clamped horizontally and released under 1e-11 and 1e-8 of the paper's gravity (0.1
/// s, generalized-alpha at 1 ms, every law) vibrates in the linear regime (terms of relative
/// size (drop / L)^2 < 1e-16, and a tension of second order in the load, so no friction and
/// the stiffness K_min), so its tip drop per unit gravity is the same at both loads, to what
/// 100 steps of Newton's relative tolerance (1e-8) could add up to, with a margin of ten. An
/// absolute tolerance (1e-8 L, the drop being about 1e-12 m) would accept the predictor of
/// every step: the drops would not scale with the load.
#[test]
fn tiny_gravity_moves_the_cantilever_linearly() {
    let s3 = section3();
    for kind in [LawKind::Constant, LawKind::Continuous, LawKind::Hysteretic] {
        let mut drops = Vec::new();
        for g in [9.8e-11, 9.8e-8] {
            let beam = horizontal(&s3, kind, 30, Support::Clamped, g);
            let opts = DynamicOptions::new(
                0.1,
                Scheme::GeneralizedAlpha {
                    step: 1e-3,
                    spectral_radius: 0.9,
                },
                0.01,
            );
            let mut per_g = Vec::new();
            let sum = run_dynamic(&beam, &opts, &mut |f| {
                per_g.push(-beam.sample(f.q, beam.length()).0[1] / g);
            })
            .unwrap();
            println!(
                "{kind}, g = {g:e}: {} Newton iterations, {} matrices",
                sum.newton_iterations, sum.factorizations
            );
            drops.push(per_g);
        }
        let scale = drops[1].iter().fold(0.0f64, |a, d| a.max(d.abs()));
        let worst = drops[0]
            .iter()
            .zip(&drops[1])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        println!(
            "{kind}: tip drop per unit gravity at 0.1 s {:.6e} s^2; largest difference between \
             the loads {:.1e} of it",
            drops[1].last().unwrap(),
            worst / scale
        );
        assert!(worst < 1e-5 * scale, "{kind}: {worst} of {scale}");
    }
}

/// Newton's stopping test leaves the energy balance to the integrator at every step size
/// (issue 16): the section-3 pendulum in its plane (hysteretic law, generalized-alpha with the
/// scenes' spectral radius 0.9, gravity 10.585 m/s^2, the magnitude of issue 16's tilted
/// (0, -9.8, -4)) closes its balance at the trapezoidal rule's second order when the step
/// halves from 0.25 to 0.125 ms (log2 of the ratio at least 1.5, the hard case's criterion;
/// 2.6 measured over issue 16's 5 s), and within its 1e-4 of the largest kinetic energy. A
/// test whose admitted energy error grows as the step shrinks (the former decrement test
/// against beta' m tol^2 ~ 1/h^2: 9.9e-5 and 4.0e-4, order -2.0) fails here.
#[test]
fn newton_leaves_the_balance_to_the_integrator() {
    let s3 = section3();
    let gravity = (9.8f64 * 9.8 + 4.0 * 4.0).sqrt();
    let beam = horizontal(&s3, LawKind::Hysteretic, 30, Support::Pinned, gravity);
    let balance = |h: f64| {
        let s = run(
            &beam,
            5.0,
            Scheme::GeneralizedAlpha {
                step: h,
                spectral_radius: 0.9,
            },
        );
        s.balance_error / s.max_kinetic
    };
    let (coarse, fine) = (balance(2.5e-4), balance(1.25e-4));
    let order = (coarse / fine).log2();
    println!("balance {coarse:.3e} at 0.25 ms, {fine:.3e} at 0.125 ms: order {order:.2}");
    assert!(coarse < 1e-4, "{coarse:.3e}");
    assert!(order >= 1.5, "{order:.2}");
}

/// Frames and steps of a 1 s generalized-alpha run of the Table 1 pendulum (4 elements, 1e-3
/// s steps) with frames every `interval` (s). A run that has not ended after a minute (the
/// run itself takes milliseconds) is reported as a hang instead of holding the suite up.
fn frames_and_steps(interval: f64) -> (usize, usize) {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let beam = pendulum(LawKind::Constant, 4);
        let scheme = Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 0.9,
        };
        let opts = DynamicOptions::new(1.0, scheme, interval);
        let mut frames = 0;
        let s = run_dynamic(&beam, &opts, &mut |_| frames += 1).unwrap();
        let _ = tx.send((frames, s.steps));
    });
    rx.recv_timeout(std::time::Duration::from_secs(60))
        .unwrap_or_else(|_| panic!("output interval {interval:e} s: no end after a minute"))
}

/// An output interval far below the step (1e-13 s against 1e-3 s) writes a frame every step,
/// as an interval of one step does: the same frames (the initial one and one a step, 1001)
/// and steps (1000). The former output loop advanced the next output time one interval at a
/// time, 1e10 additions a step, and did not end.
#[test]
fn a_tiny_output_interval_writes_a_frame_every_step() {
    let every_step = frames_and_steps(1e-3);
    assert_eq!(every_step, (1001, 1000));
    assert_eq!(frames_and_steps(1e-13), every_step);
    // An interval of 2.5 steps: output times at 2.5, 5, 7.5, ... ms, 400 of them in 1 s.
    assert_eq!(frames_and_steps(2.5e-3), (401, 1000));
}

/// A strand at rest without load is moved by round-off alone: Verlet at its estimated stable
/// step runs to the end (it stopped after 2 to 4 steps as `unstable`, its balance error of
/// 5e-27 J above the 2e-27 J it was "given"), and the balance error of either integrator is
/// below the round-off floor. The floor is a worst case (every node's round-off force along its
/// velocity): on the section-3 pendulum's swing at Verlet's tiny stable step it is 4.7e-7 J,
/// above that run's balance error (6.3e-10 J), but below 1e-4 of the largest kinetic energy,
/// far below what the checks judge (a balance open by 5 % of it; an explicit run off by all
/// it was given, which still stops: `an_explicit_run_that_creates_energy_fails` in
/// strand-scene).
#[test]
fn a_strand_at_rest_is_within_the_round_off_floor() {
    let s3 = section3();
    for kind in [LawKind::Constant, LawKind::Continuous, LawKind::Hysteretic] {
        let beam = horizontal(&s3, kind, 8, Support::Clamped, 0.0);
        for scheme in [
            Scheme::Verlet { step: None },
            Scheme::GeneralizedAlpha {
                step: 1e-4,
                spectral_radius: 0.9,
            },
        ] {
            let s = run(&beam, 0.01, scheme);
            println!(
                "{kind:?} {scheme:?}: balance {:.3e} J, floor {:.3e} J",
                s.balance_error, s.balance_floor
            );
            assert!(s.balance_error <= s.balance_floor, "{kind:?} {scheme:?}");
        }
    }
    let swing = run(
        &horizontal(&s3, LawKind::Constant, 30, Support::Pinned, 9.8),
        1.0,
        Scheme::Verlet { step: None },
    );
    println!(
        "swing: balance {:.3e} J, floor {:.3e} J, largest kinetic energy {:.3e} J",
        swing.balance_error, swing.balance_floor, swing.max_kinetic
    );
    assert!(swing.balance_floor < 1e-4 * swing.max_kinetic);
}
