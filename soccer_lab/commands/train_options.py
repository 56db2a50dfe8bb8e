"""The options of ``soccer-env train``, each declared once (:data:`TRAIN_OPTIONS`): its flag,
help and ``argparse`` settings beside the configuration field it sets and what each backend
does with it.

From the one table come the parser (:func:`parser`, in the table's order, the environment's
options of :func:`~soccer_lab.cli_args.add_env_arguments` after ``--env``), the help's
defaults (``{default}`` in a help is the field's default in
:class:`~agents.runs.training.TrainConfig`, a new run's), the configuration fields that the given
options set for each backend (:func:`given_fields`: :class:`~agents.runs.training.TrainConfig`
for ``sb3``, :class:`~agents.runs.rllib_runs.RllibTrainConfig` for ``rllib``) and the options a
backend refuses (:func:`refuse_options`).

Adding a training option: a field of :class:`~agents.runs.training.TrainConfig` (and of
:class:`~agents.runs.rllib_runs.RllibTrainConfig` when RLlib takes it) and one
:class:`TrainOption` here; nothing else in the command line names it.
"""

from __future__ import annotations

import argparse
import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from agents.policies.action_maps import ACTION_MAPS
from agents.runs.training import CRITICS, OPPONENTS, TrainConfig
from agents.sb3.algorithms import algorithm_name
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_env.perception.base import OBS_MODES
from soccer_lab.cli_args import (
    HelpFormatter,
    add_env_arguments,
    add_trust_argument,
    sensor_preset,
)

__all__ = ["TrainOption", "TRAIN_OPTIONS", "FIELD_OPTIONS", "ALGORITHMS", "BACKENDS", "parser",
           "given_fields", "refuse_options", "config_default"]

#: The training backends: stable-baselines3 and RLlib.
BACKENDS = ("sb3", "rllib")

#: The algorithms as the command line spells them.
ALGORITHMS = ("ppo", "a2c", "sac", "td3", "ddpg", "recurrent-ppo")

#: What the sb3 backend says of an option of the rllib backend only.
RLLIB_ONLY = "is for --backend rllib"
#: What the rllib backend says of an option of the sb3 backend's periodic evaluation.
SB3_EVALUATION = "is for the periodic evaluation of the sb3 backend"


def config_default(name: str) -> Any:
    """The default of :class:`~agents.runs.training.TrainConfig` field ``name``."""
    return next(f.default for f in dataclasses.fields(TrainConfig) if f.name == name)


