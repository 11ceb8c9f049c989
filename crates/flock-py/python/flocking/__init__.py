"""flocking: Olfati-Saber's flocking algorithms (IEEE TAC 51(3) 2006, Caltech CDS 03-006, ACC 2004)
and the Tanner-Jadbabaie-Pappas law, in Rust, from Python.

- :class:`Scenario`: a RON scenario (``Scenario.load``, ``Scenario.from_ron``, ``to_ron``), any
  parameter changed by its path (``with_values``), explicit initial states (``with_initial``).
- :func:`run`: a whole run as numpy arrays (:class:`Run`), and the run directory of
  ``flocking run --out`` when ``out`` is given; :func:`resume` continues an interrupted one;
  :func:`read_run` reads any run directory.
- :class:`Simulation`: a run driven step by step (``step``, ``q``, ``p``, ``t``, ``metrics``,
  ``energy``).
- :func:`sweep`: a sweep file's runs on any ``concurrent.futures.Executor`` (a local process
  pool by default, a Dask cluster, Slurm through dask-jobqueue), into the ``runs.csv`` that
  ``flocking sweep`` writes, byte for byte.
- Errors: :class:`FlockError`, :class:`ScenarioError` (a ``ValueError``, with ``field``),
  :class:`NumericalError`, :class:`RunDirectoryError` (an ``OSError``).

Example::

    import flocking

    scenario = flocking.Scenario.load("fixtures/tac2006_fig11_alg2_n100.ron")
    result = flocking.run(scenario)
    print(result.metrics["connectivity"][-1])
"""

from dataclasses import dataclass
from os import PathLike
import concurrent.futures
import csv
import os
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Union

import numpy as np

from . import _flock
from ._errors import FlockError, NumericalError, RunDirectoryError, ScenarioError
from ._flock import METRICS_HEADER, Scenario, Simulation

if TYPE_CHECKING:  # pragma: no cover
    import pandas

__all__ = [
    "FlockError",
    "METRICS_HEADER",
    "NumericalError",
    "Run",
    "RunDirectoryError",
    "Scenario",
    "ScenarioError",
    "Simulation",
    "State",
    "Trajectory",
    "read_run",
    "resume",
    "run",
    "sweep",
    "SweepResult",
]

Path = Union[str, "PathLike[str]"]


@dataclass(frozen=True)
class State:
    """The state of every agent at time ``t``: ``positions`` and ``velocities`` are (n, dim)
    float64 arrays, agent i on row i (its original index)."""

    t: float
    positions: np.ndarray
    velocities: np.ndarray


@dataclass(frozen=True)
class Trajectory:
    """The recorded states: ``times`` (T,), ``positions`` and ``velocities`` (T, n, dim) float64
    arrays; frame k is the state at ``times[k]``."""

    times: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray


@dataclass(frozen=True)
class Run:
    """A run's records, as ``flocking run --out`` writes them.

    - ``scenario``: the scenario run.
    - ``metrics``: the columns of ``metrics.csv`` by name (``t``, ``connectivity``,
      ``giant_component``, ``cohesion_radius``, ``deviation_energy``, ``velocity_mismatch``,
      ``min_distance``, ``collisions`` (int64), ``energy``, then the protocol's diagnostics), one
      entry per recorded step.
    - ``trajectory``: the recorded states, or None when the run kept none (``trajectory=False``).
    - ``final``: the final state.
    - ``path``: the run directory, or None.
    """

    scenario: Scenario
    metrics: Dict[str, np.ndarray]
    trajectory: Optional[Trajectory]
    final: State
    path: Optional[str]

    def to_pandas(self) -> "pandas.DataFrame":
        """The metrics as a pandas DataFrame, one row per recorded step (needs pandas)."""
        import pandas

        return pandas.DataFrame(self.metrics)

    @classmethod
    def _from_dict(cls, raw: Dict[str, Any]) -> "Run":
        trajectory = None
        if raw["times"] is not None:
            trajectory = Trajectory(raw["times"], raw["positions"], raw["velocities"])
        final = raw["final"]
        return cls(
            scenario=raw["scenario"],
            metrics=raw["metrics"],
            trajectory=trajectory,
            final=State(final["t"], final["positions"], final["velocities"]),
            path=raw["path"],
        )


