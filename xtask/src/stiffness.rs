//! `cargo xtask stiffness`: the section laws' all-slip stiffness K_min (Costello's thin-rod
//! wire stiffness, `strand_core::wire_bending`) against the fine model, converged in its
//! segments per pitch.
//!
//! * Bending: the frictionless virtual bending test (`strand_fine::BendingTest::frictionless`,
//!   T = 0.1 N, kappa = 0.1 1/m, six pitches) of the Table 1 geometry at lay angles 5, 15, 25,
//!   35 deg, 12 to 96 segments per pitch: M / kappa within 1 % of K_min at the finest, which
//!   must be within 2e-3 of the one before (the fine model's own error well below 1 %).
//! * Cantilevers: the frictionless strands of `validation/stiffness/` (not the paper's: other
//!   lay angles, diameters, moduli, wire counts), clamped under gravity, statics. The fine
//!   model at 5, 10, 20, 40 segments per pitch, extrapolated from the four (Richardson: two
//!   observed orders that agree, capped at 2), its finest mesh's estimated error required below 5e-4 L; the equivalent
//!   model at 32 and 64 elements with each base stiffness; the default (Costello) at 64
//!   elements within 1e-3 L of the fine model's extrapolated tip (and reported against its
//!   finest). `--coarse-first` refines 2.5, 5, 10, 20 segments per pitch instead and runs 40
//!   only for a strand whose two orders from those do not agree (same rule, a quarter of the
//!   cost where they agree: each doubling costs about four times the one before).
//!
//! It prints one table and writes `target/stiffness/report.{md,json}`; `--quick` runs the
//! bending test at 12 and 24 segments per pitch only (seconds).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use strand_core::convergence::Richardson;
use strand_core::{BaseStiffness, SectionOptions, Strand, StrandSpec};
use strand_fine::BendingTest;
use strand_scene::format::{BeamModelFile, FineModelFile, ModelsFile, SectionFile};
use strand_scene::{RunOptions, Scene, run_scene};

use crate::validate::machine::Provenance;
use crate::validate::repo_root;
use crate::validate::report::{Bound, Report, Row};

/// Options of `cargo xtask stiffness`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct StiffnessArgs {
    /// Only the bending test at 12 and 24 segments per pitch.
    #[arg(long)]
    pub quick: bool,
    /// Folder of the report and the runs [default: target/stiffness].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Also write the table into its page of the manual (docs/book/src/validation.md, between the
    /// `stiffness` markers); only for a full run.
    #[arg(long)]
    pub update_docs: bool,
    /// The cheaper refinement of the fine cantilevers: 2.5, 5, 10, 20 segments per pitch, and
    /// 40 only for a strand whose two observed orders from those four do not agree (the finest
    /// mesh costs about four times the one before; see [`coarse_first_levels`]).
    #[arg(long)]
    pub coarse_first: bool,
}

/// Lay angles of the bending test (deg).
const LAY_ANGLES: [f64; 4] = [5.0, 15.0, 25.0, 35.0];
/// K_min against the converged bending test: the figure.
const BENDING_TOL: f64 = 1e-2;
/// The fine model's change between its two finest meshes, a fifth of `BENDING_TOL`.
const BENDING_CONVERGED: f64 = 2e-3;
/// Tip of the equivalent model against the fine model (of L): the figure.
const TIP_TOL: f64 = 1e-3;
/// The fine model's estimated error at its finest mesh (of L), half of `TIP_TOL`: the
/// extrapolation from there is a small correction.
const FINE_ERROR: f64 = 5e-4;
/// Segments per pitch of the fine cantilevers: four levels, for two order estimates.
const FINE_SPP: [f64; 4] = [5.0, 10.0, 20.0, 40.0];
/// With `--coarse-first`: the four levels tried first, one coarser than [`FINE_SPP`] instead
/// of the finest.
const COARSE_FIRST_SPP: [f64; 4] = [2.5, 5.0, 10.0, 20.0];

