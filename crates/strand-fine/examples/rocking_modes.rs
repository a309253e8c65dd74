//! The softest modes of the 1+6+12 cantilever's tangent where its damped motion stalls
//! (`validation/vs-fine-1x19-cantilever.json`'s strand, `SEGMENTS` (12) a wire, `STEPS`
//! (60,000) explicit steps, `POINTS` contact points per segment on the core (unset: the
//! default, one on a strand of several layers)). The consistent tangent with the contact
//! histories frozen, symmetric part, scaled by the mass (`M^-1/2 K M^-1/2`, each segment's
//! mass on its translations and its inertia about its centre on its rotations): its lowest
//! `MODES` (12) circular frequencies, and for each the share of its kinetic energy in the
//! first layer's rotations across their axes (the segments rocking), in all of the first
//! layer's motion, and in the outer layer's; the same with every core contact stuck
//! (`FineModel::elastic_tangents`). Then Newton from the stall (the polish's
//! options with `extend_while_falling`, `ITER` (40) iterations a block): iterations and result.
//! `SAVE=FILE` writes the stalled state, `LOAD=FILE` reads it instead of running the motion.
//! `BEND=SPP`: instead, the same analysis of the 1+6+12 steel strand's virtual bending test
//! (100 N, mu = 0.3, 3 pitches, `SPP` segments per pitch) at its straight state, before the
//! first bending step. The candidate cause of stalls with one core contact per segment, a
//! first-layer segment rocking about it, would show as a soft mode with a large rocking share.
//! `cargo run --release -p strand-fine --example rocking_modes`.

mod common;
#[path = "../tests/common/mod.rs"]
mod fixtures;

use nalgebra::{DMatrix, Matrix3, SymmetricEigen};
use strand_core::{LayDirection, LayerSpec, Material, Strand, StrandSpec, WireSpec};
use strand_fine::{
    BendingTest, ContactOptions, SettleOptions, StaticOptions, settle, solve_static,
};

fn env(k: &str, d: f64) -> f64 {
    std::env::var(k).map_or(d, |v| v.parse().unwrap())
}

/// The 1+6+12 steel strand of `examples/steel-1x19-swing.json`, 1 m.
fn steel_1x19() -> Strand {
    let steel = Material {
        youngs_modulus: 2.0e11,
        poisson_ratio: 0.3,
        density: 7850.0,
    };
    let layer = |wires, deg: f64, direction| LayerSpec {
        wires,
        wire: WireSpec {
            diameter: 3.0e-3,
            material: steel,
        },
        lay_angle: deg.to_radians(),
        phase: 0.0,
        direction,
    };
    Strand::new(StrandSpec {
        length: 1.0,
        core: WireSpec {
            diameter: 3.3e-3,
            material: steel,
        },
        layers: vec![
            layer(6, 8.0, LayDirection::Right),
            layer(12, 12.0, LayDirection::Left),
        ],
        friction: 0.3,
    })
    .unwrap()
}

/// `BEND=SPP`: the bending test's straight state under 100 N, 3 pitches, `SPP` segments per
/// pitch, before its first bending step (0.0125 1/m).
fn bend(spp: usize, points: Option<usize>) {
    let mut test = BendingTest::frictionless(3, spp, 100.0, 0.0125);
    test.friction = 0.3;
    test.max_halvings = env("HALVINGS", 0.0) as usize;
    test.contact.points_per_segment = points;
    let mut straight = None;
    let r = test.run_observed(&steel_1x19(), &mut |p, m, st| {
        if p.imposed_curvature == 0.0 {
            straight = Some((m.clone(), st.clone()));
        }
    });
    println!(
        "bending test: {:?}",
        r.as_ref().map(|(c, _, _)| c.last().copied())
    );
    let (m, state) = straight.unwrap();
    analyse_both_tangents(&m, &state);
    println!("[{:.1} s CPU]", common::cpu_seconds());
}

/// The modes of the consistent tangent and of the tangent with every contact stuck.
fn analyse_both_tangents(m: &strand_fine::FineModel, state: &strand_fine::ModelState) {
    analyse(m, state, "consistent", m.element_tangents(state));
    analyse(
        m,
        state,
        "all stuck",
        m.elastic_tangents(state, |_, _| true),
    );
}

