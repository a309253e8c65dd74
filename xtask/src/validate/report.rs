//! Rows of the validation table and the report files: the table on stdout,
//! `report.md` and `report.json`.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Context;
use serde::Serialize;

use super::machine::Provenance;

/// Which side of the tolerance passes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Bound {
    /// The value must not exceed the tolerance (an error).
    AtMost(f64),
    /// The value must reach the tolerance (an observed order).
    AtLeast(f64),
    /// No tolerance (the check could not run or reports information).
    None,
}

/// Outcome of one row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Within tolerance.
    Pass,
    /// Outside tolerance, or the check could not be evaluated.
    Fail,
    /// The check cannot run in this version: neither pass nor fail.
    NotAvailable,
    /// A claim the check does not establish (it holds at the chosen discretisation but not
    /// under refinement, or its limit has no argument yet): measured and shown against its
    /// limit, neither pass nor fail.
    Open,
    /// A value reported without a limit: neither pass nor fail.
    Reported,
}

impl Status {
    fn label(self) -> &'static str {
        match self {
            Status::Pass => "pass",
            Status::Fail => "FAIL",
            Status::NotAvailable => "not available",
            Status::Open => "open",
            Status::Reported => "reported",
        }
    }
}

/// One row of the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Scene name.
    pub scene: String,
    /// Check name (as in the tolerance file).
    pub check: String,
    /// What was measured (e.g. `max`, `tip`, `x=0.92`).
    pub metric: String,
    /// Measured value; `None` when it could not be measured.
    pub value: Option<f64>,
    /// Unit of value and tolerance.
    pub unit: &'static str,
    /// Tolerance.
    pub bound: Bound,
    /// Outcome.
    pub status: Status,
    /// Why it failed, what was compared, or why it is not available.
    pub note: String,
    /// Why the tolerance is what it is (from the tolerance file).
    pub why: String,
    /// How far inside its tolerance the value lies: tolerance / value for an upper bound,
    /// value / tolerance for a lower one (above 1 passes); `None` without both.
    pub margin: Option<f64>,
}

impl Row {
    /// A measured value judged against `bound`. A non-finite value fails.
    pub fn measured(
        scene: &str,
        check: &str,
        metric: &str,
        value: f64,
        unit: &'static str,
        bound: Bound,
    ) -> Row {
        let ok = value.is_finite()
            && match bound {
                Bound::AtMost(t) => value <= t,
                Bound::AtLeast(t) => value >= t,
                Bound::None => true,
            };
        let status = match (ok, bound) {
            (false, _) => Status::Fail,
            (true, Bound::None) => Status::Reported,
            (true, _) => Status::Pass,
        };
        Row {
            scene: scene.into(),
            check: check.into(),
            metric: metric.into(),
            value: Some(value),
            unit,
            bound,
            status,
            note: String::new(),
            why: String::new(),
            margin: margin(value, bound),
        }
    }

    /// A check that could not be evaluated: a failure saying why.
    pub fn failed(scene: &str, check: &str, metric: &str, why: impl Into<String>) -> Row {
        Row {
            scene: scene.into(),
            check: check.into(),
            metric: metric.into(),
            value: None,
            unit: "",
            bound: Bound::None,
            status: Status::Fail,
            note: why.into(),
            why: String::new(),
            margin: None,
        }
    }

    /// A step that succeeded without a measurement (e.g. a golden file written).
    pub fn done(scene: &str, check: &str, note: impl Into<String>) -> Row {
        Row {
            status: Status::Pass,
            ..Row::failed(scene, check, "-", note)
        }
    }

    /// A check this version cannot run.
    pub fn not_available(scene: &str, check: &str, why: impl Into<String>) -> Row {
        Row {
            status: Status::NotAvailable,
            ..Row::failed(scene, check, "-", why)
        }
    }

