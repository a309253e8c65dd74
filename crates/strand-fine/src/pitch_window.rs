//! The window along the strand over which a bending test of a strand of several layers takes
//! its moment and curvature: whole pitches of every layer.
//!
//! Each helical layer pushes the core sideways as its wires turn round it, so the core's
//! curvature oscillates with the pitch of every layer (about +-2.5 % with the layer on the core
//! of the 1+6+12 strand). A mean over a window takes the mean of such an oscillation exactly
//! only if the window is a whole number of its periods. The window here is a weight along the
//! rest x: the convolution of boxes, one a whole pitch of each layer, centred on the strand.
//! A box of length `b` averages any function of period `p` exactly when `b / p` is whole, and
//! a convolution of boxes does so when one of its boxes does; so the weight averages every
//! layer's oscillation, whether the pitches are commensurate or not, and it is the same at any
//! length of the strand. Where one box is already a whole number of pitches of another layer
//! (within [`COMMENSURATE`]) that layer's box is left out (on pitches in the ratio 2 : 1 the
//! window is one box, a whole number of pitches of both).

use crate::segment::Pose;

/// Largest leftover of a pitch, as a fraction of that pitch, for which a box counts as a whole
/// number of the layer's pitches. An oscillation of relative amplitude `a` and period `p`
/// averaged over `n p + d` leaves at most `a |d| / (n p)`: at 1e-4 of the pitch and the
/// 2.5 % of the 1+6+12 core, under 2.5e-6.
pub const COMMENSURATE: f64 = 1e-4;

/// Shifts per pitch in the quadrature of each convolved box (midpoint rule): the means over
/// the first box are smooth and periodic in the shift (they only drift with the end
/// effects), so the rule is exact for their harmonics below this number.
const SHIFTS: usize = 32;

/// A weight along the strand's rest x: the convolution of boxes of the given lengths, centred.
#[derive(Debug, Clone, PartialEq)]
pub struct PitchWindow {
    /// Rest x of the centre (m).
    pub centre: f64,
    /// Lengths of the convolved boxes (m), each a whole pitch of a layer, longest first.
    pub boxes: Vec<f64>,
}

impl PitchWindow {
    /// The window of a bending test of `strand` (several layers) `pitches` of its longest
    /// pitch long: [`PitchWindow::for_layers`] over the layers' pitches.
    pub fn for_strand(strand: &strand_core::Strand, pitches: usize) -> PitchWindow {
        let layer_pitches: Vec<f64> = strand.layers().iter().map(|l| l.pitch).collect();
        let longest = layer_pitches.iter().copied().fold(0.0, f64::max);
        PitchWindow::for_layers(&layer_pitches, longest * pitches as f64)
    }

    /// The window of a strand `length` (m) long with layers of pitch `pitches` (m, from the
    /// core outward): one box per layer, a whole pitch, without the boxes of layers whose
    /// pitch another box spans a whole number of times ([`COMMENSURATE`]); centred. Where the
    /// boxes' total exceeds the length less the longest pitch (half a pitch clear of each
    /// clamp), the outermost layers' boxes are dropped until it fits (the layer on the core,
    /// whose oscillation of the core's curvature is the largest, keeps its box).
    pub fn for_layers(pitches: &[f64], length: f64) -> PitchWindow {
        let longest = pitches.iter().copied().fold(0.0, f64::max);
        let mut kept: Vec<f64> = Vec::new();
        for (i, &p) in pitches.iter().enumerate() {
            let spanned = pitches
                .iter()
                .enumerate()
                .any(|(j, &b)| j != i && whole(b, p) && (b > p || (b == p && j < i)));
            if !spanned {
                kept.push(p);
            }
        }
        while kept.len() > 1 && kept.iter().sum::<f64>() > length - longest {
            kept.pop();
        }
        kept.sort_by(|a, b| b.total_cmp(a));
        PitchWindow {
            centre: 0.5 * length,
            boxes: kept,
        }
    }

    /// The window's support: rest x from the centre less half the boxes' total to the centre
    /// plus half of it (m).
    pub fn support(&self) -> (f64, f64) {
        let half = 0.5 * self.boxes.iter().sum::<f64>();
        (self.centre - half, self.centre + half)
    }

    /// The first box's windows `[lo, hi]` (m) whose mean over the shifts is the weighted
    /// mean: the first box shifted over every other box (midpoint rule, [`SHIFTS`] per box).
    fn boxes(&self) -> Vec<(f64, f64)> {
        let Some((&first, rest)) = self.boxes.split_first() else {
            return Vec::new();
        };
        let mut shifts = vec![0.0];
        for &b in rest {
            shifts = shifts
                .iter()
                .flat_map(|&s| {
                    (0..SHIFTS).map(move |i| s + b * ((i as f64 + 0.5) / SHIFTS as f64 - 0.5))
                })
                .collect();
        }
        shifts
            .into_iter()
            .map(|s| {
                let c = self.centre + s;
                (c - 0.5 * first, c + 0.5 * first)
            })
            .collect()
    }

