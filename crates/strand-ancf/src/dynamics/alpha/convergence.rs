//! When Newton's iterate of a generalized-alpha step is accepted: its trajectory and its
//! energy ledger are converged ([`Correction::converged`]), and the correction answers the
//! residual it was computed from ([`Correction::answers_its_residual`]).

/// The limits of a step's convergence test.
#[derive(Debug, Clone, Copy)]
pub(super) struct Limits {
    /// Largest correction or error estimate of a converged trajectory (m).
    pub(super) tol: f64,
    /// Energy of a rigid translation of the strand by `tol` in the inertia term's metric (J).
    pub(super) energy_tol: f64,
    /// What the step may leave in the energy ledger (J).
    pub(super) ledger_tol: f64,
    /// Upper bound of the stiffness of a node of the step's exact iteration matrix
    /// `beta' M + K` (N/m): the force a correction of the node by 1 m can answer at most.
    pub(super) stiffness: f64,
    /// Round-off of a node's residual force (N).
    pub(super) force_floor: f64,
}

impl Limits {
    /// The largest residual force at a node (N) that an iterate whose error is `dn` (m), or
    /// `tol` if larger, can leave.
    ///
    /// The residual answers the iterate's error through the exact iteration matrix, `r = S e`,
    /// so `|r| <= lambda_max(S) |e|`, and a larger residual means an error above `|e|`
    /// whatever the correction says: with a matrix far stiffer than the tangent (kept from
    /// another state, or too stiff where wires slip), a stalled iteration's corrections are
    /// small while its residual is not. The error is the correction for a full Newton step,
    /// and for modified Newton contracting at theta the correction over 1 - theta, at most
    /// twice it where the matrix is kept (`refresh` 0.5); a node's error measured as a
    /// Euclidean length against Gershgorin row sums of its components costs up to sqrt(3)
    /// more in 3D: 4 in all. The bound is necessary, not sufficient: a stall whose residual
    /// stays within it passes.
    pub(super) fn residual(&self, dn: f64) -> f64 {
        4.0 * self.stiffness * dn.max(self.tol) + self.force_floor
    }
}

/// One Newton correction as the convergence test sees it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Correction {
    /// Largest displacement of the correction (m).
    pub(super) dn: f64,
    /// The last full correction's (m; infinite at the first).
    pub(super) prev: f64,
    /// Whether the error left after the correction may be estimated from the contraction
    /// rate `dn / prev` (a full step of a law without slip state).
    pub(super) estimate: bool,
    /// The correction in the inertia term's metric, `beta' dq^T M dq` (J).
    pub(super) inertial: f64,
    /// Largest node force of the residual the correction answers (N).
    pub(super) force: f64,
}

impl Correction {
    /// Whether the trajectory and the energy ledger are converged; `ledger` gives the change
    /// of the ledger's total energy the correction makes (J), evaluated only when the
    /// trajectory is.
    pub(super) fn converged(&self, limits: &Limits, ledger: impl FnOnce() -> f64) -> bool {
        let Correction {
            dn,
            prev,
            estimate,
            inertial,
            ..
        } = *self;
        // Converged when the trajectory and the energy ledger both are.
        //
        // The trajectory: this correction, or the error left after it, is below `tol`. With
        // full steps contracting at the rate theta = dn / prev, the corrections still to come
        // add up to about dn theta / (1 - theta) (the estimate of Hairer and Wanner, IV.8),
        // which accepts a fast-converging iterate one iteration earlier. Not for a law with
        // slip state: the committed trial state belongs to the forces before this correction,
        // so the correction itself is the error (and its Newton path, which decides where the
        // slip is committed, is left as it was). Or the correction's root mean square over the
        // mass is below `tol` (`inertial <= energy_tol`): the displacement is a largest value,
        // and a correction of one wire's slip state near the free end, carrying almost no
        // mass, would hold it up.
        //
        // The ledger: the error left in the step's state, delta (the correction itself, or
        // theta / (1 - theta) of it), changes the total energy by about that share of
        // `ledger()` (below), and the later steps carry the changed total on: the integrator
        // conserves the energy it is given, so each step's error stays in the balance. With
        // gamma' ~ 1/h the same delta costs more energy the smaller the step, and the steps
        // are more: a tolerance on the correction's size (or its Newton decrement against
        // beta' m tol^2 ~ 1/h^2, the former test) leaves a balance error that grows as h
        // shrinks (on issue 16's tilted pendulum in its plane, 9.9e-5 and 4.0e-4 of the
        // largest kinetic energy at 0.25 and 0.125 ms, where the integrator's own is 2.0e-5
        // and 3.0e-6). Bounding each step's by `ledger_tol` = `opts.ledger` E h / T bounds
        // the run's, T / h steps of it, by `opts.ledger` E at every step size (a fixed share,
        // not one falling with h as the integrator's error does: below the step where that
        // error is `opts.ledger`, only the errors' partial cancelling keeps Newton's share
        // small). A correction within the round-off of its coordinates is accepted whatever
        // it changes: no iteration can make it smaller.
        //
        // The ledger uses the forces before this last correction, which moved q by about
        // `tol` and the elastic energy by O(tol |Q|): an error of that step's report alone,
        // not carried on.
        let theta = dn / prev;
        let contracting = estimate && prev.is_finite() && theta < 1.0;
        let (left, share) = if contracting {
            let share = theta / (1.0 - theta);
            (dn * share, share)
        } else {
            (f64::INFINITY, 1.0)
        };
        let trajectory = dn <= limits.tol || left <= limits.tol || inertial <= limits.energy_tol;
        trajectory && share * ledger() <= limits.ledger_tol
    }

    /// Whether the residual the correction answers is within what its size allows
    /// ([`Limits::residual`]).
    pub(super) fn answers_its_residual(&self, limits: &Limits) -> bool {
        self.force <= limits.residual(self.dn)
    }
}
