//! A stretch of steps on several threads, the strand cut along its length into one piece
//! per thread, each thread holding its piece from the first step to the last.
//!
//! Rayon's sweeps give a wire to whichever thread takes it, so a wire's state, contacts and
//! loads move between the cores' caches from one sweep to the next, and seven wires split
//! unevenly between two threads. Here every wire is cut at the same places along the strand
//! ([`Cut`]): a thread moves and loads the segments of every wire in its piece and
//! evaluates their contacts, so that its work is its share of the strand's, and what passes
//! between the threads is what touches a cut: the poses and frames of the segments next to
//! it (the joints across it), the core's poses (each thread computes all the core's frames
//! for its contacts' searches) and the core's shares of the contacts whose core segment lies
//! in another piece. The threads meet twice a step at a [`SpinBarrier`]: after the drift and
//! after the loads. Each piece lives in buffers its own thread allocates for the stretch:
//! cut in place, the wires' vectors put both threads' writes on the cache lines at a cut,
//! and the stretch took 1.14 times as long (Performance page). The cut moves after every
//! stretch toward equal measured work ([`Cut::rebalanced`]).
//!
//! Each segment's arithmetic, and the order of every sum of loads on it, is the one of a
//! single thread: a segment's joint loads in joint order ([`Chain::add_joint_loads_in`]),
//! its contacts in contact order, the core's shares in wire and contact order (each piece's
//! contacts precede the next piece's: a wire's contacts are listed in segment order; a core
//! segment that another piece's contacts pair with is summed again in that order), the
//! friction loss in wire and contact order. The states are the same bit for bit on any
//! number of threads and wherever the cut. After the stretch each wire's energies are summed
//! again in one piece, so that the loads are those [`Integrator::advance`] leaves on one
//! thread. The commit of the contacts' histories costs no copy: a piece's contact loads take
//! turns between two buffers, and the last evaluation's histories are the committed ones.
//!
//! It serves the strands of one layer (no wire-to-wire links) without ties; others step
//! with rayon's sweeps.
//!
//! [`Chain::add_joint_loads_in`]: crate::chain::Chain::add_joint_loads_in

use std::ops::Range;
use std::sync::{RwLock, RwLockReadGuard};
use std::time::{Duration, Instant};

use nalgebra::Vector3;

use super::{Integrator, KickDriftStep, SegmentMotion, kick_drift_segments};
use crate::chain::SegmentRun;
use crate::contact::{self, ContactLoad};
use crate::model::{CoreShare, FineModel, ModelState, update_frames};
use crate::segment::{Frame, Pose};
use crate::spin_barrier::{BreakOnPanic, SpinBarrier};

/// Fewest segments of the core in a piece.
const MIN_PIECE: usize = 4;

/// Where the strand is cut: for every piece (one per thread) and every wire, its segments
/// and its contacts with the core.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Cut {
    /// The core's segments where pieces `1..` start.
    core_starts: Vec<usize>,
    /// `segments[t][i]`: wire `i`'s segments in piece `t` (contiguous, in order).
    segments: Vec<Vec<Range<usize>>>,
    /// `contacts[t][i]`: wire `i`'s contacts with the core in piece `t` (those of its
    /// segments there).
    contacts: Vec<Vec<Range<usize>>>,
}

impl Cut {
    /// The cut of `model` into at most `threads` pieces of about equal length (the core's
    /// segments cut evenly), or `None` when fewer than two pieces would have [`MIN_PIECE`]
    /// core segments or the model is not one the cut serves ([`Cut::at`]).
    pub(super) fn new(model: &FineModel, threads: usize) -> Option<Self> {
        let n = model.wires[0].chain.len();
        let pieces = threads.min(n / MIN_PIECE);
        if pieces < 2 {
            return None;
        }
        Self::at(model, (1..pieces).map(|p| p * n / pieces).collect())
    }

