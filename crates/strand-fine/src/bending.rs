//! Virtual bending test of a strand: moment against curvature under axial tension.
//!
//! A straight strand a whole number of pitches long is clamped at x = 0 (every wire) and its
//! other end is bound to a rigid end plate (every wire's end clamped to the plate). The plate
//! is moved so that the strand is stretched to the strain `eps = T / EA_eq` (the tension
//! `T`), then along the end poses of circular arcs of growing curvature `kappa` (quasi-static
//! load steps; the contact histories are committed after each). Under tension a bent strand
//! is in equilibrium on an arc only if the tension's pull toward the arc's centre is
//! balanced, as on a sheave: each wire carries the dead lateral pressure `T kappa` per unit
//! strand length times its share of the axial stiffness (`E_c A_c` or `cos^3(alpha) E_w A_w`
//! over `EA_eq`), away from the arc's centre, or the core carries all of it
//! ([`Pressure`]). The arc is then an equilibrium whatever the bending stiffness, the
//! internal moment is uniform, and the ends impose no shear.
//!
//! Measured (SI): the internal bending moment at cuts through the core's joints, from the
//! equilibrium of the part of the strand before the cut (clamp reactions and pressure loads),
//! averaged over the test's window ([`BendingTest::window`]: the middle pitches of a `1+m`
//! strand, whole pitches of every layer on several layers); the curvature of the core's
//! centreline over the same window (tangent angle change over arc length); the moment at the
//! clamp; the tension from the clamp reaction.

use nalgebra::{UnitQuaternion, Vector3};
use strand_core::{BondedOptions, Strand, StrandSpec};

use crate::contact::{ContactOptions, ContactState};
use crate::model::{Discretisation, FineModel, ModelState, SpringScale, Support};
use crate::pitch_window::PitchWindow;
use crate::segment::Pose;
use crate::statics::{StaticError, StaticOptions, solve_static};

/// Set-up of a virtual bending test.
#[derive(Debug, Clone, PartialEq)]
pub struct BendingTest {
    /// Strand length in pitches (at least 3; 6 removes end effects).
    pub pitches: usize,
    /// Segments per pitch of every wire.
    pub segments_per_pitch: usize,
    /// Axial tension T (N).
    pub tension: f64,
    /// Curvatures of the load steps after the tension step (1/m), each reached from the one
    /// before: increasing for a loading curve; a sequence that turns back (to negative
    /// values) reverses the load.
    pub curvatures: Vec<f64>,
    /// Contacts; the reference tension defaults to the wire tension under `T`.
    pub contact: ContactOptions,
    /// Friction coefficient mu (overrides the strand's).
    pub friction: f64,
    /// Static solver controls for each load step.
    pub statics: StaticOptions,
    /// Times a failed load step may be retried: with half its curvature increment, or, for
    /// the tension step (no curvature increment to halve), with one more stage of penalty
    /// continuation ([`StaticOptions::penalty_stages`]) than the try before.
    pub max_halvings: usize,
    /// Factors on the core's joint springs (all 1: the physical core).
    pub core_springs: SpringScale,
    /// Factors on the helical wires' joint springs (all 1: the physical wires).
    pub wire_springs: SpringScale,
    /// Which wires carry the lateral pressure that balances the tension on the arc.
    pub pressure: Pressure,
}

/// Which wires carry the dead lateral pressure `T kappa` of the bending test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pressure {
    /// Every wire its share of the axial stiffness (`E_c A_c` or `cos^3(alpha) E_w A_w` over
    /// `EA_eq`): each wire's own tension on the arc is balanced where it acts.
    #[default]
    AxialShare,
    /// The core alone, as on a strand bent over its core: the helical wires get no load from
    /// outside, only from their contacts (the setting of the thin-rod cell of
    /// `strand_core::stretched_bending`).
    Core,
}

impl BendingTest {
    /// The static solve of each load step: one step, relative residual 1e-8, at most 60
    /// Newton iterations, forces measured against `force_scale` (N; the tension, where the
    /// test has one), and no split of the step's load: the load factor of the static solve
    /// scales only the sheave pressure, not the end plate's motion, and a split would commit
    /// the contact histories at a fraction of the pressure the arc needs (a load path the
    /// test does not impose). A step that fails is retried by the test with half its
    /// curvature increment, the tension step with penalty continuation
    /// ([`BendingTest::max_halvings`]).
    pub fn load_step_statics(force_scale: f64) -> StaticOptions {
        StaticOptions {
            load_steps: 1,
            tolerance: 1e-8,
            max_iterations: 60,
            force_scale: Some(force_scale),
            min_increment: 1.0,
            ..Default::default()
        }
    }

