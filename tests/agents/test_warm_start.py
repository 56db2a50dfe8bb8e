"""A stable-baselines3 model started from a numpy policy (agents.sb3.warm_start): it acts as the
policy, added observation entries change nothing until training moves their weights, the actor
is held while the critic learns, and mismatches are refused."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

sb3 = pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize  # noqa: E402

from agents.policies import NumpyPolicy  # noqa: E402
from agents.sb3.policies import numpy_copy  # noqa: E402
from agents.sb3.warm_start import (  # noqa: E402
    FreezeActor,
    HeldRunningMeanStd,
    actor_parameters,
    load_actor,
)


class _Box(gym.Env):
    """Random observations of ``n`` entries, three actions, a reward that depends on them."""

    def __init__(self, n: int = 7) -> None:
        self.observation_space = gym.spaces.Box(-5.0, 5.0, (n,), np.float32)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self._t = 0

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self._t = 0
        return self.observation_space.sample(), {}

    def step(self, action):
        self._t += 1
        reward = -float(np.sum(np.square(action - 0.3)))
        return self.observation_space.sample(), reward, False, self._t >= 16, {}


def _policy(n_in: int = 5, normalize: bool = True, act: str = "tanh") -> NumpyPolicy:
    rng = np.random.default_rng(1)
    layers = [("linear", rng.normal(0, 0.5, (8, n_in)), rng.normal(0, 0.1, 8)), (act,),
              ("linear", rng.normal(0, 0.5, (8, 8)), rng.normal(0, 0.1, 8)), (act,),
              ("linear", rng.normal(0, 0.5, (3, 8)), rng.normal(0, 0.1, 3))]
    norm = (rng.normal(0, 1, n_in), rng.uniform(0.5, 2.0, n_in), 10.0, 1e-8) if normalize \
        else None
    return NumpyPolicy(layers, "clip", -np.ones(3), np.ones(3), normalize=norm)


def _model(n: int = 7, normalize: bool = True):
    venv = DummyVecEnv([lambda: _Box(n)])
    if normalize:
        venv = VecNormalize(venv)
    model = PPO("MlpPolicy", venv, n_steps=32, batch_size=32, n_epochs=2, seed=0,
                policy_kwargs={"net_arch": [8, 8]})
    return model, venv


def test_the_model_acts_as_the_policy_on_its_entries_whatever_the_added_ones():
    policy = _policy()
    model, norm = _model()
    load_actor(model, policy, norm)
    rng = np.random.default_rng(2)
    obs = rng.normal(0, 2, (50, 7)).astype(np.float32)
    copy = numpy_copy(model, vec_normalize=norm)
    want = policy.network_action(obs[:, :5])
    np.testing.assert_allclose(copy.network_action(obs), want, atol=1e-5)
    obs[:, 5:] = rng.normal(0, 100, (50, 2))  # the added entries do not count yet
    np.testing.assert_allclose(copy.network_action(obs), want, atol=1e-5)
    predicted = model.predict(norm.normalize_obs(obs), deterministic=True)[0]
    np.testing.assert_allclose(predicted, want, atol=1e-5)
    np.testing.assert_allclose(norm.obs_rms.mean[:5], policy.normalize[0])
    np.testing.assert_allclose(norm.obs_rms.var[5:], 1.0)


def test_the_actor_is_held_while_the_critic_learns_then_learns():
    model, norm = _model()
    load_actor(model, _policy(), norm)
    before = [p.detach().clone() for p in actor_parameters(model)]
    critic = [p.detach().clone() for p in model.policy.mlp_extractor.value_net.parameters()]
    freeze = FreezeActor(64)
    model.learn(64, callback=freeze)
    assert all(np.array_equal(a.numpy(), p.detach().numpy())
               for a, p in zip(before, actor_parameters(model)))
    assert any(not np.array_equal(a.numpy(), p.detach().numpy()) for a, p in
               zip(critic, model.policy.mlp_extractor.value_net.parameters()))
    model.learn(64, callback=freeze, reset_num_timesteps=False)
    assert not freeze.frozen
    assert any(not np.array_equal(a.numpy(), p.detach().numpy())
               for a, p in zip(before, actor_parameters(model)))


@pytest.mark.parametrize("hold", [False, True])
def test_held_statistics_keep_the_policys_entries_while_the_added_ones_follow(hold):
    policy = _policy()
    model, norm = _model()
    load_actor(model, policy, norm, count=100.0, hold=hold)
    model.learn(256)
    mean, var = norm.obs_rms.mean, norm.obs_rms.var
    held = np.allclose(mean[:5], policy.normalize[0]) and np.allclose(var[:5], policy.normalize[1])
    assert held == hold
    # the added entries follow the observations (uniform on [-5, 5]: variance 25/3)
    assert np.all(var[5:] > 3.0)
    copy = numpy_copy(model, vec_normalize=norm)
    np.testing.assert_allclose(copy.normalize[0][:5], mean[:5])


def test_held_statistics_refuse_mismatched_sizes():
    with pytest.raises(ValueError, match="held must be within"):
        HeldRunningMeanStd(np.zeros(3), np.ones(3), 4)
    with pytest.raises(ValueError, match="mean and var"):
        HeldRunningMeanStd(np.zeros(3), np.ones(2), 1)


def test_mismatches_are_refused():
    model, norm = _model()
    with pytest.raises(ValueError, match="layers"):
        load_actor(model, _policy(act="relu"), norm)
    with pytest.raises(ValueError, match="fewer than the policy's"):
        load_actor(model, _policy(n_in=9), norm)
    with pytest.raises(ValueError, match="vec_normalize"):
        load_actor(model, _policy(), None)
    bare, _ = _model(normalize=False)
    with pytest.raises(ValueError, match="vec_normalize"):
        load_actor(bare, _policy(normalize=False), norm)
    load_actor(bare, _policy(normalize=False))
    with pytest.raises(ValueError, match="steps must be an integer"):
        FreezeActor(-1)
    with pytest.raises(ValueError, match="steps must be an integer"):
        FreezeActor(1.5)
