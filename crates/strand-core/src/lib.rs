//! Constitutive core of `strand`: a wire's material and section ([`wire`]), strand geometry of
//! any number of layers ([`geometry`], SPEC 1), the frictionless bending stiffness of a helical
//! wire ([`wire_bending`]), the bonded (all-stick) stiffness of a layer's wires as rods bonded
//! to what lies beneath ([`bonded`]), the stick/slip section laws of the equivalent beam
//! ([`section`], SPEC 2), and the strand calculator's summary ([`summary`]).
//!
//! Equation numbers "(n)" in the documentation are those of Guo, Wei, Tan, Zhao (2018),
//! "Analysis of the cored stranded wire rope on the nonlinear bending dynamic
//! characteristics", Chinese J. Theor. Appl. Mech. 50(2):373-384.

pub mod bonded;
pub mod convergence;
pub mod error;
pub mod geometry;
pub mod round_off;
pub mod section;
pub mod stretched_bending;
pub mod summary;
pub mod wire;
pub mod wire_bending;

pub use bonded::{BondedOptions, BondedStiffness, StickStiffness, bonded_stiffness};
pub use error::InputError;
pub use geometry::{
    CLOSED_LAYER_TOLERANCE, Contact, DEFAULT_FRICTION, HelixLayer, Interface, LayDirection,
    LayerSpec, Material, Strand, StrandSpec, TraditionalBeam, WireSpec,
};
pub use section::{
    BaseTension, LawKind, PlanarMoment, PlanarResponse, PressureSystem, SectionLaw, SectionOptions,
    SectionResponse, SlipLimit, SlipPressure, Station, WireReport, WireState,
};
pub use stretched_bending::stretched_min_bending_stiffness;
pub use summary::{LayerSummary, SectionPoint, StrandSummary};
pub use wire_bending::BaseStiffness;
