"""``soccer-env train``: train a policy with stable-baselines3 (:func:`agents.runs.training.train`)
or, with ``--backend rllib``, with RLlib on this machine or a Ray cluster
(:mod:`soccer_lab.commands.train_rllib`).

The options (declared in :mod:`soccer_lab.commands.train_options`, which builds the parser)
become a :class:`~agents.runs.training.TrainConfig`; with ``--resume`` the rest of the
configuration comes from the checkpoint's run folder (its ``config.json``) unless given here,
and ``--steps`` (the total, the checkpoint's steps included) must exceed the checkpoint's
step count. ``--resume`` of an RLlib checkpoint folder picks the rllib backend by itself.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

from agents.runs.folders import RunRefused, TrainingStopped, read_run_config, run_folder
from agents.runs.limits import check_saved_settings
from agents.runs.training import TrainConfig, check_env_kwargs, checkpoint_steps, train
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_lab import extras
from soccer_lab.cli_args import (
    check_perception,
    env_kwargs_from_args,
    key_values,
)
from soccer_lab.commands.train_options import given_fields, parser, refuse_options

__all__ = ["parser", "main", "train_config"]


def _resumed_fields(p: argparse.ArgumentParser, args: argparse.Namespace) -> dict[str, Any]:
    """The configuration of the run that checkpoint ``args.resume`` belongs to (its folder, or
    the folder above ``checkpoints/``), without what describes that run only; settings that
    the command line does not give must lie within the limits of
    :mod:`agents.runs.limits` unless ``--trust``."""
    ckpt = Path(args.resume)
    if not ckpt.is_file():
        p.error(f"--resume: no checkpoint at {ckpt}")
    run = run_folder(ckpt)
    if not (run / "config.json").exists():
        p.error(f"--resume: no config.json in {run}")
    try:
        saved = read_run_config(run / "config.json")
        check_saved_settings(saved, run / "config.json", given_fields(args, "sb3"),
                             key_values(args.hp, "--hp"), args.trust)
    except (OSError, ValueError) as err:
        p.error(f"--resume: {err}")
    base = {k: v for k, v in saved.items()
            if k not in ("command", "resumed_from", "versions", "action_map")}
    # The run continues where it is, never where its config.json says: a run folder received
    # from elsewhere must not choose where files are written.
    base["out"] = str(run)
    return base


def train_config(args: argparse.Namespace, base: dict[str, Any]) -> TrainConfig:
    """The training configuration of the options ``args`` (of :func:`parser`) over ``base``
    (a resumed run's configuration, or empty for a new run): the environment's options, the
    evaluation's, ``--hp`` and every option of
    :data:`~soccer_lab.commands.train_options.TRAIN_OPTIONS` that sets a field
    (:func:`~soccer_lab.commands.train_options.given_fields`); raises ``ValueError`` or
    ``TypeError`` for bad values."""
    env_kwargs = env_kwargs_from_args(args, base.get("env_kwargs"))
    eval_kwargs = base.get("eval_env_kwargs")
    if args.eval_obs_mode or args.eval_perception:
        eval_kwargs = dict(env_kwargs)
        if args.eval_obs_mode:
            eval_kwargs["obs_mode"] = args.eval_obs_mode
        if args.eval_perception:
            check_perception(args.eval_perception, eval_kwargs.get("robot"),
                             "--eval-perception")
            eval_kwargs["perception"] = args.eval_perception
    hyper = {**base.get("hyperparams", {}), **key_values(args.hp, "--hp")}
    fields = {**base, "env_kwargs": env_kwargs, "hyperparams": hyper,
              "eval_env_kwargs": eval_kwargs, "progress_bar": not args.no_progress,
              **given_fields(args, "sb3")}
    if fields.get("batched") and args.workers is None and "n_workers" not in base and \
            fields.get("env_id", GOALKEEPER_ID) == GOALKEEPER_ID:
        fields["n_workers"] = 0  # the keeper's batch is one process
    cfg = TrainConfig.from_dict(fields)
    check_env_kwargs(cfg)
    return cfg


def _check_resume(p: argparse.ArgumentParser, args: argparse.Namespace, cfg: TrainConfig,
                  base: dict[str, Any]) -> None:
    """Refuse a resumed run that would train nothing (``--steps`` at or below the
    checkpoint's step count) or that stacks another number of frames than the checkpoint's
    network reads."""
    try:
        done = checkpoint_steps(args.resume)
    except ValueError as err:
        p.error(f"--resume: {err}")
    if cfg.total_steps <= done:
        given = (f"--steps {cfg.total_steps}" if args.steps is not None else
                 f"the run's total_steps {cfg.total_steps} (from its config.json; set it with "
                 "--steps)")
        p.error(f"{given} leaves nothing to train: the checkpoint {args.resume} has already "
                f"trained {done} steps, and --steps is the total count including them; e.g. "
                f"--steps {done + cfg.total_steps} trains {cfg.total_steps} more")
    saved = int(base.get("frame_stack", 1))
    if cfg.frame_stack != saved:
        p.error(f"--frame-stack {cfg.frame_stack}: the checkpoint's network reads {saved} "
                "stacked observation(s)")
    saved_critic = base.get("critic", "shared")
    if cfg.critic != saved_critic:
        p.error(f"--critic {cfg.critic}: the checkpoint's network has a {saved_critic} critic")


def _print_summary(summary: dict[str, Any], out: str) -> None:
    rate = summary["rollout_steps_per_s"]
    rollouts = f", {rate:,.0f} steps/s collecting rollouts" if math.isfinite(rate) else ""
    print(f"trained {summary['trained_steps']:,} steps in {summary['seconds'] / 60:.1f} min "
          f"({summary['steps_per_s']:,.0f} steps/s overall{rollouts})")
    for key in ("last_evaluation", "best_evaluation"):
        ev = summary.get(key)
        if ev:
            print(f"{key.replace('_', ' ')}: save rate {100 * ev['save_rate']:.1f} % "
                  f"({100 * ev['ci_low']:.1f}-{100 * ev['ci_high']:.1f}) at {ev['steps']:,} "
                  "steps")
    print(f"run folder: {out}")


def main(argv: list[str] | None = None) -> int:
    """``soccer-env train``: check the configuration, train, print the summary."""
    p = parser()
    args = p.parse_args(argv)
    from soccer_lab.commands import train_rllib

    rllib_checkpoint = train_rllib.is_rllib_checkpoint(args.resume)
    if args.backend == "rllib" or (args.backend is None and rllib_checkpoint):
        return train_rllib.main(p, args, argv)
    if rllib_checkpoint:
        p.error(f"--resume {args.resume} is an RLlib checkpoint: resume it with --backend rllib")
    refuse_options(p, args, "sb3")
    # Before the configuration, whose checks read stable-baselines3's algorithms.
    extras.require("train")
    base = _resumed_fields(p, args) if args.resume else {}
    algo = str(args.algo or base.get("algorithm", "")).upper().replace("-", "").replace("_", "")
    if algo == "RECURRENTPPO":
        extras.require("train --algo recurrent-ppo")
    if not args.no_progress:
        extras.require("train progress bar", "train",
                       hint="or train without the progress bar: --no-progress")
    try:
        cfg = train_config(args, base)
    except (ValueError, TypeError) as err:
        p.error(str(err))
    if args.resume:
        _check_resume(p, args, cfg, base)
    try:
        summary = train(cfg, resume=args.resume, command=["soccer-env", "train", *(argv or [])],
                        overwrite=args.force, trust=args.trust)
    except RunRefused as err:
        p.error(str(err))
    except TrainingStopped as stopped:
        # Ctrl-C or a failed rollout worker: the message says what happened, what was saved
        # and how to continue; no traceback (the worker's, if any, is in the message).
        print(f"soccer-env train: {stopped}", file=sys.stderr)
        return 130 if stopped.reason == "interrupted" else 1
    _print_summary(summary, cfg.out)
    return 0
