//! Which random scenes must solve: the predicate the runner's property test
//! (`tests/runner_property.rs`) asserts and the `must_solve_search` example searches with, and
//! the strand family's geometry and load estimate it rests on.

use strand_ancf::dynamics::stable_step;
use strand_core::BaseStiffness;
use strand_scene::{Analysis, BeamModelKind, IntegratorKind, Scene, SupportKind, build_beam};

/// Largest wire diameter (relative to the core's) at which `wires` wires at `lay_deg` fit
/// around the core without touching: adjacent wires' centres are `2 pi R / m` apart along the
/// circle, `2 R sin(pi / m)` in a cross-section, and a wire's cross-section across the lay is
/// its diameter over cos(alpha). For one wire, its own next turn (a pitch away) is the
/// neighbour, which the 2-wire bound covers with margin.
pub fn wire_fit(wires: u32, lay_deg: f64) -> f64 {
    let c = lay_deg.to_radians().cos();
    let s = if wires <= 2 {
        1.0
    } else {
        (std::f64::consts::PI / wires as f64).sin()
    };
    // (D/2 + d/2) s >= (d/2) / c  <=>  d/D <= s c / (1 - s c)
    let sc = (s * c).min(0.95);
    sc / (1.0 - sc)
}

/// Euclidean length of a 3-vector.
fn norm(v: &[f64; 3]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Linear cantilever deflection of the strand under the scene's loads (m): q L^4 / 8 EI +
/// P L^3 / 3 EI with q the weight per length (N/m), P the sum of the point forces' magnitudes
/// (N), all taken across the strand, and EI the smallest bending stiffness any base model
/// gives (N m^2).
pub fn cantilever_deflection(scene: &Scene) -> f64 {
    let strand = &scene.strand;
    let length = strand.length();
    let ei = [
        BaseStiffness::Costello,
        BaseStiffness::Foti,
        BaseStiffness::Papailiou,
        BaseStiffness::Paper,
    ]
    .map(|b| strand.min_bending_stiffness(b))
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    let q = strand.mass_per_length() * norm(&scene.gravity);
    let p: f64 = scene.point_forces.iter().map(|f| norm(&f.force)).sum();
    q * length.powi(4) / (8.0 * ei) + p * length.powi(3) / (3.0 * ei)
}

/// Why `model`'s run of `scene` must end `ok`, if it must.
///
/// * The strand is a beam model's (the fine model's contacts are left to the
///   property test's share of runs that end `ok`).
/// * It is held: clamped at an end, or pinned at both, so that no rigid motion takes it far
///   from the reference, and no support moves.
/// * It is slender (at least ten diameters long), the premise of a beam model.
/// * Its load bends it by at most a tenth of its length in linear theory, as a cantilever
///   (q L^4 / 8 EI + P L^3 / 3 EI with the smallest bending stiffness any law gives, all of
///   gravity and every point force taken across the strand): the geometric nonlinearity
///   changes its forces by about 1 %, so that Newton converges from the reference in one load
///   step, and an axial load stays below buckling (q L^3 <= 0.8 EI against 7.8 EI).
/// * In statics that is all. In dynamics it starts from rest, its run is within the step
///   limit, and its step is at or below the stable step the program estimates at the
///   reference: Verlet's own choice (0.9 of it) or a given step at most that; generalized-alpha
///   at most the estimate itself, where the predictor resolves every mode and Newton starts
///   close to the solution. The stable step of the loaded strand differs from the estimate by
///   the same 1 %, within Verlet's 10 % margin.
pub fn must_solve(scene: &Scene, model: &str) -> Result<String, &'static str> {
    let which = match model {
        "equivalent" => BeamModelKind::Equivalent,
        "traditional" => BeamModelKind::Traditional,
        _ => return Err("the fine model"),
    };
    let at = |kind: SupportKind| scene.supports.iter().filter(|s| s.kind == kind).count();
    let held = at(SupportKind::Clamped) > 0 || at(SupportKind::Pinned) == 2;
    if !held {
        return Err("not held");
    }
    if scene.supports.iter().any(|s| s.motion.is_some()) {
        return Err("a moving support");
    }
    let strand = &scene.strand;
    let length = strand.length();
    let outer = 0.5 * strand.outer_diameter();
    if length < 20.0 * outer {
        return Err("not slender");
    }
    let deflection = cantilever_deflection(scene);
    if deflection.is_nan() || deflection > 0.1 * length {
        return Err("a large load");
    }
    let dy = match scene.analysis {
        Analysis::Static { .. } => {
            return Ok(format!(
                "statics of a held strand bent by {:.1e} of its length",
                deflection / length
            ));
        }
        Analysis::Dynamic(dy) => dy,
    };
    if norm(&scene.velocity) > 0.0 || norm(&scene.angular_velocity) > 0.0 {
        return Err("not from rest");
    }
    let beam = build_beam(scene, which).map_err(|_| "no beam")?;
    let stable = stable_step(&beam).map_err(|_| "no stable step")?;
    let (step, limit) = match (dy.integrator, dy.time_step) {
        (IntegratorKind::Verlet, None) => (0.9 * stable, 0.9 * stable),
        (IntegratorKind::Verlet, Some(h)) => (h, 0.9 * stable),
        (IntegratorKind::GeneralizedAlpha, h) => (h.ok_or("no step")?, stable),
    };
    let steps = (dy.duration / step).ceil();
    if step > limit {
        return Err("a step above the stable one");
    }
    if steps > scene.max_steps as f64 {
        return Err("above the step limit");
    }
    Ok(format!(
        "dynamics from rest of a held strand bent by {:.1e} of its length, {steps} steps of \
         {:.2} of the stable step",
        deflection / length,
        step / stable
    ))
}
