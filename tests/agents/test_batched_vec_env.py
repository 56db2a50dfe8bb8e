"""BatchedVecEnv: the batched Goalkeeper under stable-baselines3's VecEnv contract, equal to
single environments behind SB3's own DummyVecEnv and Monitor, and PPO trains on it.
BatchedMatchVecEnv: the batched match, equal to MatchVecEnv's batches (in this process and
over worker processes), and PPO self-play on it."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

import gymnasium as gym  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.monitor import Monitor  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv  # noqa: E402

import soccer_env  # noqa: E402,F401
from agents.vec.batched import BatchedMatchVecEnv, BatchedVecEnv  # noqa: E402
from agents.vec.factories import make_match_vec_env  # noqa: E402
from agents.vec.match import MatchVecEnv  # noqa: E402
from agents.vec.self_play import SelfPlayCallback  # noqa: E402
from soccer_env.envs.batched import NotBatchable  # noqa: E402


def _pair(n: int, env_id: str, kwargs: dict, max_episode_steps: int, seed: int):
    """The batch and a DummyVecEnv of ``n`` single environments in Monitors, both seeded
    ``seed`` and reset to the same first observations."""
    ours = BatchedVecEnv(n, kwargs, max_episode_steps=max_episode_steps, env_id=env_id)
    theirs = DummyVecEnv([lambda: Monitor(gym.make(env_id, max_episode_steps=max_episode_steps,
                                                   **kwargs))
                          for _ in range(n)])
    ours.seed(seed)
    theirs.seed(seed)
    np.testing.assert_array_equal(ours.reset(), theirs.reset())
    return ours, theirs


@pytest.mark.parametrize("kwargs", [{}, {"obs_mode": "perceived", "perception": "ssl-2012"}])
def test_same_batches_as_dummy_vec_env_of_single_environments(kwargs):
    n = 4
    ours, theirs = _pair(n, "soccer_env/Goalkeeper-v0", kwargs, 120, 3)
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


# ----------------------------------------------------------------------------------------
# The batched match
# ----------------------------------------------------------------------------------------

def _same_as_match_vec_env(kwargs: dict, n: int, learner: str, opponent, steps: int,
                           workers: int = 0) -> int:
    """Step the batched match VecEnv and MatchVecEnv with the same actions; dones, events,
    scores and episode infos must agree exactly, observations to 1e-4 and rewards to 1e-6
    (the shared space's rounding; single precision in a match's own observations). Returns
    the number of finished matches."""
    ours = make_match_vec_env(kwargs, n, learner, opponent, seed=4, workers=workers,
                              batched=True)
    theirs = MatchVecEnv(kwargs, n, learner, opponent)
    theirs.seed(4)
    np.testing.assert_allclose(ours.reset(), theirs.reset(), atol=1e-4)
    rng = np.random.default_rng(1)
    ends = 0
    for t in range(steps):
        a = rng.uniform(-1, 1, (ours.num_envs, 6)).astype(np.float32)
        a[:, 3] = np.where(rng.random(ours.num_envs) < 0.05, 1.0, -1.0)
        o1, r1, d1, i1 = ours.step(a)
        o2, r2, d2, i2 = theirs.step(a)
        np.testing.assert_allclose(o1, o2, atol=1e-4, err_msg=f"step {t}")
        np.testing.assert_allclose(r1, r2, atol=1e-6)
        np.testing.assert_array_equal(d1, d2)
        for x, y in zip(i1, i2):
            assert (x["event"], x["score"], x["TimeLimit.truncated"]) == (
                y["event"], y["score"], y["TimeLimit.truncated"]), t
            assert set(x) == set(y)
            if "episode" in x:
                ends += 1
                assert x["episode"]["l"] == y["episode"]["l"]
                assert x["episode"]["r"] == pytest.approx(y["episode"]["r"], abs=1e-5)
                for key in ("is_success", "goals_for", "goals_against"):
                    assert x[key] == y[key]
                np.testing.assert_allclose(x["terminal_observation"],
                                           y["terminal_observation"], atol=1e-4)
    ours.close()
    return ends


@pytest.mark.parametrize("kwargs,learner,opponent", [
    ({"blue": 2, "yellow": 2, "match_duration": 1.5}, "blue", "idle"),
    ({"blue": 2, "yellow": 2, "max_cycles": 50, "shaping": {"ball_progress": 1.0}}, "both",
     None),
    ({"blue": 1, "yellow": 3, "match_duration": 1.0, "shaping": {"ball_distance": 0.5}},
     "yellow", "scripted"),
    ({"blue": 2, "yellow": 2, "match_duration": 1.5, "obs_mode": "perceived",
      "perception": "ssl-2012"}, "blue", "scripted"),
])
def test_batched_match_vec_env_plays_match_vec_env_batches(kwargs, learner, opponent):
    assert _same_as_match_vec_env(kwargs, 3, learner, opponent, steps=200) >= 6


def test_batched_match_workers_play_the_same_matches():
    kwargs = {"blue": 2, "yellow": 2, "match_duration": 1.0}
    assert _same_as_match_vec_env(kwargs, 4, "blue", "idle", steps=130, workers=2) >= 8


def test_batched_match_workers_are_reproducible():
    """The same seed and number of workers give the same batches, bit for bit."""
    def run() -> list[np.ndarray]:
        venv = make_match_vec_env({"blue": 2, "yellow": 2, "match_duration": 0.5}, 4, "blue",
                                  "scripted", seed=9, workers=2, batched=True)
        out = [venv.reset()]
        rng = np.random.default_rng(3)
        for _ in range(60):
            obs, rewards, _, _ = venv.step(rng.uniform(-1, 1, (8, 6)).astype(np.float32))
            out += [obs, rewards]
        venv.close()
        return out

    for a, b in zip(run(), run()):
        np.testing.assert_array_equal(a, b)


def test_batched_match_vec_env_attributes_and_refusals():
    venv = BatchedMatchVecEnv({"blue": 2, "yellow": 1}, 3, "blue", "idle")
    venv.seed(0)
    venv.reset()
    assert venv.num_envs == 6
    assert venv.get_attr("score") == [[0, 0]] * 6
    assert venv.get_attr("match_duration", [0, 5]) == [300.0, 300.0]
    with pytest.raises(ValueError, match="set_attr"):
        venv.set_attr("match_duration", 10.0)
    with pytest.raises(ValueError, match="env_method"):
        venv.env_method("render")
    with pytest.raises(ValueError, match=r"shape \(6, 6\)"):
        venv.step(np.zeros((3, 6)))
    with pytest.raises(NotBatchable, match="render"):
        BatchedMatchVecEnv({"render_mode": "rgb_array", "blue": 1, "yellow": 1}, 2)


@pytest.mark.usefixtures("one_torch_thread")
def test_ppo_self_play_on_the_batched_match():
    venv = make_match_vec_env({"blue": 2, "yellow": 2, "match_duration": 0.5}, 16, "blue",
                              "scripted", seed=0, batched=True)
    model = PPO("MlpPolicy", venv, n_steps=32, batch_size=256, n_epochs=1, seed=0)
    callback = SelfPlayCallback(update_every=512, pool_size=2)
    model.learn(2048, callback=callback)
    assert model.num_timesteps >= 2048 and callback.n_updates >= 2
    assert len(model.ep_info_buffer) > 0


def test_the_batched_shootout_as_a_vec_env():
    """Shootout-v0 through BatchedVecEnv: the same batches as DummyVecEnv of single
    environments (Monitor's episode statistics and is_success included)."""
    n = 3
    ours, theirs = _pair(n, "soccer_env/Shootout-v0", {}, 100, 1)
    rng = np.random.default_rng(2)
    ends = 0
    for _ in range(250):
        a = rng.uniform(-0.05, 0.05, (n, 6)).astype(np.float32)
        a[:, 0] = 0.8
        a[:, 3] = rng.random(n) < 0.3
        o1, r1, d1, i1 = ours.step(a)
        o2, r2, d2, i2 = theirs.step(a)
        np.testing.assert_allclose(o1, o2, atol=1e-3)
        np.testing.assert_array_equal(d1, d2)
        for k in np.nonzero(d1)[0]:
            ends += 1
            assert i1[k]["episode"]["l"] == i2[k]["episode"]["l"]
            assert i1[k].get("is_success") == i2[k].get("is_success")
    assert ends >= 5
    with pytest.raises(ValueError, match="env_id"):
        BatchedVecEnv(2, env_id="soccer_env/Match-v0")
