"""examples/python/learn_to_flock.py on a tiny budget: it trains, compares with Algorithm 2 on
held-out flocks, writes its figure, and the learned policy run through ``flocking.run`` as a
``flocking.Local`` controller is the env's rollout bit for bit (its numpy observation rows are the
env's)."""

import sys

import numpy as np
import pytest

import flocking
from conftest import FIXTURES, ROOT
from flocking.env import FlockVectorEnv

pytest.importorskip("matplotlib")
sys.path.insert(0, str(ROOT / "examples" / "python"))
import learn_to_flock  # noqa: E402


@pytest.fixture
def at_root(monkeypatch):
    """The example runs from the repository root (its fixture path is relative to it)."""
    monkeypatch.chdir(ROOT)


def test_the_example_trains_compares_and_plots(tmp_path, at_root, capsys):
    out = tmp_path / "learned.png"
    result = learn_to_flock.main(
        ["--generations", "2", "--population", "4", "--duration", "0.3", "--agents", "12",
         "--held-out", "2", "--out", str(out)]
    )
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    history = result["history"]
    for key in ("mean", "best", "algorithm2"):
        assert history[key].shape == (2,) and np.isfinite(history[key]).all()
    assert (history["best"] >= history["mean"]).all()
    assert np.isfinite(result["theta"]).all()
    rows = {row["policy"]: row for row in result["rows"]}
    assert set(rows) == {"learned (ES)", "Algorithm 2"}
    for row in rows.values():
        assert row["same_as_env"] is True
        assert np.isfinite([row["reward"], row["deviation_energy"], row["connectivity"]]).all()
        assert 0.0 <= row["connectivity"] <= 1.0
    printed = capsys.readouterr().out
    assert "learned (ES)" in printed and "Algorithm 2" in printed


def near_a_ball():
    """Algorithm 3 in 3D, 30 agents starting 0.5–7.5 m above the fixture's ball obstacle (centre
    (165, 5, 15), radius 8), under 10 % loss: agents that see a β-agent and agents that do not."""
    return flocking.Scenario.load(FIXTURES / "alg3_3d_mixed_obstacles_n100.ron").with_values(
        {
            "agents": 30,
            "duration": 0.5,
            "initial.positions.Ball.centre": [165.0, 5.0, 27.0],
            "initial.positions.Ball.radius": 3.5,
            "conditions.communication.loss": learn_to_flock.LOSS,
        }
    )


@pytest.mark.parametrize(
    "make, padded, sees_beta",
    [
        (lambda: learn_to_flock.task(agents=12, duration=0.5), True, False),
        (near_a_ball, False, True),
    ],
    ids=["fig11-task-2d", "alg3-3d-beta"],
)
def test_the_observation_rows_of_a_perception_are_the_envs(at_root, make, padded, sees_beta):
    """Policy.rows rebuilds the env's layout from a Perception: every row of every control update
    equal to the env's observation, bit for bit, under packet loss, a random policy acting: in 2D
    with rows padded, and in 3D with more agents heard than observed and β-agents."""
    scenario = make().with_values({"seed": 3})
    n = scenario.agents
    env = FlockVectorEnv(scenario, 1, seed=3, neighbours=learn_to_flock.NEIGHBOURS)
    policy = learn_to_flock.Policy(env.layout, scenario.dim, scenario.value("alpha")["d"])
    noise = np.random.default_rng(2).standard_normal(policy.parameters)
    theta = policy.initial(np.random.default_rng(1)) + 0.3 * noise  # W₂ ≠ 0: the inputs act
    seen = []

    def controller(t, perception):
        rows = policy.rows(perception)
        seen.append(rows)
        return policy.act(theta[None], rows[None])[0]

    flocking.run(scenario, trajectory=False, controls=flocking.Local(controller))
    obs, _ = env.reset(seed=3)
    for rows in seen:
        assert np.array_equal(rows, obs[0])
        obs, _, _, truncated, _ = env.step(policy.act(theta[None], obs[:1].copy()))
        if truncated[0]:
            break
    dim = scenario.dim
    assert len(seen) == 50 and obs.shape == (1, n, 5 * dim + 2 + 6 * (2 * dim + 1))
    start, k = env.layout["neighbour_mask"]
    heard = np.array([rows[:, start : start + k].sum(axis=1) for rows in seen])
    assert heard.max() == k and (heard.min() < k) == padded  # 2D pads rows, the dense 3D cloud not
    assert all((rows[:, env.layout["gamma_mask"][0]] == 1.0).all() for rows in seen)
    beta = np.array([rows[:, env.layout["beta_mask"][0]] for rows in seen])
    assert (0.0 < beta.mean() < 1.0) if sees_beta else not beta.any()
