//! One model's run against another's on the same scene (SPEC 7): centreline distance in 3D at
//! equal material coordinate (max and RMS over s), tip distance, and in dynamics the tip
//! distance over the output times and the energy differences per component (with the work of
//! moving supports where a run books it).

use std::path::Path;

use anyhow::{Context, bail};

use super::report::{Bound, Row, worse, worst};
use super::results::{Centerline, Energy, Table, summary};
use super::tolerances::DistanceTol;

/// Differences between two runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Largest centreline distance over s, at the end (m).
    pub max: f64,
    /// RMS centreline distance over the first run's points, at the end (m).
    pub rms: f64,
    /// Tip distance at the end (m).
    pub tip: f64,
    /// Dynamics: largest and RMS tip distance over the common output times (m).
    pub tip_over_time: Option<(f64, f64)>,
    /// Dynamics: largest difference over the output times of kinetic, gravity, elastic,
    /// dissipated, support work and the total (J), and the larger run's largest kinetic
    /// energy (J). Dissipated is net of the work the section law's non-potential part did on
    /// the strand (a beam model's `non_potential`; the fine model has none): the energy the
    /// strand lost, which is what its friction dissipates. The total is kinetic + gravity +
    /// elastic + that net dissipation - support work, the runs' own ledger.
    pub energy: Option<([f64; 6], f64)>,
}

/// Compares the model folders `a` and `b` (each with `centerline.csv`, and for dynamics
/// `tip.csv` and `energy.csv`); `b` is interpolated linearly at `a`'s material coordinates.
pub fn compare(a: &Path, b: &Path, dynamic: bool) -> anyhow::Result<Comparison> {
    let (ca, cb) = (Centerline::load(a)?, Centerline::load(b)?);
    // The models sample the strand at different points (a beam at its Gauss points, the fine
    // model at its joints): compare at `a`'s points inside `b`'s range.
    let (lo, hi) = (cb.s[0], cb.s[cb.s.len() - 1]);
    let slack = 1e-9 * hi.abs().max(1.0);
    let mut max: f64 = 0.0;
    let mut sum = 0.0;
    let mut count = 0usize;
    for i in 0..ca.s.len() {
        if ca.s[i] < lo - slack || ca.s[i] > hi + slack {
            continue;
        }
        let d = dist(ca.point(i), cb.position(ca.s[i]));
        max = worse(max, d);
        sum += d * d;
        count += 1;
    }
    if count == 0 {
        bail!("the runs' centrelines share no material coordinates");
    }
    let (ta, tb) = (summary_tip(a)?, summary_tip(b)?);
    let tip = dist(ta, tb);
    let mut c = Comparison {
        max: worse(max, tip),
        rms: (sum / count as f64).sqrt(),
        tip,
        tip_over_time: None,
        energy: None,
    };
    if dynamic {
        c.tip_over_time = Some(tip_over_time(a, b)?);
        let (ea, eb) = (Energy::load(a)?, Energy::load(b)?);
        let pairs = common_times(&ea.t, &eb.t);
        if pairs.is_empty() {
            bail!("energy.csv: no common output times");
        }
        let mut diff = [0.0f64; 6];
        for (i, j) in pairs {
            let (da, db) = (
                ea.dissipated[i] - ea.non_potential[i],
                eb.dissipated[j] - eb.non_potential[j],
            );
            let sa = ea.kinetic[i] + ea.gravity[i] + ea.elastic[i] + da - ea.supports[i];
            let sb = eb.kinetic[j] + eb.gravity[j] + eb.elastic[j] + db - eb.supports[j];
            let d = [
                ea.kinetic[i] - eb.kinetic[j],
                ea.gravity[i] - eb.gravity[j],
                ea.elastic[i] - eb.elastic[j],
                da - db,
                ea.supports[i] - eb.supports[j],
                sa - sb,
            ];
            for (m, v) in diff.iter_mut().zip(d) {
                *m = worse(*m, v.abs());
            }
        }
        let kmax = worst(ea.kinetic.iter().chain(&eb.kinetic).copied());
        c.energy = Some((diff, kmax));
    }
    Ok(c)
}

