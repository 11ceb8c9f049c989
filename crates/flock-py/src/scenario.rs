//! `flocking.Scenario`: a scenario of the [`flocking`] crate ([`Scenario`]) from Python — loaded from a
//! RON file or text, written back, any parameter read or changed by its dotted path
//! ([`Scenario::value`], [`Scenario::with_values`]) and explicit initial states from numpy arrays,
//! each validated as `flocking validate` does.

use std::path::PathBuf;

use flocking::estimate::{Density, Outputs};
use flocking::serde_json::{Map, Number, Value};
use flocking::{Cloud, Scenario, ScenarioError};
use numpy::{AllowTypeChange, PyArrayLike2};
use pyo3::IntoPyObjectExt;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::errors::{refuse_complex, scenario_error};
use flocking::input::MAX_NESTING;

/// A flocking scenario: the dimension, agents, algorithm and its gains, initial condition, step,
/// duration and recording, as a RON scenario file writes them.
///
/// Build one with `Scenario.load(path)` or `Scenario.from_ron(text)`; change it with
/// `with_values({"algorithm.c1": 0.05, "agents": 400})` or `with_initial(positions, velocities)`
/// (both return a new scenario, validated). Invalid values raise `flocking.ScenarioError` with the
/// CLI's message and the field in `.field`.
#[pyclass(name = "Scenario", module = "flocking", frozen, eq)]
#[derive(Clone, Debug, PartialEq)]
pub struct PyScenario {
    /// The scenario, validated.
    pub inner: Scenario,
}