    /// The same measurement reported as an open claim (`why` says why it is not established):
    /// neither a pass nor a failure, whichever side of its limit the value lies. The note
    /// says which side that is.
    pub fn opened(mut self, why: &str) -> Row {
        if self.status == Status::NotAvailable {
            return self;
        }
        let side = match self.status {
            Status::Pass => "within its limit here",
            Status::Fail => "outside its limit here",
            _ => "",
        };
        self.note = [self.note.as_str(), &format!("open ({side}): {why}")]
            .iter()
            .filter(|s| !s.is_empty())
            .copied()
            .collect::<Vec<_>>()
            .join("; ");
        self.status = Status::Open;
        self
    }

    /// Adds a note.
    pub fn with_note(mut self, note: impl Into<String>) -> Row {
        self.note = note.into();
        self
    }

    /// The row as a failure names it: scene, check and metric.
    pub fn name(&self) -> String {
        format!("{} {} {}", self.scene, self.check, self.metric)
    }

    fn value_text(&self) -> String {
        match self.value {
            Some(0.0) => format!("0{}", unit_suffix(self.unit)),
            Some(v) => format!("{v:.3e}{}", unit_suffix(self.unit)),
            None => "-".into(),
        }
    }

    fn bound_text(&self) -> String {
        match self.bound {
            Bound::AtMost(t) => format!("<= {t:.1e}{}", unit_suffix(self.unit)),
            Bound::AtLeast(t) => format!(">= {t:.2}{}", unit_suffix(self.unit)),
            Bound::None => "-".into(),
        }
    }

    fn margin_text(&self) -> String {
        match self.margin {
            Some(m) if m.is_finite() => format!("{m:.2}"),
            Some(_) => "inf".into(),
            None => "-".into(),
        }
    }

    fn check_text(&self) -> String {
        if self.metric == "-" {
            self.check.clone()
        } else {
            format!("{} {}", self.check, self.metric)
        }
    }
}

/// The margin of `value` against `bound` (see [`Row::margin`]).
fn margin(value: f64, bound: Bound) -> Option<f64> {
    if !value.is_finite() {
        return None;
    }
    match bound {
        Bound::AtMost(t) => Some(if value == 0.0 {
            f64::INFINITY
        } else {
            t / value
        }),
        Bound::AtLeast(t) if t != 0.0 => Some(value / t),
        _ => None,
    }
}

/// The larger of `a` and `b`, NaN if either is: unlike `f64::max`, which returns the other
/// value, it keeps a NaN, so that a NaN result fails the check it enters.
pub fn worse(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// The largest of `values` (0 for none), NaN if any is NaN (see [`worse`]).
pub fn worst(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, worse)
}

fn unit_suffix(unit: &str) -> String {
    if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    }
}

/// Counts of the outcomes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Rows that passed.
    pub pass: usize,
    /// Rows that failed.
    pub fail: usize,
    /// Rows not available in this version.
    pub not_available: usize,
    /// Rows whose claim is open (measured, neither pass nor fail).
    pub open: usize,
    /// Values reported without a limit.
    pub reported: usize,
}

/// The whole validation result.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// Title of `report.md`.
    pub title: String,
    /// Heading of the first column (what a row belongs to).
    pub label: String,
    /// The file the limits and their reasons come from.
    pub limits_file: String,
    /// Machine, commit, build profile and command.
    pub provenance: Provenance,
    /// Whether this was the `--quick` subset.
    pub quick: bool,
    /// Wall time of the whole validation (s).
    pub wall_time_s: f64,
    /// Outcome counts.
    pub counts: Counts,
    /// The rows.
    pub rows: Vec<Row>,
}

