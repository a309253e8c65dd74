//! `strand._strand`: the Rust side of the `strand` Python package. It wraps the same library
//! code as the `strand` command: the scene validator of `strand-scene` (errors raise
//! `strand.SceneError` with the field path), its runner (`strand run`), the section law of
//! `strand-core` (`strand section`) and the virtual bending test (`strand bend`). The
//! high-level API (`strand.run`, `strand.section`, `strand.sweep`) is the Python package
//! around it.

mod interrupt;
mod section;

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use strand_core::{LawKind, SectionLaw, SectionPoint, StrandSummary};
use strand_scene::{BendingOptions, RunOptions, Scene};

pyo3::create_exception!(
    strand,
    SceneError,
    PyValueError,
    "A scene the validator rejects. The message is the `strand` command's, naming the JSON \
     path of the fault (`strand.layers[0].lay_angle_deg: ...`); `field` holds that path."
);

/// The `SceneError` of `e`, with its field path as the attribute `field`.
fn scene_error(py: Python<'_>, e: strand_scene::SceneError) -> PyErr {
    let err = SceneError::new_err(e.to_string());
    if let Err(set) = err.value(py).setattr("field", e.path) {
        return set;
    }
    err
}

/// A section law by its scene-file name (`continuous`, `paper`, `hysteretic`, `constant`).
fn law_kind(name: &str) -> PyResult<LawKind> {
    serde_json::from_value(serde_json::Value::String(name.into())).map_err(|_| {
        PyValueError::new_err(format!(
            "law: unknown section law `{name}` (expected continuous, paper, hysteretic or constant)"
        ))
    })
}

/// A validated scene (the `strand` command's validator) and the section laws built from it.
#[pyclass(name = "Scene", module = "strand._strand", frozen)]
struct PyScene {
    scene: Scene,
    /// Section laws built so far, by kind: building one is far dearer than evaluating it.
    laws: Mutex<Vec<(LawKind, Arc<SectionLaw>)>>,
}

impl PyScene {
    fn law(&self, law: Option<&str>) -> PyResult<Arc<SectionLaw>> {
        let kind = law.map_or(Ok(self.scene.law), law_kind)?;
        let mut laws = self
            .laws
            .lock()
            .map_err(|_| PyRuntimeError::new_err("section law cache poisoned"))?;
        if let Some((_, l)) = laws.iter().find(|(k, _)| *k == kind) {
            return Ok(l.clone());
        }
        let l = Arc::new(SectionLaw::with_options(
            &self.scene.strand,
            kind,
            &self.scene.section,
        ));
        laws.push((kind, l.clone()));
        Ok(l)
    }
}

