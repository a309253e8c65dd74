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
//! Along the whole path (loading, reversal, unloading, reloading) every point is split too:
//! per layer the fine moment, the frictionless test's along the same path (scaled to the
//! point's measured curvature), their difference (the moment friction adds), and the
//! fraction of the layer's closed contacts that slip, per kind; beside it the law's friction
//! moment per layer, followed along the same measured curvatures with its slip state (as
//! `strand bend` does for `law_moment`), under `section.slip_pressure` `accumulated` and
//! `two_faces` at the nominal strain and `two_faces` at each point's measured tension, and its
//! fraction of slipping wire-stations per layer (a fine fraction is `-`, an empty CSV field,
//! where the layer has no closed contact of the kind). With `CSV=PATH` these
//! rows go to a file as well. `STICK_LOSS=X` sets the contacts' `stick_loss` (the tangential
//! penalty; default 0.05); `POINTS=P` the contact points per segment on the core
//! (`ContactOptions::points_per_segment`; default by layers, one on a strand of several).
//!
//! `LAW_ONLY=ROWS.csv STICK_SCALE=f1,f2,..` runs no fine test: it follows the law along the
//! measured curvatures of such a CSV with each layer's stick stiffness scaled by f_j. For the
//! hysteretic slider, stick stiffness f k is the same as the strain f e at stiffness k (the
//! slip state scales with it; the friction limits depend on the strain only), so layer j's
//! friction moment is the law's at the curvature path f_j kappa.
//!
//! `cargo run --release -p strand-scene --example layer_moments -- SCENE T SPP PITCHES K1,K2,..`
//! (PITCHES at least 3: the window keeps a pitch clear of each clamp).

use std::collections::BTreeMap;

use strand_core::{SectionLaw, SectionOptions, SlipPressure, Strand, WireState};
use strand_fine::interlayer::LinkKind;
use strand_fine::{BendingPoint, BendingTest, ContactOptions, ContactState, FineModel, ModelState};
use strand_scene::Scene;

#[path = "../tests/common/pitch_law.rs"]
mod pitch_law;

