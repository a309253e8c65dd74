//! Contact of a helical wire with the core: normal penalty and Coulomb friction with stick
//! (Cundall-Strack tangential spring with stored history).
//!
//! A contact point is a fixed point `p` on a helical segment's axis. It is paired with the core
//! segment whose axial span contains its projection, found by a local search from the previous
//! pairing (helical wires run nearly parallel to the core, where a global closest-point search
//! between beams is ill-posed). With `q` the closest point on that core segment's axis,
//! `n = (p - q) / |p - q|` and the rest distance `d_0` (the distance of `p` from the core axis
//! in the lay geometry), the gap is `g = |p - q| - d_0`: the chord of a helical segment lies
//! inside the helix, so `d_0` is slightly less than `r_c + r_w`, and the lay geometry touches
//! with zero gap and zero force.
//!
//! * Normal: `N = k_n max(-g, 0)` on the wire along `n` at `p`, the opposite on the core at
//!   `q`; energy `k_n g^2 / 2`. These loads are the exact gradient of that energy.
//! * Tangential: the contact point `x` (on the line `q p`, dividing it in the ratio of the
//!   radii) is stored as a material point of both bodies at each committed state. At the next
//!   evaluation their relative displacement `du` is added to the stored elastic displacement
//!   `u`, first rotated into the current tangent plane (its length kept); the force on the wire
//!   is `-k_t u_t`, capped at `mu N` (slip: `u` is shortened to the cap and `mu N` times the
//!   shortening is the work lost). Committing re-anchors both material points at the new
//!   contact point, so the history follows the contact as it moves along the core.

use nalgebra::Vector3;
use strand_core::HelixLayer;

use crate::segment::{Placement, Segment};

/// Penalty and friction parameters of a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    /// Normal penalty stiffness k_n (N/m).
    pub normal_stiffness: f64,
    /// Tangential (stick) stiffness k_t (N/m).
    pub tangential_stiffness: f64,
    /// Coulomb friction coefficient mu (-).
    pub friction: f64,
}

/// How the wire-to-core contacts are built.
///
/// Normal penalty: the line pressure a wire of tension `T_w` exerts on the core is
/// `T_w sin^2(alpha) / R_w` per unit wire length (the helix curvature times the tension);
/// `k_n` is chosen so that this pressure, lumped on a contact point's share of the segment,
/// penetrates by `penetration d_w`. Tangential stick stiffness: a wire stuck to the core by a
/// shear spring of `k'` per unit length follows the core's axial strain wave along the helix
/// (wavenumber `q = sin(alpha) / R_w` along the wire) only up to the factor
/// `1 / (1 + E_w A_w q^2 / k')`; `k' = E_w A_w q^2 / stick_loss` keeps that loss of the stick
/// bending stiffness at `stick_loss`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOptions {
    /// Allowed penetration as a fraction of the wire diameter (-); default 1e-3.
    pub penetration: f64,
    /// Reference wire tension T_w (N) for the penalty; `None`: the tension at the wire strain
    /// `reference_strain`, E_w A_w cos^2(alpha) eps_ref.
    pub reference_tension: Option<f64>,
    /// Wire strain defining the default reference tension (-); default 1e-3.
    pub reference_strain: f64,
    /// Allowed relative loss of the stick stiffness to the tangential spring's compliance
    /// (-); default 0.05.
    pub stick_loss: f64,
    /// Friction coefficient; `None`: the strand's.
    pub friction: Option<f64>,
    /// Contact points per helical segment on the core, 1 (centre) or 2 (at +-l/4); `None`
    /// (default): by the strand's layers ([`ContactOptions::points_on`]).
    pub points_per_segment: Option<usize>,
    /// Distance of the tangential contact point from the core's axis (m); `None`: the
    /// touching surfaces, r_c. The friction traction then acts r_w from the wire's axis and
    /// tilts and twists the wire's section. A study option: `Some(R_w)` puts it on the
    /// wire's axis (no eccentricity on the wire, arm R_w on the core).
    pub contact_radius: Option<f64>,
    /// How the normal penalty is set; default [`NormalPenalty::ByLayers`].
    pub normal_penalty: NormalPenalty,
}

