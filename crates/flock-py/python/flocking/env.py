"""Environments for controllers that learn: any flocking scenario as a PettingZoo ``ParallelEnv``
(:class:`FlockParallelEnv`), a Gymnasium ``Env`` of one flock (:class:`FlockEnv`) and a
Gymnasium ``VectorEnv`` of ``num_envs`` flocks stepped together in Rust (:class:`FlockVectorEnv`).

Every agent observes what it perceives through the scenario's conditions (delay, loss, range,
sensing noise, faults), in a fixed layout (:data:`FlockVectorEnv.layout`); it acts with the input
u_i the scenario's protocol would compute (an acceleration; the next velocity for the models whose
input is a velocity; the acceleration a vehicle's controller tracks), which the scenario's
actuation stage limits as it limits the protocol's; its reward is made of TAC 2006's measures
(see ``docs/environments.md``). One environment step is one control period. The scenario's own
protocol is the baseline: ``baseline_action()`` is what Algorithm 1/2/3, the boids, Vicsek, …
would command now, and stepping with it gives ``flocking run``'s trajectory bit for bit.

Needs ``gymnasium`` (≥ 1.0) and, for :class:`FlockParallelEnv`, ``pettingzoo`` (≥ 1.24)::

    pip install gymnasium pettingzoo
"""

from __future__ import annotations

from typing import Any, Callable, Optional, Union

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

from ._flocking import Scenario, _VecEnv

__all__ = ["FlockEnv", "FlockParallelEnv", "FlockVectorEnv", "RewardFunction"]

#: A reward of your own: ``f(state) -> rewards``, ``state`` a dict of numpy arrays — ``t``
#: (num_envs,), ``positions`` and ``velocities`` (num_envs, n, dim), ``failed`` (num_envs, n) and
#: ``rewards`` (num_envs, n), the default reward — returning the rewards (num_envs, n).
RewardFunction = Callable[[dict], np.ndarray]


def _scenario(scenario: Union[Scenario, str]) -> Scenario:
    """A scenario, loaded when given as a path to a RON file."""
    return scenario if isinstance(scenario, Scenario) else Scenario.load(str(scenario))


def _max_acceleration(scenario: Scenario) -> float:
    """The actuation limit |u_i| ≤ a_max of the scenario's conditions, ∞ without one."""
    try:
        limit = scenario.value("conditions.actuation.max_acceleration")
    except (KeyError, ValueError):
        return np.inf
    return np.inf if limit is None else float(limit)


