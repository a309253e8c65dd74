//! The last full cycle of a sampled oscillation: what a moment-curvature loop drawn from a
//! long run shows in full colour, over the whole path drawn pale (thousands of frames of a
//! growing or decaying motion overlap into a tangle; the last cycle is the loop the motion
//! settled to).

use std::ops::RangeInclusive;

/// The frames of the last full cycle of `v`: from the frame before its second-last upward
/// crossing of the middle of its range over the second half of the frames, to the frame of its
/// last one (both included: the cycle's path closes between them). `None` when `v` crosses
/// that level upward fewer than twice or has no spread there (a monotone or constant history).
pub fn last_cycle(v: &[f64]) -> Option<RangeInclusive<usize>> {
    let late = &v[v.len() / 2..];
    let (lo, hi) = late
        .iter()
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    if hi <= lo {
        return None;
    }
    let level = 0.5 * (lo + hi);
    let mut up = (1..v.len())
        .rev()
        .filter(|&k| v[k - 1] < level && v[k] >= level);
    let end = up.next()?;
    let start = up.next()?;
    Some(start - 1..=end)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sine of 40 samples a period over 3.5 periods: the last cycle is the last 40 steps
    /// (41 frames), between upward crossings of zero.
    #[test]
    fn the_last_cycle_of_a_sine_is_one_period() {
        let v: Vec<f64> = (0..140)
            .map(|k| (2.0 * std::f64::consts::PI * (k as f64 + 0.5) / 40.0).sin())
            .collect();
        let c = last_cycle(&v).unwrap();
        assert_eq!(c.end() - c.start(), 41, "{c:?}");
        assert!(v[*c.start()] < 0.0 && v[c.start() + 1] >= 0.0);
        assert!(v[c.end() - 1] < 0.0 && v[*c.end()] >= 0.0);
        assert_eq!(*c.end(), 120);
    }

    /// A growing oscillation about an offset still gives its last period; a ramp or a
    /// constant has no cycle.
    #[test]
    fn an_offset_growing_oscillation_has_a_cycle_and_a_ramp_none() {
        let v: Vec<f64> = (0..200)
            .map(|k| 3.0 + (k as f64 / 50.0) * (2.0 * std::f64::consts::PI * k as f64 / 25.0).cos())
            .collect();
        let c = last_cycle(&v).unwrap();
        // 25 steps a period; the crossing of a growing wave shifts by a step at most.
        assert!((24..=26).contains(&(c.end() - c.start() - 1)), "{c:?}");
        let ramp: Vec<f64> = (0..50).map(f64::from).collect();
        assert_eq!(last_cycle(&ramp), None);
        assert_eq!(last_cycle(&[1.0; 10]), None);
        assert_eq!(last_cycle(&[]), None);
    }
}
