"""flocking.sweep: a sweep file's runs on any concurrent.futures executor — the default local process
pool and a real Dask cluster (a scheduler and two worker processes over TCP on loopback) — give
the runs.csv of ``flocking sweep``, byte for byte; a bad sweep file is a ScenarioError."""

from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import flocking

from conftest import FIG11, cli

SWEEP = """Sweep(
    name: "py",
    base: Path("{base}"),
    set: {{"duration": 2.0, "initial.positions.std": 10.0}},
    axes: [
        (path: "algorithm.c1", values: List([0.02, 1e8, 0.05])),  // 1e8 blows up: an error row
        (path: "agents", values: Linspace(from: 8.0, to: 12.0, count: 2)),
    ],
    seeds: 2,
)
"""


@pytest.fixture
def spec(tmp_path: Path) -> Path:
    path = tmp_path / "sweep.ron"
    path.write_text(SWEEP.format(base=FIG11))
    return path


def cli_sweep(spec: Path, out: Path) -> bytes:
    cli("sweep", spec, "--out", out, "--jobs", "2", "--quiet")
    return (out / "runs.csv").read_bytes()


def test_the_default_executor_gives_the_cli_runs_csv(spec: Path, tmp_path: Path) -> None:
    expected = cli_sweep(spec, tmp_path / "cli")
    result = flocking.sweep(spec, tmp_path / "py")
    assert (tmp_path / "py" / "runs.csv").read_bytes() == expected
    assert len(result.columns["run"]) == 12
    assert result.columns["algorithm.c1"][4] == 1e8
    errors = result.columns["error"]
    assert all(("blow-up" in e) == (c1 == 1e8) for e, c1 in zip(errors, result.columns["algorithm.c1"]))
    ok = result.columns["algorithm.c1"] != 1e8
    assert np.all(np.isfinite(result.columns["connectivity"][ok]))
    assert np.all(np.isnan(result.columns["connectivity"][~ok]))
    # run again: every run is found finished, nothing changes
    again = flocking.sweep(spec, tmp_path / "py", executor=ThreadPoolExecutor(2))
    assert (Path(again.path) / "runs.csv").read_bytes() == expected


def test_a_dask_cluster_gives_the_cli_runs_csv(spec: Path, tmp_path: Path) -> None:
    from dask.distributed import Client, LocalCluster

    expected = cli_sweep(spec, tmp_path / "cli")
    with LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        protocol="tcp",
        dashboard_address=None,
    ) as cluster, Client(cluster) as client:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        assert len(client.scheduler_info()["workers"]) == 2
        flocking.sweep(spec, tmp_path / "dask", executor=client.get_executor())
    assert (tmp_path / "dask" / "runs.csv").read_bytes() == expected


def test_a_bad_sweep_file_is_a_scenario_error(tmp_path: Path) -> None:
    path = tmp_path / "bad.ron"
    path.write_text(SWEEP.format(base=FIG11).replace('"agents", values', '"agnets", values'))
    with pytest.raises(flocking.ScenarioError) as raised:
        flocking.sweep(path, tmp_path / "out")
    assert raised.value.field == "axes[1].path"
    assert "agents" in str(raised.value)


def test_issue_20_sweep_never_replaces_a_users_runs_csv(tmp_path: Path) -> None:
    spec = tmp_path / "seeds.ron"
    spec.write_text(
        f'Sweep(name: "seeds", base: Path("{FIG11}"), set: {{"duration": 1.0, "agents": 8}}, axes: [], seeds: 2)'
    )
    out = tmp_path / "mine"
    out.mkdir()
    (out / "runs.csv").write_bytes(b"my,own\n1,2\n")
    with pytest.raises(flocking.RunDirectoryError, match="holds runs.csv, which flocking did not write"):
        flocking.sweep(spec, out)
    assert (out / "runs.csv").read_bytes() == b"my,own\n1,2\n"
    assert sorted(p.name for p in out.iterdir()) == ["runs.csv"]
    # a sweep's own directory is marked, unlocked when done, and resumed
    flocking.sweep(spec, tmp_path / "py", executor=ThreadPoolExecutor(2))
    assert (tmp_path / "py" / ".flocking").read_text() == "written by flocking sweep\n"
    assert not (tmp_path / "py" / ".flocking.lock").exists()
    flocking.sweep(spec, tmp_path / "py", executor=ThreadPoolExecutor(2))


