//! The pitch-averaged section law (`section.pitch_samples`) against the resolved law.
//!
//! Under a curvature that is constant along a pitch every station of a 1+m strand has seen
//! the same history, so a wire's response depends only on its phase, and the resolved law's
//! average over the stations `x0 + (k - (S - 1)/2) P / (m S)`, k = 0..S, samples the layer's
//! phases at the `m S` evenly spaced angles the pitch-averaged law's bending point at `x0`
//! holds. The two must agree to rounding along any load path, with slip history; the offsets
//! here are written from the geometry (pitch, wire count), not read from the law. A phase
//! sampling with the wrong spacing or centre fails the first test (checked by mutation:
//! spacing `P / S` instead of `P / (m S)` gives moments 3 % off at S = 4). For any
//! number of layers: with every wire sticking the law is the closed form `K_min + sum_j
//! m_j k_j R_j^2 / 2` (the sum of cos^2 over `m S >= 3` evenly spaced phases is `m S / 2`),
//! and the sampled average converges with the samples at the rate of the midpoint rule of a
//! function with kinks (the stick/slip boundaries).

use proptest::prelude::*;
use std::f64::consts::PI;
use strand_core::{
    LawKind, LayDirection, LayerSpec, Material, SectionLaw, SectionOptions, Strand, StrandSpec,
    WireSpec,
};

fn options(samples: usize) -> SectionOptions {
    SectionOptions {
        pitch_samples: samples,
        ..Default::default()
    }
}

/// A 1+m strand: core 3 mm, m wires of 1 to 2 mm, any lay angle, direction, phase, friction.
fn one_layer() -> impl Strategy<Value = Strand> {
    (
        3usize..=8,
        1.0e-3..2.0e-3f64,
        5.0..25.0f64,
        any::<bool>(),
        -PI..PI,
        0.1..0.6f64,
    )
        .prop_filter_map("wires that do not fit", |(m, d, a, left, phase, mu)| {
            let material = Material {
                youngs_modulus: 2.0e11,
                poisson_ratio: 0.3,
                density: 7800.0,
            };
            Strand::new(StrandSpec {
                length: 1.0,
                core: WireSpec {
                    diameter: 3.0e-3,
                    material,
                },
                layers: vec![LayerSpec {
                    wires: m,
                    wire: WireSpec {
                        diameter: d,
                        material,
                    },
                    lay_angle: a.to_radians(),
                    phase,
                    direction: if left {
                        LayDirection::Left
                    } else {
                        LayDirection::Right
                    },
                }],
                friction: mu,
            })
            .ok()
        })
}

/// The 1x19 strand (1+6+12) of 3 mm steel wires, lay angles 10 and 14 deg in alternate
/// directions.
fn one_by_19() -> Strand {
    let mut spec = StrandSpec::paper(1.0, 2.0e11, 7800.0);
    spec.core.diameter = 3.0e-3;
    spec.layers[0].wire.diameter = 3.0e-3;
    spec.layers[0].lay_angle = 10f64.to_radians();
    let mut outer = spec.layers[0];
    outer.wires = 12;
    outer.lay_angle = 14f64.to_radians();
    outer.direction = LayDirection::Left;
    spec.layers.push(outer);
    // Closed layers stand a few microns off: a slightly larger core, as made.
    spec.core.diameter *= 1.02;
    Strand::new(spec).unwrap()
}

