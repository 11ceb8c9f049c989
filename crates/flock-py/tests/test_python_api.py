"""The Python side of the API: short reprs, the package's namespace, the optional extras (pandas,
xarray) and the messages when they are missing, Run.to_xarray, the Jupyter HTML of a run and the
dtypes of a sweep's columns."""

import html
import re
import sys
from pathlib import Path

import numpy as np
import pytest

import flocking
from conftest import FIG11, FIXTURES, short


@pytest.fixture(scope="module")
def fig11_run():
    return flocking.run(short(FIG11))


def test_reprs_are_one_short_line(fig11_run, tmp_path):
    scenario = fig11_run.scenario
    sim = flocking.Simulation(scenario)
    reprs = {
        "run": repr(fig11_run),
        "final": repr(fig11_run.final),
        "trajectory": repr(fig11_run.trajectory),
        "scenario": repr(scenario),
        "simulation": repr(sim),
    }
    for name, text in reprs.items():
        assert "\n" not in text and len(text) < 160 and "array" not in text, (name, text)
    assert reprs["run"] == (
        "Run(name='tac2006_fig11_alg2_n100', dim=2, n=100, duration=0.9, records=6, "
        f"C={fig11_run.metrics['connectivity'][-1]:.4g})"
    )
    assert reprs["final"] == "State(t=0.9, n=100, dim=2)"
    assert reprs["trajectory"] == "Trajectory(frames=6, n=100, dim=2, t=0.0..0.9)"
    assert reprs["scenario"] == (
        'Scenario(name="tac2006_fig11_alg2_n100", dim=2, agents=100, duration=0.9, step=0.01, steps=90)'
    )
    result = flocking.SweepResult("out/s", {"run": np.arange(3), "error": np.array(["", "x", ""])})
    assert repr(result) == "SweepResult(path='out/s', runs=3, columns=2, errors=1)"


def test_the_namespace_is_the_public_api():
    names = {name for name in dir(flocking) if not (name.startswith("__") and name.endswith("__"))}
    # flocking.env (it needs gymnasium) is in the namespace once imported, never before
    private = names - set(flocking.__all__) - {"env"}
    assert private == {"_bench", "_errors", "_flocking", "_render", "_run", "_sweep"}
    assert all(name.startswith("_") for name in private)
    assert set(flocking.__all__) <= names


@pytest.mark.parametrize(
    "call, module, extra",
    [
        (lambda run: run.to_pandas(), "pandas", "pandas"),
        (lambda run: run.to_xarray(), "xarray", "xarray"),
        (lambda run: flocking.SweepResult("x", {}).to_pandas(), "pandas", "pandas"),
    ],
)
def test_a_missing_extra_names_the_fix(fig11_run, monkeypatch, call, module, extra):
    monkeypatch.setitem(sys.modules, module, None)  # import fails as if not installed
    with pytest.raises(ImportError, match=re.escape(f"pip install 'flocking[{extra}]'")):
        call(fig11_run)


def test_to_xarray(fig11_run):
    xarray = pytest.importorskip("xarray")
    run = fig11_run
    data = run.to_xarray()
    assert isinstance(data, xarray.Dataset)
    assert dict(data.sizes) == {"time": 6, "agent": 100, "axis": 2}
    assert list(data["axis"].values) == ["x", "y"]
    assert np.array_equal(data["time"], run.metrics["t"])
    assert data["q"].dims == ("time", "agent", "axis")
    assert np.array_equal(data["q"], run.trajectory.positions)
    assert np.array_equal(data["p"], run.trajectory.velocities)
    for name, column in run.metrics.items():
        if name != "t":
            assert data[name].dims == ("time",) and np.array_equal(data[name], column), name
    assert data["collisions"].dtype == np.int64
    attrs = data.attrs
    assert (attrs["name"], attrs["dim"], attrs["agents"], attrs["seed"]) == ("tac2006_fig11_alg2_n100", 2, 100, 11)
    assert (attrs["step"], attrs["duration"], attrs["algorithm"]) == (0.01, 0.9, "Algorithm2")
    assert (attrs["alpha.d"], attrs["alpha.epsilon"], attrs["alpha.h"]) == (7.0, 0.1, 0.2)
    assert attrs["alpha.r"] == pytest.approx(8.4)  # resolved: 1.2 d
    assert flocking.Scenario.from_ron(attrs["scenario"]).to_ron() == run.scenario.to_ron() == attrs["scenario"]
    for value in attrs.values():
        assert isinstance(value, (str, int, float)) or all(isinstance(x, (int, float)) for x in value), value
    # units on time, the state and every metric; the gains and the rest of the scenario
    assert data["time"].attrs["units"] == "s"
    assert (data["q"].attrs["units"], data["p"].attrs["units"]) == ("m", "m s-1")
    for name in run.metrics:
        if name != "t":
            assert data[name].attrs["units"] == flocking._run.UNITS[name], name
    assert data["cohesion_radius"].attrs["units"] == "m"
    for path in ("algorithm.c1", "algorithm.c2", "initial.positions.std"):
        assert attrs[path] == run.scenario.value(path), path
    # the 3D axis and a run without trajectory
    kept = flocking.run(short(FIXTURES / "tac2006_fig13_alg2_3d_n50.ron"), trajectory=False).to_xarray()
    assert "q" not in kept and list(kept["axis"].values) == ["x", "y", "z"]
    assert kept["connectivity"].dims == ("time",)


