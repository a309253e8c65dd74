//! The fine model of a multi-layer strand: chains of every layer, wire-to-wire links.

use nalgebra::{DMatrix, DVector, Vector3};
use strand_core::BaseStiffness;
use strand_core::{LayDirection, LayerSpec, Material, Strand, StrandSpec, WireSpec};
use strand_fine::interlayer::{self, LinkKind};
use strand_fine::{
    AXIAL_TOLERANCE, BendingTest, ContactOptions, ContactState, Discretisation, FineModel,
    ModelState, NormalPenalty, Support,
};

fn steel() -> Material {
    Material {
        youngs_modulus: 2.0e11,
        poisson_ratio: 0.3,
        density: 7850.0,
    }
}

fn layer(wires: usize, d: f64, deg: f64, direction: LayDirection, material: Material) -> LayerSpec {
    LayerSpec {
        wires,
        wire: WireSpec {
            diameter: d,
            material,
        },
        lay_angle: deg.to_radians(),
        phase: 0.0,
        direction,
    }
}

/// The 1+6+12 steel strand of `examples/steel-1x19-swing.json` (outer layer left-laid, or
/// right-laid with `same_lay`), `length` long.
fn strand_1x19(length: f64, same_lay: bool) -> Strand {
    let outer = if same_lay {
        LayDirection::Right
    } else {
        LayDirection::Left
    };
    Strand::new(StrandSpec {
        length,
        core: WireSpec {
            diameter: 3.3e-3,
            material: steel(),
        },
        layers: vec![
            layer(6, 3.0e-3, 8.0, LayDirection::Right, steel()),
            layer(12, 3.0e-3, 12.0, outer, steel()),
        ],
        friction: 0.3,
    })
    .unwrap()
}

/// A fine model of `strand` with `n` segments per wire, both ends clamped, default contacts.
fn model(strand: &Strand, n: usize, options: &ContactOptions) -> FineModel {
    let mut m = FineModel::from_strand(
        strand,
        Discretisation {
            core_segments: n,
            wire_segments: n,
        },
        Support::Clamped,
        Support::Clamped,
    );
    m.add_contacts(strand, options);
    m
}

/// The links of `m` that hold a contact at `state` within `reach` (m) of touching: (kind,
/// gap).
fn touching(m: &FineModel, state: &ModelState, reach: f64) -> Vec<(LinkKind, f64)> {
    let mut out = Vec::new();
    for (w, aps) in m.wires.iter().zip(m.link_approaches(state)) {
        for (lk, ap) in w.links.iter().zip(aps) {
            if let Some(ap) = ap {
                let gap = ap.gap(lk);
                if gap < reach {
                    out.push((lk.kind, gap));
                }
            }
        }
    }
    out
}

/// Every layer is laid on its stacked radius: the chains' nodes lie on the helices of
/// `Strand::layers()`, each wire is held at both clamped ends, and the wires of the first
/// layer only carry wire-to-core contacts.
#[test]
fn every_layer_is_laid_on_its_helix_and_held() {
    let s = strand_1x19(0.2, false);
    let m = model(&s, 40, &ContactOptions::default());
    assert_eq!(m.wires.len(), 19);
    let mut w = 1;
    for (j, l) in s.layers().iter().enumerate() {
        for i in 0..l.wires() {
            let wire = &m.wires[w];
            assert_eq!(wire.layer, j + 1);
            assert_eq!(wire.anchors.len(), 2, "wire {w}");
            assert_eq!(wire.contacts.is_empty(), j > 0, "wire {w}");
            for (k, p) in wire.chain.centreline(&wire.chain.rest).iter().enumerate() {
                let x = 0.2 * k as f64 / 40.0;
                let phi = l.phase(i, x);
                let exact = Vector3::new(x, l.radius * phi.sin(), l.radius * phi.cos());
                assert!((p - exact).norm() < 1e-15, "wire {w} node {k}");
            }
            w += 1;
        }
    }
}

/// Broad and narrow phase against the lay geometry: on an alternate-lay pair (the 1+6+12
/// strand, 8 deg right on 12 deg left, crossing angle 20 deg) the links that own a contact
/// within the allowed penetration of touching at rest are the crossings of the lay phases,
/// one link per crossing, at two meshes and two phases of the outer layer; none penetrates
/// the allowed penetration (the chord sag is compensated). The count is over the whole
/// strand; the phases give it with no model input.
#[test]
fn links_find_every_crossing_of_an_alternate_lay_pair_once() {
    for (phase, n) in [(0.0, 40), (0.3, 25)] {
        let mut spec = strand_1x19(0.2, false).spec().clone();
        spec.layers[1].phase = phase;
        let s = Strand::new(spec).unwrap();
        let options = ContactOptions::default();
        let m = model(&s, n, &options);
        let delta = options.penetration * 3.0e-3;
        let found = touching(&m, &m.rest_state(), delta);
        let crossings: Vec<f64> = found
            .iter()
            .filter(|(k, _)| *k == LinkKind::Crossing)
            .map(|(_, g)| *g)
            .collect();
        let (outer, inner) = (&s.layers()[1], &s.layers()[0]);
        let geometric: usize = (0..outer.wires())
            .map(|i| interlayer::geometric_crossings(outer, i, inner, 0.0, s.length()))
            .sum();
        let worst = crossings.iter().fold(0.0f64, |a, g| a.max(g.abs()));
        println!(
            "phase {phase}, {n} segments: {} crossings found, {geometric} from the phases; \
             largest |gap| {worst:.2e} m (allowed penetration {delta:.1e} m)",
            crossings.len()
        );
        assert_eq!(crossings.len(), geometric);
        assert!(crossings.iter().all(|g| *g >= -1e-12), "{crossings:?}");
    }
}

