//! The bonded-strand rod model (`strand_core::bonded`) against independent closed forms: with
//! the wires free to slide it is Costello's frictionless stiffness; with the bond on the
//! wires' axes and a shear-rigid core it is that plus the plane-section stick stiffness; a
//! nearly straight layer delivers the whole plane-section stiffness. The section laws'
//! `bonded` stick stiffness takes the model's stick factor on each wire's spring.

use proptest::prelude::*;
use strand_core::bonded::{strand_bonded_stiffness, strand_layer_stick_stiffness};
use strand_core::{
    BondedOptions, LawKind, LayDirection, LayerSpec, Material, SectionLaw, SectionOptions,
    StickStiffness, Strand, StrandSpec, WireSpec, bonded_stiffness,
};

/// A 1+m strand (m >= 3) with its own core and wire materials.
#[allow(clippy::too_many_arguments)]
fn strand(
    dc: f64,
    ec: f64,
    nuc: f64,
    m: usize,
    dw: f64,
    ew: f64,
    nuw: f64,
    alpha_deg: f64,
) -> Option<Strand> {
    let mat = |e: f64, nu: f64| Material {
        youngs_modulus: e,
        poisson_ratio: nu,
        density: 7800.0,
    };
    Strand::new(StrandSpec {
        length: 0.3,
        core: WireSpec {
            diameter: dc,
            material: mat(ec, nuc),
        },
        layers: vec![LayerSpec {
            wires: m,
            wire: WireSpec {
                diameter: dw,
                material: mat(ew, nuw),
            },
            lay_angle: alpha_deg.to_radians(),
            phase: 0.0,
            direction: LayDirection::Right,
        }],
        friction: 0.3,
    })
    .ok()
}

fn random_strand() -> impl Strategy<Value = Strand> {
    (
        (0.5e-3..5e-3f64, 7.0..11.5f64, 0.0..0.5f64, 3usize..=9),
        (0.2..1.5f64, 0.3..3.0f64, 0.0..0.5f64, 2.0..40.0f64),
    )
        .prop_filter_map(
            "overlapping layer",
            |((dc, loge, nuc, m), (ratio, eratio, nuw, alpha))| {
                let e = 10f64.powf(loge);
                strand(dc, e, nuc, m, dc * ratio, e * eratio, nuw, alpha)
            },
        )
}

/// Costello's frictionless bending stiffness E_c I_c + m E_w I_w cos(alpha) 2 / (2 + nu_w
/// sin^2(alpha)) (thin rods with the helix's torsion; independent of the rod model's
/// Fourier solution).
fn costello(s: &Strand) -> f64 {
    let l = s.layers().first().unwrap();
    let w = &l.spec.wire;
    let (a, nu) = (l.lay_angle(), w.material.poisson_ratio);
    s.core().material.youngs_modulus * s.core().inertia()
        + l.wires() as f64 * w.material.youngs_modulus * w.inertia() * a.cos() * 2.0
            / (2.0 + nu * a.sin().powi(2))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Wires free to slide on the core: Costello's stiffness, to round-off.
    #[test]
    fn free_wires_give_costellos_stiffness(s in random_strand()) {
        let b = bonded_stiffness(&s, &BondedOptions::default()).unwrap();
        let c = costello(&s);
        prop_assert!((b.free / c - 1.0).abs() < 1e-9, "free {} Costello {}", b.free, c);
    }

    /// Bond on the wires' axes, shear-rigid core, rigid contacts: no eccentric traction on
    /// the wires and no tilt of the core, so the wires' axes follow the plane section and the
    /// bond adds the plane-section stick stiffness (m/2) eta E_w A_w R_w^2. Exactly so for
    /// wires without bending and torsion stiffness (their sections then turn freely); with
    /// them, the wires' bending energy differs from the free (sliding) wires' by a few per
    /// cent of itself (their axes are held, not free to slide).
    #[test]
    fn bond_on_the_axes_of_rigid_sections_gives_the_plane_section_stiffness(
        s in random_strand(),
    ) {
        let r = s.layers().first().unwrap().radius;
        let on_axes = BondedOptions {
            contact_radius: Some(r),
            core_shear: 1e12,
            ..Default::default()
        };
        let b = bonded_stiffness(&s, &on_axes).unwrap();
        let core = s.core().material.youngs_modulus * s.core().inertia();
        let wires = b.free - core;
        let dev = (b.bonded - b.free - b.plane_section_stick) / wires;
        prop_assert!(dev.abs() < 0.1, "bonded {} free {} stick {}", b.bonded, b.free, b.plane_section_stick);
        let limp = BondedOptions {
            wire_bending: 1e-9,
            wire_torsion: 1e-9,
            ..on_axes
        };
        let b = bonded_stiffness(&s, &limp).unwrap();
        let expected = core + b.plane_section_stick;
        prop_assert!(
            (b.bonded / expected - 1.0).abs() < 1e-6,
            "bonded {} expected {}", b.bonded, expected
        );
    }

    /// The physical bond is softer than the plane section (the eccentric traction only
    /// relaxes the wires), and stiffening the wires' and the core's shear, or the contacts,
    /// stiffens it.
    #[test]
    fn compliances_soften_the_bond(s in random_strand()) {
        let base = bonded_stiffness(&s, &BondedOptions::default()).unwrap();
        prop_assert!(base.stick_factor() > 0.0 && base.stick_factor() < 1.0);
        for o in [
            BondedOptions { core_shear: 10.0, ..Default::default() },
            BondedOptions { wire_shear: 10.0, ..Default::default() },
        ] {
            prop_assert!(bonded_stiffness(&s, &o).unwrap().bonded > base.bonded);
        }
        let k = base.plane_section_stick / s.layers().first().unwrap().radius.powi(2);
        let springs = BondedOptions {
            tangential_stiffness: Some(k),
            normal_stiffness: Some(k),
            ..Default::default()
        };
        prop_assert!(bonded_stiffness(&s, &springs).unwrap().bonded < base.bonded);
    }
}

