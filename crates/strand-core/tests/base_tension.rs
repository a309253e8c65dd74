//! K_min under tension (`section.base_tension`, `strand_core::section::base_tension`): the
//! law's tabulated stiffness against the thin-rod energy of the stretched helix evaluated
//! directly (`strand_core::stretched_bending`), its strain derivative against differences of
//! the law's own moment, and the default law unchanged.

use strand_core::section::base_tension::{NODES, RATIO_FLOOR, STRAIN_MAX, SofteningTable};
use strand_core::stretched_bending::layer_stiffness;
use strand_core::{
    BaseStiffness, BaseTension, LawKind, LayDirection, LayerSpec, Material, SectionLaw,
    SectionOptions, Strand, StrandSpec, WireSpec,
};

fn soft(nu: f64) -> Material {
    Material {
        youngs_modulus: 5e7,
        poisson_ratio: nu,
        density: 7800.0,
    }
}

/// Core 2.2 mm and six wires of diameter `wire` (m), Poisson ratio `nu`, at `deg` (the
/// `validation/vs-fine-30deg.json` strand at 30 deg, 1.5 mm, 0.3).
fn one_layer(deg: f64, wire: f64, nu: f64) -> Strand {
    let mut spec = StrandSpec::paper(0.05, 5e7, 7800.0);
    spec.core = WireSpec {
        diameter: 2.2e-3,
        material: soft(0.3),
    };
    spec.layers[0].wire.diameter = wire;
    spec.layers[0].wire.material.poisson_ratio = nu;
    spec.layers[0].lay_angle = deg.to_radians();
    spec.friction = 0.0;
    Strand::new(spec).unwrap()
}

/// The 1+6+12 geometry of `examples/steel-1x19-swing.json` in the soft material, layers at
/// `inner` (right) and `outer` (left) deg, friction 0.3.
fn two_layers(inner: f64, outer: f64) -> Strand {
    let layer = |wires, deg: f64, direction| LayerSpec {
        wires,
        wire: WireSpec {
            diameter: 3.0e-3,
            material: soft(0.3),
        },
        lay_angle: deg.to_radians(),
        phase: 0.0,
        direction,
    };
    Strand::new(StrandSpec {
        length: 1.0,
        core: WireSpec {
            diameter: 3.3e-3,
            material: soft(0.3),
        },
        layers: vec![
            layer(6, inner, LayDirection::Right),
            layer(12, outer, LayDirection::Left),
        ],
        friction: 0.3,
    })
    .unwrap()
}

fn thin_rod() -> SectionOptions {
    SectionOptions {
        base_tension: BaseTension::ThinRod,
        ..Default::default()
    }
}

/// The thin-rod ratio evaluated directly: K_j(eps) / ((1 + eps) K_j(0)).
fn direct_ratio(s: &Strand, j: usize, eps: f64) -> f64 {
    let l = &s.layers()[j];
    layer_stiffness(l, eps) / ((1.0 + eps) * layer_stiffness(l, 0.0))
}

/// Tolerance of the table against the direct value, relative to the layer's K: 1e-6, the
/// thin-rod value's own error (its second difference in the curvature errs by up to 1e-8
/// (R / r_w)^2, R / r_w up to 10 on usual layers): the table is to add no error larger than
/// what it tabulates.
const TABLE_TOLERANCE: f64 = 1e-6;

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    /// The law's K_min of one layer at any strain in its table and any lay angle, Poisson
    /// ratio and wire size: the core's E_c I_c plus Costello's layer share times the thin-rod
    /// ratio, within `TABLE_TOLERANCE` of the layer's K of the ratio evaluated directly; and
    /// the core plus the thin-rod layer value per unit rest curvature, K_j(eps) / (1 + eps),
    /// within that plus Costello's own agreement with the thin-rod value at zero strain (1e-5,
    /// `tests/stretched_bending.rs`). With the table at 11 nodes instead of 81 it fails
    /// (the interpolation error grows 4096 times).
    #[test]
    fn table_follows_the_thin_rod_energy(
        deg in 2.0f64..40.0,
        share in 0.0f64..1.0,
        nu in 0.0f64..0.45,
        wire_mm in 0.5f64..1.2,
    ) {
        let s = one_layer(deg, wire_mm * 1e-3, nu);
        let end = SofteningTable::new(&s.layers()[0]).end_strain();
        let eps = share * end;
        let law = SectionLaw::with_options(&s, LawKind::Continuous, &thin_rod());
        let core = s.core().material.youngs_modulus * s.core().inertia();
        let kj = s.layer_min_bending(&s.layers()[0], BaseStiffness::Costello);
        let (k, _) = law.base_bending_at(eps);
        let ratio = (k - core) / kj;
        let direct = direct_ratio(&s, 0, eps);
        proptest::prop_assert!(
            (ratio - direct).abs() < TABLE_TOLERANCE,
            "{} deg, eps {}: table {} direct {}", deg, eps, ratio, direct
        );
        let thin = core + layer_stiffness(&s.layers()[0], eps) / (1.0 + eps);
        proptest::prop_assert!(
            (k - thin).abs() < (TABLE_TOLERANCE + 1e-5) * kj,
            "{} deg, eps {}: law {} thin-rod {}", deg, eps, k, thin
        );
    }
}

