//! How a sweep over the wires runs: on rayon's threads or in the calling thread, and where
//! it is cut between two threads.
//!
//! A sweep over the seven wires of a one-layer strand is a few tens of microseconds of work;
//! handing it to rayon's pool costs a wake-up and a wait even with one thread in the pool
//! (the calling thread is not one of the pool's: it queues the work and blocks on a latch).
//! With one thread the sweeps run in the calling thread instead. Each wire's work is the same
//! arithmetic either way and every sum across wires is taken in a fixed order after the
//! sweep, so the results do not depend on the choice (the thread-count test of
//! `tests/settled.rs` checks it bit for bit).
//!
//! A sweep whose work is the same for every segment (the kick-drift sweep of the time
//! stepping) is cut in two halves of equal segment counts ([`halfway`]), one wire cut in two
//! if need be, and the halves run by one `rayon::join` ([`both`]): seven wires over two
//! threads as whole wires would give one thread four wires and the other three. The loads
//! sweep is cut where half its estimated cost falls (`load_span`).

/// True when sweeps over wires should run in parallel: rayon's pool, as seen from the
/// calling thread, has more than one thread (`RAYON_NUM_THREADS`).
pub(crate) fn parallel() -> bool {
    rayon::current_num_threads() > 1
}

/// Where a sweep over items of the sizes `sizes` is cut in two halves of equal size (the
/// second half one larger for an odd total): `(i, m)`, the first half is the items before `i`
/// and the first `m` units of item `i` (`m < sizes[i]`; `i == sizes.len()` for an empty
/// sweep).
pub(crate) fn halfway(sizes: impl Iterator<Item = usize> + Clone) -> (usize, usize) {
    let half = sizes.clone().sum::<usize>() / 2;
    let mut before = 0;
    for (i, n) in sizes.enumerate() {
        if before + n > half {
            return (i, half - before);
        }
        before += n;
    }
    (before, 0)
}

/// Where a sweep over whole items of the costs `costs` is cut in two: the number of items
/// in the first half, the cut with the smaller larger half (the first such).
pub(crate) fn balanced_cut(costs: impl Iterator<Item = f64> + Clone) -> usize {
    let total: f64 = costs.clone().sum();
    let mut before = 0.0;
    let (mut best, mut best_load) = (0, total);
    for (i, c) in costs.enumerate() {
        before += c;
        let load = before.max(total - before);
        if load < best_load {
            (best, best_load) = (i + 1, load);
        }
    }
    best
}

/// Runs `a` and `b`: in parallel by one `rayon::join` if `parallel`, else `a` then `b` in the
/// calling thread.
pub(crate) fn both<A, B>(parallel: bool, a: A, b: B)
where
    A: FnOnce() + Send,
    B: FnOnce() + Send,
{
    if parallel {
        rayon::join(a, b);
    } else {
        a();
        b();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halfway_cuts_the_total_in_two() {
        // Seven wires of 77 segments: 269 before the cut, 270 after, in the fourth wire.
        assert_eq!(halfway([77usize; 7].into_iter()), (3, 38));
        assert_eq!(halfway([2usize, 2].into_iter()), (1, 0));
        assert_eq!(halfway([5usize].into_iter()), (0, 2));
        assert_eq!(halfway(std::iter::empty::<usize>()), (0, 0));
        // The loads of a core (cost 1) and six wires (cost 2 each): 1 + 2 + 2 + 2 against 6.
        assert_eq!(
            balanced_cut([1.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0].into_iter()),
            4
        );
        assert_eq!(balanced_cut([1.0, 1.0].into_iter()), 1);
        assert_eq!(balanced_cut([5.0].into_iter()), 0);
        assert_eq!(balanced_cut(std::iter::empty::<f64>()), 0);
        for sizes in [vec![3usize, 0, 9, 1], vec![1, 1, 1], vec![10, 1]] {
            let (i, m) = halfway(sizes.iter().copied());
            let first: usize = sizes[..i].iter().sum::<usize>() + m;
            let total: usize = sizes.iter().sum();
            assert_eq!(first, total / 2, "{sizes:?}");
            assert!(m < sizes[i], "{sizes:?}");
        }
    }
}