/// Frictionless virtual bending of the 1+6+12 strand: M / kappa against the sum of the
/// thin-rod K_min of the core and the wires of both layers (Costello's wire stiffness, the
/// form the one-layer test converges to). Measured by `probe` below.
#[test]
#[ignore = "exploration: SPP, PITCHES from the environment"]
fn probe_frictionless_1x19() {
    let env = |k: &str, d: f64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let mut spec = strand_1x19(1.0, false).spec().clone();
    spec.friction = 0.0;
    let s = Strand::new(spec).unwrap();
    let start = std::time::Instant::now();
    let mut test = BendingTest::frictionless(
        env("PITCHES", 3.0) as usize,
        env("SPP", 12.0) as usize,
        env("T", 0.1),
        env("K", 0.1),
    );
    test.max_halvings = env("HALVINGS", 6.0) as usize;
    // RELIEF: the strain-relief penalty at that relief, 0: the penetration rule.
    let relief = env("RELIEF", -1.0);
    if relief == 0.0 {
        test.contact.normal_penalty = NormalPenalty::Penetration;
    } else if relief > 0.0 {
        test.contact.normal_penalty = NormalPenalty::StrainRelief(relief);
    }
    // ACTIVE_SET=1: load steps solved on active sets of the contacts' states
    // (StaticOptions::active_set).
    test.statics.active_set = env("ACTIVE_SET", 0.0) > 0.0;
    // STICK_LOSS: the stick spring's allowed loss of stiffness (ContactOptions::stick_loss).
    test.contact.stick_loss = env("STICK_LOSS", test.contact.stick_loss);
    // POINTS: contact points per segment on the core (unset: by layers, one here).
    if let Ok(p) = std::env::var("POINTS") {
        test.contact.points_per_segment = p.parse().ok();
    }
    // With friction (MU), curvatures K/4, K/2, K, back to -K and up to K again.
    test.friction = env("MU", 0.0);
    if test.friction > 0.0 {
        let k = env("K", 0.1);
        test.curvatures = vec![0.25 * k, 0.5 * k, k, 0.0, -k, 0.0, k];
    }
    let curve = test
        .run_with_progress(&s, &mut |p| {
            println!("{p:?} at {:.1} s", start.elapsed().as_secs_f64())
        })
        .unwrap_or_else(|e| panic!("bending test: {e}"));
    let (curve, m, state) = curve;
    let tensions = BendingTest::clamp_tensions(&m, &state);
    let t = test.tension;
    let ea = s.axial_stiffness();
    let mut w = 1;
    println!(
        "core: {:.4} of T, share {:.4}",
        tensions[0] / t,
        s.core().material.youngs_modulus * s.core().area() / ea
    );
    for (j, l) in s.layers().iter().enumerate() {
        let sum: f64 = tensions[w..w + l.wires()].iter().sum();
        println!(
            "layer {}: {:.4} of T, share {:.4}",
            j + 1,
            sum / t,
            l.wires() as f64 * l.wire_axial_stiffness() / ea
        );
        w += l.wires();
    }
    let k = curve.last().unwrap().secant_stiffness();
    println!(
        "K = {k:.6e} N m^2 = {:.5} K_min (Costello), {:.1} s",
        k / s.min_bending_stiffness(BaseStiffness::Costello),
        start.elapsed().as_secs_f64()
    );
}

