//! The hard cases. Each measures, and judges what it measured with [`Ctx::check`] against
//! the limits of `validation/hard/criteria.json`; references are independent of the code under
//! test: converged runs, closed forms, conservation of energy, loop areas.

use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, bail};
use strand_ancf::band::BandMatrix;
use strand_ancf::beam::{Beam, BeamSpec, ElementKind, PointState};
use strand_ancf::dynamics::{
    DynamicOptions, DynamicSummary, Scheme, run_dynamic_from, stable_step,
};
use strand_ancf::initial::InitialState;
use strand_ancf::statics::{StaticOptions, solve_static};
use strand_core::{LawKind, SectionLaw};
use strand_scene::format::SceneFile;
use strand_scene::{
    BeamModelKind, Failure, RunOptions, Scene, build_beam, dynamic_options, run_scene,
};

use super::{Ctx, probe};
use crate::validate::report::{Row, worse, worst};

/// What a dynamic run saw over its output frames.
#[derive(Debug, Clone, Default)]
struct History {
    /// Largest |curvature| (1/m), when (s) and where (m).
    kappa_peak: (f64, f64, f64),
    /// Largest tip speed (m/s) and when (s).
    speed_peak: (f64, f64),
    /// Every coordinate, velocity and point value seen was finite.
    finite: bool,
    /// (t, eps, kappa) at the first bending point (the root) at every frame.
    root: Vec<(f64, f64, f64)>,
    /// State at the frame of the largest kinetic energy (the bottom of a swing, where the
    /// tension and with it the stick stiffness peak) and that energy (J).
    fastest: Option<(probe::Start, f64)>,
    /// (t, total energy (J)) at every frame.
    totals: Vec<(f64, f64)>,
    /// Largest angle between the strand's end tangents (rad) and when (s): past pi / 2 the
    /// strand is folded back on itself.
    fold: (f64, f64),
    /// Largest angle between the tip's tangent and its initial direction (rad).
    tip_turn: f64,
    /// Tip positions at every frame (m).
    tips: Vec<[f64; 3]>,
}

impl History {
    /// Total energy at the first and at the last frame (J).
    fn total_ends(&self) -> (f64, f64) {
        let at = |p: Option<&(f64, f64)>| p.map_or(0.0, |p| p.1);
        (at(self.totals.first()), at(self.totals.last()))
    }
}

/// Runs the dynamics of `beam` with `opts` from rest, showing progress as `what`.
fn dynamic(
    ctx: &Ctx,
    beam: &Beam,
    opts: &DynamicOptions,
    what: &str,
) -> anyhow::Result<(DynamicSummary, History)> {
    dynamic_from(ctx, beam, opts, &InitialState::rest(beam), what)
}

/// Unit tangent of `beam` at `x` for coordinates `q`.
fn tangent(beam: &Beam, q: &[f64], x: f64) -> [f64; 3] {
    let d = beam.sample(q, x).1;
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.map(|v| v / n)
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    c.clamp(-1.0, 1.0).acos()
}

/// Runs the dynamics of `beam` with `opts` from `init`, showing progress as `what`.
fn dynamic_from(
    ctx: &Ctx,
    beam: &Beam,
    opts: &DynamicOptions,
    init: &InitialState,
    what: &str,
) -> anyhow::Result<(DynamicSummary, History)> {
    let mut h = History {
        finite: true,
        ..History::default()
    };
    let nd = beam.node_coords();
    let k = beam.spec().elements * nd;
    let dim = nd / 2;
    let l = beam.length();
    let t0 = tangent(beam, &init.q, l);
    let s = run_dynamic_from(beam, opts, init, &mut |f| {
        let ends = angle(tangent(beam, f.q, 0.0), tangent(beam, f.q, l));
        if ends > h.fold.0 {
            h.fold = (ends, f.t);
        }
        h.tip_turn = h.tip_turn.max(angle(t0, tangent(beam, f.q, l)));
        h.tips.push(tip(beam, f.q));
        h.totals.push((f.t, f.energies.total()));
        h.finite &= f.q.iter().chain(f.v).all(|x| x.is_finite())
            && f.points
                .iter()
                .all(|p| p.kappa.is_finite() && p.eps.is_finite() && p.moment.is_finite());
        for p in f.points {
            let kappa = p.kappa.hypot(p.kappa_y);
            if kappa > h.kappa_peak.0 {
                h.kappa_peak = (kappa, f.t, p.x);
            }
        }
        let speed = f.v[k..k + dim].iter().map(|v| v * v).sum::<f64>().sqrt();
        if speed > h.speed_peak.0 {
            h.speed_peak = (speed, f.t);
        }
        if let Some(p) = f.points.first() {
            h.root.push((f.t, p.eps, p.kappa));
        }
        if h.fastest
            .as_ref()
            .is_none_or(|(_, e)| f.energies.kinetic > *e)
        {
            let start = probe::Start {
                q: f.q.to_vec(),
                v: f.v.to_vec(),
            };
            h.fastest = Some((start, f.energies.kinetic));
        }
        ctx.progress(what, f.t / opts.duration);
    })
    .map_err(|e| anyhow::anyhow!("{what}: {e}"))?;
    Ok((s, h))
}

