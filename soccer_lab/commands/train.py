"""``soccer-env train``: train a policy with stable-baselines3 (:func:`agents.runs.training.train`)
or, with ``--backend rllib``, with RLlib on this machine or a Ray cluster
(:mod:`soccer_lab.commands.train_rllib`).

The options become a :class:`~agents.runs.training.TrainConfig`; with ``--resume`` the rest of the
configuration comes from the checkpoint's run folder (its ``config.json``) unless given here,
and ``--steps`` (the total, the checkpoint's steps included) must exceed the checkpoint's
step count. ``--resume`` of an RLlib checkpoint folder picks the rllib backend by itself.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from pathlib import Path
from typing import Any

from agents.policies.action_maps import ACTION_MAPS
from agents.runs.folders import RunRefused, TrainingStopped, run_folder
from agents.runs.training import (
    CRITICS,
    OPPONENTS,
    TrainConfig,
    check_env_kwargs,
    checkpoint_steps,
    train,
)
from agents.sb3.algorithms import algorithm_name
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_env.perception.base import OBS_MODES
from soccer_lab import extras
from soccer_lab.cli_args import (
    HelpFormatter,
    add_env_arguments,
    add_trust_argument,
    check_perception,
    env_kwargs_from_args,
    key_values,
    sensor_preset,
)

__all__ = ["parser", "main"]

#: Options that set a :class:`~agents.runs.training.TrainConfig` field of the same meaning:
#: (field, option's attribute).
_FIELD_OPTIONS = (("env_id", "env"), ("algorithm", "algo"), ("total_steps", "steps"),
                  ("n_envs", "n_envs"), ("n_workers", "workers"), ("seed", "seed"),
                  ("out", "out"), ("checkpoint_every", "checkpoint_every"),
                  ("eval_every", "eval_every"), ("eval_episodes", "eval_episodes"),
                  ("learner", "learner"), ("actions", "actions"), ("opponent", "opponent"),
                  ("frame_stack", "frame_stack"), ("critic", "critic"), ("batched", "batched"))

#: The algorithms as the command line spells them.
ALGORITHMS = ("ppo", "a2c", "sac", "td3", "ddpg", "recurrent-ppo")


def _algorithm(text: str) -> str:
    """``--algo``'s value in its canonical spelling (``ppo`` -> ``PPO``, ``recurrent-ppo`` ->
    ``RECURRENTPPO``)."""
    try:
        return algorithm_name(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid choice: {text!r} (choose from "
                                         f"{', '.join(ALGORITHMS)})") from None


def _default(name: str) -> Any:
    """The default of :class:`~agents.runs.training.TrainConfig` field ``name``."""
    return next(f.default for f in dataclasses.fields(TrainConfig) if f.name == name)


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env train``.

    The options default to None so that ``--resume`` can tell what is given from what the
    run's ``config.json`` sets; their help states :class:`~agents.runs.training.TrainConfig`'s
    defaults, which apply to a new run.
    """
    p = argparse.ArgumentParser(
        prog="soccer-env train", formatter_class=HelpFormatter,
        description="Train a policy with stable-baselines3 (the train extra) or with RLlib on "
                    "this machine or a Ray cluster (--backend rllib, the rllib extra). The "
                    "defaults below are a new run's; with --resume what is not given comes "
                    "from the run's config.json.",
        epilog="examples:\n"
               "  soccer-env train --obs-mode perceived --perception ssl-2012 "
               "--steps 2000000 --out runs/keeper\n"
               "  soccer-env train --algo recurrent-ppo        # memory: an LSTM policy\n"
               "  soccer-env train --frame-stack 4             # memory: the last 4 "
               "observations\n"
               "  soccer-env train --resume runs/keeper/final_model.zip --steps 3000000\n"
               "  soccer-env train --backend rllib --num-env-runners 8 --address HEAD:6379")
    p.add_argument("--backend", choices=("sb3", "rllib"), default=None,
                   help="sb3: stable-baselines3 in this process and its subprocesses; rllib: "
                        "RLlib's PPO, sampling on env runners that Ray spreads over the "
                        "machines of a cluster (default: sb3, or rllib to resume an RLlib "
                        "checkpoint)")
    p.add_argument("--num-env-runners", type=int, default=None, metavar="N",
                   help="rllib: env runners (Ray actors of one CPU each, placed on any node "
                        "of the cluster; 0 samples in this process) (default: 2)")
    p.add_argument("--address", default=None,
                   help="rllib: join the running Ray cluster at ADDRESS (HEAD:6379 of `ray "
                        "start --head --port=6379`, or auto) (default: start Ray on this "
                        "machine)")
    p.add_argument("--env", default=None, choices=(GOALKEEPER_ID, MATCH_ID),
                   help=f"environment (default: {_default('env_id')})")
    add_env_arguments(p)
    p.add_argument("--algo", default=None, type=_algorithm,
                   metavar="{" + ",".join(ALGORITHMS) + "}",
                   help="algorithm; recurrent-ppo is sb3-contrib's RecurrentPPO with an LSTM "
                        "policy (MlpLstmPolicy), whose memory carries the episode so far "
                        f"(default: {_default('algorithm').lower()})")
    p.add_argument("--steps", type=int, default=None,
                   help="total environment steps; with --resume the total including the steps "
                        "the checkpoint already trained, so it must exceed them (e.g. --resume "
                        "model_1000000_steps.zip --steps 1500000 trains 500,000 more); rllib "
                        "counts environment steps (match steps for the match), sb3 agent steps "
                        f"(default: {_default('total_steps')})")
    p.add_argument("--critic", choices=CRITICS, default=None,
                   help="PPO and A2C on Goalkeeper-v0: shared (the critic reads the actor's "
                        "observation) or privileged (the critic also reads the true state in "
                        "training, the actor only the observation; the saved numpy policy is "
                        f"the actor alone) (default: {_default('critic')})")
    p.add_argument("--frame-stack", type=int, default=None, metavar="N",
                   help="feed-forward algorithms, Goalkeeper-v0: the learner sees its last N "
                        "observations concatenated, oldest first, the episode's first "
                        "repeated to fill (1: the observation alone); the saved numpy policy "
                        "keeps the history and acts on single observations "
                        f"(default: {_default('frame_stack')})")
    p.add_argument("--n-envs", type=int, default=None, metavar="N",
                   help="parallel environments; rllib: per env runner "
                        f"(default: {_default('n_envs')}; rllib: 8)")
    p.add_argument("--workers", type=int, default=None, metavar="N",
                   help="subprocesses stepping the environments (0: all in this process) "
                        f"(default: {_default('n_workers')}; 0 with --batched)")
    p.add_argument("--batched", action="store_true", default=None,
                   help="step the environments as one batch (shared pymunk spaces). "
                        "Goalkeeper-v0: the --n-envs environments in this process (native "
                        "actions, every keeper and observation mode, each environment "
                        "perceiving on its own). Match-v0: each process's matches, in this "
                        "process or in each of --workers workers")
    p.add_argument("--seed", type=int, default=None,
                   help="seed of the environments and the learner "
                        f"(default: {_default('seed')})")
    p.add_argument("--out", default=None,
                   help="run folder; one that holds another run is refused unless --force "
                        f"(default: {_default('out')}; with --resume, the folder of the run "
                        "it resumes)")
    p.add_argument("--force", action="store_true",
                   help="train into an --out that holds another run, deleting that run's "
                        "files first (config, models, policies, statistics, checkpoints/, "
                        "tb/; nothing else)")
    p.add_argument("--hp", action="append", default=[], metavar="KEY=VALUE",
                   help="algorithm hyperparameter (JSON value), repeatable, e.g. "
                        "--hp learning_rate=1e-4 --hp policy_kwargs='{\"net_arch\": [64, 64]}' "
                        "(policy_kwargs merge over the algorithm's defaults, e.g. "
                        "recurrent-ppo's lstm_hidden_size 64); rllib: PPOConfig settings, "
                        "e.g. --hp lr=1e-4 --hp train_batch_size_per_learner=8192 --hp "
                        "model_config='{\"fcnet_hiddens\": [128, 128]}'")
    p.add_argument("--checkpoint-every", type=int, default=None, metavar="STEPS",
                   help="save a checkpoint (model and statistics) into checkpoints/ every "
                        "STEPS steps (0: none) "
                        f"(default: {_default('checkpoint_every')})")
    p.add_argument("--eval-every", type=int, default=None, metavar="STEPS",
                   help="sb3: evaluate on a fixed shot suite every STEPS steps and keep the "
                        "best model as best_model.zip (0: never) "
                        f"(default: {_default('eval_every')})")
    p.add_argument("--eval-episodes", type=int, default=None, metavar="N",
                   help="sb3: shots of each periodic evaluation "
                        f"(default: {_default('eval_episodes')})")
    p.add_argument("--eval-obs-mode", choices=OBS_MODES, default=None,
                   help="sb3: evaluate (and select the best model) under this observation "
                        "mode (default: the training environment's)")
    p.add_argument("--eval-perception", type=sensor_preset, default=None, metavar="PRESET",
                   help="sb3: evaluate under this sensor preset (as --perception) "
                        "(default: the training environment's)")
    p.add_argument("--actions", choices=tuple(ACTION_MAPS), default=None,
                   help="keeper learner's actions: native (the robot's command), velocity "
                        "(field-frame velocity and turn rate), target (where to stand, "
                        "reached by a motion controller), guard (where to stand on the guard "
                        "line), guard-residual (a correction to where the scripted keeper "
                        "would stand on it) or ball-residual (a correction to the ball "
                        "velocity the scripted keeper believes; SSL and humanoid keepers) "
                        f"(default: {_default('actions')})")
    p.add_argument("--learner", choices=("blue", "yellow", "both"), default=None,
                   help="match: the learning team; rllib: both has one shared module play "
                        "every robot, blue or yellow a module of that team against --opponent "
                        f"(default: {_default('learner')}; rllib: both)")
    p.add_argument("--opponent", default=None,
                   help=f"match: {', '.join(OPPONENTS)} (self: a frozen copy of the learner, "
                        "refreshed as it trains) or the path of a numpy policy file (.npz, "
                        "e.g. a run's final_policy.npz); rllib: self (a frozen copy of the "
                        "learning module, refreshed every 100,000 steps) or learning (the "
                        f"other team learns a module of its own) (default: "
                        f"{_default('opponent')}; rllib: self)")
    p.add_argument("--resume", default=None, metavar="CHECKPOINT",
                   help="continue from a checkpoint .zip, or a run's RLlib checkpoint folder "
                        "(its final_checkpoint or checkpoints/checkpoint_<steps>_steps; "
                        "selects --backend rllib); the rest of the configuration comes from "
                        "its run's config.json unless given here")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bar (which needs tqdm and rich, of the train extra)")
    add_trust_argument(p)
    return p