    /// The frictionless test of the all-slip stiffness K_min: one curvature `kappa` (1/m) at
    /// the tension `tension` (N), `segments_per_pitch` over `pitches` pitches, default contacts.
    ///
    /// Keep the tension low: the frictionless fine strand softens with tension, which the thin-
    /// rod K_min (`strand_core::wire_bending`) leaves out. Measured on the Table 1 geometry at
    /// 35 deg: M / kappa 1.0005, 1.0003, 0.9987, 0.9830 times Costello's K_min at T = 0.01,
    /// 0.1, 1, 10 N (about -0.16 % per newton; -0.21 % at 20 deg), while the curvature (0.1 or
    /// 1 1/m) and the length (3 or 6 pitches) change it by under 1e-4. The thin-rod energy of
    /// the stretched helix (`strand_core::stretched_bending`) carries the softening; at large
    /// strains the test's value also depends on the strand's length in pitches (Findings page).
    pub fn frictionless(
        pitches: usize,
        segments_per_pitch: usize,
        tension: f64,
        kappa: f64,
    ) -> BendingTest {
        BendingTest {
            pitches,
            segments_per_pitch,
            tension,
            curvatures: vec![kappa],
            contact: ContactOptions::default(),
            friction: 0.0,
            statics: Self::load_step_statics(tension),
            max_halvings: 6,
            core_springs: SpringScale::default(),
            wire_springs: SpringScale::default(),
            pressure: Pressure::AxialShare,
        }
    }
}

/// One measured point of the moment-curvature curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BendingPoint {
    /// Curvature imposed by the end plate (1/m).
    pub imposed_curvature: f64,
    /// Curvature of the core's centreline over the test's window (1/m).
    pub curvature: f64,
    /// Internal bending moment averaged over the test's window (N m).
    pub moment: f64,
    /// Bending moment at the clamp (N m).
    pub clamp_moment: f64,
    /// Axial tension from the clamp reaction (N).
    pub tension: f64,
    /// The strand's axial force over the test's window (N): the resultant of the loads the
    /// part after each cut through the core's joints puts on the part before, along the core's
    /// tangent at the cut ([`BendingTest::axial_profile`]), weighted as the moment is. On a
    /// strand of several layers the test holds it at the tension ([`AXIAL_TOLERANCE`]).
    pub axial_force: f64,
    /// The end plate's stretch, the strain of the arc it is moved along (-): T / EA_eq on a
    /// `1+m` strand, on several layers the stretch that holds the axial force at T.
    pub strain: f64,
    /// Newton iterations of the load step.
    pub iterations: usize,
    /// Contacts stuck, slipping and open at the end of the step.
    pub stick: usize,
    /// Contacts slipping.
    pub slip: usize,
    /// Contacts open.
    pub open: usize,
}

impl BendingPoint {
    /// Secant bending stiffness M / kappa (N m^2).
    pub fn secant_stiffness(&self) -> f64 {
        self.moment / self.curvature
    }
}

/// Failure of a bending test.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BendingError {
    /// The strand has no helical layer.
    #[error("the strand has no helical layer")]
    NoLayer,
    /// The test cannot be built: the strand a whole number of pitches long is not a valid
    /// strand, or the segment count overflows.
    #[error("{0}")]
    Setup(String),
    /// The end plate's stretch did not bring the axial force of a strand of several layers
    /// to the tension ([`AXIAL_TOLERANCE`]).
    #[error(
        "load step at curvature {curvature:.4e} 1/m: the axial force {axial_force:.6e} N does not \
         reach the tension {tension:.6e} N"
    )]
    Tension {
        /// Imposed curvature (1/m).
        curvature: f64,
        /// Axial force over the window at the last correction (N).
        axial_force: f64,
        /// The test's tension (N).
        tension: f64,
    },
    /// A load step did not reach equilibrium.
    #[error("load step at curvature {curvature:.4e} 1/m: {source}")]
    Static {
        /// Imposed curvature (1/m).
        curvature: f64,
        /// The solver's error.
        source: StaticError,
    },
}

/// A load on a segment from outside the strand: (rest x of the segment or -1 for a clamp
/// reaction, point of application, force, torque).
type ExternalLoad = (f64, Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// The end plate's anchors of one wire: (anchor index, rest ground pose).
type EndGrounds = Vec<(usize, Pose)>;

/// Arc map of the bending test: the reference point (x, y, z) of the straight strand goes to
/// the arc of curvature `kappa` stretched by `eps`, sections staying plane and normal.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ArcMap {
    kappa: f64,
    eps: f64,
}

impl ArcMap {
    fn angle(&self, x: f64) -> f64 {
        self.kappa * x * (1.0 + self.eps)
    }

    fn point(&self, r: &Vector3<f64>) -> Vector3<f64> {
        let s = r.x * (1.0 + self.eps);
        if self.kappa == 0.0 {
            return Vector3::new(s, r.y, r.z);
        }
        let th = self.kappa * s;
        let rho = 1.0 / self.kappa - r.y;
        Vector3::new(rho * th.sin(), 1.0 / self.kappa - rho * th.cos(), r.z)
    }

    fn inverse(&self, w: &Vector3<f64>) -> Vector3<f64> {
        if self.kappa == 0.0 {
            return Vector3::new(w.x / (1.0 + self.eps), w.y, w.z);
        }
        // rho = 1/kappa - y has the sign of kappa (the arc bends either way).
        let sign = self.kappa.signum();
        let (vx, vy) = (w.x, w.y - 1.0 / self.kappa);
        let th = (sign * vx).atan2(-sign * vy);
        let rho = sign * (vx * vx + vy * vy).sqrt();
        Vector3::new(
            th / self.kappa / (1.0 + self.eps),
            1.0 / self.kappa - rho,
            w.z,
        )
    }