impl Report {
    /// Builds the report and counts the outcomes.
    pub fn new(provenance: Provenance, quick: bool, wall_time_s: f64, rows: Vec<Row>) -> Report {
        let mut counts = Counts::default();
        for r in &rows {
            match r.status {
                Status::Pass => counts.pass += 1,
                Status::Fail => counts.fail += 1,
                Status::NotAvailable => counts.not_available += 1,
                Status::Open => counts.open += 1,
                Status::Reported => counts.reported += 1,
            }
        }
        Report {
            title: "Validation report".into(),
            label: "scene".into(),
            limits_file: "validation/tolerances.json".into(),
            provenance,
            quick,
            wall_time_s,
            counts,
            rows,
        }
    }

    /// The same report with another title, first-column heading and limits file.
    pub fn titled(mut self, title: &str, label: &str, limits_file: &str) -> Report {
        self.title = title.into();
        self.label = label.into();
        self.limits_file = limits_file.into();
        self
    }

    /// Whether any row failed.
    pub fn failed(&self) -> bool {
        self.counts.fail > 0
    }

    /// The failing rows.
    pub fn failures(&self) -> impl Iterator<Item = &Row> {
        self.rows.iter().filter(|r| r.status == Status::Fail)
    }

    /// The table as aligned plain text.
    pub fn table(&self) -> String {
        let head = [
            self.label.as_str(),
            "check",
            "value",
            "tolerance",
            "margin",
            "result",
        ];
        let cells: Vec<[String; 6]> = self
            .rows
            .iter()
            .map(|r| {
                [
                    r.scene.clone(),
                    r.check_text(),
                    r.value_text(),
                    r.bound_text(),
                    r.margin_text(),
                    r.status.label().to_string(),
                ]
            })
            .collect();
        let mut width = head.map(str::len);
        for c in &cells {
            for (w, s) in width.iter_mut().zip(c) {
                *w = (*w).max(s.chars().count());
            }
        }
        let line = |c: &[String]| {
            let mut s = String::new();
            for (i, (v, w)) in c.iter().zip(width).enumerate() {
                if i > 0 {
                    s.push_str("  ");
                }
                if (2..=4).contains(&i) {
                    let _ = write!(s, "{v:>w$}");
                } else {
                    let _ = write!(s, "{v:<w$}");
                }
            }
            s.trim_end().to_string()
        };
        let mut out = line(&head.map(String::from));
        out.push('\n');
        for c in &cells {
            out.push_str(&line(c));
            out.push('\n');
        }
        let notes = self.notes();
        if !notes.is_empty() {
            out.push_str("\nnotes:\n");
            for n in notes {
                out.push_str(&format!("  {n}\n"));
            }
        }
        out.push_str(&self.summary_line());
        out.push('\n');
        out
    }

    fn notes(&self) -> Vec<String> {
        self.rows
            .iter()
            .filter(|r| !r.note.is_empty())
            .map(|r| format!("{} {}: {}", r.scene, r.check_text(), r.note))
            .collect()
    }

    /// `N passed, M failed, O open, R reported, K not available (T s)`: open claims and
    /// reported values are neither passes nor failures.
    pub fn summary_line(&self) -> String {
        format!(
            "{} passed, {} failed, {} open, {} reported, {} not available ({:.1} s{})",
            self.counts.pass,
            self.counts.fail,
            self.counts.open,
            self.counts.reported,
            self.counts.not_available,
            self.wall_time_s,
            if self.quick { ", --quick" } else { "" }
        )
    }

    /// The report's table for the manual (`--update-docs`): one line of provenance and the
    /// table of [`Report::markdown`], without its title, notes and reasons.
    pub fn docs(&self) -> String {
        let p = &self.provenance;
        let md = self.markdown();
        let table = crate::book::pages::first_table(&md).unwrap_or_default();
        format!(
            "`{}` (commit `{}`, {}, {} build, {}): {}.\n\n{table}",
            p.command,
            p.commit,
            p.date,
            p.profile,
            p.machine.description(),
            self.summary_line()
        )
    }

