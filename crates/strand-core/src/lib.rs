//! Constitutive core of `strand`: strand geometry and materials ([`geometry`], SPEC 1), the
//! frictionless bending stiffness of a helical wire ([`wire_bending`]), the bonded (all-stick)
//! stiffness of the wires as rods bonded to the core ([`bonded`]), the stick/slip section laws
//! of the equivalent beam ([`section`], SPEC 2), and the strand calculator's summary
//! ([`summary`]).
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
pub mod summary;
pub mod wire_bending;

pub use bonded::{BondedOptions, BondedStiffness, StickStiffness, bonded_stiffness};
pub use error::InputError;
pub use geometry::{
    DEFAULT_FRICTION, HelixLayer, LayDirection, LayerSpec, Material, Strand, StrandSpec,
    TraditionalBeam, WireSpec,
};
pub use section::{
    LawKind, PlanarMoment, PlanarResponse, SectionLaw, SectionOptions, SectionResponse, SlipLimit,
    Station, WireReport, WireState,
};
pub use summary::{SectionPoint, StrandSummary};
pub use wire_bending::BaseStiffness;
