//! Spatial element kinematics: analytic derivatives against finite differences, the section
//! frame, exact geometry (arc, helix), rigid rotations, agreement with the planar element.

mod common;

use common::{Rng, fd_gradient, fd_jacobian, rel_err};
use nalgebra::{Matrix3, Rotation3, SVector, Unit, Vector3, Vector6};
use proptest::prelude::*;
use strand_ancf::planar::{self, PlanarCoords, PlanarPoint};
use strand_ancf::spatial::{self, SectionFrame, SpatialCoords, SpatialPoint};
use strand_ancf::{AncfError, ShapeRow};

fn point(y: &Vector6<f64>) -> SpatialPoint {
    SpatialPoint::new(
        Vector3::new(y[0], y[1], y[2]),
        Vector3::new(y[3], y[4], y[5]),
    )
}

fn x_frame() -> SectionFrame {
    SectionFrame::along(Vector3::x()).unwrap()
}

fn random_unit(rng: &mut Rng) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            return v / n;
        }
    }
}

/// Random local state with |r'| in [0.3, 2] and 1 + t0 . t >= 0.1.
fn random_local(rng: &mut Rng, frame: &SectionFrame) -> Vector6<f64> {
    loop {
        let t = random_unit(rng);
        if 1.0 + t.dot(&frame.t0()) < 0.1 {
            continue;
        }
        let n = rng.range(0.3, 2.0);
        return Vector6::new(
            n * t.x,
            n * t.y,
            n * t.z,
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        );
    }
}

/// Worst relative FD errors at `y`: gradients (eps, kappa_y, kappa_z), Hessians (same).
fn local_fd_errors(y: &Vector6<f64>, frame: &SectionFrame) -> [f64; 6] {
    let s = point(y).second(frame).unwrap();
    let h = 1e-5;
    let val = |y: &Vector6<f64>, i: usize| {
        let f = point(y).first(frame).unwrap();
        [f.eps, f.kappa[0], f.kappa[1]][i]
    };
    let grad = |y: &Vector6<f64>, i: usize| {
        let f = point(y).first(frame).unwrap();
        [f.eps_grad, f.kappa_grad[0], f.kappa_grad[1]][i]
    };
    let ag = [
        s.first.eps_grad,
        s.first.kappa_grad[0],
        s.first.kappa_grad[1],
    ];
    let ah = [s.eps_hess, s.kappa_hess[0], s.kappa_hess[1]];
    let mut e = [0.0; 6];
    for i in 0..3 {
        let g = fd_gradient(|y| val(y, i), y, h);
        let hh = fd_jacobian(|y| grad(y, i), y, h);
        e[i] = rel_err(&g, &ag[i], 1e-3);
        e[3 + i] = rel_err(&hh, &ah[i], 1e-3);
    }
    e
}

fn report(name: &str, w: &[f64; 6]) {
    eprintln!(
        "{name}: grad eps {:.1e} ky {:.1e} kz {:.1e}; hess eps {:.1e} ky {:.1e} kz {:.1e}",
        w[0], w[1], w[2], w[3], w[4], w[5]
    );
}

#[test]
fn local_derivatives_match_finite_differences() {
    let mut rng = Rng::new(3);
    let mut worst = [0.0f64; 6];
    for case in 0..600 {
        // A fixed X frame and random reference frames.
        let frame = if case % 2 == 0 {
            x_frame()
        } else {
            SectionFrame::new(random_unit(&mut rng), random_unit(&mut rng)).unwrap()
        };
        let y = random_local(&mut rng, &frame);
        let e = local_fd_errors(&y, &frame);
        for i in 0..6 {
            worst[i] = worst[i].max(e[i]);
        }
        let s = point(&y).second(&frame).unwrap();
        for h in &s.kappa_hess {
            assert!((h - h.transpose()).amax() < 1e-12 * h.amax());
        }
    }
    report("spatial local FD max rel err", &worst);
    assert!(worst.iter().all(|&e| e < 1e-6), "{worst:?}");
}

