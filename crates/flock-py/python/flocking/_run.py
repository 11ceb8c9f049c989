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

# The bytes of page that Run.player() embeds in a notebook at most.
PLAYER_BUDGET = 1_000_000

# What each column of metrics.csv measures (docs/outputs.md): to_xarray()'s ``long_name``. A
# column not listed is named by itself.
LONG_NAMES: Dict[str, str] = {
    "connectivity": "connectivity C = rank(L)/(n - 1)",
    "giant_component": "giant component C*: the largest group's share of the agents",
    "cohesion_radius": "cohesion radius R = max_i |q_i - q_c|",
    "deviation_energy": "deviation energy E~ = E/d^2 (TAC 2006 eq. 7)",
    "velocity_mismatch": "velocity mismatch K~ = K/n, K = 1/2 sum_i |p_i - p_c|^2",
    "min_distance": "least distance between two agents",
    "collisions": "pairs closer than the collision distance",
    "energy": "energy H of the algorithm's theorem (per unit mass)",
    "polarisation": "polarisation |sum_i p_i/|p_i|| / n",
    "milling": "milling |sum_i r_ic x p_i/|p_i|| / n",
    "nearest_neighbour_mean": "mean distance to the nearest neighbour",
    "nearest_neighbour_min": "least distance to the nearest neighbour",
    "group_speed": "group speed |p_c|",
    "components": "groups: connected components of the net",
    "obstacle_clearance": "least signed distance to an obstacle",
    "inside_obstacles": "agents inside obstacles",
    "defect_factor": "defect factor mu = V + w |grad V|^2 (CDS 03-006 eq. 46)",
    "normalised_defect_factor": "normalised defect factor mu_n (CDS 03-006 eq. 47)",
    "structural_energy": "structural energy H_s = V + K_r (CDS 03-006 eq. 48)",
    "translational_energy": "translational energy H_tr (CDS 03-006 eq. 49)",
    "gamma_position_error": "distance |q_mean - q_r| of the flock's centre from the gamma-agent",
    "gamma_velocity_error": "difference |p_mean - p_r| of the mean velocity from the gamma-agent's",
    "stress_towards": "agents of positive local stress (ACC 2004 eq. 31)",
    "stress_away": "agents of negative local stress (ACC 2004 eq. 31)",
    "stress_neutral": "agents of zero local stress (ACC 2004 eq. 31)",
    "velocity_disagreement": "velocity disagreement 1/2 sum_i |p_i - p_c|^2",
    "min_linked_distance": "least distance over the fixed graph's edges",
    "velocity_correlation": "velocity correlation phi_corr (Vasarhelyi et al. 2018)",
    "speed_ratio": "mean speed over the flocking speed (Vasarhelyi et al. 2018)",
    "collision_ratio": "collision ratio phi_coll (Vasarhelyi et al. 2018)",
    "wall_violation": "mean distance outside the arena phi_wall (Vasarhelyi et al. 2018)",
    "links_lost": "fraction of candidate links lost at the last control update",
    "information_age": "mean age of the neighbour states used",
    "at_acceleration_limit": "agents whose commanded acceleration was clipped",
    "at_speed_limit": "agents whose speed was clipped",
    "failed": "agents failed so far",
    "at_turn_rate_limit": "robots at their turn-rate limit",
    "at_wheel_limit": "robots at their wheel-speed limit",
    "at_airspeed_limit": "aircraft at their airspeed limit",
    "at_bank_limit": "aircraft at their bank limit",
    "at_flight_path_limit": "aircraft at their flight-path limit",
    "at_thrust_limit": "quadrotors whose rotor commands were shifted or clipped",
    "at_tilt_limit": "quadrotors held at their tilt limit",
    "acceleration_tracking_error": "mean |(p+ - p)/h - u_i|: the vehicles' tracking error",
}

