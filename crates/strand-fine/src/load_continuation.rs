//! Quasi-static load continuation of the fine statics: the load ramped from the straight
//! strand in load steps, each solved by Newton ([`crate::solve_static`]: adaptive increments
//! halved on failure, line search, optional penalty stages), the contact histories committed
//! after every converged step, so that friction follows the ramp of the load. A study option
//! of [`crate::solve_settled`] ([`crate::SettledOptions::load_continuation`], off by default):
//! where it reaches full load it replaces the damped motion; where it fails, the state it
//! started from is handed back whole (poses, velocities, contact histories) and the settle
//! runs as without it.
//!
//! Where it works and where not (the study `examples/load_continuation.rs`; performance page,
//! "A quasi-static load continuation from the straight strand"): on the short Table 1 strand
//! (0.1 m, 12 segments a wire, tip drop 3 % of the length) it reaches full load, without
//! friction on the settle's own equilibrium (3.4e-13 m at the tip) and with friction on a
//! static state 8.7e-7 m from the settle's, with 0.94 times its instructions. On the
//! Fig. 7 strand (0.4 m, 77 segments a wire, tip drop 92 % of the length) it did not reach full
//! load in any variant tried (0-3 penalty stages, 40-200 Newton iterations a load step, with
//! and without friction): stalled at 0.01 to 0.33 of the load, or, at 200 iterations a step,
//! 0.934 after 117 s of CPU, two and a half times the settle's whole run. Contacts carrying
//! only the wires' weight sit within nanometres of zero gap while a Newton step of the large
//! deflection moves the wires by micrometres.

use crate::model::{FineModel, ModelState};
use crate::statics::{StaticOptions, StaticReport, solve_static_with_progress};

/// Outcome of a load continuation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadContinuationReport {
    /// It reached full load within the tolerance.
    pub converged: bool,
    /// Load factor of the last converged load step (-).
    pub load_factor: f64,
    /// Converged load steps.
    pub load_steps: usize,
}

/// Runs the load continuation of `options` on `model` from `state`. Converged: the
/// equilibrium at full load in `state` and Newton's report. Failed: `state` as it was
/// given.
pub fn load_continuation(
    model: &FineModel,
    state: &mut ModelState,
    options: &StaticOptions,
) -> (LoadContinuationReport, Option<StaticReport>) {
    let start = state.clone();
    let (mut load_factor, mut load_steps) = (0.0, 0);
    let result = solve_static_with_progress(model, state, options, &mut |lambda| {
        load_factor = lambda;
        load_steps += 1;
    });
    let converged = result.is_ok();
    if !converged {
        state.clone_from(&start);
    }
    (
        LoadContinuationReport {
            converged,
            load_factor,
            load_steps,
        },
        result.ok(),
    )
}