#[test]
fn near_straight_derivatives_are_finite_and_correct() {
    let mut rng = Rng::new(5);
    let frame = x_frame();
    let mut worst = [0.0f64; 6];
    for _ in 0..50 {
        let t = loop {
            let t = random_unit(&mut rng);
            if 1.0 + t.x > 0.2 {
                break t;
            }
        };
        let nrm = t.cross(&random_unit(&mut rng)).normalize();
        let n = rng.range(0.5, 1.5);
        for &bend in &[0.0, 1e-12] {
            let b = t * rng.range(-1.0, 1.0) + nrm * bend;
            let a = t * n;
            let y = Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z);
            let s = point(&y).second(&frame).unwrap();
            let k = s.first.kappa;
            // |r' x r''| = n bend; per reference length |k| = n bend / n^2.
            assert!((k[0].hypot(k[1]) - bend / n).abs() < 1e-15);
            assert!(s.kappa_hess.iter().all(|h| h.iter().all(|v| v.is_finite())));
            let e = local_fd_errors(&y, &frame);
            for i in 0..6 {
                worst[i] = worst[i].max(e[i]);
            }
        }
    }
    // The reference state itself (t = t0, straight).
    let y = Vector6::new(1.0, 0.0, 0.0, 0.0, 1e-12, 0.0);
    let e = local_fd_errors(&y, &frame);
    for i in 0..6 {
        worst[i] = worst[i].max(e[i]);
    }
    report("spatial near-straight FD max rel err", &worst);
    assert!(worst.iter().all(|&e| e < 1e-6), "{worst:?}");
}

#[test]
fn section_frame_is_orthonormal_and_carries_the_reference() {
    let mut rng = Rng::new(9);
    for _ in 0..200 {
        let frame = SectionFrame::new(random_unit(&mut rng), random_unit(&mut rng)).unwrap();
        let (t0, ey0, ez0) = (frame.t0(), frame.e_y0(), frame.e_z0());
        assert!((t0.cross(&ey0) - ez0).norm() < 1e-14);
        let y = random_local(&mut rng, &frame);
        let f = point(&y).first(&frame).unwrap();
        let [ey, ez] = f.axes;
        let t = f.tangent;
        assert!((ey.norm() - 1.0).abs() < 1e-13 && (ez.norm() - 1.0).abs() < 1e-13);
        assert!(ey.dot(&ez).abs() < 1e-13 && ey.dot(&t).abs() < 1e-13 && ez.dot(&t).abs() < 1e-13);
        assert!((t.cross(&ey) - ez).norm() < 1e-13, "right-handed");
        // Components are the projections of the global curvature vector.
        let k = f.curvature;
        let sc = 1.0 + k.norm();
        assert!((f.kappa[0] - k.dot(&ey)).abs() < 1e-13 * sc);
        assert!((f.kappa[1] - k.dot(&ez)).abs() < 1e-13 * sc);
        assert!((f.kappa[0].hypot(f.kappa[1]) - k.norm()).abs() < 1e-13 * sc);
        // The minimal rotation keeps the axis t0 x t fixed.
        let axis = t0.cross(&t);
        if axis.norm() > 1e-6 {
            let m = Matrix3::from_columns(&[t, ey, ez])
                * Matrix3::from_columns(&[t0, ey0, ez0]).transpose();
            assert!((m * axis - axis).norm() < 1e-12);
        }
        // Value-only path agrees.
        let kv = point(&y).curvature(&frame).unwrap();
        assert!((kv[0] - f.kappa[0]).abs() < 1e-14 * sc && (kv[1] - f.kappa[1]).abs() < 1e-14 * sc);
    }
    // At t = t0 the frame is the reference frame.
    let frame = x_frame();
    let [ey, ez] = frame.carried(&Vector3::x()).unwrap();
    assert_eq!((ey, ez), (Vector3::y(), Vector3::z()));
}