def _resumed_fields(p: argparse.ArgumentParser, resume: str) -> dict[str, Any]:
    """The configuration of the run that checkpoint ``resume`` belongs to (its folder, or the
    folder above ``checkpoints/``), without what describes that run only."""
    ckpt = Path(resume)
    if not ckpt.is_file():
        p.error(f"--resume: no checkpoint at {ckpt}")
    run = run_folder(ckpt)
    if not (run / "config.json").exists():
        p.error(f"--resume: no config.json in {run}")
    saved = json.loads((run / "config.json").read_text())
    base = {k: v for k, v in saved.items()
            if k not in ("command", "resumed_from", "versions", "action_map")}
    # The run continues where it is, never where its config.json says: a run folder received
    # from elsewhere must not choose where files are written.
    base["out"] = str(run)
    return base


def _config(args: argparse.Namespace, base: dict[str, Any]) -> TrainConfig:
    """The training configuration of the options over ``base`` (a resumed run's); raises
    ``ValueError`` or ``TypeError`` for bad values."""
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
              "eval_env_kwargs": eval_kwargs, "progress_bar": not args.no_progress}
    for name, option in _FIELD_OPTIONS:
        value = getattr(args, option)
        if value is not None:
            fields[name] = value
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
    for option, value in (("--num-env-runners", args.num_env_runners),
                          ("--address", args.address)):
        if value is not None:
            p.error(f"{option} is for --backend rllib")
    # Before the configuration, whose checks read stable-baselines3's algorithms.
    extras.require("train")
    base = _resumed_fields(p, args.resume) if args.resume else {}
    algo = str(args.algo or base.get("algorithm", "")).upper().replace("-", "").replace("_", "")
    if algo == "RECURRENTPPO":
        extras.require("train --algo recurrent-ppo")
    if not args.no_progress:
        extras.require("train progress bar", "train",
                       hint="or train without the progress bar: --no-progress")
    try:
        cfg = _config(args, base)
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
