//! Normal penalty of the contacts of a multi-layer strand from the allowed relief of the wire
//! strain.
//!
//! A helical wire of lay angle `alpha` on the helix radius `R`, held at both ends of a strand
//! of fixed length, has the length `sqrt(P^2 + (2 pi R)^2)` per pitch `P`; a radial sink `delta`
//! shortens its path by the strain `sin^2(alpha) delta / R`. Under the strand strain `eps` the
//! wire carries `cos^2(alpha) eps` (its tension `T_w = E_w A_w cos^2(alpha) eps`), so the sink
//! relieves the share `tan^2(alpha) delta / (R eps)` of it. A penalty allowing a fixed
//! penetration (a fraction of the wire diameter at a reference pressure) relieves more than
//! the whole strain where the strain is small (a steel strand under a test tension of 100 N:
//! `eps` 3.7e-6 against a relief of 2e-5), so the helical wires carry no tension.
//!
//! Here the penetration follows the strain: every layer `i` may sink in total by
//! `D_i eps = f R_i eps / tan^2(alpha_i)` (the relief `f` of its strain), shared equally by the
//! `i + 1` interfaces beneath it (interface 0 on the core). Interface `j` carries the radial
//! line load of every layer `i >= j` resting on it, per unit strand length
//! `F_i = m_i T_i sin^2(alpha_i) / (R_i cos(alpha_i))` (the helix curvature times the wire
//! tension over the strand length per wire length; the wires of a layer carry no hoop force),
//! and sinks `delta_j = sum F_i / K_j`. With `delta_j = eps min_{i >= j} D_i / (i + 1)` the
//! stiffness per unit strand length is `K_j = sum_{i >= j} F_i / delta_j`, and per unit length
//! of a wire of layer `j`, `k_j = K_j cos(alpha_j) / m_j`: both `F` and `delta` scale with `eps`,
//! so the stiffness does not depend on the tension. For one layer it is
//! `k = E_w A_w sin^4(alpha) / (f R^2)`.

use strand_core::Strand;

/// Default allowed relief of a helical wire's strain by the contacts' radial sink (-): 1 %,
/// a fifth of the 5 % to which the fine and equivalent moment-curvature curves are compared,
/// while the normal penalty stays below the stick spring of the contacts, so the stable step
/// of the explicit settle is not shortened: on the 1+6+12 steel strand 4.1036e-7 s against
/// 4.1061e-7 s with the penetration rule at 8 segments per pitch, where 1e-3 halves it
/// (1.9699e-7 s; `probe_stable_step` in `tests/multilayer.rs`).
pub const DEFAULT_STRAIN_RELIEF: f64 = 1e-2;

/// Normal penalty per unit length of a wire of layer `j` on the layer beneath (`j = 0`: on the
/// core), for every layer of `strand` (N/m^2), allowing the relief `relief` of every layer's
/// strain (module docs). A layer laid straight (no strain relief by a sink) bounds nothing; a
/// layer whose interfaces are bounded by no layer gets `None`.
pub fn normal_stiffness_per_length(strand: &Strand, relief: f64) -> Vec<Option<f64>> {
    let layers = strand.layers();
    // Radial line load per unit strand length and unit strand strain (N/m), and the allowed
    // total sink per unit strain (m), of every layer.
    let load: Vec<f64> = layers
        .iter()
        .map(|l| {
            let (a, w) = (l.lay_angle(), &l.spec.wire);
            let ea = w.material.youngs_modulus * w.area();
            l.wires() as f64 * ea * a.cos() * a.sin().powi(2) / l.radius
        })
        .collect();
    let sink: Vec<f64> = layers
        .iter()
        .map(|l| relief * l.radius / l.lay_angle().tan().powi(2))
        .collect();
    (0..layers.len())
        .map(|j| {
            let carried: f64 = load[j..].iter().sum();
            let allowed = (j..layers.len())
                .map(|i| sink[i] / (i + 1) as f64)
                .fold(f64::INFINITY, f64::min);
            let per_strand_length = carried / allowed;
            let l = &layers[j];
            let k = per_strand_length * l.lay_angle().cos() / l.wires() as f64;
            (k.is_finite() && k > 0.0).then_some(k)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use strand_core::{LayDirection, LayerSpec, Material, StrandSpec, WireSpec};

    fn steel() -> Material {
        Material {
            youngs_modulus: 2.0e11,
            poisson_ratio: 0.3,
            density: 7850.0,
        }
    }

    fn layer(wires: usize, deg: f64, direction: LayDirection) -> LayerSpec {
        LayerSpec {
            wires,
            wire: WireSpec {
                diameter: 3e-3,
                material: steel(),
            },
            lay_angle: deg.to_radians(),
            phase: 0.0,
            direction,
        }
    }

    fn strand(layers: Vec<LayerSpec>) -> Strand {
        Strand::new(StrandSpec {
            length: 1.0,
            core: WireSpec {
                diameter: 3.3e-3,
                material: steel(),
            },
            layers,
            friction: 0.3,
        })
        .unwrap()
    }

    /// One layer: the closed form `E_w A_w sin^4(alpha) / (f R^2)`.
    #[test]
    fn one_layer_has_the_closed_form() {
        let s = strand(vec![layer(6, 8.0, LayDirection::Right)]);
        let l = &s.layers()[0];
        let a = l.lay_angle();
        let exact = l.spec.wire.material.youngs_modulus * l.spec.wire.area() * a.sin().powi(4)
            / (1e-2 * l.radius * l.radius);
        let k = normal_stiffness_per_length(&s, 1e-2)[0].unwrap();
        assert!((k / exact - 1.0).abs() < 1e-12, "{k:e} against {exact:e}");
    }

    /// The sinks the stiffnesses allow under any strain relieve every layer's strain by at
    /// most the relief asked, and the outermost layer of the 1+6+12 strand by exactly it (it
    /// bounds both interfaces); straight from the sinks, with the loads recomputed from the
    /// wire tensions and helix curvatures.
    #[test]
    fn every_layer_keeps_its_strain_within_the_relief() {
        let s = strand(vec![
            layer(6, 8.0, LayDirection::Right),
            layer(12, 12.0, LayDirection::Left),
        ]);
        let f = 1e-2;
        let eps = 3.7e-6;
        let k = normal_stiffness_per_length(&s, f);
        let layers = s.layers();
        // Radial load per unit strand length of each layer at strain eps (N/m).
        let load = |l: &strand_core::HelixLayer| {
            let (a, w) = (l.lay_angle(), &l.spec.wire);
            let tension = w.material.youngs_modulus * w.area() * a.cos().powi(2) * eps;
            l.wires() as f64 * tension * (a.sin().powi(2) / l.radius) / a.cos()
        };
        let sinks: Vec<f64> = (0..2)
            .map(|j| {
                let carried: f64 = layers[j..].iter().map(load).sum();
                let per_strand =
                    k[j].unwrap() * layers[j].wires() as f64 / layers[j].lay_angle().cos();
                carried / per_strand
            })
            .collect();
        for (i, l) in layers.iter().enumerate() {
            let sink: f64 = sinks[..=i].iter().sum();
            let a = l.lay_angle();
            let relief = a.sin().powi(2) * sink / l.radius / (a.cos().powi(2) * eps);
            assert!(relief <= f * (1.0 + 1e-12), "layer {i}: relief {relief:e}");
            if i == 1 {
                assert!(
                    (relief / f - 1.0).abs() < 1e-12,
                    "layer {i}: relief {relief:e}"
                );
            }
        }
    }
}
