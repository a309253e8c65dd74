//! Where the fine strand's bending moment sits, layer by layer, against the section law: the
//! scene's virtual bending test (as `strand bend`) along a curvature path, then at its last
//! point the internal moment at the core's joints over the middle pitch split into the core,
//! and per layer into the wires' own joint moments and their axial and shear forces times their
//! arms (each wire cut at its joint nearest the cut plane; loads of the part after the cut on
//! the part before, about the core's joint point); the same test without friction at the same
//! curvature, whose per-layer moments the friction adds to; the contacts per layer and kind
//! (states, normal force per unit strand length) over the middle pitch; and the law's friction
//! moment per layer (sum of the wires' M_slip averaged over a pitch) at the fine's tension.
//!
//! Each load point is printed as it is reached with the wall and CPU time so far.
//!
//! `cargo run --release -p strand-scene --example layer_moments -- SCENE T SPP PITCHES K1,K2,..`

use strand_core::{SectionLaw, Strand};
use strand_fine::interlayer::LinkKind;
use strand_fine::{BendingTest, ContactOptions, ContactState, FineModel, ModelState};
use strand_scene::Scene;

/// Phase stations of the law's pitch average.
const STATIONS: usize = 48;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene = Scene::load(args[1].as_ref()).expect("scene");
    let t: f64 = args[2].parse().unwrap();
    let spp: usize = args[3].parse().unwrap();
    let pitches: usize = args[4].parse().unwrap();
    let curvatures: Vec<f64> = args[5].split(',').map(|s| s.parse().unwrap()).collect();
    let strand = &scene.strand;
    let test = BendingTest {
        pitches,
        segments_per_pitch: spp,
        tension: t,
        curvatures: curvatures.clone(),
        contact: ContactOptions {
            penetration: scene.models.fine.map_or(1e-3, |f| f.penetration),
            ..ContactOptions::default()
        },
        friction: strand.friction(),
        statics: BendingTest::load_step_statics(t),
        max_halvings: 6,
        core_springs: Default::default(),
        wire_springs: Default::default(),
        pressure: Default::default(),
    };
    let layers = strand.layers().len();
    let pitch = strand
        .layers()
        .iter()
        .map(|l| l.pitch)
        .reduce(f64::max)
        .unwrap();
    let (lo, hi) = (
        (pitches as f64 / 2.0 - 1.0).max(1.0) * pitch,
        (pitches as f64 / 2.0 + 1.0).min(pitches as f64 - 1.0) * pitch,
    );
    let start = std::time::Instant::now();
    let (curve, model, state) = test
        .run_with_progress(strand, &mut |p| {
            println!(
                "  point kappa {:.5e} 1/m, M {:.5e} N m, stick {} slip {} open {}: {:.1} s wall, \
                 {:.1} s CPU",
                p.curvature,
                p.moment,
                p.stick,
                p.slip,
                p.open,
                start.elapsed().as_secs_f64(),
                cpu_seconds()
            )
        })
        .expect("bending test");
    let p = curve.last().unwrap();
    println!(
        "T {t} N, {pitches} pitches of {spp}, path {curvatures:?}: fine M {:.5e} N m at kappa \
         {:.5e} 1/m, tension {:.2} N ({:.1} s)",
        p.moment,
        p.curvature,
        p.tension,
        start.elapsed().as_secs_f64()
    );
    let parts = layer_parts(&model, &state, layers, (lo, hi));
    let friction_free = BendingTest {
        friction: 0.0,
        curvatures: vec![p.curvature],
        ..test.clone()
    };
    let (c0, m0, s0) = friction_free
        .run_with_state(strand)
        .expect("frictionless test");
    let parts0 = layer_parts(&m0, &s0, layers, (lo, hi));
    println!(
        "frictionless at kappa {:.5e}: M {:.5e} N m",
        c0.last().unwrap().curvature,
        c0.last().unwrap().moment
    );
    println!(
        "layer   own (N m)   axial x arm   shear x arm   total       frictionless total  \
         friction adds"
    );
    for j in 0..=layers {
        let [o, a, s] = parts[j];
        let [o0, a0, s0] = parts0[j];
        println!(
            "{j:5}  {o:11.4e}  {a:11.4e}  {s:11.4e}  {:11.4e}  {:11.4e}  {:11.4e}",
            o + a + s,
            o0 + a0 + s0,
            o + a + s - (o0 + a0 + s0)
        );
    }
    let total: f64 = parts.iter().flatten().sum();
    println!("sum of the parts {total:.5e} N m");
    contacts(&model, &state, (lo, hi), hi - lo);
    law_friction(&scene, strand, t / strand.axial_stiffness(), p);
}

/// CPU time of this process so far, user and system (s), from `/proc/self/stat` (clock ticks
/// of 1/100 s); NaN where that is not readable.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    // Fields after the command name in parentheses: utime and stime are the 12th and 13th.
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let tick = |i: usize| {
        f.get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    (tick(11) + tick(12)) / 100.0
}

