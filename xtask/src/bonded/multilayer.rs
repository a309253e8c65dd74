//! `cargo xtask bonded --multilayer`: the bonded (all-stick) bending stiffness of the 1+6+12
//! strand of `examples/steel-1x19-swing.json`, explained as the one-layer study explains the
//! Table 1 strand's.
//!
//! The fine model's virtual bending test with friction too high to slip (mu = 1e3; checked:
//! no contact slips and none opens or closes between the tension step and the bend) measures
//! M / kappa at 16, 32 and 40 segments per pitch (Richardson limit from the observed order) for
//! the physical strand (the bending test's default contacts), the stiff penalties and the
//! compliance-free strand, at 16 and 32 for the others (the last change as their error).
//! Each variant removes one compliance the plane-section K_max ignores: the contacts'
//! penalties (every other variant has stiff ones), the wires' torsion and shear, the
//! core's shear, the eccentricity of the first layer's bond on the core. Beside each stands
//! the rod model of the whole strand as one body (`strand_core::bonded::
//! strand_bonded_stiffness`: every layer's wires as Cosserat rods, each layer bonded to the
//! one beneath at the touching surfaces, the first to the core) with the same idealisations,
//! and the law's present multi-layer value, the per-interface stick factors of
//! `section.stick_stiffness = bonded` (each layer on a rigid-section body of the layers
//! beneath).
//!
//! Criteria (`validation/bonded/multilayer-criteria.json`): with the compliances removed, the fine
//! stiffness within 2 % of K_max; the physical strand's rod-model value within 5 % of the fine
//! model's; both extrapolations converged well inside those.

use std::fmt::Write as _;
use std::time::Instant;

use anyhow::{Context, bail};
use serde::{Deserialize, Serialize};
use strand_core::bonded::{interface_bonded_stiffness, strand_bonded_stiffness};
use strand_core::{BaseStiffness, BondedOptions, Strand};
use strand_fine::{BendingTest, ContactOptions, NormalPenalty, SpringScale};

use super::Limit;
use crate::validate::repo_root;
use crate::validate::report::{Bound, Row};

/// Segments per pitch of the refinement with an observed order. Below 16 the outer layer's
/// segments (11.4 mm at 16) are longer than the distance between its crossings (13.5 mm) and
/// a link can miss one: 8 segments per pitch gives 0.68 K_max against 0.375 at 16.
pub const MESHES: [usize; 3] = [16, 32, 40];
/// Segments per pitch of the reported variants: the last change is their error estimate.
pub const REPORTED_MESHES: [usize; 2] = [16, 32];

/// Observed order and Richardson limit of three values `k` on the meshes `n` (segments per
/// pitch, increasing): `k_i = K + C n_i^-p`, p from the ratio of the two changes (bisection on
/// [0.5, 8]); the error estimate is the distance of the limit from the finest value. Outside
/// the asymptotic range (changes of opposite signs, or no order in that bracket): the finest
/// value, with the last change as its error.
pub fn extrapolate(n: &[usize; 3], k: &[f64]) -> (Option<f64>, f64, f64) {
    let h = n.map(|n| 1.0 / n as f64);
    let (d1, d2) = (k[0] - k[1], k[1] - k[2]);
    let ratio = |p: f64| (h[0].powf(p) - h[1].powf(p)) / (h[1].powf(p) - h[2].powf(p));
    let target = d1 / d2;
    let fallback = (None, k[2], (d2 / k[2]).abs());
    // ratio(p) grows with p.
    if d1 * d2 <= 0.0 || !(ratio(0.5)..=ratio(8.0)).contains(&target) {
        return fallback;
    }
    let (mut lo, mut hi) = (0.5, 8.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let p = 0.5 * (lo + hi);
    let c = d2 / (h[1].powf(p) - h[2].powf(p));
    let limit = k[2] - c * h[2].powf(p);
    (Some(p), limit, ((limit - k[2]) / limit).abs())
}

/// Limits of the multi-layer study and their reasons.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limits {
    /// Largest |K_fine / K_max - 1| with the ignored compliances removed.
    k_max: Limit,
    /// Largest |K_rod / K_fine - 1| of the physical strand.
    physical: Limit,
    /// Largest remaining discretisation error of a judged extrapolated value (relative).
    discretisation: Limit,
}

