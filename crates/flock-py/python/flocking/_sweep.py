"""Sweeps: :func:`sweep` on any ``concurrent.futures.Executor`` and its result
:class:`SweepResult`, the columns of ``runs.csv`` with their natural dtypes."""

import concurrent.futures as _futures
import csv as _csv
from dataclasses import dataclass as _dataclass
import json as _json
import math as _math
import os as _os
import re as _re
import time as _time
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence, Union

import numpy as _np

from . import _flocking
from ._flocking import Scenario
from ._run import UNITS, Controls, Path, _progress_sink, _require

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray

# Columns of runs.csv that are text whatever they hold: the run's id and its error.
_TEXT = ("id", "error")
_INTEGER = _re.compile(r"[+-]?[0-9]+")


def _column(name: str, values: List[str]) -> Any:
    """The column ``name`` of ``runs.csv`` with the dtype its fields show (see
    :class:`SweepResult`)."""
    if name in _TEXT:
        return _np.array(values, dtype=str)
    present = [v for v in values if v != ""]
    mask = _np.array([v == "" for v in values], dtype=bool)
    if present and all(_INTEGER.fullmatch(v) for v in present):
        numbers = [int(v) if v else 0 for v in values]
        dtype = _np.int64 if max(numbers) <= _np.iinfo(_np.int64).max else _np.uint64
        data: Any = _np.array(numbers, dtype=dtype)
    elif present and all(v in ("true", "false") for v in present):
        data = _np.array([v == "true" for v in values], dtype=bool)
    else:
        try:
            return _np.array([float(v) if v else _np.nan for v in values], dtype=_np.float64)
        except ValueError:
            return _np.array(values, dtype=str)
    return _np.ma.MaskedArray(data, mask=mask) if mask.any() else data


def _read_runs(path: str) -> Dict[str, Any]:
    """The columns of ``path/runs.csv``, by name, in the order of its header."""
    with open(_os.path.join(path, "runs.csv"), newline="") as f:
        rows = list(_csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: _column(name, [row[k] for row in body]) for k, name in enumerate(header)}


