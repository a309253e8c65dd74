//! The explicit stable step: the frequency bound of `highest_frequency` lies above the exact
//! highest frequency of the linearised model (dense generalized eigenvalues of K against the
//! full mass matrix, translations and the world inertia tensors), and not far above it; the
//! integrator at the bound's step keeps the energy of the Table 1 strand with contacts.

use nalgebra::{DMatrix, Matrix3, Vector3};
use strand_core::{Strand, StrandSpec};
use strand_fine::dynamics::highest_frequency;
use strand_fine::spectrum::lanczos_highest_frequency;
use strand_fine::{
    ContactOptions, Discretisation, FineModel, Integrator, Support, stable_time_step,
};

fn model(segments: usize) -> FineModel {
    let s = Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap();
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
    m
}

/// Exact highest circular frequency (rad/s) of `M^{-1} K` with K the joints' tangent plus
/// `contacts` (closed at their stiffer spring, or closed and stuck), by a dense symmetric
/// eigen solve of `M^{-1/2} K M^{-1/2}` (M block diagonal: mass, and R diag(I_a, I_t, I_t)
/// R^T).
fn exact_highest_frequency(m: &FineModel, contacts: Contacts) -> f64 {
    let state = m.rest_state();
    let n = 6 * m.segment_count();
    let mut k = DMatrix::<f64>::zeros(n, n);
    let mut elements = m.joint_tangents(&state);
    elements.extend(match contacts {
        Contacts::Bound => m.contact_bound_tangents(&state),
        Contacts::Stuck => m.contact_stick_tangents(&state),
    });
    for e in elements {
        e.add_to_dense(&mut k);
    }
    let mut b = DMatrix::<f64>::zeros(n, n);
    let mut i = 0;
    for (w, ws) in m.wires.iter().zip(&state.wires) {
        for (seg, p) in w.chain.segments.iter().zip(&ws.poses) {
            for d in 0..3 {
                b[(6 * i + d, 6 * i + d)] = 1.0 / seg.mass.sqrt();
            }
            let r = p.rotation.to_rotation_matrix();
            let d = Matrix3::from_diagonal(&Vector3::new(
                1.0 / seg.axial_inertia.sqrt(),
                1.0 / seg.transverse_inertia.sqrt(),
                1.0 / seg.transverse_inertia.sqrt(),
            ));
            let inv_sqrt = r.matrix() * d * r.matrix().transpose();
            for a in 0..3 {
                for c in 0..3 {
                    b[(6 * i + 3 + a, 6 * i + 3 + c)] = inv_sqrt[(a, c)];
                }
            }
            i += 1;
        }
    }
    let a = &b * &k * &b;
    let sym = (&a + a.transpose()) * 0.5;
    sym.symmetric_eigenvalues()
        .iter()
        .fold(0.0f64, |x, &y| x.max(y))
        .sqrt()
}

/// Contact stiffness of a frequency computation.
#[derive(Clone, Copy)]
enum Contacts {
    /// `FineModel::contact_bound_tangents`.
    Bound,
    /// `FineModel::contact_stick_tangents`.
    Stuck,
}

/// The settle's Lanczos estimate against the dense eigen solve of the same linearisation:
/// within its stopping criterion (the Ritz residual below 1e-9 of the eigenvalue) except
/// where the top of the spectrum is a cluster it has not resolved.
#[test]
fn lanczos_finds_the_highest_frequency() {
    for segments in [6, 12, 20] {
        let m = model(segments);
        let est = lanczos_highest_frequency(&m, &m.rest_state(), 100);
        let exact = exact_highest_frequency(&m, Contacts::Stuck);
        println!(
            "{segments} segments per wire: Lanczos {:.6e} rad/s ({} steps), exact {exact:.6e} \
             rad/s, ratio {:.6}",
            est.omega,
            est.steps,
            est.omega / exact
        );
        assert!((est.omega / exact - 1.0).abs() < 1e-4);
        // Contacts stuck at the contact point are softer than at the stiffer spring in every
        // direction at the wire's axis (the top modes are the core's spin and translation
        // against the contacts).
        assert!(exact < exact_highest_frequency(&m, Contacts::Bound));
    }
}

#[test]
fn frequency_bound_is_above_the_exact_highest_frequency_and_close_to_it() {
    for segments in [6, 12, 20] {
        let m = model(segments);
        let bound = highest_frequency(&m, &m.rest_state());
        let exact = exact_highest_frequency(&m, Contacts::Bound);
        println!(
            "{segments} segments per wire: bound {bound:.4e} rad/s, exact {exact:.4e} rad/s, ratio {:.3}",
            bound / exact
        );
        assert!(
            bound >= exact * (1.0 - 1e-12),
            "bound {bound:e} below exact {exact:e}"
        );
        assert!(
            bound <= 2.0 * exact,
            "bound {bound:e} far above exact {exact:e}"
        );
    }
}

