//! Figures a `why` text of `validation/tolerances.json` quotes from the report.
//!
//! A `why` states the argument of its limit; the value a check measures lives in the report.
//! Where the argument needs a figure the same run measures (e.g. a balance at the scene's step
//! set against the same balance at half the step), the `why` writes it as a quotation
//!
//! ```text
//! {report CHECK METRIC = VALUE}          a row of the same scene
//! {report SCENE CHECK METRIC = VALUE}    a row of another scene
//! ```
//!
//! (`CHECK METRIC` as the report's check column prints it, e.g. `energy-balance equivalent`,
//! VALUE in the precision the text needs). [`stale`] compares every quotation with the row it
//! names: a figure that is not the row's value rounded to the quoted digits fails, so a
//! quotation cannot drift from the report as the code moves.

use std::collections::BTreeSet;

use super::report::{Row, Status};

/// One quotation `{report ... = VALUE}` in a `why` text.
#[derive(Debug, Clone, PartialEq)]
pub struct Quote {
    /// The row named: `CHECK METRIC` or `SCENE CHECK METRIC`.
    pub row: String,
    /// The quoted text of the value (its digits set the precision).
    pub text: String,
    /// The quoted value.
    pub value: f64,
}

/// Check and metric of a row as the report's check column prints them.
fn check_text(r: &Row) -> String {
    if r.metric == "-" {
        r.check.clone()
    } else {
        format!("{} {}", r.check, r.metric)
    }
}

/// The quotations of `why`; a quotation that does not parse is returned as an error naming it.
pub fn parse(why: &str) -> Result<Vec<Quote>, String> {
    let mut quotes = Vec::new();
    let mut rest = why;
    while let Some(start) = rest.find("{report ") {
        let body = &rest[start + "{report ".len()..];
        let end = body
            .find('}')
            .ok_or_else(|| format!("unclosed quotation `{}`", &rest[start..]))?;
        let inner = &body[..end];
        let (row, value) = inner
            .split_once(" = ")
            .ok_or_else(|| format!("quotation `{{report {inner}}}` has no ` = VALUE`"))?;
        let text = value.split_whitespace().next().unwrap_or("").to_string();
        let v: f64 = text
            .parse()
            .map_err(|_| format!("quotation `{{report {inner}}}`: `{text}` is not a number"))?;
        quotes.push(Quote {
            row: row.trim().to_string(),
            text,
            value: v,
        });
        rest = &body[end..];
    }
    Ok(quotes)
}

/// Significant digits of a number as written (`7.35e-4` has 3, `2.4e-5` 2, `0.0012` 2).
fn digits(text: &str) -> usize {
    let mantissa = text
        .split(['e', 'E'])
        .next()
        .unwrap_or("")
        .trim_start_matches(['-', '+']);
    let d: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    d.trim_start_matches('0').len().max(1)
}

/// Whether `quoted` is `value` rounded to the digits of `text`.
pub fn agrees(text: &str, quoted: f64, value: f64) -> bool {
    if value == 0.0 || quoted == 0.0 {
        return value == quoted;
    }
    let rounded: f64 = format!("{value:.*e}", digits(text) - 1)
        .parse()
        .expect("a formatted float parses");
    (rounded - quoted).abs() <= 1e-9 * quoted.abs()
}