/// The four meshes (indices into `levels`, coarse first, each twice the one before) whose
/// changes judge the fine model under `--coarse-first`: the four coarsest when their two
/// observed orders agree (Richardson's rule, `strand_core::convergence`), else the four
/// finest, and `None` while the finest of `levels` has not been run (`changes` holds the
/// changes between successive levels run so far).
pub fn coarse_first_levels(changes: &[f64]) -> Option<[usize; 4]> {
    match changes {
        [d1, d2, d3] => Richardson::from_changes([*d1, *d2, *d3], 2.0, 2.0)
            .established()
            .then_some([0, 1, 2, 3]),
        [_, _, _, _] => Some([1, 2, 3, 4]),
        _ => None,
    }
}
/// Elements of the equivalent cantilevers.
const ELEMENTS: [usize; 2] = [32, 64];

/// Runs the study and writes the report; the caller decides the exit status.
pub fn run(args: &StiffnessArgs) -> anyhow::Result<Report> {
    if args.update_docs && args.quick {
        anyhow::bail!("--update-docs writes the manual's table from a full run: drop --quick");
    }
    let t0 = Instant::now();
    let root = repo_root();
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join("stiffness"));
    let mut rows = bending(args.quick)?;
    if !args.quick {
        let dir = root.join("validation").join("stiffness");
        let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
            .with_context(|| format!("listing {}", dir.display()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "json"))
            .collect();
        names.sort();
        for path in names {
            let scene =
                Scene::load(&path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
            rows.extend(cantilever(
                &scene,
                &out.join("runs").join(&scene.name),
                args.coarse_first,
            )?);
        }
    }
    let report = Report::new(
        Provenance::detect(&root),
        args.quick,
        t0.elapsed().as_secs_f64(),
        rows,
    )
    .titled("Base stiffness report", "study", "xtask/src/stiffness.rs");
    report.write(&out)?;
    if args.update_docs {
        crate::book::pages::update(
            crate::book::pages::Page::Validation,
            "stiffness",
            &report.docs(),
        )?;
    }
    Ok(report)
}

/// The Table 1 strand (core 3 mm, six 2 mm wires, E = 2e8 Pa, nu = 0.3) at lay angle `deg`,
/// without friction.
fn table1_at(deg: f64) -> anyhow::Result<Strand> {
    let mut spec = StrandSpec::paper(1.0, 2.0e8, 7801.0);
    spec.layers[0].lay_angle = deg.to_radians();
    spec.friction = 0.0;
    Ok(Strand::new(spec)?)
}

/// The bending rows: per lay angle, M / kappa over K_min at each mesh, then the checks.
fn bending(quick: bool) -> anyhow::Result<Vec<Row>> {
    let spp: &[usize] = if quick { &[12, 24] } else { &[12, 24, 48, 96] };
    let mut rows = Vec::new();
    for deg in LAY_ANGLES {
        let s = table1_at(deg)?;
        let scene = format!("bending {deg} deg");
        let k_min = |b: BaseStiffness| s.min_bending_stiffness(b);
        let mut k = Vec::new();
        for &n in spp {
            let t = Instant::now();
            let curve = BendingTest::frictionless(6, n, 0.1, 0.1)
                .run(&s)
                .with_context(|| format!("{scene}, {n} segments per pitch"))?;
            let m = curve.last().expect("one curvature").secant_stiffness();
            eprintln!(
                "{scene}: {n} segments per pitch, {:.1} s",
                t.elapsed().as_secs_f64()
            );
            rows.push(
                Row::measured(
                    &scene,
                    "K/K_min",
                    &format!("spp={n}"),
                    m / k_min(BaseStiffness::Costello),
                    "",
                    Bound::None,
                )
                .with_note(format!(
                    "M/kappa {m:.5e} N m^2; over Foti's K_min {:.4}, Papailiou's {:.4}, the \
                     paper's {:.4}",
                    m / k_min(BaseStiffness::Foti),
                    m / k_min(BaseStiffness::Papailiou),
                    m / k_min(BaseStiffness::Paper)
                )),
            );
            k.push(m);
        }
        let (fine, prev) = (k[k.len() - 1], k[k.len() - 2]);
        let mut conv = Row::measured(
            &scene,
            "fine-convergence",
            "change",
            (fine - prev).abs() / fine,
            "",
            Bound::AtMost(BENDING_CONVERGED),
        );
        conv.why = "the fine model's change between its two finest meshes, a fifth of the 1 % \
                    claim"
            .into();
        rows.push(conv);
        let mut row = Row::measured(
            &scene,
            "K_min",
            "costello",
            (fine / k_min(BaseStiffness::Costello) - 1.0).abs(),
            "",
            Bound::AtMost(BENDING_TOL),
        );
        row.why = "K_min of the section laws within 1 % of the converged frictionless bending \
                   test (issue 15)"
            .into();
        rows.push(row);
    }
    Ok(rows)
}

