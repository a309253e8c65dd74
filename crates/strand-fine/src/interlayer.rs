//! Wire-to-wire contact: a helical wire on a wire of the layer beneath it (crossing points for
//! alternate lay, lines for the same lay direction) and on its neighbour in its own layer,
//! with the one contact law of [`crate::contact`] (normal penalty, Coulomb friction with stick
//! history).
//!
//! A [`WireLink`] is a segment `a` of one wire and a partner wire; its contact point follows
//! the closest approach of the two axes:
//!
//! * Narrow phase: with `t_a`, `t_b` the segment directions, `r = c_a - c_b` the offset of the
//!   centres and `beta = t_a . t_b`, the point of `a` is `p = c_a + s t_a` with
//!   `s = (beta t_b . r - t_a . r) / (1 - beta^2 + epsilon)`, the closest point of the two
//!   lines for crossing axes (`1 - beta^2 = sin^2(theta)` far above `epsilon`) and the centre
//!   of `a` for parallel ones, where a line contact has no closest point. `q` is the point of
//!   the partner's segment `b` closest to `p`. `epsilon = 2 delta (r_a + r_b) / l_a^2`, with
//!   `delta` the allowed penetration: at crossing angles where the contact patch
//!   (`|s| < sqrt(2 delta (r_a + r_b)) / sin(theta)`) is longer than the segment, the contact
//!   is a line contact and sits at the segment's centre. The link owns the contact only while
//!   `s` lies in `[-l_a/2, l_a/2)`: the crossing is counted once, by the segment that holds it.
//! * Broad phase: `b` is searched along the partner chain from the committed partner segment
//!   (the segment whose axial span holds the projection of `p`), so that the contact follows the
//!   wires as they slide and the strand bends; the cost is one link per segment and partner
//!   wire of the adjacent layer, linear in the number of segments.
//! * Chord sag: a segment is the chord of its helical arc; the arc stands off the chord by
//!   `delta(s) = h (1 - 4 s^2 / l^2)` (`h = R_w (1 - cos(dphi / 2))` for a helix of radius
//!   `R_w` turning by `dphi` over the segment) away from the strand axis, along the segment's
//!   body axis 2 (toward the strand axis at rest). The gap is measured between the arcs, so that
//!   the lay geometry touches with (nearly) zero gap although the chords of the outer layer sag
//!   by far more than the allowed penetration toward the layer beneath.
//! * Law: gap `g = |p' - q'| - (r_a + r_b) - g_0` between the arc points `p'`, `q'`, with `g_0`
//!   the link's rest gap where the lay geometry overlaps (else 0); the law is `contact::respond`, shared with the wire-to-core contact.
//!
//! Stiffness (N/m): the normal penalty per unit wire length of the interface
//! ([`crate::penalty`], from the allowed relief of the wire strain; or, with
//! [`crate::NormalPenalty::Penetration`], the outer wire's line pressure
//! `T_w sin^2(alpha) / R_w` at the allowed penetration) over the wire length the link stands
//! for, `l_eff` ([`link_length`]): the segment length for line contacts and, for a crossing,
//! the distance between crossings along the wire, `1 / (m_b |1/P_a +- 1/P_b| cos(alpha_a))`,
//! at any segment length (see [`crate::ContactOptions::stiffness_per_length`]).

use nalgebra::Vector3;
use rayon::prelude::*;
use strand_core::{Contact, HelixLayer};

use crate::contact::{self, ContactHistory, ContactLaw, ContactLoad, ContactState, Hold};
use crate::joint::perturb;
use crate::model::{FineModel, ModelState};
use crate::segment::{Frame, Placement, Pose, Segment};
use crate::tangent::{ElementTangent, contact_difference, contact_jacobian};

/// What a link touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinkKind {
    /// A wire of the layer beneath laid in the same direction (lines).
    Line,
    /// A wire of the layer beneath laid in the other direction (points).
    Crossing,
    /// The neighbouring wire in the same layer.
    Neighbour,
}

impl LinkKind {
    /// Name as written to `contacts.csv`.
    pub fn name(self) -> &'static str {
        match self {
            LinkKind::Line => "line",
            LinkKind::Crossing => "crossing",
            LinkKind::Neighbour => "neighbour",
        }
    }

    /// The kind of the interface `contact` of a layer with the layer beneath.
    pub fn of(contact: Contact) -> Self {
        match contact {
            Contact::Line => LinkKind::Line,
            Contact::Crossing => LinkKind::Crossing,
        }
    }
}

