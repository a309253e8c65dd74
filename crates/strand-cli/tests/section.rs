//! `strand section --json` on the bundled Table 1 scene prints the SPEC 8 sanity values.

#[path = "../../strand-scene/tests/common/temp_path.rs"]
mod temp_path;

use std::process::Command;

use temp_path::TempPath;

fn strand(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_strand"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .unwrap()
}

/// `strand` with `args`, which must succeed (else its stderr is shown), its stdout read as
/// JSON.
fn strand_json(args: &[&str]) -> serde_json::Value {
    let out = strand(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn section_json_prints_spec8_values() {
    let v = strand_json(&["section", "validation/paper-fig7-g8.json", "--json"]);
    for (key, printed, digits) in [
        ("R_w", 2.5e-3, 2),
        ("pitch", 0.043157, 5),
        ("eta", 0.829769, 6),
        ("mass_per_length", 0.211624, 6),
        ("EA", 4541.87, 6),
        ("K_min", 1.57725e-3, 6),
        ("K_max", 1.135275e-2, 7),
        ("EI_traditional", 2.357176e-2, 7),
    ] {
        let got = v[key].as_f64().unwrap_or_else(|| panic!("no {key}"));
        let rel = (got - printed).abs() / printed;
        assert!(
            rel <= 0.5 * 10f64.powi(1 - digits),
            "{key}: {got} vs {printed}"
        );
    }
}

#[test]
fn section_json_with_strain_and_curvature() {
    let v = strand_json(&[
        "section",
        "validation/paper-fig7-g8.json",
        "--strain",
        "1e-3",
        "--curvature",
        "0.05",
        "--at",
        "0.1",
        "--json",
    ]);
    let wires = v["wires"].as_array().unwrap();
    assert_eq!(wires.len(), 6);
    // Secant stiffness lies between K_min and K_max, and is M / kappa.
    let (m, k) = (
        v["moment"].as_f64().unwrap(),
        v["secant_stiffness"].as_f64().unwrap(),
    );
    assert!((m / 0.05 - k).abs() < 1e-12 * k);
    assert!(k > v["K_min"].as_f64().unwrap() && k < v["K_max"].as_f64().unwrap());
    // Each wire's state agrees with its critical curvature.
    for w in wires {
        let slip = w["state"] == "slip";
        if let Some(c) = w["critical_curvature"].as_f64() {
            assert_eq!(slip, 0.05 > c, "{w}");
        }
    }
}

#[test]
fn bad_scene_names_the_field() {
    let dir = TempPath::new("strand-cli-test");
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("bad.json");
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/paper-fig7-g8.json"
    ))
    .unwrap()
    .replace("\"lay_angle_deg\": 20.0", "\"lay_angle_deg\": 95.0");
    std::fs::write(&p, text).unwrap();
    let out = strand(&["section", p.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("strand.layers[0].lay_angle_deg: must be in (0, 90)"),
        "{err}"
    );
    let out = strand(&[
        "section",
        "validation/paper-fig7-g8.json",
        "--strain",
        "1e-3",
    ]);
    assert!(!out.status.success());
}

/// Writes `validation/paper-fig7-g8.json` with its `section` object replaced by `section`
/// (JSON text, or nothing when empty) to a temporary file.
fn fig7_with_section(tag: &str, section: &str) -> TempPath {
    let dir = TempPath::new(&format!("strand-cli-section-{tag}"));
    std::fs::create_dir_all(&dir).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../validation/paper-fig7-g8.json"
        ))
        .unwrap(),
    )
    .unwrap();
    let obj = v.as_object_mut().unwrap();
    obj.remove("section");
    if !section.is_empty() {
        obj.insert("section".into(), serde_json::from_str(section).unwrap());
    }
    let p = dir.into_sub(format!("{tag}.json"));
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    p
}

