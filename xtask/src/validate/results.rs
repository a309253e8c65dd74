//! Reading the files a run writes (`centerline.csv`, `energy.csv`).

use std::path::Path;

use anyhow::{Context, bail};

use super::report::worst;

/// A numeric CSV file with a header row.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Column names.
    pub header: Vec<String>,
    /// Rows of numbers.
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// Parses CSV text whose every field after the header is a number; an empty field (a
    /// value the run could not give) reads as NaN, which fails any check it enters.
    pub fn parse(text: &str) -> anyhow::Result<Table> {
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let header: Vec<String> = lines
            .next()
            .context("no header row")?
            .split(',')
            .map(|s| s.trim().to_string())
            .collect();
        let mut rows = Vec::new();
        for (i, line) in lines.enumerate() {
            let row = line
                .split(',')
                .map(|f| match f.trim() {
                    "" => Ok(f64::NAN),
                    f => f.parse::<f64>(),
                })
                .collect::<Result<Vec<f64>, _>>()
                .with_context(|| format!("row {}: not a number", i + 2))?;
            if row.len() != header.len() {
                bail!(
                    "row {}: {} fields for {} columns",
                    i + 2,
                    row.len(),
                    header.len()
                );
            }
            rows.push(row);
        }
        Ok(Table { header, rows })
    }

    /// Reads `path`.
    pub fn load(path: &Path) -> anyhow::Result<Table> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        Table::parse(&text).with_context(|| format!("in {}", path.display()))
    }

    /// The column named `name`.
    pub fn column(&self, name: &str) -> anyhow::Result<Vec<f64>> {
        let j = self
            .header
            .iter()
            .position(|h| h == name)
            .with_context(|| format!("no column `{name}`"))?;
        Ok(self.rows.iter().map(|r| r[j]).collect())
    }
}

/// A model folder's `summary.json` as JSON.
pub fn summary(dir: &Path) -> anyhow::Result<serde_json::Value> {
    let path = dir.join("summary.json");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("parsing {}", path.display()))
}

/// The centreline of a run at its integration points.
#[derive(Debug, Clone, PartialEq)]
pub struct Centerline {
    /// Material coordinate (m), increasing.
    pub s: Vec<f64>,
    /// Position x (m).
    pub x: Vec<f64>,
    /// Position y (m).
    pub y: Vec<f64>,
    /// Position z (m).
    pub z: Vec<f64>,
    /// Axial tension (N).
    pub tension: Vec<f64>,
}

impl Centerline {
    /// Reads `centerline.csv` in the model folder `dir`.
    pub fn load(dir: &Path) -> anyhow::Result<Centerline> {
        let t = Table::load(&dir.join("centerline.csv"))?;
        let c = Centerline {
            s: t.column("s")?,
            x: t.column("x")?,
            y: t.column("y")?,
            z: t.column("z")?,
            tension: t.column("tension")?,
        };
        if c.s.len() < 2 || c.s.windows(2).any(|w| w[1] <= w[0]) {
            bail!(
                "{}: needs at least two rows with increasing s",
                dir.join("centerline.csv").display()
            );
        }
        Ok(c)
    }

    /// The position at material coordinate `s` (m), interpolated linearly.
    pub fn position(&self, s: f64) -> [f64; 3] {
        [
            self.interpolate(&self.x, s),
            self.interpolate(&self.y, s),
            self.interpolate(&self.z, s),
        ]
    }

    /// The position of row `i` (m).
    pub fn point(&self, i: usize) -> [f64; 3] {
        [self.x[i], self.y[i], self.z[i]]
    }

    /// Linear interpolation of `values` at material coordinate `s`, clamped to the sampled
    /// range.
    pub fn interpolate(&self, values: &[f64], s: f64) -> f64 {
        let n = self.s.len();
        if s <= self.s[0] {
            return values[0];
        }
        if s >= self.s[n - 1] {
            return values[n - 1];
        }
        let i = self.s.partition_point(|&v| v <= s) - 1;
        let t = (s - self.s[i]) / (self.s[i + 1] - self.s[i]);
        values[i] + t * (values[i + 1] - values[i])
    }
}