@_dataclass(frozen=True, repr=False)
class SweepResult:
    """A finished sweep: ``path`` its output directory, ``columns`` the columns of its
    ``runs.csv`` by name, each a numpy array of the kind its fields show, column by column
    (whatever columns the header of ``runs.csv`` holds):

    - ``id`` and ``error``: str arrays; ``error`` is ``""`` for a run without error.
    - whole numbers (``run``, ``seed``, ``collisions``, integer axis values): int64;
    - ``true``/``false`` (``alpha_flock``, ``strict_alpha_flock``): bool;
    - other numbers: float64, NaN where a run has no value;
    - anything else (text axis values): str.

    An int or bool column with fields left empty (the runs that failed) is a
    ``numpy.ma.MaskedArray`` of that dtype, masked there; :meth:`to_pandas` makes it a nullable
    ``Int64`` or ``boolean`` column.
    """

    path: str
    columns: Dict[str, Any]

    def __repr__(self) -> str:
        runs = len(next(iter(self.columns.values()), ()))
        errors = int(_np.count_nonzero(self.columns["error"] != "")) if "error" in self.columns else 0
        return f"SweepResult(path={self.path!r}, runs={runs}, columns={len(self.columns)}, errors={errors})"

    def to_pandas(self) -> "pandas.DataFrame":
        """``runs.csv`` as a pandas DataFrame, one row per run, with the dtypes of ``columns``
        (masked int and bool columns as pandas' nullable ``Int64``/``UInt64`` and ``boolean``;
        needs pandas: ``pip install 'flocking[pandas]'``)."""
        pandas = _require("pandas", "pandas", "SweepResult.to_pandas()")
        data = {}
        for name, column in self.columns.items():
            if _np.ma.isMaskedArray(column):
                dtype = {"i": "Int64", "u": "UInt64", "b": "boolean"}[column.dtype.kind]
                data[name] = pandas.array(column.tolist(), dtype=dtype)
            else:
                data[name] = column
        return pandas.DataFrame(data)

    def plot(
        self,
        metric: str,
        x: str,
        y: Optional[str] = None,
        *,
        where: Optional[Mapping[str, Any]] = None,
        facet: Optional[str] = None,
        series: Optional[str] = None,
        reference: Optional[Path] = None,
        band: str = "minmax",
        log_x: bool = False,
        log_y: bool = False,
        log_colour: bool = False,
        even_cells: bool = False,
        bound: Optional[float] = None,
        bound_label: str = "bound",
        out: Optional[Path] = None,
    ) -> str:
        """Draws what ``flocking sweep plot`` draws, through the same renderer, byte for byte:
        ``metric`` (a column of ``runs.csv``) over the axis ``x`` — a line with its band over
        the seeds, or with ``y`` a heatmap; an axis of names (``algorithm``, ``vehicle``, a loss
        model) as categories. ``where`` fixes other axes (``{"agents": 50}``, values as
        ``runs.csv`` writes them or as the figure shows them), ``facet`` draws one panel per
        value of an axis, ``series`` (the overlay) one line per value on one set of axes;
        ``reference`` a CSV file of a source's values; ``band`` ``"minmax"`` or ``"quantiles"``;
        ``even_cells`` a heatmap's numeric axes in equal cells, in the order of their values
        (each cell is otherwise at its value); ``bound`` a labelled vertical line at that x. ``out`` is the file (``.svg``, ``.png``,
        or ``.csv`` for the numbers drawn; default ``path/<metric>.svg``), never written over a
        file flocking did not write. Returns the path written; the CLI's warnings (points pooled
        over an axis neither drawn nor fixed) as ``UserWarning``. A metric or axis the sweep
        does not have is a ``ValueError`` naming the nearest ones."""
        fixed = [(str(k), v if isinstance(v, str) else _json.dumps(v)) for k, v in (where or {}).items()]
        written, warnings = _flocking.sweep_plot(
            _os.fspath(self.path),
            metric,
            x,
            y,
            fixed,
            facet,
            series,
            None if reference is None else _os.fspath(reference),
            band,
            log_x,
            log_y,
            log_colour,
            even_cells,
            None if bound is None else float(bound),
            bound_label,
            None if out is None else _os.fspath(out),
        )
        import warnings as _warnings

        for message in warnings:
            _warnings.warn(message, UserWarning, stacklevel=2)
        return _os.fspath(written)

    def to_xarray(self) -> "xarray.Dataset":
        """The sweep as an ``xarray.Dataset`` (needs xarray: ``pip install 'flocking[xarray]'``).

        - Dimensions: the sweep's axes, by path, in the sweep file's order, then ``seed``;
          coordinates their values in the sweep's order (numbers, or text as ``runs.csv`` writes
          it), each with its ``long_name`` ("communication delay τ") and ``units`` when it has
          one (UDUNITS: ``s``, ``m``, ``m s-1``, ``Hz``).
        - Variables: every measured column of ``runs.csv`` (between ``seed`` and ``error``) over
          those dimensions, with ``long_name`` (the figures' name: "cohesion radius R") and
          ``units`` ("1" for ratios and counts); ``id`` and ``error`` as text. A grid point
          without a row (a shard not merged) is NaN (an int or bool column is then float).
        - Attributes: the sweep's ``name``, ``description``, ``seeds`` and ``path``.
        """
        xarray = _require("xarray", "xarray", "SweepResult.to_xarray()")
        header = list(self.columns)
        name, description, seeds, axes, labels = _flocking.sweep_names(_os.fspath(self.path), header)
        long_names = dict(zip(header, labels))
        measured = header[header.index("seed") + 1 : header.index("error")]
        dims = [path for path, _, _ in axes] + ["seed"]
        coords: Dict[str, Any] = {}
        places = []
        for path, long_name, unit in axes:
            column = self.columns[path]
            values = list(dict.fromkeys(column.tolist()))
            attrs = {"long_name": long_name}
            if unit:
                attrs["units"] = _UDUNITS.get(unit, unit)
            coords[path] = (path, _np.array(values), attrs)
            index = {v: k for k, v in enumerate(values)}
            places.append(_np.array([index[v] for v in column.tolist()]))
        coords["seed"] = ("seed", _np.arange(seeds), {"long_name": "seed"})
        places.append(_np.asarray(self.columns["seed"], dtype=_np.int64))
        shape = tuple(len(coords[d][1]) for d in dims)
        full = len(self.columns["seed"]) == int(_np.prod(shape))
        data: Dict[str, Any] = {}
        for column_name in measured + ["id", "error"]:
            column = self.columns[column_name]
            text = column.dtype.kind in "US"
            if full and not _np.ma.isMaskedArray(column):
                grid = _np.empty(shape, dtype=column.dtype)
            elif text:
                grid = _np.full(shape, "", dtype=column.dtype)
            else:
                grid = _np.full(shape, _np.nan)
                column = _np.ma.filled(_np.ma.asarray(column, dtype=float), _np.nan)
            grid[tuple(places)] = column
            attrs = {"long_name": long_names.get(column_name, column_name)}
            if not text:
                attrs["units"] = _sweep_unit(column_name)
            data[column_name] = (dims, grid, attrs)
        attrs = {"name": name, "description": description, "seeds": seeds, "path": _os.fspath(self.path)}
        return xarray.Dataset(data, coords=coords, attrs=attrs)


