//! The fine model of a strand: one segment chain per wire, supports and gravity, its state
//! (poses and momenta) and its loads and energies.
//!
//! Wire 0 is the core (straight along +X from the origin); then the helical wires layer by
//! layer.
//! Supports are ground joints: a clamp holds the wire's end point and its rotation, a pin only
//! the end point. A support joint carries the springs of the half segment between the wire's
//! end and the first segment's centre (twice the stiffness of an interior joint), so that the
//! chain's bending flexibility is distributed over the whole wire length.
//!
//! Contacts ([`crate::contact`], [`crate::interlayer`]) belong to the helical wires; their
//! partner-side loads (on the core, on a wire of the layer beneath or a neighbour) are added
//! to the partner's after the sweep over wires, in wire and contact order (the `load_share`
//! module), so the sums are the same for any number of threads. A wire's committed
//! histories and trial loads list its wire-to-core contacts first, then its links.

use nalgebra::Vector3;
use rayon::prelude::*;
use strand_core::{HelixLayer, Strand};

use crate::chain::{Chain, SegmentRun, WireSection};
use crate::contact::{
    self, ContactHistory, ContactLaw, ContactLoad, ContactOptions, ContactPoint, ContactState, Hold,
};
use crate::interlayer::{self, LinkKind, WireLink};
use crate::joint::{JointLoad, JointSpring, JointStiffness};
use crate::load_share::LoadShares;
use crate::penalty;
use crate::segment::{Frame, Placement, Pose};
use crate::sweep;

/// Boundary condition at one end of the strand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Support {
    /// No support.
    #[default]
    Free,
    /// End point and end rotation of every wire held.
    Clamped,
    /// A pivoting end fitting: the core's end point held with its rotation free, and every
    /// helical wire bound to the core's end segment ([`FineModel::bind_end`]), so the whole
    /// section turns about the pin. Holding each wire's end point instead would let the layer
    /// carry a bending moment as a couple of wire forces, which a pin does not.
    Pinned,
}

/// End of a wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    /// The start (x = 0).
    Start,
    /// The end (x = L).
    End,
}

/// A ground joint holding one segment of a wire.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// Index of the held segment in its chain.
    pub segment: usize,
    /// Fixed pose of the ground side of the joint.
    pub ground: Pose,
    /// The joint: body `a` is the ground, body `b` the segment.
    pub joint: JointSpring,
}

/// A wire of the strand with its supports.
#[derive(Debug, Clone, PartialEq)]
pub struct Wire {
    /// The segment chain.
    pub chain: Chain,
    /// Layer of the wire: 0 for the core, `j + 1` for a wire of `Strand::layers()[j]`.
    pub layer: usize,
    /// Ground joints acting on the wire.
    pub anchors: Vec<Anchor>,
    /// Contact points of this wire with the core (wires of the first layer only).
    pub contacts: Vec<ContactPoint>,
    /// Contacts of this wire's segments with other wires ([`crate::interlayer`]): with the
    /// wires of the layer beneath (outer layers) and with the next wire of its own layer.
    pub links: Vec<WireLink>,
    /// Dead force on each segment's centre (N), scaled by the load factor like gravity;
    /// empty for none.
    pub external: Vec<Vector3<f64>>,
}

impl Wire {
    /// Wire without supports.
    pub fn new(chain: Chain) -> Self {
        Self {
            chain,
            layer: 0,
            anchors: Vec::new(),
            contacts: Vec::new(),
            links: Vec::new(),
            external: Vec::new(),
        }
    }

    /// Adds the support `support` at the end `end` of the wire (nothing for `Free`).
    pub fn support(&mut self, end: End, support: Support) {
        if support == Support::Free {
            return;
        }
        let c = &self.chain;
        let (k, offset) = match end {
            End::Start => (0, c.segments[0].start_offset()),
            End::End => (c.len() - 1, c.segments[c.len() - 1].end_offset()),
        };
        let seg = c.segments[k];
        let rest = c.rest[k];
        let ground = Pose::new(rest.point(&offset), rest.rotation);
        let mut stiffness = c.section.joint_stiffness(0.5 * seg.length);
        if support == Support::Pinned {
            stiffness.rotational = Vector3::zeros();
        }
        let joint = JointSpring::at_rest(&ground, Vector3::zeros(), &rest, offset, stiffness);
        self.anchors.push(Anchor {
            segment: k,
            ground,
            joint,
        });
    }

    /// Adds loads at `poses` (frames `frames`) from joints, anchors, the gravity field
    /// `gravity` (m/s^2) and the external forces times `load_factor` to `loads`; returns
    /// (spring energy, potential of gravity and external forces relative to the rest
    /// configuration) in J.
    fn add_loads(
        &self,
        poses: &[Pose],
        frames: &[Frame],
        gravity: &Vector3<f64>,
        load_factor: f64,
        forces: &mut [Vector3<f64>],
        torques: &mut [Vector3<f64>],
    ) -> (f64, f64) {
        let run = SegmentRun::whole(poses, frames);
        self.add_loads_in(&run, gravity, load_factor, forces, torques)
    }

    /// [`Wire::add_loads`] on a run of segments only ([`Chain::add_joint_loads_in`]):
    /// `forces` and `torques` are the run's, the energies those of the run's joints,
    /// anchors and segments. Each segment receives the same sums in the same order as from
    /// [`Wire::add_loads`].
    #[inline(always)]
    pub(crate) fn add_loads_in(
        &self,
        run: &SegmentRun<'_>,
        gravity: &Vector3<f64>,
        load_factor: f64,
        forces: &mut [Vector3<f64>],
        torques: &mut [Vector3<f64>],
    ) -> (f64, f64) {
        let (a, b) = (run.first, run.first + run.poses.len());
        let mut spring = self.chain.add_joint_loads_in(run, forces, torques);
        for an in self
            .anchors
            .iter()
            .filter(|an| (a..b).contains(&an.segment))
        {
            let l = an.joint.evaluate(&an.ground, &run.poses[an.segment - a]);
            forces[an.segment - a] += l.force_b;
            torques[an.segment - a] += l.torque_b;
            spring += l.energy;
        }
        let mut potential = 0.0;
        // Potentials from the rest configuration: zero at the initial (straight) state
        // whatever the direction of gravity.
        let rest = &self.chain.rest[a..b];
        for (k, (s, r)) in self.chain.segments[a..b].iter().zip(rest).enumerate() {
            let w = gravity * s.mass;
            forces[k] += w;
            potential -= w.dot(&(run.poses[k].position - r.position));
        }
        for k in a..b.min(self.external.len()) {
            let f = self.external[k] * load_factor;
            forces[k - a] += f;
            potential -= f.dot(&(run.poses[k - a].position - rest[k - a].position));
        }
        (spring, potential)
    }
}

