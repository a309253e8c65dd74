//! Runs the fine finite-segment model of a scene (SPEC 4) and writes its result files.
//!
//! The fine model is laid along +X from the origin with wire phases measured from +Z; a scene
//! runs in the frame where its initial direction is +X and its phase reference +Z (so every
//! wire sits where the equivalent model puts it), with gravity, point forces, velocities and
//! support motions rotated into it, and every written position and velocity is rotated back,
//! so the results are in the scene's axes.
//!
//! Measured quantities along the strand (`centerline.csv`), at every node of the core's
//! centreline (its ends and the midpoints of its joint gaps):
//! * curvature: the bending part of the core joint's relative rotation over the distance
//!   between the segment centres (at a clamp, the anchor's rotation over half a segment;
//!   zero at a free or pinned end);
//! * the resultant the near part of the strand exerts on the far part across the section
//!   normal to the core there, from the momentum balance of the far part: every segment
//!   (all wires) whose centre lies beyond the section at rest contributes its total load
//!   minus its gravity; the internal loads of the far part cancel. The tension is minus the
//!   force's component along the core's tangent, the bending moment the magnitude of the
//!   moment's component normal to it, and `bending_stiffness` their ratio M / kappa. In
//!   statics the far part's total load is the equilibrium residual (zero), so the moment is
//!   that of the far part's weight.

use super::stopwatch::Stopwatch;
use std::path::Path;

use nalgebra::{UnitQuaternion, Vector3};
use strand_fine as fine;
use strand_fine::{
    ContactOptions, ContactState, Discretisation, FineModel, Integrator, ModelState, WireLoads,
};

use super::budget;
use super::record::{
    Failure, RunError, RunOptions, RunSummary, Stop, balance_open, finish, io_err,
};
use crate::along;
use crate::output::{CENTERLINE_COLUMNS, Csv, FrameFiles, VtkFrame, number, write_static_vtk};
use crate::probe::{ProbeFiles, ProbeSample};
use crate::range::Envelopes;
use crate::scene::{Analysis, End, IntegratorKind, Output, Scene, SupportKind};
use strand_ancf::beam::SupportMotion;
use strand_core::BaseStiffness;
use strand_core::round_off::{self, BalanceFloor, Travel};

/// Safety factor on the explicit stable step of the fine model. (With the step at 0.9 of
/// the linear limit instead, the Fig. 8 clamped pendulum stays stable but its energy balance,
/// spoilt by contacts slipping fast at the root near t = 0.38 s, degrades from 1e-4 to 9e-3 of
/// the largest kinetic energy.)
const STEP_SAFETY: f64 = 0.9;

fn support(scene: &Scene, end: End) -> fine::Support {
    match scene.supports.iter().find(|s| s.at == end).map(|s| s.kind) {
        None => fine::Support::Free,
        Some(SupportKind::Clamped) => fine::Support::Clamped,
        Some(SupportKind::Pinned) => fine::Support::Pinned,
    }
}

/// Rotation taking +X to the scene's initial direction and +Z to its phase reference (a unit
/// vector orthogonal to the direction).
fn frame(direction: [f64; 3], reference: [f64; 3]) -> UnitQuaternion<f64> {
    let d = Vector3::from(direction).normalize();
    let z = Vector3::from(reference).normalize();
    let m = nalgebra::Matrix3::from_columns(&[d, z.cross(&d), z]);
    UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix(&m))
}

/// The motion table of the support at `end`, if it moves.
fn motion(scene: &Scene, end: End) -> Option<SupportMotion> {
    let rows = scene
        .supports
        .iter()
        .find(|s| s.at == end)
        .and_then(|s| s.motion.as_ref())?;
    Some(SupportMotion::new(rows).expect("validated by the scene"))
}