# The vehicles' state variables (Trajectory.vehicle_columns, docs/outputs.md): (long name, unit).
VEHICLE_STATE: Dict[str, Tuple[str, str]] = {
    "heading": ("unicycle heading theta", "rad"),
    "speed": ("unicycle forward speed v", "m s-1"),
    "turn_rate": ("unicycle turn rate omega", "rad s-1"),
    "airspeed": ("fixed-wing airspeed V", "m s-1"),
    "course": ("fixed-wing course chi, from +x counter-clockwise", "rad"),
    "bank": ("fixed-wing bank phi", "rad"),
    "flight_path": ("fixed-wing flight-path angle gamma", "rad"),
    "attitude_w": ("quadrotor attitude quaternion, w", "1"),
    "attitude_x": ("quadrotor attitude quaternion, x", "1"),
    "attitude_y": ("quadrotor attitude quaternion, y", "1"),
    "attitude_z": ("quadrotor attitude quaternion, z", "1"),
    "angular_velocity_x": ("quadrotor body angular velocity, x", "rad s-1"),
    "angular_velocity_y": ("quadrotor body angular velocity, y", "rad s-1"),
    "angular_velocity_z": ("quadrotor body angular velocity, z", "rad s-1"),
    "rotor_speed_1": ("quadrotor rotor speed, front-left", "rad s-1"),
    "rotor_speed_2": ("quadrotor rotor speed, rear-left", "rad s-1"),
    "rotor_speed_3": ("quadrotor rotor speed, rear-right", "rad s-1"),
    "rotor_speed_4": ("quadrotor rotor speed, front-right", "rad s-1"),
}

