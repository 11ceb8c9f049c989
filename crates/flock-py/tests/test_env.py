"""flocking.env and controls=Local: PettingZoo's and Gymnasium's own checkers pass; the scenario's
protocol through the environment gives the CLI's run bit for bit (Fig. 11, ideal and with delay +
loss + noise); flock k of a batch of 8 is the flock alone; TAC 2006 Algorithm 2 written as a local
numpy controller has the built-in's bits ideal and under conditions; bad actions, rewards and
controllers are refused by name; Ctrl-C during a rollout leaves the environment usable."""

import sys

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")
pettingzoo = pytest.importorskip("pettingzoo")

import flocking  # noqa: E402
from conftest import FIG11, ROOT, cli_run  # noqa: E402
from flocking.env import FlockEnv, FlockParallelEnv, FlockVectorEnv  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402
from pettingzoo.test import parallel_api_test  # noqa: E402

sys.path.insert(0, str(ROOT / "examples" / "python"))
from algorithm2_local import CONDITIONS, LocalAlgorithm2  # noqa: E402


def fig11(duration: float, conditions: dict = {}) -> flocking.Scenario:  # noqa: B006
    return flocking.Scenario.load(FIG11).with_values({"duration": duration, **conditions})


def test_pettingzoo_parallel_api_test_passes_ideal_and_under_conditions():
    parallel_api_test(FlockParallelEnv(fig11(0.5)), num_cycles=60)
    parallel_api_test(FlockParallelEnv(fig11(0.5, CONDITIONS)), num_cycles=60)


def test_gymnasium_check_env_passes():
    check_env(FlockEnv(fig11(0.5)), skip_render_check=True)
    check_env(FlockEnv(fig11(0.5, CONDITIONS)), skip_render_check=True)


def rollout_final(scenario: flocking.Scenario) -> tuple:
    """The final state of a rollout of the scenario's protocol through a one-flock environment."""
    env = FlockVectorEnv(scenario, 1)
    env.reset(seed=scenario.seed)
    steps = 0
    while True:
        _, _, terminated, truncated, _ = env.step(env.baseline_action())
        steps += 1
        assert not terminated[0]
        if truncated[0]:
            break
    state = env.states()
    return state["positions"][0], state["velocities"][0], steps


@pytest.mark.parametrize("conditions", [{}, CONDITIONS], ids=["ideal", "delay+loss+noise"])
def test_the_baseline_rollout_is_the_cli_run_bit_for_bit(tmp_path, conditions):
    scenario = fig11(3.0, conditions)
    q, p, steps = rollout_final(scenario)
    sampled = "conditions.control.rate" in conditions
    assert steps == (150 if sampled else 300)  # one environment step per control period
    cli = flocking.read_run(cli_run(scenario, tmp_path / "cli", "--trajectory-format", "npy"))
    assert cli.final.t == 3.0
    assert np.array_equal(q, cli.final.positions) and np.array_equal(p, cli.final.velocities)


def batch_rollout(num_envs: int, seed: int, steps: int = 15):
    scenario = fig11(1.0, CONDITIONS)
    env = FlockVectorEnv(scenario, num_envs, seed=seed)
    obs, _ = env.reset(seed=seed)
    frames = [obs.copy()]
    pattern = np.linspace(-1.0, 1.0, scenario.agents * 2).reshape(scenario.agents, 2)
    for _ in range(steps):
        obs, rewards, *_ = env.step(np.broadcast_to(pattern, env.action_space.shape))
        frames.append(np.concatenate([obs.reshape(num_envs, -1), rewards], axis=1))
    return frames


def test_flock_k_of_a_batch_of_8_is_the_flock_alone():
    batch = batch_rollout(8, 100)
    alone = batch_rollout(1, 105)
    for b, a in zip(batch, alone):
        assert np.array_equal(b[5], a[0])
    assert not np.array_equal(batch[0][0], batch[0][1]), "two seeds, two starts"


def test_next_step_autoreset_and_reset_by_seed():
    env = FlockVectorEnv(fig11(0.05), 2)
    assert env.metadata["autoreset_mode"] == gymnasium.vector.AutoresetMode.NEXT_STEP
    first = env.reset(seed=3)[0].copy()
    zeros = np.zeros(env.action_space.shape)
    ends = [env.step(zeros) for _ in range(6)]
    assert [bool(e[3][0]) for e in ends] == [False, False, False, False, True, False]
    assert [bool(e[4]["reset"][0]) for e in ends] == [False] * 5 + [True]
    assert np.array_equal(env.reset(seed=3)[0], first)


