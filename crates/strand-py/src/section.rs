//! `Scene.section`: NumPy arrays in and out of [`strand_scene::section_batch`].

use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use strand_core::SectionLaw;
use strand_scene::section_batch::{PlanarArrays, evaluate_planar};

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
    let len = e.len();
    let mut v: [Vec<f64>; 6] = std::array::from_fn(|_| vec![0.0; len]);
    let mut trial = vec![0.0; len * law.state_len()];
    {
        let [a, b, c, d, f, g] = &mut v;
        let out = PlanarArrays {
            axial_force: a,
            moment: b,
            tangent: c,
            energy: d,
            slip_work: f,
            slipping: g,
            state: &mut trial,
        };
        evaluate_planar(law, e, k, at, s, out).map_err(|e| PyValueError::new_err(e.0))?;
    }
    let [a, b, c, d, f, g] = v;
    PyTuple::new(
        py,
        [
            a.into_pyarray(py),
            b.into_pyarray(py),
            c.into_pyarray(py),
            d.into_pyarray(py),
            f.into_pyarray(py),
            g.into_pyarray(py),
            trial.into_pyarray(py),
        ],
    )
}
