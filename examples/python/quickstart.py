"""flocking from Python: load TAC 2006 Fig. 11, run it, and plot the four metric panels of TAC 2006
Fig. 18 (connectivity C, cohesion radius R, deviation energy Ẽ, velocity mismatch K̃).

    pip install ./crates/flock-py matplotlib
    python examples/python/quickstart.py            # writes fig11_metrics.png

matplotlib is optional: without it the script prints the final metrics only.
"""

import sys
from pathlib import Path

import flocking

ROOT = Path(__file__).resolve().parents[2]


def main(out: str = "fig11_metrics.png") -> None:
    scenario = flocking.Scenario.load(ROOT / "fixtures" / "tac2006_fig11_alg2_n100.ron")
    result = flocking.run(scenario)  # the bits of `flocking run`, as numpy arrays
    m = result.metrics
    print(f"{scenario.name}: {scenario.agents} agents, {scenario.steps} steps")
    for name in ("connectivity", "cohesion_radius", "deviation_energy", "velocity_mismatch"):
        print(f"  {name:18} {m[name][-1]:.4g}")
    print(f"  final positions    {result.final.positions.shape}")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure (pip install matplotlib)")
        return

    panels = [
        ("connectivity", "connectivity C(t)", "linear"),
        ("cohesion_radius", "cohesion radius R(t)", "linear"),
        ("deviation_energy", "relative deviation energy Ẽ(t)", "log"),
        ("velocity_mismatch", "relative velocity mismatch K̃(t)", "log"),
    ]
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    for ax, (column, title, scale) in zip(axes.flat, panels):
        values = m[column]
        keep = values > 0 if scale == "log" else slice(None)
        ax.plot(m["t"][keep], values[keep])
        ax.set_yscale(scale)
        ax.set_title(title)
        ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("t (s)")
    fig.suptitle(f"{scenario.name} (TAC 2006 Fig. 18)")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"figure: {out}")


if __name__ == "__main__":
    main(*sys.argv[1:])