def test_local_numpy_algorithm2_has_the_bits_of_the_builtin_ideal_and_under_conditions():
    for conditions in ({}, CONDITIONS):
        scenario = fig11(10.0, conditions)
        builtin = flocking.run(scenario, trajectory=False)
        local = flocking.run(
            scenario, trajectory=False, controls=flocking.Local(LocalAlgorithm2(scenario))
        )
        assert np.array_equal(builtin.final.positions, local.final.positions), conditions
        assert np.array_equal(builtin.final.velocities, local.final.velocities), conditions


def test_the_local_controller_sees_what_each_agent_perceives():
    seen = []

    def record(t, perception):
        seen.append(perception)
        return np.zeros_like(perception.positions)

    scenario = fig11(0.02)
    flocking.run(scenario, controls=flocking.Local(record))
    perception = seen[0]
    n = scenario.agents
    assert len(perception) == n and perception.positions.shape == (n, 2)
    assert perception.indptr.shape == (n + 1,) and perception.indptr[-1] == len(perception.neighbours)
    start = flocking.Simulation(scenario)
    q = start.q
    i = int(np.argmax(np.diff(perception.indptr)))
    js = perception.neighbours[perception.indptr[i] : perception.indptr[i + 1]]
    assert len(js) > 0 and list(js) == sorted(js)
    dq = perception.relative_positions[perception.indptr[i] : perception.indptr[i + 1]]
    assert np.array_equal(dq, q[js] - q[i])
    assert np.all(perception.heard_by[perception.indptr[i] : perception.indptr[i + 1]] == i)
    assert np.array_equal(perception.gamma_position, [0.0, 0.0])
    assert np.array_equal(perception.gamma_velocity, [1.0, 0.5])


def test_a_local_controller_of_the_wrong_shape_is_a_controls_error(tmp_path):
    scenario = fig11(0.1, CONDITIONS)
    with pytest.raises(flocking.ControlsError, match=r"shape \(3,\)"):
        flocking.run(scenario, controls=flocking.Local(lambda t, per: np.zeros(3)))


def test_bad_actions_are_refused_naming_the_environment_agent_and_field():
    env = FlockVectorEnv(fig11(0.5), 2)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(2, 100\); expected \(2, 100, 2\)"):
        env.step(np.zeros((2, 100)))
    with pytest.raises(ValueError, match="dtype complex128"):
        env.step(np.zeros((2, 100, 2), dtype=complex))
    actions = np.zeros((2, 100, 2))
    actions[1, 42, 0] = np.nan
    with pytest.raises(ValueError, match=r"actions\[1, 42, 0\] = NaN .*environment 1, agent 42"):
        env.step(actions)
    actions[1, 42, 0] = 0.0
    env.step(actions)  # nothing was stepped by the refused calls; the env goes on


def test_a_reward_function_is_checked():
    def raises(state):
        raise KeyError("boom")

    env = FlockVectorEnv(fig11(0.5), 2, reward=raises)
    env.reset(seed=0)
    with pytest.raises(RuntimeError, match="reward function raised"):
        env.step(env.baseline_action())
    env = FlockVectorEnv(fig11(0.5), 2, reward=lambda s: np.zeros(3))
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(3,\); expected \(2, 100\)"):
        env.step(env.baseline_action())
    speed = FlockVectorEnv(fig11(0.5), 2, reward=lambda s: np.linalg.norm(s["velocities"], axis=2))
    speed.reset(seed=0)
    _, rewards, *_ = speed.step(speed.baseline_action())
    assert np.allclose(rewards, np.linalg.norm(speed.states()["velocities"], axis=2))
    with pytest.raises(ValueError, match="unknown terms"):
        FlockVectorEnv(fig11(0.5), reward_weights={"speed": 1.0})