/// A joint binding a helical wire's end segment to the core's end segment (the wires bound
/// together at a strand end, as by a clamp band or a weld).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tie {
    /// Helical wire (index into [`FineModel::wires`], at least 1).
    pub wire: usize,
    /// Segment of the helical wire.
    pub segment: usize,
    /// Segment of the core.
    pub core_segment: usize,
    /// The joint: body `a` is the core segment, body `b` the wire segment, attached at the
    /// wire's end point.
    pub joint: JointSpring,
}

/// Factors on the joint springs of a wire's section (all 1 for the physical wire). Studies
/// use them to remove one compliance that a closed form ignores, e.g. the shear of the wires
/// (`shear = 100`) when checking the plane-section stiffness; every factor must be positive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringScale {
    /// Factor on the axial springs E A / l (-).
    pub axial: f64,
    /// Factor on the shear springs kappa G A / l (-).
    pub shear: f64,
    /// Factor on the torsion springs G J / l (-).
    pub torsion: f64,
    /// Factor on the bending springs E I / l (-).
    pub bending: f64,
}

impl Default for SpringScale {
    fn default() -> Self {
        Self {
            axial: 1.0,
            shear: 1.0,
            torsion: 1.0,
            bending: 1.0,
        }
    }
}

impl SpringScale {
    /// The factors applied to `k`.
    pub fn apply(&self, k: &JointStiffness) -> JointStiffness {
        JointStiffness {
            translational: k
                .translational
                .component_mul(&Vector3::new(self.axial, self.shear, self.shear)),
            rotational: k.rotational.component_mul(&Vector3::new(
                self.torsion,
                self.bending,
                self.bending,
            )),
        }
    }
}

/// How to discretise a strand.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Discretisation {
    /// Segments of the core wire.
    pub core_segments: usize,
    /// Segments of each helical wire (the paper's Fig. 7 uses 77).
    pub wire_segments: usize,
}

/// The fine model: wires, supports and gravity.
#[derive(Debug, Clone, PartialEq)]
pub struct FineModel {
    /// Wire 0 is the core; then the helical wires layer by layer from the core outward, each
    /// layer's in phase order.
    pub wires: Vec<Wire>,
    /// Gravity (m/s^2), scaled by the load factor in static solves.
    pub gravity: Vector3<f64>,
    /// Joints binding the helical wires to the core at a strand end ([`FineModel::bind_end`]).
    pub ties: Vec<Tie>,
}

impl FineModel {
    /// Model of `strand` with supports `start` at x = 0 and `end` at x = L on every wire of
    /// every layer, each laid on its stacked radius, lay direction and phase
    /// (`Strand::layers()`).
    pub fn from_strand(
        strand: &Strand,
        disc: Discretisation,
        start: Support,
        end: Support,
    ) -> Self {
        let mut wires = vec![Wire::new(Chain::straight(
            WireSection::from_spec(strand.core()),
            Vector3::zeros(),
            strand.length(),
            disc.core_segments,
        ))];
        for (j, layer) in strand.layers().iter().enumerate() {
            for i in 0..layer.wires() {
                let mut w = Wire::new(Chain::helix(layer, i, strand.length(), disc.wire_segments));
                w.layer = j + 1;
                wires.push(w);
            }
        }
        for (i, w) in wires.iter_mut().enumerate() {
            for (at, support) in [(End::Start, start), (End::End, end)] {
                // Helical wires at a pin hang on the core's end segment (ties below).
                if i == 0 || support != Support::Pinned {
                    w.support(at, support);
                }
            }
        }
        let mut model = Self {
            wires,
            gravity: Vector3::zeros(),
            ties: Vec::new(),
        };
        if model.wires.len() > 1 {
            for (at, support) in [(End::Start, start), (End::End, end)] {
                if support == Support::Pinned {
                    model.bind_end(at);
                }
            }
        }
        model
    }

    /// A single straight wire of section `section` and length `length` (m) along +X from the
    /// origin in `n` segments.
    pub fn single_wire(
        section: WireSection,
        length: f64,
        n: usize,
        start: Support,
        end: Support,
    ) -> Self {
        let mut w = Wire::new(Chain::straight(section, Vector3::zeros(), length, n));
        w.support(End::Start, start);
        w.support(End::End, end);
        Self {
            wires: vec![w],
            gravity: Vector3::zeros(),
            ties: Vec::new(),
        }
    }

    /// Adds contact points between every wire of the first layer of `strand` and the core
    /// (wire 0), with the stiffnesses of `options` (see [`ContactOptions`]), and the
    /// wire-to-wire links of the outer layers ([`FineModel::add_links`]).
    pub fn add_contacts(&mut self, strand: &Strand, options: &ContactOptions) {
        let Some(layer) = strand.layers().first() else {
            return;
        };
        self.add_core_contacts(strand, layer, options);
        self.add_links(strand, options);
    }

