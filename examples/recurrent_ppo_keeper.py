"""sb3-contrib's RecurrentPPO: an LSTM keeper that plays from perceived observations.

    pip install torch==2.13.0 && pip install -e ".[train]"    # sb3-contrib comes with it
    python examples/recurrent_ppo_keeper.py [--tiny]

Under ``obs_mode="perceived"`` the keeper sees the estimation stack's belief, late, noisy and
sometimes stale (``ssl-2012``: 25 Hz cameras, 80 ms latency); the LSTM gives the policy a
memory of the past frames. The keeper chooses where to stand on its guard line
(``agents.policies.wrappers.GuardActions``), 25 times a second, with normalised observations: the
recipe of ``soccer-env train --algo recurrent-ppo`` (which adds worker processes, periodic
evaluation, checkpoints and a numpy export).
"""

from __future__ import annotations

import argparse
import os

import gymnasium as gym
import numpy as np
import torch
from sb3_contrib import RecurrentPPO
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import VecNormalize

import soccer_env  # noqa: F401  (registers the environments)
from agents.policies.wrappers import GuardActions
from soccer_env.envs.registration import GOALKEEPER_ID

ENV_KWARGS = {"obs_mode": "perceived", "perception": "ssl-2012", "control_dt": 0.04}


def main(tiny: bool) -> None:
    torch.set_num_threads(1)
    venv = make_vec_env(GOALKEEPER_ID, n_envs=2 if tiny else 16, seed=0,
                        env_kwargs={**ENV_KWARGS, "shaping": {"intercept": 2.0}},
                        wrapper_class=GuardActions)
    venv = VecNormalize(venv, norm_obs=True, norm_reward=False)
    model = RecurrentPPO("MlpLstmPolicy", venv, n_steps=32 if tiny else 256,
                         batch_size=64 if tiny else 1024, n_epochs=2 if tiny else 10,
                         ent_coef=0.0, policy_kwargs={"lstm_hidden_size": 64,
                                                      "log_std_init": -0.5},
                         seed=0, verbose=0 if tiny else 1)
    model.learn(128 if tiny else 500_000)
    venv.training = False

    # Evaluate without shaping, the LSTM's state carried from step to step and reset at each
    # episode's start.
    env = GuardActions(gym.make(GOALKEEPER_ID, **ENV_KWARGS))
    episodes, saves = 2 if tiny else 100, 0
    for seed in range(episodes):
        obs, info = env.reset(seed=seed)
        state, start = None, np.ones((1,), dtype=bool)
        while True:
            action, state = model.predict(venv.normalize_obs(obs[None]), state=state,
                                          episode_start=start, deterministic=True)
            obs, reward, terminated, truncated, info = env.step(action[0])
            start = np.zeros((1,), dtype=bool)
            if terminated or truncated:
                saves += bool(info.get("is_success", False))  # a time limit is no save
                break
    print(f"RecurrentPPO keeper, {model.num_timesteps} steps: {saves}/{episodes} saves "
          "(perceived ssl-2012)")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tiny", action="store_true",
                        default=bool(os.environ.get("SOCCER_EXAMPLES_TINY")),
                        help="a few steps only (CI; also SOCCER_EXAMPLES_TINY=1)")
    main(parser.parse_args().tiny)
