//! Contact of a helical wire segment with the core: normal penalty and Coulomb friction with
//! stick (Cundall-Strack tangential spring with history).
//!
//! The helical segment's centre `c` is paired with the closest point `q` on the axis of a core
//! segment found by a local search from the previous pairing (helical wires run nearly
//! parallel to the core, where a global closest-point search between beams is ill-posed).
//! With the unit normal `n = (c - q) / |c - q|` the surface gap is
//! `g = |c - q| - (r_core + r_wire)`; for `g < 0` the normal force is `k_n (-g)` along `n` on
//! the wire. The tangential spring runs between two material points, one on each body, fixed
//! in the bodies when the contact sticks (the history follows the contact as both bodies
//! move); its force `-k_t u_t` is capped at `mu N`, and when the cap is reached the core-side
//! point is moved so the spring holds exactly `mu N` (slip), which dissipates
//! `mu N |slip|`.

use nalgebra::Vector3;

use crate::segment::{Pose, Segment};

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

impl ContactLaw {
    /// Law whose penalty lets the expected normal force `force` (N) penetrate by
    /// `penetration` (m): `k_n = force / penetration`; the tangential stiffness equals the
    /// normal one.
    pub fn from_allowed_penetration(force: f64, penetration: f64, friction: f64) -> Self {
        let k = force / penetration;
        Self {
            normal_stiffness: k,
            tangential_stiffness: k,
            friction,
        }
    }
}

/// Stick state of a contact: the material points joined by the tangential spring, in the
/// body axes of the wire segment and of the core segment (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickAnchor {
    /// Point on the wire segment, relative to its centre, body axes (m).
    pub on_wire: Vector3<f64>,
    /// Point on the core segment, relative to its centre, body axes (m).
    pub on_core: Vector3<f64>,
}

/// Contact state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactState {
    /// Surfaces apart.
    Open,
    /// Closed, tangential force below mu N.
    Stick,
    /// Closed, tangential force at mu N.
    Slip,
}

/// Loads of one contact on the wire and core segments (world axes), and its state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLoad {
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
    /// State after this evaluation.
    pub state: ContactState,
    /// Anchor to commit if this evaluation is accepted (`None` when open).
    pub anchor: Option<StickAnchor>,
    /// Elastic energy in the normal and tangential springs (J).
    pub energy: f64,
    /// Length the anchor slipped in this evaluation (m); times mu N it is the work lost.
    pub slip: f64,
}

/// Index of the core segment whose axis span contains the projection of `point`, searched
/// from `guess` toward the neighbours (clamped to the chain ends).
pub fn nearest_core_segment(
    core: &[Pose],
    segments: &[Segment],
    point: &Vector3<f64>,
    guess: usize,
) -> usize {
    let mut j = guess.min(core.len() - 1);
    for _ in 0..core.len() {
        let s = (point - core[j].position).dot(&core[j].tangent());
        let half = 0.5 * segments[j].length;
        if s > half && j + 1 < core.len() {
            j += 1;
        } else if s < -half && j > 0 {
            j -= 1;
        } else {
            break;
        }
    }
    j
}