    fn rotation(&self, x: f64) -> UnitQuaternion<f64> {
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), self.angle(x))
    }

    /// Moves a pose from map `from` to this map.
    fn remap(&self, from: &ArcMap, pose: &Pose) -> Pose {
        let r = from.inverse(&pose.position);
        Pose::new(
            self.point(&r),
            self.rotation(r.x) * from.rotation(r.x).inverse() * pose.rotation,
        )
    }
}

impl BendingTest {
    /// The contacts the test builds on `strand`: [`BendingTest::contact`] with the test's
    /// friction and, unless set, the reference tension of the wires under `tension`,
    /// E_w A_w cos^2(alpha) T / EA_eq (N).
    pub fn contact_options(&self, strand: &Strand) -> ContactOptions {
        let reference = strand.layers().first().map(|layer| {
            let w = &layer.spec.wire;
            let eps = self.tension / strand.axial_stiffness();
            w.material.youngs_modulus * w.area() * layer.lay_angle().cos().powi(2) * eps
        });
        ContactOptions {
            reference_tension: self.contact.reference_tension.or(reference),
            friction: Some(self.friction),
            ..self.contact
        }
    }

    /// The idealisations of the bonded-strand rod model ([`strand_core::bonded`]) that match
    /// this test's springs and contacts on `strand`: the shear, torsion and bending factors
    /// of the wires, the core's shear factor, the contacts' stiffness per unit length and
    /// radius. `None` when a factor the rod model does not carry differs from 1 (the axial
    /// factors, the core's bending and torsion).
    pub fn rod_options(&self, strand: &Strand) -> Option<BondedOptions> {
        let [layer] = strand.layers() else {
            return None;
        };
        let (c, w) = (&self.core_springs, &self.wire_springs);
        if [c.axial, c.bending, c.torsion, w.axial] != [1.0; 4] {
            return None;
        }
        let contact = self.contact_options(strand);
        let (normal, tangential) = contact.stiffness_per_length(layer);
        Some(BondedOptions {
            wire_shear: w.shear,
            wire_torsion: w.torsion,
            wire_bending: w.bending,
            core_shear: c.shear,
            tangential_stiffness: Some(tangential),
            normal_stiffness: Some(normal),
            contact_radius: contact.contact_radius,
        })
    }

    /// Runs the test on `strand` (its length is replaced by `pitches` pitches) and returns
    /// the measured curve: the tension step first (curvature zero), then one point per
    /// curvature.
    pub fn run(&self, strand: &Strand) -> Result<Vec<BendingPoint>, BendingError> {
        self.run_with_state(strand).map(|(curve, _, _)| curve)
    }

    /// As [`BendingTest::run`], also returning the model and its final equilibrium state.
    pub fn run_with_state(
        &self,
        strand: &Strand,
    ) -> Result<(Vec<BendingPoint>, FineModel, ModelState), BendingError> {
        self.run_with_progress(strand, &mut |_| {})
    }

    /// As [`BendingTest::run_with_state`], calling `progress` with every measured point.
    pub fn run_with_progress(
        &self,
        strand: &Strand,
        progress: &mut dyn FnMut(&BendingPoint),
    ) -> Result<(Vec<BendingPoint>, FineModel, ModelState), BendingError> {
        self.run_observed(strand, &mut |p, _, _| progress(p))
    }

