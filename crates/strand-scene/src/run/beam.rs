//! Runs the beam models of a scene (equivalent and traditional, strand-ancf) and writes their
//! result files.

use super::stopwatch::Stopwatch;
use std::path::Path;

use strand_ancf::band::BandMatrix;
use strand_ancf::beam::{
    Beam, BeamError, BeamSpec, ElementKind, PointLoad, PointState, Support as BeamSupport,
    SupportMotion,
};
use strand_ancf::dynamics::{DynamicError, DynamicOptions, Scheme, run_dynamic_from, stable_step};
use strand_ancf::initial::InitialState;
use strand_ancf::statics::{StaticError, StaticOptions, solve_static};
use strand_core::{LawKind, SectionLaw};

use crate::along;
use crate::output::FrameFiles;
use crate::probe::{ProbeFiles, ProbeSample};
use crate::range::Envelopes;
use crate::scene::{Analysis, BeamModel, End, IntegratorKind, Output, Scene, SupportKind};

use super::beam_state;
use super::budget;
use super::record::{
    Failure, RunError, RunOptions, RunSummary, Stop, balance_open, finish, io_err,
};

fn beam_support(scene: &Scene, end: End) -> Option<BeamSupport> {
    scene
        .supports
        .iter()
        .find(|s| s.at == end)
        .map(|s| match s.kind {
            SupportKind::Clamped => BeamSupport::Clamped,
            SupportKind::Pinned => BeamSupport::Pinned,
        })
}

/// A beam model of a scene: the equivalent beam with the scene's law, or the traditional one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BeamModelKind {
    /// `models.equivalent`.
    Equivalent,
    /// `models.traditional` (the `constant` law).
    Traditional,
}

impl BeamModelKind {
    /// The model's name in scenes and result folders.
    pub fn name(self) -> &'static str {
        match self {
            BeamModelKind::Equivalent => "equivalent",
            BeamModelKind::Traditional => "traditional",
        }
    }
}

/// The beam `run_scene` builds for `which` model of `scene` (supports, element kind, law,
/// mass), for callers that need the strand-ancf API directly (e.g. stability studies).
pub fn build_beam(scene: &Scene, which: BeamModelKind) -> Result<Beam, RunError> {
    let (model, kind) = match which {
        BeamModelKind::Equivalent => (scene.models.equivalent.as_ref(), scene.law),
        BeamModelKind::Traditional => (scene.models.traditional.as_ref(), LawKind::Constant),
    };
    let model = model.ok_or_else(|| RunError::Setup {
        model: which.name().into(),
        message: "the scene does not name this model".into(),
    })?;
    beam_of(scene, which.name(), model, kind)
}

/// The dynamic options `run_scene` uses for `scene`; `None` for a static analysis.
pub fn dynamic_options(scene: &Scene) -> Option<DynamicOptions> {
    let Analysis::Dynamic(dy) = scene.analysis else {
        return None;
    };
    let scheme = match dy.integrator {
        IntegratorKind::Verlet => Scheme::Verlet { step: dy.time_step },
        IntegratorKind::GeneralizedAlpha => Scheme::GeneralizedAlpha {
            step: dy
                .time_step
                .expect("validated: generalized-alpha has a step"),
            spectral_radius: dy.spectral_radius,
        },
    };
    Some(DynamicOptions::new(dy.duration, scheme, dy.output_interval))
}

/// The motion table of the support at `end`, if it moves.
fn beam_motion(scene: &Scene, end: End) -> Result<Option<SupportMotion>, String> {
    let Some(rows) = scene
        .supports
        .iter()
        .find(|s| s.at == end)
        .and_then(|s| s.motion.as_ref())
    else {
        return Ok(None);
    };
    SupportMotion::new(rows).map(Some)
}

