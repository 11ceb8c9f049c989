"""Real conditions from Python (issue 21): every part of a scenario's ``conditions`` reachable by
dotted path with ``with_values`` (numbers, and enums as RON text or JSON's tagged form), validated
with a ``ScenarioError`` naming the path, its diagnostics columns in the run's metrics, the bits of
the CLI, and the consensus bounds warned at 1.1× and not at 0.9×."""

import math

import numpy as np
import pytest

import flocking
from conftest import FIXTURES, OUTPUT_FILES, cli_run, short

CYCLE = FIXTURES / "consensus_cycle_n20.ron"
DIAGNOSTICS = ["links_lost", "information_age", "at_acceleration_limit", "at_speed_limit", "failed"]


def conditioned(scenario: flocking.Scenario) -> flocking.Scenario:
    """``scenario`` with a delay, Bernoulli loss held for 0.5 s, white sensing noise, actuator
    limits and a failure, each set by its dotted path."""
    return scenario.with_values(
        {
            "conditions.communication.delay": 0.05,
            "conditions.communication.loss": "Bernoulli(p: 0.2)",
            "conditions.communication.when_lost": {"Hold": {"max_age": 0.5}},
            "conditions.sensing.noise": "White(sigma_q: 0.1, sigma_p: 0.02)",
            "conditions.actuation.max_acceleration": 2.0,
            "conditions.actuation.max_speed": 3.0,
            "conditions.faults.at": [{"agent": 3, "time": 0.2}],
            "conditions.faults.mode": "Silent",
        }
    )


def test_conditions_are_set_and_read_by_dotted_path():
    scenario = conditioned(short(CYCLE))
    assert scenario.value("conditions.communication.delay") == 0.05
    assert scenario.value("conditions.communication.loss") == {"Bernoulli": {"p": 0.2}}
    assert scenario.value("conditions.communication.when_lost") == {"Hold": {"max_age": 0.5}}
    assert scenario.value("conditions.actuation.max_speed") == 3.0
    again = flocking.Scenario.from_ron(scenario.to_ron())
    assert again == scenario
    assert "conditions" not in short(CYCLE).to_ron()  # the ideal scenario is written without them


@pytest.mark.parametrize(
    ("path", "value", "words"),
    [
        ("conditions.communication.loss", "Bernoulli(p: 1.5)", ["conditions.communication.loss", "1.5"]),
        ("conditions.communication.delay", 0.015, ["conditions.communication.delay", "whole number of steps"]),
        ("conditions.sensing.noise", "White(sigma_q: -1.0, sigma_p: 0.0)", ["sigma_q", "-1"]),
        ("conditions.actuation.max_speed", math.nan, ["conditions.actuation.max_speed"]),
    ],
)
def test_a_bad_condition_is_named(path, value, words):
    with pytest.raises(flocking.ScenarioError) as raised:
        short(CYCLE).with_values({path: value})
    for word in words:
        assert word in str(raised.value), str(raised.value)


def test_a_conditioned_run_has_its_diagnostics_and_the_bits_of_the_cli(tmp_path):
    scenario = conditioned(short(CYCLE, records=40))
    result = flocking.run(scenario)
    for name in DIAGNOSTICS:
        assert name in result.metrics, list(result.metrics)
    assert result.metrics["links_lost"][1:].max() > 0.0
    assert result.metrics["information_age"][1:].min() >= 0.05
    assert result.metrics["failed"][-1] == 1.0
    assert np.all(np.linalg.norm(result.trajectory.velocities, axis=2) <= 3.0 * (1 + 1e-12))
    cli = cli_run(scenario, tmp_path / "cli")
    flocking.run(scenario, out=tmp_path / "py")
    for name in OUTPUT_FILES:
        if name != "flocking.txt":  # its wall time differs
            assert (tmp_path / "py" / name).read_bytes() == (cli / name).read_bytes(), name


def test_failed_agents_are_marked_in_the_trajectory_the_final_state_and_read_run(tmp_path):
    # issue 28: the marks of trajectory.csv's `failed` column, in memory and read back
    scenario = conditioned(short(CYCLE, records=40))
    result = flocking.run(scenario, out=tmp_path / "run")
    failed = result.trajectory.failed
    assert failed is not None and failed.dtype == np.bool_
    assert failed.shape == result.trajectory.positions.shape[:2]
    np.testing.assert_array_equal(failed.sum(axis=1), result.metrics["failed"])
    assert not failed[0].any() and failed[-1][3] and failed[-1].sum() == 1
    np.testing.assert_array_equal(result.final.failed, failed[-1])
    again = flocking.read_run(tmp_path / "run")
    np.testing.assert_array_equal(again.trajectory.failed, failed)
    np.testing.assert_array_equal(again.final.failed, failed[-1])
    ideal = flocking.run(short(CYCLE, records=40))
    assert ideal.trajectory.failed is None and ideal.final.failed is None


def test_a_delay_of_every_state_is_warned_above_the_consensus_bound_only():
    # C₂₀ with gain c: λ_max(L) = 4, so τ* = π / (8 c)
    scenario = flocking.Scenario.load(CYCLE)
    gain = scenario.value("algorithm.gain")
    bound = math.pi / (8.0 * gain)
    step = scenario.step

    def warned(tau: float) -> bool:
        delay = round(tau / step) * step
        delayed = scenario.with_values(
            {"conditions.communication.delay": delay, "conditions.communication.delayed": "All"}
        )
        return any("conditions.communication.delay" in w for w in delayed.warnings())

    assert warned(1.1 * bound)
    assert not warned(0.9 * bound)