    /// The cut of `model` whose pieces `1..` start at the core's segments `core_starts`
    /// (increasing, inside the core), every other wire cut at the same places along the
    /// strand (between the rest centres of the core's segments on either side), or `None`
    /// when the model is not one the cut serves: wire-to-wire links or ties, a wire's
    /// contacts not in segment order, a wire whose segments go back along the strand.
    pub(super) fn at(model: &FineModel, core_starts: Vec<usize>) -> Option<Self> {
        if !model.ties.is_empty() || model.wires.iter().any(|w| !w.links.is_empty()) {
            return None;
        }
        let core = &model.wires[0].chain;
        let x = |c: &crate::Chain, k: usize| c.rest[k].position.x;
        let bounds: Vec<f64> = core_starts
            .iter()
            .map(|&k| 0.5 * (x(core, k - 1) + x(core, k)))
            .collect();
        let pieces = core_starts.len() + 1;
        let mut segments = vec![Vec::with_capacity(model.wires.len()); pieces];
        let mut contacts = vec![Vec::with_capacity(model.wires.len()); pieces];
        for w in &model.wires {
            let c = &w.chain;
            if (1..c.len()).any(|k| x(c, k) < x(c, k - 1))
                || w.contacts.windows(2).any(|p| p[1].segment < p[0].segment)
            {
                return None;
            }
            let mut start = 0;
            let mut first_contact = 0;
            for (t, seg) in segments.iter_mut().enumerate() {
                let end = match bounds.get(t) {
                    Some(&b) => (start..c.len()).find(|&k| x(c, k) >= b).unwrap_or(c.len()),
                    None => c.len(),
                };
                let last_contact = first_contact
                    + w.contacts[first_contact..]
                        .iter()
                        .take_while(|p| p.segment < end)
                        .count();
                seg.push(start..end);
                contacts[t].push(first_contact..last_contact);
                (start, first_contact) = (end, last_contact);
            }
        }
        Some(Self {
            core_starts,
            segments,
            contacts,
        })
    }

    /// True when this cut is one [`Cut::new`] could give for `model` on `threads` threads:
    /// as many pieces, and every wire's segments covered.
    pub(super) fn fits(&self, model: &FineModel, threads: usize) -> bool {
        let n = model.wires[0].chain.len();
        self.pieces() == threads.min(n / MIN_PIECE)
            && self.segments[0].len() == model.wires.len()
            && model.wires.iter().enumerate().all(|(i, w)| {
                self.segments
                    .last()
                    .is_some_and(|s| s[i].end == w.chain.len())
            })
    }

    /// The cut moved toward equal work: each start moves by half the core segments that
    /// would even out the measured busy times `busy` (s) of the two pieces beside it,
    /// keeping [`MIN_PIECE`] segments a piece. The results do not depend on the cut, only
    /// the time does.
    pub(super) fn rebalanced(&self, model: &FineModel, busy: &[f64]) -> Option<Self> {
        let n = model.wires[0].chain.len();
        let mut starts = self.core_starts.clone();
        let len = |p: usize, s: &[usize]| {
            let a = if p == 0 { 0 } else { s[p - 1] };
            let b = s.get(p).copied().unwrap_or(n);
            (b - a) as f64
        };
        for p in 0..starts.len() {
            let (a, b) = (busy[p] / len(p, &starts), busy[p + 1] / len(p + 1, &starts));
            let per_segment = 0.5 * (a + b);
            if per_segment.is_nan() || per_segment <= 0.0 {
                continue;
            }
            let shift = (0.25 * (busy[p + 1] - busy[p]) / per_segment).round();
            let lo = if p == 0 { 0 } else { starts[p - 1] } + MIN_PIECE;
            let hi = starts.get(p + 1).copied().unwrap_or(n) - MIN_PIECE;
            starts[p] = (starts[p] as f64 + shift).clamp(lo as f64, hi as f64) as usize;
        }
        if starts == self.core_starts {
            return Some(self.clone());
        }
        Self::at(model, starts)
    }

    /// Pieces of the cut.
    fn pieces(&self) -> usize {
        self.segments.len()
    }

    /// The piece holding segment `k` of wire `i`.
    fn piece_of(&self, i: usize, k: usize) -> usize {
        self.segments
            .iter()
            .position(|s| s[i].contains(&k))
            .expect("a cut holds every segment")
    }
}

/// A wire's motion in a piece: its segments' poses, velocities, angular momenta and frames
/// copied into the piece's own buffers (allocated by
/// its thread) for the stretch, so that no cache line holds two pieces' data.
#[derive(Debug, Default)]
struct WireMotion {
    poses: Vec<Pose>,
    velocities: Vec<Vector3<f64>>,
    angular_momenta: Vec<Vector3<f64>>,
    frames: Vec<Frame>,
}

