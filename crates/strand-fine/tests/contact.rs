//! Wire-to-core contact in the model: an unloaded strand with contacts stays at rest; a
//! helical segment pressed on the core sticks below mu N and slides above; strand pendulums
//! conserve energy (frictionless) and energy plus friction work (with friction).

use std::time::Instant;

use nalgebra::Vector3;
use strand_core::{Material, Strand, StrandSpec};
use strand_fine::{
    Anchor, Chain, ContactOptions, ContactState, Discretisation, FineModel, Integrator,
    JointSpring, JointStiffness, Support, Wire, WireSection, stable_time_step,
};

const TABLE1: Material = Material {
    youngs_modulus: 2.0e8,
    poisson_ratio: 0.3,
    density: 7801.0,
};

fn strand(length: f64, friction: f64) -> Strand {
    let mut spec = StrandSpec::paper(length, TABLE1.youngs_modulus, TABLE1.density);
    spec.friction = friction;
    Strand::new(spec).unwrap()
}

#[test]
fn unloaded_strand_with_contacts_stays_at_rest() {
    let s = strand(0.4, 0.3);
    let mut m = FineModel::from_strand(
        &s,
        Discretisation {
            core_segments: 77,
            wire_segments: 77,
        },
        Support::Clamped,
        Support::Free,
    );
    m.add_contacts(&s, &ContactOptions::default());
    assert_eq!(m.contact_count(), 6 * 77 * 2);
    let mut state = m.rest_state();
    let dt = stable_time_step(&m, &state, 0.9);
    let mut int = Integrator::new(&m, &state, dt);
    for _ in 0..100 {
        int.step(&m, &mut state);
    }
    let loads = int.loads();
    let f = loads
        .iter()
        .flat_map(|l| l.forces.iter())
        .fold(0.0f64, |a, f| a.max(f.norm()));
    let t = loads
        .iter()
        .flat_map(|l| l.torques.iter())
        .fold(0.0f64, |a, f| a.max(f.norm()));
    let closed_at_start = m.energies(&m.rest_state(), &mut m.load_buffers()).contact;
    assert_eq!(
        closed_at_start, 0.0,
        "the lay geometry touches with zero gap"
    );
    let closed = loads
        .iter()
        .flat_map(|l| l.contacts.iter())
        .filter(|c| c.state != ContactState::Open)
        .count();
    let moved = state
        .wires
        .iter()
        .zip(&m.rest_state().wires)
        .flat_map(|(a, b)| a.poses.iter().zip(&b.poses))
        .fold(0.0f64, |a, (p, q)| a.max((p.position - q.position).norm()));
    let e = int.energies(&m, &state);
    println!(
        "rest with contacts, 100 steps of {dt:.3e} s: max force {f:.2e} N, max torque {t:.2e} \
         N m, max displacement {moved:.2e} m, {closed} contacts closed, contact energy {:.2e} J",
        e.contact
    );
    assert!(f <= 1e-12 && t <= 1e-15, "force {f}, torque {t}");
    assert!(moved <= 1e-15);
    assert!(e.contact < 1e-30);
}

