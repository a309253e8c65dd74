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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn station(s: f64, v: f64) -> Station {
        Station {
            s,
            position: [s, 0.0, 0.0],
            curvature: v,
            moment: -2.0 * v,
            tension: v * v,
            stiffness: (v > 0.0).then_some(v),
        }
    }

    proptest! {
        /// Over frames at random times, each point's envelope holds exactly the frames in the
        /// window: its min and max are theirs, its mean theirs (to round-off) and within them.
        #[test]
        fn envelopes_are_the_window_frames_extremes_and_mean(
            frames in prop::collection::vec(
                (0.0f64..10.0, prop::collection::vec(-1e3f64..1e3, 3)), 1..40),
            t0 in 0.0f64..10.0, span in 0.0f64..10.0,
        ) {
            let window = (t0, t0 + span);
            let mut env = Envelopes::new(Some(window));
            for (t, values) in &frames {
                let st: Vec<Station> =
                    values.iter().enumerate().map(|(i, v)| station(i as f64, *v)).collect();
                env.add(*t, &st).unwrap();
            }
            let inside: Vec<&Vec<f64>> = frames
                .iter()
                .filter(|(t, _)| (window.0..=window.1).contains(t))
                .map(|(_, v)| v)
                .collect();
            prop_assert_eq!(env.frames(), inside.len());
            for (i, e) in env.extents.iter().enumerate() {
                let col: Vec<f64> = inside.iter().map(|v| v[i]).collect();
                let [lo, hi, mean] = e[0].values();
                if col.is_empty() {
                    prop_assert!(lo.is_nan() && hi.is_nan() && mean.is_nan());
                    continue;
                }
                let min = col.iter().copied().fold(f64::INFINITY, f64::min);
                let max = col.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let avg = col.iter().sum::<f64>() / col.len() as f64;
                prop_assert_eq!((lo, hi), (min, max));
                prop_assert!(lo <= mean && mean <= hi);
                // A sum of at most 40 values below 1e3: round-off well under 1e-9.
                prop_assert!((mean - avg).abs() <= 1e-9);
                // The stiffness only where defined (positive values here).
                let defined = col.iter().filter(|v| **v > 0.0).count();
                prop_assert_eq!(e[3].count, defined);
            }
        }
    }

    #[test]
    fn a_frame_with_other_points_is_refused() {
        let mut env = Envelopes::new(None);
        env.add(0.0, &[station(0.0, 1.0), station(1.0, 2.0)])
            .unwrap();
        assert!(env.add(0.1, &[station(0.0, 1.0)]).is_err());
    }
}