fn tip(beam: &Beam, q: &[f64]) -> [f64; 3] {
    beam.sample(q, beam.length()).0
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Rows common to dynamic runs: balance error relative to the largest kinetic energy, finite
/// values, and steps taken.
fn dynamic_rows(ctx: &Ctx, s: &DynamicSummary, h: &History) -> anyhow::Result<Vec<Row>> {
    let rel = s.balance_error / s.max_kinetic.max(f64::MIN_POSITIVE);
    Ok(vec![
        ctx.check("energy-balance-relative", rel, "")?
            .with_note(format!(
                "largest |E_kin + E_grav + E_el + W_diss - E_0| = {:.3e} J against the largest \
             kinetic energy {:.3e} J; dissipated {:.3e} J; {} steps of {:.3e} s{}",
                s.balance_error,
                s.max_kinetic,
                s.last.dissipated,
                s.steps,
                s.time_step,
                s.stable_step.map_or(String::new(), |h| format!(
                    " (estimated stable step {h:.3e} s)"
                ))
            )),
        ctx.check("finite", f64::from(u8::from(h.finite)), "")?,
    ])
}

// ---------------------------------------------------------------------------------------
// Real steel

/// Real steel, generalized-alpha: the tip at the end against a converged run (the same
/// scene at h/2 and h/4, Richardson estimate of the error left at h/4).
pub fn steel_generalized_alpha(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("steel-pendulum-ga")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let Scheme::GeneralizedAlpha {
        step,
        spectral_radius,
    } = opts.scheme
    else {
        bail!("steel-pendulum-ga must use generalized-alpha");
    };
    let mut tips = Vec::new();
    let mut first = None;
    for div in [1.0, 2.0, 4.0] {
        let o = DynamicOptions {
            scheme: Scheme::GeneralizedAlpha {
                step: step / div,
                spectral_radius,
            },
            ..opts
        };
        let (s, h) = dynamic(ctx, &beam, &o, &format!("h/{div}"))?;
        tips.push(tip(&beam, &s.q));
        first.get_or_insert((s, h));
    }
    let (s, h) = first.expect("three runs");
    let d1 = distance(tips[0], tips[2]);
    let d2 = distance(tips[1], tips[2]);
    let order = (distance(tips[0], tips[1]) / d2.max(f64::MIN_POSITIVE))
        .log2()
        .max(1.0);
    // Error of the scene's run against the converged limit: its distance to the h/4 run plus
    // the h/4 run's own error, d(h/2, h/4) / (2^p - 1).
    let err = d1 + d2 / (2f64.powf(order) - 1.0);
    let mut rows = vec![
        ctx.check("tip-error", err, "m")?.with_note(format!(
            "tip at t = {} s: h = {step:e} s {:?}, |h - h/4| = {d1:.3e} m, |h/2 - h/4| = \
             {d2:.3e} m, observed order {order:.2}; {} Newton iterations in {} steps",
            opts.duration,
            tips[0].map(|v| (v * 1e6).round() / 1e6),
            s.newton_iterations,
            s.steps
        )),
        ctx.report(
            "newton-per-step",
            s.newton_iterations as f64 / s.steps as f64,
            "",
        ),
    ];
    rows.extend(dynamic_rows(ctx, &s, &h)?);
    Ok(rows)
}

/// The number following `after` in `text`.
fn number_after(text: &str, after: &str) -> Option<f64> {
    let rest = &text[text.find(after)? + after.len()..];
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
        .unwrap_or(rest.len());
    rest[..end].parse().ok()
}

/// Real steel, Verlet with a step forced above the stable step: the run stops, naming the
/// estimated stable step (compared with the estimate computed here).
pub fn steel_verlet_forced_step(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("steel-pendulum-verlet-forced")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let stable = stable_step(&beam)?;
    let opts = RunOptions {
        out: ctx.out.clone(),
        vtk: false,
    };
    let message = run_scene(&scene, &opts, &mut |_, _| {})?
        .iter()
        .find_map(|s| s.failure())
        .ok_or_else(|| anyhow::anyhow!("the run at a step above the stable step did not stop"))?;
    let named = number_after(&message, "estimated stable step ")
        .map_or(f64::INFINITY, |v| (v - stable).abs() / stable);
    let status = summary_status(&ctx.out.join("equivalent"))?;
    Ok(vec![
        ctx.check("stable-step-named", named, "")?
            .with_note(format!(
                "stable step {stable:.4e} s; the run said: {message}"
            )),
        ctx.check(
            "summary-says-failed",
            f64::from(u8::from(status == "failed")),
            "",
        )?,
    ])
}

fn summary_status(dir: &Path) -> anyhow::Result<String> {
    let v = crate::validate::results::summary(dir)?;
    Ok(v["status"].as_str().unwrap_or("").to_string())
}

/// Real steel, Verlet at its estimated stable step for the whole second; its tip against the
/// converged generalized-alpha run (h/4 of steel-pendulum-ga).
pub fn steel_verlet_stable_step(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("steel-pendulum-verlet")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let (s, h) = dynamic(ctx, &beam, &opts, "verlet")?;
    let ga = ctx.scene("steel-pendulum-ga")?;
    let mut o = dynamic_options(&ga).context("a dynamic scene")?;
    if let Scheme::GeneralizedAlpha { step, .. } = &mut o.scheme {
        *step /= 4.0;
    }
    let (g, _) = dynamic(
        ctx,
        &build_beam(&ga, BeamModelKind::Equivalent)?,
        &o,
        "reference",
    )?;
    let d = distance(tip(&beam, &s.q), tip(&beam, &g.q));
    let mut rows = vec![ctx.check("tip-vs-generalized-alpha", d, "m")?];
    rows.extend(dynamic_rows(ctx, &s, &h)?);
    Ok(rows)
}

// ---------------------------------------------------------------------------------------
// Fine meshes and the stable step

/// Probe steps per trial of the bisection.
const PROBE_STEPS: usize = 3000;

fn bisection_rows(
    ctx: &Ctx,
    beam: &Beam,
    swing: Option<&probe::Start>,
) -> anyhow::Result<Vec<Row>> {
    let estimate = stable_step(beam)?;
    let t = Instant::now();
    ctx.progress("bisection", 0.0);
    let mut starts = vec![probe::Start::rest(beam), probe::Start::hanging(beam)];
    starts.extend(swing.cloned());
    let observed = probe::observed_limit(beam, &starts, estimate, PROBE_STEPS, 0.01)
        .context("no stable/unstable bracket found around the estimate")?;
    let ratio = observed / estimate;
    let from = if swing.is_some() {
        "from rest horizontal, hanging, and the fastest frame of the run"
    } else {
        "from rest horizontal and hanging"
    };
    let note = format!(
        "estimated {estimate:.4e} s, observed limit {observed:.4e} s (bisection to 1 %, \
         {PROBE_STEPS} steps per trial {from}, {:.1} s)",
        t.elapsed().as_secs_f64()
    );
    Ok(vec![
        ctx.check("limit-over-estimate-max", ratio, "")?
            .with_note(note),
        ctx.check("limit-over-estimate-min", ratio, "")?,
    ])
}

/// The observed Verlet limit of the 64-element section-3 pendulum against the estimate.
pub fn stable_step_bisection_64(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let beam = build_beam(&ctx.scene("fine-mesh-64")?, BeamModelKind::Equivalent)?;
    bisection_rows(ctx, &beam, None)
}

fn fine_mesh(ctx: &Ctx, scene: &str) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene(scene)?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let (s, h) = dynamic(ctx, &beam, &opts, "verlet")?;
    let mut rows = dynamic_rows(ctx, &s, &h)?;
    rows.push(ctx.report("steps", s.steps as f64, ""));
    let swing = h.fastest.as_ref().map(|(s, _)| s);
    rows.extend(bisection_rows(ctx, &beam, swing)?);
    Ok(rows)
}

/// 64 elements, Verlet at the estimated step for 1 s, and the observed limit.
pub fn fine_mesh_64(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    fine_mesh(ctx, "fine-mesh-64")
}