    /// As [`BendingTest::run_with_progress`], calling `observe` with every measured point and
    /// the model and equilibrium state it was measured on (e.g. to split the moment per layer
    /// along a path with load reversals).
    pub fn run_observed(
        &self,
        strand: &Strand,
        observe: &mut dyn FnMut(&BendingPoint, &FineModel, &ModelState),
    ) -> Result<(Vec<BendingPoint>, FineModel, ModelState), BendingError> {
        if self.pitches < MIN_PITCHES {
            return Err(BendingError::Setup(format!(
                "a bending test of {} pitches: at least {MIN_PITCHES}, since the moment and \
                 curvature are taken over whole pitches at least a pitch clear of each clamp \
                 (fewer leave an empty window)",
                self.pitches
            )));
        }
        // The longest pitch: every layer spans at least `pitches` of its own.
        let pitch = strand
            .layers()
            .iter()
            .map(|l| l.pitch)
            .reduce(f64::max)
            .ok_or(BendingError::NoLayer)?;
        let length = pitch * self.pitches as f64;
        let spec = StrandSpec {
            length,
            friction: self.friction,
            ..strand.spec().clone()
        };
        let strand = Strand::new(spec).map_err(|e| {
            BendingError::Setup(format!(
                "a strand of {} pitches ({length:e} m): {}",
                self.pitches,
                e.within("strand")
            ))
        })?;
        let n = self
            .pitches
            .checked_mul(self.segments_per_pitch)
            .ok_or_else(|| {
                BendingError::Setup(format!(
                    "{} pitches of {} segments: the segment count overflows",
                    self.pitches, self.segments_per_pitch
                ))
            })?;
        let mut model = FineModel::from_strand(
            &strand,
            Discretisation {
                core_segments: n,
                wire_segments: n,
            },
            Support::Clamped,
            Support::Clamped,
        );
        model.scale_springs(&self.core_springs, &self.wire_springs);
        let ea = strand.axial_stiffness();
        // The end plate's stretch: T / EA_eq, corrected on several layers so that the axial
        // force is the tension (kept from one load step to the next as the start).
        let mut eps = self.tension / ea;
        model.add_contacts(&strand, &self.contact_options(&strand));
        let core = strand.core();
        let shares: Vec<f64> = model
            .wires
            .iter()
            .map(|w| match (self.pressure, w.layer) {
                (Pressure::Core, 0) => 1.0,
                (Pressure::Core, _) => 0.0,
                (Pressure::AxialShare, 0) => core.material.youngs_modulus * core.area() / ea,
                (Pressure::AxialShare, j) => strand.layers()[j - 1].wire_axial_stiffness() / ea,
            })
            .collect();
        // Rest ground poses of the end plate's anchors.
        let end_grounds: Vec<Vec<(usize, Pose)>> = model
            .wires
            .iter()
            .map(|w| {
                w.anchors
                    .iter()
                    .enumerate()
                    .filter(|(_, a)| a.segment + 1 == w.chain.len() && a.ground.position.x > 0.0)
                    .map(|(i, a)| (i, a.ground))
                    .collect()
            })
            .collect();
        let mut state = model.rest_state();
        let mut map = ArcMap {
            kappa: 0.0,
            eps: 0.0,
        };
        let window = self.window_on(&strand, pitch);
        // One layer: the test's original measure over its box, bit for bit, and the end plate
        // held at the strain T / EA_eq (the axial force is measured, not held).
        let one_layer = (strand.layers().len() == 1).then(|| self.one_layer_window(pitch));
        let hold_tension = one_layer.is_none();
        let mut out = Vec::new();
        let steps = std::iter::once(0.0).chain(self.curvatures.iter().copied());
        // The test whose statics the load steps use: a retried step with no curvature
        // increment raises its penalty continuation, for that step only.
        let mut test = self.clone();
        for kappa in steps {
            test.statics = self.statics;
            // Reach `kappa` from the last converged curvature, halving the increment when a
            // load step fails (stick-slip changes of many contacts at once).
            let mut iterations = 0;
            let mut reached = map.kappa;
            let mut increment = kappa - reached;
            let mut halvings = 0;
            loop {
                let target = if (kappa - reached).abs() <= increment.abs() {
                    kappa
                } else {
                    reached + increment
                };
                let saved = (state.clone(), map);
                let saved_eps = eps;
                let stepped = test
                    .step_to(
                        &mut model,
                        &mut state,
                        &mut map,
                        target,
                        eps,
                        &shares,
                        &end_grounds,
                    )
                    .map_err(|source| BendingError::Static {
                        curvature: target,
                        source,
                    })
                    .and_then(|it| {
                        if !hold_tension {
                            return Ok(it);
                        }
                        let held = test.hold_tension(
                            &mut model,
                            &mut state,
                            &mut map,
                            (target, &mut eps, ea),
                            &saved.0,
                            (&shares, &end_grounds, &window),
                        )?;
                        Ok(it + held)
                    });
                match stepped {
                    Ok(it) => {
                        iterations += it;
                        reached = target;
                        if target == kappa {
                            break;
                        }
                    }
                    Err(error) => {
                        (state, map) = saved;
                        eps = saved_eps;
                        halvings += 1;
                        if halvings > self.max_halvings {
                            return Err(error);
                        }
                        if increment == 0.0 {
                            // The tension step: nothing to halve; its Newton iterates
                            // cross the stiff contacts' kinks (the penalty continuation's
                            // case, `crate::statics`), so the retry starts each solve from
                            // softer penalties.
                            test.statics.penalty_stages += 1;
                        } else {
                            increment *= 0.5;
                        }
                    }
                }
            }
            let point = self.measure(
                &model,
                &state,
                (kappa, eps),
                iterations,
                (&window, one_layer),
            );
            observe(&point, &model, &state);
            out.push(point);
        }
        Ok((out, model, state))
    }

    /// The window the test takes its moment and curvature over on `strand` (its length
    /// replaced by [`BendingTest::pitches`] pitches of the longest-pitch layer), rest x (m).
    ///
    /// * One layer: whole pitches, centred, one pitch clear of each clamp, at most two (on 3
    ///   pitches the middle one; from 4 on the middle two): a box.
    /// * Several layers: whole pitches of every layer ([`PitchWindow::for_layers`]): the
    ///   core's curvature oscillates with the pitch of each layer (about +-2.5 % with the
    ///   layer on the core of the 1+6+12 strand), and a window of whole pitches of the
    ///   longest-pitch layer alone spans a fractional number of the others' pitches, which
    ///   makes the figure depend on the strand's length (7e-3 of K_min between 3, 4, 5 and 6
    ///   pitches of a 1+6+12 strand; the Strands of several layers page).
    pub fn window(&self, strand: &Strand) -> Result<PitchWindow, BendingError> {
        let pitch = strand
            .layers()
            .iter()
            .map(|l| l.pitch)
            .reduce(f64::max)
            .ok_or(BendingError::NoLayer)?;
        Ok(self.window_on(strand, pitch))
    }

    /// [`BendingTest::window`] of a test `pitches` long on `strand` (only the length in
    /// pitches matters).
    pub fn window_of(strand: &Strand, pitches: usize) -> Result<PitchWindow, BendingError> {
        let test = BendingTest {
            pitches,
            ..BendingTest::frictionless(pitches, 4, 1.0, 1.0)
        };
        test.window(strand)
    }

