//! `cargo xtask bonded`: the bonded (all-stick) bending stiffness of the fine model, explained.
//!
//! The fine model's virtual bending test (`strand_fine::BendingTest`, friction so high that
//! no contact slips) measures the initial bending stiffness of a strand; the closed form is
//! the plane-section K_max. Each variant removes (or softens) one compliance that K_max
//! ignores: the contacts' normal and tangential penalties, the wires' shear and torsion, the
//! core's shear, the eccentricity of the bond line (friction acts on the wires' surface, r_w
//! from their axes). For each the fine model runs at 24, 48 and 96 segments per pitch and its
//! limit is extrapolated from the observed order; beside it stands the rod model of the
//! bonded strand (`strand_core::bonded`) with the same idealisations. More rows measure what
//! the extrapolation leaves: the number of pitches (end effects), two contact points per
//! segment, the tension.
//!
//! Criteria (`validation/bonded/criteria.json` holds them with their reasons): every variant's
//! extrapolated fine stiffness within the stated distance of the rod model; with the bond on
//! the wires' axes and a shear-rigid core, the fine stiffness within 2 % of K_max; the
//! physical strand's rod-model value (rigid bond) within 5 % of the fine model's. The
//! report is `target/bonded/report.{md,json}` and the table on stdout.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use serde::{Deserialize, Serialize};
use strand_core::{
    BondedOptions, BondedStiffness, LayDirection, LayerSpec, Material, Strand, StrandSpec,
    WireSpec, bonded_stiffness,
};
use strand_fine::{BendingTest, ContactOptions, SpringScale};

mod curve;
mod multilayer;

use crate::validate::machine::Provenance;
use crate::validate::repo_root;
use crate::validate::report::{Bound, Report, Row};

/// Options of `cargo xtask bonded`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct BondedArgs {
    /// Only the Table 1 strand's physical and compliance-free variants (with `--multilayer`:
    /// the 1+6+12 strand's).
    #[arg(long)]
    pub quick: bool,
    /// The 1+6+12 strand of `examples/steel-1x19-swing.json` instead of the one-layer
    /// strands (`validation/bonded/multilayer-criteria.json`; `--update-docs` writes its table into
    /// docs/book/src/multilayer.md, between the `bonded-multilayer` markers).
    #[arg(long)]
    pub multilayer: bool,
    /// Only this variant (e.g. `physical`, `removed`; `curve`: only the moment-curvature
    /// curves with friction; with `--multilayer` also `wire-torsion`, `stiff-penalties`,
    /// ...).
    #[arg(long, value_name = "NAME")]
    pub variant: Option<String>,
    /// Folder of the report [default: target/bonded].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Also write the curves' tables into their page of the manual (docs/book/src/validation.md,
    /// between the `bonded` markers); with the full study or `--variant curve`.
    #[arg(long)]
    pub update_docs: bool,
}

/// Limits of the study and their reasons (`validation/bonded/criteria.json`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Limits {
    /// Largest |K_fine / K_rod - 1| of a variant (extrapolated fine model).
    rod_model: Limit,
    /// Largest |K_fine / K_max - 1| with the ignored compliances removed.
    k_max: Limit,
    /// Largest |K_rod / K_fine - 1| of the physical strand (rigid bond in the rod model).
    physical: Limit,
    /// Largest remaining discretisation error of an extrapolated value (relative).
    discretisation: Limit,
    /// Largest |M_law / M_fine - 1| along the moment-curvature curve with friction.
    curve: Limit,
    /// Largest change of the curve's fine moment from 24 to 48 segments per pitch.
    curve_mesh: Limit,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Limit {
    value: f64,
    why: String,
}

impl Limit {
    /// The row judging `value` against this upper limit, with its reason.
    fn row(&self, strand: &str, check: &str, metric: &str, value: f64) -> Row {
        let mut r = Row::measured(strand, check, metric, value, "", Bound::AtMost(self.value));
        r.why = self.why.clone();
        r
    }
}

