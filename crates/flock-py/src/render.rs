//! `flocking._render`: one state of a run of a scenario as an RGB image, drawn by
//! [`flock_viz::snapshot_rgb`] as `flocking plot` draws a snapshot (the agents, the edges of the
//! proximity net, the obstacles, the γ-agent at time t: [`flock_viz::run_scene`]): the
//! `render_mode="rgb_array"` of the Python environments.

use flock_viz::{Frame, Scene, SnapshotOptions, run_scene, snapshot_rgb};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::scenario_error;
use crate::player::lifted;
use crate::scenario::PyScenario;

/// The image of the state (`positions`, `velocities`, of shape (n, dim), agents in the
/// scenario's order) of a run of `scenario` at time `t`: a uint8 array of shape
/// (`height`, `width`, 3), drawn as `flocking plot` draws a snapshot (3D: the oblique view).
///
/// Raises `ValueError` for an array of another shape than (agents, dim), a value or `t` that is
/// not finite, or a side outside 16–16384 pixels.
#[pyfunction]
#[pyo3(name = "_render", signature = (scenario, positions, velocities, t, width = 640, height = 480))]
pub fn render<'py>(
    py: Python<'py>,
    scenario: &PyScenario,
    positions: PyReadonlyArray2<'py, f64>,
    velocities: PyReadonlyArray2<'py, f64>,
    t: f64,
    width: u32,
    height: u32,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let scenario = &scenario.inner;
    let expected = [scenario.agents, scenario.dim];
    let state = [
        ("positions", positions.as_array()),
        ("velocities", velocities.as_array()),
    ];
    for (name, array) in &state {
        if array.shape() != expected {
            return Err(PyValueError::new_err(format!(
                "{name} has shape {:?}, but a state of this scenario has shape ({}, {}) (agents, dim)",
                array.shape(),
                expected[0],
                expected[1]
            )));
        }
        if let Some(((i, k), v)) = array.indexed_iter().find(|(_, v)| !v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "{name}[{i}, {k}] is {v}: only a finite state can be drawn"
            )));
        }
    }
    if !t.is_finite() {
        return Err(PyValueError::new_err(format!(
            "t is {t}: only a finite time can be drawn"
        )));
    }
    let [q, p] = state.map(|(_, array)| array.outer_iter().map(lifted).collect());
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
