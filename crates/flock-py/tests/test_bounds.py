"""Bounded inputs (issue 20): hostile values reach Python as typed exceptions with clear messages
— never a segfault or a ``PanicException`` — shapes are checked exactly, a pickled or written
scenario keeps its derived defaults derived, and ``Scenario.estimate`` tells a run's cost."""

import math
import pickle
import sys

import numpy as np
import pytest

import flocking
from conftest import FIG11, short

SWEEP = """Sweep(
    base: Path("{base}"),
    set: {{"duration": 0.5}},
    axes: [(path: "agents", values: {values})],
    seeds: {seeds},
)"""


def nested(depth: int) -> list:
    """A list nested ``depth`` deep, built without recursion."""
    value: list = []
    for _ in range(depth):
        value = [value]
    return value


@pytest.mark.parametrize("container", [list, tuple, "dict"])
def test_a_value_nested_10000_deep_is_a_scenario_error(container):
    scenario = flocking.Scenario.load(FIG11)
    value: object = 1.0
    for _ in range(10_000):
        value = {"x": value} if container == "dict" else container([value])
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_values({"description": value})
    assert isinstance(error.value, ValueError)
    assert error.value.field == "description"
    assert "nested more than 64 levels deep" in str(error.value)


def test_a_list_that_contains_itself_is_a_scenario_error():
    scenario = flocking.Scenario.load(FIG11)
    cycle: list = [1.0]
    cycle.append(cycle)
    loop: dict = {}
    loop["again"] = [loop]
    for value in (cycle, [[cycle]], loop):
        with pytest.raises(flocking.ScenarioError) as error:
            scenario.with_values({"description": value})
        assert "contains itself" in str(error.value)
        assert error.value.field is not None and error.value.field.startswith("description")


def test_hostile_values_are_typed_errors():
    scenario = flocking.Scenario.load(FIG11)
    for values in (
        {"agents": 2**64},
        {"agents": -1},
        {"agents": 10**30},
        {"agents": 1e300},
        {"agents": float("nan")},
        {"seed": 2**64},
        {"duration": float("inf")},
        {"step": 1e-300},
        {"description": object()},
        {"description": {1: "not a string key"}},
        {"": 1.0},
        {"obstacles.99999999999999999999.radius": 1.0},
    ):
        with pytest.raises(flocking.ScenarioError):
            scenario.with_values(values)
    with pytest.raises(TypeError):
        scenario.with_values({1: 1.0})


def test_a_transposed_positions_array_names_both_shapes():
    scenario = flocking.Scenario.load(FIG11)
    positions = np.random.default_rng(0).normal(size=(scenario.agents, 2)) * 30
    with pytest.raises(flocking.ScenarioError) as error:
        flocking.Simulation(scenario, positions.T)
    message = str(error.value)
    assert "(2, 100)" in message and "(100, 2)" in message, message
    assert "transpose" in message
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_initial(positions.T)
    message = str(error.value)
    assert "(2, 100)" in message and "(n, 2)" in message and "transpose" in message, message
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_initial(positions, np.zeros((2, 100)))
    message = str(error.value)
    assert "(2, 100)" in message and "(100, 2)" in message, message
    # the right shapes are accepted
    assert scenario.with_initial(positions, np.zeros((100, 2))).agents == 100


def test_a_pickled_scenario_is_equal_and_keeps_defaults_derived():
    scenario = flocking.Scenario.load(FIG11)
    back = pickle.loads(pickle.dumps(scenario))
    assert back == scenario
    d = scenario.alpha["d"]
    assert back.alpha["r"] == pytest.approx(1.2 * d)
    moved = back.with_values({"alpha.d": 5})
    assert moved.alpha["d"] == 5.0
    assert moved.alpha["r"] == pytest.approx(6.0)
    assert moved == scenario.with_values({"alpha.d": 5})


