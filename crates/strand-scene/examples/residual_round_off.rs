//! The round-off a static residual carries, measured against the estimate the static solver's
//! convergence test makes of it (Findings, "A held strand that the static continuation does
//! not finish"). Solves the scene's equivalent statics with `LOAD_STEPS` first steps (default
//! 6); at the converged state (or the last one before a stall) moves every coordinate by its
//! own unit round-off with 40 random sign patterns and prints, per free coordinate, the
//! largest change of its force against `16 eps (|K| |q|)_i` (the positions counted with the
//! strand's extent), largest ratio last.
//!
//! ```text
//! cargo run --release -p strand-scene --example residual_round_off -- SCENE.json [LOAD_STEPS]
//! ```

use strand_ancf::band::BandMatrix;
use strand_ancf::statics::{StaticError, StaticOptions, solve_static};
use strand_scene::{BeamModelKind, Scene, build_beam};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: residual_round_off SCENE.json [LOAD_STEPS]");
    let scene = Scene::parse(&std::fs::read_to_string(path).unwrap()).unwrap();
    let beam = build_beam(&scene, BeamModelKind::Equivalent).unwrap();
    let load_steps = args.get(2).map_or(6, |s| s.parse().unwrap());
    let opts = StaticOptions {
        load_steps,
        ..Default::default()
    };
    let sol = match solve_static(&beam, &opts, &mut |_| {}) {
        Ok(s) => {
            println!("converged at the full load");
            s
        }
        Err(StaticError::Stalled {
            last: Some(l),
            reached,
            ..
        }) => {
            println!("stalled at load fraction {reached}");
            *l
        }
        Err(e) => panic!("{e}"),
    };
    let (n, nc, nd) = (beam.dofs(), beam.coords(), beam.node_coords());
    let b = beam.bandwidth();
    let mut k = BandMatrix::zeros(n, b, b);
    let mut trial = sol.slip.clone();
    let mut f0 = vec![0.0; nc];
    beam.internal(&sol.q, &sol.slip, &mut trial, &mut f0, Some(&mut k), None)
        .unwrap();
    let mut spread = vec![0.0f64; nc];
    let mut seed = 12345u64;
    let mut f = vec![0.0; nc];
    for _ in 0..40 {
        let mut q = sol.q.clone();
        for v in q.iter_mut() {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let sign = if seed >> 63 == 0 { 1.0 } else { -1.0 };
            *v += sign * f64::EPSILON * v.abs();
        }
        beam.internal(&q, &sol.slip, &mut trial, &mut f, None, None)
            .unwrap();
        for (s, (a, c)) in spread.iter_mut().zip(f.iter().zip(&f0)) {
            *s = s.max((a - c).abs());
        }
    }
    let half = nd / 2;
    let mut extent = vec![0.0f64; half];
    for node in sol.q.chunks_exact(nd) {
        for (e, x) in extent.iter_mut().zip(node) {
            *e = e.max(x.abs());
        }
    }
    let mut size = vec![0.0; n];
    for (g, x) in sol.q.iter().enumerate() {
        if let Some(i) = beam.free_index(g) {
            let c = g % nd;
            size[i] = if c < half {
                x.abs().max(extent[c])
            } else {
                x.abs()
            };
        }
    }
    let mut rows = Vec::new();
    for g in 0..nc {
        let Some(i) = beam.free_index(g) else {
            continue;
        };
        let kq: f64 = (0..n).map(|j| k.get(i, j).abs() * size[j]).sum();
        let estimate = 16.0 * f64::EPSILON * kq;
        rows.push((spread[g] / estimate, g, spread[g], estimate));
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    println!("node component measured(N) estimate(N) ratio");
    for (ratio, g, measured, estimate) in rows {
        println!(
            "{} {} {measured:.3e} {estimate:.3e} {ratio:.2}",
            g / nd,
            g % nd
        );
    }
}
