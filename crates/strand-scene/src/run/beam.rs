//! Runs the beam models of a scene (equivalent and traditional, strand-ancf) and writes their
//! result files.

use std::path::Path;
use std::time::Instant;

use strand_ancf::beam::{
    Beam, BeamSpec, ElementKind, PointLoad, PointState, Support as BeamSupport, SupportMotion,
};
use strand_ancf::dynamics::{DynamicOptions, Scheme, run_dynamic_from};
use strand_ancf::initial::InitialState;
use strand_ancf::statics::{StaticOptions, solve_static};
use strand_core::{LawKind, SectionLaw, WireState};

use crate::output::{Csv, FrameFiles, number, write_vtk_polyline};
use crate::scene::{Analysis, BeamModel, End, IntegratorKind, Scene, SupportKind};

use super::record::{BALANCE_WARNING, RunError, RunOptions, RunSummary, finish, io_err};

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
    let law = SectionLaw::with_options(strand, kind, &scene.section);
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
    let beam = beam_of(scene, name, model, kind)?;
    let law = beam.law();
    let dir = opts.out.join(name);
    std::fs::create_dir_all(&dir).map_err(io_err(&dir))?;
    let element = match beam.spec().element {
        ElementKind::Planar => "planar ANCF cable beam in the XY plane (4 coordinates per node)",
        ElementKind::Spatial => {
            "spatial ANCF cable beam (6 coordinates per node), section frames carried without \
             spin about the tangent, committed with every accepted step"
        }
    };
    let mut built = vec![
        format!(
            "{element}, {} elements of {:.4e} m, {} bending points and 2 axial points per element",
            model.elements,
            beam.element_length(),
            beam.bending_points()
        ),
        format!("section law `{kind}`"),
    ];
    if beam.spec().element == ElementKind::Spatial && law.sliders() > 0 {
        let r = scene.phase_reference;
        built.push(format!(
            "wire phases measured from ({:.4}, {:.4}, {:.4}) at x = 0",
            r[0], r[1], r[2]
        ));
    }
    if !scene.point_forces.is_empty() {
        built.push(format!(
            "{} point force(s), constant",
            scene.point_forces.len()
        ));
    }
    if beam.has_moving_supports() {
        built.push(
            "moving supports: the held position follows its table (statics: the last row with \
             the load steps)"
                .into(),
        );
    }
    if law.sliders() > 0 {
        built.push(format!(
            "{} friction sliders per bending point",
            law.sliders()
        ));
    }
    let mut summary = RunSummary {
        scene: scene.name.clone(),
        model: name.to_string(),
        law: kind.name().to_string(),
        analysis: String::new(),
        status: "ok".into(),
        error: None,
        dofs: beam.dofs(),
        elements: model.elements,
        integration_points: beam.bending_points(),
        steps: 0,
        newton_iterations: 0,
        wall_time_s: 0.0,
        tip: [f64::NAN; 3],
        time_step: None,
        stable_time_step: None,
        energy_balance_error: None,
        energy_balance_relative: None,
        dissipated: None,
        non_potential_work: None,
        built,
        warnings: Vec::new(),
    };
    if kind == LawKind::Paper {
        summary.warnings.push(
            "the `paper` law's moment drops at each switch (non-monotone, eq. (23)); Newton may \
             fail to converge"
                .into(),
        );
    }
    let result = match scene.analysis {
        Analysis::Static { load_steps } => {
            summary.analysis = "static".into();
            run_static(&beam, load_steps, &dir, opts.vtk, &mut summary, &mut |f| {
                progress(name, f)
            })
        }
        Analysis::Dynamic(_) => {
            summary.analysis = "dynamic".into();
            if matches!(kind, LawKind::Continuous | LawKind::Paper) {
                summary.warnings.push(format!(
                    "the `{kind}` law is not a potential (its moment depends on the tension): in \
                     dynamics its non-potential work can feed energy into axial-bending \
                     vibrations; `hysteretic` is the energetically consistent law"
                ));
            }
            let o = dynamic_options(scene).expect("a dynamic analysis");
            match InitialState::rigid(&beam, scene.velocity, scene.angular_velocity) {
                Err(e) => Err(e.to_string()),
                Ok(init) => {
                    if init.discarded > 0.0 {
                        summary.warnings.push(format!(
                            "the initial velocity field moves a fixed support (up to {:.3e} \
                             m/s): the support holds those coordinates at rest",
                            init.discarded
                        ));
                    }
                    run_dynamics(&beam, &o, &init, &dir, opts.vtk, &mut summary, &mut |f| {
                        progress(name, f)
                    })
                }
            }
        }
    };
    finish(summary, result, &dir)
}