    /// The wire-to-core contact points of the first layer's wires.
    fn add_core_contacts(&mut self, strand: &Strand, layer: &HelixLayer, options: &ContactOptions) {
        let wire = &layer.spec.wire;
        let (mut normal_per_length, shear_per_length) = options.stiffness_per_length(layer);
        if let Some(k) = options
            .relief_on(strand)
            .and_then(|f| penalty::normal_stiffness_per_length(strand, f)[0])
        {
            normal_per_length = k;
        }
        let friction = options.friction.unwrap_or(strand.friction());
        let n_pts = options.points_on(strand);
        let (rc, rw) = (strand.core().radius(), wire.radius());
        let core_share = options.contact_radius.unwrap_or(rc) / (rc + rw);
        let (core_wire, helical) = self.wires.split_at_mut(1);
        let core = &core_wire[0].chain;
        let core_frames: Vec<Frame> = core.rest.iter().map(Frame::of).collect();
        // Wires of the first layer (a wire built by hand, of layer 0 past the core, counts
        // as one).
        for w in helical.iter_mut().filter(|w| w.layer <= 1) {
            let c = &w.chain;
            let mut points = Vec::with_capacity(n_pts * c.len());
            for (k, seg) in c.segments.iter().enumerate() {
                let share = seg.length / n_pts as f64;
                let law = ContactLaw {
                    normal_stiffness: normal_per_length * share,
                    tangential_stiffness: shear_per_length * share,
                    friction,
                };
                for i in 0..n_pts {
                    let a = if n_pts == 1 {
                        0.0
                    } else {
                        (i as f64 - 0.5) * 0.5 * seg.length
                    };
                    let offset = Vector3::new(a, 0.0, 0.0);
                    // In the arithmetic of the load evaluation (frames), so that the lay
                    // geometry touches with exactly zero gap.
                    let p = Frame::of(&c.rest[k]).point(&offset);
                    let j = contact::nearest_core_segment(&core_frames, &core.segments, &p, 0);
                    let q = contact::closest_on_axis(&p, &core_frames[j], core.segments[j].length);
                    let rest_distance = (p - q).norm();
                    points.push(ContactPoint {
                        segment: k,
                        offset,
                        rest_distance,
                        core_share,
                        law,
                    });
                }
            }
            w.contacts = points;
        }
    }

    /// Adds the wire-to-wire links of `strand` ([`crate::interlayer`]): every segment of a
    /// wire of layer `j >= 1` with every wire of layer `j - 1` (crossings for alternate lay,
    /// lines for the same lay direction), and, in a strand of several layers, in a layer whose
    /// neighbouring wires stand less than [`NEIGHBOUR_GAP`] wire diameters apart, every
    /// segment of wire `i` with wire `i + 1` (cyclically, for three wires or more). A `1+m`
    /// strand keeps the model its validation measured, without neighbour links (the scene
    /// runner warns where its gap is that small): with them the `vs-fine-12deg` cantilever,
    /// 7.6e-6 m between neighbours, took minutes instead of seconds and its reference moved.
    /// Normal stiffness: per unit length from the allowed strain relief ([`crate::penalty`],
    /// [`ContactOptions::relief_on`]), or else the outer wire's line
    /// pressure under the reference tension of `options` (taken as the first layer's wire
    /// tension, carried to every layer at the same strand strain) at the allowed penetration,
    /// over the wire length each link stands for; the stick stiffness per unit length of the
    /// layer ([`ContactOptions::stiffness_per_length`]). Nothing for a model whose wires are
    /// not those of `strand` ([`FineModel::from_strand`]).
    pub fn add_links(&mut self, strand: &Strand, options: &ContactOptions) {
        let layers = strand.layers();
        let Some(first_layer) = layers.first() else {
            return;
        };
        // Only a model laid from `strand` (its wires in layer order).
        if self.wires.len() != 1 + strand.helical_wires() {
            return;
        }
        let wire_tension = |l: &HelixLayer, eps: f64| {
            let w = &l.spec.wire;
            w.material.youngs_modulus * w.area() * l.lay_angle().cos().powi(2) * eps
        };
        // The strand strain of the reference tension.
        let eps = options
            .reference_tension
            .map_or(options.reference_strain, |t| {
                t / wire_tension(first_layer, 1.0)
            });
        let friction = options.friction.unwrap_or(strand.friction());
        let strained = options
            .relief_on(strand)
            .map(|f| penalty::normal_stiffness_per_length(strand, f));
        let mut first = Vec::with_capacity(layers.len());
        let mut n = 1;
        for l in layers {
            first.push(n);
            n += l.wires();
        }
        let frames: Vec<Vec<Frame>> = self
            .wires
            .iter()
            .map(|w| w.chain.rest.iter().map(Frame::of).collect())
            .collect();
        for (j, outer) in layers.iter().enumerate() {
            let opts = ContactOptions {
                reference_tension: Some(wire_tension(outer, eps)),
                ..*options
            };
            let (mut normal_per_length, shear_per_length) = opts.stiffness_per_length(outer);
            if let Some(k) = strained.as_ref().and_then(|k| k[j]) {
                normal_per_length = k;
            }
            let ra = outer.spec.wire.radius();
            let delta = options.penetration * outer.spec.wire.diameter;
            // Partners: (first wire, wire count, radius, kind, crossing distance along the
            // outer wire (m); infinite for parallel wires).
            let mut partners = Vec::new();
            if j > 0 {
                let inner = &layers[j - 1];
                let kind = LinkKind::of(strand.interface(j).contact);
                let rate = (outer.direction().sign() / outer.pitch
                    - inner.direction().sign() / inner.pitch)
                    .abs();
                let spacing = 1.0 / (inner.wires() as f64 * rate * outer.lay_angle().cos());
                partners.push((first[j - 1], inner.wires(), inner, kind, spacing, false));
            }
            if layers.len() > 1
                && outer.wires() >= 3
                && outer.wire_gap() <= NEIGHBOUR_GAP * outer.spec.wire.diameter
            {
                partners.push((
                    first[j],
                    outer.wires(),
                    outer,
                    LinkKind::Neighbour,
                    f64::INFINITY,
                    true,
                ));
            }
            for i in 0..outer.wires() {
                let wi = first[j] + i;
                let chain = &self.wires[wi].chain;
                let mut links = Vec::new();
                for (k, seg) in chain.segments.iter().enumerate() {
                    let la = seg.length;
                    let sag = helix_sag(outer, &chain.rest[k]);
                    let length = |spacing: f64| interlayer::link_length(la, spacing);
                    for &(p0, m, inner, kind, spacing, neighbour) in &partners {
                        let partners: Vec<usize> = if neighbour {
                            vec![p0 + (i + 1) % m]
                        } else {
                            (p0..p0 + m).collect()
                        };
                        let rb = inner.spec.wire.radius();
                        for pw in partners {
                            let pc = &self.wires[pw].chain;
                            let l_eff = length(spacing);
                            let mut link = WireLink {
                                segment: k,
                                partner: pw,
                                kind,
                                radii: ra + rb,
                                rest_gap: 0.0,
                                sag,
                                partner_sag: helix_sag(inner, &pc.rest[0]),
                                epsilon: 2.0 * delta * (ra + rb) / (la * la),
                                partner_share: rb / (ra + rb),
                                length: l_eff,
                                law: ContactLaw {
                                    normal_stiffness: normal_per_length * l_eff,
                                    tangential_stiffness: shear_per_length * l_eff,
                                    friction,
                                },
                            };
                            let guess = rest_partner(pc, chain.rest[k].position.x);
                            let (_, ap) = interlayer::pair(
                                &link,
                                &frames[wi][k],
                                la,
                                &frames[pw],
                                &pc.segments,
                                guess,
                            );
                            if (-0.5 * la..0.5 * la).contains(&ap.s) {
                                link.rest_gap = rest_gap(&link, &ap, outer);
                            }
                            links.push(link);
                        }
                    }
                }
                self.wires[wi].links = links;
            }
        }
    }

