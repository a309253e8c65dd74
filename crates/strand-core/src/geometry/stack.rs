//! The layers stacked on the core: helix radii wire on wire, closed layers, and the interface
//! of each layer with the one beneath.
//!
//! Layer j = 1..N outward (index j - 1 in [`super::Strand::layers`]) lies on the layer beneath:
//! R_1 = r_c + r_w1, R_j = R_(j-1) + r_w(j-1) + r_wj.
//!
//! # Closed layers
//!
//! A layer is closed when its neighbouring wires touch: six wires of the core's diameter laid
//! round it close exactly at lay angle 0 and overlap by a few microns at any lay angle, since a
//! wire's section along the circle, d_w / cos(alpha), is wider than d_w (Cardinal's steel core,
//! 1+6 x 3.34 mm at 5.696 deg, is short by 1.657e-5 m). Stranding machines make such layers:
//! the wires close on each other and stand a few microns off the layer beneath. This module
//! builds the layer that way: when neighbours would overlap on the stacked radius, the layer is
//! lifted to the radius where they touch, R_j = d_w / (2 cos(alpha) sin(pi/m)) (for a single
//! wire, its own next turn: d_w / (2 pi cos(alpha))), and the layers outside stack on the lifted
//! radius. The lift is accepted only while wires thinner by the manufacturing tolerance of a
//! wire's diameter would fit on the stacked radius: the gap's shortfall at most
//! [`CLOSED_LAYER_TOLERANCE`] d_w / cos(alpha). Drawn round wire is made to about 1 % of its
//! diameter (EN 50189 steel wire of 2.25-3 mm: +-0.03 mm, 1-1.3 %; EN 60889 aluminium of more
//! than 3 mm: +-1 %), so a shortfall inside it is a layer that closes with wires a tolerance
//! thinner, and one beyond it is a layer that cannot be built. Bound: the lift is at most
//! 0.01 d_w / (2 cos(alpha) sin(pi/m)), 0.01 d_w for six wires at small lay angles (1.66e-5 m,
//! 0.5 % of d_w, for Cardinal's steel layer). The layer beneath is not in contact across that
//! stand-off in this geometry; the section laws take the interface as in contact (the friction
//! limit of a closed layer on the layer beneath is the contact-pressure one, module
//! `section::pressure`), which is how the wires settle under tension.

use super::layer::{HelixLayer, LayerSpec, neighbour_chord, wire_gap};
use crate::error::InputError;
use crate::wire::WireSpec;

/// Largest relative shortfall of a closed layer's gap, as a share of the wire's section width
/// d_w / cos(alpha), that the stacking lifts instead of refusing (module docs): the
/// manufacturing tolerance of a drawn wire's diameter, about 1 %.
pub const CLOSED_LAYER_TOLERANCE: f64 = 0.01;

/// How a layer touches the layer (or core) beneath it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Contact {
    /// Along lines: a helical layer on the straight core, or on a helical layer laid in the
    /// same direction.
    Line,
    /// At crossing points: a helical layer on one laid in the other direction.
    Crossing,
}

impl Contact {
    /// Name as printed (`line`, `crossing`).
    pub fn name(self) -> &'static str {
        match self {
            Contact::Line => "line",
            Contact::Crossing => "crossing",
        }
    }
}

impl std::fmt::Display for Contact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The contact of layer `layer` (0-based) with the layer beneath it (the core for layer 0).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Interface {
    /// Index of the outer layer of the interface (0-based).
    pub layer: usize,
    /// Line or crossing-point contact.
    pub contact: Contact,
    /// Angle between the wires of the two layers (rad): alpha_j on the core, |alpha_j -
    /// alpha_(j-1)| for the same lay direction, alpha_j + alpha_(j-1) for alternate lay.
    pub crossing_angle: f64,
}

/// The interface of `layers[j]` with the layer beneath (`layers[j - 1]`, or the core).
pub(crate) fn interface(layers: &[HelixLayer], j: usize) -> Interface {
    let a = layers[j].lay_angle();
    let (contact, crossing_angle) = match j.checked_sub(1).map(|i| &layers[i]) {
        None => (Contact::Line, a),
        Some(b) if b.direction() == layers[j].direction() => {
            (Contact::Line, (a - b.lay_angle()).abs())
        }
        Some(b) => (Contact::Crossing, a + b.lay_angle()),
    };
    Interface {
        layer: j,
        contact,
        crossing_angle,
    }
}

/// Stacks `layers` on `core` (module docs), refusing a layer whose wires overlap beyond the
/// closed-layer tolerance. Errors name the field below `strand` (`layers[k].wires`).
pub(crate) fn stack(core: &WireSpec, layers: &[LayerSpec]) -> Result<Vec<HelixLayer>, InputError> {
    let mut out: Vec<HelixLayer> = Vec::with_capacity(layers.len());
    for (k, l) in layers.iter().enumerate() {
        let stacked = match out.last() {
            None => core.radius() + l.wire.radius(),
            Some(b) => b.radius + b.spec.wire.radius() + l.wire.radius(),
        };
        let gap = wire_gap(l, stacked);
        let width = l.wire.diameter / l.lay_angle.cos();
        let lift = if gap.is_nan() || gap < -CLOSED_LAYER_TOLERANCE * width {
            let rule = if l.wires == 1 {
                "a single wire's neighbouring turns need 2 pi R_w >= d_w / cos(alpha)"
            } else {
                "neighbouring wires need 2 R_w sin(pi/m) >= d_w / cos(alpha)"
            };
            return Err(InputError::new(
                format!("layers[{k}].wires"),
                format!(
                    "{} wires of diameter {} m at lay angle {:.4} deg overlap: {rule} (short by \
                     {:.3e} m, beyond the closed-layer tolerance of {} % of the wire's width)",
                    l.wires,
                    l.wire.diameter,
                    l.lay_angle.to_degrees(),
                    -gap,
                    100.0 * CLOSED_LAYER_TOLERANCE
                ),
            ));
        } else if gap < 0.0 {
            -gap / (2.0 * neighbour_chord(l.wires))
        } else {
            0.0
        };
        let radius = stacked + lift;
        out.push(HelixLayer {
            spec: *l,
            radius,
            pitch: 2.0 * std::f64::consts::PI * radius / l.lay_angle.tan(),
            eta: l.lay_angle.cos().powi(3),
            lift,
        });
    }
    Ok(out)
}