fn to_json<T: serde::Serialize>(v: &T) -> PyResult<String> {
    serde_json::to_string(v).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

#[pymethods]
impl PyScene {
    /// Parses and validates scene JSON; raises `SceneError` naming the field path.
    #[new]
    fn new(py: Python<'_>, text: &str) -> PyResult<Self> {
        let scene = Scene::parse(text).map_err(|e| scene_error(py, e))?;
        Ok(PyScene {
            scene,
            laws: Mutex::new(Vec::new()),
        })
    }

    /// Scene name.
    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    /// Strand length (m).
    #[getter]
    fn length(&self) -> f64 {
        self.scene.strand.length()
    }

    /// The scene's section law (its name).
    #[getter]
    fn law_name(&self) -> &'static str {
        self.scene.law.name()
    }

    /// The models the scene runs, in their order.
    #[getter]
    fn models(&self) -> Vec<&'static str> {
        let m = &self.scene.models;
        let named = [
            m.equivalent.is_some(),
            m.traditional.is_some(),
            m.fine.is_some(),
        ];
        strand_scene::MODEL_NAMES
            .iter()
            .zip(named)
            .filter_map(|(n, k)| k.then_some(*n))
            .collect()
    }

    /// The derived quantities `strand section` prints, as JSON (`StrandSummary`).
    fn summary_json(&self) -> PyResult<String> {
        to_json(&StrandSummary::new(&self.scene.strand, &self.scene.section))
    }

    /// Values of hysteretic state per point of `law` (0 for the laws without state).
    #[pyo3(signature = (law=None))]
    fn state_len(&self, law: Option<&str>) -> PyResult<usize> {
        Ok(self.law(law)?.state_len())
    }

    /// One point of the section law from a state without slip, as `strand section --json`
    /// prints it after the summary (`SectionPoint`), as JSON.
    #[pyo3(signature = (strain, curvature, at, law=None))]
    fn section_point_json(
        &self,
        strain: f64,
        curvature: f64,
        at: f64,
        law: Option<&str>,
    ) -> PyResult<String> {
        let kind = law.map_or(Ok(self.scene.law), law_kind)?;
        let p = SectionPoint::new(
            &self.scene.strand,
            kind,
            &self.scene.section,
            strain,
            curvature,
            at,
        );
        to_json(&p)
    }

    /// The section law over 1-D float64 arrays of equal length (see `strand.section`):
    /// returns (axial_force, moment, tangent, energy, slip_work, slipping, state).
    #[pyo3(signature = (strain, curvature, x, state, law=None))]
    fn section<'py>(
        &self,
        py: Python<'py>,
        strain: numpy::PyReadonlyArray1<'py, f64>,
        curvature: numpy::PyReadonlyArray1<'py, f64>,
        x: numpy::PyReadonlyArray1<'py, f64>,
        state: numpy::PyReadonlyArray1<'py, f64>,
        law: Option<&str>,
    ) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        let law = self.law(law)?;
        section::evaluate(py, &law, &strain, &curvature, &x, &state)
    }

    /// Runs the scene as `strand run` does, writing `out/<model>/`; returns each model's
    /// `summary.json` text. `models` keeps only those models (all when empty); `threads` sizes
    /// the Rust thread pool (default: the global one); `progress(model, fraction)` is called
    /// at most every 0.1 s. Ctrl-C stops the run and raises `KeyboardInterrupt`.
    #[pyo3(signature = (out, models, vtk=false, max_steps=None, threads=None, progress=None))]
    fn run(
        &self,
        py: Python<'_>,
        out: PathBuf,
        models: Vec<String>,
        vtk: bool,
        max_steps: Option<usize>,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Vec<String>> {
        let mut scene = self.scene.clone();
        if let Some(n) = max_steps {
            if n < 1 {
                return Err(PyValueError::new_err("max_steps must be at least 1"));
            }
            scene.max_steps = n;
        }
        scene
            .models
            .keep_only(&models)
            .map_err(|e| PyValueError::new_err(format!("models: {e}")))?;
        let opts = RunOptions { out, vtk };
        let result = interrupt::run_interruptible(py, threads, progress, move |hook| {
            strand_scene::run_scene(&scene, &opts, &mut |m, f| hook(m, f))
        })?;
        let summaries = result.map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        summaries.iter().map(to_json).collect()
    }

    /// The virtual bending test of `strand bend`, writing `out/bending.csv` and
    /// `out/summary.json`; returns the summary as JSON.
    #[pyo3(signature = (out, tension, curvatures, pitches=6, segments_per_pitch=12, threads=None, progress=None))]
    fn bend(
        &self,
        py: Python<'_>,
        out: PathBuf,
        tension: f64,
        curvatures: Vec<f64>,
        pitches: usize,
        segments_per_pitch: usize,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<String> {
        let scene = self.scene.clone();
        let opts = BendingOptions {
            tension,
            curvatures,
            pitches,
            segments_per_pitch,
            out,
        };
        let result = interrupt::run_interruptible(py, threads, progress, move |hook| {
            strand_scene::run_bending(&scene, &opts, &mut |_, f| hook("bending", f))
        })?;
        let summary = result.map_err(|e| PyValueError::new_err(e.to_string()))?;
        to_json(&summary)
    }

    /// The section law's bending curve of `strand bend --model equivalent`: the moment at
    /// tension `tension` (N) along 0 -> a -> -a -> a (`amplitude` a, 1/m; default three times
    /// the largest critical curvature), `steps` steps from 0 to a, averaged over the longest
    /// pitch; writes `out/law-bending.csv` and `out/law-summary.json`, returns the summary as
    /// JSON.
    #[pyo3(signature = (out, tension, amplitude=None, steps=100))]
    fn law_bend(
        &self,
        py: Python<'_>,
        out: PathBuf,
        tension: f64,
        amplitude: Option<f64>,
        steps: usize,
    ) -> PyResult<String> {
        let scene = self.scene.clone();
        let opts = strand_scene::LawBendingOptions {
            tension,
            amplitude,
            steps,
            out,
        };
        let summary = py
            .detach(move || strand_scene::run_law_bending(&scene, &opts))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        to_json(&summary)
    }
}

/// The module `strand._strand`.
#[pymodule]
fn _strand(m: &Bound<'_, PyModule>) -> PyResult<()> {
    interrupt::install_quiet_panic_hook();
    m.add_class::<PyScene>()?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
