//! The state of a beam along the strand as its result files give it: `centerline.csv` from
//! s = 0 to s = L (the two ends and every bending integration point), `wires.csv` (the stick or
//! slip state of every wire at every bending point) and, for statics, a VTK polyline.
//!
//! Curvature sign (one convention for every file and `strand section --curvature`): in a planar
//! scene the signed `kappa_z = (r' x r'') . Z / |r'|^2`, positive when the strand turns
//! counter-clockwise seen from +Z (toward +y for a strand along +x), so the paper's hanging
//! cantilever (along +x under gravity along -y, convex side toward +y) has negative curvature;
//! in a 3D scene the magnitude `|r' x r''| / |r'|^2`.

use std::path::Path;

use strand_ancf::beam::{Beam, ElementKind, PointState};
use strand_core::{SectionLaw, Station, WireState};

use crate::output::{CENTERLINE_COLUMNS, Csv, number, write_static_vtk};

/// One row of `centerline.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Row {
    /// Material coordinate (m).
    pub s: f64,
    /// Position (m).
    pub position: [f64; 3],
    /// Curvature (1/m; the module's sign convention).
    pub curvature: f64,
    /// Axial force EA eps (N).
    pub tension: f64,
    /// Secant bending stiffness |M| / |kappa| (N m^2); at zero curvature the tangent.
    pub stiffness: f64,
    /// Bending moment (N m): the section law's at the row's strain, curvature and slip state,
    /// signed like the curvature (planar) or its magnitude (3D); at an end, with a law with
    /// slip state, the slip state of the nearest bending point (a state lives at the bending
    /// points only).
    pub moment: f64,
    /// Curvature components (kappa_y, kappa_z) (1/m).
    kappa: [f64; 2],
    /// Axial strain.
    eps: f64,
    /// Index of the bending point whose slip state this row uses.
    point: usize,
}

/// The rows of `centerline.csv` for the state `(q, slip, points)`: s = 0, every bending point,
/// s = L. The ends take the elements' fields there (position, strain, curvature) and the
/// section law's moment and secant at them; with a law with slip state, from the nearest
/// bending point's state (the law's response to the end's strain and curvature from it, not
/// that point's secant times the end's curvature, which a residual slip moment at a curvature
/// near zero sends far out). A row that cannot be evaluated (a degenerate element) is left out.
pub(crate) fn rows(beam: &Beam, q: &[f64], slip: &[f64], points: &[PointState]) -> Vec<Row> {
    let law = beam.law();
    let ea = law.axial_stiffness();
    let mut out = Vec::with_capacity(points.len() + 2);
    let end = |x: f64, point: usize| {
        beam.section_at(q, slip, x, point).ok().map(|p| Row {
            s: p.x,
            position: p.position,
            curvature: 0.0,
            tension: ea * p.eps,
            stiffness: 0.0,
            moment: 0.0,
            kappa: [p.kappa_y, p.kappa_z],
            eps: p.eps,
            point,
        })
    };
    out.extend(end(0.0, 0));
    for (i, pt) in points.iter().enumerate() {
        out.push(Row {
            s: pt.x,
            position: beam.sample(q, pt.x).0,
            curvature: 0.0,
            tension: ea * pt.eps,
            stiffness: 0.0,
            moment: 0.0,
            kappa: [pt.kappa_y, pt.kappa],
            eps: pt.eps,
            point: i,
        });
    }
    out.extend(end(beam.length(), points.len().saturating_sub(1)));
    let planar = beam.spec().element == ElementKind::Planar;
    for r in &mut out {
        let sl = beam.point_slip(slip, r.point);
        let st = law.station(r.s);
        let [ky, kz] = r.kappa;
        r.curvature = if planar { kz } else { ky.hypot(kz) };
        r.moment = moment(law, &st, r.eps, r.kappa, sl, planar);
        // The secant from the moment just evaluated where it is the same quotient as
        // `secant`'s (one law evaluation a row, not two); `secant` at zero curvature.
        r.stiffness = match (planar, ky, kz) {
            (true, _, kz) if kz != 0.0 => r.moment / kz,
            (false, ky, kz) if ky != 0.0 => r.moment / ky.hypot(kz),
            _ => secant(law, &st, r.eps, r.kappa, sl),
        };
    }
    out
}

/// The law's bending moment at `(eps, kappa)` with slip state `sl` (N m): `M_z` in the plane
/// (`planar`), else the magnitude of the moment vector.
fn moment(
    law: &SectionLaw,
    st: &Station,
    eps: f64,
    [ky, kz]: [f64; 2],
    sl: &[f64],
    planar: bool,
) -> f64 {
    let mut trial = vec![0.0; sl.len()];
    if planar || ky == 0.0 && kz == 0.0 {
        let m = law.planar(st, eps, kz, sl, &mut trial).moment;
        return if planar { m } else { m.abs() };
    }
    let r = law.vector(st, eps, [ky, kz], sl, &mut trial);
    r.moment[0].hypot(r.moment[1])
}

