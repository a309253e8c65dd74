//! A barrier for a few threads that each hold a core: a waiter first spins on an atomic
//! generation counter, so that passing the barrier costs a cache line's hand-over rather
//! than a sleep and a wake-up, and parks (sleeps until woken) once it has spun for its spin
//! budget. The budget adapts: it halves after every wait that ended parked (on a machine
//! with more runnable threads than cores the other party is often not running, and spinning
//! for it only takes a core from the threads that are) and doubles, up to
//! [`MAX_SPIN`], after every wait that ended spinning.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::thread::Thread;
use std::time::{Duration, Instant};

/// Longest spin before parking (s): well above a wait on an idle machine (the few
/// microseconds by which two balanced halves of a sweep end apart), well below a time slice.
pub(crate) const MAX_SPIN: f64 = 50e-6;
/// Shortest spin budget (s).
const MIN_SPIN: f64 = 0.5e-6;
/// Spins between looks at the clock.
const SPINS_PER_LOOK: usize = 32;

/// A party's state at the barrier, on cache lines of its own (the other parties only look
/// at it when it may be parked).
#[derive(Debug, Default)]
#[repr(align(128))]
struct Party {
    /// The party's thread, to wake it (set at its first wait).
    thread: OnceLock<Thread>,
    /// True while the party is parked or about to park.
    sleeping: AtomicBool,
    /// Spin budget (s), as the bits of an `f64`.
    budget: AtomicU64,
    /// Waits that ended parked (for studies and tests).
    parked: AtomicU64,
}

/// A reusable barrier for a fixed number of parties, each calling [`SpinBarrier::wait`] with
/// its own index.
#[derive(Debug)]
pub(crate) struct SpinBarrier {
    parties: Vec<Party>,
    arrived: Padded<AtomicUsize>,
    /// The waiters spin on it: on a cache line apart from `arrived`, which every arrival
    /// writes.
    generation: Padded<AtomicUsize>,
    broken: AtomicBool,
}

/// A value on cache lines of its own.
#[derive(Debug, Default)]
#[repr(align(128))]
struct Padded<T>(T);

impl<T> std::ops::Deref for Padded<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.0
    }
}

impl SpinBarrier {
    /// Barrier for `parties` threads (at least 1).
    pub(crate) fn new(parties: usize) -> Self {
        assert!(parties >= 1, "a barrier needs a party");
        Self {
            parties: (0..parties)
                .map(|_| Party {
                    budget: AtomicU64::new(MAX_SPIN.to_bits()),
                    ..Party::default()
                })
                .collect(),
            arrived: Padded(AtomicUsize::new(0)),
            generation: Padded(AtomicUsize::new(0)),
            broken: AtomicBool::new(false),
        }
    }

