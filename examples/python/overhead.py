"""The cost of Python around flocking: `flocking run` (the release CLI) against `flocking.run` in a fresh
`python` process on the same scenario, alternately, and `Simulation.step(1000)` against the CLI's
agent-steps/s.

    python examples/python/overhead.py [--cli target/release/flocking] [--repeat 5]

Scenarios: TAC 2006 Fig. 11 (n = 100, 10,000 steps, CSV trajectory) and n = 10⁵ agents of
Algorithm 2 in 2D (uniform in a box at about one agent per d², 50 steps, `.npy` trajectory).
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import flocking

ROOT = Path(__file__).resolve().parents[2]


def big(n: int, steps: int) -> flocking.Scenario:
    """n agents of Algorithm 2 in 2D, uniform in a box of about one agent per d²."""
    half = (n**0.5) * 7.0 / 2
    scenario = flocking.Scenario.load(ROOT / "fixtures" / "tac2006_fig11_alg2_n100.ron")
    return scenario.with_values(
        {
            "name": f"alg2_2d_n{n}",
            "agents": n,
            "initial.positions": {"Box": {"min": [-half, -half], "max": [half, half]}},
            "duration": steps * scenario.step,
            "record_every": 10,
        }
    )


def timed(command):
    """The wall time of ``command`` and what it printed."""
    start = time.perf_counter()
    done = subprocess.run(command, check=True, capture_output=True, text=True)
    return time.perf_counter() - start, done.stdout


def compare(cli: str, path: Path, out: Path, fmt: str, repeat: int) -> None:
    cli_cmd = [cli, "run", str(path), "--out", str(out / "cli"), "--force", "--quiet",
               "--trajectory-format", fmt]
    py_code = (
        "import time, flocking; s = flocking.Scenario.load({!r}); start = time.perf_counter(); "
        "flocking.run(s, out={!r}, force=True, trajectory_format={!r}, trajectory={}); "
        "print(time.perf_counter() - start)"
    )
    py_cmd = [sys.executable, "-c", py_code.format(str(path), str(out / "py"), fmt, True)]
    lean_cmd = [sys.executable, "-c", py_code.format(str(path), str(out / "lean"), fmt, False)]
    cli_times, py_times, call_times, lean_times, import_times = [], [], [], [], []
    for _ in range(repeat):
        cli_times.append(timed(cli_cmd)[0])
        wall, printed = timed(py_cmd)
        py_times.append(wall)
        call_times.append(float(printed))
        lean_times.append(float(timed(lean_cmd)[1]))
        import_times.append(timed([sys.executable, "-c", "import flocking"])[0])
    same = all(
        (out / "cli" / f).read_bytes() == (out / "py" / f).read_bytes()
        for f in ("metrics.csv", "final.csv", f"trajectory.{fmt}")
    )
    c, p, call, lean, imp = (
        min(x) for x in (cli_times, py_times, call_times, lean_times, import_times)
    )
    median = lambda x: sorted(x)[repeat // 2]  # noqa: E731
    print(f"{path.stem} (best of {repeat}; medians in brackets), identical outputs: {same}")
    print(f"  flocking run (process)              {c:.3f} s [{median(cli_times):.3f}]")
    print(f"  python -c flocking.run (process)    {p:.3f} s [{median(py_times):.3f}]"
          f"  ratio {p / c:.3f} [{median(py_times) / median(cli_times):.3f}]")
    print(f"  of which `python -c 'import flocking'` {imp:.3f} s; flocking.run call {call:.3f} s"
          f"  ratio call / CLI process {call / c:.3f} [{median(call_times) / median(cli_times):.3f}]")
    print(f"  flocking.run(..., trajectory=False) call {lean:.3f} s  ratio {lean / c:.3f} "
          f"[{median(lean_times) / median(cli_times):.3f}] (the trajectory not kept in memory)")


def stepping(cli: str, scenario: flocking.Scenario, work: Path, repeat: int, steps: int = 1000):
    """Best of ``repeat``: `Simulation.step(steps)` and `flocking run` of those steps, alternately."""
    scenario = scenario.with_values({"duration": steps * scenario.step, "record_every": steps})
    path = work / f"{scenario.name}_steps.ron"
    path.write_text(scenario.to_ron())
    command = [cli, "run", str(path), "--out", str(work / "step-cli"), "--force", "--quiet"]
    cli_rate = rate = 0.0
    for _ in range(repeat):
        printed = timed(command)[1]
        found = re.search(r"\(([0-9.e+]+) agent-steps/s\)", printed)
        cli_rate = max(cli_rate, float(found.group(1)))
        sim = flocking.Simulation(scenario)
        start = time.perf_counter()
        sim.step(steps)
        rate = max(rate, scenario.agents * steps / (time.perf_counter() - start))
    print(f"{scenario.name}: Simulation.step({steps}) {rate:.3e} agent-steps/s, "
          f"flocking run {cli_rate:.3e} agent-steps/s (best of {repeat}), ratio {rate / cli_rate:.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", default=str(ROOT / "target" / "release" / "flocking"))
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    print(f"load: {os.getloadavg()}")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        fig11 = ROOT / "fixtures" / "tac2006_fig11_alg2_n100.ron"
        compare(args.cli, fig11, work / "fig11", "csv", args.repeat)
        large = big(100_000, 50)
        path = work / f"{large.name}.ron"
        path.write_text(large.to_ron())
        compare(args.cli, path, work / "big", "npy", args.repeat)
        stepping(args.cli, flocking.Scenario.load(fig11), work, args.repeat)
        stepping(args.cli, big(10_000, 1000), work, args.repeat)
    print(f"load: {os.getloadavg()}")


if __name__ == "__main__":
    main()
