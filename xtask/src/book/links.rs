//! The check of the book's internal links: every relative link and image of every page
//! resolves to a file of the book's source (a page must be a chapter of `SUMMARY.md`, or mdBook
//! does not render it), and every `#anchor` to a heading of the page it names, with the ids
//! mdBook gives headings (`mdbook-html`'s `id_from_content` and `unique_id`). The repository's
//! `README.md` is checked the same way against the repository's files ([`check_readme`]): its
//! links into the book are what a reader of the repository's web view follows first.

use std::collections::{BTreeMap, HashSet};
use std::path::{Component, Path, PathBuf};

use anyhow::Context;
use pulldown_cmark::{Event, Options, Parser, Tag, TagEnd};

/// A link of a page: where it is and what it points to.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// 1-based line of the link in its page.
    pub line: usize,
    /// The link's destination as written.
    pub target: String,
}

/// A page's headings and links.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PageLinks {
    /// The ids mdBook gives the page's headings (and definition-list terms), in order.
    pub ids: Vec<String>,
    /// The page's links and images.
    pub links: Vec<Link>,
}

/// A link that does not resolve.
#[derive(Debug, Clone, PartialEq)]
pub struct Broken {
    /// The page, as a path under the book's source folder.
    pub page: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// The link as written.
    pub target: String,
    /// Why it does not resolve.
    pub why: String,
}

impl std::fmt::Display for Broken {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}: broken link `{}`: {}",
            self.page.display(),
            self.line,
            self.target,
            self.why
        )
    }
}

/// A link to a page's heading that was found: the page (under the book's source folder) and
/// the id, for the check against the rendered HTML.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Anchor {
    /// The page the anchor is on.
    pub page: PathBuf,
    /// The heading id.
    pub id: String,
}

/// The options mdBook 0.5 parses Markdown with (`mdbook-markdown`'s `new_cmark_parser` with
/// the default `[output.html]` settings), so that headings and links are read as mdBook reads
/// them.
fn options() -> Options {
    Options::ENABLE_TABLES
        | Options::ENABLE_FOOTNOTES
        | Options::ENABLE_STRIKETHROUGH
        | Options::ENABLE_TASKLISTS
        | Options::ENABLE_HEADING_ATTRIBUTES
        | Options::ENABLE_SMART_PUNCTUATION
        | Options::ENABLE_DEFINITION_LIST
        | Options::ENABLE_GFM
}

/// mdBook's heading id of a heading's text: lower case, alphanumerics, `_` and `-` kept,
/// whitespace to `-`, everything else dropped.
pub fn id_from_content(content: &str) -> String {
    content
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|ch| {
            if ch.is_alphanumeric() || ch == '_' || ch == '-' {
                Some(ch)
            } else if ch.is_whitespace() {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

/// mdBook's unique id: `id`, or `id-1`, `id-2`, ... when taken.
fn unique_id(id: &str, used: &mut HashSet<String>) -> String {
    if used.insert(id.to_string()) {
        return id.to_string();
    }
    (1u32..)
        .map(|k| format!("{id}-{k}"))
        .find(|c| used.insert(c.clone()))
        .expect("an unused suffix exists")
}

/// The headings' ids and the links of one page's Markdown.
pub fn scan(markdown: &str) -> PageLinks {
    let line_of = |offset: usize| markdown[..offset].bytes().filter(|&b| b == b'\n').count() + 1;
    let mut page = PageLinks::default();
    let mut used = HashSet::new();
    // The heading (or term) being read: its explicit id, if any, and its text so far.
    let mut heading: Option<(Option<String>, String)> = None;
    for (event, range) in Parser::new_ext(markdown, options()).into_offset_iter() {
        match event {
            Event::Start(Tag::Heading { id, .. }) => {
                heading = Some((id.map(|i| i.to_string()), String::new()));
            }
            Event::Start(Tag::DefinitionListTitle) => heading = Some((None, String::new())),
            Event::End(TagEnd::Heading(_)) | Event::End(TagEnd::DefinitionListTitle) => {
                if let Some((explicit, text)) = heading.take() {
                    // An explicit id is used as written and does not enter the counter.
                    let id =
                        explicit.unwrap_or_else(|| unique_id(&id_from_content(&text), &mut used));
                    page.ids.push(id);
                }
            }
            Event::Text(t) | Event::Code(t) | Event::InlineMath(t) | Event::DisplayMath(t) => {
                if let Some((_, text)) = heading.as_mut() {
                    text.push_str(&t);
                }
            }
            Event::SoftBreak | Event::HardBreak => {
                if let Some((_, text)) = heading.as_mut() {
                    text.push(' ');
                }
            }
            Event::Start(Tag::Link { dest_url, .. })
            | Event::Start(Tag::Image { dest_url, .. }) => {
                page.links.push(Link {
                    line: line_of(range.start),
                    target: dest_url.to_string(),
                });
            }
            _ => {}
        }
    }
    page
}

/// Whether a link leaves the book (has a URL scheme such as `https:` or `mailto:`).
fn is_external(target: &str) -> bool {
    match target.split_once(':') {
        Some((scheme, _)) => {
            !scheme.is_empty()
                && scheme
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
        }
        None => false,
    }
}

/// `path` with `.` and `..` resolved lexically; `None` when it climbs above its root.
fn normalize(path: &Path) -> Option<PathBuf> {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    return None;
                }
            }
            Component::Normal(p) => out.push(p),
            Component::RootDir | Component::Prefix(_) => return None,
        }
    }
    Some(out)
}