class FlockVectorEnv(VectorEnv):
    """``num_envs`` flocks of ``scenario`` (a :class:`flocking.Scenario` or a RON path), flock k
    seeded ``seed + k``, stepped together in Rust by one call with the GIL released.

    ``step(actions)`` takes actions (num_envs, n, dim) and returns observations
    (num_envs, n, size), rewards (num_envs, n) — one per agent —, terminations and truncations
    (num_envs,) and infos (``reset``: which flocks this step reset; ``fault``: why a flock was
    terminated; ``failed``: (num_envs, n) the agents a fault removed). The observation and reward
    arrays are written in place, allocated once: each call overwrites the arrays the last one
    returned (``copy=True`` returns copies). After a flock's episode ends, its next step resets it
    and ignores its actions (Gymnasium's ``AutoresetMode.NEXT_STEP``).
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": ["rgb_array"]}

    def __init__(
        self,
        scenario: Union[Scenario, str],
        num_envs: int = 1,
        *,
        seed: Optional[int] = None,
        neighbours: int = 6,
        reward_weights: Optional[dict] = None,
        reward: Optional[RewardFunction] = None,
        render_mode: Optional[str] = None,
        copy: bool = False,
    ) -> None:
        self.scenario = _scenario(scenario)
        weights = {"deviation": 1.0, "mismatch": 0.1, "collision": 1.0, "gamma": 0.01}
        unknown = set(reward_weights or {}) - set(weights)
        if unknown:
            raise ValueError(
                f"reward_weights: unknown terms {sorted(unknown)}; the terms are {sorted(weights)}"
            )
        weights.update(reward_weights or {})
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode={render_mode!r}: the one mode is 'rgb_array'")
        self._engine = _VecEnv(
            self.scenario,
            num_envs,
            self.scenario.seed if seed is None else seed,
            neighbours,
            [weights[k] for k in ("deviation", "mismatch", "collision", "gamma")],
        )
        self.num_envs = num_envs
        self.agents, self.dim = self.scenario.agents, self.scenario.dim
        #: The observation's fields: name → (start, length) in an agent's row.
        self.layout = dict(self._engine.layout())
        self.size = sum(length for _, length in self.layout.values())
        a_max = _max_acceleration(self.scenario)
        self.single_observation_space = spaces.Box(
            -np.inf, np.inf, (self.agents, self.size), np.float64
        )
        self.single_action_space = spaces.Box(-a_max, a_max, (self.agents, self.dim), np.float64)
        self.observation_space = spaces.Box(
            -np.inf, np.inf, (num_envs, self.agents, self.size), np.float64
        )
        self.action_space = spaces.Box(
            -a_max, a_max, (num_envs, self.agents, self.dim), np.float64
        )
        self.render_mode = render_mode
        self._reward = reward
        self._copy = copy

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        """Restarts every flock (flock k seeded ``seed + k``, or with its own seed when ``seed``
        is None) and returns (observations, infos)."""
        if seed is not None:
            self.action_space.seed(seed)
        obs = self._engine.reset(seed)
        return (obs.copy() if self._copy else obs), {}

    def step(self, actions):
        """One control period of every flock with ``actions`` (num_envs, n, dim)."""
        actions = self._actions(actions)
        obs, rewards, terminated, truncated, reset, faults = self._engine.step(actions)
        if self._reward is not None:
            rewards[...] = self._custom_rewards(rewards)
        infos: dict[str, Any] = {"reset": reset}
        if any(f is not None for f in faults):
            infos["fault"] = np.array(faults, dtype=object)
        if self._copy:
            obs, rewards = obs.copy(), rewards.copy()
        return obs, rewards, terminated, truncated, infos

    def baseline_action(self) -> np.ndarray:
        """What the scenario's protocol would command every agent of every flock for what it
        perceives now (num_envs, n, dim); stepping with it gives ``flocking run``'s bits."""
        return self._engine.protocol_actions()

    def states(self) -> dict:
        """The flocks' true states: ``t`` (num_envs,), ``positions`` and ``velocities``
        (num_envs, n, dim), ``failed`` (num_envs, n)."""
        t, q, p, failed = self._engine.states()
        return {"t": t, "positions": q, "velocities": p, "failed": failed}

    def render(self, k: int = 0) -> np.ndarray:
        """Flock ``k`` drawn as the snapshots of ``flocking plot`` draw it: (480, 640, 3) uint8."""
        from ._flocking import _render

        state = self.states()
        return _render(
            self.scenario, state["positions"][k], state["velocities"][k], float(state["t"][k])
        )

    def _actions(self, actions) -> np.ndarray:
        """``actions`` as a C-contiguous float64 array of shape (num_envs, n, dim), or a
        ValueError naming the shape or dtype."""
        array = np.asarray(actions)
        if array.dtype.kind not in "fiu":
            raise ValueError(
                f"actions of dtype {array.dtype}: give real numbers (float64), one row of "
                f"{self.dim} per agent"
            )
        shape = (self.num_envs, self.agents, self.dim)
        if array.shape != shape:
            raise ValueError(f"actions of shape {array.shape}; expected {shape} (num_envs, n, dim)")
        return np.ascontiguousarray(array, dtype=np.float64)

    def _custom_rewards(self, rewards: np.ndarray) -> np.ndarray:
        """The user's reward of the states reached, checked."""
        state = self.states()
        state["rewards"] = rewards.copy()
        try:
            custom = np.asarray(self._reward(state), dtype=np.float64)
        except Exception as error:
            raise RuntimeError(
                f"the reward function raised at t = {state['t'].tolist()}: {error!r}"
            ) from error
        if custom.shape != rewards.shape:
            raise ValueError(
                f"the reward function returned shape {custom.shape}; expected {rewards.shape} "
                "(num_envs, n): one reward per agent of every flock"
            )
        bad = np.argwhere(~np.isfinite(custom))
        if len(bad):
            e, i = bad[0]
            raise ValueError(
                f"the reward function returned {custom[e, i]} for environment {e}, agent {i}: "
                "return finite rewards"
            )
        return custom