/// A short helical segment on a clamped core, its rotation held by a rotational spring,
/// pressed on the core by N (ramped) and then pulled along the core axis by P (ramped, then
/// held). Returns (wire displacement along x over the hold, final state, stored tangential
/// force, tangential stiffness).
fn press_and_pull(pull_ratio: f64) -> (f64, ContactState, f64, f64, f64) {
    let mu = 0.3;
    let s = strand(0.03, mu);
    let layer = *s.layers().first().unwrap();
    let core = Chain::straight(
        WireSection::from_spec(s.core()),
        Vector3::new(-0.01, 0.0, 0.0),
        0.03,
        3,
    );
    let mut core = Wire::new(core);
    core.support(strand_fine::End::Start, Support::Clamped);
    core.support(strand_fine::End::End, Support::Clamped);
    let wire = Chain::helix(&layer, 0, 0.005, 1);
    let rest = wire.rest[0];
    let mut wire = Wire::new(wire);
    let hold = JointStiffness {
        translational: Vector3::zeros(),
        rotational: Vector3::repeat(1.0),
    };
    wire.anchors.push(Anchor {
        segment: 0,
        ground: rest,
        joint: JointSpring::at_rest(&rest, Vector3::zeros(), &rest, Vector3::zeros(), hold),
    });
    let mut m = FineModel {
        wires: vec![core, wire],
        gravity: Vector3::zeros(),
        ties: Vec::new(),
    };
    let opts = ContactOptions {
        points_per_segment: Some(1),
        ..Default::default()
    };
    m.add_contacts(&s, &opts);
    let law = m.wires[1].contacts[0].law;
    // Press with the reference force of the penalty (it penetrates by 1e-3 d_w).
    let normal = law.normal_stiffness * 1e-3 * 2.0e-3;
    let radial = Vector3::new(0.0, rest.position.y, rest.position.z).normalize();
    let mut state = m.rest_state();
    let dt = stable_time_step(&m, &state, 0.9);
    let mass = m.wires[1].chain.segments[0].mass;
    let period = 2.0 * std::f64::consts::PI * (mass / law.normal_stiffness).sqrt();
    let ramp = (200.0 * period / dt) as usize;
    let mut int = Integrator::new(&m, &state, dt);
    let pull = pull_ratio * mu * normal;
    // Mean wire position over the first and the last fifth of the hold (the ramps leave a
    // small free oscillation).
    let (mut x0, mut x1) = (0.0, 0.0);
    let window = ramp / 5;
    let mut hold_start = 0.0;
    for step in 0..3 * ramp {
        let a = (step as f64 / ramp as f64).min(1.0);
        let b = ((step as f64 - ramp as f64) / ramp as f64).clamp(0.0, 1.0);
        m.wires[1].external = vec![-radial * (normal * a) + Vector3::x() * (pull * b)];
        int.step(&m, &mut state);
        let xs = state.wires[1].poses[0].position.x;
        if step == 2 * ramp {
            hold_start = xs;
        }
        if step > 2 * ramp && xs - hold_start > 2e-3 {
            // Sliding: stop before the segment leaves the short core.
            (x0, x1) = (hold_start, xs);
            break;
        }
        let x = xs / window as f64;
        if (2 * ramp..2 * ramp + window).contains(&step) {
            x0 += x;
        } else if step >= 3 * ramp - window {
            x1 += x;
        }
    }
    let c = int.loads()[1].contacts[0];
    println!(
        "press N = {normal:.4e} N, pull {pull_ratio} mu N: normal force {:.4e} N, tangential \
         {:.4e} N = {:.4} mu N, state {:?}, x moved {:.3e} m over the hold (stick spring \
         displacement P / k_t = {:.3e} m)",
        c.normal_force,
        c.tangential_force.norm(),
        c.tangential_force.norm() / (mu * c.normal_force),
        c.state,
        x1 - x0,
        pull / law.tangential_stiffness
    );
    (
        x1 - x0,
        c.state,
        c.tangential_force.norm() / (mu * c.normal_force),
        pull / law.tangential_stiffness,
        c.normal_force / normal,
    )
}

#[test]
fn pressed_segment_sticks_below_mu_n_and_slides_above() {
    let (dx, state, ratio, spring, n) = press_and_pull(0.9);
    assert_eq!(state, ContactState::Stick);
    assert!((n - 1.0).abs() < 0.02, "normal force ratio {n}");
    assert!((ratio - 0.9).abs() < 0.02, "friction ratio {ratio}");
    assert!(dx.abs() < 0.05 * spring, "drift {dx:e} vs {spring:e}");
    let (dx, state, ratio, spring, _) = press_and_pull(1.1);
    assert_eq!(state, ContactState::Slip);
    assert!((ratio - 1.0).abs() < 1e-9, "friction ratio {ratio}");
    assert!(dx > 100.0 * spring, "slide {dx:e} vs {spring:e}");
}