/// The 1+6+12 strand with friction (mu = 0.3, 100 N, 3 outer pitches, 16 segments per pitch,
/// the strain-relief penalty): the first bending step, 0.0125 1/m, converges by plain Newton
/// with no halving of the increment, its contacts satisfy the Coulomb bounds (closed: N > 0
/// and |F_t| <= mu N; slipping: |F_t| = mu N) and its secant stiffness lies between the
/// closed forms K_min (all slip, Costello) and K_max (plane sections). Until the crossing
/// rule kept the more central of two links, this step stalled at a scaled residual of about
/// 2e-2 (Multilayer page, "Fine bending with friction"). At 8 segments per pitch, see
/// [`friction_bending_path_of_1x19_at_8_segments_per_pitch_finishes`].
#[test]
fn friction_bending_step_of_1x19_converges_within_the_coulomb_bounds() {
    let s = strand_1x19(1.0, false);
    let mu = s.spec().friction;
    let mut test = BendingTest::frictionless(3, 16, 100.0, 0.0125);
    test.friction = mu;
    test.max_halvings = 0;
    let (curve, m, state) = test
        .run_with_state(&s)
        .expect("first friction bending step");
    let p = curve.last().unwrap();
    let (closed, slipping) = coulomb_counts(&m, &state, mu);
    let k = p.secant_stiffness();
    let (k_min, k_max) = (
        s.min_bending_stiffness(BaseStiffness::Costello),
        s.max_bending_stiffness(BaseStiffness::Costello),
    );
    println!(
        "kappa {:.4e} 1/m in {} Newton iterations: {closed} contacts closed, {slipping} \
         slipping; M / kappa = {k:.4e} N m^2 = {:.4} K_min, {:.4} K_max",
        p.curvature,
        p.iterations,
        k / k_min,
        k / k_max
    );
    assert!(closed > 0 && slipping > 0 && slipping < closed);
    assert!(k_min < k && k < k_max, "{k} outside [{k_min}, {k_max}]");
}

/// Closed and slipping contacts of `m` at `state`, each checked against the Coulomb bounds
/// (open: no force; closed: N > 0 and |F_t| <= mu N; slipping: |F_t| = mu N).
fn coulomb_counts(m: &FineModel, state: &ModelState, mu: f64) -> (usize, usize) {
    let mut loads = m.load_buffers();
    m.compute_loads(state, 1.0, &mut loads);
    let (mut closed, mut slipping) = (0, 0);
    for c in loads.iter().flat_map(|l| &l.contacts) {
        let ft = c.tangential_force.norm();
        match c.state {
            ContactState::Open => assert_eq!(c.force_wire, Vector3::zeros()),
            ContactState::Stick => {
                assert!(c.normal_force > 0.0 && ft <= mu * c.normal_force * (1.0 + 1e-12));
                closed += 1;
            }
            ContactState::Slip => {
                assert!(c.normal_force > 0.0);
                assert!((ft - mu * c.normal_force).abs() <= 1e-12 * mu * c.normal_force);
                closed += 1;
                slipping += 1;
            }
        }
    }
    (closed, slipping)
}

/// The path of `strand bend examples/steel-1x19-swing.json --tension 100 --curvatures
/// 0.0125,0.05,-0.05,0.05 --pitches 3 --segments-per-pitch 8` (mu = 0.3, the default contacts:
/// one point per segment on the core) runs to its end, every point's contacts within the
/// Coulomb bounds and its secant stiffness `M / kappa` between the closed forms K_min (all
/// slip, Costello) and K_max (plane sections). With the end plate held at the strain T / EA_eq
/// instead of the axial force at the tension (`BendingTest::hold_tension` switched off) the
/// first step stalls at 9.77e-3 1/m (scaled residual 1.5e-3 after six halvings); the softest
/// modes of the tangent there are not the first layer's segments rocking on their single core
/// contact (Multilayer page, "The stick regime of the default contacts").
#[test]
fn friction_bending_path_of_1x19_at_8_segments_per_pitch_finishes() {
    let s = strand_1x19(1.0, false);
    let mu = s.spec().friction;
    let mut test = BendingTest::frictionless(3, 8, 100.0, 0.0125);
    test.friction = mu;
    test.curvatures = vec![0.0125, 0.05, -0.05, 0.05];
    let (k_min, k_max) = (
        s.min_bending_stiffness(BaseStiffness::Costello),
        s.max_bending_stiffness(BaseStiffness::Costello),
    );
    let mut points = 0;
    let (curve, _, _) = test
        .run_observed(&s, &mut |p, m, state| {
            let (closed, slipping) = coulomb_counts(m, state, mu);
            if p.imposed_curvature != 0.0 {
                let k = p.secant_stiffness();
                assert!(k_min < k && k < k_max, "{k} outside [{k_min}, {k_max}]");
                assert!(closed > 0 && slipping > 0);
                points += 1;
            }
        })
        .expect("the 8-segment path");
    assert_eq!(points, 4);
    assert_eq!(curve.last().unwrap().imposed_curvature, 0.05);
}