/// One idealisation of the strand.
#[derive(Debug, Clone)]
struct Variant {
    name: &'static str,
    what: &'static str,
    core: SpringScale,
    wire: SpringScale,
    /// Stiff penalties (strain relief 1e-4, stick loss 5e-4) or the bending test's defaults.
    stiff: bool,
    /// The first layer's bond on its wires' axes.
    axes: bool,
    /// Whether the refinement is judged (the physical and the compliance-free strand).
    judged: bool,
    /// Refined on [`MESHES`] with an observed order (else on [`REPORTED_MESHES`]).
    refined: bool,
    /// Run only when named by `--variant`: the wires' shear alone (over 11 minutes at 32
    /// segments per pitch on the loaded 2-core machine) and the core's shear alone; both are
    /// part of `removed`.
    on_request: bool,
}

fn variant(name: &'static str, what: &'static str) -> Variant {
    Variant {
        name,
        what,
        core: SpringScale::default(),
        wire: SpringScale::default(),
        stiff: true,
        axes: false,
        judged: false,
        refined: false,
        on_request: false,
    }
}

fn torsion(f: f64) -> SpringScale {
    SpringScale {
        torsion: f,
        ..Default::default()
    }
}

fn shear(f: f64) -> SpringScale {
    SpringScale {
        shear: f,
        ..Default::default()
    }
}

/// The variants; `quick`: the physical and the compliance-free strand only.
fn variants(quick: bool) -> Vec<Variant> {
    let physical = Variant {
        stiff: false,
        judged: true,
        refined: true,
        ..variant(
            "physical",
            "real wires and core, the bending test's default contacts (strain relief 1e-2, \
             stick loss 0.05)",
        )
    };
    let removed = Variant {
        wire: SpringScale {
            torsion: 100.0,
            shear: 10.0,
            ..Default::default()
        },
        core: shear(100.0),
        axes: true,
        judged: true,
        refined: true,
        ..variant(
            "removed",
            "wires' G J x100 and kappa G A x10, first layer's bond on its axes, core shear x100",
        )
    };
    if quick {
        return vec![physical, removed];
    }
    vec![
        physical,
        Variant {
            refined: true,
            ..variant(
                "stiff-penalties",
                "real wires and core, stiff penalties (strain relief 1e-4, stick loss 5e-4)",
            )
        },
        Variant {
            wire: torsion(100.0),
            ..variant("wire-torsion", "wires' G J x100")
        },
        Variant {
            wire: shear(10.0),
            on_request: true,
            ..variant("wire-shear", "wires' kappa G A x10")
        },
        Variant {
            core: shear(100.0),
            on_request: true,
            ..variant("core-shear", "core's kappa G A x100")
        },
        Variant {
            axes: true,
            ..variant("bond-on-axes", "first layer's bond on its wires' axes")
        },
        removed,
    ]
}

/// Measured stiffnesses of one variant.
#[derive(Debug, Clone, Serialize)]
pub struct Measured {
    pub variant: String,
    pub what: String,
    pub judged: bool,
    /// Segments per pitch and M / kappa at each (N m^2).
    pub meshes: Vec<usize>,
    pub fine: Vec<f64>,
    pub order: Option<f64>,
    /// Extrapolated limit (N m^2) and its error estimate (relative).
    pub limit: f64,
    pub limit_error: f64,
    /// Rod model of the strand as one body, rigid bonds (N m^2).
    pub rod: f64,
    /// The law's per-interface value K_min + sum_j f_j K_stick,j (N m^2), same idealisations
    /// (the variant's bond radius on the first interface only).
    pub law: f64,
    pub k_max: f64,
    pub k_min: f64,
    /// Moment at the clamp over the moment in the middle pitch, finest mesh (-).
    pub clamp_ratio: f64,
    pub wall_time: f64,
}

/// The 1+6+12 strand of `examples/steel-1x19-swing.json`.
pub fn strand() -> anyhow::Result<Strand> {
    let path = repo_root().join("examples/steel-1x19-swing.json");
    let scene = strand_scene::Scene::load(&path).with_context(|| format!("{}", path.display()))?;
    Ok(scene.strand)
}