/// Runs the fine model `m` of `scene` and writes `DIR/fine/`.
pub(crate) fn run_fine(
    scene: &Scene,
    m: &crate::scene::FineModel,
    opts: &RunOptions,
    progress: &mut dyn FnMut(&str, f64),
) -> Result<RunSummary, RunError> {
    let name = "fine";
    let strand = &scene.strand;
    let rot = frame(scene.direction, scene.phase_reference);
    let n = m.segments_per_wire;
    let mut model = FineModel::from_strand(
        strand,
        Discretisation {
            core_segments: n,
            wire_segments: n,
        },
        support(scene, End::Start),
        support(scene, End::End),
    );
    model.gravity = rot.inverse() * Vector3::from(scene.gravity);
    for p in &scene.point_forces {
        model.add_point_force(p.s, rot.inverse() * Vector3::from(p.force));
    }
    let mut bound = None;
    if m.bind_free_end {
        for (end, e) in [(End::Start, fine::End::Start), (End::End, fine::End::End)] {
            if support(scene, end) == fine::Support::Free && !strand.layers().is_empty() {
                model.bind_end(e);
                bound = Some(end);
            }
        }
    }
    let contact = ContactOptions {
        penetration: m.penetration,
        ..ContactOptions::default()
    };
    model.add_contacts(strand, &contact);
    let dir = opts.out.join(name);
    std::fs::create_dir_all(&dir).map_err(io_err(&dir))?;

    let mut built = vec![format!(
        "finite-segment chains: core and {} helical wires in {} layers, {n} rigid segments each \
         ({} in all)",
        model.wires.len() - 1,
        strand.layers().len(),
        model.segment_count()
    )];
    if let Some(end) = bound {
        built.push(format!(
            "helical wires bound to the core at the free {} end",
            if end == End::Start { "start" } else { "end" }
        ));
    }
    let mut warnings = Vec::new();
    if let [layer] = strand.layers() {
        let gap = layer.wire_gap();
        if gap <= fine::NEIGHBOUR_GAP * layer.spec.wire.diameter {
            warnings.push(format!(
                "the helical wires are {gap:.3e} m apart: wire-to-wire contact in the layer is \
                 not modelled in a 1+m strand"
            ));
        }
    }
    if !strand.layers().is_empty() {
        let penalty = match contact.relief_on(strand) {
            Some(f) => format!(
                "normal penalty allowing each layer's contacts to relieve {f:.0e} of its strain; \
                 the penetration {:.1e} only decides crossing against line contact",
                m.penetration
            ),
            None => format!(
                "penalty for a penetration of {:.1e} wire diameters",
                m.penetration
            ),
        };
        built.push(format!(
            "{} wire-to-core contacts ({penalty}, Coulomb friction mu = {} with stick springs)",
            model.contact_count(),
            strand.friction()
        ));
        if model.link_count() > 0 {
            built.push(format!(
                "{} wire-to-wire contact links (crossings and lines with the layer beneath, \
                 neighbours closer than {} wire diameters in a layer; the same law)",
                model.link_count(),
                fine::NEIGHBOUR_GAP
            ));
        }
    }
    let analysis = match scene.analysis {
        Analysis::Static { .. } => "static",
        Analysis::Dynamic(_) => "dynamic",
    };
    let mut summary = RunSummary::start(
        &scene.name,
        name,
        "contact and friction (no section law)",
        analysis,
    );
    summary.dofs = 6 * model.segment_count();
    summary.elements = model.segment_count();
    summary.built = built;
    summary.warnings = warnings;
    // Planar scenes write signed curvatures and moments about the scene's Z (in the model's
    // axes here); 3D scenes their magnitudes.
    let plane = scene.is_planar().then(|| rot.inverse() * Vector3::z());
    if !scene.point_forces.is_empty() {
        summary.built.push(format!(
            "{} point force(s) on the core, split between the segments around them",
            scene.point_forces.len()
        ));
    }
    let mut state = model.rest_state();
    if scene.starts_moving() {
        model.set_rigid_velocity(
            &mut state,
            rot.inverse() * Vector3::from(scene.velocity),
            rot.inverse() * Vector3::from(scene.angular_velocity),
        );
    }
    let motions = [motion(scene, End::Start), motion(scene, End::End)];
    let result = match scene.analysis {
        Analysis::Static { load_steps } => run_static(
            &model,
            &mut state,
            load_steps,
            scene.max_steps,
            &mut summary,
            &mut |f| progress(name, f),
        ),
        Analysis::Dynamic(dy) => {
            let stable = fine::stable_time_step(&model, &state, STEP_SAFETY);
            summary.stable_time_step = Some(stable);
            let dt = match (dy.integrator, dy.time_step) {
                (IntegratorKind::Verlet, Some(dt)) if dt > stable => Err(Stop::new(
                    Failure::UnstableStep,
                    format!(
                        "analysis.time_step: {dt:e} s is above the fine model's stable step \
                         {stable:.3e} s"
                    ),
                )),
                (IntegratorKind::Verlet, Some(dt)) => Ok(dt),
                (IntegratorKind::Verlet, None) => Ok(stable),
                (IntegratorKind::GeneralizedAlpha, _) => {
                    summary.warnings.push(format!(
                        "the fine model integrates explicitly (symplectic kick-drift-kick) at \
                         its stable step {stable:.3e} s; the scene's generalized-alpha step \
                         applies to the beam models"
                    ));
                    Ok(stable)
                }
            };
            dt.and_then(|dt| {
                let mut frames = Frames::new(dy.duration, dt, dy.output_interval, &mut summary);
                frames.floor = BalanceFloor::new(
                    strand.axial_stiffness(),
                    strand.max_bending_stiffness(BaseStiffness::Costello),
                    strand.length(),
                    n,
                );
                frames.mass = strand.mass_per_length() * strand.length();
                let norm = |v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
                let loads = frames.mass * norm(&scene.gravity)
                    + scene
                        .point_forces
                        .iter()
                        .map(|p| norm(&p.force))
                        .sum::<f64>();
                frames.load_terms = loads * 2.0 * strand.length();
                budget_check(&model, &state, &frames, scene.max_steps)?;
                run_dynamic(
                    &mut model,
                    &mut state,
                    &motions,
                    &frames,
                    (rot, plane),
                    (&dir, opts.vtk, &scene.output),
                    &mut summary,
                    &mut |f| progress(name, f),
                )
            })
        }
    };
    // The final (or last computed) state along the strand, and the contact states.
    let statics = analysis == "static";
    let written = write_state(
        &model,
        &state,
        (rot, plane),
        &dir,
        opts.vtk && statics,
        if statics { &scene.output.probes } else { &[] },
        &mut summary,
    )
    .map_err(Stop::output);
    let tip = rot
        * model
            .core_centreline(&state)
            .last()
            .copied()
            .unwrap_or_default();
    summary.tip = tip.iter().all(|v| v.is_finite()).then(|| tip.into());
    let result = result.and(written);
    finish(summary, result, &dir)
}

