"""The classic models from Python: their parameters by dotted path, a run with the order
measures in its metrics, runs that repeat bit for bit, and the error of a condition a velocity
model cannot take."""

import numpy as np
import pytest

import flocking
from conftest import FIXTURES, assert_runs_equal, short

VICSEK = FIXTURES / "vicsek1995_fig2a_n400.ron"
BOIDS = FIXTURES / "boids_small_n200.ron"


def test_model_parameters_by_path():
    scenario = flocking.Scenario.load(VICSEK)
    assert scenario.value("algorithm.eta") == 2.0
    quiet = scenario.with_values({"algorithm.eta": 0.1, "agents": 100})
    assert quiet.value("algorithm.eta") == 0.1
    assert quiet.agents == 100


def test_a_vicsek_run_orders_at_low_noise(tmp_path):
    scenario = flocking.Scenario.load(VICSEK).with_values(
        {"algorithm.eta": 0.1, "duration": 1500.0, "record_every": 100}
    )
    result = flocking.run(scenario, out=tmp_path / "vicsek")
    polarisation = result.metrics["polarisation"]
    assert polarisation[0] < 0.2  # random headings: about 1/√N
    assert polarisation[-1] > 0.95
    speeds = np.linalg.norm(result.trajectory.velocities[-1], axis=1)
    assert np.allclose(speeds, 0.03, rtol=1e-12)
    positions = result.trajectory.positions
    assert positions.min() >= 0.0 and positions.max() < 10.0  # wrapped into the box


def test_boids_runs_repeat_bit_for_bit(tmp_path):
    """The random activation order is keyed by step and the scenario's seed: two runs, and two
    simulations stepped alike, have the same bits."""
    scenario = short(BOIDS, records=20)
    whole = flocking.run(scenario, out=tmp_path / "whole")
    sim = flocking.Simulation(scenario)
    sim.step(7)
    again = flocking.Simulation(scenario)
    again.step(7)
    assert np.array_equal(sim.q, again.q) and np.array_equal(sim.p, again.p)
    assert_runs_equal(whole, flocking.run(scenario, out=tmp_path / "again"))


def test_velocity_models_refuse_actuation_limits():
    scenario = flocking.Scenario.load(BOIDS)
    with pytest.raises(flocking.ScenarioError, match="conditions.actuation"):
        scenario.with_values({"conditions.actuation.max_acceleration": 1.0})