def read_sweep(dir: Path) -> SweepResult:
    """Reads the output directory of a finished sweep, written by ``flocking sweep`` (merged, for
    a sharded one) or :func:`sweep`: its ``runs.csv`` as a :class:`SweepResult`. A directory that
    is not a sweep's is a ``RunDirectoryError``, as for the CLI; one whose ``runs.csv`` is not
    assembled yet a ``FileNotFoundError`` saying how to finish it."""
    path = _os.fspath(dir)
    _flocking.sweep_names(path, [])  # refuses a directory that is not a sweep's
    if not _os.path.isfile(_os.path.join(path, "runs.csv")):
        raise FileNotFoundError(
            f"{path} has no runs.csv: the sweep has not finished; run it again (flocking sweep SWEEP --out {path}) to finish and assemble it"
        )
    return SweepResult(path, _read_runs(path))


# The parameter table's units (flocking::sweep::labels) in UDUNITS, as Run.to_xarray writes them.
_UDUNITS = {"m/s": "m s-1", "m/s²": "m s-2"}


def _sweep_unit(column: str) -> str:
    """The unit of a measured column of ``runs.csv``: a metric's as in ``metrics.csv``, a settled
    one as its metric's, ``connected_from`` a time; "1" for ratios, counts and fractions."""
    if column == "connected_from":
        return "s"
    return UNITS.get(column.removeprefix("settled_"), "1")


