//! Range envelopes (`range.csv`, dynamics): at every measured point along s, the minimum,
//! maximum and mean over the output frames (those within `output.range_window`, if given) of
//! the curvature, bending moment, tension and bending stiffness, as line design reads them.

use std::path::Path;

use crate::along::Station;
use crate::output::Csv;

/// The quantities of `range.csv`, each with `_min`, `_max`, `_mean` columns after `s`.
pub const RANGE_QUANTITIES: [&str; 4] = ["curvature", "moment", "tension", "bending_stiffness"];

/// Min, max and sum of one quantity at one point over the frames where it is defined.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Extent {
    min: f64,
    max: f64,
    sum: f64,
    count: usize,
}

impl Extent {
    const EMPTY: Extent = Extent {
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
        sum: 0.0,
        count: 0,
    };

    fn add(&mut self, v: Option<f64>) {
        if let Some(v) = v.filter(|v| v.is_finite()) {
            self.min = self.min.min(v);
            self.max = self.max.max(v);
            self.sum += v;
            self.count += 1;
        }
    }

    /// (min, max, mean); non-finite (written empty) where no frame defined it.
    fn values(&self) -> [f64; 3] {
        if self.count == 0 {
            return [f64::NAN; 3];
        }
        // The mean of values in [min, max] is in it but for round-off: held there.
        let mean = (self.sum / self.count as f64).clamp(self.min, self.max);
        [self.min, self.max, mean]
    }
}

/// The envelopes of a run being taken, frame by frame.
#[derive(Debug, Clone)]
pub struct Envelopes {
    window: Option<(f64, f64)>,
    s: Vec<f64>,
    extents: Vec<[Extent; 4]>,
    frames: usize,
}

impl Envelopes {
    /// Envelopes over the frames at times in `window` (s, inclusive; `None`: every frame).
    pub fn new(window: Option<(f64, f64)>) -> Envelopes {
        Envelopes {
            window,
            s: Vec::new(),
            extents: Vec::new(),
            frames: 0,
        }
    }

    /// Takes the frame at time `t` (s) into the envelopes, if in the window. The first frame
    /// taken fixes the points; a frame with a different count of points is refused.
    pub fn add(&mut self, t: f64, stations: &[Station]) -> Result<(), String> {
        if let Some((t0, t1)) = self.window
            && !(t0..=t1).contains(&t)
        {
            return Ok(());
        }
        if self.frames == 0 {
            self.s = stations.iter().map(|p| p.s).collect();
            self.extents = vec![[Extent::EMPTY; 4]; stations.len()];
        } else if stations.len() != self.s.len() {
            return Err(format!(
                "range.csv: a frame at t = {t} s has {} points along the strand, the first {}",
                stations.len(),
                self.s.len()
            ));
        }
        for (e, p) in self.extents.iter_mut().zip(stations) {
            e[0].add(Some(p.curvature));
            e[1].add(Some(p.moment));
            e[2].add(Some(p.tension));
            e[3].add(p.stiffness);
        }
        self.frames += 1;
        Ok(())
    }

    /// Frames taken so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Writes `dir/range.csv`; returns the number of empty fields (a quantity no frame in
    /// the window defined, e.g. the stiffness of a strand that stayed straight).
    pub fn write(&self, dir: &Path) -> Result<usize, String> {
        let p = dir.join("range.csv");
        let e = |e: std::io::Error| format!("writing {}: {e}", p.display());
        let mut header = vec!["s".to_string()];
        for q in RANGE_QUANTITIES {
            for stat in ["min", "max", "mean"] {
                header.push(format!("{q}_{stat}"));
            }
        }
        let header: Vec<&str> = header.iter().map(String::as_str).collect();
        let mut c = Csv::create(&p, &header).map_err(e)?;
        for (s, ext) in self.s.iter().zip(&self.extents) {
            let mut row = vec![*s];
            for x in ext {
                row.extend(x.values());
            }
            c.row(&row).map_err(e)?;
        }
        let blanks = c.blanks();
        c.finish().map_err(e)?;
        Ok(blanks)
    }
}
