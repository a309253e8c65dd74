//! Regression against `golden/<scene>.json`: the tip, a few centreline points and, for
//! dynamics, the energies at the end of every model's run, stored with their provenance.
//! `--bless` rewrites the files; numbers are never edited by hand.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::{Deserialize, Serialize};

use super::machine::Provenance;
use super::report::{Bound, Row, worse, worst};
use super::results::{Centerline, Energy};
use super::tolerances::GoldenTol;

/// Fractions of the length where centreline points are stored.
const SAMPLES: [f64; 4] = [0.25, 0.5, 0.75, 1.0];

/// Stored results of one model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSnapshot {
    /// Tip position at the end (m): (x, y), and z for a run that leaves the XY plane.
    pub tip: Vec<f64>,
    /// Centreline points (s, x, y), and z for a run that leaves the XY plane, at the end (m).
    pub centerline: Vec<Vec<f64>>,
    /// Dynamics: kinetic, gravity, elastic and dissipated energy at the end (J).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy_end: Option<[f64; 4]>,
}

impl ModelSnapshot {
    /// Takes the snapshot from the model folder `dir` of a run of a strand of length
    /// `length`, with the tip from its summary.
    pub fn take(dir: &Path, tip: [f64; 3], length: f64, dynamic: bool) -> anyhow::Result<Self> {
        let c = Centerline::load(dir)?;
        // A planar run keeps the stored form (x, y); z is stored where the run has one.
        let spatial = tip[2] != 0.0 || c.z.iter().any(|z| *z != 0.0);
        let dims = if spatial { 3 } else { 2 };
        let centerline = SAMPLES
            .iter()
            .map(|f| {
                let s = f * length;
                let mut row = vec![s];
                row.extend_from_slice(&c.position(s)[..dims]);
                row
            })
            .collect();
        let energy_end = if dynamic {
            Some(Energy::load(dir)?.last())
        } else {
            None
        };
        Ok(ModelSnapshot {
            tip: tip[..dims].to_vec(),
            centerline,
            energy_end,
        })
    }
}

/// A golden file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Golden {
    /// Scene name.
    pub scene: String,
    /// Where the numbers came from.
    pub provenance: Provenance,
    /// The tolerance comparisons use (copied from the tolerance file when blessed).
    pub tolerance: GoldenTolerance,
    /// Results by model name.
    pub models: BTreeMap<String, ModelSnapshot>,
}

/// The tolerance stored with a golden file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoldenTolerance {
    /// Position (m).
    pub position: f64,
    /// Energy (J).
    pub energy: f64,
}