    /// Binds every helical wire to the core at the end `end`: a joint from the wire's end
    /// point to the core's end segment, relaxed at rest, with the springs of half a wire
    /// segment (as a support).
    pub fn bind_end(&mut self, end: End) {
        let (core, helical) = self.wires.split_at(1);
        let core = &core[0].chain;
        let cs = match end {
            End::Start => 0,
            End::End => core.len() - 1,
        };
        for (i, w) in helical.iter().enumerate() {
            let c = &w.chain;
            let (k, offset) = match end {
                End::Start => (0, c.segments[0].start_offset()),
                End::End => (c.len() - 1, c.segments[c.len() - 1].end_offset()),
            };
            let point = c.rest[k].point(&offset);
            let on_core = core.rest[cs]
                .rotation
                .inverse_transform_vector(&(point - core.rest[cs].position));
            let stiffness = c.section.joint_stiffness(0.5 * c.segments[k].length);
            self.ties.push(Tie {
                wire: i + 1,
                segment: k,
                core_segment: cs,
                joint: JointSpring::at_rest(&core.rest[cs], on_core, &c.rest[k], offset, stiffness),
            });
        }
    }

    /// Adds a constant point force `force` (N, scaled by the load factor like gravity) at the
    /// strand coordinate `s` (m): on the core, split linearly between the two segments whose
    /// rest centres enclose `s` (all on the end segment beyond the last centre), so its
    /// resultant and its moment about `s` are those of the point force.
    pub fn add_point_force(&mut self, s: f64, force: Vector3<f64>) {
        let core = &mut self.wires[0];
        let n = core.chain.len();
        if core.external.is_empty() {
            core.external = vec![Vector3::zeros(); n];
        }
        let x: Vec<f64> = core.chain.rest.iter().map(|p| p.position.x).collect();
        let k = x.partition_point(|&c| c <= s);
        if k == 0 {
            core.external[0] += force;
        } else if k == n {
            core.external[n - 1] += force;
        } else {
            let a = (s - x[k - 1]) / (x[k] - x[k - 1]);
            core.external[k - 1] += force * (1.0 - a);
            core.external[k] += force * a;
        }
    }

    /// Scales the springs of the core's joints and supports by `core` and those of every
    /// helical wire (joints, supports and ties to the core) by `helical`.
    pub fn scale_springs(&mut self, core: &SpringScale, helical: &SpringScale) {
        for (i, w) in self.wires.iter_mut().enumerate() {
            let s = if i == 0 { core } else { helical };
            for j in &mut w.chain.joints {
                j.stiffness = s.apply(&j.stiffness);
            }
            for a in &mut w.anchors {
                a.joint.stiffness = s.apply(&a.joint.stiffness);
            }
        }
        for t in &mut self.ties {
            t.joint.stiffness = helical.apply(&t.joint.stiffness);
        }
    }

    /// This model with the normal penalty of every contact (wire-to-core points and
    /// wire-to-wire links) scaled by `factor` (-): the softer contacts of a penalty
    /// continuation ([`crate::StaticOptions::penalty_stages`]).
    pub fn with_normal_penalty_scaled(&self, factor: f64) -> FineModel {
        let mut m = self.clone();
        for w in &mut m.wires {
            for c in &mut w.contacts {
                c.law.normal_stiffness *= factor;
            }
            for l in &mut w.links {
                l.law.normal_stiffness *= factor;
            }
        }
        m
    }

    /// Total number of wire-to-core contact points.
    pub fn contact_count(&self) -> usize {
        self.wires.iter().map(|w| w.contacts.len()).sum()
    }

    /// Total number of wire-to-wire links ([`crate::interlayer`]).
    pub fn link_count(&self) -> usize {
        self.wires.iter().map(|w| w.links.len()).sum()
    }

    /// Total number of segments.
    pub fn segment_count(&self) -> usize {
        self.wires.iter().map(|w| w.chain.len()).sum()
    }

