"""Every flock error is a Python exception with the CLI's message: scenario errors a
`ValueError` naming the field, blow-ups an `ArithmeticError`, run directories an `OSError`."""

import math

import numpy as np
import pytest

import flocking
from conftest import FIG11, cli, cli_run, short


def cli_error(*args) -> str:
    """The message the CLI prints after ``error: `` for ``args`` (it must fail)."""
    done = cli(*args, check=False)
    assert done.returncode != 0
    line = next(line for line in done.stderr.splitlines() if line.startswith("error: "))
    return line[len("error: ") :]


def test_exception_classes():
    assert issubclass(flocking.ScenarioError, flocking.FlockError)
    assert issubclass(flocking.ScenarioError, ValueError)
    assert issubclass(flocking.NumericalError, flocking.FlockError)
    assert issubclass(flocking.NumericalError, ArithmeticError)
    assert issubclass(flocking.RunDirectoryError, flocking.FlockError)
    assert issubclass(flocking.RunDirectoryError, OSError)
    assert flocking.ScenarioError.__module__ == "flocking"


def test_missing_file(tmp_path):
    path = tmp_path / "missing.ron"
    with pytest.raises(flocking.ScenarioError) as error:
        flocking.Scenario.load(path)
    assert error.value.field is None
    assert str(error.value) == cli_error("validate", path)


def test_syntax_error_names_line_column_and_field(tmp_path):
    path = tmp_path / "bad.ron"
    path.write_text(FIG11.read_text().replace("c2: 0.4", 'c2: "fast"'))
    with pytest.raises(flocking.ScenarioError) as error:
        flocking.Scenario.load(path)
    assert str(error.value) == cli_error("validate", path)
    assert f"{path}:" in str(error.value)
    with pytest.raises(flocking.ScenarioError, match=r"^<string>:\d+:\d+: "):
        flocking.Scenario.from_ron(path.read_text())


def test_invalid_value_in_a_file(tmp_path):
    path = tmp_path / "bad.ron"
    path.write_text(FIG11.read_text().replace("dim: 2", "dim: 4"))
    with pytest.raises(flocking.ScenarioError) as error:
        flocking.Scenario.load(path)
    assert error.value.field == "dim"
    assert str(error.value) == cli_error("validate", path)


@pytest.mark.parametrize(
    "values, field",
    [
        ({"alpha.d": -1.0}, "alpha.d"),
        ({"agents": 0}, "agents"),
        ({"step": 0.0}, "step"),
        ({"algorithm.c1": "strong"}, "algorithm.c1"),
        ({"agents": 2.5}, "agents"),
        ({"alpha.dd": 1.0}, "alpha.dd"),
        ({"algorithm.c1": math.inf}, "algorithm.c1"),
        ({"algorithm.c1": object()}, "algorithm.c1"),
    ],
)
def test_with_values_errors_name_the_field(values, field):
    scenario = flocking.Scenario.load(FIG11)
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_values(values)
    assert error.value.field == field, str(error.value)
    assert f"`{field}`" in str(error.value)


def test_with_values_error_is_the_clis(tmp_path):
    # the same invalid value, written into a file for the CLI
    path = tmp_path / "bad.ron"
    text = FIG11.read_text().replace("c1: 0.02", "c1: -0.02")
    path.write_text(text)
    with pytest.raises(flocking.ScenarioError) as error:
        flocking.Scenario.load(FIG11).with_values({"algorithm.c1": -0.02})
    # the CLI places it in the file: the line and column of `c1:`
    line, row = next((k, l) for k, l in enumerate(text.splitlines(), 1) if "c1: -0.02" in l)
    place = f"{path}:{line}:{row.index('c1') + 1}: "
    assert cli_error("validate", path) == place + str(error.value)


def test_explicit_state_errors():
    scenario = flocking.Scenario.load(FIG11)
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_initial(np.zeros((5, 3)))
    assert error.value.field is not None and error.value.field.startswith("initial")
    with pytest.raises(flocking.ScenarioError):
        scenario.with_initial(np.full((5, 2), np.nan))
    with pytest.raises(flocking.ScenarioError) as error:
        flocking.Simulation(scenario, np.zeros((7, 2)))
    assert error.value.field == "positions"
    assert "(7, 2)" in str(error.value) and "(100, 2)" in str(error.value)
    sim = flocking.Simulation(scenario)
    with pytest.raises(flocking.ScenarioError):
        sim.set_state(velocities=np.zeros((100, 3)))
    with pytest.raises(flocking.ScenarioError):
        sim.set_state(positions=np.full((100, 2), np.inf))
    assert np.isfinite(sim.q).all()


def blowing_up() -> flocking.Scenario:
    return flocking.Scenario.load(FIG11).with_values({"step": 1.0, "duration": 50.0})


def test_blow_up_is_the_clis_numerical_error(tmp_path):
    scenario = blowing_up()
    with pytest.warns(UserWarning, match="largest stable step"):
        with pytest.raises(flocking.NumericalError) as error:
            flocking.run(scenario, out=tmp_path / "py")
    assert (error.value.step, error.value.t, error.value.agent) == (1, 1.0, 2)
    path = tmp_path / "blow.ron"
    path.write_text(scenario.to_ron())
    assert str(error.value) == cli_error("run", path, "--out", tmp_path / "cli", "--quiet")
    # both keep the records up to the last good step, marked failed
    for name in ("py", "cli"):
        note = (tmp_path / f"{name}.partial" / "INCOMPLETE").read_text()
        assert note.startswith("failed: numerical blow-up at step 1")
    with pytest.raises(flocking.RunDirectoryError, match="cannot be resumed"):
        flocking.resume(tmp_path / "py")


def test_blow_up_in_a_simulation():
    sim = flocking.Simulation(blowing_up())
    with pytest.raises(flocking.NumericalError, match="numerical blow-up at step 1"):
        sim.step(10)
    assert sim.steps == 1


def test_occupied_output_directory(tmp_path):
    scenario = short(FIG11)
    flocking.run(scenario, out=tmp_path / "out")
    with pytest.raises(flocking.RunDirectoryError, match="already holds files") as error:
        flocking.run(scenario, out=tmp_path / "out")
    assert isinstance(error.value, OSError)
    assert "force=True" in str(error.value)
    flocking.run(scenario, out=tmp_path / "out", force=True)


def test_unknown_trajectory_format(tmp_path):
    with pytest.raises(ValueError, match="unknown trajectory format"):
        flocking.run(short(FIG11), out=tmp_path / "out", trajectory_format="parquet")


def test_read_run_errors(tmp_path):
    with pytest.raises(flocking.RunDirectoryError) as error:
        flocking.read_run(tmp_path / "nothing")
    assert isinstance(error.value, OSError)
    out = cli_run(short(FIG11), tmp_path / "cli")
    metrics = out / "metrics.csv"
    lines = metrics.read_text().splitlines()
    metrics.write_text("\n".join(lines[:2] + ["1.0,oops"] + lines[3:]) + "\n")
    with pytest.raises(flocking.RunDirectoryError, match=r"metrics.csv:3: ") as error:
        flocking.read_run(out)
    assert error.value.path == str(metrics)


def test_resume_without_an_interrupted_run(tmp_path):
    with pytest.raises(flocking.RunDirectoryError, match="there is no interrupted run"):
        flocking.resume(tmp_path / "nothing")
    out = cli_run(short(FIG11), tmp_path / "done")
    with pytest.raises(flocking.RunDirectoryError, match="holds a complete run"):
        flocking.resume(out)