/// The assembled tangent with the wire-to-wire links (central differences of each link's
/// loads, `FineModel::link_tangents`) against the change of the whole model's loads along a
/// direction that moves every outer segment: `K v = -(F(x + v) - F(x - v)) / 2`, on the 1+6+12
/// strand with its outer layer pressed into the layer beneath (crossing links closed) and
/// with friction (stuck links). Checks the blocks' placement on the two wires' segments, their
/// signs and the one-contact-per-crossing rule against the load evaluation. Both sides are
/// central differences of the same loads: they agree to their truncation error, far below
/// the 1e-4 asked.
#[test]
fn link_tangent_matches_the_change_of_the_loads() {
    let s = strand_1x19(0.1, false);
    let options = ContactOptions {
        reference_tension: Some(1000.0),
        ..ContactOptions::default()
    };
    let m = model(&s, 10, &options);
    let mut state = m.rest_state();
    let push = 2.0 * options.penetration * 3.0e-3;
    for w in &mut state.wires[7..] {
        for p in &mut w.poses {
            let r = Vector3::new(0.0, p.position.y, p.position.z);
            p.position -= r.normalize() * push;
        }
    }
    let mut loads = m.load_buffers();
    m.compute_loads(&state, 1.0, &mut loads);
    m.commit_contacts(&mut state, &loads);
    let links = m.link_tangents(&state);
    assert!(links.len() > 10, "{} closed links", links.len());
    let n = 6 * m.segment_count();
    let mut k = DMatrix::<f64>::zeros(n, n);
    for e in m.element_tangents(&state) {
        e.add_to_dense(&mut k);
    }
    // Every segment of the outer layer moves (the first layer's wires rest on the core at
    // zero gap, where the wire-to-core tangent holds the normal spring of a closed contact
    // by design).
    let outer = m.segment_offsets()[7];
    let v: Vec<f64> = (0..n)
        .map(|i| {
            let h = if i % 6 < 3 { 1e-9 } else { 1e-7 };
            if i < 6 * outer {
                0.0
            } else {
                h * (0.7 * i as f64).sin()
            }
        })
        .collect();
    let flat = |st: &ModelState| -> Vec<f64> {
        let mut l = m.load_buffers();
        m.compute_loads(st, 1.0, &mut l);
        l.iter()
            .flat_map(|w| {
                w.forces
                    .iter()
                    .zip(&w.torques)
                    .flat_map(|(f, t)| [f.x, f.y, f.z, t.x, t.y, t.z])
                    .collect::<Vec<_>>()
            })
            .collect()
    };
    let moved = |sign: f64| {
        let mut st = state.clone();
        let mut g = 0;
        for w in &mut st.wires {
            for p in &mut w.poses {
                for dof in 0..6 {
                    strand_fine::joint::perturb(p, dof, sign * v[6 * g + dof]);
                }
                g += 1;
            }
        }
        flat(&st)
    };
    let (fp, fm) = (moved(1.0), moved(-1.0));
    let kv = &k * DVector::from_vec(v.clone());
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for i in 0..n {
        let d = -(fp[i] - fm[i]) / 2.0;
        worst = worst.max((kv[i] - d).abs());
        scale = scale.max(d.abs());
    }
    println!(
        "{} closed links; largest load change {scale:.3e}, largest difference {worst:.3e}",
        links.len()
    );
    assert!(worst <= 1e-4 * scale, "{worst} vs {scale}");
}

/// Frictionless 1+6+12 strand (3 pitches of the outer layer, T = 0.1 N, kappa = 0.1 1/m):
/// M / kappa is the sum of the thin-rod K_min of the core and of the wires of both layers
/// (Costello's wire stiffness, `Strand::min_bending_stiffness`) within 1 %, converged in the
/// segment length. Measured (`probe_frictionless_1x19` with `RELIEF=0`, SPP = 8, 12, 16, 24,
/// 32): 1.00105, 1.00068, 1.00055, 1.00045, 1.00041 K_min; the test runs 12 and 24 and asks them within
/// 2e-3 of each other (a fifth of the tolerance). The penalty is the penetration rule at the
/// test's tension: with the strain-relief penalty, stiff at any tension, Newton does not
/// converge on the tension step at 12 segments per pitch and 0.1 N (scaled residual 1.3e-2;
/// `RELIEF=1e-2 SPP=12 T=0.1 HALVINGS=0` on the probe; open).
#[test]
fn frictionless_1x19_bends_with_the_sum_of_thin_rod_k_min() {
    let mut spec = strand_1x19(1.0, false).spec().clone();
    spec.friction = 0.0;
    let s = Strand::new(spec).unwrap();
    check_frictionless_k_min(&s, "");
}

/// The frictionless bending test of `s` (3 pitches, T = 0.1 N, kappa = 0.1 1/m, the
/// penetration rule) at 12 and 24 segments per pitch: M / kappa within 2e-3 of each other
/// and the finer within 1 % of K_min (Costello's wire stiffness). `label` starts the line
/// printed.
fn check_frictionless_k_min(s: &Strand, label: &str) {
    let k = |spp: usize| {
        let mut test = BendingTest::frictionless(3, spp, 0.1, 0.1);
        test.contact.normal_penalty = NormalPenalty::Penetration;
        test.run(s)
            .expect("bending test")
            .last()
            .unwrap()
            .secant_stiffness()
    };
    let (coarse, fine) = (k(12), k(24));
    let k_min = s.min_bending_stiffness(BaseStiffness::Costello);
    println!(
        "{label}M/kappa {coarse:.6e}, {fine:.6e} N m^2 at 12, 24 segments per pitch: {:.5}, \
         {:.5} K_min",
        coarse / k_min,
        fine / k_min
    );
    assert!((fine - coarse).abs() < 2e-3 * fine, "not converged");
    assert!((fine / k_min - 1.0).abs() < 1e-2, "{} K_min", fine / k_min);
}

