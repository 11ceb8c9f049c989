"""Type stubs of flocking: Olfati-Saber's flocking algorithms in Rust, from Python."""

import concurrent.futures
from os import PathLike
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike[str]]
_Rows = npt.ArrayLike
_Value = Union[None, bool, int, float, str, List[Any], Dict[str, Any]]
_Controls = Callable[
    [float, npt.NDArray[np.float64], npt.NDArray[np.float64], "Neighbours"], npt.ArrayLike
]
"""``f(t, q, p, neighbours) -> u``: the inputs u (n, dim) of the state q, p (n, dim) at time t."""

METRICS_HEADER: str
"""The header of ``metrics.csv`` before the protocol's diagnostic columns."""

class FlockError(Exception):
    """Any error of flocking."""

class ScenarioError(FlockError, ValueError):
    """An invalid scenario; ``field`` is the dotted path of the field at fault, or None."""

    field: Optional[str]
    def __init__(self, message: str, field: Optional[str] = ...) -> None: ...

class NumericalError(FlockError, ArithmeticError):
    """A numerical blow-up after ``step`` steps (time ``t``), first at agent ``agent``."""

    step: int
    t: float
    agent: int
    def __init__(self, message: str, step: int, t: float, agent: int) -> None: ...

class RunDirectoryError(FlockError, OSError):
    """A run directory that cannot be written or read; ``path`` names it or the file at fault."""

    path: Optional[str]
    def __init__(self, message: str, path: Optional[str] = ...) -> None: ...

class ControlsError(FlockError, ValueError):
    """A ``controls`` function returned something other than (n, dim) finite inputs; ``expected``
    is (n, dim), ``given`` the shape returned (None when it was not an array)."""

    expected: Tuple[int, int]
    given: Optional[Tuple[int, ...]]
    def __init__(
        self, message: str, expected: Tuple[int, int], given: Optional[Tuple[int, ...]] = ...
    ) -> None: ...

class SimulationError(FlockError, RuntimeError):
    """A :class:`Simulation` whose step Ctrl-C cut short after it had changed the state."""

class Neighbours:
    """The proximity net handed to a ``controls`` function, as CSR arrays: agent i's neighbours
    are ``indices[indptr[i]:indptr[i + 1]]`` (ascending) at ``distances[indptr[i]:indptr[i + 1]]``."""

    @property
    def indptr(self) -> npt.NDArray[np.int64]:
        """Where each agent's neighbours start in ``indices`` (n + 1 entries)."""
    @property
    def indices(self) -> npt.NDArray[np.int64]:
        """The neighbours j of every agent i in turn."""
    @property
    def distances(self) -> npt.NDArray[np.float64]:
        """‖q_j − q_i‖ for each entry of ``indices``."""
    def pairs(self) -> npt.NDArray[np.int64]:
        """The directed edges (i, j) as an (m, 2) array, in the order of ``indices``."""
    def __len__(self) -> int: ...

class Perception:
    """What every agent perceives at a control update (agents in original order), handed to a
    ``Local`` controller: agent i measures itself at ``positions[i]``, ``velocities[i]`` and heard
    ``neighbours[indptr[i]:indptr[i + 1]]`` at ``relative_positions`` q_j − q_i and
    ``relative_velocities`` p_j − p_i of the same rows (``heard_by[k]`` heard entry k)."""

    t: float
    positions: npt.NDArray[np.float64]
    velocities: npt.NDArray[np.float64]
    indptr: npt.NDArray[np.int64]
    neighbours: npt.NDArray[np.int64]
    heard_by: npt.NDArray[np.int64]
    relative_positions: npt.NDArray[np.float64]
    relative_velocities: npt.NDArray[np.float64]
    gamma_position: Optional[npt.NDArray[np.float64]]
    gamma_velocity: Optional[npt.NDArray[np.float64]]
    beta_indptr: npt.NDArray[np.int64]
    beta_relative_positions: npt.NDArray[np.float64]
    beta_relative_velocities: npt.NDArray[np.float64]
    def __len__(self) -> int: ...

class Local:
    """``controls=Local(f)``: ``f(t, perception)`` returns every agent's input u (n × dim) from
    what each perceives (:class:`Perception`), under every condition and vehicle."""

    def __init__(self, f: Callable[[float, Perception], npt.ArrayLike]) -> None: ...
    @property
    def function(self) -> Callable[[float, Perception], npt.ArrayLike]: ...
    def __call__(self, t: float, perception: Perception) -> npt.ArrayLike: ...