fn beam_of(scene: &Scene, name: &str, model: &BeamModel, kind: LawKind) -> Result<Beam, RunError> {
    let setup = |message: String| RunError::Setup {
        model: name.to_string(),
        message,
    };
    let strand = &scene.strand;
    let law = match (kind, model.bending_stiffness, model.axial_stiffness) {
        (LawKind::Constant, ei, ea) if ei.is_some() || ea.is_some() => {
            let envelope = strand.traditional();
            SectionLaw::constant(
                strand,
                ei.unwrap_or(envelope.bending_stiffness),
                ea.unwrap_or(envelope.axial_stiffness),
            )
        }
        _ => SectionLaw::with_options(strand, kind, &scene.section),
    };
    let mass = model.mass_per_length.unwrap_or(strand.mass_per_length());
    let spec = BeamSpec {
        elements: model.elements,
        bending_points: model.integration_points,
        mass_per_length: mass,
        element: if scene.is_planar() {
            ElementKind::Planar
        } else {
            ElementKind::Spatial
        },
        direction: scene.direction,
        gravity: scene.gravity,
        start: beam_support(scene, End::Start),
        end: beam_support(scene, End::End),
        phase_reference: Some(scene.phase_reference),
        point_loads: scene
            .point_forces
            .iter()
            .map(|p| PointLoad {
                s: p.s,
                force: p.force,
            })
            .collect(),
        start_motion: beam_motion(scene, End::Start).map_err(setup)?,
        end_motion: beam_motion(scene, End::End).map_err(setup)?,
    };
    Beam::new(spec, law).map_err(|e| RunError::Setup {
        model: name.to_string(),
        message: e.to_string(),
    })
}

pub(crate) fn run_beam(
    scene: &Scene,
    name: &str,
    model: &BeamModel,
    kind: LawKind,
    opts: &RunOptions,
    progress: &mut dyn FnMut(&str, f64),
) -> Result<RunSummary, RunError> {
    let dir = opts.out.join(name);
    let analysis = match scene.analysis {
        Analysis::Static { .. } => "static",
        Analysis::Dynamic(_) => "dynamic",
    };
    let mut summary = RunSummary::start(&scene.name, name, kind.name(), analysis);
    summary.elements = model.elements;
    std::fs::create_dir_all(&dir).map_err(io_err(&dir))?;
    let beam = match beam_of(scene, name, model, kind) {
        Ok(b) => b,
        Err(e) => {
            let message = match e {
                RunError::Setup { message, .. } => message,
                other => other.to_string(),
            };
            return finish(summary, Err(Stop::new(Failure::Setup, message)), &dir);
        }
    };
    let law = beam.law();
    let element = match beam.spec().element {
        ElementKind::Planar => "planar ANCF cable beam in the XY plane (4 coordinates per node)",
        ElementKind::Spatial => {
            "spatial ANCF cable beam (6 coordinates per node), section frames carried without \
             spin about the tangent, committed with every accepted step"
        }
    };
    summary.built.push(format!(
        "{element}, {} elements of {:.4e} m, {} bending points and 2 axial points per element",
        model.elements,
        beam.element_length(),
        beam.bending_points()
    ));
    summary.built.push(format!("section law `{kind}`"));
    if beam.spec().element == ElementKind::Spatial && law.sliders() > 0 {
        let r = scene.phase_reference;
        summary.built.push(format!(
            "wire phases measured from ({:.4}, {:.4}, {:.4}) at x = 0",
            r[0], r[1], r[2]
        ));
    }
    if !scene.point_forces.is_empty() {
        summary.built.push(format!(
            "{} point force(s), constant",
            scene.point_forces.len()
        ));
    }
    if beam.has_moving_supports() {
        summary.built.push(
            "moving supports: the held position follows its table (statics: the last row with \
             the load steps)"
                .into(),
        );
    }
    if law.sliders() > 0 {
        summary.built.push(format!(
            "{} friction sliders per bending point",
            law.sliders()
        ));
    }
    summary.dofs = beam.dofs();
    summary.integration_points = beam.bending_points();
    if kind == LawKind::Paper {
        summary.warnings.push(
            "the `paper` law's moment drops at each switch (non-monotone, eq. (23)); Newton may \
             fail to converge"
                .into(),
        );
    }
    let result = match scene.analysis {
        Analysis::Static { load_steps } => {
            let files = Files {
                dir: &dir,
                vtk: opts.vtk,
                output: &scene.output,
            };
            run_static(&beam, load_steps, &files, &mut summary, &mut |f| {
                progress(name, f)
            })
        }
        Analysis::Dynamic(_) => {
            if matches!(kind, LawKind::Continuous | LawKind::Paper) {
                summary.warnings.push(format!(
                    "the `{kind}` law is not a potential (its moment depends on the tension): in \
                     dynamics its non-potential work can feed energy into axial-bending \
                     vibrations; `hysteretic` is the energetically consistent law"
                ));
            }
            let o = dynamic_options(scene).expect("a dynamic analysis");
            budget(&beam, &o, scene.max_steps, &mut summary).and_then(|o| {
                let init = InitialState::rigid(&beam, scene.velocity, scene.angular_velocity)
                    .map_err(|e| {
                        Stop::new(failure_of_beam(&e), format!("the initial state: {e}"))
                    })?;
                if init.discarded > 0.0 {
                    summary.warnings.push(format!(
                        "the initial velocity field moves a fixed support (up to {:.3e} m/s): \
                         the support holds those coordinates at rest",
                        init.discarded
                    ));
                }
                let files = Files {
                    dir: &dir,
                    vtk: opts.vtk,
                    output: &scene.output,
                };
                run_dynamics(&beam, &o, &init, &files, &mut summary, &mut |f| {
                    progress(name, f)
                })
            })
        }
    };
    finish(summary, result, &dir)
}