/// The bending test's settings shared by every run of one strand.
#[derive(Debug, Clone, Copy)]
struct Loading {
    /// Axial strain of the tension (-).
    strain: f64,
    /// Wire strain of the contacts' reference tension (-): it sets the normal penalty.
    reference_strain: f64,
    /// Bending strain kappa R_w at the wires' axes (-).
    bending_strain: f64,
}

/// One idealisation of the strand (a row of the study).
#[derive(Debug, Clone)]
struct Variant {
    name: &'static str,
    what: &'static str,
    core: SpringScale,
    wire: SpringScale,
    contact: ContactOptions,
    /// Factor on the loading's strain (tension rows).
    strain_factor: f64,
    /// Whether the rod model is the reference (false: reported only).
    compare: bool,
    /// Whether the refinement must be in its asymptotic range (false: reported only).
    asymptotic: bool,
}

/// Stiff penalties: allowed penetration 1e-5 d_w, stick loss 5e-4 (the rod model puts their
/// compliance at a few parts in 1e3 of the bonded stiffness; see the `rigid` column).
fn stiff() -> ContactOptions {
    ContactOptions {
        penetration: 1e-5,
        stick_loss: 5e-4,
        points_per_segment: Some(1),
        ..Default::default()
    }
}

fn variant(name: &'static str, what: &'static str) -> Variant {
    Variant {
        name,
        what,
        core: SpringScale::default(),
        wire: SpringScale::default(),
        contact: stiff(),
        strain_factor: 1.0,
        compare: true,
        asymptotic: true,
    }
}

/// The variants of the Table 1 strand.
fn variants(quick: bool, r_w: f64) -> Vec<Variant> {
    let physical = variant("physical", "real wires and core, stiff penalties");
    let removed = Variant {
        core: SpringScale {
            shear: 100.0,
            ..Default::default()
        },
        contact: ContactOptions {
            contact_radius: Some(r_w),
            ..stiff()
        },
        ..variant(
            "removed",
            "bond on the wires' axes and core shear x100: the plane-section strand",
        )
    };
    if quick {
        return vec![physical, removed];
    }
    let mut v = vec![physical.clone()];
    v.push(Variant {
        contact: ContactOptions {
            penetration: 1e-3,
            ..stiff()
        },
        ..variant(
            "normal-penalty",
            "normal penalty 100 times softer (1e-3 d_w)",
        )
    });
    v.push(Variant {
        contact: ContactOptions {
            stick_loss: 0.05,
            ..stiff()
        },
        ..variant(
            "stick-penalty",
            "tangential penalty 100 times softer (loss 0.05)",
        )
    });
    v.push(Variant {
        wire: SpringScale {
            shear: 10.0,
            ..Default::default()
        },
        ..variant("wire-shear", "wires' kappa G A x10")
    });
    v.push(Variant {
        wire: SpringScale {
            torsion: 10.0,
            ..Default::default()
        },
        ..variant("wire-torsion", "wires' G J x10")
    });
    v.push(Variant {
        core: SpringScale {
            shear: 100.0,
            ..Default::default()
        },
        ..variant("core-shear", "core's kappa G A x100")
    });
    v.push(Variant {
        contact: ContactOptions {
            contact_radius: Some(r_w),
            ..stiff()
        },
        ..variant(
            "bond-on-axes",
            "bond line on the wires' axes (no eccentricity on them)",
        )
    });
    v.push(removed);
    for (name, f) in [("tension-x10", 10.0), ("tension-x100", 100.0)] {
        v.push(Variant {
            strain_factor: f,
            compare: false,
            ..variant(name, "tension 10 and 100 times higher, same penalties")
        });
    }
    // Two contact points per segment resist the rocking of a segment on the core with their
    // tangential springs at +-l/4: a rotational spring k_t l^2 / 16 per unit length against
    // the wire's own G J k^2, which it exceeds until l is a small fraction of a millimetre,
    // so the pair bonds the wire's section and the refinement is far from its limit at 96
    // segments per pitch. With the stiff penalties Newton stalls on it, so this pair compares
    // one and two points at penalties 10 times softer and the tension of tension-x10 (at the
    // low tension one of the two points rocks open).
    let moderate = |points: usize| ContactOptions {
        penetration: 1e-4,
        stick_loss: 5e-3,
        points_per_segment: Some(points),
        ..Default::default()
    };
    v.push(Variant {
        contact: moderate(1),
        strain_factor: 10.0,
        compare: false,
        ..variant(
            "one-point",
            "penalties 10 times softer, tension as tension-x10",
        )
    });
    v.push(Variant {
        contact: moderate(2),
        strain_factor: 10.0,
        compare: false,
        asymptotic: false,
        ..variant(
            "two-points",
            "as one-point with two contact points per segment",
        )
    });
    v
}