class Scenario:
    """A flocking scenario, as a RON scenario file writes it (immutable: changes return copies)."""

    @staticmethod
    def load(path: _Path) -> Scenario:
        """Reads and validates the RON scenario file at ``path``."""
    @staticmethod
    def from_ron(text: str, origin: str = "<string>") -> Scenario:
        """Parses and validates scenario text in RON."""
    def to_ron(self) -> str:
        """The scenario as RON text with every default filled in."""
    def value(self, path: str) -> _Value:
        """The value of the parameter at the dotted ``path`` (``"alpha.d"``)."""
    def with_values(self, values: Dict[str, _Value]) -> Scenario:
        """A copy with the parameters at the dotted paths replaced, validated."""
    def with_initial(self, positions: _Rows, velocities: Optional[_Rows] = None) -> Scenario:
        """A copy starting from the given n × dim positions and velocities (zero if omitted);
        another shape (a transposed (dim, n) array) raises :class:`ScenarioError` naming both."""
    def estimate(
        self, *, out: bool = False, trajectory: bool = True, trajectory_format: str = "csv"
    ) -> Dict[str, Optional[float]]:
        """The estimated cost of one run: ``steps``, ``records``, ``agent_steps``,
        ``memory_bytes`` (peak), ``disk_bytes`` (written into ``out`` when ``out`` is True, with
        ``trajectory`` and ``trajectory_format`` as :func:`run` takes them), ``seconds`` (one
        thread) and ``start_mean_degree``: the mean degree of the start's net within the sensing
        range, which scales memory and time above the α-lattice's (None when too dense to count,
        which :func:`run` refuses)."""
    def warnings(self) -> List[str]:
        """The warnings ``flocking validate`` and ``flocking run`` print for this scenario, each
        naming the field and the fix: a step above the largest stable step, agents starting at
        the same point, a γ-agent faster than the vehicle, initial velocities the vehicle clips,
        a model of one step (Vicsek, boids, Couzin) at another step than its paper's, a start
        denser than the α-lattice."""
    @property
    def name(self) -> str:
        """The scenario's name."""
    @property
    def dim(self) -> int:
        """The dimension, 2 or 3."""
    @property
    def agents(self) -> int:
        """The number of agents n."""
    @property
    def step(self) -> float:
        """The time step h."""
    @property
    def duration(self) -> float:
        """The simulated time T."""
    @property
    def seed(self) -> int:
        """The seed of the initial condition's random stream."""
    @property
    def alpha(self) -> Dict[str, float]:
        """The α parameters, defaults resolved: d, r, epsilon, a, b, h, c1, c2."""
    @property
    def steps(self) -> int:
        """The number of steps of a run."""
    @property
    def record_every(self) -> int:
        """Steps between records (the last step is always recorded)."""
    def __eq__(self, other: object) -> bool: ...
    def __reduce__(self) -> Tuple[Any, Tuple[str]]: ...

class Simulation:
    """The simulation of a scenario, stepped from Python."""

    def __init__(
        self,
        scenario: Scenario,
        positions: Optional[_Rows] = None,
        velocities: Optional[_Rows] = None,
        *,
        controls: Optional[_Controls] = None,
    ) -> None: ...
    def step(self, k: int = 1) -> None:
        """Advances the state by ``k`` steps of h (GIL released; Ctrl-C stops between steps, or
        within a second inside a long one, which is then not taken or, cut inside a vehicle's inner
        steps or the conditions' stage, leaves the simulation torn: :class:`SimulationError`
        afterwards; an exception of ``controls`` stops before the step it was called for)."""
    def set_state(
        self, positions: Optional[_Rows] = None, velocities: Optional[_Rows] = None
    ) -> None:
        """Replaces the positions and/or velocities (n × dim) at the current time."""
    @property
    def q(self) -> npt.NDArray[np.float64]:
        """The positions, n × dim (a copy), agents in original order."""
    @property
    def p(self) -> npt.NDArray[np.float64]:
        """The velocities, n × dim (a copy), agents in original order."""
    @property
    def t(self) -> float:
        """The time t = steps · h."""
    @property
    def steps(self) -> int:
        """The number of steps taken."""
    @property
    def dim(self) -> int:
        """The dimension, 2 or 3."""
    @property
    def agents(self) -> int:
        """The number of agents n."""
    @property
    def scenario(self) -> Scenario:
        """The scenario simulated."""
    def metrics(self) -> Dict[str, Union[float, int]]:
        """The flocking metrics of the current state, named as the columns of metrics.csv."""
    def energy(self) -> float:
        """The energy H of the current state."""

