"""controls=: the inputs u_i computed in Python on the proximity net — TAC 2006 Algorithm 2 in
numpy has the bits of the built-in one; bad results are ControlsErrors naming the shapes; an
exception of the function stops a run cleanly (records kept, resumable) and is raised again;
sweeps pickle the function to their workers."""

import sys
import traceback
from pathlib import Path

import numpy as np
import pytest

import flocking
from conftest import FIG11, FIXTURES, ROOT, assert_runs_equal, short

sys.path.insert(0, str(ROOT / "examples" / "python"))
from algorithm2_numpy import Algorithm2  # noqa: E402


def zero_inputs(t, q, p, neighbours):
    """No input at all (module level: picklable for a sweep's worker processes)."""
    return np.zeros_like(q)


def test_numpy_algorithm2_has_the_bits_of_the_builtin():
    scenario = flocking.Scenario.load(FIG11).with_values({"duration": 10.0})
    builtin = flocking.run(scenario)
    numpy_run = flocking.run(scenario, controls=Algorithm2(scenario))
    assert_runs_equal(builtin, numpy_run)  # every record: metrics, energy, trajectory, bit for bit


def test_bump_is_rho_h_with_a_bad_h_refused():
    rho = flocking.bump(np.array([[-0.1, 0.0, 0.1], [0.6, 1.0, 1.5]]), 0.2)
    assert rho.shape == (2, 3) and rho.dtype == np.float64
    assert rho[0].tolist() == [0.0, 1.0, 1.0] and rho[1, 2] == 0.0
    assert abs(rho[1, 0] - 0.5) < 1e-15 and abs(rho[1, 1]) < 1e-15
    # an element's value does not depend on its neighbours in the array (lanes of four)
    x = np.linspace(0.0, 1.0, 4001)
    alone = np.array([flocking.bump(np.array([v]), 0.2)[0] for v in x[:41]])
    assert np.array_equal(flocking.bump(x, 0.2)[:41], alone)
    assert np.array_equal(flocking.bump(x[1:42], 0.2), flocking.bump(x, 0.2)[1:42])
    for h in (0.0, 1.0, float("nan")):
        with pytest.raises(ValueError, match="h = "):
            flocking.bump(x, h)


def test_the_example_reports_bit_identity(capsys):
    import algorithm2_numpy

    algorithm2_numpy.main(2.0)
    out = capsys.readouterr().out
    assert out.count("max |q_numpy − q_rust| = 0, bit-identical: True") == 1


def test_the_function_sees_the_state_in_original_order_and_the_net():
    scenario = short(FIG11)
    sim = flocking.Simulation(scenario)
    seen = []

    def inspect(t, q, p, neighbours):
        seen.append((t, q.copy(), p.copy(), neighbours))
        return np.zeros_like(q)

    controlled = flocking.Simulation(scenario, controls=inspect)
    controlled.step(1)
    t, q, p, net = seen[0]
    assert t == 0.0 and np.array_equal(q, sim.q) and np.array_equal(p, sim.p)
    assert q.shape == (100, 2) and q.dtype == np.float64
    assert len(net) == 100 and net.indptr.shape == (101,) and net.indptr[0] == 0
    assert net.indptr.dtype == net.indices.dtype == np.int64
    r = scenario.alpha["r"]
    pairs = net.pairs()
    assert pairs.shape == (net.indptr[-1], 2)
    distances = np.linalg.norm(q[pairs[:, 1]] - q[pairs[:, 0]], axis=1)
    assert np.allclose(distances, net.distances, rtol=1e-15) and np.all(net.distances < r)
    # the net is N_i = {j ≠ i : ‖q_j − q_i‖ < r}, ascending j, both directions
    every = np.linalg.norm(q[:, None] - q[None], axis=2)
    expected = {(i, j) for i in range(100) for j in range(100) if i != j and every[i, j] < r}
    assert set(map(tuple, pairs.tolist())) == expected
    for i in range(100):
        row = net.indices[net.indptr[i] : net.indptr[i + 1]]
        assert np.all(np.diff(row) > 0)
    # energy and metrics still come from the scenario's protocol
    assert controlled.energy() != 0.0 and "controls=python" in repr(controlled)


