"""The Python API: scenarios, shapes and dtypes of results, `read_run` of both trajectory
formats, docstrings and the shipped type stubs."""

import inspect
import pickle
from pathlib import Path

import numpy as np
import pytest

import flocking
from conftest import FIG11, FIXTURES, assert_runs_equal, short

# the columns of every metrics.csv, then those of Fig. 11's: Algorithm 2's γ-tracking errors
METRICS = flocking.METRICS_HEADER.split(",")
COLUMNS = METRICS + ["gamma_position_error", "gamma_velocity_error"]


def test_scenario_round_trips():
    scenario = flocking.Scenario.load(FIG11)
    assert (scenario.name, scenario.dim, scenario.agents) == ("tac2006_fig11_alg2_n100", 2, 100)
    assert (scenario.step, scenario.duration, scenario.steps, scenario.record_every) == (
        0.01,
        100.0,
        10_000,
        20,
    )
    again = flocking.Scenario.from_ron(scenario.to_ron())
    assert again.to_ron() == scenario.to_ron()
    assert pickle.loads(pickle.dumps(scenario)).to_ron() == scenario.to_ron()
    assert "agents=100" in repr(scenario)
    assert scenario.warnings() == []


def test_values_by_path():
    scenario = flocking.Scenario.load(FIG11)
    assert scenario.value("algorithm.c1") == 0.02
    assert scenario.value("alpha.r") is None  # follows d
    assert scenario.value("initial.positions") == {"Gaussian": {"mean": [0.0, 0.0], "std": 50.0}}
    changed = scenario.with_values({"algorithm.c1": 0.05, "agents": 400, "alpha.d": np.float64(8)})
    assert (changed.agents, changed.value("algorithm.c1"), changed.value("alpha.d")) == (
        400,
        0.05,
        8.0,
    )
    assert changed != scenario and scenario.agents == 100  # a copy
    assert scenario.with_values({"agents": np.int64(50)}).agents == 50
    assert scenario.with_values({"agents": 50.0}).agents == 50
    gamma = {"Static": {"position": [1.0, 2.0]}}
    assert scenario.with_values({"algorithm.gamma": gamma}).value("algorithm.gamma") == gamma


def test_run_shapes_and_dtypes():
    scenario = short(FIG11)
    result = flocking.run(scenario)
    frames = -(-scenario.steps // scenario.record_every) + 1  # and the last step
    assert list(result.metrics) == COLUMNS
    for name, column in result.metrics.items():
        assert column.shape == (frames,), name
        assert column.dtype == (np.int64 if name in ("collisions", "components") else np.float64), name
    assert result.trajectory.times.shape == (frames,)
    assert np.array_equal(result.trajectory.times, result.metrics["t"])
    assert result.trajectory.positions.shape == (frames, 100, 2)
    assert result.trajectory.velocities.shape == (frames, 100, 2)
    assert result.trajectory.positions.dtype == np.float64
    assert result.final.positions.shape == (100, 2)
    assert result.final.t == result.metrics["t"][-1] == scenario.steps * scenario.step
    assert result.path is None
    assert result.scenario == scenario
    kept = flocking.run(scenario, trajectory=False)
    assert kept.trajectory is None
    assert np.array_equal(kept.final.positions, result.final.positions)


def test_diagnostic_columns_follow_energy():
    result = flocking.run(short(FIXTURES / "tr2003_fig9_sink_n100.ron"))
    names = list(result.metrics)
    assert names[: len(METRICS)] == METRICS
    for name in names[len(METRICS) :]:
        # the stress counts (ACC 2004 eq. 31) count agents: integers, as collisions and components
        counts = name in ("stress_towards", "stress_away", "stress_neutral")
        assert result.metrics[name].dtype == (np.int64 if counts else np.float64), name


def test_simulation_shapes():
    sim = flocking.Simulation(flocking.Scenario.load(FIXTURES / "tac2006_fig13_alg2_3d_n50.ron"))
    assert (sim.dim, sim.agents, sim.steps, sim.t) == (3, 50, 0, 0.0)
    assert sim.q.shape == sim.p.shape == (50, 3)
    assert sim.q.dtype == np.float64
    assert list(sim.metrics()) == [name for name in METRICS if name not in ("t", "energy")]
    assert isinstance(sim.metrics()["components"], int)
    assert isinstance(sim.metrics()["collisions"], int)
    assert isinstance(sim.energy(), float)
    q = sim.q
    q[0] += 1.0  # a copy: the simulation is unchanged
    assert not np.array_equal(q, sim.q)
    sim.set_state(velocities=sim.p + 1.0)  # a perturbation
    sim.step(2)
    assert sim.steps == 2 and "steps=2" in repr(sim)


@pytest.mark.parametrize("trajectory_format", ["csv", "npy"])
def test_read_run_round_trips(tmp_path, trajectory_format):
    scenario = short(FIXTURES / "tac2006_fig13_alg2_3d_n50.ron")
    result = flocking.run(scenario, out=tmp_path / "out", trajectory_format=trajectory_format)
    assert (tmp_path / "out" / f"trajectory.{trajectory_format}").exists()
    back = flocking.read_run(tmp_path / "out")
    assert_runs_equal(result, back)
    assert back.path == str(tmp_path / "out")
    assert back.scenario.to_ron() == scenario.to_ron()
    if trajectory_format == "npy":
        raw = np.load(tmp_path / "out" / "trajectory.npy")
        assert np.array_equal(raw["q"], result.trajectory.positions)


def test_to_pandas():
    pandas = pytest.importorskip("pandas")
    frame = flocking.run(short(FIG11)).to_pandas()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == COLUMNS


def test_every_public_name_has_a_docstring():
    for name in flocking.__all__:
        item = getattr(flocking, name)
        if name == "METRICS_HEADER":
            continue
        assert inspect.getdoc(item), name
        for member, value in vars(item).items() if inspect.isclass(item) else []:
            if not member.startswith("_") and callable(value):
                assert inspect.getdoc(getattr(item, member)), f"{name}.{member}"


def test_type_stubs_are_shipped():
    package = Path(flocking.__file__).parent
    assert (package / "py.typed").exists()
    stubs = (package / "__init__.pyi").read_text()
    for name in flocking.__all__:
        assert name in stubs, name


def test_quickstart_runs(tmp_path, monkeypatch, capsys):
    path = Path(__file__).resolve().parents[3] / "examples" / "python" / "quickstart.py"
    namespace = {"__name__": "quickstart", "__file__": str(path)}
    exec(compile(path.read_text(), str(path), "exec"), namespace)
    monkeypatch.chdir(tmp_path)
    namespace["main"]("fig11.png")
    printed = capsys.readouterr().out
    assert "connectivity       1\n" in printed


def test_readme_example_runs(tmp_path, monkeypatch):
    root = Path(__file__).resolve().parents[3]
    readme = (root / "README.md").read_text()
    section = readme.split("## Use it from Python", 1)[1]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    (tmp_path / "fixtures").symlink_to(FIXTURES)
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(code, namespace)
    assert namespace["again"].final.t == 50.0
    assert namespace["sim"].t == 10.0
    assert namespace["data"].attrs["name"] == "tac2006_fig11_alg2_n100"
    assert namespace["mine"].final.t == 50.0
    assert (tmp_path / "out" / "py-fig11-damped" / "metrics.csv").exists()
    exec(code, {})  # again: the example does not collide with itself
