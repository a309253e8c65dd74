//! `cargo xtask book`: checks the manual's internal links and `README.md`'s relative links,
//! and builds the manual with mdBook into `target/book/`. The manual's source is `docs/book/` (`book.toml`, `src/SUMMARY.md`).

pub mod links;
pub mod pages;

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, bail};

/// The mdBook release the book is written for (its `book.toml` format is 0.5's); installed
/// by `cargo xtask book` when no mdBook 0.5 is on the PATH. 0.5.4 needs Rust 1.88.
const MDBOOK_VERSION: &str = "0.5.4";

/// Options of `cargo xtask book`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct BookArgs {
    /// Only check the links; do not build.
    #[arg(long)]
    pub check_only: bool,
    /// Folder of the rendered book [default: target/book].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// The workspace's target folder (`$CARGO_TARGET_DIR` or `target/`).
fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map_or_else(
        || crate::validate::repo_root().join("target"),
        PathBuf::from,
    )
}

/// Checks the book's and the README's links, then builds the book; fails naming the file and
/// line of each broken link.
pub fn run(args: &BookArgs) -> anyhow::Result<()> {
    let src = pages::book_src();
    let mut result = links::check(&src)?;
    let readme = links::check_readme(&crate::validate::repo_root(), &src)?;
    for b in &result.broken {
        eprintln!("docs/book/src/{b}");
    }
    for b in &readme.broken {
        eprintln!("{b}");
    }
    let broken = result.broken.len() + readme.broken.len();
    if broken > 0 {
        bail!("{broken} broken link(s) in the book and README.md");
    }
    println!(
        "book: {} internal links and {} anchors resolve; README.md: {} relative links",
        result.links,
        result.anchors.len(),
        readme.links
    );
    // The README's anchors into the book are checked against the rendered pages too.
    result.anchors.extend(readme.anchors);
    result.anchors.sort();
    result.anchors.dedup();
    if args.check_only {
        return Ok(());
    }
    let mdbook = mdbook()?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| target_dir().join("book"));
    let out = std::path::absolute(&out).context("resolving the output folder")?;
    let book = crate::validate::repo_root().join("docs/book");
    let status = Command::new(&mdbook)
        .arg("build")
        .arg(&book)
        .arg("--dest-dir")
        .arg(&out)
        .status()
        .with_context(|| format!("running {}", mdbook.display()))?;
    if !status.success() {
        bail!("mdbook build failed");
    }
    // The anchors the check found must be ids of the rendered pages: this holds the check's
    // id rule to mdBook's own.
    let missing = links::missing_in_html(&out, &result.anchors)?;
    if !missing.is_empty() {
        for a in &missing {
            eprintln!(
                "{}: no element with id `{}` in the rendered page",
                a.page.display(),
                a.id
            );
        }
        bail!("the link check's heading ids differ from mdBook's");
    }
    println!("book: {}", out.join("index.html").display());
    Ok(())
}

/// The version an `mdbook` binary reports (`mdbook v0.5.4` -> `0.5.4`), if it runs.
fn version_of(exe: &Path) -> Option<String> {
    let out = Command::new(exe).arg("--version").output().ok()?;
    if !out.status.success() {
        return None;
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let word = text.split_whitespace().last()?;
    Some(word.trim_start_matches('v').to_string())
}

/// Whether a reported mdBook version reads this book (0.5.x).
fn suitable(version: &str) -> bool {
    version.starts_with("0.5.")
}

/// An mdBook 0.5 binary: `mdbook` on the PATH if it is one, else the one in
/// `target/tools/bin/`, installed there with `cargo install --locked` when missing.
fn mdbook() -> anyhow::Result<PathBuf> {
    let on_path = PathBuf::from("mdbook");
    if let Some(v) = version_of(&on_path) {
        if suitable(&v) {
            return Ok(on_path);
        }
        println!(
            "book: `mdbook` on the PATH is {v}; the book needs 0.5 (installing {MDBOOK_VERSION})"
        );
    }
    let root = target_dir().join("tools");
    let local = root.join("bin").join("mdbook");
    if version_of(&local).is_some_and(|v| suitable(&v)) {
        return Ok(local);
    }
    println!(
        "book: installing mdbook {MDBOOK_VERSION} into {}",
        root.display()
    );
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .args(["install", "mdbook", "--locked", "--version", MDBOOK_VERSION])
        .args(["--no-default-features", "--features", "search"])
        .arg("--root")
        .arg(&root)
        .status()
        .context("running cargo install mdbook")?;
    if !status.success() || version_of(&local).is_none() {
        bail!("cargo install mdbook {MDBOOK_VERSION} failed");
    }
    Ok(local)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_mdbook_0_5_is_suitable() {
        assert!(suitable("0.5.4"));
        assert!(suitable("0.5.0"));
        assert!(!suitable("0.4.52"));
        assert!(!suitable("0.6.0"));
    }
}