/// Per layer (0 the core): wires' own joint moment, axial force x arm, shear force x arm (N m),
/// averaged over the core's joints in [lo, hi].
fn layer_parts(
    model: &FineModel,
    state: &ModelState,
    layers: usize,
    (lo, hi): (f64, f64),
) -> Vec<[f64; 3]> {
    let mut parts = vec![[0.0; 3]; layers + 1];
    let core = &model.wires[0];
    let cs = &state.wires[0].poses;
    let mut cuts = 0;
    for j in 0..core.chain.joints.len() {
        let x = core.chain.rest[j].point(&core.chain.joints[j].offset_a).x;
        if x < lo - 1e-9 || x > hi + 1e-9 {
            continue;
        }
        let jt = &core.chain.joints[j];
        let c = cs[j].point(&jt.offset_a);
        let normal = (cs[j].tangent() + cs[j + 1].tangent()).normalize();
        let l = jt.evaluate(&cs[j], &cs[j + 1]);
        parts[0][0] += (l.torque_a + (cs[j].position - c).cross(&l.force_a)).z;
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
            let part = &mut parts[w.layer];
            part[0] += (lw.torque_a + (ws.poses[k].position - q).cross(&lw.force_a)).z;
            part[1] += (q - c).cross(&axial).z;
            part[2] += (q - c).cross(&(lw.force_a - axial)).z;
        }
        cuts += 1;
    }
    for p in &mut parts {
        for v in p.iter_mut() {
            *v /= cuts as f64;
        }
    }
    parts
}

/// Contact states and normal force per unit strand length (N/m) over the middle pitch, per
/// layer of the wire carrying the contact and kind.
fn contacts(model: &FineModel, state: &ModelState, (lo, hi): (f64, f64), span: f64) {
    let mut loads = model.load_buffers();
    model.compute_loads(state, 1.0, &mut loads);
    // (layer, kind) -> [open, stick, slip, sum N, sum |F_t|]
    let mut rows: std::collections::BTreeMap<(usize, &str), [f64; 5]> = Default::default();
    for (w, l) in model.wires.iter().zip(&loads).skip(1) {
        let nc = w.contacts.len();
        for (i, c) in l.contacts.iter().enumerate() {
            let (seg, kind) = if i < nc {
                (w.contacts[i].segment, "core")
            } else {
                let lk = &w.links[i - nc];
                let kind = match lk.kind {
                    LinkKind::Line => "line",
                    LinkKind::Crossing => "crossing",
                    LinkKind::Neighbour => "neighbour",
                };
                (lk.segment, kind)
            };
            let x = w.chain.rest[seg].position.x;
            if x < lo || x > hi {
                continue;
            }
            let r = rows.entry((w.layer, kind)).or_default();
            match c.state {
                ContactState::Open => r[0] += 1.0,
                ContactState::Stick => r[1] += 1.0,
                ContactState::Slip => r[2] += 1.0,
            }
            r[3] += c.normal_force;
            r[4] += c.tangential_force.norm();
        }
    }
    println!("contacts over the middle pitch (layer of the carrying wire, kind)");
    println!("layer kind        open  stick   slip  N per length (N/m)  |F_t| per length (N/m)");
    for ((layer, kind), r) in rows {
        println!(
            "{layer:5} {kind:10} {:5} {:6} {:6}  {:18.4e}  {:18.4e}",
            r[0],
            r[1],
            r[2],
            r[3] / span,
            r[4] / span
        );
    }
}

/// The law's friction moment per layer (N m): the wires' M_slip summed per layer, averaged over
/// a pitch, at the strain of the fine test's tension and its curvature, bent from straight.
fn law_friction(scene: &Scene, strand: &Strand, eps: f64, p: &strand_fine::BendingPoint) {
    let law = SectionLaw::with_options(strand, scene.law, &scene.section);
    let pitch = strand.layers()[0].pitch;
    let eps_fine = eps * p.tension / (eps * strand.axial_stiffness());
    for (label, e) in [("nominal tension", eps), ("fine's tension", eps_fine)] {
        let mut per_layer = vec![0.0; strand.layers().len()];
        let mut slipping = vec![0usize; strand.layers().len()];
        let slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        let mut m = 0.0;
        for i in 0..STATIONS {
            let st = law.station(pitch * (i as f64 + 0.5) / STATIONS as f64);
            m += law.planar(&st, e, p.curvature, &slip, &mut trial).moment;
            for w in law.planar_wires(&st, e, p.curvature, &slip) {
                per_layer[w.layer - 1] += w.m_slip;
                if w.state == strand_core::WireState::Slip {
                    slipping[w.layer - 1] += 1;
                }
            }
        }
        let n = STATIONS as f64;
        println!(
            "law at {label} (strain {e:.4e}), bent from straight: M {:.5e} N m; friction moment \
             per layer {:?} N m; slipping wire-stations per layer {slipping:?} of {}",
            m / n,
            per_layer.iter().map(|v| v / n).collect::<Vec<_>>(),
            STATIONS
        );
    }
}