/// 128 elements.
pub fn fine_mesh_128(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    fine_mesh(ctx, "fine-mesh-128")
}

/// 256 elements.
pub fn fine_mesh_256(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    fine_mesh(ctx, "fine-mesh-256")
}

// ---------------------------------------------------------------------------------------
// Whipping, chatter, loop area

/// The section-3 pinned pendulum for 2 s: energy balance, no NaN, curvature peaks.
pub fn whip_pendulum(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("whip-pendulum")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let (s, h) = dynamic(ctx, &beam, &opts, "verlet")?;
    let mut rows = dynamic_rows(ctx, &s, &h)?;
    let (k, kt, kx) = h.kappa_peak;
    let (v, vt) = h.speed_peak;
    rows.push(
        ctx.report("curvature-peak", k, "1/m")
            .with_note(format!("at t = {kt:.3} s, s = {kx:.4} m")),
    );
    rows.push(
        ctx.report("tip-speed-peak", v, "m/s")
            .with_note(format!("at t = {vt:.3} s")),
    );
    Ok(rows)
}

/// A hanging strand (tension from its weight) rocked by a small sideways gravity so that the
/// root curvature oscillates about the wires' critical curvatures; generalized-alpha.
pub fn stick_slip_chatter(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("chatter-hanging")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let (s, h) = dynamic(ctx, &beam, &opts, "generalized-alpha")?;
    let mut rows = dynamic_rows(ctx, &s, &h)?;
    // Critical curvatures at the root for the root's mean strain.
    let law = beam.law();
    let x0 = beam_points(&beam, &s)?.first().map_or(0.0, |p| p.x);
    let st = law.station(x0);
    let eps = h.root.iter().map(|r| r.1).sum::<f64>() / h.root.len().max(1) as f64;
    let kc: Vec<f64> = law
        .planar_wires(&st, eps, 1.0, &vec![0.0; law.state_len()])
        .iter()
        .filter(|w| w.k_stick > 0.0)
        .filter_map(|w| w.critical_curvature)
        .collect();
    let (kc_min, kc_max) = kc
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &c| (a.min(c), b.max(c)));
    let amp = worst(h.root.iter().map(|r| r.2.abs()));
    let switches = h
        .root
        .windows(2)
        .filter(|w| (w[0].2.abs() > kc_min) != (w[1].2.abs() > kc_min))
        .count();
    rows.push(
        ctx.check("root-amplitude-over-first-critical", amp / kc_min, "")?
            .with_note(format!(
                "root |kappa| up to {amp:.3e} 1/m; critical curvatures at the root {kc_min:.3e} \
                 to {kc_max:.3e} 1/m (strain {eps:.3e}); the root crossed the first critical \
                 curvature {switches} times"
            )),
    );
    rows.push(ctx.check(
        "newton-per-step",
        s.newton_iterations as f64 / s.steps as f64,
        "",
    )?);
    rows.push(ctx.check("dissipated", s.last.dissipated, "J")?);
    // The same scene at 1 ms: the runner must flag the open energy balance.
    let mut file = scene.file.clone();
    file.analysis.time_step = Some(1e-3);
    let coarse = Scene::from_file(file)?;
    let opts = RunOptions {
        out: ctx.out.join("coarse"),
        vtk: false,
    };
    let summaries = run_scene(&coarse, &opts, &mut |_, f| ctx.progress("h = 1 ms", f))?;
    let warning = summaries[0]
        .warnings
        .iter()
        .find(|w| w.contains("energy balance"))
        .cloned();
    rows.push(
        ctx.check(
            "coarse-step-warned",
            f64::from(u8::from(warning.is_some())),
            "",
        )?
        .with_note(format!(
            "h = 1 ms: balance error {:.3e} of the largest kinetic energy; {}",
            summaries[0].energy_balance_relative.unwrap_or(f64::NAN),
            warning.unwrap_or_else(|| "no warning".into())
        )),
    );
    Ok(rows)
}

/// The bending points of `beam` at the end of `s`.
fn beam_points(beam: &Beam, s: &DynamicSummary) -> anyhow::Result<Vec<PointState>> {
    let mut pts = vec![PointState::default(); beam.points()];
    let mut trial = s.slip.clone();
    let mut force = vec![0.0; beam.coords()];
    beam.internal(&s.q, &s.slip, &mut trial, &mut force, None, Some(&mut pts))?;
    Ok(pts)
}

/// The hysteretic law cycled at the chatter strand's root tension: the loop area (trapezoid
/// over the moment history), the law's reported slip work and the closed form of Coulomb
/// sliders, sum_i (M+_i + M-_i) (2 A - (M+_i + M-_i) / K_i) over the wires that slip, agree.
pub fn hysteretic_loop_area(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("chatter-hanging")?;
    let strand = &scene.strand;
    let law = SectionLaw::with_options(strand, LawKind::Hysteretic, &scene.section);
    let g = scene.gravity[1].hypot(scene.gravity[0]);
    let eps = strand.mass_per_length() * g * strand.length() / law.axial_stiffness();
    let st = law.station(0.0);
    let zero = vec![0.0; law.state_len()];
    let plus = law.planar_wires(&st, eps, 1.0, &zero);
    let minus = law.planar_wires(&st, eps, -1.0, &zero);
    let kmax = plus.iter().map(|w| w.k_stick).fold(0.0, f64::max);
    // Sliders: (K, M+ + M-).
    let sliders: Vec<(f64, f64)> = plus
        .iter()
        .zip(&minus)
        .filter(|(p, _)| p.k_stick > 1e-9 * kmax)
        .map(|(p, m)| (p.k_stick, p.m_slip + m.m_slip))
        .collect();
    let kbar = sliders
        .iter()
        .map(|(k, m)| m / (2.0 * k))
        .fold(f64::INFINITY, f64::min);
    let n = 20_000usize;
    let (mut worst_area, mut worst_work, mut scale) = (0.0f64, 0.0f64, 0.0f64);
    let mut notes = Vec::new();
    let amplitudes = [0.5, 0.9, 1.1, 1.5, 3.0, 10.0];
    for a in amplitudes.map(|f| f * kbar) {
        let closed: f64 = sliders
            .iter()
            .map(|&(k, m)| {
                if 2.0 * a * k > m {
                    m * (2.0 * a - m / k)
                } else {
                    0.0
                }
            })
            .sum();
        let mut slip = zero.clone();
        let mut trial = zero.clone();
        let (mut area, mut work) = (0.0, 0.0);
        let mut prev = (0.0, 0.0);
        for i in 0..=3 * n {
            let kappa = a * (2.0 * PI * i as f64 / n as f64).sin();
            let r = law.planar(&st, eps, kappa, &slip, &mut trial);
            slip.copy_from_slice(&trial);
            if i > 2 * n {
                area += 0.5 * (r.moment + prev.1) * (kappa - prev.0);
                work += r.slip_work;
            }
            prev = (kappa, r.moment);
        }
        scale = scale.max(closed);
        worst_area = worst_area.max((area - closed).abs());
        worst_work = worst_work.max((work - area).abs());
        notes.push(format!(
            "A = {a:.3e}: area {area:.4e}, slip work {work:.4e}, closed form {closed:.4e} J/m"
        ));
    }
    Ok(vec![
        ctx.check("loop-area-vs-closed-form", worst_area / scale, "")?
            .with_note(format!(
                "strain {eps:.3e}, {} sliding wires, third cycle of {n} steps; {}",
                sliders.len(),
                notes.join("; ")
            )),
        ctx.check("slip-work-vs-loop-area", worst_work / scale, "")?,
    ])
}

