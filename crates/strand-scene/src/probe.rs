//! Probes (`output.probes`): the time history of the strand at a material coordinate s,
//! `probe_<s>.csv` in each model's folder, one row per output frame (statics: one row, the
//! equilibrium, at t = 0).

use std::path::{Path, PathBuf};

use crate::output::{Csv, number};

/// The columns of `probe_<s>.csv`, in order.
pub const PROBE_COLUMNS: [&str; 12] = [
    "t",
    "x",
    "y",
    "z",
    "vx",
    "vy",
    "vz",
    "curvature",
    "moment",
    "tension",
    "sticking",
    "slipping",
];

/// The strand at a probe at one time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProbeSample {
    /// Position (m).
    pub position: [f64; 3],
    /// Velocity (m/s).
    pub velocity: [f64; 3],
    /// Curvature (1/m), the sign convention of `centerline.csv`.
    pub curvature: f64,
    /// Bending moment (N m).
    pub moment: f64,
    /// Tension (N).
    pub tension: f64,
    /// Helical wires sticking there.
    pub sticking: usize,
    /// Helical wires slipping there.
    pub slipping: usize,
}

/// The file name of the probe at `s` (m): `probe_<s>.csv` with s as `centerline.csv` writes
/// it (e.g. `probe_25.csv`, `probe_0.125.csv`).
pub fn file_name(s: f64) -> String {
    format!("probe_{}.csv", number(s))
}

/// The open probe files of a model's run.
pub struct ProbeFiles {
    files: Vec<(f64, Csv, PathBuf)>,
}

impl ProbeFiles {
    /// Creates `probe_<s>.csv` in `dir` for every s of `probes` (m); an error names the file.
    pub fn create(dir: &Path, probes: &[f64]) -> Result<ProbeFiles, String> {
        let files = probes
            .iter()
            .map(|&s| {
                let p = dir.join(file_name(s));
                Csv::create(&p, &PROBE_COLUMNS)
                    .map(|c| (s, c, p.clone()))
                    .map_err(|e| format!("writing {}: {e}", p.display()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ProbeFiles { files })
    }

    /// Whether there are no probes.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Writes the row of time `t` (s) of every probe, `sample(s)` giving the strand at s.
    pub fn write(
        &mut self,
        t: f64,
        mut sample: impl FnMut(f64) -> ProbeSample,
    ) -> Result<(), String> {
        for (s, csv, path) in &mut self.files {
            let p = sample(*s);
            let [x, y, z] = p.position;
            let [vx, vy, vz] = p.velocity;
            csv.row(&[
                t,
                x,
                y,
                z,
                vx,
                vy,
                vz,
                p.curvature,
                p.moment,
                p.tension,
                p.sticking as f64,
                p.slipping as f64,
            ])
            .map_err(|e| format!("writing {}: {e}", path.display()))?;
        }
        Ok(())
    }

    /// Non-finite numbers written as empty fields so far.
    pub fn blanks(&self) -> usize {
        self.files.iter().map(|(_, c, _)| c.blanks()).sum()
    }

    /// Flushes the files; an error names the file.
    pub fn finish(self) -> Result<(), String> {
        for (_, csv, path) in self.files {
            csv.finish()
                .map_err(|e| format!("writing {}: {e}", path.display()))?;
        }
        Ok(())
    }
}
