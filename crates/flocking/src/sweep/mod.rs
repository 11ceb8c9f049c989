//! Ensembles and parameter sweeps: one scenario run over a grid of parameter values and random
//! seeds, each run reduced to one row of `runs.csv`.
//!
//! A sweep file (RON) names a base scenario, fixed changes to it, axes — a parameter path and its
//! values — and a number of seeds:
//!
//! ```ron
//! Sweep(
//!     name: "alg2_c1_n",
//!     base: Path("../fixtures/tac2006_fig11_alg2_n100.ron"),   // or Inline(Scenario(…))
//!     set: {"duration": 40.0},
//!     axes: [
//!         (path: "algorithm.c1", values: Logspace(from: 0.005, to: 0.5, count: 5)),
//!         (path: "agents", values: List([25, 50, 100])),
//!     ],
//!     seeds: 20,
//! )
//! ```
//!
//! The runs are the cartesian product of the axes' values (the first axis outermost) times the
//! seeds 0, 1, …, `seeds` − 1 (innermost), which replace the scenario's `seed`. Each run has an
//! index in that order and an id derived from its values alone ([`RunSpec::id`]), so that the
//! rows of `runs.csv` never depend on how, where or in which order the runs were computed.
//!
//! - [`Sweep`]: the file ([`Sweep::load`], [`str::parse`]), its runs ([`Sweep::runs`]), the
//!   scenario of a run ([`Sweep::scenario`]).
//! - [`run_one`]: one run, reduced to a [`RunRow`]; [`run_one_with`] with the protocol changed by a
//!   [`MapProtocol`](crate::MapProtocol).
//! - [`store`]: the output directory — a row file per finished run (so that a killed sweep
//!   resumes), `runs.csv` assembled in run order, shards and their merge.
//! - [`execute`]: every pending run of this machine's share on N workers.
//! - [`ParameterLabel`], [`metric_label`]: what figures call the parameters and the columns.

mod execute;
mod labels;
mod row;
pub mod store;

use std::collections::BTreeMap;
use std::fmt;
use std::hash::Hasher;
use std::path::Path;
use std::str::FromStr;

use ron::extensions::Extensions;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::Scenario;
use crate::error::ScenarioError;

pub use execute::{ExecuteOptions, Executed, Shard, estimate, execute, share};
pub use labels::ParameterLabel;
pub use row::{
    Outcome, RunRow, SEED_COLUMN, header, metric_label, run_one, run_one_with, value_field,
};

/// The most runs a sweep may have (grid points × seeds): each run's scenario is checked before
/// the first starts, and each leaves a row.
pub const MAX_RUNS: usize = 1_000_000;

/// A sweep file.
///
/// # Example
/// ```
/// use flocking::sweep::Sweep;
///
/// # std::env::set_current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))?; // the workspace root
/// let sweep: Sweep = r#"Sweep(
///     base: Path("fixtures/tac2006_fig11_alg2_n100.ron"),
///     set: {"duration": 1.0, "agents": 10},
///     axes: [(path: "algorithm.c1", values: Linspace(from: 0.01, to: 0.03, count: 3))],
///     seeds: 2,
/// )"#.parse()?;
/// let runs = sweep.runs();
/// assert_eq!(runs.len(), 6);
/// assert_eq!(runs[1].seed, 1);
/// let scenario = sweep.scenario(&runs[5])?;
/// assert_eq!(scenario.value("algorithm.c1")?, serde_json::json!(0.03));
/// let row = flocking::sweep::run_one(&sweep, &runs[0], None);
/// assert!(row.outcome.is_ok());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sweep {
    /// A short name.
    #[serde(default)]
    pub name: String,
    /// What the sweep asks.
    #[serde(default)]
    pub description: String,
    /// The scenario every run starts from.
    pub base: Base,
    /// Changes made to the base scenario for every run, by parameter path.
    #[serde(default)]
    pub set: BTreeMap<String, Value>,
    /// The axes: the runs are the cartesian product of their values.
    #[serde(default)]
    pub axes: Vec<Axis>,
    /// The number of seeds (replicates) per point of the grid: seeds 0, 1, …, `seeds` − 1.
    pub seeds: u64,
    /// ε₁ of TAC 2006 Definition 5 (Ẽ ≤ ε₁), judged over each run's last quarter.
    #[serde(default = "default_epsilon")]
    pub epsilon1: f64,
    /// ε₂ of TAC 2006 Definition 5, relative to the group's speed: K̃ ≤ ε₂ ‖p_c‖² (for a group
    /// at rest, relative to the speed of its approach).
    #[serde(default = "default_epsilon")]
    pub epsilon2: f64,
    /// The fraction of each run's duration after which it has settled: the `settled_*` columns
    /// of `runs.csv` are over the records at t ≥ `settle` × duration (default 0.25, in [0, 1)).
    #[serde(default = "default_settle")]
    pub settle: f64,
}

