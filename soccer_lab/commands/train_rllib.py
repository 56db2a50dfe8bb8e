"""``soccer-env train --backend rllib``: train with RLlib on this machine or a Ray cluster
(:func:`agents.runs.rllib_runs.train`).

The options of ``soccer-env train`` keep their meaning where RLlib has one: ``--env``, the
environment options, ``--steps`` (environment steps; for the match, match steps however many
robots play), ``--n-envs`` (environments per env runner), ``--seed``, ``--out``, ``--force``,
``--hp`` (RLlib ``PPOConfig`` settings), ``--checkpoint-every``, ``--actions`` and
``--frame-stack`` (the keeper), ``--resume`` (an RLlib checkpoint folder of a run), ``--trust``
and ``--no-progress``. The match's ``--learner`` and ``--opponent`` choose the policy mapping
(:data:`agents.runs.rllib.POLICY_MAPPINGS`):

=================================================  ==============  ==========================
options                                            mapping         modules
=================================================  ==============  ==========================
``--learner both`` (the default)                   shared          ``shared`` plays every
                                                                   robot
``--learner blue --opponent self`` (or no          self-play       ``main`` learns and plays
``--opponent``)                                                    blue, ``opponent`` (a
                                                                   frozen copy of ``main``)
                                                                   yellow
``--learner blue --opponent learning``             per-team        ``blue`` and ``yellow``,
                                                                   both learning
``--learner blue --opponent scripted`` (``idle``,  fixed-opponent  ``main`` learns and plays
a numpy policy file ``PATH.npz``)                                  blue; the environment
                                                                   plays yellow with that
                                                                   policy
=================================================  ==============  ==========================

The options that have no meaning with RLlib are refused, naming the option: ``--algo``
other than ppo, ``--workers`` (use ``--num-env-runners``), ``--critic privileged`` and the
periodic evaluation (``--eval-every``, ``--eval-episodes``, ``--eval-obs-mode``,
``--eval-perception``; ``soccer-env eval`` reads the run's ``final_policy.npz``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from agents.runs.folders import RunRefused, TrainingStopped, read_run_config, run_folder
from agents.runs.limits import check_saved_settings
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_lab import extras
from soccer_lab.cli_args import env_kwargs_from_args, key_values
from soccer_lab.commands.train_options import TRAIN_OPTIONS, given_fields, refuse_options

__all__ = ["main", "is_rllib_checkpoint", "REFUSED"]

#: The options of ``soccer-env train`` that the RLlib backend refuses: (attribute, the
#: option as given, why), from :data:`~soccer_lab.commands.train_options.TRAIN_OPTIONS`.
REFUSED = tuple((o.dest, o.flag, o.refused["rllib"]) for o in TRAIN_OPTIONS
                if "rllib" in o.refused)

#: ``--opponent`` values of the RLlib backend given by name (besides the path of a numpy policy
#: file, ``.npz``): self-play, a learning module per team, or a fixed opponent.
OPPONENTS = ("self", "learning", "scripted", "idle")


def is_rllib_checkpoint(path: str | None) -> bool:
    """Whether ``path`` is an RLlib checkpoint folder (without importing Ray)."""
    return path is not None and (Path(path) / "rllib_checkpoint.json").is_file()


def _refuse_options(p: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """``p.error`` naming the first option that makes no sense with RLlib."""
    if args.algo not in (None, "PPO"):
        p.error(f"--algo {args.algo.lower()}: the rllib backend trains PPO only")
    if args.critic == "privileged":
        p.error("--critic privileged is stable-baselines3's asymmetric actor-critic; the rllib "
                "backend trains RLlib's PPO module (a shared critic)")
    refuse_options(p, args, "rllib")


def _policy_mapping(p: argparse.ArgumentParser, args: argparse.Namespace, env_id: str,
                    base: dict[str, Any]) -> dict[str, Any]:
    """The ``policy_mapping`` and ``learner`` fields of ``--learner`` and ``--opponent`` (see
    the module docstring), over a resumed run's."""
    learner, opponent = args.learner, args.opponent
    if learner is None and opponent is None:
        return {}
    if env_id != MATCH_ID:
        given = "--learner" if learner is not None else "--opponent"
        p.error(f"{given} is for {MATCH_ID}")
    if opponent is not None and opponent not in OPPONENTS and not opponent.endswith(".npz"):
        p.error(f"--opponent {opponent}: with --backend rllib the opponent is 'self' (a "
                "frozen copy of the learning module, refreshed as it trains), 'learning' "
                "(the other team learns a module of its own), 'scripted', 'idle' or the path "
                "of a numpy policy file (.npz)")
    if learner == "both":
        if opponent is not None:
            p.error(f"--opponent {opponent} with --learner both: both teams play the one "
                    "shared learning module")
        return {"policy_mapping": "shared", "opponent": None}
    team = learner or base.get("learner", "blue")
    if opponent is None and base.get("policy_mapping") == "fixed-opponent":
        return {"learner": team}  # the resumed run's opponent
    if opponent in (None, "self", "learning"):
        mapping = "per-team" if opponent == "learning" else "self-play"
        return {"policy_mapping": mapping, "learner": team, "opponent": None}
    return {"policy_mapping": "fixed-opponent", "learner": team, "opponent": opponent}


