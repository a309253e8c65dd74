//! The fine model honours every scene field of 3D motion (`initial.velocity`,
//! `initial.angular_velocity`, `loads.points`, `supports[].motion`), each checked against a
//! closed form with a bound from the physics it leaves out, on a strand along a direction out
//! of every coordinate plane. (A moving support in statics is refused by name:
//! `bad_input.rs`.)

mod common;
#[path = "common/temp_path.rs"]
mod temp_path;

use std::path::Path;

use nalgebra::{Rotation3, Unit, Vector3};
use serde_json::{Value, json};
use strand_scene::{RunOptions, Scene, run_scene};
use temp_path::TempPath;

/// Direction of every strand here: out of every coordinate plane.
const DIR: [f64; 3] = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
const L: f64 = 0.4;
const E: f64 = 2.0e8;
const RHO: f64 = 7801.0;
const D: f64 = 3.0e-3;

fn run(scene: Value, tag: &str) -> TempPath {
    let scene = Scene::parse(&scene.to_string()).expect("valid scene");
    let out = TempPath::new(&format!("strand-fine-fields-{tag}"));
    let opts = RunOptions {
        out: out.to_path_buf(),
        vtk: false,
    };
    run_scene(&scene, &opts, &mut |_, _| {}).expect("run succeeds");
    out.into_sub("fine")
}

/// Tip positions over time.
fn tips(dir: &Path) -> Vec<(f64, Vector3<f64>)> {
    let c = common::csv_columns(&dir.join("tip.csv"));
    (0..c["t"].len())
        .map(|i| (c["t"][i], Vector3::new(c["x"][i], c["y"][i], c["z"][i])))
        .collect()
}

/// The core wire alone (no contacts: the fields' effect is not mixed with friction), or with
/// six helical wires.
fn strand(layer: bool) -> Value {
    let layers = if layer {
        json!([{ "wires": 6, "diameter": 2.0e-3, "lay_angle_deg": 20.0, "phase_deg": 0.0,
                 "youngs_modulus": E, "poisson_ratio": 0.3, "density": RHO }])
    } else {
        json!([])
    };
    json!({
        "length": L,
        "core": { "diameter": D, "youngs_modulus": E, "poisson_ratio": 0.3, "density": RHO },
        "layers": layers,
        "friction": 0.3
    })
}

fn dynamic(strand: Value, duration: f64) -> Value {
    json!({
        "name": "fine-fields",
        "strand": strand,
        "law": "hysteretic",
        "supports": [],
        "initial": { "direction": DIR },
        "loads": { "gravity": [0.0, 0.0, 0.0] },
        "analysis": { "kind": "dynamic", "duration": duration, "integrator": "verlet",
                      "output_interval": duration / 4.0 },
        "models": { "fine": { "segments_per_wire": 10 } }
    })
}

fn dir() -> Vector3<f64> {
    Vector3::from(DIR)
}

/// A free strand with wires, no load, `initial.velocity` v: every segment moves by v t. The
/// symplectic steps translate a rigid state exactly, so only round-off is left (1e-12 m per
/// step at most over a few thousand steps).
#[test]
fn initial_velocity_translates_the_strand() {
    let v = [0.3, -0.2, 0.5];
    let mut s = dynamic(strand(true), 0.02);
    s["initial"]["velocity"] = json!(v);
    let d = run(s, "velocity");
    for (t, x) in tips(&d) {
        let want = L * dir() + t * Vector3::from(v);
        assert!(
            (x - want).norm() < 1e-9,
            "t = {t}: tip {x:?} against {want:?}"
        );
    }
}

/// A strand with wires pinned at the origin, no gravity, `initial.angular_velocity` w normal
/// to it: a rigid rotation at the rate |w|, up to the centrifugal stretch. The rod's stretch
/// under its own centrifugal load is `dL = rho w^2 L^3 / (3 E)` (3.3e-6 m here); released
/// unstretched the strand oscillates between 0 and about 2 dL, and its moment of inertia with
/// it (relative 6 dL / L), which changes the turned angle by at most that times w t. The bound
/// is 2 dL + 6 dL w t, doubled for the wires' helices (stiffer along the strand, not softer).
#[test]
fn initial_angular_velocity_turns_the_strand_about_the_origin() {
    let w = 2.0;
    let axis = Unit::new_normalize(dir().cross(&Vector3::z()));
    let mut s = dynamic(strand(true), 0.2);
    s["supports"] = json!([{ "at": "start", "kind": "pinned" }]);
    s["initial"]["angular_velocity"] = json!([w * axis.x, w * axis.y, w * axis.z]);
    let d = run(s, "spin");
    let dl = RHO * w * w * L.powi(3) / (3.0 * E);
    let tips = tips(&d);
    assert_eq!(tips.len(), 5);
    for (t, x) in tips {
        let want = Rotation3::from_axis_angle(&axis, w * t) * (L * dir());
        let bound = 2.0 * (2.0 * dl + 6.0 * dl * w * t);
        assert!(
            (x - want).norm() < bound,
            "t = {t}: tip {x:?} against {want:?} ({:.2e} m, bound {bound:.2e} m)",
            (x - want).norm()
        );
    }
}