class State:
    """The state of every agent at time ``t``: (n, dim) positions and velocities, (n, k)
    vehicle states named by ``vehicle_columns`` (None for point masses), and with
    ``conditions.faults`` which agents have failed, (n,) booleans (None without)."""

    t: float
    positions: npt.NDArray[np.float64]
    velocities: npt.NDArray[np.float64]
    vehicle: Optional[npt.NDArray[np.float64]]
    vehicle_columns: Tuple[str, ...]
    failed: Optional[npt.NDArray[np.bool_]]
    def __init__(
        self,
        t: float,
        positions: npt.NDArray[np.float64],
        velocities: npt.NDArray[np.float64],
        vehicle: Optional[npt.NDArray[np.float64]] = None,
        vehicle_columns: Tuple[str, ...] = (),
        failed: Optional[npt.NDArray[np.bool_]] = None,
    ) -> None: ...

class Trajectory:
    """The recorded states: times (T,), positions and velocities (T, n, dim), the vehicle
    states (T, n, k) named by ``vehicle_columns`` (None for point masses), and with
    ``conditions.faults`` which agents have failed, (T, n) booleans (None without)."""

    times: npt.NDArray[np.float64]
    positions: npt.NDArray[np.float64]
    velocities: npt.NDArray[np.float64]
    vehicle: Optional[npt.NDArray[np.float64]]
    vehicle_columns: Tuple[str, ...]
    failed: Optional[npt.NDArray[np.bool_]]
    def __init__(
        self,
        times: npt.NDArray[np.float64],
        positions: npt.NDArray[np.float64],
        velocities: npt.NDArray[np.float64],
        vehicle: Optional[npt.NDArray[np.float64]] = None,
        vehicle_columns: Tuple[str, ...] = (),
        failed: Optional[npt.NDArray[np.bool_]] = None,
    ) -> None: ...

class Run:
    """A run's records: scenario, metrics columns, trajectory, final state and directory."""

    scenario: Scenario
    metrics: Dict[str, npt.NDArray[Any]]
    trajectory: Optional[Trajectory]
    final: State
    path: Optional[str]
    verdict: Optional[str]
    def __init__(
        self,
        scenario: Scenario,
        metrics: Dict[str, npt.NDArray[Any]],
        trajectory: Optional[Trajectory],
        final: State,
        path: Optional[str],
        verdict: Optional[str] = None,
    ) -> None: ...
    def to_pandas(self) -> Any:
        """The metrics as a pandas DataFrame (needs ``flocking[pandas]``)."""
    def to_xarray(self) -> Any:
        """The run as an ``xarray.Dataset``: q, p over time × agent × axis, the vehicle's state
        over time × agent, the metrics over time (each with ``long_name`` and units, counts
        int64), the scenario's parameters as attributes, each once (needs ``flocking[xarray]``)."""
    def player_html(
        self, *, max_frames: int = 500, size: int = 480, max_bytes: Optional[int] = None
    ) -> str:
        """The run in the self-contained canvas player of ``flocking plot``, with the readout of
        its metrics; with ``max_bytes``, fewer frames (evenly spaced) when it would be larger."""
    def player(self, *, max_frames: int = 500, size: int = 480, max_bytes: int = 1_000_000) -> Any:
        """The player in an iframe for Jupyter, within ``max_bytes`` (1 MB by default)."""
    def plot(
        self,
        dir: Optional[_Path] = None,
        *,
        outputs: Optional[Sequence[str]] = None,
        times: Optional[Sequence[float]] = None,
        stress_edges: bool = False,
    ) -> List[str]:
        """Draws the run's figures into ``dir/figures`` (``dir`` default :attr:`path`) as
        ``flocking plot`` does (:func:`plot`); returns the files written."""
    def _repr_html_(self) -> str: ...

def _render(
    scenario: Scenario,
    positions: _Rows,
    velocities: _Rows,
    t: float,
    width: int = 640,
    height: int = 480,
) -> npt.NDArray[np.uint8]:
    """The state (positions, velocities: (agents, dim), agents in original order) of a run of
    ``scenario`` at time ``t`` drawn as ``flocking plot`` draws a snapshot: an RGB image of shape
    (height, width, 3), uint8. :class:`ScenarioError` (a ``ValueError``) for an array of another
    shape or of complex numbers, as :class:`Simulation`; ``ValueError`` for a value or ``t`` that
    is not finite, or a side outside 16–16384."""

def bump(x: npt.ArrayLike, h: float) -> npt.NDArray[np.float64]:
    """ρ_h(x) of TAC 2006 eq. 10 for every element of ``x``, with the bits of the built-in
    protocols (for a ``controls`` function written in numpy); ``ValueError`` unless 0 < h < 1."""

def run(
    scenario: Scenario,
    out: Optional[_Path] = None,
    *,
    trajectory: bool = True,
    trajectory_format: str = "csv",
    checkpoint_every: int = 1000,
    force: bool = False,
    controls: Optional[_Controls] = None,
) -> Run:
    """Runs ``scenario`` to its end (the bits of ``flocking run``), into ``out`` when given; its
    inputs u from ``controls`` when given."""