/// A load path of curvatures (1/m): up to `a`, down to `-b`, up to `c`, in `n` steps each.
fn path(a: f64, b: f64, c: f64, n: usize) -> Vec<f64> {
    let mut out = Vec::new();
    let mut k0 = 0.0;
    for k1 in [a, -b, c] {
        for i in 1..=n {
            out.push(k0 + (k1 - k0) * i as f64 / n as f64);
        }
        k0 = k1;
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The pitch-averaged law at a point is the resolved law averaged over the stations that
    /// carry the same phases, step by step along a load path with reversals (hysteretic: the
    /// slip state of each sample committed as the resolved station's is).
    #[test]
    fn pitch_average_is_the_resolved_average_over_its_phases(
        strand in one_layer(),
        samples in 2usize..=9,
        x0 in 0.0..1.0f64,
        eps in 1e-4..2e-3f64,
        amps in (0.1..30.0f64, 0.1..30.0f64, 0.1..30.0f64),
        kind in prop::sample::select(vec![LawKind::Continuous, LawKind::Hysteretic, LawKind::Paper]),
    ) {
        let resolved = SectionLaw::with_options(&strand, kind, &options(0));
        let averaged = SectionLaw::with_options(&strand, kind, &options(samples));
        prop_assert_eq!(averaged.sliders(), samples * resolved.sliders());
        let layer = &strand.layers()[0];
        let (p, m) = (layer.pitch, layer.wires() as f64);
        let centre = 0.5 * (samples as f64 - 1.0);
        let stations: Vec<_> = (0..samples)
            .map(|k| resolved.station(x0 + (k as f64 - centre) * p / (m * samples as f64)))
            .collect();
        let point = averaged.station(x0);
        let scale = resolved.still_curvature(eps).max(1e-9);
        let (mut s_avg, mut s_res) = (
            vec![0.0; averaged.state_len()],
            vec![vec![0.0; resolved.state_len()]; samples],
        );
        let mut t_avg = s_avg.clone();
        let mut t_res = s_res.clone();
        let stick = resolved.stick_bending_stiffness();
        for kappa in path(amps.0 * scale, amps.1 * scale, amps.2 * scale, 12) {
            let a = averaged.planar(&point, eps, kappa, &s_avg, &mut t_avg);
            let (mut moment, mut tangent, mut work) = (0.0, 0.0, 0.0);
            for ((st, s), t) in stations.iter().zip(&s_res).zip(&mut t_res) {
                let r = resolved.planar(st, eps, kappa, s, t);
                moment += r.moment / samples as f64;
                tangent += r.moment_curvature / samples as f64;
                work += r.slip_work / samples as f64;
            }
            // Rounding of sums over m S terms, each at most the stick moment or the friction
            // limit's (both bounded by the stick moment at the largest curvature).
            let bound = 1e-11 * stick * (amps.0.max(amps.1).max(amps.2) * scale);
            prop_assert!((a.moment - moment).abs() <= bound,
                "{kind} S = {samples} kappa = {kappa:.3e}: {} against {moment}", a.moment);
            // The tangent of a sample at its slip threshold may take either side under
            // rounding: one sample's share of the stick stiffness.
            let share = stick / (m * samples as f64);
            prop_assert!((a.moment_curvature - tangent).abs() <= share * 1.000001,
                "{kind}: tangent {} against {tangent}", a.moment_curvature);
            prop_assert!((a.slip_work - work).abs() <= bound * scale + 1e-300);
            s_avg.copy_from_slice(&t_avg);
            for (s, t) in s_res.iter_mut().zip(&t_res) {
                s.copy_from_slice(t);
            }
        }
    }
}

/// With every wire sticking (a curvature below the still curvature, from straight) the
/// pitch-averaged law of the 1x19 strand is the closed-form stick stiffness K_min + sum_j m_j
/// k_j R_j^2 / 2 at every sample count and point, for the laws with sliders.
#[test]
fn sticking_pitch_average_is_the_closed_form_stick_stiffness() {
    let strand = one_by_19();
    for kind in [LawKind::Continuous, LawKind::Hysteretic] {
        let resolved = SectionLaw::with_options(&strand, kind, &options(0));
        // The closed form from the layers' constants (m_j / 2) k_j R_j^2, not from a station.
        let closed = resolved.stick_bending_stiffness();
        for samples in [2, 3, 4, 7, 16] {
            let law = SectionLaw::with_options(&strand, kind, &options(samples));
            let eps = 1e-3;
            let kappa = 0.5 * law.still_curvature(eps);
            for x in [0.0, 0.013, 0.2, 0.777] {
                let st = law.station(x);
                let slip = vec![0.0; law.state_len()];
                let mut trial = slip.clone();
                let r = law.planar(&st, eps, kappa, &slip, &mut trial);
                assert!(
                    (r.moment / kappa - closed).abs() <= 1e-12 * closed,
                    "{kind} S = {samples} x = {x}: {} against {closed}",
                    r.moment / kappa
                );
            }
        }
    }
}

/// Beyond first slip, the 1x19 strand's pitch-averaged moment converges as the samples grow:
/// the changes from S to 2S fall at least linearly (the midpoint rule of a function with
/// kinks converges at order 2, with jumps of the tangent at order 1), and the law at a point
/// depends on the point only through that error.
#[test]
fn pitch_average_converges_with_the_samples() {
    let strand = one_by_19();
    let eps = 1e-3;
    for kind in [LawKind::Continuous, LawKind::Hysteretic] {
        let probe = SectionLaw::with_options(&strand, kind, &options(2));
        let kappa = 5.0 * probe.still_curvature(eps);
        let moment = |samples: usize, x: f64| {
            let law = SectionLaw::with_options(&strand, kind, &options(samples));
            let slip = vec![0.0; law.state_len()];
            let mut trial = slip.clone();
            law.planar(&law.station(x), eps, kappa, &slip, &mut trial)
                .moment
        };
        let ms: Vec<f64> = [4, 8, 16, 32, 64].iter().map(|&s| moment(s, 0.1)).collect();
        let changes: Vec<f64> = ms.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
        for c in changes.windows(2) {
            assert!(
                c[1] <= 0.5 * c[0] * 1.05 || c[1] <= 1e-9 * ms[4].abs(),
                "{kind}: {changes:?}"
            );
        }
        // The point's own place within the pitch: at 64 samples within the last change.
        let spread = (moment(64, 0.1) - moment(64, 0.3)).abs();
        assert!(
            spread <= changes[3].max(1e-9 * ms[4].abs()),
            "{kind}: {spread}"
        );
    }
}

/// The Newton iterations' moment ([`SectionLaw::planar_moment`], with the closed-form layer
/// states of a strand of several layers) is the wire loop's of [`SectionLaw::planar`] for
/// the pitch-averaged samples as for wires: along a load path with reversals of the 1x19
/// strand (`hysteretic`, S = 4), to the rounding of sums over the samples.
#[test]
fn newton_moment_matches_the_sample_loop() {
    let strand = one_by_19();
    let law = SectionLaw::with_options(&strand, LawKind::Hysteretic, &options(4));
    let eps = 1e-3;
    let scale = law.still_curvature(eps);
    let stick = law.stick_bending_stiffness();
    let st = law.station(0.37);
    let mut slip = vec![0.0; law.state_len()];
    let mut trial = slip.clone();
    for kappa in path(8.0 * scale, 6.0 * scale, 9.0 * scale, 40) {
        let fast = law.planar_moment(&st, eps, kappa, &slip);
        let full = law.planar(&st, eps, kappa, &slip, &mut trial);
        let bound = 1e-12 * stick * 9.0 * scale;
        assert!(
            (fast.moment - full.moment).abs() <= bound,
            "kappa {kappa:.3e}: {} against {}",
            fast.moment,
            full.moment
        );
        slip.copy_from_slice(&trial);
    }
}