/// Refuses a dynamic run of more than `max_steps` steps, with the time it would take at the
/// cost of a step timed on this model now.
fn budget_check(
    model: &FineModel,
    state: &ModelState,
    frames: &Frames,
    max_steps: usize,
) -> Result<(), Stop> {
    let steps = budget::steps_of(frames.duration, frames.dt);
    if steps <= max_steps as f64 {
        return Ok(());
    }
    let mut probe = state.clone();
    let mut int = Integrator::new(model, &probe, frames.dt);
    let t = budget::time_of(|| int.step(model, &mut probe));
    budget::check(
        steps,
        frames.dt,
        max_steps,
        (t, t),
        &format!("{} a step (timed now)", budget::duration(t)),
    )
}

fn run_static(
    model: &FineModel,
    state: &mut ModelState,
    load_steps: usize,
    max_steps: usize,
    summary: &mut RunSummary,
    progress: &mut dyn FnMut(f64),
) -> Result<(), Stop> {
    if model.contact_count() > 0 {
        return run_settle(model, state, max_steps, summary, progress);
    }
    let opts = fine::StaticOptions {
        load_steps,
        ..fine::StaticOptions::default()
    };
    let clock = Stopwatch::start();
    let report = fine::solve_static_with_progress(model, state, &opts, progress);
    clock.record(summary);
    let report = report.map_err(|e| {
        let reason = match e {
            fine::StaticError::NonFinite { .. } => Failure::NonFinite,
            _ => Failure::NoConvergence,
        };
        Stop::new(reason, e.to_string())
    })?;
    summary.steps = report.load_steps;
    summary.newton_iterations = report.iterations;
    summary.built.push(format!(
        "static equilibrium: Newton on the sparse tangent, residual {:.2e} of the largest \
         segment weight",
        report.residual
    ));
    Ok(())
}

/// Statics with contacts: damped motion to rest, then Newton ([`fine::solve_settled`]);
/// Newton load stepping from the straight strand stalls where weight-loaded contacts near
/// zero gap switch state between iterations. The motion takes at most `max_steps` steps.
fn run_settle(
    model: &FineModel,
    state: &mut ModelState,
    max_steps: usize,
    summary: &mut RunSummary,
    progress: &mut dyn FnMut(f64),
) -> Result<(), Stop> {
    let mut opts = fine::SettledOptions::default();
    opts.settle.max_steps = Some(max_steps as u64);
    let clock = Stopwatch::start();
    let mut first = None;
    let report = fine::solve_settled(model, state, &opts, &mut |_, _, ratio| {
        // Progress: the residual's fall to its allowance, on a log scale.
        let r0 = *first.get_or_insert(ratio.max(10.0));
        progress((r0 / ratio.max(1.0)).ln() / r0.ln());
    });
    clock.record(summary);
    let r = report.map_err(|e| match e {
        fine::SettleError::NonFinite { .. } => Stop::new(Failure::NonFinite, e.to_string()),
        fine::SettleError::StepLimit { .. } => Stop::new(
            Failure::StepLimit,
            format!(
                "{e}: the motion stopped at analysis.max_steps = {max_steps}; raise \
                 analysis.max_steps (or pass --max-steps) to let it settle"
            ),
        ),
        fine::SettleError::NotSettled { .. } => Stop::new(Failure::NoConvergence, e.to_string()),
    })?;
    let s = &r.settle;
    summary.steps = s.steps as usize;
    summary.time_step = Some(s.time_step);
    summary.newton_iterations = r.iterations;
    summary.built.push(format!(
        "static equilibrium with contacts: damped motion from rest (gravity ramped over \
         {:.3} s, mass-proportional damping at {:.3} 1/s, {} explicit steps of {:.3e} s, \
         {:.3} s), then Newton from the settled state",
        s.ramp_time, s.damping_rate, s.steps, s.time_step, s.time,
    ));
    if s.discarded_steps > 0 {
        summary.warnings.push(format!(
            "the damped motion at its default step turned non-finite after {} steps and was \
             run again from rest at the shorter fallback step ({:.3e} s)",
            s.discarded_steps, s.time_step
        ));
    }
    if s.allowance_ratio > 1.0 {
        summary.warnings.push(format!(
            "the damped motion did not come to rest (largest segment force or torque {:.2e} \
             times the allowance after {} steps, {:.3} s); Newton started from where it stopped",
            s.allowance_ratio, s.steps, s.time
        ));
    }
    match r.polish {
        Some(p) => summary.built.push(format!(
            "converged: every segment's force and torque within {:.0e} of the largest segment \
             load {:.3e} N (or within round-off {:.1e} N with a Newton correction within the \
             round-off of the positions) after {} Newton iterations in {} attempt(s) (largest \
             scaled load {:.2e})",
            opts.polish.tolerance, p.force_scale, p.roundoff, r.iterations, r.attempts, p.residual
        )),
        None => summary.warnings.push(format!(
            "settled but not polished: every segment's force and torque is within {:.0e} of the \
             largest segment load {:.3e} N (largest scaled load {:.2e}), not the {:.0e} asked \
             for; Newton from the settled state stalled in {} attempts on contacts switching \
             state between iterations",
            r.tolerance, s.force_scale, r.residual, opts.polish.tolerance, r.attempts
        )),
    }
    Ok(())
}

