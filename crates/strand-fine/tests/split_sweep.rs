//! The steps split between two threads (`Integrator::advance` with more than one thread in
//! rayon's pool and `split_sweeps` on: the calling thread and one partner, each sweep split by cost, contacts of
//! one wire lent to the other thread) give the same numbers, bit for bit, as the steps in
//! one thread: states, committed histories, friction loss, loads and energies. On a
//! one-layer strand with ties (a pinned end binds the wires to the core) and on a 1+6+12
//! strand with wire-to-wire links, damped, under a ramped load.

use nalgebra::Vector3;
use strand_core::{LayDirection, LayerSpec, Material, Strand, StrandSpec, WireSpec};
use strand_fine::{
    ContactOptions, ContactState, Discretisation, FineModel, Integrator, ModelState, Support,
    WireLoads, stable_time_step,
};

fn table1(segments: usize) -> FineModel {
    let s = Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap();
    let mut m = FineModel::from_strand(
        &s,
        Discretisation {
            core_segments: segments,
            wire_segments: segments,
        },
        Support::Clamped,
        Support::Pinned,
    );
    m.add_contacts(&s, &ContactOptions::default());
    m
}

fn strand_1x19(segments: usize) -> FineModel {
    let steel = Material {
        youngs_modulus: 2.0e11,
        poisson_ratio: 0.3,
        density: 7850.0,
    };
    let wire = |diameter| WireSpec {
        diameter,
        material: steel,
    };
    let layer = |wires, deg: f64, direction| LayerSpec {
        wires,
        wire: wire(3.0e-3),
        lay_angle: deg.to_radians(),
        phase: 0.0,
        direction,
    };
    let s = Strand::new(StrandSpec {
        length: 0.1,
        core: wire(3.3e-3),
        layers: vec![
            layer(6, 8.0, LayDirection::Right),
            layer(12, 12.0, LayDirection::Left),
        ],
        friction: 0.3,
    })
    .unwrap();
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

/// `stretches` calls of `advance` of `steps` steps each on `threads` threads, damped, the
/// gravity `g` (m/s^2, along -y) ramped in over 300 steps.
fn run(
    m: &FineModel,
    threads: usize,
    stretches: usize,
    steps: u64,
) -> (ModelState, Vec<WireLoads>, f64) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut s = m.rest_state();
        let dt = stable_time_step(m, &s, 0.9);
        let ramp = move |t: f64| (t / (300.0 * dt)).min(1.0);
        let mut int = Integrator::new(m, &s, dt);
        int.split_sweeps = true;
        int.damping_rate = 30.0;
        int.load_factor = 0.0;
        int.reload(m, &s);
        for _ in 0..stretches {
            int.advance(m, &mut s, steps, &ramp);
        }
        let e = int.energies(m, &s).total();
        (s, int.loads().to_vec(), e)
    })
}

fn closed(loads: &[WireLoads]) -> usize {
    loads
        .iter()
        .flat_map(|l| &l.contacts)
        .filter(|c| c.state != ContactState::Open)
        .count()
}

fn same_on_one_and_two_threads(mut m: FineModel, stretches: usize, steps: u64) {
    m.gravity = Vector3::new(0.0, -8.0, 0.0);
    let (one, loads_one, e_one) = run(&m, 1, stretches, steps);
    let (two, loads_two, e_two) = run(&m, 2, stretches, steps);
    assert!(
        closed(&loads_one) > 10,
        "{} contacts closed",
        closed(&loads_one)
    );
    assert!(one.friction_work > 0.0, "no slip: friction not exercised");
    assert!(one == two, "the states on 1 and 2 threads differ");
    assert!(
        loads_one == loads_two,
        "the loads on 1 and 2 threads differ"
    );
    assert_eq!(e_one.to_bits(), e_two.to_bits());
}

#[test]
fn split_steps_of_a_one_layer_strand_with_ties_match_one_thread() {
    let m = table1(12);
    assert!(!m.ties.is_empty());
    same_on_one_and_two_threads(m, 4, 100);
}

#[test]
fn split_steps_of_a_1x19_strand_with_links_match_one_thread() {
    let m = strand_1x19(8);
    assert!(m.link_count() > 0);
    same_on_one_and_two_threads(m, 3, 50);
}