    /// The model at rest in its undeformed configuration.
    pub fn rest_state(&self) -> ModelState {
        ModelState {
            wires: self
                .wires
                .iter()
                .map(|w| WireState {
                    poses: w.chain.rest.clone(),
                    velocities: vec![Vector3::zeros(); w.chain.len()],
                    angular_momenta: vec![Vector3::zeros(); w.chain.len()],
                })
                .collect(),
            contacts: self
                .wires
                .iter()
                .map(|w| {
                    let core = w.contacts.iter().map(|cp| {
                        let p = w.chain.rest[cp.segment].point(&cp.offset);
                        let core = &self.wires[0].chain;
                        ContactHistory::open(contact::nearest_core_segment(
                            &core.rest,
                            &core.segments,
                            &p,
                            0,
                        ))
                    });
                    let links = w.links.iter().map(|l| {
                        let x = w.chain.rest[l.segment].position.x;
                        ContactHistory::open(rest_partner(&self.wires[l.partner].chain, x))
                    });
                    core.chain(links).collect()
                })
                .collect(),
            friction_work: 0.0,
        }
    }

    /// Load buffers sized for this model.
    pub fn load_buffers(&self) -> Vec<WireLoads> {
        self.wires
            .iter()
            .enumerate()
            .map(|(i, w)| WireLoads {
                forces: vec![Vector3::zeros(); w.chain.len()],
                torques: vec![Vector3::zeros(); w.chain.len()],
                spring_energy: 0.0,
                gravity_energy: 0.0,
                contacts: vec![ContactLoad::open_at(0); w.contacts.len() + w.links.len()],
                ties: Vec::with_capacity(self.ties.iter().filter(|t| t.wire == i).count()),
                core_shares: Vec::with_capacity(w.contacts.len()),
                contact_energy: 0.0,
                friction_energy: 0.0,
                slip_work: 0.0,
                frames: vec![Frame::default(); w.chain.len()],
            })
            .collect()
    }

    /// Computes the loads on every segment at `state` with gravity and external forces
    /// scaled by `load_factor`, in parallel over wires; contacts are evaluated from the
    /// committed histories in `state` and their trial results kept in `loads` (see
    /// [`FineModel::commit_contacts`]). The result is the same for any number of threads.
    pub fn compute_loads(&self, state: &ModelState, load_factor: f64, loads: &mut [WireLoads]) {
        // Every wire's frames first: contacts read their partners' (the core's, and the
        // wires' of the layer beneath and of the neighbours).
        let mut frames: Vec<Vec<Frame>> = loads
            .iter_mut()
            .map(|l| std::mem::take(&mut l.frames))
            .collect();
        let update = |(f, s): (&mut Vec<Frame>, &WireState)| update_frames(&s.poses, f);
        if sweep::parallel() {
            frames
                .par_iter_mut()
                .zip(state.wires.par_iter())
                .for_each(update);
        } else {
            frames.iter_mut().zip(&state.wires).for_each(update);
        }
        self.loads_at_frames(state, load_factor, &frames, loads);
        LoadShares::new(self).add_all(self, loads);
        for (l, f) in loads.iter_mut().zip(frames) {
            l.frames = f;
        }
    }

    /// [`FineModel::compute_loads`] with every segment's frame at `state` given in `frames`
    /// (one list per wire, [`update_frames`] of its poses; the time stepping updates them
    /// in its own sweep over the wires, right after the drift), each wire's own loads only:
    /// the shares its contacts and ties put on other wires are left in `loads` to be added
    /// ([`LoadShares`]).
    pub(crate) fn loads_at_frames(
        &self,
        state: &ModelState,
        load_factor: f64,
        frames: &[Vec<Frame>],
        loads: &mut [WireLoads],
    ) {
        let wire_loads = |(i, l): (usize, &mut WireLoads)| {
            self.wire_loads_at_frames(
                i,
                &state.wires[i],
                &state.contacts[i],
                frames,
                &state.wires[0].poses,
                load_factor,
                l,
            )
        };
        if sweep::parallel() {
            loads.par_iter_mut().enumerate().for_each(wire_loads);
        } else {
            loads.iter_mut().enumerate().for_each(wire_loads);
        }
    }