/// Segments per pitch of the refinement.
const MESHES: [usize; 3] = [24, 48, 96];

/// Measured initial stiffnesses of one variant.
#[derive(Debug, Clone, Serialize)]
struct Measured {
    strand: String,
    variant: String,
    what: String,
    /// Whether the refinement is judged (asymptotic range expected).
    asymptotic: bool,
    /// Stiffness at each mesh of [`MESHES`] (N m^2).
    fine: Vec<f64>,
    /// Observed order of convergence (-).
    order: Option<f64>,
    /// Extrapolated limit (N m^2) and its error estimate (relative).
    limit: f64,
    limit_error: f64,
    /// The same at 6 pitches, 48 segments per pitch (N m^2), physical variant only.
    six_pitches: Option<f64>,
    /// Moment at the clamp over the moment in the middle pitches (-), finest mesh.
    clamp_ratio: f64,
    /// Rod model with the variant's penalties and with a rigid bond (N m^2).
    rod: f64,
    rod_rigid: f64,
    k_max: f64,
    wall_time: f64,
}

/// Table 1 strand and a second strand (five wires at 35 deg, wires softer than the core).
fn strands() -> Vec<(&'static str, Strand)> {
    let table1 = Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).expect("Table 1 strand");
    let mat = |e: f64, nu: f64, rho: f64| Material {
        youngs_modulus: e,
        poisson_ratio: nu,
        density: rho,
    };
    let five = Strand::new(StrandSpec {
        length: 0.12,
        core: WireSpec {
            diameter: 2.0e-3,
            material: mat(1.5e8, 0.3, 7800.0),
        },
        layers: vec![LayerSpec {
            wires: 5,
            wire: WireSpec {
                diameter: 1.7e-3,
                material: mat(7.5e7, 0.33, 2700.0),
            },
            lay_angle: 35f64.to_radians(),
            phase: 0.0,
            direction: LayDirection::Right,
        }],
        friction: 0.3,
    })
    .expect("five-wire strand");
    vec![("table1", table1), ("five-wires-35deg", five)]
}

fn bending_test(
    strand: &Strand,
    load: &Loading,
    v: &Variant,
    spp: usize,
    pitches: usize,
) -> BendingTest {
    let layer = strand.layers().first().expect("a helical layer");
    let w = &layer.spec.wire;
    let wire_ea = w.material.youngs_modulus * w.area() * layer.lay_angle().cos().powi(2);
    let tension = load.strain * v.strain_factor * strand.axial_stiffness();
    BendingTest {
        pitches,
        segments_per_pitch: spp,
        tension,
        curvatures: vec![load.bending_strain / layer.radius],
        contact: ContactOptions {
            reference_tension: Some(wire_ea * load.reference_strain),
            ..v.contact
        },
        friction: 1e3,
        statics: BendingTest::load_step_statics(tension),
        max_halvings: 6,
        core_springs: v.core,
        wire_springs: v.wire,
        pressure: Default::default(),
    }
}

