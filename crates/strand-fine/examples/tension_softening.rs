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
    let core = &model.wires[0];
    let cs = &state.wires[0].poses;
    let n = core.chain.len();
    let mut parts = [0.0; 4];
    let mut cuts = 0;
    for j in (n / 3)..(2 * n / 3) {
        let jt = &core.chain.joints[j];
        let c = cs[j].point(&jt.offset_a);
        let normal = (cs[j].tangent() + cs[j + 1].tangent()).normalize();
        let l = jt.evaluate(&cs[j], &cs[j + 1]);
        parts[0] += (l.torque_a + (cs[j].position - c).cross(&l.force_a)).z;
        for (w, ws) in model.wires.iter().zip(&state.wires).skip(1) {
            let (k, _) = w
                .chain
                .joints
                .iter()
                .enumerate()
                .map(|(k, jw)| (k, (ws.poses[k].point(&jw.offset_a) - c).dot(&normal).abs()))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            let jw = &w.chain.joints[k];
            let lw = jw.evaluate(&ws.poses[k], &ws.poses[k + 1]);
            let q = ws.poses[k].point(&jw.offset_a);
            let tangent = (ws.poses[k].tangent() + ws.poses[k + 1].tangent()).normalize();
            let axial = tangent * lw.force_a.dot(&tangent);
            parts[1] += (lw.torque_a + (ws.poses[k].position - q).cross(&lw.force_a)).z;
            parts[2] += (q - c).cross(&axial).z;
            parts[3] += (q - c).cross(&(lw.force_a - axial)).z;
        }
        cuts += 1;
    }
    let [core_m, own, axial, shear] = parts.map(|x| x / cuts as f64 / scale);
    println!(
        "moment over K_min kappa: core {core_m:.5}, wires' own {own:.5}, wires' axial forces x \
         arms {axial:.5}, shear x arms {shear:.5}; sum {:.5}",
        core_m + own + axial + shear
    );
}
