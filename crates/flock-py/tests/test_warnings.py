"""The warnings before a run (issue 53) from Python: ``Scenario.warnings()`` returns the messages
``flocking validate`` prints, each naming the field and the fix, and none for a scenario that
needs none."""

import flocking
from conftest import FIG11


def fig11(old, new):
    """TAC 2006 Fig. 11 with ``old`` replaced by ``new`` in its RON text."""
    text = FIG11.read_text()
    assert old in text
    return flocking.Scenario.from_ron(text.replace(old, new, 1))


def test_the_fixture_warns_of_nothing():
    assert flocking.Scenario.load(FIG11).warnings() == []


def test_fig11_on_unicycles_warns_of_the_gamma_agent_and_the_initial_speeds():
    # its γ-agent at 1.12 m/s and starting speeds up to 2.8 m/s, robots of 0.22 m/s
    warnings = fig11("    initial: (", "    vehicle: Unicycle(()),\n    initial: (").warnings()
    gamma = [w for w in warnings if w.startswith("warning: `algorithm.gamma.velocity`")]
    start = [w for w in warnings if w.startswith("warning: `initial.velocities`")]
    assert len(gamma) == 1 and len(start) == 1, warnings
    assert "vehicle.max_speed = 0.22" in gamma[0] and "Fix: " in gamma[0]
    assert "Headings(speed: 0.22)" in start[0]


def test_vicsek_at_the_olfati_saber_step_warns_of_the_step():
    text = FIG11.read_text()
    start = text.index("    algorithm: Algorithm2(")
    end = text.index("    initial: (")
    swapped = text[:start] + "    algorithm: Vicsek(eta: 2.0),\n" + text[end:]
    swapped = swapped.replace("velocities: Box(min: [-2.0, -2.0], max: [2.0, 2.0])", "velocities: Headings(speed: 0.03)")
    warnings = flocking.Scenario.from_ron(swapped).warnings()
    assert [w for w in warnings if w.startswith("warning: `step` = 0.01")], warnings
    assert "set `step: 1.0`" in warnings[0]
    at_paper = flocking.Scenario.from_ron(swapped.replace("step: 0.01", "step: 1.0"))
    assert at_paper.warnings() == []