/// Initial stiffness M / kappa (N m^2) and clamp-to-middle moment ratio of one run.
fn measure(strand: &Strand, test: &BendingTest) -> anyhow::Result<(f64, f64)> {
    let curve = test.run(strand).context("bending test")?;
    let p = curve.last().context("no bending point")?;
    if p.slip > 0 || p.open > 0 {
        bail!(
            "{} contacts slip and {} are open: not bonded",
            p.slip,
            p.open
        );
    }
    Ok((p.secant_stiffness(), p.clamp_moment / p.moment))
}

/// Observed order and Richardson limit of three values on meshes halving the segment; the
/// error estimate is the distance of the limit from the finest value.
fn extrapolate(k: &[f64]) -> (Option<f64>, f64, f64) {
    let (d1, d2) = (k[1] - k[0], k[2] - k[1]);
    let order = (d1 / d2).log2();
    if d1 * d2 > 0.0 && order.is_finite() && order > 0.5 {
        let limit = k[2] + d2 / (2f64.powf(order) - 1.0);
        (Some(order), limit, ((limit - k[2]) / limit).abs())
    } else {
        // Not in the asymptotic range: the finest value, with the last change as its error.
        (None, k[2], (d2 / k[2]).abs())
    }
}

fn rod(strand: &Strand, options: &BondedOptions) -> anyhow::Result<BondedStiffness> {
    bonded_stiffness(strand, options).context("rod model: the strand needs at least 3 wires")
}

/// Runs one variant on the refinement meshes and the rod model beside it.
fn study(sname: &str, strand: &Strand, load: &Loading, v: &Variant) -> anyhow::Result<Measured> {
    let t = Instant::now();
    let mut fine = Vec::new();
    let mut clamp_ratio = 0.0;
    for spp in MESHES {
        let test = bending_test(strand, load, v, spp, 3);
        let (k, c) = measure(strand, &test).with_context(|| format!("{spp} segments per pitch"))?;
        eprintln!(
            "  {sname} {:<14} {spp:>3} segments per pitch: K = {k:.5e} N m^2",
            v.name
        );
        fine.push(k);
        clamp_ratio = c;
    }
    let six_pitches = if v.name == "physical" {
        let test = bending_test(strand, load, v, MESHES[1], 6);
        Some(measure(strand, &test).context("6 pitches")?.0)
    } else {
        None
    };
    let (order, limit, limit_error) = extrapolate(&fine);
    let test = bending_test(strand, load, v, MESHES[0], 3);
    let options = test
        .rod_options(strand)
        .context("the variant's factors have no rod-model counterpart")?;
    let rod_pen = rod(strand, &options)?;
    let rod_rigid = rod(
        strand,
        &BondedOptions {
            tangential_stiffness: None,
            normal_stiffness: None,
            ..options
        },
    )?;
    Ok(Measured {
        strand: sname.into(),
        variant: v.name.into(),
        what: v.what.into(),
        asymptotic: v.asymptotic,
        fine,
        order,
        limit,
        limit_error,
        six_pitches,
        clamp_ratio,
        rod: if v.compare { rod_pen.bonded } else { f64::NAN },
        rod_rigid: rod_rigid.bonded,
        k_max: strand.max_bending_stiffness(strand_core::BaseStiffness::Costello),
        wall_time: t.elapsed().as_secs_f64(),
    })
}