/// The energy ledger of a dynamic run.
#[derive(Debug, Clone, PartialEq)]
pub struct Energy {
    /// Time (s).
    pub t: Vec<f64>,
    /// Kinetic energy (J).
    pub kinetic: Vec<f64>,
    /// Gravity potential (J).
    pub gravity: Vec<f64>,
    /// Elastic energy (J).
    pub elastic: Vec<f64>,
    /// Dissipated work (J).
    pub dissipated: Vec<f64>,
    /// Sum of the four minus the work of moving supports (J).
    pub total: Vec<f64>,
    /// Work of moving supports on the strand (J; zero where the file has no `support_work`).
    pub supports: Vec<f64>,
    /// Work the section law's non-potential part did on the strand (J; zero where the file
    /// has no `non_potential`, as for the fine model, whose wires have no section law).
    pub non_potential: Vec<f64>,
}

impl Energy {
    /// Reads `energy.csv` in the model folder `dir`.
    pub fn load(dir: &Path) -> anyhow::Result<Energy> {
        let t = Table::load(&dir.join("energy.csv"))?;
        let e = Energy {
            t: t.column("t")?,
            kinetic: t.column("kinetic")?,
            gravity: t.column("gravity")?,
            elastic: t.column("elastic")?,
            dissipated: t.column("dissipated")?,
            total: t.column("total")?,
            supports: t
                .column("support_work")
                .unwrap_or_else(|_| vec![0.0; t.rows.len()]),
            non_potential: t
                .column("non_potential")
                .unwrap_or_else(|_| vec![0.0; t.rows.len()]),
        };
        if e.t.is_empty() {
            bail!("{}: no rows", dir.join("energy.csv").display());
        }
        Ok(e)
    }

    /// Largest |total - total(0)| over the output frames relative to the largest kinetic
    /// energy.
    pub fn balance_relative(&self) -> f64 {
        let e0 = self.total[0];
        let err = worst(self.total.iter().map(|e| (e - e0).abs()));
        let kmax = worst(self.kinetic.iter().copied());
        err / kmax.max(f64::MIN_POSITIVE)
    }

    /// The last frame: kinetic, gravity, elastic, dissipated.
    pub fn last(&self) -> [f64; 4] {
        let i = self.t.len() - 1;
        [
            self.kinetic[i],
            self.gravity[i],
            self.elastic[i],
            self.dissipated[i],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_interpolates() {
        let t = Table::parse("s,x,y,z,tension\n0,0,0,0,2\n1,1,-1,3,0\n").unwrap();
        assert_eq!(t.column("y").unwrap(), [0.0, -1.0]);
        assert!(t.column("w").is_err());
        let c = Centerline {
            s: t.column("s").unwrap(),
            x: t.column("x").unwrap(),
            y: t.column("y").unwrap(),
            z: t.column("z").unwrap(),
            tension: t.column("tension").unwrap(),
        };
        assert_eq!(c.interpolate(&c.tension, 0.25), 1.5);
        assert_eq!(c.position(0.5), [0.5, -0.5, 1.5]);
        assert_eq!(c.interpolate(&c.tension, 2.0), 0.0);
        assert!(Table::parse("a,b\n1\n").is_err());
    }

    #[test]
    fn balance_is_relative_to_the_largest_kinetic_energy() {
        let e = Energy {
            t: vec![0.0, 1.0, 2.0],
            kinetic: vec![0.0, 2.0, 1.0],
            gravity: vec![0.0; 3],
            elastic: vec![0.0; 3],
            dissipated: vec![0.0; 3],
            total: vec![0.0, 0.1, -0.2],
            supports: vec![0.0; 3],
            non_potential: vec![0.0; 3],
        };
        assert!((e.balance_relative() - 0.1).abs() < 1e-15);
    }
}
