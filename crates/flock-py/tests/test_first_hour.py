"""What a newcomer meets in the first hour (issue 28): ``flocking.__version__``, a progress line
that only a terminal gets (or whoever asks), a sweep of a grid defined in Python, and messages
without Rust's names."""

import re
import sys

import pytest

import flocking
from conftest import FIG11, ROOT, short


class _Terminal:
    """A stand-in ``sys.stderr`` that says it is a terminal and keeps what is written."""

    def __init__(self):
        self.text = ""

    def isatty(self):
        return True

    def write(self, text):
        self.text += text
        return len(text)

    def flush(self):
        pass


def test_the_version_is_the_workspace_version():
    cargo = (ROOT / "Cargo.toml").read_text()
    version = re.search(r'^version = "([^"]+)"', cargo, re.MULTILINE).group(1)
    assert flocking.__version__ == version


def test_a_run_shows_progress_only_on_a_terminal_or_when_asked(capfd, monkeypatch):
    scenario = short(FIG11, records=40)
    # pytest's captured stderr is no terminal: nothing, by default
    flocking.run(scenario)
    assert capfd.readouterr().err == ""
    flocking.run(scenario, progress=False)
    assert capfd.readouterr().err == ""
    # asked for, the line is drawn on sys.stderr and cleared at the end
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    flocking.run(scenario)
    assert "%" in terminal.text and "steps/s" in terminal.text, terminal.text
    assert terminal.text.endswith("\r")
    terminal.text = ""
    flocking.run(scenario, progress=False)
    assert terminal.text == ""


def _grid_sweep(tmp_path, name, progress=None):
    base = flocking.Scenario.load(FIG11).with_values({"duration": 1.0, "agents": 10})
    return flocking.sweep(
        base,
        tmp_path / name,
        axes={"algorithm.c1": [0.02, 0.04], "initial.positions.std": [5.0, 10.0]},
        seeds=2,
        progress=progress,
    )


def test_a_sweep_of_a_grid_defined_in_python_is_the_sweep_file_it_stands_for(tmp_path, monkeypatch):
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    result = _grid_sweep(tmp_path, "grid")
    assert "sweep: 8/8 runs" in terminal.text, terminal.text
    columns = result.columns
    assert len(columns["run"]) == 2 * 2 * 2
    assert sorted(set(columns["algorithm.c1"].tolist())) == [0.02, 0.04]
    assert sorted(set(columns["seed"].tolist())) == [0, 1]
    assert all(e == "" for e in columns["error"])
    # the same grid as a sweep file: the same runs.csv, byte for byte
    base = tmp_path / "base.ron"
    base.write_text(flocking.Scenario.load(FIG11).with_values({"duration": 1.0, "agents": 10}).to_ron())
    spec = tmp_path / "grid.ron"
    spec.write_text(
        f"""Sweep(name: "x", base: Path("{base}"),
        axes: [(path: "algorithm.c1", values: List([0.02, 0.04])),
               (path: "initial.positions.std", values: List([5.0, 10.0]))],
        seeds: 2)"""
    )
    monkeypatch.setattr(sys, "stderr", _Terminal())
    again = flocking.sweep(spec, tmp_path / "file", progress=False)
    assert (tmp_path / "grid" / "runs.csv").read_bytes() == (tmp_path / "file" / "runs.csv").read_bytes()
    assert again.columns["id"].tolist() == columns["id"].tolist()
    with pytest.raises(TypeError, match="axes="):
        flocking.sweep(flocking.Scenario.load(FIG11), tmp_path / "none")
    with pytest.raises(ValueError, match="seeds"):
        flocking.sweep(flocking.Scenario.load(FIG11), tmp_path / "none", axes={"agents": [5]}, seeds=0)


def test_a_sweep_shows_no_progress_in_a_pipe(tmp_path, capfd):
    _grid_sweep(tmp_path, "quiet")
    assert "sweep:" not in capfd.readouterr().err


def test_messages_name_no_rust_types():
    scenario = flocking.Scenario.load(FIG11)
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_values({"agents": 10.5})
    assert "whole number" in str(error.value) and "usize" not in str(error.value)
    with pytest.raises(flocking.ScenarioError) as error:
        scenario.with_values({"agent": 10})
    assert str(error.value).startswith("`agent`: no such parameter"), str(error.value)
    assert "no value read" not in str(error.value)


def test_every_enum_is_set_as_ron_text_from_python():
    """Issue 53: `{"vehicle": "Unicycle(())"}` failed while the conditions' enums worked."""
    base = flocking.Scenario.load(FIG11)
    robots = base.with_values({"vehicle": "Unicycle((max_speed: 0.3))", "algorithm.c1": 0.05})
    assert robots.value("vehicle.max_speed") == 0.3
    assert "Unicycle" in robots.to_ron()
    vicsek = base.with_values({"algorithm": "Vicsek(eta: 0.3)"})
    assert vicsek.value("algorithm.eta") == 0.3
    with pytest.raises(flocking.ScenarioError) as refused:
        base.with_values({"vehicle": "Bicycle(())"})
    assert refused.value.field == "vehicle"


def test_read_run_of_a_directory_that_is_not_a_run_says_so(tmp_path):
    with pytest.raises(flocking.RunDirectoryError, match="not a run directory"):
        flocking.read_run(tmp_path)


def test_a_warning_says_warning_once(recwarn):
    robots = flocking.Scenario.load(FIG11).with_values({"vehicle": "Unicycle(())", "duration": 0.05})
    flocking.run(robots)
    messages = [str(w.message) for w in recwarn.list if w.category is UserWarning]
    assert messages and all(not m.startswith("warning:") for m in messages), messages
    assert any(m.startswith("`algorithm.gamma.velocity`") for m in messages), messages