// ---------------------------------------------------------------------------------------
// Kinematic states: compression, zero tension, near-straight, rigid rotation

/// `beam`'s strand with the spatial element instead.
fn spatial(beam: &Beam) -> anyhow::Result<Beam> {
    Ok(Beam::new(
        BeamSpec {
            element: ElementKind::Spatial,
            ..beam.spec().clone()
        },
        beam.law().clone(),
    )?)
}

/// The straight-strand scene with each section law, planar and spatial.
fn strand_beams(ctx: &Ctx) -> anyhow::Result<Vec<(String, Beam)>> {
    let scene = ctx.scene("straight-strand")?;
    let mut out = Vec::new();
    for law in ["continuous", "paper", "hysteretic"] {
        let mut file: SceneFile = scene.file.clone();
        file.law = Some(law.into());
        let s = Scene::from_file(file)?;
        let planar = build_beam(&s, BeamModelKind::Equivalent)?;
        out.push((format!("{law}/spatial"), spatial(&planar)?));
        out.push((format!("{law}/planar"), planar));
    }
    Ok(out)
}

/// Coordinates of a circular arc of curvature `kappa` (1/m) along +x from the origin, bending
/// toward +y, uniformly stretched by `1 + e`, rotated by `theta` about the axis `axis`.
fn arc(beam: &Beam, kappa: f64, e: f64, theta: f64, axis: [f64; 3]) -> Vec<f64> {
    let nd = beam.node_coords();
    let l = beam.element_length();
    let mut q = vec![0.0; beam.coords()];
    for i in 0..=beam.spec().elements {
        let x = i as f64 * l;
        let (r, t) = if kappa == 0.0 {
            ([x, 0.0, 0.0], [1.0, 0.0, 0.0])
        } else {
            let a = kappa * x;
            (
                [a.sin() / kappa, (1.0 - a.cos()) / kappa, 0.0],
                [a.cos(), a.sin(), 0.0],
            )
        };
        let r = rotate(r.map(|v| v * (1.0 + e)), theta, axis);
        let t = rotate(t.map(|v| v * (1.0 + e)), theta, axis);
        let d = nd / 2;
        q[i * nd..i * nd + d].copy_from_slice(&r[..d]);
        q[i * nd + d..i * nd + nd].copy_from_slice(&t[..d]);
    }
    q
}

/// Rodrigues rotation of `v` by `theta` about the unit `axis`.
fn rotate(v: [f64; 3], theta: f64, n: [f64; 3]) -> [f64; 3] {
    let (s, c) = theta.sin_cos();
    let dot = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
    let cross = [
        n[1] * v[2] - n[2] * v[1],
        n[2] * v[0] - n[0] * v[2],
        n[0] * v[1] - n[1] * v[0],
    ];
    [0, 1, 2].map(|i| v[i] * c + cross[i] * s + n[i] * dot * (1.0 - c))
}

const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// Forces, tangent, energy and point states of `beam` at `q` (zero slip state).
struct Eval {
    force: Vec<f64>,
    energy: f64,
    points: Vec<PointState>,
    tangent_finite: bool,
}