/// The table's interpolation error against the thin-rod value evaluated directly, at the
/// midpoints between nodes (where a cubic Hermite interpolant errs most), on the
/// `vs-fine-30deg` layer and on both layers of the soft 1+6+12 strand: below
/// `TABLE_TOLERANCE` at the table's [`NODES`]. Measured at 6, 11, 21, 41 nodes: 1e-7 at 6,
/// then the noise of the direct value itself (a few 1e-9: its minimisation over migration and
/// spin by Newton on difference gradients). With the node slopes set to zero (a mutation of
/// the table) the check fails.
#[test]
fn table_error_is_below_the_thin_rod_values_own() {
    let strands = [one_layer(30.0, 1.5e-3, 0.3), two_layers(8.0, 12.0)];
    for s in &strands {
        for (j, l) in s.layers().iter().enumerate() {
            let errors: Vec<f64> = [6, 11, NODES, 41]
                .iter()
                .map(|&nodes| {
                    let t = SofteningTable::with_nodes(l, nodes);
                    let h = t.end_strain() / (nodes - 1) as f64;
                    (0..nodes - 1)
                        .step_by((nodes / 10).max(1))
                        .map(|i| {
                            let eps = (i as f64 + 0.5) * h;
                            (t.ratio(eps).0 - direct_ratio(s, j, eps)).abs()
                        })
                        .fold(0.0, f64::max)
                })
                .collect();
            println!(
                "layer {} at {:.1} deg: largest error at 6, 11, {NODES}, 41 nodes {}",
                j + 1,
                l.lay_angle().to_degrees(),
                errors
                    .iter()
                    .map(|e| format!("{e:.2e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
            assert!(errors[2] < TABLE_TOLERANCE, "{errors:?}");
        }
    }
}

/// What the solvers read: `dM/deps` and `dM/dkappa` of the planar and vector laws are the
/// central differences of their moments, and the base part of `energy_strain` (the law's
/// less the tension-free law's: the wires' parts are the same) is the strain derivative of
/// the stored energies' difference, `(K_min(eps) - K_min(0)) kappa^2 / 2`, on the soft 1+6+12
/// strand with both stick/slip laws at strains inside both layers' tables. Tolerance 1e-6 of
/// the scale: the differences' truncation (h = 1e-8 in eps against table steps of 3e-5, so
/// O((h / step)^2) of the slope) and round-off (1e-16 / 1e-8 of the moment) are far below.
/// The derivative of the table is the interpolant's own; with the law's `dM/deps` taken from
/// the node slopes scaled by 1.01 (a mutation) the check fails.
#[test]
fn strain_derivatives_are_those_of_the_moment() {
    let s = two_layers(8.0, 12.0);
    let ends: Vec<f64> = s
        .layers()
        .iter()
        .map(|l| SofteningTable::new(l).end_strain())
        .collect();
    println!("table ends {ends:?}");
    for kind in [LawKind::Continuous, LawKind::Hysteretic] {
        let law = SectionLaw::with_options(&s, kind, &thin_rod());
        let fixed = SectionLaw::new(&s, kind);
        let slip = vec![0.0; law.state_len()];
        let mut trial = slip.clone();
        for (x, eps, kappa) in [
            (0.013, 1e-4, 0.5),
            (0.2, 3.3e-4, -2.0),
            (0.31, 5.2e-4, 0.05),
        ] {
            assert!(ends.iter().all(|e| eps < *e), "{eps} inside the tables");
            let st = law.station(x);
            let h = 1e-8;
            let mut at = |l: &SectionLaw, e: f64, k: f64| l.planar(&st, e, k, &slip, &mut trial);
            let r = at(&law, eps, kappa);
            let r0 = at(&fixed, eps, kappa);
            let (p, m) = (at(&law, eps + h, kappa), at(&law, eps - h, kappa));
            let (p0, m0) = (at(&fixed, eps + h, kappa), at(&fixed, eps - h, kappa));
            let dm = (p.moment - m.moment) / (2.0 * h);
            let de = ((p.energy - p0.energy) - (m.energy - m0.energy)) / (2.0 * h);
            let (pk, mk) = (at(&law, eps, kappa + h), at(&law, eps, kappa - h));
            let dk = (pk.moment - mk.moment) / (2.0 * h);
            let scale = law.base_bending_stiffness() * kappa.abs() * 100.0;
            let base_strain = r.energy_strain - r0.energy_strain;
            println!(
                "{kind} eps {eps:.1e} kappa {kappa}: dM/deps {:.6e} (diff {dm:.6e}), base \
                 energy_strain {base_strain:.6e} (diff {de:.6e}), {} slipping",
                r.moment_strain, r.slipping
            );
            assert!((r.moment_strain - dm).abs() < 1e-6 * scale, "{dm}");
            assert!(
                (base_strain - de).abs() < 1e-6 * scale * kappa.abs(),
                "{de}"
            );
            assert!(
                (r.moment_curvature - dk).abs() < 1e-6 * r.moment_curvature,
                "{dk}"
            );
            // The vector law in the plane of bending reads the same (summed in another
            // order: to round-off).
            let v = law.vector(&st, eps, [0.0, kappa], &slip, &mut trial);
            assert!((v.moment_strain[1] - r.moment_strain).abs() < 1e-12 * scale);
            assert!((v.energy_strain - r.energy_strain).abs() < 1e-12 * scale * kappa.abs());
            // Out of the plane the base stiffness acts on kappa_y alike.
            let vy = |e: f64| law.vector(&st, e, [kappa, 0.0], &slip, &mut trial.clone());
            let dmy = (vy(eps + h).moment[0] - vy(eps - h).moment[0]) / (2.0 * h);
            assert!((vy(eps).moment_strain[0] - dmy).abs() < 1e-6 * scale);
        }
    }
}

/// The default law (`base_tension` `fixed`) reads no strain in K_min: the base part of the
/// moment is `K_min kappa` with the tension-free K_min at every strain, `dM/deps` of a law
/// without wires zero; and the thin-rod law at zero or negative strain is that law bit for
/// bit (the table's ratio is exactly 1 there).
#[test]
fn fixed_is_the_tension_free_law_and_thin_rod_meets_it_at_zero_strain() {
    let s = two_layers(8.0, 12.0);
    let fixed = SectionLaw::new(&s, LawKind::Hysteretic);
    let soft = SectionLaw::with_options(&s, LawKind::Hysteretic, &thin_rod());
    let k0 = s.min_bending_stiffness(BaseStiffness::Costello);
    for eps in [-1e-3, 0.0, 1e-3, 1e-2] {
        assert_eq!(fixed.base_bending_at(eps), (k0, 0.0));
        assert_eq!(fixed.planar_linear(eps, 0.3).moment, k0 * 0.3);
    }
    let slip = vec![0.0; fixed.state_len()];
    let st = fixed.station(0.07);
    for eps in [-1e-3, 0.0] {
        let a = fixed.planar(&st, eps, 0.4, &slip, &mut slip.clone());
        let b = soft.planar(&st, eps, 0.4, &slip, &mut slip.clone());
        assert_eq!(a, b, "eps {eps}");
    }
    // Under tension the thin-rod law is softer, and beyond the table it holds its end value.
    let (k1, _) = soft.base_bending_at(1e-4);
    assert!(k1 < k0);
    assert_eq!(
        soft.base_bending_at(STRAIN_MAX),
        (soft.base_bending_at(2.0 * STRAIN_MAX).0, 0.0)
    );
}

/// The law follows the thin-rod ratio down to `RATIO_FLOOR` and holds it beyond (module docs,
/// "Where it applies"): on layers at 2 to 35 deg the table ends where the directly evaluated
/// ratio is the floor (to the bisection's 1e-6 of the strain, 1e-5 in the ratio), or at
/// `STRAIN_MAX` with the ratio above it; the law never reads a ratio below the floor.
#[test]
fn the_law_holds_the_floor_beyond_the_table() {
    for deg in [2.0, 5.0, 10.0, 20.0, 30.0, 35.0] {
        let s = one_layer(deg, 1.5e-3, 0.3);
        let t = SofteningTable::new(&s.layers()[0]);
        let end = t.end_strain();
        let at_end = direct_ratio(&s, 0, end);
        println!("{deg} deg: table to strain {end:.3e}, ratio there {at_end:.6}");
        if end < STRAIN_MAX {
            assert!((at_end - RATIO_FLOOR).abs() < 1e-5, "{at_end}");
        } else {
            assert!(at_end >= RATIO_FLOOR);
        }
        for f in [0.5, 0.99, 1.0, 1.5, 10.0] {
            let (r, d) = t.ratio(f * end);
            assert!(r >= RATIO_FLOOR - 1e-5, "{deg} deg at {f} of the end: {r}");
            if f > 1.0 {
                assert_eq!((r, d), (t.ratio(end).0, 0.0));
            }
        }
    }
}