fn default_epsilon() -> f64 {
    0.01
}

fn default_settle() -> f64 {
    flock_metrics::Closest::SETTLE
}

/// The base scenario of a sweep.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Base {
    /// A scenario file, relative to the sweep file's directory.
    Path(String),
    /// The scenario itself.
    Inline(Box<Scenario>),
}

/// An axis: a parameter path and its values.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// The parameter, as [`Scenario::with_values`] names it (`algorithm.c1`, `obstacles.0.radius`).
    pub path: String,
    /// Its values.
    pub values: Values,
}

/// The values of an axis.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Values {
    /// These values, in order (numbers, or anything the parameter takes: whole RON values such
    /// as `[Ball(centre: [150.0, 0.0], radius: 12.0)]` keep their enum variant's name, as the
    /// externally tagged `{"Ball": {…}}` that [`Scenario::with_values`] reads).
    List(#[serde(deserialize_with = "tagged_values")] Vec<Value>),
    /// `count` values evenly spaced from `from` to `to`, both included.
    Linspace {
        /// The first value.
        from: f64,
        /// The last value.
        to: f64,
        /// How many (≥ 1; 1 gives `from`).
        count: usize,
    },
    /// `count` values evenly spaced in logarithm from `from` to `to` (both > 0), both included.
    Logspace {
        /// The first value.
        from: f64,
        /// The last value.
        to: f64,
        /// How many (≥ 1).
        count: usize,
    },
}

/// A value of any shape, read through serde's buffered content so that a RON enum variant keeps
/// its name (`Ball(…)` → `{"Ball": {…}}`, a unit variant `Line` → `"Line"`): read directly as a
/// [`Value`], RON drops the names of structs and variants, and `Ball(…)` became an untagged map
/// that no obstacle field takes.
#[derive(Deserialize)]
#[serde(untagged)]
enum Tagged {
    /// The value, its variants tagged.
    Value(Value),
}

fn tagged_values<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<Vec<Value>, D::Error> {
    let values: Vec<Tagged> = Deserialize::deserialize(deserializer)?;
    Ok(values
        .into_iter()
        .map(|Tagged::Value(value)| value)
        .collect())
}

impl Values {
    /// How many values.
    #[must_use]
    pub fn count(&self) -> usize {
        match self {
            Self::List(values) => values.len(),
            Self::Linspace { count, .. } | Self::Logspace { count, .. } => *count,
        }
    }

    /// The values, in order; the end points of a spacing exactly as written.
    #[must_use]
    pub fn expand(&self) -> Vec<Value> {
        let (from, to, count, log) = match *self {
            Self::List(ref values) => return values.clone(),
            Self::Linspace { from, to, count } => (from, to, count, false),
            Self::Logspace { from, to, count } => (from, to, count, true),
        };
        let between = |a: f64, b: f64, k: usize| a + (b - a) * k as f64 / (count - 1) as f64;
        (0..count)
            .map(|k| match k {
                0 => from,
                k if k + 1 == count => to,
                k if log => between(from.ln(), to.ln(), k).exp(),
                k => between(from, to, k),
            })
            .map(Value::from)
            .collect()
    }
}