/// Runs the study and writes the report; the caller decides the exit status.
pub fn run(args: &BondedArgs) -> anyhow::Result<Report> {
    if args.multilayer {
        return run_multilayer(args);
    }
    if args.update_docs && (args.quick || args.variant.as_ref().is_some_and(|v| v != "curve")) {
        anyhow::bail!(
            "--update-docs writes the manual's curve tables: run the full study or --variant curve"
        );
    }
    let t0 = Instant::now();
    let root = repo_root();
    let path = root.join("validation/bonded/criteria.json");
    let text = std::fs::read_to_string(&path).with_context(|| format!("{}", path.display()))?;
    let limits: Limits =
        serde_json::from_str(&text).with_context(|| format!("{}", path.display()))?;
    let load = Loading {
        strain: 2.2e-4,
        reference_strain: 2.2e-3,
        bending_strain: 2.5e-5,
    };
    let mut measured = Vec::new();
    let mut failed = Vec::new();
    for (si, (sname, strand)) in strands().into_iter().enumerate() {
        if args.quick && si > 0 {
            break;
        }
        let layer = *strand.layers().first().expect("a helical layer");
        let list = if si == 0 {
            variants(args.quick, layer.radius)
        } else {
            variants(true, layer.radius)
        };
        for v in list
            .iter()
            .filter(|v| args.variant.as_ref().is_none_or(|n| n == v.name))
        {
            match study(sname, &strand, &load, v) {
                Ok(m) => measured.push(m),
                Err(e) => failed.push(Row::failed(sname, v.name, "-", format!("{e:#}"))),
            }
        }
    }
    let mut rows = judge(&measured, &limits);
    rows.extend(failed);
    // The equivalent law against the fine bending test with friction (not in --quick).
    let mut curves = Vec::new();
    if !args.quick && args.variant.as_ref().is_none_or(|n| n == "curve") {
        let strand = curve::strand();
        for t in curve::TENSIONS {
            match curve::run(&strand, t) {
                Ok(c) => {
                    rows.extend(curve::judge(&c, &limits.curve, &limits.curve_mesh));
                    curves.push(c);
                }
                Err(e) => rows.push(Row::failed(
                    "table1",
                    &format!("curve-T{t}"),
                    "-",
                    format!("{e:#}"),
                )),
            }
        }
    }
    let (report, out) = write_report(
        args,
        t0,
        rows,
        "Bonded stiffness study",
        "validation/bonded/criteria.json",
        "bonded",
    )?;
    let mut detail = details(&measured);
    for c in &curves {
        detail += &curve::details(c);
    }
    write_study(&out, &detail, &measured)?;
    std::fs::write(
        out.join("curves.json"),
        serde_json::to_string_pretty(&curves)? + "\n",
    )?;
    print!("{detail}");
    if args.update_docs {
        crate::book::pages::update(
            crate::book::pages::Page::Validation,
            "bonded",
            &curve_docs(&report, &curves),
        )?;
    }
    Ok(report)
}

/// `--multilayer`: the 1+6+12 strand's study ([`multilayer`]).
fn run_multilayer(args: &BondedArgs) -> anyhow::Result<Report> {
    if args.update_docs && (args.quick || args.variant.is_some()) {
        anyhow::bail!(
            "--update-docs writes the full multi-layer table: run it without --quick and --variant"
        );
    }
    let t0 = Instant::now();
    let limits = multilayer::limits()?;
    let (measured, failed) = multilayer::run(args.quick, args.variant.as_deref());
    let mut rows = multilayer::judge(&measured, &limits);
    rows.extend(failed);
    let (report, out) = write_report(
        args,
        t0,
        rows,
        "Bonded stiffness study, 1+6+12 strand",
        "validation/bonded/multilayer-criteria.json",
        "bonded-multilayer",
    )?;
    let detail = multilayer::details(&measured);
    write_study(&out, &detail, &measured)?;
    print!("{detail}");
    if args.update_docs {
        crate::book::pages::update(
            crate::book::pages::Page::Multilayer,
            "bonded-multilayer",
            &(report.docs() + "\n" + &detail),
        )?;
    }
    Ok(report)
}

/// The report of `rows`, judged against the criteria file `criteria`, titled `title` and timed
/// from `t0`, written into `--out` or `target/<default_out>`; returns it and the folder.
fn write_report(
    args: &BondedArgs,
    t0: Instant,
    rows: Vec<Row>,
    title: &str,
    criteria: &str,
    default_out: &str,
) -> anyhow::Result<(Report, PathBuf)> {
    let root = repo_root();
    let report = Report::new(
        Provenance::detect(&root),
        args.quick,
        t0.elapsed().as_secs_f64(),
        rows,
    )
    .titled(title, "strand", criteria);
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join(default_out));
    report.write(&out)?;
    Ok((report, out))
}

