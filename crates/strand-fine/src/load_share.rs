//! The loads one wire's contacts and ties put on other wires, and the fixed order they are
//! summed in.
//!
//! A contact of a helical wire with the core, a link between two wires
//! ([`crate::interlayer`]) and a tie of a wire to the core each act on two wires. The loads'
//! sweep evaluates each with the wire that owns it; the other wire's share is added to that
//! wire's loads afterwards, in a fixed order: the core's contacts in wire and contact order,
//! the links in wire and link order, the ties in tie order. The sums therefore do not depend
//! on the thread count. [`FineModel::compute_loads`] adds the shares after its sweep; the time
//! stepping adds each wire's inside its own kick-drift sweep, the wires in parallel
//! ([`crate::dynamics::Integrator::advance`]), so that no serial pass separates the two
//! sweeps of a step. Both go through [`LoadShares::add_to`]: the same arithmetic, bit for bit.

use nalgebra::Vector3;

use crate::model::{FineModel, WireLoads};

/// For every wire, the other wires' contacts and ties whose loads it takes, in the order of
/// their sum.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct LoadShares {
    /// The core takes the shares of the helical wires' contacts with it.
    core_contacts: bool,
    /// Per wire: (source wire, link index) of the links whose partner it is, in wire and link
    /// order.
    links: Vec<Vec<(usize, usize)>>,
    /// Per wire: (tie index, slot in the tied wire's [`WireLoads::ties`]) of the ties acting on
    /// it (every tie on the core, a wire's own ties on it), in tie order.
    ties: Vec<Vec<(usize, usize)>>,
}

impl LoadShares {
    /// The shares of `model`'s contacts, links and ties.
    pub(crate) fn new(model: &FineModel) -> Self {
        let n = model.wires.len();
        let mut links = vec![Vec::new(); n];
        for (i, w) in model.wires.iter().enumerate() {
            for (k, lk) in w.links.iter().enumerate() {
                links[lk.partner].push((i, k));
            }
        }
        let mut ties = vec![Vec::new(); n];
        let mut slots = vec![0usize; n];
        for (i, t) in model.ties.iter().enumerate() {
            let slot = slots[t.wire];
            slots[t.wire] += 1;
            ties[0].push((i, slot));
            ties[t.wire].push((i, slot));
        }
        Self {
            core_contacts: model.wires.iter().skip(1).any(|w| !w.contacts.is_empty()),
            links,
            ties,
        }
    }

    /// True when wire `w` takes loads from other wires.
    pub(crate) fn takes(&self, w: usize) -> bool {
        (w == 0 && self.core_contacts) || !self.links[w].is_empty() || !self.ties[w].is_empty()
    }

    /// Adds to wire `w`'s `forces` (N), `torques` (N m) and `spring_energy` (J) the shares of
    /// the other wires' contacts and ties evaluated in `loads` (the tie energies are booked
    /// on the core).
    pub(crate) fn add_to(
        &self,
        model: &FineModel,
        w: usize,
        loads: &[WireLoads],
        forces: &mut [Vector3<f64>],
        torques: &mut [Vector3<f64>],
        spring_energy: &mut f64,
    ) {
        if w == 0 && self.core_contacts {
            for l in &loads[1..] {
                for c in &l.core_shares {
                    forces[c.segment] += c.force;
                    torques[c.segment] += c.torque;
                }
            }
        }
        for &(i, k) in &self.links[w] {
            let c = &loads[i].contacts[model.wires[i].contacts.len() + k];
            forces[c.core_segment] += c.force_core;
            torques[c.core_segment] += c.torque_core;
        }
        for &(tie, slot) in &self.ties[w] {
            let t = &model.ties[tie];
            let l = &loads[t.wire].ties[slot];
            if w == 0 {
                forces[t.core_segment] += l.force_a;
                torques[t.core_segment] += l.torque_a;
                *spring_energy += l.energy;
            } else {
                forces[t.segment] += l.force_b;
                torques[t.segment] += l.torque_b;
            }
        }
    }

    /// Adds every wire's shares to its own loads in `loads` (in place).
    pub(crate) fn add_all(&self, model: &FineModel, loads: &mut [WireLoads]) {
        for w in 0..loads.len() {
            if !self.takes(w) {
                continue;
            }
            let mut forces = std::mem::take(&mut loads[w].forces);
            let mut torques = std::mem::take(&mut loads[w].torques);
            let mut energy = loads[w].spring_energy;
            self.add_to(model, w, loads, &mut forces, &mut torques, &mut energy);
            let l = &mut loads[w];
            (l.forces, l.torques, l.spring_energy) = (forces, torques, energy);
        }
    }
}
