//! The step budget of a run: a dynamic run whose step count exceeds `analysis.max_steps` is
//! refused before it starts, with the count and an estimate of its time from the cost of a
//! step measured on this machine.

use std::time::Instant;

use super::record::{Failure, Stop};

/// Steps of `step` (s) that fit `duration` (s), as a float (no overflow for any input).
pub(crate) fn steps_of(duration: f64, step: f64) -> f64 {
    (duration / step).ceil().max(1.0)
}

/// The fastest of a few timed calls of `f` (s): the cost of one call on this machine now.
pub(crate) fn time_of(mut f: impl FnMut()) -> f64 {
    (0..3)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Refuses a run of `steps` steps of `step` (s) above `limit`, saying how long it would take at
/// `per_step` (s, a low and a high estimate of one step's cost) and what `cost` that is.
pub(crate) fn check(
    steps: f64,
    step: f64,
    limit: usize,
    per_step: (f64, f64),
    cost: &str,
) -> Result<(), Stop> {
    if steps <= limit as f64 {
        return Ok(());
    }
    let (lo, hi) = (steps * per_step.0, steps * per_step.1);
    let time = if hi > 1.5 * lo {
        format!("{} to {}", duration(lo), duration(hi))
    } else {
        duration(hi)
    };
    Err(Stop::new(
        Failure::StepLimit,
        format!(
            "{steps:.4e} time steps of {step:.4e} s would exceed analysis.max_steps = {limit}; at \
             {cost} the run would take about {time}. Shorten analysis.duration or lengthen the \
             step, or raise analysis.max_steps (or pass --max-steps) to run it anyway"
        ),
    ))
}

/// A duration in the largest unit that keeps it above 1 (s, min, h, days, years); below a
/// second in seconds with an exponent.
pub(crate) fn duration(seconds: f64) -> String {
    const UNITS: [(f64, &str); 4] = [
        (365.25 * 86400.0, "years"),
        (86400.0, "days"),
        (3600.0, "h"),
        (60.0, "min"),
    ];
    for (size, unit) in UNITS {
        if seconds >= size {
            return format!("{:.3} {unit}", seconds / size);
        }
    }
    if seconds >= 1.0 {
        format!("{seconds:.3} s")
    } else {
        format!("{seconds:.3e} s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_do_not_overflow_and_refusals_name_count_and_time() {
        assert_eq!(steps_of(1e12, 5e-4), 2e15);
        assert!(steps_of(1.0, 1e-300).is_finite() && steps_of(1.0, 1e-300) > 9e299);
        assert_eq!(
            steps_of(1.0, f64::MIN_POSITIVE),
            f64::INFINITY.min(1.0 / f64::MIN_POSITIVE)
        );
        assert!(check(1e7, 1e-3, 10_000_000, (1e-3, 1e-3), "").is_ok());
        let e = check(2e15, 5e-4, 10_000_000, (1e-4, 1e-3), "x").unwrap_err();
        assert_eq!(e.reason, Failure::StepLimit);
        assert!(e.message.contains("2.0000e15 time steps"), "{}", e.message);
        // 2e11 s to 2e12 s.
        assert!(
            e.message.contains("6337.618 years to 63376.176 years"),
            "{}",
            e.message
        );
        assert_eq!(duration(90.0), "1.500 min");
        assert_eq!(duration(2.5), "2.500 s");
        assert_eq!(duration(4.1e-6), "4.100e-6 s");
    }
}