/// The dynamic options with the step the run will take, once the step count is within
/// `max_steps` (refused otherwise, with the count and the time it would take). Verlet without
/// a step takes 0.9 of the estimated stable step, estimated here once.
fn budget(
    beam: &Beam,
    opts: &DynamicOptions,
    max_steps: usize,
    summary: &mut RunSummary,
) -> Result<DynamicOptions, Stop> {
    let mut opts = *opts;
    let (step, implicit) = match opts.scheme {
        Scheme::Verlet { step: Some(h) } => (h, false),
        Scheme::Verlet { step: None } => {
            let stable = stable_step(beam).map_err(|e| {
                Stop::new(
                    failure_of_beam(&e),
                    format!("estimating the stable step: {e}"),
                )
            })?;
            summary.stable_time_step = Some(stable);
            opts.scheme = Scheme::Verlet {
                step: Some(0.9 * stable),
            };
            (0.9 * stable, false)
        }
        Scheme::GeneralizedAlpha { step, .. } => (step, true),
    };
    let steps = budget::steps_of(opts.duration, step);
    if steps <= max_steps as f64 {
        return Ok(opts);
    }
    // The cost of a step: one force evaluation (Verlet), or 2 to 10 Newton iterations, each a
    // force evaluation and at times a tangent (generalized-alpha).
    let mut q = beam.reference().to_vec();
    q.iter_mut().for_each(|x| *x *= 1.0 + 1e-9);
    let slip = beam.initial_state();
    let mut trial = slip.clone();
    let mut force = vec![0.0; beam.coords()];
    let mut k = BandMatrix::zeros(beam.dofs(), beam.bandwidth(), beam.bandwidth());
    let f = budget::time_of(|| {
        let _ = beam.internal(&q, &slip, &mut trial, &mut force, None, None);
    });
    let (per_step, cost) = if implicit {
        let t = budget::time_of(|| {
            let _ = beam.internal(&q, &slip, &mut trial, &mut force, Some(&mut k), None);
        });
        (
            (2.0 * f, 10.0 * t),
            format!(
                "2 to 10 Newton iterations a step ({} a force evaluation, {} with the tangent, \
                 timed now)",
                budget::duration(f),
                budget::duration(t)
            ),
        )
    } else {
        (
            (f, f),
            format!(
                "{} a step (a force evaluation, timed now)",
                budget::duration(f)
            ),
        )
    };
    budget::check(steps, step, max_steps, per_step, &cost).map(|()| opts)
}