/// The Markdown files under `src`, as paths relative to it, sorted.
fn markdown_files(src: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in
            std::fs::read_dir(&dir).with_context(|| format!("reading {}", dir.display()))?
        {
            let path = entry?.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path.strip_prefix(src).expect("under src").to_path_buf());
            }
        }
    }
    out.sort();
    Ok(out)
}

/// The result of checking a book's source folder.
#[derive(Debug, Clone, Default)]
pub struct Check {
    /// The links that do not resolve.
    pub broken: Vec<Broken>,
    /// Every anchor that links point to and that was found, for the rendered-HTML check.
    pub anchors: Vec<Anchor>,
    /// The number of internal links checked.
    pub links: usize,
}

/// Checks every page under `src` (the folder holding `SUMMARY.md`).
pub fn check(src: &Path) -> anyhow::Result<Check> {
    let files = markdown_files(src)?;
    let mut pages = BTreeMap::new();
    for f in &files {
        let path = src.join(f);
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("reading {}", path.display()))?;
        pages.insert(f.clone(), scan(&text));
    }
    let summary = PathBuf::from("SUMMARY.md");
    let Some(summary_page) = pages.get(&summary) else {
        anyhow::bail!("{} has no SUMMARY.md", src.display());
    };
    // The chapters: pages SUMMARY.md links to (mdBook renders only those).
    let chapters: HashSet<PathBuf> = summary_page
        .links
        .iter()
        .filter(|l| !is_external(&l.target))
        .filter_map(|l| normalize(Path::new(l.target.split('#').next().unwrap_or(""))))
        .collect();

    let mut result = Check::default();
    for (page, links) in &pages {
        let dir = page.parent().unwrap_or(Path::new(""));
        for link in &links.links {
            if is_external(&link.target) {
                continue;
            }
            result.links += 1;
            let broken = |why: String| Broken {
                page: page.clone(),
                line: link.line,
                target: link.target.clone(),
                why,
            };
            let (path, anchor) = match link.target.split_once('#') {
                Some((p, a)) => (p, Some(a)),
                None => (link.target.as_str(), None),
            };
            if path.starts_with('/') {
                result.broken.push(broken(
                    "an absolute path: write it relative to the page".into(),
                ));
                continue;
            }
            let target = if path.is_empty() {
                Some(page.clone())
            } else {
                normalize(&dir.join(path))
            };
            let Some(target) = target else {
                result.broken.push(broken(
                    "leaves the book's source folder (mdBook does not copy it)".into(),
                ));
                continue;
            };
            if !src.join(&target).is_file() {
                result.broken.push(broken(format!(
                    "no file {}",
                    Path::new("docs/book/src").join(&target).display()
                )));
                continue;
            }
            let is_page = target.extension().is_some_and(|e| e == "md");
            if is_page && page != &summary && !chapters.contains(&target) {
                result.broken.push(broken(format!(
                    "{} is not a chapter of SUMMARY.md (mdBook does not render it)",
                    target.display()
                )));
                continue;
            }
            if let Some(id) = anchor {
                if !is_page {
                    result
                        .broken
                        .push(broken("an anchor on a file that is not a page".into()));
                } else if !pages[&target].ids.iter().any(|i| i == id) {
                    result.broken.push(broken(format!(
                        "no heading with id `{id}` in {}",
                        target.display()
                    )));
                } else {
                    result.anchors.push(Anchor {
                        page: target.clone(),
                        id: id.to_string(),
                    });
                }
            }
        }
    }
    result.anchors.sort();
    result.anchors.dedup();
    Ok(result)
}