/// A wire's loads in a piece, touched by the piece's thread only: the forces and torques on
/// its segments, and its contacts' loads in two buffers that take turns, the last
/// evaluation's (whose histories are the committed ones once the kick has passed: the
/// commit costs no copy) and the one being evaluated.
#[derive(Debug, Default)]
struct WireLoadsPart {
    forces: Vec<Vector3<f64>>,
    torques: Vec<Vector3<f64>>,
    contacts: Vec<ContactLoad>,
    committed: Vec<ContactLoad>,
}

/// What a piece's loads hand to the other pieces: the core's shares of its contacts whose
/// core segment lies in another piece, by that piece, each with its wire, in wire and
/// contact order; and the slip work of each wire's contacts, in contact order (J).
#[derive(Debug, Default)]
struct Outbox {
    shares: Vec<Vec<(usize, CoreShare)>>,
    slip: Vec<Vec<f64>>,
}

/// [`Integrator::advance`] of `steps` steps on one thread per piece of `cut` (the calling
/// thread takes the first); returns each piece's busy time (s).
pub(super) fn advance(
    int: &mut Integrator,
    model: &FineModel,
    state: &mut ModelState,
    steps: u64,
    load_factor: &(dyn Fn(f64) -> f64 + Sync),
    cut: &Cut,
) -> Vec<f64> {
    let pieces = cut.pieces();
    let core_slip_work = int.loads[0].slip_work;
    let motion: Vec<RwLock<Vec<WireMotion>>> = (0..pieces).map(|_| RwLock::default()).collect();
    let outboxes: Vec<RwLock<Outbox>> = (0..pieces).map(|_| RwLock::default()).collect();
    let stretch = Stretch {
        model,
        cut,
        motion: &motion,
        outboxes: &outboxes,
        barrier: SpinBarrier::new(pieces),
        steps,
        dt: int.dt,
        damp: (-int.damping_rate * int.dt).exp(),
        start: int.time,
        load_factor,
        start_factor: int.load_factor,
        core_slip_work,
        core_len: model.wires[0].chain.len(),
    };
    let start = Start {
        state: &*state,
        loads: &int.loads,
        frames: &int.frames,
    };
    let last = pieces - 1;
    let friction_work = state.friction_work;
    let own = std::thread::scope(|scope| {
        let others: Vec<_> = (1..pieces)
            .map(|t| {
                let (stretch, start) = (&stretch, &start);
                let fw = (t == last).then_some(friction_work);
                scope.spawn(move || stretch.run(t, start, fw))
            })
            .collect();
        let mut own = vec![stretch.run(0, &start, None)];
        own.extend(others.into_iter().map(|h| h.join().expect(POISONED)));
        own
    });
    let busy: Vec<f64> = own.iter().map(|o| o.1).collect();
    let fw = own[last].2.expect("the last piece sums the friction loss");
    let factor = own[0].3;
    drop(stretch);
    // The pieces' buffers back into the state and the loads.
    for (t, (m, (l, ..))) in motion.into_iter().zip(own).enumerate() {
        let m = m.into_inner().expect(POISONED);
        for (i, (m, l)) in m.into_iter().zip(l).enumerate() {
            let (r, c) = (cut.segments[t][i].clone(), cut.contacts[t][i].clone());
            let s = &mut state.wires[i];
            s.poses[r.clone()].copy_from_slice(&m.poses);
            s.velocities[r.clone()].copy_from_slice(&m.velocities);
            s.angular_momenta[r.clone()].copy_from_slice(&m.angular_momenta);
            int.frames[i][r.clone()].copy_from_slice(&m.frames);
            // The last evaluation, committed by the last kick.
            for (h, e) in state.contacts[i][c.clone()].iter_mut().zip(&l.committed) {
                *h = e.history;
            }
            let w = &mut int.loads[i];
            w.forces[r.clone()].copy_from_slice(&l.forces);
            w.torques[r].copy_from_slice(&l.torques);
            w.contacts[c].copy_from_slice(&l.committed);
        }
    }
    state.friction_work = fw;
    int.load_factor = factor;
    for _ in 0..steps {
        int.time += int.dt;
    }
    int.steps += steps;
    update_frames(&state.wires[0].poses, &mut int.frames[0]);
    if steps > 0 {
        finish_loads(int, model, state);
    }
    busy
}