/// Rule of the contacts' normal penalty.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum NormalPenalty {
    /// [`NormalPenalty::StrainRelief`] at [`crate::penalty::DEFAULT_STRAIN_RELIEF`] on a strand
    /// of several layers; [`NormalPenalty::Penetration`] on a `1+m` strand, which the
    /// one-layer validation measured.
    #[default]
    ByLayers,
    /// `penetration d_w` at the reference tension ([`ContactOptions`]).
    Penetration,
    /// Every interface sinks by at most this relief (-) of each layer's strain, at any
    /// tension ([`crate::penalty`]); `penetration` then only sets where a wire-to-wire
    /// contact turns from a crossing into a line.
    StrainRelief(f64),
}

impl Default for ContactOptions {
    fn default() -> Self {
        Self {
            penetration: 1e-3,
            reference_tension: None,
            reference_strain: 1e-3,
            stick_loss: 0.05,
            friction: None,
            points_per_segment: None,
            contact_radius: None,
            normal_penalty: NormalPenalty::ByLayers,
        }
    }
}

impl ContactOptions {
    /// The strain relief that sets the normal penalty on `strand` (see
    /// [`ContactOptions::normal_penalty`]), `None` for the penetration rule.
    pub fn relief_on(&self, strand: &strand_core::Strand) -> Option<f64> {
        match self.normal_penalty {
            NormalPenalty::ByLayers => {
                (strand.layers().len() > 1).then_some(crate::penalty::DEFAULT_STRAIN_RELIEF)
            }
            NormalPenalty::Penetration => None,
            NormalPenalty::StrainRelief(f) => Some(f),
        }
    }

    /// Contact points per segment of a first-layer wire on the core of `strand`: the option
    /// where set, else 2 on a `1+m` strand (what the one-layer validation measured) and 1 on a
    /// strand of several layers. Two points at `+-l/4` of a rigid segment carry the stick
    /// stiffness per unit length of one, but their springs also hold the segment's rotation
    /// about the contact normal (tangential springs) and its tilt toward the core (normal
    /// springs), a rotational spring of `k l^2 / 16` per unit length for the per-length
    /// stiffness `k`, which the continuous contact of a rod does not have (it holds the
    /// surface line, not the section's rotation). It vanishes as `l^2`, but against the wires'
    /// shear and torsion, which carry the rolling of the first layer's wires between the core
    /// and the crossings of a second layer, it bonds the sections until the segments are a
    /// small fraction of a millimetre: the all-stick stiffness of the 1+6+12 strand then
    /// falls from 0.458 to 0.378 K_max between 16 and 64 segments per pitch, where one point
    /// gives 0.366 and 0.363 (Multi-layer page).
    pub fn points_on(&self, strand: &strand_core::Strand) -> usize {
        self.points_per_segment
            .unwrap_or(if strand.layers().len() > 1 { 1 } else { 2 })
            .clamp(1, 2)
    }

    /// Normal and tangential stiffness of the contacts per unit length of a helical wire of
    /// `layer` (N/m^2): `T_w sin^2(alpha) / (R_w penetration d_w)` and
    /// `E_w A_w q^2 / stick_loss` (see [`ContactOptions`]).
    pub fn stiffness_per_length(&self, layer: &HelixLayer) -> (f64, f64) {
        let wire = &layer.spec.wire;
        let (ew, aw) = (wire.material.youngs_modulus, wire.area());
        let alpha = layer.lay_angle();
        let tension = self
            .reference_tension
            .unwrap_or(ew * aw * alpha.cos().powi(2) * self.reference_strain);
        let pressure = tension * alpha.sin().powi(2) / layer.radius;
        let q = alpha.sin() / layer.radius;
        (
            pressure / (self.penetration * wire.diameter),
            ew * aw * q * q / self.stick_loss,
        )
    }
}

