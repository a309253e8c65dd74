//! The settle's fast motion (isotropic rotational inertia at 0.9 of the stable step) lands on
//! the static equilibrium, checked against references that do not come from that motion:
//! * without friction the static state is unique, so the fast motion and the motion with the
//!   segments' own inertia at 0.75 of the step (the earlier default) must end, after the
//!   Newton polish, within the polish's own error of each other;
//! * with friction the state depends on the load path, so the check is the model's own loads
//!   at the result, evaluated afresh: every segment's force and torque within the settle's
//!   tolerance of the largest segment weight.
//!
//! The same for the quasi-static load continuation from the straight strand
//! ([`SettledOptions::load_continuation`]): without friction on the settle's equilibrium, with
//! friction on a static state (every segment within the rest allowance, every closed contact
//! inside its friction cone), a failed continuation leaves the settle's result as it was, and
//! the result is the same on one and three threads.

use nalgebra::Vector3;
use strand_core::{Strand, StrandSpec};
use strand_fine::pseudo_transient::PseudoTransientOptions;
use strand_fine::{
    ContactOptions, ContactState, Discretisation, FineModel, ModelState, SettledOptions,
    StaticOptions, Support, solve_settled,
};

/// The short Table 1 strand of `tests/settled.rs` (0.1 m, 12 segments a wire), clamped at one
/// end, under g = 8 m/s^2 along -y, with friction `mu`.
fn strand_model(mu: f64) -> FineModel {
    let strand = Strand::new(StrandSpec::paper(0.1, 2.0e8, 7801.0)).unwrap();
    let mut m = FineModel::from_strand(
        &strand,
        Discretisation {
            core_segments: 12,
            wire_segments: 12,
        },
        Support::Clamped,
        Support::Free,
    );
    m.add_contacts(
        &strand,
        &ContactOptions {
            friction: Some(mu),
            ..ContactOptions::default()
        },
    );
    m.gravity = Vector3::new(0.0, -8.0, 0.0);
    m
}

/// Settles `m` from rest with `opts`; returns the state, the report's tolerance and the
/// settle's steps.
fn settled(m: &FineModel, opts: &SettledOptions) -> (ModelState, f64, u64) {
    let mut state = m.rest_state();
    let r = solve_settled(m, &mut state, opts, &mut |_, _, _| {}).unwrap();
    (state, r.tolerance, r.settle.steps)
}

/// The old default path: the segments' own inertia, 0.75 of the stable step.
fn old_path() -> SettledOptions {
    let mut o = SettledOptions::default();
    o.settle.isotropic_inertia = false;
    o.settle.safety = 0.75;
    o
}

/// Largest force and torque of the model's own loads at `state` over the largest segment
/// weight (and that weight times the largest segment length).
fn scaled_residual(m: &FineModel, state: &ModelState) -> f64 {
    let mut loads = m.load_buffers();
    m.compute_loads(state, 1.0, &mut loads);
    let segs = || m.wires.iter().flat_map(|w| w.chain.segments.iter());
    let weight = segs().map(|s| s.mass).fold(0.0, f64::max) * m.gravity.norm();
    let length = segs().map(|s| s.length).fold(0.0, f64::max);
    loads
        .iter()
        .flat_map(|l| l.forces.iter().zip(&l.torques))
        .map(|(f, t)| (f.norm() / weight).max(t.norm() / (weight * length)))
        .fold(0.0, f64::max)
}

fn tip(m: &FineModel, state: &ModelState) -> Vector3<f64> {
    *m.core_centreline(state).last().unwrap()
}

#[test]
fn without_friction_the_fast_settle_lands_on_the_unique_equilibrium() {
    let m = strand_model(0.0);
    let (fast, tol, fast_steps) = settled(&m, &SettledOptions::default());
    let (old, old_tol, old_steps) = settled(&m, &old_path());
    let (a, b) = (tip(&m, &fast), tip(&m, &old));
    let drop = -b.y;
    println!(
        "fast {fast_steps} steps, old {old_steps}; tips {a:?} / {b:?}: {:.3e} m apart, drop \
         {drop:.4e} m",
        (a - b).norm()
    );
    // A residual of 1e-9 of the largest segment weight on every segment moves the tip by at
    // most about 1e-9 of the drop under the full weight (the tip is linear in the loads near
    // equilibrium; every segment's weight is within a factor 2 of the largest): 1e-7 of the
    // drop leaves room for the round-off allowance of the polish.
    assert!(
        (a - b).norm() <= 1e-7 * drop,
        "tips {:.3e} m apart, beyond 1e-7 of the drop {drop:.3e} m",
        (a - b).norm()
    );
    assert_eq!((tol, old_tol), (1e-9, 1e-9), "both polished by Newton");
    assert!(scaled_residual(&m, &fast) <= 1e-8);
    // The point of the fast path: fewer steps (the stable step is longer).
    assert!(
        fast_steps < old_steps,
        "{fast_steps} steps, old {old_steps}"
    );
}

