"""SweepResult.plot draws what ``flocking sweep plot`` draws, byte for byte, through the same
renderer (lines, heatmaps, categories, the overlay, the CSV of the numbers); its refusals are
ValueErrors naming the nearest metric. SweepResult.to_xarray gives the sweep on its grid: the
axes and the seed as dimensions, the metrics as variables with long names and units."""

from pathlib import Path

import numpy as np
import pytest

import flocking

from conftest import FIG11, cli

# loss models as categories (issue 53), a delay as numbers
SWEEP = """Sweep(
    name: "py_plot",
    description: "loss models against delay",
    base: Path("{base}"),
    set: {{"duration": 2.0, "initial.positions.std": 10.0, "agents": 8}},
    axes: [
        (path: "conditions.communication.loss", values: List(["None", "Bernoulli(p: 0.3)", "GilbertElliott(p_fail: 0.1, p_recover: 0.9)"])),
        (path: "conditions.communication.delay", values: List([0.0, 0.05])),
    ],
    seeds: 2,
)
"""

LOSS = "conditions.communication.loss"
DELAY = "conditions.communication.delay"


@pytest.fixture(scope="module")
def swept(tmp_path_factory) -> flocking.SweepResult:
    tmp = tmp_path_factory.mktemp("sweep_plot")
    spec = tmp / "sweep.ron"
    spec.write_text(SWEEP.format(base=FIG11))
    return flocking.sweep(spec, tmp / "out")


# each: the CLI's arguments after DIR, and SweepResult.plot's
CASES = [
    (["--x", LOSS, "--metric", "cohesion_radius", "--where", f"{DELAY}=0.05"],
     dict(metric="cohesion_radius", x=LOSS, where={DELAY: 0.05})),
    (["--x", DELAY, "--y", LOSS, "--metric", "velocity_mismatch", "--log-colour"],
     dict(metric="velocity_mismatch", x=DELAY, y=LOSS, log_colour=True)),
    (["--x", DELAY, "--overlay", LOSS, "--metric", "min_distance", "--band", "quantiles"],
     dict(metric="min_distance", x=DELAY, series=LOSS, band="quantiles")),
    (["--x", DELAY, "--facet", LOSS, "--metric", "alpha_flock", "--bound", "0.02"],
     dict(metric="alpha_flock", x=DELAY, facet=LOSS, bound=0.02)),
    (["--x", DELAY, "--y", LOSS, "--metric", "alpha_flock", "--even-cells", "--bound", "0.03"],
     dict(metric="alpha_flock", x=DELAY, y=LOSS, even_cells=True, bound=0.03)),
]


@pytest.mark.parametrize("case", range(len(CASES)))
@pytest.mark.parametrize("ext", ["svg", "png", "csv"])
def test_plot_draws_the_cli_figure_byte_for_byte(swept, tmp_path: Path, case: int, ext: str) -> None:
    args, kwargs = CASES[case]
    cli("sweep", "plot", swept.path, *args, "--out", tmp_path / f"cli.{ext}")
    written = swept.plot(**kwargs, out=tmp_path / f"py.{ext}")
    assert written == str(tmp_path / f"py.{ext}")
    assert (tmp_path / f"py.{ext}").read_bytes() == (tmp_path / f"cli.{ext}").read_bytes()


def test_categories_are_named_in_the_sweep_order(swept, tmp_path: Path) -> None:
    with pytest.warns(UserWarning, match="pools 4 runs over conditions.communication.delay"):
        swept.plot("cohesion_radius", LOSS, out=tmp_path / "loss.csv")
    rows = (tmp_path / "loss.csv").read_text().splitlines()
    assert [row.split(",")[1] for row in rows[1:3]] == ["None", "Bernoulli(p: 0.3)"]
    assert rows[3].startswith(',"GilbertElliott(p_fail: 0.1, p_recover: 0.9)",,4,')


def test_a_mistyped_metric_names_the_nearest(swept, tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"did you mean cohesion_radius\?"):
        swept.plot("cohesion_radiu", DELAY, out=tmp_path / "never.svg")
    assert not (tmp_path / "never.svg").exists()
    with pytest.raises(ValueError, match="band"):
        swept.plot("cohesion_radius", DELAY, band="iqr", out=tmp_path / "never.svg")


def test_to_xarray_lays_the_runs_on_the_sweep_grid(swept) -> None:
    ds = swept.to_xarray()
    assert ds["cohesion_radius"].dims == (LOSS, DELAY, "seed")
    assert ds.sizes == {LOSS: 3, DELAY: 2, "seed": 2}
    # as runs.csv writes them (here as the sweep file gives them), in the sweep's order
    assert list(ds[LOSS].values) == [
        "None",
        "Bernoulli(p: 0.3)",
        "GilbertElliott(p_fail: 0.1, p_recover: 0.9)",
    ]
    assert list(ds[DELAY].values) == [0.0, 0.05]
    assert ds[DELAY].attrs == {"long_name": "communication delay τ", "units": "s"}
    assert ds["cohesion_radius"].attrs == {"long_name": "cohesion radius R", "units": "m"}
    assert ds["alpha_flock"].attrs["units"] == "1"
    assert ds["connected_from"].attrs["units"] == "s"
    # every run in its place: run k is (loss, delay, seed) in the sweep's order
    runs = swept.columns["run"]
    radius = swept.columns["cohesion_radius"]
    for k in range(len(runs)):
        loss, rest = divmod(int(runs[k]), 4)
        delay, seed = divmod(rest, 2)
        np.testing.assert_equal(ds["cohesion_radius"].values[loss, delay, seed], radius[k])
        assert ds["id"].values[loss, delay, seed] == swept.columns["id"][k]
    assert ds.attrs == {"name": "py_plot", "description": "loss models against delay", "seeds": 2, "path": swept.path}
    for name, variable in ds.data_vars.items():
        assert "long_name" in variable.attrs, name


def test_read_sweep_reads_a_finished_directory(swept, tmp_path: Path) -> None:
    again = flocking.read_sweep(swept.path)
    assert list(again.columns) == list(swept.columns)
    np.testing.assert_array_equal(again.columns["cohesion_radius"], swept.columns["cohesion_radius"])
    (tmp_path / "empty").mkdir()
    with pytest.raises(flocking.RunDirectoryError):
        flocking.read_sweep(tmp_path / "empty")