/// A segment of one wire and a partner wire that may touch it (fixed data).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WireLink {
    /// Segment of the wire carrying the link.
    pub segment: usize,
    /// Index of the partner wire in the model.
    pub partner: usize,
    /// Line, crossing or neighbour contact.
    pub kind: LinkKind,
    /// Sum of the two wires' radii r_a + r_b (m).
    pub radii: f64,
    /// Rest gap of the link where the lay geometry overlaps, else 0 (m).
    pub rest_gap: f64,
    /// Chord sag h of this wire's segments (m).
    pub sag: f64,
    /// Chord sag of the partner's segments (m).
    pub partner_sag: f64,
    /// Regularisation epsilon of the closest point (-), module docs.
    pub epsilon: f64,
    /// Share of the gap from the partner's axis to the contact point, r_b / (r_a + r_b) (-).
    pub partner_share: f64,
    /// Wire length the link stands for, l_eff (m).
    pub length: f64,
    /// Penalty and friction.
    pub law: ContactLaw,
}

/// Wire length (m) a link of a segment `segment` long stands for, given the distance
/// `spacing` (m) between the crossings of its wire with the partner layer along the wire
/// (infinite for a line contact or a neighbour): a crossing is held by one link
/// ([`duplicates`]), so it stands for the whole `spacing` whatever the segment's length; a
/// line stands for its segment. Either way the stiffness per unit wire length, the law's
/// per-length stiffness times this length summed over a wire's links and divided by the
/// wire's length, does not depend on the mesh.
pub fn link_length(segment: f64, spacing: f64) -> f64 {
    if spacing.is_finite() {
        spacing
    } else {
        segment
    }
}

/// Closest approach of a link's segment and a partner segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Approach {
    /// Parameter s of the point on the link's segment, from its centre (m).
    pub s: f64,
    /// Parameter of the point on the partner segment, from its centre, clamped (m).
    pub t: f64,
    /// Arc point of the link's wire (m).
    pub point: Vector3<f64>,
    /// Arc point of the partner wire (m).
    pub partner_point: Vector3<f64>,
}

impl Approach {
    /// Gap between the surfaces, `|p' - q'| - (r_a + r_b) - g_0` (m).
    pub fn gap(&self, link: &WireLink) -> f64 {
        (self.point - self.partner_point).norm() - link.radii - link.rest_gap
    }
}

/// Sag of the arc over a chord of half-length `half` at `s` from its centre, for the sag `h`
/// at the centre (m).
fn sag_at(h: f64, s: f64, half: f64) -> f64 {
    let u = s / half;
    h * (1.0 - u * u)
}

/// The body axis 2 of the segment at `a` (toward the strand axis at rest) times `length`.
fn normal<P: Placement>(a: &P, length: f64) -> Vector3<f64> {
    a.point(&Vector3::new(0.0, length, 0.0)) - a.centre()
}

/// Closest approach of the segment at `a` (length `la`) and the partner segment at `b`
/// (length `lb`) for `link` (module docs).
pub fn approach<P: Placement>(link: &WireLink, a: &P, la: f64, b: &P, lb: f64) -> Approach {
    let (ta, tb) = (a.tangent(), b.tangent());
    let r = a.centre() - b.centre();
    let beta = ta.dot(&tb);
    let s = (beta * tb.dot(&r) - ta.dot(&r)) / (1.0 - beta * beta + link.epsilon);
    let p = a.centre() + ta * s;
    let t = tb.dot(&(p - b.centre())).clamp(-0.5 * lb, 0.5 * lb);
    let q = b.centre() + tb * t;
    // Arc points: the arcs stand off their chords away from the strand axis (-e2).
    let sa = sag_at(link.sag, s.clamp(-0.5 * la, 0.5 * la), 0.5 * la);
    let sb = sag_at(link.partner_sag, t, 0.5 * lb);
    Approach {
        s,
        t,
        point: p - normal(a, sa),
        partner_point: q - normal(b, sb),
    }
}

