//! Result files of a run (SPEC 6): CSV with a header row and SI units, `summary.json`, and
//! legacy VTK polylines that ParaView opens as a time series.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// A CSV file being written: a header, then rows of numbers or text.
pub struct Csv {
    w: BufWriter<File>,
}

impl Csv {
    /// Creates `path` and writes the header.
    pub fn create(path: &Path, header: &[&str]) -> io::Result<Csv> {
        let mut w = BufWriter::new(File::create(path)?);
        writeln!(w, "{}", header.join(","))?;
        Ok(Csv { w })
    }

    /// Writes one row of numbers (shortest representation that reads back exactly).
    pub fn row(&mut self, values: &[f64]) -> io::Result<()> {
        let mut first = true;
        for v in values {
            if !first {
                self.w.write_all(b",")?;
            }
            first = false;
            write!(self.w, "{}", number(*v))?;
        }
        self.w.write_all(b"\n")
    }

    /// Writes one row of already formatted fields.
    pub fn text_row(&mut self, fields: &[String]) -> io::Result<()> {
        writeln!(self.w, "{}", fields.join(","))
    }

    /// Flushes the file.
    pub fn finish(mut self) -> io::Result<()> {
        self.w.flush()
    }
}

/// A number as text that reads back exactly: plain in [1e-4, 1e6), exponent form outside.
pub fn number(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || (1e-4..1e6).contains(&a) || !v.is_finite() {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Writes a polyline through `points` (m) with per-point scalars as a legacy VTK file.
pub fn write_vtk_polyline(
    path: &Path,
    title: &str,
    points: &[[f64; 3]],
    scalars: &[(&str, Vec<f64>)],
) -> io::Result<()> {
    let mut w = BufWriter::new(File::create(path)?);
    writeln!(w, "# vtk DataFile Version 3.0")?;
    writeln!(w, "{}", title.replace('\n', " "))?;
    writeln!(w, "ASCII")?;
    writeln!(w, "DATASET POLYDATA")?;
    writeln!(w, "POINTS {} double", points.len())?;
    for p in points {
        writeln!(w, "{} {} {}", p[0], p[1], p[2])?;
    }
    writeln!(w, "LINES 1 {}", points.len() + 1)?;
    write!(w, "{}", points.len())?;
    for i in 0..points.len() {
        write!(w, " {i}")?;
    }
    writeln!(w)?;
    if !scalars.is_empty() {
        writeln!(w, "POINT_DATA {}", points.len())?;
        for (name, values) in scalars {
            writeln!(w, "SCALARS {name} double 1")?;
            writeln!(w, "LOOKUP_TABLE default")?;
            for v in values {
                writeln!(w, "{v}")?;
            }
        }
    }
    w.flush()
}
