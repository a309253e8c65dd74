//! The assembled tangent ([`Tangent::FrozenMeans`]) equals the finite-difference Jacobian of
//! the assembled generalized elastic forces with the neighbouring elements' mean strains held
//! (`internal_frozen`), for every law, away from stick/slip switch points; the Jacobian of the
//! forces the solvers balance (`internal`) differs from it by the coupling through those means
//! alone, small enough for modified Newton to converge; the forces evaluated without the
//! tangent (the lean path of the iterations that keep their matrix) are those evaluated with
//! it, and so are those without the bending points' books once the books are taken; a rigid
//! motion of the unstrained strand produces no force and no energy.
//!
//! [`Tangent::FrozenMeans`]: strand_ancf::beam::Tangent::FrozenMeans

use strand_ancf::band::BandMatrix;
use strand_ancf::beam::{Beam, BeamSpec, ElementKind, PointState, Support};
use strand_core::section::base_tension::SofteningTable;
use strand_core::{BaseTension, LawKind, SectionLaw, SectionOptions, Strand, StrandSpec};

fn strand() -> Strand {
    let mut spec = StrandSpec::paper(0.4, 2.0e8, 7801.0);
    spec.layers[0].phase = 0.3;
    Strand::new(spec).unwrap()
}

fn beam(kind: LawKind, start: Option<Support>) -> Beam {
    supported(kind, start, None)
}

fn supported(kind: LawKind, start: Option<Support>, end: Option<Support>) -> Beam {
    let s = strand();
    Beam::new(
        BeamSpec {
            elements: 4,
            bending_points: None,
            mass_per_length: s.mass_per_length(),
            element: ElementKind::Planar,
            direction: [1.0, 0.0, 0.0],
            gravity: [0.0, -9.81, 0.0],
            start,
            end,
            ..Default::default()
        },
        SectionLaw::new(&s, kind),
    )
    .unwrap()
}

/// A bent and stretched configuration: an arc of curvature `k` with strain `eps`.
fn arc(beam: &Beam, k: f64, eps: f64) -> Vec<f64> {
    let mut q = beam.reference().to_vec();
    let n = q.len() / 4;
    for j in 0..n {
        let s = j as f64 * beam.element_length();
        let th = -k * s;
        let (c, si) = (th.cos(), th.sin());
        let (x, y) = if k == 0.0 {
            (s, 0.0)
        } else {
            (si / -k, (1.0 - c) / k)
        };
        let st = 1.0 + eps;
        q[4 * j..4 * j + 4].copy_from_slice(&[st * x, -st * y.abs() * k.signum(), st * c, st * si]);
    }
    q
}

/// The arc of [`arc`] perturbed off its symmetry, and a committed slip state that is not
/// zero, so the hysteretic law's return mapping starts from somewhere.
fn perturbed(beam: &Beam, k: f64, eps: f64) -> (Vec<f64>, Vec<f64>) {
    let mut q = arc(beam, k, eps);
    for (i, v) in q.iter_mut().enumerate() {
        *v += 1e-3 * ((i as f64) * 2.3).cos();
    }
    let slip = (0..beam.state_len())
        .map(|i| 1e-5 * ((i as f64) * 0.7).sin())
        .collect();
    (q, slip)
}

#[test]
fn tangent_matches_finite_differences_with_the_means_held() {
    for kind in [
        LawKind::Constant,
        LawKind::Continuous,
        LawKind::Paper,
        LawKind::Hysteretic,
    ] {
        check_tangent(&beam(kind, None), kind.name());
    }
}

/// The same with K_min following the strain (`section.base_tension` `thin_rod`): the
/// coupling `dM/deps = K_min'(eps) kappa` of the tabulated base stiffness is in the tangent
/// (the arcs' strains, 5e-4 to 2e-3 give or take 1e-4, lie inside the paper strand's table,
/// which ends at 2.8e-3). Without that coupling (the law's `moment_strain` left at the wires'
/// part, a mutation) the check fails (133 times the allowed difference at kappa = 0.5).
#[test]
fn tangent_matches_finite_differences_with_k_min_under_tension() {
    let s = strand();
    let options = SectionOptions {
        base_tension: BaseTension::ThinRod,
        ..Default::default()
    };
    let end = SofteningTable::new(&s.layers()[0]).end_strain();
    println!("table to strain {end:.3e}");
    assert!(end > 2e-3);
    for kind in [LawKind::Continuous, LawKind::Hysteretic] {
        let b = Beam::new(
            BeamSpec {
                elements: 4,
                bending_points: None,
                mass_per_length: s.mass_per_length(),
                element: ElementKind::Planar,
                direction: [1.0, 0.0, 0.0],
                gravity: [0.0, -9.81, 0.0],
                ..Default::default()
            },
            SectionLaw::with_options(&s, kind, &options),
        )
        .unwrap();
        check_tangent(&b, &format!("{kind} thin_rod"));
    }
}