/// A two-material conductor section: steel 1+6 (3 mm, 8 deg right) under twelve aluminium
/// wires (3 mm, 12 deg left). Frictionless M / kappa against the sum of the thin-rod K_min,
/// as for the steel strand (3 outer pitches, T = 0.1 N, kappa = 0.1 1/m), at 12 and 24
/// segments per pitch within 2e-3 of each other and the finer within 1 % of K_min.
#[test]
fn frictionless_steel_aluminium_section_bends_with_the_sum_of_thin_rod_k_min() {
    let aluminium = Material {
        youngs_modulus: 6.9e10,
        poisson_ratio: 0.33,
        density: 2700.0,
    };
    let s = Strand::new(StrandSpec {
        length: 1.0,
        core: WireSpec {
            diameter: 3.0e-3,
            material: steel(),
        },
        layers: vec![
            layer(6, 3.0e-3, 8.0, LayDirection::Right, steel()),
            layer(12, 3.0e-3, 12.0, LayDirection::Left, aluminium),
        ],
        friction: 0.0,
    })
    .unwrap();
    check_frictionless_k_min(&s, "steel/aluminium: ");
}

/// The same count on a same-lay pair (both layers right-laid, crossing angle 4 deg): the
/// crossings of the lay phases, now slow (one every 6.4 outer pitches per wire pair) and
/// long, are each held by one link.
#[test]
fn links_find_every_crossing_of_a_same_lay_pair_once() {
    let s = strand_1x19(0.6, true);
    let options = ContactOptions::default();
    let m = model(&s, 120, &options);
    let delta = options.penetration * 3.0e-3;
    let found = touching(&m, &m.rest_state(), delta);
    let lines = found.iter().filter(|(k, _)| *k == LinkKind::Line).count();
    let (outer, inner) = (&s.layers()[1], &s.layers()[0]);
    let geometric: usize = (0..outer.wires())
        .map(|i| interlayer::geometric_crossings(outer, i, inner, 0.0, s.length()))
        .sum();
    println!("same lay: {lines} line contacts found, {geometric} crossings from the phases");
    assert_eq!(lines, geometric);
}

/// The loads with wire-to-wire contacts are the same, bit for bit, on 1 and 3 threads (the
/// partners' shares are summed in wire and link order after the parallel sweep).
#[test]
fn link_loads_do_not_depend_on_the_thread_count() {
    let s = strand_1x19(0.1, false);
    let options = ContactOptions {
        reference_tension: Some(1000.0),
        ..ContactOptions::default()
    };
    let m = model(&s, 10, &options);
    let mut state = m.rest_state();
    for w in &mut state.wires[7..] {
        for p in &mut w.poses {
            let r = Vector3::new(0.0, p.position.y, p.position.z);
            p.position -= r.normalize() * 6e-6;
        }
    }
    let loads = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut l = m.load_buffers();
            m.compute_loads(&state, 1.0, &mut l);
            l
        })
    };
    let (one, three) = (loads(1), loads(3));
    let closed = one
        .iter()
        .flat_map(|l| &l.contacts)
        .filter(|c| c.state != strand_fine::ContactState::Open)
        .count();
    assert!(closed > 20, "{closed}");
    for (a, b) in one.iter().zip(&three) {
        assert_eq!(a.forces, b.forces);
        assert_eq!(a.torques, b.torques);
    }
}

/// Band of the tension shares in `wires_carry_their_share_of_the_tension`: the 5 % to which
/// the fine and equivalent moment-curvature curves are to agree (issue target), not an error
/// bound of the model.
const SHARE_BAND: f64 = 0.05;