#[test]
fn antiparallel_and_degenerate_tangents_are_reported() {
    let frame = x_frame();
    let p = SpatialPoint::new(Vector3::new(-1.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0));
    assert!(matches!(
        p.second(&frame),
        Err(AncfError::AntiparallelTangent { .. })
    ));
    assert!(p.first(&frame).is_err() && p.curvature(&frame).is_err());
    // Strain and the global curvature vector need no frame.
    assert_eq!(p.strain().unwrap(), 0.0);
    assert!((p.curvature_vector().unwrap() - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-15);
    // Close to, but above, the limit: finite.
    let a = Vector3::new(-1.0, 1e-3, 0.0);
    let q = SpatialPoint::new(a, Vector3::new(0.0, 1.0, 0.3));
    let s = q.second(&frame).unwrap();
    assert!(s.kappa_hess.iter().all(|h| h.iter().all(|v| v.is_finite())));
    let z = SpatialPoint::new(Vector3::new(0.0, 5e-9, 0.0), Vector3::zeros());
    assert!(matches!(
        z.first(&frame),
        Err(AncfError::DegenerateTangent { .. })
    ));
    assert!(SectionFrame::new(Vector3::x(), Vector3::x() * 2.0).is_err());
    assert!(SectionFrame::new(Vector3::zeros(), Vector3::z()).is_err());
    // The default phase reference: Z projected off the direction; X for a strand along Z.
    let fz = SectionFrame::along(Vector3::z()).unwrap();
    assert!((fz.e_z0() - Vector3::x()).norm() < 1e-15);
    let fm = SectionFrame::along(-Vector3::z()).unwrap();
    assert!((fm.e_z0() - Vector3::x()).norm() < 1e-15);
    let d = Vector3::new(0.0, 1.0, 1.0).normalize();
    let f = SectionFrame::along(d).unwrap();
    assert!((f.e_z0() - Vector3::new(0.0, -1.0, 1.0).normalize()).norm() < 1e-15);
    for d in [Vector3::x(), Vector3::new(0.6, -0.8, 0.0)] {
        assert_eq!(SectionFrame::along(d).unwrap().e_z0(), Vector3::z());
    }
}

fn element_from(rng: &mut Rng, l: f64) -> SpatialCoords {
    let r1 = Vector3::new(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    );
    let d = Vector3::new(1.0, rng.range(-0.4, 0.4), rng.range(-0.4, 0.4));
    let r2 = r1 + d * l;
    let s1 = (Vector3::x() + random_unit(rng) * 0.5) * rng.range(0.7, 1.4);
    let s2 = (Vector3::x() + random_unit(rng) * 0.5) * rng.range(0.7, 1.4);
    let mut q = SpatialCoords::zeros();
    for (k, v) in [r1, s1, r2, s2].iter().enumerate() {
        q.fixed_rows_mut::<3>(3 * k).copy_from(v);
    }
    q
}

fn elem_val(q: &SpatialCoords, row: &ShapeRow, f: &SectionFrame, i: usize) -> f64 {
    let s = SpatialPoint::at(q, row).first(f).unwrap();
    [s.eps, s.kappa[0], s.kappa[1]][i]
}

fn elem_grad(q: &SpatialCoords, row: &ShapeRow, f: &SectionFrame, i: usize) -> SVector<f64, 12> {
    let s = SpatialPoint::at(q, row).first(f).unwrap();
    let g = [s.eps_grad, s.kappa_grad[0], s.kappa_grad[1]][i];
    spatial::scatter_gradient(row, &g)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(150))]

    /// Element-size (12) gradients and (12x12) Hessians through the shape rows.
    #[test]
    fn element_derivatives_match_finite_differences(seed in 1u64..u64::MAX, l in 0.05f64..2.0, xi in 0.0f64..=1.0) {
        let mut rng = Rng::new(seed);
        let q = element_from(&mut rng, l);
        let frame = x_frame();
        let row = ShapeRow::new(xi * l, l);
        let p = SpatialPoint::at(&q, &row);
        prop_assume!(p.dr.norm() > 0.2 && p.dr.x > -0.5 * p.dr.norm());
        let s = p.second(&frame).unwrap();
        let ag = [s.first.eps_grad, s.first.kappa_grad[0], s.first.kappa_grad[1]];
        let ah = [s.eps_hess, s.kappa_hess[0], s.kappa_hess[1]];
        for i in 0..3 {
            let g = fd_gradient(|q| elem_val(q, &row, &frame, i), &q, 1e-6);
            let h = fd_jacobian(|q| elem_grad(q, &row, &frame, i), &q, 1e-6);
            let eg = rel_err(&g, &spatial::scatter_gradient(&row, &ag[i]), 1e-3);
            let eh = rel_err(&h, &spatial::scatter_hessian(&row, &ah[i]), 1e-3);
            prop_assert!(eg < 1e-6, "grad {i}: {eg}");
            prop_assert!(eh < 1e-6, "hess {i}: {eh}");
        }
    }
}

