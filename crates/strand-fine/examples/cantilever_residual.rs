//! Where the residual of a stalled multi-layer settle sits: the 1+6+12 cantilever of
//! `validation/vs-fine-1x19-cantilever.json` (0.08 m, core 2.2 mm, 6 + 12 wires of
//! 1.5 mm at 20 deg right / left, E 5e7 Pa, clamped at its start, g = 10 m/s^2 across),
//! `SEGMENTS` (12) a wire, damped motion for `STEPS` (150,000) explicit steps; `FRICTION`
//! (0.3) sets mu, `LAYERS` (2) keeps the first layers only. Prints, every `EVERY` (10,000) steps, the residual's ratio to the settle's
//! allowance, the worst segment (wire, layer, segment, force or torque) and how many contacts
//! changed state (open / stick / slip) since the last print; at the end the worst segments
//! with the contacts acting on them, and Newton from the stalled state with 0 and
//! `STAGES` (2) penalty stages, `ITER` (40) iterations (`EXTEND=1`: more blocks of `ITER`
//! while each halves the residual, `StaticOptions::extend_while_falling`):
//! `cargo run --release -p strand-fine --example cantilever_residual`.
//! `SAVE=PATH` writes the state where the motion stopped to `PATH-end.state` (and at the
//! step counts in `SAVE_AT`, comma-separated, to `PATH-N.state`); `LOAD=FILE` starts Newton
//! from a saved state instead of running the motion (a 48-segment motion is minutes of CPU,
//! Newton from it seconds). `CENTRELINE=DIR` writes the core's centreline after Newton
//! without penalty stages to `DIR/centerline.csv` (s, x, y, z at the joints, as `strand run`).

mod common;
#[path = "../tests/common/mod.rs"]
mod fixtures;

use nalgebra::Vector3;
use strand_fine::{
    ContactState, FineModel, ModelState, SettleOptions, StaticOptions, WireLoads, settle,
    solve_static,
};

fn env(k: &str, d: f64) -> f64 {
    std::env::var(k).map_or(d, |v| v.parse().unwrap())
}

fn layer_of(w: usize) -> usize {
    match w {
        0 => 0,
        1..=6 => 1,
        _ => 2,
    }
}

/// Per segment: (ratio of |F| to F_ref, ratio of |T| to F_ref l) with F_ref the largest
/// segment weight and l the segment's length.
fn worst(m: &FineModel, loads: &[WireLoads], f_ref: f64) -> Vec<(f64, usize, usize, bool)> {
    let mut out = Vec::new();
    for (wi, (w, l)) in m.wires.iter().zip(loads).enumerate() {
        for (si, (f, t)) in l.forces.iter().zip(&l.torques).enumerate() {
            let len = w.chain.segments[si].length;
            let (rf, rt) = (f.norm() / f_ref, t.norm() / (f_ref * len));
            out.push((rf.max(rt), wi, si, rt > rf));
        }
    }
    out.sort_by(|a, b| b.0.total_cmp(&a.0));
    out
}

fn states(loads: &[WireLoads]) -> Vec<ContactState> {
    loads
        .iter()
        .flat_map(|l| l.contacts.iter().map(|c| c.state))
        .collect()
}

fn counts(s: &[ContactState]) -> (usize, usize, usize) {
    let n = |x| s.iter().filter(|&&c| c == x).count();
    (
        n(ContactState::Open),
        n(ContactState::Stick),
        n(ContactState::Slip),
    )
}

