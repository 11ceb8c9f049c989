#!/usr/bin/env python3
"""Time VMAS's `flocking` scenario on the CPU (benchmark for flocking issue 52).

Measures agent-steps per second = num_envs * n_agents * steps / seconds for
`env.step(actions)` (which returns observations, rewards, dones and infos), the
median of several repeats, and the resident-memory increase per environment
caused by `vmas.make_env` (VmRSS from /proc/self/status).

Each size runs in its own child process so that one size cannot disturb the
memory figure of another, and so that a size that is too slow or too large is
stopped (wall-clock budget, RSS ceiling) instead of hanging the benchmark.

Usage:
    python vmas_flocking.py --sizes 1024x10,64x100,1x10000 --repeats 5 --json out.json

A size "ExN" is E parallel environments of N learning agents each. If a size
with E == 1 fails (budget, memory or error), the agent counts of
--fallback-agents are tried in increasing order, stopping at the first failure,
so the largest single-environment swarm VMAS handles within the budget is
reported.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shlex
import signal
import statistics
import subprocess
import sys
import time


def read_loadavg() -> str:
    with open("/proc/loadavg") as f:
        return f.read().strip()


def rss_kib(pid: int | str = "self") -> int:
    """Resident set size (VmRSS) of a process in KiB."""
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError(f"no VmRSS in /proc/{pid}/status")


def fail(message: str) -> None:
    """Bad input: a clear message on stderr and exit status 2."""
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def progress(message: str) -> None:
    """A worker's progress line; the driver keeps the last one of a failed size."""
    print(message, file=sys.stderr, flush=True)


def parse_sizes(text: str) -> list[tuple[int, int]]:
    sizes = []
    for item in text.split(","):
        item = item.strip()
        try:
            envs, agents = item.lower().split("x")
            sizes.append((int(envs), int(agents)))
        except ValueError:
            fail(f"--sizes item {item!r} is not NUM_ENVSxN_AGENTS (e.g. 1024x10)")
        if sizes[-1][0] < 1 or sizes[-1][1] < 1:
            fail(f"--sizes item {item!r} must have positive counts")
    return sizes


# VMAS's flocking scenario spawns the target, 5 obstacles and the agents one by
# one at uniformly random points of [-1, 1]^2, redrawing until a point is at
# least `min_dist_between_entities` (default 0.15) from all earlier ones, with
# no cap on retries (vmas/simulator/utils.py, find_random_pos_for_entity).
# Random sequential packing of discs of diameter 0.15 jams at about 54.7 % cover,
# i.e. roughly 120 points in the 2 x 2 square, so reset() never returns for
# larger swarms with the default.  "auto" keeps the default up to
# AUTO_DEFAULT_MAX_AGENTS agents and above that uses the spacing d at which the
# discs cover AUTO_COVER of the square: N * pi * d^2 / 4 = AUTO_COVER * 4.
AUTO_DEFAULT_MAX_AGENTS = 100
AUTO_COVER = 0.3


def spawn_min_dist(option: str, n_agents: int) -> float | None:
    """The `min_dist_between_entities` kwarg to pass, or None for the default."""
    if option == "default":
        return None
    if option == "auto":
        if n_agents <= AUTO_DEFAULT_MAX_AGENTS:
            return None
        n_entities = n_agents + 6  # target + 5 obstacles
        return round((16.0 * AUTO_COVER / (3.141592653589793 * n_entities)) ** 0.5, 4)
    return float(option)


