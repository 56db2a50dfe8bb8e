"""The privileged critic: the actor never reads the truth, the critic does."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

import torch as th  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402

import soccer_env  # noqa: E402, F401
from agents.policies.wrappers import ACTOR_KEY, CRITIC_KEY, PrivilegedObservation  # noqa: E402
from agents.sb3.privileged import PrivilegedActorCriticPolicy  # noqa: E402

GK = "soccer_env/Goalkeeper-v0"
KW = dict(obs_mode="perceived", perception="ssl-2012", belief_features=True)


def _model(env, seed=0):
    return PPO(PrivilegedActorCriticPolicy, env, n_steps=64, batch_size=64, n_epochs=2,
               seed=seed, verbose=0, policy_kwargs={"net_arch": [32, 32]})


def _tensors(obs):
    return {k: th.as_tensor(v)[None] for k, v in obs.items()}


def test_actor_is_blind_to_the_critic_input():
    """Change the critic's input (the truth) arbitrarily: the actor's action distribution is
    bit-for-bit the same, the value is not; and training for a few updates keeps it so."""
    env = PrivilegedObservation(gym.make(GK, **KW))
    model = _model(env)
    rng = np.random.default_rng(0)
    for trained in (False, True):
        if trained:
            model.learn(256)
        obs, _ = env.reset(seed=1)
        for _ in range(5):
            base = _tensors(obs)
            moved = dict(base)
            moved[CRITIC_KEY] = base[CRITIC_KEY] + th.as_tensor(
                rng.normal(0.0, 3.0, base[CRITIC_KEY].shape), dtype=th.float32)
            with th.no_grad():
                d0 = model.policy.get_distribution(base).distribution
                d1 = model.policy.get_distribution(moved).distribution
                v0, v1 = model.policy.predict_values(base), model.policy.predict_values(moved)
            assert th.equal(d0.mean, d1.mean) and th.equal(d0.stddev, d1.stddev)
            assert not th.equal(v0, v1)
            obs, *_ = env.step(env.action_space.sample())


def test_actor_takes_no_gradient_from_the_critic_input():
    env = PrivilegedObservation(gym.make(GK, **KW))
    model = _model(env)
    obs, _ = env.reset(seed=0)
    t = _tensors(obs)
    t[CRITIC_KEY].requires_grad_(True)
    t[ACTOR_KEY].requires_grad_(True)
    mean = model.policy.get_distribution(t).distribution.mean.sum()
    mean.backward()
    assert t[CRITIC_KEY].grad is None or not t[CRITIC_KEY].grad.any()
    assert t[ACTOR_KEY].grad.abs().sum() > 0


def test_critic_sees_the_truth_and_the_belief():
    """The critic's entry is a truth-mode observation of the same layout, then the actor's."""
    env = PrivilegedObservation(gym.make(GK, **KW))
    truth = gym.make(GK, obs_mode="truth", perception="ssl-2012", belief_features=True)
    obs, _ = env.reset(seed=4)
    tobs, _ = truth.reset(seed=4)
    n = len(obs[ACTOR_KEY])
    for _ in range(30):
        np.testing.assert_allclose(obs[CRITIC_KEY][:n], tobs, atol=1e-5)
        np.testing.assert_array_equal(obs[CRITIC_KEY][n:], obs[ACTOR_KEY])
        assert env.observation_space.contains(obs)
        a = np.zeros(6, np.float32)
        obs, *_ = env.step(a)
        tobs, *_ = truth.step(a)
    assert not np.allclose(obs[CRITIC_KEY][:n], obs[ACTOR_KEY], atol=1e-3)


def test_bad_input():
    with pytest.raises(TypeError, match="single-agent soccer_env task"):
        PrivilegedObservation(gym.make("CartPole-v1"))
    env = PrivilegedObservation(gym.make(GK, **KW))
    with pytest.raises(ValueError, match="share_features_extractor"):
        PPO(PrivilegedActorCriticPolicy, env,
            policy_kwargs={"share_features_extractor": True})


def test_training_ships_an_actor_for_the_plain_environment(tmp_path):
    """``train(critic="privileged")``: the numpy copy of the actor takes the plain perceived
    observation and acts as the trained model does on the actor's part (normalised with the
    actor entry's statistics)."""
    from agents.policies import NumpyPolicy
    from agents.runs.training import TrainConfig, train

    cfg = TrainConfig(env_kwargs=dict(KW), critic="privileged", total_steps=512, n_envs=2,
                      n_workers=0, out=str(tmp_path / "run"), checkpoint_every=0,
                      eval_every=0, progress_bar=False, actions="guard",
                      hyperparams={"n_steps": 128, "policy_kwargs": {"net_arch": [16]}})
    train(cfg)
    policy = NumpyPolicy.load(tmp_path / "run" / "final_policy.npz")
    assert policy.meta["critic"] == "privileged"
    plain = gym.make(GK, **KW)
    obs, _ = plain.reset(seed=0)
    assert policy.obs_size == plain.observation_space.shape[0]
    from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize

    from agents.runs.resolve import load_sb3
    from agents.sb3.normalization import read_vecnormalize, vecnormalize_on

    # Loaded without unpickling: the spaces and the privileged policy class from the run.
    model = load_sb3(tmp_path / "run" / "final_model.zip")
    assert isinstance(model, PPO)
    stats = vecnormalize_on(read_vecnormalize(tmp_path / "run" / "final_vecnormalize.npz"),
                            DummyVecEnv([lambda: PrivilegedObservation(gym.make(GK, **KW))]))
    assert isinstance(stats, VecNormalize)
    for _ in range(20):
        dict_obs = {"actor": obs[None], "critic": np.zeros((1, 2 * len(obs)), np.float32)}
        expected, _ = model.predict(stats.normalize_obs(dict_obs), deterministic=True)
        np.testing.assert_allclose(policy.network_action(obs), expected[0], atol=1e-5)
        obs, *_ = plain.step(policy(obs))


def test_config_refuses_what_it_cannot_do():
    from agents.runs.training import TrainConfig

    for bad in (dict(critic="oracle"), dict(critic="privileged", algorithm="SAC"),
                dict(critic="privileged", frame_stack=4),
                dict(critic="privileged", env_id="soccer_env/Match-v0")):
        with pytest.raises(ValueError, match="critic"):
            TrainConfig(**bad)


def test_worker_processes_carry_dict_observations():
    """The training VecEnv in worker processes batches the ``Dict`` observations as
    stable-baselines3 expects (a dict of arrays), also through ``VecNormalize``."""
    from stable_baselines3.common.vec_env import VecNormalize

    from agents.runs.training import TrainConfig, make_vec_env

    cfg = TrainConfig(env_kwargs=dict(KW), critic="privileged", n_envs=4, n_workers=2,
                      actions="guard")
    venv = VecNormalize(make_vec_env(cfg))
    try:
        obs = venv.reset()
        assert set(obs) == {ACTOR_KEY, CRITIC_KEY}
        assert obs[ACTOR_KEY].shape == (4, 30) and obs[CRITIC_KEY].shape == (4, 60)
        for _ in range(3):
            obs, _, _, _ = venv.step(np.zeros((4, 1), np.float32))
            assert obs[CRITIC_KEY].shape == (4, 60)
    finally:
        venv.close()