/// The assembled tangent of `b` against central differences of its forces with the means
/// held, at three bent and stretched arcs (module docs).
fn check_tangent(b: &Beam, kind: &str) {
    {
        let n = b.coords();
        for (k, eps) in [(0.5, 1e-3), (3.0, 2e-3), (0.01, 5e-4)] {
            let mut q = arc(b, k, eps);
            // Perturb so that the state is generic.
            for (i, v) in q.iter_mut().enumerate() {
                *v += 1e-4 * ((i as f64) * 1.7).sin();
            }
            let slip = b.initial_state();
            let mut trial = slip.clone();
            let mut f0 = vec![0.0; n];
            let mut t = BandMatrix::zeros(b.dofs(), b.bandwidth(), b.bandwidth());
            b.internal(&q, &slip, &mut trial, &mut f0, Some(&mut t), None)
                .unwrap();
            let base = b
                .internal(&q, &slip, &mut trial, &mut f0, None, None)
                .unwrap();
            // Row scales: a row mixes stiff axial and soft bending entries, so each entry is
            // compared with a relative tolerance plus a small floor of its row's largest entry.
            let row_scale: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| t.get(i, j).abs()).fold(0.0, f64::max))
                .collect();
            let mut worst: f64 = 0.0;
            let mut skipped = 0;
            for j in 0..n {
                let h = 1e-7;
                let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
                let mut qp = q.clone();
                qp[j] += h;
                // The tangent holds the neighbours' mean strains the law reads.
                let ep = b
                    .internal_frozen(&qp, &q, &slip, &mut trial, &mut fp, None, None)
                    .unwrap();
                let mut qm = q.clone();
                qm[j] -= h;
                let em = b
                    .internal_frozen(&qm, &q, &slip, &mut trial, &mut fm, None, None)
                    .unwrap();
                if ep.slipping != base.slipping || em.slipping != base.slipping {
                    skipped += 1;
                    continue; // the difference straddles a switch
                }
                for i in 0..n {
                    let fd = (fp[i] - fm[i]) / (2.0 * h);
                    let an = t.get(i, j);
                    let allowed = 1e-4 * an.abs() + 1e-7 * row_scale[i] + 1e-12;
                    worst = worst.max((fd - an).abs() / allowed);
                }
            }
            println!(
                "{kind} k {k}: worst difference {worst:.2e} of the allowed, skipped {skipped}, {} slipping",
                base.slipping
            );
            assert!(
                skipped < n / 2,
                "{kind}: too many columns straddle a switch"
            );
            assert!(
                worst < 1.0,
                "{kind} k {k}: tangent differs from FD ({worst:e} of the allowed)"
            );
        }
    }
}

