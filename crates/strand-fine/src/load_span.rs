//! A wire's loads on a span of its segments: the loads sweep cut inside a wire, so that its
//! two halves carry equal work (seven wires of a one-layer strand over two threads as whole
//! wires leave one half about 8 % above the other).
//!
//! Each segment's force and torque are summed in the order of the whole wire's evaluation
//! ([`crate::model`]: the joint before it, the joint after it, the anchors, gravity, the
//! external force, its contacts in list order), so the loads are the same bit for bit. A
//! joint across the cut is evaluated by both halves, each adding its load on its own segment.
//! The wire's energies, sums over all its joints, segments and contacts, are summed after the
//! sweep in the whole wire's order ([`span_energies`]) from the joints' energies the spans
//! keep and the contacts' own.

use std::ops::Range;

use nalgebra::Vector3;

use crate::contact::{self, ContactHistory, ContactLoad};
use crate::model::{Wire, WireLoads};
use crate::segment::{Frame, Pose, Segment};

/// Where the loads sweep is cut: before segment `segment` of wire `wire` (`segment == 0`:
/// between whole wires).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LoadCut {
    /// The wire cut, or the first wire of the second half.
    pub wire: usize,
    /// The first segment of the second half in that wire (0: the whole wire in it).
    pub segment: usize,
}

/// Relative cost of a wire's loads: a joint with its segment 5, a contact 3 (instruction
/// counts of the Fig. 7 settle: about 600 and 350 instructions).
fn cost(w: &Wire) -> f64 {
    (5 * w.chain.len() + 3 * (w.contacts.len() + w.links.len())) as f64
}

/// A wire whose loads can be evaluated in spans: no wire-to-wire links (their duplicates are
/// resolved over the whole wire) and its contacts in segment order.
fn cuttable(w: &Wire) -> bool {
    w.links.is_empty()
        && w.chain.len() >= 2
        && w.contacts.windows(2).all(|p| p[0].segment <= p[1].segment)
}

/// The cut of the loads sweep over `wires` into two halves of about equal cost: inside the
/// wire where the half falls if it is [`cuttable`], its cost taken as spread evenly over its
/// segments; else between whole wires ([`crate::sweep::balanced_cut`]).
pub(crate) fn plan(wires: &[Wire]) -> LoadCut {
    let total: f64 = wires.iter().map(cost).sum();
    let mut before = 0.0;
    for (i, w) in wires.iter().enumerate() {
        let c = cost(w);
        if before + c > 0.5 * total && cuttable(w) {
            let n = w.chain.len();
            let m = ((0.5 * total - before) / c * n as f64).round() as usize;
            if (1..n).contains(&m) {
                return LoadCut {
                    wire: i,
                    segment: m,
                };
            }
            break;
        }
        before += c;
    }
    LoadCut {
        wire: crate::sweep::balanced_cut(wires.iter().map(cost)),
        segment: 0,
    }
}

/// The loads of segments `first..first + forces.len()` of one wire and of its contacts
/// `first_contact..first_contact + contacts.len()` (those of these segments), with the
/// energies of its joints `first..first + joint_energies.len()`.
pub(crate) struct LoadSpan<'a> {
    first: usize,
    forces: &'a mut [Vector3<f64>],
    torques: &'a mut [Vector3<f64>],
    first_contact: usize,
    contacts: &'a mut [ContactLoad],
    joint_energies: &'a mut [f64],
}

impl<'a> LoadSpan<'a> {
    /// The two spans of `loads`, the loads of `wire`, cut before segment `m`.
    pub(crate) fn halves(wire: &Wire, loads: &'a mut WireLoads, m: usize) -> (Self, Self) {
        let c = wire.contacts.partition_point(|cp| cp.segment < m);
        let nc = wire.contacts.len();
        let (f0, f1) = loads.forces.split_at_mut(m);
        let (t0, t1) = loads.torques.split_at_mut(m);
        let (c0, c1) = loads.contacts[..nc].split_at_mut(c);
        let (e0, e1) = loads.joint_energies.split_at_mut(m);
        (
            LoadSpan {
                first: 0,
                forces: f0,
                torques: t0,
                first_contact: 0,
                contacts: c0,
                joint_energies: e0,
            },
            LoadSpan {
                first: m,
                forces: f1,
                torques: t1,
                first_contact: c,
                contacts: c1,
                joint_energies: e1,
            },
        )
    }