/// The wires carry their share of the tension: the 1+6+12 steel strand pulled to 100 N
/// (strain about 3.9e-6, the plate's stretch that holds the axial force at 100 N) in the
/// virtual bending test, 8 segments per pitch. Each layer's clamp force against its share of
/// the axial stiffness at the plate's stretch `eps`, `m E_w A_w cos^3(alpha_c) eps` with the
/// chords' lay angle `tan(alpha_c) = tan(alpha) sinc(dphi / 2)` (the chain's own geometry),
/// and the core's `E_c A_c eps`: no layer above its share, none more than [`SHARE_BAND`]
/// below. Measured: core 1.00000, layers 0.9805 and 0.9771 of their shares (0.9727 and 0.9832
/// with the plate at T / EA_eq, before the test held the tension). The penalty allows each
/// layer to lose 1 % (`penalty::DEFAULT_STRAIN_RELIEF`); the rest (2 % and 2.3 %) is not the
/// penalty and is not explained (open). With the penetration rule (1e-3 d at this tension, the state before
/// the strain-relief penalty and the rest gaps) the layers carry 0.20 and 0.03 of their
/// shares and the test fails.
#[test]
fn wires_carry_their_share_of_the_tension() {
    let s = strand_1x19(1.0, false);
    let tension = 100.0;
    let spp = 8;
    let test = BendingTest {
        curvatures: Vec::new(),
        ..BendingTest::frictionless(3, spp, tension, 0.0)
    };
    let (curve, m, state) = test.run_with_state(&s).expect("tension step");
    let forces = BendingTest::clamp_tensions(&m, &state);
    // The end plate's stretch that holds the tension.
    let eps = curve[0].strain;
    let dphi = 2.0 * std::f64::consts::PI / spp as f64;
    let mut expected = vec![s.core().material.youngs_modulus * s.core().area() * eps];
    for l in s.layers() {
        // The layer's pitch is a whole share of the test's; its segments turn by dphi times
        // the ratio of the pitches.
        let turn = dphi * s.layers()[1].pitch / l.pitch;
        let half = 0.5 * turn;
        let chord = (l.lay_angle().tan() * half.sin() / half).atan();
        let w = &l.spec.wire;
        let ea = w.material.youngs_modulus * w.area();
        expected.push(l.wires() as f64 * ea * chord.cos().powi(3) * eps);
    }
    let mut w = 1;
    let mut carried = vec![forces[0]];
    for l in s.layers() {
        carried.push(forces[w..w + l.wires()].iter().sum());
        w += l.wires();
    }
    for (j, (c, e)) in carried.iter().zip(&expected).enumerate() {
        println!("layer {j}: {c:.4} N of {e:.4} N ({:.5})", c / e);
    }
    // The core is held at the plate's strain and carries its share exactly (no friction).
    assert!(
        (carried[0] / expected[0] - 1.0).abs() < 1e-6,
        "core {}",
        carried[0]
    );
    for (j, (c, e)) in carried.iter().zip(&expected).enumerate().skip(1) {
        assert!(
            *c <= e * (1.0 + 1e-6) && *c >= e * (1.0 - SHARE_BAND),
            "layer {j}: {c} N, share {e} N"
        );
    }
}

/// The explorations' strand: the 1+6+12 strand three outer pitches long, and the segments
/// per pitch `SPP` from the environment (12).
fn three_outer_pitches() -> (usize, Strand) {
    let spp: usize = std::env::var("SPP")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(12);
    let s = strand_1x19(1.0, false);
    let pitch = s.layers()[1].pitch;
    let s = Strand::new(StrandSpec {
        length: 3.0 * pitch,
        ..s.spec().clone()
    })
    .unwrap();
    (spp, s)
}

#[test]
#[ignore = "exploration: rest gaps by SPP"]
fn probe_rest_gaps() {
    let (spp, s) = three_outer_pitches();
    let m = model(&s, 3 * spp, &ContactOptions::default());
    let mut pos = Vec::new();
    for w in &m.wires {
        for l in &w.links {
            if l.rest_gap > 0.0 {
                pos.push((l.rest_gap, l.sag + l.partner_sag, l.segment));
            }
        }
    }
    let (outer, inner) = (&s.layers()[1], &s.layers()[0]);
    let geometric: usize = (0..outer.wires())
        .map(|i| interlayer::geometric_crossings(outer, i, inner, 0.0, s.length()))
        .sum();
    let found = touching(&m, &m.rest_state(), 1e-9).len();
    println!(
        "{} links with a rest gap, {geometric} crossings, {found} touching",
        pos.len()
    );
    let mx = pos.iter().fold(0.0f64, |a, p| a.max(p.0));
    let mn = pos.iter().fold(0.0f64, |a, p| a.min(p.0));
    println!("rest gaps {mn:e} .. {mx:e}, sags {:e}", pos[0].1);
    pos.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap());
    println!(
        "largest: {:?}",
        pos.iter()
            .take(40)
            .map(|p| format!("{:.2e}", p.0))
            .collect::<Vec<_>>()
    );
}

/// The settle's stable step (0.9 x 2 / omega_max, every contact closed and stuck) of the
/// 1+6+12 strand, 3 outer pitches at SPP segments per pitch, under each normal penalty.
#[test]
#[ignore = "exploration: stable step by penalty rule"]
fn probe_stable_step() {
    let (spp, s) = three_outer_pitches();
    for (name, penalty) in [
        (
            "penetration 1e-3 d at strain 1e-3",
            NormalPenalty::Penetration,
        ),
        ("strain relief 1e-2", NormalPenalty::StrainRelief(1e-2)),
        ("strain relief 1e-3", NormalPenalty::StrainRelief(1e-3)),
    ] {
        let options = ContactOptions {
            normal_penalty: penalty,
            ..ContactOptions::default()
        };
        let m = model(&s, 3 * spp, &options);
        let settle = strand_fine::SettleOptions::default();
        let moving = strand_fine::settle::motion_model(&m, &settle);
        let dt = strand_fine::settle_time_step(&moving, &m.rest_state(), settle.safety);
        println!("{name}: stable step {dt:.4e} s");
    }
}