/// A free core wire pulled at its end along its axis by a point force F: its centre of mass
/// accelerates at F / m, and the tip follows it up to the bar's axial response to a step
/// load, whose quasi-static tip offset is F L / (3 EA) and whose overshoot at most doubles it;
/// the bound is 2 F L / EA (1.4e-4 m here, against a displacement of 2.8e-2 m).
#[test]
fn point_force_accelerates_the_free_strand() {
    let f = 0.5;
    let mut s = dynamic(strand(false), 0.05);
    let force = f * dir();
    s["loads"]["points"] = json!([{ "s": L, "force": [force.x, force.y, force.z] }]);
    let d = run(s, "point-axial");
    let area = std::f64::consts::PI * D * D / 4.0;
    let m = RHO * area * L;
    let bound = 2.0 * f * L / (E * area);
    for (t, x) in tips(&d) {
        let want = (L + f * t * t / (2.0 * m)) * dir();
        assert!(
            (x - want).norm() < bound,
            "t = {t}: tip {x:?} against {want:?} ({:.2e} m, bound {bound:.2e} m)",
            (x - want).norm()
        );
    }
}

/// A core wire clamped at the origin, a small force normal to it at s = L/2 (statics): the
/// tip deflects by `F s^2 (3 L - s) / (6 EI)`, the deflection beyond s being the slope's. The
/// chain's own error is measured by refinement: at 40 segments the deflection must be nearer
/// the closed form than twice its change from 20 segments (a chain converging at first order
/// or faster), which a force at the wrong place or of the wrong size fails.
#[test]
fn point_force_bends_the_clamped_strand_where_it_acts() {
    let f = 1e-4;
    let normal = dir().cross(&Vector3::z()).normalize();
    let sag = |segments: usize| {
        let force = f * normal;
        let s = json!({
            "name": "fine-point-static",
            "strand": strand(false),
            "supports": [{ "at": "start", "kind": "clamped" }],
            "initial": { "direction": DIR },
            "loads": { "gravity": [0.0, 0.0, 0.0],
                       "points": [{ "s": L / 2.0, "force": [force.x, force.y, force.z] }] },
            "analysis": { "kind": "static", "load_steps": 1 },
            "models": { "fine": { "segments_per_wire": segments } }
        });
        let c = common::csv_columns(
            &run(s, &format!("point-static-{segments}")).join("centerline.csv"),
        );
        let tip = Vector3::new(
            *c["x"].last().unwrap(),
            *c["y"].last().unwrap(),
            *c["z"].last().unwrap(),
        );
        (tip - L * dir()).dot(&normal)
    };
    let ei = E * std::f64::consts::PI * D.powi(4) / 64.0;
    let a = L / 2.0;
    let want = f * a * a * (3.0 * L - a) / (6.0 * ei);
    // Small deflection (w / L = 2.1e-3): geometric nonlinearity of order (w / L)^2.
    assert!(want / L < 5e-3);
    let (w20, w40) = (sag(20), sag(40));
    println!(
        "tip deflection {w20:.6e} m (20 segments), {w40:.6e} m (40), closed form {want:.6e} m"
    );
    assert!(
        (w40 - want).abs() < 2.0 * (w40 - w20).abs() + 1e-4 * want,
        "tip deflection {w40:e} m (20 segments: {w20:e} m) against {want:e} m"
    );
    assert!((w40 / want - 1.0).abs() < 0.02, "{w40:e} against {want:e}");
}

/// A free core wire whose start is pinned and moved along the strand at a constant speed V
/// (`supports[].motion`): the strand follows as a rigid body up to the axial wave the sudden
/// start sends along it, of tip amplitude at most `2 V L / c` with `c = sqrt(E / rho)` (2.5e-4
/// m here, against a displacement of 5e-3 m).
#[test]
fn support_motion_carries_the_strand() {
    let v = 0.05;
    let mut s = dynamic(strand(false), 0.1);
    let m = v * dir();
    s["supports"] = json!([{ "at": "start", "kind": "pinned",
                             "motion": [[0.0, 0.0, 0.0, 0.0], [1.0, m.x, m.y, m.z]] }]);
    let d = run(s, "motion");
    let c = (E / RHO).sqrt();
    let bound = 2.0 * v * L / c;
    for (t, x) in tips(&d) {
        let want = (L + v * t) * dir();
        assert!(
            (x - want).norm() < bound,
            "t = {t}: tip {x:?} against {want:?} ({:.2e} m, bound {bound:.2e} m)",
            (x - want).norm()
        );
    }
}
