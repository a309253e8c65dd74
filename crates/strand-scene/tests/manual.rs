//! The manual's Scenes page against the scene format itself: every field of the format has a
//! row on the page (and no row names a field that does not exist), and every JSON example on
//! the Scenes and Getting-started pages, and every bundled scene, is read and validated by the
//! real scene reader.
//!
//! The field list comes from the format's own `Deserialize` implementations, traced with
//! `serde-reflection`: the reader's field names (serde renames included) and nesting, with no
//! hand-kept list and no change to the library's types or dependencies (a JSON schema from
//! `schemars` would need a derive on every format type in the library).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use serde_reflection::{ContainerFormat, Format, Registry, Tracer, TracerConfig};
use strand_scene::Scene;
use strand_scene::format::SceneFile;

/// A page of the manual, by file name under `docs/book/src/`.
fn page(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs/book/src")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The scene format's registry of containers, traced from `SceneFile`'s `Deserialize`.
fn registry() -> Registry {
    let mut tracer = Tracer::new(TracerConfig::default());
    tracer
        .trace_simple_type::<SceneFile>()
        .expect("the scene format traces");
    tracer.registry().expect("every format is resolved")
}

/// The dotted paths of every leaf field below `format` (a list of objects adds `[]`).
fn leaves(registry: &Registry, format: &Format, path: &str, out: &mut BTreeSet<String>) {
    match format {
        Format::Option(inner) => leaves(registry, inner, path, out),
        Format::Seq(inner) if matches!(**inner, Format::TypeName(_)) => {
            leaves(registry, inner, &format!("{path}[]"), out)
        }
        Format::TypeName(name) => match &registry[name] {
            ContainerFormat::Struct(fields) => {
                for f in fields {
                    let p = if path.is_empty() {
                        f.name.clone()
                    } else {
                        format!("{path}.{}", f.name)
                    };
                    leaves(registry, &f.value, &p, out);
                }
            }
            other => panic!("{path}: a container the page does not describe: {other:?}"),
        },
        _ => {
            out.insert(path.to_string());
        }
    }
}

/// Every leaf field of the scene format, e.g. `strand.layers[].lay_angle_deg`.
fn format_fields() -> BTreeSet<String> {
    let registry = registry();
    let mut out = BTreeSet::new();
    leaves(
        &registry,
        &Format::TypeName("SceneFile".into()),
        "",
        &mut out,
    );
    out
}

/// The fields the page's reference tables name: the first cell of every table row that is a
/// single code span, e.g. `` | `strand.length` | ... ``.
fn documented_fields(markdown: &str) -> BTreeSet<String> {
    markdown
        .lines()
        .filter_map(|l| l.trim().strip_prefix('|'))
        .filter_map(|row| row.split('|').next())
        .map(str::trim)
        .filter(|cell| cell.len() > 2 && cell.starts_with('`') && cell.ends_with('`'))
        .map(|cell| cell.trim_matches('`').to_string())
        .filter(|f| !f.contains(' '))
        .collect()
}

/// Fields of the format missing from the page, and rows of the page naming no field.
fn compare(page: &str) -> (Vec<String>, Vec<String>) {
    let fields = format_fields();
    let documented = documented_fields(page);
    let missing = fields.difference(&documented).cloned().collect();
    let unknown = documented.difference(&fields).cloned().collect();
    (missing, unknown)
}

#[test]
fn the_format_has_the_fields_a_scene_is_known_to_have() {
    // A check of the tracing itself against fields every bundled scene uses, so that an empty
    // or truncated trace cannot pass the page test below.
    let fields = format_fields();
    for f in [
        "name",
        "strand.length",
        "strand.core.diameter",
        "strand.layers[].lay_angle_deg",
        "supports[].motion",
        "loads.points[].force",
        "analysis.kind",
        "models.fine.segments_per_wire",
    ] {
        assert!(fields.contains(f), "{f} not traced; traced: {fields:?}");
    }
    assert!(fields.len() >= 40, "{} fields traced", fields.len());
}

#[test]
fn every_field_of_the_scene_format_has_its_row_on_the_scenes_page() {
    let (missing, unknown) = compare(&page("scenes.md"));
    assert!(
        missing.is_empty(),
        "fields of the scene format missing from docs/book/src/scenes.md: {missing:?}"
    );
    assert!(
        unknown.is_empty(),
        "rows of docs/book/src/scenes.md that name no field of the format: {unknown:?}"
    );
}

#[test]
fn a_deleted_row_fails_the_page_test() {
    // The mutation the page test must catch: the row of one field removed from the page.
    let text = page("scenes.md");
    let row = text
        .lines()
        .find(|l| l.starts_with("| `analysis.spectral_radius` |"))
        .expect("the page has the row");
    let mutated = text.replacen(&format!("{row}\n"), "", 1);
    let (missing, _) = compare(&mutated);
    assert_eq!(missing, ["analysis.spectral_radius"]);
    // And a row for a field that does not exist is reported.
    let extra = format!("{text}\n| `analysis.spectral_radiuss` | x |\n");
    let (_, unknown) = compare(&extra);
    assert_eq!(unknown, ["analysis.spectral_radiuss"]);
}

/// The ```json blocks of a page, with the line each starts on.
fn json_blocks(markdown: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (k, line) in markdown.lines().enumerate() {
        let fence = line.trim_start();
        match current.as_mut() {
            None if fence.starts_with("```json") => current = Some((k + 1, String::new())),
            Some(_) if fence.starts_with("```") => out.push(current.take().expect("open")),
            Some((_, text)) => {
                text.push_str(line);
                text.push('\n');
            }
            None => {}
        }
    }
    assert!(current.is_none(), "an unclosed ```json block");
    out
}

#[test]
fn every_json_example_of_the_manual_is_a_valid_scene() {
    let mut count = 0;
    for name in ["scenes.md", "getting-started.md"] {
        for (line, text) in json_blocks(&page(name)) {
            if let Err(e) = Scene::parse(&text) {
                panic!("docs/book/src/{name}:{line}: the example is not a valid scene: {e}");
            }
            count += 1;
        }
    }
    // One example per kind of analysis at least (static, dynamic with each integrator).
    assert!(count >= 3, "{count} examples");
}

#[test]
fn a_broken_example_is_rejected_naming_its_field() {
    // The check above can fail: the first example with its lay angle out of range.
    let (_, text) = json_blocks(&page("scenes.md")).remove(0);
    let bad = text.replacen("\"lay_angle_deg\": ", "\"lay_angle_deg\": 95.0, \"x\": ", 1);
    assert_ne!(bad, text, "the first example has a lay angle");
    assert!(Scene::parse(&bad).is_err());
}

/// The scene files under `dir` (recursively), leaving out the criteria and tolerance files.
fn scene_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            scene_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "json")
            && !matches!(
                path.file_name().and_then(|n| n.to_str()),
                Some("criteria.json" | "multilayer-criteria.json" | "tolerances.json")
            )
        {
            out.push(path);
        }
    }
}

#[test]
fn the_bundled_scenes_are_valid() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    scene_files(&root.join("examples"), &mut files);
    scene_files(&root.join("validation"), &mut files);
    assert!(files.len() >= 30, "{} scenes", files.len());
    for f in files {
        if let Err(e) = Scene::load(&f) {
            panic!("{}: {e}", f.display());
        }
    }
}
