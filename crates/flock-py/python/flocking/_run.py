"""Runs: :func:`run`, :func:`resume`, :func:`read_run` and their result :class:`Run` (with
:class:`State` and :class:`Trajectory`), as numpy arrays, pandas, xarray and, in Jupyter, HTML."""

from dataclasses import dataclass as _dataclass
import html as _html
import importlib as _importlib
from os import PathLike as _PathLike
import sys as _sys
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _flocking
from ._flocking import Scenario

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray

Path = Union[str, "_PathLike[str]"]
Controls = Callable[..., Any]


# The unit of every column of metrics.csv (docs/outputs.md); "1" for a dimensionless ratio or a count.
UNITS: Dict[str, str] = {
    "t": "s",
    "connectivity": "1",
    "giant_component": "1",
    "cohesion_radius": "m",
    "deviation_energy": "1",
    "velocity_mismatch": "m2 s-2",
    "min_distance": "m",
    "collisions": "1",
    "energy": "m2 s-2",
    "polarisation": "1",
    "milling": "1",
    "nearest_neighbour_mean": "m",
    "nearest_neighbour_min": "m",
    "group_speed": "m s-1",
    "components": "1",
    "obstacle_clearance": "m",
    "inside_obstacles": "1",
    "defect_factor": "m2",
    "normalised_defect_factor": "1",
    "structural_energy": "m2 s-2",
    "translational_energy": "m2 s-2",
    "gamma_position_error": "m",
    "gamma_velocity_error": "m s-1",
    "stress_towards": "1",
    "stress_away": "1",
    "stress_neutral": "1",
    "velocity_disagreement": "m2 s-2",
    "min_linked_distance": "m",
    "velocity_correlation": "1",
    "speed_ratio": "1",
    "collision_ratio": "1",
    "wall_violation": "m",
    "links_lost": "1",
    "information_age": "s",
    "at_acceleration_limit": "1",
    "at_speed_limit": "1",
    "failed": "1",
}

# The top-level fields of a scenario written into to_xarray()'s attributes, flattened.
_SCENARIO_FIELDS = (
    "algorithm",
    "alpha",
    "initial",
    "integrator",
    "collision_distance",
    "obstacles",
    "conditions",
)


def _show_progress(progress: Optional[bool]) -> bool:
    """Whether to draw a progress line: as asked, else when ``sys.stderr`` is a terminal."""
    if progress is not None:
        return bool(progress)
    try:
        return bool(_sys.stderr is not None and _sys.stderr.isatty())
    except (AttributeError, ValueError):
        return False


def _flatten(prefix: str, value: Any, attrs: Dict[str, Any]) -> None:
    """``value`` (a scenario's value: numbers, strings, lists, dicts, an enum as ``{"Variant":
    ...}``) as netCDF-safe attributes named by dotted paths: ``algorithm = "Algorithm2"``,
    ``algorithm.c1 = 0.02``, ``initial.positions.std = 50.0``."""
    if value is None:
        return
    if isinstance(value, bool):
        attrs[prefix] = int(value)
    elif isinstance(value, (int, float, str)):
        attrs[prefix] = value
    elif isinstance(value, dict):
        if len(value) == 1:
            (key, inner), = value.items()
            if key[:1].isupper():  # an enum variant and its fields
                attrs[prefix] = key
                if isinstance(inner, dict):
                    for k, v in inner.items():
                        _flatten(f"{prefix}.{k}", v, attrs)
                elif inner is not None:
                    _flatten(f"{prefix}.value", inner, attrs)
                return
        for key, inner in value.items():
            _flatten(f"{prefix}.{key}", inner, attrs)
    elif isinstance(value, (list, tuple)):
        number = lambda v: isinstance(v, (int, float)) and not isinstance(v, bool)  # noqa: E731
        if value and all(number(v) for v in value):
            attrs[prefix] = list(value)
        elif value and all(isinstance(v, (list, tuple)) and all(number(x) for x in v) for v in value):
            # rows of numbers (explicit positions, a graph's edges): one flat list, row after row
            attrs[prefix] = [x for v in value for x in v]
        else:
            for k, inner in enumerate(value):
                _flatten(f"{prefix}.{k}", inner, attrs)


