//! Cost of the strand beam on the paper's section-3 strand (L = 1 m, E = 2e9 Pa, 30 elements,
//! `continuous` law, hanging shape): one element's forces and tangent, the full residual and
//! tangent assembly, the parts of a Newton iteration (with the exact tangent and with the
//! material iteration matrix of the stick/slip laws), steps of each integrator on the pinned
//! pendulum, and the static solves of the paper's scenes by continuation.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use strand_ancf::band::{BandMatrix, BandSolver};
use strand_ancf::beam::{Beam, BeamSpec, ElementKind, PointState, Support, Tangent};
use strand_ancf::dynamics::{DynamicOptions, Scheme, run_dynamic, stable_step};
use strand_ancf::statics::{StaticOptions, solve_static};
use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

fn section3(length: f64) -> Strand {
    Strand::new(StrandSpec::paper(length, 2.0e9, 5747.0)).unwrap()
}

/// A beam of `elements` elements of the 30-element mesh's length (1/30 m).
fn beam(elements: usize, kind: LawKind, support: Support, element: ElementKind) -> Beam {
    let s = section3(elements as f64 / 30.0);
    Beam::new(
        BeamSpec {
            elements,
            bending_points: None,
            mass_per_length: s.mass_per_length(),
            element,
            direction: [1.0, 0.0, 0.0],
            gravity: [0.0, -12.0, 0.0],
            start: Some(support),
            end: None,
            ..Default::default()
        },
        SectionLaw::new(&s, kind),
    )
    .unwrap()
}

fn assembly(c: &mut Criterion) {
    for element in [ElementKind::Planar, ElementKind::Spatial] {
        for n in [1usize, 30] {
            let b = beam(n, LawKind::Continuous, Support::Clamped, element);
            // A hanging state from the static solution of the 30-element beam.
            let q = if n == 30 {
                solve_static(&b, &StaticOptions::default(), &mut |_| {})
                    .unwrap()
                    .q
            } else {
                b.reference()
                    .iter()
                    .enumerate()
                    .map(|(i, v)| v + 1e-3 * (i as f64).sin())
                    .collect()
            };
            let mut force = vec![0.0; b.coords()];
            let mut k = BandMatrix::zeros(b.dofs(), b.bandwidth(), b.bandwidth());
            let state = b.initial_state();
            let mut trial = state.clone();
            let name = format!("{element:?} {n} element(s)");
            c.bench_function(&format!("{name}: forces"), |bch| {
                bch.iter(|| {
                    b.internal(black_box(&q), &state, &mut trial, &mut force, None, None)
                        .unwrap()
                })
            });
            c.bench_function(&format!("{name}: forces and tangent"), |bch| {
                bch.iter(|| {
                    b.internal(
                        black_box(&q),
                        &state,
                        &mut trial,
                        &mut force,
                        Some(&mut k),
                        None,
                    )
                    .unwrap()
                })
            });
        }
    }
}

fn integrators(c: &mut Criterion) {
    let b = beam(
        30,
        LawKind::Continuous,
        Support::Pinned,
        ElementKind::Planar,
    );
    let hs = stable_step(&b).unwrap();
    let mut g = c.benchmark_group("section-3 pendulum, 30 elements, continuous law");
    g.sample_size(10);
    g.bench_function("Verlet: 1000 steps at 0.9 of the stable step", |bch| {
        let o = DynamicOptions::new(1000.0 * 0.9 * hs, Scheme::Verlet { step: None }, 1.0);
        bch.iter(|| run_dynamic(&b, &o, &mut |_| {}).unwrap())
    });
    g.bench_function("generalized-alpha: 50 steps of 1 ms from rest", |bch| {
        let scheme = Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 1.0,
        };
        let o = DynamicOptions::new(0.05, scheme, 1.0);
        bch.iter(|| run_dynamic(&b, &o, &mut |_| {}).unwrap())
    });
    g.finish();
}

