"""``flocking._render``: a state drawn as the snapshots draw it, an RGB image in memory (the
``render_mode="rgb_array"`` of the environments, issue 52)."""

import numpy as np
import pytest

import flocking

from conftest import FIG11, FIXTURES

FIG13_3D = FIXTURES / "tac2006_fig13_alg2_3d_n50.ron"
WHITE = np.array([255, 255, 255], dtype=np.uint8)


def state(path):
    """The scenario at ``path`` and its state after a few steps (the agents moving)."""
    scenario = flocking.Scenario.load(path)
    sim = flocking.Simulation(scenario)
    sim.step(5)
    return scenario, sim.q, sim.p, sim.t


@pytest.mark.parametrize("path", [FIG11, FIG13_3D], ids=["2d", "3d"])
def test_an_image_of_the_requested_size_that_moves_with_the_state(path):
    scenario, q, p, t = state(path)
    image = flocking._render(scenario, q, p, t)
    assert image.shape == (480, 640, 3) and image.dtype == np.uint8
    drawn = np.any(image != WHITE, axis=2)
    # the axes, labels, agents and edges: some of the image, far from all of it
    assert 0.01 < drawn.mean() < 0.5
    # the same state gives the same bits; a shifted one another image
    assert np.array_equal(flocking._render(scenario, q, p, t), image)
    shifted = flocking._render(scenario, q + 3.0, p, t)
    assert shifted.shape == image.shape and not np.array_equal(shifted, image)
    turned = flocking._render(scenario, q, -p, t)
    assert not np.array_equal(turned, image)
    small = flocking._render(scenario, q, p, t, width=320, height=200)
    assert small.shape == (200, 320, 3)


def test_a_state_of_another_shape_is_refused_naming_the_array_and_both_shapes():
    # the checks of Simulation's positions and velocities: ScenarioError, a ValueError
    scenario, q, p, t = state(FIG11)
    with pytest.raises(flocking.ScenarioError, match=r"\(100, 3\).*\(100, 2\)") as refused:
        flocking._render(scenario, np.zeros((100, 3)), p, t)
    assert refused.value.field == "positions"
    with pytest.raises(flocking.ScenarioError, match=r"\(2, 100\).*\(100, 2\).*transpose") as refused:
        flocking._render(scenario, q, p.T, t)
    assert refused.value.field == "velocities"
    with pytest.raises(flocking.ScenarioError, match="complex"):
        flocking._render(scenario, q + 0j, p, t)
    bad = q.copy()
    bad[7, 1] = np.nan
    with pytest.raises(ValueError, match=r"positions\[7, 1\] is NaN"):
        flocking._render(scenario, bad, p, t)
    with pytest.raises(ValueError, match="8 × 480 pixels"):
        flocking._render(scenario, q, p, t, width=8)
