//! Statics with contacts and friction ([`strand_fine::solve_settled`]): a short Table 1
//! strand clamped horizontally under gravity reaches rest within the stated residual, and its
//! tip deflection lies between those of the all-slip (K_min) and all-stick (K_max) elastica
//! (constant EI, inextensible: the independent shooting solution), up to the segment chain's
//! own discretisation error.

use nalgebra::Vector3;
use strand_core::{BaseStiffness, Strand, StrandSpec};
use strand_elastica::{Cantilever, ConstantEi, Options, solve};
use strand_fine::{
    ContactOptions, Discretisation, FineModel, SettledOptions, Support, solve_settled,
};

/// `strand` as 12 segments a wire with the default contacts, clamped at one end and free at
/// the other, under gravity `g` (m/s^2) along -y.
fn clamped_under_gravity(strand: &Strand, g: f64) -> FineModel {
    let mut m = FineModel::from_strand(
        strand,
        Discretisation {
            core_segments: 12,
            wire_segments: 12,
        },
        Support::Clamped,
        Support::Free,
    );
    m.add_contacts(strand, &ContactOptions::default());
    m.gravity = Vector3::new(0.0, -g, 0.0);
    m
}

#[test]
fn short_strand_settles_between_the_all_slip_and_all_stick_elastica() {
    let (length, g) = (0.1, 8.0);
    let strand = Strand::new(StrandSpec::paper(length, 2.0e8, 7801.0)).unwrap();
    let m = clamped_under_gravity(&strand, g);
    let mut state = m.rest_state();
    let t = std::time::Instant::now();
    let opts = SettledOptions::default();
    let r = solve_settled(&m, &mut state, &opts, &mut |_, _, _| {}).unwrap();
    let tip = *m.core_centreline(&state).last().unwrap();
    println!(
        "settled in {:.3} s of motion ({} steps), Newton {:?} iterations, residual {:.2e} \
         (tolerance {:.0e}); tip ({:.6}, {:.6}) m; {:.1} s",
        r.settle.time,
        r.settle.steps,
        r.polish.map(|p| p.iterations),
        r.residual,
        r.tolerance,
        tip.x,
        tip.y,
        t.elapsed().as_secs_f64()
    );
    assert!(
        r.residual <= r.tolerance.max(1e-6),
        "residual {:e}",
        r.residual
    );
    let q = strand.mass_per_length() * g;
    let drop = |ei: f64| {
        let s = solve(
            &Cantilever::new(length, q),
            &ConstantEi::new(ei),
            &Options::default(),
        )
        .unwrap();
        -s.tip_displacement()[1]
    };
    let (stick, slip) = (
        drop(strand.max_bending_stiffness(BaseStiffness::default())),
        drop(strand.min_bending_stiffness(BaseStiffness::default())),
    );
    // A chain of rigid segments deflects more than the continuum of the same stiffness, at
    // second order in the segment length: 1.00e-2, 2.52e-3 of q L^4 / 8 EI at 10, 20 segments
    // (tests/cantilever.rs), so (10/12)^2 1.0 % at 12. The all-slip bound of this chain is the
    // elastica's drop with that allowance (measured: 9e-4 beyond Costello's K_min elastica).
    let chain = 1.0e-2 * (10.0f64 / 12.0).powi(2);
    println!(
        "tip drop {:.6} m; all-stick {stick:.6} m, all-slip {slip:.6} m ({:+.1e}; the chain's \
         allowance {chain:.1e})",
        -tip.y,
        -tip.y / slip - 1.0
    );
    assert!(-tip.y > stick && -tip.y < slip * (1.0 + chain));
}

/// Convergence with a scale, with contacts: the short strand under its weight times 1e-12,
/// 1e-6, 1e-3 and 1e3 settles and converges (the settle's duration set by the strand's first
/// bending frequency when gravity's is lower; the residual against the loads in play, or the
/// Newton correction within the round-off of the positions), and its tip drops between the
/// linear deflections q L^4 / (8 K) of the all-stick (K_max) and all-slip (K_min) closed
/// forms (the all-slip one with the chain's discretisation allowance); without friction it
/// is the all-slip one within that allowance. Without friction the deflection is linear in
/// the load: the drops per unit load at 1e-6 and 1e-3 agree within 1e-3 (the geometric
/// nonlinearity at 1e-3 is of order (drop / L)^2, 2e-8). At 1e3 the strand hangs like a
/// string, its drop within L plus the core-alone stretch and L minus the root's bending length.
#[test]
fn tiny_loads_settle_between_the_stick_and_slip_stiffness() {
    let (length, g) = (0.1, 8.0);
    for mu in [0.0, 0.3] {
        let mut spec = StrandSpec::paper(length, 2.0e8, 7801.0);
        spec.friction = mu;
        let strand = Strand::new(spec).unwrap();
        let mut per_load = Vec::new();
        for factor in [1e-12, 1e-6, 1e-3, 1e3] {
            let m = clamped_under_gravity(&strand, g * factor);
            let mut state = m.rest_state();
            let r = solve_settled(
                &m,
                &mut state,
                &SettledOptions::default(),
                &mut |_, _, _| {},
            )
            .unwrap();
            let drop = -m.core_centreline(&state).last().unwrap().y;
            let q = strand.mass_per_length() * g * factor;
            let linear = |k: f64| q * length.powi(4) / (8.0 * k);
            let (stick, slip) = (
                linear(strand.max_bending_stiffness(BaseStiffness::default())),
                linear(strand.min_bending_stiffness(BaseStiffness::default())),
            );
            println!(
                "mu {mu}, weight x {factor:e}: {} steps ({:.3} s), Newton {:?} in {} attempts; \
                 drop {drop:.6e} m = {:.4} of the all-slip drop (all-stick {:.4})",
                r.settle.steps,
                r.settle.time,
                r.polish.map(|p| p.iterations),
                r.attempts,
                drop / slip,
                stick / slip
            );
            assert!(r.polish.is_some(), "Newton converged");
            if factor > 1.0 {
                // Hanging like a string: the drop exceeds L by no more than the stretch if
                // the core alone carried the weight (q L^2 / (2 E_c A_c)), and falls short
                // of L by no more than twice the root's bending length sqrt(K_max / (q L)).
                let core = strand.core();
                let stretch =
                    q * length * length / (2.0 * core.material.youngs_modulus * core.area());
                let bend =
                    (strand.max_bending_stiffness(BaseStiffness::default()) / (q * length)).sqrt();
                println!(
                    "  hanging: drop - L {:.3e} m (stretch bound {stretch:.3e}, bending length {bend:.3e})",
                    drop - length
                );
                assert!(drop <= length + stretch && drop >= length - 2.0 * bend);
                continue;
            }
            // The 12-segment chain's own discretisation error (see the test above).
            let chain = 1.0e-2 * (10.0f64 / 12.0).powi(2);
            assert!(
                drop > stick && drop < slip * (1.0 + chain),
                "between the closed forms"
            );
            if mu == 0.0 {
                // Frictionless, every wire slips: the drop is the all-slip closed form's, up
                // to the chain's allowance and the round-off of positions of order L (a
                // segment's worth of ulps per segment along the chain).
                let roundoff = 12.0 * f64::EPSILON * length;
                assert!(
                    (drop - slip).abs() <= chain * slip + roundoff,
                    "frictionless drop {drop:e} m against q L^4 / (8 K_min) = {slip:e} m"
                );
            }
            per_load.push(drop / factor);
        }
        if mu == 0.0 {
            assert!((per_load[1] / per_load[2] - 1.0).abs() < 1e-3);
        }
    }
}
