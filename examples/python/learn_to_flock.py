"""Learning to flock with an evolution strategy, against TAC 2006 Algorithm 2, under packet loss.

The task: the Fig. 11 fixture (Algorithm 2, 2D, d = 7, γ-agent in uniform motion) made small and
short — ``AGENTS`` = 25 agents from a Gaussian cloud of standard deviation ``SPREAD`` = 8 m (the
start's connectivity C is about 0.93 on the held-out flocks), velocities uniform in [−2, 2]²,
``DURATION`` = 5 s — with every packet lost with probability 0.1 (``Bernoulli(p: 0.1)``) and the
accelerations limited to ``A_MAX`` = 5 m/s² by the scenario's actuation stage, for the learned
policy and Algorithm 2 alike.

The policy: one shared network for every agent, from the agent's observation row
(``flocking.env``'s layout: own velocity, the k = 6 nearest agents heard, the γ-agent, the nearest
β-agent, with masks) to its acceleration,

    u_i = A_MAX · tanh(W₂ tanh(W₁ S o_i + b₁) + b₂),

S a fixed scaling (relative positions in units of d), 16 hidden units: each component of u_i in
[−A_MAX, A_MAX], and the actuation stage clips its norm to A_MAX. It starts at u = 0 (W₂ = 0).

The training: OpenAI-ES (Salimans, Ho, Chen, Sidor, Sutskever, *Evolution strategies as a scalable
alternative to reinforcement learning*, arXiv:1703.03864, 2017: Gaussian perturbations, mirrored
(antithetic) sampling and centred-rank fitness shaping; here the step by Adam with weight
decay): each generation draws P/2 Gaussian directions ε and evaluates θ ± σε as the P flocks of
one ``FlockVectorEnv`` — flock k acts with candidate k, all P flocks stepped by one call per
control period. A candidate's fitness
is its mean episode reward (Σ_t mean_i r_i, the env's default reward of TAC 2006's measures)
minus Algorithm 2's on the same start and the same packet draws (a second batch of the same
seeds, stepped with ``baseline_action()``): the subtraction does not depend on θ, it only removes
the variance of the random starts from the ranking, and it draws Algorithm 2's curve on the same
seeds. Training seeds and held-out seeds are disjoint. σ = 0.05, Adam's step 0.03 and
the weight decay 0.005 were set once for this script, not tuned.

The comparison, on held-out seeds: the mean episode reward through the env (both policies on the
same seeds), and the final normalised deviation energy Ẽ = E(q)/d², the connectivity C and the
collisions from ``flocking.run`` — the learned policy as a ``flocking.Local`` controller that
builds the same observation rows from the ``Perception``, Algorithm 2 the scenario's own. The
script checks that every held-out run of ``flocking.run`` ends in the env's final state bit for
bit, for both policies: the two paths are the same system, and the numpy observation below is
the env's.

What the default run shows (150 generations × 32, seed 0; 8 held-out flocks; the figure
``docs/figures/environments/learned_vs_algorithm2.png``): the learned policy gets the better
reward — an episode reward of −211 ± 134 against Algorithm 2's −337 ± 77 (mean ± standard
deviation over the flocks) — and it does not flock.
At T its agents' velocities agree better (K̃ = 0.15 against 0.29; the cloud moves at 1.26 m/s, the
γ-agent at 1.12 m/s), but its spacing is not corrected (Ẽ stays at 0.13, about its start value,
where Algorithm 2's falls to 0.0033) and its close pairs stay close (4.25 pairs closer than d_c at
T against 0). It keeps more links (C(T) = 0.92 against 0.62): its cloud keeps the start's shape,
while Algorithm 2's flock, spreading to the lattice's spacing, splits into groups within the 5 s.
Algorithm 2 pays for its lattice: while the start's close pairs push apart, its K̃ rises to
several times its start value in the first two seconds (the figure's K̃ panel), and the reward's
mismatch term charges every step of it. On this horizon the default reward ranks a policy that
aligns velocities and leaves spacing and collisions as they were above TAC 2006's protocol: the
ES found what the reward pays for, not flocking. A longer horizon, other weights
(``reward_weights=``) or a policy that sees more than 6 neighbours change the task; this script
does not claim what they would give. The run takes 1.5–3 minutes on two shared cores.

Run it from the repository root (needs matplotlib):

    python examples/python/learn_to_flock.py [--generations G] [--population P] [--out PNG] [--seed S]
"""

