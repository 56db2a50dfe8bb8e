"""Tianshou: PPO on the keeper, its environments in Tianshou's vector environments.

    pip install torch==2.13.0 && pip install -e ".[tianshou]"   # an environment of its own
    python examples/tianshou_keeper.py [--tiny] [--obs-mode perceived] [--vector subproc]

The keeper chooses where to stand on its guard line (``agents.policies.wrappers.GuardActions``).
Tianshou's collector checks every transition it stores for NaN, the infos included, and takes
a None for a NaN; the default infos hold none (``info["outcome"]`` is the empty string until
the shot ends), so they go into its buffer as they are (``info_mode="flat"`` works too, with
smaller buffers). ``--vector subproc`` steps the environments in worker processes
(``SubprocVectorEnv``) instead of in this one (``DummyVectorEnv``). After training, the policy
plays held-out shots deterministically and the saves are counted from the infos'
``is_success``.
"""

from __future__ import annotations

import argparse
import os

import gymnasium as gym
import numpy as np
import torch
from tianshou.algorithm import PPO
from tianshou.algorithm.modelfree.reinforce import ProbabilisticActorPolicy
from tianshou.algorithm.optim import AdamOptimizerFactory
from tianshou.data import Collector, VectorReplayBuffer
from tianshou.env import DummyVectorEnv, SubprocVectorEnv
from tianshou.trainer import OnPolicyTrainerParams
from tianshou.utils.net.common import Net
from tianshou.utils.net.continuous import ContinuousActorProbabilistic, ContinuousCritic
from torch.distributions import Independent, Normal

import soccer_env  # noqa: F401  (registers the environments)
from agents.policies.wrappers import GuardActions
from soccer_env.envs.registration import GOALKEEPER_ID

VECTORS = {"dummy": DummyVectorEnv, "subproc": SubprocVectorEnv}


def make_keeper(obs_mode: str) -> gym.Env:
    """One keeper environment (the default infos), acting on its guard line."""
    perception = {"perception": "ssl-2012"} if obs_mode == "perceived" else {}
    return GuardActions(gym.make(GOALKEEPER_ID, obs_mode=obs_mode, **perception))


def gaussian(loc_scale: tuple[torch.Tensor, torch.Tensor]) -> Independent:
    """The action distribution of the actor's (mean, standard deviation)."""
    loc, scale = loc_scale
    return Independent(Normal(loc, scale), 1)


def build_ppo(env: gym.Env, hidden: int) -> PPO:
    """PPO with a tanh MLP actor (state-independent standard deviation) and critic."""
    obs_shape, act_shape = env.observation_space.shape, env.action_space.shape
    actor = ContinuousActorProbabilistic(
        preprocess_net=Net(state_shape=obs_shape, hidden_sizes=(hidden, hidden),
                           activation=torch.nn.Tanh),
        action_shape=act_shape, unbounded=True)
    torch.nn.init.constant_(actor.sigma_param, -0.5)
    critic = ContinuousCritic(preprocess_net=Net(state_shape=obs_shape,
                                                 hidden_sizes=(hidden, hidden),
                                                 activation=torch.nn.Tanh))
    # The guard action's box is [-1, 1] already: no scaling, samples clipped to it.
    policy = ProbabilisticActorPolicy(actor=actor, dist_fn=gaussian, deterministic_eval=True,
                                      action_space=env.action_space,
                                      observation_space=env.observation_space,
                                      action_scaling=False, action_bound_method="clip")
    return PPO(policy=policy, critic=critic, optim=AdamOptimizerFactory(lr=3e-4),
               ent_coef=0.0, max_grad_norm=0.5, gamma=0.99)


def evaluate(ppo: PPO, obs_mode: str, episodes: int) -> tuple[int, float]:
    """Deterministic play on held-out shots: the saves and the mean episode length."""
    env = make_keeper(obs_mode)
    ppo.policy.eval()
    saves, steps = 0, 0
    for seed in range(10_000, 10_000 + episodes):
        obs, info = env.reset(seed=seed)
        done = False
        while not done:
            with torch.no_grad():
                action = ppo.policy.compute_action(obs)
            obs, reward, terminated, truncated, info = env.step(np.atleast_1d(action))
            steps += 1
            done = terminated or truncated
        saves += bool(info.get("is_success", False))  # absent after the time limit
    env.close()
    return saves, steps / episodes


def main(args: argparse.Namespace) -> None:
    """Train PPO on ``args.envs`` keepers, testing on as many after each epoch; evaluate."""
    torch.set_num_threads(1)
    torch.manual_seed(0)
    vector = VECTORS[args.vector]
    train_envs = vector([lambda: make_keeper(args.obs_mode)] * args.envs)
    test_envs = vector([lambda: make_keeper(args.obs_mode)] * args.envs)
    train_envs.seed(0)
    test_envs.seed(1_000)
    ppo = build_ppo(make_keeper(args.obs_mode), args.hidden)
    training = Collector(ppo, train_envs, VectorReplayBuffer(args.rollout, args.envs),
                         exploration_noise=True)
    testing = Collector(ppo, test_envs)
    result = ppo.run_training(OnPolicyTrainerParams(
        training_collector=training, test_collector=testing, max_epochs=args.epochs,
        epoch_num_steps=args.steps // args.epochs, collection_step_num_env_steps=args.rollout,
        update_step_num_repetitions=args.repeats, batch_size=args.batch_size,
        test_step_num_episodes=args.envs, verbose=False, show_progress=False))
    print(f"PPO keeper ({args.obs_mode}, {args.envs} {vector.__name__}s): trained "
          f"{result.timing.total_time:.1f} s, {training.collect_step} steps, "
          f"best test return {result.best_reward:.2f}")
    train_envs.close()
    test_envs.close()
    saves, length = evaluate(ppo, args.obs_mode, args.episodes)
    print(f"evaluation: {saves}/{args.episodes} saves, {length:.0f} steps per shot")


def parse(argv: list[str] | None = None) -> argparse.Namespace:
    """The command line; ``--tiny`` (or SOCCER_EXAMPLES_TINY=1) sets the CI sizes."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tiny", action="store_true",
                   default=bool(os.environ.get("SOCCER_EXAMPLES_TINY")),
                   help="a few thousand steps, small network (CI; also SOCCER_EXAMPLES_TINY=1)")
    p.add_argument("--obs-mode", choices=("truth", "perceived"), default="truth")
    p.add_argument("--vector", choices=sorted(VECTORS), default="dummy")
    p.add_argument("--envs", type=int, default=4,
                   help="environments of each vector environment (training, test)")
    p.add_argument("--steps", type=int, default=None, help="training steps")
    args = p.parse_args(argv)
    tiny = args.tiny
    args.steps = args.steps or (2_048 if tiny else 500_000)
    args.epochs = 2 if tiny else 50
    args.rollout = 512 if tiny else 2_048
    args.repeats = 2 if tiny else 10
    args.batch_size = 128 if tiny else 256
    args.hidden = 32 if tiny else 64
    args.episodes = 4 if tiny else 100
    return args


if __name__ == "__main__":
    main(parse())