    /// Wire `i`'s own loads into `l` ([`FineModel::loads_at_frames`] for one wire), from its
    /// state `s`, its committed histories `hist`, every wire's frames `frames` (the wire's
    /// own, the core's, its partners') and the core's poses `core_poses` (for the ties).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn wire_loads_at_frames(
        &self,
        i: usize,
        s: &WireState,
        hist: &[ContactHistory],
        frames: &[Vec<Frame>],
        core_poses: &[Pose],
        load_factor: f64,
        l: &mut WireLoads,
    ) {
        let g = self.gravity * load_factor;
        let core_segs = &self.wires[0].chain.segments;
        let w = &self.wires[i];
        let all_frames = frames;
        let frames = &all_frames[i];
        l.forces.iter_mut().for_each(|f| *f = Vector3::zeros());
        l.torques.iter_mut().for_each(|t| *t = Vector3::zeros());
        let (spring, grav) = w.add_loads(
            &s.poses,
            frames,
            &g,
            load_factor,
            &mut l.forces,
            &mut l.torques,
        );
        l.spring_energy = spring;
        l.gravity_energy = grav;
        if i == 0 {
            return;
        }
        let (mut ce, mut fe, mut sw) = (0.0, 0.0, 0.0);
        let nc = w.contacts.len();
        let (to_core, to_wires) = l.contacts.split_at_mut(nc);
        let core_frames = &all_frames[0];
        l.core_shares.clear();
        for ((cp, h), out) in w.contacts.iter().zip(hist).zip(to_core) {
            contact::evaluate_into(cp, h, &frames[cp.segment], core_frames, core_segs, out);
            let c = &*out;
            l.core_shares.push(CoreShare {
                segment: c.core_segment,
                force: c.force_core,
                torque: c.torque_core,
            });
            l.forces[cp.segment] += c.force_wire;
            l.torques[cp.segment] += c.torque_wire;
            ce += c.normal_energy;
            fe += c.tangential_energy;
            sw += c.slip_work;
        }
        for ((lk, h), out) in w.links.iter().zip(&hist[nc..]).zip(to_wires.iter_mut()) {
            let k = lk.segment;
            *out = interlayer::evaluate(
                lk,
                h,
                &frames[k],
                w.chain.segments[k].length,
                &all_frames[lk.partner],
                &self.wires[lk.partner].chain.segments,
            );
        }
        // One contact per crossing at the chords' nodes.
        // Links held by the static solve's active set are kept as held.
        let dropped = interlayer::duplicates(&w.links, |i| {
            let c = &to_wires[i];
            (c.state != ContactState::Open && hist[nc + i].hold == Hold::Free)
                .then(|| interlayer::centrality(c, w.chain.segments[w.links[i].segment].length))
        });
        for ((lk, out), drop) in w.links.iter().zip(to_wires.iter_mut()).zip(dropped) {
            if drop {
                *out = ContactLoad::open_at(out.core_segment);
            }
            let (k, c) = (lk.segment, *out);
            l.forces[k] += c.force_wire;
            l.torques[k] += c.torque_wire;
            ce += c.normal_energy;
            fe += c.tangential_energy;
            sw += c.slip_work;
        }
        l.contact_energy = ce;
        l.friction_energy = fe;
        l.slip_work = sw;
        l.ties.clear();
        for t in self.ties.iter().filter(|t| t.wire == i) {
            l.ties.push(
                t.joint
                    .evaluate(&core_poses[t.core_segment], &s.poses[t.segment]),
            );
        }
    }

    /// Commits the contact histories evaluated into `loads` (at `state`) as the new
    /// committed state, and adds their slip work to the accumulated friction loss.
    pub fn commit_contacts(&self, state: &mut ModelState, loads: &[WireLoads]) {
        for (h, l) in state.contacts.iter_mut().zip(loads) {
            for (hi, c) in h.iter_mut().zip(&l.contacts) {
                *hi = c.history;
            }
            state.friction_work += l.slip_work;
        }
    }

    /// Energies at `state` (computes loads into `loads`).
    pub fn energies(&self, state: &ModelState, loads: &mut [WireLoads]) -> Energies {
        self.compute_loads(state, 1.0, loads);
        self.energies_from_loads(state, loads)
    }

    /// Energies at `state` from loads already evaluated there (no load evaluation).
    pub fn energies_from_loads(&self, state: &ModelState, loads: &[WireLoads]) -> Energies {
        let mut e = Energies {
            friction_work: state.friction_work,
            ..Default::default()
        };
        for ((w, s), l) in self.wires.iter().zip(&state.wires).zip(loads) {
            e.spring += l.spring_energy;
            e.gravity += l.gravity_energy;
            e.contact += l.contact_energy;
            e.friction_stored += l.friction_energy;
            for (k, seg) in w.chain.segments.iter().enumerate() {
                e.kinetic_translation += 0.5 * seg.mass * s.velocities[k].norm_squared();
                e.kinetic_rotation += seg.rotational_energy(&s.poses[k], &s.angular_momenta[k]);
            }
        }
        e
    }

    /// Centreline of the core (the strand centreline) at `state` (m).
    pub fn core_centreline(&self, state: &ModelState) -> Vec<Vector3<f64>> {
        self.wires[0].chain.centreline(&state.wires[0].poses)
    }
}

/// Neighbouring wires of a layer standing less than this many wire diameters apart (across
/// the wires, `HelixLayer::wire_gap`) are given wire-to-wire links: bending and tension can
/// close such a gap.
pub const NEIGHBOUR_GAP: f64 = 0.05;

/// Largest gap of a lay-geometry contact seen through the chords, as a share of the two
/// arcs' sags (-): measured on the 1+6+12 strand at 8, 12 and 24 segments per pitch, the
/// crossings' gaps are 0.017, 0.012 and 0.012 of the sags, while the closest approaches that
/// are no crossing stand off by 0.35 of them or more (`probe_rest_gaps` in
/// `tests/multilayer.rs`; the test `rest_gaps_close_exactly_the_crossings` checks that the
/// links given a positive rest gap are the crossings of the lay phases).
pub const CHORD_GAP_SHARE: f64 = 0.1;

/// Rest gap of `link` of a wire of `outer` owning the approach `ap` in the lay geometry (m):
/// the lay geometry is the unloaded equilibrium the section law assumes, so the contacts it
/// makes touch with zero gap and zero force. A wire on the layer beneath
/// touches it on the stacked radius, or stands off by the lift of a closed layer, which the
/// section law takes as in contact (`strand_core` module `stack`); through the chords the
/// approach's gap is off by a small share of the two arcs' sags, so every gap up to the lift
/// plus [`CHORD_GAP_SHARE`] of the sags is that contact and is taken as the rest gap (any
/// positive gap left would let the layer sink before it carries pressure, relieving its
/// wires' strain: a sink of 5e-7 m unloads the outer wires of a 1+6+12 steel strand at
/// 100 N). Only crossings: along a line contact (same lay) the gap grows so slowly from the
/// crossing of the lay phases that the links of the segments around it would be taken as
/// touching too (86 links for 72 crossings on the same-lay 1+6+12 strand at 120 segments over
/// 0.6 m): line contacts and neighbours keep their gap (open). An overlap is always taken as
/// the rest gap.
fn rest_gap(link: &WireLink, ap: &interlayer::Approach, outer: &HelixLayer) -> f64 {
    let gap = ap.gap(link);
    let chord_error = CHORD_GAP_SHARE * (link.sag + link.partner_sag) + outer.lift;
    if link.kind == LinkKind::Crossing && gap <= chord_error {
        gap
    } else {
        gap.min(0.0)
    }
}

/// Sag of the helical arc of `layer` over the chord of the segment at rest pose `rest` (m):
/// the helix radius less the distance of the chord's midpoint from the strand axis.
fn helix_sag(layer: &HelixLayer, rest: &Pose) -> f64 {
    let p = rest.position;
    (layer.radius - (p.y * p.y + p.z * p.z).sqrt()).max(0.0)
}

/// Segment of `chain` whose rest centre is nearest to the strand coordinate `x` (chains of a
/// strand are laid in equal steps of x).
fn rest_partner(chain: &Chain, x: f64) -> usize {
    let n = chain.len();
    let first = chain.rest[0].position.x;
    let last = chain.rest[n - 1].position.x;
    if n == 1 || last <= first {
        return 0;
    }
    let k = ((x - first) / (last - first) * (n - 1) as f64).round();
    (k.max(0.0) as usize).min(n - 1)
}