from __future__ import annotations

import argparse
import time
from dataclasses import dataclass
from typing import Optional

import numpy as np

import flocking
from algorithm2_numpy import FIXTURE
from flocking.env import FlockVectorEnv

AGENTS = 25
SPREAD = 8.0
DURATION = 5.0
LOSS = "Bernoulli(p: 0.1)"
A_MAX = 5.0
NEIGHBOURS = 6
HIDDEN = 16
#: Training flocks are seeded from here on, the held-out ones from 0: disjoint for G·P < 10⁶.
TRAIN_SEEDS = 1_000_000
OUT = "docs/figures/environments/learned_vs_algorithm2.png"


def task(agents: int = AGENTS, duration: float = DURATION) -> flocking.Scenario:
    """The Fig. 11 fixture, small and short, under 10 % Bernoulli loss and |u_i| ≤ A_MAX."""
    return flocking.Scenario.load(FIXTURE).with_values(
        {
            "agents": agents,
            "duration": duration,
            "initial.positions.Gaussian.std": SPREAD,
            "conditions.communication.loss": LOSS,
            "conditions.actuation.max_acceleration": A_MAX,
        }
    )


class Policy:
    """The shared network u_i = A_MAX tanh(W₂ tanh(W₁ S o_i + b₁) + b₂) of the observation row o_i,
    its parameters a flat vector θ (W₁, b₁, W₂, b₂)."""

    def __init__(self, layout: dict, dim: int, d: float, hidden: int = HIDDEN) -> None:
        self.layout, self.dim, self.hidden = layout, dim, hidden
        self.size = sum(length for _, length in layout.values())
        # S: relative positions (of neighbours, γ-agent, β-agent) in units of d, the rest as is.
        self.scale = np.ones(self.size)
        for name in ("neighbours", "gamma", "beta"):
            start, length = layout[name]
            for slot in range(start, start + length, 2 * dim):
                self.scale[slot : slot + dim] = 1.0 / d
        self.shapes = [(hidden, self.size), (hidden,), (dim, hidden), (dim,)]
        self.parameters = sum(int(np.prod(s)) for s in self.shapes)

    def initial(self, rng: np.random.Generator) -> np.ndarray:
        """θ₀: W₁ ~ N(0, 1/size), the rest 0 (the policy u = 0)."""
        theta = np.zeros(self.parameters)
        theta[: self.hidden * self.size] = rng.standard_normal(self.hidden * self.size) / np.sqrt(
            self.size
        )
        return theta

    def act(self, thetas: np.ndarray, obs: np.ndarray) -> np.ndarray:
        """The inputs (P, n, dim) of P parameter vectors ``thetas`` (P, parameters), candidate k
        acting on the observations ``obs[k]`` (n, size)."""
        p = thetas.shape[0]
        parts, at = [], 0
        for shape in self.shapes:
            count = int(np.prod(shape))
            parts.append(thetas[:, at : at + count].reshape(p, *shape))
            at += count
        w1, b1, w2, b2 = parts
        hidden = np.tanh((obs * self.scale) @ w1.transpose(0, 2, 1) + b1[:, None, :])
        return A_MAX * np.tanh(hidden @ w2.transpose(0, 2, 1) + b2[:, None, :])

    def rows(self, perception: flocking.Perception) -> np.ndarray:
        """Every agent's observation row (n, size) from its ``perception``, as the env builds it
        (``flocking::env::Layout::observe``): the k nearest agents heard by ‖q_j − q_i‖ (ties by
        entry), the γ-agent, the nearest β-agent (ties by entry), relative to the agent."""
        d, layout = self.dim, self.layout
        q, p = perception.positions, perception.velocities
        n = q.shape[0]
        rows = np.zeros((n, self.size))
        start, length = layout["velocity"]
        rows[:, start : start + length] = p
        heard_by, indptr = perception.heard_by, perception.indptr
        dq, dp = perception.relative_positions, perception.relative_velocities
        order = np.lexsort((np.arange(len(heard_by)), _square(dq), heard_by))
        rank = np.arange(len(order)) - indptr[heard_by[order]]
        observed = rank < layout["neighbour_mask"][1]
        kept, slot = order[observed], rank[observed]
        i, start = heard_by[kept], layout["neighbours"][0] + slot * 2 * d
        for c in range(d):
            rows[i, start + c] = dq[kept, c]
            rows[i, start + d + c] = dp[kept, c]
        rows[i, layout["neighbour_mask"][0] + slot] = 1.0
        if perception.gamma_position is not None:
            start = layout["gamma"][0]
            rows[:, start : start + d] = perception.gamma_position - q
            rows[:, start + d : start + 2 * d] = perception.gamma_velocity - p
            rows[:, layout["gamma_mask"][0]] = 1.0
        beta_indptr = perception.beta_indptr
        counts = np.diff(beta_indptr)
        if counts.any():
            owner = np.repeat(np.arange(n), counts)
            bq, bp = perception.beta_relative_positions, perception.beta_relative_velocities
            order = np.lexsort((np.arange(len(owner)), _square(bq), owner))
            nearest = order[np.arange(len(order)) == beta_indptr[owner[order]]]
            start = layout["beta"][0]
            rows[owner[nearest], start : start + d] = bq[nearest]
            rows[owner[nearest], start + d : start + 2 * d] = bp[nearest]
            rows[owner[nearest], layout["beta_mask"][0]] = 1.0
        return rows

    def controller(self, theta: np.ndarray) -> flocking.Local:
        """θ as a local controller of ``flocking.run``: every agent's input from its perception."""
        return flocking.Local(
            lambda t, perception: self.act(theta[None], self.rows(perception)[None])[0]
        )


