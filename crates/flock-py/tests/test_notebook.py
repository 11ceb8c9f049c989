"""A run in a notebook (issue 53 item 7): ``to_xarray()`` with each attribute once, the vehicle's
parameters and state, a ``long_name`` on every variable; counts as integers; the progress of a
run and of a sweep in Jupyter, kept when done; the embedded player within its byte budget."""

import html
import re
import sys
import types

import numpy as np
import pytest

import flocking
from conftest import FIG11, FIXTURES, short

UNICYCLE = FIXTURES / "unicycle_alg2_n50.ron"


@pytest.fixture(scope="module")
def unicycle_run():
    return flocking.run(short(UNICYCLE, records=5))


def test_to_xarray_names_each_attribute_once_and_every_variable(unicycle_run):
    pytest.importorskip("xarray")
    data = unicycle_run.to_xarray()
    attrs = data.attrs
    # alpha_d and alpha.d were both written: one name per parameter, whatever its separator
    spellings = {}
    for name in attrs:
        spellings.setdefault(re.sub(r"[._]", "", name), []).append(name)
    assert [names for names in spellings.values() if len(names) > 1] == []
    assert not any(name.startswith("alpha_") for name in attrs)
    assert attrs["alpha.d"] == unicycle_run.scenario.alpha["d"]
    # every variable and coordinate says what it is
    for name in list(data.data_vars) + list(data.coords):
        assert data[name].attrs.get("long_name"), name
    assert "velocity mismatch" in data["velocity_mismatch"].attrs["long_name"]


def test_to_xarray_holds_the_vehicles_parameters_and_state(unicycle_run):
    pytest.importorskip("xarray")
    data = unicycle_run.to_xarray()
    attrs = data.attrs
    assert attrs["vehicle"] == "Unicycle"
    for name in ("handle", "max_speed", "max_turn_rate", "inner_step"):
        assert attrs[f"vehicle.{name}"] == unicycle_run.scenario.value(f"vehicle.{name}"), name
    trajectory = unicycle_run.trajectory
    assert trajectory.vehicle_columns == ("heading", "speed", "turn_rate")
    for k, (name, units) in enumerate((("heading", "rad"), ("speed", "m s-1"), ("turn_rate", "rad s-1"))):
        assert data[name].dims == ("time", "agent")
        assert data[name].attrs["units"] == units
        assert np.array_equal(data[name].values, trajectory.vehicle[:, :, k])
    # a point mass has no vehicle state
    point = flocking.run(short(FIG11)).to_xarray()
    assert point.attrs["vehicle"] == "PointMass" and "heading" not in point


def test_counts_are_integers(unicycle_run):
    pandas = pytest.importorskip("pandas")
    frame = unicycle_run.to_pandas()
    assert isinstance(frame, pandas.DataFrame)
    counts = ["collisions", "components", "at_speed_limit", "at_turn_rate_limit", "at_wheel_limit"]
    for name in counts:
        assert frame[name].dtype == np.int64, (name, frame[name].dtype)
        assert unicycle_run.metrics[name].dtype == np.int64, name
    for name in ("connectivity", "velocity_mismatch", "acceleration_tracking_error"):
        assert frame[name].dtype == np.float64, name
    pytest.importorskip("xarray")
    assert unicycle_run.to_xarray()["at_speed_limit"].dtype == np.int64


class _Handle:
    """An IPython display handle that keeps every update."""

    def __init__(self, shown):
        self.shown = [shown]

    def update(self, obj):
        self.shown.append(obj)