/// Axial strain of the tension and bending strain kappa R at the outer layer's axes (-): the
/// one-layer study's, so that the bend leaves every contact closed and sticking.
const STRAIN: f64 = 2.2e-4;
const BENDING_STRAIN: f64 = 2.5e-5;

fn options(strand: &Strand, v: &Variant) -> BondedOptions {
    BondedOptions {
        wire_shear: v.wire.shear,
        wire_torsion: v.wire.torsion,
        core_shear: v.core.shear,
        contact_radius: v.axes.then(|| strand.layers()[0].radius),
        ..Default::default()
    }
}

fn bending_test(strand: &Strand, v: &Variant, spp: usize) -> BendingTest {
    let outer = strand.layers().last().expect("a helical layer");
    let tension = STRAIN * strand.axial_stiffness();
    // The bending test's default contacts (one point per segment on the core on several
    // layers), with the variant's bond radius and penalties.
    let mut contact = ContactOptions {
        contact_radius: v.axes.then(|| strand.layers()[0].radius),
        ..Default::default()
    };
    if v.stiff {
        contact.normal_penalty = NormalPenalty::StrainRelief(1e-4);
        contact.stick_loss = 5e-4;
    }
    BendingTest {
        pitches: 3,
        segments_per_pitch: spp,
        tension,
        curvatures: vec![BENDING_STRAIN / outer.radius],
        contact,
        friction: 1e3,
        statics: BendingTest::load_step_statics(tension),
        max_halvings: 3,
        core_springs: v.core,
        wire_springs: v.wire,
        pressure: Default::default(),
    }
}

/// M / kappa (N m^2) and the clamp-to-middle moment ratio of one run; fails where a contact
/// slips or one opens or closes in the bend.
fn measure(strand: &Strand, test: &BendingTest) -> anyhow::Result<(f64, f64)> {
    let curve = test.run(strand).context("bending test")?;
    let (Some(first), Some(p)) = (curve.first(), curve.last()) else {
        bail!("no bending point");
    };
    if p.slip > 0 || p.stick != first.stick {
        bail!(
            "not bonded: {} contacts slip, {} closed against {} under the tension alone",
            p.slip,
            p.stick,
            first.stick
        );
    }
    Ok((p.secant_stiffness(), p.clamp_moment / p.moment))
}

/// Runs one variant on the meshes, with the rod model and the law beside it.
fn study(strand: &Strand, v: &Variant) -> anyhow::Result<Measured> {
    let t = Instant::now();
    let mut fine = Vec::new();
    let mut clamp_ratio = 0.0;
    let meshes: &[usize] = if v.refined { &MESHES } else { &REPORTED_MESHES };
    for &spp in meshes {
        let (k, c) = measure(strand, &bending_test(strand, v, spp))
            .with_context(|| format!("{spp} segments per pitch"))?;
        eprintln!(
            "  1x19 {:<18} {spp:>3} segments per pitch: K = {k:.5e} N m^2",
            v.name
        );
        fine.push(k);
        clamp_ratio = c;
    }
    let (order, limit, limit_error) = if v.refined {
        extrapolate(&MESHES, &fine)
    } else {
        (None, fine[1], ((fine[1] - fine[0]) / fine[1]).abs())
    };
    let o = options(strand, v);
    let rod = strand_bonded_stiffness(strand, &o).context("rod model")?;
    let mut law = rod.free;
    for (j, l) in strand.layers().iter().enumerate() {
        // The bond radius of the variant is the first layer's on the core only.
        let oj = BondedOptions {
            contact_radius: if j == 0 { o.contact_radius } else { None },
            ..o
        };
        let b = interface_bonded_stiffness(strand, j, &oj).context("interface model")?;
        law += b.stick_factor() * strand.layer_plane_section_stick(l);
    }
    Ok(Measured {
        variant: v.name.into(),
        what: v.what.into(),
        judged: v.judged,
        meshes: meshes.to_vec(),
        fine,
        order,
        limit,
        limit_error,
        rod: rod.bonded,
        law,
        k_max: strand.max_bending_stiffness(BaseStiffness::Costello),
        k_min: strand.min_bending_stiffness(BaseStiffness::Costello),
        clamp_ratio,
        wall_time: t.elapsed().as_secs_f64(),
    })
}