    /// Waits, as party `me`, until all parties have called `wait` for this generation.
    /// Everything a party wrote before its call is visible to every party after it returns.
    /// Panics if the barrier was broken ([`SpinBarrier::break_it`]) while waiting.
    pub(crate) fn wait(&self, me: usize) {
        let party = &self.parties[me];
        party.thread.get_or_init(std::thread::current);
        let generation = self.generation.load(Ordering::Acquire);
        if self.arrived.fetch_add(1, Ordering::AcqRel) + 1 == self.parties.len() {
            // Last to arrive: every other party is waiting on the generation, none can
            // arrive again before it moves on.
            self.arrived.store(0, Ordering::Relaxed);
            self.generation.fetch_add(1, Ordering::SeqCst);
            for (i, p) in self.parties.iter().enumerate() {
                // A party that parks raises its flag before its last look at the
                // generation: a look here that sees it lowered was before it (both
                // sequentially consistent), and that party then sees the new generation.
                if i != me
                    && p.sleeping.load(Ordering::SeqCst)
                    && p.sleeping.swap(false, Ordering::SeqCst)
                {
                    p.thread
                        .get()
                        .expect("a parked party has its thread")
                        .unpark();
                }
            }
            return;
        }
        let passed = || self.generation.load(Ordering::Acquire) != generation;
        let budget = f64::from_bits(party.budget.load(Ordering::Relaxed));
        let start = Instant::now();
        loop {
            for _ in 0..SPINS_PER_LOOK {
                if passed() {
                    if budget < MAX_SPIN {
                        party
                            .budget
                            .store((2.0 * budget).min(MAX_SPIN).to_bits(), Ordering::Relaxed);
                    }
                    return;
                }
                std::hint::spin_loop();
            }
            if start.elapsed().as_secs_f64() > budget {
                break;
            }
        }
        // Park. The flag is raised before the last look at the generation, and the last
        // party moves the generation before it looks at the flag (both sequentially
        // consistent): either this party sees the new generation or it is woken.
        party.sleeping.store(true, Ordering::SeqCst);
        while self.generation.load(Ordering::SeqCst) == generation {
            assert!(
                !self.broken.load(Ordering::Relaxed),
                "a thread of the split sweep panicked"
            );
            std::thread::park_timeout(Duration::from_millis(10));
        }
        party.sleeping.store(false, Ordering::Relaxed);
        party.parked.fetch_add(1, Ordering::Relaxed);
        party
            .budget
            .store((0.5 * budget).max(MIN_SPIN).to_bits(), Ordering::Relaxed);
    }

    /// Waits that ended parked, over all parties.
    #[cfg(test)]
    pub(crate) fn parked(&self) -> u64 {
        self.parties
            .iter()
            .map(|p| p.parked.load(Ordering::Relaxed))
            .sum()
    }

    /// Breaks the barrier: every party waiting now or later panics instead of waiting for
    /// one that will not come (called when a party unwinds).
    pub(crate) fn break_it(&self) {
        self.broken.store(true, Ordering::Relaxed);
    }
}

/// Breaks `barrier` when dropped during a panic, so that the other parties do not wait for
/// the panicking thread forever.
pub(crate) struct BreakOnPanic<'a>(pub(crate) &'a SpinBarrier);

impl Drop for BreakOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.break_it();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two threads take turns writing a shared counter between barrier calls; each sees the
    /// other's writes after the barrier (a barrier that let a thread through early would
    /// see a stale value). One thread now and then sleeps past the spin budget, so that the
    /// other parks and is woken: both paths are taken.
    #[test]
    fn parties_see_each_others_writes_after_the_barrier() {
        let barrier = SpinBarrier::new(2);
        let value = AtomicU64::new(0);
        let rounds = 20_000u64;
        std::thread::scope(|s| {
            for me in 0..2u64 {
                let (barrier, value) = (&barrier, &value);
                s.spawn(move || {
                    for r in 0..rounds {
                        if r % 2 == me {
                            let v = value.load(Ordering::Relaxed);
                            assert_eq!(v, r, "round {r}: the other's write not seen");
                            value.store(v + 1, Ordering::Relaxed);
                            if r % 1000 == me {
                                std::thread::sleep(Duration::from_millis(1));
                            }
                        }
                        barrier.wait(me as usize);
                    }
                });
            }
        });
        assert_eq!(value.load(Ordering::Relaxed), rounds);
        assert!(barrier.parked() >= 20, "{} waits parked", barrier.parked());
    }

    /// A panicking party breaks the barrier, and the other panics instead of hanging.
    #[test]
    fn a_panicking_party_breaks_the_barrier() {
        let barrier = SpinBarrier::new(2);
        let other = std::thread::scope(|s| {
            let b = &barrier;
            let waiter = s.spawn(move || b.wait(0));
            let quitter = s.spawn(move || {
                let _guard = BreakOnPanic(b);
                panic!("quit");
            });
            assert!(quitter.join().is_err());
            waiter.join()
        });
        assert!(other.is_err(), "the waiter should have panicked");
    }
}
