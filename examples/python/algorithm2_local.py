"""TAC 2006 Algorithm 2 written as a *local* controller in numpy — each agent's input from what it
perceives, ``controls=flocking.Local(...)`` — against the built-in one, ideal and under delay,
packet loss and sensing noise.

Olfati-Saber, *Flocking for multi-agent dynamic systems: algorithms and theory*, IEEE TAC 51(3)
2006, eq. 23 and 25-26 (``/work/shared/SPEC.md`` § Algorithm 2), agent i's input from its own
measured state (q_i, p_i), the relative states (q_j − q_i, p_j − p_i) of the agents it heard and
the γ-agent's (q_r, p_r):

    u_i = c₁^α Σ_j φ_α(‖q_j − q_i‖_σ) n_ij + c₂^α Σ_j a_ij(q) (p_j − p_i)
          − c₁ (q_i − q_r) − c₂ (p_i − p_r)

The arithmetic is ``algorithm2_numpy.py``'s, ``Algorithm2.inputs`` (the operations of
flock-protocols, in their order);
here the relative states come from the perception (``flocking.Perception``), which the scenario's
conditions shaped, so the same function runs under every condition. Measured on x86-64: the bits
of the built-in Algorithm 2, ideal and with delay + Gilbert–Elliott loss + sensing noise.

Run it from the repository root:  python examples/python/algorithm2_local.py [duration]
"""

import sys

import numpy as np

import flocking
from algorithm2_numpy import FIXTURE, Algorithm2

#: Delay 30 ms, Gilbert–Elliott loss held 0.1 s, white sensing noise, control at 50 Hz.
CONDITIONS = {
    "conditions.communication.delay": 0.03,
    "conditions.communication.loss": "GilbertElliott(p_fail: 0.2, p_recover: 1.0)",
    "conditions.communication.when_lost": "Hold(max_age: 0.1)",
    "conditions.sensing.noise": "White(sigma_q: 0.02, sigma_p: 0.01)",
    "conditions.control.rate": 50.0,
}


class LocalAlgorithm2(Algorithm2):
    """The inputs of TAC 2006 Algorithm 2 from every agent's perception: a ``Local`` controller."""

    def __call__(self, t, perception):
        return self.inputs(
            perception.positions,
            perception.velocities,
            perception.heard_by,
            perception.relative_positions,
            perception.relative_velocities,
            (perception.gamma_position, perception.gamma_velocity),
        )


def scenario_with(conditions: dict, duration: float) -> flocking.Scenario:
    """The Fig. 11 fixture for ``duration`` seconds under ``conditions`` (paths and values)."""
    return flocking.Scenario.load(FIXTURE).with_values({"duration": duration, **conditions})


def compare(scenario: flocking.Scenario) -> bool:
    """Whether the local numpy Algorithm 2 gives every bit of the built-in run's final state."""
    builtin = flocking.run(scenario, trajectory=False)
    local = flocking.run(scenario, trajectory=False, controls=flocking.Local(LocalAlgorithm2(scenario)))
    return bool(
        np.array_equal(builtin.final.positions, local.final.positions)
        and np.array_equal(builtin.final.velocities, local.final.velocities)
    )


def main(duration: float = 20.0) -> None:
    for label, conditions in (("ideal", {}), ("delay + loss + noise", CONDITIONS)):
        identical = compare(scenario_with(conditions, duration))
        print(f"Fig. 11, T = {duration} s, {label}: local numpy Algorithm 2 bit-identical: {identical}")


if __name__ == "__main__":
    main(*(float(a) for a in sys.argv[1:2]))
