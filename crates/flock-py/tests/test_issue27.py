"""Issue 27, "Never lose a user's file, round two", from Python: a run made with ``controls=f``
is not resumed without them, ``out='pydir/'`` just works, an ``out`` that is not a directory is
refused before the run."""

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import flocking
from conftest import FIG11, short

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "examples" / "python"))
from algorithm2_numpy import Algorithm2  # noqa: E402


class Boom(Exception):
    """The exception of the failing controls."""


def failing_after(steps, step, f):
    """``f``, raising ``Boom`` from step ``steps`` + 1 on."""

    def g(t, q, p, neighbours):
        if t >= (steps + 0.5) * step:
            raise Boom()
        return f(t, q, p, neighbours)

    return g


def test_issue_27_a_controls_run_is_not_resumed_without_them(tmp_path):
    scenario = short(FIG11)
    alg2 = Algorithm2(scenario)
    out = tmp_path / "out"
    with pytest.raises(Boom):
        flocking.run(scenario, out, controls=failing_after(47, scenario.step, alg2), checkpoint_every=10)
    partial = Path(f"{out}.partial")
    assert (partial / "controls.txt").read_text().startswith("inputs from Python controls=")
    before = {p.name: p.read_bytes() for p in partial.iterdir() if p.is_file()}
    with pytest.raises(flocking.RunDirectoryError, match="was made with Python controls=.*neither run"):
        flocking.resume(out)
    assert {p.name: p.read_bytes() for p in partial.iterdir() if p.is_file()} == before
    # issue 49: another function is refused too; the same one (by its module and name) resumes
    with pytest.raises(flocking.RunDirectoryError, match="not with Python controls=algorithm2_numpy.Algorithm2"):
        flocking.resume(out, controls=alg2)
    flocking.resume(out, controls=failing_after(10**9, scenario.step, alg2))
    assert (out / "flocking.txt").exists() and (out / "controls.txt").exists()
    # a run of the protocol is not resumed with controls
    plain = tmp_path / "plain"
    flocking.run(scenario, plain)
    assert not (plain / "controls.txt").exists()


def test_issue_27_out_with_a_trailing_slash_just_works(tmp_path):
    run = flocking.run(short(FIG11), f"{tmp_path}/pydir/")
    assert (tmp_path / "pydir" / "metrics.csv").is_file()
    assert not (tmp_path / "pydir" / ".partial").exists()
    assert not (tmp_path / "pydir.partial").exists()
    assert run.final is not None


def test_issue_27_an_out_that_is_a_file_is_refused_before_the_run(tmp_path):
    mine = tmp_path / "mine"
    mine.write_text("mine\n")
    with pytest.raises(flocking.RunDirectoryError, match="is a file, not a directory"):
        flocking.run(short(FIG11), mine)
    assert mine.read_text() == "mine\n"
    assert not (tmp_path / "mine.partial").exists()


def test_issue_27_the_cli_resource_estimate_guards_python(tmp_path):
    # a delay of 10⁶ s: 10⁸ states of 100 agents in the delay line, some 300 GB (it aborted the
    # interpreter); the CLI refuses it with its estimate, and so does Python now
    scenario = flocking.Scenario.load(FIG11).with_values({"conditions.communication.delay": 1e6})
    with pytest.raises(MemoryError, match="a run needs about .* of memory but .* is available"):
        flocking.Simulation(scenario)
    with pytest.raises(MemoryError, match="a run needs about"):
        flocking.run(scenario)
    with pytest.raises(MemoryError, match="a run needs about"):
        flocking.run(scenario, tmp_path / "out")
    assert not (tmp_path / "out").exists() and not (tmp_path / "out.partial").exists()


def refused_in_a_child(spec, out):
    """``flocking.sweep(spec, out)`` in a child process limited to 4 GiB of address space and a
    minute (an unbounded read or a hang fails the test, not the machine): its exit code and output;
    3 for a ``ScenarioError``, whose message is printed."""
    import resource

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))

    script = (
        "import flocking, sys\n"
        "try:\n"
        f"    flocking.sweep({str(spec)!r}, {str(out)!r})\n"
        "except flocking.ScenarioError as e:\n"
        "    print(e); sys.exit(3)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=60, preexec_fn=limit
    )
    return done.returncode, done.stdout + done.stderr


