//! How a step's two sweeps over the wires are split between the calling thread and one
//! partner thread, balanced by cost rather than by the count of wires.
//!
//! The calling thread owns the wires `0..owned`, the partner the rest: each moves its own
//! wires in the kick-drift sweep and evaluates their loads in the loads sweep. The wires are
//! whole units of the kick-drift sweep (its cost is the same for every segment), so that
//! sweep is balanced to within a wire. The loads sweep is balanced further by lending
//! contacts: the last contacts with the core of one wire without links are evaluated by the
//! other thread, which writes them into a buffer of its own; the calling thread then copies
//! them into place and adds the loads of all that wire's contacts, in contact order, after
//! the sweep ([`crate::model::FineModel::add_core_contacts_loads`]). Every load is the same
//! arithmetic, added in the same order, as in one thread: the split changes only who does it.
//!
//! The costs are instruction counts of the one-layer Fig. 7 strand's settle steps
//! (callgrind of `examples/settle_cost`, one thread): a segment's kick, drift and frame
//! about 320 instructions, its joint, anchor and gravity loads about 520, a contact with
//! the core about 470 (two a segment). A wire-to-wire link is taken as two contacts (not measured: it only
//! moves the split, never the numbers).

use crate::model::{FineModel, LoadSlots, WireLoads};

/// Fewest steps of one [`crate::Integrator::advance`] call that are split this way (the
/// partner thread is started once a call); shorter calls go through rayon's pool.
pub(crate) const SPLIT_MIN_STEPS: u64 = 8;

/// The loads of all wires while they are split between two threads: wires `0..head.len()`
/// in `head`, the rest in `tail`.
pub(crate) struct SplitLoads<'a> {
    /// The calling thread's wires' loads.
    pub(crate) head: &'a mut [WireLoads],
    /// The partner's wires' loads.
    pub(crate) tail: &'a mut [WireLoads],
}

impl LoadSlots for SplitLoads<'_> {
    #[inline(always)]
    fn slot(&self, i: usize) -> &WireLoads {
        match i.checked_sub(self.head.len()) {
            None => &self.head[i],
            Some(j) => &self.tail[j],
        }
    }
    #[inline(always)]
    fn slot_mut(&mut self, i: usize) -> &mut WireLoads {
        match i.checked_sub(self.head.len()) {
            None => &mut self.head[i],
            Some(j) => &mut self.tail[j],
        }
    }
}

/// Kick, drift and frame of one segment (instructions).
const KICK_DRIFT_COST: f64 = 320.0;
/// Joint, anchor and gravity loads of one segment (instructions).
const SEGMENT_LOADS_COST: f64 = 520.0;
/// One contact evaluation with the core (instructions).
const CONTACT_COST: f64 = 470.0;
/// One wire-to-wire link (instructions; taken as two contacts).
const LINK_COST: f64 = 2.0 * CONTACT_COST;

/// Contacts with the core of one wire evaluated by the thread that does not own the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LentContacts {
    /// The wire (without links).
    pub(crate) wire: usize,
    /// The first lent contact: the contacts `first..` of the wire are lent.
    pub(crate) first: usize,
}

/// The split of a step's sweeps between the calling thread and one partner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SweepSplit {
    /// The calling thread's wires are `0..owned`, the partner's `owned..`.
    pub(crate) owned: usize,
    /// Contacts lent: by the calling thread to the partner if positive, the other way if
    /// negative.
    pub(crate) lend: i64,
}

impl SweepSplit {
    /// The split for `model` by the cost model, or `None` for a model of one wire.
    pub(crate) fn new(model: &FineModel) -> Option<Self> {
        let n = model.wires.len();
        if n < 2 {
            return None;
        }
        let kick_drift: Vec<f64> = model
            .wires
            .iter()
            .map(|w| KICK_DRIFT_COST * w.chain.len() as f64)
            .collect();
        let loads = loads_costs(model);
        let prefix = |costs: &[f64], k: usize| costs[..k].iter().sum::<f64>();
        let (kd_total, loads_total) = (prefix(&kick_drift, n), prefix(&loads, n));
        // The owned count that balances the kick-drift sweep best; of equals, the one that
        // leaves the loads sweep the least to lend.
        let owned = (1..n)
            .min_by(|&a, &b| {
                let off = |k: usize| {
                    (
                        (prefix(&kick_drift, k) - 0.5 * kd_total).abs(),
                        (prefix(&loads, k) - 0.5 * loads_total).abs(),
                    )
                };
                off(a).partial_cmp(&off(b)).unwrap()
            })
            .unwrap();
        let excess = prefix(&loads, owned) - 0.5 * loads_total;
        Some(Self {
            owned,
            lend: (excess / CONTACT_COST).round() as i64,
        })
    }

    /// The lent contacts of `model`: the last `|lend|` contacts with the core of the
    /// lending thread's wire without links that has the most of them (the last such wire
    /// of equals), at most all of its contacts; `None` if nothing is lent.
    pub(crate) fn lent(&self, model: &FineModel) -> Option<LentContacts> {
        let n = model.wires.len();
        let lenders = if self.lend > 0 {
            0..self.owned
        } else {
            self.owned..n
        };
        lenders
            .filter(|&i| i > 0 && model.wires[i].links.is_empty())
            .max_by_key(|&i| model.wires[i].contacts.len())
            .and_then(|wire| {
                let nc = model.wires[wire].contacts.len();
                let m = (self.lend.unsigned_abs() as usize).min(nc);
                (m > 0).then_some(LentContacts {
                    wire,
                    first: nc - m,
                })
            })
    }