/// One run of a sweep: its index in run order, its axis values (one per axis) and its seed.
#[derive(Clone, Debug, PartialEq)]
pub struct RunSpec {
    /// The position of the run in run order (axes outermost first, seeds innermost).
    pub index: usize,
    /// One value per axis.
    pub values: Vec<Value>,
    /// The scenario's seed.
    pub seed: u64,
}

impl RunSpec {
    /// The run's id: 16 hexadecimal digits of the 64-bit FNV-1a hash of its axis paths and values
    /// and its seed, written canonically (`path=value;…;seed=k`). It depends on the values alone,
    /// never on the index, the worker or the machine.
    #[must_use]
    pub fn id(&self, axes: &[Axis]) -> String {
        let mut hasher = fnv::FnvHasher::default();
        for (axis, value) in axes.iter().zip(&self.values) {
            hasher.write(format!("{}={value};", axis.path).as_bytes());
        }
        hasher.write(format!("seed={}", self.seed).as_bytes());
        format!("{:016x}", hasher.finish())
    }
}

/// Why a sweep file cannot be used.
#[derive(Clone, Debug, PartialEq)]
pub enum SweepError {
    /// The file could not be read.
    Io {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The text is not a sweep in RON (line and column 1-based).
    Syntax {
        /// Where the text came from.
        origin: String,
        /// Line.
        line: usize,
        /// Column.
        col: usize,
        /// The parser's message.
        message: String,
    },
    /// The base scenario, or the base with `set` applied, is invalid.
    Base(ScenarioError),
    /// A field of the sweep is out of its domain.
    Invalid {
        /// The field (`axes[1].values`, `seeds`).
        field: String,
        /// Why, and the fix.
        why: String,
    },
    /// A run's scenario is invalid: the base with `set` and the run's axis values.
    Run {
        /// The run's index in run order.
        index: usize,
        /// The run's values, as `path = value, …, seed = k`.
        values: String,
        /// The scenario's error.
        error: Box<ScenarioError>,
    },
    /// An error of the value written at `line`:`col` of the sweep's text.
    At {
        /// Where the text came from.
        origin: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// The error.
        error: Box<SweepError>,
    },
}

impl SweepError {
    /// The field at fault (`seeds`, `axes[1].path`, or the scenario's field of a base or run error).
    #[must_use]
    pub fn field(&self) -> Option<String> {
        match self {
            Self::Invalid { field, .. } => Some(field.clone()),
            Self::Base(e) => e.field(),
            Self::Run { error, .. } => error.field(),
            Self::At { error, .. } => error.field(),
            Self::Io { .. } | Self::Syntax { .. } => None,
        }
    }

    /// The error without its place in the text.
    #[must_use]
    pub fn problem(&self) -> &Self {
        match self {
            Self::At { error, .. } => error.problem(),
            other => other,
        }
    }

    /// The error at the line and column of its field in `text` (the axis whose value a run's
    /// error names, or the axes).
    fn placed(self, origin: &str, text: &str, axes: &[Axis]) -> Self {
        let field = match &self {
            Self::Invalid { field, .. } => field.clone(),
            Self::Run { error, .. } => {
                // `obstacles[0].radius` as a path: `obstacles.0.radius`.
                let named = error
                    .field()
                    .unwrap_or_default()
                    .replace('[', ".")
                    .replace(']', "");
                axes.iter()
                    .position(|axis| {
                        named == axis.path || named.starts_with(&format!("{}.", axis.path))
                    })
                    .map_or_else(|| "axes".to_owned(), |k| format!("axes[{k}].values"))
            }
            _ => return self,
        };
        match crate::error::locate(text, &field) {
            Some((line, col)) => Self::At {
                origin: origin.to_owned(),
                line,
                col,
                error: Box::new(self),
            },
            None => self,
        }
    }
}

impl fmt::Display for SweepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, message } => write!(f, "cannot read sweep {path}: {message}"),
            Self::Syntax {
                origin,
                line,
                col,
                message,
            } => write!(f, "{origin}:{line}:{col}: {message}"),
            Self::Base(e) => write!(f, "the base scenario: {e}"),
            Self::Invalid { field, why } => write!(f, "`{field}`: {why}"),
            Self::Run {
                index,
                values,
                error,
            } => write!(
                f,
                "run {index} ({values}) is invalid: {error}; change the axis values or `set` so that every run is valid"
            ),
            Self::At {
                origin,
                line,
                col,
                error,
            } => write!(f, "{origin}:{line}:{col}: {error}"),
        }
    }
}

