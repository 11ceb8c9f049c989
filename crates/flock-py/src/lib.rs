//! `flocking._flocking`, the extension module of the Python package `flocking` (`python/flocking`): the
//! [`flocking`] crate's scenarios, runs, run directories and simulations, with states and records as
//! numpy arrays.
//!
//! - [`scenario`]: `Scenario` — load, parse, write back, change any parameter by its path,
//!   explicit initial states.
//! - [`run`]: `run`, `resume` and `read_run` — whole runs, in memory and in run directories.
//! - [`simulation`]: `Simulation` — a run driven step by step.
//! - [`controls`]: `controls=`, the inputs u_i computed by a Python function on the proximity net;
//!   [`local`]: `controls=Local(f)`, a local controller of what each agent perceives.
//! - [`mod@env`]: `_VecEnv`, the engine of `flocking.env` (Gymnasium, PettingZoo).
//! - [`sweep`]: the pieces of `flocking.sweep` — a run of a sweep in any worker process, the output
//!   directory of `flocking sweep`.
//! - [`player`]: the HTML player of a run held in memory (`Run.player()`).
//! - [`mod@plot`]: `flocking.plot` and `Run.plot`, the figures of `flocking plot`.
//! - [`render`]: `_render`, one state as an RGB image (`render_mode="rgb_array"`).
//! - [`progress`]: the progress line of `flocking.run` and `flocking.resume`.
//! - [`mod@bench`]: `flocking.bench`, the engine of `flocking bench` with the same report.
//! - [`errors`]: flocking's errors as the Python exceptions of `flocking._errors`, with the CLI's
//!   messages; [`interrupt`]: Ctrl-C between steps while the GIL is released.

use pyo3::prelude::*;

pub mod bench;
pub mod controls;
pub mod env;
pub mod errors;
pub mod inputs;
pub mod interrupt;
pub mod local;
pub mod player;
pub mod plot;
pub mod progress;
pub mod render;
pub mod run;
pub mod scenario;
pub mod simulation;
pub mod sweep;

/// The extension module `flocking._flocking`; the package `flocking` re-exports its names.
#[pymodule]
fn _flocking(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_class::<scenario::PyScenario>()?;
    module.add_class::<simulation::PySimulation>()?;
    module.add_class::<controls::PyNeighbours>()?;
    module.add_class::<local::PyLocal>()?;
    module.add_class::<env::PyVecEnv>()?;
    module.add_class::<local::PyPerception>()?;
    module.add_class::<sweep::SweepLock>()?;
    module.add_class::<bench::PyBenchReport>()?;
    module.add_class::<bench::PyWorkloadReport>()?;
    module.add_function(wrap_pyfunction!(bench::bench, module)?)?;
    module.add_function(wrap_pyfunction!(controls::bump, module)?)?;
    module.add_function(wrap_pyfunction!(run::run, module)?)?;
    module.add_function(wrap_pyfunction!(run::resume, module)?)?;
    module.add_function(wrap_pyfunction!(run::read_run, module)?)?;
    module.add_function(wrap_pyfunction!(player::run_player_html, module)?)?;
    module.add_function(wrap_pyfunction!(plot::plot_run, module)?)?;
    module.add_function(wrap_pyfunction!(render::render, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_read, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_load, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_run, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_check, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_prepare, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_write_row, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_assemble, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_plot, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep_names, module)?)?;
    module.add("METRICS_HEADER", flocking::run_dir::METRICS_HEADER)?;
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