#[test]
fn strand_with_contacts_keeps_its_energy_at_the_estimated_step() {
    let mut m = model(20);
    m.gravity = Vector3::new(0.0, -9.8065, 0.0);
    let mut state = m.rest_state();
    let dt = stable_time_step(&m, &state, 0.9);
    let mut int = Integrator::new(&m, &state, dt);
    let e0 = int.energies(&m, &state);
    let steps = (0.02 / dt).ceil() as usize;
    let mut worst: f64 = 0.0;
    for _ in 0..steps {
        int.step(&m, &mut state);
        let e = int.energies(&m, &state);
        worst = worst.max((e.balance() - e0.balance()).abs());
    }
    let drop = e0.gravity - int.energies(&m, &state).gravity;
    println!(
        "dt {dt:.3e} s, {steps} steps: largest balance error {worst:.3e} J of a drop {drop:.3e} J"
    );
    assert!(drop > 0.0);
    assert!(
        worst < 1e-3 * drop,
        "balance error {worst:e} J against a drop {drop:e} J"
    );
}

/// `Integrator::advance` (the second half kick of a step and the first of the next in one
/// sweep) gives the same numbers, bit for bit, as `Integrator::step` with the same load
/// factors, damped, with contacts and a ramped load.
#[test]
fn advance_matches_single_steps_bit_for_bit() {
    let mut m = model(12);
    m.gravity = Vector3::new(0.0, -8.0, 0.0);
    let state0 = m.rest_state();
    let dt = stable_time_step(&m, &state0, 0.9);
    let ramp = |t: f64| (t / (300.0 * dt)).min(1.0);
    let (mut a, mut b) = (state0.clone(), state0.clone());
    let mut ia = Integrator::new(&m, &a, dt);
    let mut ib = Integrator::new(&m, &b, dt);
    for i in [&mut ia, &mut ib] {
        i.damping_rate = 30.0;
        i.load_factor = 0.0;
    }
    ia.reload(&m, &a);
    ib.reload(&m, &b);
    for _ in 0..4 {
        ia.advance(&m, &mut a, 100, &ramp);
    }
    for _ in 0..400 {
        ib.load_factor = ramp(ib.time + dt);
        ib.step(&m, &mut b);
    }
    assert_eq!(ia.time.to_bits(), ib.time.to_bits());
    assert!(a.wires[1].poses[5].position != state0.wires[1].poses[5].position);
    assert_eq!(a, b);
}

/// `Integrator::advance` gives the same numbers, bit for bit, on one thread (its sweeps in
/// the calling thread) and on three (the strand cut along its length into three pieces, one
/// per thread), damped, with contacts and a ramped load; and the same as
/// `Integrator::step`, whose sweeps go through rayon.
#[test]
fn advance_does_not_depend_on_the_thread_count() {
    let mut m = model(12);
    m.gravity = Vector3::new(0.0, -8.0, 0.0);
    let state0 = m.rest_state();
    let dt = stable_time_step(&m, &state0, 0.9);
    let ramp = |t: f64| (t / (300.0 * dt)).min(1.0);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut s = state0.clone();
            let mut int = Integrator::new(&m, &s, dt);
            int.damping_rate = 30.0;
            int.load_factor = 0.0;
            int.reload(&m, &s);
            for _ in 0..4 {
                int.advance(&m, &mut s, 100, &ramp);
            }
            (s, int.loads().to_vec())
        })
    };
    let (one, loads_one) = run(1);
    let (three, loads_three) = run(3);
    assert!(one.wires[1].poses[5].position != state0.wires[1].poses[5].position);
    let closed = loads_one
        .iter()
        .flat_map(|l| &l.contacts)
        .filter(|c| c.state != strand_fine::ContactState::Open)
        .count();
    assert!(closed > 10, "{closed} contacts closed");
    assert!(one == three, "the states on 1 and 3 threads differ");
    assert!(
        loads_one == loads_three,
        "the loads on 1 and 3 threads differ"
    );
    let mut b = state0.clone();
    let mut ib = Integrator::new(&m, &b, dt);
    ib.damping_rate = 30.0;
    ib.load_factor = 0.0;
    ib.reload(&m, &b);
    for _ in 0..400 {
        ib.load_factor = ramp(ib.time + dt);
        ib.step(&m, &mut b);
    }
    assert!(one == b, "advance and step differ");
}
