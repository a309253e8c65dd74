//! Planar bending laws for the elastica and the robust inversion moment -> curvature.
//!
//! The shooting integrates the bending moment along the strand, so at every integration point
//! the law has to be inverted: find the signed curvature `kappa` whose moment equals the
//! moment of the load. [`invert_moment`] does this for any law that is monotone in `kappa`,
//! smooth or only piecewise smooth (safeguarded Newton on an expanding bracket).

use strand_core::{SectionLaw, Station};

use crate::ElasticaError;

/// A planar section law: signed bending moment as a function of the signed curvature, the
/// axial tension and the material coordinate.
///
/// The moment must have the sign of the curvature and grow monotonically with it (strictly
/// somewhere, so that every moment is reached). Position-dependent data are precomputed per
/// integration point by [`PlanarLaw::point`]: the solver builds the points of its integration
/// grid once and reuses them for every shooting iteration and continuation step.
pub trait PlanarLaw {
    /// Data the law needs at one material coordinate (e.g. the wire phases of a station).
    type Point;

    /// Precomputes the data at material coordinate `s` (m).
    fn point(&self, s: f64) -> Self::Point;

    /// Signed bending moment M (N m) and its tangent dM/dkappa (N m^2) at a precomputed
    /// point, for signed curvature `kappa` (1/m) and axial tension `tension` (N, positive in
    /// tension).
    fn moment(&self, point: &Self::Point, kappa: f64, tension: f64) -> (f64, f64);
}

/// Constant bending stiffness: M = EI kappa.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstantEi {
    /// Bending stiffness EI (N m^2).
    pub bending_stiffness: f64,
}

impl ConstantEi {
    /// Law with bending stiffness `ei` (N m^2).
    pub fn new(ei: f64) -> Self {
        ConstantEi {
            bending_stiffness: ei,
        }
    }
}

impl PlanarLaw for ConstantEi {
    type Point = ();
    fn point(&self, _s: f64) {}
    fn moment(&self, _: &(), kappa: f64, _tension: f64) -> (f64, f64) {
        (self.bending_stiffness * kappa, self.bending_stiffness)
    }
}

/// A law given by a closure `f(s, kappa, tension) -> (M, dM/dkappa)` (units as in
/// [`PlanarLaw::moment`]); the point is the material coordinate itself.
#[derive(Debug, Clone, Copy)]
pub struct FnLaw<F>(pub F);

impl<F: Fn(f64, f64, f64) -> (f64, f64)> PlanarLaw for FnLaw<F> {
    type Point = f64;
    fn point(&self, s: f64) -> f64 {
        s
    }
    fn moment(&self, s: &f64, kappa: f64, tension: f64) -> (f64, f64) {
        (self.0)(*s, kappa, tension)
    }
}

/// Adapter for a strand section law of `strand-core` ([`SectionLaw::planar`]).
///
/// The axial strain that sets the friction limits is `eps = T / EA` with EA the law's axial
/// stiffness (only tension presses the wires on the core). The `hysteretic` law is evaluated
/// from a virgin (zero) slip state, which on the monotone loading of a statics problem is the
/// `continuous` law. The `paper` law is not monotone; its inversion picks a curvature whose
/// moment matches, and the error estimate of the solution shows the resulting roughness.
#[derive(Debug, Clone, PartialEq)]
pub struct StrandLaw {
    law: SectionLaw,
}

/// Most slip-state entries [`StrandLaw`] keeps on the stack.
const STACK_STATE: usize = 32;

impl StrandLaw {
    /// Wraps `law`.
    pub fn new(law: SectionLaw) -> Self {
        StrandLaw { law }
    }
    /// The wrapped section law.
    pub fn section_law(&self) -> &SectionLaw {
        &self.law
    }
    /// Axial stiffness EA of the law (N), for extensible kinematics.
    pub fn axial_stiffness(&self) -> f64 {
        self.law.axial_stiffness()
    }
    /// Axial strain the law sees under tension `tension` (N).
    pub fn strain(&self, tension: f64) -> f64 {
        tension / self.law.axial_stiffness()
    }
}