# The top-level fields of a scenario written into to_xarray()'s attributes, flattened (the α
# parameters are written resolved, from Scenario.alpha).
_SCENARIO_FIELDS = (
    "algorithm",
    "initial",
    "integrator",
    "collision_distance",
    "vehicle",
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


def _in_notebook() -> bool:
    """Whether this runs in a Jupyter kernel (IPython already imported, with a kernel)."""
    ipython = _sys.modules.get("IPython")
    if ipython is None:
        return False
    try:
        shell = ipython.get_ipython()
    except AttributeError:
        return False
    return shell is not None and getattr(shell, "kernel", None) is not None


class _TerminalProgress:
    """A progress line on ``sys.stderr``, redrawn in place (``\\r``) and cleared at the end."""

    def __init__(self) -> None:
        self.width = 0

    def update(self, line: str, fraction: float) -> None:
        self.width = max(self.width, len(line))
        _sys.stderr.write("\r" + line.ljust(self.width))
        _sys.stderr.flush()

    def close(self, line: str) -> None:
        if self.width:
            _sys.stderr.write("\r" + " " * self.width + "\r")
            _sys.stderr.flush()


class _NotebookProgress:
    """In Jupyter: a progress bar and its line in one output, updated in place through an
    ``IPython.display`` handle, and kept when done with the last line."""

    def __init__(self) -> None:
        display = _importlib.import_module("IPython.display")
        self._html = display.HTML
        self.fraction = 0.0
        self.handle = display.display(self._html(self._bar("starting…", 0.0)), display_id=True)

    @staticmethod
    def _bar(line: str, fraction: float) -> str:
        return (
            f'<div style="font-family:monospace;font-size:12px"><progress max="1" value="{fraction:.3f}" '
            f'style="width:16em;vertical-align:middle"></progress> {_html.escape(line)}</div>'
        )

    def update(self, line: str, fraction: float) -> None:
        # the text bar of the terminal's line is the <progress> element here
        text = line.split("] ", 1)[-1]
        self.fraction = fraction
        self.handle.update(self._html(self._bar(text, fraction)))

    def close(self, line: str) -> None:
        # the last line of a finished run says (100 %); an interrupted one keeps its last fraction
        self.handle.update(self._html(self._bar(line, 1.0 if "(100 %)" in line else self.fraction)))


def _progress_sink(progress: Optional[bool]) -> Optional[Any]:
    """Where a run's or a sweep's progress goes: in Jupyter a bar kept when done (unless
    ``progress=False``), elsewhere a line on ``sys.stderr`` when asked or when it is a terminal."""
    if progress is False:
        return None
    if _in_notebook():
        return _NotebookProgress()
    return _TerminalProgress() if _show_progress(progress) else None


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
      (int64), then the protocol's diagnostics, its counts int64), one entry per recorded step.
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
        """The metrics as a pandas DataFrame, one row per recorded step, the counts
        (``collisions``, ``components``, ``failed``, every ``at_…_limit``, …) as int64 (needs
        pandas: ``pip install 'flocking[pandas]'``)."""
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
        - With a ``vehicle`` other than ``PointMass``, its state variables (``heading``,
          ``speed``, ``turn_rate`` of a unicycle, …, ``Trajectory.vehicle_columns``) over
          (time, agent), each with its ``long_name`` and unit.
        - Every variable and coordinate has a ``long_name`` (what it measures,
          ``docs/outputs.md``); the counts (``collisions``, ``components``, every
          ``at_…_limit``, …) are int64.
        - Attributes, each name once: the scenario's ``name``, ``dim``, ``agents``, ``seed``,
          ``step``, ``duration``, ``record_every``; the rest of the scenario flattened by dotted
          path (``algorithm`` the variant's name and its gains ``algorithm.c1``, …; the resolved
          α parameters ``alpha.d``, ``alpha.r``, ``alpha.epsilon``, ``alpha.a``, ``alpha.b``,
          ``alpha.h``, ``alpha.c1``, ``alpha.c2``; ``initial.positions``, ``integrator``,
          ``collision_distance``, the vehicle and its parameters ``vehicle = "Unicycle"``,
          ``vehicle.max_speed``, …, ``obstacles.0.radius``, ``conditions.communication.delay``;
          booleans as 0/1); the full RON text as ``scenario``, and ``verdict`` and ``path``
          when the run has them.
        """
        xarray = _require("xarray", "xarray", "Run.to_xarray()")
        scenario = self.scenario
        n, dim = self.final.positions.shape
        metrics = dict(self.metrics)
        times = metrics.pop("t")
        coords: Dict[str, Any] = {
            "agent": ("agent", _np.arange(n), {"long_name": "agent index i"}),
            "axis": ("axis", ["x", "y", "z"][:dim], {"long_name": "axis of space"}),
        }
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
            if trajectory.vehicle is not None:
                for k, column in enumerate(trajectory.vehicle_columns):
                    long_name, units = VEHICLE_STATE.get(column, (column.replace("_", " "), "1"))
                    data[column] = (
                        ("time", "agent"),
                        trajectory.vehicle[:, :, k],
                        {"long_name": long_name, "units": units},
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
            long_name = LONG_NAMES.get(name, name.replace("_", " "))
            data[name] = ((metrics_time,), column, {"long_name": long_name, "units": UNITS.get(name, "1")})
        algorithm = scenario.value("algorithm")
        attrs: Dict[str, Any] = {
            "name": scenario.name,
            "dim": scenario.dim,
            "agents": scenario.agents,
            "seed": scenario.seed,
            "step": scenario.step,
            "duration": scenario.duration,
            "record_every": scenario.record_every,
        }
        for field in _SCENARIO_FIELDS:
            try:
                value = scenario.value(field)
            except ValueError:
                continue
            _flatten(field, value, attrs)
        attrs["algorithm"] = next(iter(algorithm)) if isinstance(algorithm, dict) else str(algorithm)
        attrs.update({f"alpha.{name}": value for name, value in scenario.alpha.items()})
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

    def player_html(self, *, max_frames: int = 500, size: int = 480, max_bytes: Optional[int] = None) -> str:
        """The run in the self-contained canvas player of ``flocking plot`` (``player.html``),
        with the readout of its metrics, at most ``max_frames`` frames on a ``size`` × ``size``
        canvas; with ``max_bytes``, fewer frames when the page would be larger (evenly spaced,
        first and last kept; the page says so). Needs the trajectory."""
        if self.trajectory is None:
            raise ValueError("the run kept no trajectory: run it with trajectory=True")
        t = self.trajectory
        metrics = [(name, _np.asarray(column, dtype=float)) for name, column in self.metrics.items()]
        return _flocking.run_player_html(
            self.scenario,
            t.times,
            t.positions,
            t.velocities,
            metrics,
            max_frames=max_frames,
            size=size,
            max_bytes=max_bytes,
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

    def player(self, *, max_frames: int = 500, size: int = 480, max_bytes: int = PLAYER_BUDGET) -> _Html:
        """The HTML player of :meth:`player_html` in an iframe, for Jupyter to show, within
        ``max_bytes`` (1 MB by default, :data:`PLAYER_BUDGET`, as a notebook keeps it in the
        ``.ipynb``): a larger run shows fewer frames, evenly spaced, first and last kept, and the
        player says how many under its canvas (200 agents × 501 frames: 198 frames, 0.96 MB of
        2.4 MB)."""
        player = _html.escape(
            self.player_html(max_frames=max_frames, size=size, max_bytes=max_bytes), quote=True
        )
        width, height = size + 320, size + 180
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

    ``progress``: the simulated time, steps/s and the time left while it runs. In Jupyter (an
    IPython kernel) a bar in the cell's output, updated in place and kept when done with the
    run's last line (steps, wall time); elsewhere a line on ``sys.stderr``, redrawn and cleared at
    the end, by default only when ``sys.stderr`` is a terminal (never in a pipe or a captured
    stream). ``False`` hides it, ``True`` draws it anywhere.

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
        progress=_progress_sink(progress),
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
            progress=_progress_sink(progress),
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