/// Evaluates the contact of wire segment `wire` (radius `r_wire`) with core segment `core`
/// (radius `r_core`, length `core_length`), from the committed anchor `anchor`.
pub fn evaluate(
    law: &ContactLaw,
    wire: &Pose,
    r_wire: f64,
    core: &Pose,
    r_core: f64,
    core_length: f64,
    anchor: Option<StickAnchor>,
) -> ContactLoad {
    let t = core.tangent();
    let c = wire.position;
    let s = (c - core.position)
        .dot(&t)
        .clamp(-0.5 * core_length, 0.5 * core_length);
    let q = core.position + t * s;
    let d = c - q;
    let dist = d.norm();
    let gap = dist - (r_core + r_wire);
    let zero = Vector3::zeros();
    if gap >= 0.0 || dist == 0.0 {
        return ContactLoad {
            force_wire: zero,
            torque_wire: zero,
            force_core: zero,
            torque_core: zero,
            normal_force: 0.0,
            tangential_force: zero,
            state: ContactState::Open,
            anchor: None,
            energy: 0.0,
            slip: 0.0,
        };
    }
    let n = d / dist;
    let fn_ = law.normal_stiffness * (-gap);
    let anchor = anchor.unwrap_or_else(|| StickAnchor {
        on_wire: wire.rotation.inverse_transform_vector(&(-n * r_wire)),
        on_core: core
            .rotation
            .inverse_transform_vector(&(q + n * r_core - core.position)),
    });
    let aw = wire.point(&anchor.on_wire);
    let ac = core.point(&anchor.on_core);
    let u = aw - ac;
    let ut = u - n * u.dot(&n);
    let mut ft = -law.tangential_stiffness * ut;
    let cap = law.friction * fn_;
    let mut state = ContactState::Stick;
    let mut new_anchor = anchor;
    let mut slip = 0.0;
    let ftn = ft.norm();
    if ftn > cap {
        ft *= if ftn > 0.0 { cap / ftn } else { 0.0 };
        state = ContactState::Slip;
        // Move the core-side point so the spring holds exactly mu N.
        let ac_new = aw + ft / law.tangential_stiffness;
        slip = (ac_new - ac).norm();
        new_anchor.on_core = core
            .rotation
            .inverse_transform_vector(&(ac_new - core.position));
    }
    let fw = n * fn_ + ft;
    ContactLoad {
        force_wire: fw,
        torque_wire: (aw - c).cross(&ft),
        force_core: -fw,
        torque_core: (q - core.position).cross(&(-n * fn_)) + (ac - core.position).cross(&(-ft)),
        normal_force: fn_,
        tangential_force: ft,
        state,
        anchor: Some(new_anchor),
        energy: 0.5 * (fn_ * (-gap) + ft.norm_squared() / law.tangential_stiffness),
        slip,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    /// A wire segment lying on a fixed core segment, pressed by N and pulled along the core
    /// by P, integrated in time with the anchor committed every step.
    fn pull(pull_force: f64, normal: f64, mu: f64) -> (f64, ContactState) {
        let (rc, rw) = (1.5e-3, 1.0e-3);
        let law = ContactLaw::from_allowed_penetration(normal, 1e-6, mu);
        let core_seg = Segment::cylinder(0.02, rc, 7801.0);
        let wire_seg = Segment::cylinder(0.005, rw, 7801.0);
        let core = Pose::new(Vector3::zeros(), UnitQuaternion::identity());
        // Start at the static penetration N / k_n.
        let mut wire = Pose::new(
            Vector3::new(0.0, rc + rw - normal / law.normal_stiffness, 0.0),
            UnitQuaternion::identity(),
        );
        let mut v = Vector3::zeros();
        let mut anchor = None;
        let omega = (law.tangential_stiffness / wire_seg.mass).sqrt();
        let dt = 0.05 / omega;
        let external = Vector3::new(pull_force, -normal, 0.0);
        let mut state = ContactState::Open;
        // Critical damping of the wire: a sudden pull must not overshoot into slip.
        let damping = 2.0 * omega * wire_seg.mass;
        for _ in 0..20_000 {
            let l = evaluate(&law, &wire, rw, &core, rc, core_seg.length, anchor);
            anchor = l.anchor;
            state = l.state;
            let f = l.force_wire + external - damping * v;
            v += f * (dt / wire_seg.mass);
            // Translation only: the torque is resisted by the wire's own chain in a strand.
            wire.position += v * dt;
        }
        (wire.position.x, state)
    }

    #[test]
    fn sticks_below_mu_n_and_slides_above() {
        let (n, mu) = (1.0, 0.3);
        let k = n / 1e-6;
        // Below mu N: only the spring displacement P / k_t.
        let (x, state) = pull(0.9 * mu * n, n, mu);
        assert_eq!(state, ContactState::Stick);
        assert!(
            (x - 0.9 * mu * n / k).abs() < 1e-3 * 0.9 * mu * n / k,
            "x = {x:e}"
        );
        // Above mu N: it slides at the damped terminal speed (P - mu N) / c over the run
        // time T = 1000 / omega with c = 2 omega m: (P - mu N) 500 / k, plus the spring
        // displacement mu N / k.
        let (x, state) = pull(1.1 * mu * n, n, mu);
        assert_eq!(state, ContactState::Slip);
        let expected = 0.1 * mu * n * 500.0 / k + mu * n / k;
        assert!(
            (x - expected).abs() < 0.02 * expected,
            "x = {x:e}, expected {expected:e}"
        );
    }

    #[test]
    fn open_when_apart() {
        let law = ContactLaw::from_allowed_penetration(1.0, 1e-6, 0.3);
        let core = Pose::new(Vector3::zeros(), UnitQuaternion::identity());
        let wire = Pose::new(Vector3::new(0.0, 2.6e-3, 0.0), UnitQuaternion::identity());
        let l = evaluate(&law, &wire, 1e-3, &core, 1.5e-3, 0.02, None);
        assert_eq!(l.state, ContactState::Open);
        assert_eq!(l.force_wire, Vector3::zeros());
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
