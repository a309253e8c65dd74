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

use nalgebra::{Matrix3, SMatrix, Vector3};
use rayon::prelude::*;

use crate::contact::ContactHistory;
use crate::load_share::LoadShares;
use crate::model::{Energies, FineModel, ModelState, WireLoads, WireState, update_frames};
use crate::segment::{Frame, Pose, Segment};
use crate::sweep;

mod partition;

/// Fewest steps of an [`Integrator::advance`] that run on threads holding a piece of the
/// strand each ([`partition`]): a stretch starts a thread per piece.
const PARTITION_MIN_STEPS: u64 = 8;

/// `B = M^{-1/2}` block by block at `state`, one 6 x 6 block per segment: `m^{-1/2} I` on its
/// translations (kg^-1/2) and `R I^{-1/2} R^T` on its rotations (kg^-1/2 m^-1; the world
/// inertia tensor of the axisymmetric segment, axial and transverse inertia apart).
pub(crate) fn inverse_sqrt_mass_blocks(
    model: &FineModel,
    state: &ModelState,
) -> Vec<SMatrix<f64, 6, 6>> {
    let mut blocks: Vec<SMatrix<f64, 6, 6>> = Vec::with_capacity(model.segment_count());
    for (w, s) in model.wires.iter().zip(&state.wires) {
        for (seg, p) in w.chain.segments.iter().zip(&s.poses) {
            let r = p.rotation.to_rotation_matrix();
            let d = Matrix3::from_diagonal(&Vector3::new(
                seg.axial_inertia.sqrt().recip(),
                seg.transverse_inertia.sqrt().recip(),
                seg.transverse_inertia.sqrt().recip(),
            ));
            let mut b = SMatrix::<f64, 6, 6>::zeros();
            b.fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(Matrix3::identity() * seg.mass.sqrt().recip()));
            b.fixed_view_mut::<3, 3>(3, 3)
                .copy_from(&(r.matrix() * d * r.matrix().transpose()));
            blocks.push(b);
        }
    }
    blocks
}

/// Upper bound on the highest circular frequency (rad/s) of the model linearised at `state`:
/// Gershgorin row sums of `B K B`, similar to `M^{-1} K`, with `B = M^{-1/2}` block by block:
/// `m^{-1/2}` for a segment's translations and `R I^{-1/2} R^T` for its rotations (the world
/// inertia tensor of the axisymmetric segment, axial and transverse inertia apart). Contacts
/// enter closed, with their stiffer spring (normal or tangential) in every direction, so the
/// bound holds whichever contacts close. (With the smallest principal inertia in every
/// direction instead, the bound was 2.1-7.6 times the exact highest frequency on the Table 1
/// strand at 77-10 segments per wire; block by block it is 1.3-1.6 times.)
pub fn highest_frequency(model: &FineModel, state: &ModelState) -> f64 {
    let blocks = inverse_sqrt_mass_blocks(model, state);
    // The assembled 6x6 blocks (summed before taking absolute values: the diagonal blocks
    // of neighbouring joints partly cancel).
    let mut elements = model.joint_tangents(state);
    elements.extend(model.contact_bound_tangents(state));
    let mut assembled: Vec<((usize, usize), SMatrix<f64, 6, 6>)> = Vec::new();
    for e in elements {
        for (bi, si) in e.segments.iter().enumerate() {
            let Some(si) = *si else { continue };
            for (bj, sj) in e.segments.iter().enumerate() {
                let Some(sj) = *sj else { continue };
                let k = e.stiffness.fixed_view::<6, 6>(6 * bi, 6 * bj).into_owned();
                assembled.push(((si, sj), k));
            }
        }
    }
    assembled.sort_by_key(|(key, _)| *key);
    let mut rows = vec![0.0; 6 * blocks.len()];
    let mut i = 0;
    while i < assembled.len() {
        let (key, mut k) = assembled[i];
        i += 1;
        while i < assembled.len() && assembled[i].0 == key {
            k += assembled[i].1;
            i += 1;
        }
        let b = blocks[key.0] * k * blocks[key.1];
        for r in 0..6 {
            rows[6 * key.0 + r] += b.row(r).iter().map(|v| v.abs()).sum::<f64>();
        }
    }
    rows.iter().fold(0.0f64, |a, &b| a.max(b)).sqrt()
}

