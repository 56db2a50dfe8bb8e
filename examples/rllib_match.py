"""Train the soccer match with RLlib: self-play PPO whose env runners Ray spreads over the
machines of a cluster (docs/tutorials/ray-cluster.md).

    python examples/rllib_match.py                      # Ray on this machine
    python examples/rllib_match.py --address HEAD:6379  # a running cluster
    python examples/rllib_match.py --tiny               # seconds: what the tests run

Blue's robots play module ``main``, which learns; yellow's play ``opponent``, a frozen copy of
``main`` that :class:`agents.runs.rllib.SelfPlayCallback` refreshes as it trains. After training,
the example saves a checkpoint, builds the algorithm again from it
(``Algorithm.from_checkpoint``) and evaluates the learner deterministically against its
copy. ``SOCCER_ENV_EXAMPLE_TINY=1`` is the same as ``--tiny``.

The same training from the command line, with a run folder, checkpoints and ``--resume``::

    soccer-env train --backend rllib --env soccer_env/Match-v0 --learner blue \\
        --opponent self --env-kwarg blue=2 --env-kwarg yellow=2 --num-env-runners 2
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import ray
from ray.rllib.algorithms.algorithm import Algorithm

from agents.runs.rllib import ppo_config
from soccer_env.envs.registration import MATCH_ID


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tiny", action="store_true",
                   default=os.environ.get("SOCCER_ENV_EXAMPLE_TINY") == "1",
                   help="a 1 v 1 match of 40 steps, tiny batches and network, 2 iterations")
    p.add_argument("--iterations", type=int, default=None, help="training iterations")
    p.add_argument("--num-env-runners", type=int, default=2)
    p.add_argument("--address", default=None, help="a running Ray cluster (HEAD:6379)")
    p.add_argument("--out", default="runs/rllib_match", help="checkpoint folder")
    args = p.parse_args(argv)

    if args.tiny:
        env_config = {"blue": 1, "yellow": 1, "max_cycles": 40}
        hyperparams = {"train_batch_size_per_learner": 100, "minibatch_size": 50,
                       "num_epochs": 1, "model_config": {"fcnet_hiddens": [16]}}
        iterations, self_play_every = args.iterations or 2, 100
    else:
        # 2 v 2 matches of 30 s with shaping towards the ball and the opponent goal.
        env_config = {"blue": 2, "yellow": 2, "match_duration": 30.0,
                      "shaping": {"ball_progress": 1.0, "ball_distance": 0.1}}
        hyperparams = {}
        iterations, self_play_every = args.iterations or 100, 50_000

    ray.init(address=args.address, logging_level="WARNING")
    config = ppo_config(MATCH_ID, env_config, policy_mapping="self-play", learner="blue",
                        num_env_runners=args.num_env_runners, hyperparams=hyperparams,
                        self_play_every=self_play_every)
    # Deterministic evaluation on an env runner of its own, with the training runners'
    # observation statistics (RLlib's advice for MeanStdFilter); it asks for no CPU, as it
    # runs while the training runners wait.
    config.evaluation(evaluation_num_env_runners=1, evaluation_duration=1,
                      evaluation_duration_unit="episodes",
                      evaluation_config={"explore": False, "use_worker_filter_stats": False,
                                         "num_cpus_per_env_runner": 0})
    algo = config.build_algo()
    t0 = time.perf_counter()
    for _ in range(iterations):
        result = algo.train()
        runners = result["env_runners"]
        returns = runners.get("module_episode_return_mean", {})  # once a match has ended
        print(f"iteration {result['training_iteration']}: "
              f"{int(result['num_env_steps_sampled_lifetime']):,} steps, "
              f"learner's return {float(returns.get('main', float('nan'))):.3f}, "
              f"self-play copies {result['self_play_updates']}, "
              f"steps by node {dict(runners['steps_by_node'])}")
    print(f"trained in {time.perf_counter() - t0:.1f} s")
    checkpoint = algo.save_to_path(str(Path(args.out).resolve()))
    algo.stop()

    # A checkpoint is a pickle: build from your own checkpoints only (soccer-env train signs
    # its own and loads no other without --trust).
    restored = Algorithm.from_checkpoint(checkpoint)
    evaluation = restored.evaluate()["env_runners"]
    print(f"evaluation match: blue (learner) {evaluation['blue_goals']:.0f} : "
          f"{evaluation['yellow_goals']:.0f} yellow (its frozen copy), "
          f"{evaluation['episode_len_mean']:.0f} steps")
    print(f"checkpoint: {checkpoint}")
    restored.stop()
    ray.shutdown()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
