//! Newton's iteration of a generalized-alpha step: modified Newton on the kept, co-rotated
//! iteration matrix, with the secant acceleration and the line search of the stick/slip laws;
//! each correction is judged by [`super::convergence`].

use super::convergence::{Correction, Limits};
use super::{AlphaState, AlphaWork, Parameters, step_by};
use crate::beam::{Beam, Evaluation, PointState, Tangent};
use crate::dynamics::DynamicOptions;
use crate::measure::dot;

/// Why an iteration matrix is built ([`super::Rebuilds`]).
#[derive(Clone, Copy)]
enum Why {
    StepSize,
    SlowStep,
    SlowIteration,
}

/// Largest secant factor g of the Newton acceleration in a generalized-alpha step (a larger
/// one extrapolates from two nearly equal corrections, where the iteration is not contracting).
const MAX_SECANT: f64 = 10.0;

/// Iterates from the predicted state `st` to the step's solution: the accepted iterate's
/// evaluation (`None` when Newton did not converge within `opts.max_iterations` or
/// diverged), and the iterations made.
pub(super) fn solve(
    beam: &Beam,
    opts: &DynamicOptions,
    p: &Parameters,
    limits: &Limits,
    st: &mut AlphaState,
    w: &mut AlphaWork,
    pts_new: &mut [PointState],
) -> (Option<Evaluation>, usize) {
    let Parameters {
        beta_p, gamma_p, h, ..
    } = *p;
    let nf = beam.dofs();
    let linear = beam.law().is_linear();
    // Modified Newton: the factorized iteration matrix S = beta' M + K is kept across
    // iterations and steps and rebuilt when the step size changes or a correction shrinks by
    // less than `opts.refresh`; every force evaluation is exact, so the converged state is the
    // same as with full Newton. With a linear law the kept matrix is the exact tangent, also
    // turned node by node with the strand since it was built (`dq = R S^-1 R^T r`, module
    // `corotation`), and rebuilt at a step's start when the last step's final contraction was
    // slower than `opts.rebuild_rate`. With the stick/slip laws the matrix is the symmetric
    // one of [`Tangent::Iteration`] (LDL^T; no slower to converge than the exact tangent on
    // the section-3 pendulum), turned only while the nodes turn together
    // ([`Corotation::turns_together`]): where the strand bends or chatters under the kept
    // matrix (`long-run-100s` of `cargo xtask hard`, the soft Fig. 8 pendulum on 8 elements)
    // turning every node by its own slope took 60 % more iterations and twice the matrices
    // (2,100,007 and 475,770 against 1,313,426 and 222,357; one turn for the whole strand,
    // that of its mean slope, 1,768,053 and 374,359), and turning only coherent turns
    // 1,336,599 and 231,069 (all without the secant acceleration below). On the section-3
    // pendulum the turned matrix saves the `continuous` law iterations and matrices (no turn,
    // every node, coherent turns: 4727 (612), 4210 (380), 4489 (467), again without the
    // acceleration) and the hysteretic law next to none (4320 (770), 4304 (695), 4292 (698)).
    let tangent = if linear {
        Tangent::FrozenMeans
    } else {
        let unloading = if beam.law().kind().has_state() {
            opts.unloading
        } else {
            0.0
        };
        Tangent::Iteration { unloading }
    };
    let estimate = !beam.law().kind().has_state();
    let mut iterations = 0;
    let mut outcome = None;
    let mut fresh = w.factor_h != h || w.stale;
    // What a matrix built now is counted as (`Rebuilds`).
    let mut why = if w.factor_h != h {
        Why::StepSize
    } else {
        Why::SlowStep
    };
    w.stale = false;
    // A strand of several layers with a stick/slip law keeps a fresh matrix whose correction
    // still shrank by less than `opts.refresh` (below).
    let keep_slow_fresh = opts.keep_slow_fresh && !linear && beam.law().layer_count() > 1;
    let mut prev = f64::INFINITY;
    let mut full_step = true;
    let mut history = false;
    let mut ev = w.evaluate(beam, st, pts_new, fresh.then_some(tangent));
    iterations += 1;
    while let Some(e) = ev {
        if fresh {
            w.k.add_scaled(beta_p, beam.mass());
            w.factorizations += 1;
            match why {
                Why::StepSize => w.rebuilds.step_size += 1,
                Why::SlowStep => w.rebuilds.slow_step += 1,
                Why::SlowIteration => w.rebuilds.slow_iteration += 1,
            }
            if !w.solver.factorize(&w.k) {
                w.factor_h = 0.0;
                break;
            }
            w.factor_h = h;
            w.rot.reset(&st.q);
        } else {
            w.rot.update(&st.q);
            if !linear && !w.rot.turns_together() {
                w.rot.clear();
            }
        }
        w.dq.copy_from_slice(&w.r);
        w.rot.apply(&mut w.dq, true);
        w.solver.solve(&mut w.dq);
        w.rot.apply(&mut w.dq, false);
        if w.matrix_scale != 1.0 {
            for d in &mut w.dq {
                *d /= w.matrix_scale;
            }
        }
        let dn = w.lengths.displacement(&w.dq);
        if !dn.is_finite() || dn > beam.length() {
            // Diverged: the step is retried in halves, with a fresh matrix.
            w.factor_h = 0.0;
            break;
        }
        // The Newton decrement r . dq (J): the drop of the step's incremental potential the
        // correction promises (for a linear problem, twice its distance to the minimum), and
        // the slope of that potential along -dq.
        let decrement = dot(&w.r, &w.dq);
        // The same correction in the inertia term's metric alone, beta' dq^T M dq (J).
        let inertial = {
            beam.vector_mass().mul_vec(&w.dq, &mut w.mv);
            beta_p * dot(&w.dq, &w.mv)
        };
        let correction = Correction {
            dn,
            prev,
            estimate: estimate && full_step,
            inertial,
            force: w.lengths.force(&w.r),
        };
        let theta = dn / prev;
        // The change of the ledger's total energy that the correction makes (J). The iterate's
        // velocity and acceleration follow q (v = v* + gamma' (q - q*), q'' likewise with
        // beta'), so the total, 1/2 v^T M v - Q_g . q + elastic, has the gradient
        // gamma' M v - Q_g + Q_e = gamma' M v - M q'' + r, and the correction -dq changes it by
        // (gamma' v - q'') . M dq + r . dq to first order; beta' dq^T M dq bounds the second
        // order (the kinetic part, gamma'^2/2 dq^T M dq, is half of it at spectral radius 0.9)
        // and guards a matrix that is not positive definite (a strand in compression, a matrix
        // kept from another state), whose decrement can be small for a large correction.
        let ledger = || {
            let first: f64 = st
                .vf
                .iter()
                .zip(&st.acc)
                .zip(&w.mv)
                .map(|((v, a), m)| (gamma_p * v - a) * m)
                .sum();
            (first + decrement).abs() + inertial
        };
        let converged = correction.converged(limits, ledger);
        step_by(beam, st, &w.dq, 1.0, gamma_p, beta_p);
        // The residual test holds for a correction within round-off too: with a matrix far
        // stiffer than the tangent, a stalled iteration's corrections are that small.
        if (converged || w.lengths.within_round_off(beam, &w.dq, &st.q, 0.0))
            && correction.answers_its_residual(limits)
        {
            if linear && !fresh && theta.is_finite() && theta > opts.rebuild_rate {
                w.stale = true;
            }
            outcome = Some(e);
            break;
        }
        if iterations >= opts.max_iterations {
            break;
        }
        // Secant acceleration of a slow kept matrix (Anderson mixing of depth one, Walker and
        // Ni 2011), for the stick/slip laws. Their matrix is stiffer than their tangent where
        // wires slip (the hysteretic law's `unloading` share: on the section-3 pendulum, with
        // no wire changing state, the corrections after a fresh matrix shrink by 0.48 per
        // iteration at 0.25, 0.24 at 0.1, 0.004 at 0), so modified Newton contracts linearly,
        // by theta per iteration.
        // Two corrections of the same matrix, c_k and c_{k-1}, with the move between their
        // iterates, d_{k-1}, give the secant estimate of the step to the root: the iterate
        // moves by -(c_k - g u), u = d_{k-1} + c_k - c_{k-1}, with g minimizing
        // |c_k - g (c_k - c_{k-1})|, when theta > 0.1 and the incremental potential still
        // falls along it (r . (c_k - g u) > 0). On the section-3 pendulum at 1e-3 s steps:
        // continuous 4489 (467) -> 4250 (474) iterations (matrices), hysteretic 4292 (698) ->
        // 4209 (602); on `long-run-100s`'s pendulum with either law, 20 s: 8.5 and 7.1 %
        // fewer iterations. The convergence tests above always judge the plain correction.
        let mut secant = None;
        if !linear && history && !fresh && theta.is_finite() && theta > 0.1 {
            let (mut dd, mut cd) = (0.0, 0.0);
            for i in 0..nf {
                let d = w.dq[i] - w.last_correction[i];
                dd += d * d;
                cd += w.dq[i] * d;
                w.secant[i] = w.last_move[i] + d;
            }
            let g = cd / dd;
            if g.is_finite() && g.abs() < MAX_SECANT {
                let falls = decrement - g * dot(&w.r, &w.secant);
                secant = (falls > 0.0).then_some((g, falls));
            }
        }
        if !linear {
            // The plain correction, before any secant step changes `dq`.
            w.last_correction.copy_from_slice(&w.dq);
        }
        let mut slope = decrement;
        if let Some((g, falls)) = secant {
            step_by(beam, st, &w.secant, -g, gamma_p, beta_p);
            for (d, u) in w.dq.iter_mut().zip(&w.secant) {
                *d -= g * u;
            }
            slope = falls;
        }
        let accelerated = secant.is_some();
        history = !linear;
        // Rebuild the iteration matrix when the last correction shrank by less than
        // `opts.refresh`: a stale tangent converges linearly at about that rate.
        let built_here = fresh;
        fresh = dn > opts.refresh * prev;
        // Unless the matrix was built at this very iterate: then it is not stale but stiffer
        // than the tangent, and one built at the next iterate is no better. On a strand of
        // several layers the slipping wires' share of their stick stiffness
        // (`opts.unloading`) is many times their tangent, K_max - K_min being large against
        // K_min (the Cardinal span of the Performance page: with a matrix built at every
        // iterate, corrections shrank by 0.90 per iteration, the slipping layers' share about
        // ten times the tangent), and such a tail cost a matrix per iteration. The matrix is
        // kept and the secant acceleration below takes the iteration on (0.5 s of that span:
        // 3393 -> 3015 iterations, 1467 -> 693 matrices). A 1+m strand keeps the rule it had.
        if fresh && built_here && keep_slow_fresh {
            fresh = false;
            w.rebuilds.kept_slow_fresh += 1;
        }
        if fresh {
            why = Why::SlowIteration;
        }
        prev = dn;
        ev = w.evaluate(beam, st, pts_new, fresh.then_some(tangent));
        iterations += 1;
        // After a secant step the next correction's ratio to this one is no contraction rate.
        full_step = !accelerated;
        if history {
            w.last_move.copy_from_slice(&w.dq);
        }
        if fresh {
            history = false;
        }
        // Line search: where the potential rises again at the full correction (a stick/slip
        // kink was overshot: the slope -r . dq changed sign), step back to the root of the
        // slope's secant.
        let rises = dot(&w.r, &w.dq);
        if ev.is_some() && slope > 0.0 && rises < 0.0 {
            let alpha = slope / (slope - rises);
            if alpha < opts.backtrack && iterations < opts.max_iterations {
                step_by(beam, st, &w.dq, alpha - 1.0, gamma_p, beta_p);
                for d in &mut w.last_move {
                    *d *= alpha;
                }
                ev = w.evaluate(beam, st, pts_new, fresh.then_some(tangent));
                iterations += 1;
                full_step = false;
            }
        }
    }
    (outcome, iterations)
}