/// Writes `centerline.csv` and `wires.csv` for the state `(q, slip, points)`.
fn write_state(
    beam: &Beam,
    q: &[f64],
    slip: &[f64],
    points: &[PointState],
    dir: &Path,
) -> Result<(), String> {
    let law = beam.law();
    let ea = law.axial_stiffness();
    let planar = beam.spec().element == ElementKind::Planar;
    let p = dir.join("centerline.csv");
    let e = |e: std::io::Error| format!("writing {}: {e}", p.display());
    let mut c = Csv::create(
        &p,
        &[
            "s",
            "x",
            "y",
            "z",
            "curvature",
            "tension",
            "bending_stiffness",
        ],
    )
    .map_err(e)?;
    let pw = dir.join("wires.csv");
    let ew = |e: std::io::Error| format!("writing {}: {e}", pw.display());
    let mut wires =
        Csv::create(&pw, &["s", "wire", "phase", "critical_curvature", "state"]).map_err(ew)?;
    for (i, pt) in points.iter().enumerate() {
        let (r, _) = beam.sample(q, pt.x);
        let st = law.station(pt.x);
        let sl = beam.point_slip(slip, i);
        // Planar: signed curvature and the planar secant; spatial: the curvature magnitude and
        // |M| / |kappa| of the vector law.
        let kappa = [pt.kappa_y, pt.kappa];
        let k = pt.kappa_y.hypot(pt.kappa);
        let (curvature, secant) = if pt.kappa_y == 0.0 {
            (pt.kappa, law.planar_secant(&st, pt.eps, pt.kappa, sl))
        } else {
            let mut tr = vec![0.0; sl.len()];
            let r = law.vector(&st, pt.eps, kappa, sl, &mut tr);
            (k, r.moment[0].hypot(r.moment[1]) / k)
        };
        c.row(&[pt.x, r[0], r[1], r[2], curvature, ea * pt.eps, secant])
            .map_err(e)?;
        // Phases from the neutral axis of the current bending direction: the planar
        // convention for the planar element, the vector law's in 3D.
        let report = if planar {
            law.planar_wires(&st, pt.eps, pt.kappa, sl)
        } else {
            law.vector_wires(&st, pt.eps, kappa, sl)
        };
        for wr in report {
            let crit = wr.critical_curvature.map_or("inf".to_string(), number);
            let state = match wr.state {
                WireState::Stick => "stick",
                WireState::Slip => "slip",
            };
            wires
                .text_row(&[
                    number(pt.x),
                    wr.wire.to_string(),
                    number(wr.phase),
                    crit,
                    state.to_string(),
                ])
                .map_err(ew)?;
        }
    }
    c.finish().map_err(e)?;
    wires.finish().map_err(ew)
}

fn tip_of(beam: &Beam, q: &[f64]) -> [f64; 3] {
    beam.sample(q, beam.length()).0
}

fn run_static(
    beam: &Beam,
    load_steps: usize,
    dir: &Path,
    vtk: bool,
    summary: &mut RunSummary,
    progress: &mut dyn FnMut(f64),
) -> Result<(), String> {
    let opts = StaticOptions {
        load_steps,
        ..StaticOptions::default()
    };
    let t0 = Instant::now();
    let sol = solve_static(beam, &opts, progress);
    summary.wall_time_s = t0.elapsed().as_secs_f64();
    let sol = sol.map_err(|e| e.to_string())?;
    summary.steps = sol.steps;
    summary.newton_iterations = sol.iterations;
    summary.tip = tip_of(beam, &sol.q);
    if sol.cuts > 0 {
        summary
            .warnings
            .push(format!("{} load steps were cut and retried", sol.cuts));
    }
    if vtk {
        write_static_vtk(beam, &sol.q, dir)?;
    }
    write_state(beam, &sol.q, &sol.slip, &sol.points, dir)
}