/// The force-only evaluation and the evaluation with the tangent are separate code paths; they
/// must give the same forces, energies, slip state and point states up to rounding.
#[test]
fn forces_without_the_tangent_equal_those_with_it() {
    for kind in [
        LawKind::Constant,
        LawKind::Continuous,
        LawKind::Paper,
        LawKind::Hysteretic,
    ] {
        let b = beam(kind, Some(Support::Pinned));
        let n = b.coords();
        for (k, eps) in [(0.5, 1e-3), (3.0, 2e-3), (8.0, -1e-3)] {
            let (q, slip) = perturbed(&b, k, eps);
            let (mut trial_a, mut trial_b) = (slip.clone(), slip.clone());
            let (mut fa, mut fb) = (vec![0.0; n], vec![0.0; n]);
            let (mut pa, mut pb) = (
                vec![PointState::default(); b.points()],
                vec![PointState::default(); b.points()],
            );
            let mut t = BandMatrix::zeros(b.dofs(), b.bandwidth(), b.bandwidth());
            let ea = b
                .internal(
                    &q,
                    &slip,
                    &mut trial_a,
                    &mut fa,
                    Some(&mut t),
                    Some(&mut pa),
                )
                .unwrap();
            let eb = b
                .internal(&q, &slip, &mut trial_b, &mut fb, None, Some(&mut pb))
                .unwrap();
            let scale = fa.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for i in 0..n {
                assert!(
                    (fa[i] - fb[i]).abs() <= 1e-12 * scale,
                    "{kind} k {k}: force {i}: {} with the tangent, {} without",
                    fa[i],
                    fb[i]
                );
            }
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
            assert!(close(ea.energy, eb.energy), "{kind} k {k}: energy");
            assert!(close(ea.slip_work, eb.slip_work), "{kind} k {k}: slip work");
            assert_eq!(ea.slipping, eb.slipping, "{kind} k {k}: slipping wires");
            assert!(ea.slipping > 0 || kind == LawKind::Constant || k < 1.0);
            for (x, y) in trial_a.iter().zip(&trial_b) {
                assert!(close(*x, *y), "{kind} k {k}: trial slip {x} and {y}");
            }
            for (x, y) in pa.iter().zip(&pb) {
                assert!(close(x.kappa, y.kappa) && close(x.moment, y.moment));
                assert!(close(x.eps, y.eps) && close(x.energy_strain, y.energy_strain));
                assert_eq!((x.x, x.weight, x.slipping), (y.x, y.weight, y.slipping));
            }
        }
    }
}

/// The forces of a Newton iteration without the bending points' books, completed by
/// `book_points` at the same iterate, are the booked evaluation: the forces, iteration
/// matrix, trial state and points bit for bit; the energy up to the order of its sum (the
/// axial points' part first), a few ulps of its terms.
#[test]
fn forces_without_books_then_books_equal_a_booked_evaluation() {
    use strand_ancf::beam::Tangent;
    for kind in [
        LawKind::Constant,
        LawKind::Continuous,
        LawKind::Paper,
        LawKind::Hysteretic,
    ] {
        let b = beam(kind, Some(Support::Pinned));
        let n = b.coords();
        let tangent = Tangent::Iteration { unloading: 0.25 };
        for (k, eps) in [(0.5, 1e-3), (3.0, 2e-3), (8.0, -1e-3)] {
            let (q, slip) = perturbed(&b, k, eps);
            let (mut trial_a, mut trial_b) = (slip.clone(), vec![7.0; slip.len()]);
            let (mut fa, mut fb) = (vec![0.0; n], vec![0.0; n]);
            let (mut pa, mut pb) = (
                vec![PointState::default(); b.points()],
                vec![PointState::default(); b.points()],
            );
            let mut ta = BandMatrix::zeros(b.dofs(), b.bandwidth(), b.bandwidth());
            let mut tb = ta.clone();
            let ea = b
                .internal_with(
                    &q,
                    &slip,
                    &mut trial_a,
                    &mut fa,
                    Some((&mut ta, tangent)),
                    Some(&mut pa),
                )
                .unwrap();
            let axial = b
                .internal_unbooked(
                    &q,
                    &slip,
                    &mut [],
                    &mut fb,
                    Some((&mut tb, tangent)),
                    &mut pb,
                )
                .unwrap();
            let mut books = axial;
            b.book_points(&slip, &mut trial_b, &mut pb, &mut books);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&fa), bits(&fb), "{kind} k {k}: forces");
            assert_eq!(ta, tb, "{kind} k {k}: iteration matrix");
            assert_eq!(bits(&trial_a), bits(&trial_b), "{kind} k {k}: trial state");
            assert_eq!(pa, pb, "{kind} k {k}: points");
            assert_eq!(books.slip_work.to_bits(), ea.slip_work.to_bits());
            assert_eq!(books.slipping, ea.slipping);
            // The energy's terms are at most |axial| + |books| each: the two sums differ by
            // their rounding, a few ulps of that.
            let terms = axial.energy.abs() + (books.energy - axial.energy).abs();
            let energy = books.energy;
            assert!(
                (energy - ea.energy).abs() <= 64.0 * f64::EPSILON * terms,
                "{kind} k {k}: energy {energy} against {}",
                ea.energy
            );
        }
    }
    // Not for the frozen-means tangent, whose path books inline.
    let b = beam(LawKind::Hysteretic, Some(Support::Pinned));
    let mut t = BandMatrix::zeros(b.dofs(), b.bandwidth(), b.bandwidth());
    let (mut f, mut p) = (
        vec![0.0; b.coords()],
        vec![PointState::default(); b.points()],
    );
    let q = b.reference().to_vec();
    let slip = b.initial_state();
    assert!(
        b.internal_unbooked(
            &q,
            &slip,
            &mut [],
            &mut f,
            Some((&mut t, Tangent::FrozenMeans)),
            &mut p
        )
        .is_err()
    );
}

