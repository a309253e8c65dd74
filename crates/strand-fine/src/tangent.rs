//! Tangent stiffness of the whole model as a list of element blocks.
//!
//! Generalized coordinates: per segment (global index `s`), six entries starting at `6 s`:
//! the translation of the centre (m) and a world-frame rotation increment (rad).

use nalgebra::{DMatrix, Matrix3, SMatrix, Vector3};
use rayon::prelude::*;

use crate::contact::{self, ContactLoad, ContactPoint};
use crate::joint::perturb;
use crate::model::{FineModel, ModelState};
use crate::segment::{Frame, Placement, Pose};

/// Stiffness of one element (joint or anchor) on its segments.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementTangent {
    /// Global segment index of body `a` (`None` for the ground) and of body `b`.
    pub segments: [Option<usize>; 2],
    /// `-d(loads)/d(coordinates)` over (a, b), 12 x 12.
    pub stiffness: SMatrix<f64, 12, 12>,
}

impl ElementTangent {
    /// Adds the element's blocks to the dense tangent `k` of the whole model (`6 n` square for
    /// `n` segments, coordinates as in the module docs); a ground side adds nothing. For
    /// dense analysis of small models.
    pub fn add_to_dense(&self, k: &mut DMatrix<f64>) {
        for (bi, si) in self.segments.iter().enumerate() {
            let Some(si) = si else { continue };
            for (bj, sj) in self.segments.iter().enumerate() {
                let Some(sj) = sj else { continue };
                for r in 0..6 {
                    for c in 0..6 {
                        k[(6 * si + r, 6 * sj + c)] += self.stiffness[(6 * bi + r, 6 * bj + c)];
                    }
                }
            }
        }
    }
}

/// A contact taken as closed, at a state: its point on the wire's axis and the core segment
/// paired with it.
struct ClosedContact<'a> {
    /// Index of the wire and of the contact in the wire's list.
    index: (usize, usize),
    contact: &'a ContactPoint,
    /// Pose of the wire segment that carries the contact.
    wire: &'a Pose,
    /// The contact point on the wire segment's axis (m).
    point: Vector3<f64>,
    /// Index of the core segment nearest to `point`.
    core_segment: usize,
    /// Pose of that core segment.
    core: &'a Pose,
}

impl FineModel {
    /// Global index of each wire's first segment.
    pub fn segment_offsets(&self) -> Vec<usize> {
        let mut off = Vec::with_capacity(self.wires.len());
        let mut n = 0;
        for w in &self.wires {
            off.push(n);
            n += w.chain.len();
        }
        off
    }

