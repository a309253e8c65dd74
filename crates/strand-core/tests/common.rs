//! Strands shared by the core's tests.
#![allow(dead_code)]

use strand_core::StrandSpec;

/// The paper's Table 1 strand (SPEC 8).
pub fn table1() -> StrandSpec {
    StrandSpec::paper(0.4, 2.0e8, 7801.0)
}