def test_a_run_too_large_for_the_worker_that_takes_it_is_refused_there(tmp_path: Path) -> None:
    # an executor of the caller's runs on machines the sweep does not see, so the sweep's own
    # check is not made; each run is checked where it lands. A delay of 10⁶ s holds 10⁸ states
    # of 8 agents (some 25 GB): the worker refuses it before allocating, the row already
    # written is kept, and the directory is resumable (the default pool refuses it up front)
    spec = delays(tmp_path, 1e6)
    out = tmp_path / "out"
    with pytest.raises(MemoryError) as refused:
        flocking.sweep(spec, out, executor=ThreadPoolExecutor(1))
    said = refused_with_the_first_row_kept(refused.value, out)
    assert "on the worker that took it: a run needs about" in said, said
    assert "of it the delay line of conditions.communication.delay" in said, said
    assert not (out / "runs.csv").exists() and not (out / ".flocking.lock").exists()
    with pytest.raises(MemoryError, match="a run needs about"):
        flocking.sweep(spec, out)
    # the same sweep without the large run finishes on the same executor
    small = tmp_path / "small.ron"
    small.write_text(spec.read_text().replace("List([0.0, 1000000.0])", "List([0.0, 0.1])"))
    result = flocking.sweep(small, tmp_path / "small", executor=ThreadPoolExecutor(1))
    assert list(result.columns["error"]) == ["", ""]


def test_a_run_beyond_a_dask_workers_memory_limit_is_refused_on_it(tmp_path: Path) -> None:
    # workers limited to 300 MB (their nanny ends one at 95 % of it): a delay of 2·10⁴ s holds
    # 2·10⁶ slots of 8 agents' states, about 672 MB by the CLI's estimate, which fits this machine but
    # not a worker. It is refused on the worker before it allocates, by the estimate and the limit
    # of the worker (a check against the machine alone would let it start); the small run's row
    # is kept
    from dask.distributed import Client, LocalCluster

    spec = delays(tmp_path, 2e4)
    out = tmp_path / "dask"
    with LocalCluster(
        n_workers=1,
        threads_per_worker=1,
        processes=True,
        memory_limit="300MB",
        host="127.0.0.1",
        protocol="tcp",
        dashboard_address=None,
    ) as cluster, Client(cluster) as client:
        with pytest.raises(MemoryError) as refused:
            flocking.sweep(spec, out, executor=client.get_executor())
    said = refused_with_the_first_row_kept(refused.value, out)
    assert "the worker that took it (its memory limit counted)" in said, said
    assert "a run needs about 692.0 MB of memory but 285.0 MB is available, 672.0 MB of it the delay line" in said, said


def delays(tmp_path: Path, delay: float) -> Path:
    """A sweep of Fig. 11 with 8 agents for 1 s: run 0 without a delay, run 1 with ``delay``."""
    spec = tmp_path / "delays.ron"
    spec.write_text(
        f"""Sweep(name: "delays", base: Path("{FIG11}"), set: {{"duration": 1.0, "agents": 8}},
        axes: [(path: "conditions.communication.delay", values: List([0.0, {delay!r}]))], seeds: 1)"""
    )
    return spec


def refused_with_the_first_row_kept(error: BaseException, out: Path) -> str:
    """The message of a refusal of run 1, after run 0's row was written in ``out``."""
    said = str(error)
    assert said.startswith("run 1 ("), said
    rows = [p.name for p in (out / "rows").iterdir()]
    assert len(rows) == 1 and rows[0].startswith("00000000-"), rows
    return said