/// Centreline of `q` sampled 4 times per element (m).
fn centreline(beam: &Beam, q: &[f64]) -> Vec<[f64; 3]> {
    let samples = 4 * beam.spec().elements;
    (0..=samples)
        .map(|i| beam.sample(q, beam.length() * i as f64 / samples as f64).0)
        .collect()
}

/// The static state as one VTK frame, `vtk/centerline_00000.vtk`, like a dynamic run's.
fn write_static_vtk(beam: &Beam, q: &[f64], dir: &Path) -> Result<(), String> {
    let d = dir.join("vtk");
    let path = d.join("centerline_00000.vtk");
    std::fs::create_dir_all(&d)
        .and_then(|_| write_vtk_polyline(&path, "static equilibrium", &centreline(beam, q), &[]))
        .map_err(|e| format!("writing {}: {e}", path.display()))
}

fn run_dynamics(
    beam: &Beam,
    opts: &DynamicOptions,
    init: &InitialState,
    dir: &Path,
    vtk: bool,
    summary: &mut RunSummary,
    progress: &mut dyn FnMut(f64),
) -> Result<(), String> {
    let moving = beam.has_moving_supports();
    let extra: &[&str] = if moving {
        &["non_potential", "support_work"]
    } else {
        &["non_potential"]
    };
    let mut files = FrameFiles::create(dir, vtk, extra)?;
    let n = beam.spec().elements;
    let nd = beam.node_coords();
    let k = n * nd;
    // Velocity of the tip: the last node's position coordinates.
    let dim = nd / 2;
    let mut write_error: Option<String> = None;
    let mut last_q = init.q.clone();
    let mut last_points: Vec<PointState> = Vec::new();
    let t0 = Instant::now();
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
        if let Err(err) = files.write(f.t, x, v, energies, || centreline(beam, f.q)) {
            write_error = Some(format!("writing results: {err}"));
        }
        last_q.copy_from_slice(f.q);
        last_points.clear();
        last_points.extend_from_slice(f.points);
        progress(f.t / opts.duration);
    });
    summary.wall_time_s = t0.elapsed().as_secs_f64();
    files.finish()?;
    if let Some(e) = write_error {
        return Err(e);
    }
    summary.tip = tip_of(beam, &last_q);
    let s = result.map_err(|e| e.to_string())?;
    summary.steps = s.steps;
    summary.newton_iterations = s.newton_iterations;
    summary.time_step = Some(s.time_step);
    summary.stable_time_step = s.stable_step;
    summary.energy_balance_error = Some(s.balance_error);
    summary.energy_balance_relative = Some(s.balance_error / s.max_kinetic.max(f64::MIN_POSITIVE));
    summary.dissipated = Some(s.last.dissipated);
    summary.non_potential_work = Some(s.last.non_potential);
    // Above round-off of the energy sums: the law has put energy into the strand.
    if s.last.non_potential > 1e-9 * s.max_kinetic {
        let kind = beam.law().kind();
        let (work, relative) = (
            s.last.non_potential,
            s.last.non_potential / s.max_kinetic.max(f64::MIN_POSITIVE),
        );
        summary.warnings.push(if kind == LawKind::Hysteretic {
            // The hysteretic law has no strain term: only the 3D turn term is left.
            format!(
                "the `hysteretic` law put {work:.3e} J into the strand ({relative:.2e} of the \
                 largest kinetic energy): the work of the wires' moment normal to the bending \
                 direction, which the section law does not apply, as the bending direction \
                 turns under slipped wires (energy.csv `non_potential`)"
            )
        } else {
            format!(
                "the `{kind}` law put {work:.3e} J into the strand ({relative:.2e} of the largest \
                 kinetic energy): the work of its non-potential part (energy.csv \
                 `non_potential`) is positive; the motion is not physical; use `hysteretic`"
            )
        });
    }
    let relative = s.balance_error / s.max_kinetic.max(f64::MIN_POSITIVE);
    if relative > BALANCE_WARNING {
        summary.warnings.push(format!(
            "energy balance not closed: the error {:.3e} J is {relative:.2e} of the largest \
             kinetic energy; the time step {:.3e} s is too coarse for this motion (with the \
             stick/slip laws Newton may end steps on a stick/slip cycle): reduce it",
            s.balance_error, s.time_step
        ));
    }
    write_state(beam, &s.q, &s.slip, &last_points, dir)
}