fn evaluate(beam: &Beam, q: &[f64]) -> anyhow::Result<Eval> {
    let slip = beam.initial_state();
    let mut trial = slip.clone();
    let mut force = vec![0.0; beam.coords()];
    let mut points = vec![PointState::default(); beam.points()];
    let b = beam.bandwidth();
    let mut k = BandMatrix::zeros(beam.dofs(), b, b);
    let ev = beam.internal(
        q,
        &slip,
        &mut trial,
        &mut force,
        Some(&mut k),
        Some(&mut points),
    )?;
    let n = beam.dofs();
    let tangent_finite = (0..n).all(|i| {
        (i.saturating_sub(b)..(i + b + 1).min(n))
            .filter(|&j| k.in_band(i, j))
            .all(|j| k.get(i, j).is_finite())
    });
    Ok(Eval {
        force,
        energy: ev.energy,
        points,
        tangent_finite,
    })
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// Uniform compression, an arc at zero tension and a compressed arc: energies and end forces
/// against closed forms (for eps <= 0 the friction terms vanish: M = K_min kappa).
pub fn compression_zero_tension(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let (mut uniform_e, mut uniform_f, mut arc_e, mut finite) = (0.0f64, 0.0f64, 0.0f64, true);
    let mut secant = 0.0f64;
    for (name, beam) in strand_beams(ctx)? {
        let law = beam.law();
        let (ea, kmin) = (law.axial_stiffness(), law.base_bending_stiffness());
        let l = beam.length();
        // Uniform compression: N = EA e at the free end, energy 1/2 EA e^2 L.
        let e = -1e-3;
        let ev = evaluate(&beam, &arc(&beam, 0.0, e, 0.0, Z))?;
        finite &= ev.tangent_finite && ev.force.iter().all(|f| f.is_finite());
        uniform_e = uniform_e.max(rel(ev.energy, 0.5 * ea * e * e * l));
        let end = beam.spec().elements * beam.node_coords();
        uniform_f = uniform_f.max(rel(ev.force[end], ea * e));
        // Arcs at zero tension and in compression: kappa = 1/m over 0.4 m.
        for e in [0.0, -1e-3] {
            let k0 = 1.0;
            let ev = evaluate(&beam, &arc(&beam, k0, e, 0.0, Z))?;
            finite &= ev.tangent_finite && ev.force.iter().all(|f| f.is_finite());
            // Curvature per reference length (the turning rate d theta / dx): a uniformly
            // scaled arc keeps k0.
            let kappa = k0;
            let exact = l * (0.5 * ea * e * e + 0.5 * kmin * kappa * kappa);
            arc_e = arc_e.max(rel(ev.energy, exact));
            if name.ends_with("planar") {
                for p in &ev.points {
                    secant = secant.max(rel(p.moment / p.kappa, kmin));
                }
            }
        }
    }
    Ok(vec![
        ctx.check("uniform-compression-energy", uniform_e, "")?
            .with_note(
                "relative error against 1/2 EA eps^2 L, eps = -1e-3, every law, planar and spatial",
            ),
        ctx.check("uniform-compression-end-force", uniform_f, "")?
            .with_note("relative error of the end node's axial force against EA eps"),
        ctx.check("arc-energy", arc_e, "")?.with_note(
            "arcs of curvature 1/m at zero strain and at eps = -1e-3: relative error against \
             L (1/2 EA eps^2 + 1/2 K_min kappa^2)",
        ),
        ctx.check("arc-secant-vs-K_min", secant, "")?,
        ctx.check("finite", f64::from(u8::from(finite)), "")?,
    ])
}

/// Curvature 1e-12 and exactly zero: finite forces and tangents; under tension every wire
/// sticks (secant: the law's all-stick stiffness), in compression none carries (K_min).
pub fn near_straight(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let (mut secant, mut finite, mut straight_moment) = (0.0f64, true, 0.0f64);
    for (name, beam) in strand_beams(ctx)? {
        for e in [1e-4, -1e-4, 0.0] {
            for kappa in [1e-12, 0.0] {
                let ev = evaluate(&beam, &arc(&beam, kappa, e, 0.0, Z))
                    .with_context(|| format!("{name}, strain {e}, curvature {kappa}"))?;
                finite &= ev.tangent_finite
                    && ev.force.iter().all(|f| f.is_finite())
                    && ev.energy.is_finite();
                if kappa == 0.0 {
                    for p in &ev.points {
                        straight_moment = straight_moment.max(p.moment.abs());
                    }
                } else if e != 0.0 && name.ends_with("planar") {
                    let expect = if e > 0.0 {
                        beam.law().stick_bending_stiffness()
                    } else {
                        beam.law().base_bending_stiffness()
                    };
                    for p in &ev.points {
                        secant = secant.max(rel(p.moment / p.kappa, expect));
                    }
                }
            }
        }
    }
    Ok(vec![
        ctx.check("secant-stiffness", secant, "")?.with_note(
            "curvature 1e-12 1/m: largest relative deviation of M/kappa from K_max \
             (eps = 1e-4, all wires stick) and K_min (eps = -1e-4) over the bending points",
        ),
        ctx.check("straight-moment", straight_moment, "N m")?,
        ctx.check("finite", f64::from(u8::from(finite)), "")?,
    ])
}

/// A straight strand turned rigidly at 100 rad/s through 10 rad (planar, about Z; spatial,
/// about a skew axis): no strain, no curvature, no force, no energy. The spatial element at a
/// half turn about Z (tangent opposite to the reference) must stop with a named error.
pub fn rigid_rotation(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let omega = 100.0;
    let skew = [1.0 / 3f64.sqrt(); 3];
    let (mut force, mut energy, mut strain, mut curvature) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut angles = 0;
    for (name, beam) in strand_beams(ctx)? {
        let ea = beam.law().axial_stiffness();
        let axis = if name.ends_with("planar") { Z } else { skew };
        for i in 0..=270 {
            let theta = omega * i as f64 * 3.7e-4;
            let ev = evaluate(&beam, &arc(&beam, 0.0, 0.0, theta, axis))
                .with_context(|| format!("{name} at {theta} rad"))?;
            angles += 1;
            force = worse(force, worst(ev.force.iter().map(|f| f.abs() / ea)));
            energy = worse(energy, ev.energy.abs());
            for p in &ev.points {
                strain = strain.max(p.eps.abs());
                curvature = curvature.max(p.kappa.hypot(p.kappa_y));
            }
        }
    }
    let (_, sp) = strand_beams(ctx)?.swap_remove(0);
    let half_turn = match evaluate(&sp, &arc(&sp, 0.0, 0.0, PI, Z)) {
        Ok(_) => "no error".to_string(),
        Err(e) => format!("{e:#}"),
    };
    let named = half_turn.contains("opposite to the reference tangent");
    Ok(vec![
        ctx.check("force-over-EA", force, "")?.with_note(format!(
            "{angles} rigidly rotated states (angles 0-10 rad, every law, planar about Z and \
             spatial about (1,1,1)/sqrt 3)"
        )),
        ctx.check("energy", energy, "J")?,
        ctx.check("strain", strain, "")?,
        ctx.check("curvature", curvature, "1/m")?,
        ctx.check("spatial-half-turn-named", f64::from(u8::from(named)), "")?
            .with_note(format!("spatial element turned by pi about Z: {half_turn}")),
    ])
}

// ---------------------------------------------------------------------------------------
// Sudden load, long run

/// Gravity switched on at t = 0 on the clamped Table 1 strand (trapezoidal generalized-alpha).
pub fn sudden_gravity(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    energy_drift(ctx, "sudden-gravity")
}

/// The paper's pinned pendulum (Table 1 strand) for 100 s with generalized-alpha.
pub fn long_run_100s(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let (s, h, wall, mut rows) = timed_generalized_alpha(ctx, "long-run-100s")?;
    let scale = s.max_kinetic.max(f64::MIN_POSITIVE);
    let (e0, e1) = h.total_ends();
    // Energy put in by the integrator: the largest rise of the total above its start.
    let rise = worst(h.totals.iter().map(|(_, e)| e - e0)) / scale;
    // Drift over the last tenth of the run: a bounded drift has settled by then.
    let end = h.totals.last().map_or(0.0, |p| p.0);
    let late = h
        .totals
        .iter()
        .find(|(t, _)| *t >= 0.9 * end)
        .map_or(e0, |p| p.1);
    let tail = (e1 - late).abs() / scale;
    rows.push(ctx.check("energy-rise", rise, "")?.with_note(format!(
        "largest total energy above the start {:+.3e} of the largest kinetic energy \
             ({:.3e} J); numerical damping removed {:.3e} J by the end; {} steps, {} Newton \
             iterations, {wall:.1} s",
        rise,
        s.max_kinetic,
        e0 - e1,
        s.steps,
        s.newton_iterations
    )));
    rows.push(
        ctx.check("energy-drift-last-tenth", tail, "")?
            .with_note(format!(
                "total energy change from t = {:.1} s to the end, relative to the largest \
             kinetic energy",
                0.9 * end
            )),
    );
    Ok(rows)
}

fn energy_drift(ctx: &Ctx, scene: &str) -> anyhow::Result<Vec<Row>> {
    let (s, h, wall, mut rows) = timed_generalized_alpha(ctx, scene)?;
    let (e0, e1) = h.total_ends();
    let drift = (e1 - e0) / s.max_kinetic.max(f64::MIN_POSITIVE);
    rows.push(
        ctx.check("energy-drift-at-end", drift.abs(), "")?
            .with_note(format!(
                "total energy at the end minus at the start: {:.3e} J ({:+.3e} of the largest \
                 kinetic energy, {:.3e} J); {} steps, {} Newton iterations, {wall:.1} s",
                e1 - e0,
                drift,
                s.max_kinetic,
                s.steps,
                s.newton_iterations
            )),
    );
    Ok(rows)
}

/// Runs the equivalent model of scene `name` (generalized-alpha): its summary, history, wall
/// time (s) and the common dynamic rows.
fn timed_generalized_alpha(
    ctx: &Ctx,
    name: &str,
) -> anyhow::Result<(DynamicSummary, History, f64, Vec<Row>)> {
    let scene = ctx.scene(name)?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let t = Instant::now();
    let (s, h) = dynamic(ctx, &beam, &opts, "generalized-alpha")?;
    let wall = t.elapsed().as_secs_f64();
    let rows = dynamic_rows(ctx, &s, &h)?;
    Ok((s, h, wall, rows))
}

// ---------------------------------------------------------------------------------------
// The paper law, non-finite values, bad input

/// Statics with the non-monotone `paper` law: each scene converges or stops naming the law
/// and where, in bounded time; a solve starved of iterations must stop with that message.
pub fn paper_law_statics(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let mut rows = Vec::new();
    let mut worst = 0.0f64;
    let mut notes = Vec::new();
    let mut named = true;
    for name in ["paper-law-statics-fig7", "paper-law-statics-sec3"] {
        let scene = ctx.scene(name)?;
        let t = Instant::now();
        let opts = RunOptions {
            out: ctx.out.join(name),
            vtk: false,
        };
        let r = run_scene(&scene, &opts, &mut |_, f| ctx.progress(name, f));
        worst = worst.max(t.elapsed().as_secs_f64());
        let s = r?;
        match s[0].failure() {
            None => notes.push(format!(
                "{name}: converged, {} load steps, {} Newton iterations, {}",
                s[0].steps,
                s[0].newton_iterations,
                s[0].warnings.join("; ")
            )),
            Some(m) => {
                named &= diagnosis_named(&m);
                notes.push(format!("{name}: stopped: {m}"));
            }
        }
    }
    rows.push(
        ctx.check("wall-time", worst, "s")?
            .with_note(notes.join("; ")),
    );
    // Forced failure: two Newton iterations per step, no cutting below 1/4 of the load.
    let scene = ctx.scene("paper-law-statics-sec3")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = StaticOptions {
        max_iterations: 2,
        min_step: 0.25,
        ..StaticOptions::default()
    };
    let forced = match solve_static(&beam, &opts, &mut |_| {}) {
        Ok(_) => "converged".to_string(),
        Err(e) => e.to_string(),
    };
    named &= diagnosis_named(&forced);
    rows.push(
        ctx.check(
            "failure-names-law-and-place",
            f64::from(u8::from(named)),
            "",
        )?
        .with_note(format!("starved solve: {forced}")),
    );
    Ok(rows)
}

/// A `paper`-law failure message names the law, its non-monotonicity, the load reached and
/// the place.
fn diagnosis_named(m: &str) -> bool {
    m.contains("`paper` law")
        && m.contains("non-monotone")
        && m.contains("load fraction")
        && m.contains("x = ")
}

/// A scene whose gravity (1e300 m/s^2) overflows the forces: the run stops naming the step,
/// the time, the element, the place and the quantity, and keeps what it computed.
pub fn non_finite_stop(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("non-finite-gravity")?;
    let opts = RunOptions {
        out: ctx.out.clone(),
        vtk: false,
    };
    let summaries = run_scene(&scene, &opts, &mut |_, _| {})?;
    let message = match summaries.first() {
        Some(s) if s.reason == Some(Failure::NonFinite) => s.error.clone().unwrap_or_default(),
        Some(s) if s.failed() => bail!(
            "the run failed for another reason than a non-finite value: {}",
            s.failure().unwrap_or_default()
        ),
        _ => bail!("the run with gravity 1e300 m/s^2 did not stop"),
    };
    let named = ["(step ", "t = ", "non-finite", "element ", "x = "]
        .iter()
        .all(|k| message.contains(k));
    let dir = ctx.out.join("equivalent");
    let rows_kept = std::fs::read_to_string(dir.join("tip.csv"))
        .map(|t| t.lines().count().saturating_sub(1))
        .unwrap_or(0);
    let status = summary_status(&dir)?;
    Ok(vec![
        ctx.check(
            "message-names-step-time-element-quantity",
            f64::from(u8::from(named)),
            "",
        )?
        .with_note(message),
        ctx.check("tip-rows-kept", rows_kept as f64, "")?,
        ctx.check(
            "summary-says-failed",
            f64::from(u8::from(status == "failed")),
            "",
        )?,
    ])
}

/// Bad scene files (each rejected naming its JSON path, never a panic) and random strand
/// parameters through the runner's set-up.
pub fn bad_input(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let good = std::fs::read_to_string(
        crate::validate::repo_root().join("validation/hard/straight-strand.json"),
    )?;
    let v: serde_json::Value = serde_json::from_str(&good)?;
    // Sets (or adds) the value at the JSON pointer `ptr`.
    let set = |ptr: &str, x: serde_json::Value| {
        let mut s = v.clone();
        let (parent, key) = ptr.rsplit_once('/').expect("a pointer below the root");
        match s.pointer_mut(parent).expect("pointer in the scene") {
            serde_json::Value::Object(m) => {
                m.insert(key.to_string(), x);
            }
            other => *other.pointer_mut(&format!("/{key}")).expect("an element") = x,
        }
        s.to_string()
    };
    let raw = |from: &str, to: &str| {
        let t = v.to_string();
        assert!(t.contains(from), "{from}");
        t.replacen(from, to, 1)
    };
    use serde_json::json;
    let cases: Vec<(&str, String, &str, &str)> = vec![
        ("empty file", String::new(), "", "empty"),
        ("whitespace", " \n\t".into(), "", "empty"),
        ("not an object", "[1, 2]".into(), "[0]", "invalid type"),
        ("truncated", good[..good.len() / 2].to_string(), "*", "EOF"),
        (
            "wrong type",
            set("/strand/length", json!("0.4 m")),
            "strand.length",
            "invalid type",
        ),
        (
            "NaN literal",
            raw("\"length\":0.4", "\"length\":NaN"),
            "strand.length",
            "",
        ),
        (
            "Infinity literal",
            raw("\"length\":0.4", "\"length\":Infinity"),
            "strand.length",
            "",
        ),
        (
            "overflowing number",
            raw("\"length\":0.4", "\"length\":1e999"),
            "strand.length",
            "",
        ),
        (
            "negative size",
            set("/strand/core/diameter", json!(-3e-3)),
            "strand.core.diameter",
            "positive",
        ),
        (
            "zero size",
            set("/strand/length", json!(0.0)),
            "strand.length",
            "positive",
        ),
        (
            "zero elements",
            set("/models/equivalent/elements", json!(0)),
            "models.equivalent.elements",
            "",
        ),
        (
            "huge element count",
            set("/models/equivalent/elements", json!(2_000_000_000i64)),
            "models.equivalent.elements",
            "GiB",
        ),
        (
            "overlapping layer",
            set("/strand/layers/0/wires", json!(9)),
            "strand.layers[0].wires",
            "overlap",
        ),
        (
            "lay angle 95 deg",
            set("/strand/layers/0/lay_angle_deg", json!(95.0)),
            "strand.layers[0].lay_angle_deg",
            "(0, 90)",
        ),
        (
            "unknown field",
            set("/strand/colour", json!("red")),
            "strand.colour",
            "unknown field",
        ),
    ];
    let mut failed = Vec::new();
    for (what, text, path, word) in &cases {
        let r = std::panic::catch_unwind(|| strand_scene::Scene::parse(text));
        match r {
            Err(_) => failed.push(format!("{what}: panicked")),
            Ok(Ok(_)) => failed.push(format!("{what}: accepted")),
            Ok(Err(e)) if (*path != "*" && e.path != *path) || !e.message.contains(word) => {
                failed.push(format!("{what}: `{e}` (expected path `{path}`, `{word}`)"))
            }
            Ok(Err(_)) => {}
        }
    }
    let n = cases.len();
    let (tried, accepted, panics, refused, setup_errors) = random_strands(&v, 400);
    Ok(vec![
        ctx.check(
            "rejected-with-path",
            (n - failed.len()) as f64 / n as f64,
            "",
        )?
        .with_note(if failed.is_empty() {
            format!("{n} bad files, each rejected naming its JSON path")
        } else {
            failed.join("; ")
        }),
        ctx.check("random-strand-panics", panics as f64, "")?
            .with_note(format!(
                "{tried} random strands (values of any sign and magnitude, NaN, infinity) \
                 through Scene::from_file, build_beam, the stable step and the forces: \
                 {accepted} accepted with finite results, {refused} rejected naming a JSON \
                 path, {setup_errors} stopped by the set-up with an error; counted here: \
                 panics, non-finite results and rejections without a path"
            )),
    ])
}

/// Random strand parameters through the set-up: (tried, accepted and finite, panics or
/// non-finite results or rejections without a path, rejections with a path, set-up errors).
fn random_strands(good: &serde_json::Value, n: usize) -> (usize, usize, usize, usize, usize) {
    let base: SceneFile = serde_json::from_value(good.clone()).expect("a scene file");
    // xorshift64*: deterministic, so a failure reproduces.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        state.wrapping_mul(0x2545_F491_4F6C_DD1D)
    };
    let mut value = |typical: f64| -> f64 {
        let r = next();
        match r % 64 {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => -typical,
            3 => 0.0,
            4 => f64::MAX,
            // Up to a factor 30 either way of the typical value.
            _ => typical * 10f64.powf(((r >> 8) % 2001) as f64 / 1000.0 * 1.5 - 1.5),
        }
    };
    let (mut accepted, mut bad, mut refused, mut setup) = (0, 0, 0, 0);
    for _ in 0..n {
        let mut f = base.clone();
        f.strand.length = value(0.4);
        f.strand.core.diameter = value(3e-3);
        f.strand.core.youngs_modulus = value(2e8);
        f.strand.core.density = value(7801.0);
        f.strand.friction = Some(value(0.3));
        let l = &mut f.strand.layers[0];
        l.diameter = value(2e-3);
        l.youngs_modulus = value(2e8);
        l.density = value(7801.0);
        l.lay_angle_deg = Some(value(20.0));
        l.wires = (value(6.0).to_bits() % 12) as i64 - 1;
        if let Some(m) = f.models.equivalent.as_mut() {
            m.elements = (value(8.0).to_bits() % 40) as i64;
        }
        let r = std::panic::catch_unwind(move || -> Result<bool, String> {
            let scene = Scene::from_file(f).map_err(|e| format!("path:{}", e.path))?;
            let setup = |e: &dyn std::fmt::Display| format!("setup:{e}");
            let beam = build_beam(&scene, BeamModelKind::Equivalent).map_err(|e| setup(&e))?;
            let h = stable_step(&beam).map_err(|e| setup(&e))?;
            let slip = beam.initial_state();
            let mut trial = slip.clone();
            let mut force = vec![0.0; beam.coords()];
            beam.internal(beam.reference(), &slip, &mut trial, &mut force, None, None)
                .map_err(|e| setup(&e))?;
            Ok(h.is_finite() && h > 0.0 && force.iter().all(|x| x.is_finite()))
        });
        match r {
            Ok(Ok(true)) => accepted += 1,
            // A rejection must name the JSON path of the fault.
            Ok(Err(e)) if e.starts_with("path:") && e.len() > 5 => refused += 1,
            Ok(Err(e)) if e.starts_with("setup:") => setup += 1,
            _ => bad += 1,
        }
    }
    (n, accepted, bad, refused, setup)
}