/// Without `section`, K_min is Costello's (core E I plus six wires E I cos(alpha) 2 / (2 + nu
/// sin^2 alpha), written out here) and the paper's cos^3 value is shown beside it.
#[test]
fn section_shows_the_base_stiffness_and_both_values() {
    let p = fig7_with_section("default", "");
    let v = strand_json(&["section", p.to_str().unwrap(), "--json"]);
    let (e, a) = (2.0e8, 20f64.to_radians());
    let i = |d: f64| std::f64::consts::PI * d.powi(4) / 64.0;
    let costello = e * i(3e-3) + 6.0 * e * i(2e-3) * a.cos() * 2.0 / (2.0 + 0.3 * a.sin().powi(2));
    assert_eq!(v["base_stiffness"], "costello");
    let k_min = v["K_min"].as_f64().unwrap();
    assert!(
        (k_min - costello).abs() < 1e-12 * costello,
        "{k_min} vs {costello}"
    );
    let paper = v["K_min_paper"].as_f64().unwrap();
    assert!((paper - 1.57725e-3).abs() < 5e-6 * 1.57725e-3, "{paper}");
    // The text table names the form and prints both values.
    let out = strand(&["section", p.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("costello (section.base_stiffness)"), "{text}");
    assert!(
        text.contains(&format!("{k_min:.6e} N m^2 (used)")),
        "{text}"
    );
    assert!(text.contains(&format!("{paper:.6e}")), "{text}");
    // A scene naming the paper's form uses it.
    let p = fig7_with_section("foti", r#"{"base_stiffness": "foti"}"#);
    let v = strand_json(&["section", p.to_str().unwrap(), "--json"]);
    assert_eq!(v["base_stiffness"], "foti");
    assert!(v["K_min"].as_f64().unwrap() > costello);
    // Unknown forms and keys are rejected naming the field.
    for (section, field) in [
        (
            r#"{"base_stiffness": "cos3"}"#,
            "section.base_stiffness: unknown base stiffness",
        ),
        (r#"{"bonded": 1}"#, "section"),
    ] {
        let p = fig7_with_section("bad", section);
        let out = strand(&["section", p.to_str().unwrap()]);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(field), "{err}");
    }
}

/// Without `section`, the wires' stick stiffness is the bonded strand's: K_max is K_min plus
/// the plane-section stick stiffness (m/2) eta E_w A_w R_w^2 (written out here) times the
/// stick factor, which is below 1; the plane section's K_max is shown beside it, and a scene
/// naming `plane_section` uses it.
#[test]
fn section_shows_the_stick_stiffness_and_both_values() {
    let p = fig7_with_section("stick-default", "");
    let v = strand_json(&["section", p.to_str().unwrap(), "--json"]);
    let (e, a, r_w) = (2.0e8, 20f64.to_radians(), 2.5e-3);
    let area = std::f64::consts::PI * 2e-3f64.powi(2) / 4.0;
    let plane = 3.0 * a.cos().powi(3) * e * area * r_w * r_w;
    let get = |k: &str| v[k].as_f64().unwrap_or_else(|| panic!("no {k}"));
    let (k_min, k_max, k_plane, f) = (
        get("K_min"),
        get("K_max"),
        get("K_max_plane_section"),
        get("stick_factor"),
    );
    assert_eq!(v["stick_stiffness"], "bonded");
    assert!(
        (k_plane - k_min - plane).abs() < 1e-12 * k_plane,
        "{k_plane} vs {}",
        k_min + plane
    );
    assert!(f > 0.5 && f < 1.0, "stick factor {f}");
    assert!(
        (k_max - k_min - f * plane).abs() < 1e-12 * k_max,
        "{k_max} vs {}",
        k_min + f * plane
    );
    let out = strand(&["section", p.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!(
            "bonded (section.stick_stiffness), factor {f:.4} on eq. (22a)"
        )),
        "{text}"
    );
    assert!(
        text.contains(&format!("{k_max:.6e} N m^2 (used)")),
        "{text}"
    );
    assert!(text.contains(&format!("{k_plane:.6e}")), "{text}");
    // The plane section, named.
    let p = fig7_with_section("plane", r#"{"stick_stiffness": "plane_section"}"#);
    let v = strand_json(&["section", p.to_str().unwrap(), "--json"]);
    assert_eq!(v["stick_stiffness"], "plane_section");
    assert_eq!(v["stick_factor"].as_f64(), Some(1.0));
    assert_eq!(v["K_max"], v["K_max_plane_section"]);
    // An unknown form is rejected naming the field.
    let p = fig7_with_section("bad-stick", r#"{"stick_stiffness": "shear_lag"}"#);
    let out = strand(&["section", p.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("section.stick_stiffness: unknown stick stiffness"),
        "{err}"
    );
}

/// One curvature sign for `strand section --curvature` and the result files. At the bending
/// points of the section-3 strand hanging under g = 12 (equivalent model, `continuous` law:
/// no slip state) where some wires stick and some slip, `strand section` at a row's strain
/// (tension / EA) and curvature gives the row's bending stiffness and, wire by wire, the
/// critical curvature and state of wires.csv. The opposite sign mirrors the wire phases and
/// gives other per-wire values, so a flipped convention fails.
#[test]
fn section_reads_the_curvature_of_the_result_files() {
    let out = TempPath::new("strand-cli-sign");
    let scene = "validation/paper-sec3-g12.json";
    let o = strand(&[
        "run",
        scene,
        "--model",
        "equivalent",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let dir = out.join("equivalent");
    let read = |f: &str| -> Vec<Vec<String>> {
        std::fs::read_to_string(dir.join(f))
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(String::from).collect())
            .collect()
    };
    let (centre, wires) = (read("centerline.csv"), read("wires.csv"));
    let num = |s: &str| s.parse::<f64>().unwrap();
    let v = strand_json(&["section", scene, "--json"]);
    let ea = v["EA"].as_f64().unwrap();
    let section = |s: &str, eps: f64, k: f64| -> serde_json::Value {
        strand_json(&[
            "section",
            scene,
            "--strain",
            &format!("{eps:e}"),
            "--curvature",
            &format!("{k:e}"),
            "--at",
            s,
            "--json",
        ])
    };
    let mut checked = 0;
    for row in centre.iter().step_by(7) {
        let here: Vec<&Vec<String>> = wires.iter().filter(|w| w[0] == row[0]).collect();
        let slipping = here.iter().filter(|w| w[4] == "slip").count();
        if here.is_empty() || slipping == 0 || slipping == here.len() {
            continue;
        }
        let (eps, k) = (num(&row[5]) / ea, num(&row[4]));
        assert!(
            k < 0.0,
            "the hanging cantilever's curvature is negative: {row:?}"
        );
        let p = section(&row[0], eps, k);
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(1e-300);
        assert!(
            rel(p["secant_stiffness"].as_f64().unwrap(), num(&row[6])) < 1e-9,
            "{p} vs {row:?}"
        );
        let same = |p: &serde_json::Value| {
            here.iter()
                .zip(p["wires"].as_array().unwrap())
                .all(|(w, pw)| {
                    let crit = pw["critical_curvature"]
                        .as_f64()
                        .map_or(String::new(), |c| format!("{c}"));
                    let close = match (crit.is_empty(), w[3].is_empty()) {
                        (true, true) => true,
                        (false, false) => rel(num(&crit), num(&w[3])) < 1e-9,
                        _ => false,
                    };
                    close && pw["state"] == w[4].as_str()
                })
        };
        assert!(same(&p), "{p} vs {here:?}");
        assert!(
            !same(&section(&row[0], eps, -k)),
            "the sign matters at {row:?}"
        );
        checked += 1;
    }
    assert!(checked >= 3, "{checked} mixed rows");
}