def _algorithm(text: str) -> str:
    """``--algo``'s value in its canonical spelling (``ppo`` -> ``PPO``, ``recurrent-ppo`` ->
    ``RECURRENTPPO``)."""
    try:
        return algorithm_name(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid choice: {text!r} (choose from "
                                         f"{', '.join(ALGORITHMS)})") from None


@dataclass(frozen=True)
class TrainOption:
    """One option of ``soccer-env train``.

    Attributes:
        flag: the option string (``"--steps"``); its attribute in the parsed arguments is
            :attr:`dest`.
        help: what it does; ``{default}`` in it stands for :attr:`field`'s default in
            :class:`~agents.runs.training.TrainConfig`, written by :attr:`show`.
        field: the configuration field its value sets, or None for an option that steers the
            command (``--backend``, ``--resume``, ...).
        backends: the backends whose configuration :attr:`field` is set on (``sb3``:
            :class:`~agents.runs.training.TrainConfig`, ``rllib``:
            :class:`~agents.runs.rllib_runs.RllibTrainConfig`); a backend not named leaves the
            field alone unless it refuses the option.
        refused: backend -> why that backend refuses the option when it is given (the error
            reads ``"{flag} {why}"``).
        show: how the help writes the default of :attr:`field`.
        settings: the keyword arguments of ``ArgumentParser.add_argument`` (``type``,
            ``choices``, ``metavar``, ``action``, ...); ``default`` is None unless given, so
            that ``--resume`` tells what is given from what the run's ``config.json`` sets.
    """

    flag: str
    help: str
    field: str | None = None
    backends: tuple[str, ...] = ("sb3",)
    refused: Mapping[str, str] = dataclasses.field(default_factory=dict)
    show: Callable[[Any], str] = str
    settings: Mapping[str, Any] = dataclasses.field(default_factory=dict)

    @property
    def dest(self) -> str:
        """The option's attribute in the parsed arguments (``--n-envs`` -> ``n_envs``)."""
        return self.flag.lstrip("-").replace("-", "_")

    def add_to(self, p: argparse.ArgumentParser) -> None:
        """Add the option to ``p``, its help's ``{default}`` filled in."""
        text = self.help
        if self.field is not None and "{default}" in text:
            text = text.replace("{default}", self.show(config_default(self.field)))
        p.add_argument(self.flag, **{"default": None, **self.settings}, help=text)


#: The options of ``soccer-env train`` in the order of its help (the environment's options
#: follow ``--env``; ``--trust`` ends the list).
TRAIN_OPTIONS: tuple[TrainOption, ...] = (
    TrainOption("--backend", "sb3: stable-baselines3 in this process and its subprocesses; "
                "rllib: RLlib's PPO, sampling on env runners that Ray spreads over the machines "
                "of a cluster (default: sb3, or rllib to resume an RLlib checkpoint)",
                settings={"choices": BACKENDS}),
    TrainOption("--num-env-runners", "rllib: env runners (Ray actors of one CPU each, placed "
                "on any node of the cluster; 0 samples in this process) (default: 2)",
                field="num_env_runners", backends=("rllib",), refused={"sb3": RLLIB_ONLY},
                settings={"type": int, "metavar": "N"}),
    TrainOption("--address", "rllib: join the running Ray cluster at ADDRESS (HEAD:6379 of "
                "`ray start --head --port=6379`, or auto) (default: start Ray on this "
                "machine)", refused={"sb3": RLLIB_ONLY}),
    TrainOption("--env", "environment (default: {default})", field="env_id",
                backends=BACKENDS, settings={"choices": (GOALKEEPER_ID, MATCH_ID)}),
    TrainOption("--algo", "algorithm; recurrent-ppo is sb3-contrib's RecurrentPPO with an LSTM "
                "policy (MlpLstmPolicy), whose memory carries the episode so far "
                "(default: {default})", field="algorithm", show=lambda v: str(v).lower(),
                settings={"type": _algorithm, "metavar": "{" + ",".join(ALGORITHMS) + "}"}),
    TrainOption("--steps", "total environment steps; with --resume the total including the "
                "steps the checkpoint already trained, so it must exceed them (e.g. --resume "
                "model_1000000_steps.zip --steps 1500000 trains 500,000 more); rllib counts "
                "environment steps (match steps for the match), sb3 agent steps "
                "(default: {default})", field="total_steps", backends=BACKENDS,
                settings={"type": int}),
    TrainOption("--critic", "PPO and A2C on Goalkeeper-v0: shared (the critic reads the "
                "actor's observation) or privileged (the critic also reads the true state in "
                "training, the actor only the observation; the saved numpy policy is the actor "
                "alone) (default: {default})", field="critic", settings={"choices": CRITICS}),
    TrainOption("--frame-stack", "feed-forward algorithms, Goalkeeper-v0: the learner sees its "
                "last N observations concatenated, oldest first, the episode's first repeated "
                "to fill (1: the observation alone); the saved numpy policy keeps the history "
                "and acts on single observations (default: {default})", field="frame_stack",
                backends=BACKENDS, settings={"type": int, "metavar": "N"}),
    TrainOption("--n-envs", "parallel environments; rllib: per env runner "
                "(default: {default}; rllib: 8)", field="n_envs", backends=BACKENDS,
                settings={"type": int, "metavar": "N"}),
    TrainOption("--workers", "subprocesses stepping the environments (0: all in this process) "
                "(default: {default}; 0 with --batched)", field="n_workers",
                refused={"rllib": "sets stable-baselines3's subprocesses; with --backend "
                                  "rllib use --num-env-runners"},
                settings={"type": int, "metavar": "N"}),
    TrainOption("--worker-timeout", "seconds a worker subprocess may take to answer; one that "
                "gives no reply in time (stopped, deadlocked, in an endless loop) ends training "
                "as a worker that died does, with a checkpoint and the command that resumes "
                "(at least 300 s until its first step) (default: {default})",
                field="worker_timeout",
                refused={"rllib": "sets stable-baselines3's subprocesses"},
                settings={"type": float, "metavar": "SECONDS"}),
    TrainOption("--batched", "step the environments as one batch (shared pymunk spaces). "
                "Goalkeeper-v0: the --n-envs environments in this process (native actions, "
                "every keeper and observation mode, each environment perceiving on its own). "
                "Match-v0: each process's matches, in this process or in each of --workers "
                "workers", field="batched", settings={"action": "store_true"}),
    TrainOption("--seed", "seed of the environments and the learner (default: {default})",
                field="seed", backends=BACKENDS, settings={"type": int}),
    TrainOption("--out", "run folder; one that holds another run is refused unless --force "
                "(default: {default}; with --resume, the folder of the run it resumes)",
                field="out", backends=BACKENDS),
    TrainOption("--force", "train into an --out that holds another run, deleting that run's "
                "files first (config, models, policies, statistics, checkpoints/, tb/; nothing "
                "else)", settings={"action": "store_true", "default": False}),
    TrainOption("--hp", "algorithm hyperparameter (JSON value), repeatable, e.g. --hp "
                "learning_rate=1e-4 --hp policy_kwargs='{\"net_arch\": [64, 64]}' "
                "(policy_kwargs merge over the algorithm's defaults, e.g. recurrent-ppo's "
                "lstm_hidden_size 64); rllib: PPOConfig settings, e.g. --hp lr=1e-4 --hp "
                "train_batch_size_per_learner=8192 --hp model_config='{\"fcnet_hiddens\": "
                "[128, 128]}'", settings={"action": "append", "default": [],
                                         "metavar": "KEY=VALUE"}),
    TrainOption("--checkpoint-every", "save a checkpoint (model and statistics) into "
                "checkpoints/ every STEPS steps (0: none) (default: {default})",
                field="checkpoint_every", backends=BACKENDS,
                settings={"type": int, "metavar": "STEPS"}),
    TrainOption("--eval-every", "sb3: evaluate on a fixed shot suite every STEPS steps and "
                "keep the best model as best_model.zip (0: never) (default: {default})",
                field="eval_every",
                refused={"rllib": "is stable-baselines3's periodic evaluation, which the rllib "
                                  "backend does not run (evaluate the run's final_policy.npz "
                                  "with soccer-env eval)"},
                settings={"type": int, "metavar": "STEPS"}),
    TrainOption("--eval-episodes", "sb3: shots of each periodic evaluation "
                "(default: {default})", field="eval_episodes",
                refused={"rllib": SB3_EVALUATION}, settings={"type": int, "metavar": "N"}),
    TrainOption("--eval-obs-mode", "sb3: evaluate (and select the best model) under this "
                "observation mode (default: the training environment's)",
                refused={"rllib": SB3_EVALUATION}, settings={"choices": OBS_MODES}),
    TrainOption("--eval-perception", "sb3: evaluate under this sensor preset (as "
                "--perception) (default: the training environment's)",
                refused={"rllib": SB3_EVALUATION},
                settings={"type": sensor_preset, "metavar": "PRESET"}),
    TrainOption("--actions", "keeper learner's actions: native (the robot's command), velocity "
                "(field-frame velocity and turn rate), target (where to stand, reached by a "
                "motion controller), guard (where to stand on the guard line), guard-residual "
                "(a correction to where the scripted keeper would stand on it) or "
                "ball-residual (a correction to the ball velocity the scripted keeper "
                "believes; SSL and humanoid keepers) (default: {default})", field="actions",
                backends=BACKENDS, settings={"choices": tuple(ACTION_MAPS)}),
    TrainOption("--learner", "match: the learning team; rllib: both has one shared module play "
                "every robot, blue or yellow a module of that team against --opponent "
                "(default: {default}; rllib: both)", field="learner",
                settings={"choices": ("blue", "yellow", "both")}),
    TrainOption("--opponent", f"match: {', '.join(OPPONENTS)} (self: a frozen copy of the "
                "learner, refreshed as it trains) or the path of a numpy policy file (.npz, "
                "e.g. a run's final_policy.npz); rllib: self (a frozen copy of the learning "
                "module, refreshed every 100,000 steps), learning (the other team learns a "
                "module of its own), or scripted, idle or a .npz file, which the environment "
                "plays the other team with (default: {default}; rllib: self)",
                field="opponent"),
    TrainOption("--resume", "continue from a checkpoint .zip, or a run's RLlib checkpoint "
                "folder (its final_checkpoint or checkpoints/checkpoint_<steps>_steps; selects "
                "--backend rllib); the rest of the configuration comes from its run's "
                "config.json unless given here", settings={"metavar": "CHECKPOINT"}),
    TrainOption("--no-progress", "no progress bar (which needs tqdm and rich, of the train "
                "extra)", settings={"action": "store_true", "default": False}),
)

#: The options that set a :class:`~agents.runs.training.TrainConfig` field: (field, the option's
#: attribute in the parsed arguments).
FIELD_OPTIONS = tuple((o.field, o.dest) for o in TRAIN_OPTIONS
                      if o.field is not None and "sb3" in o.backends)


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env train``: :data:`TRAIN_OPTIONS`, the environment's options
    after ``--env`` and ``--trust`` last.

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
    for option in TRAIN_OPTIONS:
        option.add_to(p)
        if option.field == "env_id":  # the environment's options follow the environment
            add_env_arguments(p)
    add_trust_argument(p)
    return p


def given_fields(args: argparse.Namespace, backend: str) -> dict[str, Any]:
    """The configuration fields of ``backend`` (one of :data:`BACKENDS`) that the options
    given in ``args`` set: field -> value, for every option whose value is not None."""
    return {o.field: getattr(args, o.dest) for o in TRAIN_OPTIONS
            if o.field is not None and backend in o.backends
            and getattr(args, o.dest) is not None}


def refuse_options(p: argparse.ArgumentParser, args: argparse.Namespace, backend: str
                   ) -> None:
    """``p.error`` naming the first option given in ``args`` that ``backend`` refuses, and
    why."""
    for o in TRAIN_OPTIONS:
        why = o.refused.get(backend)
        if why is not None and getattr(args, o.dest) is not None:
            p.error(f"{o.flag} {why}")