def _ron_value(value: Any) -> str:
    """A Python value of an axis as RON: numbers and booleans as written, strings quoted (an
    enum of the scenario given whole as a string, ``"Bernoulli(p: 0.1)"``, stays one)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, _np.integer)):
        return str(int(value))
    if isinstance(value, (float, _np.floating)):
        x = float(value)
        if not _math.isfinite(x):
            raise ValueError(f"axis value {x!r} is not finite")
        return repr(x)
    if isinstance(value, str):
        return _json.dumps(value, ensure_ascii=False)
    raise TypeError(
        f"axis value {value!r} is a {type(value).__name__}: give numbers, booleans or strings"
    )


def _grid_text(base: Scenario, axes: Mapping[str, Sequence[Any]], seeds: int, name: Optional[str]) -> str:
    """The sweep file of ``base`` over ``axes`` (path -> values) × ``seeds`` seeds, base inlined."""
    if isinstance(seeds, bool) or not isinstance(seeds, (int, _np.integer)) or seeds < 1:
        raise ValueError(f"seeds = {seeds!r}: give a whole number of seeds >= 1")
    parts = []
    for path, values in axes.items():
        if isinstance(values, (str, bytes)) or not isinstance(values, Sequence) and not isinstance(values, _np.ndarray):
            raise TypeError(f"axis {path!r}: give a list of values, not {values!r}")
        listed = ", ".join(_ron_value(v) for v in values)
        parts.append(f"(path: {_json.dumps(str(path))}, values: List([{listed}]))")
    title = base.name if name is None else name
    # the scenario's RON begins with its extensions (`#![enable(implicit_some)]`): they go first
    lines = base.to_ron().splitlines()
    extensions = [line for line in lines if line.startswith("#![")]
    body = "\n".join(line for line in lines if not line.startswith("#!["))
    return "\n".join(extensions) + (
        f"\nSweep(name: {_json.dumps(title, ensure_ascii=False)}, base: Inline({body}), "
        f"axes: [{', '.join(parts)}], seeds: {int(seeds)})"
    )


class _SweepProgress:
    """``runs done/total`` with runs/s and the time left, told to a progress sink (a line on a
    terminal's ``sys.stderr``, or a bar in Jupyter kept when done: ``_run._progress_sink``) at
    most five times a second."""

    def __init__(self, done: int, total: int, sink: Any) -> None:
        self.done, self.total, self.start, self.last, self.sink = done, total, _time.monotonic(), 0.0, sink
        self.first = done

    def advance(self) -> None:
        self.done += 1
        now = _time.monotonic()
        if now - self.last < 0.2 and self.done < self.total:
            return
        self.last = now
        elapsed = now - self.start
        ran = self.done - self.first
        rate = ran / elapsed if elapsed > 0 else 0.0
        left = f"{(self.total - self.done) / rate:.0f} s left" if rate > 0 else "…"
        self.sink.update(f"sweep: {self.done}/{self.total} runs  {rate:.2f} runs/s  {left}", self.done / self.total)

    def clear(self) -> None:
        elapsed = _time.monotonic() - self.start
        share = 100 * self.done / max(self.total, 1)
        self.sink.close(f"sweep: {self.done}/{self.total} runs in {elapsed:.1f} s ({share:.0f} %)")


def _sweep_run(text: str, index: int, controls: Optional[Controls] = None, check: bool = False):
    """Runs run ``index`` of the self-contained sweep ``text`` (in a worker process); with
    ``check``, refused with ``MemoryError`` when it does not fit in that worker's machine or
    within its Dask worker's memory limit."""
    limit = _dask_worker_memory_limit() if check else None
    return _flocking.sweep_run(text, index, controls, check, limit)


def _dask_worker_memory_limit() -> Optional[float]:
    """The bytes a Dask worker may hold before its nanny ends it (its ``memory_limit`` times the
    ``distributed.worker.memory.terminate`` fraction), when this runs on one with a limit;
    ``None`` elsewhere."""
    try:
        from distributed import get_worker

        worker = get_worker()
    except (ImportError, ValueError):
        return None
    limit = worker.memory_manager.memory_limit
    if not limit:
        return None
    import dask

    terminate = dask.config.get("distributed.worker.memory.terminate", default=False)
    return float(limit) * (float(terminate) if terminate else 1.0)


def sweep(
    spec: Union[Path, Scenario],
    out: Path,
    executor: Optional[_futures.Executor] = None,
    *,
    controls: Optional[Controls] = None,
    axes: Optional[Mapping[str, Sequence[Any]]] = None,
    seeds: Optional[int] = None,
    name: Optional[str] = None,
    progress: Optional[bool] = None,
) -> SweepResult:
    """Runs the sweep file ``spec`` into the output directory ``out``, as ``flocking sweep`` does:
    the same row files, ``runs.csv`` (byte for byte) and ``times.csv``; runs found finished in
    ``out`` are skipped, so an interrupted sweep resumes.

    Or a grid defined here: ``spec`` a :class:`Scenario` (the base), ``axes`` a dict from
    parameter path to its values (``{"algorithm.c1": [0.01, 0.02], "agents": [50, 100]}``; an
    enum of the scenario as a string of RON, ``"Bernoulli(p: 0.1)"``) and ``seeds`` the seeds of
    each grid point (default 1): the sweep file with that base inlined, the same runs and rows
    (``out/sweep.ron`` keeps it; ``name`` defaults to the base's).

    ``progress``: runs done, runs/s and the time left: in Jupyter a bar kept when done, elsewhere a
    line on ``sys.stderr``, by default only when ``sys.stderr`` is a terminal.

    Each run is one call of a worker function submitted to ``executor``: a local process pool
    with one worker per core by default; a Dask cluster with
    ``dask.distributed.Client(...).get_executor()``; a Slurm cluster with dask-jobqueue's
    ``SLURMCluster`` behind such a client. Every worker needs this package installed. Rows are
    written by this process as their runs finish; ``runs.csv`` is assembled in run order at the
    end, so it does not depend on the executor or the order of completion.

    ``controls`` computes every run's inputs as in :func:`run`; it is sent to the workers, so it
    must be picklable: a function defined at the top level of an importable module. An exception
    it raises is raised here (the rows of the runs finished so far are kept: run the sweep again
    to continue).

    ``out`` must be new, empty or a sweep's output directory (flocking marks it with a
    ``.flocking`` file); one holding files flocking did not write is refused, and so is one that
    another process is writing (its lock is held until ``runs.csv`` is written).

    Raises :class:`ScenarioError` for a bad sweep file, :class:`RunDirectoryError` for a
    directory of another sweep, of files flocking did not write, or being written, and, with the
    default local pool, ``MemoryError`` when its workers' runs do not fit in this machine's memory
    (the CLI's estimate, each run's start counted); with an executor of your own, ``MemoryError``
    naming the first run that does not fit in the memory of the machine whose worker took it (and
    a Dask worker's ``memory_limit``), checked there before the run starts (the rows of the runs
    finished so far are kept). A run that fails (an invalid value, a blow-up) is a row with its
    error, not an exception.
    """
    if isinstance(spec, Scenario):
        if axes is None:
            raise TypeError("a sweep of a Scenario needs axes={path: [values, ...]}")
        text, count = _flocking.sweep_load(
            _grid_text(spec, axes, 1 if seeds is None else seeds, name), "<sweep>", _os.getcwd()
        )
    else:
        if axes is not None or seeds is not None or name is not None:
            raise TypeError(
                "axes=, seeds= and name= define a grid around a Scenario; a sweep file has its own"
            )
        spec_path = _os.fspath(spec)
        # read as the CLI reads it: a FIFO or /dev/zero is refused, a file is read up to the limit
        text, count = _flocking.sweep_load(
            _flocking.sweep_read(spec_path),
            spec_path,
            _os.path.dirname(_os.path.abspath(spec_path)),
        )
    out_path = _os.fspath(out)
    # an executor of the caller's runs on machines this process does not see: each run is
    # checked on the worker that takes it
    check_on_worker = executor is not None
    if executor is None:
        # the local pool's workers each hold a run: refused before ``out`` is made when they
        # do not fit (a remote executor's workers are not this machine's)
        _flocking.sweep_check(text, out_path, _os.cpu_count() or 1)
    # the lock of ``out`` is held until runs.csv is written: a second writer is refused
    finished, lock = _flocking.sweep_prepare(out_path, text)
    try:
        finished = set(finished)
        pending = [k for k in range(count) if k not in finished]
        own = executor is None
        if executor is None:
            executor = _futures.ProcessPoolExecutor(max_workers=_os.cpu_count() or 1)
        futures = []
        sink = _progress_sink(progress)
        bar = _SweepProgress(count - len(pending), count, sink) if sink is not None else None
        try:
            futures = [
                executor.submit(_sweep_run, text, k, controls, check_on_worker) for k in pending
            ]
            for future in _futures.as_completed(futures):
                index, run_id, fields, wall_time = future.result()
                _flocking.sweep_write_row(out_path, index, run_id, fields, wall_time)
                if bar is not None:
                    bar.advance()
        except BaseException:
            # Ctrl-C, or a failed run of `controls` (issue 27): cancel the runs not started,
            # keep every run finished meanwhile, and do not wait for the running ones
            for future in futures:
                future.cancel()
            for future in futures:
                if future.done() and not future.cancelled() and future.exception() is None:
                    index, run_id, fields, wall_time = future.result()
                    _flocking.sweep_write_row(out_path, index, run_id, fields, wall_time)
            if own:
                own = False
                executor.shutdown(wait=False, cancel_futures=True)
            raise
        finally:
            if bar is not None:
                bar.clear()
            if own:
                executor.shutdown()
        _flocking.sweep_assemble(out_path, text)
    finally:
        lock.release()
    return SweepResult(out_path, _read_runs(out_path))
