//! Elastica shooting solution of a planar cantilever under a uniform distributed load (SPEC 7):
//! the independent reference for the statics of strand beams.
//!
//! The cantilever ([`Cantilever`]) is clamped at s = 0 and loaded by q per unit material
//! length in -Y. Its exact equilibrium is a two-point boundary value problem in the material
//! coordinate s (clamp at s = 0, moment-free end at s = L); [`solve`] shoots on the root
//! moment M(0) with a fixed-step RK4 integration, inverting the section law M(kappa, T, s)
//! for the curvature at every stage ([`invert_moment`]), so any law monotone in the curvature
//! can be used: constant EI ([`ConstantEi`]), a closure ([`FnLaw`]) or a stick/slip strand law
//! of `strand-core` ([`StrandLaw`]). Nothing here discretises the beam in elements, which is
//! what makes it a reference for the finite-element models.
//!
//! Very soft strands (q L^3 / K of order 100) curl at the root and hang; the shooting map then
//! has several roots (other equilibria), so the solver follows the loaded branch by
//! continuation in the load from a nearly linear problem. The solution carries a Richardson
//! error estimate from three resolutions.
//!
//! # Example
//!
//! ```
//! use strand_elastica::{Cantilever, ConstantEi, Options, solve};
//!
//! // q L^3 / EI = 1: tip shortening u/L = 0.0087536 and drop v/L = 0.1234714.
//! let sol = solve(&Cantilever::new(1.0, 1.0), &ConstantEi::new(1.0), &Options::default())?;
//! let [dx, dy] = sol.tip_displacement();
//! assert!((-dx - 0.0087536).abs() < 1e-7 && (-dy - 0.1234714).abs() < 1e-7);
//! assert!(sol.error.position < 1e-10);
//! let mid = sol.position(0.5); // cubic Hermite between the RK4 nodes
//! assert!(mid[1] < 0.0);
//! # Ok::<(), strand_elastica::ElasticaError>(())
//! ```

mod error;
pub mod law;
mod solve;

pub use error::ElasticaError;
pub use law::{ConstantEi, FnLaw, PlanarLaw, StrandLaw, invert_moment};
pub use solve::{Cantilever, ErrorEstimate, Options, Sample, Solution, solve};
