//! `cargo xtask validate` exits non-zero and names the failing checks when the model is
//! broken, and exits zero on the scene as it is.

#[path = "../../crates/strand-scene/tests/common/temp_path.rs"]
mod temp_path;

use std::process::Command;

use temp_path::TempPath;

fn validate(out: &str, extra: &[&str]) -> std::process::Output {
    let dir = TempPath::new(&format!("xtask-exit-{out}"));
    Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(["validate", "--quick", "--scene", "paper-sec3-g8", "--out"])
        .arg(&*dir)
        .args(extra)
        .output()
        .expect("xtask runs")
}

#[test]
fn a_broken_model_fails_with_the_check_named() {
    let out = validate("broken", &["--perturb-stiffness", "1.05"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(
        stderr.contains("validation failed: paper-sec3-g8 equivalent-vs-elastica max"),
        "{stderr}"
    );
    assert!(stdout.contains("FAIL"), "{stdout}");
}

#[test]
fn bless_with_a_perturbation_is_refused() {
    let out = validate("bless", &["--perturb-stiffness", "1.05", "--bless"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("refused"));
}