    /// [`BendingTest::window`] with the longest pitch `pitch` (m).
    fn window_on(&self, strand: &Strand, pitch: f64) -> PitchWindow {
        if let [_] = strand.layers() {
            let (lo, hi) = self.one_layer_window(pitch);
            return PitchWindow {
                centre: 0.5 * (lo + hi),
                boxes: vec![hi - lo],
            };
        }
        PitchWindow::for_strand(strand, self.pitches)
    }

    /// The one-layer window: rest x from `lo` to `hi` (m), whole pitches `pitch` (m).
    fn one_layer_window(&self, pitch: f64) -> (f64, f64) {
        (
            (self.pitches as f64 / 2.0 - 1.0).max(1.0) * pitch,
            (self.pitches as f64 / 2.0 + 1.0).min(self.pitches as f64 - 1.0) * pitch,
        )
    }

    /// One load step to curvature `kappa`: remaps the state, moves the end plate, sets the
    /// pressure and solves; returns the Newton iterations.
    fn step_to(
        &self,
        model: &mut FineModel,
        state: &mut ModelState,
        map: &mut ArcMap,
        kappa: f64,
        eps: f64,
        shares: &[f64],
        end_grounds: &[Vec<(usize, Pose)>],
    ) -> Result<usize, StaticError> {
        {
            let next = ArcMap { kappa, eps };
            // Initial guess: the previous equilibrium carried by the change of arc.
            for ws in &mut state.wires {
                for p in &mut ws.poses {
                    *p = next.remap(map, p);
                }
            }
            *map = next;
            for (w, grounds) in model.wires.iter_mut().zip(end_grounds) {
                for &(i, g) in grounds {
                    let a = &mut w.anchors[i];
                    a.ground = Pose::new(
                        map.point(&g.position),
                        map.rotation(g.position.x) * g.rotation,
                    );
                }
            }
            // Sheave pressure, away from the arc's centre.
            for (w, &share) in model.wires.iter_mut().zip(shares) {
                w.external = w
                    .chain
                    .rest
                    .iter()
                    .zip(&w.chain.segments)
                    .map(|(r, s)| {
                        let th = map.angle(r.position.x);
                        let dx = s.length * r.tangent().x;
                        Vector3::new(th.sin(), -th.cos(), 0.0) * (share * self.tension * kappa * dx)
                    })
                    .collect();
            }
            let rep = solve_static(model, state, &self.statics)?;
            Ok(rep.iterations)
        }
    }

    /// Holds the strand's axial force over `window` at the tension after a converged load
    /// step to curvature `kappa` (1/m) at the end plate's stretch `eps`: while the axial force
    /// `N` ([`BendingTest::axial_profile`] over the window) differs from `T` by more than
    /// [`AXIAL_TOLERANCE`] `T`, the stretch moves by `(T - N) / k` (`k` the strand's axial
    /// stiffness EA_eq (N) at first, then the secant of the last two solves) and the step is
    /// solved again from the contact histories committed at its start (`start`), with the last
    /// equilibrium as the initial guess. Returns the Newton iterations; `eps` ends at the held
    /// stretch.
    fn hold_tension(
        &self,
        model: &mut FineModel,
        state: &mut ModelState,
        map: &mut ArcMap,
        (kappa, eps, ea): (f64, &mut f64, f64),
        start: &ModelState,
        (shares, end_grounds, window): (&[f64], &[EndGrounds], &PitchWindow),
    ) -> Result<usize, BendingError> {
        let target = self.tension;
        let mut iterations = 0;
        let mut last: Option<(f64, f64)> = None;
        for _ in 0..MAX_AXIAL_CORRECTIONS {
            let n = window.mean(&Self::axial_profile(model, state));
            if (n - target).abs() <= AXIAL_TOLERANCE * target {
                return Ok(iterations);
            }
            let k = match last {
                Some((e0, n0)) if *eps != e0 && (n - n0) / (*eps - e0) > 0.0 => {
                    (n - n0) / (*eps - e0)
                }
                _ => ea,
            };
            last = Some((*eps, n));
            *eps += (target - n) / k;
            state.contacts.clone_from(&start.contacts);
            state.friction_work = start.friction_work;
            iterations += self
                .step_to(model, state, map, kappa, *eps, shares, end_grounds)
                .map_err(|source| BendingError::Static {
                    curvature: kappa,
                    source,
                })?;
        }
        Err(BendingError::Tension {
            curvature: kappa,
            axial_force: window.mean(&Self::axial_profile(model, state)),
            tension: target,
        })
    }

