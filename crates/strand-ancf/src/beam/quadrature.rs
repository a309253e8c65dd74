//! Integration points of an element: the reduced axial rule, the hourglass point and the
//! bending points (the pitch rule, the scene's Gauss rule, or four Gauss points for a law
//! without sliders or a pitch-averaged one), with the section law's stations.

use strand_core::{SectionLaw, Station};

use super::strain_recovery::recovery_weights;
use super::{AXIAL_POINTS, BeamError, BeamSpec, ElementKind};
use crate::shape::{
    MAX_GAUSS_POINTS, QuadraturePoint, ShapeRow, element_quadrature, gauss_legendre,
};

/// One bending integration point.
#[derive(Debug, Clone)]
pub(crate) struct BendPoint {
    pub qp: QuadraturePoint,
    pub station: Station,
    /// Weights of the element's own axial-point strains in the strain the section law reads
    /// here (module `strain_recovery`).
    pub interp: [f64; AXIAL_POINTS],
    /// Weights of the mean strains of the elements [`ElementRule::others`].
    pub others: [f64; 2],
    /// Planar bending stiffness with every wire sticking (N m^2).
    pub stick: f64,
}

/// Quadrature of one element (all elements have the same length but different stations).
#[derive(Debug, Clone)]
pub(crate) struct ElementRule {
    pub axial: Vec<QuadraturePoint>,
    /// Shape row at the element midpoint (hourglass stabilization).
    pub mid: ShapeRow,
    pub bend: Vec<BendPoint>,
    /// The two other elements whose mean strains enter the strain the section law reads.
    pub others: [usize; 2],
}

/// Most bending points the pitch rule may put in one element: 1024 (a planar element spanning
/// 256 pitches, a spatial one 85). A cubic element's curvature cannot follow the strand over
/// more; more elements resolve the same points better.
pub const MAX_BENDING_POINTS: usize = 1024;

/// Bending points the pitch rule puts on each quarter pitch of the strand.
///
/// The planar element: one. The spatial element: three. In space the bending direction turns,
/// every wire passes its slip limit in turn, and the stick/slip laws' Newton iterations
/// converge more reliably with the wires' states sampled three times as finely: with the
/// `hysteretic` law at 1 ms, steps cut because Newton did not converge in 25 iterations, one
/// against three points per quarter pitch: the tilted-plane pendulum (5 s) 262 against 225, the
/// spinning whip (5 s) 18 against 5, the folded strand 25 against 15, the spin pendulum 5
/// against 2, and the rotation-invariance scene of `strand-scene`'s `tests/rotation.rs` (Table 1
/// strand, 8 elements, 1 s) 773 of 1543 steps against none. In the plane one point per quarter
/// pitch cut none of the bundled scenes' steps.
pub fn points_per_quarter_pitch(element: ElementKind) -> f64 {
    match element {
        ElementKind::Planar => 1.0,
        ElementKind::Spatial => 3.0,
    }
}

/// Bending points the pitch rule puts in an element of length `l` (m) for the wire pitch
/// `pitch` (m): [`points_per_quarter_pitch`] on each quarter pitch the element spans,
/// `max(4, n ceil(4 l / P))`. Computed in floating point so that it cannot overflow; compare
/// with [`MAX_BENDING_POINTS`] before building.
pub fn pitch_rule_points(l: f64, pitch: f64, element: ElementKind) -> f64 {
    (points_per_quarter_pitch(element) * (4.0 * l / pitch).ceil()).max(4.0)
}

/// Fewest elements, from `n` elements asking for `points` bending points each, that keep the
/// pitch rule within [`MAX_BENDING_POINTS`].
fn min_elements(n: usize, points: f64) -> f64 {
    (n as f64 * points / MAX_BENDING_POINTS as f64).ceil()
}

/// Bending integration points of element `e`: the pitch rule or the scene's Gauss rule.
pub(super) fn element_rule(
    law: &SectionLaw,
    spec: &BeamSpec,
    e: usize,
    l: f64,
) -> Result<ElementRule, BeamError> {
    let setup = |source| BeamError::Kinematics { element: e, source };
    let axial = element_quadrature(l, AXIAL_POINTS).map_err(setup)?;
    let x0 = e as f64 * l;
    // The shortest of the layers' pitches sets the rule: it resolves every layer's phases.
    // A pitch-averaged law's bending point stands for the whole pitch around it: the element
    // is sized by its curvature and takes the Gauss rule of the constant law.
    let n = match (spec.bending_points, law.strand().shortest_pitch()) {
        (Some(n), _) => n,
        (None, Some(pitch)) if law.sliders() > 0 && !law.is_pitch_averaged() => {
            let points = pitch_rule_points(l, pitch, spec.element);
            if points > MAX_BENDING_POINTS as f64 {
                return Err(BeamError::Setup(format!(
                    "elements of {l:.4e} m span {:.4e} wire pitches: the pitch rule asks for \
                     {points:.4e} bending points per element, above the cap of \
                     {MAX_BENDING_POINTS}; use at least {} elements",
                    l / pitch,
                    min_elements(spec.elements, points)
                )));
            }
            points as usize
        }
        _ => 4,
    };
    // Elements needing more than `MAX_GAUSS_POINTS` are split into equal parts.
    let sub = n.div_ceil(MAX_GAUSS_POINTS).max(1);
    let rule = gauss_legendre(n.div_ceil(sub)).map_err(setup)?;
    let h = l / sub as f64;
    let mut pts: Vec<(f64, f64)> = Vec::with_capacity(sub * rule.n());
    for k in 0..sub {
        pts.extend(rule.on_interval(k as f64 * h, (k + 1) as f64 * h));
    }
    let xa: Vec<f64> = axial.iter().map(|a| a.row.x).collect();
    let mut others = [0; 2];
    let bend = pts
        .into_iter()
        .map(|(x, weight)| {
            let (interp, idx, w) = recovery_weights(e, spec.elements, x, l, &xa);
            others = idx;
            let station = law.station(x0 + x);
            BendPoint {
                qp: QuadraturePoint {
                    weight,
                    row: ShapeRow::new(x, l),
                },
                stick: law.planar_stick_stiffness(&station),
                station,
                interp,
                others: w,
            }
        })
        .collect();
    Ok(ElementRule {
        axial,
        mid: ShapeRow::new(0.5 * l, l),
        bend,
        others,
    })
}
