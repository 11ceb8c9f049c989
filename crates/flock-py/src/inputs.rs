//! What a Python controller gives back, checked (`checked_inputs`), and what it failed with
//! ([`Failure`]): shared by `controls=f` ([`crate::controls`]) and `controls=Local(f)`
//! ([`crate::local`]).

use std::sync::{Mutex, MutexGuard, PoisonError};

use numpy::{AllowTypeChange, PyArrayLikeDyn};
use pyo3::prelude::*;

use crate::errors::{exception, is_complex};

/// What `f` failed with, and the state (positions, velocities as rows, agents in original order)
/// at the start of the step it failed in — `None` when that step began before the simulation was
/// built with `f`.
#[derive(Debug)]
pub struct Failure {
    /// The exception `f` raised, or a `flocking.ControlsError` for a result of the wrong shape or
    /// not finite.
    pub error: PyErr,
    /// The state the failed step started from.
    pub start: Option<(Vec<f64>, Vec<f64>)>,
}

/// A shape as Python prints it: `(100, 2)`, `(200,)`.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [single] => format!("({single},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// `flocking.ControlsError`: `f` returned something that is not n × dim finite inputs.
fn controls_error(
    py: Python<'_>,
    message: String,
    expected: (usize, usize),
    given: Option<Vec<usize>>,
) -> PyErr {
    exception(py, "ControlsError", (message, expected, given))
}

/// `u`, what a controls function returned at time `t`, written into `out` when it is an array of
/// n × dim finite real numbers; else a `flocking.ControlsError` naming the shapes (or the agent
/// whose input is not finite).
pub(crate) fn checked_inputs(
    py: Python<'_>,
    u: &Bound<'_, PyAny>,
    (n, dim): (usize, usize),
    t: f64,
    out: &mut [f64],
) -> PyResult<()> {
    let expected = format!("({n}, {dim}) (n agents × dim)");
    if is_complex(u)? {
        return Err(controls_error(
            py,
            format!(
                "controls returned complex numbers, not real accelerations of shape {expected}: \
                 return `u.real` when the imaginary parts are zero"
            ),
            (n, dim),
            None,
        ));
    }
    let array = if u.is_none() {
        None
    } else {
        u.extract::<PyArrayLikeDyn<'_, f64, AllowTypeChange>>().ok()
    };
    let Some(u) = array else {
        let kind = u.get_type().name()?;
        return Err(controls_error(
            py,
            format!("controls returned a {kind}, not an array of floats of shape {expected}"),
            (n, dim),
            None,
        ));
    };
    let u = u.as_array();
    if u.shape() != [n, dim] {
        return Err(controls_error(
            py,
            format!(
                "controls returned an array of shape {}; expected {expected} at t = {t}",
                shape_text(u.shape())
            ),
            (n, dim),
            Some(u.shape().to_vec()),
        ));
    }
    if let Some(k) = u.iter().position(|x| !x.is_finite()) {
        let i = k / dim;
        let row: Vec<f64> = (0..dim).map(|c| u[[i, c]]).collect();
        return Err(controls_error(
            py,
            format!(
                "controls returned an input that is not finite at t = {t}: u[{i}] = {row:?}; return finite numbers"
            ),
            (n, dim),
            Some(vec![n, dim]),
        ));
    }
    for (o, &x) in out.iter_mut().zip(u.iter()) {
        *o = x;
    }
    Ok(())
}

/// The slot's value, whatever a panicking holder left in it.
pub(crate) fn lock<T>(slot: &Mutex<T>) -> MutexGuard<'_, T> {
    slot.lock().unwrap_or_else(PoisonError::into_inner)
}
