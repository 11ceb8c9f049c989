"""The cost of computing the inputs in Python (``controls=``): milliseconds per step of
``Simulation.step`` with the built-in TAC 2006 Algorithm 2, with the same algorithm in numpy
(``algorithm2_numpy.py``), and with a function that returns zeros (the bare cost of the call: the
state and the net copied into numpy arrays, the GIL taken, the result checked), at n = 10³ and
10⁴ agents of the Fig. 11 scenario (its Gaussian cloud widened to keep the density).

Run it from the repository root:  python examples/python/controls_overhead.py
"""

import os
import sys
import time

import numpy as np

import flocking

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from algorithm2_numpy import FIXTURE, Algorithm2  # noqa: E402


def zeros(t, q, p, neighbours):
    """No input: the cost of a call of ``controls`` alone."""
    return np.zeros_like(q)


def ms_per_step(scenario, controls, steps):
    """The best of three timings of ``steps`` steps, in ms per step."""
    best = float("inf")
    for _ in range(3):
        sim = flocking.Simulation(scenario, controls=controls)
        sim.step(1)  # the first step's allocations
        start = time.perf_counter()
        sim.step(steps)
        best = min(best, (time.perf_counter() - start) / steps)
    return 1e3 * best


def main():
    base = flocking.Scenario.load(FIXTURE)
    print(f"{'n':>6} {'built-in':>10} {'numpy Alg. 2':>13} {'ratio':>6} {'zeros':>8}  (ms/step)")
    for n, steps in ((1_000, 200), (10_000, 40)):
        std = 50.0 * (n / 100) ** 0.5
        scenario = base.with_values({"agents": n, "initial.positions.std": std})
        builtin = ms_per_step(scenario, None, steps)
        numpy_alg2 = ms_per_step(scenario, Algorithm2(scenario), steps)
        bare = ms_per_step(scenario, zeros, steps)
        print(f"{n:>6} {builtin:>10.3f} {numpy_alg2:>13.3f} {numpy_alg2 / builtin:>6.1f} {bare:>8.3f}")


if __name__ == "__main__":
    main()