/// The reason a beam evaluation failed.
fn failure_of_beam(e: &BeamError) -> Failure {
    match e {
        BeamError::NonFinite { .. } => Failure::NonFinite,
        BeamError::Setup(_) => Failure::Setup,
        BeamError::Kinematics { .. } => Failure::NoConvergence,
    }
}

fn failure_of_static(e: &StaticError) -> Failure {
    match e {
        StaticError::Stalled { .. } | StaticError::Budget { .. } => Failure::NoConvergence,
        StaticError::Beam(b) => failure_of_beam(b),
    }
}

fn failure_of_dynamic(e: &DynamicError) -> Failure {
    match e {
        DynamicError::Beam { source, .. } => failure_of_beam(source),
        DynamicError::Newton { .. } | DynamicError::Singular(_) => Failure::NoConvergence,
        DynamicError::Unstable { .. } | DynamicError::Diverged { .. } => Failure::UnstableStep,
        DynamicError::Setup(_) => Failure::Setup,
    }
}

/// Where a beam's run writes and what it writes beyond the standard files.
struct Files<'a> {
    dir: &'a Path,
    vtk: bool,
    output: &'a Output,
}

/// The strand at probe `s` (m) in the state `(q, slip)` with velocities `v` (m/s, `None`: at
/// rest) whose rows along s are `rows`: position and velocity from the elements' shape
/// functions at s; curvature, moment and tension interpolated linearly between the rows
/// around s; the wire states of the row nearest s.
fn probe_sample(
    beam: &Beam,
    (q, v, slip): (&[f64], Option<&[f64]>, &[f64]),
    rows: &[beam_state::Row],
    stations: &[along::Station],
    s: f64,
) -> ProbeSample {
    let p = along::interpolate(stations, s);
    let (i, w) = along::bracket(&stations.iter().map(|p| p.s).collect::<Vec<_>>(), s);
    let near = if w > 0.5 { i + 1 } else { i }.min(rows.len() - 1);
    let (sticking, slipping) = beam_state::wire_counts(beam, &rows[near], slip);
    ProbeSample {
        position: beam.sample(q, s).0,
        velocity: v.map_or([0.0; 3], |v| beam.sample(v, s).0),
        curvature: p.curvature,
        moment: p.moment,
        tension: p.tension,
        sticking,
        slipping,
    }
}

/// Writes `centerline.csv` and `wires.csv` (and with `vtk` the static frame, with `probes`
/// the one row of each probe file) for the state `(q, slip, points)`; records the tip and any
/// non-finite values left empty.
fn write_state(
    beam: &Beam,
    state: (&[f64], &[f64], &[PointState]),
    dir: &Path,
    vtk: Option<&str>,
    probes: Option<&[f64]>,
    summary: &mut RunSummary,
) -> Result<(), Stop> {
    let (q, slip, points) = state;
    summary.tip = Some(beam.sample(q, beam.length()).0);
    let rows = beam_state::rows(beam, q, slip, points);
    let blanks = beam_state::write(beam, &rows, slip, dir).map_err(Stop::output)?;
    if blanks > 0 {
        summary.warnings.push(format!(
            "centerline.csv: {blanks} non-finite values left empty"
        ));
    }
    if let Some(title) = vtk {
        beam_state::write_vtk(&rows, dir, title).map_err(Stop::output)?;
    }
    if let Some(probes) = probes.filter(|p| !p.is_empty() && !rows.is_empty()) {
        let stations = beam_state::stations(&rows);
        let mut files = ProbeFiles::create(dir, probes).map_err(Stop::output)?;
        files
            .write(0.0, |s| {
                probe_sample(beam, (q, None, slip), &rows, &stations, s)
            })
            .map_err(Stop::output)?;
        let blanks = files.blanks();
        files.finish().map_err(Stop::output)?;
        if blanks > 0 {
            summary.warnings.push(format!(
                "probe files: {blanks} non-finite values left empty"
            ));
        }
    }
    Ok(())
}

