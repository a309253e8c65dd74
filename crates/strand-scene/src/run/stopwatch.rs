//! The solve's clocks: wall time and the process's CPU time (all threads), the pair every
//! `summary.json` reports. CPU time counts the work a run did whatever else the machine runs,
//! so it is the fairer figure for comparing runs taken on a shared machine.

use std::time::Instant;

use super::record::RunSummary;

/// Both clocks from one start.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stopwatch {
    wall: Instant,
    cpu: Option<f64>,
}

impl Stopwatch {
    /// Starts both clocks.
    pub(crate) fn start() -> Stopwatch {
        Stopwatch {
            wall: Instant::now(),
            cpu: process_cpu_time(),
        }
    }

    /// Writes the time since the start into `summary` (`wall_time_s`, `cpu_time_s`).
    pub(crate) fn record(&self, summary: &mut RunSummary) {
        summary.wall_time_s = self.wall.elapsed().as_secs_f64();
        summary.cpu_time_s = self
            .cpu
            .zip(process_cpu_time())
            .map(|(a, b)| (b - a).max(0.0));
    }
}

/// CPU time of this process so far, all threads (s); `None` where there is no such clock.
pub(crate) fn process_cpu_time() -> Option<f64> {
    #[cfg(unix)]
    {
        let t = rustix::time::clock_gettime(rustix::time::ClockId::ProcessCPUTime);
        Some(t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Busy work advances the CPU clock by about the wall time it takes (one thread).
    #[cfg(unix)]
    #[test]
    fn cpu_clock_counts_busy_work() {
        let w = Stopwatch::start();
        let mut x = 0.0f64;
        let t = Instant::now();
        while t.elapsed().as_secs_f64() < 0.05 {
            x = std::hint::black_box(x + 1.0).sqrt();
        }
        let mut s = RunSummary::start("s", "m", "l", "static");
        w.record(&mut s);
        let cpu = s.cpu_time_s.unwrap();
        // At least part of the busy wall time is spent on the CPU (the machine may be shared).
        assert!(
            cpu > 0.005 && cpu <= s.wall_time_s * 2.0 + 0.01,
            "{cpu} {}",
            s.wall_time_s
        );
    }
}
