//! Fine reference model of a strand (SPEC 4): every wire, the straight core and each helical
//! wire, is its own chain of rigid cylindrical segments laid along its undeformed centreline
//! and joined by the joint springs of the finite segment method (Hamper, Recuero, Escalona,
//! Shabana 2012). The model uses only the strand's geometry and materials; none of the
//! equivalent beam's section laws.
//!
//! * [`segment`]: rigid cylinders and their poses; [`so3`]: rotation helpers.
//! * [`chain`]: a wire laid as a segment chain; [`joint`]: the joint springs.
//! * [`model`]: wires, supports, gravity, state, loads and energies.
//! * [`statics`]: Newton-Raphson static equilibrium; [`mod@settle`]: static equilibrium with
//!   contacts by damped motion and Newton; [`pseudo_transient`]: implicit pseudo-time steps
//!   to equilibrium; [`dynamics`]: symplectic time stepping;
//!   [`motion`]: moving supports and rigid initial velocities.
//! * [`contact`]: wire-to-core contact (penalty and Cundall-Strack friction with history),
//!   added to a model by [`FineModel::add_contacts`]; [`interlayer`]: wire-to-wire contact
//!   (crossings and lines with the layer beneath, neighbours in a layer) with the same law.
//! * [`bending`]: the virtual bending test (moment against curvature under tension);
//!   [`pitch_window`]: the window of whole pitches of every layer it measures over.
//!
//! Units are SI throughout (m, kg, s, N, rad).
//!
//! Design:
//! * Generalized coordinates per segment: centre translation and a world-frame rotation
//!   increment (`R <- exp(dw) R`); loads are the exact negative gradient of the joint energy
//!   in these coordinates, so the model conserves momentum and energy.
//! * Supports are ground joints carrying the springs of the half segment between the wire's
//!   end and its first segment's centre (a clamp holds position and rotation, a pin the
//!   position only); with them the cantilever converges at second order in the segment
//!   length.
//! * Element tangents are central differences of the exact element loads (12 x 12 per
//!   joint or contact, contact histories frozen); the static solve factors their assembly
//!   with a sparse LU. The explicit stable step bounds contacts as closed springs.
//! * Loads are computed in parallel over wires; each wire's loads depend on that wire (and,
//!   for contacts, on its partners' poses) only, and the partners' share of the contact loads
//!   (the core's, then the wire-to-wire links') is summed in a fixed order, so results are
//!   identical for any number of threads.
//! * Contact histories are committed only on accepted time steps and converged load steps.

pub mod bending;
pub mod chain;
pub mod contact;
pub mod dynamics;
pub mod interlayer;
pub mod joint;
pub mod load_continuation;
mod load_share;
pub mod model;
pub mod motion;
pub mod penalty;
pub mod pitch_window;
pub mod pseudo_transient;
pub mod segment;
pub mod settle;
pub mod so3;
pub mod sparse_tangent;
pub mod spectrum;
mod spin_barrier;
pub mod statics;
mod sweep;
pub mod tangent;

pub use bending::{AXIAL_TOLERANCE, BendingError, BendingPoint, BendingTest, Pressure};
pub use chain::{Chain, WireSection};
pub use contact::{
    ContactHistory, ContactLaw, ContactLoad, ContactOptions, ContactPoint, ContactState, Hold,
    NormalPenalty,
};
pub use dynamics::{Integrator, stable_time_step};
pub use joint::{JointLoad, JointSpring, JointStiffness};
pub use model::{
    Anchor, Discretisation, End, Energies, FineModel, ModelState, NEIGHBOUR_GAP, SpringScale,
    Support, Tie, Wire, WireLoads, WireState,
};
pub use pitch_window::PitchWindow;
pub use segment::{Pose, Segment};
pub use settle::{
    SettleError, SettleOptions, SettleReport, SettledOptions, SettledReport, damping_and_ramp,
    settle, settle_time_step, solve_settled,
};
pub use statics::{
    RelaxationOptions, StaticError, StaticOptions, StaticReport, solve_relaxation, solve_static,
    solve_static_with_progress,
};
