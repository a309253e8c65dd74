//! Hermite shape functions (eq. (27)) and Gauss-Legendre rules.

use strand_ancf::shape::{shape, shape_dx, shape_dxx};
use strand_ancf::{AncfError, ShapeRow, element_quadrature, gauss_legendre};

#[test]
fn gauss_rules_integrate_polynomials_exactly() {
    let mut worst = 0.0f64;
    for n in 1..=10 {
        let rule = gauss_legendre(n).unwrap();
        assert_eq!(rule.n(), n);
        assert_eq!(rule.points().len(), n);
        for k in 0..2 * n {
            let exact = if k % 2 == 0 {
                2.0 / (k as f64 + 1.0)
            } else {
                0.0
            };
            let approx: f64 = rule
                .points()
                .iter()
                .zip(rule.weights())
                .map(|(x, w)| w * x.powi(k as i32))
                .sum();
            worst = worst.max((approx - exact).abs());
            assert!(
                (approx - exact).abs() < 1e-15,
                "n {n} k {k}: {approx} vs {exact}"
            );
        }
        // Degree 2n is not integrated exactly: the rule has exactly n points' power.
        let k = 2 * n;
        let approx: f64 = rule
            .points()
            .iter()
            .zip(rule.weights())
            .map(|(x, w)| w * x.powi(k as i32))
            .sum();
        assert!((approx - 2.0 / (k as f64 + 1.0)).abs() > 1e-6, "n {n}");
        // Ascending, symmetric, inside (-1, 1), positive weights.
        let p = rule.points();
        assert!(p.windows(2).all(|w| w[0] < w[1]));
        assert!(p.iter().all(|x| x.abs() < 1.0));
        assert!(rule.weights().iter().all(|&w| w > 0.0));
        for i in 0..n {
            assert_eq!(p[i], -p[n - 1 - i]);
        }
    }
    eprintln!("Gauss-Legendre n = 1..10, degree <= 2n-1: max abs error {worst:.1e}");
}

#[test]
fn gauss_rules_match_closed_forms() {
    let r2 = gauss_legendre(2).unwrap();
    assert!((r2.points()[1] - 1.0 / 3f64.sqrt()).abs() < 1e-15);
    assert!((r2.weights()[0] - 1.0).abs() < 1e-15);
    let r3 = gauss_legendre(3).unwrap();
    assert!((r3.points()[2] - 0.6f64.sqrt()).abs() < 1e-15);
    assert!((r3.weights()[1] - 8.0 / 9.0).abs() < 1e-15);
    assert!((r3.weights()[0] - 5.0 / 9.0).abs() < 1e-15);
    let r5 = gauss_legendre(5).unwrap();
    let x = (5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let w = (322.0 - 13.0 * 70f64.sqrt()) / 900.0;
    assert!((r5.points()[4] - x).abs() < 1e-15 && (r5.weights()[4] - w).abs() < 1e-15);
    assert!((r5.weights()[2] - 128.0 / 225.0).abs() < 1e-15);
    assert!(matches!(
        gauss_legendre(0),
        Err(AncfError::QuadratureOrder { n: 0 })
    ));
    assert!(gauss_legendre(11).is_err());
}

#[test]
fn element_quadrature_maps_to_the_element() {
    let l = 0.37;
    let pts = element_quadrature(l, 4).unwrap();
    let sum: f64 = pts.iter().map(|p| p.weight).sum();
    assert!((sum - l).abs() < 1e-15);
    // integral of x^3 over [0, l].
    let i3: f64 = pts.iter().map(|p| p.weight * p.row.x.powi(3)).sum();
    assert!((i3 - l.powi(4) / 4.0).abs() < 1e-15);
    assert!(pts.iter().all(|p| p.row == ShapeRow::new(p.row.x, l)));
    assert!(element_quadrature(0.0, 3).is_err() && element_quadrature(f64::NAN, 3).is_err());
}

#[test]
fn hermite_functions_interpolate_nodal_values_and_slopes() {
    let l = 0.8;
    // Nodal values (eq. (27)): S1(0)=1, S2'(0)=1, S3(l)=1, S4'(l)=1, all others zero.
    let s0 = shape(0.0, l);
    let sl = shape(l, l);
    let d0 = shape_dx(0.0, l);
    let dl = shape_dx(l, l);
    assert_eq!(s0, [1.0, 0.0, 0.0, 0.0]);
    assert!(
        (sl[2] - 1.0).abs() < 1e-15
            && sl[0].abs() < 1e-15
            && sl[1].abs() < 1e-15
            && sl[3].abs() < 1e-15
    );
    assert_eq!(d0, [0.0, 1.0, 0.0, 0.0]);
    assert!(
        (dl[3] - 1.0).abs() < 1e-15
            && dl[0].abs() < 1e-14
            && dl[1].abs() < 1e-15
            && dl[2].abs() < 1e-14
    );
    // Any cubic is reproduced exactly from its end values and slopes.
    let p = |x: f64| 0.3 - 1.2 * x + 0.7 * x * x - 2.1 * x * x * x;
    let dp = |x: f64| -1.2 + 1.4 * x - 6.3 * x * x;
    let ddp = |x: f64| 1.4 - 12.6 * x;
    let q = [p(0.0), dp(0.0), p(l), dp(l)];
    for i in 0..=20 {
        let x = l * i as f64 / 20.0;
        let r = ShapeRow::new(x, l);
        let dot = |c: &[f64; 4]| c.iter().zip(&q).map(|(a, b)| a * b).sum::<f64>();
        assert!((dot(&r.s) - p(x)).abs() < 1e-14);
        assert!((dot(&r.ds) - dp(x)).abs() < 1e-13);
        assert!((dot(&r.dds) - ddp(x)).abs() < 1e-12);
        // Derivatives against central differences.
        let h = 1e-6;
        for k in 0..4 {
            let fd1 = (shape(x + h, l)[k] - shape(x - h, l)[k]) / (2.0 * h);
            let fd2 = (shape_dx(x + h, l)[k] - shape_dx(x - h, l)[k]) / (2.0 * h);
            assert!((fd1 - r.ds[k]).abs() < 1e-8, "{k}");
            assert!((fd2 - shape_dxx(x, l)[k]).abs() < 1e-7, "{k}");
        }
        // Rigid translation: S1 + S3 = 1.
        assert!((r.s[0] + r.s[2] - 1.0).abs() < 1e-15);
    }
}
