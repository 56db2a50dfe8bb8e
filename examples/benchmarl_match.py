"""BenchMARL: MAPPO or IPPO on the 2 vs 2 match, evaluated, then reloaded from its checkpoint.

    pip install torch==2.13.0 && pip install -e ".[benchmarl]"   # an environment of its own
    python examples/benchmarl_match.py --algorithm mappo         # or ippo
    python examples/benchmarl_match.py --algorithm ippo --tiny   # seconds: what the tests run
    python examples/benchmarl_match.py --restore CHECKPOINT.pt   # reload and play a match

The task is ``SoccerTask.MATCH`` (:mod:`agents.runs.benchmarl`): the match through TorchRL's
``PettingZooWrapper``, one group per team, both teams learning. After training, BenchMARL
evaluates the policies (its logs in the experiment folder under ``--out``: CSV files and a
JSON file), and the example builds the experiment again from its checkpoint
(``Experiment.reload_from_file``), checks that its policies are the trained ones and plays one
deterministic match with them; ``--restore`` does the last in a new process.
``SOCCER_EXAMPLES_TINY=1`` is the same as ``--tiny``. BenchMARL pins an older TorchRL than the
clients extra does, hence its own environment (docs/guide/rl-libraries.md).
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import torch
from benchmarl.algorithms import IppoConfig, MappoConfig
from benchmarl.experiment import Experiment, ExperimentConfig
from benchmarl.models.mlp import MlpConfig
from torchrl.envs.utils import ExplorationType, set_exploration_type

from agents.runs.benchmarl import SoccerTask

ALGORITHMS = {"mappo": MappoConfig, "ippo": IppoConfig}


def experiment_config(args: argparse.Namespace) -> ExperimentConfig:
    """BenchMARL's default experiment, sized by ``--tiny`` and ``--iterations``, logging to
    CSV files (no Weights & Biases) and checkpointing at its end."""
    config = ExperimentConfig.get_from_yaml()
    frames, envs = (160, 2) if args.tiny else (12_000, 10)
    config.max_n_iters = args.iterations or (2 if args.tiny else 200)
    config.max_n_frames = None
    config.on_policy_collected_frames_per_batch = frames
    config.on_policy_n_envs_per_worker = envs
    config.on_policy_n_minibatch_iters = 2 if args.tiny else 20
    config.on_policy_minibatch_size = 80 if args.tiny else 1200
    config.lr = 3e-4
    config.evaluation = True
    config.evaluation_interval = frames * config.max_n_iters  # once, at the end
    config.evaluation_episodes = 1 if args.tiny else 5
    config.render = False
    config.loggers = ["csv"]
    config.checkpoint_at_end = True
    config.save_folder = str(args.out)
    return config


def play_match(experiment: Experiment) -> str:
    """One match of the experiment's policies, deterministic: its score and length."""
    with torch.no_grad(), set_exploration_type(ExplorationType.DETERMINISTIC):
        rollout = experiment.test_env.rollout(experiment.max_steps, policy=experiment.policy,
                                              break_when_any_done=True)
    last = rollout[-1]["next"]
    return (f"blue {int(last['blue', 'info', 'score_blue'][0])} : "
            f"{int(last['blue', 'info', 'score_yellow'][0])} yellow, "
            f"{rollout.shape[0]} steps")


def train(args: argparse.Namespace) -> Experiment:
    """Train ``--algorithm`` on the match; BenchMARL evaluates the policies at the end and
    saves a checkpoint."""
    # 2 vs 2; full size: matches of 30 s shaped towards the ball and the opponent goal.
    task = SoccerTask.MATCH.get_task({"max_cycles": 40} if args.tiny else None)
    model = MlpConfig.get_from_yaml()
    if args.tiny:
        model.num_cells = [16]
    experiment = Experiment(task=task, algorithm_config=ALGORITHMS[args.algorithm].get_from_yaml(),
                            model_config=model, seed=0, config=experiment_config(args))
    t0 = time.perf_counter()
    experiment.run()
    print(f"{args.algorithm}: {experiment.n_iters_performed} iterations, "
          f"{experiment.total_frames:,} steps in {time.perf_counter() - t0:.1f} s, "
          f"mean return {experiment.mean_return:.3f}")
    print(f"evaluation match: {play_match(experiment)}")
    return experiment


def reload(checkpoint: Path, trained: Experiment | None = None) -> bool:
    """Build the experiment again from ``checkpoint`` and play a match; whether its policies'
    weights are ``trained``'s (True without ``trained``)."""
    # A checkpoint holds pickles: reload your own only.
    restored = Experiment.reload_from_file(str(checkpoint))
    same = True
    if trained is not None:
        before, after = trained.policy.state_dict(), restored.policy.state_dict()
        same = before.keys() == after.keys() and all(
            torch.equal(v, after[k]) for k, v in before.items() if isinstance(v, torch.Tensor))
    print(f"reloaded {checkpoint.name} ({restored.n_iters_performed} iterations"
          f"{'' if trained is None else ', weights identical' if same else ', weights DIFFER'})"
          f": {play_match(restored)}")
    restored.close()
    return same


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--algorithm", choices=sorted(ALGORITHMS), default="mappo")
    p.add_argument("--tiny", action="store_true",
                   default=bool(os.environ.get("SOCCER_EXAMPLES_TINY")),
                   help="matches of 40 steps, a tiny network, 2 iterations of 160 steps")
    p.add_argument("--iterations", type=int, default=None, help="training iterations")
    p.add_argument("--out", type=Path, default=Path("runs/benchmarl_match"),
                   help="where BenchMARL writes the experiment's folder")
    p.add_argument("--restore", type=Path, default=None,
                   help="no training: reload this checkpoint (.pt) and play a match")
    args = p.parse_args(argv)
    torch.set_num_threads(1)
    if args.restore is not None:
        return 0 if reload(args.restore) else 1
    args.out.mkdir(parents=True, exist_ok=True)
    experiment = train(args)
    checkpoint = sorted((experiment.folder_name / "checkpoints").glob("checkpoint_*.pt"))[-1]
    same = reload(checkpoint, experiment)
    print(f"checkpoint: {checkpoint}")
    experiment.close()
    return 0 if same else 1


if __name__ == "__main__":
    raise SystemExit(main())