def run(
    scenario: Scenario,
    out: Optional[Path] = None,
    *,
    trajectory: bool = True,
    trajectory_format: str = "csv",
    checkpoint_every: int = 1000,
    force: bool = False,
) -> Run:
    """Runs ``scenario`` to its end: the bits of ``flocking run`` of the same scenario.

    With ``out``, also writes its run directory as ``flocking run --out`` does, byte for byte
    (``trajectory_format`` ``"csv"`` or ``"npy"``; a checkpoint every ``checkpoint_every``
    steps; an existing directory is replaced only with ``force``). ``trajectory=False`` keeps
    only the metrics and the final state in memory.

    The GIL is released while Rust runs. Ctrl-C raises ``KeyboardInterrupt`` after the current
    step; ``out`` is then left resumable with :func:`resume` (or ``flocking run --resume``).

    Raises :class:`ScenarioError`, :class:`NumericalError` (the records up to the last good step
    stay in ``out.partial``) or :class:`RunDirectoryError`; the scenario's warnings are issued as
    ``UserWarning``.
    """
    raw = _flock.run(
        scenario,
        None if out is None else str(out),
        trajectory=trajectory,
        trajectory_format=trajectory_format,
        checkpoint_every=checkpoint_every,
        force=force,
    )
    return Run._from_dict(raw)


def resume(dir: Path, *, checkpoint_every: int = 1000) -> Run:
    """Continues the interrupted or killed run in ``dir`` (or ``dir.partial``) from its last
    checkpoint, as ``flocking run --resume`` does (the finished directory is byte-identical to that
    of an uninterrupted run), and returns the whole run read back from it."""
    return Run._from_dict(_flock.resume(str(dir), checkpoint_every=checkpoint_every))


def read_run(dir: Path) -> Run:
    """Reads a run directory written by ``flocking run --out`` or :func:`run` (complete, or an
    interrupted ``DIR.partial``), with a ``trajectory.csv`` or a ``trajectory.npy``; the final
    state is the last recorded one."""
    return Run._from_dict(_flock.read_run(str(dir)))


@dataclass(frozen=True)
class SweepResult:
    """A finished sweep: ``path`` its output directory, ``columns`` the columns of its
    ``runs.csv`` by name (numbers as float64 arrays, empty fields as NaN; ``id``, ``error`` and
    non-numeric axis values as lists of str)."""

    path: str
    columns: Dict[str, Any]

    def to_pandas(self) -> "pandas.DataFrame":
        """``runs.csv`` as a pandas DataFrame, one row per run (needs pandas)."""
        import pandas

        return pandas.read_csv(os.path.join(self.path, "runs.csv"))


def _sweep_run(text: str, index: int):
    """Runs run ``index`` of the self-contained sweep ``text`` (in a worker process)."""
    return _flock.sweep_run(text, index)


def _read_runs(path: str) -> Dict[str, Any]:
    with open(os.path.join(path, "runs.csv"), newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    columns: Dict[str, Any] = {}
    for k, name in enumerate(header):
        values: List[str] = [row[k] for row in body]
        if name in ("alpha_flock", "strict_alpha_flock"):
            columns[name] = np.array(
                [{"true": 1.0, "false": 0.0}.get(v, np.nan) for v in values]
            )
            continue
        try:
            columns[name] = np.array([float(v) if v else np.nan for v in values])
        except ValueError:
            columns[name] = values
    return columns


def sweep(
    spec: Path,
    out: Path,
    executor: Optional[concurrent.futures.Executor] = None,
) -> SweepResult:
    """Runs the sweep file ``spec`` into the output directory ``out``, as ``flocking sweep`` does:
    the same row files, ``runs.csv`` (byte for byte) and ``times.csv``; runs found finished in
    ``out`` are skipped, so an interrupted sweep resumes.

    Each run is one call of a worker function submitted to ``executor``: a local process pool
    with one worker per core by default; a Dask cluster with
    ``dask.distributed.Client(...).get_executor()``; a Slurm cluster with dask-jobqueue's
    ``SLURMCluster`` behind such a client. Every worker needs this package installed. Rows are
    written by this process as their runs finish; ``runs.csv`` is assembled in run order at the
    end, so it does not depend on the executor or the order of completion.

    Raises :class:`ScenarioError` for a bad sweep file and :class:`RunDirectoryError` for a
    directory of another sweep; a run that fails is a row with its error, not an exception.
    """
    spec_path = os.fspath(spec)
    with open(spec_path) as f:
        text, count = _flock.sweep_load(
            f.read(), spec_path, os.path.dirname(os.path.abspath(spec_path))
        )
    out_path = os.fspath(out)
    finished = set(_flock.sweep_prepare(out_path, text))
    pending = [k for k in range(count) if k not in finished]
    own = executor is None
    if executor is None:
        executor = concurrent.futures.ProcessPoolExecutor(max_workers=os.cpu_count() or 1)
    try:
        futures = [executor.submit(_sweep_run, text, k) for k in pending]
        for future in concurrent.futures.as_completed(futures):
            index, run_id, fields, wall_time = future.result()
            _flock.sweep_write_row(out_path, index, run_id, fields, wall_time)
    finally:
        if own:
            executor.shutdown()
    _flock.sweep_assemble(out_path, text)
    return SweepResult(out_path, _read_runs(out_path))
