//! Result files of a run (SPEC 6): CSV with a header row and SI units, `summary.json`, and
//! legacy VTK polylines that ParaView opens as a time series.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// A CSV file being written: a header, then rows of numbers or text. A result file never
/// holds `NaN` or `inf`: a non-finite number is written as an empty field and counted
/// ([`Csv::blanks`]), so that the run can say so.
pub struct Csv {
    w: BufWriter<File>,
    blanks: usize,
}

impl Csv {
    /// Creates `path` and writes the header.
    pub fn create(path: &Path, header: &[&str]) -> io::Result<Csv> {
        let mut w = BufWriter::new(File::create(path)?);
        writeln!(w, "{}", header.join(","))?;
        Ok(Csv { w, blanks: 0 })
    }

    /// Writes one row of numbers (shortest representation that reads back exactly; empty for
    /// a non-finite value).
    pub fn row(&mut self, values: &[f64]) -> io::Result<()> {
        let mut first = true;
        for v in values {
            if !first {
                self.w.write_all(b",")?;
            }
            first = false;
            if v.is_finite() {
                write!(self.w, "{}", number(*v))?;
            } else {
                self.blanks += 1;
            }
        }
        self.w.write_all(b"\n")
    }

    /// Non-finite numbers written as empty fields so far.
    pub fn blanks(&self) -> usize {
        self.blanks
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

/// A number as text that reads back exactly: plain in [1e-4, 1e6), exponent form outside;
/// empty for a non-finite value (result files hold no `NaN` or `inf`).
pub fn number(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() {
        String::new()
    } else if v == 0.0 || (1e-4..1e6).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Writes a polyline through `points` (m) with per-point scalars as a legacy VTK file; a
/// non-finite value is an error (nothing is written).
pub fn write_vtk_polyline(
    path: &Path,
    title: &str,
    points: &[[f64; 3]],
    scalars: &[(&str, Vec<f64>)],
) -> io::Result<()> {
    if let Some(bad) = points
        .iter()
        .flatten()
        .chain(scalars.iter().flat_map(|(_, v)| v))
        .find(|v| !v.is_finite())
    {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("a non-finite value ({bad}) in a VTK frame"),
        ));
    }
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

/// The columns of `centerline.csv` (SPEC 6), in order; a model may add its own after them.
/// `moment` (N m) came last, after the SPEC 6 columns, so that readers of those keep working.
pub const CENTERLINE_COLUMNS: [&str; 8] = [
    "s",
    "x",
    "y",
    "z",
    "curvature",
    "tension",
    "bending_stiffness",
    "moment",
];

/// One VTK frame: a polyline through `points` (m) with per-point scalars.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VtkFrame {
    /// The polyline's points (m).
    pub points: Vec<[f64; 3]>,
    /// Named point data, one value per point.
    pub scalars: Vec<(&'static str, Vec<f64>)>,
}

/// Writes the one frame of a static run, `vtk/centerline_00000.vtk` in `dir`: a polyline
/// through `points` (m) with per-point scalars (see [`write_vtk_polyline`]). An error names
/// the file.
pub fn write_static_vtk(
    dir: &Path,
    title: &str,
    points: &[[f64; 3]],
    scalars: &[(&str, Vec<f64>)],
) -> Result<(), String> {
    let d = dir.join("vtk");
    std::fs::create_dir_all(&d).map_err(|e| format!("writing {}: {e}", d.display()))?;
    let path = d.join("centerline_00000.vtk");
    write_vtk_polyline(&path, title, points, scalars)
        .map_err(|e| format!("writing {}: {e}", path.display()))
}

/// The per-frame files of a dynamic run in a model folder: `tip.csv`, `energy.csv` (the SPEC 6
/// columns, then any extra ones) and, if asked, `vtk/centerline_NNNNN.vtk`.
pub struct FrameFiles {
    tip: (Csv, PathBuf),
    energy: (Csv, PathBuf),
    vtk: Option<PathBuf>,
    frame: usize,
}

impl FrameFiles {
    /// Creates the files in `dir`; `extra` names energy columns after `total`. Errors name
    /// the file.
    pub fn create(dir: &Path, vtk: bool, extra: &[&str]) -> Result<FrameFiles, String> {
        let io = |p: &Path| {
            let p = p.display().to_string();
            move |e: io::Error| format!("writing {p}: {e}")
        };
        let pt = dir.join("tip.csv");
        let tip = Csv::create(&pt, &["t", "x", "y", "z", "vx", "vy", "vz"]).map_err(io(&pt))?;
        let pe = dir.join("energy.csv");
        let mut header = vec!["t", "kinetic", "gravity", "elastic", "dissipated", "total"];
        header.extend_from_slice(extra);
        let energy = Csv::create(&pe, &header).map_err(io(&pe))?;
        let vtk = if vtk {
            let d = dir.join("vtk");
            std::fs::create_dir_all(&d).map_err(io(&d))?;
            Some(d)
        } else {
            None
        };
        Ok(FrameFiles {
            tip: (tip, pt),
            energy: (energy, pe),
            vtk,
            frame: 0,
        })
    }

    /// Writes the frame at time `t` (s): tip position `x` (m) and velocity `v` (m/s), the
    /// energies in the header's order after `t` (J), and, with VTK output, the centreline
    /// with its point data that `centreline()` yields.
    pub fn write(
        &mut self,
        t: f64,
        x: [f64; 3],
        v: [f64; 3],
        energies: &[f64],
        centreline: impl FnOnce() -> VtkFrame,
    ) -> io::Result<()> {
        self.tip.0.row(&[t, x[0], x[1], x[2], v[0], v[1], v[2]])?;
        let mut row = Vec::with_capacity(1 + energies.len());
        row.push(t);
        row.extend_from_slice(energies);
        self.energy.0.row(&row)?;
        if let Some(d) = &self.vtk {
            let path = d.join(format!("centerline_{:05}.vtk", self.frame));
            let f = centreline();
            write_vtk_polyline(&path, &format!("t = {t} s"), &f.points, &f.scalars)?;
        }
        self.frame += 1;
        Ok(())
    }

    /// Non-finite numbers written as empty fields so far.
    pub fn blanks(&self) -> usize {
        self.tip.0.blanks() + self.energy.0.blanks()
    }

    /// Flushes the CSV files; an error names the file.
    pub fn finish(self) -> Result<(), String> {
        for (csv, path) in [self.tip, self.energy] {
            csv.finish()
                .map_err(|e| format!("writing {}: {e}", path.display()))?;
        }
        Ok(())
    }
}