/// Contact state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactState {
    /// Surfaces apart.
    #[default]
    Open,
    /// Closed, tangential force below mu N.
    Stick,
    /// Closed, tangential force at mu N.
    Slip,
}

/// A contact point of a helical wire segment (fixed data).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Segment of the helical wire carrying the point.
    pub segment: usize,
    /// The point on the segment's axis, body axes, relative to its centre (m).
    pub offset: Vector3<f64>,
    /// Distance of the point from the core axis at rest (m): the gap is measured from it.
    pub rest_distance: f64,
    /// Share of the gap from the core axis to the contact point, r_c / (r_c + r_w) (-).
    pub core_share: f64,
    /// Penalty and friction.
    pub law: ContactLaw,
}

/// How a static solve holds a contact's state through the Newton iterations of one active
/// set ([`crate::statics`]): `Free` is the contact law itself; the held states fix its
/// branch, so that the loads are smooth in the positions while the solve runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Hold {
    /// The law decides open, stick or slip at every evaluation.
    #[default]
    Free,
    /// No force, whatever the gap.
    Open,
    /// Closed and stuck: the normal spring acts at any gap (in tension too, `N = -k_n g`),
    /// the tangential spring without the Coulomb cap.
    Stick,
    /// Closed and slipping: the normal spring as for `Stick`; the tangential force is
    /// `mu max(N, 0)` along the held direction ([`ContactHistory::slip_direction`] in the
    /// tangent plane), none where the held direction is zero (frictionless).
    Slip,
}

/// Committed history of a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactHistory {
    /// Core segment paired at the last commit.
    pub core_segment: usize,
    /// True when the contact was closed at the last commit.
    pub closed: bool,
    /// Stored tangential elastic displacement of the wire relative to the core, world axes
    /// (m).
    pub displacement: Vector3<f64>,
    /// Contact point at the last commit in the wire segment's body axes (m).
    pub on_wire: Vector3<f64>,
    /// Contact point at the last commit in core segment `core_segment`'s body axes (m).
    pub on_core: Vector3<f64>,
    /// State held by the static solve's active set; `Free` in every committed history.
    pub hold: Hold,
    /// Direction of the friction force on the wire held with [`Hold::Slip`] (world axes,
    /// projected on the current tangent plane at every evaluation).
    pub slip_direction: Vector3<f64>,
}

impl ContactHistory {
    /// Open contact paired with core segment `core_segment`, no stored displacement.
    pub fn open(core_segment: usize) -> Self {
        Self {
            core_segment,
            closed: false,
            displacement: Vector3::zeros(),
            on_wire: Vector3::zeros(),
            on_core: Vector3::zeros(),
            hold: Hold::Free,
            slip_direction: Vector3::zeros(),
        }
    }
}

/// Loads of one contact evaluation (world axes), its state, energies and the history to
/// commit if the evaluation is accepted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLoad {
    /// Core segment the core-side loads act on.
    pub core_segment: usize,
    /// Force on the wire segment (N).
    pub force_wire: Vector3<f64>,
    /// Torque on the wire segment about its centre (N m).
    pub torque_wire: Vector3<f64>,
    /// Force on the core segment (N).
    pub force_core: Vector3<f64>,
    /// Torque on the core segment about its centre (N m).
    pub torque_core: Vector3<f64>,
    /// Normal force N >= 0 (N).
    pub normal_force: f64,
    /// Tangential force on the wire (N).
    pub tangential_force: Vector3<f64>,
    /// Open, stick or slip.
    pub state: ContactState,
    /// Penalty energy k_n g^2 / 2 (J).
    pub normal_energy: f64,
    /// Energy stored in the tangential spring, |F_t|^2 / (2 k_t) (J).
    pub tangential_energy: f64,
    /// Work lost to slip since the last commit (J).
    pub slip_work: f64,
    /// History to commit.
    pub history: ContactHistory,
}

