"""flocking: Olfati-Saber's flocking algorithms (IEEE TAC 51(3) 2006, Caltech CDS 03-006, ACC 2004)
and the Tanner-Jadbabaie-Pappas law and velocity consensus, in Rust, from Python.

- :class:`Scenario`: a RON scenario (``Scenario.load``, ``Scenario.from_ron``, ``to_ron``), any
  parameter changed by its path (``with_values``), explicit initial states (``with_initial``).
- :func:`run`: a whole run as numpy arrays (:class:`Run`: ``to_pandas``, ``to_xarray``, an HTML
  summary with a snapshot in Jupyter, ``player()``), a progress line in a terminal, and the run directory of ``flocking run --out`` when ``out`` is
  given; :func:`resume` continues an interrupted one; :func:`read_run` reads any run directory;
  :func:`plot` (and ``Run.plot``) draws a run directory's figures as ``flocking plot`` does.
- :class:`Simulation`: a run driven step by step (``step``, ``q``, ``p``, ``t``, ``metrics``,
  ``energy``).
- ``controls=f`` (of :func:`run`, :func:`resume`, :class:`Simulation` and :func:`sweep`): the
  inputs u_i computed by ``f(t, q, p, neighbours)`` in numpy on the proximity net
  (:class:`Neighbours`), everything else from the scenario's algorithm; ``controls=Local(g)``:
  a local controller ``g(t, perception)`` of what every agent perceives (:class:`Perception`:
  the delay, loss, range and noise of the scenario applied), under every condition and vehicle.
- :mod:`flocking.env`: the scenario as Gymnasium and PettingZoo environments (many flocks stepped
  together in Rust), the scenario's protocol as the baseline.
- :func:`sweep`: a sweep file's runs, or a grid around a :class:`Scenario` defined in Python
  (``axes=``, ``seeds=``), on any ``concurrent.futures.Executor`` (a local process
  pool by default, a Dask cluster, Slurm through dask-jobqueue), into the ``runs.csv`` that
  ``flocking sweep`` writes, byte for byte (:class:`SweepResult`).
- :func:`bench`: ``flocking bench`` from Python, the same engine and report
  (:class:`BenchReport`, :class:`WorkloadReport`).
- :func:`bump`: the built-in bump ρ_h, for ``controls`` functions written in numpy.
- Errors: :class:`FlockError`, :class:`ScenarioError` (a ``ValueError``, with ``field``),
  :class:`NumericalError`, :class:`RunDirectoryError` (an ``OSError``), :class:`ControlsError`,
  :class:`SimulationError`.

Example::

    import flocking

    scenario = flocking.Scenario.load("fixtures/tac2006_fig11_alg2_n100.ron")
    result = flocking.run(scenario)
    print(result.metrics["connectivity"][-1])
"""

from ._bench import BenchReport, WorkloadReport, bench
from ._errors import (
    ControlsError,
    FlockError,
    NumericalError,
    RunDirectoryError,
    ScenarioError,
    SimulationError,
)
from ._flocking import (
    METRICS_HEADER,
    Local,
    Neighbours,
    Perception,
    Scenario,
    Simulation,
    __version__,
    _render,
    bump,
)
from ._run import Run, State, Trajectory, plot, read_run, resume, run
from ._sweep import SweepResult, read_sweep, sweep

__all__ = [
    "BenchReport",
    "ControlsError",
    "FlockError",
    "Local",
    "METRICS_HEADER",
    "Neighbours",
    "NumericalError",
    "Perception",
    "Run",
    "RunDirectoryError",
    "Scenario",
    "ScenarioError",
    "Simulation",
    "SimulationError",
    "State",
    "SweepResult",
    "Trajectory",
    "WorkloadReport",
    "bench",
    "bump",
    "plot",
    "read_run",
    "read_sweep",
    "resume",
    "run",
    "sweep",
]