/// Distance between two stored points of 2 or 3 coordinates (a missing z is zero) (m).
fn distance(a: &[f64], b: &[f64]) -> f64 {
    let at = |p: &[f64], k: usize| p.get(k).copied().unwrap_or(0.0);
    if a.len() < 2 || b.len() < 2 || a.len() > 3 || b.len() > 3 {
        return f64::INFINITY;
    }
    (0..3)
        .map(|k| (at(a, k) - at(b, k)).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Path of the golden file of `scene` in `dir`.
pub fn path(dir: &Path, scene: &str) -> PathBuf {
    dir.join(format!("{scene}.json"))
}

/// Writes the golden file of `scene`.
pub fn bless(
    dir: &Path,
    scene: &str,
    provenance: &Provenance,
    tol: &GoldenTol,
    models: BTreeMap<String, ModelSnapshot>,
) -> anyhow::Result<PathBuf> {
    let g = Golden {
        scene: scene.into(),
        provenance: provenance.clone(),
        tolerance: GoldenTolerance {
            position: tol.position,
            energy: tol.energy,
        },
        models,
    };
    let p = path(dir, scene);
    let text = serde_json::to_string_pretty(&g).context("serializing a golden file")?;
    std::fs::write(&p, text + "\n").with_context(|| format!("writing {}", p.display()))?;
    Ok(p)
}

/// Compares the current results with the golden file of `scene`: per model, the largest
/// position difference and, for dynamics, the largest energy difference. A missing or
/// unreadable golden file is a failure.
pub fn compare(
    dir: &Path,
    scene: &str,
    tol: &GoldenTol,
    current: &BTreeMap<String, ModelSnapshot>,
) -> Vec<Row> {
    const CHECK: &str = "golden";
    let p = path(dir, scene);
    if !p.exists() {
        return vec![Row::failed(
            scene,
            CHECK,
            "-",
            format!(
                "{} is missing: review the results, then run `cargo xtask validate --bless \
                 --scene {scene}`",
                p.display()
            ),
        )];
    }
    let golden: Golden = match std::fs::read_to_string(&p)
        .map_err(anyhow::Error::from)
        .and_then(|t| serde_json::from_str(&t).map_err(anyhow::Error::from))
    {
        Ok(g) => g,
        Err(e) => {
            return vec![Row::failed(
                scene,
                CHECK,
                "-",
                format!("reading {}: {e}", p.display()),
            )];
        }
    };
    let mut rows = Vec::new();
    let names: Vec<&String> = golden.models.keys().chain(current.keys()).collect();
    let mut seen = Vec::new();
    for name in names {
        if seen.contains(&name) {
            continue;
        }
        seen.push(name);
        let (Some(g), Some(c)) = (golden.models.get(name), current.get(name)) else {
            let why = if current.contains_key(name) {
                "has no stored results for this model: re-bless after review"
            } else {
                "stores results for a model this run did not produce"
            };
            rows.push(Row::failed(
                scene,
                CHECK,
                &format!("{name} position"),
                format!("{} {why}", p.display()),
            ));
            continue;
        };
        let mut dp = distance(&g.tip, &c.tip);
        if g.centerline.len() != c.centerline.len() {
            dp = f64::INFINITY;
        }
        for (a, b) in g.centerline.iter().zip(&c.centerline) {
            let d = if a.is_empty() || b.is_empty() || (a[0] - b[0]).abs() > 1e-12 {
                f64::INFINITY
            } else {
                distance(&a[1..], &b[1..])
            };
            dp = worse(dp, d);
        }
        rows.push(Row::measured(
            scene,
            CHECK,
            &format!("{name} position"),
            dp,
            "m",
            Bound::AtMost(tol.position),
        ));
        match (g.energy_end, c.energy_end) {
            (Some(a), Some(b)) => {
                let de = worst(a.iter().zip(&b).map(|(x, y)| (x - y).abs()));
                rows.push(Row::measured(
                    scene,
                    CHECK,
                    &format!("{name} energy"),
                    de,
                    "J",
                    Bound::AtMost(tol.energy),
                ));
            }
            (None, None) => {}
            _ => rows.push(Row::failed(
                scene,
                CHECK,
                &format!("{name} energy"),
                "the stored and current runs differ in kind (static/dynamic): re-bless after \
                 review",
            )),
        }
    }
    let stored = &golden.provenance;
    if let Some(first) = rows.first_mut()
        && first.note.is_empty()
    {
        first.note = format!(
            "stored {} at commit {}",
            stored.date,
            &stored.commit[..stored.commit.len().min(12)]
        );
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validate::machine::Machine;
    use crate::validate::report::Status;

    fn snap(dx: f64) -> BTreeMap<String, ModelSnapshot> {
        snap_z(dx, None)
    }

    /// A snapshot; with `z`, of a run off the XY plane.
    fn snap_z(dx: f64, z: Option<f64>) -> BTreeMap<String, ModelSnapshot> {
        let mut m = BTreeMap::new();
        let mut tip = vec![0.1 + dx, -0.3];
        let mut point = vec![0.1, 0.09, -0.02];
        if let Some(z) = z {
            tip.push(z);
            point.push(0.5 * z);
        }
        m.insert(
            "equivalent".to_string(),
            ModelSnapshot {
                tip,
                centerline: vec![point],
                energy_end: Some([1.0, -2.0, 0.5, 0.1]),
            },
        );
        m
    }

    /// Position and energy limits of 1e-6 for the tests.
    fn test_tol() -> GoldenTol {
        GoldenTol {
            position: 1e-6,
            energy: 1e-6,
            why: "test".into(),
            quick: None,
        }
    }

    /// Provenance of a test snapshot.
    fn test_provenance() -> Provenance {
        Provenance {
            command: "test".into(),
            commit: "abc".into(),
            date: "today".into(),
            profile: "debug".into(),
            machine: Machine::detect(),
        }
    }

    /// A stored z counts: a run that moves off the plane by 1e-3 m fails, and a stored planar
    /// snapshot compares with a planar run (missing z is zero).
    #[test]
    fn distances_include_z() {
        let dir = std::env::temp_dir().join(format!("xtask-golden-z-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let tol = test_tol();
        let prov = test_provenance();
        bless(&dir, "s", &prov, &tol, snap_z(0.0, Some(0.2))).unwrap();
        let rows = compare(&dir, "s", &tol, &snap_z(0.0, Some(0.2)));
        assert!(rows.iter().all(|r| r.status == Status::Pass), "{rows:?}");
        let rows = compare(&dir, "s", &tol, &snap_z(0.0, Some(0.201)));
        assert_eq!(rows[0].status, Status::Fail);
        assert!((rows[0].value.unwrap() - 1e-3).abs() < 1e-12, "{rows:?}");
        bless(&dir, "s", &prov, &tol, snap(0.0)).unwrap();
        let rows = compare(&dir, "s", &tol, &snap_z(0.0, Some(0.0)));
        assert!(rows.iter().all(|r| r.status == Status::Pass), "{rows:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn missing_file_says_bless_and_changes_fail() {
        let dir = std::env::temp_dir().join(format!("xtask-golden-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let tol = test_tol();
        let rows = compare(&dir, "s", &tol, &snap(0.0));
        assert_eq!(rows[0].status, Status::Fail);
        assert!(rows[0].note.contains("--bless"), "{}", rows[0].note);
        let prov = test_provenance();
        bless(&dir, "s", &prov, &tol, snap(0.0)).unwrap();
        let rows = compare(&dir, "s", &tol, &snap(0.0));
        assert!(rows.iter().all(|r| r.status == Status::Pass), "{rows:?}");
        let rows = compare(&dir, "s", &tol, &snap(1e-3));
        assert_eq!(rows[0].status, Status::Fail);
        assert_eq!(rows[1].status, Status::Pass);
        // A NaN anywhere fails its comparison (`f64::max` would drop it and pass).
        let rows = compare(&dir, "s", &tol, &snap(f64::NAN));
        assert_eq!(rows[0].status, Status::Fail);
        for (i, energy) in [(0, false), (1, false), (0, true)] {
            let mut bad = snap(0.0);
            let m = bad.get_mut("equivalent").unwrap();
            if energy {
                m.energy_end.as_mut().unwrap()[2] = f64::NAN;
            } else {
                m.centerline[0][1 + i] = f64::NAN;
            }
            let rows = compare(&dir, "s", &tol, &bad);
            let failed = rows.iter().filter(|r| r.status == Status::Fail).count();
            assert_eq!(failed, 1, "{rows:?}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn nan_is_the_worst_value() {
        use crate::validate::report::{worse, worst};
        assert!(worse(1.0, f64::NAN).is_nan() && worse(f64::NAN, 1.0).is_nan());
        assert!(worst([0.1, f64::NAN, 3.0]).is_nan());
        assert_eq!(worst([0.1, 3.0, 2.0]), 3.0);
        assert_eq!(worst([]), 0.0);
    }
}