# --------------------------------------------------------------------------
# Worker: one size, in its own process. Prints one JSON line on stdout.
# --------------------------------------------------------------------------
def run_worker(args: argparse.Namespace) -> None:
    import torch

    torch.set_num_threads(args.threads)
    import vmas

    num_envs, n_agents = parse_sizes(args.worker)[0]
    torch.manual_seed(args.seed)
    scenario_kwargs = {"n_agents": n_agents}
    min_dist = spawn_min_dist(args.min_dist, n_agents)
    if min_dist is not None:
        scenario_kwargs["min_dist_between_entities"] = min_dist

    rss_before = rss_kib()
    t0 = time.perf_counter()
    env = vmas.make_env(
        scenario="flocking",
        num_envs=num_envs,
        device="cpu",
        continuous_actions=True,
        seed=args.seed,
        **scenario_kwargs,  # every other scenario kwarg left at its default
    )
    make_env_s = time.perf_counter() - t0
    rss_after_make = rss_kib()
    progress(f"make_env done in {make_env_s:.1f} s, RSS +{rss_after_make - rss_before} KiB")

    # Random actions in the action space, generated before any timing.
    # VMAS's own sampler draws uniform(-u_range, u_range) per action component.
    n_sets = args.action_sets
    action_sets = [env.get_random_actions() for _ in range(n_sets)]
    obs_dim = int(env.observation_space[0].shape[0])
    act_dim = int(env.action_space[0].shape[0])
    u_range = float(env.agents[0].u_range)

    # Warmup: the first step also tells how long one step takes, which sets
    # the number of timed steps per repeat (at least --min-time seconds).
    # A warmup step slower than --min-time already amortises any first-call
    # cost, so very slow sizes stop warming up after one step.
    warm_times = []
    for i in range(max(args.warmup, 1)):
        t0 = time.perf_counter()
        out = env.step(action_sets[i % n_sets])
        warm_times.append(time.perf_counter() - t0)
        progress(f"warmup step {i + 1} took {warm_times[-1]:.2f} s")
        if warm_times[-1] > args.min_time:
            break
    warm_s = min(warm_times)  # least disturbed by other load on the machine
    steps = args.steps or max(1, min(args.max_steps, int(args.min_time / max(warm_s, 1e-9)) + 1))

    times = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        for i in range(steps):
            out = env.step(action_sets[i % n_sets])
        times.append(time.perf_counter() - t0)
        progress(f"repeat {len(times)} ({steps} steps) took {times[-1]:.2f} s")
    obs = out[0]
    assert len(obs) == n_agents and tuple(obs[0].shape) == (num_envs, obs_dim)
    rss_end = rss_kib()

    med = statistics.median(times)
    rate = [num_envs * n_agents * steps / t for t in times]
    print(
        json.dumps(
            {
                "num_envs": num_envs,
                "n_agents": n_agents,
                "status": "ok",
                "steps_per_repeat": steps,
                "repeats": args.repeats,
                "warmup_steps": len(warm_times),
                "warmup_seconds": warm_times,
                "repeat_seconds": times,
                "median_seconds": med,
                "agent_steps_per_second_median": num_envs * n_agents * steps / med,
                "agent_steps_per_second_min": min(rate),
                "agent_steps_per_second_max": max(rate),
                "env_steps_per_second_median": num_envs * steps / med,
                "make_env_seconds": make_env_s,
                "rss_before_make_env_kib": rss_before,
                "rss_after_make_env_kib": rss_after_make,
                "rss_end_kib": rss_end,
                "rss_increase_per_env_kib": (rss_after_make - rss_before) / num_envs,
                "rss_increase_per_agent_kib": (rss_after_make - rss_before)
                / (num_envs * n_agents),
                "obs_dim": obs_dim,
                "action_dim": act_dim,
                "u_range": u_range,
                "n_entities": len(env.world.entities),
                "scenario_kwargs": scenario_kwargs,
            }
        ),
        flush=True,
    )


# --------------------------------------------------------------------------
# Driver: spawns one worker per size, enforces wall-clock and RSS limits.
# --------------------------------------------------------------------------
def run_size(args: argparse.Namespace, num_envs: int, n_agents: int) -> dict:
    cmd = [
        sys.executable,
        os.path.abspath(__file__),
        "--worker",
        f"{num_envs}x{n_agents}",
        "--repeats",
        str(args.repeats),
        "--warmup",
        str(args.warmup),
        "--steps",
        str(args.steps),
        "--min-time",
        str(args.min_time),
        "--max-steps",
        str(args.max_steps),
        "--threads",
        str(args.threads),
        "--seed",
        str(args.seed),
        "--action-sets",
        str(args.action_sets),
        "--min-dist",
        args.min_dist,
    ]
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads), MKL_NUM_THREADS=str(args.threads))
    start = time.perf_counter()
    load_before = read_loadavg()
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
        start_new_session=True,
    )
    peak = 0
    reason = None
    while proc.poll() is None:
        try:
            peak = max(peak, rss_kib(proc.pid))
        except (FileNotFoundError, RuntimeError, ProcessLookupError):
            pass
        elapsed = time.perf_counter() - start
        if elapsed > args.budget:
            reason = f"exceeded the wall-clock budget of {args.budget:.0f} s"
        elif peak > args.max_rss_mib * 1024:
            reason = f"exceeded the RSS ceiling of {args.max_rss_mib} MiB"
        if reason:
            os.killpg(proc.pid, signal.SIGKILL)
            break
        time.sleep(0.5)
    stdout, stderr = proc.communicate()
    elapsed = time.perf_counter() - start
    scenario_kwargs = {"n_agents": n_agents}
    min_dist = spawn_min_dist(args.min_dist, n_agents)
    if min_dist is not None:
        scenario_kwargs["min_dist_between_entities"] = min_dist
    base = {
        "num_envs": num_envs,
        "n_agents": n_agents,
        "scenario_kwargs": scenario_kwargs,
        "wall_seconds": elapsed,
        "peak_rss_kib_sampled": peak,
        "loadavg_before": load_before,
        "loadavg_after": read_loadavg(),
    }
    if reason is None and proc.returncode == 0:
        result = json.loads(stdout.strip().splitlines()[-1])
        result.update(base)
        return result
    lines = stderr.strip().splitlines()
    if reason is None:
        reason = f"worker exited with code {proc.returncode}: {' | '.join(lines[-3:])}"
    progress_lines = [x for x in lines if x.startswith(("make_env", "warmup", "repeat"))]
    base.update(
        status="failed",
        reason=reason,
        last_progress=progress_lines[-1] if progress_lines else "make_env not finished",
    )
    return base


