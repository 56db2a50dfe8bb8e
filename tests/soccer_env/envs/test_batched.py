"""The batched Goalkeeper (``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")``):
the same episodes as single environments seeded ``seed + k``, through episode ends and
autoresets; Gymnasium's vector API; bad input."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401
from soccer_env.envs.batched import GoalkeeperVectorEnv

GK = "soccer_env/Goalkeeper-v0"


def _compare(kwargs: dict, n: int, steps: int, seed: int, keeper_actions: str,
             env_id: str = GK) -> tuple[int, float]:
    """Step a batch and ``n`` single environments with the same actions; return how many
    episodes ended and the share of observations equal bit for bit. Terminations,
    truncations and outcomes must agree exactly, observations and rewards to 1e-3: the
    batch's worlds lie on patches of one space, whose offset coordinates round differently
    (about 1e-12 m), and a contact between keeper and ball can amplify that within an
    episode."""
    vec = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", **kwargs)
    singles = [gym.make(env_id, **kwargs) for _ in range(n)]
    obs, _ = vec.reset(seed=seed)
    expected = np.stack([e.reset(seed=seed + k)[0] for k, e in enumerate(singles)])
    np.testing.assert_array_equal(obs, expected)
    rng = np.random.default_rng(seed)
    pending, ends, exact = [False] * n, 0, 0
    for t in range(steps):
        if keeper_actions == "random":
            a = rng.uniform(-1, 1, (n, 6)).astype(np.float32)
        elif keeper_actions == "attack":  # forward at the ball, kicking now and then
            a = rng.uniform(-0.05, 0.05, (n, 6)).astype(np.float32)
            a[:, 0] = rng.uniform(0.3, 1.0, n)
            a[:, 3] = rng.random(n) < 0.3
        else:  # drive about, no kicker or dribbler
            a = np.zeros((n, 6), np.float32)
            a[:, :3] = rng.uniform(-1, 1, (n, 3))
        obs, rewards, terminated, truncated, info = vec.step(a)
        for k, e in enumerate(singles):
            if pending[k]:  # Gymnasium's next-step autoreset: the new episode's first obs
                o, (r, te, tr) = e.reset()[0], (0.0, False, False)
                i = {}
            else:
                o, r, te, tr, i = e.step(a[k])
            pending[k] = te or tr
            np.testing.assert_allclose(obs[k], o, atol=1e-3, err_msg=f"step {t}, env {k}")
            exact += bool(np.array_equal(obs[k], o))
            assert (terminated[k], truncated[k]) == (te, tr), (t, k)
            assert rewards[k] == pytest.approx(r, abs=1e-3), (t, k)
            if te or tr:
                ends += 1
                assert info["_outcome"][k]
                assert info["outcome"][k] == i["outcome"]  # ("" at the time limit)
                if te:
                    assert info["is_success"][k] == i["is_success"]
    vec.close()
    return ends, exact / (steps * n)


@pytest.mark.parametrize("kwargs,actions", [
    ({}, "random"),
    ({"shaping": {"intercept": 2.0, "ball_distance": 0.5, "action_cost": 0.1,
                  "outside_area": 1.0}}, "drive"),
    ({"control_dt": 0.04, "field": "ssl-2012", "max_episode_steps": 120}, "random"),
])
def test_the_batch_plays_the_single_environments_episodes(kwargs, actions):
    ends, exact = _compare(kwargs, n=6, steps=500, seed=21, keeper_actions=actions)
    assert ends >= 20  # saves, goals, outs and time limits, each followed by an autoreset
    assert exact >= 0.9  # bit for bit as a rule; contacts amplify the patches' rounding


@pytest.mark.parametrize("kwargs", [
    {},
    {"shaping": {"ball_progress": 1.0, "ball_distance": 0.5, "action_cost": 0.1},
     "max_episode_steps": 150},
])
def test_the_batched_shootout_plays_the_single_environments_episodes(kwargs):
    """Shootout-v0's vector entry point: the scripted keeper over the batch, goals, saves and
    outs, the reward terms and the time limit as in single environments."""
    ends, exact = _compare(kwargs, n=6, steps=300, seed=8, keeper_actions="attack",
                           env_id="soccer_env/Shootout-v0")
    assert ends >= 12  # saves, outs, goals (and time limits), each followed by an autoreset
    assert exact >= 0.9


@pytest.mark.parametrize("env_id,kwargs,actions", [
    (GK, {"obs_mode": "perceived", "perception": "ssl-2012"}, "random"),
    (GK, {"obs_mode": "raw", "perception": "realistic", "belief_features": True}, "random"),
    (GK, {"obs_mode": "truth", "perception": "ssl-2012"}, "drive"),  # latency, no sensors
    (GK, {"obs_mode": "perceived",
          "perception": {"vision": "realistic", "randomize": {"latency": (0.02, 0.1),
                                                              "actuation_latency": (0.0, 0.06)}}},
     "random"),
    ("soccer_env/Shootout-v0", {"obs_mode": "perceived", "perception": "realistic"},
     "attack"),
    # Humanoid keepers with their three team-mates: walks, heads, falls, perception.
    (GK, {"robot": "humanoid"}, "random"),
    (GK, {"robot": "humanoid-2012", "obs_mode": "perceived"}, "random"),
    ("soccer_env/Shootout-v0", {"robot": "humanoid"}, "random"),
])
def test_the_batch_perceives_as_the_single_environments(env_id, kwargs, actions):
    """Raw and perceived observations, actuation latency and humanoids in the batch: each
    environment keeps the single environment's perception, command channels and head control
    (the same sensor draws from its own stream), fed from the batch's worlds. (A humanoid
    attacker walking at random rarely ends a shootout within 300 steps.)"""
    ends, exact = _compare(kwargs, n=4, steps=300, seed=5, keeper_actions=actions,
                           env_id=env_id)
    assert ends >= (0 if env_id != GK and "robot" in kwargs else 6)
    # Bit for bit as a rule; a walking humanoid attacker moves from the first step, and the
    # patches' rounding (1e-15 m) shows at once in observation entries near zero.
    assert exact >= (0.0 if env_id != GK and "robot" in kwargs else 0.9)


@pytest.mark.parametrize("env_id,kwargs,batched", [
    (GK, {"obs_mode": "perceived", "perception": "ssl-2012"}, True),
    (GK, {"obs_mode": "perceived", "field": "ssl-div-b",
          "perception": {"vision": "ssl-2012", "ball_filter": "ekf-2phase"}}, True),
    (GK, {"obs_mode": "perceived", "perception": {"vision": "realistic", "ball_filter": "kf"}},
     True),
    (GK, {"obs_mode": "perceived",
          "perception": {"vision": "realistic", "ball_filter": "ekf-improved"}}, True),
    ("soccer_env/Shootout-v0", {"obs_mode": "perceived", "perception": "ssl-2012"}, True),
    (GK, {"obs_mode": "perceived", "perception": "harsh"}, False),  # jitter: out of order
    (GK, {"obs_mode": "perceived", "perception": {"vision": "realistic", "ball_filter": "ls"}},
     False),
])
def test_perceived_batches_estimate_as_one_and_equal_the_single_environments(
        env_id, kwargs, batched, monkeypatch):
    """Perceived batches whose configuration allows it run one batched pipeline (the cameras
    of every field in one array pass, the filters of every environment together); the
    others keep each environment's own. Either way the episodes are the single
    environments'. (Small batches keep each environment's pipeline, which is faster there;
    the test lowers that bound to run the batched pipeline on three environments.)"""
    import soccer_env.perception.batched as perception_batch

    vec = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point", **kwargs)
    assert vec.unwrapped._senses.vision is None  # below MIN_BATCH
    vec.close()
    monkeypatch.setattr(perception_batch, "MIN_BATCH", 1)
    vec = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point", **kwargs)
    assert (vec.unwrapped._senses.vision is not None) == batched
    vec.close()
    ends, exact = _compare(kwargs, n=3, steps=200, seed=9, keeper_actions="random",
                           env_id=env_id)
    assert exact >= 0.9


def test_vector_api_and_seeding():
    env = GoalkeeperVectorEnv(num_envs=3)
    assert env.observation_space.shape == (3, 19) and env.action_space.shape == (3, 6)
    assert env.metadata["autoreset_mode"] == gym.vector.AutoresetMode.NEXT_STEP
    first, _ = env.reset(seed=5)
    again, _ = env.reset(seed=5)
    np.testing.assert_array_equal(first, again)
    listed, _ = env.reset(seed=[5, 6, 7])
    np.testing.assert_array_equal(listed, first)
    other, _ = env.reset(seed=[7, 6, 5])
    np.testing.assert_array_equal(other[0], first[2])
    assert env.observation_space.contains(first)
    obs, rewards, terminated, truncated, info = env.step(env.action_space.sample())
    assert obs.dtype == np.float32 and rewards.shape == (3,) and terminated.dtype == bool
    assert info["truth"]["time"].tolist() == pytest.approx([1 / 60] * 3) and info["_truth"].all()


def test_make_vec_batches_what_it_can_and_falls_back_to_single_environments():
    batched = gym.make_vec(GK, num_envs=3)
    assert isinstance(batched, GoalkeeperVectorEnv)
    with pytest.warns(UserWarning, match="SyncVectorEnv: the batched Goalkeeper does not "
                                         "run the pixels detector"):
        sync = gym.make_vec(GK, num_envs=2, obs_mode="perceived", field="ssl-2012",
                            perception={"vision": "ssl-2012", "detector": "pixels"})
    assert isinstance(sync, gym.vector.SyncVectorEnv)
    obs, _ = sync.reset(seed=0)
    assert obs.shape == (2, 19)
    sync.close()


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="pixels detector"):
        GoalkeeperVectorEnv(2, obs_mode="perceived", field="ssl-2012",
                            perception={"vision": "ssl-2012", "detector": "pixels"})
    with pytest.raises(ValueError, match="does not render"):
        GoalkeeperVectorEnv(2, render_mode="rgb_array")
    with pytest.raises(ValueError, match="num_envs must be an integer in 1..65536, got 0"):
        GoalkeeperVectorEnv(0)
    with pytest.raises(ValueError, match=r"autoreset_mode must be one of \['NextStep', "
                                         r"'SameStep', 'Disabled'\], got 'Later'"):
        GoalkeeperVectorEnv(2, autoreset_mode="Later")
    with pytest.raises(TypeError, match="unexpected keyword argument 'frameskip'"):
        GoalkeeperVectorEnv(2, frameskip=4)
    env = GoalkeeperVectorEnv(2, out_of_range_actions="raise")
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros((2, 6)))
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"actions must have shape \(2, 6\)"):
        env.step(np.zeros(6))
    bad = np.zeros((2, 6))
    bad[1, 2] = np.nan
    with pytest.raises(ValueError, match="environment 1"):
        env.step(bad)
    with pytest.raises(ValueError, match="seed must be an int, None or a list of 2 seeds"):
        env.reset(seed=[1, 2, 3])