#[test]
fn with_friction_the_fast_settle_meets_the_residual_of_the_models_own_loads() {
    let m = strand_model(0.3);
    let (fast, tol, _) = settled(&m, &SettledOptions::default());
    let r = scaled_residual(&m, &fast);
    println!("scaled residual {r:.3e} (tolerance met {tol:.0e})");
    // Newton accepts a residual within the round-off of the stiff joints (100 ulps of the
    // coordinates on the stiffest spring, here above 1e-9 of the weight); the settle's
    // tolerance bounds the result whether Newton converged or stalled.
    assert!(
        r <= 1e-4,
        "scaled residual {r:.3e} (tolerance met {tol:.0e})"
    );
}

/// The damped motion handed over to the pseudo-transient continuation at 100 times the
/// settle's allowance.
fn continued() -> SettledOptions {
    SettledOptions {
        pseudo_transient: Some(PseudoTransientOptions::default()),
        ..SettledOptions::default()
    }
}

#[test]
fn without_friction_the_continuation_lands_on_the_unique_equilibrium() {
    let m = strand_model(0.0);
    let mut state = m.rest_state();
    let r = solve_settled(&m, &mut state, &continued(), &mut |_, _, _| {}).unwrap();
    let (motion, _, motion_steps) = settled(&m, &SettledOptions::default());
    let (a, b) = (tip(&m, &state), tip(&m, &motion));
    let drop = -b.y;
    println!(
        "continuation after {} steps: {:?}; the motion alone {motion_steps} steps; tips {a:?} \
         / {b:?}: {:.3e} m apart",
        r.settle.steps,
        r.pseudo_transient,
        (a - b).norm()
    );
    let pt = r.pseudo_transient.expect("the continuation ran");
    assert!(
        pt.converged,
        "the continuation reached the settle's tolerance"
    );
    assert_eq!(r.tolerance, 1e-9, "polished by Newton");
    // The bound of `without_friction_the_fast_settle_lands_on_the_unique_equilibrium`: both
    // states within 1e-9 of the weight on every segment.
    assert!(
        (a - b).norm() <= 1e-7 * drop,
        "tips {:.3e} m apart, beyond 1e-7 of the drop {drop:.3e} m",
        (a - b).norm()
    );
    assert!(scaled_residual(&m, &state) <= 1e-8);
    assert!(
        r.settle.steps < motion_steps,
        "{} steps, the motion alone {motion_steps}",
        r.settle.steps
    );
}

#[test]
fn with_friction_the_continuation_meets_the_residual_of_the_models_own_loads() {
    let m = strand_model(0.3);
    let mut state = m.rest_state();
    let r = solve_settled(&m, &mut state, &continued(), &mut |_, _, _| {}).unwrap();
    let res = scaled_residual(&m, &state);
    println!(
        "{} steps, continuation {:?}, Newton {} iterations; scaled residual {res:.3e}",
        r.settle.steps, r.pseudo_transient, r.iterations
    );
    assert!(res <= 1e-4, "scaled residual {res:.3e}");
    // A continuation that stalls hands back the state it started from, and the motion goes on
    // from there as it would have without it: the default path's result, bit for bit.
    if !r.pseudo_transient.expect("the continuation ran").converged {
        let (motion, _, motion_steps) = settled(&m, &SettledOptions::default());
        assert_eq!(r.settle.steps, motion_steps);
        assert_eq!(tip(&m, &state), tip(&m, &motion));
        assert_eq!(state.wires, motion.wires);
    }
}

/// The quasi-static load continuation from the straight strand in five load steps, with
/// one penalty stage.
fn loaded() -> SettledOptions {
    SettledOptions {
        load_continuation: Some(StaticOptions {
            load_steps: 5,
            penalty_stages: 1,
            ..StaticOptions::default()
        }),
        ..SettledOptions::default()
    }
}

