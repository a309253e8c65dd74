//! Explicit symplectic time stepping of the segment chains.
//!
//! Kick-drift-kick splitting of `H = T + V`: half a step of loads on the momenta (linear and
//! world-frame angular), then the exact free flight of every segment (straight line, and the
//! exact torque-free motion of an axisymmetric rigid body, [`crate::Segment::free_rotation`]),
//! then the second half kick. Each part is an exact flow of a piece of the Hamiltonian, so the
//! scheme is symplectic, time-reversible and second order: the energy error stays bounded.
//!
//! The stable step comes from the system: a Gershgorin bound on the highest frequency of the
//! tangent stiffness against the masses ([`stable_time_step`]).

use nalgebra::Vector3;
use rayon::prelude::*;

use crate::model::{Energies, FineModel, ModelState, WireLoads};

/// Upper bound on the highest circular frequency (rad/s) of the model linearised at `state`:
/// Gershgorin row sums of `M'^{-1/2} K M'^{-1/2}`, where `M'` is the segment mass for
/// translations and the smallest principal inertia for rotations (`M' <= M`, so the bound
/// holds for the true mass matrix too). Contacts enter closed, with their stiffer spring
/// (normal or tangential) in every direction, so the bound holds whichever contacts close.
pub fn highest_frequency(model: &FineModel, state: &ModelState) -> f64 {
    let mut diag = Vec::with_capacity(6 * model.segment_count());
    for w in &model.wires {
        for s in &w.chain.segments {
            let i = s.axial_inertia.min(s.transverse_inertia);
            diag.extend_from_slice(&[s.mass, s.mass, s.mass, i, i, i]);
        }
    }
    let mut rows = vec![0.0; diag.len()];
    let mut elements = model.joint_tangents(state);
    elements.extend(model.contact_bound_tangents(state));
    for e in elements {
        for (bi, si) in e.segments.iter().enumerate() {
            let Some(si) = si else { continue };
            for (bj, sj) in e.segments.iter().enumerate() {
                let Some(sj) = sj else { continue };
                for r in 0..6 {
                    for c in 0..6 {
                        let (gi, gj) = (6 * si + r, 6 * sj + c);
                        let v = e.stiffness[(6 * bi + r, 6 * bj + c)].abs();
                        rows[gi] += v / (diag[gi] * diag[gj]).sqrt();
                    }
                }
            }
        }
    }
    rows.iter().fold(0.0f64, |a, &b| a.max(b)).sqrt()
}

/// Stable step (s) of the explicit scheme at `state`: `safety * 2 / omega_max`, with the
/// frequency bound of [`highest_frequency`] (`safety` in (0, 1], e.g. 0.9).
pub fn stable_time_step(model: &FineModel, state: &ModelState, safety: f64) -> f64 {
    safety * 2.0 / highest_frequency(model, state)
}

/// Kick-drift-kick integrator with its load buffers (allocation-free steps).
#[derive(Debug, Clone)]
pub struct Integrator {
    /// Time step (s).
    pub dt: f64,
    /// Simulated time (s).
    pub time: f64,
    /// Steps taken.
    pub steps: u64,
    loads: Vec<WireLoads>,
}

impl Integrator {
    /// Integrator with step `dt` (s) for `model`, with the loads at `state` evaluated.
    pub fn new(model: &FineModel, state: &ModelState, dt: f64) -> Self {
        let mut loads = model.load_buffers();
        model.compute_loads(state, 1.0, &mut loads);
        Self {
            dt,
            time: 0.0,
            steps: 0,
            loads,
        }
    }

    /// Loads at the current state (after the last step).
    pub fn loads(&self) -> &[WireLoads] {
        &self.loads
    }

    /// Advances `state` by one step.
    pub fn step(&mut self, model: &FineModel, state: &mut ModelState) {
        let dt = self.dt;
        let h = 0.5 * dt;
        model
            .wires
            .par_iter()
            .zip(state.wires.par_iter_mut())
            .zip(self.loads.par_iter())
            .for_each(|((w, s), l)| {
                for (k, seg) in w.chain.segments.iter().enumerate() {
                    // Kick.
                    s.velocities[k] += l.forces[k] * (h / seg.mass);
                    s.angular_momenta[k] += l.torques[k] * h;
                    // Drift: exact free flight.
                    let p = &mut s.poses[k];
                    p.position += s.velocities[k] * dt;
                    p.rotation = seg.free_rotation(&p.rotation, &s.angular_momenta[k], dt);
                }
            });
        model.compute_loads(state, 1.0, &mut self.loads);
        model.commit_contacts(state, &self.loads);
        model
            .wires
            .par_iter()
            .zip(state.wires.par_iter_mut())
            .zip(self.loads.par_iter())
            .for_each(|((w, s), l)| {
                for (k, seg) in w.chain.segments.iter().enumerate() {
                    s.velocities[k] += l.forces[k] * (h / seg.mass);
                    s.angular_momenta[k] += l.torques[k] * h;
                }
            });
        self.time += dt;
        self.steps += 1;
    }

    /// Energies of `state` from the loads already evaluated (no extra load evaluation).
    pub fn energies(&self, model: &FineModel, state: &ModelState) -> Energies {
        model.energies_from_loads(state, &self.loads)
    }
}

/// Velocity (m/s) of the world point `offset` (body axes) of segment `k` of wire `w`.
pub fn point_velocity(
    model: &FineModel,
    state: &ModelState,
    w: usize,
    k: usize,
    offset: &Vector3<f64>,
) -> Vector3<f64> {
    let s = &state.wires[w];
    let seg = &model.wires[w].chain.segments[k];
    let p = &s.poses[k];
    let omega = seg.angular_velocity(p, &s.angular_momenta[k]);
    s.velocities[k] + omega.cross(&(p.rotation * offset))
}
