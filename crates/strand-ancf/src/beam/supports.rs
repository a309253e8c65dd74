//! Supports: which global coordinates the supports hold, the numbering of the free ones, and
//! the prescribed motion of a supported end.
//!
//! A support holds its end's position (pinned) or position and slope (clamped); the held
//! coordinates are eliminated. A support with a [`SupportMotion`] moves its end's position
//! along a table of displacements (the slope of a clamped end keeps its direction): the held
//! position coordinates are `r_ref + d(t)` in dynamics and `r_ref + lambda d_last` at load
//! factor `lambda` in statics (the table's last row applied with the load steps, e.g. to
//! pretension a span).
//!
//! # Dynamics of a moving support
//!
//! With `d(t)` linear between rows, the support's velocity is constant between rows and jumps
//! at them: its acceleration is a sum of impulses. Between rows the held coordinates move at
//! constant velocity and add nothing to the free equations (`M_fp a_p = 0`); a jump `dV` of
//! their velocity is an impulse that the consistent mass passes to the free coordinates, whose
//! velocities jump by `-M_ff^-1 M_fp dV` (the elastic forces are bounded and take no part in an
//! impulse). The integrators apply a jump at the first step boundary at or after its row's
//! time, so its timing is exact to one step, and the held positions themselves are exact at
//! every step. The energy the support puts in is the kinetic energy change of each jump plus,
//! between jumps, the work of the reaction `(M q'' + Q_e - Q)_p` on the held coordinates'
//! displacement (trapezoidal rule over each step).

use super::{Beam, BeamError, BeamSpec, Support};

/// Free-coordinate index of every global coordinate (`None` where a support holds it) and the
/// number of free coordinates, for `nd` coordinates per node: a pinned end holds its position,
/// a clamped one its position and slope.
pub(super) fn free_coordinates(spec: &BeamSpec, nd: usize) -> (Vec<Option<usize>>, usize) {
    let n = spec.elements;
    let dim = nd / 2;
    let n_glob = (n + 1) * nd;
    let mut fixed = vec![false; n_glob];
    for (node, s) in [(0, spec.start), (n, spec.end)] {
        let count = match s {
            None => 0,
            Some(Support::Pinned) => dim,
            Some(Support::Clamped) => nd,
        };
        for k in 0..count {
            fixed[node * nd + k] = true;
        }
    }
    let mut free_index = vec![None; n_glob];
    let mut n_free = 0;
    for (g, f) in fixed.iter().enumerate() {
        if !f {
            free_index[g] = Some(n_free);
            n_free += 1;
        }
    }
    (free_index, n_free)
}

/// `g0..g0 + n_free` if the free coordinates are exactly those (see [`super::Beam::free_span`]).
pub(super) fn free_span(
    free_index: &[Option<usize>],
    n_free: usize,
) -> Option<std::ops::Range<usize>> {
    let g0 = free_index.iter().position(|f| f.is_some())?;
    let span = g0..g0 + n_free;
    free_index
        .iter()
        .enumerate()
        .all(|(g, f)| *f == span.contains(&g).then(|| g - g0))
        .then_some(span)
}

/// The global position coordinates that moving supports hold: `(coordinate, motion, component)`
/// with motion 0 for the start and 1 for the end. Errors when a motion has no support or a
/// planar beam's motion leaves the XY plane.
pub(super) fn moving_coordinates(
    spec: &BeamSpec,
    nd: usize,
) -> Result<Vec<(usize, usize, usize)>, BeamError> {
    let dim = nd / 2;
    let mut out = Vec::new();
    for (m, (motion, support, node, end)) in [
        (&spec.start_motion, spec.start, 0, "start"),
        (&spec.end_motion, spec.end, spec.elements, "end"),
    ]
    .into_iter()
    .enumerate()
    {
        let Some(motion) = motion else { continue };
        if support.is_none() {
            return Err(BeamError::Setup(format!(
                "the {end} has a prescribed motion but no support"
            )));
        }
        if dim == 2 && motion.rows().iter().any(|r| r[3] != 0.0) {
            return Err(BeamError::Setup(format!(
                "the motion of the {end} support leaves the XY plane of a planar beam"
            )));
        }
        out.extend((0..dim).map(|c| (node * nd + c, m, c)));
    }
    Ok(out)
}

