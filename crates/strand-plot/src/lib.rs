//! Charts of strand results as PNG and SVG, with an embedded font (DejaVu Sans) so that text
//! renders on a machine without system fonts: the chart primitives ([`chart`]) used by the
//! reports of `cargo xtask`, and the charts of a run ([`plot_run`], `strand run --plot`).

pub mod chart;
pub mod cycle;
mod run_charts;
pub mod table;

pub use chart::{Chart, Mark, PlotError, Series, color, range, register_fonts, save, save_grid};
pub use run_charts::plot_run;