class FlockEnv(gymnasium.Env):
    """One flock of ``scenario`` as a Gymnasium ``Env``: the whole flock is the agent, observing
    (n, size) and acting (n, dim) (a centralised view of distributed agents: each row of the
    observation is what that agent perceives alone). The reward is the mean of the agents'
    rewards (each in ``info["rewards"]``). Arguments as :class:`FlockVectorEnv`.
    """

    metadata = {"render_modes": ["rgb_array"]}

    def __init__(self, scenario: Union[Scenario, str], **kwargs: Any) -> None:
        self.vector = FlockVectorEnv(scenario, 1, copy=True, **kwargs)
        self.observation_space = self.vector.single_observation_space
        self.action_space = self.vector.single_action_space
        self.render_mode = self.vector.render_mode

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        obs, _ = self.vector.reset(seed=seed)
        return obs[0], {}

    def step(self, action):
        obs, rewards, terminated, truncated, infos = self.vector.step(np.asarray(action)[None])
        info = {"rewards": rewards[0]}
        if "fault" in infos:
            info["fault"] = infos["fault"][0]
        return obs[0], float(rewards[0].mean()), bool(terminated[0]), bool(truncated[0]), info

    def baseline_action(self) -> np.ndarray:
        """What the scenario's protocol would command now (n, dim)."""
        return self.vector.baseline_action()[0]

    def render(self):
        return self.vector.render(0) if self.render_mode == "rgb_array" else None


def _parallel_env_base():
    """PettingZoo's ``ParallelEnv``, imported when first needed."""
    from pettingzoo import ParallelEnv

    return ParallelEnv


class FlockParallelEnv(_parallel_env_base()):
    """One flock of ``scenario`` as a PettingZoo ``ParallelEnv``: one agent per flock member
    (``agent_0`` … ``agent_{n-1}``), each observing its own row (size,) and acting with its input
    (dim,). An agent a fault removes is terminated; every agent is truncated when the run's
    duration is reached, and all are terminated if the state blows up (``infos[a]["fault"]``).
    Arguments as :class:`FlockVectorEnv`.
    """

    metadata = {"name": "flocking_v0", "render_modes": ["rgb_array"], "is_parallelizable": True}

    def __init__(self, scenario: Union[Scenario, str], **kwargs: Any) -> None:
        self.vector = FlockVectorEnv(scenario, 1, copy=True, **kwargs)
        self.possible_agents = [f"agent_{i}" for i in range(self.vector.agents)]
        self.agents: list = []
        self.render_mode = self.vector.render_mode
        row = self.vector.single_observation_space
        act = self.vector.single_action_space
        self._observation_space = spaces.Box(-np.inf, np.inf, row.shape[1:], np.float64)
        self._action_space = spaces.Box(act.low[0], act.high[0], act.shape[1:], np.float64)

    def observation_space(self, agent):
        return self._observation_space

    def action_space(self, agent):
        return self._action_space

    def reset(self, seed: Optional[int] = None, options: Optional[dict] = None):
        obs, _ = self.vector.reset(seed=seed)
        self.agents = list(self.possible_agents)
        return self._per_agent(obs[0]), {a: {} for a in self.agents}

    def step(self, actions: dict):
        missing = [a for a in self.agents if a not in actions]
        if missing:
            raise ValueError(f"no action for {missing[:5]}: give one (dim,) array per live agent")
        batch = np.zeros((1, self.vector.agents, self.vector.dim))
        for a in self.agents:
            batch[0, int(a.split("_")[1])] = actions[a]
        obs, rewards, terminated, truncated, infos = self.vector.step(batch)
        failed = self.vector.states()["failed"][0]
        live = list(self.agents)
        fault = infos.get("fault", [None])[0]
        out = (
            {a: obs[0][self._index(a)] for a in live},
            {a: float(rewards[0][self._index(a)]) for a in live},
            {a: bool(terminated[0] or failed[self._index(a)]) for a in live},
            {a: bool(truncated[0]) for a in live},
            {a: ({"fault": fault} if fault else {}) for a in live},
        )
        self.agents = [a for a in live if not (out[2][a] or out[3][a])]
        return out

    def baseline_action(self) -> dict:
        """What the scenario's protocol would command each live agent now."""
        u = self.vector.baseline_action()[0]
        return {a: u[self._index(a)] for a in self.agents}

    def render(self):
        return self.vector.render(0) if self.render_mode == "rgb_array" else None

    def _per_agent(self, rows: np.ndarray) -> dict:
        return {a: rows[self._index(a)] for a in self.agents}

    @staticmethod
    def _index(agent: str) -> int:
        return int(agent.split("_")[1])