/// Poses and momenta of one wire's segments.
#[derive(Debug, Clone, PartialEq)]
pub struct WireState {
    /// Pose of each segment.
    pub poses: Vec<Pose>,
    /// Velocity of each segment's centre (m/s).
    pub velocities: Vec<Vector3<f64>>,
    /// Angular momentum of each segment about its centre, world axes (kg m^2/s).
    pub angular_momenta: Vec<Vector3<f64>>,
}

/// State of the whole model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelState {
    /// One entry per wire, in the model's wire order.
    pub wires: Vec<WireState>,
    /// Committed contact histories, one list per wire (empty for the core).
    pub contacts: Vec<Vec<ContactHistory>>,
    /// Work lost to friction on committed steps (J).
    pub friction_work: f64,
}

/// Sets `frames` to the frames of `poses` ([`Frame::of`]), one for one.
pub(crate) fn update_frames(poses: &[Pose], frames: &mut [Frame]) {
    for (f, p) in frames.iter_mut().zip(poses) {
        *f = Frame::of(p);
    }
}

/// Loads on one wire's segments and its energies.
#[derive(Debug, Clone, PartialEq)]
pub struct WireLoads {
    /// Resultant force on each segment (N).
    pub forces: Vec<Vector3<f64>>,
    /// Resultant torque on each segment about its centre (N m).
    pub torques: Vec<Vector3<f64>>,
    /// Elastic energy of the wire's joints and anchors (J).
    pub spring_energy: f64,
    /// Potential of gravity and external forces, -sum F . (x - x_rest) (J).
    pub gravity_energy: f64,
    /// Trial contact results of this wire's contact points.
    pub contacts: Vec<ContactLoad>,
    /// Penalty energy of this wire's contacts (J).
    pub contact_energy: f64,
    /// Energy in this wire's tangential contact springs (J).
    pub friction_energy: f64,
    /// Slip work of this wire's contacts since the last commit (J).
    pub slip_work: f64,
    /// Loads of this wire's ties to the core ([`FineModel::ties`] with this wire, in tie
    /// order; body `a` the core segment).
    pub ties: Vec<JointLoad>,
    /// The core's share of this wire's contacts with the core, in contact order (the same
    /// numbers as in `contacts`, packed: the core's loads are summed from them).
    pub core_shares: Vec<CoreShare>,
    /// Frames of the wire's segments at the last evaluation (scratch of
    /// [`FineModel::compute_loads`]).
    pub frames: Vec<Frame>,
}

/// The load a contact with the core puts on the core.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoreShare {
    /// Core segment (index in the core's chain).
    pub segment: usize,
    /// Force on the core segment (N).
    pub force: Vector3<f64>,
    /// Torque on the core segment about its centre (N m).
    pub torque: Vector3<f64>,
}

/// Energies of the model (J).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energies {
    /// Translational kinetic energy.
    pub kinetic_translation: f64,
    /// Rotational kinetic energy.
    pub kinetic_rotation: f64,
    /// Gravity potential relative to the rest configuration (zero at the initial state).
    pub gravity: f64,
    /// Elastic energy of joints and supports.
    pub spring: f64,
    /// Penalty energy of the contacts.
    pub contact: f64,
    /// Energy stored in the tangential (stick) springs of the contacts.
    pub friction_stored: f64,
    /// Work lost to friction on committed steps (not part of [`Energies::total`]).
    pub friction_work: f64,
}

impl Energies {
    /// Sum of all energies (kinetic, potential, springs, contact).
    pub fn total(&self) -> f64 {
        self.kinetic_translation
            + self.kinetic_rotation
            + self.gravity
            + self.spring
            + self.contact
            + self.friction_stored
    }

