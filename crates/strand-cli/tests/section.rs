//! `strand section --json` on the bundled Table 1 scene prints the SPEC 8 sanity values.

use std::process::Command;

fn strand(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_strand"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .unwrap()
}

#[test]
fn section_json_prints_spec8_values() {
    let out = strand(&["section", "validation/paper-fig7-g8.json", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
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
    let out = strand(&[
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
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
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
    let dir = std::env::temp_dir().join(format!("strand-cli-test-{}", std::process::id()));
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
fn fig7_with_section(tag: &str, section: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("strand-cli-section-{}", std::process::id()));
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
    let p = dir.join(format!("{tag}.json"));
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    p
}

/// Without `section`, K_min is Costello's (core E I plus six wires E I cos(alpha) 2 / (2 + nu
/// sin^2 alpha), written out here) and the paper's cos^3 value is shown beside it.
#[test]
fn section_shows_the_base_stiffness_and_both_values() {
    let p = fig7_with_section("default", "");
    let out = strand(&["section", p.to_str().unwrap(), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
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
    let out = strand(&["section", p.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
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