use pitch_law::{PitchLaw, pitch_stations};

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
    if pitches < strand_fine::bending::MIN_PITCHES {
        eprintln!(
            "layer_moments: {pitches} pitches: the test needs at least {} (its window of whole \
             pitches keeps a pitch clear of each clamp; fewer leave no cut and no contact to \
             measure)",
            strand_fine::bending::MIN_PITCHES
        );
        std::process::exit(2);
    }
    if let Ok(path) = std::env::var("LAW_ONLY") {
        law_only(&scene, t, &path);
        return;
    }
    let test = BendingTest {
        pitches,
        segments_per_pitch: spp,
        tension: t,
        curvatures: curvatures.clone(),
        contact: ContactOptions {
            penetration: scene.models.fine.map_or(1e-3, |f| f.penetration),
            stick_loss: std::env::var("STICK_LOSS")
                .map_or(ContactOptions::default().stick_loss, |v| v.parse().unwrap()),
            points_per_segment: std::env::var("POINTS").ok().map(|v| v.parse().unwrap()),
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
    let mut records: Vec<Record> = Vec::new();
    let (curve, model, state) = test
        .run_observed(strand, &mut |p, model, state| {
            records.push(Record {
                point: *p,
                parts: BendingTest::layer_moment_parts(model, state, layers, (lo, hi)),
                contacts: contact_rows(model, state, (lo, hi)),
            });
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
    let parts = BendingTest::layer_moment_parts(&model, &state, layers, (lo, hi));
    let friction_free = BendingTest {
        friction: 0.0,
        curvatures: vec![p.curvature],
        ..test.clone()
    };
    let (c0, m0, s0) = friction_free
        .run_with_state(strand)
        .expect("frictionless test");
    let parts0 = BendingTest::layer_moment_parts(&m0, &s0, layers, (lo, hi));
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

    // The whole path: the frictionless test along the same curvatures (path-independent, so
    // one run), then per point and layer the moment friction adds against the law's.
    let mut free: Vec<(BendingPoint, Vec<[f64; 3]>)> = Vec::new();
    BendingTest {
        friction: 0.0,
        ..test.clone()
    }
    .run_observed(strand, &mut |p, model, state| {
        free.push((
            *p,
            BendingTest::layer_moment_parts(model, state, layers, (lo, hi)),
        ))
    })
    .expect("frictionless test along the path");
    path_table(&scene, strand, t, &records, &free, layers);
}

/// One measured point of the test with friction and what the path table reads of it.
struct Record {
    point: BendingPoint,
    parts: Vec<[f64; 3]>,
    contacts: BTreeMap<(usize, &'static str), [f64; 5]>,
}

/// The law followed along a curvature path at `STATIONS` stations of one pitch with its
/// committed slip state, reporting per layer the wires' friction moment (the moment beyond
/// K_min kappa, N m) and the fraction of slipping wire-stations.
struct LawLayers(PitchLaw);

impl LawLayers {
    fn new(strand: &Strand, scene: &Scene, pressure: SlipPressure, eps: f64) -> Self {
        let options = SectionOptions {
            slip_pressure: pressure,
            ..scene.section
        };
        let pitch_law = PitchLaw::new(
            SectionLaw::with_options(strand, scene.law, &options),
            strand,
            STATIONS,
        );
        let law = &pitch_law.law;
        // Per layer, the wires' critical curvature over the stations (straight strand at the
        // test's strain): a wire reverses its slip after twice its own on unloading.
        let mut critical = vec![(f64::INFINITY, 0.0f64); strand.layers().len()];
        let zero = vec![0.0; law.state_len()];
        for st in &pitch_law.stations {
            for w in law.planar_wires(st, eps, 1e-9, &zero) {
                if let Some(c) = w.critical_curvature {
                    let e = &mut critical[w.layer - 1];
                    *e = (e.0.min(c), e.1.max(c));
                }
            }
        }
        println!(
            "law {}: critical curvature per layer (least, largest) {critical:.4?} 1/m; layer \
             stick stiffness {:.4?} N m^2",
            pressure.name(),
            (0..strand.layers().len())
                .map(|j| law.layer_stick_stiffness(j))
                .collect::<Vec<_>>()
        );
        Self(pitch_law)
    }

    /// Moves the law to `kappa` at strain `eps` and commits; returns its moment, the wires'
    /// friction moment per layer and the fraction of slipping wire-stations per layer. The
    /// friction moment is sum_i F_i l_i with F_i = k (l_i kappa - s_i), s_i the committed
    /// slip strain and l_i = -R sin(phi_i) the lever; that K_min kappa plus it is the law's
    /// moment is checked (panics beyond 1e-9 relative).
    fn step(&mut self, eps: f64, kappa: f64) -> (f64, Vec<f64>, Vec<f64>) {
        let layers = self.0.layers();
        let (mut moment, mut friction, mut slipping) = (0.0, vec![0.0; layers], vec![0.0; layers]);
        let mut counts = vec![0.0; layers];
        self.0.step(
            eps,
            kappa,
            (1e-9, 1e-12),
            |layer, m| {
                friction[layer] += m;
                counts[layer] += 1.0;
            },
            |law, st, slip, m| {
                for w in law.planar_wires(st, eps, kappa, slip) {
                    if w.state == WireState::Slip {
                        slipping[w.layer - 1] += 1.0;
                    }
                }
                moment += m;
            },
        );
        let n = STATIONS as f64;
        for j in 0..layers {
            friction[j] /= n;
            slipping[j] /= counts[j];
        }
        (moment / n, friction, slipping)
    }
}

/// Prints (and with `CSV=PATH` writes) per point of the path: the fine moment, and per layer
/// the fine moment, the frictionless one at the same measured curvature, the moment friction
/// adds, the fraction of closed contacts slipping per kind, and the law's friction moment
/// and slipping fraction under `accumulated` and `two_faces`.
fn path_table(
    scene: &Scene,
    strand: &Strand,
    t: f64,
    records: &[Record],
    free: &[(BendingPoint, Vec<[f64; 3]>)],
    layers: usize,
) {
    let eps = t / strand.axial_stiffness();
    let mut laws = [
        LawLayers::new(strand, scene, SlipPressure::Accumulated, eps),
        LawLayers::new(strand, scene, SlipPressure::TwoFaces, eps),
        // The same at each point's measured tension of the fine test (as a beam would give
        // the law its own axial strain).
        LawLayers::new(strand, scene, SlipPressure::TwoFaces, eps),
    ];
    let mut header = vec![
        "imposed_curvature".to_string(),
        "curvature".into(),
        "moment".into(),
        "tension".into(),
        "law_moment_accumulated".into(),
        "law_moment_two_faces".into(),
        "law_moment_two_faces_measured".into(),
    ];
    for j in 0..=layers {
        header.push(format!("fine_{j}"));
        header.push(format!("frictionless_{j}"));
    }
    for j in 1..=layers {
        header.extend([
            format!("friction_fine_{j}"),
            format!("friction_accumulated_{j}"),
            format!("friction_two_faces_{j}"),
            format!("slipping_accumulated_{j}"),
            format!("slipping_two_faces_{j}"),
            format!("friction_two_faces_measured_{j}"),
        ]);
    }
    let kinds: Vec<(usize, &str)> = records
        .iter()
        .flat_map(|r| r.contacts.keys().copied())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    for (j, kind) in &kinds {
        header.push(format!("slip_fraction_{j}_{kind}"));
    }
    let mut rows = Vec::new();
    // Skip the tension step (curvature zero).
    for (r, (p0, parts0)) in records.iter().zip(free).skip(1) {
        let p = &r.point;
        let scale = p.curvature / p0.curvature;
        let eps_fine = p.tension / strand.axial_stiffness();
        let laws_out: Vec<_> = laws
            .iter_mut()
            .enumerate()
            .map(|(i, l)| l.step(if i == 2 { eps_fine } else { eps }, p.curvature))
            .collect();
        let mut row = vec![
            p.imposed_curvature,
            p.curvature,
            p.moment,
            p.tension,
            laws_out[0].0,
            laws_out[1].0,
            laws_out[2].0,
        ];
        let fine: Vec<f64> = r.parts.iter().map(|q| q.iter().sum()).collect();
        let fine0: Vec<f64> = parts0
            .iter()
            .map(|q| q.iter().sum::<f64>() * scale)
            .collect();
        for j in 0..=layers {
            row.extend([fine[j], fine0[j]]);
        }
        for j in 1..=layers {
            row.extend([
                fine[j] - fine0[j],
                laws_out[0].1[j - 1],
                laws_out[1].1[j - 1],
                laws_out[0].2[j - 1],
                laws_out[1].2[j - 1],
                laws_out[2].1[j - 1],
            ]);
        }
        for key in &kinds {
            let c = r.contacts.get(key).copied().unwrap_or_default();
            // Undefined (NaN, shown as `-`) where no contact of the kind is closed.
            row.push(if c[1] + c[2] > 0.0 {
                c[2] / (c[1] + c[2])
            } else {
                f64::NAN
            });
        }
        rows.push(row);
    }
    println!("path, per point: friction moment per layer (N m): fine, law accumulated, two_faces");
    println!(
        "kappa (1/m)   fine M     law acc    law two   {}",
        (1..=layers)
            .map(|j| format!("| L{j} fine   acc       two      slip fine/acc/two "))
            .collect::<String>()
    );
    for row in &rows {
        let mut line = format!(
            "{:+.4e} {:+.4e} {:+.4e} {:+.4e} ",
            row[1], row[2], row[4], row[5]
        );
        let base = 7 + 2 * (layers + 1);
        for j in 0..layers {
            let q = &row[base + 6 * j..base + 6 * j + 6];
            // The fine layer's slipping fraction of its contacts on the layer beneath.
            let inner = kinds
                .iter()
                .position(|&(l, k)| {
                    l == j + 1
                        && (if j == 0 {
                            k == "core"
                        } else {
                            k == "crossing" || k == "line"
                        })
                })
                .map_or(f64::NAN, |i| row[base + 6 * layers + i]);
            line += &format!(
                "| {:+.4} {:+.4} {:+.4} {}/{:.2}/{:.2} ",
                q[0],
                q[1],
                q[2],
                fraction(inner),
                q[3],
                q[4]
            );
        }
        println!("{line}");
    }
    if let Ok(path) = std::env::var("CSV") {
        let mut text = header.join(",") + "\n";
        for row in &rows {
            text += &row
                .iter()
                .map(|v| {
                    if v.is_nan() {
                        String::new()
                    } else {
                        format!("{v:.8e}")
                    }
                })
                .collect::<Vec<_>>()
                .join(",");
            text += "\n";
        }
        std::fs::write(&path, text).expect("CSV");
        println!("rows written to {path}");
    }
}

/// A slipping fraction for the table (two decimals), or `-` where it is undefined: the layer
/// has no closed contact of the kind in the window (NaN in the rows; an empty field in the
/// CSV).
fn fraction(v: f64) -> String {
    if v.is_nan() {
        " -  ".to_string()
    } else {
        format!("{v:.2}")
    }
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

/// Contact states and normal force per unit strand length (N/m) over the middle pitch, per
/// layer of the wire carrying the contact and kind.
fn contacts(model: &FineModel, state: &ModelState, (lo, hi): (f64, f64), span: f64) {
    let rows = contact_rows(model, state, (lo, hi));
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

/// Per (layer of the carrying wire, kind) over the middle pitch: open, stick, slip counts and
/// the sums of N and |F_t| (N).
fn contact_rows(
    model: &FineModel,
    state: &ModelState,
    (lo, hi): (f64, f64),
) -> BTreeMap<(usize, &'static str), [f64; 5]> {
    let mut loads = model.load_buffers();
    model.compute_loads(state, 1.0, &mut loads);
    // (layer, kind) -> [open, stick, slip, sum N, sum |F_t|]
    let mut rows: BTreeMap<(usize, &'static str), [f64; 5]> = Default::default();
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
    rows
}

/// The law's friction moment per layer (N m): the wires' M_slip summed per layer, averaged over
/// a pitch, at the strain of the fine test's tension and its curvature, bent from straight.
fn law_friction(scene: &Scene, strand: &Strand, eps: f64, p: &strand_fine::BendingPoint) {
    let law = SectionLaw::with_options(strand, scene.law, &scene.section);
    let stations = pitch_stations(&law, strand, STATIONS);
    let eps_fine = eps * p.tension / (eps * strand.axial_stiffness());
    for (label, e) in [("nominal tension", eps), ("fine's tension", eps_fine)] {
        let mut per_layer = vec![0.0; strand.layers().len()];
        let mut slipping = vec![0usize; strand.layers().len()];
        let slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        let mut m = 0.0;
        for st in &stations {
            m += law.planar(st, e, p.curvature, &slip, &mut trial).moment;
            for w in law.planar_wires(st, e, p.curvature, &slip) {
                per_layer[w.layer - 1] += w.m_slip;
                if w.state == strand_core::WireState::Slip {
                    slipping[w.layer - 1] += 1;
                }
            }
        }
        let n = STATIONS as f64;
        println!(
            "law at {label} (strain {e:.4e}), bent from straight: M {:.5e} N m; friction moment \
             per layer {:?} N m; slipping wire-stations per layer {slipping:?} of {:?}",
            m / n,
            per_layer.iter().map(|v| v / n).collect::<Vec<_>>(),
            strand
                .layers()
                .iter()
                .map(|l| l.wires() * STATIONS)
                .collect::<Vec<_>>()
        );
    }
}

/// The law's friction moment per layer along the measured curvatures of a CSV written by
/// this example (`LAW_ONLY`), each layer's stick stiffness scaled by `STICK_SCALE` (see the
/// module docs), under `accumulated` and `two_faces` at the nominal strain; with `CSV=PATH`
/// the rows go to a file.
fn law_only(scene: &Scene, t: f64, path: &str) {
    let strand = &scene.strand;
    let eps = t / strand.axial_stiffness();
    let layers = strand.layers().len();
    let scales: Vec<f64> = std::env::var("STICK_SCALE").map_or(vec![1.0; layers], |v| {
        v.split(',').map(|s| s.parse().unwrap()).collect()
    });
    assert_eq!(scales.len(), layers, "STICK_SCALE: one factor per layer");
    let text = std::fs::read_to_string(path).expect("rows");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "curvature")
        .expect("curvature");
    let kappas: Vec<f64> = lines
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect();
    // One law per (pressure, layer): layer j's rows come from the law at f_j kappa.
    let mut laws: Vec<Vec<LawLayers>> = [SlipPressure::Accumulated, SlipPressure::TwoFaces]
        .iter()
        .map(|&p| {
            (0..layers)
                .map(|_| LawLayers::new(strand, scene, p, eps))
                .collect()
        })
        .collect();
    let mut out = String::from("curvature");
    for name in ["accumulated", "two_faces"] {
        for j in 1..=layers {
            out += &format!(",friction_{name}_{j}");
        }
    }
    out += "\n";
    println!("stick stiffness scaled per layer by {scales:?}");
    for &kappa in &kappas {
        let mut row = vec![kappa];
        for per_layer in &mut laws {
            for (j, law) in per_layer.iter_mut().enumerate() {
                row.push(law.step(eps, scales[j] * kappa).1[j]);
            }
        }
        println!(
            "{}",
            row.iter()
                .map(|v| format!("{v:+.4e}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
        out += &row
            .iter()
            .map(|v| format!("{v:.8e}"))
            .collect::<Vec<_>>()
            .join(",");
        out += "\n";
    }
    if let Ok(csv) = std::env::var("CSV") {
        std::fs::write(&csv, out).expect("CSV");
    }
}
