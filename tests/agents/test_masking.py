"""Steps whose action the environment ignored are kept out of PPO's policy update
(agents.sb3.masking.IgnoredActions), and the team-residual VecEnv flags them."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

sb3 = pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv  # noqa: E402

from agents.sb3.masking import IgnoredActions  # noqa: E402


class _Flags(gym.Env):
    """Every third step's info says its action was ignored."""

    def __init__(self) -> None:
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (3,), np.float32)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (2,), np.float32)
        self._t = 0

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        return self.observation_space.sample(), {}

    def step(self, action):
        self._t += 1
        info = {"correction_ignored": self._t % 3 == 0}
        return self.observation_space.sample(), float(action[0]), False, False, info


def test_ignored_steps_have_no_advantage_and_the_rest_are_normalised():
    venv = DummyVecEnv([_Flags, _Flags])
    model = PPO("MlpPolicy", venv, n_steps=30, batch_size=60, n_epochs=1, seed=0,
                normalize_advantage=False, policy_kwargs={"net_arch": [8]})
    mask = IgnoredActions()
    model.learn(60, callback=mask)
    adv = model.rollout_buffer.advantages
    ignored = np.zeros_like(adv, dtype=bool)
    ignored[2::3] = True  # steps 3, 6, ... of each environment sit at rows 2, 5, ...
    assert np.all(adv[ignored] == 0.0)
    live = adv[~ignored]
    assert abs(live.mean()) < 1e-6 and live.std() == pytest.approx(1.0, rel=1e-4)
    assert mask.ignored_fraction == pytest.approx(1 / 3)


def test_ppo_normalising_its_advantages_is_refused():
    model = PPO("MlpPolicy", DummyVecEnv([_Flags]), n_steps=8, batch_size=8, seed=0)
    with pytest.raises(ValueError, match="normalize_advantage=False"):
        model.learn(8, callback=IgnoredActions())


def test_the_team_residual_vec_env_flags_the_restarts():
    import soccer_env
    from agents.scripted import ignored_rows, scripted_team_from_params, team_residual_params
    from agents.vec.factories import make_match_vec_env
    from agents.vec.team_residual import TeamResidualVecEnv

    kwargs = {"blue": 2, "yellow": 2, "match_duration": 4.0, "game": True}
    env = soccer_env.parallel_env(**kwargs)
    params = team_residual_params(env, "blue")
    env.close()
    venv = TeamResidualVecEnv(make_match_vec_env(kwargs, n_matches=2, learner="blue",
                                                 opponent="scripted", seed=0, workers=1,
                                                 batched=False), params)
    team = scripted_team_from_params(params)
    obs = venv.reset()
    seen = set()
    for _ in range(120):
        want = ignored_rows(team, obs)
        obs, _, _, infos = venv.step(np.zeros((4, 6), np.float32))
        got = np.array([info["correction_ignored"] for info in infos])
        np.testing.assert_array_equal(got, want)
        seen.update(got.tolist())
    assert seen == {True, False}  # the kick-off, then open play
    venv.close()