/// Pinned Table 1 strand released horizontally under gravity for `duration` s; returns
/// (max |balance - balance_0| / potential drop, friction work / drop, wall s).
fn strand_pendulum(mu: f64, duration: f64, threads: usize) -> (f64, f64, f64, Vec<f64>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let s = strand(0.4, mu);
        let mut m = FineModel::from_strand(
            &s,
            Discretisation {
                core_segments: 40,
                wire_segments: 40,
            },
            Support::Pinned,
            Support::Free,
        );
        m.add_contacts(&s, &ContactOptions::default());
        m.gravity = Vector3::new(0.0, -9.8065, 0.0);
        let mut state = m.rest_state();
        let dt = stable_time_step(&m, &state, 0.9);
        let mut int = Integrator::new(&m, &state, dt);
        let e0 = int.energies(&m, &state);
        let steps = (duration / dt).ceil() as usize;
        let (mut err, mut min_g) = (0.0f64, e0.gravity);
        let t = Instant::now();
        let mut closed = 0;
        for _ in 0..steps {
            int.step(&m, &mut state);
            let e = int.energies(&m, &state);
            err = err.max((e.balance() - e0.balance()).abs());
            min_g = min_g.min(e.gravity);
        }
        for l in int.loads() {
            closed += l
                .contacts
                .iter()
                .filter(|c| c.state != ContactState::Open)
                .count();
        }
        let wall = t.elapsed().as_secs_f64();
        let e = int.energies(&m, &state);
        let drop = e0.gravity - min_g;
        let tip = m.core_centreline(&state)[40];
        println!(
            "strand pendulum mu = {mu}, {threads} thread(s): dt = {dt:.3e} s, {steps} steps, \
             drop {drop:.3e} J, max |E + W_f - E0| = {:.3e} of the drop, contact energy \
             {:.3e} J, friction stored {:.3e} J, friction work {:.3e} J, {closed} of {} \
             contacts closed, tip ({:.5}, {:.5}) m, {:.3e} segment-steps/s",
            err / drop,
            e.contact,
            e.friction_stored,
            e.friction_work,
            m.contact_count(),
            tip.x,
            tip.y,
            (steps * m.segment_count()) as f64 / wall
        );
        let fingerprint = state
            .wires
            .iter()
            .flat_map(|w| w.poses.iter().map(|p| p.position.y))
            .collect();
        (err / drop, e.friction_work / drop, wall, fingerprint)
    })
}

#[test]
fn frictionless_strand_pendulum_conserves_energy() {
    let (err, work, _, _) = strand_pendulum(0.0, 0.05, 2);
    assert!(err < 1e-3, "energy error {err:e} of the drop");
    assert_eq!(work, 0.0);
}

#[test]
fn strand_pendulum_with_friction_balances_energy_and_is_deterministic() {
    let (err, work, _, _) = strand_pendulum(0.3, 0.05, 2);
    assert!(err < 1e-3, "energy balance error {err:e} of the drop");
    assert!(work > 0.0);
    let (_, _, _, b) = strand_pendulum(0.3, 0.01, 1);
    let (_, _, _, c) = strand_pendulum(0.3, 0.01, 2);
    assert_eq!(b, c, "same numbers on 1 and 2 threads");
}

#[test]
#[ignore = "open problem: Newton stalls in the first load step (contacts at zero gap opening and \
            closing under gravity without tension); MU, G, STEPS from the environment"]