#[pymethods]
impl PyScenario {
    /// Reads and validates the RON scenario file at `path`.
    ///
    /// Raises `flocking.ScenarioError` when the file cannot be read, is not a scenario (the message
    /// gives the line and column) or holds a value out of its domain.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        Scenario::load(&path)
            .map(|inner| Self { inner })
            .map_err(|e| scenario_error(py, &e))
    }

    /// Parses and validates scenario text in RON; `origin` names the text in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_ron(py: Python<'_>, text: &str, origin: &str) -> PyResult<Self> {
        Scenario::parse(text, origin)
            .map(|inner| Self { inner })
            .map_err(|e| scenario_error(py, &e))
    }

    /// The scenario as RON text with every default filled in (what a run writes to
    /// `scenario.ron`; `Scenario.from_ron` reads it back).
    fn to_ron(&self) -> PyResult<String> {
        self.inner
            .to_ron()
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// The value of the parameter at the dotted `path` (`"alpha.d"`, `"algorithm.c1"`,
    /// `"obstacles.0.radius"`): numbers, strings, lists, dicts (an enum as `{"Variant": ...}`),
    /// `None` for a default left unset.
    ///
    /// Raises `flocking.ScenarioError` for a path that names no parameter (the message lists those
    /// there are).
    fn value(&self, py: Python<'_>, path: &str) -> PyResult<Py<PyAny>> {
        let value = self.inner.value(path).map_err(|e| scenario_error(py, &e))?;
        to_python(py, &value)
    }

    /// A copy with the parameter at each dotted path of `values` replaced (`{"algorithm.c1":
    /// 0.05, "agents": 400}`), validated as a loaded scenario: defaults left unset follow the
    /// values they depend on (r = 1.2 d when only `alpha.d` changes).
    ///
    /// Raises `flocking.ScenarioError` naming the field: a path that names no parameter, a value of
    /// the wrong type, or one out of its domain.
    fn with_values(&self, py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Self> {
        let mut changes = Vec::with_capacity(values.len());
        for (path, value) in values.iter() {
            let path: String = path.extract()?;
            let value =
                to_json(&value, &path, &mut Vec::new()).map_err(|e| scenario_error(py, &e))?;
            changes.push((path, value));
        }
        self.inner
            .with_values(changes)
            .map(|inner| Self { inner })
            .map_err(|e| scenario_error(py, &e))
    }

    /// A copy that starts from the given state: `positions` and `velocities` are n × dim arrays
    /// (velocities zero when omitted), agent i on row i. `agents` becomes n; the state is written
    /// into the scenario (`initial: (positions: Explicit([...]), ...)`), so a run directory's
    /// `scenario.ron` still reruns it.
    ///
    /// Raises `flocking.ScenarioError` for rows of another dimension than the scenario's or values
    /// that are not finite.
    #[pyo3(signature = (positions, velocities = None))]
    fn with_initial(
        &self,
        py: Python<'_>,
        positions: &Bound<'_, PyAny>,
        velocities: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        refuse_complex(py, positions, "initial.positions")?;
        if let Some(v) = velocities {
            refuse_complex(py, v, "initial.velocities")?;
        }
        let positions: PyArrayLike2<'_, f64, AllowTypeChange> = positions.extract()?;
        let velocities: Option<PyArrayLike2<'_, f64, AllowTypeChange>> =
            velocities.map(|v| v.extract()).transpose()?;
        let mut inner = self.inner.clone();
        let dim = inner.dim;
        let positions =
            rows(&positions, "positions", None, dim).map_err(|e| scenario_error(py, &e))?;
        let agents = positions.len();
        let velocities = velocities
            .map(|v| rows(&v, "velocities", Some(agents), dim))
            .transpose()
            .map_err(|e| scenario_error(py, &e))?;
        inner.agents = agents;
        inner.initial.positions = Cloud::Explicit(positions);
        inner.initial.velocities = velocities.map_or(Cloud::Zero, Cloud::Explicit);
        inner.validate().map_err(|e| scenario_error(py, &e))?;
        Ok(Self { inner })
    }

    /// The estimated cost of one run of this scenario, before it starts (what `flocking run`
    /// prints): a dict of `steps`, `records`, `agent_steps`, `memory_bytes` (peak, one run),
    /// `disk_bytes` (what the chosen outputs write into `out`; 0 for a run in memory) and
    /// `seconds` (on one thread, from the rates measured in docs/performance.md), and
    /// `start_mean_degree`: the mean degree of the start's net within the sensing range, which
    /// scales memory and time when it exceeds the α-lattice's (`None` when too dense to count:
    /// `flocking run` then refuses the scenario).
    ///
    /// `out` says whether the run writes a directory (`flocking.run(scenario, out=...)`), with
    /// `trajectory` and `trajectory_format` as `flocking.run` takes them.
    #[pyo3(signature = (*, out = false, trajectory = true, trajectory_format = "csv"))]
    fn estimate<'py>(
        &self,
        py: Python<'py>,
        out: bool,
        trajectory: bool,
        trajectory_format: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let csv = match trajectory_format {
            "csv" => true,
            "npy" => false,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown trajectory_format {other:?}: give \"csv\" or \"npy\""
                )));
            }
        };
        let outputs = if out {
            Outputs {
                metrics: true,
                trajectory_csv: trajectory.then_some(csv),
                checkpoint: true,
            }
        } else {
            Outputs::NONE
        };
        let estimate = self.inner.estimate_at_start(&outputs);
        let dict = PyDict::new(py);
        dict.set_item("steps", estimate.steps)?;
        dict.set_item("records", estimate.records)?;
        dict.set_item("agent_steps", estimate.agent_steps)?;
        dict.set_item("memory_bytes", estimate.memory_bytes)?;
        dict.set_item("disk_bytes", estimate.disk_bytes)?;
        dict.set_item("seconds", estimate.seconds)?;
        let degree = match estimate.density {
            Density::Start(degree) => Some(degree),
            Density::Lattice | Density::TooDense => None,
        };
        dict.set_item("start_mean_degree", degree)?;
        Ok(dict)
    }

    /// The warnings `flocking validate` and `flocking run` print for this valid scenario
    /// ([`flocking::Scenario::warnings`]), each naming the field and the fix.
    fn warnings(&self) -> Vec<String> {
        self.inner
            .warnings()
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    /// The scenario's name.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    /// The dimension, 2 or 3.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim
    }

    /// The number of agents n.
    #[getter]
    fn agents(&self) -> usize {
        self.inner.agents
    }

    /// The time step h.
    #[getter]
    fn step(&self) -> f64 {
        self.inner.step
    }

    /// The simulated time T.
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.duration
    }

    /// The seed of the initial condition's random stream.
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.seed
    }

    /// The α-interaction's parameters with defaults resolved (r = 1.2 d when unset): a dict of
    /// d, r, epsilon (ε of the σ-norm), a, b, h (of the bump ρ_h), c1 and c2 (c₁^α, c₂^α).
    #[getter]
    fn alpha<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let config = &self.inner.alpha;
        let params = config.params();
        let dict = PyDict::new(py);
        for (name, value) in [
            ("d", params.d),
            ("r", params.r),
            ("epsilon", params.epsilon),
            ("a", params.a),
            ("b", params.b),
            ("h", params.h),
            ("c1", config.c1),
            ("c2", config.c2),
        ] {
            dict.set_item(name, value)?;
        }
        Ok(dict)
    }

    /// The number of steps of a run, ⌈T / h⌉.
    #[getter]
    fn steps(&self) -> u64 {
        self.inner.steps()
    }

    /// Steps between records (the last step is always recorded).
    #[getter]
    fn record_every(&self) -> u64 {
        self.inner.record_every
    }

    fn __repr__(&self) -> String {
        format!(
            "Scenario(name={:?}, dim={}, agents={}, duration={:?}, step={:?}, steps={})",
            self.inner.name,
            self.inner.dim,
            self.inner.agents,
            self.inner.duration,
            self.inner.step,
            self.inner.steps()
        )
    }

    /// Pickles as its RON text.
    fn __reduce__(slf: &Bound<'_, Self>) -> PyResult<(Py<PyAny>, (String,))> {
        let from_ron = slf.get_type().getattr("from_ron")?.unbind();
        Ok((from_ron, (slf.get().to_ron()?,)))
    }
}