fn run_static(
    beam: &Beam,
    load_steps: usize,
    files: &Files,
    summary: &mut RunSummary,
    progress: &mut dyn FnMut(f64),
) -> Result<(), Stop> {
    let opts = StaticOptions {
        load_steps,
        ..StaticOptions::default()
    };
    let clock = Stopwatch::start();
    let sol = solve_static(beam, &opts, progress);
    clock.record(summary);
    let title = format!("{} static", summary.scene);
    let vtk = files.vtk.then_some(title.as_str());
    let (dir, probes) = (files.dir, Some(&files.output.probes[..]));
    let sol = match sol {
        Ok(sol) => sol,
        Err(e) => {
            let stop = Stop::new(failure_of_static(&e), e.to_string());
            // The last converged load step's state, for the files.
            if let StaticError::Stalled {
                last: Some(last),
                reached,
                ..
            }
            | StaticError::Budget {
                last: Some(last),
                reached,
                ..
            } = &e
            {
                summary.steps = last.steps;
                summary.newton_iterations = last.iterations;
                summary.warnings.push(format!(
                    "the files hold the last equilibrium found, at load fraction {reached:.6}"
                ));
                let last = (&last.q[..], &last.slip[..], &last.points[..]);
                write_state(beam, last, dir, vtk, probes, summary)?;
            }
            return Err(stop);
        }
    };
    summary.steps = sol.steps;
    summary.newton_iterations = sol.iterations;
    if sol.cuts > 0 {
        summary.warnings.push(format!(
            "{} continuation steps were cut and retried (Newton did not converge at their size)",
            sol.cuts
        ));
    }
    write_state(
        beam,
        (&sol.q, &sol.slip, &sol.points),
        dir,
        vtk,
        probes,
        summary,
    )
}