    /// Rest x of `per_box` points in each of the first box's shifted windows (midpoint
    /// rule): their plain mean of a function is its weighted mean over the window (exact for
    /// a sum of functions each periodic with one layer's pitch, up to harmonic `per_box` of
    /// the first box's layer and 32 of the others).
    pub fn stations(&self, per_box: usize) -> Vec<f64> {
        self.boxes()
            .into_iter()
            .flat_map(|(lo, hi)| {
                (0..per_box).map(move |i| lo + (hi - lo) * (i as f64 + 0.5) / per_box as f64)
            })
            .collect()
    }

    /// The weighted means of the moment and the curvature (N m, 1/m): the moment `profile`
    /// (rest x of every cut through the core's joints, moment), linear between the cuts; the
    /// curvature of the core whose segments, each `l` (m) long at rest, have the poses
    /// `poses`: over each box, the change of the tangent angle (linear between segment
    /// centres) over the arc length between the box's ends on the deformed centreline (linear
    /// between segment centres).
    pub fn measure(&self, profile: &[(f64, f64)], poses: &[Pose], l: f64) -> (f64, f64) {
        let moment = Prefix::new(profile);
        let n = poses.len();
        let angle: Vec<f64> = poses
            .iter()
            .map(|p| {
                let t = p.tangent();
                t.y.atan2(t.x)
            })
            .collect();
        let mut arc = vec![0.0; n];
        for k in 1..n {
            arc[k] = arc[k - 1] + (poses[k].position - poses[k - 1].position).norm();
        }
        // Segment k's centre is at rest x (k + 1/2) l.
        let at = |v: &[f64], x: f64| {
            let u = (x / l - 0.5).clamp(0.0, (n - 1) as f64);
            let k = (u.floor() as usize).min(n - 2);
            let f = u - k as f64;
            (1.0 - f) * v[k] + f * v[k + 1]
        };
        let boxes = self.boxes();
        let (mut m, mut kappa) = (0.0, 0.0);
        for &(lo, hi) in &boxes {
            m += (moment.integral(hi) - moment.integral(lo)) / (hi - lo);
            kappa += (at(&angle, hi) - at(&angle, lo)) / (at(&arc, hi) - at(&arc, lo));
        }
        let count = boxes.len().max(1) as f64;
        (m / count, kappa / count)
    }

    /// The weighted mean (unit of the values) of a `profile` (rest x in m, value) linear
    /// between its points.
    pub fn mean(&self, profile: &[(f64, f64)]) -> f64 {
        let prefix = Prefix::new(profile);
        let boxes = self.boxes();
        boxes
            .iter()
            .map(|&(lo, hi)| (prefix.integral(hi) - prefix.integral(lo)) / (hi - lo))
            .sum::<f64>()
            / boxes.len().max(1) as f64
    }

    /// One line for outputs: the boxes and the support (m).
    pub fn describe(&self) -> String {
        let (lo, hi) = self.support();
        let boxes: Vec<String> = self.boxes.iter().map(|b| format!("{b:.6e}")).collect();
        let what = if boxes.len() == 1 {
            "a box"
        } else {
            "boxes convolved"
        };
        format!(
            "whole pitches of every layer: {what} of {} m, centred, rest x {lo:.6e} to {hi:.6e} m",
            boxes.join(" and ")
        )
    }
}

/// Whether `b` is a whole number (at least one) of pitches `p` within [`COMMENSURATE`].
fn whole(b: f64, p: f64) -> bool {
    let r = b / p;
    r.round() >= 1.0 && (r - r.round()).abs() <= COMMENSURATE
}

/// The integral from the first cut of a profile linear between its points.
struct Prefix<'a> {
    points: &'a [(f64, f64)],
    sums: Vec<f64>,
}

impl<'a> Prefix<'a> {
    fn new(points: &'a [(f64, f64)]) -> Self {
        let mut sums = vec![0.0; points.len()];
        for k in 1..points.len() {
            let ((x0, m0), (x1, m1)) = (points[k - 1], points[k]);
            sums[k] = sums[k - 1] + 0.5 * (m0 + m1) * (x1 - x0);
        }
        Prefix { points, sums }
    }

