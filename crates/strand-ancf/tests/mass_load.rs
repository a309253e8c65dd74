//! Constant mass matrix (eq. (44)) and distributed loads (eq. (45)).

use nalgebra::{SMatrix, SVector, Vector2, Vector3};
use strand_ancf::element_quadrature;
use strand_ancf::load::{
    hermite_load, planar_gravity, planar_uniform_load, spatial_gravity, spatial_uniform_load,
};
use strand_ancf::mass::{hermite_mass, planar_mass, spatial_mass};

/// `mu integral of S^T S dx` by 4-point Gauss quadrature (exact for degree 6).
fn quadrature_mass<const N: usize, const D: usize>(mu: f64, l: f64) -> SMatrix<f64, N, N> {
    let mut m = SMatrix::<f64, N, N>::zeros();
    for p in element_quadrature(l, 4).unwrap() {
        let mut s = SMatrix::<f64, D, N>::zeros();
        for k in 0..4 {
            for d in 0..D {
                s[(d, k * D + d)] = p.row.s[k];
            }
        }
        m += s.transpose() * s * (mu * p.weight);
    }
    m
}

#[test]
fn mass_matrix_matches_quadrature() {
    for &(mu, l) in &[(0.211624, 0.05), (0.155904, 1.0 / 30.0), (2.5, 1.7)] {
        let m8 = planar_mass(mu, l);
        let m12 = spatial_mass(mu, l);
        let e8 = (m8 - quadrature_mass::<8, 2>(mu, l)).amax() / m8.amax();
        let e12 = (m12 - quadrature_mass::<12, 3>(mu, l)).amax() / m12.amax();
        assert!(e8 < 1e-14 && e12 < 1e-14, "{e8} {e12}");
        assert!((m12 - m12.transpose()).amax() == 0.0);
        // Positive definite.
        assert!(m12.cholesky().is_some() && m8.cholesky().is_some());
        assert!(hermite_mass(l).cholesky().is_some());
    }
}

#[test]
fn mass_matrix_total_mass_and_rigid_rotation_energy() {
    let (mu, l) = (0.211624, 0.05);
    let m = spatial_mass(mu, l);
    for d in 0..3 {
        // Sum of the translational entries of direction d: mu l.
        let idx = [d, 6 + d];
        let total: f64 = idx
            .iter()
            .flat_map(|&i| idx.iter().map(move |&j| (i, j)))
            .map(|(i, j)| m[(i, j)])
            .sum();
        assert!((total - mu * l).abs() < 1e-16, "{total}");
        // Kinetic energy of a unit translation velocity.
        let mut v = SVector::<f64, 12>::zeros();
        v[d] = 1.0;
        v[6 + d] = 1.0;
        assert!((0.5 * v.dot(&(m * v)) - 0.5 * mu * l).abs() < 1e-16);
    }
    // Straight element along X spinning about Z through x = 0 at rate w: v(x) = w x Y,
    // kinetic energy 1/2 mu w^2 l^3 / 3 (checks the slope entries).
    let w = 3.0;
    let mut v = SVector::<f64, 12>::zeros();
    v[4] = w; // d r'/dt at node 1 = w Y
    v[7] = w * l; // node 2 velocity
    v[10] = w; // node 2 slope rate
    let t = 0.5 * v.dot(&(m * v));
    let exact = 0.5 * mu * w * w * l.powi(3) / 3.0;
    assert!((t - exact).abs() < 1e-14 * exact, "{t} vs {exact}");
    // Planar: same numbers.
    let m8 = planar_mass(mu, l);
    let mut v8 = SVector::<f64, 8>::zeros();
    v8[3] = w;
    v8[5] = w * l;
    v8[7] = w;
    assert!((0.5 * v8.dot(&(m8 * v8)) - t).abs() < 1e-18);
}