def test_a_result_of_the_wrong_shape_names_both_shapes():
    sim = flocking.Simulation(short(FIG11), controls=lambda t, q, p, nb: np.zeros((99, 2)))
    with pytest.raises(flocking.ControlsError) as raised:
        sim.step(5)
    error = raised.value
    assert isinstance(error, ValueError) and isinstance(error, flocking.FlockError)
    assert (error.expected, error.given) == ((100, 2), (99, 2))
    assert "(99, 2)" in str(error) and "(100, 2)" in str(error)
    assert sim.steps == 0  # stopped before the step


def test_a_result_that_is_not_finite_or_not_an_array_is_refused():
    def nan_at_7(t, q, p, nb):
        u = np.zeros_like(q)
        u[7, 1] = np.nan
        return u

    with pytest.raises(flocking.ControlsError, match=r"u\[7\]") as raised:
        flocking.run(short(FIG11), controls=nan_at_7)
    assert raised.value.given == (100, 2)
    with pytest.raises(flocking.ControlsError, match="returned a NoneType") as raised:
        flocking.Simulation(short(FIG11), controls=lambda t, q, p, nb: None).step()
    assert raised.value.given is None
    # lists and integer arrays of the right shape are inputs
    sim = flocking.Simulation(short(FIG11), controls=lambda t, q, p, nb: np.zeros(q.shape, int).tolist())
    sim.step(2)
    assert sim.steps == 2


class Boom(Exception):
    pass


def failing_after(steps, h, controls):
    """``controls`` until t reaches ``steps`` steps of h, then Boom."""

    def f(t, q, p, nb):
        if t >= steps * h - h / 2:
            raise Boom(f"at t = {t}")
        return controls(t, q, p, nb)

    return f


def test_an_exception_stops_a_simulation_before_its_step():
    scenario = short(FIG11)
    reference = flocking.Simulation(scenario)
    reference.step(7)
    sim = flocking.Simulation(scenario, controls=failing_after(7, scenario.step, Algorithm2(scenario)))
    with pytest.raises(Boom) as raised:
        sim.step(20)
    assert sim.steps == 7
    assert np.array_equal(sim.q, reference.q) and np.array_equal(sim.p, reference.p)
    frames = [frame.name for frame in traceback.extract_tb(raised.tb)]
    assert "f" in frames  # the traceback reaches into the function


@pytest.mark.parametrize("integrator", ["SymplecticEuler", "Rk4"])
def test_an_exception_stops_a_run_resumably(tmp_path, integrator):
    scenario = short(FIG11).with_values({"integrator": integrator})
    alg2 = Algorithm2(scenario)
    failing = failing_after(47, scenario.step, alg2)
    out = tmp_path / "out"
    with pytest.raises(Boom):
        flocking.run(scenario, out, controls=failing, checkpoint_every=10)
    partial = Path(f"{out}.partial")
    assert not out.exists() and (partial / "INCOMPLETE").exists()
    kept = flocking.read_run(partial)
    assert kept.final.t == 40 * scenario.step  # the records up to the failed step (every 20)
    # the same function (its module and name recorded), which no longer fails
    resumed = flocking.resume(out, controls=failing_after(10**9, scenario.step, alg2))
    assert_runs_equal(resumed, flocking.read_run(out))
    reference = flocking.run(scenario, tmp_path / "reference")
    for name in ("metrics.csv", "trajectory.csv", "final.csv", "flocking.txt"):
        assert (out / name).read_bytes() == (tmp_path / "reference" / name).read_bytes(), name


def test_a_sweep_sends_the_function_to_its_workers(tmp_path):
    spec = tmp_path / "sweep.ron"
    spec.write_text(
        f"""Sweep(name: "controls", base: Path("{FIG11}"),
        set: {{"duration": 1.0, "agents": 10, "initial.positions.std": 5.0}},
        axes: [(path: "algorithm.c1", values: List([0.02, 0.05]))], seeds: 1)"""
    )
    builtin = flocking.sweep(spec, tmp_path / "builtin")
    controlled = flocking.sweep(spec, tmp_path / "zeros", controls=zero_inputs)
    assert list(controlled.columns["error"]) == ["", ""]
    # no inputs: every agent keeps its velocity, unlike the flock of the built-in protocol
    assert not np.array_equal(controlled.columns["velocity_mismatch"], builtin.columns["velocity_mismatch"])
    scenario = flocking.Scenario.load(FIG11).with_values(
        {"duration": 1.0, "agents": 10, "initial.positions.std": 5.0, "seed": int(controlled.columns["seed"][0])}
    )
    alone = flocking.run(scenario, controls=zero_inputs)
    assert controlled.columns["velocity_mismatch"][0] == alone.metrics["velocity_mismatch"][-1]