/// The rows as the stations along the strand that probes and range envelopes read.
pub(crate) fn stations(rows: &[Row]) -> Vec<crate::along::Station> {
    rows.iter()
        .map(|r| crate::along::Station {
            s: r.s,
            position: r.position,
            curvature: r.curvature,
            moment: r.moment,
            tension: r.tension,
            stiffness: Some(r.stiffness),
        })
        .collect()
}

/// Sticking and slipping wires at row `r` of the state with slip state `slip` (the counts of
/// `wires.csv` there; at an end, those of the nearest bending point).
pub(crate) fn wire_counts(beam: &Beam, r: &Row, slip: &[f64]) -> (usize, usize) {
    let law = beam.law();
    let st = law.station(r.s);
    let sl = beam.point_slip(slip, r.point);
    let report = if beam.spec().element == ElementKind::Planar {
        law.planar_wires(&st, r.eps, r.kappa[1], sl)
    } else {
        law.vector_wires(&st, r.eps, r.kappa, sl)
    };
    let slipping = report.iter().filter(|w| w.state == WireState::Slip).count();
    (report.len() - slipping, slipping)
}

/// Secant stiffness |M| / |kappa| of the law at `(eps, kappa)` with slip state `sl`; at zero
/// curvature its limit, the tangent.
fn secant(law: &SectionLaw, st: &Station, eps: f64, [ky, kz]: [f64; 2], sl: &[f64]) -> f64 {
    if ky == 0.0 {
        // Planar bending (or none): the planar law, whose secant at zero is the tangent.
        return law.planar_secant(st, eps, kz, sl);
    }
    let mut trial = vec![0.0; sl.len()];
    let r = law.vector(st, eps, [ky, kz], sl, &mut trial);
    r.moment[0].hypot(r.moment[1]) / ky.hypot(kz)
}

/// Writes `centerline.csv` and `wires.csv` for `rows` of the state with slip state `slip`;
/// returns the number of non-finite values left empty.
pub(crate) fn write(beam: &Beam, rows: &[Row], slip: &[f64], dir: &Path) -> Result<usize, String> {
    let law = beam.law();
    let p = dir.join("centerline.csv");
    let e = |e: std::io::Error| format!("writing {}: {e}", p.display());
    let mut c = Csv::create(&p, &CENTERLINE_COLUMNS).map_err(e)?;
    let pw = dir.join("wires.csv");
    let ew = |e: std::io::Error| format!("writing {}: {e}", pw.display());
    let mut wires = Csv::create(
        &pw,
        &["s", "wire", "phase", "critical_curvature", "state", "layer"],
    )
    .map_err(ew)?;
    let planar = beam.spec().element == ElementKind::Planar;
    for r in rows {
        let [x, y, z] = r.position;
        c.row(&[r.s, x, y, z, r.curvature, r.tension, r.stiffness, r.moment])
            .map_err(e)?;
        // The per-wire table, at the bending points (not the ends): phases from the neutral
        // axis of the current bending direction, the planar convention for the planar
        // element, the vector law's in 3D.
        if r.s == 0.0 || r.s == beam.length() {
            continue;
        }
        let st = law.station(r.s);
        let sl = beam.point_slip(slip, r.point);
        let report = if planar {
            law.planar_wires(&st, r.eps, r.kappa[1], sl)
        } else {
            law.vector_wires(&st, r.eps, r.kappa, sl)
        };
        for wr in report {
            let state = match wr.state {
                WireState::Stick => "stick",
                WireState::Slip => "slip",
            };
            wires
                .text_row(&[
                    number(r.s),
                    wr.wire.to_string(),
                    number(wr.phase),
                    // Empty for a wire without lever: it never slips.
                    wr.critical_curvature.map_or(String::new(), number),
                    state.to_string(),
                    // Appended so that readers of the first five columns keep working.
                    wr.layer.to_string(),
                ])
                .map_err(ew)?;
        }
    }
    let blanks = c.blanks();
    c.finish().map_err(e)?;
    wires.finish().map_err(ew)?;
    Ok(blanks)
}

/// The rows as a VTK polyline: positions (m) and the point data of every frame (curvature,
/// tension, bending stiffness, moment).
pub(crate) fn vtk_frame(rows: &[Row]) -> crate::output::VtkFrame {
    let column = |f: fn(&Row) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    crate::output::VtkFrame {
        points: rows.iter().map(|r| r.position).collect(),
        scalars: vec![
            ("curvature", column(|r| r.curvature)),
            ("tension", column(|r| r.tension)),
            ("bending_stiffness", column(|r| r.stiffness)),
            ("moment", column(|r| r.moment)),
        ],
    }
}

/// Writes the static state as `vtk/centerline_00000.vtk`, the one frame of a static run, with
/// the point data of [`vtk_frame`].
pub(crate) fn write_vtk(rows: &[Row], dir: &Path, title: &str) -> Result<(), String> {
    let f = vtk_frame(rows);
    write_static_vtk(dir, title, &f.points, &f.scalars)
}