/// A nearly straight layer (lay angle 0.5 deg) carries no varying wire force: the bond
/// delivers the plane-section stiffness to within (k r)^2, k = sin(alpha) / R_w.
#[test]
fn straight_wires_bond_fully() {
    let s = strand(3e-3, 2e8, 0.3, 6, 2e-3, 2e8, 0.3, 0.5).unwrap();
    let b = bonded_stiffness(&s, &BondedOptions::default()).unwrap();
    assert!(
        (b.stick_factor() - 1.0).abs() < 1e-3,
        "{}",
        b.stick_factor()
    );
}

/// Fewer than three wires: the core also sees the second harmonic, which the model leaves
/// out, so it declines unless the core's sections cannot tilt; a rigid core's tilt is the
/// same for six wires whether imposed as a constraint or as a very stiff spring.
#[test]
fn two_wires_need_a_shear_rigid_core() {
    let s = strand(3e-3, 2e8, 0.3, 2, 2e-3, 2e8, 0.3, 20.0).unwrap();
    assert!(bonded_stiffness(&s, &BondedOptions::default()).is_none());
    let rigid = BondedOptions {
        core_shear: f64::INFINITY,
        ..Default::default()
    };
    let b = bonded_stiffness(&s, &rigid).unwrap();
    assert!(b.stick_factor() > 0.0 && b.stick_factor() < 1.0);
    let s = strand(3e-3, 2e8, 0.3, 6, 2e-3, 2e8, 0.3, 20.0).unwrap();
    let stiff = BondedOptions {
        core_shear: 1e12,
        ..Default::default()
    };
    let (a, b) = (
        bonded_stiffness(&s, &rigid).unwrap().bonded,
        bonded_stiffness(&s, &stiff).unwrap().bonded,
    );
    assert!((a / b - 1.0).abs() < 1e-9, "{a} {b}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The section laws' stick stiffness: `bonded` scales each wire's plane-section spring by
    /// the rod model's stick factor (rigid bond on the touching surfaces), `plane_section` by
    /// 1. The law's all-stick secant, averaged over a pitch at a curvature far below the first
    /// slip, is K_min plus the factor times (m/2) eta E_w A_w R_w^2 (written out here), and the
    /// friction limit is unchanged: far beyond the last slip both forms give the same moment.
    #[test]
    fn the_stick_factor_scales_the_wires_springs_only(s in random_strand()) {
        let l = *s.layers().first().unwrap();
        let w = &l.spec.wire;
        let plane = 0.5 * l.wires() as f64 * l.eta * w.material.youngs_modulus * w.area()
            * l.radius * l.radius;
        let rod = bonded_stiffness(&s, &BondedOptions::default()).unwrap();
        prop_assert_eq!(StickStiffness::Bonded.factor(&s, 0), rod.stick_factor());
        prop_assert_eq!(StickStiffness::PlaneSection.factor(&s, 0), 1.0);
        let eps = 1e-3;
        let mean_moment = |law: &SectionLaw, kappa: f64| {
            let n = 64;
            (0..n)
                .map(|i| {
                    let st = law.station(l.pitch * (i as f64 + 0.5) / n as f64);
                    law.planar(&st, eps, kappa, &[], &mut []).moment
                })
                .sum::<f64>()
                / n as f64
        };
        for stick in StickStiffness::ALL {
            let options = SectionOptions { stick_stiffness: stick, ..Default::default() };
            let law = SectionLaw::with_options(&s, LawKind::Continuous, &options);
            let k_min = law.base_bending_stiffness();
            let want = k_min + stick.factor(&s, 0) * plane;
            prop_assert!((law.stick_bending_stiffness() - want).abs() <= 1e-12 * want);
            // Below the first slip (the smallest limit is mu sin(alpha) eta E A cos^2 eps
            // times the lever angle near the neutral axis; 1e-12 1/m is far below it).
            let kappa = 1e-12;
            let secant = mean_moment(&law, kappa) / kappa;
            prop_assert!((secant - want).abs() <= 1e-9 * want, "{} vs {}", secant, want);
        }
        let [bonded, plane_law] = [StickStiffness::Bonded, StickStiffness::PlaneSection].map(|stick| {
            let options = SectionOptions { stick_stiffness: stick, ..Default::default() };
            SectionLaw::with_options(&s, LawKind::Continuous, &options)
        });
        // Where every wire slips in both forms, the moments agree (the wires' part to
        // round-off).
        let kappa = 1e3;
        let mut slipping = 0;
        for i in 0..64 {
            let st = bonded.station(l.pitch * (i as f64 + 0.5) / 64.0);
            let a = bonded.planar(&st, eps, kappa, &[], &mut []);
            let b = plane_law.planar(&st, eps, kappa, &[], &mut []);
            if a.slipping == l.wires() && b.slipping == l.wires() {
                slipping += 1;
                let wires = a.moment - bonded.base_bending_stiffness() * kappa;
                prop_assert!(
                    (a.moment - b.moment).abs() <= 1e-9 * wires.abs(),
                    "{} vs {}", a.moment, b.moment
                );
            }
        }
        prop_assert!(slipping > 0);
    }
}

/// A strand of two layers (each m >= 3) of its own materials, lay angles and directions.
fn two_layers(
    (dc, ec, m1, d1, e1, a1): (f64, f64, usize, f64, f64, f64),
    (m2, d2, e2, a2): (usize, f64, f64, f64),
    (right1, right2): (bool, bool),
) -> Option<Strand> {
    let mat = |e: f64, nu: f64| Material {
        youngs_modulus: e,
        poisson_ratio: nu,
        density: 7800.0,
    };
    let dir = |r: bool| {
        if r {
            LayDirection::Right
        } else {
            LayDirection::Left
        }
    };
    let layer = |m: usize, d: f64, e: f64, nu: f64, a: f64, right: bool| LayerSpec {
        wires: m,
        wire: WireSpec {
            diameter: d,
            material: mat(e, nu),
        },
        lay_angle: a.to_radians(),
        phase: 0.0,
        direction: dir(right),
    };
    Strand::new(StrandSpec {
        length: 0.3,
        core: WireSpec {
            diameter: dc,
            material: mat(ec, 0.3),
        },
        layers: vec![
            layer(m1, d1, e1, 0.28, a1, right1),
            layer(m2, d2, e2, 0.33, a2, right2),
        ],
        friction: 0.3,
    })
    .ok()
}

fn random_two_layers() -> impl Strategy<Value = Strand> {
    (
        (1e-3..4e-3f64, 3usize..=8, 0.6..1.2f64, 3.0..25.0f64),
        (
            0.6..1.2f64,
            3.0..25.0f64,
            0.3..3.0f64,
            any::<(bool, bool)>(),
        ),
    )
        .prop_filter_map(
            "overlapping layer",
            |((dc, m1, r1, a1), (r2, a2, er, dirs))| {
                let (d1, d2) = (dc * r1, dc * r1 * r2);
                // The outer layer closed or nearly so: as many wires as fit on its radius.
                let radius = 0.5 * dc + d1 + 0.5 * d2;
                let m2 =
                    ((std::f64::consts::PI / (0.5 * d2 / radius).asin()).floor() as usize).max(3);
                two_layers(
                    (dc, 2e11, m1, d1, 2e11 * er, a1),
                    (m2, d2, 2e11 / er, a2),
                    dirs,
                )
            },
        )
}

/// Costello's frictionless stiffness of every layer and the core, summed.
fn costello_sum(s: &Strand) -> f64 {
    s.layers().iter().fold(
        s.core().material.youngs_modulus * s.core().inertia(),
        |sum, l| {
            let w = &l.spec.wire;
            let (a, nu) = (l.lay_angle(), w.material.poisson_ratio);
            sum + l.wires() as f64 * w.material.youngs_modulus * w.inertia() * a.cos() * 2.0
                / (2.0 + nu * a.sin().powi(2))
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The whole strand as one body (`strand_bonded_stiffness`): with every wire free to
    /// slide on what lies beneath it, the sum of Costello's stiffnesses of the layers and the
    /// core's E I, to round-off; the mirror image of the strand (every lay direction
    /// reversed) has the same stiffness, bonded and free; the bond lies between the free
    /// strand and the plane-section bound of rigid-section wires (the energy of the plane
    /// section's own field, here taken as K_max plus the wires' share of the free stiffness,
    /// which bounds it from above only loosely: the bonded value must stay below K_max plus
    /// the whole of K_min).
    #[test]
    fn the_strand_as_one_body_is_costello_when_free_and_mirror_symmetric(s in random_two_layers()) {
        let o = BondedOptions::default();
        let b = strand_bonded_stiffness(&s, &o).unwrap();
        let c = costello_sum(&s);
        prop_assert!((b.free / c - 1.0).abs() < 1e-9, "free {} Costello {}", b.free, c);
        let mut spec = s.spec().clone();
        for l in &mut spec.layers {
            l.direction = match l.direction {
                LayDirection::Right => LayDirection::Left,
                LayDirection::Left => LayDirection::Right,
            };
        }
        let mirror = strand_bonded_stiffness(&Strand::new(spec).unwrap(), &o).unwrap();
        prop_assert!((mirror.bonded / b.bonded - 1.0).abs() < 1e-9, "{} {}", mirror.bonded, b.bonded);
        prop_assert!(b.bonded > b.free);
        prop_assert!(b.bonded < b.free + b.plane_section_stick + c);
    }

    /// One layer: the strand as one body is the one-interface model (`bonded_stiffness`).
    #[test]
    fn one_layer_as_one_body_is_the_interface_model(s in random_strand()) {
        for o in [
            BondedOptions::default(),
            BondedOptions { wire_torsion: 10.0, core_shear: 3.0, ..Default::default() },
        ] {
            let a = bonded_stiffness(&s, &o).unwrap();
            let b = strand_bonded_stiffness(&s, &o).unwrap();
            prop_assert!((a.bonded / b.bonded - 1.0).abs() < 1e-9, "{} {}", a.bonded, b.bonded);
            prop_assert!((a.free / b.free - 1.0).abs() < 1e-9, "{} {}", a.free, b.free);
        }
    }
}

/// Nearly straight layers, either direction: the bond delivers the plane-section stiffness
/// of both layers as the lay angles tend to zero, the deficit 1 - stick factor falling as
/// alpha^2 (the plane section's mismatch with a helix, and so every source term of the rod
/// equations, is first order in sin(alpha); the energy it releases second order).
#[test]
fn straight_layers_bond_fully_as_one_body() {
    for dirs in [(true, true), (true, false), (false, true), (false, false)] {
        let deficit = |a: f64| {
            let s = two_layers((3e-3, 2e11, 6, 3e-3, 2e11, a), (12, 3e-3, 2e11, a), dirs).unwrap();
            1.0 - strand_bonded_stiffness(&s, &BondedOptions::default())
                .unwrap()
                .stick_factor()
        };
        let (d1, d2) = (deficit(0.2), deficit(0.1));
        assert!(d2 > 0.0 && d2 < 1e-3, "{dirs:?}: {d2}");
        assert!((d2 / d1 - 0.25).abs() < 0.01, "{dirs:?}: {d1} {d2}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The one-body stick stiffness in the section law (`section.stick_stiffness =
    /// one_body`): the layers' shares, each its wires' moment bonded less free, sum to the
    /// one-body stick stiffness `bonded - free` computed from the energy (the shares come
    /// from the moment dU/dkappa, so this is Clapeyron's theorem on the solved field, not an
    /// identity of the code); the law's all-stick stiffness is K_min plus that, and with
    /// Costello's K_min (the default, and the free strand's value) it is the one-body bonded
    /// stiffness itself. Every factor is positive.
    #[test]
    fn one_body_layers_sum_to_the_strand_as_one_body(s in random_two_layers()) {
        let o = BondedOptions::default();
        let b = strand_bonded_stiffness(&s, &o).unwrap();
        let shares = strand_layer_stick_stiffness(&s, &o).unwrap();
        let stick = b.bonded - b.free;
        let sum: f64 = shares.iter().sum();
        prop_assert!((sum / stick - 1.0).abs() < 1e-9, "shares {:?} sum {} vs {}", shares, sum, stick);
        // Each layer's factor is its share over its plane-section value; where a share is
        // not positive (no spring can carry it), the even factor on every layer.
        let plane: Vec<f64> = s.layers().iter().map(|l| s.layer_plane_section_stick(l)).collect();
        let even = shares.iter().any(|&k| k <= 0.0);
        for (j, p) in plane.iter().enumerate() {
            let f = StickStiffness::OneBody.factor(&s, j);
            prop_assert!(f > 0.0, "layer {}: factor {}", j, f);
            let want = if even { stick / plane.iter().sum::<f64>() } else { shares[j] / p };
            prop_assert!((f / want - 1.0).abs() < 1e-12, "layer {}: {} vs {}", j, f, want);
        }
        let options = SectionOptions { stick_stiffness: StickStiffness::OneBody, ..Default::default() };
        let law = SectionLaw::with_options(&s, LawKind::Continuous, &options);
        let k_stick = law.stick_bending_stiffness() - law.base_bending_stiffness();
        prop_assert!((k_stick / stick - 1.0).abs() < 1e-9, "{} vs {}", k_stick, stick);
        prop_assert!((law.stick_bending_stiffness() / b.bonded - 1.0).abs() < 1e-9,
            "{} vs {}", law.stick_bending_stiffness(), b.bonded);
    }

    /// One layer: `one_body` is `bonded`, bit for bit (the law takes the per-interface factor
    /// there), and the one-body share is the one-interface model's `bonded - free` to
    /// round-off.
    #[test]
    fn one_body_on_one_layer_is_bonded(s in random_strand()) {
        prop_assert_eq!(StickStiffness::OneBody.factor(&s, 0), StickStiffness::Bonded.factor(&s, 0));
        let o = BondedOptions::default();
        let a = bonded_stiffness(&s, &o).unwrap();
        let share = strand_layer_stick_stiffness(&s, &o).unwrap()[0];
        prop_assert!((share / (a.bonded - a.free) - 1.0).abs() < 1e-9, "{} vs {}", share, a.bonded - a.free);
    }
}

/// Three layers (1+6+12+18, alternate lays): the shares still sum to the one-body stick
/// stiffness, and nearly straight layers each bond fully (every factor tends to 1 as the
/// lay angles tend to zero, as the one-body stiffness does).
#[test]
fn one_body_shares_on_three_layers() {
    let strand = |alpha: f64| {
        let mut spec = two_layers(
            (3.3e-3, 2e11, 6, 3e-3, 2e11, alpha),
            (12, 3e-3, 2e11, alpha),
            (true, false),
        )
        .unwrap()
        .spec()
        .clone();
        let mut outer = spec.layers[1];
        outer.wires = 18;
        outer.direction = LayDirection::Right;
        spec.layers.push(outer);
        Strand::new(spec).expect("a 1+6+12+18 strand")
    };
    let s = strand(12.0);
    let o = BondedOptions::default();
    let b = strand_bonded_stiffness(&s, &o).unwrap();
    let shares = strand_layer_stick_stiffness(&s, &o).unwrap();
    assert_eq!(shares.len(), 3);
    let sum: f64 = shares.iter().sum();
    assert!(
        (sum / (b.bonded - b.free) - 1.0).abs() < 1e-9,
        "{shares:?} {b:?}"
    );
    let straight = strand(0.1);
    for j in 0..3 {
        let f = StickStiffness::OneBody.factor(&straight, j);
        assert!((1.0 - f).abs() < 1e-3, "layer {j}: {f}");
    }
}