    /// Element tangents at `state`: joints, anchors and contacts (gravity is a constant load
    /// and adds no stiffness).
    pub fn element_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        let mut out = self.joint_tangents(state);
        out.extend(self.contact_tangents(state));
        out.extend(self.link_tangents(state));
        out
    }

    /// Tangents of the contacts at `state` with the committed histories frozen: central
    /// differences of the contact loads over the wire segment and the paired core segment
    /// (the consistent tangent of the stick or slip branch; zero for an open contact). The
    /// steps stay below a tenth of the distance to the branch's ends (zero gap, the
    /// stick-slip limit): under a light load these are far below 1e-10 m.
    pub fn contact_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        let offsets = self.segment_offsets();
        let core = &self.wires[0].chain;
        let core_poses = &state.wires[0].poses;
        let core_frames: Vec<Frame> = core_poses.iter().map(Frame::of).collect();
        let per_wire: Vec<Vec<ElementTangent>> = self
            .wires
            .par_iter()
            .zip(state.wires.par_iter())
            .zip(state.contacts.par_iter())
            .zip(offsets.par_iter())
            .map(|(((w, s), hist), &off)| {
                let mut out = Vec::new();
                for (cp, h) in w.contacts.iter().zip(hist) {
                    let wire = s.poses[cp.segment];
                    let p = Frame::of(&wire).point(&cp.offset);
                    let j = contact::nearest_core_segment(
                        &core_frames,
                        &core.segments,
                        &p,
                        h.core_segment,
                    );
                    let lj = core.segments[j].length;
                    let hc = h.core_segment.min(core_poses.len() - 1);
                    // Loads are invariant under a translation of all bodies: evaluate about
                    // the core segment's centre, where coordinates are small and a step of
                    // 1e-15 m still moves them by many ulps.
                    let origin = core_poses[j].position;
                    let local = |pose: &Pose| Pose::new(pose.position - origin, pose.rotation);
                    let eval = |col: usize, step: f64| -> ContactLoad {
                        let mut wp = local(&wire);
                        let mut cj = local(&core_poses[j]);
                        let mut anchor = local(&core_poses[hc]);
                        if col < 6 {
                            perturb(&mut wp, col, step);
                        } else {
                            perturb(&mut cj, col - 6, step);
                            if hc == j {
                                anchor = cj;
                            }
                        }
                        let (wp, cj, anchor) = (Frame::of(&wp), Frame::of(&cj), Frame::of(&anchor));
                        contact::evaluate_pair(cp, h, &wp, &cj, j, lj, &anchor)
                    };
                    if eval(0, 0.0).state == contact::ContactState::Open {
                        // Held open by the static solve's active set: no load, no tangent.
                        if h.hold == contact::Hold::Open {
                            continue;
                        }
                        // A contact at exactly zero gap (the lay geometry) enters with its
                        // normal spring, so that Newton sees the core under the wire before
                        // it penetrates.
                        let q = contact::closest_on_axis(&p, &core_frames[j], lj);
                        let d = p - q;
                        if d.norm() > cp.rest_distance || d.norm() == 0.0 {
                            continue;
                        }
                        let n = d.normalize();
                        let b =
                            contact_jacobian(&(p - wire.position), &(q - core_poses[j].position));
                        let bn = n.transpose() * b;
                        out.push(ElementTangent {
                            segments: [Some(off + cp.segment), Some(j)],
                            stiffness: bn.transpose() * bn * cp.law.normal_stiffness,
                        });
                        continue;
                    }
                    let c0 = eval(0, 0.0);
                    let k = contact_difference(
                        &c0,
                        &cp.law,
                        1e-7 * w.chain.section.radius,
                        h.hold,
                        eval,
                    );
                    out.push(ElementTangent {
                        segments: [Some(off + cp.segment), Some(j)],
                        stiffness: k,
                    });
                }
                out
            })
            .collect();
        per_wire.into_iter().flatten().collect()
    }

    /// Stiffness bounds of every contact as if closed: an isotropic spring of the larger of
    /// `k_n`, `k_t` between the contact points of the wire and the paired core segment (for
    /// the stable time step).
    pub fn contact_bound_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        let mut out = self.closed_contact_tangents(state, |c| {
            let law = &c.contact.law;
            let k = law.normal_stiffness.max(law.tangential_stiffness);
            let b = contact_jacobian(&(c.point - c.wire.position), &(c.point - c.core.position));
            Some(b.transpose() * b * k)
        });
        out.extend(self.link_bound_tangents(state));
        out
    }

    /// Tangents of every contact as if closed and stuck, at `state`: the normal spring `k_n`
    /// along the line between the axes and the stick spring `k_t` across it, acting at the
    /// contact point between the surfaces (so the core turns about its axis on the arm of its
    /// radius and the wire on its own). Slip and opening only soften a contact, so these
    /// bound the contact stiffness in every state (geometric terms of the contact forces
    /// aside), closer than [`FineModel::contact_bound_tangents`], which puts `max(k_n, k_t)`
    /// in every direction at the wire's axis.
    pub fn contact_stick_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        let mut out = self.stick_tangents_where(state, |_, _| true);
        // Wire-to-wire links: the isotropic bound.
        out.extend(self.link_bound_tangents(state));
        out
    }

    /// Tangents of the joints and of the wire-to-core contacts `closed(wire, contact)`
    /// (indices as in [`ModelState::contacts`]) taken stuck, as in
    /// [`FineModel::contact_stick_tangents`], at `state`, with the wire-to-wire links'
    /// consistent tangents: the elastic tangent of friction, which a contact that goes on
    /// slipping does not have but one that sticks again does (the continuation of
    /// [`crate::pseudo_transient`] builds its steps on it).
    pub fn elastic_tangents(
        &self,
        state: &ModelState,
        closed: impl Fn(usize, usize) -> bool,
    ) -> Vec<ElementTangent> {
        let mut out = self.joint_tangents(state);
        out.extend(self.stick_tangents_where(state, closed));
        out.extend(self.link_tangents(state));
        out
    }

    /// [`FineModel::contact_stick_tangents`] of the wire-to-core contacts `keep(wire,
    /// contact)`.
    fn stick_tangents_where(
        &self,
        state: &ModelState,
        keep: impl Fn(usize, usize) -> bool,
    ) -> Vec<ElementTangent> {
        let core = &self.wires[0].chain;
        self.closed_contact_tangents(state, |c| {
            if !keep(c.index.0, c.index.1) {
                return None;
            }
            let q =
                contact::closest_on_axis(&c.point, c.core, core.segments[c.core_segment].length);
            let d = c.point - q;
            let n = if d.norm() > 0.0 {
                d.normalize()
            } else {
                return None;
            };
            let x = q + d * c.contact.core_share;
            let b = contact_jacobian(&(x - c.wire.position), &(x - c.core.position));
            let law = &c.contact.law;
            let spring = n * n.transpose() * (law.normal_stiffness - law.tangential_stiffness)
                + Matrix3::identity() * law.tangential_stiffness;
            Some(b.transpose() * spring * b)
        })
    }

    /// The blocks `stiffness` gives for every contact closed at `state`, each on its wire
    /// segment and the core segment nearest to its point (`None`: the contact adds nothing).
    fn closed_contact_tangents(
        &self,
        state: &ModelState,
        stiffness: impl Fn(&ClosedContact) -> Option<SMatrix<f64, 12, 12>>,
    ) -> Vec<ElementTangent> {
        let offsets = self.segment_offsets();
        let core = &self.wires[0].chain;
        let core_poses = &state.wires[0].poses;
        let mut out = Vec::with_capacity(self.contact_count());
        for (i, ((w, s), (hist, &off))) in self
            .wires
            .iter()
            .zip(&state.wires)
            .zip(state.contacts.iter().zip(&offsets))
            .enumerate()
        {
            for (k, (cp, h)) in w.contacts.iter().zip(hist).enumerate() {
                let wire = &s.poses[cp.segment];
                let p = wire.point(&cp.offset);
                let j =
                    contact::nearest_core_segment(core_poses, &core.segments, &p, h.core_segment);
                let closed = ClosedContact {
                    index: (i, k),
                    contact: cp,
                    wire,
                    point: p,
                    core_segment: j,
                    core: &core_poses[j],
                };
                if let Some(k) = stiffness(&closed) {
                    out.push(ElementTangent {
                        segments: [Some(off + cp.segment), Some(j)],
                        stiffness: k,
                    });
                }
            }
        }
        out
    }

    /// Tangents of the joints, anchors and ties at `state`.
    pub fn joint_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        let offsets = self.segment_offsets();
        let per_wire: Vec<Vec<ElementTangent>> = self
            .wires
            .par_iter()
            .zip(state.wires.par_iter())
            .zip(offsets.par_iter())
            .map(|((w, s), &off)| {
                let c = &w.chain;
                let mut out = Vec::with_capacity(c.joints.len() + w.anchors.len());
                for (k, j) in c.joints.iter().enumerate() {
                    out.push(ElementTangent {
                        segments: [Some(off + k), Some(off + k + 1)],
                        stiffness: j.stiffness(&s.poses[k], &s.poses[k + 1], c.segments[k].length),
                    });
                }
                for a in &w.anchors {
                    let l = c.segments[a.segment].length;
                    out.push(ElementTangent {
                        segments: [None, Some(off + a.segment)],
                        stiffness: a.joint.stiffness(&a.ground, &s.poses[a.segment], l),
                    });
                }
                out
            })
            .collect();
        let mut out: Vec<ElementTangent> = per_wire.into_iter().flatten().collect();
        for t in &self.ties {
            let (a, b) = (
                &state.wires[0].poses[t.core_segment],
                &state.wires[t.wire].poses[t.segment],
            );
            let l = self.wires[t.wire].chain.segments[t.segment].length;
            out.push(ElementTangent {
                segments: [Some(t.core_segment), Some(offsets[t.wire] + t.segment)],
                stiffness: t.joint.stiffness(a, b, l),
            });
        }
        out
    }
}