/// Tip (x, y, z) of `scene` run with `models` and the section `base` into `dir`.
fn tip(
    scene: &Scene,
    models: ModelsFile,
    base: Option<BaseStiffness>,
    dir: &std::path::Path,
) -> anyhow::Result<[f64; 3]> {
    let mut file = scene.file.clone();
    file.models = models;
    if let Some(b) = base {
        file.section = Some(SectionFile {
            base_stiffness: Some(b.name().into()),
            ..Default::default()
        });
    }
    let s = Scene::from_file(file).map_err(|e| anyhow::anyhow!("{}: {e}", scene.name))?;
    let opts = RunOptions {
        out: dir.to_path_buf(),
        vtk: false,
    };
    let t = Instant::now();
    let summary = run_scene(&s, &opts, &mut |_, _| {})
        .with_context(|| format!("{} into {}", scene.name, dir.display()))?;
    eprintln!(
        "{}: {} in {:.1} s",
        scene.name,
        dir.display(),
        t.elapsed().as_secs_f64()
    );
    if let Some(e) = summary[0].failure() {
        anyhow::bail!("{}: {e}", scene.name);
    }
    summary[0]
        .tip
        .with_context(|| format!("{}: no tip position", scene.name))
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The cantilever rows of one scene: the fine model's tips and its convergence, then the
/// equivalent model's tip with each base stiffness against the finest.
fn cantilever(
    scene: &Scene,
    out: &std::path::Path,
    coarse_first: bool,
) -> anyhow::Result<Vec<Row>> {
    let name = &scene.name;
    let strand = &scene.strand;
    let l = strand.length();
    let pitch = strand.layers().first().context("a stranded scene")?.pitch;
    let penetration = scene.file.models.fine.as_ref().and_then(|f| f.penetration);
    let mut rows = Vec::new();
    let run_fine = |spp: f64| -> anyhow::Result<(i64, [f64; 3])> {
        let segments = (spp * l / pitch).round().max(2.0) as i64;
        let models = ModelsFile {
            fine: Some(FineModelFile {
                segments_per_wire: segments,
                penetration,
                bind_free_end: None,
            }),
            ..Default::default()
        };
        Ok((
            segments,
            tip(scene, models, None, &out.join(format!("fine-{segments}")))?,
        ))
    };
    let mut fine = Vec::new();
    if coarse_first {
        for spp in COARSE_FIRST_SPP {
            fine.push(run_fine(spp)?);
        }
        let changes = |f: &[(i64, [f64; 3])]| -> Vec<f64> {
            f.windows(2).map(|w| distance(&w[0].1, &w[1].1)).collect()
        };
        if coarse_first_levels(&changes(&fine)).is_none() {
            fine.push(run_fine(FINE_SPP[3])?);
        }
        let used = coarse_first_levels(&changes(&fine)).expect("four changes decide");
        fine = used.iter().map(|&i| fine[i]).collect();
    } else {
        for spp in FINE_SPP {
            fine.push(run_fine(spp)?);
        }
    }
    let finest = fine[fine.len() - 1].1;
    for (segments, t) in &fine {
        rows.push(
            Row::measured(
                name,
                "fine-tip",
                &format!("segments={segments}"),
                distance(t, &finest) / l,
                "L",
                Bound::None,
            )
            .with_note(format!(
                "{:.2} segments per pitch; tip ({:.6}, {:.6}, {:.6}) m, distance to the finest",
                *segments as f64 * pitch / l,
                t[0],
                t[1],
                t[2]
            )),
        );
    }
    // Richardson: the finest's error from the three changes, its order established by two
    // estimates that agree and capped at the segments' second order. Without an established
    // order the estimate is NaN, which fails the row.
    let d = [0, 1, 2].map(|k| distance(&fine[k].1, &fine[k + 1].1));
    let richardson = Richardson::from_changes(d, 2.0, 2.0);
    let (order, estimate) = (richardson.order, richardson.finest_error);
    let middle = fine[fine.len() - 2].1;
    let converged = match richardson.limit(&middle, &finest) {
        Some(limit) => [limit[0], limit[1], limit[2]],
        None => finest,
    };
    let mut row = Row::measured(
        name,
        "fine-error",
        "finest",
        estimate / l,
        "L",
        Bound::AtMost(FINE_ERROR),
    )
    .with_note(format!(
        "differences {:.3e}, {:.3e}, {:.3e} m between the meshes (orders {:.2}, {:.2}, used \
         {order:.2}); extrapolated tip ({:.6}, {:.6}, {:.6}) m",
        d[0],
        d[1],
        d[2],
        richardson.observed_orders[0],
        richardson.observed_orders[1],
        converged[0],
        converged[1],
        converged[2]
    ));
    row.why = "the fine model's own error at its finest mesh (Richardson), half of the 1e-3 L \
               claim"
        .into();
    rows.push(row);
    for base in BaseStiffness::ALL {
        let mut tips = Vec::new();
        for n in ELEMENTS {
            let models = ModelsFile {
                equivalent: Some(BeamModelFile {
                    elements: n as i64,
                    integration_points: None,
                    mass_per_length: None,
                    bending_stiffness: None,
                    axial_stiffness: None,
                }),
                ..Default::default()
            };
            let dir = out.join(format!("equivalent-{base}-{n}"));
            tips.push(tip(scene, models, Some(base), &dir)?);
        }
        let t = tips[tips.len() - 1];
        let bound = if base == SectionOptions::default().base_stiffness {
            Bound::AtMost(TIP_TOL)
        } else {
            Bound::None
        };
        let mut row = Row::measured(
            name,
            "equivalent-vs-fine",
            &format!("{base} tip"),
            distance(&t, &converged) / l,
            "L",
            bound,
        )
        .with_note(format!(
            "{} elements: tip ({:.6}, {:.6}) m, {:.2e} L from the finest fine mesh; {} \
             elements {:.1e} L away",
            ELEMENTS[1],
            t[0],
            t[1],
            distance(&t, &finest) / l,
            ELEMENTS[0],
            distance(&tips[0], &t) / l
        ));
        if bound != Bound::None {
            row.why = "the equivalent model's tip within 1e-3 L of the fine model extrapolated \
                       in segments per pitch (issue 15)"
                .into();
        }
        rows.push(row);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_finest_mesh_runs_only_where_the_coarse_orders_disagree() {
        // Second-order changes: two orders of 2.0, established on the four coarse meshes.
        assert_eq!(
            coarse_first_levels(&[4e-4, 1e-4, 2.5e-5]),
            Some([0, 1, 2, 3])
        );
        // Orders 2.0 and 1.0 disagree: the finest mesh is needed.
        assert_eq!(coarse_first_levels(&[4e-4, 1e-4, 5e-5]), None);
        // Then the four finest judge, whatever their orders.
        assert_eq!(
            coarse_first_levels(&[4e-4, 1e-4, 5e-5, 1.2e-5]),
            Some([1, 2, 3, 4])
        );
        assert_eq!(coarse_first_levels(&[4e-4, 1e-4]), None);
    }
}