def resume(
    dir: _Path, *, checkpoint_every: int = 1000, controls: Optional[_Controls] = None
) -> Run:
    """Continues the interrupted run in ``dir`` (with the same ``controls`` it was made with)."""

def read_run(dir: _Path) -> Run:
    """Reads a run directory (CSV or .npy trajectory)."""

def plot(
    dir: _Path,
    *,
    outputs: Optional[Sequence[str]] = None,
    times: Optional[Sequence[float]] = None,
    stress_edges: bool = False,
) -> List[str]:
    """Draws the figures of the run directory ``dir`` into ``dir/figures``, the files of
    ``flocking plot dir`` byte for byte: ``outputs`` some of ``"snapshots"``, ``"metrics"``,
    ``"gif"``, ``"player"`` (default all), ``times`` the snapshot times (s); returns the paths."""

class SweepResult:
    """A finished sweep: its output directory and the columns of its ``runs.csv`` (int64, bool,
    float64 or str arrays; int and bool columns with empty fields masked)."""

    path: str
    columns: Dict[str, Any]
    def __init__(self, path: str, columns: Dict[str, Any]) -> None: ...
    def to_pandas(self) -> Any:
        """``runs.csv`` as a pandas DataFrame with the dtypes of ``columns`` (needs
        ``flocking[pandas]``)."""
    def plot(
        self,
        metric: str,
        x: str,
        y: Optional[str] = None,
        *,
        where: Optional[Mapping[str, Any]] = None,
        facet: Optional[str] = None,
        series: Optional[str] = None,
        reference: Optional[_Path] = None,
        band: str = "minmax",
        log_x: bool = False,
        log_y: bool = False,
        log_colour: bool = False,
        even_cells: bool = False,
        bound: Optional[float] = None,
        bound_label: str = "bound",
        out: Optional[_Path] = None,
    ) -> str:
        """Draws what ``flocking sweep plot`` draws, byte for byte, into ``out`` (``.svg``,
        ``.png`` or ``.csv``; default ``path/<metric>.svg``); returns the path written."""
    def to_xarray(self) -> Any:
        """The sweep as an ``xarray.Dataset``: dimensions the axes and ``seed``, the measured
        columns as variables with ``long_name`` and ``units`` (needs ``flocking[xarray]``)."""

def read_sweep(dir: _Path) -> SweepResult:
    """Reads the output directory of a finished sweep (``flocking sweep`` or :func:`sweep`)."""

def sweep(
    spec: _Path,
    out: _Path,
    executor: Optional[concurrent.futures.Executor] = None,
    *,
    controls: Optional[_Controls] = None,
) -> SweepResult:
    """Runs the sweep file ``spec`` into ``out`` on ``executor`` (a local process pool by default,
    a Dask cluster through ``Client.get_executor()``): ``runs.csv`` byte for byte that of
    ``flocking sweep``; finished runs in ``out`` are skipped."""

class BenchReport:
    """The report of :func:`bench` on the α-lattice; ``str()`` is what ``flocking bench`` prints."""

    n: int
    dim: int
    steps: int
    threads: int
    agent_steps_per_second: float
    ns_per_agent_step: float
    ms_per_step: float
    ms_per_plain_step: float
    ms_per_recorded_step: Optional[float]
    peak_memory: Optional[int]
    bytes_per_agent: Optional[float]
    conditions_bytes_per_agent: int
    mean_neighbours: float
    setup_seconds: float
    elapsed_seconds: float
    connectivity: float
    min_distance: float

class WorkloadReport:
    """The report of :func:`bench` with ``workload=``; ``str()`` is what ``flocking bench
    --workload`` prints."""

    n: int
    times: List[float]
    median_seconds: float
    build_times: List[float]
    median_seconds_with_building: float
    agent_steps_per_second: float
    threads: int

def bench(
    n: Optional[int] = None,
    dim: Optional[int] = None,
    steps: Optional[int] = None,
    *,
    algorithm: Union[None, int, str] = None,
    threads: Optional[int] = None,
    warmup: Optional[int] = None,
    shuffled: Optional[bool] = None,
    delay: Optional[float] = None,
    delayed: Optional[str] = None,
    loss: Optional[float] = None,
    sensing_noise: Union[None, float, Tuple[float, float], List[float]] = None,
    control_rate: Optional[float] = None,
    max_acceleration: Optional[float] = None,
    vehicle: Optional[str] = None,
    workload: Optional[str] = None,
    seeds: Optional[int] = None,
    scale_to: Optional[int] = None,
) -> Union[BenchReport, WorkloadReport]:
    """Times the simulation loop as ``flocking bench`` does, its flags as keywords."""
