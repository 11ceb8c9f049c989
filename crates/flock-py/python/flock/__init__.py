"""flock: Olfati-Saber's flocking algorithms (IEEE TAC 51(3) 2006, Caltech CDS 03-006, ACC 2004)
and the Tanner-Jadbabaie-Pappas law, in Rust, from Python.

- :class:`Scenario`: a RON scenario (``Scenario.load``, ``Scenario.from_ron``, ``to_ron``), any
  parameter changed by its path (``with_values``), explicit initial states (``with_initial``).
- :func:`run`: a whole run as numpy arrays (:class:`Run`), and the run directory of
  ``flock run --out`` when ``out`` is given; :func:`resume` continues an interrupted one;
  :func:`read_run` reads any run directory.
- :class:`Simulation`: a run driven step by step (``step``, ``q``, ``p``, ``t``, ``metrics``,
  ``energy``).
- Errors: :class:`FlockError`, :class:`ScenarioError` (a ``ValueError``, with ``field``),
  :class:`NumericalError`, :class:`RunDirectoryError` (an ``OSError``).

Example::

    import flock

    scenario = flock.Scenario.load("fixtures/tac2006_fig11_alg2_n100.ron")
    result = flock.run(scenario)
    print(result.metrics["connectivity"][-1])
"""

from dataclasses import dataclass
from os import PathLike
from typing import TYPE_CHECKING, Any, Dict, Optional, Union

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
    """A run's records, as ``flock run --out`` writes them.

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
    """Runs ``scenario`` to its end: the bits of ``flock run`` of the same scenario.

    With ``out``, also writes its run directory as ``flock run --out`` does, byte for byte
    (``trajectory_format`` ``"csv"`` or ``"npy"``; a checkpoint every ``checkpoint_every``
    steps; an existing directory is replaced only with ``force``). ``trajectory=False`` keeps
    only the metrics and the final state in memory.

    The GIL is released while Rust runs. Ctrl-C raises ``KeyboardInterrupt`` after the current
    step; ``out`` is then left resumable with :func:`resume` (or ``flock run --resume``).

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
    checkpoint, as ``flock run --resume`` does (the finished directory is byte-identical to that
    of an uninterrupted run), and returns the whole run read back from it."""
    return Run._from_dict(_flock.resume(str(dir), checkpoint_every=checkpoint_every))


def read_run(dir: Path) -> Run:
    """Reads a run directory written by ``flock run --out`` or :func:`run` (complete, or an
    interrupted ``DIR.partial``), with a ``trajectory.csv`` or a ``trajectory.npy``; the final
    state is the last recorded one."""
    return Run._from_dict(_flock.read_run(str(dir)))
