//! Free-vibration decay of a sampled history (a probe's displacement): its cycles, each
//! cycle's amplitude, and the logarithmic decrement per cycle.
//!
//! A cycle runs from one upward crossing of the history's mean to the next; its amplitude is
//! half its peak-to-peak range. Cycles delimited by mean crossings are robust to the small
//! ripples of higher modes that make spurious local maxima.

/// One cycle of a history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    /// Start of the cycle: the sample at or after the upward mean crossing (s).
    pub start: f64,
    /// Index of the start sample.
    pub start_index: usize,
    /// Time of the cycle's largest value (s).
    pub peak_time: f64,
    /// Index of the cycle's largest value.
    pub peak_index: usize,
    /// Half the cycle's peak-to-peak range (the history's unit).
    pub amplitude: f64,
}

/// The cycles of a history and their decay.
#[derive(Debug, Clone, PartialEq)]
pub struct Decay {
    /// The history's mean over the samples analysed.
    pub mean: f64,
    /// The complete cycles, in time order.
    pub cycles: Vec<Cycle>,
    /// The logarithmic decrement per cycle, -d ln(a)/dk, the least-squares slope of the
    /// cycles' log amplitudes against the cycle count; `None` with fewer than two cycles.
    pub decrement: Option<f64>,
    /// The mean period of the complete cycles (s); `None` with fewer than one.
    pub period: Option<f64>,
}

/// The cycles of `y(t)` over the samples with `t >= from` and their logarithmic decrement.
/// `t` increases; `t` and `y` have the same length.
pub fn decay(t: &[f64], y: &[f64], from: f64) -> Decay {
    assert_eq!(t.len(), y.len(), "one value per time");
    let first = t.iter().position(|&ti| ti >= from).unwrap_or(t.len());
    let (t, y) = (&t[first..], &y[first..]);
    let mean = if y.is_empty() {
        0.0
    } else {
        y.iter().sum::<f64>() / y.len() as f64
    };
    let ups: Vec<usize> = (1..y.len())
        .filter(|&i| y[i - 1] < mean && y[i] >= mean)
        .collect();
    let cycles: Vec<Cycle> = ups
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let (mut hi, mut lo) = (a, a);
            for i in a..=b {
                if y[i] > y[hi] {
                    hi = i;
                }
                if y[i] < y[lo] {
                    lo = i;
                }
            }
            Cycle {
                start: t[a],
                start_index: first + a,
                peak_time: t[hi],
                peak_index: first + hi,
                amplitude: 0.5 * (y[hi] - y[lo]),
            }
        })
        .collect();
    let period = match (ups.first(), ups.last()) {
        (Some(&a), Some(&b)) if b > a => Some((t[b] - t[a]) / (ups.len() - 1) as f64),
        _ => None,
    };
    Decay {
        mean,
        decrement: log_decrement(&cycles),
        cycles,
        period,
    }
}

/// The least-squares slope of ln(a_k) against k, negated.
fn log_decrement(cycles: &[Cycle]) -> Option<f64> {
    let n = cycles.len();
    if n < 2 || cycles.iter().any(|c| c.amplitude <= 0.0) {
        return None;
    }
    let k_mean = (n - 1) as f64 / 2.0;
    let l_mean = cycles.iter().map(|c| c.amplitude.ln()).sum::<f64>() / n as f64;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (k, c) in cycles.iter().enumerate() {
        let dk = k as f64 - k_mean;
        sxy += dk * (c.amplitude.ln() - l_mean);
        sxx += dk * dk;
    }
    Some(-sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sampled damped cosine: its decrement is 2 pi zeta / sqrt(1 - zeta^2) in closed form.
    #[test]
    fn damped_cosine_has_its_closed_form_decrement() {
        let (zeta, omega, dt) = (0.02_f64, 2.0 * std::f64::consts::PI * 2.0, 1e-4);
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let t: Vec<f64> = (0..60_000).map(|i| i as f64 * dt).collect();
        let y: Vec<f64> = t
            .iter()
            .map(|&t| 0.3 - (-zeta * omega * t).exp() * (wd * t).cos())
            .collect();
        let d = decay(&t, &y, 0.0);
        let exact = 2.0 * std::f64::consts::PI * zeta / (1.0 - zeta * zeta).sqrt();
        let got = d.decrement.unwrap();
        // The cycles' half ranges are not the envelope at one instant: a cycle's maximum and
        // minimum are half a period apart, a relative shift that is the same in every cycle,
        // so the slope of the logs is exact up to the sampling (dt omega)^2 and the mean's
        // offset from the true centre (a fraction of the last amplitude, third order here).
        assert!((got - exact).abs() < 1e-3 * exact, "{got} vs {exact}");
        assert!((d.period.unwrap() - 2.0 * std::f64::consts::PI / wd).abs() < 2.0 * dt);
        assert!(d.cycles.len() >= 10);
    }

    #[test]
    fn undamped_cosine_has_no_decrement() {
        let t: Vec<f64> = (0..20_000).map(|i| i as f64 * 1e-4).collect();
        let y: Vec<f64> = t.iter().map(|&t| (13.0 * t).sin()).collect();
        let d = decay(&t, &y, 0.0);
        assert!(d.decrement.unwrap().abs() < 1e-6, "{:?}", d.decrement);
    }

    #[test]
    fn too_short_a_history_has_none() {
        let d = decay(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0], 0.0);
        assert_eq!(d.decrement, None);
        assert!(d.cycles.is_empty());
    }
}