/// Helix of radius `rho` and rise `h` per radian, by arc length `s`: position and unit
/// tangent. Curvature `rho / (rho^2 + h^2)`.
fn helix(rho: f64, h: f64, s: f64) -> (Vector3<f64>, Vector3<f64>) {
    let c = (rho * rho + h * h).sqrt();
    let th = s / c;
    (
        Vector3::new(rho * th.cos(), rho * th.sin(), h * th),
        Vector3::new(-rho * th.sin(), rho * th.cos(), h) / c,
    )
}

/// The curvature vector is per reference length: a helix of radius rho and lead 2 pi h
/// traversed with uniform stretch lambda (`r(lambda s)`, `s` the arc length of the helix)
/// turns its tangent by `lambda rho / (rho^2 + h^2)` per unit material length, while the
/// curvature per deformed length stays `rho / (rho^2 + h^2)`.
#[test]
fn curvature_is_per_reference_length() {
    let (rho, h): (f64, f64) = (0.3, 0.1);
    let c = (rho * rho + h * h).sqrt();
    let frame = x_frame();
    for &lambda in &[0.8, 1.0, 1.003, 1.5] {
        for &s in &[0.2f64, 1.1] {
            let th = s / c;
            let tangent = Vector3::new(-rho * th.sin(), rho * th.cos(), h) / c;
            let normal = Vector3::new(-th.cos(), -th.sin(), 0.0);
            let kdef = rho / (c * c);
            let a = tangent * lambda;
            let b = normal * (lambda * lambda * kdef);
            let f = point(&Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z))
                .first(&frame)
                .unwrap();
            let k = f.kappa[0].hypot(f.kappa[1]);
            assert!((k - lambda * kdef).abs() < 1e-13, "{k}");
            assert!((f.curvature.norm() - lambda * kdef).abs() < 1e-13);
        }
    }
}

fn helix_error(rho: f64, h: f64, l: f64) -> [f64; 2] {
    let s0 = 0.3;
    let (r1, t1) = helix(rho, h, s0);
    let (r2, t2) = helix(rho, h, s0 + l);
    let mut q = SpatialCoords::zeros();
    for (k, v) in [r1, t1, r2, t2].iter().enumerate() {
        q.fixed_rows_mut::<3>(3 * k).copy_from(v);
    }
    let kexact = rho / (rho * rho + h * h);
    let mut e = [0.0f64; 2];
    for i in 0..=64 {
        let row = ShapeRow::new(l * i as f64 / 64.0, l);
        let p = SpatialPoint::at(&q, &row);
        e[0] = e[0].max((p.curvature_vector().unwrap().norm() / kexact - 1.0).abs());
        e[1] = e[1].max(p.strain().unwrap().abs());
    }
    e
}

