//! The assembled static tangent (joints, anchors and contacts) against a central-difference
//! Jacobian of the residual loads, on a strand with some contacts closed, frictionless and
//! with friction (stick and slip, committed histories), away from switch points; and under a
//! light load, where contacts penetrate by less than the tangent's default difference step.

use nalgebra::{DMatrix, Vector3};
use strand_core::{Strand, StrandSpec};
use strand_fine::joint::perturb;
use strand_fine::{
    ContactOptions, ContactState, Discretisation, FineModel, ModelState, Pose, Support, so3,
};

fn model(mu: f64) -> FineModel {
    model_of(0.4, 12, mu)
}

/// Table 1 strand of length `length` (m), `segments` per wire, friction `mu`, clamped at the
/// start, with contacts and gravity 8 m/s^2.
fn model_of(length: f64, segments: usize, mu: f64) -> FineModel {
    let mut spec = StrandSpec::paper(length, 2e8, 7801.0);
    spec.friction = mu;
    let s = Strand::new(spec).unwrap();
    let mut m = FineModel::from_strand(
        &s,
        Discretisation {
            core_segments: segments,
            wire_segments: segments,
        },
        Support::Clamped,
        Support::Free,
    );
    m.add_contacts(&s, &ContactOptions::default());
    m.gravity = Vector3::new(0.0, -8.0, 0.0);
    m
}

/// Residual loads (forces and torques of every segment) at `state`, full load.
fn residual(m: &FineModel, state: &ModelState) -> Vec<f64> {
    let mut l = m.load_buffers();
    m.compute_loads(state, 1.0, &mut l);
    l.iter()
        .flat_map(|w| w.forces.iter().zip(&w.torques))
        .flat_map(|(f, t)| f.iter().chain(t.iter()).copied().collect::<Vec<_>>())
        .collect()
}

fn assembled(m: &FineModel, state: &ModelState) -> DMatrix<f64> {
    let n = 6 * m.segment_count();
    let mut k = DMatrix::zeros(n, n);
    for e in m.element_tangents(state) {
        e.add_to_dense(&mut k);
    }
    k
}

fn pose_mut(state: &mut ModelState, mut g: usize) -> &mut Pose {
    for w in &mut state.wires {
        if g < w.poses.len() {
            return &mut w.poses[g];
        }
        g -= w.poses.len();
    }
    unreachable!()
}

/// `-d(residual)/d(coordinates)` by central differences: translations by `hx` (m), world
/// rotation increments by `hx / 0.01 m` (rad).
fn finite_difference(m: &FineModel, state: &ModelState, hx: f64) -> DMatrix<f64> {
    let n = 6 * m.segment_count();
    let mut k = DMatrix::zeros(n, n);
    for col in 0..n {
        let h = if col % 6 < 3 { hx } else { hx / 0.01 };
        let mut sp = state.clone();
        perturb(pose_mut(&mut sp, col / 6), col % 6, h);
        let mut sm = state.clone();
        perturb(pose_mut(&mut sm, col / 6), col % 6, -h);
        let (rp, rm) = (residual(m, &sp), residual(m, &sm));
        for r in 0..n {
            k[(r, col)] = -(rp[r] - rm[r]) / (2.0 * h);
        }
    }
    k
}

/// Deterministic pseudo-random numbers in [-1, 1).
fn uniform(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
}

/// Moves every segment by up to `dx` (m) and turns it by up to `dw` (rad).
fn shake(state: &mut ModelState, seed: &mut u64, dx: f64, dw: f64) {
    for w in &mut state.wires {
        for p in &mut w.poses {
            let mut v = || Vector3::new(uniform(seed), uniform(seed), uniform(seed));
            p.position += v() * dx;
            p.rotation = so3::exp(&(v() * dw)) * p.rotation;
        }
    }
}

