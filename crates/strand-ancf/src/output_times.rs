//! When a dynamic run writes a frame: at the first step at or past each multiple of the
//! output interval, and at the last step.
//!
//! The output times are `k * interval`, `k = 1, 2, ...`; the frame index of a time `t` is
//! computed from `t` directly (`floor(t / interval)`), so that an interval far below the
//! step costs one division per step (not one addition per skipped output time, about `h /
//! interval` of them) and the output times carry no drift from repeated addition.

/// The output schedule of a run of steps `h` (s) with frames every `interval` (s).
#[derive(Debug, Clone, Copy)]
pub(crate) struct OutputTimes {
    interval: f64,
    /// A time within this of an output time (s) is taken for it: `1e-9 h`, far above the
    /// round-off of `step * h` and far below a step.
    slack: f64,
    /// Index of the last output time a frame was written for.
    last: f64,
    /// The interval is at most a step: every step writes a frame.
    every_step: bool,
}

impl OutputTimes {
    /// The schedule of frames every `interval` (s) at steps of `h` (s).
    pub(crate) fn new(interval: f64, h: f64) -> OutputTimes {
        OutputTimes {
            interval,
            slack: 1e-9 * h,
            last: 0.0,
            // At most one step apart, consecutive steps always pass an output time; deciding it
            // here also keeps `t / interval` from overflowing for an interval near the
            // smallest float.
            every_step: interval <= h,
        }
    }

    /// Whether the step ending at `t` (s) writes a frame: it has reached an output time not
    /// yet written, or it is the run's `last` step.
    pub(crate) fn due(&mut self, t: f64, last: bool) -> bool {
        if self.every_step {
            return true;
        }
        let k = ((t + self.slack) / self.interval).floor();
        let due = k > self.last;
        if due {
            self.last = k;
        }
        due || last
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steps `1..=n` of `h` that write a frame.
    fn frames(interval: f64, h: f64, n: usize) -> Vec<usize> {
        let mut o = OutputTimes::new(interval, h);
        (1..=n).filter(|&s| o.due(s as f64 * h, s == n)).collect()
    }

    #[test]
    fn frames_fall_on_the_first_step_at_or_past_each_output_time() {
        // An interval of 2.5 steps: output times 2.5 h, 5 h, 7.5 h, 10 h.
        assert_eq!(frames(2.5e-3, 1e-3, 10), vec![3, 5, 8, 10]);
        // A multiple of the step: every fourth step, and the last.
        assert_eq!(frames(4e-3, 1e-3, 10), vec![4, 8, 10]);
        // A step of 0.1 in binary is not exact; 10 * 0.1 still writes at the tenth step.
        assert_eq!(frames(1.0, 0.1, 20), vec![10, 20]);
        // Longer than the run: the last step alone.
        assert_eq!(frames(1.0, 1e-3, 10), vec![10]);
    }

    #[test]
    fn an_interval_below_the_step_writes_every_step() {
        for interval in [1e-3, 1e-13, f64::MIN_POSITIVE] {
            assert_eq!(frames(interval, 1e-3, 7), (1..=7).collect::<Vec<_>>());
        }
        // Just above the step: the first step comes before the first output time, and every
        // later step passes one.
        assert_eq!(
            frames(1e-3 * (1.0 + 1e-6), 1e-3, 1000),
            (2..=1000).collect::<Vec<_>>()
        );
    }
}