/// The partner segment for the point of `link`'s segment at `a`: searched from `guess` along
/// the partner chain (poses `partner`, segments `segments`) to the segment whose axial span
/// holds the projection of the closest point; returns it with the approach.
pub fn pair<P: Placement>(
    link: &WireLink,
    a: &P,
    la: f64,
    partner: &[P],
    segments: &[Segment],
    guess: usize,
) -> (usize, Approach) {
    let mut b = guess.min(partner.len() - 1);
    let mut ap = approach(link, a, la, &partner[b], segments[b].length);
    for _ in 0..4 {
        let p = a.centre() + a.tangent() * ap.s;
        let next = contact::nearest_core_segment(partner, segments, &p, b);
        if next == b {
            break;
        }
        b = next;
        ap = approach(link, a, la, &partner[b], segments[b].length);
    }
    (b, ap)
}

/// Share of the segment length by which a link's ownership reaches past each end of its
/// segment (module docs): where two chords kink, the closest approach to a crossing moves by
/// up to a few hundredths of a segment from one chord to the next, so that without the reach
/// a crossing at a node could belong to neither.
pub const OWNERSHIP_REACH: f64 = 0.25;

/// True when the approach `ap` on a segment of length `la` lies within the segment's reach.
pub fn owns(ap: &Approach, la: f64) -> bool {
    let half = (0.5 + OWNERSHIP_REACH) * la;
    (-half..half).contains(&ap.s)
}

/// One contact per crossing: where the links of one partner wire on two consecutive segments
/// (`links` in segment-major order, the same partners on every segment) both hold a contact
/// (`rank(i)`: its rank, `None` where link `i` holds none), the lower-ranked is dropped, so
/// that a crossing at a node between two chords is counted once. The loads rank by
/// [`centrality`]; [`FineModel::link_approaches`] by depth. Returns the dropped flags.
pub fn duplicates(links: &[WireLink], rank: impl Fn(usize) -> Option<f64>) -> Vec<bool> {
    let mut dropped = vec![false; links.len()];
    let Some(first) = links.first() else {
        return dropped;
    };
    let stride = links
        .iter()
        .position(|l| l.segment != first.segment)
        .unwrap_or(links.len());
    for i in 0..links.len().saturating_sub(stride) {
        let j = i + stride;
        if dropped[i]
            || links[j].segment != links[i].segment + 1
            || links[j].partner != links[i].partner
        {
            continue;
        }
        if let (Some(di), Some(dj)) = (rank(i), rank(j)) {
            dropped[if di < dj { i } else { j }] = true;
        }
    }
    dropped
}

/// How central the contact point of the closed link load `c` is on its segment of length
/// `la`: `-|s| / la` with `s` its distance from the segment's centre along the axis (-).
/// The one-contact-per-crossing rule of the loads keeps the more central of two links: the
/// crossing stays with one link until it slides past the node between their segments. (Kept
/// by depth, it jumped between the two with micrometres of sliding: the chords kink at the
/// node, and whichever link carried the crossing left the other the deeper, so that Newton
/// stalled on the 1+6+12 strand with friction; Multilayer page.)
pub fn centrality(c: &ContactLoad, la: f64) -> f64 {
    -c.history.on_wire.x.abs() / la
}

/// Evaluates `link` of the segment at `a` (length `la`) against partner segment `b` at `pb`
/// (length `lb`), from the committed `history` anchored on the partner segment at `anchor`.
pub fn evaluate_pair<P: Placement>(
    link: &WireLink,
    history: &ContactHistory,
    a: &P,
    la: f64,
    (pb, b, lb): (&P, usize, f64),
    anchor: &P,
) -> ContactLoad {
    let ap = approach(link, a, la, pb, lb);
    // A link held closed keeps its contact as it moves past its segment's reach.
    let held_closed = matches!(history.hold, Hold::Stick | Hold::Slip);
    if !owns(&ap, la) && !held_closed {
        return ContactLoad::open_at(b);
    }
    contact::respond(
        &link.law,
        history,
        (&ap.point, &ap.partner_point),
        link.radii + link.rest_gap,
        link.partner_share,
        a,
        (pb, b),
        anchor,
    )
}

/// Evaluates `link` of the segment at `a` (length `la`) against the partner wire (poses
/// `partner`, segments `segments`), pairing it from the history's partner segment.
pub fn evaluate<P: Placement>(
    link: &WireLink,
    history: &ContactHistory,
    a: &P,
    la: f64,
    partner: &[P],
    segments: &[Segment],
) -> ContactLoad {
    let (b, _) = pair(link, a, la, partner, segments, history.core_segment);
    let anchor = &partner[history.core_segment.min(partner.len() - 1)];
    evaluate_pair(
        link,
        history,
        a,
        la,
        (&partner[b], b, segments[b].length),
        anchor,
    )
}

