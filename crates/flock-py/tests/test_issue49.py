"""Issue 49, "Never lose a user's data, round three", from Python: a refused ``flocking.resume``
keeps every byte of the interrupted run, SIGINT stops a long step within 2 s, ``flocking.bench``
has the guards of a run, an npy trajectory reads back its vehicle's columns by name, and a run is
resumed only with the ``controls`` it was made with."""

import _thread
import hashlib
import math
import os
import signal
import struct
import subprocess
import sys
import textwrap
import threading
import time

import pytest

import flocking
from conftest import FIG11, FIXTURES

MAGIC = b"FLOCKCK6"


def checksums(directory):
    """The SHA-256 of every file of ``directory`` (not its subdirectories), by name."""
    return {
        entry.name: hashlib.sha256(entry.read_bytes()).hexdigest()
        for entry in sorted(directory.iterdir())
        if entry.is_file()
    }


def fnv1a(data: bytes) -> int:
    """The 64-bit FNV-1a hash that ends a checkpoint."""
    value = 0xCBF29CE484222325
    for byte in data:
        value = ((value ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return value


def forge_position(partial, value: float) -> None:
    """Writes ``value`` as the first coordinate of the checkpoint's first position, its hash made
    to match (checkpoint.rs: the magic, nine u64 words, then the positions)."""
    path = partial / "checkpoint.bin"
    body = bytearray(path.read_bytes()[:-8])
    assert body.startswith(MAGIC)
    struct.pack_into("<d", body, len(MAGIC) + 9 * 8, value)
    path.write_bytes(bytes(body) + struct.pack("<Q", fnv1a(bytes(body))))


def interrupted(tmp_path, name, scenario, **run):
    """``scenario`` run into ``tmp_path/name`` and stopped by Ctrl-C (``_thread.interrupt_main``)
    a fifth of a second in: its ``DIR.partial``, with a checkpoint."""
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        flocking.run(scenario, out=tmp_path / name, checkpoint_every=100, **run)
    timer.join()
    partial = tmp_path / f"{name}.partial"
    assert (partial / "checkpoint.bin").exists()
    return partial


def long(scenario: flocking.Scenario) -> flocking.Scenario:
    return scenario.with_values({"duration": 100_000 * scenario.step, "record_every": 1000})


@pytest.mark.parametrize("value", [math.nan, math.inf, 1e300])
def test_issue_49_a_refused_resume_keeps_every_byte_of_the_interrupted_run(tmp_path, value):
    partial = interrupted(tmp_path, "r", long(flocking.Scenario.load(FIG11)))
    forge_position(partial, value)
    before = checksums(partial)
    with pytest.raises(flocking.ScenarioError, match=r"positions\[0\]") as error:
        flocking.resume(tmp_path / "r")
    assert "is kept as it was" in str(error.value)
    assert checksums(partial) == before


def test_issue_49_an_unreadable_conditions_state_keeps_the_run(tmp_path):
    scenario = long(flocking.Scenario.load(FIG11)).with_values(
        {"conditions.communication.delay": 0.05}
    )
    partial = interrupted(tmp_path, "c", scenario, trajectory=False)
    path = partial / "checkpoint.bin"
    body = path.read_bytes()[:-8]
    # the conditions' state is the last text of the checkpoint: cut its closing bracket
    forged = body[:-1]
    path.write_bytes(forged + struct.pack("<Q", fnv1a(forged)))
    before = checksums(partial)
    with pytest.raises(flocking.ScenarioError, match="no readable state of the conditions"):
        flocking.resume(tmp_path / "c")
    assert checksums(partial) == before


def test_issue_49_a_run_is_resumed_only_with_its_own_controls(tmp_path):
    scenario = long(flocking.Scenario.load(FIG11))
    calls = []

    def mine(t, q, p, neighbours):
        calls.append(t)
        if len(calls) > 30:
            raise RuntimeError("stop here")
        return -p

    def other(t, q, p, neighbours):
        return -2 * p

    with pytest.raises(RuntimeError, match="stop here"):
        flocking.run(scenario, out=tmp_path / "r", controls=mine, checkpoint_every=10)
    partial = tmp_path / "r.partial"
    before = checksums(partial)
    with pytest.raises(flocking.RunDirectoryError, match="not with Python controls=.*other"):
        flocking.resume(tmp_path / "r", controls=other)
    assert checksums(partial) == before


SIGINT_SCRIPT = textwrap.dedent(
    """
    import sys, time
    import flocking
    scenario = flocking.Scenario.load(sys.argv[1]).with_values({changes})
    {setup}
    print("started", flush=True)
    try:
        {work}
    except KeyboardInterrupt as error:
        print("interrupted", time.monotonic(), flush=True)
        {after}
    """
)


def sigint(tmp_path, fixture, changes, work, setup="pass", after="pass"):
    """Runs ``work`` in a Python of its own, sends it SIGINT 1.5 s after it starts, and returns
    its output and how long it took to raise KeyboardInterrupt."""
    script = tmp_path / "script.py"
    script.write_text(
        SIGINT_SCRIPT.format(changes=changes, setup=setup, work=work, after=after)
    )
    child = subprocess.Popen(
        [sys.executable, str(script), str(FIXTURES / fixture)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
    )
    try:
        assert child.stdout.readline().strip() == "started", child.stderr.read()
        time.sleep(1.5)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=60)
    finally:
        child.kill()  # a child that ignored the signal is not left running (no-op once it exited)
    assert child.returncode == 0, err
    lines = out.split("\n")
    assert lines[0].startswith("interrupted"), out + err
    return lines, float(lines[0].split()[1]) - sent


def test_issue_49_sigint_stops_a_step_of_every_pair_within_2_s(tmp_path):
    # Cucker-Smale without a cutoff, 30,000 agents: seconds a step, which ignored SIGINT
    lines, took = sigint(
        tmp_path,
        "cucker_smale2007_n50.ron",
        "{'agents': 30000, 'integrator': 'SymplecticEuler', "
        "'initial.positions': {'Box': {'min': [0.0, 0.0], 'max': [1e5, 1e5]}}}",
        "sim.step(1)",
        setup="sim = flocking.Simulation(scenario)",
        after="print(sim.steps)",
    )
    assert took < 2.0, took
    # cut while the inputs were summed, before the state changed: still at its start, usable
    assert lines[1] == "0"


def test_issue_49_sigint_stops_a_vehicles_inner_steps_within_2_s(tmp_path):
    lines, took = sigint(
        tmp_path,
        "unicycle_alg2_n50.ron",
        "{'vehicle.inner_step': 1e-9, 'duration': 1.0}",
        "flocking.run(scenario, out='r', checkpoint_every=1)",
    )
    assert took < 2.0, took
    note = (tmp_path / "r.partial" / "INCOMPLETE").read_text()
    assert "cut short mid-way" in note and "Resume:" in note


def test_issue_49_a_simulation_torn_by_sigint_steps_no_more(tmp_path):
    # cut inside the unicycles' inner steps, the state is between two steps: never continued
    lines, took = sigint(
        tmp_path,
        "unicycle_alg2_n50.ron",
        "{'vehicle.inner_step': 1e-9, 'duration': 1.0}",
        "sim.step(1)",
        setup="sim = flocking.Simulation(scenario)",
        after=(
            "try:\n        sim.step(1)\n"
            "    except flocking.SimulationError as torn:\n"
            "        print(type(torn).__name__, flush=True)"
        ),
    )
    assert took < 2.0, took
    assert lines[1] == "SimulationError", lines


def test_issue_49_sigint_stops_a_benchmark_within_2_s(tmp_path):
    _, took = sigint(
        tmp_path,
        "tac2006_fig11_alg2_n100.ron",
        "{}",
        "flocking.bench(n=1_000_000, steps=100_000)",
    )
    assert took < 2.0, took


def test_issue_49_bench_has_the_guards_of_run():
    with pytest.raises(MemoryError, match="delay line"):
        flocking.bench(n=100, steps=2, delay=1e6)
    with pytest.raises(ValueError, match="dim, delay do"):
        flocking.bench(workload="vicsek", dim=3, delay=0.1)
    with pytest.raises(ValueError, match="seeds=0"):
        flocking.bench(workload="vicsek", seeds=0)
    with pytest.raises(ValueError, match="scale_to=0"):
        flocking.bench(workload="boids-small", scale_to=0)
    with pytest.raises(ValueError, match="seeds applies only with workload"):
        flocking.bench(seeds=3)
    with pytest.raises(ValueError, match="steps=1000000000000000"):
        flocking.bench(n=10, steps=10**15)
    with pytest.raises(TypeError):
        flocking.bench(n=10, steps=1e15)


def test_issue_49_an_npy_trajectory_reads_back_its_vehicle_columns_by_name(tmp_path):
    scenario = flocking.Scenario.load(FIXTURES / "unicycle_alg2_n50.ron").with_values(
        {"duration": 1.0}
    )
    flocking.run(scenario, out=tmp_path / "npy", trajectory_format="npy")
    flocking.run(scenario, out=tmp_path / "csv")
    npy, csv = flocking.read_run(tmp_path / "npy"), flocking.read_run(tmp_path / "csv")
    assert npy.trajectory.vehicle_columns == ("heading", "speed", "turn_rate")
    assert npy.final.vehicle_columns == csv.final.vehicle_columns