/// Fraction of the linear limit `omega dt = 2` the kick-drift-kick scheme keeps in large
/// motion. Its rotations are not a linear system: the exact free flight of a turning segment
/// passes angular momentum between its transverse axes and its axis, whose inertia is 5 to 80
/// times smaller. Measured on a pinned single-wire pendulum (40 segments, 0.5 s): stable at
/// omega_max dt = 1.25, blown up at 1.43 (omega_max exact), while the straight wire at rest is
/// stable to 2.
pub const MOTION_FACTOR: f64 = 0.6;

/// Stable step (s) of the explicit scheme at `state`: `safety * MOTION_FACTOR * 2 /
/// omega_max`, with the frequency bound of [`highest_frequency`] (`safety` in (0, 1], e.g.
/// 0.9).
pub fn stable_time_step(model: &FineModel, state: &ModelState, safety: f64) -> f64 {
    safety * MOTION_FACTOR * 2.0 / highest_frequency(model, state)
}

/// One wire's share of a kick-drift sweep: its index, its state, its committed contact
/// histories, its segments' frames and its buffers of the loads with the shares added.
type KickDrift<'a> = (
    usize,
    (
        (
            (&'a mut WireState, &'a mut Vec<ContactHistory>),
            &'a mut Vec<Frame>,
        ),
        &'a mut Shared,
    ),
);

/// Forces (N) and torques (N m) on a wire's segments with the other wires' shares added
/// ([`LoadShares`]): the kick's loads, for a wire that takes shares.
type Shared = (Vec<Vector3<f64>>, Vec<Vector3<f64>>);

/// Kick-drift-kick integrator with its load buffers (allocation-free steps).
#[derive(Debug, Clone)]
pub struct Integrator {
    /// Time step (s).
    pub dt: f64,
    /// Simulated time (s).
    pub time: f64,
    /// Steps taken.
    pub steps: u64,
    /// Factor on gravity and the external forces (-); 1 in dynamics.
    pub load_factor: f64,
    /// Rate gamma (1/s) of a viscous damping proportional to the masses and inertias: every
    /// step scales the momenta by exp(-gamma dt). Zero in dynamics (the energy balance does
    /// not book it); [`crate::settle()`] uses it to bring the strand to rest.
    pub damping_rate: f64,
    loads: Vec<WireLoads>,
    /// Every segment's frame after the last drift of [`Integrator::advance`] (one list per
    /// wire), for the loads of the step.
    frames: Vec<Vec<Frame>>,
    /// Where each wire's shares of the other wires' contacts and ties come from.
    shares: LoadShares,
    /// Each wire's loads with its shares added, during [`Integrator::advance`] (empty for a
    /// wire that takes none).
    shared: Vec<Shared>,
    /// The cut of the strand into pieces of the last stretch on several threads, moved
    /// toward equal work after every stretch ([`partition`]).
    cut: Option<partition::Cut>,
}

impl Integrator {
    /// Integrator with step `dt` (s) for `model`, with the loads at `state` evaluated.
    pub fn new(model: &FineModel, state: &ModelState, dt: f64) -> Self {
        let mut loads = model.load_buffers();
        model.compute_loads(state, 1.0, &mut loads);
        let frames = loads.iter().map(|l| l.frames.clone()).collect();
        let shares = LoadShares::new(model);
        let shared = (0..model.wires.len())
            .map(|w| {
                let n = if shares.takes(w) {
                    loads[w].forces.len()
                } else {
                    0
                };
                (vec![Vector3::zeros(); n], vec![Vector3::zeros(); n])
            })
            .collect();
        Self {
            dt,
            time: 0.0,
            steps: 0,
            load_factor: 1.0,
            damping_rate: 0.0,
            loads,
            frames,
            shares,
            shared,
            cut: None,
        }
    }

    /// Re-evaluates the loads at `state` with the current `load_factor` (after changing it
    /// by more than a step's worth).
    pub fn reload(&mut self, model: &FineModel, state: &ModelState) {
        model.compute_loads(state, self.load_factor, &mut self.loads);
    }

