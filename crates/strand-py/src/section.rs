//! `Scene.section`: NumPy arrays in and out of [`strand_scene::section_batch`].

use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use strand_core::SectionLaw;
use strand_scene::section_batch::{PlanarOutputs, evaluate_planar};

fn slice<'a>(name: &str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| PyValueError::new_err(format!("{name}: a contiguous float64 array")))
}

/// Evaluates `law` at every point; returns (axial_force, moment, tangent, energy, slip_work,
/// slipping, state) as new arrays, `state` flat (points x state length).
pub fn evaluate<'py>(
    py: Python<'py>,
    law: &SectionLaw,
    strain: &PyReadonlyArray1<'py, f64>,
    curvature: &PyReadonlyArray1<'py, f64>,
    x: &PyReadonlyArray1<'py, f64>,
    state: &PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyTuple>> {
    let (e, k, at, s) = (
        slice("strain", strain)?,
        slice("curvature", curvature)?,
        slice("x", x)?,
        slice("state", state)?,
    );
    let mut out = PlanarOutputs::zeros(e.len(), law.state_len());
    evaluate_planar(law, e, k, at, s, out.arrays()).map_err(|e| PyValueError::new_err(e.0))?;
    let PlanarOutputs {
        axial_force,
        moment,
        tangent,
        energy,
        slip_work,
        slipping,
        state,
    } = out;
    PyTuple::new(
        py,
        [
            axial_force.into_pyarray(py),
            moment.into_pyarray(py),
            tangent.into_pyarray(py),
            energy.into_pyarray(py),
            slip_work.into_pyarray(py),
            slipping.into_pyarray(py),
            state.into_pyarray(py),
        ],
    )
}