/// The rows of the `name` array, checked to be (n, `dim`) — (`agents`, `dim`) when `agents` is
/// given: a transposed (dim, n) array is refused with both shapes, not read as dim agents.
fn rows(
    array: &PyArrayLike2<'_, f64, AllowTypeChange>,
    name: &str,
    agents: Option<usize>,
    dim: usize,
) -> Result<Vec<Vec<f64>>, ScenarioError> {
    let array = array.as_array();
    let (given_rows, given_cols) = array.dim();
    let rows_ok = agents.is_none_or(|n| n == given_rows);
    if given_cols != dim || !rows_ok {
        let n = agents.map_or_else(|| "n".to_owned(), |n| n.to_string());
        let fix = if given_rows == dim && agents.is_none_or(|n| n == given_cols) {
            "the array is transposed: pass its transpose (`array.T`), one row per agent"
        } else {
            "give one row of dim coordinates per agent"
        };
        return Err(ScenarioError::invalid(
            format!("initial.{name}"),
            Repr(format!("an array of shape ({given_rows}, {given_cols})")),
            format!("the scenario is {dim}D, so the shape must be ({n}, {dim})"),
            fix,
        ));
    }
    Ok(array.outer_iter().map(|row| row.to_vec()).collect())
}

/// `value` (a Python number, string, bool, `None`, list, tuple or dict) as JSON, for the
/// parameter at `path`; `within` holds the lists and dicts being converted around it.
///
/// # Errors
/// Any other type, a float that is not finite, a list or dict that contains itself, or nesting
/// deeper than [`MAX_NESTING`], as an invalid value of `path`.
fn to_json(
    value: &Bound<'_, PyAny>,
    path: &str,
    within: &mut Vec<usize>,
) -> Result<Value, ScenarioError> {
    let invalid = |why: &str| {
        ScenarioError::invalid(
            path,
            Repr(
                value
                    .repr()
                    .map_or_else(|_| "?".to_owned(), |r| r.to_string()),
            ),
            why,
            "give a number, a string, a bool, None, or a list or dict of them",
        )
    };
    let container = value.is_instance_of::<PyList>()
        || value.is_instance_of::<PyTuple>()
        || value.is_instance_of::<PyDict>();
    if container {
        let id = value.as_ptr() as usize;
        // Both errors name the parameter (the path given, not the path down to the culprit,
        // which can be 64 segments long) and do not show the value (its repr could be huge).
        let root = path.split('.').count().saturating_sub(within.len());
        let root = path
            .split('.')
            .take(root.max(1))
            .collect::<Vec<_>>()
            .join(".");
        let nested = |why: String| {
            ScenarioError::invalid(
                root.clone(),
                Repr(format!("(a list or dict at `{path}`)")),
                why,
                "give the value as the scenario file writes it (a scenario nests about 6 levels)",
            )
        };
        if within.contains(&id) {
            return Err(nested("the list or dict contains itself".to_owned()));
        }
        if within.len() >= MAX_NESTING {
            return Err(nested(format!(
                "lists or dicts are nested more than {MAX_NESTING} levels deep"
            )));
        }
        within.push(id);
        let converted = container_to_json(value, path, within, &invalid);
        within.pop();
        return converted;
    }
    if value.is_none() {
        Ok(Value::Null)
    } else if let Ok(flag) = value.cast::<PyBool>() {
        Ok(Value::Bool(flag.is_true()))
    } else if value.is_instance_of::<PyInt>() {
        if let Ok(integer) = value.extract::<i64>() {
            Ok(Value::from(integer))
        } else if let Ok(integer) = value.extract::<u64>() {
            Ok(Value::from(integer))
        } else {
            Err(invalid("the integer does not fit in 64 bits"))
        }
    } else if let Ok(float) = value.cast::<PyFloat>() {
        Number::from_f64(float.value())
            .map(Value::Number)
            .ok_or_else(|| invalid("the number is not finite"))
    } else if let Ok(text) = value.cast::<PyString>() {
        Ok(Value::String(text.to_string()))
    } else if let Ok(integer) = value.extract::<i64>() {
        // numpy's integer scalars
        Ok(Value::from(integer))
    } else if let Ok(list) = value.call_method0("tolist") {
        // numpy's arrays and other scalars
        to_json(&list, path, within)
    } else {
        Err(invalid("this type is not a parameter value"))
    }
}

