//! The spatial beam: analytic tangent against finite differences in a 3D bent state (all
//! laws; section frames of the straight strand and frames committed at another state), zero
//! force under a rigid motion, and the same answers as the planar beam on planar scenes
//! (statics and dynamics).

use strand_ancf::band::BandMatrix;
use strand_ancf::beam::{Beam, BeamSpec, ElementKind, Support, pitch_rule_points};
use strand_ancf::dynamics::{DynamicOptions, Scheme, run_dynamic};
use strand_ancf::statics::{StaticOptions, solve_static};
use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};

fn strand(length: f64, e: f64, rho: f64) -> Strand {
    let mut spec = StrandSpec::paper(length, e, rho);
    spec.layers[0].phase = 0.3;
    Strand::new(spec).unwrap()
}

fn beam(s: &Strand, kind: LawKind, element: ElementKind, n: usize, support: Support) -> Beam {
    beam_with(s, kind, element, n, support, None)
}

/// [`beam`] with `bending_points` per element instead of the pitch rule.
fn beam_with(
    s: &Strand,
    kind: LawKind,
    element: ElementKind,
    n: usize,
    support: Support,
    bending_points: Option<usize>,
) -> Beam {
    Beam::new(
        BeamSpec {
            elements: n,
            bending_points,
            mass_per_length: s.mass_per_length(),
            element,
            direction: [1.0, 0.0, 0.0],
            gravity: [0.0, -9.8, 0.0],
            start: Some(support),
            end: None,
            ..Default::default()
        },
        SectionLaw::new(s, kind),
    )
    .unwrap()
}

/// A helix-like 3D configuration: bending about both section axes with stretch.
fn bent(b: &Beam, k: f64) -> Vec<f64> {
    let mut q = b.reference().to_vec();
    let n = q.len() / 6;
    for j in 0..n {
        let s = j as f64 * b.element_length();
        let (a, c) = (k * s, 0.5 * k * s);
        let r = [
            s * (1.0 - 0.1 * a * a),
            -0.5 * k * s * s,
            0.3 * k * s * s * (1.0 + 0.2 * c),
        ];
        let d = [1.0 - 0.3 * a * a, -a, 0.6 * a + 0.2 * a * c];
        q[6 * j..6 * j + 6].copy_from_slice(&[r[0], r[1], r[2], d[0] * 1.001, d[1], d[2]]);
    }
    q
}

#[test]
fn spatial_tangent_matches_finite_differences() {
    let s = strand(0.4, 2.0e8, 7801.0);
    for kind in [
        LawKind::Constant,
        LawKind::Continuous,
        LawKind::Paper,
        LawKind::Hysteretic,
    ] {
        for (k, committed) in [(0.3, false), (3.0, false), (3.0, true)] {
            let b = beam(&s, kind, ElementKind::Spatial, 3, Support::Clamped);
            let n = b.coords();
            let q = bent(&b, k);
            let mut slip = b.initial_state();
            let mut trial = slip.clone();
            if committed {
                // Frames (and slip) committed at another bent state, turned about the strand
                // axis: the current frames differ from the initial ones by the holonomy of
                // X -> committed -> current tangent.
                let turn = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::x_axis(), 1.2);
                let mut other = bent(&b, 0.8 * k);
                for c in other.chunks_exact_mut(3) {
                    let v = turn * nalgebra::Vector3::new(c[0], c[1], c[2]);
                    c.copy_from_slice(v.as_slice());
                }
                let mut f = vec![0.0; n];
                b.internal(&other, &slip, &mut trial, &mut f, None, None)
                    .unwrap();
                slip.copy_from_slice(&trial);
            }
            let mut f0 = vec![0.0; n];
            let mut t = BandMatrix::zeros(b.dofs(), b.bandwidth(), b.bandwidth());
            let base = b
                .internal(&q, &slip, &mut trial, &mut f0, Some(&mut t), None)
                .unwrap();
            let free: Vec<usize> = (0..n).filter(|&g| b.free_index(g).is_some()).collect();
            let row_scale: Vec<f64> = (0..b.dofs())
                .map(|i| (0..b.dofs()).map(|j| t.get(i, j).abs()).fold(0.0, f64::max))
                .collect();
            let (mut worst, mut skipped): (f64, usize) = (0.0, 0);
            for &gj in &free {
                let j = b.free_index(gj).unwrap();
                let h = 1e-7;
                let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
                let mut qp = q.clone();
                qp[gj] += h;
                // The tangent holds the neighbours' mean strains the law reads.
                let ep = b
                    .internal_frozen(&qp, &q, &slip, &mut trial, &mut fp, None, None)
                    .unwrap();
                let mut qm = q.clone();
                qm[gj] -= h;
                let em = b
                    .internal_frozen(&qm, &q, &slip, &mut trial, &mut fm, None, None)
                    .unwrap();
                if ep.slipping != base.slipping || em.slipping != base.slipping {
                    skipped += 1;
                    continue;
                }
                for &gi in &free {
                    let i = b.free_index(gi).unwrap();
                    let fd = (fp[gi] - fm[gi]) / (2.0 * h);
                    let an = t.get(i, j);
                    let allowed = 1e-4 * an.abs() + 1e-7 * row_scale[i] + 1e-12;
                    worst = worst.max((fd - an).abs() / allowed);
                }
            }
            println!(
                "spatial {kind} k {k} committed {committed}: worst {worst:.2e} of the allowed, \
                 skipped {skipped}, {} slipping",
                base.slipping
            );
            assert!(skipped < free.len() / 2);
            assert!(worst < 1.0, "{kind} k {k}: {worst}");
        }
    }
}