/// Failed rows for every stale or broken quotation in the `why` texts of `rows`.
///
/// A quotation naming a row this run did not produce is checked only when `complete` (the
/// full run of every scene, unperturbed): then it fails as naming no row; otherwise (`--quick`,
/// `--scene`) it is skipped, as its row was not run.
pub fn stale(rows: &[Row], complete: bool) -> Vec<Row> {
    let mut seen = BTreeSet::new();
    let mut failed = Vec::new();
    for r in rows {
        if r.why.is_empty() || !seen.insert((r.scene.clone(), r.check.clone())) {
            continue;
        }
        let fail = |what: &str, note: String| Row::failed(&r.scene, "why-quote", what, note);
        let quotes = match parse(&r.why) {
            Ok(q) => q,
            Err(e) => {
                failed.push(fail(&r.check, format!("the why of {}: {e}", r.check)));
                continue;
            }
        };
        for q in quotes {
            let target = rows.iter().find(|t| {
                let own = format!("{} {}", t.scene, check_text(t));
                (t.scene == r.scene && check_text(t) == q.row) || own == q.row
            });
            match target {
                Some(t) => match t.value {
                    Some(v) if agrees(&q.text, q.value, v) => {}
                    Some(v) => failed.push(fail(
                        &q.row,
                        format!(
                            "the why of {} quotes {} = {}, the report's row is {v:.3e}: quote the \
                             report or cite the row",
                            r.check, q.row, q.text
                        ),
                    )),
                    None => failed.push(fail(
                        &q.row,
                        format!(
                            "the why of {} quotes {} = {}, the row has no value ({})",
                            r.check,
                            q.row,
                            q.text,
                            if t.status == Status::Fail {
                                "it failed"
                            } else {
                                "not measured"
                            }
                        ),
                    )),
                },
                None if complete => failed.push(fail(
                    &q.row,
                    format!(
                        "the why of {} quotes `{}`, a row the report does not have",
                        r.check, q.row
                    ),
                )),
                None => {}
            }
        }
    }
    failed
}

#[cfg(test)]
mod tests {
    use super::super::report::Bound;
    use super::*;

    fn row(scene: &str, check: &str, metric: &str, value: f64, why: &str) -> Row {
        let mut r = Row::measured(scene, check, metric, value, "m", Bound::AtMost(1.0));
        r.why = why.into();
        r
    }

    #[test]
    fn quotations_parse_with_their_digits() {
        let q = parse("at h {report energy-balance equivalent = 2.4e-5}, at h/2 3.3e-4").unwrap();
        assert_eq!(q.len(), 1);
        assert_eq!(q[0].row, "energy-balance equivalent");
        assert_eq!(q[0].value, 2.4e-5);
        assert_eq!(digits("7.35e-4"), 3);
        assert_eq!(digits("2.4e-5"), 2);
        assert_eq!(digits("0.0012"), 2);
        assert_eq!(digits("3"), 1);
        assert!(parse("{report energy-balance equivalent 2.4e-5}").is_err());
        assert!(parse("{report a b = x}").is_err());
        assert!(parse("{report a b = 1").is_err());
    }

    #[test]
    fn a_figure_agrees_only_with_its_rounding() {
        assert!(agrees("2.4e-5", 2.4e-5, 2.359e-5));
        assert!(!agrees("2.6e-5", 2.6e-5, 2.359e-5));
        assert!(agrees("7.35e-4", 7.35e-4, 7.345e-4 + 1e-12));
        assert!(!agrees("7.35e-4", 7.35e-4, 7.3e-4));
        assert!(agrees("0", 0.0, 0.0));
    }

    #[test]
    fn a_stale_quotation_fails_and_a_true_one_passes() {
        let why_true = "balance {report energy-balance equivalent = 2.4e-5} at h";
        let why_stale = "balance {report energy-balance equivalent = 2.6e-5} at h";
        let other = "the other scene's {report s equivalent-vs-fine max = 1.0e-3}";
        let rows = |why: &str| {
            vec![
                row("s", "energy-balance", "equivalent", 2.359e-5, why),
                row("s", "equivalent-vs-fine", "max", 1.04e-3, ""),
                row("t", "golden", "-", 0.0, other),
            ]
        };
        assert!(stale(&rows(why_true), true).is_empty());
        let f = stale(&rows(why_stale), true);
        assert_eq!(f.len(), 1);
        assert_eq!(f[0].status, Status::Fail);
        assert!(f[0].note.contains("2.6e-5"), "{}", f[0].note);
        // A row of another scene, named with the scene.
        let mut r = rows(why_true);
        r[1].value = Some(1.06e-3);
        assert_eq!(stale(&r, true).len(), 1);
    }

    #[test]
    fn a_quotation_of_a_missing_row_fails_only_in_a_complete_run() {
        let rows = vec![row(
            "s",
            "golden",
            "-",
            0.0,
            "{report convergence-order order = 3.5}",
        )];
        assert!(stale(&rows, false).is_empty());
        assert_eq!(stale(&rows, true).len(), 1);
    }
}