def test_a_written_scenario_keeps_defaults_derived(tmp_path):
    scenario = short(FIG11, records=1)
    flocking.run(scenario, tmp_path / "run", trajectory=False)
    loaded = flocking.Scenario.load(tmp_path / "run" / "scenario.ron")
    assert loaded == scenario
    moved = loaded.with_values({"alpha.d": 5})
    assert moved.alpha["r"] == pytest.approx(6.0)
    assert flocking.Scenario.from_ron(loaded.to_ron()) == loaded


@pytest.mark.parametrize(
    "seeds, values",
    [
        ("18446744073709551615", "List([10])"),
        ("300000", "List([10, 20, 30, 40])"),
        ("1", "Linspace(from: 10.0, to: 20.0, count: 10000000000000)"),
        ("2", "Linspace(from: 10.0, to: 20.0, count: 18446744073709551615)"),
    ],
)
def test_huge_sweep_counts_are_scenario_errors(tmp_path, seeds, values):
    path = tmp_path / "huge.sweep.ron"
    path.write_text(SWEEP.format(base=str(FIG11), values=values, seeds=seeds))
    with pytest.raises(flocking.ScenarioError) as error:
        flocking.sweep(path, tmp_path / "out")
    assert "1000000" in str(error.value)
    assert not (tmp_path / "out").exists()


def test_a_sweep_seed_count_beyond_u64_is_a_scenario_error(tmp_path):
    path = tmp_path / "huge.sweep.ron"
    path.write_text(SWEEP.format(base=str(FIG11), values="List([10])", seeds="18446744073709551616"))
    with pytest.raises(flocking.ScenarioError):
        flocking.sweep(path, tmp_path / "out")


def test_no_entry_point_panics_on_bad_arguments(tmp_path):
    """Out-of-range numbers are OverflowError/ValueError/TypeError, never a PanicException."""
    scenario = flocking.Scenario.load(FIG11)
    calls = [
        lambda: flocking.Simulation(scenario).step(-1),
        lambda: flocking.Simulation(scenario).step(2**64),
        lambda: flocking.run(scenario, tmp_path / "a", checkpoint_every=-1),
        lambda: flocking.run(scenario, tmp_path / "b", trajectory_format="xml"),
        lambda: flocking.Scenario.from_ron("(" * 100_000),
        lambda: flocking.Scenario.from_ron("\0" * 1000),
        lambda: scenario.estimate(trajectory_format="xml"),
    ]
    for call in calls:
        with pytest.raises((ValueError, TypeError, OverflowError)) as error:
            call()
        assert type(error.value).__name__ != "PanicException"


def test_estimate_is_the_clis():
    scenario = flocking.Scenario.load(FIG11)
    estimate = scenario.estimate()
    assert set(estimate) == {
        "steps",
        "records",
        "agent_steps",
        "memory_bytes",
        "disk_bytes",
        "seconds",
        "start_mean_degree",
    }
    # 100 agents of a Gaussian cloud of σ = 50 m: about one neighbour within r = 8.4 m each
    assert 0.2 < estimate["start_mean_degree"] < 6
    assert estimate["steps"] == scenario.steps == 10_000
    assert estimate["records"] == 501
    assert estimate["agent_steps"] == 100 * 10_000
    assert 5e6 < estimate["memory_bytes"] < 100e6
    assert estimate["disk_bytes"] == 0.0  # in memory
    assert 0 < estimate["seconds"] < 10
    written = scenario.estimate(out=True)
    assert written["disk_bytes"] > 1e6  # the CSV trajectory of 501 records of 100 agents
    npy = scenario.estimate(out=True, trajectory_format="npy")
    bare = scenario.estimate(out=True, trajectory=False)
    assert bare["disk_bytes"] < npy["disk_bytes"] < written["disk_bytes"]
    huge = scenario.with_values({"agents": 1_000_000, "duration": 1e5})
    assert huge.estimate()["memory_bytes"] > 2e8
    assert huge.estimate()["seconds"] > 3600
    assert math.isfinite(huge.estimate(out=True)["disk_bytes"])
    # 10⁶ agents in the same cloud see thousands each: too dense to count, and refused
    assert huge.estimate()["start_mean_degree"] is None
    with pytest.raises(MemoryError, match="the start is too dense to estimate"):
        flocking.Simulation(huge)
