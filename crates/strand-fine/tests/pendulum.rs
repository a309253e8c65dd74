//! Dynamics: a pinned wire released horizontally under gravity (frictionless, undamped)
//! conserves energy; the parallel sweep over wires gives identical numbers for any thread
//! count; throughput in segment-steps per second.

use std::time::Instant;

use nalgebra::Vector3;
use strand_core::{Material, Strand, StrandSpec, WireSpec};
use strand_fine::{
    Discretisation, FineModel, Integrator, ModelState, Support, WireSection, stable_time_step,
};

const STEEL_TABLE1: Material = Material {
    youngs_modulus: 2.0e8,
    poisson_ratio: 0.3,
    density: 7801.0,
};

fn table1() -> Strand {
    Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap()
}

#[test]
fn pinned_pendulum_conserves_energy() {
    let section = WireSection::from_spec(&WireSpec {
        diameter: 3.0e-3,
        material: STEEL_TABLE1,
    });
    let mut m = FineModel::single_wire(section, 0.4, 40, Support::Pinned, Support::Free);
    m.gravity = Vector3::new(0.0, -9.8065, 0.0);
    let mut state = m.rest_state();
    let dt = stable_time_step(&m, &state, 0.9);
    let mut int = Integrator::new(&m, &state, dt);
    let e0 = int.energies(&m, &state);
    let steps = (0.5 / dt).ceil() as usize;
    let mut max_err: f64 = 0.0;
    let mut min_gravity = e0.gravity;
    let t = Instant::now();
    for _ in 0..steps {
        int.step(&m, &mut state);
        let e = int.energies(&m, &state);
        max_err = max_err.max((e.total() - e0.total()).abs());
        min_gravity = min_gravity.min(e.gravity);
    }
    let wall = t.elapsed().as_secs_f64();
    let drop = e0.gravity - min_gravity;
    let tip = m.core_centreline(&state)[40];
    println!(
        "pendulum: dt = {dt:.3e} s, {steps} steps, potential drop {drop:.4e} J, max |E - E0| \
         {max_err:.3e} J = {:.2e} of the drop; tip at 0.5 s ({:.4}, {:.4}) m; \
         {:.2e} segment-steps/s (with energy evaluation)",
        max_err / drop,
        tip.x,
        tip.y,
        (steps * 40) as f64 / wall
    );
    assert!(drop > 0.01, "the pendulum must swing down");
    assert!(max_err < 1e-3 * drop);
}

fn run_strand(threads: usize, steps: usize) -> (ModelState, f64, f64) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut m = FineModel::from_strand(
            &table1(),
            Discretisation {
                core_segments: 77,
                wire_segments: 77,
            },
            Support::Clamped,
            Support::Free,
        );
        m.gravity = Vector3::new(0.0, -9.8065, 0.0);
        let mut state = m.rest_state();
        let dt = stable_time_step(&m, &state, 0.9);
        let mut int = Integrator::new(&m, &state, dt);
        let t = Instant::now();
        for _ in 0..steps {
            int.step(&m, &mut state);
        }
        let wall = t.elapsed().as_secs_f64();
        (state, dt, (steps * m.segment_count()) as f64 / wall)
    })
}

#[test]
fn same_numbers_with_one_or_two_threads() {
    let (a, dt, rate1) = run_strand(1, 2000);
    let (b, _, rate2) = run_strand(2, 2000);
    println!(
        "strand 7 x 77 segments, dt = {dt:.3e} s: {rate1:.3e} segment-steps/s on 1 thread, \
         {rate2:.3e} on 2"
    );
    assert_eq!(a, b);
}