    /// The report as Markdown.
    pub fn markdown(&self) -> String {
        let p = &self.provenance;
        let mut s = format!("# {}\n\n", self.title);
        let _ = writeln!(s, "* command: `{}`", p.command);
        let _ = writeln!(s, "* commit: `{}`", p.commit);
        let _ = writeln!(s, "* date: {}", p.date);
        let _ = writeln!(s, "* build profile: {}", p.profile);
        let _ = writeln!(s, "* machine: {}", p.machine.description());
        let _ = writeln!(s, "* result: {}\n", self.summary_line());
        let _ = writeln!(
            s,
            "| {} | check | value | tolerance | margin | result |\n|---|---|---:|---:|---:|---|",
            self.label
        );
        for r in &self.rows {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} |",
                r.scene,
                r.check_text(),
                r.value_text(),
                r.bound_text(),
                r.margin_text(),
                r.status.label()
            );
        }
        let notes = self.notes();
        if !notes.is_empty() {
            s.push_str("\nNotes:\n\n");
            for n in notes {
                let _ = writeln!(s, "* {n}");
            }
        }
        let _ = writeln!(s, "\nWhy these tolerances (`{}`):\n", self.limits_file);
        let mut seen: Vec<(&str, &str)> = Vec::new();
        for r in self.rows.iter().filter(|r| !r.why.is_empty()) {
            if !seen.contains(&(&r.scene, &r.check)) {
                seen.push((&r.scene, &r.check));
                let _ = writeln!(s, "* {} {}: {}", r.scene, r.check, r.why);
            }
        }
        s
    }

    /// Writes `report.md` and `report.json` into `dir`.
    pub fn write(&self, dir: &Path) -> anyhow::Result<()> {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        let md = dir.join("report.md");
        std::fs::write(&md, self.markdown())
            .with_context(|| format!("writing {}", md.display()))?;
        let js = dir.join("report.json");
        let text = serde_json::to_string_pretty(self).context("serializing the report")?;
        std::fs::write(&js, text + "\n").with_context(|| format!("writing {}", js.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_judge_values() {
        let r = Row::measured("s", "c", "m", 1.0, "m", Bound::AtMost(2.0));
        assert_eq!(r.status, Status::Pass);
        assert_eq!(r.margin, Some(2.0));
        let r = Row::measured("s", "c", "m", 3.0, "m", Bound::AtMost(2.0));
        assert_eq!(r.status, Status::Fail);
        assert!(r.margin.unwrap() < 1.0);
        let r = Row::measured("s", "c", "order", 1.5, "", Bound::AtLeast(2.0));
        assert_eq!(r.status, Status::Fail);
        let r = Row::measured("s", "c", "m", f64::NAN, "m", Bound::AtMost(2.0));
        assert_eq!(r.status, Status::Fail);
        assert_eq!(
            Row::not_available("s", "c", "why").status,
            Status::NotAvailable
        );
        assert_eq!(
            Row::measured("s", "c", "m", 1.0, "m", Bound::None).status,
            Status::Reported
        );
    }

    /// An open claim is neither a pass nor a failure on either side of its limit, and the
    /// counts keep it apart.
    #[test]
    fn open_claims_are_not_passes() {
        let inside = Row::measured("s", "c", "m", 1.0, "m", Bound::AtMost(2.0)).opened("why");
        let outside = Row::measured("s", "c", "m", 3.0, "m", Bound::AtMost(2.0)).opened("why");
        assert_eq!(
            (inside.status, outside.status),
            (Status::Open, Status::Open)
        );
        assert!(inside.note.contains("within") && outside.note.contains("outside"));
        let r = Report::new(
            Provenance::detect(std::path::Path::new(".")),
            true,
            0.0,
            vec![
                inside,
                outside,
                Row::measured("s", "c", "m", 1.0, "m", Bound::None),
            ],
        );
        assert_eq!((r.counts.pass, r.counts.fail, r.counts.open), (0, 0, 2));
        assert_eq!(r.counts.reported, 1);
        assert!(!r.failed());
    }
}