impl ContactLoad {
    /// Load of an open contact paired with core segment `core_segment`.
    pub fn open_at(core_segment: usize) -> Self {
        let z = Vector3::zeros();
        Self {
            core_segment,
            force_wire: z,
            torque_wire: z,
            force_core: z,
            torque_core: z,
            normal_force: 0.0,
            tangential_force: z,
            state: ContactState::Open,
            normal_energy: 0.0,
            tangential_energy: 0.0,
            slip_work: 0.0,
            history: ContactHistory::open(core_segment),
        }
    }
}

/// Index of the core segment whose axis span contains the projection of `point`, searched
/// from `guess` toward the neighbours (clamped to the chain ends).
pub fn nearest_core_segment<P: Placement>(
    core: &[P],
    segments: &[Segment],
    point: &Vector3<f64>,
    guess: usize,
) -> usize {
    core_search(core, segments, point, guess).0
}

/// The local search of [`nearest_core_segment`]: the segment found and the projection of
/// `point` on its axis from its centre (m), `(point - c) . t`, which [`closest_on_axis`]
/// would compute again. Inlined: with the panic of its unreachable end it is no longer
/// inlined by itself, and the call was 0.4 % of a settle step.
#[inline(always)]
fn core_search<P: Placement>(
    core: &[P],
    segments: &[Segment],
    point: &Vector3<f64>,
    guess: usize,
) -> (usize, f64) {
    let mut j = guess.min(core.len() - 1);
    let mut last_move = 0i8;
    for _ in 0..core.len() {
        let s = (point - core[j].centre()).dot(&core[j].tangent());
        let half = 0.5 * segments[j].length;
        // Never step back: in a kinked chain a point can project outside both neighbours.
        if s > half && j + 1 < core.len() && last_move >= 0 {
            j += 1;
            last_move = 1;
        } else if s < -half && j > 0 && last_move <= 0 {
            j -= 1;
            last_move = -1;
        } else {
            return (j, s);
        }
    }
    unreachable!(
        "every move of the core search goes the first one's way, at most len - 1 of them: it \
         ends on a segment it projected on within len projections"
    )
}

/// Closest point (m) to `p` on the axis of the core segment at `core` of length `length`.
pub fn closest_on_axis<P: Placement>(p: &Vector3<f64>, core: &P, length: f64) -> Vector3<f64> {
    let s = (p - core.centre()).dot(&core.tangent());
    on_axis(core, length, s)
}

/// The point of the axis of the core segment at `core` (length `length`, m) at the axial
/// coordinate `s` from its centre (m), clamped to the segment.
fn on_axis<P: Placement>(core: &P, length: f64, s: f64) -> Vector3<f64> {
    core.centre() + core.tangent() * s.clamp(-0.5 * length, 0.5 * length)
}

/// Evaluates contact point `cp` of the wire segment at `wire` against core segment `j` at
/// `cj` (length `core_length`), from the committed `history`, whose anchor sits on the core
/// segment at `anchor_core` (segment `history.core_segment`, `j` or a neighbour).
pub fn evaluate_pair<W: Placement, C: Placement>(
    cp: &ContactPoint,
    history: &ContactHistory,
    wire: &W,
    cj: &C,
    j: usize,
    core_length: f64,
    anchor_core: &C,
) -> ContactLoad {
    let p = wire.point(&cp.offset);
    let q = closest_on_axis(&p, cj, core_length);
    respond(
        &cp.law,
        history,
        (&p, &q),
        cp.rest_distance,
        cp.core_share,
        wire,
        (cj, j),
        anchor_core,
    )
}

