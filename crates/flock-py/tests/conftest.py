"""Shared helpers of the Python package's tests: the fixtures, and the release CLI whose outputs
the Python results must equal bit for bit (``FLOCK_CLI``, set by ``scripts/test-python``)."""

import os
import signal
import subprocess
from pathlib import Path

import numpy as np
import pytest

import flocking

ROOT = Path(__file__).resolve().parents[3]
FIXTURES = Path(os.environ.get("FLOCK_FIXTURES", ROOT / "fixtures"))
FIG11 = FIXTURES / "tac2006_fig11_alg2_n100.ron"
OUTPUT_FILES = ["metrics.csv", "final.csv", "scenario.ron", "flocking.txt"]

# The Ctrl-C tests need SIGINT to raise KeyboardInterrupt, here and in the Pythons they start: a
# shell without job control starts a background job with SIGINT ignored, and Python then leaves it
# ignored (a suite started so failed every Ctrl-C test and left their children running).
signal.signal(signal.SIGINT, signal.default_int_handler)


def cli_path() -> Path:
    """The `flocking` binary: ``FLOCK_CLI``, else the workspace's release build."""
    path = Path(os.environ.get("FLOCK_CLI", ROOT / "target" / "release" / "flocking"))
    if not path.exists():
        pytest.fail(f"the flock CLI is missing at {path}: cargo build --release -p flock-cli")
    return path


def cli(*args, check=True) -> subprocess.CompletedProcess:
    """Runs the CLI with ``args``; its exit code must be 0 when ``check``."""
    done = subprocess.run(
        [str(cli_path()), *map(str, args)], capture_output=True, text=True, timeout=300
    )
    if check and done.returncode != 0:
        pytest.fail(f"flocking {' '.join(map(str, args))} failed: {done.stderr}")
    return done


def cli_run(scenario: flocking.Scenario, out: Path, *args) -> Path:
    """``flocking run`` of ``scenario`` (written to a file beside ``out``) into ``out``."""
    path = out.parent / f"{out.name}.ron"
    path.write_text(scenario.to_ron())
    cli("run", path, "--out", out, "--quiet", *args)
    return out


def short(path: Path, records: int = 4) -> flocking.Scenario:
    """The scenario at ``path`` cut to ``records`` records after t = 0 (and a last one)."""
    scenario = flocking.Scenario.load(path)
    steps = records * scenario.record_every + scenario.record_every // 2
    return scenario.with_values({"duration": steps * scenario.step})


def assert_runs_equal(a: flocking.Run, b: flocking.Run) -> None:
    """Every recorded number of ``a`` and ``b`` is the same, bit for bit."""
    assert list(a.metrics) == list(b.metrics)
    for name in a.metrics:
        assert a.metrics[name].dtype == b.metrics[name].dtype, name
        assert np.array_equal(a.metrics[name], b.metrics[name], equal_nan=True), name
    assert a.trajectory is not None and b.trajectory is not None
    for field in ("times", "positions", "velocities"):
        assert np.array_equal(getattr(a.trajectory, field), getattr(b.trajectory, field)), field
    assert a.final.t == b.final.t
    assert np.array_equal(a.final.positions, b.final.positions)
    assert np.array_equal(a.final.velocities, b.final.velocities)


def assert_same_files(a: Path, b: Path, names) -> None:
    """The files ``names`` of directories ``a`` and ``b`` are byte-identical."""
    for name in names:
        assert (a / name).read_bytes() == (b / name).read_bytes(), name
