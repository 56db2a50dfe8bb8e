"""SuperSuit to stable-baselines3: PPO with one shared policy for every robot of the match.

    pip install supersuit==3.11.0
    python examples/supersuit_match_ppo.py [--tiny]

``pettingzoo_env_to_vec_env_v1`` makes each agent of the parallel match one entry of a
vector environment, ``concat_vec_envs_v1`` stacks several matches (in worker processes: the
environments are picklable) and gives stable-baselines3's ``VecEnv``. Both teams' robots are
learners of the same policy (self-play by parameter sharing; yellow sees the field in its own
frame). ``info_mode="flat"`` keeps the infos that cross the process boundary small.
The package's own adapter, ``agents.vec.match.MatchVecEnv``, does the same with a fixed
opponent or self-play against a frozen copy (``soccer-env train --env soccer_env/Match-v0``).
"""

from __future__ import annotations

import argparse
import os

import supersuit as ss
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.utils import set_random_seed
from stable_baselines3.common.vec_env import VecMonitor

import soccer_env


def main(tiny: bool) -> None:
    torch.set_num_threads(1)
    match = soccer_env.parallel_env(blue=2, yellow=2, match_duration=20.0,
                                    max_cycles=100 if tiny else 1200,
                                    shaping={"ball_progress": 1.0, "ball_distance": 0.1},
                                    info_mode="flat")
    venv = ss.pettingzoo_env_to_vec_env_v1(match)
    venv = ss.concat_vec_envs_v1(venv, 2 if tiny else 4, num_cpus=1 if tiny else 2,
                                 base_class="stable_baselines3")
    # SuperSuit 3.11's stable-baselines3 wrapper has no seed(), which PPO(seed=...) calls
    # (AttributeError: 'ConcatVecEnv' object has no attribute 'seed'): seed the matches
    # through the wrapped vector environment's reset instead (each match keeps its generator
    # across the resets that follow), and torch and numpy with set_random_seed.
    venv.venv.reset(seed=0)
    set_random_seed(0)
    venv = VecMonitor(venv)
    print(f"{venv.num_envs} learners (agents x matches), observations "
          f"{venv.observation_space.shape}")
    model = PPO("MlpPolicy", venv, n_steps=32 if tiny else 256, batch_size=64 if tiny else 512,
                n_epochs=2 if tiny else 10, verbose=0 if tiny else 1)
    model.learn(256 if tiny else 200_000)
    print(f"trained {model.num_timesteps} agent steps")
    venv.close()

    # The shared policy plays the match's four robots.
    env = soccer_env.parallel_env(blue=2, yellow=2, max_cycles=50 if tiny else 1200)
    obs, infos = env.reset(seed=1)
    while env.agents:
        actions = {a: model.predict(obs[a], deterministic=True)[0] for a in env.agents}
        obs, rewards, terminations, truncations, infos = env.step(actions)
    print("score:", infos["blue_0"]["score"])


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tiny", action="store_true",
                        default=bool(os.environ.get("SOCCER_EXAMPLES_TINY")),
                        help="a few steps only (CI; also SOCCER_EXAMPLES_TINY=1)")
    main(parser.parse_args().tiny)