/// Linearity of the loads about the tension state of the 1+6+12 test (SPP, T, MU from the
/// environment; 3 pitches, histories committed): `|F(x + a v) - F(x) + a K v| / |a K v|`
/// along a fixed direction `v` moving every segment (1 m per unit `a` in translation, 30 rad
/// in rotation), for amplitudes `a` from 1e-12 to 1e-7 m, with the closed contacts counted.
/// Separates a tangent error (large at every amplitude) from contact states switching
/// (small at small amplitudes, large beyond them).
#[test]
#[ignore = "exploration: tangent consistency at the tension state"]
fn probe_tangent_at_tension() {
    let env = |k: &str, d: f64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let s = strand_1x19(1.0, false);
    let mut test = BendingTest {
        curvatures: Vec::new(),
        ..BendingTest::frictionless(3, env("SPP", 8.0) as usize, env("T", 100.0), 0.0)
    };
    test.friction = env("MU", 100.0);
    let (_, m, state) = test.run_with_state(&s).expect("tension step");
    let n = 6 * m.segment_count();
    let mut k = DMatrix::<f64>::zeros(n, n);
    let parts: [(&str, Vec<strand_fine::tangent::ElementTangent>); 3] = [
        ("joints", m.joint_tangents(&state)),
        ("core contacts", m.contact_tangents(&state)),
        ("links", m.link_tangents(&state)),
    ];
    for (_, p) in &parts {
        for e in p {
            e.add_to_dense(&mut k);
        }
    }
    let flat = |st: &ModelState| -> (Vec<f64>, usize) {
        let mut l = m.load_buffers();
        m.compute_loads(st, 1.0, &mut l);
        let closed = l
            .iter()
            .flat_map(|w| &w.contacts)
            .filter(|c| c.state != strand_fine::ContactState::Open)
            .count();
        (
            l.iter()
                .flat_map(|w| {
                    w.forces
                        .iter()
                        .zip(&w.torques)
                        .flat_map(|(f, t)| [f.x, f.y, f.z, t.x, t.y, t.z])
                        .collect::<Vec<_>>()
                })
                .collect(),
            closed,
        )
    };
    let (f0, c0) = flat(&state);
    let v: Vec<f64> = (0..n)
        .map(|i| {
            let h = if i % 6 < 3 { 1.0 } else { 30.0 };
            h * (0.7 * i as f64).sin()
        })
        .collect();
    let kv = &k * DVector::from_vec(v.clone());
    for a in [1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7] {
        let mut st = state.clone();
        let mut g = 0;
        for w in &mut st.wires {
            for p in &mut w.poses {
                for dof in 0..6 {
                    strand_fine::joint::perturb(p, dof, a * v[6 * g + dof]);
                }
                g += 1;
            }
        }
        let (f1, c1) = flat(&st);
        let (mut worst, mut scale, mut at) = (0.0f64, 0.0f64, 0);
        for i in 0..n {
            let d = -(f1[i] - f0[i]);
            let e = (a * kv[i] - d).abs();
            if e > worst {
                worst = e;
                at = i;
            }
            scale = scale.max((a * kv[i]).abs());
        }
        println!(
            "a {a:.0e}: largest |K a v| {scale:.3e}, largest error {worst:.3e} ({:.2e}) at \
             dof {at} (segment {}), closed {c0} -> {c1}",
            worst / scale,
            at / 6
        );
    }
}

/// The stick stiffness per unit length of the crossings does not depend on the mesh: on the
/// 1+6+12 strand (0.6 m) at segments of 15.3 to 2.6 mm (the crossings 13.5 mm apart along an
/// outer wire), the tangential stiffnesses of the links holding a crossing at rest sum, per
/// unit length of the outer wires, to the closed form: the layer's stick stiffness per unit
/// length `k' = E_w A_w (sin(alpha) / R)^2 / stick_loss` times the crossings' spacing along
/// the wire `s = 1 / (m_b (1/P_a + 1/P_b) cos(alpha_a))` for each crossing of the lay phases
/// (each crossing stands for `s` of wire); likewise the normal stiffness with the interface's
/// penalty per unit length (`penalty::normal_stiffness_per_length`). With a crossing
/// standing for the shorter of the segment and the spacing, the sum fell with the segment
/// length (to 0.19 of the closed form at 2.6 mm) and the all-stick stiffness kept falling
/// with refinement.
#[test]
fn crossing_stiffness_per_length_does_not_depend_on_the_mesh() {
    let length = 0.6;
    let s = strand_1x19(length, false);
    let options = ContactOptions::default();
    let (outer, inner) = (&s.layers()[1], &s.layers()[0]);
    let (alpha, wire) = (outer.lay_angle(), &outer.spec.wire);
    let ea = wire.material.youngs_modulus * wire.area();
    let k_t = ea * (alpha.sin() / outer.radius).powi(2) / options.stick_loss;
    let k_n = strand_fine::penalty::normal_stiffness_per_length(&s, 1e-2)[1].unwrap();
    let spacing =
        1.0 / (inner.wires() as f64 * (1.0 / outer.pitch + 1.0 / inner.pitch) * alpha.cos());
    let crossings: usize = (0..outer.wires())
        .map(|i| interlayer::geometric_crossings(outer, i, inner, 0.0, s.length()))
        .sum();
    let wire_length = outer.wires() as f64 * length / alpha.cos();
    let delta = options.penetration * wire.diameter;
    for n in [40, 60, 120, 240] {
        let m = model(&s, n, &options);
        let state = m.rest_state();
        let (mut count, mut sum_t, mut sum_n) = (0, 0.0, 0.0);
        for (w, aps) in m.wires.iter().zip(m.link_approaches(&state)) {
            for (lk, ap) in w.links.iter().zip(aps) {
                if lk.kind == LinkKind::Crossing && ap.is_some_and(|ap| ap.gap(lk) < delta) {
                    count += 1;
                    sum_t += lk.law.tangential_stiffness;
                    sum_n += lk.law.normal_stiffness;
                }
            }
        }
        let (per_t, per_n) = (sum_t / wire_length, sum_n / wire_length);
        let exact = crossings as f64 * spacing / wire_length;
        println!(
            "{n} segments ({:.2e} m): {count} crossings, stick {:.6} k', normal {:.6} k_n per \
             unit length (closed form {exact:.6})",
            length / n as f64 / alpha.cos(),
            per_t / k_t,
            per_n / k_n
        );
        assert_eq!(count, crossings, "{n} segments");
        assert!(
            (per_t / (k_t * exact) - 1.0).abs() < 1e-9,
            "{n}: stick {per_t:e}"
        );
        assert!(
            (per_n / (k_n * exact) - 1.0).abs() < 1e-9,
            "{n}: normal {per_n:e}"
        );
    }
}

