"""Self-play PPO on batched matches: hundreds of 2 vs 2 matches per process.

    python examples/batched_self_play.py [--tiny]

``make_match_vec_env(..., batched=True, workers=2)`` splits the matches over two worker
processes, each stepping its half as one batch (shared pymunk spaces, numpy over the batch;
``agents.vec.batched.BatchedMatchVecEnv``), and exposes every blue robot of every match as one
entry of stable-baselines3's ``VecEnv`` (parameter sharing). The yellow team starts as the
scripted team and ``SelfPlayCallback`` replaces it with frozen copies of the learner as
training goes on, each match drawing one from a pool when it restarts. The same run from the
command line: ``soccer-env train --env soccer_env/Match-v0 --batched --workers 2
--n-envs 256 --opponent self``.
"""

from __future__ import annotations

import argparse
import os

import torch
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecMonitor

import soccer_env
from agents.vec.factories import make_match_vec_env
from agents.vec.self_play import SelfPlayCallback


def main(tiny: bool) -> None:
    torch.set_num_threads(1)
    matches = 8 if tiny else 256
    venv = make_match_vec_env(
        {"blue": 2, "yellow": 2, "match_duration": 2.0 if tiny else 60.0,
         "shaping": {"ball_progress": 1.0, "ball_distance": 0.1}},
        n_matches=matches, learner="blue", opponent="scripted", seed=0, workers=2,
        batched=True)
    venv = VecMonitor(venv)
    print(f"{venv.num_envs} learners ({matches} matches x 2 blue robots), observations "
          f"{venv.observation_space.shape}")
    model = PPO("MlpPolicy", venv, n_steps=16 if tiny else 128,
                batch_size=64 if tiny else 4096, n_epochs=2 if tiny else 5, seed=0,
                verbose=0 if tiny else 1)
    callback = SelfPlayCallback(update_every=256 if tiny else 500_000, pool_size=4)
    model.learn(512 if tiny else 20_000_000, callback=callback)
    print(f"trained {model.num_timesteps} agent steps, {callback.n_updates} opponent copies")
    venv.close()

    # The shared policy plays blue against the scripted yellow team in one match.
    from agents.scripted import ScriptedTeam

    env = soccer_env.parallel_env(blue=2, yellow=2, match_duration=2.0 if tiny else 60.0)
    yellow = ScriptedTeam.for_env(env, "yellow")
    obs, infos = env.reset(seed=1)
    while env.agents:
        actions = {a: model.predict(obs[a], deterministic=True)[0]
                   for a in env.agents if a.startswith("blue")}
        actions.update(yellow(obs))
        obs, rewards, terminations, truncations, infos = env.step(actions)
    print("score:", infos["blue_0"]["score"])


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tiny", action="store_true",
                        help="a few hundred steps (what the tests run)")
    args = parser.parse_args()
    main(args.tiny or os.environ.get("SOCCER_EXAMPLES_TINY") == "1")