/// Prescribed displacement of a supported end: a table of rows `[t, dx, dy, dz]` (s, m),
/// linear between rows, from zero at t = 0 to the first row (when it is later) and constant
/// after the last.
#[derive(Debug, Clone, PartialEq)]
pub struct SupportMotion {
    /// Rows, starting with `[0, 0, 0, 0]`, times strictly increasing.
    rows: Vec<[f64; 4]>,
}

impl SupportMotion {
    /// The motion of the table `rows`. Errors (naming the row) unless every value is finite,
    /// the times are non-negative and strictly increasing, and a row at t = 0 has zero
    /// displacement (the strand starts straight at its supports).
    pub fn new(rows: &[[f64; 4]]) -> Result<SupportMotion, String> {
        if rows.is_empty() {
            return Err("the motion table has no rows".into());
        }
        let mut out = vec![[0.0; 4]];
        for (i, r) in rows.iter().enumerate() {
            if let Some(c) = r.iter().position(|v| !v.is_finite()) {
                return Err(format!("row {i}, column {c}: must be finite"));
            }
            let last = out.last().expect("non-empty")[0];
            if r[0] < 0.0 {
                return Err(format!("row {i}: time {} s must not be negative", r[0]));
            }
            if r[0] == 0.0 && i == 0 {
                if r[1..] != [0.0; 3] {
                    return Err(
                        "row 0: the displacement at t = 0 must be zero (the strand starts \
                         straight at its supports)"
                            .into(),
                    );
                }
                continue;
            }
            if r[0] <= last {
                return Err(format!(
                    "row {i}: times must increase (t = {} s after {last} s)",
                    r[0]
                ));
            }
            out.push(*r);
        }
        Ok(SupportMotion { rows: out })
    }

    /// The rows, starting with `[0, 0, 0, 0]`.
    pub fn rows(&self) -> &[[f64; 4]] {
        &self.rows
    }

    /// Index of the segment `[rows[k], rows[k + 1])` holding `t`, or `None` past the last row.
    fn segment(&self, t: f64) -> Option<usize> {
        let k = self.rows.partition_point(|r| r[0] <= t);
        (k < self.rows.len()).then(|| k.saturating_sub(1))
    }

    /// Displacement at time `t` (m).
    pub fn displacement(&self, t: f64) -> [f64; 3] {
        match self.segment(t) {
            None => self.last(),
            Some(k) => {
                let (a, b) = (self.rows[k], self.rows[k + 1]);
                let s = (t - a[0]) / (b[0] - a[0]);
                std::array::from_fn(|c| a[c + 1] + s * (b[c + 1] - a[c + 1]))
            }
        }
    }

    /// Velocity at time `t` (m/s): the slope of the row segment that starts at or before `t`
    /// (at a row, the following segment's), zero after the last row.
    pub fn velocity(&self, t: f64) -> [f64; 3] {
        match self.segment(t) {
            None => [0.0; 3],
            Some(k) => {
                let (a, b) = (self.rows[k], self.rows[k + 1]);
                std::array::from_fn(|c| (b[c + 1] - a[c + 1]) / (b[0] - a[0]))
            }
        }
    }

    /// The displacement of the last row (m): what statics applies at the full load.
    pub fn last(&self) -> [f64; 3] {
        let r = self.rows.last().expect("non-empty");
        [r[1], r[2], r[3]]
    }
}

impl Beam {
    /// Whether a support moves.
    pub fn has_moving_supports(&self) -> bool {
        !self.moving.is_empty()
    }

    /// Number of coordinates moving supports hold.
    pub fn moving_coords(&self) -> usize {
        self.moving.len()
    }

    /// Sets the coordinates that moving supports hold to their place at time `t` (s).
    pub fn move_supports(&self, q: &mut [f64], t: f64) {
        for &(g, m, c) in &self.moving {
            let d = self.motions[m].as_ref().expect("moving").displacement(t);
            q[g] = self.q_ref[g] + d[c];
        }
    }