/// The bending test holds the axial force of a strand of several layers at the tension: the
/// frictionless 1+6+12 strand at T = 0.01 N (3 outer pitches of 12 segments, one arc at
/// 0.1 1/m). The test moves its end plate until the axial force over its window is T; the
/// clamp's reaction (`BendingPoint::tension`, the anchors' forces at x = 0) is an independent
/// reading of the same force through another section:
///
/// * straight, the axial force is the same through every section: the clamp's reading is T
///   within the correction's tolerance plus the spread of the axial force over every cut of
///   the core's joints (what the equilibrium's residual leaves; 1.6e-5 T). Measured 5.4e-7 T
///   off;
/// * bent, a rod on an arc of curvature kappa under normal loads only has dN/ds = kappa Q and
///   dM/ds = -Q, so N + kappa M is the same along it: the clamp's N_c = T + kappa (M_w - M_c)
///   with M_w the window's moment and M_c the clamp's. The core's curvature varies by
///   +-2.5 % along the strand (the inner layer's pitch), so the relation holds within 5 % of
///   kappa |M_w - M_c|, the allowance with the tolerance. Measured: 1.3 % of it (5.9e-7 N).
///
/// Before the test held the tension (the plate at T / EA_eq) the clamp read 0.98649 T
/// straight (failing) and 371 T bent (checked once).
#[test]
fn the_axial_force_of_several_layers_is_held_at_the_tension() {
    let mut spec = strand_1x19(1.0, false).spec().clone();
    spec.friction = 0.0;
    let s = Strand::new(spec).unwrap();
    let (tension, kappa) = (0.01, 0.1);
    let test = BendingTest::frictionless(3, 12, tension, kappa);
    let mut spread = Vec::new();
    let (curve, _, _) = test
        .run_observed(&s, &mut |_, m, state| {
            let n: Vec<f64> = BendingTest::axial_profile(m, state)
                .iter()
                .map(|p| p.1)
                .collect();
            let (lo, hi) = n
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            spread.push(hi - lo);
        })
        .expect("bending test");
    let (straight, bent) = (&curve[0], &curve[1]);
    for p in [straight, bent] {
        println!("window axial force {:.9e} N", p.axial_force);
        assert!(
            (p.axial_force - tension).abs() <= AXIAL_TOLERANCE * tension,
            "window axial force {} N",
            p.axial_force
        );
    }
    let allowance = AXIAL_TOLERANCE * tension + spread[0];
    println!(
        "straight: clamp {:.9e} N, T {tension} N (allowance {allowance:.2e} N), plate strain \
         {:.6e} (T / EA_eq {:.6e})",
        straight.tension,
        straight.strain,
        tension / s.axial_stiffness()
    );
    assert!(
        (straight.tension - tension).abs() <= allowance,
        "straight: clamp {} N",
        straight.tension
    );
    let predicted = tension + kappa * (bent.moment - bent.clamp_moment);
    let allowance =
        AXIAL_TOLERANCE * tension + 0.05 * kappa * (bent.moment - bent.clamp_moment).abs();
    println!(
        "bent: clamp {:.9e} N, T + kappa (M_w - M_c) {predicted:.9e} N: {:.2e} N off (allowance \
         {allowance:.2e} N)",
        bent.tension,
        bent.tension - predicted
    );
    assert!(
        (bent.tension - predicted).abs() <= allowance,
        "bent: clamp {} N against {predicted} N",
        bent.tension
    );
}