def _square(v: np.ndarray) -> np.ndarray:
    """‖v‖² of every row, summed in the order of the Rust layout (0 + v₀² + v₁² …)."""
    total = v[:, 0] * v[:, 0]
    for c in range(1, v.shape[1]):
        total = total + v[:, c] * v[:, c]
    return total


def rollout(env: FlockVectorEnv, act, seed: int) -> np.ndarray:
    """One episode of every flock of ``env`` from ``seed + k``, acting with ``act(obs)``: the
    episode rewards Σ_t mean_i r_i (num_envs,). A flock whose state blows up stops the run."""
    obs, _ = env.reset(seed=seed)
    total = np.zeros(env.num_envs)
    while True:
        obs, rewards, terminated, truncated, infos = env.step(act(obs))
        if terminated.any():
            raise RuntimeError(f"a flock was terminated: {infos['fault'][terminated.argmax()]}")
        total += rewards.mean(axis=1)
        if truncated.all():
            return total


def centred_ranks(x: np.ndarray) -> np.ndarray:
    """The ranks of ``x`` mapped to [−0.5, 0.5] (Salimans et al. 2017's fitness shaping)."""
    ranks = np.empty(len(x))
    ranks[np.argsort(x)] = np.arange(len(x))
    return ranks / (len(x) - 1) - 0.5


@dataclass
class Adam:
    """Adam (Kingma & Ba 2015) on a flat vector, ascending."""

    lr: float
    beta1: float = 0.9
    beta2: float = 0.999
    m: Optional[np.ndarray] = None
    v: Optional[np.ndarray] = None
    t: int = 0

    def ascend(self, theta: np.ndarray, gradient: np.ndarray) -> np.ndarray:
        if self.m is None:
            self.m, self.v = np.zeros_like(theta), np.zeros_like(theta)
        self.t += 1
        self.m = self.beta1 * self.m + (1 - self.beta1) * gradient
        self.v = self.beta2 * self.v + (1 - self.beta2) * gradient * gradient
        m = self.m / (1 - self.beta1**self.t)
        v = self.v / (1 - self.beta2**self.t)
        return theta + self.lr * m / (np.sqrt(v) + 1e-8)