/// The spatial element's Newton iterations leave out the hysteretic law's slip work
/// (`internal_unbooked`), and `book_points` at the same iterate completes it: the forces,
/// iteration matrix, trial state (slip, bending direction, frames), points, energy and
/// slipping wires are the booked evaluation's bit for bit, and so is the slip work once
/// booked, from a committed state whose bending direction differs from the iterate's (the
/// trapezoid's limit at the step's start).
#[test]
fn spatial_forces_without_slip_work_then_books_equal_a_booked_evaluation() {
    use strand_ancf::beam::{PointState, Tangent};
    let s = strand(0.4, 2.0e8, 7801.0);
    let b = beam(
        &s,
        LawKind::Hysteretic,
        ElementKind::Spatial,
        3,
        Support::Clamped,
    );
    let n = b.coords();
    let tangent = Tangent::Iteration { unloading: 0.25 };
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (k, turn) in [(3.0, 1.2), (6.0, -0.7)] {
        // Committed at another bent state turned about the strand axis: another bending
        // direction, and wires slipped there.
        let mut slip = b.initial_state();
        let mut trial = slip.clone();
        let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::x_axis(), turn);
        let mut other = bent(&b, 0.8 * k);
        for c in other.chunks_exact_mut(3) {
            let v = rot * nalgebra::Vector3::new(c[0], c[1], c[2]);
            c.copy_from_slice(v.as_slice());
        }
        let mut f = vec![0.0; n];
        b.internal(&other, &slip, &mut trial, &mut f, None, None)
            .unwrap();
        slip.copy_from_slice(&trial);
        let q = bent(&b, k);
        let (mut trial_a, mut trial_b) = (slip.clone(), vec![7.0; slip.len()]);
        let (mut fa, mut fb) = (vec![0.0; n], vec![0.0; n]);
        let (mut pa, mut pb) = (
            vec![PointState::default(); b.points()],
            vec![PointState::default(); b.points()],
        );
        let mut ta = BandMatrix::zeros(b.dofs(), b.bandwidth(), b.bandwidth());
        let mut tb = ta.clone();
        let booked = b
            .internal_with(
                &q,
                &slip,
                &mut trial_a,
                &mut fa,
                Some((&mut ta, tangent)),
                Some(&mut pa),
            )
            .unwrap();
        let mut ev = b
            .internal_unbooked(
                &q,
                &slip,
                &mut trial_b,
                &mut fb,
                Some((&mut tb, tangent)),
                &mut pb,
            )
            .unwrap();
        assert_eq!(ev.slip_work, 0.0, "k {k}: left out");
        b.book_points(&slip, &mut trial_b, &mut pb, &mut ev);
        assert!(
            booked.slipping > 0 && booked.slip_work > 0.0,
            "k {k}: {booked:?}"
        );
        assert_eq!(bits(&fa), bits(&fb), "k {k}: forces");
        assert_eq!(ta, tb, "k {k}: iteration matrix");
        assert_eq!(bits(&trial_a), bits(&trial_b), "k {k}: trial state");
        assert_eq!(pa, pb, "k {k}: points");
        assert_eq!(
            ev.energy.to_bits(),
            booked.energy.to_bits(),
            "k {k}: energy"
        );
        assert_eq!(ev.slip_work.to_bits(), booked.slip_work.to_bits());
        assert_eq!(ev.slipping, booked.slipping);
    }
}

