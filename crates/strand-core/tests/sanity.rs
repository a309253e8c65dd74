//! SPEC 8 sanity values of the Table 1 strand: closed forms written out independently of the
//! library's formulas (to 1e-9), and the digits SPEC prints (to their precision).

mod common;

use approx::assert_relative_eq;
use std::f64::consts::PI;
use strand_core::{BaseStiffness, LawKind, SectionLaw, SectionOptions, Strand};

#[test]
fn table1_closed_forms() {
    let s = Strand::new(common::table1()).unwrap();
    let l = s.layers().first().unwrap();
    let a = 20f64.to_radians();
    let (e, rho) = (2.0e8, 7801.0);
    let (dc, dw) = (3.0e-3, 2.0e-3);
    let rw = dc / 2.0 + dw / 2.0;
    let (ac, aw) = (PI * dc * dc / 4.0, PI * dw * dw / 4.0);
    let (ic, iw) = (PI * dc.powi(4) / 64.0, PI * dw.powi(4) / 64.0);
    let eta = a.cos() * a.cos() * a.cos();
    let tol = 1e-9;
    assert_relative_eq!(l.radius, rw, max_relative = tol);
    assert_relative_eq!(l.pitch, 2.0 * PI * rw / a.tan(), max_relative = tol);
    assert_relative_eq!(l.eta, eta, max_relative = tol);
    assert_relative_eq!(
        s.mass_per_length(),
        rho * (ac + 6.0 * aw / a.cos()),
        max_relative = tol
    );
    assert_relative_eq!(
        s.axial_stiffness(),
        e * ac + 6.0 * eta * e * aw,
        max_relative = tol
    );
    let paper = BaseStiffness::Paper;
    let kmin = e * ic + 6.0 * eta * e * iw;
    assert_relative_eq!(s.min_bending_stiffness(paper), kmin, max_relative = tol);
    let kmax = kmin + 3.0 * eta * e * aw * rw * rw;
    assert_relative_eq!(s.max_bending_stiffness(paper), kmax, max_relative = tol);
    // The default: Costello's wire stiffness E I cos(alpha) 2 / (2 + nu sin^2 alpha), nu = 0.3.
    let costello = e * ic + 6.0 * e * iw * a.cos() * 2.0 / (2.0 + 0.3 * a.sin().powi(2));
    let default = BaseStiffness::default();
    assert_relative_eq!(
        s.min_bending_stiffness(default),
        costello,
        max_relative = tol
    );
    let d = dc + 2.0 * dw;
    assert_relative_eq!(
        s.traditional().bending_stiffness,
        e * PI * d.powi(4) / 64.0,
        max_relative = tol
    );
    // The all-stick value is the sum over the six wires at any station (sum of sin^2 = 3).
    let law = SectionLaw::with_options(&s, LawKind::Continuous, &SectionOptions::paper());
    for x in [0.0, 0.013, 0.2, 0.4] {
        let st = law.station(x);
        let secant = law.planar_secant(&st, 1e-3, 0.0, &[]);
        assert_relative_eq!(secant, kmax, max_relative = tol);
    }
}

#[test]
fn table1_printed_values() {
    let s = Strand::new(common::table1()).unwrap();
    let l = s.layers().first().unwrap();
    let p = |v: f64, printed: f64, digits: i32| {
        let rel = (v - printed).abs() / printed.abs();
        assert!(
            rel <= 0.5 * 10f64.powi(1 - digits),
            "{v} vs printed {printed}"
        );
    };
    p(l.radius, 2.5e-3, 2);
    p(l.pitch, 0.043157, 5);
    p(l.eta, 0.829769, 6);
    p(s.mass_per_length(), 0.211624, 6);
    p(s.axial_stiffness(), 4541.87, 6);
    let paper = BaseStiffness::Paper;
    p(s.min_bending_stiffness(paper), 1.57725e-3, 6);
    p(s.max_bending_stiffness(paper), 1.135275e-2, 7);
    p(s.traditional().bending_stiffness, 2.357176e-2, 7);
    // Section-3 strand: E = 2e9 scales every stiffness by ten, rho = 5747.
    let mut sec3 = common::table1();
    sec3.length = 1.0;
    for m in [&mut sec3.core.material, &mut sec3.layers[0].wire.material] {
        m.youngs_modulus = 2.0e9;
        m.density = 5747.0;
    }
    let s3 = Strand::new(sec3).unwrap();
    p(s3.mass_per_length(), 0.155904, 6);
    p(s3.min_bending_stiffness(paper), 1.57725e-2, 6);
    p(s3.max_bending_stiffness(paper), 1.135275e-1, 7);
}
