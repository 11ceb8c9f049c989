"""controls=flocking.Local in sweeps and resumes: TAC 2006 Algorithm 2 as a local numpy controller,
sent to a sweep's worker processes, gives the built-in sweep's rows bit for bit under packet loss
and delay; a run it stops with an exception resumes from its checkpoint to the uninterrupted run's
bytes; a resume with another local controller is refused."""

import sys
from pathlib import Path

import numpy as np
import pytest

import flocking
from conftest import FIG11, ROOT

sys.path.insert(0, str(ROOT / "examples" / "python"))
from algorithm2_local import LocalAlgorithm2  # noqa: E402

#: 20 agents for 1 s with delay, so that the delay line and the links are part of what resumes.
SMALL = {"duration": 1.0, "agents": 20, "initial.positions.Gaussian.std": 15.0,
         "conditions.communication.delay": 0.02}


def test_a_sweep_of_a_local_controller_has_the_builtin_rows(tmp_path):
    base = flocking.Scenario.load(FIG11).with_values(SMALL)
    axes = {"conditions.communication.loss": ["Bernoulli(p: 0.0)", "Bernoulli(p: 0.2)"]}
    builtin = flocking.sweep(base, tmp_path / "builtin", axes=axes, seeds=2)
    local = flocking.sweep(base, tmp_path / "local", axes=axes, seeds=2,
                           controls=flocking.Local(LocalAlgorithm2(base)))
    assert list(local.columns["error"]) == [""] * 4
    for name in ("velocity_mismatch", "deviation_energy", "connectivity", "min_distance"):
        assert np.array_equal(local.columns[name], builtin.columns[name]), name
    # the workers do call the controller: no input at all gives other rows
    idle = flocking.sweep(base, tmp_path / "idle", axes=axes, seeds=2, controls=flocking.Local(no_input))
    assert not np.array_equal(idle.columns["velocity_mismatch"], builtin.columns["velocity_mismatch"])


def no_input(t, perception):
    """No input (module level: picklable for a sweep's workers)."""
    return np.zeros_like(perception.positions)


class FailingLocal:
    """Algorithm 2 as a local controller that raises once t reaches ``when``."""

    def __init__(self, scenario, when):
        self.inner, self.when = LocalAlgorithm2(scenario), when

    def __call__(self, t, perception):
        if t >= self.when:
            raise RuntimeError(f"stopped at t = {t}")
        return self.inner(t, perception)


def test_a_local_controller_run_stopped_by_an_exception_resumes_bit_for_bit(tmp_path):
    scenario = flocking.Scenario.load(FIG11).with_values(SMALL)
    out = tmp_path / "out"
    with pytest.raises(RuntimeError, match="stopped at t"):
        flocking.run(scenario, out, controls=flocking.Local(FailingLocal(scenario, 0.5)),
                     checkpoint_every=20)
    assert (Path(f"{out}.partial") / "INCOMPLETE").exists()
    with pytest.raises(flocking.RunDirectoryError, match="controls"):
        flocking.resume(out, controls=flocking.Local(LocalAlgorithm2(scenario)))
    resumed = flocking.resume(out, controls=flocking.Local(FailingLocal(scenario, 1e9)))
    reference = flocking.run(scenario, tmp_path / "reference")
    assert np.array_equal(resumed.final.positions, reference.final.positions)
    for name in ("metrics.csv", "trajectory.csv", "final.csv"):
        assert (out / name).read_bytes() == (tmp_path / "reference" / name).read_bytes(), name