    /// Total energy plus the work lost to friction: constant up to the integrator's error.
    pub fn balance(&self) -> f64 {
        self.total() + self.friction_work
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::tests::table1;
    use nalgebra::UnitQuaternion;

    fn max_loads(loads: &[WireLoads]) -> (f64, f64) {
        let f = loads
            .iter()
            .flat_map(|l| l.forces.iter())
            .map(|f| f.norm())
            .fold(0.0, f64::max);
        let t = loads
            .iter()
            .flat_map(|l| l.torques.iter())
            .map(|f| f.norm())
            .fold(0.0, f64::max);
        (f, t)
    }

    fn paper_model() -> FineModel {
        FineModel::from_strand(
            &table1(),
            Discretisation {
                core_segments: 77,
                wire_segments: 77,
            },
            Support::Clamped,
            Support::Free,
        )
    }

    /// Typical spring force of a wire joint: the helical wire's E A times a strain of 1e-3.
    fn typical_force(m: &FineModel) -> (f64, f64) {
        let s = m.wires[1].chain.section;
        let f = s.youngs_modulus * s.area * 1e-3;
        (f, f * m.wires[1].chain.segments[0].length)
    }

    #[test]
    fn unloaded_strand_is_at_rest() {
        let m = paper_model();
        assert_eq!(m.wires.len(), 7);
        let state = m.rest_state();
        let mut loads = m.load_buffers();
        m.compute_loads(&state, 1.0, &mut loads);
        let (f, t) = max_loads(&loads);
        let (f0, t0) = typical_force(&m);
        println!(
            "unloaded strand: max force {f:.2e} N ({:.2e} of {f0:.3} N), max torque {t:.2e} N m \
             ({:.2e} of {t0:.2e} N m)",
            f / f0,
            t / t0
        );
        assert!(f <= 1e-12 * f0, "force {f} vs {f0}");
        assert!(t <= 1e-12 * t0, "torque {t} vs {t0}");
        let e = m.energies(&state, &mut loads);
        assert!(e.spring.abs() < 1e-20, "{}", e.spring);
    }

    /// The potential energies (gravity, joints, contacts, stick springs) are zero at the rest
    /// state whatever the direction of gravity (a scene's strand may start along any
    /// direction: the runner turns gravity into the model's frame), and gravity's measures the
    /// work of the weight from there.
    #[test]
    fn potentials_start_at_zero_at_rest_for_any_gravity() {
        let mut m = paper_model();
        m.add_contacts(&table1(), &crate::contact::ContactOptions::default());
        m.gravity = Vector3::new(3.0, -7.0, 5.0);
        let mut state = m.rest_state();
        let mut loads = m.load_buffers();
        let e = m.energies(&state, &mut loads);
        let weight: f64 = m
            .wires
            .iter()
            .flat_map(|w| &w.chain.segments)
            .map(|s| s.mass)
            .sum::<f64>()
            * m.gravity.norm();
        // The weight's work over the strand length (0.4 m).
        let scale = weight * 0.4;
        for (name, v) in [
            ("gravity", e.gravity),
            ("spring", e.spring),
            ("contact", e.contact),
            ("stick springs", e.friction_stored),
        ] {
            assert!(v.abs() <= 1e-12 * scale, "{name}: {v} J at rest");
        }
        // Translating every segment by d lowers the potential by the weight's work.
        let d = Vector3::new(0.01, 0.02, -0.03);
        for w in &mut state.wires {
            for p in &mut w.poses {
                p.position += d;
            }
        }
        let e = m.energies(&state, &mut loads);
        let work = weight / m.gravity.norm() * m.gravity.dot(&d);
        assert!(
            (e.gravity + work).abs() <= 1e-12 * work.abs(),
            "{} vs {}",
            e.gravity,
            -work
        );
    }

    #[test]
    fn wires_bound_at_the_free_end_rest_and_move_rigidly_without_load() {
        let mut m = paper_model();
        m.bind_end(End::End);
        assert_eq!(m.ties.len(), 6);
        let mut state = m.rest_state();
        let mut loads = m.load_buffers();
        m.compute_loads(&state, 1.0, &mut loads);
        let (f0, _) = typical_force(&m);
        assert!(max_loads(&loads).0 <= 1e-12 * f0);
        // Pulling the core's end segment away from the wires loads the ties: equal and
        // opposite forces on the core and on the wires' end segments.
        let last = m.wires[0].chain.len() - 1;
        state.wires[0].poses[last].position.x += 1e-6;
        m.compute_loads(&state, 1.0, &mut loads);
        let on_wires: Vector3<f64> = loads[1..]
            .iter()
            .map(|l| l.forces.iter().sum::<Vector3<f64>>())
            .sum();
        let on_core: Vector3<f64> = loads[0].forces.iter().sum();
        assert!(
            on_wires.x > 0.0,
            "the ties pull the wires along: {on_wires}"
        );
        assert!((on_wires + on_core).norm() <= 1e-9 * on_wires.norm());
    }

    #[test]
    fn rigid_motion_of_a_free_strand_is_load_free() {
        let m = FineModel::from_strand(
            &table1(),
            Discretisation {
                core_segments: 60,
                wire_segments: 77,
            },
            Support::Free,
            Support::Free,
        );
        let mut state = m.rest_state();
        let g = UnitQuaternion::from_scaled_axis(Vector3::new(0.01, -0.02, 0.015));
        let shift = Vector3::new(1e-3, -2e-3, 5e-4);
        for w in &mut state.wires {
            for p in &mut w.poses {
                *p = Pose::new(g * p.position + shift, g * p.rotation);
            }
        }
        let mut loads = m.load_buffers();
        m.compute_loads(&state, 1.0, &mut loads);
        let (f, t) = max_loads(&loads);
        // Moving the poses rounds every coordinate (|x| <= 0.4 m) by about one ulp: the
        // joint gaps then carry a few ulps of position, times the stiffest spring E A / l.
        let k = m
            .wires
            .iter()
            .flat_map(|w| w.chain.joints.iter())
            .map(|j| j.stiffness.translational.max())
            .fold(0.0, f64::max);
        let ulp = f64::EPSILON * 0.4;
        assert!(f <= 10.0 * ulp * k, "force {f} vs {}", ulp * k);
        let l = m.wires[0].chain.segments[0].length;
        assert!(t <= 10.0 * ulp * k * l, "torque {t} vs {}", ulp * k * l);
        let e = m.energies(&state, &mut loads);
        assert!(e.spring < 1e-20, "{}", e.spring);
    }
    /// A pinned strand turned rigidly about its pin carries no load: the pin holds the core's
    /// end point only and the helical wires turn with the core's end segment. (Holding every
    /// wire's end point instead resists the turn with the wires' axial springs.)
    #[test]
    fn pinned_strand_turns_freely_about_its_pin() {
        let m = FineModel::from_strand(
            &table1(),
            Discretisation {
                core_segments: 30,
                wire_segments: 30,
            },
            Support::Pinned,
            Support::Free,
        );
        assert_eq!(m.ties.len(), 6);
        assert_eq!(m.wires[0].anchors.len(), 1);
        assert!(m.wires[1..].iter().all(|w| w.anchors.is_empty()));
        let mut state = m.rest_state();
        let g = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.0, 0.05));
        for w in &mut state.wires {
            for p in &mut w.poses {
                *p = Pose::new(g * p.position, g * p.rotation);
            }
        }
        let mut loads = m.load_buffers();
        m.compute_loads(&state, 1.0, &mut loads);
        let (f, _) = max_loads(&loads);
        let (f0, _) = typical_force(&m);
        assert!(f <= 1e-9 * f0, "force {f} vs {f0}");
        // The same turn against a pin on every wire end: the wires' end springs resist.
        let mut each = m.clone();
        each.ties.clear();
        for w in &mut each.wires[1..] {
            w.support(End::Start, Support::Pinned);
        }
        each.compute_loads(&state, 1.0, &mut loads);
        let (f_each, _) = max_loads(&loads);
        assert!(f_each > 1e-3 * f0, "per-wire pins resist: {f_each} vs {f0}");
    }
}
