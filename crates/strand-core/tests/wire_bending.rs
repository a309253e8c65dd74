//! The frictionless bending stiffness of a helical wire (`strand_core::wire_bending`): each form
//! against its limit at alpha -> 0, its second-order term, and the thin-rod energy average it
//! comes from, computed here by quadrature over the wire's position around the core.

use std::f64::consts::PI;

use proptest::prelude::*;
use strand_core::{BaseStiffness, Material, WireSpec};

/// The energy average of the module docs by quadrature over theta: the wire's bending and
/// twist rates from the strand's curvature resolved in its frame, with bending stiffness 1 and
/// torsional stiffness 1 / (1 + nu), per unit strand length (`stiffness = true`); or the same
/// weights applied to the compliances (`stiffness = false`).
fn thin_rod_average(alpha: f64, nu: f64, stiffness: bool) -> f64 {
    let (s, c) = alpha.sin_cos();
    let n = 720;
    let (mut bend, mut twist) = (0.0, 0.0);
    for k in 0..n {
        let theta = 2.0 * PI * (k as f64 + 0.5) / n as f64;
        // Rotation rates per unit wire length for unit strand curvature.
        let radial = c * theta.cos();
        let binormal = c * c * theta.sin();
        let tangent = c * s * theta.sin();
        bend += radial * radial + binormal * binormal;
        twist += tangent * tangent;
    }
    // Per unit wire length over cos^2(alpha) (the rates carry one cos each), times the wire
    // length per unit strand length 1 / cos(alpha): weights (1 + cos^2)/2 and sin^2/2.
    let w_bend = bend / n as f64 / (c * c);
    let w_twist = twist / n as f64 / (c * c);
    if stiffness {
        c * (w_bend + w_twist / (1.0 + nu))
    } else {
        c / (w_bend + w_twist * (1.0 + nu))
    }
}

#[test]
fn every_form_is_the_straight_wire_at_zero_lay_angle() {
    // factor = 1 + b alpha^2 + O(alpha^4), with b from the series of each closed form.
    let nu = 0.3;
    for (form, b) in [
        (BaseStiffness::Costello, -(1.0 + nu) / 2.0),
        (BaseStiffness::Foti, -0.5 - nu / (2.0 * (1.0 + nu))),
        (BaseStiffness::Papailiou, -0.5),
        (BaseStiffness::Paper, -1.5),
    ] {
        assert!((form.factor(1e-9, nu) - 1.0).abs() < 1e-15, "{form}");
        for alpha in [1e-2, 2e-3] {
            let got = (form.factor(alpha, nu) - 1.0) / (alpha * alpha);
            assert!((got - b).abs() < alpha, "{form}: {got} vs {b} at {alpha}");
        }
    }
}

#[test]
fn foti_and_costello_are_the_stiffness_and_compliance_averages() {
    for deg in [5.0, 15.0, 20.0, 25.0, 35.0, 60.0] {
        let a = f64::to_radians(deg);
        for nu in [0.0, 0.3, 0.45] {
            let foti = thin_rod_average(a, nu, true);
            let costello = thin_rod_average(a, nu, false);
            let f = BaseStiffness::Foti.factor(a, nu);
            let c = BaseStiffness::Costello.factor(a, nu);
            assert!(
                (f - foti).abs() < 1e-12,
                "Foti at {deg} deg, nu {nu}: {f} vs {foti}"
            );
            assert!(
                (c - costello).abs() < 1e-12,
                "Costello at {deg} deg: {c} vs {costello}"
            );
        }
    }
}

#[test]
fn wire_stiffness_is_the_factor_times_e_i() {
    let wire = WireSpec {
        diameter: 2e-3,
        material: Material {
            youngs_modulus: 2e8,
            poisson_ratio: 0.3,
            density: 7801.0,
        },
    };
    let a = 20f64.to_radians();
    let ei = 2e8 * PI * 2e-3f64.powi(4) / 64.0;
    let k = BaseStiffness::Costello.wire_stiffness(&wire, a);
    assert!((k - ei * a.cos() * 2.0 / (2.0 + 0.3 * a.sin().powi(2))).abs() < 1e-15 * ei);
    // The values in the module docs' table (20 deg, nu = 0.3).
    for (form, printed) in [
        (BaseStiffness::Costello, 0.9235),
        (BaseStiffness::Foti, 0.9270),
        (BaseStiffness::Papailiou, 0.9397),
        (BaseStiffness::Paper, 0.8298),
    ] {
        assert!((form.factor(a, 0.3) - printed).abs() < 5e-5, "{form}");
    }
}

#[test]
fn names_round_trip() {
    for form in BaseStiffness::ALL {
        assert_eq!(BaseStiffness::from_name(form.name()), Some(form));
    }
    assert_eq!(BaseStiffness::from_name("cos3"), None);
    assert_eq!(BaseStiffness::default(), BaseStiffness::Costello);
}

proptest! {
    /// paper < Costello <= Foti <= Papailiou, all below the straight wire, with equality of the
    /// last three at nu = 0.
    #[test]
    fn forms_are_ordered(deg in 0.5f64..85.0, nu in 0.0f64..0.5) {
        let a = deg.to_radians();
        let f = |b: BaseStiffness| b.factor(a, nu);
        let (p, c, fo, pa) = (
            f(BaseStiffness::Paper),
            f(BaseStiffness::Costello),
            f(BaseStiffness::Foti),
            f(BaseStiffness::Papailiou),
        );
        prop_assert!(p < c && c <= fo * (1.0 + 1e-15) && fo <= pa * (1.0 + 1e-15) && pa < 1.0);
        let (c0, f0) = (
            BaseStiffness::Costello.factor(a, 0.0),
            BaseStiffness::Foti.factor(a, 0.0),
        );
        prop_assert!((c0 - a.cos()).abs() < 1e-15 && (f0 - a.cos()).abs() < 1e-15);
    }
}