/// Jacobian of the relative displacement of a contact point, wire side minus core side, with
/// respect to (dx_w, dw_w, dx_c, dw_c), for the arms `arm_wire`, `arm_core` (m) from the
/// segment centres.
pub(crate) fn contact_jacobian(
    arm_wire: &Vector3<f64>,
    arm_core: &Vector3<f64>,
) -> SMatrix<f64, 3, 12> {
    let mut b = SMatrix::<f64, 3, 12>::zeros();
    b.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&Matrix3::identity());
    b.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&(-arm_wire.cross_matrix()));
    b.fixed_view_mut::<3, 3>(0, 6)
        .copy_from(&(-Matrix3::identity()));
    b.fixed_view_mut::<3, 3>(0, 9)
        .copy_from(&arm_core.cross_matrix());
    b
}

/// Central differences of a contact element's loads over the 12 coordinates of its two
/// segments, `-dQ/dq` (N/m, N, N m per rad): `eval(col, h)` gives the loads with coordinate
/// `col` moved by `h`. Steps of `step_x0` (m) and 1e-7 rad, shrunk to a tenth of the distance
/// from `c0` to the nearest switch of the law (the penalty's kink at zero gap, the stick-slip
/// limit; for a state held by the static solve's active set, [`contact::Hold`], only the
/// friction cap's kink at N = 0), so that the differences stay on one branch.
pub(crate) fn contact_difference(
    c0: &ContactLoad,
    law: &contact::ContactLaw,
    step_x0: f64,
    hold: contact::Hold,
    eval: impl Fn(usize, f64) -> ContactLoad,
) -> SMatrix<f64, 12, 12> {
    let mut margin = c0.normal_force / law.normal_stiffness;
    let cap = law.friction * c0.normal_force;
    if hold != contact::Hold::Free {
        // A held state's loads are smooth but for the friction cap's kink at N = 0 (slip).
        margin = match hold {
            contact::Hold::Slip => margin.abs(),
            _ => f64::INFINITY,
        };
    } else if cap > 0.0 {
        margin = margin.min(match c0.state {
            contact::ContactState::Slip => c0.slip_work / cap,
            _ => (cap - c0.tangential_force.norm()) / law.tangential_stiffness,
        });
    }
    let shrink = (0.1 * margin / step_x0).clamp(1e-5, 1.0);
    let step_x = step_x0 * shrink;
    let mut k = SMatrix::<f64, 12, 12>::zeros();
    for col in 0..12 {
        let h = if col % 6 < 3 { step_x } else { 1e-7 * shrink };
        let (lp, lm) = (eval(col, h), eval(col, -h));
        for (blk, (x, y)) in [
            (lp.force_wire, lm.force_wire),
            (lp.torque_wire, lm.torque_wire),
            (lp.force_core, lm.force_core),
            (lp.torque_core, lm.torque_core),
        ]
        .iter()
        .enumerate()
        {
            for r in 0..3 {
                k[(3 * blk + r, col)] = -(x[r] - y[r]) / (2.0 * h);
            }
        }
    }
    k
}
