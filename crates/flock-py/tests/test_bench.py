"""``flocking.bench``: the engine of ``flocking bench`` with the same report (issue 31). Timings
differ between two runs; what the engine computes does not: the same configuration gives the
CLI's header, conditions, neighbours and final metrics line for line."""

import pytest

import flocking
from conftest import cli

# the report lines that do not depend on the clock or the process
DETERMINISTIC = ("flocking bench:", "  conditions", "  vehicle", "  agents numbered", "  mean neighbours", "  final C")


def stable_lines(report: str) -> list:
    return [line for line in report.splitlines() if line.startswith(DETERMINISTIC)]


@pytest.mark.parametrize(
    "keywords, flags",
    [
        (dict(n=400, steps=10, threads=1), ["--n", "400", "--steps", "10", "--threads", "1"]),
        (
            dict(n=300, dim=3, steps=3, algorithm=1, shuffled=True, threads=2),
            ["--n", "300", "--dim", "3", "--steps", "3", "--algorithm", "1", "--shuffled", "--threads", "2"],
        ),
        (
            dict(n=300, steps=4, delay=0.05, loss=0.1, sensing_noise=(0.1, 0.05), threads=1),
            ["--n", "300", "--steps", "4", "--delay", "0.05", "--loss", "0.1", "--sensing-noise", "0.1,0.05", "--threads", "1"],
        ),
        (dict(n=200, steps=2, vehicle="unicycle"), ["--n", "200", "--steps", "2", "--vehicle", "unicycle"]),
    ],
)
def test_the_report_is_the_clis(keywords, flags):
    report = flocking.bench(**keywords)
    printed = cli("bench", *flags).stdout
    assert stable_lines(str(report)) == stable_lines(printed)
    assert len(stable_lines(printed)) >= 3


def test_the_figures_are_attributes():
    report = flocking.bench(n=500, steps=10, threads=1)
    assert isinstance(report, flocking.BenchReport)
    assert (report.n, report.dim, report.steps, report.threads) == (500, 2, 10, 1)
    assert report.agent_steps_per_second == pytest.approx(500 * 10 / report.elapsed_seconds)
    assert report.ns_per_agent_step == pytest.approx(1e9 / report.agent_steps_per_second)
    assert report.ms_per_step == pytest.approx(report.elapsed_seconds * 1e3 / 10)
    assert report.ms_per_recorded_step is not None
    assert report.conditions_bytes_per_agent == 0
    # an α-lattice's interior agent has 6 neighbours in 2D; the rim fewer
    assert 4.0 < report.mean_neighbours < 6.0
    assert report.connectivity == 1.0
    # the printed figure (Rust's `{:.4e}`, e.g. 8.1951e6) is the attribute's to 4 decimals
    printed = next(line for line in str(report).splitlines() if "agent-steps/s" in line)
    assert float(printed.split()[-1]) == pytest.approx(report.agent_steps_per_second, rel=1e-4)
    assert repr(report).startswith("<BenchReport Algorithm 2, 2D, n = 500")


def test_one_sensing_noise_gives_both_deviations():
    one = str(flocking.bench(n=100, steps=1, sensing_noise=0.2))
    assert "sensing noise 0.2 m, 0.2 m/s (white)" in one


def test_a_workload_reports_its_seeds():
    report = flocking.bench(workload="boids-small", seeds=3, threads=1)
    assert isinstance(report, flocking.WorkloadReport)
    assert report.n == 200 and len(report.times) == 3 and report.threads == 1
    assert sorted(report.times)[1] == pytest.approx(report.median_seconds)
    # building each seed's model, timed apart, and the frameworks' timing of both
    assert len(report.build_times) == 3 and all(b > 0 for b in report.build_times)
    both = sorted(t + b for t, b in zip(report.times, report.build_times))
    assert report.median_seconds_with_building == pytest.approx(both[1])
    assert report.median_seconds_with_building > report.median_seconds
    assert str(report).startswith("boids_small_n200: 200 birds, box [100.0, 100.0], 100 steps, 3 seed(s)")


def test_the_vicsek_workload_scales_at_the_papers_density():
    report = flocking.bench(workload="vicsek", seeds=1, scale_to=2500, threads=1)
    assert report.n == 2500 and len(report.times) == 1
    # ρ = 4: a box of side √(2500 / 4) = 25
    assert str(report).startswith("vicsek1995_fig2a_n400: 2500 agents, box [25.0, 25.0], 100 steps")


@pytest.mark.parametrize(
    "keywords, named",
    [
        (dict(algorithm=4), "algorithm='4'"),
        (dict(vehicle="boat"), "vehicle='boat'"),
        (dict(delayed="some"), "delayed='some'"),
        (dict(workload="boids"), "workload='boids'"),
        (dict(threads=0), "threads=0"),
        (dict(sensing_noise=(1, 2, 3)), "sensing_noise=(1, 2, 3)"),
        (dict(n=1), "n=1: a benchmark needs at least 2 agents"),
        (dict(delay=0.015), "delay"),
    ],
)
def test_bad_values_name_the_keyword(keywords, named):
    with pytest.raises(ValueError, match=named.replace("(", r"\(").replace(")", r"\)")):
        flocking.bench(**{"n": 100, "steps": 1, **keywords})