// ---------------------------------------------------------------------------------------
// Three-dimensional large motion

/// The section-3 pendulum spun about the vertical (3 rad/s) and released, 5 s of
/// generalized-alpha: the strand whips round in 3D, its tangent passing the opposite of its
/// initial direction, where a section frame carried from the initial tangent is singular.
pub fn spinning_whip(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("spinning-whip")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let init = InitialState::rigid(&beam, scene.velocity, scene.angular_velocity)?;
    let (s, h) = dynamic_from(ctx, &beam, &opts, &init, "generalized-alpha")?;
    let mut rows = dynamic_rows(ctx, &s, &h)?;
    let off_plane = h.tips.iter().map(|p| p[2].abs()).fold(0.0, f64::max);
    rows.push(
        ctx.check("tip-turn-deg", h.tip_turn.to_degrees(), "deg")?
            .with_note(format!(
                "largest angle of the tip's tangent from its initial direction; the tip left \
                 the plane of release by up to {off_plane:.3} m; {} steps, {} Newton iterations",
                s.steps, s.newton_iterations
            )),
    );
    rows.push(ctx.report("dissipated", s.last.dissipated, "J"));
    Ok(rows)
}

/// A strand pinned at both ends whose end support is driven back past the start (to 0.2 L
/// from it, off the plane), under gravity across: the strand folds back on itself, its end
/// tangents nearly opposite.
pub fn folded_strand(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("folded-strand")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let (s, h) = dynamic(ctx, &beam, &opts, "generalized-alpha")?;
    let mut rows = vec![ctx.check("finite", f64::from(u8::from(h.finite)), "")?];
    rows.push(
        ctx.check("fold-deg", h.fold.0.to_degrees(), "deg")?
            .with_note(format!(
                "largest angle between the tangents at the two ends, at t = {:.2} s; {} steps, \
                 {} Newton iterations",
                h.fold.1, s.steps, s.newton_iterations
            )),
    );
    rows.push(
        ctx.report(
            "energy-balance-relative",
            s.balance_error / s.max_kinetic.max(f64::MIN_POSITIVE),
            "",
        )
        .with_note(format!(
            "spectral radius {}: numerical damping takes energy the ledger does not book; \
             support work {:.3e} J, dissipated {:.3e} J",
            scene_rho(&scene),
            s.last.supports,
            s.last.dissipated
        )),
    );
    Ok(rows)
}

