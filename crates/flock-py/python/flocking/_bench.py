"""``flocking.bench``: the benchmark of ``flocking bench`` (docs/performance.md) from Python."""

from typing import Optional, Sequence, Tuple, Union

from . import _flocking
from ._flocking import BenchReport, WorkloadReport


def bench(
    n: Optional[int] = None,
    dim: Optional[int] = None,
    steps: Optional[int] = None,
    *,
    algorithm: Union[None, int, str] = None,
    threads: Optional[int] = None,
    warmup: Optional[int] = None,
    shuffled: Optional[bool] = None,
    delay: Optional[float] = None,
    delayed: Optional[str] = None,
    loss: Optional[float] = None,
    sensing_noise: Union[None, float, Tuple[float, float], Sequence[float]] = None,
    control_rate: Optional[float] = None,
    max_acceleration: Optional[float] = None,
    vehicle: Optional[str] = None,
    workload: Optional[str] = None,
    seeds: Optional[int] = None,
    scale_to: Optional[int] = None,
) -> Union[BenchReport, WorkloadReport]:
    """Times the simulation loop exactly as ``flocking bench`` does, its flags as keywords
    (``--sensing-noise`` is ``sensing_noise``; one number gives σ_q and σ_p), and returns the
    report: ``str(report)`` is what the command prints, its figures are attributes
    (``agent_steps_per_second``, ``bytes_per_agent``, ``ms_per_step``, …).

    ``workload="boids-small"`` or ``"boids-large"`` times the ABM frameworks' boids benchmark
    instead, and ``"vicsek"`` the Vicsek model at its paper's density (``seeds``, ``scale_to``);
    either returns a :class:`WorkloadReport` (the keywords of the α-lattice do not apply to it and
    are refused). ``threads`` runs on a pool of that many workers (default: all cores).
    ``peak_memory`` is the interpreter's whole process. The defaults are the command's (n =
    100,000 in 2D, 20 steps after 3 of warm-up, Algorithm 2; 10 seeds of a workload). Invalid
    values raise ``ValueError`` naming the keyword; a benchmark whose estimate does not fit in
    this machine's memory raises ``MemoryError`` before it starts; Ctrl-C raises
    ``KeyboardInterrupt`` within a second.
    """
    if sensing_noise is not None and not isinstance(sensing_noise, (tuple, list)):
        sensing_noise = (sensing_noise, sensing_noise)
    if sensing_noise is not None and len(sensing_noise) != 2:
        raise ValueError(
            f"sensing_noise={sensing_noise!r}: give one standard deviation or two (sigma_q, sigma_p)"
        )
    return _flocking.bench(
        n,
        dim,
        steps,
        algorithm=None if algorithm is None else str(algorithm),
        threads=threads,
        warmup=warmup,
        shuffled=shuffled,
        delay=delay,
        delayed=delayed,
        loss=loss,
        sensing_noise=None if sensing_noise is None else tuple(float(s) for s in sensing_noise),
        control_rate=control_rate,
        max_acceleration=max_acceleration,
        vehicle=vehicle,
        workload=workload,
        seeds=seeds,
        scale_to=scale_to,
    )
