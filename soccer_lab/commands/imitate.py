"""``soccer-env imitate``: train a keeper by DAgger with a privileged teacher
(:func:`agents.runs.imitation.imitate`): the scripted keeper behind ``"ball-residual"``
actions learns, from perceived observations, the correction that its belief's ball velocity
needs to be the true one."""

from __future__ import annotations

import argparse
import dataclasses
import os
from types import SimpleNamespace

from agents.runs.imitation import ImitationConfig, imitate
from soccer_lab import extras
from soccer_lab.cli_args import HelpFormatter, add_env_arguments, env_kwargs_from_args

__all__ = ["parser", "main"]

_EXAMPLE = ("soccer-env imitate --robot humanoid-2012 --obs-mode perceived --env-kwarg "
            "perception='{\"camera\": \"kidsize-2012\", \"ball_tracker\": \"kick\"}' "
            "--env-kwarg belief_features=true --out runs/humanoid-keeper")


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env imitate``."""
    d = SimpleNamespace(**{f.name: f.default for f in dataclasses.fields(ImitationConfig)})
    p = argparse.ArgumentParser(
        prog="soccer-env imitate", formatter_class=HelpFormatter,
        description="Train a keeper on perceived observations by DAgger: round 0 plays the "
                    "scripted keeper, each later round the network fitted so far; every "
                    "step is labelled with the ball-residual action that would give the "
                    "scripted keeper the true ball velocity, and the network (tanh MLP over "
                    "the last FRAME-STACK observations) is fitted to all labels so far. "
                    "Writes a run folder whose final_policy.npz 'soccer-env eval --policy' "
                    "reads.",
        epilog=f"example:\n  {_EXAMPLE}")
    add_env_arguments(p)
    p.add_argument("--rounds", type=int, default=d.rounds, help="DAgger rounds")
    p.add_argument("--episodes", type=int, default=d.episodes, help="shots per round")
    p.add_argument("--frame-stack", type=int, default=d.frame_stack,
                   help="observations the network reads at once")
    p.add_argument("--hidden", type=int, nargs="+", default=list(d.hidden), metavar="N",
                   help="hidden layer sizes")
    p.add_argument("--epochs", type=int, default=d.epochs,
                   help="passes over the data set after each round")
    p.add_argument("--seed", type=int, default=d.seed,
                   help="seeds the network and offsets the training shots")
    p.add_argument("--eval-episodes", type=int, default=d.eval_episodes,
                   help="held-out shots after each round, beside the scripted keeper (0: none)")
    p.add_argument("--workers", type=int, default=None,
                   help="processes playing the shots; the result does not depend on it "
                        "(default: all cores)")
    p.add_argument("--out", default="runs/imitate",
                   help="the run folder; one that holds another run is refused")
    return p


def main(argv: list[str] | None = None) -> int:
    """``soccer-env imitate``: check the configuration, train, print each round."""
    p = parser()
    args = p.parse_args(argv)
    extras.require("imitate")
    workers = args.workers if args.workers is not None else (os.cpu_count() or 1)
    try:
        env_kwargs = env_kwargs_from_args(args)
        cfg = ImitationConfig(env_kwargs=env_kwargs, rounds=args.rounds,
                              episodes=args.episodes, frame_stack=args.frame_stack,
                              hidden=tuple(args.hidden), epochs=args.epochs, seed=args.seed,
                              eval_episodes=args.eval_episodes, workers=workers,
                              torch_threads=workers)
    except (ValueError, TypeError) as err:
        p.error(str(err))
    try:
        summary = imitate(cfg, args.out, command=["soccer-env", "imitate", *(argv or [])])
    except FileExistsError as err:
        p.error(f"--out: {err}")
    for row in summary["rounds"]:
        line = f"round {row['round']}: {row['steps']:,} steps, loss {row['loss']:.4f} " \
               f"(zero correction {row['zero_loss']:.4f})"
        if "save_rate" in row:
            line += (f", held-out save rate {100 * row['save_rate']:.1f} % (scripted "
                     f"{100 * row['scripted_save_rate']:.1f} %)")
        print(line)
    print(f"trained in {summary['train_seconds'] / 60:.1f} min "
          f"({summary['steps_per_s']:,.0f} steps/s); policy: {summary['final_policy']}")
    return 0