/// Runs the variants (`only`: one by name, also those run on request only).
pub fn run(quick: bool, only: Option<&str>) -> (Vec<Measured>, Vec<Row>) {
    let mut measured = Vec::new();
    let mut failed = Vec::new();
    let strand = match strand() {
        Ok(s) => s,
        Err(e) => {
            return (
                measured,
                vec![Row::failed("1x19", "-", "-", format!("{e:#}"))],
            );
        }
    };
    for v in variants(quick).iter().filter(|v| match only {
        Some(n) => n == v.name,
        None => !v.on_request,
    }) {
        match study(&strand, v) {
            Ok(m) => measured.push(m),
            Err(e) => failed.push(Row::failed("1x19", v.name, "-", format!("{e:#}"))),
        }
    }
    (measured, failed)
}

/// Loads `validation/bonded/multilayer-criteria.json`.
pub fn limits() -> anyhow::Result<Limits> {
    let path = repo_root().join("validation/bonded/multilayer-criteria.json");
    let text = std::fs::read_to_string(&path).with_context(|| format!("{}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{}", path.display()))
}

/// The criteria's rows.
pub fn judge(m: &[Measured], limits: &Limits) -> Vec<Row> {
    let row = |check: &str, metric: &str, value: f64, limit: &Limit| {
        limit.row("1x19", check, metric, value)
    };
    let mut rows = Vec::new();
    for x in m.iter().filter(|x| x.judged) {
        rows.push(row(
            &x.variant,
            "discretisation",
            x.limit_error,
            &limits.discretisation,
        ));
        if x.variant == "removed" {
            rows.push(row(
                &x.variant,
                "|K_fine/K_max - 1|",
                (x.limit / x.k_max - 1.0).abs(),
                &limits.k_max,
            ));
        }
        if x.variant == "physical" {
            rows.push(row(
                &x.variant,
                "|K_rod/K_fine - 1|",
                (x.rod / x.limit - 1.0).abs(),
                &limits.physical,
            ));
            rows.push(
                Row::measured(
                    "1x19",
                    "physical",
                    "law (per interface) / K_fine",
                    x.law / x.limit,
                    "",
                    Bound::None,
                )
                .with_note("reported: the law's present bonded stick stiffness"),
            );
        }
    }
    rows
}

/// The study's table as Markdown.
pub fn details(m: &[Measured]) -> String {
    let Some(first) = m.first() else {
        return String::new();
    };
    let mut s = format!(
        "1+6+12 strand of `examples/steel-1x19-swing.json`: K_min {:.4e}, K_max {:.4e} N m^2 \
         (Costello's K_min plus the plane-section stick stiffness)\n\n",
        first.k_min, first.k_max
    );
    s += "| variant | K/K_max (segments per pitch) | order | limit | its error | \
          rod model, one body | fine/rod - 1 | law per interface | clamp/middle moment | what |\n\
          |---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for x in m {
        let r = |k: f64| k / x.k_max;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.4} | {:.1e} | {:.4} | {:+.2e} | {:.4} | {:.4} | {} |",
            x.variant,
            x.fine
                .iter()
                .zip(&x.meshes)
                .map(|(k, n)| format!("{:.4} ({n})", r(*k)))
                .collect::<Vec<_>>()
                .join(", "),
            x.order.map_or("-".into(), |p| format!("{p:.2}")),
            r(x.limit),
            x.limit_error,
            r(x.rod),
            x.limit / x.rod - 1.0,
            r(x.law),
            x.clamp_ratio,
            x.what
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sequence with a known limit and order on uneven meshes is extrapolated exactly; a
    /// sequence that turns back is not.
    #[test]
    fn extrapolation_recovers_a_known_limit_and_order() {
        for p in [1.0, 2.0, 3.3] {
            let k: Vec<f64> = MESHES
                .iter()
                .map(|&n| 2.0 + 0.7 * (n as f64).powf(-p))
                .collect();
            let (order, limit, _) = extrapolate(&MESHES, &k);
            assert!((order.unwrap() - p).abs() < 1e-9, "{order:?}");
            assert!((limit - 2.0).abs() < 1e-12, "{limit}");
        }
        let (order, limit, error) = extrapolate(&MESHES, &[1.0, 1.1, 1.05]);
        assert!(order.is_none() && limit == 1.05 && (error - 0.05 / 1.05).abs() < 1e-15);
    }
}