/// The contact law between the point `p` of the body at `wire` and the point `q` of the
/// partner body at `cj` (its segment index `j`), both bodies' contact points on the line
/// `q p`: penalty on the gap `|p - q| - rest_distance` along `n = (p - q) / |p - q|` and the
/// stick/slip spring from the committed `history`, anchored on the partner at `anchor_core`
/// (module docs); the contact point divides `q p` at `share` from `q`. One law for the
/// wire-to-core contacts and the wire-to-wire ones ([`crate::interlayer`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn respond<W: Placement, C: Placement>(
    law: &ContactLaw,
    history: &ContactHistory,
    pq: (&Vector3<f64>, &Vector3<f64>),
    rest_distance: f64,
    share: f64,
    wire: &W,
    partner: (&C, usize),
    anchor_core: &C,
) -> ContactLoad {
    let mut out = ContactLoad::open_at(partner.1);
    respond_into(
        law,
        history,
        pq,
        rest_distance,
        share,
        wire,
        partner,
        anchor_core,
        &mut out,
    );
    out
}

/// [`respond`] written into `out` (the load buffer's slot: no copy of the result).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn respond_into<W: Placement, C: Placement>(
    law: &ContactLaw,
    history: &ContactHistory,
    (p, q): (&Vector3<f64>, &Vector3<f64>),
    rest_distance: f64,
    share: f64,
    wire: &W,
    (cj, j): (&C, usize),
    anchor_core: &C,
    out: &mut ContactLoad,
) {
    let (p, q) = (*p, *q);
    let d = p - q;
    let dist = d.norm();
    let gap = dist - rest_distance;
    let held_closed = matches!(history.hold, Hold::Stick | Hold::Slip);
    if history.hold == Hold::Open || (gap >= 0.0 && !held_closed) || dist == 0.0 {
        *out = ContactLoad::open_at(j);
        return;
    }
    let n = d / dist;
    let fn_ = law.normal_stiffness * (-gap);
    let x = q + d * share;
    // Tangential elastic displacement of the wire relative to the core.
    let (u, aw, ac) = if history.closed {
        let aw = wire.point(&history.on_wire);
        let ac = anchor_core.point(&history.on_core);
        let u0 = history.displacement;
        let mut ur = u0 - n * n.dot(&u0);
        let (l0, lr) = (u0.norm(), ur.norm());
        if lr > 0.0 {
            ur *= l0 / lr;
        }
        let du = aw - ac;
        (ur + du - n * n.dot(&du), aw, ac)
    } else {
        (Vector3::zeros(), x, x)
    };
    let kt = law.tangential_stiffness;
    let cap = law.friction * fn_.max(0.0);
    let un = u.norm();
    let slips = match history.hold {
        Hold::Free => kt * un > cap,
        Hold::Slip => true,
        Hold::Stick | Hold::Open => false,
    };
    let held_direction = (history.hold == Hold::Slip)
        .then(|| history.slip_direction - n * n.dot(&history.slip_direction))
        .filter(|d| d.norm() > 0.0);
    let (u_el, state, slip_work) = if history.hold == Hold::Slip {
        // Held slip: the friction force mu N along the held direction, none without one.
        let u_el = held_direction.map_or(Vector3::zeros(), |d| d * (-cap / (kt * d.norm())));
        (
            u_el,
            ContactState::Slip,
            cap * un - 0.5 * kt * u_el.norm_squared(),
        )
    } else if slips {
        let u_el = if un > 0.0 { u * (cap / (kt * un)) } else { u };
        (u_el, ContactState::Slip, cap * (un - cap / kt))
    } else {
        (u, ContactState::Stick, 0.0)
    };
    let ft = -kt * u_el;
    let f_n = n * fn_;
    let (c, cc) = (wire.centre(), cj.centre());
    *out = ContactLoad {
        core_segment: j,
        force_wire: f_n + ft,
        torque_wire: (p - c).cross(&f_n) + (aw - c).cross(&ft),
        force_core: -(f_n + ft),
        torque_core: (q - cc).cross(&(-f_n)) + (ac - cc).cross(&(-ft)),
        normal_force: fn_,
        tangential_force: ft,
        state,
        normal_energy: 0.5 * fn_ * (-gap),
        tangential_energy: 0.5 * kt * u_el.norm_squared(),
        slip_work,
        history: ContactHistory {
            core_segment: j,
            closed: true,
            displacement: u_el,
            on_wire: wire.to_body(&(x - c)),
            on_core: cj.to_body(&(x - cc)),
            hold: Hold::Free,
            slip_direction: Vector3::zeros(),
        },
    };
}