/// The loads of every wire after a stretch as one thread leaves them: each wire's energies
/// and the core's shares summed in one piece from the pieces' results, then the shares
/// added to the core.
fn finish_loads(int: &mut Integrator, model: &FineModel, state: &ModelState) {
    let g = model.gravity * int.load_factor;
    let core_len = model.wires[0].chain.len();
    let longest = model.wires.iter().map(|w| w.chain.len()).max().unwrap_or(0);
    let (mut f, mut t) = (
        vec![Vector3::zeros(); longest],
        vec![Vector3::zeros(); longest],
    );
    for (i, ((w, s), l)) in model
        .wires
        .iter()
        .zip(&state.wires)
        .zip(&mut int.loads)
        .enumerate()
    {
        let m = w.chain.len();
        let run = SegmentRun::whole(&s.poses, &int.frames[i]);
        let (spring, grav) = w.add_loads_in(&run, &g, int.load_factor, &mut f[..m], &mut t[..m]);
        l.spring_energy = spring;
        l.gravity_energy = grav;
        if i == 0 {
            continue;
        }
        let (mut ce, mut fe, mut sw) = (0.0, 0.0, 0.0);
        l.core_shares.clear();
        for c in &l.contacts[..w.contacts.len()] {
            ce += c.normal_energy;
            fe += c.tangential_energy;
            sw += c.slip_work;
            l.core_shares.push(CoreShare {
                segment: c.core_segment,
                force: c.force_core,
                torque: c.torque_core,
            });
        }
        (l.contact_energy, l.friction_energy, l.slip_work) = (ce, fe, sw);
    }
    debug_assert!(int.loads[0].forces.len() == core_len);
    int.shares.add_all(model, &mut int.loads);
}

/// The state and loads a stretch starts from, copied into the pieces' buffers.
struct Start<'a> {
    state: &'a ModelState,
    loads: &'a [crate::model::WireLoads],
    frames: &'a [Vec<Frame>],
}

/// A stretch of steps shared by the threads.
struct Stretch<'a> {
    model: &'a FineModel,
    cut: &'a Cut,
    /// Each piece's motion, written in the kick-drift phase by its thread and read near
    /// the cuts (and the core's poses) by the others in the loads phase.
    motion: &'a [RwLock<Vec<WireMotion>>],
    /// Each piece's outbox, written in the loads phase by its thread and read by the others
    /// in the kick-drift phase.
    outboxes: &'a [RwLock<Outbox>],
    barrier: SpinBarrier,
    steps: u64,
    dt: f64,
    damp: f64,
    /// Time at the stretch's start (s).
    start: f64,
    load_factor: &'a (dyn Fn(f64) -> f64 + Sync),
    /// Load factor before the stretch's first step (-).
    start_factor: f64,
    /// The core's slip work (J; it has no contacts of its own: the friction loss adds it as
    /// one thread does).
    core_slip_work: f64,
    /// Segments of the core.
    core_len: usize,
}

/// Panic message of a poisoned lock: another thread of the stretch panicked.
const POISONED: &str = "a thread of the stretch panicked";