    /// The strand's axial force (N) at every cut through a joint of the core at `state`, with
    /// the cut's rest x (m): the loads the part after the cut puts on the part before, along
    /// the core's tangent at the cut (the mean of its two segments' tangents), each wire cut at
    /// its joint nearest the cut plane (as [`BendingTest::layer_moment_parts`] cuts them).
    pub fn axial_profile(model: &FineModel, state: &ModelState) -> Vec<(f64, f64)> {
        let core = &model.wires[0];
        let cs = &state.wires[0].poses;
        (0..core.chain.joints.len())
            .map(|j| {
                let jt = &core.chain.joints[j];
                let x = core.chain.rest[j].point(&jt.offset_a).x;
                let c = cs[j].point(&jt.offset_a);
                let axis = (cs[j].tangent() + cs[j + 1].tangent()).normalize();
                let mut force = jt.evaluate(&cs[j], &cs[j + 1]).force_a;
                for (w, ws) in model.wires.iter().zip(&state.wires).skip(1) {
                    let k = nearest_joint(w, &ws.poses, &c, &axis);
                    let jw = &w.chain.joints[k];
                    force += jw.evaluate(&ws.poses[k], &ws.poses[k + 1]).force_a;
                }
                (x, force.dot(&axis))
            })
            .collect()
    }

    /// Axial force of every wire at the clamp (x = 0) at `state`, from its clamp reaction, in
    /// model wire order (N).
    pub fn clamp_tensions(model: &FineModel, state: &ModelState) -> Vec<f64> {
        model
            .wires
            .iter()
            .zip(&state.wires)
            .map(|(w, s)| {
                w.anchors
                    .iter()
                    .filter(|a| a.segment == 0)
                    .map(|a| -a.joint.evaluate(&a.ground, &s.poses[a.segment]).force_b.x)
                    .sum()
            })
            .collect()
    }

    /// The internal bending moment (N m) at every cut through a joint of the core at `state`,
    /// with the cut's rest x (m): from the equilibrium of the part of the strand before the
    /// cut (clamp reactions and pressure loads), about the core's centreline at the cut. The
    /// first entry (x = 0) is the moment at the clamp. The test's moment is the mean over the
    /// cuts in the test's window ([`BendingTest::window`]).
    pub fn moment_profile(model: &FineModel, state: &ModelState) -> Vec<(f64, f64)> {
        Self::moment_profile_of(model, state, &Self::external_loads(model, state).0)
    }

    /// [`BendingTest::moment_profile`] from the external loads `ext`.
    fn moment_profile_of(
        model: &FineModel,
        state: &ModelState,
        ext: &[ExternalLoad],
    ) -> Vec<(f64, f64)> {
        let core = &model.wires[0].chain;
        let line = core.centreline(&state.wires[0].poses);
        let l = core.segments[0].length;
        line.iter()
            .enumerate()
            .map(|(k, c)| {
                let x = k as f64 * l;
                (x, moment_at(ext, x, c))
            })
            .collect()
    }

    /// The moment at the core's cuts in rest x `[lo, hi]` (m) split by layer (0 the core, up to
    /// `layers`), averaged over the cuts (N m): each wire cut at its joint nearest the core's cut
    /// plane, the loads of the part after the cut on the part before as [own joint moment, axial
    /// force x arm, shear force x arm] about the core's joint point. Their sum over a layer is
    /// that layer's part of the cut moment; over all layers, the core's cut moment.
    pub fn layer_moment_parts(
        model: &FineModel,
        state: &ModelState,
        layers: usize,
        (lo, hi): (f64, f64),
    ) -> Vec<[f64; 3]> {
        let mut parts = vec![[0.0; 3]; layers + 1];
        let core = &model.wires[0];
        let cs = &state.wires[0].poses;
        let mut cuts = 0;
        for j in 0..core.chain.joints.len() {
            let x = core.chain.rest[j].point(&core.chain.joints[j].offset_a).x;
            if x < lo - 1e-9 || x > hi + 1e-9 {
                continue;
            }
            let jt = &core.chain.joints[j];
            let c = cs[j].point(&jt.offset_a);
            let normal = (cs[j].tangent() + cs[j + 1].tangent()).normalize();
            let l = jt.evaluate(&cs[j], &cs[j + 1]);
            parts[0][0] += (l.torque_a + (cs[j].position - c).cross(&l.force_a)).z;
            for (w, ws) in model.wires.iter().zip(&state.wires).skip(1) {
                let k = nearest_joint(w, &ws.poses, &c, &normal);
                let jw = &w.chain.joints[k];
                let lw = jw.evaluate(&ws.poses[k], &ws.poses[k + 1]);
                let q = ws.poses[k].point(&jw.offset_a);
                let tangent = (ws.poses[k].tangent() + ws.poses[k + 1].tangent()).normalize();
                let axial = tangent * lw.force_a.dot(&tangent);
                let part = &mut parts[w.layer];
                part[0] += (lw.torque_a + (ws.poses[k].position - q).cross(&lw.force_a)).z;
                part[1] += (q - c).cross(&axial).z;
                part[2] += (q - c).cross(&(lw.force_a - axial)).z;
            }
            cuts += 1;
        }
        for p in &mut parts {
            for v in p.iter_mut() {
                *v /= cuts as f64;
            }
        }
        parts
    }