def _resumed_fields(p: argparse.ArgumentParser, args: argparse.Namespace) -> dict[str, Any]:
    """The configuration of the run that RLlib checkpoint ``args.resume`` belongs to; settings
    that the command line does not give must lie within the limits of
    :mod:`agents.runs.limits` unless ``--trust``."""
    resume = args.resume
    ckpt = Path(resume)
    if not is_rllib_checkpoint(resume):
        p.error(f"--resume: no RLlib checkpoint at {ckpt} (a run's final_checkpoint or "
                "checkpoints/checkpoint_<steps>_steps folder)")
    run = run_folder(ckpt)
    try:
        saved = read_run_config(run / "config.json")
    except (OSError, ValueError) as err:
        p.error(f"--resume: no readable config.json in {run} ({err})")
    if saved.get("backend") != "rllib":
        p.error(f"--resume: {run} is not a run of --backend rllib")
    try:
        check_saved_settings(saved, run / "config.json", given_fields(args, "rllib"),
                             key_values(args.hp, "--hp"), args.trust)
    except ValueError as err:
        p.error(f"--resume: {err}")
    base = {k: v for k, v in saved.items()
            if k not in ("backend", "command", "resumed_from", "versions")}
    # The run continues where it is, never where its config.json says.
    base["out"] = str(run)
    return base


def _config_fields(p: argparse.ArgumentParser, args: argparse.Namespace,
                   base: dict[str, Any]) -> dict[str, Any]:
    try:
        hyper = {**base.get("hyperparams", {}), **key_values(args.hp, "--hp")}
        env_kwargs = env_kwargs_from_args(args, base.get("env_kwargs"))
    except ValueError as err:
        p.error(str(err))
    fields = {**base, "env_kwargs": env_kwargs, "hyperparams": hyper,
              "progress": not args.no_progress, **given_fields(args, "rllib")}
    env_id = fields.get("env_id", GOALKEEPER_ID)
    mapping = _policy_mapping(p, args, env_id, base)
    if base and mapping.get("policy_mapping", base.get("policy_mapping")) != base.get(
            "policy_mapping"):
        p.error(f"--learner/--opponent: the checkpoint's modules are those of policy mapping "
                f"{base.get('policy_mapping')!r}, not {mapping['policy_mapping']!r}")
    return {**fields, **mapping}


def main(p: argparse.ArgumentParser, args: argparse.Namespace, argv: list[str] | None
         ) -> int:
    """``soccer-env train --backend rllib`` with the parsed ``args`` of ``p``."""
    # Every check of the options comes before Ray is imported, so that it holds without it.
    _refuse_options(p, args)
    base = _resumed_fields(p, args) if args.resume else {}
    fields = _config_fields(p, args, base)
    extras.require("train --backend rllib")
    try:
        from agents.runs import rllib_runs
    except ImportError as err:  # Ray without its RLlib part, or a broken installation
        print(f"soccer-env train --backend rllib needs the rllib extra: "
              f"{extras.install_command(['rllib'])} ({err})", file=sys.stderr)
        return 2
    try:
        cfg = rllib_runs.RllibTrainConfig.from_dict(fields)
    except (ValueError, TypeError) as err:
        p.error(str(err))
    try:
        summary = rllib_runs.train(cfg, resume=args.resume,
                                   command=["soccer-env", "train", *(argv or [])],
                                   overwrite=args.force, trust=args.trust,
                                   address=args.address)
    except RunRefused as err:
        p.error(str(err))
    except TrainingStopped as stopped:
        print(f"soccer-env train: {stopped}", file=sys.stderr)
        return 130
    address = f" --address {args.address}" if args.address else ""
    rate = summary["steps_per_s"] or 0.0
    print(f"trained {summary['trained_steps']:,} steps in {summary['seconds'] / 60:.1f} min "
          f"({rate:,.0f} steps/s) in {summary['iterations']} iterations; "
          f"{len(summary['steps_by_node'])} of the cluster's "
          f"{len(summary['cluster_nodes'])} node(s) sampled")
    print(f"final checkpoint: {summary['final_checkpoint']}")
    if summary.get("final_policy"):
        print(f"numpy policy (soccer-env eval, matches, ratings): {summary['final_policy']}")
    print(f"continue with: {summary['resume_command']}{address}")
    print(f"run folder: {cfg.out}")
    return 0