/// The section-3 pendulum of `validation/paper-fig14-pendulum.json`: 30 planar elements, 1 m,
/// pinned, gravity 9.8 m/s^2.
fn pendulum(kind: LawKind) -> Beam {
    let s = section3(1.0);
    Beam::new(
        BeamSpec {
            elements: 30,
            bending_points: None,
            mass_per_length: s.mass_per_length(),
            element: ElementKind::Planar,
            direction: [1.0, 0.0, 0.0],
            gravity: [0.0, -9.8, 0.0],
            start: Some(Support::Pinned),
            end: None,
            ..Default::default()
        },
        SectionLaw::new(&s, kind),
    )
    .unwrap()
}

/// The paper's section-3 pendulum exactly as `validation/paper-fig14-pendulum.json` sets it
/// up (gravity 9.8 m/s^2, 1 s), solved by generalized-alpha at 1 ms steps (spectral radius
/// 0.9, the scenes' default); only the solve is timed. See also `examples/pendulum_speed.rs`,
/// which reports steps, iterations and the tip error against a converged run.
fn paper_pendulum(c: &mut Criterion) {
    let mut g = c.benchmark_group("paper-fig14 pendulum, 1 s, generalized-alpha 1 ms");
    g.sample_size(10);
    for kind in [LawKind::Constant, LawKind::Continuous, LawKind::Hysteretic] {
        let b = pendulum(kind);
        let scheme = Scheme::GeneralizedAlpha {
            step: 1e-3,
            spectral_radius: 0.9,
        };
        let o = DynamicOptions::new(1.0, scheme, 0.01);
        g.bench_function(kind.name(), |bch| {
            bch.iter(|| run_dynamic(&b, &o, &mut |_| {}).unwrap())
        });
    }
    g.finish();
}