    /// M / kappa (N m^2) over the window from rest x `lo` to `hi` (m) at `state`: the mean of
    /// the [`BendingTest::moment_profile`] over the window (trapezoid rule, linear between the
    /// cuts) over the core's mean curvature there (the change of its tangent angle, linear
    /// between segment centres, over the window's arc length on the stretched core).
    ///
    /// On a strand of several layers the core's curvature oscillates with the pitch of the
    /// layer on it (about 2.5 % on the 1+6+12 cell), so a figure over whole pitches of the
    /// longest-pitch layer alone depends on where the window falls; a window of a whole number
    /// of that layer's pitches ([`BendingTest::centred_window`]) removes most of it, and the
    /// test's own figure ([`BendingPoint::secant_stiffness`]) takes whole pitches of every
    /// layer ([`BendingTest::window`]; the Strands of several layers page of the manual).
    pub fn window_stiffness(model: &FineModel, state: &ModelState, (lo, hi): (f64, f64)) -> f64 {
        let m = Self::moment_profile(model, state);
        let mut integral = 0.0;
        for w in m.windows(2) {
            let ((x0, m0), (x1, m1)) = (w[0], w[1]);
            let (a, b) = (x0.max(lo), x1.min(hi));
            if b > a {
                let at = |x: f64| m0 + (m1 - m0) * (x - x0) / (x1 - x0);
                integral += 0.5 * (at(a) + at(b)) * (b - a);
            }
        }
        let moment = integral / (hi - lo);
        let chain = &model.wires[0].chain;
        let poses = &state.wires[0].poses;
        let n = poses.len();
        let l = chain.segments[0].length;
        let angle = |k: usize| {
            let t = poses[k].tangent();
            t.y.atan2(t.x)
        };
        // Segment k's centre is at rest x (k + 1/2) l.
        let at = |x: f64| {
            let u = (x / l - 0.5).clamp(0.0, (n - 1) as f64);
            let k = (u.floor() as usize).min(n - 2);
            (k, u - k as f64)
        };
        let theta = |x: f64| {
            let (k, f) = at(x);
            (1.0 - f) * angle(k) + f * angle(k + 1)
        };
        let ((first, _), (last, _)) = (at(lo), at(hi));
        let last = last.max(first) + 1;
        let stretch = (first..last)
            .map(|k| (poses[k + 1].position - poses[k].position).norm())
            .sum::<f64>()
            / ((last - first) as f64 * l);
        moment / ((theta(hi) - theta(lo)) / ((hi - lo) * stretch))
    }

    /// The window of `count` periods `period` (m) centred on a strand `length` (m) long: rest
    /// x from (length - count period) / 2 to (length + count period) / 2 (m).
    pub fn centred_window(length: f64, period: f64, count: usize) -> (f64, f64) {
        let span = count as f64 * period;
        (0.5 * (length - span), 0.5 * (length + span))
    }

    /// Clamp reactions (rest x -1) and pressure loads (rest x of their segment) at `state`,
    /// and the axial tension from the clamp reactions (N).
    fn external_loads(model: &FineModel, state: &ModelState) -> (Vec<ExternalLoad>, f64) {
        let mut ext: Vec<ExternalLoad> = Vec::new();
        let mut tension = 0.0;
        for (w, s) in model.wires.iter().zip(&state.wires) {
            for a in &w.anchors {
                if a.segment != 0 {
                    continue;
                }
                let l = a.joint.evaluate(&a.ground, &s.poses[a.segment]);
                tension -= l.force_b.x;
                ext.push((-1.0, s.poses[a.segment].position, l.force_b, l.torque_b));
            }
            for ((r, p), f) in w.chain.rest.iter().zip(&s.poses).zip(&w.external) {
                ext.push((r.position.x, p.position, *f, Vector3::zeros()));
            }
        }
        (ext, tension)
    }

    fn measure(
        &self,
        model: &FineModel,
        state: &ModelState,
        (kappa, eps): (f64, f64),
        iterations: usize,
        (window, one_layer): (&PitchWindow, Option<(f64, f64)>),
    ) -> BendingPoint {
        let loads = {
            let mut loads = model.load_buffers();
            model.compute_loads(state, 1.0, &mut loads);
            loads
        };
        // Clamp reactions on the segments (start anchors) and pressure loads, with the rest
        // x of the segment they act on.
        let (ext, tension) = Self::external_loads(model, state);
        let profile = Self::moment_profile_of(model, state, &ext);
        let core = &model.wires[0].chain;
        let l = core.segments[0].length;
        let line = core.centreline(&state.wires[0].poses);
        let poses = &state.wires[0].poses;
        let (moment, curvature) = match one_layer {
            Some(box_) => one_layer_measure(&profile, poses, l, box_),
            None => window.measure(&profile, poses, l),
        };
        let count = |st: ContactState| {
            loads
                .iter()
                .flat_map(|l| l.contacts.iter())
                .filter(|c| c.state == st)
                .count()
        };
        BendingPoint {
            imposed_curvature: kappa,
            curvature,
            moment,
            clamp_moment: moment_at(&ext, 1e-12, &line[0]),
            tension,
            axial_force: window.mean(&Self::axial_profile(model, state)),
            strain: eps,
            iterations,
            stick: count(ContactState::Stick),
            slip: count(ContactState::Slip),
            open: count(ContactState::Open),
        }
    }
}

