"""TAC 2006 Algorithm 2 written in numpy and run through ``controls=``, against the built-in one.

Olfati-Saber, *Flocking for multi-agent dynamic systems: algorithms and theory*, IEEE TAC 51(3)
2006, eq. 23 and 25-26 (see ``/work/shared/SPEC.md`` § Algorithm 2):

    u_i = c₁^α Σ_j φ_α(‖q_j − q_i‖_σ) n_ij + c₂^α Σ_j a_ij(q) (p_j − p_i)
          − c₁ (q_i − q_r) − c₂ (p_i − p_r)

with the σ-norm ‖z‖_σ = (√(1 + ε‖z‖²) − 1)/ε written as ‖z‖² / (√(1 + ε‖z‖²) + 1), its gradient
n_ij = (q_j − q_i)/√(1 + ε‖q_j − q_i‖²), the bump ρ_h, a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) and the
action φ_α(z) = ρ_h(z / r_α) φ(z − d_α), φ(z) = ½[(a + b) σ₁(z + c) + (a − b)], σ₁(z) =
z / √(1 + z²), c = |a − b| / √(4ab).

Every floating-point operation is the one of flock-math and flock-protocols (``sigma.rs``
``norm_and_gradient_scale``, ``bump.rs``, ``action.rs`` ``action_and_bump``, ``alpha.rs``
``input``, ``gamma.rs``), in the same order: each agent's two sums start at 0 and add
its neighbours' terms in ascending j (``numpy.add.at`` adds in index order, unbuffered). The bump
ρ_h is ``flocking.bump``, the library's own: its cosine is a vector polynomial (``wide``'s
``f64x4::sin_cos``), whose bits neither ``numpy.cos`` nor ``math.cos`` reproduces (they differ
from it by up to 2 ULP in a quarter of the phases). Measured on x86-64: the bits of the built-in
Algorithm 2 over the whole of Fig. 11 (10 000 steps).

Run it from the repository root:  python examples/python/algorithm2_numpy.py [duration]
"""

import math
import sys

import numpy as np

import flocking

FIXTURE = "fixtures/tac2006_fig11_alg2_n100.ron"


class Algorithm2:
    """The inputs u of TAC 2006 Algorithm 2 for ``scenario`` (an Algorithm2 scenario whose γ-agent
    moves at constant velocity, or is static): a ``controls`` function."""

    def __init__(self, scenario: flocking.Scenario) -> None:
        alpha = scenario.alpha
        (kind, algorithm), = scenario.value("algorithm").items()
        if kind != "Algorithm2":
            raise ValueError(f"{scenario.name} runs {kind}, not Algorithm2")
        (gamma_kind, gamma), = algorithm["gamma"].items()
        if gamma_kind not in ("Static", "ConstantVelocity"):
            raise ValueError(f"a γ-agent {gamma_kind} is not written here")
        if algorithm.get("feedback", "Linear") != "Linear":
            raise ValueError("only the linear navigational feedback is written here")
        self.epsilon, self.h = alpha["epsilon"], alpha["h"]
        self.c1_alpha, self.c2_alpha = alpha["c1"], alpha["c2"]
        self.c1, self.c2 = algorithm["c1"], algorithm["c2"]
        a, b = alpha["a"], alpha["b"]
        c = abs(a - b) / math.sqrt(4.0 * a * b)
        d_alpha = self._sigma_of_length(alpha["d"])
        self.r_alpha = self._sigma_of_length(alpha["r"])
        # φ_α's profile: scale · σ₁(z − shift) + offset (BumpedAction::alpha)
        self.scale, self.shift, self.offset = 0.5 * (a + b), d_alpha - c, 0.5 * (a - b)
        self.q_r0 = np.array(gamma["position"], dtype=float)
        self.p_r = np.array(gamma.get("velocity", [0.0] * scenario.dim), dtype=float)

    def _sigma_of_length(self, d: float) -> float:
        d2 = d * d
        return d2 / (math.sqrt(1.0 + self.epsilon * d2) + 1.0)

    def __call__(self, t, q, p, neighbours):
        rows = np.repeat(np.arange(len(q)), np.diff(neighbours.indptr))
        cols = neighbours.indices
        return self.inputs(q, p, rows, q[cols] - q[rows], p[cols] - p[rows],
                           (self.q_r0 + self.p_r * t, self.p_r))

    def inputs(self, q, p, rows, dq, dp, reference):
        """u of every agent at (q, p), agent ``rows[k]`` having neighbour k at relative position
        ``dq[k]`` and velocity ``dp[k]``, the γ-agent at ``reference`` = (q_r, p_r)."""
        d2 = dq[:, 0] * dq[:, 0]
        for k in range(1, q.shape[1]):
            d2 = d2 + dq[:, k] * dq[:, k]
        root = np.sqrt(1.0 + self.epsilon * d2)
        z, gradient_scale = d2 / (root + 1.0), 1.0 / root
        rho = flocking.bump(z / self.r_alpha, self.h)
        x = z - self.shift
        phi = rho * (self.scale * (x / np.sqrt(1.0 + x * x)) + self.offset)
        gradient = np.zeros_like(q)
        consensus = np.zeros_like(q)
        np.add.at(gradient, rows, dq * (phi * gradient_scale)[:, None])
        np.add.at(consensus, rows, dp * rho[:, None])
        u_alpha = gradient * self.c1_alpha + consensus * self.c2_alpha
        q_r, p_r = reference
        return u_alpha + (-((q - q_r) * self.c1) - (p - p_r) * self.c2)


def compare(scenario: flocking.Scenario):
    """The final positions of the built-in Algorithm 2 and of the numpy one: (max |Δq|, whether
    every bit agrees)."""
    builtin = flocking.run(scenario, trajectory=False)
    numpy_run = flocking.run(scenario, trajectory=False, controls=Algorithm2(scenario))
    a, b = builtin.final.positions, numpy_run.final.positions
    return float(np.max(np.abs(a - b))), bool(np.array_equal(a, b) and np.array_equal(
        builtin.final.velocities, numpy_run.final.velocities))


def main(duration: float = 100.0) -> None:
    scenario = flocking.Scenario.load(FIXTURE).with_values({"duration": duration})
    difference, identical = compare(scenario)
    print(f"{scenario.name}, T = {duration} s: "
          f"max |q_numpy − q_rust| = {difference:.3g}, bit-identical: {identical}")


if __name__ == "__main__":
    main(*(float(a) for a in sys.argv[1:2]))
