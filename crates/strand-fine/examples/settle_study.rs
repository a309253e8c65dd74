//! The Fig. 7 fine statics (Table 1 strand, 0.4 m, clamped, gravity G m/s^2 along -y, 77
//! segments a wire) settled along a chosen path, for the path-dependence figures of
//! `strand_fine::settle`:
//! `cargo run --release -p strand-fine --example settle_study -- G SAFETY INERTIA [SEGMENTS] [x]`.
//! SAFETY: fraction of the stable step; INERTIA > 0: every segment's axial inertia times it
//! (1: the strand's own inertia, the settle's isotropic inertia off); INERTIA < 0: both
//! rotational inertias the transverse one times |INERTIA| (-1: the settle's default motion).
//! A sixth argument prints the stable step for isotropic inertias 1, 2, 4 and 16 times the
//! transverse one. Prints the steps, the Newton polish and the tip.

mod common;

use strand_fine::{FineModel, SettledOptions, settle_time_step, solve_settled};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().unwrap());
    let (g, safety, axial) = (arg(1, 8.0), arg(2, 0.75), arg(3, 1.0));
    let n = arg(4, 77.0) as usize;
    let mut m = common::fig7_model(g, n);
    let rest = m.rest_state();
    // AXIAL > 0: the axial inertia times AXIAL; AXIAL < 0: both rotational inertias the
    // transverse one times |AXIAL| (the settle's own isotropic inertia off).
    let scale = |m: &mut FineModel, f: f64| {
        for seg in m.wires.iter_mut().flat_map(|w| w.chain.segments.iter_mut()) {
            if f > 0.0 {
                seg.axial_inertia *= f;
            } else {
                seg.transverse_inertia *= -f;
                seg.axial_inertia = seg.transverse_inertia;
            }
        }
    };
    if args.len() > 5 {
        for f in [-1.0, -2.0, -4.0, -16.0] {
            let mut s = m.clone();
            scale(&mut s, f);
            println!(
                "rotational inertia {f}: step {:.4e} s at safety 1",
                settle_time_step(&s, &rest, 1.0)
            );
        }
    }
    scale(&mut m, axial);
    let mut opts = SettledOptions::default();
    opts.settle.isotropic_inertia = false;
    opts.settle.safety = safety;
    let mut state = m.rest_state();
    let t0 = std::time::Instant::now();
    let r = solve_settled(&m, &mut state, &opts, &mut |_, _, _| {}).unwrap();
    let tip = *m.core_centreline(&state).last().unwrap();
    println!(
        "g {g} safety {safety} axial x{axial}: {}, tip ({:.10}, {:.10}) [{:.1} s wall]",
        common::settled_line(&r),
        tip.x,
        tip.y,
        t0.elapsed().as_secs_f64()
    );
}