def train(scenario, policy, generations, population, seed, sigma=0.05, lr=0.03, decay=0.005):
    """OpenAI-ES: θ and the history (generation → mean, best reward of the population, and
    Algorithm 2's mean on the same seeds)."""
    if population < 2 or population % 2:
        raise ValueError(f"--population {population}: give an even number ≥ 2 (antithetic pairs)")
    rng = np.random.default_rng(seed)
    theta = policy.initial(rng)
    envs = FlockVectorEnv(scenario, population, neighbours=NEIGHBOURS)
    reference = FlockVectorEnv(scenario, population, neighbours=NEIGHBOURS)
    adam = Adam(lr)
    history = {"mean": [], "best": [], "algorithm2": []}
    for g in range(generations):
        half = rng.standard_normal((population // 2, policy.parameters))
        eps = np.concatenate([half, -half])
        seeds, candidates = TRAIN_SEEDS + g * population, theta + sigma * eps
        rewards = rollout(envs, lambda obs: policy.act(candidates, obs), seeds)
        baseline = rollout(reference, lambda obs: reference.baseline_action(), seeds)
        shaped = centred_ranks(rewards - baseline)
        gradient = shaped @ eps / (population * sigma) - decay * theta
        theta = adam.ascend(theta, gradient)
        history["mean"].append(float(rewards.mean()))
        history["best"].append(float(rewards.max()))
        history["algorithm2"].append(float(baseline.mean()))
        print(
            f"generation {g + 1:4d}: reward mean {rewards.mean():8.2f}  best {rewards.max():8.2f}"
            f"  Algorithm 2 on the same seeds {baseline.mean():8.2f}",
            flush=True,
        )
    return theta, {k: np.array(v) for k, v in history.items()}


def evaluate(scenario, policy, theta, seeds):
    """Both policies on held-out flocks 0 … seeds − 1: their episode rewards through the env and
    their ``flocking.run`` metrics, each run checked against the env's final state bit for bit."""
    env = FlockVectorEnv(scenario, seeds, neighbours=NEIGHBOURS)
    learned = lambda obs: np.stack([policy.act(theta[None], o[None])[0] for o in obs])  # noqa: E731
    results = {}
    for name, act, controls in (
        ("learned (ES)", learned, policy.controller(theta)),
        ("Algorithm 2", lambda obs: env.baseline_action(), None),
    ):
        rewards = rollout(env, act, 0)
        final = env.states()
        runs, same = [], True
        for k in range(seeds):
            flock = scenario.with_values({"seed": k})
            run = flocking.run(flock, trajectory=False, controls=controls)
            same &= bool(np.array_equal(run.final.positions, final["positions"][k]))
            same &= bool(np.array_equal(run.final.velocities, final["velocities"][k]))
            runs.append(run.metrics)
        results[name] = {"rewards": rewards, "metrics": runs, "same_as_env": same}
    return results


def table(results) -> list:
    """One row per policy: the means (± standard deviation) over the held-out flocks."""
    rows = []
    for name, result in results.items():
        final = lambda column: np.array([m[column][-1] for m in result["metrics"]])  # noqa: E731
        peak = np.array([m["collisions"][1:].max() for m in result["metrics"]])
        rows.append(
            {
                "policy": name,
                "reward": result["rewards"].mean(),
                "reward_std": result["rewards"].std(),
                "deviation_energy": final("deviation_energy").mean(),
                "connectivity": final("connectivity").mean(),
                "collisions": final("collisions").mean(),
                "peak_collisions": peak.mean(),
                "velocity_mismatch": final("velocity_mismatch").mean(),
                "group_speed": final("group_speed").mean(),
                "same_as_env": result["same_as_env"],
            }
        )
    return rows


def print_table(rows, seeds: int, duration: float) -> None:
    print(
        f"\nheld-out flocks 0–{seeds - 1}, 10 % loss, means over the flocks; Ẽ, C, K̃, group speed "
        f"|p̄| and collisions at T = {duration} s"
    )
    print(
        f"{'policy':<14} {'episode reward':>16} {'Ẽ(T)':>8} {'C(T)':>6} {'K̃(T)':>8} {'|p̄|(T)':>8}"
        f" {'coll.(T)':>8} {'max coll. t>0':>13} {'run = env':>9}"
    )
    for r in rows:
        print(
            f"{r['policy']:<14} {r['reward']:8.2f} ± {r['reward_std']:5.2f}"
            f" {r['deviation_energy']:8.4f} {r['connectivity']:6.3f} {r['velocity_mismatch']:8.4f}"
            f" {r['group_speed']:8.3f} {r['collisions']:8.2f}"
            f" {r['peak_collisions']:13.2f} {str(r['same_as_env']):>9}"
        )


def plot(history, results, out: str, title: str) -> None:
    """The learning curve, and the held-out runs' C, Ẽ, collisions, K̃ and |p̄| over time (means
    over the flocks)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 3, figsize=(15, 8))
    generations = np.arange(1, len(history["mean"]) + 1)
    ax = axes[0, 0]
    ax.plot(generations, history["mean"], label="ES population, mean")
    ax.plot(generations, history["best"], lw=0.8, alpha=0.6, label="ES population, best")
    ax.plot(generations, history["algorithm2"], "k--", label="Algorithm 2, same seeds")
    ax.set(
        xlabel="generation",
        ylabel="episode reward Σₜ meanᵢ rᵢ",
        title="training (new seeds every generation)",
    )
    ax.legend(fontsize=8)
    for ax, column, label in (
        (axes[0, 1], "connectivity", "connectivity C(t)"),
        (axes[0, 2], "deviation_energy", "normalised deviation energy Ẽ(t)"),
        (axes[1, 0], "collisions", "collisions: pairs closer than d_c"),
        (axes[1, 1], "velocity_mismatch", "velocity mismatch K̃(t) (m²/s²)"),
        (axes[1, 2], "group_speed", "group speed |p̄|(t) (m/s)"),
    ):
        for (name, result), style in zip(results.items(), ("-", "k--")):
            t = result["metrics"][0]["t"]
            ax.plot(t, np.mean([m[column] for m in result["metrics"]], axis=0), style, label=name)
        ax.set(xlabel="t (s)", ylabel=label, title=label)
        ax.legend(fontsize=8)
    seeds = len(next(iter(results.values()))["metrics"])
    fig.suptitle(f"{title}\nright and below: held-out flocks 0–{seeds - 1}, means", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--generations", type=int, default=150)
    parser.add_argument("--population", type=int, default=32)
    parser.add_argument("--seed", type=int, default=0, help="the seed of the ES's perturbations")
    parser.add_argument("--out", default=OUT, help="the figure (PNG)")
    parser.add_argument("--agents", type=int, default=AGENTS)
    parser.add_argument("--duration", type=float, default=DURATION, help="episode length (s)")
    parser.add_argument("--held-out", type=int, default=8, help="held-out flocks of the comparison")
    args = parser.parse_args(argv)
    scenario = task(args.agents, args.duration)
    probe = FlockVectorEnv(scenario, 1, neighbours=NEIGHBOURS)
    policy = Policy(probe.layout, scenario.dim, scenario.value("alpha")["d"])
    print(
        f"{scenario.agents} agents, {args.duration} s, 10 % loss; policy of {policy.parameters} "
        f"parameters; OpenAI-ES, {args.generations} generations of {args.population}"
    )
    start = time.perf_counter()
    theta, history = train(scenario, policy, args.generations, args.population, args.seed)
    trained = time.perf_counter() - start
    results = evaluate(scenario, policy, theta, args.held_out)
    rows = table(results)
    print_table(rows, args.held_out, args.duration)
    plot(
        history,
        results,
        args.out,
        f"OpenAI-ES, shared {HIDDEN}-tanh policy vs TAC 2006 Algorithm 2: {scenario.agents} agents, "
        f"{args.duration} s, 10 % Bernoulli loss, |u| ≤ {A_MAX} "
        f"({args.generations} generations × {args.population}, seed {args.seed})",
    )
    print(f"training {trained:.0f} s; figure {args.out}")
    return {"history": history, "rows": rows, "theta": theta}


if __name__ == "__main__":
    main()
