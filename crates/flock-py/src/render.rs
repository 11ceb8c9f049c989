//! `flocking._render`: one state of a run of a scenario as an RGB image, drawn by
//! [`flock_viz::snapshot_rgb`] as `flocking plot` draws a snapshot (the agents, the edges of the
//! proximity net, the obstacles, the γ-agent at time t: [`flock_viz::run_scene`]): the
//! `render_mode="rgb_array"` of the Python environments.

use flock_viz::{Frame, Scene, SnapshotOptions, run_scene, snapshot_rgb};
use numpy::ndarray::{Array3, ArrayView1};
use numpy::{AllowTypeChange, IntoPyArray, PyArray3, PyArrayLike2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::{refuse_complex, scenario_error};
use crate::player::lifted;
use crate::scenario::PyScenario;
use crate::simulation::rows;

/// The image of the state (`positions`, `velocities`, of shape (n, dim), agents in the
/// scenario's order) of a run of `scenario` at time `t`: a uint8 array of shape
/// (`height`, `width`, 3), drawn as `flocking plot` draws a snapshot (3D: the oblique view).
///
/// Raises `ScenarioError` (a `ValueError`) for an array of another shape than (agents, dim) or of
/// complex numbers, as `Simulation` does; `ValueError` for a value or `t` that is not finite, or
/// a side outside 16–16384 pixels.
#[pyfunction]
#[pyo3(name = "_render", signature = (scenario, positions, velocities, t, width = 640, height = 480))]
pub fn render<'py>(
    py: Python<'py>,
    scenario: &PyScenario,
    positions: &Bound<'py, PyAny>,
    velocities: &Bound<'py, PyAny>,
    t: f64,
    width: u32,
    height: u32,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let scenario = &scenario.inner;
    let dim = scenario.dim;
    let lift = |array: &Bound<'py, PyAny>, name| {
        refuse_complex(py, array, name)?;
        let array = array.extract::<PyArrayLike2<'_, f64, AllowTypeChange>>()?;
        let values =
            rows(&array, name, (scenario.agents, dim)).map_err(|e| scenario_error(py, &e))?;
        if let Some((k, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "{name}[{}, {}] is {v}: only a finite state can be drawn",
                k / dim,
                k % dim
            )));
        }
        Ok::<Vec<_>, PyErr>(
            values
                .chunks_exact(dim)
                .map(|row| lifted(ArrayView1::from(row)))
                .collect(),
        )
    };
    let (q, p) = (
        lift(positions, "positions")?,
        lift(velocities, "velocities")?,
    );
    if !t.is_finite() {
        return Err(PyValueError::new_err(format!(
            "t is {t}: only a finite time can be drawn"
        )));
    }
    let scene = Scene::new(scenario.dim, scenario.range()).with_frame(Frame::new(t, q, p));
    let scene = run_scene(scenario, scene).map_err(|e| scenario_error(py, &e))?;
    let style = SnapshotOptions::default().style;
    let pixels = py
        .detach(|| snapshot_rgb(&scene, 0, &style, width, height))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let image = Array3::from_shape_vec((height as usize, width as usize, 3), pixels)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(image.into_pyarray(py))
}