fn strand_cantilever_with_contacts_reaches_equilibrium() {
    let s = strand(0.4, 0.3);
    let mut m = FineModel::from_strand(
        &s,
        Discretisation {
            core_segments: 40,
            wire_segments: 40,
        },
        Support::Clamped,
        Support::Free,
    );
    let env = |k: &str, d: f64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    m.add_contacts(
        &s,
        &ContactOptions {
            friction: Some(env("MU", 0.3)),
            ..Default::default()
        },
    );
    m.gravity = Vector3::new(0.0, -env("G", 8.0), 0.0);
    let mut state = m.rest_state();
    let t = Instant::now();
    let rep = strand_fine::solve_relaxation(
        &m,
        &mut state,
        &strand_fine::RelaxationOptions {
            load_steps: env("STEPS", 10.0) as usize,
            tolerance: env("TOL", 1e-6),
            ..Default::default()
        },
    )
    .expect("static solve with contacts");
    let tip = m.core_centreline(&state)[40];
    let loads = {
        let mut l = m.load_buffers();
        m.compute_loads(&state, 1.0, &mut l);
        l
    };
    let count = |st: ContactState| {
        loads
            .iter()
            .flat_map(|l| l.contacts.iter())
            .filter(|c| c.state == st)
            .count()
    };
    println!(
        "strand cantilever g = 8 with contacts: {} Newton iterations over {} load steps, \
         residual {:.2e} F_ref, {:.2} s; tip ({:.5}, {:.5}) m; contacts open {}, stick {}, slip {}",
        rep.iterations,
        rep.load_steps,
        rep.residual,
        t.elapsed().as_secs_f64(),
        tip.x,
        tip.y,
        count(ContactState::Open),
        count(ContactState::Stick),
        count(ContactState::Slip)
    );
    assert!(tip.y < -0.05, "the strand hangs down");
}

/// The paper's Fig. 8 pendulum with contacts: 7 wires x 77 segments, Table 1 strand,
/// released horizontal under gravity 9.8065 m/s^2 for 0.5 s; wall time and throughput.
#[test]
#[ignore = "speed study, about 1 min per boundary condition; MU from the environment (0.3)"]
fn fig8_pendulum_speed() {
    let mu = std::env::var("MU")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.3);
    for support in [Support::Clamped, Support::Pinned] {
        let s = strand(0.4, mu);
        let mut m = FineModel::from_strand(
            &s,
            Discretisation {
                core_segments: 77,
                wire_segments: 77,
            },
            support,
            Support::Free,
        );
        m.add_contacts(&s, &ContactOptions::default());
        m.gravity = Vector3::new(0.0, -9.8065, 0.0);
        let mut state = m.rest_state();
        let t0 = Instant::now();
        let dt = stable_time_step(&m, &state, 0.9);
        let mut int = Integrator::new(&m, &state, dt);
        let e0 = int.energies(&m, &state);
        let setup = t0.elapsed().as_secs_f64();
        let steps = (0.5 / dt).ceil() as usize;
        let (mut err, mut min_g) = (0.0f64, e0.gravity);
        let t = Instant::now();
        for k in 0..steps {
            int.step(&m, &mut state);
            if k % 100 == 0 || k + 1 == steps {
                let e = int.energies(&m, &state);
                err = err.max((e.balance() - e0.balance()).abs());
                min_g = min_g.min(e.gravity);
            }
        }
        let wall = t.elapsed().as_secs_f64();
        let e = int.energies(&m, &state);
        let tip = m.core_centreline(&state)[77];
        println!(
            "Fig. 8 {support:?}, mu = {mu}: dt = {dt:.3e} s, {steps} steps, wall {wall:.1} s (set-up {:.2} \
             s), {:.3e} segment-steps/s on {} threads; max |E + W_f - E0| {:.2e} of the drop \
             {:.3e} J; friction work {:.3e} J; tip at 0.5 s ({:.4}, {:.4}) m",
            setup,
            (steps * m.segment_count()) as f64 / wall,
            rayon::current_num_threads(),
            err / (e0.gravity - min_g),
            e0.gravity - min_g,
            e.friction_work,
            tip.x,
            tip.y
        );
    }
}