impl std::error::Error for SweepError {}

impl Sweep {
    /// Reads a sweep file; a `Path` base is read relative to the file's directory and inlined.
    ///
    /// # Errors
    /// As [`Sweep::parse`], and a file that cannot be read.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, SweepError> {
        let path = path.as_ref();
        let text = crate::input::read_text(path).map_err(|message| SweepError::Io {
            path: path.display().to_string(),
            message,
        })?;
        Self::parse(
            &text,
            &path.display().to_string(),
            path.parent().unwrap_or(Path::new("")),
        )
    }

    /// Parses sweep text from `origin` (named in errors) with `Path` bases relative to `dir`, and
    /// checks it: the base scenario and `set` valid, every axis path a parameter of the scenario
    /// given once and not in `set`, every axis with at least one value, `seeds` ≥ 1, at most
    /// [`MAX_RUNS`] runs, and every run's scenario valid (an invalid one is an error naming its
    /// values, at the line of its axis).
    ///
    /// # Errors
    /// The first problem found, with its line and column for syntax errors.
    pub fn parse(text: &str, origin: &str, dir: &Path) -> Result<Self, SweepError> {
        let text = crate::input::without_bom(text);
        let mut sweep = Self::read(text, origin)?;
        if let Base::Path(path) = &sweep.base {
            let scenario = Scenario::load(dir.join(path)).map_err(SweepError::Base)?;
            sweep.base = Base::Inline(Box::new(scenario));
        }
        sweep
            .check()
            .and_then(|()| sweep.check_runs())
            .map_err(|e| e.placed(origin, text, &sweep.axes))?;
        Ok(sweep)
    }

    /// Parses a self-contained sweep that [`Sweep::parse`] has already checked and
    /// [`Sweep::to_ron`] wrote (`sweep.ron` of an output directory, the text a worker of
    /// Python's `flocking.sweep` gets with each run): the sweep is checked again — base, `set`,
    /// axes, the run count — but not every run's scenario, which would make each of N workers'
    /// calls cost N validations. A run whose scenario is invalid is still refused when it runs
    /// ([`run_one`] gives its error row).
    ///
    /// # Errors
    /// As [`Sweep::parse`], less the runs' checks; a `Path` base (the text is not self-contained).
    pub fn parse_checked(text: &str, origin: &str) -> Result<Self, SweepError> {
        let text = crate::input::without_bom(text);
        let sweep = Self::read(text, origin)?;
        sweep
            .check()
            .map_err(|e| e.placed(origin, text, &sweep.axes))?;
        Ok(sweep)
    }

    /// The sweep of RON text `text` from `origin`, unchecked; a syntax error with its line and
    /// column.
    fn read(text: &str, origin: &str) -> Result<Self, SweepError> {
        crate::input::ron_options()
            .from_str(text)
            .map_err(|e| SweepError::Syntax {
                origin: origin.to_owned(),
                line: e.span.start.line,
                col: e.span.start.col,
                message: crate::input::ron_message(&e.code),
            })
    }

    /// The number of runs, the grid's points times the seeds.
    ///
    /// # Errors
    /// More than [`MAX_RUNS`] (checked without overflow).
    pub fn run_count(&self) -> Result<usize, SweepError> {
        let too_many = || SweepError::Invalid {
            field: "seeds".into(),
            why: format!(
                "the axes' values times {} seeds exceed {MAX_RUNS} runs; give fewer values or seeds, \
                 or split the sweep",
                self.seeds
            ),
        };
        let seeds = usize::try_from(self.seeds).map_err(|_| too_many())?;
        self.axes
            .iter()
            .map(|axis| axis.values.count())
            .try_fold(seeds, usize::checked_mul)
            .filter(|&runs| runs <= MAX_RUNS)
            .ok_or_else(too_many)
    }

    /// Every run's scenario valid: the first invalid one, with its values.
    fn check_runs(&self) -> Result<(), SweepError> {
        for run in self.runs() {
            self.scenario(&run).map_err(|error| SweepError::Run {
                index: run.index,
                values: self
                    .axes
                    .iter()
                    .zip(&run.values)
                    .map(|(axis, value)| format!("{} = {value}", axis.path))
                    .chain([format!("seed = {}", run.seed)])
                    .collect::<Vec<_>>()
                    .join(", "),
                error: Box::new(error),
            })?;
        }
        Ok(())
    }

    fn check(&self) -> Result<(), SweepError> {
        let invalid = |field: String, why: String| Err(SweepError::Invalid { field, why });
        let base = self.base_scenario()?;
        if self.seeds == 0 {
            return invalid("seeds".into(), "0 seeds give no run; give 1 or more".into());
        }
        for (k, axis) in self.axes.iter().enumerate() {
            // a field of the conditions that the base leaves unset has no value to read, but
            // the axis's first value sets it: such a path is checked by setting it
            if let Err(unreadable) = base.value(&axis.path) {
                let Some(first) = axis.values.expand().into_iter().next() else {
                    return invalid(format!("axes[{k}].path"), unreadable.to_string());
                };
                if let Err(e) = base.with_values([(axis.path.as_str(), first)]) {
                    return invalid(format!("axes[{k}].path"), e.to_string());
                }
            }
            if axis.path == SEED_COLUMN {
                // issue 27: else `run,id,seed,seed`, and N runs of N / seeds simulations
                return invalid(
                    format!("axes[{k}].path"),
                    "`seed` is given by `seeds` (each run's seed is 0, 1, …, seeds − 1, replacing \
                     the scenario's): an axis on it would be overridden; remove the axis and \
                     give `seeds: N` for N seeds"
                        .into(),
                );
            }
            if let Some(first) = self.axes[..k].iter().position(|a| a.path == axis.path) {
                return invalid(
                    format!("axes[{k}].path"),
                    format!(
                        "`{}` is already the path of axes[{first}]; give each parameter one axis \
                         (put all its values in one list)",
                        axis.path
                    ),
                );
            }
            if self.set.contains_key(&axis.path) {
                return invalid(
                    format!("axes[{k}].path"),
                    format!(
                        "`{}` is also in `set`, which the axis would override; remove it from `set`",
                        axis.path
                    ),
                );
            }
            let field = format!("axes[{k}].values");
            match axis.values {
                Values::List(ref values) if values.is_empty() => {
                    return invalid(field, "an empty list; give at least one value".into());
                }
                Values::Linspace { from, to, count } | Values::Logspace { from, to, count }
                    if count == 0 || !from.is_finite() || !to.is_finite() =>
                {
                    return invalid(
                        field,
                        format!(
                            "from {from} to {to} in {count} values: give finite ends and count ≥ 1"
                        ),
                    );
                }
                Values::Linspace { count, .. } | Values::Logspace { count, .. }
                    if count > MAX_RUNS =>
                {
                    return invalid(
                        field,
                        format!("{count} values: more than the {MAX_RUNS} runs a sweep may have"),
                    );
                }
                Values::Logspace { from, to, .. } if from <= 0.0 || to <= 0.0 => {
                    return invalid(
                        field,
                        format!("Logspace from {from} to {to}: both ends must be > 0"),
                    );
                }
                _ => {}
            }
        }
        self.run_count()?;
        if !(0.0..1.0).contains(&self.settle) {
            return invalid(
                "settle".into(),
                format!(
                    "{}: give the fraction of the duration after which a run has settled, in [0, 1)",
                    self.settle
                ),
            );
        }
        for (name, value) in [("epsilon1", self.epsilon1), ("epsilon2", self.epsilon2)] {
            if !(value.is_finite() && value > 0.0) {
                return invalid(name.into(), format!("{value}: give a finite value > 0"));
            }
        }
        Ok(())
    }

    /// The base scenario with `set` applied.
    ///
    /// # Errors
    /// A base given by path that was never loaded, or a `set` that makes it invalid.
    pub fn base_scenario(&self) -> Result<Scenario, SweepError> {
        let Base::Inline(base) = &self.base else {
            return Err(SweepError::Invalid {
                field: "base".into(),
                why: "a path base is read by Sweep::load or Sweep::parse".into(),
            });
        };
        base.with_values(self.set.iter().map(|(k, v)| (k.as_str(), v.clone())))
            .map_err(SweepError::Base)
    }

    /// Every run, in run order.
    #[must_use]
    pub fn runs(&self) -> Vec<RunSpec> {
        let values: Vec<Vec<Value>> = self.axes.iter().map(|a| a.values.expand()).collect();
        let points: usize = values.iter().map(Vec::len).product();
        let mut runs = Vec::with_capacity(points.saturating_mul(self.seeds as usize).min(MAX_RUNS));
        for point in 0..points {
            let mut rest = point;
            let mut chosen = vec![Value::Null; values.len()];
            for (k, axis) in values.iter().enumerate().rev() {
                chosen[k] = axis[rest % axis.len()].clone();
                rest /= axis.len();
            }
            for seed in 0..self.seeds {
                runs.push(RunSpec {
                    index: runs.len(),
                    values: chosen.clone(),
                    seed,
                });
            }
        }
        runs
    }

    /// The scenario of a run: the base, `set`, the run's axis values and its seed.
    ///
    /// # Errors
    /// The scenario error of a value the parameter does not take (named by its path).
    pub fn scenario(&self, run: &RunSpec) -> Result<Scenario, ScenarioError> {
        let base = self.base_scenario().map_err(|e| match e {
            SweepError::Base(e) => e,
            other => ScenarioError::invalid("base", "", other.to_string(), "load the sweep file"),
        })?;
        let mut values: Vec<(&str, Value)> = self
            .axes
            .iter()
            .zip(&run.values)
            .map(|(axis, value)| (axis.path.as_str(), value.clone()))
            .collect();
        values.push(("seed", Value::from(run.seed)));
        base.with_values(values)
    }

    /// The sweep as RON with its base inlined: self-contained, as `sweep.ron` of an output
    /// directory and the workers of other processes or machines read it.
    ///
    /// # Errors
    /// The RON serializer's error (never for a loaded sweep).
    pub fn to_ron(&self) -> Result<String, ron::Error> {
        let config = ron::ser::PrettyConfig::new().extensions(Extensions::IMPLICIT_SOME);
        ron::ser::to_string_pretty(self, config)
    }

    /// The Definition 5 criteria of the sweep's runs (their last quarter, ε₁, ε₂).
    #[must_use]
    pub fn criteria(&self) -> flock_metrics::FlockingCriteria {
        flock_metrics::FlockingCriteria {
            epsilon1: self.epsilon1,
            epsilon2: self.epsilon2,
            ..flock_metrics::FlockingCriteria::default()
        }
    }
}

/// Parses self-contained sweep text (an `Inline` base, or paths relative to the current
/// directory).
impl FromStr for Sweep {
    type Err = SweepError;

    fn from_str(text: &str) -> Result<Self, SweepError> {
        Self::parse(text, "<string>", Path::new(""))
    }
}
