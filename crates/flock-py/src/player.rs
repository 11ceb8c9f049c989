//! `Run.player`'s page: the self-contained canvas player of `flocking plot`
//! ([`flock_viz::player_html`]) of a run held as numpy arrays, drawn as [`flock_viz::run_scene`]
//! draws a run directory (obstacles, γ-agent, desired distance), with its metrics' readout, within
//! a byte budget.

use flock_viz::{Frame, Metrics, PlayerOptions, Scene, player_html, run_scene};
use flocking::glam::DVec3;
use numpy::ndarray::{ArrayView1, Axis};
use numpy::{PyReadonlyArray1, PyReadonlyArray3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::scenario_error;
use crate::scenario::PyScenario;

/// The player page of a run of `scenario` recorded at `times`, with `positions` and
/// `velocities` of shape (T, n, dim) and the readout of `metrics` (the columns of `metrics.csv`
/// as (name, values) pairs, `t` among them); at most `max_frames` frames are embedded, and fewer
/// when the page would exceed `max_bytes` (a longer run is subsampled evenly, first and last
/// frames kept, and the page says so), on a canvas of `size` × `size` pixels.
///
/// Raises `ValueError` for arrays of another shape, metrics without `t` or of another length,
/// or a run that cannot be drawn within `max_bytes`.
#[pyfunction]
#[pyo3(signature = (scenario, times, positions, velocities, metrics, *, max_frames = 500, size = 480, max_bytes = None))]
#[allow(clippy::too_many_arguments)]
pub fn run_player_html(
    py: Python<'_>,
    scenario: &PyScenario,
    times: PyReadonlyArray1<'_, f64>,
    positions: PyReadonlyArray3<'_, f64>,
    velocities: PyReadonlyArray3<'_, f64>,
    metrics: Vec<(String, Vec<f64>)>,
    max_frames: usize,
    size: u32,
    max_bytes: Option<usize>,
) -> PyResult<String> {
    let scenario = &scenario.inner;
    let (times, positions, velocities) = (
        times.as_array(),
        positions.as_array(),
        velocities.as_array(),
    );
    let shape = positions.shape();
    if shape != velocities.shape() || shape[0] != times.len() || shape[2] != scenario.dim {
        return Err(PyValueError::new_err(format!(
            "times {:?}, positions {:?} and velocities {:?} are not (T,), (T, n, {}) and (T, n, {})",
            times.shape(),
            shape,
            velocities.shape(),
            scenario.dim,
            scenario.dim
        )));
    }
    let mut scene = Scene::new(scenario.dim, scenario.range());
    scene.frames = (0..times.len())
        .map(|k| {
            let q = positions.index_axis(Axis(0), k);
            let p = velocities.index_axis(Axis(0), k);
            Frame::new(
                times[k],
                q.outer_iter().map(lifted).collect(),
                p.outer_iter().map(lifted).collect(),
            )
        })
        .collect();
    let scene = run_scene(scenario, scene).map_err(|e| scenario_error(py, &e))?;
    let metrics =
        Metrics::from_columns(metrics).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let options = PlayerOptions {
        canvas_size: (size, size),
        max_frames,
        max_bytes,
        ..PlayerOptions::default()
    };
    py.detach(|| player_html(&scene, Some(&metrics), &options))
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// A point or vector of a state array's row (length 2 or 3), lifted to 3D (z = 0 in 2D) as the
/// figures hold it.
pub(crate) fn lifted(row: ArrayView1<'_, f64>) -> DVec3 {
    DVec3::new(row[0], row[1], if row.len() > 2 { row[2] } else { 0.0 })
}
