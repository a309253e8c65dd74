//! The result files as the charts read them: CSV with a header row.

use std::path::Path;

/// A CSV file of numbers by column; a field that is empty or not a number reads as NaN (the
/// charts leave such points out).
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Table {
    /// Reads `path`.
    pub fn load(path: &Path) -> std::io::Result<Table> {
        let (header, rows) = read_csv(path, |f| f.parse().unwrap_or(f64::NAN))?;
        Ok(Table { header, rows })
    }

    /// The column `name`; empty if there is none.
    pub fn column(&self, name: &str) -> Vec<f64> {
        let Some(i) = self.header.iter().position(|h| h == name) else {
            return Vec::new();
        };
        self.rows
            .iter()
            .map(|r| r.get(i).copied().unwrap_or(f64::NAN))
            .collect()
    }
}

/// A CSV file of text fields (e.g. the stick/slip states of `wires.csv`).
#[derive(Debug, Clone, PartialEq)]
pub struct TextTable {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl TextTable {
    /// Reads `path`.
    pub fn load(path: &Path) -> std::io::Result<TextTable> {
        let (header, rows) = read_csv(path, str::to_string)?;
        Ok(TextTable { header, rows })
    }

    /// Whether the file has no rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The rows.
    pub fn rows(&self) -> impl Iterator<Item = TextRow<'_>> {
        self.rows.iter().map(|fields| TextRow {
            header: &self.header,
            fields,
        })
    }
}

/// The header and the non-blank rows of the CSV file `path`, each field trimmed and read by
/// `field`.
fn read_csv<T>(
    path: &Path,
    field: impl Fn(&str) -> T,
) -> std::io::Result<(Vec<String>, Vec<Vec<T>>)> {
    let text = std::fs::read_to_string(path)?;
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap_or_default()
        .split(',')
        .map(|h| h.trim().to_string())
        .collect();
    let rows = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|f| field(f.trim())).collect())
        .collect();
    Ok((header, rows))
}

/// One row of a [`TextTable`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextRow<'a> {
    header: &'a [String],
    fields: &'a [String],
}

impl TextRow<'_> {
    /// The field of column `name`.
    pub fn get(&self, name: &str) -> Option<&str> {
        let i = self.header.iter().position(|h| h == name)?;
        self.fields.get(i).map(String::as_str)
    }

    /// The field of column `name` as a number.
    pub fn number(&self, name: &str) -> Option<f64> {
        self.get(name)?.parse().ok()
    }
}