#[test]
fn helix_curvature_converges() {
    let (rho, h) = (0.5, 0.2);
    let mut prev: Option<[f64; 2]> = None;
    for k in 0..6 {
        let l = 0.5 / f64::powi(2.0, k);
        let e = helix_error(rho, h, l);
        let ord = prev.map(|p| [(p[0] / e[0]).log2(), (p[1] / e[1]).log2()]);
        eprintln!(
            "helix l = {l:.4}: |k/k_exact - 1| = {:.3e}, |eps| = {:.3e}, orders {:?}",
            e[0],
            e[1],
            ord.map(|o| o.map(|v| (v * 100.0).round() / 100.0))
        );
        if let Some(o) = ord {
            assert!(o[0] > 1.85 && o[1] > 3.8, "{o:?}");
        }
        prev = Some(e);
    }
}

fn rotate(q: &SpatialCoords, m: &Matrix3<f64>) -> SpatialCoords {
    let mut out = *q;
    for k in 0..4 {
        let v = m * q.fixed_rows::<3>(3 * k);
        out.fixed_rows_mut::<3>(3 * k).copy_from(&v);
    }
    out
}

#[test]
fn rigid_rotation_invariance() {
    let mut rng = Rng::new(13);
    let frame = x_frame();
    let l = 0.8;
    let mut checked = 0;
    for _ in 0..300 {
        let q = element_from(&mut rng, l);
        let rot = Rotation3::from_axis_angle(
            &Unit::new_normalize(random_unit(&mut rng)),
            rng.range(-3.0, 3.0),
        );
        let m = *rot.matrix();
        let qr = rotate(&q, &m);
        // The reference frame rotated with the strand.
        let framer = SectionFrame::new(m * frame.t0(), m * frame.e_z0()).unwrap();
        for i in 0..=8 {
            let row = ShapeRow::new(l * i as f64 / 8.0, l);
            let a = SpatialPoint::at(&q, &row);
            let b = SpatialPoint::at(&qr, &row);
            let (Ok(fa), Ok(fb)) = (a.second(&frame), b.first(&frame)) else {
                continue;
            };
            checked += 1;
            let sc = 1.0 + fa.first.curvature.norm();
            // Invariant for a fixed reference frame: strain and curvature magnitude.
            assert!((fa.first.eps - fb.eps).abs() < 1e-13);
            let ka = fa.first.kappa[0].hypot(fa.first.kappa[1]);
            let kb = fb.kappa[0].hypot(fb.kappa[1]);
            assert!((ka - kb).abs() < 1e-13 * sc);
            assert!((fb.curvature - m * fa.first.curvature).norm() < 1e-13 * sc);
            // Components invariant when the reference frame rotates too, and gradients
            // rotate with the coordinates.
            let fr = b.second(&framer).unwrap();
            for c in 0..2 {
                assert!((fr.first.kappa[c] - fa.first.kappa[c]).abs() < 1e-12 * sc);
                let g = fa.first.kappa_grad[c];
                let ga = m * Vector3::new(g[0], g[1], g[2]);
                let gb = m * Vector3::new(g[3], g[4], g[5]);
                let expect = Vector6::new(ga.x, ga.y, ga.z, gb.x, gb.y, gb.z);
                assert!((fr.first.kappa_grad[c] - expect).amax() < 1e-11 * (1.0 + g.amax()));
            }
        }
    }
    assert!(checked > 2000, "{checked}");
}