/// The study's table `detail` as `study.md` and its measured values as `study.json` in `out`.
fn write_study(out: &Path, detail: &str, measured: &impl Serialize) -> anyhow::Result<()> {
    std::fs::write(out.join("study.md"), detail)
        .with_context(|| format!("writing {}", out.join("study.md").display()))?;
    std::fs::write(
        out.join("study.json"),
        serde_json::to_string_pretty(measured)? + "\n",
    )?;
    Ok(())
}

/// The manual's `bonded` block: the report's provenance, its judged rows and the curves' tables.
fn curve_docs(report: &Report, curves: &[curve::Curve]) -> String {
    let mut s = report.docs();
    for c in curves {
        s += "\n";
        s += &curve::details(c);
    }
    s
}

/// The criteria's rows.
fn judge(m: &[Measured], limits: &Limits) -> Vec<Row> {
    let mut rows = Vec::new();
    for x in m {
        let (strand, variant) = (x.strand.as_str(), x.variant.as_str());
        if x.asymptotic {
            rows.push(
                limits
                    .discretisation
                    .row(strand, variant, "discretisation", x.limit_error),
            );
        } else {
            let k96 = x.fine[x.fine.len() - 1];
            rows.push(
                Row::measured(
                    strand,
                    variant,
                    "K_96 / K_max",
                    k96 / x.k_max,
                    "",
                    Bound::None,
                )
                .with_note("reported only: not in the asymptotic range (see study.md)"),
            );
        }
        if x.rod.is_finite() {
            rows.push(limits.rod_model.row(
                strand,
                variant,
                "|K_fine/K_rod - 1|",
                (x.limit / x.rod - 1.0).abs(),
            ));
        }
        if x.variant == "removed" {
            rows.push(limits.k_max.row(
                strand,
                variant,
                "|K_fine/K_max - 1|",
                (x.limit / x.k_max - 1.0).abs(),
            ));
        }
        if x.variant == "physical" {
            rows.push(limits.physical.row(
                strand,
                "physical",
                "|K_rod,rigid/K_fine - 1|",
                (x.rod_rigid / x.limit - 1.0).abs(),
            ));
        }
    }
    rows
}

/// The study's table as Markdown.
fn details(m: &[Measured]) -> String {
    let mut s = String::from(
        "| strand | variant | K/K_max at 24, 48, 96 segments per pitch | order | limit | its error | rod model | fine/rod - 1 | rod, rigid bond | clamp/middle moment | what |\n\
         |---|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for x in m {
        let r = |k: f64| k / x.k_max;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.4} | {:.1e} | {} | {} | {:.4} | {:.4} | {} |",
            x.strand,
            x.variant,
            x.fine
                .iter()
                .map(|k| format!("{:.4}", r(*k)))
                .collect::<Vec<_>>()
                .join(", "),
            x.order.map_or("-".into(), |p| format!("{p:.2}")),
            r(x.limit),
            x.limit_error,
            if x.rod.is_finite() {
                format!("{:.4}", r(x.rod))
            } else {
                "-".into()
            },
            if x.rod.is_finite() {
                format!("{:+.2e}", x.limit / x.rod - 1.0)
            } else {
                "-".into()
            },
            r(x.rod_rigid),
            x.clamp_ratio,
            x.what
        );
        if let Some(k6) = x.six_pitches {
            let _ = writeln!(
                s,
                "| {} | 6 pitches | {:.4} at 48 (3 pitches: {:.4}) | | | | | | | | end effects |",
                x.strand,
                r(k6),
                r(x.fine[1])
            );
        }
    }
    s
}