/// The parts of one Newton iteration of generalized-alpha on the paper's section-3 pendulum
/// (30 planar elements, pinned), bent into an arc of curvature 3/m with a small stretch so that
/// wires slip: the forces alone (every iteration), the forces and tangent, the iteration
/// matrix `K + beta' M` and its factorization (iterations that refresh it), the product with
/// the mass matrix and the solve (every iteration).
fn newton_iteration(c: &mut Criterion) {
    for kind in [LawKind::Constant, LawKind::Continuous, LawKind::Hysteretic] {
        let b = pendulum(kind);
        let (k0, stretch) = (3.0, 1.0 + 2e-4);
        let mut q = b.reference().to_vec();
        let l = b.element_length();
        for j in 0..=30 {
            let x = j as f64 * l;
            let (sn, cs) = (k0 * x).sin_cos();
            q[4 * j..4 * j + 4].copy_from_slice(&[
                stretch * sn / k0,
                stretch * (cs - 1.0) / k0,
                stretch * cs,
                -stretch * sn,
            ]);
        }
        let slip = b.initial_state();
        let mut trial = slip.clone();
        let mut force = vec![0.0; b.coords()];
        let n = b.dofs();
        let mut k = BandMatrix::zeros(n, b.bandwidth(), b.bandwidth());
        let mut g = c.benchmark_group(format!("Newton iteration, pendulum, {}", kind.name()));
        g.bench_function("forces", |bch| {
            bch.iter(|| {
                b.internal(black_box(&q), &slip, &mut trial, &mut force, None, None)
                    .unwrap()
            })
        });
        g.bench_function("forces and tangent", |bch| {
            bch.iter(|| {
                b.internal(
                    black_box(&q),
                    &slip,
                    &mut trial,
                    &mut force,
                    Some(&mut k),
                    None,
                )
                .unwrap()
            })
        });
        // The iteration matrix of the stick/slip laws: the material part, built in the force
        // pass (slipping wires at a tenth of their stick stiffness, as the hysteretic law's
        // default), symmetric.
        let mut km = k.clone();
        let iteration = Tangent::Iteration { unloading: 0.1 };
        g.bench_function("forces and iteration matrix", |bch| {
            bch.iter(|| {
                b.internal_with(
                    black_box(&q),
                    &slip,
                    &mut trial,
                    &mut force,
                    Some((&mut km, iteration)),
                    None,
                )
                .unwrap()
            })
        });
        // The stick/slip laws' Newton iterations: the forces without the bending points'
        // books, and the books of the accepted iterate (once a step).
        let mut pts = vec![PointState::default(); b.points()];
        g.bench_function("forces without books", |bch| {
            bch.iter(|| {
                b.internal_unbooked(black_box(&q), &slip, &mut [], &mut force, None, &mut pts)
                    .unwrap()
            })
        });
        g.bench_function("books of the accepted iterate", |bch| {
            bch.iter(|| {
                let mut ev = Default::default();
                b.book_points(&slip, &mut trial, black_box(&mut pts), &mut ev);
                ev
            })
        });
        let mut solver = BandSolver::default();
        let beta_p = 1.0 / (0.25 * 1e-6);
        let mut sm = km.clone();
        g.bench_function("iteration matrix factorization (LDL^T)", |bch| {
            bch.iter(|| {
                sm.fill_zero();
                sm.add_scaled(1.0, &km);
                sm.add_scaled(beta_p, b.mass());
                assert!(solver.factorize(black_box(&sm)));
                assert!(solver.is_symmetric());
            })
        });
        let qf: Vec<f64> = q[b.free_span().unwrap()].iter().map(|v| v.abs()).collect();
        let mut kq = vec![0.0; b.dofs()];
        g.bench_function("round-off of the residual, |K| |q|", |bch| {
            bch.iter(|| km.abs_mul_vec(black_box(&qf), &mut kq))
        });
        let mut s = k.clone();
        g.bench_function("iteration matrix and factorization", |bch| {
            bch.iter(|| {
                s.fill_zero();
                s.add_scaled(1.0, &k);
                s.add_scaled(beta_p, b.mass());
                assert!(solver.factorize(black_box(&s)));
            })
        });
        let x: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut y = vec![0.0; n];
        g.bench_function("mass times vector", |bch| {
            bch.iter(|| b.vector_mass().mul_vec(black_box(&x), &mut y))
        });
        g.bench_function("solve", |bch| {
            bch.iter(|| {
                y.copy_from_slice(&x);
                solver.solve(black_box(&mut y));
            })
        });
        g.finish();
    }
}

/// The static solves of the paper's scenes by continuation (`statics.rs`): the section-3
/// strand under g = 12 (30 elements, Figs. 9-12) and the Table 1 strand under g = 8 (8
/// elements, Fig. 7), equivalent (`continuous`) and traditional (`constant`) beams.
fn static_scenes(c: &mut Criterion) {
    let mut g = c.benchmark_group("static scenes by continuation");
    g.sample_size(10);
    for (name, strand, elements, gravity) in [
        ("section-3 g = 12", section3(1.0), 30, 12.0),
        (
            "Table 1 g = 8",
            Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap(),
            8,
            8.0,
        ),
    ] {
        for kind in [LawKind::Continuous, LawKind::Constant] {
            let b = Beam::new(
                BeamSpec {
                    elements,
                    bending_points: None,
                    mass_per_length: strand.mass_per_length(),
                    element: ElementKind::Planar,
                    direction: [1.0, 0.0, 0.0],
                    gravity: [0.0, -gravity, 0.0],
                    start: Some(Support::Clamped),
                    end: None,
                    ..Default::default()
                },
                SectionLaw::new(&strand, kind),
            )
            .unwrap();
            g.bench_function(format!("{name}, {} law", kind.name()), |bch| {
                bch.iter(|| solve_static(&b, &StaticOptions::default(), &mut |_| {}).unwrap())
            });
        }
    }
    g.finish();
}

criterion_group!(
    benches,
    assembly,
    integrators,
    paper_pendulum,
    newton_iteration,
    static_scenes
);
criterion_main!(benches);