@pytest.fixture
def jupyter(monkeypatch):
    """A stand-in IPython kernel: ``get_ipython()`` has a kernel, and ``display`` keeps what it
    shows (the handles, in order)."""
    handles = []

    class HTML:
        def __init__(self, data):
            self.data = data

    def display(obj, display_id=False):
        assert display_id is True
        handles.append(_Handle(obj))
        return handles[-1]

    shell = types.SimpleNamespace(kernel=object())
    ipython = types.ModuleType("IPython")
    ipython.get_ipython = lambda: shell
    display_module = types.ModuleType("IPython.display")
    display_module.HTML = HTML
    display_module.display = display
    ipython.display = display_module
    monkeypatch.setitem(sys.modules, "IPython", ipython)
    monkeypatch.setitem(sys.modules, "IPython.display", display_module)
    return handles


def test_a_run_in_jupyter_shows_a_bar_kept_when_done(jupyter, capfd):
    flocking.run(short(FIG11, records=40))
    assert capfd.readouterr().err == ""  # no terminal line in a notebook
    assert len(jupyter) == 1
    shown = [obj.data for obj in jupyter[0].shown]
    assert all("<progress" in text for text in shown)
    assert any("steps/s" in text and "%" in text for text in shown[1:-1]), shown
    # kept: the last update is the run's last line, full, not a cleared output
    last = shown[-1]
    assert 'value="1.000"' in last, last
    assert re.search(r"t = [0-9.]+ of [0-9.]+ s \(100 %\): [0-9]+ steps in [0-9.]+ s", html.unescape(last)), last
    # progress=False shows nothing
    flocking.run(short(FIG11), progress=False)
    assert len(jupyter) == 1


def test_a_sweep_in_jupyter_shows_a_bar_kept_when_done(jupyter, tmp_path):
    base = flocking.Scenario.load(FIG11).with_values({"duration": 0.5, "agents": 10})
    flocking.sweep(base, tmp_path / "s", axes={"algorithm.c1": [0.02, 0.04]}, seeds=1)
    assert len(jupyter) == 1
    last = html.unescape(jupyter[0].shown[-1].data)
    assert "sweep: 2/2 runs in" in last and "(100 %)" in last and 'value="1.000"' in last, last


def test_outside_jupyter_an_imported_ipython_without_kernel_is_no_notebook(monkeypatch, capfd):
    ipython = types.ModuleType("IPython")
    ipython.get_ipython = lambda: None  # IPython imported in a plain interpreter
    monkeypatch.setitem(sys.modules, "IPython", ipython)
    flocking.run(short(FIG11))
    assert capfd.readouterr().err == ""


def test_the_embedded_player_of_200_agents_and_501_frames_fits_its_budget():
    scenario = flocking.Scenario.load(FIG11).with_values({"agents": 200, "duration": 10.0, "record_every": 2})
    run = flocking.run(scenario)
    frames = len(run.trajectory.times)
    assert frames == 501
    whole = run.player_html()
    assert len(whole.encode()) > 2 * flocking._run.PLAYER_BUDGET, len(whole.encode())
    page = run.player()._repr_html_()
    player = html.unescape(re.search(r'<iframe srcdoc="([^"]*)"', page).group(1))
    assert len(player.encode()) <= flocking._run.PLAYER_BUDGET == 1_000_000
    data = re.search(r'<script id="flock-data" type="application/json">(.*?)</script>', player).group(1)
    import json

    times = json.loads(data)["t"]
    shown = len(times)
    assert 100 < shown < frames
    # evenly spaced, first and last kept
    assert times[0] == 0.0 and times[-1] == pytest.approx(run.trajectory.times[-1])
    gaps = np.diff(times)
    assert gaps.max() - gaps.min() <= 0.02 + 1e-9
    assert f"{shown} of {frames} frames, evenly spaced, to fit 1 MB" in player
    # the readout's measures are the run's metrics at the frames shown
    measures = {m["label"]: m["v"] for m in json.loads(data)["measures"]}
    assert measures["connectivity C"][-1] == pytest.approx(run.metrics["connectivity"][-1], rel=1e-3)
    print(f"player: {len(whole.encode())} bytes whole, {len(player.encode())} embedded ({shown} of {frames} frames)")
