"""BatchedVecEnv: the batched Goalkeeper under stable-baselines3's VecEnv contract, equal to
single environments behind SB3's own DummyVecEnv and Monitor, and PPO trains on it."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

import gymnasium as gym  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.monitor import Monitor  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv  # noqa: E402

import soccer_env  # noqa: E402,F401
from agents.batched import BatchedVecEnv  # noqa: E402


def test_same_batches_as_dummy_vec_env_of_single_environments():
    n = 4
    ours = BatchedVecEnv(n, max_episode_steps=120)
    theirs = DummyVecEnv([lambda: Monitor(gym.make("soccer_env/Goalkeeper-v0",
                                                   max_episode_steps=120))
                          for _ in range(n)])
    ours.seed(3)
    theirs.seed(3)
    np.testing.assert_array_equal(ours.reset(), theirs.reset())
    rng = np.random.default_rng(0)
    ends = 0
    for t in range(400):
        a = np.zeros((n, 6), np.float32)
        a[:, :3] = rng.uniform(-1, 1, (n, 3))
        o1, r1, d1, i1 = ours.step(a)
        o2, r2, d2, i2 = theirs.step(a)
        np.testing.assert_allclose(o1, o2, atol=1e-3, err_msg=f"step {t}")
        np.testing.assert_allclose(r1, r2, atol=1e-3)
        np.testing.assert_array_equal(d1, d2)
        for k in np.nonzero(d1)[0]:
            ends += 1
            a_, b_ = i1[k], i2[k]
            assert a_["TimeLimit.truncated"] == b_["TimeLimit.truncated"]
            np.testing.assert_allclose(a_["terminal_observation"], b_["terminal_observation"],
                                       atol=1e-3)
            assert a_["episode"]["l"] == b_["episode"]["l"]
            assert a_["episode"]["r"] == pytest.approx(b_["episode"]["r"], abs=1e-3)
            assert a_.get("is_success") == b_.get("is_success")
    assert ends >= 10


@pytest.mark.usefixtures("one_torch_thread")
def test_ppo_trains_on_the_batch():
    venv = BatchedVecEnv(32, env_kwargs={"shaping": {"intercept": 2.0}})
    model = PPO("MlpPolicy", venv, n_steps=32, batch_size=256, n_epochs=1, seed=0)
    model.learn(2048)
    assert model.num_timesteps >= 2048 and len(model.ep_info_buffer) > 0
