//! The explicit stable step: the frequency bound of `highest_frequency` lies above the exact
//! highest frequency of the linearised model (dense generalized eigenvalues of K against the
//! full mass matrix, translations and the world inertia tensors), and not far above it; the
//! integrator at the bound's step keeps the energy of the Table 1 strand with contacts.

use nalgebra::{DMatrix, Matrix3, Vector3};
use strand_core::{Strand, StrandSpec};
use strand_fine::dynamics::highest_frequency;
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

/// Exact highest circular frequency (rad/s) of `M^{-1} K` with K the bound tangent (joints
/// and contacts closed at their stiffer spring), by a dense symmetric eigen solve of
/// `M^{-1/2} K M^{-1/2}` (M block diagonal: mass, and R diag(I_a, I_t, I_t) R^T).
fn exact_highest_frequency(m: &FineModel) -> f64 {
    let state = m.rest_state();
    let n = 6 * m.segment_count();
    let mut k = DMatrix::<f64>::zeros(n, n);
    let mut elements = m.joint_tangents(&state);
    elements.extend(m.contact_bound_tangents(&state));
    for e in elements {
        for (bi, si) in e.segments.iter().enumerate() {
            let Some(si) = si else { continue };
            for (bj, sj) in e.segments.iter().enumerate() {
                let Some(sj) = sj else { continue };
                for r in 0..6 {
                    for c in 0..6 {
                        k[(6 * si + r, 6 * sj + c)] += e.stiffness[(6 * bi + r, 6 * bj + c)];
                    }
                }
            }
        }
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

#[test]
fn frequency_bound_is_above_the_exact_highest_frequency_and_close_to_it() {
    for segments in [6, 12, 20] {
        let m = model(segments);
        let bound = highest_frequency(&m, &m.rest_state());
        let exact = exact_highest_frequency(&m);
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
