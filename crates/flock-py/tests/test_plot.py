"""``flocking.plot`` and ``Run.plot``: the figures of ``flocking plot``, byte for byte, through the
same renderer, without the CLI."""

import shutil

import pytest

import flocking

from conftest import FIG11, cli, short


def figures(dir):
    """The files of ``dir/figures``: name → bytes."""
    return {path.name: path.read_bytes() for path in sorted((dir / "figures").iterdir())}


def test_run_plot_draws_the_clis_files_byte_for_byte(tmp_path):
    scenario = short(FIG11, records=6)
    run = flocking.run(scenario, tmp_path / "py", progress=False)
    shutil.copytree(tmp_path / "py", tmp_path / "cli")
    written = run.plot()
    assert sorted(written) == sorted(str(tmp_path / "py" / "figures" / name) for name in [
        "snapshots.svg", "snapshots.png", "metrics.svg", "metrics.png", "animation.gif", "player.html"
    ])
    cli("plot", tmp_path / "cli")
    assert figures(tmp_path / "py") == figures(tmp_path / "cli")


def test_plot_draws_the_outputs_and_times_chosen_as_the_cli(tmp_path):
    scenario = short(FIG11, records=6)
    flocking.run(scenario, tmp_path / "py", progress=False)
    shutil.copytree(tmp_path / "py", tmp_path / "cli")
    times = [0.0, float(scenario.duration)]
    written = flocking.plot(tmp_path / "py", outputs=["snapshots", "gif"], times=times, stress_edges=True)
    assert sorted(p.rsplit("/", 1)[1] for p in written) == ["animation.gif", "snapshots.png", "snapshots.svg"]
    cli("plot", tmp_path / "cli", "--outputs", "snapshots,gif", "--times", "0," + repr(times[1]), "--stress-edges")
    assert figures(tmp_path / "py") == figures(tmp_path / "cli")


def test_what_cannot_be_plotted_says_why(tmp_path):
    scenario = short(FIG11, records=4)
    in_memory = flocking.run(scenario, progress=False)
    with pytest.raises(ValueError, match="no directory to draw from: run it with flocking.run"):
        in_memory.plot()
    run = flocking.run(scenario, tmp_path / "o", progress=False)
    with pytest.raises(ValueError, match=r"snapshot time 99 s is outside the run, which spans 0 s to"):
        run.plot(times=[0, 99])
    assert not (tmp_path / "o" / "figures").exists()
    with pytest.raises(ValueError, match='"movie" is not a figure'):
        run.plot(outputs=["movie"])
    with pytest.raises(flocking.RunDirectoryError, match="not a directory"):
        flocking.plot(tmp_path / "nowhere")