fn main() {
    if let Ok(spp) = std::env::var("BEND") {
        let points = std::env::var("POINTS").ok().and_then(|p| p.parse().ok());
        return bend(spp.parse().unwrap(), points);
    }
    let n = env("SEGMENTS", 12.0) as usize;
    let steps = env("STEPS", 60_000.0) as u64;
    let contact = ContactOptions {
        points_per_segment: std::env::var("POINTS").ok().and_then(|p| p.parse().ok()),
        ..Default::default()
    };
    let m = fixtures::cantilever_1x19_with(0.3, 2, n, &contact);
    let mut state = m.rest_state();
    if let Ok(p) = std::env::var("LOAD") {
        common::load_state(&mut state, &p);
    } else {
        let opts = SettleOptions {
            max_steps: Some(steps),
            ..SettleOptions::default()
        };
        let r = settle(&m, &mut state, &opts, &mut |_, _, _| {});
        println!("settle: {r:?}");
        if let Ok(p) = std::env::var("SAVE") {
            common::save_state(&state, &p);
        }
    }
    analyse_both_tangents(&m, &state);
    let polish = StaticOptions {
        load_steps: 1,
        min_increment: 1.0,
        potential_descent: false,
        max_iterations: env("ITER", 40.0) as usize,
        extend_while_falling: true,
        ..StaticOptions::default()
    };
    let mut st = state.clone();
    let r = solve_static(&m, &mut st, &polish);
    println!("Newton from the stall: {r:?}");
    println!("[{:.1} s CPU]", common::cpu_seconds());
}

/// Prints the softest modes of `tangents` (see the module docs).
fn analyse(
    model: &strand_fine::FineModel,
    state: &strand_fine::ModelState,
    label: &str,
    tangents: Vec<strand_fine::tangent::ElementTangent>,
) {
    let offsets = model.segment_offsets();
    let dim = 6 * model.segment_count();
    let mut k = DMatrix::<f64>::zeros(dim, dim);
    for e in tangents {
        e.add_to_dense(&mut k);
    }
    let ks = 0.5 * (&k + k.transpose());
    // M^-1/2 block by block: 1/sqrt(m) on translations, R I^-1/2 R^T on rotations.
    let mut b = DMatrix::<f64>::zeros(dim, dim);
    for (wi, w) in model.wires.iter().enumerate() {
        for (si, seg) in w.chain.segments.iter().enumerate() {
            let g = 6 * (offsets[wi] + si);
            for r in 0..3 {
                b[(g + r, g + r)] = 1.0 / seg.mass.sqrt();
            }
            let rot = state.wires[wi].poses[si].rotation.to_rotation_matrix();
            let d = Matrix3::from_diagonal(&nalgebra::Vector3::new(
                1.0 / seg.axial_inertia.sqrt(),
                1.0 / seg.transverse_inertia.sqrt(),
                1.0 / seg.transverse_inertia.sqrt(),
            ));
            let blk = rot.matrix() * d * rot.matrix().transpose();
            for r in 0..3 {
                for c in 0..3 {
                    b[(g + 3 + r, g + 3 + c)] = blk[(r, c)];
                }
            }
        }
    }
    let a = &b * ks * &b;
    let eig = SymmetricEigen::new(a);
    let mut order: Vec<usize> = (0..dim).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let layer_of = |wi: usize| match wi {
        0 => 0,
        1..=6 => 1,
        _ => 2,
    };
    println!(
        "{} segments, {} dof, {} core contact points; tangent {}",
        model.segment_count(),
        dim,
        model.wires.iter().map(|w| w.contacts.len()).sum::<usize>(),
        label
    );
    println!("mode  omega (rad/s)  rocking(L1)  L1 all  L2 all  core");
    let negative = order.iter().filter(|&&i| eig.eigenvalues[i] < 0.0).count();
    let mut most = (0.0, 0.0);
    for (rank, &i) in order.iter().enumerate() {
        let lam = eig.eigenvalues[i];
        let v = eig.eigenvectors.column(i);
        // v is in mass-scaled coordinates: |v|^2 splits the mode's kinetic energy.
        let (mut rock, mut l1, mut l2, mut core) = (0.0, 0.0, 0.0, 0.0);
        for (wi, w) in model.wires.iter().enumerate() {
            for si in 0..w.chain.len() {
                let g = 6 * (offsets[wi] + si);
                let e: f64 = (0..6).map(|r| v[g + r] * v[g + r]).sum();
                match layer_of(wi) {
                    0 => core += e,
                    1 => {
                        l1 += e;
                        // rotation across the segment's axis, in body axes 2 and 3
                        let rot = state.wires[wi].poses[si].rotation;
                        let wv = nalgebra::Vector3::new(v[g + 3], v[g + 4], v[g + 5]);
                        let body = rot.inverse() * wv;
                        rock += body.y * body.y + body.z * body.z;
                    }
                    _ => l2 += e,
                }
            }
        }
        let omega = lam.signum() * lam.abs().sqrt();
        if rock > most.0 {
            most = (rock, omega);
        }
        if rank >= env("MODES", 12.0) as usize {
            continue;
        }
        println!(
            "{:4}  {:12.4e}  {:10.3}  {:6.3}  {:6.3}  {:5.3}",
            i, omega, rock, l1, l2, core
        );
    }
    println!(
        "{negative} negative eigenvalues; the mode most of the first layer's rocking: share {:.3} at omega {:.4e} rad/s",
        most.0, most.1
    );
}
