//! Whether a sweep over the wires runs on rayon's threads or in the calling thread.
//!
//! A sweep over the seven wires of a one-layer strand is a few tens of microseconds of work;
//! handing it to rayon's pool costs a wake-up and a wait even with one thread in the pool
//! (the calling thread is not one of the pool's: it queues the work and blocks on a latch).
//! With one thread the sweeps run in the calling thread instead. Each wire's work is the same
//! arithmetic either way and every sum across wires is taken in a fixed order after the
//! sweep, so the results do not depend on the choice (the thread-count test of
//! `tests/settled.rs` checks it bit for bit).

/// True when sweeps over wires should run in parallel: rayon's pool, as seen from the
/// calling thread, has more than one thread (`RAYON_NUM_THREADS`).
pub(crate) fn parallel() -> bool {
    rayon::current_num_threads() > 1
}
