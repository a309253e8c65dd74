//! Supports: which global coordinates the supports hold, and the numbering of the free ones.

use super::{BeamSpec, Support};

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

/// `g0..g0 + n_free` if the free coordinates are exactly those (see [`Beam::free_span`]).
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