/// The one-layer test's moment and curvature over the window from rest x `lo` to `hi` (m):
/// the mean moment over the cuts in the window; the tangent angle change of the core's
/// segments over the arc length between their centres.
fn one_layer_measure(
    profile: &[(f64, f64)],
    poses: &[Pose],
    l: f64,
    (lo, hi): (f64, f64),
) -> (f64, f64) {
    let mut sum = 0.0;
    let mut cuts = 0;
    for &(x, m) in profile {
        if x >= lo - 1e-12 && x <= hi + 1e-12 {
            sum += m;
            cuts += 1;
        }
    }
    let first = ((lo / l).round() as usize).min(poses.len() - 1);
    let last = ((hi / l).round() as usize).saturating_sub(1).max(first + 1);
    let angle = |p: &Pose| {
        let t = p.tangent();
        t.y.atan2(t.x)
    };
    let arc: f64 = (first..last)
        .map(|k| (poses[k + 1].position - poses[k].position).norm())
        .sum();
    let curvature = (angle(&poses[last]) - angle(&poses[first])) / arc;
    (sum / cuts.max(1) as f64, curvature)
}

/// Fewest pitches of a bending test: its window keeps a pitch clear of each clamp.
pub const MIN_PITCHES: usize = 3;

/// Most corrections of the end plate's stretch in one load step ([`BendingTest::hold_tension`]).
const MAX_AXIAL_CORRECTIONS: usize = 12;

/// Relative tolerance on the axial force a strand of several layers is held at: its mean over
/// the window within `AXIAL_TOLERANCE T` of the tension `T`. Single cuts of one equilibrium
/// scatter more (the wires are cut at their joints nearest the core's cut plane): on the
/// frictionless 1+6+12 at 0.01 N, straight, 12 segments per pitch, by up to 1.6e-5 T over
/// every cut, by 2e-6 T over cuts at 0.3, 0.5 and 0.7 of the length; the static solve stops at
/// a residual of 1e-8 of `T`. The clamp's independent reading agrees within that scatter
/// (`the_axial_force_of_several_layers_is_held_at_the_tension`).
pub const AXIAL_TOLERANCE: f64 = 1e-6;

/// Index of the joint of wire `w` (poses `poses`) nearest the plane through `c` (m) normal to
/// `normal`.
fn nearest_joint(
    w: &crate::model::Wire,
    poses: &[Pose],
    c: &Vector3<f64>,
    normal: &Vector3<f64>,
) -> usize {
    w.chain
        .joints
        .iter()
        .enumerate()
        .map(|(k, jw)| (k, (poses[k].point(&jw.offset_a) - c).dot(normal).abs()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(k, _)| k)
}

/// The bending moment about z at a cut at rest x `x_cut` through the point `c` (N m): minus
/// the moment about `c` of the external loads before the cut.
fn moment_at(ext: &[ExternalLoad], x_cut: f64, c: &Vector3<f64>) -> f64 {
    -ext.iter()
        .filter(|e| e.0 < x_cut)
        .map(|(_, p, f, t)| ((p - c).cross(f) + t).z)
        .sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strand of 3e10 pitches is not a valid strand (longer than 1e9 m): the test says so
    /// instead of panicking.
    #[test]
    fn an_impossible_length_is_an_error() {
        let strand = Strand::new(StrandSpec::paper(0.4, 2e8, 7801.0)).unwrap();
        let test = BendingTest {
            pitches: 30_000_000_000,
            segments_per_pitch: 12,
            tension: 10.0,
            curvatures: vec![1.0],
            contact: ContactOptions::default(),
            friction: 0.3,
            statics: StaticOptions::default(),
            max_halvings: 1,
            core_springs: SpringScale::default(),
            wire_springs: SpringScale::default(),
            pressure: Pressure::AxialShare,
        };
        match test.run(&strand) {
            Err(BendingError::Setup(m)) => assert!(m.contains("strand.length"), "{m}"),
            other => panic!("{other:?}"),
        }
    }

    /// Two pitches leave the window a pitch clear of each clamp empty (no cut, a NaN moment
    /// before): the test refuses them, naming the reason, before building anything.
    #[test]
    fn fewer_than_three_pitches_are_refused() {
        let strand = Strand::new(StrandSpec::paper(0.4, 2e8, 7801.0)).unwrap();
        for pitches in [0, 1, 2] {
            match BendingTest::frictionless(pitches, 8, 1.0, 0.1).run(&strand) {
                Err(BendingError::Setup(m)) => {
                    assert!(
                        m.contains("at least 3") && m.contains("empty window"),
                        "{m}"
                    )
                }
                other => panic!("{pitches} pitches: {other:?}"),
            }
        }
    }

    #[test]
    fn arc_map_inverts() {
        let m = ArcMap {
            kappa: 2.0,
            eps: 1e-3,
        };
        let r = Vector3::new(0.1, 2e-3, -1e-3);
        let back = m.inverse(&m.point(&r));
        assert!((back - r).norm() < 1e-15);
        let straight = ArcMap {
            kappa: 0.0,
            eps: 1e-3,
        };
        let p = Pose::new(straight.point(&r), UnitQuaternion::identity());
        let q = m.remap(&straight, &p);
        assert!((q.position - m.point(&r)).norm() < 1e-15);
        // Bent the other way (load reversal).
        let n = ArcMap {
            kappa: -2.0,
            eps: 1e-3,
        };
        assert!((n.inverse(&n.point(&r)) - r).norm() < 1e-15);
        let q = n.remap(&m, &Pose::new(m.point(&r), m.rotation(r.x)));
        assert!((q.position - n.point(&r)).norm() < 1e-15);
    }
}