def test_issue_27_a_sweep_file_is_read_as_the_cli_reads_it(tmp_path):
    # /dev/zero was read without bound, a FIFO waited for a writer
    fifo = tmp_path / "fifo.ron"
    os.mkfifo(fifo)
    for spec in ["/dev/zero", fifo]:
        code, said = refused_in_a_child(spec, tmp_path / "out")
        assert code == 3, said
        assert "not a regular file" in said and str(spec) in said, said
    assert not (tmp_path / "out").exists()


def test_a_sweep_with_a_crowded_run_is_refused_before_out_is_made(tmp_path):
    # one run packs 12,000 agents into a cloud of 5 cm (each sees all the others, some 7.9 GB);
    # its worker was started and killed: the local pool's memory is now checked first, as the CLI's
    spec = tmp_path / "crowd.ron"
    spec.write_text(
        f"""Sweep(name: "crowd", base: Path("{FIG11}"),
        set: {{"duration": 1.0, "agents": 12000}},
        axes: [(path: "initial.positions.std", values: List([500.0, 0.05]))], seeds: 1)"""
    )
    code, said = refused_in_a_child(spec, tmp_path / "out")
    assert code == 1, said
    assert re.search(r"MemoryError: a run needs about [0-9.]+ GB of memory but", said), said
    assert not (tmp_path / "out").exists()


def test_issue_27_ctrl_c_stops_a_sweep_at_once_and_keeps_its_rows(tmp_path):
    spec = tmp_path / "sweep.ron"
    spec.write_text(
        f"""Sweep(name: "long", base: Path("{FIG11}"),
        set: {{"duration": 60.0}},
        axes: [(path: "algorithm.c1", values: Linspace(from: 0.01, to: 0.05, count: 80))], seeds: 1)"""
    )
    out = tmp_path / "out"
    # the default executor, one worker per core: a Ctrl-C waited for all 80 runs (about 16 s here)
    script = (
        "import flocking, sys, time\n"
        "try:\n"
        f"    flocking.sweep({str(spec)!r}, {str(out)!r})\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', time.time(), flush=True)\n"
        "    sys.exit(130)\n"
    )
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    rows = out / "rows"
    deadline = time.time() + 120
    try:
        while not (rows.is_dir() and len(list(rows.glob("*.csv"))) >= 2):
            assert child.poll() is None and time.time() < deadline, "no row written"
            time.sleep(0.05)
        sent = time.time()
        child.send_signal(signal.SIGINT)
        stdout, _ = child.communicate(timeout=120)
    finally:
        child.kill()  # not left running when the test fails (no-op once it exited)
    assert child.returncode == 130, stdout
    raised = float(stdout.split()[1])
    assert raised - sent < 1.0, f"KeyboardInterrupt {raised - sent:.2f} s after Ctrl-C"
    kept = len(list(rows.glob("*.csv")))
    assert 2 <= kept < 80
    # the same call resumes: every run, each once
    result = flocking.sweep(spec, out)
    assert len(result.columns["run"]) == 80


def test_complex_arrays_are_refused_not_cast():
    """numpy would cast a complex array to float with only a ComplexWarning, dropping the
    imaginary parts: a start state or a controls result with complex numbers is refused, naming
    it (and one whose imaginary parts are zero too: the caller passes ``.real``)."""
    scenario = short(FIG11)
    n, dim = scenario.agents, scenario.dim
    positions = np.zeros((n, dim), dtype=complex)
    positions[:, 0] = np.arange(n) * 5.0 + 1j
    with pytest.raises(flocking.ScenarioError) as raised:
        scenario.with_initial(positions)
    assert raised.value.field == "initial.positions"
    assert "complex" in str(raised.value)
    with pytest.raises(flocking.ScenarioError) as raised:
        flocking.Simulation(scenario, np.arange(n * dim, dtype=float).reshape(n, dim), positions)
    assert raised.value.field == "velocities"
    with pytest.raises(flocking.ControlsError, match="complex") as raised:
        flocking.Simulation(scenario, controls=lambda t, q, p, nb: np.zeros(q.shape, complex)).step()
    # the real parts pass
    started = scenario.with_initial(positions.real)
    assert started.agents == n
