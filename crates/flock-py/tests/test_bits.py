"""Python results are the CLI's bits: `flocking.run` against `flocking run` of the same scenario, its
run directory byte for byte, and `Simulation` stepped k times against a run."""

import numpy as np
import pytest

import flocking
from conftest import (
    FIG11,
    FIXTURES,
    OUTPUT_FILES,
    assert_runs_equal,
    assert_same_files,
    cli,
    cli_run,
    short,
)


def test_fig11_run_directory_is_the_clis_byte_for_byte(tmp_path):
    cli("run", FIG11, "--out", tmp_path / "cli", "--quiet")
    result = flocking.run(flocking.Scenario.load(FIG11), out=tmp_path / "py")
    assert result.path == str(tmp_path / "py")
    assert_same_files(tmp_path / "cli", tmp_path / "py", OUTPUT_FILES + ["trajectory.csv"])
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == sorted(
        p.name for p in (tmp_path / "cli").iterdir()
    )
    assert_runs_equal(result, flocking.read_run(tmp_path / "cli"))
    assert result.metrics["connectivity"][-1] == 1.0


@pytest.mark.parametrize("fixture", sorted(p.name for p in FIXTURES.glob("*.ron")))
def test_every_fixture_matches_the_cli(tmp_path, fixture):
    scenario = short(FIXTURES / fixture)
    cli_dir = cli_run(scenario, tmp_path / "cli")
    result = flocking.run(scenario)
    assert_runs_equal(result, flocking.read_run(cli_dir))


def test_npy_trajectory_matches_the_cli_byte_for_byte(tmp_path):
    scenario = short(FIXTURES / "tac2006_fig13_alg2_3d_n50.ron")
    cli_dir = cli_run(scenario, tmp_path / "cli", "--trajectory-format", "npy")
    result = flocking.run(scenario, out=tmp_path / "py", trajectory_format="npy")
    assert_same_files(cli_dir, tmp_path / "py", OUTPUT_FILES + ["trajectory.npy"])
    assert_runs_equal(result, flocking.read_run(cli_dir))


def test_explicit_initial_state_matches_the_cli(tmp_path):
    rng = np.random.default_rng(3)
    positions = rng.uniform(-20.0, 20.0, size=(30, 2))
    velocities = rng.normal(size=(30, 2))
    scenario = short(FIG11).with_initial(positions, velocities)
    assert scenario.agents == 30
    result = flocking.run(scenario)
    assert np.array_equal(result.trajectory.positions[0], positions)
    assert np.array_equal(result.trajectory.velocities[0], velocities)
    assert_runs_equal(result, flocking.read_run(cli_run(scenario, tmp_path / "cli")))
    # the same start given to a Simulation
    sim = flocking.Simulation(short(FIG11).with_values({"agents": 30}), positions, velocities)
    sim.step(scenario.steps)
    assert np.array_equal(sim.q, result.final.positions)
    assert np.array_equal(sim.p, result.final.velocities)


@pytest.mark.parametrize(
    "fixture", ["tac2006_fig11_alg2_n100.ron", "tac2006_fig13_alg2_3d_n50.ron"]
)
def test_stepping_k_times_equals_run(fixture):
    scenario = short(FIXTURES / fixture)
    result = flocking.run(scenario)
    sim = flocking.Simulation(scenario)
    sim.step(scenario.steps)
    assert sim.steps == scenario.steps
    assert sim.t == result.final.t
    assert np.array_equal(sim.q, result.final.positions)
    assert np.array_equal(sim.p, result.final.velocities)
    metrics = sim.metrics()
    for name, value in metrics.items():
        assert value == result.metrics[name][-1], name
    assert sim.energy() == result.metrics["energy"][-1]
    # one step at a time, the same bits
    single = flocking.Simulation(scenario)
    for _ in range(scenario.steps):
        single.step()
    assert np.array_equal(single.q, sim.q) and np.array_equal(single.p, sim.p)


def test_simulation_records_match_the_trajectory():
    scenario = short(FIG11)
    result = flocking.run(scenario)
    sim = flocking.Simulation(scenario)
    for k in range(len(result.trajectory.times) - 1):
        assert sim.t == result.trajectory.times[k]
        assert np.array_equal(sim.q, result.trajectory.positions[k])
        assert np.array_equal(sim.p, result.trajectory.velocities[k])
        sim.step(min(scenario.record_every, scenario.steps - sim.steps))


def test_set_state_with_the_same_state_changes_no_bit():
    scenario = short(FIG11)
    result = flocking.run(scenario)
    sim = flocking.Simulation(scenario)
    sim.step(7)
    sim.set_state(sim.q.copy(), sim.p.copy())
    sim.step(scenario.steps - 7)
    assert np.array_equal(sim.q, result.final.positions)