/// Number of crossings of wire `i` of `outer` with the wires of `inner` laid in the other
/// direction over the strand interval `[x0, x1)` (m), from the lay phases: the solutions of
/// `phi_outer(i, x) = phi_inner(j, x) (mod 2 pi)` for every wire `j`.
pub fn geometric_crossings(
    outer: &HelixLayer,
    i: usize,
    inner: &HelixLayer,
    x0: f64,
    x1: f64,
) -> usize {
    use std::f64::consts::PI;
    let rate = 2.0
        * PI
        * (outer.direction().sign() / outer.pitch - inner.direction().sign() / inner.pitch);
    let mut n = 0;
    for j in 0..inner.wires() {
        // phi_o(x) - phi_i(x) = d0 + rate x; count x with d0 + rate x = 2 pi k.
        let d0 = outer.spec.phase + 2.0 * PI * i as f64 / outer.wires() as f64
            - inner.spec.phase
            - 2.0 * PI * j as f64 / inner.wires() as f64;
        let (u0, u1) = ((d0 + rate * x0) / (2.0 * PI), (d0 + rate * x1) / (2.0 * PI));
        let (lo, hi) = if u0 <= u1 { (u0, u1) } else { (u1, u0) };
        // Integers k in [lo, hi) (or (hi, lo] for a falling phase): half-open like [x0, x1).
        let count = if u0 <= u1 {
            (hi.ceil() - lo.ceil()) as i64
        } else {
            (hi.floor() - lo.floor()) as i64
        };
        n += count.max(0) as usize;
    }
    n
}