fn main() {
    let n = env("SEGMENTS", 12.0) as usize;
    let steps = env("STEPS", 150_000.0) as u64;
    let every = env("EVERY", 10_000.0) as u64;
    let m = fixtures::cantilever_1x19(env("FRICTION", 0.3), env("LAYERS", 2.0) as usize, n);
    let f_ref = m
        .wires
        .iter()
        .flat_map(|w| w.chain.segments.iter())
        .map(|seg| seg.mass * 10.0)
        .fold(0.0, f64::max);
    println!(
        "{} segments, {} core contacts + links, {} links; F_ref {f_ref:.3e} N",
        m.segment_count(),
        m.contact_count(),
        m.link_count()
    );
    let mut loads = m.load_buffers();
    let mut prev: Option<Vec<ContactState>> = None;
    let mut prev_tip = Vector3::zeros();
    let mut last_step = 0u64;
    let opts = SettleOptions {
        max_steps: Some(steps),
        ..SettleOptions::default()
    };
    let mut state = m.rest_state();
    let save = std::env::var("SAVE").ok();
    let save_at: Vec<u64> = std::env::var("SAVE_AT").map_or(Vec::new(), |v| {
        v.split(',').map(|x| x.parse().unwrap()).collect()
    });
    let load = std::env::var("LOAD").ok();
    let mut check = 0u64;
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    let mut motion = |st: &ModelState, t, ratio| {
        check += 100;
        if let Some(p) = &save
            && save_at.contains(&check)
        {
            common::save_state(st, &format!("{p}-{check}.state"));
        }
        lo = lo.min(ratio);
        hi = hi.max(ratio);
        if check < last_step + every {
            return;
        }
        last_step = check;
        m.compute_loads(st, 1.0, &mut loads);
        let w = worst(&m, &loads, f_ref);
        let now = states(&loads);
        let changed = prev
            .as_ref()
            .map_or(0, |p| p.iter().zip(&now).filter(|(a, b)| a != b).count());
        let opened = prev.as_ref().map_or(0, |p| {
            p.iter()
                .zip(&now)
                .filter(|(a, b)| (**a == ContactState::Open) != (**b == ContactState::Open))
                .count()
        });
        let speed = st
            .wires
            .iter()
            .flat_map(|w| w.velocities.iter())
            .map(|v| v.norm())
            .fold(0.0, f64::max);
        let (o, k, sl) = counts(&now);
        let tip = *m.core_centreline(st).last().unwrap();
        println!(
            "t {t:.3} s ratio {ratio:.3e}: worst {:.2} F_ref (wire {} layer {} seg {} {}); \
             open/stick/slip {o}/{k}/{sl}, {changed} changed ({opened} opened or closed); \
             tip moved {:.2e} m; ratio over the last {every} steps {lo:.2e}..{hi:.2e}, \
             largest speed {speed:.2e} m/s",
            w[0].0,
            w[0].1,
            layer_of(w[0].1),
            w[0].2,
            if w[0].3 { "torque" } else { "force" },
            (tip - prev_tip).norm()
        );
        prev = Some(now);
        prev_tip = tip;
        (lo, hi) = (f64::INFINITY, 0.0);
    };
    if let Some(p) = &load {
        common::load_state(&mut state, p);
        println!("state from {p}");
    } else {
        let r = settle(&m, &mut state, &opts, &mut motion);
        println!("settle: {r:?}");
        if let Some(p) = &save {
            common::save_state(&state, &format!("{p}-end.state"));
        }
    }
    m.compute_loads(&state, 1.0, &mut loads);
    let w = worst(&m, &loads, f_ref);
    let mut per_layer = [0.0f64; 3];
    for &(r, wi, _, _) in &w {
        per_layer[layer_of(wi)] = per_layer[layer_of(wi)].max(r);
    }
    println!(
        "largest residual by layer (core, inner, outer) in F_ref: {:.3e} {:.3e} {:.3e}",
        per_layer[0], per_layer[1], per_layer[2]
    );
    for &(r, wi, si, torque) in w.iter().take(8) {
        println!(
            "  wire {wi} (layer {}) seg {si}: {r:.3} F_ref ({})",
            layer_of(wi),
            if torque { "torque" } else { "force" }
        );
        let wl = &m.wires[wi];
        let nc = wl.contacts.len();
        for (k, c) in loads[wi].contacts.iter().enumerate() {
            let (seg, what) = if k < nc {
                (wl.contacts[k].segment, "core".to_string())
            } else {
                let lk = &wl.links[k - nc];
                (
                    lk.segment,
                    format!("{:?} with wire {}", lk.kind, lk.partner),
                )
            };
            if seg == si && c.state != ContactState::Open {
                println!(
                    "    contact {what}: {:?}, N {:.3e} N ({:.2} F_ref), |Ft| {:.3e} N",
                    c.state,
                    c.normal_force,
                    c.normal_force / f_ref,
                    c.tangential_force.norm()
                );
            }
        }
    }
    let tip = *m.core_centreline(&state).last().unwrap();
    println!("tip ({:.6e}, {:.6e}, {:.6e})", tip.x, tip.y, tip.z);
    for stages in [0, env("STAGES", 2.0) as usize] {
        let mut st = state.clone();
        let polish = StaticOptions {
            load_steps: 1,
            min_increment: 1.0,
            potential_descent: false,
            penalty_stages: stages,
            max_iterations: env("ITER", 40.0) as usize,
            extend_while_falling: env("EXTEND", 0.0) != 0.0,
            ..StaticOptions::default()
        };
        let res = solve_static(&m, &mut st, &polish);
        if let (Ok(path), true) = (std::env::var("CENTRELINE"), stages == 0 && res.is_ok()) {
            let c = m.core_centreline(&st);
            let mut out = String::from("s,x,y,z\n");
            for (k, p) in c.iter().enumerate() {
                let s = 0.08 * k as f64 / (c.len() - 1) as f64;
                out += &format!("{s:?},{:?},{:?},{:?}\n", p.x, p.y, p.z);
            }
            std::fs::write(format!("{path}/centerline.csv"), out).unwrap();
        }
        let t2 = *m.core_centreline(&st).last().unwrap();
        println!(
            "Newton, {stages} penalty stages: {res:?}; tip moved {:.3e} m to ({:.6e}, {:.6e}, \
             {:.6e})",
            (t2 - tip).norm(),
            t2.x,
            t2.y,
            t2.z
        );
    }
    println!("[{:.1} s CPU]", common::cpu_seconds());
}