/// Largest ratio of a closed contact's tangential force to its Coulomb cap `mu N` at
/// `state`, the model's own loads evaluated afresh.
fn cone_ratio(m: &FineModel, state: &ModelState, mu: f64) -> f64 {
    let mut loads = m.load_buffers();
    m.compute_loads(state, 1.0, &mut loads);
    loads
        .iter()
        .flat_map(|l| l.contacts.iter())
        .filter(|c| c.state != ContactState::Open)
        .map(|c| {
            let cap = mu * c.normal_force;
            if cap > 0.0 {
                c.tangential_force.norm() / cap
            } else if c.tangential_force.norm() > 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

#[test]
fn without_friction_the_load_continuation_lands_on_the_unique_equilibrium() {
    let m = strand_model(0.0);
    let mut state = m.rest_state();
    let r = solve_settled(&m, &mut state, &loaded(), &mut |_, _, _| {}).unwrap();
    let (motion, _, motion_steps) = settled(&m, &SettledOptions::default());
    let (a, b) = (tip(&m, &state), tip(&m, &motion));
    let drop = -b.y;
    println!(
        "continuation {:?}, Newton {} iterations; the motion {motion_steps} steps; tips {a:?} / \
         {b:?}: {:.3e} m apart",
        r.load_continuation,
        r.iterations,
        (a - b).norm()
    );
    assert!(r.load_continuation.expect("it ran").converged);
    assert_eq!(r.settle.steps, 0, "no motion");
    // The bound of `without_friction_the_fast_settle_lands_on_the_unique_equilibrium`: both
    // states within 1e-9 of the weight (plus round-off) on every segment.
    assert!(
        (a - b).norm() <= 1e-7 * drop,
        "tips {:.3e} m apart, beyond 1e-7 of the drop {drop:.3e} m",
        (a - b).norm()
    );
    // Newton's criterion: within the tolerance of the weight plus the round-off allowance
    // (100 ulps of the largest coordinate on the stiffest joint spring), here 2e-7 of it.
    let p = r.polish.expect("converged");
    let allowed = r.tolerance + p.roundoff / p.force_scale;
    let res = scaled_residual(&m, &state);
    assert!(
        res <= allowed,
        "scaled residual {res:.3e} beyond {allowed:.3e}"
    );
}

#[test]
fn with_friction_the_load_continuation_lands_on_a_static_state() {
    let mu = 0.3;
    let m = strand_model(mu);
    let mut state = m.rest_state();
    let r = solve_settled(&m, &mut state, &loaded(), &mut |_, _, _| {}).unwrap();
    let (motion, _, _) = settled(&m, &SettledOptions::default());
    let res = scaled_residual(&m, &state);
    let cone = cone_ratio(&m, &state, mu);
    println!(
        "continuation {:?}, Newton {} iterations; scaled residual {res:.3e}, largest |F_t| / mu \
         N {cone:.6}; tip {:.3e} m from the settle's",
        r.load_continuation,
        r.iterations,
        (tip(&m, &state) - tip(&m, &motion)).norm()
    );
    assert!(r.load_continuation.expect("it ran").converged);
    // Every segment within the settle's rest allowance (1e-4 of the largest weight), every
    // closed contact inside its friction cone (the cap, to the rounding of its product).
    assert!(res <= 1e-4, "scaled residual {res:.3e}");
    assert!(cone <= 1.0 + 1e-12, "|F_t| / mu N {cone}");
}

#[test]
fn a_failed_load_continuation_leaves_the_settle_as_it_was() {
    let m = strand_model(0.3);
    // Twenty Newton iterations a step and no halving: the first of five load steps converges
    // (its contact histories committed), the second does not.
    let opts = SettledOptions {
        load_continuation: Some(StaticOptions {
            load_steps: 5,
            max_iterations: 20,
            min_increment: 0.2,
            ..StaticOptions::default()
        }),
        ..SettledOptions::default()
    };
    let mut state = m.rest_state();
    let r = solve_settled(&m, &mut state, &opts, &mut |_, _, _| {}).unwrap();
    let lc = r.load_continuation.expect("it ran");
    assert!(!lc.converged);
    assert_eq!(lc.load_steps, 1, "{lc:?}");
    let (motion, _, motion_steps) = settled(&m, &SettledOptions::default());
    assert_eq!(r.settle.steps, motion_steps);
    assert!(
        state.wires == motion.wires,
        "poses differ from the settle's"
    );
    assert!(
        state.contacts == motion.contacts,
        "contact histories differ from the settle's"
    );
}

#[test]
fn the_load_continuation_does_not_depend_on_the_thread_count() {
    let m = strand_model(0.3);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut state = m.rest_state();
            let r = solve_settled(&m, &mut state, &loaded(), &mut |_, _, _| {}).unwrap();
            (state, r.iterations)
        })
    };
    let (one, it1) = run(1);
    let (three, it3) = run(3);
    assert_eq!(it1, it3);
    assert!(
        one.wires == three.wires,
        "poses differ between 1 and 3 threads"
    );
    assert!(
        one.contacts == three.contacts,
        "contact histories differ between 1 and 3 threads"
    );
}