/// Distance between two points (m).
fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The tip position at the end from a model folder's `summary.json` (m).
fn summary_tip(dir: &Path) -> anyhow::Result<[f64; 3]> {
    let v = summary(dir)?;
    let tip = v["tip"]
        .as_array()
        .filter(|a| a.len() == 3)
        .with_context(|| format!("{}: no tip", dir.join("summary.json").display()))?;
    let mut out = [0.0; 3];
    for (o, t) in out.iter_mut().zip(tip) {
        *o = t.as_f64().unwrap_or(f64::NAN);
    }
    Ok(out)
}

/// Index pairs of equal output times (to 1e-9 of the step between frames).
fn common_times(a: &[f64], b: &[f64]) -> Vec<(usize, usize)> {
    let tol = 1e-9 * a.last().copied().unwrap_or(1.0).abs().max(1e-12);
    let mut out = Vec::new();
    let mut j = 0;
    for (i, &t) in a.iter().enumerate() {
        while j < b.len() && b[j] < t - tol {
            j += 1;
        }
        if j < b.len() && (b[j] - t).abs() <= tol {
            out.push((i, j));
        }
    }
    out
}

fn tip_over_time(a: &Path, b: &Path) -> anyhow::Result<(f64, f64)> {
    let load = |d: &Path| -> anyhow::Result<[Vec<f64>; 4]> {
        let t = Table::load(&d.join("tip.csv"))?;
        Ok([
            t.column("t")?,
            t.column("x")?,
            t.column("y")?,
            t.column("z")?,
        ])
    };
    let (ta, tb) = (load(a)?, load(b)?);
    let pairs = common_times(&ta[0], &tb[0]);
    if pairs.is_empty() {
        bail!("tip.csv: no common output times");
    }
    let mut max: f64 = 0.0;
    let mut sum = 0.0;
    for &(i, j) in &pairs {
        let d = dist(
            [ta[1][i], ta[2][i], ta[3][i]],
            [tb[1][j], tb[2][j], tb[3][j]],
        );
        max = worse(max, d);
        sum += d * d;
    }
    Ok((max, (sum / pairs.len() as f64).sqrt()))
}

/// The limit of a dynamic comparison's total-energy difference: the sum of the two runs'
/// energy-balance limits (each relative to its own largest kinetic energy, so to the larger
/// run's too), since the total energies of two runs from the same state differ by no more
/// than their two balance errors; `open` when either of those limits is an open claim (the
/// total inherits it and is reported as open, neither pass nor fail).
#[derive(Debug, Clone, PartialEq)]
pub struct TotalLimit {
    /// Sum of the two balance limits (relative to the largest kinetic energy).
    pub limit: f64,
    /// Why a balance limit it sums is open, if one is.
    pub open: Option<String>,
}

/// The rows of `check` for the comparison of `a` with `b`; in dynamics the total energy's
/// difference is judged against `balance` ([`TotalLimit`]).
pub fn rows(
    scene: &str,
    check: &str,
    a: &Path,
    b: &Path,
    dynamic: bool,
    tol: &DistanceTol,
    balance: Option<&TotalLimit>,
) -> Vec<Row> {
    let c = match compare(a, b, dynamic).context("comparing the runs") {
        Ok(c) => c,
        Err(e) => return vec![Row::failed(scene, check, "-", format!("{e:#}"))],
    };
    let end = if dynamic { " at the end" } else { "" };
    let mut rows = vec![
        Row::measured(scene, check, "max", c.max, "m", Bound::AtMost(tol.max))
            .with_note(format!("largest centreline distance over s{end}")),
        Row::measured(scene, check, "rms", c.rms, "m", Bound::AtMost(tol.rms)),
        Row::measured(scene, check, "tip", c.tip, "m", Bound::AtMost(tol.tip)),
    ];
    if let Some((max, rms)) = c.tip_over_time {
        rows.push(Row::measured(
            scene,
            check,
            "tip max over t",
            max,
            "m",
            Bound::AtMost(tol.max),
        ));
        rows.push(Row::measured(
            scene,
            check,
            "tip rms over t",
            rms,
            "m",
            Bound::AtMost(tol.rms),
        ));
    }
    if let Some((diff, kmax)) = c.energy {
        rows.extend(energy_rows(scene, check, &diff, kmax, tol.energy, balance));
    }
    rows
}