/// Time stepping and output frames of a dynamic run.
struct Frames {
    /// The round-off floor of the energy balance: the strand's axial and bending stiffness
    /// on the segments of a wire (contacts, which carry no force at rest, left out).
    floor: BalanceFloor,
    /// Mass of the strand (kg), for its root mean square speed.
    mass: f64,
    /// The terms of the load potential in absolute value (J): the weight and the point forces
    /// times twice the length (the distance of the strand's points from the origin, moving
    /// supports aside), whose round-off the potential keeps.
    load_terms: f64,
    duration: f64,
    /// Time step (s).
    dt: f64,
    /// Steps between output frames.
    every: usize,
}

impl Frames {
    /// Frames every `interval` (s) of a run of `duration` (s) at a step of about `dt` (s): the
    /// step is shortened so that output times fall on steps (a warning says so when that costs
    /// more than 1 % more steps); an interval shorter than the step writes a frame every step
    /// (with a warning).
    fn new(duration: f64, dt: f64, interval: f64, summary: &mut RunSummary) -> Frames {
        if interval < dt {
            summary.warnings.push(format!(
                "analysis.output_interval {interval:.3e} s is shorter than the fine model's time \
                 step {dt:.3e} s: a frame is written at every step"
            ));
            return Frames {
                floor: BalanceFloor::new(0.0, 0.0, 1.0, 1),
                mass: 0.0,
                load_terms: 0.0,
                duration,
                dt,
                every: 1,
            };
        }
        let every = budget::steps_of(interval, dt) as usize;
        let short = interval / every as f64;
        if short < 0.99 * dt {
            summary.warnings.push(format!(
                "the fine model's time step was shortened from {dt:.4e} s to {short:.4e} s so that \
                 the output times (every {interval:.3e} s) fall on steps ({:.0} % more steps): \
                 an output interval that is a multiple of the step avoids it",
                100.0 * (dt / short - 1.0)
            ));
        }
        Frames {
            floor: BalanceFloor::new(0.0, 0.0, 1.0, 1),
            mass: 0.0,
            load_terms: 0.0,
            duration,
            dt: short,
            every,
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn run_dynamic(
    model: &mut FineModel,
    state: &mut ModelState,
    motions: &[Option<SupportMotion>; 2],
    frames: &Frames,
    (rot, plane): (UnitQuaternion<f64>, Option<Vector3<f64>>),
    (dir, vtk, output): (&Path, bool, &Output),
    summary: &mut RunSummary,
    progress: &mut dyn FnMut(f64),
) -> Result<(), Stop> {
    let moving = motions.iter().any(Option::is_some);
    let mut extra = vec!["kinetic_rotation", "contact", "friction_stored"];
    if moving {
        extra.push("support_work");
    }
    let mut files = FrameFiles::create(dir, vtk, &extra).map_err(Stop::output)?;
    let mut probes = ProbeFiles::create(dir, &output.probes).map_err(Stop::output)?;
    let mut envelopes = Envelopes::new(output.range_window);
    let ends = [fine::End::Start, fine::End::End];
    // Support displacement (model axes) at time t.
    let place = |m: usize, t: f64| -> Vector3<f64> {
        motions[m].as_ref().map_or(Vector3::zeros(), |mo| {
            rot.inverse() * Vector3::from(mo.displacement(t))
        })
    };
    let core = &model.wires[0].chain;
    let last = core.len() - 1;
    let tip_offset = core.segments[last].end_offset();
    let (every, dt) = (frames.every, frames.dt);
    let steps = ((frames.duration / dt) * (1.0 - 1e-12)).ceil() as usize;
    summary.time_step = Some(dt);
    let mut int = Integrator::new(model, state, dt);
    let e0 = int.energies(model, state);
    let (mut err, mut max_kinetic) = (0.0f64, 0.0f64);
    // Largest stored energy (J): the scale of the round-off of its evaluation.
    let mut max_stored = (e0.spring + e0.contact + e0.friction_stored).abs();
    let mut path = Travel::start(
        0.0,
        e0.kinetic_translation + e0.kinetic_rotation,
        frames.mass,
    );
    // Work of the moving supports (J): minus the force on the ground times its displacement,
    // trapezoidal over each step.
    let mut support_work = 0.0;
    let mut ground_force = ends.map(|e| model.support_force(state, e));
    let mut write = |t: f64,
                     model: &FineModel,
                     state: &ModelState,
                     e: &fine::Energies,
                     work: f64|
     -> std::io::Result<()> {
        let x = rot * state.wires[0].poses[last].point(&tip_offset);
        let v = rot * fine::dynamics::point_velocity(model, state, 0, last, &tip_offset);
        let energies = [
            e.kinetic_translation + e.kinetic_rotation,
            e.gravity,
            e.spring + e.contact + e.friction_stored,
            e.friction_work,
            e.balance() - work,
            e.kinetic_rotation,
            e.contact,
            e.friction_stored,
            work,
        ];
        let n = if moving { 9 } else { 8 };
        let (stations, loads) = measure(model, state, rot, plane);
        files.write(t, x.into(), v.into(), &energies[..n], || {
            vtk_frame(&stations)
        })?;
        let other = |e: String| std::io::Error::other(e);
        probes
            .write(t, |s| {
                probe_sample(model, state, &loads, &stations, rot, s, true)
            })
            .map_err(other)?;
        envelopes.add(t, &stations).map_err(other)
    };
    write(0.0, model, state, &e0, 0.0)
        .map_err(|e| Stop::output(format!("writing results: {e}")))?;
    let clock = Stopwatch::start();
    let mut failure = None;
    // The state of the last output frame: what the files keep if the run blows up.
    let (mut last_good, mut last_t) = (state.clone(), 0.0);
    for k in 1..=steps {
        // The ground takes its place at the step's end before the drift's loads.
        let mut shift = [Vector3::zeros(); 2];
        for (m, end) in ends.into_iter().enumerate() {
            if motions[m].is_some() {
                let (a, b) = (place(m, int.time), place(m, int.time + int.dt));
                model.move_support(end, b);
                shift[m] = b - a;
                support_work -= 0.5 * ground_force[m].dot(&shift[m]);
            }
        }
        int.step(model, state);
        for (m, end) in ends.into_iter().enumerate() {
            if motions[m].is_some() {
                ground_force[m] = model.support_force(state, end);
                support_work -= 0.5 * ground_force[m].dot(&shift[m]);
            }
        }
        let e = int.energies(model, state);
        if !e.balance().is_finite() {
            failure = Some(non_finite(model, state, k, int.time));
            break;
        }
        err = err.max((e.balance() - support_work - e0.balance()).abs());
        max_kinetic = max_kinetic.max(e.kinetic_translation + e.kinetic_rotation);
        max_stored = max_stored.max((e.spring + e.contact + e.friction_stored).abs());
        path.advance(
            int.time,
            e.kinetic_translation + e.kinetic_rotation,
            frames.mass,
        );
        if k % every == 0 || k == steps {
            write(int.time, model, state, &e, support_work)
                .map_err(|e| Stop::output(format!("writing results: {e}")))?;
            last_good.clone_from(state);
            last_t = int.time;
            progress(int.time / frames.duration);
        }
    }
    if failure.is_some() {
        *state = last_good;
        summary.warnings.push(format!(
            "centerline.csv and contacts.csv hold the last output frame, t = {last_t:.6e} s"
        ));
    }
    clock.record(summary);
    summary.steps = int.steps as usize;
    let blanks = files.blanks();
    files.finish().map_err(Stop::output)?;
    if blanks > 0 {
        summary.warnings.push(format!(
            "tip.csv, energy.csv: {blanks} non-finite values left empty"
        ));
    }
    let blanks = probes.blanks();
    probes.finish().map_err(Stop::output)?;
    if blanks > 0 {
        summary.warnings.push(format!(
            "probe files: {blanks} non-finite values left empty"
        ));
    }
    super::beam::finish_range(&envelopes, dir, summary)?;
    let relative = err / max_kinetic.max(f64::MIN_POSITIVE);
    summary.energy_balance_error = Some(err);
    summary.energy_balance_relative = Some(relative);
    summary.dissipated = Some(state.friction_work);
    summary.built.push(format!(
        "explicit symplectic kick-drift-kick, {} steps of {:.3e} s",
        int.steps, dt
    ));
    if let Some(f) = failure {
        return Err(Stop::new(Failure::NonFinite, f));
    }
    let floor = frames.floor.work(path.distance)
        + frames.floor.evaluation(max_stored)
        + round_off::OPERATIONS * f64::EPSILON * frames.load_terms;
    if balance_open(err, max_kinetic, floor) {
        summary.warnings.push(format!(
            "energy balance not closed: the error {err:.3e} J is {relative:.2e} of the largest \
             kinetic energy; the explicit step {dt:.3e} s is at the stability limit, so an open \
             balance points at contacts switching faster than the step resolves (or a blow-up \
             in the making): check the contact states and the motion"
        ));
    }
    Ok(())
}

/// Diagnosis of a non-finite state: the first segment with a non-finite pose or momentum.
fn non_finite(model: &FineModel, state: &ModelState, step: usize, t: f64) -> String {
    for (w, ws) in state.wires.iter().enumerate() {
        for k in 0..ws.poses.len() {
            let p = &ws.poses[k];
            let bad = if !p.position.iter().all(|v| v.is_finite()) {
                Some("position")
            } else if !p.rotation.coords.iter().all(|v| v.is_finite()) {
                Some("rotation")
            } else if !ws.velocities[k].iter().all(|v| v.is_finite()) {
                Some("velocity")
            } else if !ws.angular_momenta[k].iter().all(|v| v.is_finite()) {
                Some("angular momentum")
            } else {
                None
            };
            if let Some(q) = bad {
                let x = model.wires[w].chain.rest[k].position.x;
                return format!(
                    "non-finite {q} at step {step} (t = {t:.6e} s), wire {w} segment {k} \
                     (x = {x:.4e} m at rest)"
                );
            }
        }
    }
    format!("non-finite energy at step {step} (t = {t:.6e} s)")
}

/// Writes `centerline.csv` (measured along the core) and `contacts.csv` for `state`, and with
/// `vtk` the state as the one frame of a static run. `plane`: the scene's Z in the model's
/// axes for a planar scene, whose curvatures and moments are then signed about it (the sign
/// convention of the beams' files); in 3D they are magnitudes.
fn write_state(
    model: &FineModel,
    state: &ModelState,
    (rot, plane): (UnitQuaternion<f64>, Option<Vector3<f64>>),
    dir: &Path,
    vtk: bool,
    probes: &[f64],
    summary: &mut RunSummary,
) -> Result<(), String> {
    let mut loads = model.load_buffers();
    model.compute_loads(state, 1.0, &mut loads);
    if !probes.is_empty() {
        let stations = stations_of(&measure_along(model, state, &loads, plane), rot);
        let mut files = ProbeFiles::create(dir, probes)?;
        files.write(0.0, |s| {
            probe_sample(model, state, &loads, &stations, rot, s, false)
        })?;
        let blanks = files.blanks();
        files.finish()?;
        if blanks > 0 {
            summary.warnings.push(format!(
                "probe files: {blanks} non-finite values left empty"
            ));
        }
    }
    let p = dir.join("centerline.csv");
    let e = |e: std::io::Error| format!("writing {}: {e}", p.display());
    let mut c = Csv::create(&p, &CENTERLINE_COLUMNS).map_err(e)?;
    let rows = measure_along(model, state, &loads, plane);
    let stiffness = secant_along(&rows);
    for (row, k) in rows.iter().zip(&stiffness) {
        let x = rot * row.position;
        // M / kappa is undefined where the strand is straight everywhere: left empty.
        c.text_row(&[
            number(row.s),
            number(x.x),
            number(x.y),
            number(x.z),
            number(row.curvature),
            number(row.tension),
            k.map_or(String::new(), number),
            number(row.moment),
        ])
        .map_err(e)?;
    }
    c.finish().map_err(e)?;
    if vtk {
        let points: Vec<[f64; 3]> = rows.iter().map(|r| (rot * r.position).into()).collect();
        let column = |f: fn(&Station) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
        write_static_vtk(
            dir,
            "fine model, static",
            &points,
            &[
                ("curvature", column(|r| r.curvature)),
                ("tension", column(|r| r.tension)),
                ("moment", column(|r| r.moment)),
            ],
        )?;
    }
    let pc = dir.join("contacts.csv");
    let ec = |e: std::io::Error| format!("writing {}: {e}", pc.display());
    let mut cc = Csv::create(
        &pc,
        &[
            "s",
            "wire",
            "state",
            "normal_force",
            "pressure",
            "friction_force",
            "layer",
            "partner_wire",
            "partner_layer",
            "kind",
        ],
    )
    .map_err(ec)?;
    for (w, (wire, l)) in model.wires.iter().zip(&loads).enumerate().skip(1) {
        for (cp, cl) in wire.contacts.iter().zip(&l.contacts) {
            let seg = wire.chain.segments[cp.segment];
            let s = wire.chain.rest[cp.segment].point(&cp.offset).x;
            // Length of helical wire the contact point stands for (m).
            let per_segment = wire
                .contacts
                .iter()
                .filter(|o| o.segment == cp.segment)
                .count();
            let share = seg.length / per_segment as f64;
            let state = match cl.state {
                ContactState::Open => "open",
                ContactState::Stick => "stick",
                ContactState::Slip => "slip",
            };
            cc.text_row(&[
                number(s),
                w.to_string(),
                state.to_string(),
                number(cl.normal_force),
                number(cl.normal_force / share),
                number(cl.tangential_force.norm()),
                wire.layer.to_string(),
                "0".to_string(),
                "0".to_string(),
                "core".to_string(),
            ])
            .map_err(ec)?;
        }
        // Wire-to-wire links: the closed ones (a link is a segment against a whole partner
        // wire; most are apart at any time), at the rest x of their contact point.
        let nc = wire.contacts.len();
        for (lk, cl) in wire.links.iter().zip(&l.contacts[nc..]) {
            if cl.state == ContactState::Open {
                continue;
            }
            let s = wire.chain.rest[lk.segment].point(&cl.history.on_wire).x;
            let state = if cl.state == ContactState::Stick {
                "stick"
            } else {
                "slip"
            };
            cc.text_row(&[
                number(s),
                w.to_string(),
                state.to_string(),
                number(cl.normal_force),
                number(cl.normal_force / lk.length),
                number(cl.tangential_force.norm()),
                wire.layer.to_string(),
                lk.partner.to_string(),
                model.wires[lk.partner].layer.to_string(),
                lk.kind.name().to_string(),
            ])
            .map_err(ec)?;
        }
    }
    cc.finish().map_err(ec)
}

/// The measured stations along the core in scene axes (with their secant stiffness) and the
/// loads they were measured from.
fn measure(
    model: &FineModel,
    state: &ModelState,
    rot: UnitQuaternion<f64>,
    plane: Option<Vector3<f64>>,
) -> (Vec<along::Station>, Vec<WireLoads>) {
    let mut loads = model.load_buffers();
    model.compute_loads(state, 1.0, &mut loads);
    let rows = measure_along(model, state, &loads, plane);
    (stations_of(&rows, rot), loads)
}

/// The stations as probes and range envelopes read them, positions in scene axes.
fn stations_of(rows: &[Station], rot: UnitQuaternion<f64>) -> Vec<along::Station> {
    rows.iter()
        .zip(secant_along(rows))
        .map(|(r, k)| along::Station {
            s: r.s,
            position: (rot * r.position).into(),
            curvature: r.curvature,
            moment: r.moment,
            tension: r.tension,
            stiffness: k,
        })
        .collect()
}

/// A dynamic frame's VTK polyline: the core's centreline nodes with curvature, tension and
/// moment (the stiffness, undefined on a straight strand, is left out).
fn vtk_frame(stations: &[along::Station]) -> VtkFrame {
    let column = |f: fn(&along::Station) -> f64| stations.iter().map(f).collect::<Vec<f64>>();
    VtkFrame {
        points: stations.iter().map(|p| p.position).collect(),
        scalars: vec![
            ("curvature", column(|p| p.curvature)),
            ("tension", column(|p| p.tension)),
            ("moment", column(|p| p.moment)),
        ],
    }
}

/// The fine model at probe `s` (m): position, curvature, moment and tension interpolated
/// linearly between the measured stations around s; the velocity (with `moving`, else zero)
/// of the core's axis at s, on the segment whose rest span is nearest; for each helical
/// wire the state of its contact point nearest s (open contacts count as neither).
fn probe_sample(
    model: &FineModel,
    state: &ModelState,
    loads: &[WireLoads],
    stations: &[along::Station],
    rot: UnitQuaternion<f64>,
    s: f64,
    moving: bool,
) -> ProbeSample {
    let p = along::interpolate(stations, s);
    let core = &model.wires[0].chain;
    let velocity = if moving {
        let k = (0..core.len())
            .min_by(|&a, &b| {
                let d = |k: usize| (core.rest[k].position.x - s).abs();
                d(a).total_cmp(&d(b))
            })
            .unwrap_or(0);
        let half = 0.5 * core.segments[k].length;
        let off = Vector3::new((s - core.rest[k].position.x).clamp(-half, half), 0.0, 0.0);
        (rot * fine::dynamics::point_velocity(model, state, 0, k, &off)).into()
    } else {
        [0.0; 3]
    };
    let (mut sticking, mut slipping) = (0, 0);
    for (wire, l) in model.wires.iter().zip(loads).skip(1) {
        let nearest = wire
            .contacts
            .iter()
            .zip(&l.contacts)
            .min_by(|(a, _), (b, _)| {
                let d = |c: &fine::ContactPoint| {
                    (wire.chain.rest[c.segment].point(&c.offset).x - s).abs()
                };
                d(a).total_cmp(&d(b))
            });
        match nearest.map(|(_, cl)| cl.state) {
            Some(ContactState::Stick) => sticking += 1,
            Some(ContactState::Slip) => slipping += 1,
            _ => {}
        }
    }
    ProbeSample {
        position: p.position,
        velocity,
        curvature: p.curvature,
        moment: p.moment,
        tension: p.tension,
        sticking,
        slipping,
    }
}

/// One measured station along the core.
struct Station {
    s: f64,
    position: Vector3<f64>,
    curvature: f64,
    tension: f64,
    moment: f64,
}

/// M / kappa at every station (N m^2); where the curvature is zero (a free or pinned end), its
/// limit along the strand: the ratio at the nearest station with curvature. `None` where no
/// station is bent.
fn secant_along(rows: &[Station]) -> Vec<Option<f64>> {
    let ratio = |r: &Station| (r.curvature != 0.0).then(|| r.moment / r.curvature);
    (0..rows.len())
        .map(|i| {
            ratio(&rows[i]).or_else(|| {
                (1..rows.len()).find_map(|d| {
                    let near = [i.checked_sub(d), Some(i + d).filter(|&j| j < rows.len())];
                    near.into_iter().flatten().find_map(|j| ratio(&rows[j]))
                })
            })
        })
        .collect()
}

/// Curvature, tension and bending moment at the core's centreline nodes (module docs);
/// curvature and moment signed about `plane` if given, else magnitudes.
fn measure_along(
    model: &FineModel,
    state: &ModelState,
    loads: &[WireLoads],
    plane: Option<Vector3<f64>>,
) -> Vec<Station> {
    // The bending part of a rotation vector in the axes of the segment at `pose`, in the
    // model's axes; its length is the bending angle.
    let bend = |theta: Vector3<f64>, pose: &fine::Pose| {
        pose.rotation * Vector3::new(0.0, theta.y, theta.z)
    };
    let signed = |v: Vector3<f64>| match plane {
        Some(z) => v.dot(&z),
        None => v.norm(),
    };
    let core = &model.wires[0];
    let poses = &state.wires[0].poses;
    let nodes = core.chain.centreline(poses);
    let rest_nodes = core.chain.centreline(&core.chain.rest);
    let n = core.chain.len();
    let mut out = Vec::with_capacity(n + 1);
    for (i, node) in nodes.iter().enumerate() {
        let s = rest_nodes[i].x;
        // Tangent: the neighbouring segments' axes.
        let t = if i == 0 {
            poses[0].tangent()
        } else if i == n {
            poses[n - 1].tangent()
        } else {
            (poses[i - 1].tangent() + poses[i].tangent()).normalize()
        };
        let curvature = if i == 0 || i == n {
            let seg = if i == 0 { 0 } else { n - 1 };
            core.anchors
                .iter()
                .find(|a| a.segment == seg && a.joint.stiffness.rotational.y > 0.0)
                .map_or(0.0, |a| {
                    // The anchor turns from the ground to the segment at x = 0, from the
                    // segment to the ground at x = L.
                    let turn = bend(a.joint.rotation_strain(&a.ground, &poses[seg]), &poses[seg]);
                    let turn = if i == 0 { turn } else { -turn };
                    signed(turn) / (0.5 * core.chain.segments[seg].length)
                })
        } else {
            let j = &core.chain.joints[i - 1];
            let l = (poses[i].position - poses[i - 1].position).norm();
            signed(bend(j.rotation_strain(&poses[i - 1], &poses[i]), &poses[i])) / l
        };
        // Resultant on the far part (every segment whose rest centre lies beyond s).
        let (mut force, mut moment) = (Vector3::zeros(), Vector3::zeros());
        for ((w, ws), l) in model.wires.iter().zip(&state.wires).zip(loads) {
            for (k, seg) in w.chain.segments.iter().enumerate() {
                if w.chain.rest[k].position.x <= s {
                    continue;
                }
                let f = l.forces[k] - model.gravity * seg.mass;
                let r = ws.poses[k].position - node;
                force += f;
                moment += l.torques[k] + r.cross(&f);
            }
        }
        // `force`, `moment`: the near part's action on the far part (the far part's own
        // internal loads cancel in the sums).
        // The moment that bends the near part's end; with the curvature's sign convention the
        // hanging cantilever's is negative, like its curvature.
        let bending = moment - t * moment.dot(&t);
        out.push(Station {
            s,
            position: *node,
            curvature,
            tension: -force.dot(&t),
            moment: signed(-bending),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::{BeamModelKind, build_beam};

    /// The fine model lays wire 1 (phase 0 at x = 0) along the scene's phase reference, where
    /// the equivalent model's section frame puts phase 0, for any initial direction and with
    /// the default or a given reference.
    #[test]
    fn the_same_wire_sits_at_the_same_place_in_both_models() {
        let text = include_str!("../../../../validation/paper-fig7-g8.json");
        let mut file: crate::format::SceneFile = serde_json::from_str(text).unwrap();
        let h = 0.5f64.sqrt();
        for (d, r) in [
            ([1.0, 0.0, 0.0], None),
            ([0.0, 0.0, 1.0], None),
            ([0.0, 0.0, -1.0], None),
            ([-1.0, 0.0, 0.0], None),
            ([0.0, h, h], None),
            ([0.3, -0.2, 0.93], None),
            ([0.3, -0.2, 0.93], Some([1.0, 2.0, 0.0])),
            ([-1.0, 1e-9, 0.0], Some([0.0, 1.0, 1.0])),
        ] {
            let init = file.initial.get_or_insert(crate::format::InitialFile {
                direction: None,
                phase_reference: None,
                velocity: None,
                angular_velocity: None,
            });
            init.direction = Some(d);
            init.phase_reference = r;
            let scene = Scene::from_file(file.clone()).unwrap();
            let rot = frame(scene.direction, scene.phase_reference);
            let dir = Vector3::from(scene.direction);
            let reference = Vector3::from(scene.phase_reference);
            assert!((rot * Vector3::x() - dir).norm() < 1e-14, "{d:?}");
            assert!((rot * Vector3::z() - reference).norm() < 1e-14, "{d:?}");
            // The fine model's wire 1 at x = 0, relative to the core, in scene axes.
            let layer = scene.strand.layers().first().unwrap();
            let chain = strand_fine::Chain::helix(layer, 0, scene.strand.length(), 40);
            let start = chain.segments[0].start_offset();
            let wire = rot * chain.rest[0].point(&start);
            let expect = reference * layer.radius;
            assert!(
                (wire - expect).norm() < 1e-12,
                "{d:?}: {wire:?} vs {expect:?}"
            );
            // The equivalent model's phase axis at the first bending point.
            let beam = build_beam(&scene, BeamModelKind::Equivalent).unwrap();
            if let Some([_, _, ez]) = beam.point_frame(&beam.initial_state(), 0) {
                assert!((ez - reference).norm() < 1e-14, "{d:?}");
            } else {
                assert_eq!(
                    scene.phase_reference,
                    [0.0, 0.0, 1.0],
                    "planar: phases from Z"
                );
            }
        }
    }
}