/// Checks the tangent at `state` against differences with translation steps `hx` (m) to a
/// relative error `tol` and returns the contact counts (open, stick, slip).
fn check(m: &FineModel, state: &ModelState, hx: f64, tol: f64) -> [usize; 3] {
    let mut loads = m.load_buffers();
    m.compute_loads(state, 1.0, &mut loads);
    // Away from the kink of the penalty and from the stick-slip limit: every gap and every
    // closed contact's distance to the limit at least 2 steps from zero.
    let core = &state.wires[0].poses;
    for ((w, s), l) in m.wires.iter().zip(&state.wires).zip(&loads).skip(1) {
        for (cp, c) in w.contacts.iter().zip(&l.contacts) {
            let p = s.poses[cp.segment].point(&cp.offset);
            let j = c.core_segment;
            let q = strand_fine::contact::closest_on_axis(
                &p,
                &core[j],
                m.wires[0].chain.segments[j].length,
            );
            let gap = (p - q).norm() - cp.rest_distance;
            assert!(
                gap.abs() > 2.0 * hx,
                "a contact sits at the kink: gap {gap:e}"
            );
            let cap = cp.law.friction * c.normal_force;
            if cap > 0.0 {
                let margin = match c.state {
                    ContactState::Slip => c.slip_work / cap,
                    _ => (cap - c.tangential_force.norm()) / cp.law.tangential_stiffness,
                };
                assert!(margin > 2.0 * hx, "a contact sits at the stick-slip limit");
            }
        }
    }
    let k = assembled(m, state);
    let fd = finite_difference(m, state, hx);
    let scale = fd.norm();
    let err = (&k - &fd).norm() / scale;
    let mut worst: f64 = 0.0;
    for c in 0..k.ncols() {
        let col = fd
            .column(c)
            .norm()
            .max(1e-6 * scale / (k.ncols() as f64).sqrt());
        worst = worst.max((k.column(c) - fd.column(c)).norm() / col);
    }
    let count = |st: ContactState| {
        loads
            .iter()
            .flat_map(|l| l.contacts.iter())
            .filter(|c| c.state == st)
            .count()
    };
    let counts = [
        count(ContactState::Open),
        count(ContactState::Stick),
        count(ContactState::Slip),
    ];
    println!(
        "tangent vs finite differences: relative error {err:.2e} (worst column {worst:.2e}); \
         contacts open {}, stick {}, slip {}",
        counts[0], counts[1], counts[2]
    );
    assert!(err < tol, "tangent off by {err:e}");
    assert!(
        worst < 1e3 * tol,
        "a column of the tangent is off by {worst:e}"
    );
    counts
}

#[test]
fn static_tangent_matches_finite_differences_with_contacts() {
    for mu in [0.0, 0.3] {
        let m = model(mu);
        let mut state = m.rest_state();
        let mut seed = 7;
        // Some contacts pressed, some open; histories open (no friction yet).
        shake(&mut state, &mut seed, 2e-6, 2e-4);
        let [open, stick, slip] = check(&m, &state, 1e-10, 1e-6);
        assert!(open > 0 && stick + slip > 0);
        // Commit, move on: closed histories load the friction springs.
        let mut loads = m.load_buffers();
        m.compute_loads(&state, 1.0, &mut loads);
        m.commit_contacts(&mut state, &loads);
        shake(&mut state, &mut seed, 1e-6, 1e-4);
        let [open, stick, slip] = check(&m, &state, 1e-10, 1e-6);
        assert!(open > 0 && slip > 0);
        if mu > 0.0 {
            assert!(stick > 0, "both friction branches are exercised");
        }
    }
}

/// Under a light load contacts penetrate by 1e-11 m and stick within 1e-13 m of slip, less
/// than the default difference step of the contact tangent (1e-10 m): its steps must shrink
/// with the distance to the switch. A short strand keeps the coordinates small, so that the
/// reference differences with 1e-14 m steps are not lost in round-off.
#[test]
fn static_tangent_matches_finite_differences_under_light_contact() {
    let seed_for = |mu: f64| if mu > 0.0 { 11 } else { 3 };
    for mu in [0.0, 0.3] {
        let m = model_of(0.02, 6, mu);
        let mut state = m.rest_state();
        let mut seed = seed_for(mu);
        shake(&mut state, &mut seed, 2e-11, 2e-9);
        let mut loads = m.load_buffers();
        m.compute_loads(&state, 1.0, &mut loads);
        m.commit_contacts(&mut state, &loads);
        shake(&mut state, &mut seed, 1e-12, 1e-10);
        let [open, stick, slip] = check(&m, &state, 1e-14, 1e-3);
        assert!(open > 0 && stick + slip > 0);
    }
}