/// A list, tuple or dict as JSON (see [`to_json`]).
fn container_to_json(
    value: &Bound<'_, PyAny>,
    path: &str,
    within: &mut Vec<usize>,
    invalid: &dyn Fn(&str) -> ScenarioError,
) -> Result<Value, ScenarioError> {
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut map = Map::new();
        for (key, item) in dict.iter() {
            let key: String = key
                .extract()
                .map_err(|_| invalid("a dict's keys must be strings"))?;
            let item = to_json(&item, &format!("{path}.{key}"), within)?;
            map.insert(key, item);
        }
        return Ok(Value::Object(map));
    }
    value
        .try_iter()
        .map_err(|_| invalid("the list cannot be read"))?
        .enumerate()
        .map(|(k, item)| {
            let item = item.map_err(|_| invalid("the list cannot be read"))?;
            to_json(&item, &format!("{path}.{k}"), within)
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Value::Array)
}

/// A Python `repr`, shown as it is in an error's value.
struct Repr(String);

impl std::fmt::Debug for Repr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// A JSON value as Python: `None`, bool, int, float, str, list or dict.
fn to_python(py: Python<'_>, value: &Value) -> PyResult<Py<PyAny>> {
    match value {
        Value::Null => Ok(py.None()),
        Value::Bool(flag) => flag.into_py_any(py),
        Value::Number(number) => match (number.as_i64(), number.as_u64()) {
            (Some(integer), _) => integer.into_py_any(py),
            (None, Some(integer)) => integer.into_py_any(py),
            (None, None) => number.as_f64().unwrap_or(f64::NAN).into_py_any(py),
        },
        Value::String(text) => text.into_py_any(py),
        Value::Array(items) => {
            let items = items
                .iter()
                .map(|item| to_python(py, item))
                .collect::<PyResult<Vec<_>>>()?;
            PyList::new(py, items)?.into_py_any(py)
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (key, item) in map {
                dict.set_item(key, to_python(py, item)?)?;
            }
            dict.into_py_any(py)
        }
    }
}