#[test]
fn rigid_motion_gives_no_force_or_energy() {
    for kind in [LawKind::Constant, LawKind::Continuous, LawKind::Hysteretic] {
        let b = beam(kind, None);
        let n = b.coords();
        let (c, s) = (0.7f64.cos(), 0.7f64.sin());
        let mut q = b.reference().to_vec();
        for j in 0..n / 4 {
            let v = &mut q[4 * j..4 * j + 4];
            let (x, y, dx, dy) = (v[0], v[1], v[2], v[3]);
            v.copy_from_slice(&[
                c * x - s * y + 3.0,
                s * x + c * y - 2.0,
                c * dx - s * dy,
                s * dx + c * dy,
            ]);
        }
        let slip = b.initial_state();
        let mut trial = slip.clone();
        let mut f = vec![0.0; n];
        let e = b
            .internal(&q, &slip, &mut trial, &mut f, None, None)
            .unwrap();
        let fmax = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(fmax < 1e-9, "{kind}: force {fmax}");
        assert!(e.energy.abs() < 1e-15, "{kind}: energy {}", e.energy);
    }
}

/// The contiguous span of free coordinates, where there is one, maps free index `i` to global
/// coordinate `g0 + i`; a pinned end at x = L leaves its slope free after its fixed position,
/// so there is none.
#[test]
fn free_span_matches_the_free_indices() {
    for (start, end, contiguous) in [
        (Some(Support::Pinned), None, true),
        (Some(Support::Clamped), Some(Support::Clamped), true),
        (None, None, true),
        (Some(Support::Clamped), Some(Support::Pinned), false),
    ] {
        let b = supported(LawKind::Constant, start, end);
        let span = b.free_span();
        assert_eq!(span.is_some(), contiguous, "{start:?} {end:?}");
        if let Some(span) = span {
            assert_eq!(span.len(), b.dofs());
            for g in 0..b.coords() {
                let expected = span.contains(&g).then(|| g - span.start);
                assert_eq!(
                    b.free_index(g),
                    expected,
                    "{start:?} {end:?}: coordinate {g}"
                );
            }
        }
    }
}