    /// Moves contacts towards the thread that spent less time on its share of the loads
    /// sweeps of a stretch of `steps` steps (`busy` = (calling thread, partner), s): half
    /// the measured difference, in contacts at the mean cost of the sweep's work. The cost
    /// of a contact depends on its state (open contacts are cheaper than closed ones), which
    /// the cost model cannot know; the split only moves work, never changes a number.
    pub(crate) fn rebalance(&mut self, model: &FineModel, busy: (f64, f64), steps: u64) {
        let units: f64 = loads_costs(model).iter().sum::<f64>() / CONTACT_COST;
        let per_contact = (busy.0 + busy.1) / (steps as f64 * units);
        if steps == 0 || per_contact.is_nan() || per_contact <= 0.0 {
            return;
        }
        let shift = (0.5 * (busy.0 - busy.1) / steps as f64 / per_contact).round() as i64;
        let most = model
            .wires
            .iter()
            .map(|w| w.contacts.len())
            .max()
            .unwrap_or(0) as i64;
        self.lend = (self.lend + shift).clamp(-most, most);
    }

    /// Cost (instructions) of each thread's share of the kick-drift sweep and of the loads
    /// sweep by the cost model: ((calling thread, partner), (calling thread, partner)).
    #[cfg(test)]
    pub(crate) fn shares(&self, model: &FineModel) -> ((f64, f64), (f64, f64)) {
        let mut kd = (0.0, 0.0);
        let mut loads = (0.0, 0.0);
        for (i, w) in model.wires.iter().enumerate() {
            let mine = i < self.owned;
            let contacts = if i == 0 { 0 } else { w.contacts.len() };
            let mut lent = 0;
            if let Some(l) = self.lent(model).filter(|l| l.wire == i) {
                lent = contacts - l.first;
            }
            let k = KICK_DRIFT_COST * w.chain.len() as f64;
            let own = SEGMENT_LOADS_COST * w.chain.len() as f64
                + CONTACT_COST * (contacts - lent) as f64
                + LINK_COST * w.links.len() as f64;
            let away = CONTACT_COST * lent as f64;
            if mine {
                kd.0 += k;
                loads.0 += own;
                loads.1 += away;
            } else {
                kd.1 += k;
                loads.1 += own;
                loads.0 += away;
            }
        }
        (kd, loads)
    }
}

/// Cost (instructions) of each wire's loads by the cost model.
fn loads_costs(model: &FineModel) -> Vec<f64> {
    model
        .wires
        .iter()
        .enumerate()
        .map(|(i, w)| {
            let contacts = if i == 0 { 0 } else { w.contacts.len() };
            SEGMENT_LOADS_COST * w.chain.len() as f64
                + CONTACT_COST * contacts as f64
                + LINK_COST * w.links.len() as f64
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::tests::table1;
    use crate::contact::ContactOptions;
    use crate::model::{Discretisation, Support};

    fn fig7(segments: usize) -> FineModel {
        let s = table1();
        let mut m = FineModel::from_strand(
            &s,
            Discretisation {
                core_segments: segments,
                wire_segments: segments,
            },
            Support::Clamped,
            Support::Free,
        );
        m.add_contacts(&s, &ContactOptions::default());
        m
    }

    /// On the one-layer strand the loads sweep is balanced to within one contact's cost
    /// by the lent contacts, and the kick-drift sweep to within one wire's.
    #[test]
    fn the_one_layer_strand_is_split_evenly() {
        for segments in [12, 40, 77] {
            let m = fig7(segments);
            let split = SweepSplit::new(&m).unwrap();
            let ((kd0, kd1), (l0, l1)) = split.shares(&m);
            let wire_kd = KICK_DRIFT_COST * segments as f64;
            assert!((kd0 - kd1).abs() <= wire_kd, "{kd0} {kd1}");
            assert!((l0 - l1).abs() <= CONTACT_COST, "{segments}: {l0} {l1}");
            assert!(split.lent(&m).is_some());
        }
    }

    /// Rebalancing moves lent contacts towards the thread that spent less time on the
    /// loads sweep, by half the difference, and no further than a wire's contacts.
    #[test]
    fn rebalancing_moves_contacts_to_the_less_busy_thread() {
        let m = fig7(77);
        let split = SweepSplit::new(&m).unwrap();
        let moved = |busy: (f64, f64)| {
            let mut s = split;
            s.rebalance(&m, busy, 100);
            s.lend - split.lend
        };
        assert_eq!(moved((1.0, 1.0)), 0);
        let (more, fewer) = (moved((1.1, 0.9)), moved((0.9, 1.1)));
        assert!(more > 0 && fewer < 0 && more == -fewer, "{more} {fewer}");
        // A tenth of the sweep's time apart: half of it is a twentieth of the sweep's
        // contact equivalents.
        let units = loads_costs(&m).iter().sum::<f64>() / CONTACT_COST;
        assert!(
            (more as f64 - 0.05 * units).abs() <= 1.0,
            "{more} of {units}"
        );
        let mut s = split;
        s.rebalance(&m, (100.0, 0.0), 100);
        assert_eq!(s.lend, m.wires[1].contacts.len() as i64);
    }
}