impl PlanarLaw for StrandLaw {
    type Point = Station;
    fn point(&self, s: f64) -> Station {
        self.law.station(s)
    }
    fn moment(&self, st: &Station, kappa: f64, tension: f64) -> (f64, f64) {
        let eps = self.strain(tension);
        let n = self.law.state_len();
        let r = if n == 0 {
            self.law.planar(st, eps, kappa, &[], &mut [])
        } else if n <= STACK_STATE {
            let slip = [0.0; STACK_STATE];
            let mut trial = [0.0; STACK_STATE];
            self.law.planar(st, eps, kappa, &slip[..n], &mut trial[..n])
        } else {
            let slip = vec![0.0; n];
            let mut trial = vec![0.0; n];
            self.law.planar(st, eps, kappa, &slip, &mut trial)
        };
        (r.moment, r.moment_curvature)
    }
}

/// Finds the curvature `kappa` (1/m) with `m(kappa).0 == target` for a moment function
/// `m(kappa) -> (M, dM/dkappa)` that is non-decreasing in `kappa`.
///
/// Safeguarded Newton: a bracket [0, hi] on the side of the target is grown from `guess` (a
/// nearby curvature, e.g. the previous integration point's) or from the linear estimate, at
/// least doubling hi, until it holds the root; then Newton steps are taken when they stay
/// inside the bracket and bisection steps otherwise,
/// so kinks of a piecewise smooth law (stick/slip switches) cannot make it cycle. Returns an
/// error when no curvature reaches the target (a saturating law) or when the bracket closes on
/// a jump of the moment (a law that is not monotone); the error's `s` is NaN (the caller knows
/// where it evaluated the law).
pub fn invert_moment(
    m: impl Fn(f64) -> (f64, f64),
    target: f64,
    guess: f64,
) -> Result<f64, ElasticaError> {
    let fail = |what: &str| ElasticaError::Inversion {
        s: f64::NAN,
        moment: target,
        reason: what.to_string(),
    };
    if !target.is_finite() {
        return Err(fail("the moment is not finite"));
    }
    let (m0, k0) = m(0.0);
    let f0 = m0 - target;
    if f0 == 0.0 {
        return Ok(0.0);
    }
    // Root lies toward `dir` from zero.
    let dir = if f0 < 0.0 { 1.0 } else { -1.0 };
    // Bracket [lo, hi] in the direction `dir` (as magnitudes along dir): g(lo) < 0 <= g(hi),
    // with g(t) = dir * (m(dir t) - target).
    let g = |t: f64| {
        let (mm, dm) = m(dir * t);
        (dir * (mm - target), dm)
    };
    let mut lo = 0.0;
    let first = if guess * dir > 0.0 {
        guess.abs()
    } else if k0 > 0.0 && k0.is_finite() {
        (target - m0).abs() / k0
    } else {
        1.0
    };
    let mut hi = first.max(f64::MIN_POSITIVE);
    let (mut ghi, mut dhi) = g(hi);
    let mut expansions = 0;
    while ghi < 0.0 {
        lo = hi;
        // Newton extrapolation from the current point, at least doubling.
        let step = if dhi > 0.0 { -ghi / dhi } else { hi };
        hi += step.max(hi);
        (ghi, dhi) = g(hi);
        expansions += 1;
        if expansions > 2100 || !hi.is_finite() || !ghi.is_finite() {
            return Err(fail("no curvature reaches this moment (the law saturates)"));
        }
    }
    if ghi == 0.0 {
        return Ok(dir * hi);
    }
    // Safeguarded Newton inside [lo, hi].
    let mut t = if guess * dir > lo && guess * dir < hi {
        guess.abs()
    } else {
        hi
    };
    let (mut gt, mut dt) = if t == hi { (ghi, dhi) } else { g(t) };
    for _ in 0..200 {
        if gt == 0.0 {
            return Ok(dir * t);
        }
        if gt < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let newton = if dt > 0.0 { t - gt / dt } else { f64::NAN };
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - t).abs() <= 4.0 * f64::EPSILON * t.abs() || hi - lo <= 4.0 * f64::EPSILON * hi {
            t = next;
            (gt, _) = g(t);
            break;
        }
        t = next;
        (gt, dt) = g(t);
    }
    // Accept when the moment matches to round-off; otherwise the bracket closed on a jump.
    let scale = target.abs() + (dt.abs() + k0.abs()) * t.abs();
    if gt.abs() <= 1e-9 * scale {
        Ok(dir * t)
    } else {
        Err(fail(
            "the moment jumps over this value: the law is not monotone in the curvature",
        ))
    }
}