def test_the_default_reward_penalises_collisions():
    """Two agents of Fig. 11 placed 0.5 apart (d_c = 1.75): each is penalised w_C = 1 more than
    the same pair 3.5 apart (both within r, the same other terms but the deviation)."""
    weights = {"deviation": 0.0, "mismatch": 0.0, "gamma": 0.0, "collision": 1.0}
    env = FlockVectorEnv(fig11(0.5), 1, reward_weights=weights)
    env.reset(seed=0)
    _, rewards, *_ = env.step(np.zeros(env.action_space.shape))
    q = env.states()["positions"][0]
    d = np.linalg.norm(q[:, None] - q[None], axis=2)
    np.fill_diagonal(d, np.inf)
    assert np.array_equal(-rewards[0], (d < 1.75).sum(axis=1).astype(float))


def test_ctrl_c_during_a_rollout_leaves_the_environment_usable():
    env = FlockVectorEnv(fig11(1.0), 4)
    env.reset(seed=0)
    with pytest.raises(KeyboardInterrupt):
        for k in range(50):
            env.step(env.baseline_action())
            if k == 10:
                raise KeyboardInterrupt
    obs, rewards, *_ = env.step(env.baseline_action())
    assert np.all(np.isfinite(obs)) and np.all(np.isfinite(rewards))


def test_rgb_array_renders_the_flock_as_the_snapshots_do():
    env = FlockEnv(fig11(0.5), render_mode="rgb_array")
    check_env(env)  # with its render check
    env.reset(seed=1)
    first = env.render()
    assert first.shape == (480, 640, 3) and first.dtype == np.uint8
    for _ in range(30):
        env.step(env.baseline_action())
    assert not np.array_equal(env.render(), first)
    vec = FlockVectorEnv(fig11(0.5), 2)
    vec.reset(seed=1)
    assert np.array_equal(vec.render(0), first)
    assert not np.array_equal(vec.render(1), first), "flock 1 starts elsewhere"
    with pytest.raises(ValueError, match="rgb_array"):
        FlockEnv(fig11(0.5), render_mode="human")


@pytest.mark.parametrize(
    "fixture",
    [
        "unicycle_alg2_n50",
        "crazyflie_alg2_3d_n50",
        "alg3_3d_mixed_obstacles_n100",
        "vicsek1995_fig2a_n400",
        "boids_small_n200",
        "tanner2003_fig3_fixed_n10",
    ],
)
def test_every_model_and_vehicle_through_the_environment_is_its_run(fixture):
    """Vehicles (a unicycle, a quadrotor), Algorithm 3's β-agents in 3D, the velocity models and a
    fixed graph: the baseline through the environment gives ``flocking.run``'s final bits."""
    scenario = flocking.Scenario.load(FIG11.parent / f"{fixture}.ron")
    scenario = scenario.with_values({"duration": 12 * scenario.step})
    if scenario.value("integrator") == "Rk4":
        # the ideal loop's RK4 evaluates the protocol at its later stages: refused for a policy
        with pytest.raises(flocking.ScenarioError, match="integrator") as refused:
            FlockVectorEnv(scenario, 1)
        assert refused.value.field == "integrator"
        scenario = scenario.with_values({"integrator": "SymplecticEuler"})
    q, p, _ = rollout_final(scenario)
    run = flocking.run(scenario, trajectory=False)
    assert np.array_equal(q, run.final.positions) and np.array_equal(p, run.final.velocities)


def test_the_observation_holds_the_nearest_beta_agent_when_an_obstacle_is_near():
    scenario = flocking.Scenario.load(FIG11.parent / "alg3_3d_mixed_obstacles_n100.ron")
    env = FlockVectorEnv(scenario, 1)
    obs, _ = env.reset(seed=scenario.seed)
    start, length = env.layout["beta"]
    mask = env.layout["beta_mask"][0]
    for _ in range(3000):
        if obs[0, :, mask].any():
            break
        obs, *_ = env.step(env.baseline_action())
    near = obs[0, :, mask] == 1.0
    assert near.any(), "the flock reaches an obstacle"
    beta = obs[0, near, start : start + length]
    # q̂ − q_i nonzero and within r′ (TAC 2006 § VII, r′ below the interaction range r = 1.2 d)
    distances = np.linalg.norm(beta[:, :3], axis=1)
    assert np.all(distances > 0) and np.all(distances < float(scenario.value("alpha.d")) * 1.2)
    assert not obs[0, ~near, start : start + length].any(), "zeros without a β-agent"
