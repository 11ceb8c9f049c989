"""Ctrl-C (KeyboardInterrupt) stops a run or a `Simulation.step` between steps, leaving a run
directory resumable as `flocking run` does; the GIL is released while Rust runs."""

import _thread
import threading
import time

import pytest

import flocking
from conftest import FIG11, OUTPUT_FILES, assert_same_files, cli_run


def long_fig11(steps: int) -> flocking.Scenario:
    """Fig. 11 for ``steps`` steps, recording rarely."""
    scenario = flocking.Scenario.load(FIG11)
    return scenario.with_values({"duration": steps * scenario.step, "record_every": 1000})


def interrupt_after(seconds: float) -> threading.Timer:
    timer = threading.Timer(seconds, _thread.interrupt_main)
    timer.start()
    return timer


def test_ctrl_c_stops_a_run_resumably(tmp_path):
    scenario = long_fig11(100_000)
    timer = interrupt_after(0.3)
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt) as error:
        flocking.run(scenario, out=tmp_path / "py", checkpoint_every=0)
    timer.join()
    assert time.monotonic() - start < 2.0
    partial = tmp_path / "py.partial"
    assert "interrupted after step" in str(error.value)
    assert str(partial) in str(error.value)
    note = (partial / "INCOMPLETE").read_text()
    assert note.startswith("incomplete: interrupted after step")
    assert (partial / "checkpoint.bin").exists()
    # resumed, the directory is the uninterrupted run's, byte for byte
    resumed = flocking.resume(tmp_path / "py")
    assert resumed.path == str(tmp_path / "py")
    cli_dir = cli_run(scenario, tmp_path / "cli")
    assert_same_files(cli_dir, tmp_path / "py", OUTPUT_FILES + ["trajectory.csv"])


def test_ctrl_c_stops_a_run_in_memory():
    timer = interrupt_after(0.2)
    with pytest.raises(KeyboardInterrupt, match="interrupted after step"):
        flocking.run(long_fig11(100_000), trajectory=False)
    timer.join()


def test_ctrl_c_stops_a_simulation_between_steps():
    sim = flocking.Simulation(long_fig11(100_000))
    timer = interrupt_after(0.2)
    # a bound, so that a missed interrupt fails the test (10**6 steps take seconds) instead of
    # running on
    steps = 10**6
    with pytest.raises(KeyboardInterrupt):
        sim.step(steps)
    timer.join()
    assert 0 < sim.steps < steps
    assert sim.t == sim.steps * 0.01 or abs(sim.t - sim.steps * 0.01) < 1e-9
    sim.step(3)  # still usable


def test_the_gil_is_released_while_rust_runs():
    scenario = long_fig11(30_000)
    done = threading.Event()
    worker = threading.Thread(target=lambda: (flocking.run(scenario, trajectory=False), done.set()))
    sim = flocking.Simulation(scenario)
    stepper = threading.Thread(target=lambda: sim.step(30_000))
    worker.start()
    stepper.start()
    spins = 0
    while not done.is_set():
        spins += 1
        time.sleep(0.001)
    worker.join()
    stepper.join()
    assert spins > 20
    assert sim.steps == 30_000