def _svg_snapshot(positions: _np.ndarray, t: float, size: int = 320) -> str:
    """The agents at one instant as a small SVG (x right, y up; 3D seen from the top), each a dot:
    about 40 bytes an agent."""
    n = len(positions)
    header = f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" viewBox="0 0 {size} {size}">'
    if n == 0:
        return header + "</svg>"
    xy = _np.asarray(positions, dtype=float)[:, :2]
    finite = _np.isfinite(xy).all(axis=1)
    if not finite.any():
        return header + "</svg>"
    lo, hi = xy[finite].min(axis=0), xy[finite].max(axis=0)
    span = float(max(hi[0] - lo[0], hi[1] - lo[1], 1e-9))
    margin = 10.0
    scale = (size - 2 * margin) / span
    centre = (lo + hi) / 2
    dots = []
    for (x, y), ok in zip(xy, finite):
        if ok:
            px = size / 2 + (x - centre[0]) * scale
            py = size / 2 - (y - centre[1]) * scale
            dots.append(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="2"/>')
    caption = f'<text x="6" y="{size - 6}" font-size="11" font-family="sans-serif">t = {t:g} s, {span:.3g} m across</text>'
    return f'{header}<rect width="100%" height="100%" fill="white"/><g fill="#1f77b4">{"".join(dots)}</g>{caption}</svg>'


class _Html:
    """An HTML fragment that Jupyter shows (``_repr_html_``)."""

    def __init__(self, html: str) -> None:
        self.html = html

    def _repr_html_(self) -> str:
        return self.html

    def __repr__(self) -> str:
        return f"<HTML of {len(self.html)} characters: display it in Jupyter>"


def _require(module: str, extra: str, what: str) -> Any:
    """Imports the optional dependency ``module`` of ``what``, or says how to install it."""
    try:
        return _importlib.import_module(module)
    except ImportError as error:
        raise ImportError(
            f"{what} needs {module}, which is not installed: pip install 'flocking[{extra}]'"
        ) from error


@_dataclass(frozen=True, repr=False)
class State:
    """The state of every agent at time ``t``: ``positions`` and ``velocities`` are (n, dim)
    float64 arrays, agent i on row i (its original index). With a ``vehicle`` other than
    ``PointMass``, the positions and velocities are the reference point's and ``vehicle`` is
    the (n, k) array of each vehicle's state, named by ``vehicle_columns`` (``heading``,
    ``bank``, ``attitude_w``…, docs/vehicles.md); None for point masses. With
    ``conditions.faults``, ``failed`` (n,) is True for each agent that has failed (the
    ``failed`` column of ``final.csv``); None without faults."""

    t: float
    positions: _np.ndarray
    velocities: _np.ndarray
    vehicle: Optional[_np.ndarray] = None
    vehicle_columns: Tuple[str, ...] = ()
    failed: Optional[_np.ndarray] = None

    def __repr__(self) -> str:
        n, dim = self.positions.shape
        return f"State(t={self.t}, n={n}, dim={dim})"


@_dataclass(frozen=True, repr=False)
class Trajectory:
    """The recorded states: ``times`` (T,), ``positions`` and ``velocities`` (T, n, dim) float64
    arrays; frame k is the state at ``times[k]``. ``vehicle`` (T, n, k) holds the vehicles'
    states named by ``vehicle_columns`` (None for point masses). With ``conditions.faults``,
    ``failed`` (T, n) is True where an agent has failed (the ``failed`` column of
    ``trajectory.csv``; its sum over a frame is that record's ``failed`` metric); None without."""

    times: _np.ndarray
    positions: _np.ndarray
    velocities: _np.ndarray
    vehicle: Optional[_np.ndarray] = None
    vehicle_columns: Tuple[str, ...] = ()
    failed: Optional[_np.ndarray] = None

    def __repr__(self) -> str:
        frames, n, dim = self.positions.shape
        span = f", t={self.times[0]}..{self.times[-1]}" if frames else ""
        return f"Trajectory(frames={frames}, n={n}, dim={dim}{span})"


@_dataclass(frozen=True, repr=False)
class Run:
    """A run's records, as ``flocking run --out`` writes them.

    - ``scenario``: the scenario run.
    - ``metrics``: the columns of ``metrics.csv`` by name (``t``, ``connectivity``,
      ``giant_component``, ``cohesion_radius``, ``deviation_energy``, ``velocity_mismatch``,
      ``min_distance``, ``collisions`` (int64), ``energy``, ``polarisation``, ``milling``,
      ``nearest_neighbour_mean``, ``nearest_neighbour_min``, ``group_speed``, ``components``
      (int64), then the protocol's diagnostics), one entry per recorded step.
    - ``trajectory``: the recorded states, or None when the run kept none (``trajectory=False``);
      recorded at the same instants as the metrics.
    - ``final``: the final state.
    - ``path``: the run directory, or None.
    - ``verdict``: the model's verdict judged over the last quarter of the run — TAC 2006
      Definition 5, or a classic model's own states (the first line of ``flocking.txt``) — or
      None (an interrupted run, or no record in the window).

    In Jupyter a run shows a summary table and a snapshot of the final state (a few kB however
    many agents); ``run.player()`` shows the HTML player of ``flocking plot``.
    """

    scenario: Scenario
    metrics: Dict[str, _np.ndarray]
    trajectory: Optional[Trajectory]
    final: State
    path: Optional[str]
    verdict: Optional[str] = None

    def __repr__(self) -> str:
        n, dim = self.final.positions.shape
        records = len(self.metrics.get("t", ()))
        connectivity = self.metrics.get("connectivity")
        final_c = f", C={connectivity[-1]:.4g}" if connectivity is not None and len(connectivity) else ""
        path = f", path={self.path!r}" if self.path is not None else ""
        return (
            f"Run(name={self.scenario.name!r}, dim={dim}, n={n}, duration={self.final.t}, "
            f"records={records}{final_c}{path})"
        )

    def to_pandas(self) -> "pandas.DataFrame":
        """The metrics as a pandas DataFrame, one row per recorded step (needs pandas:
        ``pip install 'flocking[pandas]'``)."""
        pandas = _require("pandas", "pandas", "Run.to_pandas()")
        return pandas.DataFrame(self.metrics)

    def to_xarray(self) -> "xarray.Dataset":
        """The run as an ``xarray.Dataset`` (needs xarray: ``pip install 'flocking[xarray]'``).

        - Dimensions ``time`` × ``agent`` × ``axis`` (coordinates: the record times, agent
          indices 0..n−1, and ``"x"``, ``"y"`` (, ``"z"``)).
        - ``q`` and ``p``: positions and velocities (time, agent, axis), when the run kept its
          trajectory; with ``conditions.faults`` also ``agent_failed`` (time, agent), True
          where the agent has failed (its sum over ``agent`` is the metric ``failed``).
        - Units (``units`` attributes, UDUNITS): ``time`` in s, ``q`` in m, ``p`` in m s-1, and
          every metric's, "1" for ratios and counts (``docs/outputs.md``).
        - Every column of ``metrics.csv`` but ``t`` as a variable over ``time``: a run records
          its metrics and its trajectory at the same instants (t = 0, every ``record_every``
          steps and the last step), so they share the one ``time`` dimension. (A run directory
          whose files disagree would give the metrics their own ``metrics_time``.)
        - Attributes: the scenario's ``name``, ``dim``, ``agents``, ``seed``, ``step``,
          ``duration``, ``record_every``, ``algorithm``, the resolved α parameters as
          ``alpha_d``, ``alpha_r``, ``alpha_epsilon``, ``alpha_a``, ``alpha_b``, ``alpha_h``,
          ``alpha_c1``, ``alpha_c2``; the rest of the scenario flattened by dotted path (the gains
          ``algorithm.c1``, ``algorithm.c2``, …, ``algorithm`` the variant's name, likewise
          ``initial.positions``, ``integrator``, ``collision_distance``, ``obstacles.0.radius``,
          ``conditions.communication.delay``; booleans as 0/1); the full RON text as
          ``scenario``, and ``verdict`` and ``path`` when the run has them.
        """
        xarray = _require("xarray", "xarray", "Run.to_xarray()")
        scenario = self.scenario
        n, dim = self.final.positions.shape
        metrics = dict(self.metrics)
        times = metrics.pop("t")
        coords: Dict[str, Any] = {"agent": _np.arange(n), "axis": ["x", "y", "z"][:dim]}
        data: Dict[str, Any] = {}
        trajectory = self.trajectory
        if trajectory is not None:
            coords["time"] = trajectory.times
            data["q"] = (
                ("time", "agent", "axis"),
                trajectory.positions,
                {"long_name": "position q_i", "units": "m"},
            )
            data["p"] = (
                ("time", "agent", "axis"),
                trajectory.velocities,
                {"long_name": "velocity p_i", "units": "m s-1"},
            )
            if trajectory.failed is not None:
                data["agent_failed"] = (
                    ("time", "agent"),
                    trajectory.failed,
                    {"long_name": "agent i has failed", "units": "1"},
                )
        same = trajectory is None or _np.array_equal(trajectory.times, times)
        metrics_time = "time" if same else "metrics_time"
        coords[metrics_time] = times
        for name, column in metrics.items():
            data[name] = ((metrics_time,), column, {"units": UNITS.get(name, "1")})
        algorithm = scenario.value("algorithm")
        attrs: Dict[str, Any] = {
            "name": scenario.name,
            "dim": scenario.dim,
            "agents": scenario.agents,
            "seed": scenario.seed,
            "step": scenario.step,
            "duration": scenario.duration,
            "record_every": scenario.record_every,
            "algorithm": next(iter(algorithm)) if isinstance(algorithm, dict) else str(algorithm),
        }
        attrs.update({f"alpha_{name}": value for name, value in scenario.alpha.items()})
        for field in _SCENARIO_FIELDS:
            try:
                value = scenario.value(field)
            except ValueError:
                continue
            _flatten(field, value, attrs)
        attrs["algorithm"] = next(iter(algorithm)) if isinstance(algorithm, dict) else str(algorithm)
        attrs["scenario"] = scenario.to_ron()
        if self.verdict is not None:
            attrs["verdict"] = self.verdict
        if self.path is not None:
            attrs["path"] = self.path
        dataset = xarray.Dataset(data, coords=coords, attrs=attrs)
        for time in ("time", "metrics_time"):
            if time in dataset.coords:
                dataset[time].attrs.update({"units": "s", "long_name": "time t"})
        return dataset

    def _summary(self) -> Dict[str, str]:
        """The rows of the HTML summary: name, dim, n, duration, the final C, C*, Ẽ, K̃, the least
        distance of the run and the model's verdict."""
        n, dim = self.final.positions.shape
        rows = {"name": self.scenario.name, "dim": str(dim), "n": str(n), "duration": f"{self.final.t:g}"}
        last = {
            "final C": "connectivity",
            "final C*": "giant_component",
            "final Ẽ": "deviation_energy",
            "final K̃": "velocity_mismatch",
        }
        for label, name in last.items():
            column = self.metrics.get(name)
            if column is not None and len(column):
                rows[label] = f"{column[-1]:.4g}"
        distances = self.metrics.get("min_distance")
        if distances is not None and len(distances):
            rows["least distance"] = f"{_np.nanmin(distances):.4g}"
        if self.verdict is not None:
            rows["verdict"] = self.verdict
        return rows

    def player_html(self, *, max_frames: int = 500, size: int = 480) -> str:
        """The run in the self-contained canvas player of ``flocking plot`` (``player.html``), at
        most ``max_frames`` frames on a ``size`` × ``size`` canvas. Needs the trajectory."""
        if self.trajectory is None:
            raise ValueError("the run kept no trajectory: run it with trajectory=True")
        t = self.trajectory
        return _flocking.run_player_html(
            self.scenario, t.times, t.positions, t.velocities, max_frames=max_frames, size=size
        )

    def plot(
        self,
        dir: Optional[Path] = None,
        *,
        outputs: Optional[Sequence[str]] = None,
        times: Optional[Sequence[float]] = None,
        stress_edges: bool = False,
    ) -> List[str]:
        """Draws the run's figures into ``dir/figures`` as ``flocking plot dir`` does (:func:`plot`),
        ``dir`` the run's directory (default :attr:`path`, that of ``flocking.run(..., out=dir)``
        or :func:`read_run`); returns the files written."""
        if dir is None:
            dir = self.path
        if dir is None:
            raise ValueError(
                "this run has no directory to draw from: run it with flocking.run(scenario, out=DIR) "
                "(or read one with flocking.read_run(DIR)), then plot; run.player() shows a run held "
                "only in memory"
            )
        return plot(dir, outputs=outputs, times=times, stress_edges=stress_edges)

    def player(self, *, max_frames: int = 500, size: int = 480) -> _Html:
        """The HTML player of :meth:`player_html` in an iframe, for Jupyter to show (its size
        grows with agents × frames: about 11 MB at n = 1,000 and 500 frames)."""
        player = _html.escape(self.player_html(max_frames=max_frames, size=size), quote=True)
        width, height = size + 80, size + 160
        return _Html(
            f'<iframe srcdoc="{player}" style="width:{width}px;height:{height}px;border:none"></iframe>'
        )

    def _repr_html_(self) -> str:
        """A summary table and a snapshot of the final state, light whatever the run's size (the
        player is ``run.player()``)."""
        rows = "".join(
            f"<tr><th style='text-align:left'>{_html.escape(k)}</th><td style='text-align:left'>{_html.escape(v)}</td></tr>"
            for k, v in self._summary().items()
        )
        table = f"<table>{rows}</table>"
        snapshot = _svg_snapshot(self.final.positions, self.final.t)
        hint = "<p><code>run.player()</code> shows the HTML player.</p>" if self.trajectory is not None else ""
        return f"<div style='display:flex;gap:1em;align-items:flex-start'>{table}<div>{snapshot}{hint}</div></div>"

    @classmethod
    def _from_dict(cls, raw: Dict[str, Any]) -> "Run":
        trajectory = None
        columns = tuple(raw["vehicle_columns"])
        if raw["times"] is not None:
            trajectory = Trajectory(
                raw["times"], raw["positions"], raw["velocities"], raw["vehicle"], columns, raw["failed"]
            )
        final = raw["final"]
        vehicle = final["vehicle"] if columns else None
        return cls(
            scenario=raw["scenario"],
            metrics=raw["metrics"],
            trajectory=trajectory,
            final=State(
                final["t"], final["positions"], final["velocities"], vehicle, columns, final["failed"]
            ),
            path=raw["path"],
            verdict=raw["verdict"],
        )


def run(
    scenario: Scenario,
    out: Optional[Path] = None,
    *,
    trajectory: bool = True,
    trajectory_format: str = "csv",
    checkpoint_every: int = 1000,
    force: bool = False,
    controls: Optional[Controls] = None,
    progress: Optional[bool] = None,
) -> Run:
    """Runs ``scenario`` to its end: the bits of ``flocking run`` of the same scenario.

    ``progress``: a line of the simulated time, steps/s and the time left on ``sys.stderr`` while
    it runs; by default only when ``sys.stderr`` is a terminal (never in a notebook's captured
    output or a pipe). ``False`` hides it, ``True`` draws it anywhere.

    With ``out``, also writes its run directory as ``flocking run --out`` does, byte for byte
    (``trajectory_format`` ``"csv"`` or ``"npy"``; a checkpoint every ``checkpoint_every``
    steps; an existing directory is replaced only with ``force``). ``trajectory=False`` keeps
    only the metrics and the final state in memory.

    ``controls``, a function ``f(t, q, p, neighbours)`` (q and p (n, dim) float64 arrays, agents
    in original order; ``neighbours`` a :class:`Neighbours`, the proximity net built with the
    scenario protocol's interaction range) returning the inputs u as an (n, dim) array, replaces
    the inputs u_i of the scenario's protocol — only them: the net's range, the energy H and the
    diagnostic columns still come from the scenario's algorithm. A result of another shape or not
    finite raises :class:`ControlsError`. An exception of ``f`` stops the run before the step it
    was called for, keeps the records so far and a checkpoint in ``out.partial`` (resumable with
    ``resume(out, controls=f)``, as after Ctrl-C) and is raised again.

    The GIL is released while Rust runs (and taken for each call of ``controls``). Ctrl-C raises
    ``KeyboardInterrupt`` after the current step, or within a second when that step is long (it is
    then cut short and not kept); ``out`` is then left resumable with :func:`resume` (or
    ``flocking run --resume``).

    Raises :class:`ScenarioError`, :class:`NumericalError` (the records up to the last good step
    stay in ``out.partial``) or :class:`RunDirectoryError`; the scenario's warnings are issued as
    ``UserWarning``.
    """
    raw = _flocking.run(
        scenario,
        None if out is None else str(out),
        trajectory=trajectory,
        trajectory_format=trajectory_format,
        checkpoint_every=checkpoint_every,
        force=force,
        controls=controls,
        progress=_show_progress(progress),
    )
    return Run._from_dict(raw)


def resume(
    dir: Path,
    *,
    checkpoint_every: int = 1000,
    controls: Optional[Controls] = None,
    progress: Optional[bool] = None,
) -> Run:
    """Continues the interrupted or killed run in ``dir`` (or ``dir.partial``) from its last
    checkpoint, as ``flocking run --resume`` does (the finished directory is byte-identical to that
    of an uninterrupted run), and returns the whole run read back from it. A run made with
    ``controls`` must be resumed with the same ``controls`` (the directory does not hold it)."""
    return Run._from_dict(
        _flocking.resume(
            str(dir),
            checkpoint_every=checkpoint_every,
            controls=controls,
            progress=_show_progress(progress),
        )
    )


def plot(
    dir: Path,
    *,
    outputs: Optional[Sequence[str]] = None,
    times: Optional[Sequence[float]] = None,
    stress_edges: bool = False,
) -> List[str]:
    """Draws the figures of the run directory ``dir`` into ``dir/figures``, the files of
    ``flocking plot dir`` byte for byte, by the same renderer (no CLI needed): ``outputs`` some of
    ``"snapshots"``, ``"metrics"``, ``"gif"``, ``"player"`` (default all), ``times`` the snapshot
    times in seconds (default the scenario's ``snapshots``, else six even times), ``stress_edges``
    each edge coloured by the sign of its stress weight. Returns the paths written.

    ``ValueError`` for an unknown output or a time outside the run (naming it and the run's
    span); :class:`RunDirectoryError` for a directory that is not a complete run of flocking's,
    holds figures flocking did not write, or is being written."""
    if isinstance(outputs, str):
        outputs = [outputs]
    written = _flocking.plot_run(
        str(dir),
        outputs=None if outputs is None else list(outputs),
        times=None if times is None else [float(t) for t in times],
        stress_edges=stress_edges,
    )
    return [str(path) for path in written]


def read_run(dir: Path) -> Run:
    """Reads a run directory written by ``flocking run --out`` or :func:`run` (complete, or an
    interrupted ``DIR.partial``), with a ``trajectory.csv`` or a ``trajectory.npy``; the final
    state is the last recorded one."""
    return Run._from_dict(_flocking.read_run(str(dir)))
