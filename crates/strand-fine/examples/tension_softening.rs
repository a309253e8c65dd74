//! The frictionless fine strand under tension against the thin-rod energy of the stretched
//! helix (`strand_core::stretched_bending`), and where the moment goes: the
//! `validation/vs-fine-30deg.json` strand (core 2.2 mm, six 1.5 mm wires at 30 deg,
//! E = 5e7 Pa, nu = 0.3), frictionless virtual bending test at tension T (N), curvature K
//! (1/m), PITCHES pitches of SPP segments; the internal moment at the core's joints in the
//! middle third split into the core's joint moment, the wires' own joint moments, their
//! axial forces times their arms and their shear forces times their arms (loads the part
//! after the cut exerts on the part before, about the core's joint point; each wire cut at
//! its joint nearest the cut plane).
//!
//! `cargo run --release -p strand-fine --example tension_softening -- T K SPP PITCHES [cell]`
//!
//! With `cell` the test is set up as the thin-rod cell: lateral pressure on the core only,
//! shear springs 100 times stiffer, penetration 1e-5 of the wire diameter (else the default
//! test: pressure shared by axial stiffness, physical springs, penetration 1e-3).

#[path = "../tests/common/mod.rs"]
mod fixtures;

use strand_core::{BaseStiffness, stretched_min_bending_stiffness};
use strand_fine::BendingTest;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().unwrap());
    let (t, kappa) = (arg(1, 1.0), arg(2, 0.5));
    let (spp, pitches) = (arg(3, 24.0) as usize, arg(4, 6.0) as usize);
    let cell = args.get(5).is_some_and(|a| a == "cell");
    let strand = fixtures::vs_fine_30deg();
    let k_min = strand.min_bending_stiffness(BaseStiffness::Costello);
    let eps = t / strand.axial_stiffness();
    let test = if cell {
        fixtures::thin_rod_cell(pitches, spp, t, kappa, 1e-5)
    } else {
        BendingTest::frictionless(pitches, spp, t, kappa)
    };
    let (curve, model, state) = test.run_with_state(&strand).unwrap();
    let p = curve.last().unwrap();
    let scale = k_min * p.curvature;
    println!(
        "T {t} N (strain {eps:.4e}), {pitches} pitches of {spp}{}: M / kappa {:.5} K_min, \
         thin-rod {:.5} K_min",
        if cell { ", cell" } else { "" },
        p.secant_stiffness() / k_min,
        stretched_min_bending_stiffness(&strand, eps) / k_min
    );
    // The cut moment over the middle third of the core's joints, split into the core's part
    // and the wires' own moments, axial forces x arms and shear forces x arms.
    let core = &model.wires[0];
    let n = core.chain.len();
    let rest_x = |j: usize| core.chain.rest[j].point(&core.chain.joints[j].offset_a).x;
    let layers = model.wires.iter().map(|w| w.layer).max().unwrap_or(0);
    let split = BendingTest::layer_moment_parts(
        &model,
        &state,
        layers,
        (rest_x(n / 3), rest_x(2 * n / 3 - 1)),
    );
    let mut parts = [split[0][0], 0.0, 0.0, 0.0];
    for layer in &split[1..] {
        for (p, v) in parts[1..].iter_mut().zip(layer) {
            *p += v;
        }
    }
    let [core_m, own, axial, shear] = parts.map(|x| x / scale);
    println!(
        "moment over K_min kappa: core {core_m:.5}, wires' own {own:.5}, wires' axial forces x \
         arms {axial:.5}, shear x arms {shear:.5}; sum {:.5}",
        core_m + own + axial + shear
    );
}