fn scene_rho(scene: &Scene) -> f64 {
    match scene.analysis {
        strand_scene::Analysis::Dynamic(d) => d.spectral_radius,
        _ => f64::NAN,
    }
}

/// The section-3 pendulum released under gravity (0, -9.8, -4) in the tilted plane that holds
/// its direction and gravity, with the phase reference the plane's normal, 5 s of
/// generalized-alpha: the spatial beam against the planar beam's run in the XY plane turned
/// into the tilted plane. The planar run at half the step gives the integrator's own error,
/// the scale the two element kinds' difference is judged against, and the order at which the
/// planar run's energy balance closes (the trapezoidal rule's O(h^2): the ledger books each
/// slider's slip work from its own slip, at the friction limit of the step's end, so what is
/// left is the integrator's). The spatial run's distance from
/// the plane of motion, where the planar run is an exact solution of its equations, is
/// reported with the work of the law's non-potential part.
pub fn tilted_pendulum(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let scene = ctx.scene("tilted-pendulum")?;
    let beam = build_beam(&scene, BeamModelKind::Equivalent)?;
    if beam.spec().element != ElementKind::Spatial {
        bail!("tilted-pendulum must run on the spatial element");
    }
    let opts = dynamic_options(&scene).context("a dynamic scene")?;
    let (s, h) = dynamic(ctx, &beam, &opts, "spatial")?;
    let mut rows = dynamic_rows(ctx, &s, &h)?;
    // The same pendulum in the XY plane: gravity turned onto -Y, phases from +Z.
    let g = scene.gravity;
    let gn = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    let mut file = scene.file.clone();
    file.name = "tilted-pendulum-planar".into();
    if let Some(l) = file.loads.as_mut() {
        l.gravity = Some([0.0, -gn, 0.0]);
    }
    if let Some(i) = file.initial.as_mut() {
        i.phase_reference = None;
    }
    let planar = Scene::from_file(file)?;
    if !planar.is_planar() {
        bail!("the planar copy of tilted-pendulum is not planar");
    }
    let pb = build_beam(&planar, BeamModelKind::Equivalent)?;
    let (sp, hp) = dynamic(ctx, &pb, &opts, "planar")?;
    let mut fine = opts;
    let Scheme::GeneralizedAlpha {
        step,
        spectral_radius,
    } = opts.scheme
    else {
        bail!("tilted-pendulum must use generalized-alpha");
    };
    fine.scheme = Scheme::GeneralizedAlpha {
        step: 0.5 * step,
        spectral_radius,
    };
    let (sf, hf) = dynamic(ctx, &pb, &fine, "planar at h/2")?;
    // The planar run's (x, y) turned into the tilted plane: X stays, -Y goes to gravity.
    let down = [g[0] / gn, g[1] / gn, g[2] / gn];
    let turn = |p: [f64; 3]| {
        let d = -p[1];
        [p[0] + d * down[0], d * down[1], d * down[2]]
    };
    let largest = |a: &[[f64; 3]], b: &[[f64; 3]], f: &dyn Fn([f64; 3]) -> [f64; 3]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| distance(f(*x), *y))
            .fold(0.0, f64::max)
    };
    let apart = largest(&hp.tips, &h.tips, &turn);
    let integrator = largest(&hp.tips, &hf.tips, &|p| p);
    let passed = h.tips.iter().any(|p| p[0] < -0.5);
    rows.push(
        ctx.check("tip-from-planar-over-integrator", apart / integrator, "")?
            .with_note(format!(
                "largest tip distance over 5 s from the planar run turned into the plane \
                 {apart:.3e} m; the planar run at h and h/2 differ by {integrator:.3e} m; the \
                 tip {} behind the pin",
                if passed { "swung" } else { "never swung" }
            )),
    );
    // The plane of motion holds the initial direction and gravity.
    let d = scene.direction;
    let normal = [
        d[1] * down[2] - d[2] * down[1],
        d[2] * down[0] - d[0] * down[2],
        d[0] * down[1] - d[1] * down[0],
    ];
    let off_plane = h
        .tips
        .iter()
        .map(|p| (p[0] * normal[0] + p[1] * normal[1] + p[2] * normal[2]).abs())
        .fold(0.0, f64::max)
        / (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
    rows.push(
        ctx.report("tip-off-plane", off_plane, "m")
            .with_note(format!(
                "largest distance of the spatial run's tip from the plane of motion over 5 s; the \
         law's non-potential work on the spatial run {:.3e} J (zero in the plane)",
                s.last.non_potential
            )),
    );
    let relative = |s: &DynamicSummary| s.balance_error / s.max_kinetic.max(f64::MIN_POSITIVE);
    let (bh, bf) = (relative(&sp), relative(&sf));
    rows.push(
        ctx.check("planar-energy-balance-relative", bh, "")?
            .with_note(format!(
                "the planar run's balance at h = {:.3e} s; {:.3e} at h/2",
                sp.time_step, bf
            )),
    );
    rows.push(ctx.check("planar-balance-order", (bh / bf).log2(), "")?);
    rows.push(ctx.check("tip-turn-deg", h.tip_turn.to_degrees(), "deg")?);
    Ok(rows)
}