    /// Sets the coordinates that moving supports hold to their place at load factor `lambda`
    /// of a static solve: `lambda` times the last row of their tables.
    pub fn move_supports_static(&self, q: &mut [f64], lambda: f64) {
        for &(g, m, c) in &self.moving {
            let d = self.motions[m].as_ref().expect("moving").last();
            q[g] = self.q_ref[g] + lambda * d[c];
        }
    }

    /// Velocities (m/s) of the coordinates moving supports hold at time `t`, in their order
    /// ([`Self::moving_coords`] values): the slopes of their tables (see
    /// [`SupportMotion::velocity`]).
    pub fn support_velocity(&self, t: f64, out: &mut [f64]) {
        for (o, &(_, m, c)) in out.iter_mut().zip(&self.moving) {
            *o = self.motions[m].as_ref().expect("moving").velocity(t)[c];
        }
    }

    /// The global coordinate of each moving held coordinate, in their order.
    pub fn moving_coordinate(&self, k: usize) -> usize {
        self.moving[k].0
    }

    /// `out = M_fp dv` over the free coordinates: the momentum the consistent mass passes to
    /// them from the velocities `dv` of the moving held coordinates.
    pub fn held_coupling(&self, dv: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for &(a, k, m) in &self.held_mass {
            if let Some(i) = self.free_index[a] {
                out[i] += m * dv[k];
            }
        }
    }

    /// Kinetic energy `1/2 v^T M v` (J) of free velocities `vf` and moving held velocities
    /// `vh`; `mv` is scratch of the free size.
    pub fn kinetic_energy(&self, vf: &[f64], vh: &[f64], mv: &mut [f64]) -> f64 {
        self.vector_mass.mul_vec(vf, mv);
        let mut t = 0.5 * vf.iter().zip(mv.iter()).map(|(a, b)| a * b).sum::<f64>();
        for &(a, k, m) in &self.held_mass {
            match self.free_index[a] {
                Some(i) => t += vf[i] * m * vh[k],
                None => {
                    if let Some(j) = self.moving.iter().position(|e| e.0 == a) {
                        t += 0.5 * vh[j] * m * vh[k];
                    }
                }
            }
        }
        t
    }

    /// Elastic force minus `lambda` times the dead load on the moving held coordinates (N),
    /// in their order: the reaction of their supports without its inertial part.
    pub fn held_force(&self, force: &[f64], lambda: f64, out: &mut [f64]) {
        for (o, &(g, _, _)) in out.iter_mut().zip(&self.moving) {
            *o = force[g] - lambda * self.gravity_force[g];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn motion_is_linear_between_rows_and_held_after() {
        let m = SupportMotion::new(&[[1.0, 1.0, 0.0, -2.0], [3.0, 2.0, 4.0, 0.0]]).unwrap();
        assert_eq!(m.displacement(0.0), [0.0; 3]);
        assert_eq!(m.displacement(0.5), [0.5, 0.0, -1.0]);
        assert_eq!(m.displacement(2.0), [1.5, 2.0, -1.0]);
        assert_eq!(m.displacement(7.0), [2.0, 4.0, 0.0]);
        assert_eq!(m.velocity(0.0), [1.0, 0.0, -2.0]);
        assert_eq!(m.velocity(1.0), [0.5, 2.0, 1.0]);
        assert_eq!(m.velocity(3.0), [0.0; 3]);
        assert_eq!(m.last(), [2.0, 4.0, 0.0]);
        assert!(SupportMotion::new(&[[0.0, 1.0, 0.0, 0.0]]).is_err());
        assert!(SupportMotion::new(&[[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]]).is_err());
        assert!(SupportMotion::new(&[[-1.0, 0.0, 0.0, 0.0]]).is_err());
        assert!(SupportMotion::new(&[[1.0, f64::NAN, 0.0, 0.0]]).is_err());
        assert!(SupportMotion::new(&[]).is_err());
        let z = SupportMotion::new(&[[0.0, 0.0, 0.0, 0.0], [2.0, 2.0, 0.0, 0.0]]).unwrap();
        assert_eq!(z.rows().len(), 2);
        assert_eq!(z.velocity(0.0), [1.0, 0.0, 0.0]);
    }
}