def print_table(results: list[dict]) -> None:
    head = f"{'envs':>6} {'agents':>7} {'steps':>6} {'agent-steps/s (median)':>23} {'min..max':>23} {'RSS/env':>12} {'status'}"
    print(head)
    print("-" * len(head))
    for r in results:
        if r["status"] == "ok":
            print(
                f"{r['num_envs']:>6} {r['n_agents']:>7} {r['steps_per_repeat']:>6} "
                f"{r['agent_steps_per_second_median']:>23,.0f} "
                f"{r['agent_steps_per_second_min']:>11,.0f}..{r['agent_steps_per_second_max']:<10,.0f} "
                f"{r['rss_increase_per_env_kib'] / 1024:>8.3f} MiB ok"
            )
        else:
            print(f"{r['num_envs']:>6} {r['n_agents']:>7} {'-':>6} {'-':>23} {'-':>23} {'-':>12} {r['reason']}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", default="1024x10,64x100,1x10000", help="comma-separated NUM_ENVSxN_AGENTS")
    p.add_argument("--repeats", type=int, default=5, help="timed repeats; the median is reported")
    p.add_argument("--warmup", type=int, default=3, help="untimed steps before timing (stops after one step slower than --min-time)")
    p.add_argument("--steps", type=int, default=0, help="timed steps per repeat (0: choose from --min-time)")
    p.add_argument("--min-time", type=float, default=2.0, help="target seconds per repeat when --steps is 0")
    p.add_argument("--max-steps", type=int, default=1000, help="cap on steps per repeat when --steps is 0")
    p.add_argument("--threads", type=int, default=2, help="torch.set_num_threads value")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--action-sets", type=int, default=8, help="distinct pre-generated random action sets, cycled")
    p.add_argument("--min-dist", default="auto",
                   help="scenario kwarg min_dist_between_entities: 'default' (0.15), 'auto' "
                   "(default up to 100 agents, else a spacing that can be packed) or a number")
    p.add_argument("--budget", type=float, default=300.0, help="wall-clock seconds allowed per size")
    p.add_argument("--max-rss-mib", type=int, default=8192, help="RSS ceiling per size (MiB)")
    p.add_argument("--fallback-agents", default="1000,2000,5000",
                   help="agent counts tried (ascending) when a 1xN size fails; empty to disable")
    p.add_argument("--json", default=None, help="write results to this JSON file (refuses to overwrite)")
    p.add_argument("--worker", default=None, help=argparse.SUPPRESS)
    args = p.parse_args()

    if args.worker:
        run_worker(args)
        return

    sizes = parse_sizes(args.sizes)
    if args.json and os.path.exists(args.json):
        fail(f"--json {args.json!r} exists; choose another path or move it away first")
    fallback = [int(n) for n in args.fallback_agents.split(",") if n.strip()]

    import torch
    from importlib.metadata import version

    meta = {
        "vmas_version": version("vmas"),
        "torch_version": torch.__version__,
        "python": platform.python_version(),
        "machine": platform.machine(),
        "cpu_count": os.cpu_count(),
        "torch_threads": args.threads,
        "device": "cpu",
        "scenario": "flocking",
        "scenario_kwargs": "n_agents (per size; see results[].scenario_kwargs); defaults "
        "n_obstacles=5, n_lidar_rays=12, collision_reward=-0.1, dist_shaping_factor=1, "
        f"min_dist_between_entities=0.15 unless --min-dist ({args.min_dist}) overrides it",
        "make_env_kwargs": {"continuous_actions": True, "device": "cpu", "seed": args.seed},
        "command": shlex.join(["python"] + sys.argv),
        "loadavg_before": read_loadavg(),
        "started_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
    results = []
    for num_envs, n_agents in sizes:
        r = run_size(args, num_envs, n_agents)
        results.append(r)
        print(json.dumps(r), file=sys.stderr, flush=True)
        if r["status"] != "ok" and num_envs == 1:
            for n in sorted(x for x in fallback if x < n_agents):
                fr = run_size(args, 1, n)
                fr["fallback_for"] = f"1x{n_agents}"
                results.append(fr)
                print(json.dumps(fr), file=sys.stderr, flush=True)
                if fr["status"] != "ok":
                    break
    meta["loadavg_after"] = read_loadavg()
    meta["finished_utc"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    print_table(results)
    if args.json:
        with open(args.json, "x") as f:
            json.dump({"meta": meta, "results": results}, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