    /// The integral from the first point to `x` (clamped to the points' range).
    fn integral(&self, x: f64) -> f64 {
        let p = self.points;
        let k = p.partition_point(|q| q.0 <= x);
        if k == 0 {
            return 0.0;
        }
        if k == p.len() {
            return self.sums[k - 1];
        }
        let ((x0, m0), (x1, m1)) = (p[k - 1], p[k]);
        let mx = m0 + (m1 - m0) * (x - x0) / (x1 - x0);
        self.sums[k - 1] + 0.5 * (m0 + mx) * (x - x0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{UnitQuaternion, Vector3};

    /// The 1+6+12 pitches (inner, outer; m): not commensurate, both boxes kept, the longest
    /// first; the support is their sum, centred.
    #[test]
    fn incommensurate_pitches_keep_a_box_each() {
        let w = PitchWindow::for_layers(&[0.140828, 0.181794], 3.0 * 0.181794);
        assert_eq!(w.boxes, vec![0.181794, 0.140828]);
        let (lo, hi) = w.support();
        assert!((hi - lo - (0.181794 + 0.140828)).abs() < 1e-15);
        assert!((0.5 * (lo + hi) - 1.5 * 0.181794).abs() < 1e-15);
    }

    /// A box two pitches of the inner layer long spans it: one box; and equal pitches one box.
    #[test]
    fn commensurate_pitches_share_a_box() {
        let w = PitchWindow::for_layers(&[0.1, 0.2 * (1.0 + 1e-6)], 0.6);
        assert_eq!(w.boxes.len(), 1);
        assert_eq!(w.boxes[0], 0.2 * (1.0 + 1e-6));
        let w = PitchWindow::for_layers(&[0.1, 0.2 * (1.0 + 1e-3)], 0.6);
        assert_eq!(w.boxes.len(), 2);
        let w = PitchWindow::for_layers(&[0.15, 0.15], 0.6);
        assert_eq!(w.boxes, vec![0.15]);
    }

    /// Boxes that do not fit half a longest pitch clear of each clamp are dropped from the
    /// outermost layer inward.
    #[test]
    fn boxes_that_do_not_fit_are_dropped_from_outside() {
        let w = PitchWindow::for_layers(&[0.1, 0.13, 0.17], 3.0 * 0.17);
        assert_eq!(w.boxes, vec![0.13, 0.1]);
        let w = PitchWindow::for_layers(&[0.1, 0.13, 0.17], 4.0 * 0.17);
        assert_eq!(w.boxes.len(), 3);
    }

    /// The weighted mean of `c + a sin(2 pi x / p_j)` for each pitch `p_j` of the window is
    /// `c` (to the quadrature's round-off), while a plain box of one pitch misses it for the
    /// other pitch; and the weighted mean of a linear function is its value at the centre.
    #[test]
    fn the_weight_averages_every_layers_oscillation() {
        let (p1, p2) = (0.140828, 0.181794);
        let w = PitchWindow::for_layers(&[p1, p2], 3.0 * p2);
        let n = 4000;
        let dx = 3.0 * p2 / n as f64;
        for p in [p1, p2] {
            let profile: Vec<(f64, f64)> = (0..=n)
                .map(|k| {
                    let x = k as f64 * dx;
                    (x, 1.0 + 0.025 * (std::f64::consts::TAU * x / p + 0.3).sin())
                })
                .collect();
            let m: f64 = w
                .boxes()
                .iter()
                .map(|&(lo, hi)| {
                    let pre = Prefix::new(&profile);
                    (pre.integral(hi) - pre.integral(lo)) / (hi - lo)
                })
                .sum::<f64>()
                / w.boxes().len() as f64;
            // Linear interpolation of the sine between points: relative error
            // (2 pi dx / p)^2 / 8 of the amplitude.
            let interp = 0.025 * (std::f64::consts::TAU * dx / p).powi(2) / 8.0;
            assert!(
                (m - 1.0).abs() < interp + 1e-12,
                "period {p}: {:.3e}",
                m - 1.0
            );
        }
        let profile = [(0.0, 2.0), (3.0 * p2, 2.0 + 3.0 * 3.0 * p2)];
        let pre = Prefix::new(&profile);
        let m: f64 = w
            .boxes()
            .iter()
            .map(|&(lo, hi)| (pre.integral(hi) - pre.integral(lo)) / (hi - lo))
            .sum::<f64>()
            / w.boxes().len() as f64;
        assert!((m - (2.0 + 3.0 * w.centre)).abs() < 1e-12);
    }

    /// On a circular arc of curvature `kappa` (the segments' tangents turn by `kappa l` from
    /// one to the next, centres a chord apart) the measured curvature is `kappa` times the
    /// arc over the chord between centres, (kappa l / 2) / sin(kappa l / 2).
    #[test]
    fn an_arc_measures_its_curvature() {
        let (kappa, l, n) = (2.0, 0.005, 120);
        let poses: Vec<Pose> = (0..n)
            .map(|k| {
                let th = kappa * l * (k as f64 + 0.5);
                Pose::new(
                    Vector3::new(th.sin() / kappa, (1.0 - th.cos()) / kappa, 0.0),
                    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), th),
                )
            })
            .collect();
        let profile: Vec<(f64, f64)> = (0..=n).map(|k| (k as f64 * l, 1.0)).collect();
        let w = PitchWindow::for_layers(&[0.13, 0.17], n as f64 * l);
        let (m, k) = w.measure(&profile, &poses, l);
        assert!((m - 1.0).abs() < 1e-14);
        let chord = (0.5 * kappa * l) / (0.5 * kappa * l).sin();
        assert!((k / kappa - chord).abs() < 1e-12, "{k}");
    }
}
