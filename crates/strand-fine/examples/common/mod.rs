//! What the settle examples share: the Fig. 7 fine model and the line that reports a settled
//! solve.

use nalgebra::Vector3;
use strand_core::{Strand, StrandSpec};
use strand_fine::{ContactOptions, Discretisation, FineModel, SettledReport, Support};

/// The Fig. 7 fine model: the Table 1 strand, 0.4 m, clamped at its start and free at its
/// end, `segments` segments a wire (77: the figure's), gravity `g` (m/s^2) along -y, and the
/// default contacts.
pub fn fig7_model(g: f64, segments: usize) -> FineModel {
    let strand = Strand::new(StrandSpec::paper(0.4, 2.0e8, 7801.0)).unwrap();
    let mut m = FineModel::from_strand(
        &strand,
        Discretisation {
            core_segments: segments,
            wire_segments: segments,
        },
        Support::Clamped,
        Support::Free,
    );
    m.gravity = Vector3::new(0.0, -g, 0.0);
    m.add_contacts(&strand, &ContactOptions::default());
    m
}

/// The motion's steps and time and Newton's polish of a settled solve `r`, as the settle
/// examples print them.
#[allow(dead_code)]
pub fn settled_line(r: &SettledReport) -> String {
    format!(
        "{} steps of {:.4e} s, {:.3} s, Newton {} it in {} attempts, residual {:.2e}",
        r.settle.steps, r.settle.time_step, r.settle.time, r.iterations, r.attempts, r.residual,
    )
}