impl Stretch<'_> {
    /// Thread `t`'s piece of the stretch, from `start`; returns the piece's loads, the time
    /// it was busy (s: the stretch's time less its waits at the barrier), the friction loss
    /// (J) if the piece was given it to sum (`friction_work`, the last piece: in its
    /// kick-drift phase, beside the other pieces' work) and the last step's load factor.
    fn run(
        &self,
        t: usize,
        start: &Start<'_>,
        mut friction_work: Option<f64>,
    ) -> (Vec<WireLoadsPart>, f64, Option<f64>, f64) {
        let _guard = BreakOnPanic(&self.barrier);
        let model = self.model;
        let (segments, contacts) = (&self.cut.segments[t], &self.cut.contacts[t]);
        let core_range = segments[0].clone();
        // The piece's buffers, allocated by this thread.
        let mut own: Vec<WireLoadsPart> = Vec::with_capacity(model.wires.len());
        {
            let mut mine = self.motion[t].write().expect(POISONED);
            for (i, (r, c)) in segments.iter().zip(contacts).enumerate() {
                let s = &start.state.wires[i];
                mine.push(WireMotion {
                    poses: s.poses[r.clone()].to_vec(),
                    velocities: s.velocities[r.clone()].to_vec(),
                    angular_momenta: s.angular_momenta[r.clone()].to_vec(),
                    frames: start.frames[i][r.clone()].to_vec(),
                });
                let l = &start.loads[i];
                let contacts = l.contacts[c.clone()].to_vec();
                let mut committed = contacts.clone();
                for (e, h) in committed
                    .iter_mut()
                    .zip(&start.state.contacts[i][c.clone()])
                {
                    e.history = *h;
                }
                own.push(WireLoadsPart {
                    forces: l.forces[r.clone()].to_vec(),
                    torques: l.torques[r.clone()].to_vec(),
                    contacts,
                    committed,
                });
            }
            let mut outbox = self.outboxes[t].write().expect(POISONED);
            let count: usize = contacts.iter().map(|r| r.len()).sum();
            outbox.shares = vec![Vec::with_capacity(count); self.cut.pieces()];
            outbox.slip = contacts
                .iter()
                .map(|r| Vec::with_capacity(r.len()))
                .collect();
        }
        self.barrier.wait(t);
        let (begun, mut waited) = (Instant::now(), Duration::ZERO);
        let mut kd = KickDriftStep {
            dt: self.dt,
            damp: self.damp,
            first: true,
            last: false,
            own: false,
        };
        let mut time = self.start;
        let mut last_factor = self.start_factor;
        // The core's forces and torques with the shares added, and all its frames.
        let mut core_forces = vec![Vector3::zeros(); core_range.len()];
        let mut core_torques = vec![Vector3::zeros(); core_range.len()];
        let mut core_frames = vec![Frame::default(); self.core_len];
        let mut contested: Vec<usize> = Vec::with_capacity(core_range.len());
        let mut guards: Vec<RwLockReadGuard<'_, _>> = Vec::with_capacity(self.motion.len());
        let mut boxes: Vec<RwLockReadGuard<'_, Outbox>> = Vec::with_capacity(self.outboxes.len());
        for i in 0..=self.steps {
            (kd.first, kd.last) = (i == 0, i == self.steps);
            {
                let mut mine = self.motion[t].write().expect(POISONED);
                // The core: its own loads and, once they are the pieces' own, its shares.
                let (forces, torques) = if kd.own {
                    // The core's loads with the shares of the piece's own contacts are summed
                    // in the loads phase; a segment that contacts of another piece pair with
                    // is summed again here, every share in wire and contact order.
                    boxes.extend(self.outboxes.iter().map(|b| b.read().expect(POISONED)));
                    contested.clear();
                    for b in &boxes {
                        for (_, c) in &b.shares[t] {
                            if !contested.contains(&c.segment) {
                                contested.push(c.segment);
                            }
                        }
                    }
                    for &j in &contested {
                        let k = j - core_range.start;
                        let (mut f, mut q) = (own[0].forces[k], own[0].torques[k]);
                        for w in 1..model.wires.len() {
                            for (p, b) in boxes.iter().enumerate() {
                                if p == t {
                                    for e in own[w].committed.iter().filter(|e| e.core_segment == j)
                                    {
                                        f += e.force_core;
                                        q += e.torque_core;
                                    }
                                } else {
                                    for (_, c) in b.shares[t]
                                        .iter()
                                        .filter(|(x, c)| *x == w && c.segment == j)
                                    {
                                        f += c.force;
                                        q += c.torque;
                                    }
                                }
                            }
                        }
                        (core_forces[k], core_torques[k]) = (f, q);
                    }
                    if let Some(fw) = friction_work.as_mut() {
                        // The friction loss of the loads evaluated last (committed now), each
                        // wire's slip work summed in contact order and the wires in order, as
                        // one thread sums them.
                        *fw += self.core_slip_work;
                        for w in 1..model.wires.len() {
                            let mut sw = 0.0;
                            for b in &boxes {
                                for s in &b.slip[w] {
                                    sw += s;
                                }
                            }
                            *fw += sw;
                        }
                    }
                    boxes.clear();
                    (&core_forces[..], &core_torques[..])
                } else {
                    (&own[0].forces[..], &own[0].torques[..])
                };
                for (i, (m, l)) in mine.iter_mut().zip(&own).enumerate() {
                    let (f, q) = if i == 0 {
                        (forces, torques)
                    } else {
                        (&l.forces[..], &l.torques[..])
                    };
                    let r = segments[i].clone();
                    let motion = SegmentMotion {
                        poses: &mut m.poses,
                        velocities: &mut m.velocities,
                        angular_momenta: &mut m.angular_momenta,
                    };
                    kick_drift_segments(&model.wires[i].chain.segments[r], motion, f, q, &kd);
                    if !kd.last && i > 0 {
                        update_frames(&m.poses, &mut m.frames);
                    }
                }
            }
            if kd.last {
                break;
            }
            let waiting = Instant::now();
            self.barrier.wait(t);
            waited += waiting.elapsed();
            let factor = (self.load_factor)(time + self.dt);
            let g = model.gravity * factor;
            {
                guards.extend(self.motion.iter().map(|p| p.read().expect(POISONED)));
                let all = &guards;
                // All the core's frames, from every piece's poses.
                for (p, r) in all.iter().zip(&self.cut.segments) {
                    for (f, pose) in core_frames[r[0].clone()].iter_mut().zip(p[0].poses.iter()) {
                        *f = Frame::of(pose);
                    }
                }
                let core_segs = &model.wires[0].chain.segments;
                let mut outbox = self.outboxes[t].write().expect(POISONED);
                outbox.shares.iter_mut().for_each(Vec::clear);
                for (i, (w, l)) in model.wires.iter().zip(own.iter_mut()).enumerate() {
                    l.forces.fill(Vector3::zeros());
                    l.torques.fill(Vector3::zeros());
                    let (a, b) = (segments[i].start, segments[i].end);
                    let m = &all[t][i];
                    // The neighbours across the cuts, for the joints there.
                    let across = |k: usize| {
                        let p = self.cut.piece_of(i, k);
                        let q = k - self.cut.segments[p][i].start;
                        let frame = if i == 0 {
                            core_frames[k]
                        } else {
                            all[p][i].frames[q]
                        };
                        (all[p][i].poses[q], frame)
                    };
                    let before = (a > 0).then(|| across(a - 1));
                    let after = (b < w.chain.len()).then(|| across(b));
                    let own_frames: &[Frame] = if i == 0 {
                        &core_frames[a..b]
                    } else {
                        &m.frames
                    };
                    let run = SegmentRun {
                        first: a,
                        poses: &m.poses,
                        frames: own_frames,
                        before: before.as_ref().map(|(p, f)| (p, f)),
                        after: after.as_ref().map(|(p, f)| (p, f)),
                    };
                    w.add_loads_in(&run, &g, factor, &mut l.forces, &mut l.torques);
                    let slip = &mut outbox.slip[i];
                    slip.clear();
                    if i == 0 {
                        core_forces.copy_from_slice(&l.forces);
                        core_torques.copy_from_slice(&l.torques);
                        continue;
                    }
                    let cps = &w.contacts[contacts[i].clone()];
                    let hist = l.committed.iter().map(|e| &e.history);
                    for ((cp, h), out) in cps.iter().zip(hist).zip(l.contacts.iter_mut()) {
                        let k = cp.segment - a;
                        contact::evaluate_into(cp, h, &m.frames[k], &core_frames, core_segs, out);
                        l.forces[k] += out.force_wire;
                        l.torques[k] += out.torque_wire;
                        slip.push(out.slip_work);
                    }
                    for out in l.contacts.iter() {
                        let j = out.core_segment;
                        if core_range.contains(&j) {
                            core_forces[j - core_range.start] += out.force_core;
                            core_torques[j - core_range.start] += out.torque_core;
                        } else {
                            let share = CoreShare {
                                segment: j,
                                force: out.force_core,
                                torque: out.torque_core,
                            };
                            outbox.shares[self.cut.piece_of(0, j)].push((i, share));
                        }
                    }
                    // The evaluation just made is the one the next kick commits.
                    std::mem::swap(&mut l.contacts, &mut l.committed);
                }
                drop(outbox);
                guards.clear();
            }
            time += self.dt;
            kd.own = true;
            let waiting = Instant::now();
            self.barrier.wait(t);
            waited += waiting.elapsed();
            last_factor = factor;
        }
        let busy = (begun.elapsed() - waited).as_secs_f64();
        (own, busy, friction_work, last_factor)
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;
    use strand_core::{Strand, StrandSpec};

    use super::*;
    use crate::{ContactOptions, Discretisation, Support};

    /// The Fig. 7 strand, 16 segments in the core and 23 in each helical wire (so that
    /// contacts near a cut pair with the other piece's core segments), clamped, under
    /// gravity, with contacts.
    fn model() -> FineModel {
        let s = Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap();
        let mut m = FineModel::from_strand(
            &s,
            Discretisation {
                core_segments: 16,
                wire_segments: 23,
            },
            Support::Clamped,
            Support::Free,
        );
        m.add_contacts(&s, &ContactOptions::default());
        m.gravity = Vector3::new(0.0, -8.0, 0.0);
        m
    }

    /// A stretch on pieces gives the state, the loads and the friction loss of one thread,
    /// bit for bit, wherever the strand is cut (two pieces cut near either end or in the
    /// middle, three pieces), over stretches that start from a stretch's end, with contacts
    /// sticking and slipping under a ramped load.
    #[test]
    fn a_stretch_on_pieces_is_one_thread_bit_for_bit_wherever_the_cut() {
        let m = model();
        let s0 = m.rest_state();
        let dt = crate::stable_time_step(&m, &s0, 0.9);
        let ramp = move |t: f64| (t / (150.0 * dt)).min(1.0);
        let start = || {
            let mut int = Integrator::new(&m, &s0, dt);
            int.damping_rate = 30.0;
            int.load_factor = 0.0;
            int.reload(&m, &s0);
            (s0.clone(), int)
        };
        let (mut one, mut int_one) = start();
        for _ in 0..3 {
            int_one.advance_on(&m, &mut one, 100, &ramp, false);
        }
        let slipping = int_one
            .loads()
            .iter()
            .flat_map(|l| &l.contacts)
            .filter(|c| c.state == crate::ContactState::Slip)
            .count();
        assert!(
            slipping > 0,
            "no contact slips: the check would not see friction"
        );
        assert!(one.friction_work > 0.0);
        let mut crossing = 0;
        for starts in [vec![4], vec![8], vec![12], vec![5, 11]] {
            let cut = Cut::at(&m, starts.clone()).expect("the strand is cut");
            // Contacts whose core segment lies in another piece than their own segment:
            // the shares the pieces hand over.
            let across = (1..m.wires.len())
                .flat_map(|i| {
                    let cut = &cut;
                    m.wires[i]
                        .contacts
                        .iter()
                        .zip(&int_one.loads()[i].contacts)
                        .map(move |(cp, c)| {
                            cut.piece_of(i, cp.segment) != cut.piece_of(0, c.core_segment)
                        })
                })
                .filter(|&x| x)
                .count();
            crossing += across;
            let (mut s, mut int) = start();
            for _ in 0..3 {
                advance(&mut int, &m, &mut s, 100, &ramp, &cut);
            }
            assert!(s == one, "the state cut at {starts:?} differs");
            assert!(
                int.loads() == int_one.loads(),
                "the loads cut at {starts:?} differ"
            );
            assert_eq!(int.time.to_bits(), int_one.time.to_bits());
            assert_eq!(int.load_factor.to_bits(), int_one.load_factor.to_bits());
        }
        assert!(
            crossing > 0,
            "no contact pairs across a cut: the shares handed over are untested"
        );
        // The friction loss of a few steps alone (the accumulated loss hides the last bits
        // of a step's): from the state reached, the loss set to zero.
        let few = |cut: Option<&Cut>| {
            let (mut s, mut int) = (one.clone(), int_one.clone());
            s.friction_work = 0.0;
            match cut {
                Some(cut) => {
                    advance(&mut int, &m, &mut s, 3, &ramp, cut);
                }
                None => int.advance_on(&m, &mut s, 3, &ramp, false),
            }
            s.friction_work
        };
        let alone = few(None);
        assert!(alone > 0.0);
        for starts in [vec![8], vec![5, 11]] {
            let cut = Cut::at(&m, starts.clone()).unwrap();
            assert_eq!(
                few(Some(&cut)).to_bits(),
                alone.to_bits(),
                "cut at {starts:?}"
            );
        }
    }

    /// The cut moves toward the piece that took less time and keeps its pieces.
    #[test]
    fn the_cut_moves_toward_equal_work() {
        let m = model();
        let cut = Cut::new(&m, 2).unwrap();
        assert_eq!(cut.core_starts, vec![8]);
        let later = cut.rebalanced(&m, &[1.0, 3.0]).unwrap();
        assert!(later.core_starts[0] > 8, "{:?}", later.core_starts);
        let sooner = cut.rebalanced(&m, &[3.0, 1.0]).unwrap();
        assert!(sooner.core_starts[0] < 8, "{:?}", sooner.core_starts);
        let far = cut.rebalanced(&m, &[1.0, 1e6]).unwrap();
        assert_eq!(far.core_starts, vec![16 - MIN_PIECE]);
        assert_eq!(cut.rebalanced(&m, &[2.0, 2.0]).unwrap(), cut);
    }
}
