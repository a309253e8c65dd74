//! Reading the result files in the runner's tests.

use std::collections::HashMap;
use std::path::Path;

/// Columns of a CSV result file by header name; an empty field (a value the run could not
/// write) reads as NaN.
pub fn csv_columns(path: &Path) -> HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let mut cols: HashMap<String, Vec<f64>> =
        header.iter().map(|h| (h.clone(), Vec::new())).collect();
    for l in lines {
        for (h, v) in header.iter().zip(l.split(',')) {
            cols.get_mut(h).unwrap().push(v.parse().unwrap_or(f64::NAN));
        }
    }
    cols
}