#[test]
fn rotation_about_reference_tangent_rotates_components() {
    // Not invariant: with a fixed reference frame, turning the strand by psi about t0 turns
    // (kappa_y, kappa_z) by psi.
    let mut rng = Rng::new(17);
    let frame = x_frame();
    let l = 0.8;
    for _ in 0..100 {
        let q = element_from(&mut rng, l);
        let psi = rng.range(-3.0, 3.0);
        let m = *Rotation3::from_axis_angle(&Vector3::x_axis(), psi).matrix();
        let qr = rotate(&q, &m);
        for i in 0..=4 {
            let row = ShapeRow::new(l * i as f64 / 4.0, l);
            let (Ok(a), Ok(b)) = (
                SpatialPoint::at(&q, &row).curvature(&frame),
                SpatialPoint::at(&qr, &row).curvature(&frame),
            ) else {
                continue;
            };
            let (c, s) = (psi.cos(), psi.sin());
            let expect = [c * a[0] - s * a[1], s * a[0] + c * a[1]];
            let sc = 1.0 + a[0].hypot(a[1]);
            assert!((b[0] - expect[0]).abs() < 1e-12 * sc && (b[1] - expect[1]).abs() < 1e-12 * sc);
        }
    }
    // A bend in the XY plane turned by 90 degrees about X is a pure kappa_y bend.
    let y = Vector6::new(1.0, 0.1, 0.0, 0.0, 2.0, 0.0);
    let a = point(&y).curvature(&frame).unwrap();
    let m = *Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2).matrix();
    let (ra, rb) = (
        m * Vector3::new(y[0], y[1], y[2]),
        m * Vector3::new(y[3], y[4], y[5]),
    );
    let b = SpatialPoint::new(ra, rb).curvature(&frame).unwrap();
    assert!(a[0].abs() < 1e-15 && a[1] > 1.0);
    assert!((b[0] + a[1]).abs() < 1e-14 && b[1].abs() < 1e-14, "{b:?}");
}

#[test]
fn planar_states_agree_with_planar_element() {
    let mut rng = Rng::new(21);
    let frame = x_frame();
    let mut checked = 0;
    for _ in 0..300 {
        let l = rng.range(0.1, 1.5);
        let q8 = PlanarCoords::from_fn(|i, _| match i % 4 {
            0 | 1 => rng.range(-1.0, 1.0) + if i == 4 { l } else { 0.0 },
            _ => rng.range(-1.2, 1.2),
        });
        let q12 = SpatialCoords::from_fn(|i, _| {
            if i % 3 == 2 {
                0.0
            } else {
                q8[2 * (i / 3) + i % 3]
            }
        });
        for j in 0..=6 {
            let row = ShapeRow::new(l * j as f64 / 6.0, l);
            let p = PlanarPoint::at(&q8, &row);
            let s = SpatialPoint::at(&q12, &row);
            let (Ok(a), Ok(b)) = (p.second(), s.second(&frame)) else {
                continue;
            };
            checked += 1;
            let sc = 1.0 + a.first.kappa.abs();
            assert!((a.first.eps - b.first.eps).abs() < 1e-14);
            assert!((a.first.kappa - b.first.kappa[1]).abs() < 1e-13 * sc);
            assert_eq!(b.first.kappa[0], 0.0);
            // In-plane derivative blocks equal, out-of-plane parts of kappa_z vanish.
            let inplane = [0usize, 1, 3, 4];
            for (i, &si) in inplane.iter().enumerate() {
                let gs = 1e-12 * (1.0 + a.first.kappa_grad.amax());
                assert!((a.first.kappa_grad[i] - b.first.kappa_grad[1][si]).abs() < gs);
                assert!((a.first.eps_grad[i] - b.first.eps_grad[si]).abs() < 1e-14);
                for (j, &sj) in inplane.iter().enumerate() {
                    let hs = 1e-12 * (1.0 + a.kappa_hess.amax());
                    assert!((a.kappa_hess[(i, j)] - b.kappa_hess[1][(si, sj)]).abs() < hs);
                    assert!((a.eps_hess[(i, j)] - b.eps_hess[(si, sj)]).abs() < hs);
                }
            }
            assert_eq!(b.first.kappa_grad[1][2], 0.0);
            assert_eq!(b.first.kappa_grad[1][5], 0.0);
            // Element-level: the 8-vector is the in-plane part of the 12-vector.
            let g8 = planar::scatter_gradient(&row, &a.first.kappa_grad);
            let g12 = spatial::scatter_gradient(&row, &b.first.kappa_grad[1]);
            for k in 0..8 {
                assert!((g8[k] - g12[3 * (k / 2) + k % 2]).abs() < 1e-11 * (1.0 + g8.amax()));
            }
        }
    }
    assert!(checked > 1500, "{checked}");
}
