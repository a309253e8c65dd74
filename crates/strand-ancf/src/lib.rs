//! Gradient-deficient ANCF cable element of the equivalent strand beam (SPEC 3; paper
//! section 2.1-2.4): kinematics and constant matrices.
//!
//! * [`shape`]: cubic Hermite shape functions (eq. (27)) and Gauss-Legendre rules;
//! * [`planar`]: planar element (8 coordinates), strain and signed curvature with analytic
//!   gradients and Hessians;
//! * [`spatial`]: spatial element (12 coordinates, eq. (24)), strain and curvature vector in
//!   a section frame carried by the minimal rotation, with analytic gradients and Hessians;
//! * [`mass`]: constant consistent mass matrix (eq. (44));
//! * [`load`]: generalized force of a uniform distributed load (eq. (45));
//! * [`dynamics::stable_step`]: the explicit scheme's stable step from the assembled system.
//!
//! Kinematic derivatives are given with respect to the local variables `(r', r'')` at a
//! point (4 values planar, 6 spatial) and mapped to the element coordinates with the
//! `scatter_*`/`add_*` functions of each element module: an element sums the contributions
//! of all section quantities at a Gauss point in the small local space and maps them once.
//! [`PlanarSecond::tangent`] and [`SpatialSecond::tangent`] form that local sum from the
//! section resultants and their tangents. Everything is stack-allocated (nalgebra fixed-size
//! types).
//!
//! Equation numbers "(n)" are those of Guo, Wei, Tan, Zhao (2018), "Analysis of the cored
//! stranded wire rope on the nonlinear bending dynamic characteristics", Chinese J. Theor.
//! Appl. Mech. 50(2):373-384.

pub mod band;
pub mod beam;
mod corotation;
pub mod dynamics;
pub mod error;
pub mod initial;
pub mod load;
pub mod mass;
mod measure;
mod moving_support;
mod output_times;
pub mod planar;
mod scatter;
pub mod shape;
pub mod spatial;
mod stability;
pub mod statics;

pub use error::{AncfError, MIN_ALIGNMENT, MIN_STRETCH};
pub use planar::{PlanarFirst, PlanarPoint, PlanarSecond, PlanarSection};
pub use shape::{GaussRule, QuadraturePoint, ShapeRow, element_quadrature, gauss_legendre};
pub use spatial::{SectionFrame, SpatialFirst, SpatialPoint, SpatialSecond, SpatialSection};