def test_to_xarray_of_a_run_directory(tmp_path):
    pytest.importorskip("xarray")
    run = flocking.run(short(FIG11), tmp_path / "out")
    data = flocking.read_run(tmp_path / "out").to_xarray()
    assert data.attrs["verdict"] == run.verdict and data.attrs["path"] == str(tmp_path / "out")
    assert np.array_equal(data["q"], run.trajectory.positions)


def test_the_html_of_a_run_is_a_summary_and_a_snapshot_and_the_player_on_request(fig11_run, tmp_path):
    page = fig11_run._repr_html_()
    for label in ("name", "dim", "n", "duration", "final C", "final C*", "final Ẽ", "final K̃", "least distance"):
        assert f">{html.escape(label)}</th>" in page, label
    least = f"{fig11_run.metrics['min_distance'].min():.4g}"
    assert f"<td style='text-align:left'>{least}</td>" in page
    # a snapshot of the final state, one dot per agent, and no player
    assert page.count("<circle ") == 100 and "<svg" in page
    assert "<iframe" not in page and "run.player()" in page
    frame = re.search(r'<iframe srcdoc="([^"]*)"', fig11_run.player()._repr_html_())
    assert frame is not None  # the player, escaped into one attribute
    player = html.unescape(frame.group(1))
    assert player.startswith("<!DOCTYPE html>") and 'id="play"' in player and "flock-data" in player
    assert player == fig11_run.player_html()
    # a finished run directory's verdict is shown; a run without trajectory has no player
    run = flocking.run(short(FIG11), tmp_path / "out", trajectory=False)
    page = run._repr_html_()
    assert "verdict" in page and "α-flocking" in page and "<iframe" not in page and "run.player()" not in page
    assert run.verdict is not None and run.verdict == (tmp_path / "out" / "flocking.txt").read_text().splitlines()[0]


def test_the_html_of_a_thousand_agents_stays_under_100_kb():
    # issue 28: the whole player was embedded, 11.2 MB at n = 1,000
    scenario = short(FIG11, records=20).with_values({"agents": 1000})
    run = flocking.run(scenario)
    page = run._repr_html_()
    assert page.count("<circle ") == 1000
    assert len(page.encode()) < 100_000, len(page.encode())


def test_sweep_columns_have_natural_dtypes(tmp_path):
    spec = tmp_path / "sweep.ron"
    spec.write_text(
        f"""Sweep(name: "dtypes", base: Path("{FIG11}"),
        set: {{"duration": 2.0, "initial.positions.std": 10.0}},
        axes: [(path: "algorithm.c1", values: List([0.02, 1e8])), (path: "agents", values: List([8, 12]))],
        seeds: 1)"""
    )
    result = flocking.sweep(spec, tmp_path / "out")
    columns = result.columns
    assert columns["run"].dtype == np.int64 and columns["seed"].dtype == np.int64
    assert columns["agents"].dtype == np.int64 and columns["algorithm.c1"].dtype == np.float64
    assert columns["id"].dtype.kind == "U" and columns["error"].dtype.kind == "U"
    failed = columns["algorithm.c1"] == 1e8  # blows up: an error row
    assert all(e != "" for e in columns["error"][failed]) and all(e == "" for e in columns["error"][~failed])
    # the failed runs leave int and bool fields empty: masked there
    for name, dtype in (("collisions", np.int64), ("alpha_flock", np.bool_), ("strict_alpha_flock", np.bool_)):
        column = columns[name]
        assert column.dtype == dtype and np.ma.isMaskedArray(column), name
        assert np.array_equal(np.ma.getmaskarray(column), failed), name
    assert np.all(np.isnan(columns["connectivity"][failed]))
    assert np.all(np.isnan(columns["obstacle_clearance"]))  # no obstacles: an empty float column
    pandas = pytest.importorskip("pandas")
    frame = result.to_pandas()
    assert list(frame.columns) == list(columns)
    assert str(frame["run"].dtype) == "int64" and str(frame["collisions"].dtype) == "Int64"
    assert str(frame["alpha_flock"].dtype) == "boolean" and frame["alpha_flock"].isna().tolist() == failed.tolist()
    assert frame["connectivity"].dtype == np.float64
    assert frame["id"].tolist() == columns["id"].tolist()