#[test]
fn uniform_load_matches_quadrature_and_does_the_right_work() {
    let (mu, l) = (0.211624, 0.05);
    let g = Vector3::new(0.0, -9.8065, 0.0);
    let q = spatial_gravity(mu, &g, l);
    // Quadrature of S^T f.
    let f = g * mu;
    let mut qq = SVector::<f64, 12>::zeros();
    for p in element_quadrature(l, 3).unwrap() {
        for k in 0..4 {
            for d in 0..3 {
                qq[3 * k + d] += p.weight * p.row.s[k] * f[d];
            }
        }
    }
    assert!((q - qq).amax() < 1e-16, "{}", (q - qq).amax());
    // Work over a rigid translation u = weight . u.
    let u = Vector3::new(0.3, -0.7, 0.2);
    let mut du = SVector::<f64, 12>::zeros();
    du.fixed_rows_mut::<3>(0).copy_from(&u);
    du.fixed_rows_mut::<3>(6).copy_from(&u);
    let work = q.dot(&du);
    assert!((work - mu * l * g.dot(&u)).abs() < 1e-15, "{work}");
    // Work over the linear field delta r = x e (a rotation of a straight element): f.e l^2/2.
    let e = Vector3::new(0.0, 1.0, 0.0);
    let mut dr = SVector::<f64, 12>::zeros();
    dr.fixed_rows_mut::<3>(3).copy_from(&e);
    dr.fixed_rows_mut::<3>(6).copy_from(&(e * l));
    dr.fixed_rows_mut::<3>(9).copy_from(&e);
    assert!((q.dot(&dr) - f.dot(&e) * l * l / 2.0).abs() < 1e-16);
    // Planar agrees with the in-plane part.
    let f2 = Vector2::new(1.5, -2.0);
    let q8 = planar_uniform_load(&f2, l);
    let q12 = spatial_uniform_load(&Vector3::new(f2.x, f2.y, 0.0), l);
    for k in 0..8 {
        assert_eq!(q8[k], q12[3 * (k / 2) + k % 2]);
    }
    let qg = planar_gravity(mu, &Vector2::new(0.0, -9.8065), l);
    assert!((qg[1] + qg[5] + mu * l * 9.8065).abs() < 1e-15);
    let h = hermite_load(l);
    assert!((h[0] + h[2] - l).abs() < 1e-16 && (h[1] + h[3]).abs() < 1e-18);
}

/// The beam's mass in Kronecker form gives the same products as its band matrix, for both
/// element kinds and every support case (supports remove whole position or slope vectors).
#[test]
fn vector_mass_is_the_band_mass() {
    use strand_ancf::beam::{Beam, BeamSpec, ElementKind, Support};
    use strand_core::{LawKind, SectionLaw, Strand, StrandSpec};
    let s = Strand::new(StrandSpec::paper(0.3, 2.0e9, 5747.0)).unwrap();
    for element in [ElementKind::Planar, ElementKind::Spatial] {
        for (start, end) in [
            (None, None),
            (Some(Support::Pinned), None),
            (Some(Support::Clamped), Some(Support::Pinned)),
            (Some(Support::Pinned), Some(Support::Clamped)),
        ] {
            let b = Beam::new(
                BeamSpec {
                    elements: 5,
                    bending_points: None,
                    mass_per_length: s.mass_per_length(),
                    element,
                    direction: [1.0, 0.0, 0.0],
                    gravity: [0.0, -9.81, 0.0],
                    start,
                    end,
                    ..Default::default()
                },
                SectionLaw::new(&s, LawKind::Constant),
            )
            .unwrap();
            let n = b.dofs();
            assert_eq!(b.vector_mass().n(), n);
            let x: Vec<f64> = (0..n).map(|i| (0.7 * i as f64).sin() + 0.1).collect();
            let (mut y0, mut y1) = (vec![0.0; n], vec![0.0; n]);
            b.mass().mul_vec(&x, &mut y0);
            b.vector_mass().mul_vec(&x, &mut y1);
            let scale = y0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for (i, (a, c)) in y0.iter().zip(&y1).enumerate() {
                assert!(
                    (a - c).abs() <= 1e-14 * scale,
                    "{element:?} {start:?} {end:?}: row {i}: {a:e} against {c:e}"
                );
            }
        }
    }
}