    /// Loads at the current state (after the last step).
    pub fn loads(&self) -> &[WireLoads] {
        &self.loads
    }

    /// Advances `state` by one step at the current `load_factor`: [`Integrator::advance`] by
    /// one step (the same arithmetic as a kick, drift, load evaluation, commit and kick).
    pub fn step(&mut self, model: &FineModel, state: &mut ModelState) {
        let load_factor = self.load_factor;
        self.advance(model, state, 1, &move |_| load_factor);
    }

    /// Advances `state` by `steps` steps, the load factor of each step set by
    /// `load_factor(t)` at the step's end time `t` (s). The same results, bit for bit, as
    /// `steps` calls of [`Integrator::step`] with those load factors, in two sweeps over the
    /// wires per step instead of four: the commit of a step's contact histories, its second
    /// half kick (and damping), the first half kick and drift of the next and the segments'
    /// frames at the new poses are one sweep, the loads the other. With more than one
    /// thread in rayon's pool and at least 8 steps, the strand is cut along its length into
    /// one piece per thread, each thread holding its piece for all the steps (`partition`
    /// module; a strand of one layer without ties); otherwise the sweeps run in parallel
    /// over the wires when rayon's pool has more than one thread, else in the calling
    /// thread (`sweep` module). The numbers are the same every way.
    pub fn advance(
        &mut self,
        model: &FineModel,
        state: &mut ModelState,
        steps: u64,
        load_factor: &(dyn Fn(f64) -> f64 + Sync),
    ) {
        let threads = rayon::current_num_threads();
        let cut = if threads > 1 && steps >= PARTITION_MIN_STEPS {
            match self.cut.take() {
                Some(c) if c.fits(model, threads) => Some(c),
                _ => partition::Cut::new(model, threads),
            }
        } else {
            None
        };
        if let Some(cut) = cut {
            let busy = partition::advance(self, model, state, steps, load_factor, &cut);
            self.cut = cut.rebalanced(model, &busy).or(Some(cut));
        } else if sweep::parallel() {
            // On one of the pool's threads: the sweeps' halves are handed to the other
            // threads of the pool without waking the calling thread every time.
            rayon::scope(|_| self.advance_on(model, state, steps, load_factor, true));
        } else {
            self.advance_on(model, state, steps, load_factor, false);
        }
    }

    /// [`Integrator::advance`], its sweeps over the wires in parallel if `parallel`.
    fn advance_on(
        &mut self,
        model: &FineModel,
        state: &mut ModelState,
        steps: u64,
        load_factor: &(dyn Fn(f64) -> f64 + Sync),
        parallel: bool,
    ) {
        let mut kd = KickDriftStep {
            dt: self.dt,
            damp: (-self.damping_rate * self.dt).exp(),
            first: true,
            last: false,
            own: false,
        };
        for i in 0..=steps {
            // Commit (the previous step's), kick (the previous step's second half and this
            // step's first), then drift and frames; after the last step, commit and the
            // second half.
            (kd.first, kd.last) = (i == 0, i == steps);
            let ModelState {
                wires, contacts, ..
            } = &mut *state;
            let (all_loads, shares) = (&self.loads, &self.shares);
            let kick_drift = |(wi, (((s, hist), frames), shared)): KickDrift<'_>| {
                kick_drift_wire(model, shares, all_loads, wi, s, hist, frames, shared, &kd);
            };
            if parallel {
                wires
                    .par_iter_mut()
                    .zip(contacts.par_iter_mut())
                    .zip(self.frames.par_iter_mut())
                    .zip(self.shared.par_iter_mut())
                    .enumerate()
                    .for_each(kick_drift);
            } else {
                wires
                    .iter_mut()
                    .zip(contacts.iter_mut())
                    .zip(self.frames.iter_mut())
                    .zip(self.shared.iter_mut())
                    .enumerate()
                    .for_each(kick_drift);
            }
            if !kd.first {
                // The friction loss, summed in wire order as `commit_contacts` does.
                for l in &self.loads {
                    state.friction_work += l.slip_work;
                }
            }
            if kd.last {
                break;
            }
            self.load_factor = load_factor(self.time + self.dt);
            model.loads_at_frames(state, self.load_factor, &self.frames, &mut self.loads);
            kd.own = true;
            self.time += self.dt;
            self.steps += 1;
        }
        if kd.own {
            // The loads at the last step's end, shares added, as `compute_loads` gives them.
            self.shares.add_all(model, &mut self.loads);
        }
    }

    /// Energies of `state` from the loads already evaluated (no extra load evaluation).
    pub fn energies(&self, model: &FineModel, state: &ModelState) -> Energies {
        model.energies_from_loads(state, &self.loads)
    }
}

