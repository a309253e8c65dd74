//! The studies' tables in the book: each study's `--update-docs` replaces the text between a
//! pair of marker comments on its page, so that no measured number is copied by hand.
//!
//! A page holds a block as
//!
//! ```text
//! <!-- begin generated: NAME (cargo xtask ... --update-docs) -->
//! ...
//! <!-- end generated: NAME -->
//! ```
//!
//! where the text after `NAME` in the begin marker is free (it says which command writes the
//! block).

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};

/// A page of the book (file name under `docs/book/src/`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Page {
    /// `validation.md`: validate, hard, paper, bonded, stiffness.
    Validation,
    /// `performance.md`: pareto, bench-peers.
    Performance,
    /// `multilayer.md`: multilayer-curve, bonded-multilayer.
    Multilayer,
}

impl Page {
    /// The page's file name under `docs/book/src/`.
    pub fn file(self) -> &'static str {
        match self {
            Page::Validation => "validation.md",
            Page::Performance => "performance.md",
            Page::Multilayer => "multilayer.md",
        }
    }
}

/// The book's source folder, `docs/book/src/`.
pub fn book_src() -> PathBuf {
    crate::validate::repo_root().join("docs/book/src")
}

/// The folder of the book's figures, `docs/book/src/figures/`, which the studies' plots are
/// copied into.
pub fn figures_dir() -> PathBuf {
    book_src().join("figures")
}

/// Writes `content` into block `name` of `page` (see the module docs); prints what it updated.
pub fn update(page: Page, name: &str, content: &str) -> anyhow::Result<()> {
    let path = book_src().join(page.file());
    update_file(&path, name, content)?;
    println!("updated {} (block `{name}`)", path.display());
    Ok(())
}

/// [`update`] on a file given by its path.
pub fn update_file(path: &Path, name: &str, content: &str) -> anyhow::Result<()> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let new = replace_block(&text, name, content)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    std::fs::write(path, new).with_context(|| format!("writing {}", path.display()))
}

/// `text` with the lines between block `name`'s markers replaced by `content` (the markers
/// kept). Fails when the block's begin or end marker is missing, appears twice, or the end
/// comes first.
pub fn replace_block(text: &str, name: &str, content: &str) -> Result<String, String> {
    let begin = format!("<!-- begin generated: {name} ");
    let begin_bare = format!("<!-- begin generated: {name} -->");
    let end = format!("<!-- end generated: {name} -->");
    let find_one = |pat: &dyn Fn(&str) -> bool, what: &str| -> Result<usize, String> {
        let mut hits = text
            .lines()
            .scan(0usize, |offset, line| {
                let at = *offset;
                *offset += line.len() + 1;
                Some((at, line))
            })
            .filter(|(_, line)| pat(line.trim()));
        let Some((at, _)) = hits.next() else {
            return Err(format!("no {what} marker of block `{name}`"));
        };
        if hits.next().is_some() {
            return Err(format!("the {what} marker of block `{name}` appears twice"));
        }
        Ok(at)
    };
    let b = find_one(&|l: &str| l.starts_with(&begin) || l == begin_bare, "begin")?;
    let e = find_one(&|l: &str| l == end, "end")?;
    if e < b {
        return Err(format!(
            "the end marker of block `{name}` comes before its begin"
        ));
    }
    let after_begin = b + text[b..].find('\n').map_or(text.len() - b, |i| i + 1);
    let mut out = String::with_capacity(text.len() + content.len());
    out.push_str(&text[..after_begin]);
    if !text[..after_begin].ends_with('\n') {
        out.push('\n');
    }
    out.push('\n');
    out.push_str(content.trim_matches('\n'));
    out.push_str("\n\n");
    out.push_str(&text[e..]);
    Ok(out)
}

/// The first Markdown table in `markdown` (its header, rule and rows), if any.
pub fn first_table(markdown: &str) -> Option<String> {
    let lines: Vec<&str> = markdown
        .lines()
        .skip_while(|l| !l.trim_start().starts_with('|'))
        .take_while(|l| l.trim_start().starts_with('|'))
        .collect();
    (lines.len() >= 2).then(|| lines.join("\n"))
}

