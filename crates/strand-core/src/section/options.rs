//! Choices a scene makes about the section law beyond its kind (the scene's `section` object).

use super::{BaseTension, SlipLimit, SlipPressure};
use crate::bonded::StickStiffness;
use crate::wire_bending::BaseStiffness;

/// Options of the section laws of the equivalent beam. Build with struct update syntax,
/// `SectionOptions { base_stiffness: BaseStiffness::Paper, ..Default::default() }`, so that
/// options added later keep their defaults.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct SectionOptions {
    /// The helical wires' frictionless bending stiffness in K_min (`section.base_stiffness`;
    /// default Costello's).
    pub base_stiffness: BaseStiffness,
    /// The helical wires' stick stiffness (`section.stick_stiffness`; default the bonded
    /// strand's, the plane section's K_stick times the rod model's stick factor).
    pub stick_stiffness: StickStiffness,
    /// The slipping wires' friction limit (`section.slip_limit`; default Papailiou's, the
    /// capstan gain from the nearest neutral-axis crossing on the axial projection cos(alpha)).
    pub slip_limit: SlipLimit,
    /// The contact pressure that sets each layer's friction limit (`section.slip_pressure`;
    /// default `two_faces`, the accumulated pressure of the layers outside on both faces of a
    /// layer under others, module `pressure`). A strand of one layer has the same law under
    /// every choice.
    pub slip_pressure: SlipPressure,
    /// Whether K_min follows the axial strain (`section.base_tension`; default `fixed`, the
    /// tension-free value; module `base_tension`).
    pub base_tension: BaseTension,
    /// Phase samples per wire of the pitch-averaged law (`section.pitch_samples`; default 0,
    /// the resolved law): with `S >= 2` each bending point stands for the whole pitch around
    /// it, every wire's slider evaluated at `S` phases spread over the wire spacing `P / m`
    /// of its layer (so the layer's `m S` sliders sample its phases evenly), each carrying
    /// `1 / S` of the wire (module docs, "The pitch-averaged law").
    pub pitch_samples: usize,
}

impl SectionOptions {
    /// The paper's section: K_min with eta = cos^3(alpha) (eqs. (10), (11)), the
    /// plane-section stick stiffness (eq. (22a)) and the friction limit of eqs. (20), (22b)
    /// as printed.
    pub fn paper() -> Self {
        SectionOptions {
            base_stiffness: BaseStiffness::Paper,
            stick_stiffness: StickStiffness::PlaneSection,
            slip_limit: SlipLimit::Paper,
            slip_pressure: SlipPressure::OwnLayer,
            base_tension: BaseTension::Fixed,
            pitch_samples: 0,
        }
    }
}
