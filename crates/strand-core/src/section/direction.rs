//! The bending direction the friction limits follow (module docs of `section`, "Bending
//! direction of the friction limits").

/// State values per station that hold the stored bending direction of the hysteretic law
/// (after the wires' slips): the unit vector `b` (y, z) of the neutral axis's reference half of
/// the last committed bending beyond the still curvature, (0, 0) before any.
pub(super) const DIRECTION_STATE: usize = 2;

/// The bending direction of a curvature vector as the section law reads it: the angle `beta`
/// of the reference half `b` of the neutral axis (module docs), measured from z toward y as
/// the wire phases are, and d beta / d kappa (m).
#[derive(Debug, Clone, Copy)]
pub(super) struct BendingDirection {
    pub beta: f64,
    pub dbeta: [f64; 2],
}

impl BendingDirection {
    /// The direction of `kappa`; for zero curvature `b = +z` with no derivative.
    #[inline(always)]
    pub fn of(kappa: [f64; 2]) -> Self {
        let n = kappa[0].hypot(kappa[1]);
        if n == 0.0 {
            return BendingDirection {
                beta: 0.0,
                dbeta: [0.0; 2],
            };
        }
        let b = neutral_axis(kappa);
        // beta = atan2(kappa_y, kappa_z) up to a constant (0 or pi).
        BendingDirection {
            beta: b[0].atan2(b[1]),
            dbeta: [kappa[1] / n / n, -kappa[0] / n / n],
        }
    }

    /// The stored direction `tail` ([`DIRECTION_STATE`] values), without derivative; `None`
    /// where none is stored.
    #[inline(always)]
    pub fn stored(tail: &[f64]) -> Option<Self> {
        let stored = [tail[0], tail[1]];
        (stored != [0.0; 2]).then(|| BendingDirection {
            beta: stored[0].atan2(stored[1]),
            dbeta: [0.0; 2],
        })
    }

    /// The direction the hysteretic law reads at curvature `kappa` with the stored direction
    /// `tail` ([`DIRECTION_STATE`] values): `kappa`'s own beyond the still curvature `still`
    /// (1/m), else the stored one (`kappa`'s own if none is stored yet); writes the trial
    /// tail, the direction of `kappa` beyond `still`, else the stored one (module docs).
    #[inline(always)]
    pub fn select(kappa: [f64; 2], still: f64, tail: &[f64], trial: Option<&mut [f64]>) -> Self {
        let stored = [tail[0], tail[1]];
        let (dir, axis) = if kappa[0].hypot(kappa[1]) > still {
            (Self::of(kappa), neutral_axis(kappa))
        } else if let Some(dir) = Self::stored(&stored) {
            (dir, stored)
        } else {
            (Self::of(kappa), stored)
        };
        if let Some(t) = trial {
            t[..DIRECTION_STATE].copy_from_slice(&axis);
        }
        dir
    }

    /// Signed angle (rad, in (-pi, pi]) of the wire at `phase` from `b`: the phase itself
    /// when `b = +z` (planar bending), so that the planar law's values are met bit for bit.
    #[inline(always)]
    pub fn wire_angle(&self, phase: f64) -> f64 {
        if self.beta == 0.0 {
            phase
        } else {
            crate::geometry::wrap_angle(phase - self.beta)
        }
    }
}

/// Reference half of the neutral axis for a curvature vector: the unit vector along `kappa`
/// with a non-negative z component (+y when `kappa_z = 0`); +z for zero curvature.
fn neutral_axis(kappa: [f64; 2]) -> [f64; 2] {
    let n = kappa[0].hypot(kappa[1]);
    if n == 0.0 {
        return [0.0, 1.0];
    }
    let s = if kappa[1] > 0.0 || (kappa[1] == 0.0 && kappa[0] >= 0.0) {
        1.0
    } else {
        -1.0
    };
    [s * kappa[0] / n, s * kappa[1] / n]
}