/// Copies `from/STEM.png` for each stem into the book's figures folder.
pub fn copy_figures(from: &Path, stems: &[&str]) -> anyhow::Result<()> {
    let dir = figures_dir();
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    for stem in stems {
        let src = from.join(format!("{stem}.png"));
        if !src.exists() {
            bail!("{} was not drawn", src.display());
        }
        let to = dir.join(format!("{stem}.png"));
        std::fs::copy(&src, &to).with_context(|| format!("copying to {}", to.display()))?;
        println!("updated {}", to.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAGE: &str = "# Page\n\nText before.\n\n\
        <!-- begin generated: validate (cargo xtask validate --update-docs) -->\n\n\
        | a | b |\n|---|---|\n| 1 | 2 |\n\n\
        <!-- end generated: validate -->\n\nText after.\n\n\
        <!-- begin generated: hard -->\nold\n<!-- end generated: hard -->\n";

    #[test]
    fn replaces_only_its_own_block_and_keeps_the_markers() {
        let new = replace_block(PAGE, "validate", "| a | b |\n|---|---|\n| 3 | 4 |").unwrap();
        assert!(new.contains("| 3 | 4 |"));
        assert!(!new.contains("| 1 | 2 |"));
        assert!(new.starts_with("# Page\n\nText before.\n\n<!-- begin generated: validate ("));
        assert!(new.contains("<!-- end generated: validate -->\n\nText after."));
        // The other block is untouched.
        assert!(new.contains("<!-- begin generated: hard -->\nold\n<!-- end generated: hard -->"));
        // Replacing twice with the same content is a fixed point.
        let again = replace_block(&new, "validate", "| a | b |\n|---|---|\n| 3 | 4 |").unwrap();
        assert_eq!(again, new);
        let hard = replace_block(&new, "hard", "\n\nnew\n").unwrap();
        assert!(
            hard.contains("<!-- begin generated: hard -->\n\nnew\n\n<!-- end generated: hard -->")
        );
    }

    #[test]
    fn a_missing_doubled_or_reversed_marker_is_an_error() {
        assert!(
            replace_block(PAGE, "pareto", "x")
                .unwrap_err()
                .contains("no begin marker of block `pareto`")
        );
        let doubled = format!("{PAGE}<!-- end generated: hard -->\n");
        assert!(
            replace_block(&doubled, "hard", "x")
                .unwrap_err()
                .contains("twice")
        );
        let reversed = "<!-- end generated: x -->\n<!-- begin generated: x -->\n";
        assert!(
            replace_block(reversed, "x", "y")
                .unwrap_err()
                .contains("before")
        );
        // A block name that is a prefix of another is not mistaken for it.
        let prefix =
            "<!-- begin generated: validate-quick -->\n<!-- end generated: validate-quick -->\n";
        assert!(replace_block(prefix, "validate", "y").is_err());
    }

    #[test]
    fn first_table_takes_the_first_table_whole() {
        let md = "# R\n\ntext\n\n| x | y |\n|---|---|\n| 1 | 2 |\n\nmore\n\n| z |\n|---|\n";
        assert_eq!(first_table(md).unwrap(), "| x | y |\n|---|---|\n| 1 | 2 |");
        assert_eq!(first_table("no table"), None);
    }

    /// Each study's block is on the page its `--update-docs` writes to, once.
    #[test]
    fn every_studys_block_is_on_its_page() {
        for (page, blocks) in [
            (
                Page::Validation,
                &["validate", "hard", "paper", "stiffness", "bonded"][..],
            ),
            (Page::Performance, &["pareto", "bench-peers"][..]),
        ] {
            let text = std::fs::read_to_string(book_src().join(page.file())).unwrap();
            for block in blocks {
                if let Err(e) = replace_block(&text, block, "x") {
                    panic!("{}: {e}", page.file());
                }
            }
        }
    }
}
