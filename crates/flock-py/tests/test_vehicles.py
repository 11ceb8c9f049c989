"""Vehicles from Python: a run's vehicle states in memory and read back from its directory, with
their column names, the same bits both ways; the limits of the robots in every recorded state;
their parameters by dotted path; and the error of a vehicle in the wrong dimension."""

import numpy as np
import pytest

import flocking
from conftest import FIXTURES

ROBOTS = FIXTURES / "unicycle_alg2_n50.ron"
QUADS = FIXTURES / "crazyflie_alg2_3d_n50.ron"


def test_vehicle_states_in_memory_and_on_disk(tmp_path):
    scenario = flocking.Scenario.load(QUADS).with_values({"duration": 0.5, "record_every": 10})
    result = flocking.run(scenario, out=tmp_path / "quads")
    columns = result.final.vehicle_columns
    assert columns[:4] == ("attitude_w", "attitude_x", "attitude_y", "attitude_z")
    assert len(columns) == 11
    assert result.final.vehicle.shape == (50, 11)
    assert result.trajectory.vehicle.shape == (6, 50, 11)
    # unit quaternions
    norms = np.linalg.norm(result.trajectory.vehicle[..., :4], axis=-1)
    assert np.allclose(norms, 1.0, atol=1e-12)
    back = flocking.read_run(tmp_path / "quads")
    assert back.final.vehicle_columns == columns
    assert np.array_equal(back.trajectory.vehicle, result.trajectory.vehicle)
    assert np.array_equal(back.final.vehicle, result.final.vehicle)


def test_robots_stay_within_their_limits():
    scenario = flocking.Scenario.load(ROBOTS).with_values({"duration": 60.0, "record_every": 20})
    assert scenario.value("vehicle.max_speed") == 0.22
    result = flocking.run(scenario)
    heading, speed, turn_rate = np.moveaxis(result.trajectory.vehicle, -1, 0)
    assert np.abs(speed).max() <= 0.22 * (1 + 1e-12)
    assert np.abs(turn_rate).max() <= 2.84 * (1 + 1e-12)
    assert np.abs(heading).max() <= np.pi
    assert result.metrics["at_speed_limit"].max() > 0


def test_point_masses_have_no_vehicle_states():
    scenario = flocking.Scenario.load(ROBOTS).with_values(
        {"vehicle": "PointMass", "duration": 0.5, "record_every": 10}
    )
    result = flocking.run(scenario)
    assert result.final.vehicle is None
    assert result.final.vehicle_columns == ()


def test_a_quadrotor_in_the_plane_is_refused():
    scenario = flocking.Scenario.load(ROBOTS)
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_values({"vehicle": {"Quadrotor": {}}})
    assert error.value.field == "vehicle"
    assert "set dim: 3" in str(error.value)
