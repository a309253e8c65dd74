//! Length measures of vectors of free coordinates, for the solvers' step sizes and
//! convergence tests: a position coordinate is a length (m); a slope coordinate is
//! dimensionless, and is measured by the displacement it makes across an element (times the
//! element length), so that a correction of the slopes near a free end counts as much as the
//! positions it moves, not as if a slope of 1e-8 were a displacement of 1e-8 m.

use crate::beam::Beam;

/// Length scale of each free coordinate: 1 for a position, the element length for a slope.
pub(crate) fn length_scales(beam: &Beam) -> Vec<f64> {
    let nd = beam.node_coords();
    let mut scale = vec![0.0; beam.dofs()];
    for g in 0..beam.coords() {
        if let Some(i) = beam.free_index(g) {
            scale[i] = if g % nd < nd / 2 {
                1.0
            } else {
                beam.element_length()
            };
        }
    }
    scale
}

/// The largest displacement a change `dq` of the free coordinates makes (m), with the
/// coordinates' length scales `scale` ([`length_scales`]).
pub(crate) fn displacement(dq: &[f64], scale: &[f64]) -> f64 {
    dq.iter()
        .zip(scale)
        .fold(0.0f64, |a, (x, s)| a.max((x * s).abs()))
}

/// `sum_i a_i b_i`.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `sum_i s_i^2 a_i b_i`: the inner product of two changes of the free coordinates in length
/// units (m^2).
pub(crate) fn scaled_dot(a: &[f64], b: &[f64], scale: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .zip(scale)
        .map(|((x, y), s)| s * s * x * y)
        .sum()
}

/// Unit round-offs of a coordinate that a Newton correction of it may be lost in.
pub(crate) const ROUND_OFF: f64 = 16.0;

/// Whether every component of the correction `dq` (free coordinates) is within `tol` (m) or
/// within the round-off of the positions it moves, both in length units (`scale`,
/// [`length_scales`]; `q` all coordinates): a correction of a node's position or slope moves
/// points near the node, whose positions are known only to the unit round-off of their size,
/// so a position far from the origin cannot be corrected by less than its last bits, while a
/// transverse coordinate near zero can.
pub(crate) fn within_round_off(
    beam: &Beam,
    dq: &[f64],
    q: &[f64],
    scale: &[f64],
    tol: f64,
) -> bool {
    let nd = beam.node_coords();
    let dim = nd / 2;
    q.chunks_exact(nd).enumerate().all(|(node, c)| {
        (0..nd).all(|k| {
            let g = node * nd + k;
            beam.free_index(g).is_none_or(|i| {
                let size = (c[k] * scale[i]).abs().max(c[k % dim].abs());
                (dq[i] * scale[i]).abs() <= tol + ROUND_OFF * f64::EPSILON * size
            })
        })
    })
}