/// Checks the relative links and images of the Markdown file `file` (a path under `root`, the
/// repository) against the files under `root`: each must name a file of the repository
/// (relative to `file`'s folder, not leaving `root`), and each `#anchor` a heading of the
/// Markdown file it names (or of `file` itself), with mdBook's heading ids. Anchors into pages
/// of the book under `book_src` are returned in [`Check::anchors`] (paths under `book_src`),
/// for the check against the rendered book.
pub fn check_file(root: &Path, file: &Path, book_src: &Path) -> anyhow::Result<Check> {
    let path = root.join(file);
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let own = scan(&text);
    let dir = file.parent().unwrap_or(Path::new(""));
    let book_rel = book_src.strip_prefix(root).ok().map(Path::to_path_buf);
    let mut result = Check::default();
    for link in &own.links {
        if is_external(&link.target) {
            continue;
        }
        result.links += 1;
        let broken = |why: String| Broken {
            page: file.to_path_buf(),
            line: link.line,
            target: link.target.clone(),
            why,
        };
        let (target, anchor) = match link.target.split_once('#') {
            Some((p, a)) => (p, Some(a)),
            None => (link.target.as_str(), None),
        };
        if target.starts_with('/') {
            result.broken.push(broken(
                "an absolute path: write it relative to the file".into(),
            ));
            continue;
        }
        let target = if target.is_empty() {
            Some(file.to_path_buf())
        } else {
            normalize(&dir.join(target))
        };
        let Some(target) = target else {
            result.broken.push(broken("leaves the repository".into()));
            continue;
        };
        let on_disk = root.join(&target);
        if !on_disk.exists() {
            result
                .broken
                .push(broken(format!("no file {}", target.display())));
            continue;
        }
        let Some(id) = anchor else { continue };
        if target.extension().is_none_or(|e| e != "md") || !on_disk.is_file() {
            result
                .broken
                .push(broken("an anchor on a file that is not Markdown".into()));
            continue;
        }
        let ids = if target == file {
            own.ids.clone()
        } else {
            let text = std::fs::read_to_string(&on_disk)
                .with_context(|| format!("reading {}", on_disk.display()))?;
            scan(&text).ids
        };
        if !ids.iter().any(|i| i == id) {
            result.broken.push(broken(format!(
                "no heading with id `{id}` in {}",
                target.display()
            )));
        } else if let Some(page) = book_rel
            .as_deref()
            .and_then(|b| target.strip_prefix(b).ok())
        {
            result.anchors.push(Anchor {
                page: page.to_path_buf(),
                id: id.to_string(),
            });
        }
    }
    result.anchors.sort();
    result.anchors.dedup();
    Ok(result)
}

/// [`check_file`] on the repository's `README.md`.
pub fn check_readme(root: &Path, book_src: &Path) -> anyhow::Result<Check> {
    check_file(root, Path::new("README.md"), book_src)
}