/// The energy rows of a dynamic comparison, each difference relative to `kmax`. Two
/// components have a limit that follows from an argument: gravity's (`gravity`, the weight
/// times the position limit: the potential of gravity is the weight times the height of the
/// centre of mass, which moves no more than the centreline) and the total's (`balance`, the
/// two runs' balance limits). How the rest splits among kinetic, elastic and dissipated
/// energy and the supports' work is bounded by neither (energy traded between kinetic and
/// elastic leaves the position and the total unchanged), so those rows are reported without
/// a limit.
fn energy_rows(
    scene: &str,
    check: &str,
    diff: &[f64; 6],
    kmax: f64,
    gravity: Option<f64>,
    balance: Option<&TotalLimit>,
) -> Vec<Row> {
    let names = [
        "kinetic",
        "gravity",
        "elastic",
        "dissipated",
        "support work",
        "total",
    ];
    let moving = diff[4] != 0.0;
    let mut rows = Vec::new();
    for (name, &d) in names.iter().zip(diff) {
        if *name == "support work" && !moving {
            continue;
        }
        let (bound, why) = match *name {
            "gravity" => (
                gravity,
                "an `energy` tolerance (the weight times the position limit)",
            ),
            "total" => (
                balance.map(|b| b.limit),
                "an `energy-balance` tolerance (the two runs' balances)",
            ),
            _ => (None, ""),
        };
        let metric = format!("{name} energy");
        let note = format!("{d:.3e} J over the output times, relative to {kmax:.3e} J");
        let value = d / kmax.max(f64::MIN_POSITIVE);
        let row = match (why.is_empty(), bound) {
            (true, _) => {
                Row::measured(scene, check, &metric, value, "", Bound::None).with_note(format!(
                    "{note}; bounded by neither the position limit nor the balances (energy \
                     traded among these components leaves both unchanged): reported"
                ))
            }
            (false, Some(limit)) => {
                let row = Row::measured(scene, check, &metric, value, "", Bound::AtMost(limit))
                    .with_note(note);
                match balance.and_then(|b| b.open.as_deref()) {
                    Some(why) if *name == "total" => row.opened(&format!(
                        "its limit sums the two runs' energy-balance limits, one of which is \
                         open: {why}"
                    )),
                    _ => row,
                }
            }
            (false, None) => Row::failed(
                scene,
                check,
                &metric,
                format!("a dynamic scene needs {why} in validation/tolerances.json"),
            ),
        };
        rows.push(row);
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validate::report::Status;

    fn write_run(dir: &Path, dy: f64, dk: f64) {
        std::fs::create_dir_all(dir).unwrap();
        let mut c = String::from("s,x,y,z,curvature,tension,bending_stiffness\n");
        for i in 0..=10 {
            let s = i as f64 * 0.1;
            c += &format!("{s},{s},{},0,0,0,1\n", -0.1 * s + dy * s);
        }
        std::fs::write(dir.join("centerline.csv"), c).unwrap();
        let mut t = String::from("t,x,y,z,vx,vy,vz\n");
        let mut e = String::from("t,kinetic,gravity,elastic,dissipated,total\n");
        for k in 0..=4 {
            let time = k as f64 * 0.01;
            t += &format!("{time},1,{},0,0,0,0\n", -0.1 + dy * k as f64);
            e += &format!("{time},{},-1,0,0,0\n", 1.0 + dk * k as f64);
        }
        std::fs::write(dir.join("tip.csv"), t).unwrap();
        std::fs::write(dir.join("energy.csv"), e).unwrap();
        let tip = format!("{{\"tip\": [1.0, {}, 0.0]}}", -0.1 + dy);
        std::fs::write(dir.join("summary.json"), tip).unwrap();
    }

    #[test]
    fn distances_and_energy_differences() {
        let root = std::env::temp_dir().join(format!("xtask-compare-{}", std::process::id()));
        let (a, b) = (root.join("a"), root.join("b"));
        write_run(&a, 0.0, 0.0);
        write_run(&b, 1e-3, 0.01);
        let c = compare(&a, &b, true).unwrap();
        assert!(
            (c.max - 1e-3).abs() < 1e-12 && (c.tip - 1e-3).abs() < 1e-12,
            "{c:?}"
        );
        let (tmax, _) = c.tip_over_time.unwrap();
        assert!((tmax - 4e-3).abs() < 1e-12);
        let (diff, kmax) = c.energy.unwrap();
        assert!((diff[0] - 0.04).abs() < 1e-12 && (diff[5] - 0.04).abs() < 1e-12);
        assert_eq!(diff[4], 0.0);
        assert!((kmax - 1.04).abs() < 1e-12);
        let tol = DistanceTol {
            max: 2e-3,
            rms: 2e-3,
            tip: 2e-3,
            energy: Some(0.01),
            why: "test".into(),
            quick: None,
            equivalent: None,
        };
        let total = TotalLimit {
            limit: 0.01,
            open: None,
        };
        let r = rows("s", "equivalent-vs-fine", &a, &b, true, &tol, Some(&total));
        let with = |s: Status| -> Vec<&str> {
            r.iter()
                .filter(|r| r.status == s)
                .map(|r| r.metric.as_str())
                .collect()
        };
        assert_eq!(
            with(Status::Fail),
            ["tip max over t", "tip rms over t", "total energy"],
            "{r:?}"
        );
        // Kinetic energy moved into elastic energy changes neither the position nor the
        // total: those components are reported, not judged.
        assert_eq!(
            with(Status::Reported),
            ["kinetic energy", "elastic energy", "dissipated energy"]
        );
        // Without a balance limit the total row cannot be judged: it fails, saying so.
        let r = rows("s", "equivalent-vs-fine", &a, &b, true, &tol, None);
        assert!(
            r.iter()
                .any(|r| r.metric == "total energy" && r.status == Status::Fail)
        );
        // A total whose limit sums an open balance limit is open, neither pass nor fail.
        let open = TotalLimit {
            limit: 0.01,
            open: Some("the fine model's balance limit is not argued".into()),
        };
        let r = rows("s", "equivalent-vs-fine", &a, &b, true, &tol, Some(&open));
        let total = r.iter().find(|r| r.metric == "total energy").unwrap();
        assert_eq!(total.status, Status::Open, "{total:?}");
        assert!(total.note.contains("not argued"), "{}", total.note);
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// The gravity row fails when one run's centre of mass sits lower by more than the
    /// position limit admits (a perturbed input: the gravity column shifted).
    #[test]
    fn a_gravity_energy_difference_fails_its_row() {
        let root = std::env::temp_dir().join(format!("xtask-compare-g-{}", std::process::id()));
        let (a, b) = (root.join("a"), root.join("b"));
        write_run(&a, 0.0, 0.0);
        write_run(&b, 0.0, 0.0);
        let mut e = String::from("t,kinetic,gravity,elastic,dissipated,total\n");
        for k in 0..=4 {
            let time = k as f64 * 0.01;
            // 0.02 J lower, the same total (kinetic takes it): only gravity's row moves.
            e += &format!("{time},1.02,-1.02,0,0,0\n");
        }
        std::fs::write(b.join("energy.csv"), e).unwrap();
        let tol = DistanceTol {
            max: 2e-3,
            rms: 2e-3,
            tip: 2e-3,
            energy: Some(0.01),
            why: "test".into(),
            quick: None,
            equivalent: None,
        };
        let total = TotalLimit {
            limit: 0.01,
            open: None,
        };
        let r = rows("s", "c", &a, &b, true, &tol, Some(&total));
        let failed: Vec<&str> = r
            .iter()
            .filter(|r| r.status == Status::Fail)
            .map(|r| r.metric.as_str())
            .collect();
        assert_eq!(failed, ["gravity energy"], "{r:?}");
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// A beam run whose law put in by non-potential work what its slip dissipated loses no
    /// energy net: against a run without either, the dissipated and total rows agree.
    #[test]
    fn dissipation_is_compared_net_of_non_potential_work() {
        let root = std::env::temp_dir().join(format!("xtask-compare-np-{}", std::process::id()));
        let (a, b) = (root.join("a"), root.join("b"));
        write_run(&a, 0.0, 0.0);
        write_run(&b, 0.0, 0.0);
        let mut e = String::from("t,kinetic,gravity,elastic,dissipated,total,non_potential\n");
        for k in 0..=4 {
            let (time, w) = (k as f64 * 0.01, 0.02 * k as f64);
            e += &format!("{time},1,-1,0,{w},0,{w}\n");
        }
        std::fs::write(a.join("energy.csv"), e).unwrap();
        let (diff, _) = compare(&a, &b, true).unwrap().energy.unwrap();
        assert_eq!(diff, [0.0; 6]);
        std::fs::remove_dir_all(&root).unwrap();
    }
}