fn run_dynamics(
    beam: &Beam,
    opts: &DynamicOptions,
    init: &InitialState,
    out: &Files,
    summary: &mut RunSummary,
    progress: &mut dyn FnMut(f64),
) -> Result<(), Stop> {
    let dir = out.dir;
    let moving = beam.has_moving_supports();
    let extra: &[&str] = if moving {
        &["non_potential", "support_work"]
    } else {
        &["non_potential"]
    };
    let mut files = FrameFiles::create(dir, out.vtk, extra).map_err(Stop::output)?;
    let mut probes = ProbeFiles::create(dir, &out.output.probes).map_err(Stop::output)?;
    let mut envelopes = Envelopes::new(out.output.range_window);
    let n = beam.spec().elements;
    let nd = beam.node_coords();
    let k = n * nd;
    // Velocity of the tip: the last node's position coordinates.
    let dim = nd / 2;
    let mut write_error: Option<String> = None;
    let mut last_q = init.q.clone();
    let mut last_slip = init.state.clone();
    let mut last_points: Vec<PointState> = Vec::new();
    let mut last_t = 0.0;
    let clock = Stopwatch::start();
    let result = run_dynamic_from(beam, opts, init, &mut |f| {
        if write_error.is_some() {
            return;
        }
        let e = &f.energies;
        let (mut x, mut v) = ([0.0; 3], [0.0; 3]);
        x[..dim].copy_from_slice(&f.q[k..k + dim]);
        v[..dim].copy_from_slice(&f.v[k..k + dim]);
        let all = [
            e.kinetic,
            e.gravity,
            e.elastic,
            e.dissipated,
            e.total(),
            e.non_potential,
            e.supports,
        ];
        let energies = &all[..if moving { 7 } else { 6 }];
        let rows = beam_state::rows(beam, f.q, f.slip, f.points);
        let stations = beam_state::stations(&rows);
        if let Err(err) = files.write(f.t, x, v, energies, || beam_state::vtk_frame(&rows)) {
            write_error = Some(format!("writing results: {err}"));
        }
        let state = (f.q, Some(f.v), f.slip);
        let written = if rows.is_empty() {
            Ok(())
        } else {
            probes.write(f.t, |s| probe_sample(beam, state, &rows, &stations, s))
        };
        if let Err(err) = written.and_then(|()| envelopes.add(f.t, &stations)) {
            write_error = Some(err);
        }
        last_q.copy_from_slice(f.q);
        last_slip.copy_from_slice(f.slip);
        last_points.clear();
        last_points.extend_from_slice(f.points);
        last_t = f.t;
        progress(f.t / opts.duration);
    });
    clock.record(summary);
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
    finish_range(&envelopes, dir, summary)?;
    if let Some(e) = write_error {
        return Err(Stop::output(e));
    }
    let s = match result {
        Ok(s) => s,
        Err(e) => {
            let stop = Stop::new(failure_of_dynamic(&e), e.to_string());
            if !last_points.is_empty() {
                summary.warnings.push(format!(
                    "centerline.csv and wires.csv hold the last output frame, t = {last_t:.6e} s"
                ));
                write_state(
                    beam,
                    (&last_q, &last_slip, &last_points),
                    dir,
                    None,
                    None,
                    summary,
                )?;
            }
            return Err(stop);
        }
    };
    summary.steps = s.steps;
    summary.newton_iterations = s.newton_iterations;
    summary.time_step = Some(s.time_step);
    summary.stable_time_step = s.stable_step.or(summary.stable_time_step);
    summary.non_potential_work = Some(s.last.non_potential);
    // Above round-off of the energy sums and the round-off floor of the balance: the law has
    // put energy into the strand.
    if s.last.non_potential > (1e-9 * s.max_kinetic).max(s.balance_floor) {
        let kind = beam.law().kind();
        let (work, relative) = (
            s.last.non_potential,
            s.last.non_potential / s.max_kinetic.max(f64::MIN_POSITIVE),
        );
        // The hysteretic law has no non-potential part: its slip energy is booked as slip
        // work.
        summary.warnings.push(format!(
            "the `{kind}` law put {work:.3e} J into the strand ({relative:.2e} of the largest \
             kinetic energy): the work of its non-potential part (energy.csv `non_potential`) \
             is positive; the motion is not physical; use `hysteretic`"
        ));
    }
    let relative = s.balance_error / s.max_kinetic.max(f64::MIN_POSITIVE);
    summary.energy_balance_error = Some(s.balance_error);
    summary.energy_balance_relative = Some(relative);
    summary.dissipated = Some(s.last.dissipated);
    if s.cut_steps > 0 {
        summary.warnings.push(format!(
            "steps were cut {} times: where Newton did not converge at the step of {:.3e} s \
             asked for, the step was taken in two halves (again, down to 1/1024 of it)",
            s.cut_steps, s.time_step
        ));
    }
    if opts.output_interval < s.time_step {
        summary.warnings.push(format!(
            "analysis.output_interval {:.3e} s is shorter than the time step {:.3e} s: a frame \
             is written at every step",
            opts.output_interval, s.time_step
        ));
    }
    if balance_open(s.balance_error, s.max_kinetic, s.balance_floor) {
        summary.warnings.push(format!(
            "energy balance not closed: the error {:.3e} J is {relative:.2e} of the largest \
             kinetic energy; the time step {:.3e} s is too coarse for this motion (with the \
             stick/slip laws Newton may end steps on a stick/slip cycle): reduce it",
            s.balance_error, s.time_step
        ));
    }
    write_state(
        beam,
        (&s.q, &s.slip, &last_points),
        dir,
        None,
        None,
        summary,
    )
}

/// Writes `range.csv` from `envelopes`; warns of a window that took no frame and of empty
/// fields.
pub(crate) fn finish_range(
    envelopes: &Envelopes,
    dir: &Path,
    summary: &mut RunSummary,
) -> Result<(), Stop> {
    if envelopes.frames() == 0 {
        summary.warnings.push(
            "range.csv: no output frame in output.range_window; the file holds only its header"
                .into(),
        );
    }
    let blanks = envelopes.write(dir).map_err(Stop::output)?;
    if blanks > 0 {
        summary.warnings.push(format!(
            "range.csv: {blanks} fields left empty (a quantity no frame in the window defined)"
        ));
    }
    Ok(())
}