#[test]
fn spatial_rigid_motion_gives_no_force() {
    let s = strand(0.4, 2.0e8, 7801.0);
    let b = beam(
        &s,
        LawKind::Continuous,
        ElementKind::Spatial,
        4,
        Support::Clamped,
    );
    // Rotate the straight strand by 0.5 rad about (1, 2, 3) and translate it.
    let axis = nalgebra::Vector3::new(1.0, 2.0, 3.0).normalize();
    let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), 0.5);
    let mut q = b.reference().to_vec();
    for j in 0..q.len() / 6 {
        let r = rot * nalgebra::Vector3::new(q[6 * j], q[6 * j + 1], q[6 * j + 2]);
        let d = rot * nalgebra::Vector3::new(q[6 * j + 3], q[6 * j + 4], q[6 * j + 5]);
        q[6 * j..6 * j + 6].copy_from_slice(&[r.x + 1.0, r.y - 2.0, r.z, d.x, d.y, d.z]);
    }
    let mut f = vec![0.0; q.len()];
    let state = b.initial_state();
    let mut trial = state.clone();
    assert!(b.internal(&q, &[], &mut [], &mut f, None, None).is_err());
    let e = b
        .internal(&q, &state, &mut trial, &mut f, None, None)
        .unwrap();
    let fmax = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert!(
        fmax < 1e-9 && e.energy.abs() < 1e-15,
        "force {fmax}, energy {}",
        e.energy
    );
}

#[test]
fn planar_and_spatial_agree_on_planar_scenes() {
    // Both elements with the bending points the pitch rule gives the spatial one (three per
    // quarter pitch against the planar element's one), so that the runs differ by the elements
    // alone, not by their quadratures.
    let points = |s: &Strand, n: usize| {
        let pitch = s.layers().first().unwrap().pitch;
        Some(pitch_rule_points(s.length() / n as f64, pitch, ElementKind::Spatial) as usize)
    };
    // Statics: the paper's section-3 strand under g = 12.
    let s3 = strand(1.0, 2.0e9, 5747.0);
    let mut tips = Vec::new();
    for element in [ElementKind::Planar, ElementKind::Spatial] {
        let b = beam_with(
            &s3,
            LawKind::Continuous,
            element,
            30,
            Support::Clamped,
            points(&s3, 30),
        );
        let sol = solve_static(&b, &StaticOptions::default(), &mut |_| {}).unwrap();
        let (tip, _) = b.sample(&sol.q, b.length());
        tips.push(tip);
    }
    let d = (0..3)
        .map(|c| (tips[0][c] - tips[1][c]).powi(2))
        .sum::<f64>()
        .sqrt();
    println!("static tips {tips:?}: distance {d:.3e} m");
    // The distance includes the spatial tip's z: the wires' moment out of the plane of
    // bending (`SectionLaw::vector`), which the planar element leaves out, bends the spatial
    // one out of its plane (measured 4.9e-10 m).
    assert!(d < 1e-8, "planar and spatial statics differ by {d} m");

    // Dynamics: the Table 1 pinned pendulum with the hysteretic law, 0.2 s. Here the wires
    // slip, and their moment out of the plane of bending moves the spatial element out of
    // it: the runs differ by that physics, which the planar element leaves out; it must stay
    // below the integrator's own error, the planar run's change when the step is halved.
    let s1 = strand(0.4, 2.0e8, 7801.0);
    let mut tips = Vec::new();
    for (element, step) in [
        (ElementKind::Planar, 5e-4),
        (ElementKind::Spatial, 5e-4),
        (ElementKind::Planar, 2.5e-4),
    ] {
        let b = beam_with(
            &s1,
            LawKind::Hysteretic,
            element,
            8,
            Support::Pinned,
            points(&s1, 8),
        );
        let mut opts = DynamicOptions::new(
            0.2,
            Scheme::GeneralizedAlpha {
                step,
                spectral_radius: 1.0,
            },
            0.1,
        );
        // Converged far below the default: the two elements' Newton iterations use different
        // iteration matrices (the planar one only the material part), so at the default
        // tolerance their states differ by what Newton leaves, not by the elements.
        opts.increment = 1e-13;
        let r = run_dynamic(&b, &opts, &mut |_| {}).unwrap();
        tips.push(b.sample(&r.q, b.length()).0);
    }
    let dist = |a: [f64; 3], b: [f64; 3]| (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt();
    let d = dist(tips[0], tips[1]);
    let step_error = dist(tips[0], tips[2]);
    println!(
        "dynamic tips {tips:?}: planar to spatial {d:.3e} m ({:.3e} m out of the plane), \
         h to h/2 {step_error:.3e} m",
        tips[1][2]
    );
    assert!(tips[1][2] != 0.0, "no moment out of the plane");
    assert!(
        d < step_error,
        "planar and spatial dynamics differ by {d} m, the step error is {step_error} m"
    );
}
