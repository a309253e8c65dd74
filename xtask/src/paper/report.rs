//! The paper report: one finding per statement of the paper, our number beside it.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::Serialize;

use crate::validate::machine::Provenance;

/// How our result stands against the paper's statement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// Same statement, numbers of the same order or within the stated values.
    Agrees,
    /// Part of the statement holds.
    Partly,
    /// Our result contradicts the statement.
    Differs,
    /// We cannot compute it (yet); never a pass.
    NotAvailable,
}

impl Verdict {
    /// The word in the report.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Agrees => "agrees",
            Verdict::Partly => "partly",
            Verdict::Differs => "differs",
            Verdict::NotAvailable => "not available",
        }
    }
}

/// One statement of the paper and our result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Finding {
    /// Figure, e.g. `Fig. 12`.
    pub figure: String,
    /// What the paper states.
    pub paper: String,
    /// What we get.
    pub ours: String,
    /// Verdict.
    pub verdict: Verdict,
    /// Where and why we differ, or how the number was measured.
    pub why: String,
}

impl Finding {
    /// A finding.
    pub fn new(
        figure: &str,
        paper: impl Into<String>,
        ours: impl Into<String>,
        verdict: Verdict,
        why: impl Into<String>,
    ) -> Finding {
        Finding {
            figure: figure.into(),
            paper: paper.into(),
            ours: ours.into(),
            verdict,
            why: why.into(),
        }
    }
}

/// The whole report.
#[derive(Debug, Clone, Serialize)]
pub struct PaperReport {
    /// Machine, commit, build profile, command, date.
    pub provenance: Provenance,
    /// Wall time of the whole command (s).
    pub wall_time_s: f64,
    /// Findings, in figure order.
    pub findings: Vec<Finding>,
    /// Figures written (PNG and SVG), relative to the report's folder.
    pub figures: Vec<(String, Vec<String>)>,
}

fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

impl PaperReport {
    /// The findings for the manual (`--update-docs`): the report's Markdown from its
    /// provenance line to the end of the findings table, without its title and figures.
    pub fn docs(&self) -> String {
        let md = self.markdown();
        let body = md.split("\n## Figures").next().unwrap_or(&md);
        body.lines()
            .skip_while(|l| !l.starts_with('`'))
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The report as Markdown.
    pub fn markdown(&self) -> String {
        let p = &self.provenance;
        let mut m = String::new();
        let _ = writeln!(m, "# The paper's Figs. 7-15, reproduced\n");
        let _ = writeln!(
            m,
            "Guo, Wei, Tan, Zhao (2018), Chinese J. Theor. Appl. Mech. 50(2):373-384; what the \
             paper states is taken from SPEC section 8. Each row puts our number beside the \
             paper's statement; `not available` is never a pass.\n"
        );
        let _ = writeln!(
            m,
            "`{}` on {}; commit `{}`, {} build, {}; {:.1} s.\n",
            p.command,
            p.machine.description(),
            p.commit,
            p.profile,
            p.date,
            self.wall_time_s
        );
        let count = |v: Verdict| self.findings.iter().filter(|f| f.verdict == v).count();
        let _ = writeln!(
            m,
            "{} statements: {} agree, {} partly, {} differ, {} not available.\n",
            self.findings.len(),
            count(Verdict::Agrees),
            count(Verdict::Partly),
            count(Verdict::Differs),
            count(Verdict::NotAvailable)
        );
        let _ = writeln!(
            m,
            "| figure | paper | ours | verdict | where we differ, and why |"
        );
        let _ = writeln!(m, "|---|---|---|---|---|");
        for f in &self.findings {
            let _ = writeln!(
                m,
                "| {} | {} | {} | **{}** | {} |",
                f.figure,
                cell(&f.paper),
                cell(&f.ours),
                f.verdict.word(),
                cell(&f.why)
            );
        }
        let _ = writeln!(m, "\n## Figures\n");
        for (title, files) in &self.figures {
            if let Some(png) = files.iter().find(|f| f.ends_with(".png")) {
                let _ = writeln!(m, "### {title}\n\n![{title}]({png})\n");
            }
        }
        m
    }

    /// Writes `report.md` and `report.json` into `dir`; returns their paths.
    pub fn write(&self, dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
        let md = dir.join("report.md");
        let json = dir.join("report.json");
        std::fs::write(&md, self.markdown())
            .with_context(|| format!("writing {}", md.display()))?;
        std::fs::write(&json, serde_json::to_string_pretty(self)? + "\n")
            .with_context(|| format!("writing {}", json.display()))?;
        Ok(vec![md, json])
    }
}

/// `v` with 3 significant digits in scientific notation.
pub fn sci(v: f64) -> String {
    format!("{v:.2e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_escapes_cells_and_counts_verdicts() {
        let r = PaperReport {
            provenance: Provenance::detect(Path::new(".")),
            wall_time_s: 1.0,
            findings: vec![
                Finding::new("Fig. 7", "a|b", "c", Verdict::NotAvailable, "d"),
                Finding::new("Fig. 12", "0.149 N", "0.1499 N", Verdict::Agrees, ""),
            ],
            figures: vec![("Fig. 12".into(), vec!["fig12.png".into()])],
        };
        let md = r.markdown();
        assert!(md.contains("a\\|b") && md.contains("**not available**"));
        assert!(md.contains("1 agree, 0 partly, 0 differ, 1 not available"));
        assert!(md.contains("![Fig. 12](fig12.png)"));
    }
}
