"""Policies: the numpy copy of trained actors, loading by reference, and the shipped ones."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401
from agents import ScriptedGoalkeeper
from agents.policies import IdlePolicy, NumpyPolicy, SB3Policy, make_policy

sb3 = pytest.importorskip("stable_baselines3")


@pytest.fixture(scope="module")
def env():
    e = gym.make("soccer_env/Goalkeeper-v0")
    yield e
    e.close()


def _observations(env, n=64):
    rng = np.random.default_rng(0)
    obs, _ = env.reset(seed=0)
    out = [obs]
    for _ in range(n - 1):
        obs, *_ = env.step(rng.uniform(-1, 1, 6).astype(np.float32))
        out.append(obs)
    # Also points far outside the visited region, where clipping and squashing matter.
    return np.concatenate([np.array(out), rng.normal(0, 5, (16, out[0].size))]).astype(
        np.float32)


@pytest.mark.parametrize("algo,kwargs", [
    ("PPO", {"n_steps": 64, "batch_size": 64}),
    ("A2C", {"n_steps": 8}),
    ("PPO", {"n_steps": 64, "batch_size": 64, "use_sde": True}),
    ("SAC", {"learning_starts": 0, "buffer_size": 1000}),
    ("SAC", {"learning_starts": 0, "buffer_size": 1000, "use_sde": True}),
    ("TD3", {"learning_starts": 0, "buffer_size": 1000}),
])
def test_numpy_copy_acts_as_the_model(env, algo, kwargs):
    """The numpy actor gives stable-baselines3's deterministic actions (after a little
    training, so that the weights are not at their initial values)."""
    model = getattr(sb3, algo)("MlpPolicy", env, seed=0, device="cpu", **kwargs)
    model.learn(128)
    policy = NumpyPolicy.from_sb3(model)
    obs = _observations(env)
    expected = model.predict(obs, deterministic=True)[0]
    np.testing.assert_allclose(policy(obs), expected, atol=2e-5)
    np.testing.assert_allclose(policy(obs[3]), expected[3], atol=2e-5)
    assert policy.meta["algorithm"] == algo


def test_save_and_load_round_trip(env, tmp_path):
    model = sb3.PPO("MlpPolicy", env, seed=1, device="cpu",
                    policy_kwargs={"net_arch": [32, 16]})
    policy = NumpyPolicy.from_sb3(model, {"note": "round trip"})
    path = policy.save(tmp_path / "p.npz")
    loaded = NumpyPolicy.load(path)
    obs = _observations(env, 8)
    np.testing.assert_array_equal(loaded(obs), policy(obs))
    assert loaded.meta["note"] == "round trip" and loaded.obs_size == 19
    assert path.stat().st_size < 20_000


def test_make_policy_resolves_references(env, tmp_path):
    assert isinstance(make_policy("scripted", env), ScriptedGoalkeeper)
    idle = make_policy("idle", env)
    assert isinstance(idle, IdlePolicy) and not idle(np.zeros(19)).any()
    model = sb3.PPO("MlpPolicy", env, seed=0, device="cpu")
    model.save(tmp_path / "final_model.zip")
    from_zip = make_policy(tmp_path / "final_model.zip", env)
    from_dir = make_policy(tmp_path, env)
    assert isinstance(from_zip, NumpyPolicy) and isinstance(from_dir, NumpyPolicy)
    obs = _observations(env, 4)
    np.testing.assert_allclose(from_zip(obs), model.predict(obs, deterministic=True)[0],
                               atol=2e-5)
    fn = lambda o: np.zeros(6, np.float32)  # noqa: E731
    assert make_policy(fn, env) is fn


def test_sb3_policy_wraps_predict(env):
    model = sb3.PPO("MlpPolicy", env, seed=0, device="cpu")
    obs = _observations(env, 2)[0]
    np.testing.assert_array_equal(SB3Policy(model)(obs),
                                  model.predict(obs, deterministic=True)[0])


def test_bad_references_are_refused(env, tmp_path):
    with pytest.raises(ValueError, match="policy must be one of"):
        make_policy("keeper.pt", env)
    with pytest.raises(FileNotFoundError):
        make_policy(tmp_path / "missing.zip", env)
    with pytest.raises(ValueError, match="unknown baseline"):
        make_policy("baseline:nope", env)
    other = gym.make("soccer_env/Goalkeeper-v0")
    small = NumpyPolicy([("linear", np.zeros((6, 7)), np.zeros(6))], "clip", -np.ones(6),
                        np.ones(6))
    small.save(tmp_path / "small.npz")
    with pytest.raises(ValueError, match="observations of size 7"):
        make_policy(tmp_path / "small.npz", other)
    with pytest.raises(ValueError, match="obs must have shape"):
        small(np.zeros(19))
    with pytest.raises(ValueError, match="output must be"):
        NumpyPolicy([("linear", np.zeros((6, 7)), np.zeros(6))], "softmax", -np.ones(6),
                    np.ones(6))


def test_copy_is_frozen_and_carries_observation_normalisation(env, tmp_path):
    """The numpy copy owns its weights (later training does not move it) and, from a
    VecNormalize run, normalises observations with the statistics of the moment."""
    from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize

    venv = VecNormalize(DummyVecEnv([lambda: gym.make("soccer_env/Goalkeeper-v0")]))
    model = sb3.PPO("MlpPolicy", venv, n_steps=64, batch_size=64, seed=0, device="cpu")
    model.learn(64)
    policy = NumpyPolicy.from_sb3(model, vec_normalize=venv)
    obs = _observations(env, 16)
    before = policy(obs)
    np.testing.assert_allclose(before, model.predict(venv.normalize_obs(obs),
                                                     deterministic=True)[0], atol=2e-5)
    model.learn(128)
    np.testing.assert_array_equal(policy(obs), before)
    loaded = NumpyPolicy.load(policy.save(tmp_path / "n.npz"))
    np.testing.assert_array_equal(loaded(obs), before)