/// What a kick-drift sweep does to every wire at one step of [`Integrator::advance`].
#[derive(Debug, Clone, Copy)]
struct KickDriftStep {
    /// Time step (s).
    dt: f64,
    /// Factor exp(-gamma dt) of the damping on the momenta over a step (-).
    damp: f64,
    /// The first sweep of a stretch: no commit, no second half kick.
    first: bool,
    /// The last sweep of a stretch: commit and the second half kick only.
    last: bool,
    /// The loads are each wire's own, without the other wires' shares ([`LoadShares`]):
    /// the kick adds them.
    own: bool,
}

/// One wire's share of a kick-drift sweep: wire `wi`'s commit of its contact histories, its
/// kicks with the loads `loads[wi]` (and its shares of the other wires' loads), its drift and
/// its frames at the new poses.
#[allow(clippy::too_many_arguments)]
#[inline]
fn kick_drift_wire(
    model: &FineModel,
    shares: &LoadShares,
    loads: &[WireLoads],
    wi: usize,
    s: &mut WireState,
    hist: &mut [ContactHistory],
    frames: &mut [Frame],
    shared: &mut Shared,
    kd: &KickDriftStep,
) {
    let (w, l) = (&model.wires[wi], &loads[wi]);
    if !kd.first {
        for (hi, c) in hist.iter_mut().zip(&l.contacts) {
            *hi = c.history;
        }
    }
    let (forces, torques) = if kd.own && shares.takes(wi) {
        let (f, t) = shared;
        f.copy_from_slice(&l.forces);
        t.copy_from_slice(&l.torques);
        shares.add_to(model, wi, loads, f, t, &mut 0.0);
        (&f[..], &t[..])
    } else {
        (&l.forces[..], &l.torques[..])
    };
    let WireState {
        poses,
        velocities,
        angular_momenta,
    } = s;
    let motion = SegmentMotion {
        poses,
        velocities,
        angular_momenta,
    };
    kick_drift_segments(&w.chain.segments, motion, forces, torques, kd);
    if !kd.last {
        update_frames(&s.poses, frames);
    }
}

/// Poses, velocities (m/s) and angular momenta (kg m^2/s) of a run of segments.
struct SegmentMotion<'a> {
    poses: &'a mut [Pose],
    velocities: &'a mut [Vector3<f64>],
    angular_momenta: &'a mut [Vector3<f64>],
}

/// The kicks (the forces `forces` and torques `torques`, N and N m) and the drift of the
/// segments `segments` ([`kick_drift_wire`] without the commit and the frames).
#[inline(always)]
fn kick_drift_segments(
    segments: &[Segment],
    m: SegmentMotion<'_>,
    forces: &[Vector3<f64>],
    torques: &[Vector3<f64>],
    kd: &KickDriftStep,
) {
    let (dt, damp) = (kd.dt, kd.damp);
    let h = 0.5 * dt;
    for (k, seg) in segments.iter().enumerate() {
        let (dv, dl) = (forces[k] * (h / seg.mass), torques[k] * h);
        if !kd.first {
            m.velocities[k] += dv;
            m.angular_momenta[k] += dl;
            if damp < 1.0 {
                m.velocities[k] *= damp;
                m.angular_momenta[k] *= damp;
            }
        }
        if kd.last {
            continue;
        }
        m.velocities[k] += dv;
        m.angular_momenta[k] += dl;
        let p = &mut m.poses[k];
        p.position += m.velocities[k] * dt;
        p.rotation = seg.free_rotation(&p.rotation, &m.angular_momenta[k], dt);
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
