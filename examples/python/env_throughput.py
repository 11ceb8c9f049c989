"""Agent-steps per second of ``flocking.env.FlockVectorEnv``: ``num_envs`` flocks of the TAC 2006
Fig. 11 scenario (Algorithm 2, n agents, its Gaussian cloud widened as √n to keep the density)
stepped by one Python call each, the observations (k = 6 nearest perceived neighbours, the
γ-agent) and rewards written into numpy arrays, at (num_envs, n) = (1024, 10), (64, 100) and
(1, 10000) by default. Timed: ``env.step(actions)`` from Python, actions drawn before the clock
starts; not timed: building and resetting the environments. Median of ``--repeats`` timings of
``--steps`` steps after ``--warmup`` steps; memory per environment = the growth of the process's
resident set while the environments were built, over num_envs.

Run it from the repository root:  python examples/python/env_throughput.py [--sizes 1024x10,64x100,1x10000]
"""

import argparse
import json
import os
import statistics
import time

import numpy as np

import flocking
from flocking.env import FlockVectorEnv

FIXTURE = "fixtures/tac2006_fig11_alg2_n100.ron"


def rss_bytes() -> int:
    """The resident set of this process (Linux /proc)."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    return 0


def scenario(n: int) -> flocking.Scenario:
    """Fig. 11 with ``n`` agents at its density, long enough never to end while timed."""
    return flocking.Scenario.load(FIXTURE).with_values(
        {"agents": n, "initial.positions.Gaussian.std": 50.0 * (n / 100) ** 0.5, "duration": 1e4}
    )


def measure(num_envs: int, n: int, steps: int, warmup: int, repeats: int) -> dict:
    """The median agent-steps per second of ``steps`` steps, and the memory per environment."""
    before = rss_bytes()
    env = FlockVectorEnv(scenario(n), num_envs, seed=1)
    env.reset(seed=1)
    memory = (rss_bytes() - before) / num_envs
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1.0, 1.0, env.action_space.shape)
    for _ in range(warmup):
        env.step(actions)
    rates = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(steps):
            env.step(actions)
        rates.append(num_envs * n * steps / (time.perf_counter() - start))
    return {
        "num_envs": num_envs,
        "agents": n,
        "agent_steps_per_s": statistics.median(rates),
        "min": min(rates),
        "max": max(rates),
        "bytes_per_env": memory,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="1024x10,64x100,1x10000")
    parser.add_argument("--steps", type=int, default=50)
    parser.add_argument("--warmup", type=int, default=5)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--json", help="write the results here too")
    args = parser.parse_args()
    load = open("/proc/loadavg").read().split()[:3]
    rows = []
    for size in args.sizes.split(","):
        num_envs, n = map(int, size.split("x"))
        rows.append(measure(num_envs, n, args.steps, args.warmup, args.repeats))
        r = rows[-1]
        print(
            f"({num_envs:>5}, {n:>6}): {r['agent_steps_per_s']:.3g} agent-steps/s "
            f"(min {r['min']:.3g}, max {r['max']:.3g}), {r['bytes_per_env'] / 1e6:.3g} MB per env"
        )
    print(f"load average before: {' '.join(load)}, after: {' '.join(open('/proc/loadavg').read().split()[:3])}; "
          f"{os.cpu_count()} CPUs")
    if args.json:
        with open(args.json, "w") as out:
            json.dump({"load_before": load, "rows": rows}, out, indent=1)


if __name__ == "__main__":
    main()