/// The tangent the solvers factorize against the Jacobian of the forces they balance
/// ([`Beam::internal`], the neighbours' mean strains recovered at the same coordinates): the
/// difference is exactly the coupling through those means (the finite difference of
/// `internal_frozen` in its `means_at` argument alone), nothing else; it vanishes where the
/// moment does not depend on the strain (the `constant` law; a shortened strand, whose wires
/// carry no friction); and it is small enough that the modified Newton iteration on the
/// tangent converges to the solvers' equilibrium: its error contracts by the spectral radius of
/// `T^-1 (J - T)` per iteration, which must be below 1 for the iteration to converge at all
/// (bound asserted on a clamped strand, whose free tangent is regular).
#[test]
fn solver_jacobian_differs_from_the_tangent_by_the_means_coupling_only() {
    use nalgebra::DMatrix;
    for kind in [
        LawKind::Constant,
        LawKind::Continuous,
        LawKind::Paper,
        LawKind::Hysteretic,
    ] {
        let b = beam(kind, Some(Support::Clamped));
        let n = b.coords();
        let dofs = b.dofs();
        let free: Vec<usize> = (0..n).filter(|&g| b.free_index(g).is_some()).collect();
        for (k, eps) in [(0.5, 1e-3), (3.0, 2e-3), (3.0, -1e-3)] {
            let mut q = arc(&b, k, eps);
            for (i, v) in q.iter_mut().enumerate() {
                *v += 1e-4 * ((i as f64) * 1.7).sin();
            }
            let slip = b.initial_state();
            let mut trial = slip.clone();
            let mut f0 = vec![0.0; n];
            let mut t = BandMatrix::zeros(dofs, b.bandwidth(), b.bandwidth());
            let base = b
                .internal(&q, &slip, &mut trial, &mut f0, Some(&mut t), None)
                .unwrap();
            let mut tf = DMatrix::<f64>::zeros(dofs, dofs);
            let mut jac = DMatrix::<f64>::zeros(dofs, dofs);
            let mut coupling = DMatrix::<f64>::zeros(dofs, dofs);
            let h = 1e-7;
            let mut skipped = 0;
            let mut worst: f64 = 0.0;
            let row_scale: Vec<f64> = (0..dofs)
                .map(|i| (0..dofs).map(|j| t.get(i, j).abs()).fold(0.0, f64::max))
                .collect();
            for (cj, &gj) in free.iter().enumerate() {
                let (mut qp, mut qm) = (q.clone(), q.clone());
                qp[gj] += h;
                qm[gj] -= h;
                let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
                // The solvers' forces: means recovered at the perturbed coordinates.
                let ep = b
                    .internal(&qp, &slip, &mut trial, &mut fp, None, None)
                    .unwrap();
                let em = b
                    .internal(&qm, &slip, &mut trial, &mut fm, None, None)
                    .unwrap();
                // The coupling alone: coordinates held, the means moved.
                let (mut cp, mut cm) = (vec![0.0; n], vec![0.0; n]);
                let mp = b
                    .internal_frozen(&q, &qp, &slip, &mut trial, &mut cp, None, None)
                    .unwrap();
                let mm = b
                    .internal_frozen(&q, &qm, &slip, &mut trial, &mut cm, None, None)
                    .unwrap();
                if [ep.slipping, em.slipping, mp.slipping, mm.slipping]
                    .iter()
                    .any(|&s| s != base.slipping)
                {
                    skipped += 1;
                    continue; // the difference straddles a switch
                }
                for (ri, &gi) in free.iter().enumerate() {
                    let j_fd = (fp[gi] - fm[gi]) / (2.0 * h);
                    let c_fd = (cp[gi] - cm[gi]) / (2.0 * h);
                    let an = t.get(ri, cj);
                    tf[(ri, cj)] = an;
                    jac[(ri, cj)] = j_fd;
                    coupling[(ri, cj)] = c_fd;
                    // Central differences of a smooth force at h = 1e-7: truncation h^2 times
                    // the third derivative and round-off eps_mach |f| / h, well below 1e-7 of
                    // the row's largest stiffness (the bound of the frozen test above).
                    let allowed = 1e-4 * an.abs() + 1e-7 * row_scale[ri] + 1e-12;
                    worst = worst.max((j_fd - an - c_fd).abs() / allowed);
                }
            }
            assert!(
                skipped < dofs / 2,
                "{kind}: too many columns straddle a switch"
            );
            assert!(
                worst < 1.0,
                "{kind} k {k} eps {eps}: J - T is not the means coupling ({worst:e} of the allowed)"
            );
            let c_max = coupling.amax();
            let t_max = tf.amax();
            if kind == LawKind::Constant || eps < 0.0 {
                assert!(
                    c_max <= 1e-7 * t_max,
                    "{kind} k {k} eps {eps}: coupling {c_max:e} where the moment has no strain dependence"
                );
            }
            // Contraction of the modified Newton iteration on T toward the zero of the
            // solvers' forces.
            let step = tf
                .clone()
                .lu()
                .solve(&coupling)
                .expect("regular free tangent");
            let rho = step
                .complex_eigenvalues()
                .iter()
                .map(|z| z.norm())
                .fold(0.0, f64::max);
            println!(
                "{kind} k {k} eps {eps}: |C|max/|T|max {:.2e}, contraction {rho:.3e}, {} slipping, skipped {skipped}",
                c_max / t_max,
                base.slipping
            );
            assert!(rho < 1.0, "{kind} k {k} eps {eps}: contraction {rho}");
        }
    }
}