/// A link taken at a state: its segments' poses and the partner segment it pairs with.
struct Paired<'a> {
    link: &'a WireLink,
    history: &'a ContactHistory,
    /// Pose and length of the link's segment.
    own: (&'a Pose, f64),
    /// Partner segment index, pose and length.
    partner: (usize, &'a Pose, f64),
    /// Pose of the partner segment the history is anchored on.
    anchor: &'a Pose,
    /// Global indices of the link's segment and of the partner segment.
    global: [usize; 2],
}

impl FineModel {
    /// Every link at `state` with its pairing, per wire in link order.
    fn paired_links<'a>(&'a self, state: &'a ModelState) -> Vec<Vec<Paired<'a>>> {
        let offsets = self.segment_offsets();
        let frames: Vec<Vec<Frame>> = state
            .wires
            .iter()
            .map(|w| w.poses.iter().map(Frame::of).collect())
            .collect();
        let mut all = Vec::with_capacity(self.wires.len());
        for (i, (w, s)) in self.wires.iter().zip(&state.wires).enumerate() {
            let mut out = Vec::with_capacity(w.links.len());
            let hist = &state.contacts[i][w.contacts.len()..];
            for (lk, h) in w.links.iter().zip(hist) {
                let pc = &self.wires[lk.partner].chain;
                let pp = &state.wires[lk.partner].poses;
                let la = w.chain.segments[lk.segment].length;
                let own = &s.poses[lk.segment];
                let (b, _) = pair(
                    lk,
                    &frames[i][lk.segment],
                    la,
                    &frames[lk.partner],
                    &pc.segments,
                    h.core_segment,
                );
                out.push(Paired {
                    link: lk,
                    history: h,
                    own: (own, la),
                    partner: (b, &pp[b], pc.segments[b].length),
                    anchor: &pp[h.core_segment.min(pp.len() - 1)],
                    global: [offsets[i] + lk.segment, offsets[lk.partner] + b],
                });
            }
            all.push(out);
        }
        all
    }

    /// The contact each link holds at `state`: its closest approach where the link owns one
    /// (within its segment's reach, one per crossing, [`duplicates`] by the smaller gap; the
    /// loads keep the more central link, [`centrality`]),
    /// else `None`; per wire in link order.
    pub fn link_approaches(&self, state: &ModelState) -> Vec<Vec<Option<Approach>>> {
        self.paired_links(state)
            .iter()
            .zip(&self.wires)
            .map(|(paired, w)| {
                let aps: Vec<Option<Approach>> = paired
                    .iter()
                    .map(|c| {
                        let ap = approach(c.link, c.own.0, c.own.1, c.partner.1, c.partner.2);
                        owns(&ap, c.own.1).then_some(ap)
                    })
                    .collect();
                let dropped = duplicates(&w.links, |i| aps[i].map(|ap| -ap.gap(&w.links[i])));
                aps.into_iter()
                    .zip(dropped)
                    .map(|(ap, d)| if d { None } else { ap })
                    .collect()
            })
            .collect()
    }

    /// Tangents of the closed links at `state` with the committed histories frozen and the
    /// pairing kept: central differences of the link loads over the link's segment and the
    /// partner segment, with the steps of [`FineModel::contact_tangents`].
    pub fn link_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        if self.link_count() == 0 {
            return Vec::new();
        }
        let per_wire = self.paired_links(state);
        // The loads at `state`, for the one-contact-per-crossing rule of the load evaluation.
        let mut kept: Vec<&Paired> = Vec::new();
        for (paired, w) in per_wire.iter().zip(&self.wires) {
            let loads: Vec<ContactLoad> = paired
                .par_iter()
                .map(|c| {
                    let (own, la) = c.own;
                    let (b, pb, lb) = c.partner;
                    evaluate_pair(c.link, c.history, own, la, (pb, b, lb), c.anchor)
                })
                .collect();
            let dropped = duplicates(&w.links, |i| {
                (loads[i].state != ContactState::Open && paired[i].history.hold == Hold::Free)
                    .then(|| centrality(&loads[i], paired[i].own.1))
            });
            kept.extend(
                paired
                    .iter()
                    .zip(&loads)
                    .zip(dropped)
                    .filter(|((_, l), d)| !d && l.state != ContactState::Open)
                    .map(|((c, _), _)| c),
            );
        }
        kept.par_iter()
            .filter_map(|c| {
                let (own, la) = c.own;
                let (b, pb, lb) = c.partner;
                let same_anchor = std::ptr::eq(c.anchor, pb);
                // Loads are invariant under a translation of all bodies: evaluate about the
                // partner segment's centre.
                let origin = pb.position;
                let local = |pose: &Pose| Pose::new(pose.position - origin, pose.rotation);
                let eval = |col: usize, step: f64| -> ContactLoad {
                    let mut a = local(own);
                    let mut p = local(pb);
                    let mut anchor = local(c.anchor);
                    if col < 6 {
                        perturb(&mut a, col, step);
                    } else {
                        perturb(&mut p, col - 6, step);
                        if same_anchor {
                            anchor = p;
                        }
                    }
                    let (a, p, anchor) = (Frame::of(&a), Frame::of(&p), Frame::of(&anchor));
                    evaluate_pair(c.link, c.history, &a, la, (&p, b, lb), &anchor)
                };
                let c0 = eval(0, 0.0);
                if c0.state == ContactState::Open {
                    return None;
                }
                let k = contact_difference(
                    &c0,
                    &c.link.law,
                    1e-7 * 0.5 * c.link.radii,
                    c.history.hold,
                    eval,
                );
                Some(ElementTangent {
                    segments: c.global.map(Some),
                    stiffness: k,
                })
            })
            .collect()
    }

    /// Stiffness bounds of the links that may close at `state` (gap below the sum of the
    /// radii): an isotropic spring of the larger of `k_n`, `k_t` between the link's contact
    /// point on both segments (for the stable time step).
    pub fn link_bound_tangents(&self, state: &ModelState) -> Vec<ElementTangent> {
        if self.link_count() == 0 {
            return Vec::new();
        }
        self.paired_links(state)
            .iter()
            .flatten()
            .filter_map(|c| {
                let (own, la) = c.own;
                let (_, pb, lb) = c.partner;
                let ap = approach(c.link, own, la, pb, lb);
                if ap.gap(c.link) > c.link.radii {
                    return None;
                }
                let law = &c.link.law;
                let k = law.normal_stiffness.max(law.tangential_stiffness);
                let x = ap.partner_point + (ap.point - ap.partner_point) * c.link.partner_share;
                let b = contact_jacobian(&(x - own.position), &(x - pb.position));
                Some(ElementTangent {
                    segments: c.global.map(Some),
                    stiffness: b.transpose() * b * k,
                })
            })
            .collect()
    }
}
