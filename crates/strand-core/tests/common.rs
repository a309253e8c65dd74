//! Strands shared by the core's tests.
#![allow(dead_code)]

use strand_core::{LayDirection, LayerSpec, Material, StrandSpec, WireSpec};

/// The paper's Table 1 strand (SPEC 8).
pub fn table1() -> StrandSpec {
    let mat = Material {
        youngs_modulus: 2.0e8,
        poisson_ratio: 0.3,
        density: 7801.0,
    };
    StrandSpec {
        length: 0.4,
        core: WireSpec {
            diameter: 3.0e-3,
            material: mat,
        },
        layers: vec![LayerSpec {
            wires: 6,
            wire: WireSpec {
                diameter: 2.0e-3,
                material: mat,
            },
            lay_angle: 20f64.to_radians(),
            phase: 0.0,
            direction: LayDirection::Right,
        }],
        friction: 0.3,
    }
}