    /// Evaluates the span's loads of `wire` at `poses` (frames `frames`), its contacts
    /// against the core (`core_frames`, `core_segments`) from the committed `histories` (all
    /// of the wire's), under the gravity `gravity` (m/s^2, load factor applied) and the
    /// external forces times `load_factor`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn evaluate(
        self,
        wire: &Wire,
        poses: &[Pose],
        frames: &[Frame],
        core_frames: &[Frame],
        core_segments: &[Segment],
        histories: &[ContactHistory],
        gravity: &Vector3<f64>,
        load_factor: f64,
    ) {
        let span: Range<usize> = self.first..self.first + self.forces.len();
        let k0 = span.start;
        self.forces.fill(Vector3::zeros());
        self.torques.fill(Vector3::zeros());
        let chain = &wire.chain;
        // The joints touching the span: the one before its first segment to the one after
        // its last.
        let joints = k0.saturating_sub(1)..span.end.min(chain.joints.len());
        for k in joints {
            let j = &chain.joints[k];
            let l = j.evaluate_in(&poses[k], &frames[k], &poses[k + 1], &frames[k + 1]);
            if k >= k0 {
                self.forces[k - k0] += l.force_a;
                self.torques[k - k0] += l.torque_a;
                self.joint_energies[k - k0] = l.energy;
            }
            if span.contains(&(k + 1)) {
                self.forces[k + 1 - k0] += l.force_b;
                self.torques[k + 1 - k0] += l.torque_b;
            }
        }
        for a in wire.anchors.iter().filter(|a| span.contains(&a.segment)) {
            let l = a.joint.evaluate(&a.ground, &poses[a.segment]);
            self.forces[a.segment - k0] += l.force_b;
            self.torques[a.segment - k0] += l.torque_b;
        }
        for k in span.clone() {
            self.forces[k - k0] += gravity * chain.segments[k].mass;
        }
        for (k, f) in wire
            .external
            .iter()
            .enumerate()
            .filter(|(k, _)| span.contains(k))
        {
            self.forces[k - k0] += f * load_factor;
        }
        let nc = self.contacts.len();
        let c0 = self.first_contact;
        let contacts = wire.contacts[c0..c0 + nc]
            .iter()
            .zip(&histories[c0..c0 + nc]);
        for ((cp, h), out) in contacts.zip(self.contacts.iter_mut()) {
            contact::evaluate_into(cp, h, &frames[cp.segment], core_frames, core_segments, out);
            self.forces[cp.segment - k0] += out.force_wire;
            self.torques[cp.segment - k0] += out.torque_wire;
        }
    }
}

/// Sets the energies of `loads`, the loads of `wire` at `poses` evaluated in spans, summed in
/// the order of the whole wire's evaluation: the joints' (kept by the spans) and the anchors'
/// spring energy, the potential of gravity `gravity` (m/s^2, load factor applied) and of the
/// external forces times `load_factor`, the contacts' energies and slip work.
pub(crate) fn span_energies(
    wire: &Wire,
    poses: &[Pose],
    gravity: &Vector3<f64>,
    load_factor: f64,
    loads: &mut WireLoads,
) {
    let mut spring = 0.0;
    for e in &loads.joint_energies {
        spring += e;
    }
    for a in &wire.anchors {
        spring += a.joint.evaluate(&a.ground, &poses[a.segment]).energy;
    }
    let rest = &wire.chain.rest;
    let mut potential = 0.0;
    for (k, s) in wire.chain.segments.iter().enumerate() {
        let w = gravity * s.mass;
        potential -= w.dot(&(poses[k].position - rest[k].position));
    }
    for (k, f) in wire.external.iter().enumerate() {
        let f = f * load_factor;
        potential -= f.dot(&(poses[k].position - rest[k].position));
    }
    let (mut ce, mut fe, mut sw) = (0.0, 0.0, 0.0);
    for c in &loads.contacts[..wire.contacts.len()] {
        ce += c.normal_energy;
        fe += c.tangential_energy;
        sw += c.slip_work;
    }
    loads.spring_energy = spring;
    loads.gravity_energy = potential;
    loads.contact_energy = ce;
    loads.friction_energy = fe;
    loads.slip_work = sw;
}
