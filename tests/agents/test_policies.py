"""Policies: the numpy copy of trained actors, loading by reference, and the shipped ones."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401
from agents import ScriptedGoalkeeper
from agents.policies import IdlePolicy, NumpyPolicy
from agents.runs.resolve import make_policy

sb3 = pytest.importorskip("stable_baselines3")

from agents.sb3.policies import SB3Policy, numpy_copy  # noqa: E402


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
        obs, _, term, trunc, _ = env.step(rng.uniform(-1, 1, 6).astype(np.float32))
        out.append(obs)
        if term or trunc:
            obs, _ = env.reset()
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
    policy = numpy_copy(model)
    obs = _observations(env)
    expected = model.predict(obs, deterministic=True)[0]
    np.testing.assert_allclose(policy(obs), expected, atol=2e-5)
    np.testing.assert_allclose(policy(obs[3]), expected[3], atol=2e-5)
    assert policy.meta["algorithm"] == algo


def test_save_and_load_round_trip(env, tmp_path):
    model = sb3.PPO("MlpPolicy", env, seed=1, device="cpu",
                    policy_kwargs={"net_arch": [32, 16]})
    policy = numpy_copy(model, {"note": "round trip"})
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
    policy = numpy_copy(model, vec_normalize=venv)
    obs = _observations(env, 16)
    before = policy(obs)
    np.testing.assert_allclose(before, model.predict(venv.normalize_obs(obs),
                                                     deterministic=True)[0], atol=2e-5)
    model.learn(128)
    np.testing.assert_array_equal(policy(obs), before)
    loaded = NumpyPolicy.load(policy.save(tmp_path / "n.npz"))
    np.testing.assert_array_equal(loaded(obs), before)


# ------------------------------------------------------------------------------------------
# Policies with memory: RecurrentPPO's LSTM and stacked frames
# ------------------------------------------------------------------------------------------

def _episode_against_sb3(model, policy, env, seed, obs_fn=lambda o: o, max_steps=400):
    """Run one episode of ``env`` with ``model``'s deterministic recurrent actions (state
    carried, ``episode_start`` at the first step) and return the largest difference between
    them and ``policy``'s, called on the plain observations; and the episode's length."""
    policy.reset()
    obs, _ = env.reset(seed=seed)
    state, start, worst, steps = None, np.ones(1, bool), 0.0, 0
    while steps < max_steps:
        expected, state = model.predict(obs_fn(obs), state=state, episode_start=start,
                                        deterministic=True)
        start = np.zeros(1, bool)
        worst = max(worst, float(np.abs(policy(obs) - expected).max()))
        obs, _, term, trunc, _ = env.step(expected)
        steps += 1
        if term or trunc:
            break
    return worst, steps


@pytest.fixture(scope="module")
def recurrent_model():
    """A little-trained RecurrentPPO (two LSTM layers, behind VecNormalize) and its
    VecNormalize."""
    contrib = pytest.importorskip("sb3_contrib")
    from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize

    venv = VecNormalize(DummyVecEnv([lambda: gym.make("soccer_env/Goalkeeper-v0")] * 2))
    model = contrib.RecurrentPPO("MlpLstmPolicy", venv, n_steps=64, batch_size=128, seed=0,
                                 device="cpu", policy_kwargs={"lstm_hidden_size": 16,
                                                              "n_lstm_layers": 2,
                                                              "net_arch": [32]})
    model.learn(256)
    return model, venv


def test_recurrent_numpy_copy_acts_as_the_model_over_episodes(env, recurrent_model, tmp_path):
    """The numpy LSTM carries its state as sb3-contrib's predict(state, episode_start) does,
    over whole episodes, after a save and load, and restarts at reset()."""
    from agents.policies import NumpyRecurrentPolicy

    model, venv = recurrent_model
    copy = numpy_copy(model, {"note": "lstm"}, vec_normalize=venv)
    assert isinstance(copy, NumpyRecurrentPolicy) and copy.stateful
    assert (copy.obs_size, copy.hidden_size, copy.n_lstm_layers) == (19, 16, 2)
    policy = NumpyPolicy.load(copy.save(tmp_path / "lstm.npz"))
    assert isinstance(policy, NumpyRecurrentPolicy) and policy.meta["note"] == "lstm"
    assert policy.meta["algorithm"] == "RecurrentPPO"
    for seed in (0, 1):  # the second episode starts from a reset state
        worst, steps = _episode_against_sb3(model, policy, env, seed, venv.normalize_obs)
        assert steps > 20 and worst < 1e-5, (seed, steps, worst)
    # Memory matters: the same observation after other observations gives another action.
    obs = _observations(env, 8)
    policy.reset()
    first = policy(obs[0])
    for o in obs[1:]:
        policy(o)
    assert not np.allclose(policy(obs[0]), first, atol=1e-4)
    policy.reset()
    np.testing.assert_array_equal(policy(obs[0]), first)


def test_recurrent_numpy_copy_takes_batches_of_separate_episodes(env, recurrent_model):
    model, venv = recurrent_model
    policy = numpy_copy(model, vec_normalize=venv)
    obs = _observations(env, 12)[:12].reshape(4, 3, 19)  # 4 steps of 3 environments
    state = None
    for t in range(4):
        expected, state = model.predict(venv.normalize_obs(obs[t]), state=state,
                                        episode_start=np.full(3, t == 0), deterministic=True)
        np.testing.assert_allclose(policy(obs[t]), expected, atol=1e-5)
    np.testing.assert_allclose(policy.state[1], state[1], atol=1e-5)
    with pytest.raises(ValueError, match="reset"):
        policy(obs[0, :2])


def test_recurrent_model_loads_by_file_and_as_sb3_policy(env, recurrent_model, tmp_path):
    """A RecurrentPPO .zip without a run's config.json is recognised as RecurrentPPO (not
    opened as PPO, which would drop the LSTM); make_policy gives its numpy copy; SB3Policy
    carries the state too."""
    from agents.policies import NumpyRecurrentPolicy
    from agents.policies.files import UnsafeFileError
    from agents.runs.resolve import load_sb3

    model, _ = recurrent_model
    model.save(tmp_path / "final_model.zip")
    spaces = {"observation_space": env.observation_space, "action_space": env.action_space}
    assert type(load_sb3(tmp_path / "final_model.zip", **spaces)).__name__ == "RecurrentPPO"
    # Without a run's config.json nor the spaces, only unpickling could tell them: refused
    # unless trusted.
    with pytest.raises(UnsafeFileError, match="trust"):
        load_sb3(tmp_path / "final_model.zip")
    assert type(load_sb3(tmp_path / "final_model.zip", trust=True)).__name__ == "RecurrentPPO"
    policy = make_policy(tmp_path / "final_model.zip", env)  # no VecNormalize file beside it
    assert isinstance(policy, NumpyRecurrentPolicy)
    worst, _ = _episode_against_sb3(model, policy, env, 2)
    assert worst < 1e-5
    wrapped = SB3Policy(model)
    assert wrapped.stateful
    worst, _ = _episode_against_sb3(model, wrapped, env, 2)
    assert worst == 0.0


def test_numpy_policy_with_a_stack_acts_as_the_model_on_the_stacked_env(env, tmp_path):
    """A PPO trained behind stack_frames and VecNormalize: its numpy copy, called with the
    plain environment's single observations, gives the model's actions on the stacked
    ones over whole episodes."""
    from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize

    from agents.policies.wrappers import stack_frames

    n = 3
    make = lambda: stack_frames(gym.make("soccer_env/Goalkeeper-v0"), n)  # noqa: E731
    venv = VecNormalize(DummyVecEnv([make] * 2))
    model = sb3.PPO("MlpPolicy", venv, n_steps=64, batch_size=128, seed=0, device="cpu")
    model.learn(256)
    policy = NumpyPolicy.load(numpy_copy(model, vec_normalize=venv, frame_stack=n)
                              .save(tmp_path / "stack.npz"))
    assert policy.frame_stack == n and policy.obs_size == 19 and policy.input_size == 57
    stacked = make()
    for seed in (0, 1):
        policy.reset()
        obs, _ = env.reset(seed=seed)
        sobs, _ = stacked.reset(seed=seed)
        steps, done = 0, False
        while not done:
            expected = model.predict(venv.normalize_obs(sobs), deterministic=True)[0]
            np.testing.assert_allclose(policy(obs), expected, atol=2e-5)
            obs, _, term, trunc, _ = env.step(expected)
            sobs, *_ = stacked.step(expected)
            steps, done = steps + 1, term or trunc
        assert steps > 20