/// Evaluates contact point `cp` of the wire segment at `wire` against the core (poses
/// `core`, segments `core_segments`), pairing it by a local search from the history's core
/// segment.
pub fn evaluate<P: Placement>(
    cp: &ContactPoint,
    history: &ContactHistory,
    wire: &P,
    core: &[P],
    core_segments: &[Segment],
) -> ContactLoad {
    let mut out = ContactLoad::open_at(history.core_segment);
    evaluate_into(cp, history, wire, core, core_segments, &mut out);
    out
}

/// [`evaluate`] written into `out` (a load buffer's slot: no copy of the result).
pub fn evaluate_into<P: Placement>(
    cp: &ContactPoint,
    history: &ContactHistory,
    wire: &P,
    core: &[P],
    core_segments: &[Segment],
    out: &mut ContactLoad,
) {
    let p = wire.point(&cp.offset);
    let (j, s) = core_search(core, core_segments, &p, history.core_segment);
    let (cj, length) = (&core[j], core_segments[j].length);
    // The search's last projection is the one the closest point needs.
    let q = on_axis(cj, length, s);
    let anchor = &core[history.core_segment.min(core.len() - 1)];
    respond_into(
        &cp.law,
        history,
        (&p, &q),
        cp.rest_distance,
        cp.core_share,
        wire,
        (cj, j),
        anchor,
        out,
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::segment::{Frame, Pose};
    use nalgebra::UnitQuaternion;

    fn point(k: f64) -> ContactPoint {
        ContactPoint {
            segment: 0,
            offset: Vector3::zeros(),
            rest_distance: 2.5e-3,
            core_share: 0.6,
            law: ContactLaw {
                normal_stiffness: k,
                tangential_stiffness: k,
                friction: 0.3,
            },
        }
    }

    /// A wire segment lying on a fixed core segment, pressed by N and pulled along the core
    /// by P, integrated in time with the history committed every step.
    fn pull(pull_force: f64, normal: f64) -> (f64, ContactState) {
        let cp = point(normal / 1e-6);
        let law = cp.law;
        let core_seg = Segment::cylinder(0.02, 1.5e-3, 7801.0);
        let wire_seg = Segment::cylinder(0.005, 1e-3, 7801.0);
        let core = [Pose::new(Vector3::zeros(), UnitQuaternion::identity())];
        let mut wire = Pose::new(
            Vector3::new(0.0, 2.5e-3 - normal / law.normal_stiffness, 0.0),
            UnitQuaternion::identity(),
        );
        let mut v = Vector3::zeros();
        let mut h = ContactHistory::open(0);
        let omega = (law.tangential_stiffness / wire_seg.mass).sqrt();
        let dt = 0.05 / omega;
        let external = Vector3::new(pull_force, -normal, 0.0);
        let mut state = ContactState::Open;
        // Critical damping of the wire: a sudden pull must not overshoot into slip.
        let damping = 2.0 * omega * wire_seg.mass;
        for _ in 0..20_000 {
            let l = evaluate(&cp, &h, &wire, &core, &[core_seg]);
            h = l.history;
            state = l.state;
            let f = l.force_wire + external - damping * v;
            v += f * (dt / wire_seg.mass);
            wire.position += v * dt;
        }
        (wire.position.x, state)
    }

    #[test]
    fn sticks_below_mu_n_and_slides_above() {
        let (n, mu) = (1.0, 0.3);
        let k = n / 1e-6;
        let (x, state) = pull(0.9 * mu * n, n);
        assert_eq!(state, ContactState::Stick);
        assert!(
            (x - 0.9 * mu * n / k).abs() < 1e-3 * 0.9 * mu * n / k,
            "x = {x:e}"
        );
        // Above mu N: the damped terminal speed (P - mu N) / c over T = 1000 / omega with
        // c = 2 omega m gives (P - mu N) 500 / k, plus the spring displacement mu N / k.
        let (x, state) = pull(1.1 * mu * n, n);
        assert_eq!(state, ContactState::Slip);
        let expected = 0.1 * mu * n * 500.0 / k + mu * n / k;
        assert!(
            (x - expected).abs() < 0.02 * expected,
            "x = {x:e}, expected {expected:e}"
        );
    }

    #[test]
    fn open_at_zero_gap() {
        let cp = point(1e6);
        let core = [Pose::new(Vector3::zeros(), UnitQuaternion::identity())];
        let seg = [Segment::cylinder(0.02, 1.5e-3, 7801.0)];
        for y in [2.5e-3, 2.6e-3] {
            let wire = Pose::new(Vector3::new(0.0, y, 0.0), UnitQuaternion::identity());
            let l = evaluate(&cp, &ContactHistory::open(0), &wire, &core, &seg);
            assert_eq!(l.state, ContactState::Open);
            assert_eq!(l.force_wire, Vector3::zeros());
        }
    }

    /// `evaluate` (the search's last projection reused, the result written in place) against
    /// the composition it replaces: the search, then `evaluate_pair` (closest point computed
    /// afresh), bit for bit, on a kinked core chain, with open, stuck and slipping contacts,
    /// committed histories and points beyond the chain's ends.
    #[test]
    fn evaluate_is_search_then_pair() {
        let n = 6;
        let segs: Vec<_> = (0..n)
            .map(|k| Segment::cylinder(0.01 + 1e-3 * k as f64, 1.5e-3, 7801.0))
            .collect();
        let core: Vec<Frame> = (0..n)
            .map(|k| {
                let turn = UnitQuaternion::from_scaled_axis(Vector3::new(
                    0.1 * k as f64,
                    0.3 * (k % 2) as f64,
                    -0.2,
                ));
                Frame::of(&Pose::new(
                    Vector3::new(0.01 * k as f64, 1e-4 * k as f64, -2e-4),
                    turn,
                ))
            })
            .collect();
        let mut cp = point(1e6);
        cp.offset = Vector3::new(1e-3, -2e-4, 3e-4);
        let mut compared = [0usize; 3];
        for (i, x) in [-0.02, 0.0, 0.004, 0.013, 0.027, 0.038, 0.05, 0.09]
            .into_iter()
            .enumerate()
        {
            for (guess, lift) in [(0, 2.2e-3), (3, 2.45e-3), (5, 2.6e-3), (2, 2.3e-3)] {
                let turn =
                    UnitQuaternion::from_scaled_axis(Vector3::new(0.2, -0.1, 0.05 * i as f64));
                let wire = Frame::of(&Pose::new(Vector3::new(x, lift, 1e-4), turn));
                for history in [
                    ContactHistory::open(guess),
                    ContactHistory {
                        core_segment: guess,
                        closed: true,
                        displacement: Vector3::new(1e-7, -3e-7, 2e-7),
                        on_wire: Vector3::new(-2e-4, 1e-3, 0.0),
                        on_core: Vector3::new(1e-3, 1.4e-3, 5e-4),
                        hold: Hold::Free,
                        slip_direction: Vector3::zeros(),
                    },
                ] {
                    let got = evaluate(&cp, &history, &wire, &core, &segs);
                    let p = wire.point(&cp.offset);
                    let j = nearest_core_segment(&core, &segs, &p, history.core_segment);
                    let anchor = &core[history.core_segment.min(n - 1)];
                    let want =
                        evaluate_pair(&cp, &history, &wire, &core[j], j, segs[j].length, anchor);
                    assert_eq!(got, want, "x {x}, guess {guess}, lift {lift}");
                    compared[got.state as usize] += 1;
                }
            }
        }
        // Every branch of the law was compared.
        assert!(compared.iter().all(|&c| c > 0), "{compared:?}");
    }

    /// The held states against the closed forms of one contact (k_n = k_t = 1e6 N/m, mu =
    /// 0.3): a contact held stuck keeps its normal spring at a positive gap (tension
    /// `k_n g`) and its tangential spring past the cap; one held open carries nothing while
    /// it penetrates; one held slipping carries `mu N` along the held direction; `Free` is
    /// the law.
    #[test]
    fn held_states_fix_the_law_branch() {
        let cp = point(1e6);
        let core = [Pose::new(Vector3::zeros(), UnitQuaternion::identity())];
        let seg = [Segment::cylinder(0.02, 1.5e-3, 7801.0)];
        let at = |x: f64, gap: f64| {
            Pose::new(
                Vector3::new(x, 2.5e-3 + gap, 0.0),
                UnitQuaternion::identity(),
            )
        };
        let with = |hold: Hold, h: ContactHistory| ContactHistory {
            hold,
            slip_direction: Vector3::new(0.0, 0.0, 1.0),
            ..h
        };
        let open = ContactHistory::open(0);
        let close = |a: Vector3<f64>, b: Vector3<f64>| (a - b).norm() <= 1e-9 * b.norm().max(1.0);
        // Apart by 1 um: the law is open; held stuck, the spring pulls the wire in by 1 N.
        let apart = at(0.0, 1e-6);
        assert_eq!(
            evaluate(&cp, &open, &apart, &core, &seg).state,
            ContactState::Open
        );
        let l = evaluate(&cp, &with(Hold::Stick, open), &apart, &core, &seg);
        assert!(close(l.force_wire, Vector3::new(0.0, -1.0, 0.0)), "{l:?}");
        // Pressed by 1 um: the law pushes out by 1 N; held open, nothing.
        let pressed = at(0.0, -1e-6);
        let l = evaluate(&cp, &open, &pressed, &core, &seg);
        assert!(close(l.force_wire, Vector3::new(0.0, 1.0, 0.0)), "{l:?}");
        let l = evaluate(&cp, &with(Hold::Open, open), &pressed, &core, &seg);
        assert_eq!(l.state, ContactState::Open);
        assert_eq!(l.force_wire, Vector3::zeros());
        // Closed at `pressed`, then slid 1 um along the core: k_t u = 1 N past the cap 0.3 N.
        let stuck = evaluate(&cp, &open, &pressed, &core, &seg).history;
        let slid = at(1e-6, -1e-6);
        let l = evaluate(&cp, &stuck, &slid, &core, &seg);
        assert_eq!(l.state, ContactState::Slip);
        assert!(
            close(l.tangential_force, Vector3::new(-0.3, 0.0, 0.0)),
            "{l:?}"
        );
        let l = evaluate(&cp, &with(Hold::Stick, stuck), &slid, &core, &seg);
        assert_eq!(l.state, ContactState::Stick);
        assert!(
            close(l.tangential_force, Vector3::new(-1.0, 0.0, 0.0)),
            "{l:?}"
        );
        let l = evaluate(&cp, &with(Hold::Slip, stuck), &slid, &core, &seg);
        assert_eq!(l.state, ContactState::Slip);
        assert!(
            close(l.tangential_force, Vector3::new(0.0, 0.0, 0.3)),
            "{l:?}"
        );
        // Held states are never committed.
        assert_eq!(l.history.hold, Hold::Free);
    }

    #[test]
    fn local_search_finds_the_covering_segment() {
        let segs = vec![Segment::cylinder(0.01, 1e-3, 1000.0); 10];
        let poses: Vec<_> = (0..10)
            .map(|k| {
                Pose::new(
                    Vector3::new(0.005 + 0.01 * k as f64, 0.0, 0.0),
                    UnitQuaternion::identity(),
                )
            })
            .collect();
        let p = Vector3::new(0.0731, 0.002, 0.0);
        assert_eq!(nearest_core_segment(&poses, &segs, &p, 0), 7);
        assert_eq!(nearest_core_segment(&poses, &segs, &p, 9), 7);
        assert_eq!(
            nearest_core_segment(&poses, &segs, &Vector3::new(-1.0, 0.0, 0.0), 5),
            0
        );
    }
}