/// The anchors of `anchors` that the rendered book in `html` does not carry as an `id`: a
/// check of [`id_from_content`] against mdBook itself.
pub fn missing_in_html(html: &Path, anchors: &[Anchor]) -> anyhow::Result<Vec<Anchor>> {
    let mut missing = Vec::new();
    for a in anchors {
        let file = html.join(a.page.with_extension("html"));
        let text = std::fs::read_to_string(&file)
            .with_context(|| format!("reading {}", file.display()))?;
        if !text.contains(&format!("id=\"{}\"", a.id)) {
            missing.push(a.clone());
        }
    }
    Ok(missing)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heading_ids_follow_mdbooks_rules() {
        let md = "# Getting started\n\n## `strand run`: the main job\n\n## Getting started\n\n\
                  ### The friction limit (eq. 20) {#limit}\n\n## Getting started\n\n\
                  ```text\n# not a heading\n```\n";
        let page = scan(md);
        assert_eq!(
            page.ids,
            [
                "getting-started",
                "strand-run-the-main-job",
                "getting-started-1",
                "limit",
                "getting-started-2"
            ]
        );
    }

    #[test]
    fn links_outside_code_are_found_with_their_lines() {
        let md = "# A\n\nSee [b](b.md#x) and\n![fig](figures/f.png).\n\n```json\n[c](c.md)\n```\n\
                  `[d](d.md)` [e](https://example.org) [f](#a)\n";
        let page = scan(md);
        let got: Vec<(usize, &str)> = page
            .links
            .iter()
            .map(|l| (l.line, l.target.as_str()))
            .collect();
        assert_eq!(
            got,
            [
                (3, "b.md#x"),
                (4, "figures/f.png"),
                (9, "https://example.org"),
                (9, "#a")
            ]
        );
    }

    /// A small book in a temporary folder: every kind of broken link is reported with its page
    /// and line, and the good ones are not.
    #[test]
    fn broken_links_are_reported_with_file_and_line() {
        let dir = std::env::temp_dir().join(format!("strand-book-links-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("figures")).unwrap();
        std::fs::write(
            dir.join("SUMMARY.md"),
            "# Summary\n\n- [A](a.md)\n- [B](b.md)\n",
        )
        .unwrap();
        std::fs::write(
            dir.join("a.md"),
            "# A page\n\n[ok](b.md#second-part)\n[ok](#a-page)\n![ok](figures/f.png)\n\
             [bad anchor](b.md#third)\n[no file](c.md)\n[outside](../../README.md)\n\
             [not a chapter](orphan.md)\n[absolute](/b.md)\n",
        )
        .unwrap();
        std::fs::write(dir.join("b.md"), "# B\n\n## Second part\n").unwrap();
        std::fs::write(dir.join("orphan.md"), "# O\n").unwrap();
        std::fs::write(dir.join("figures/f.png"), b"png").unwrap();
        let result = check(&dir).unwrap();
        let got: Vec<String> = result.broken.iter().map(|b| b.to_string()).collect();
        assert_eq!(
            got,
            [
                "a.md:6: broken link `b.md#third`: no heading with id `third` in b.md",
                "a.md:7: broken link `c.md`: no file docs/book/src/c.md",
                "a.md:8: broken link `../../README.md`: leaves the book's source folder \
                 (mdBook does not copy it)",
                "a.md:9: broken link `orphan.md`: orphan.md is not a chapter of SUMMARY.md \
                 (mdBook does not render it)",
                "a.md:10: broken link `/b.md`: an absolute path: write it relative to the page",
            ]
        );
        assert_eq!(result.links, 10);
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A small repository in a temporary folder: the README's links to files, to headings of
    /// the book's pages and of its own, good and broken, each broken one with its line.
    #[test]
    fn readme_links_are_checked_against_the_repository() {
        let dir = std::env::temp_dir().join(format!("strand-readme-links-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let src = dir.join("docs/book/src");
        std::fs::create_dir_all(src.join("figures")).unwrap();
        std::fs::write(src.join("SUMMARY.md"), "# Summary\n\n- [A](a.md)\n").unwrap();
        std::fs::write(src.join("a.md"), "# A page\n\n## `strand run`: the job\n").unwrap();
        std::fs::write(src.join("figures/f.png"), b"png").unwrap();
        std::fs::write(dir.join("CHANGELOG.md"), "# Changelog\n").unwrap();
        std::fs::write(
            dir.join("README.md"),
            "# strand\n\n## Quick start\n\n\
             [ok](docs/book/src/a.md#strand-run-the-job)\n\
             ![ok](docs/book/src/figures/f.png)\n[ok](CHANGELOG.md) [ok](#quick-start)\n\
             [ok](docs/book/) [ok](https://example.org/x.md#y)\n\
             [bad anchor](docs/book/src/a.md#the-job)\n[no file](docs/book/src/b.md)\n\
             [own anchor](#quick)\n[outside](../x.md)\n[absolute](/CHANGELOG.md)\n\
             [anchor on a figure](docs/book/src/figures/f.png#x)\n",
        )
        .unwrap();
        let result = check_readme(&dir, &src).unwrap();
        let got: Vec<String> = result.broken.iter().map(|b| b.to_string()).collect();
        assert_eq!(
            got,
            [
                "README.md:9: broken link `docs/book/src/a.md#the-job`: no heading with id \
                 `the-job` in docs/book/src/a.md",
                "README.md:10: broken link `docs/book/src/b.md`: no file docs/book/src/b.md",
                "README.md:11: broken link `#quick`: no heading with id `quick` in README.md",
                "README.md:12: broken link `../x.md`: leaves the repository",
                "README.md:13: broken link `/CHANGELOG.md`: an absolute path: write it \
                 relative to the file",
                "README.md:14: broken link `docs/book/src/figures/f.png#x`: an anchor on a \
                 file that is not Markdown",
            ]
        );
        assert_eq!(result.links, 11);
        assert_eq!(
            result.anchors,
            [Anchor {
                page: PathBuf::from("a.md"),
                id: "strand-run-the-job".into()
            }]
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The repository's README has no broken link (what `cargo xtask book` checks, here in the
    /// default test suite).
    #[test]
    fn the_readmes_links_resolve() {
        let root = crate::validate::repo_root();
        let result = check_readme(&root, &super::super::pages::book_src()).unwrap();
        let broken: Vec<String> = result.broken.iter().map(|b| b.to_string()).collect();
        assert!(broken.is_empty(), "{}", broken.join("\n"));
        assert!(result.links > 0 && !result.anchors.is_empty());
    }

    /// The book in the repository has no broken link (what `cargo xtask book` checks before it
    /// builds, here in the default test suite).
    #[test]
    fn the_books_links_resolve() {
        let src = super::super::pages::book_src();
        let result = check(&src).unwrap();
        let broken: Vec<String> = result.broken.iter().map(|b| b.to_string()).collect();
        assert!(broken.is_empty(), "{}", broken.join("\n"));
        assert!(result.links > 0);
    }
}
