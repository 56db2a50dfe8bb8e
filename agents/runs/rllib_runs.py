"""Training runs with RLlib (``soccer-env train --backend rllib``), on one machine or a Ray
cluster.

A run is described by an :class:`RllibTrainConfig` and writes into its folder:

* ``config.json``: the configuration (``"backend": "rllib"``), the command line and the
  library versions;
* ``results.jsonl``: one line per training iteration (steps, time, episode returns, the
  keeper's save rate or the match's goals, the steps each Ray node sampled in the
  iteration);
* ``checkpoints/checkpoint_<steps>_steps/`` every ``checkpoint_every`` environment steps and
  ``final_checkpoint/``: RLlib checkpoints (``Algorithm.save_to_path``), each with
  :data:`CHECKPOINT_INFO` (its steps and iteration, JSON) and :data:`SIGNATURE_FILE`, signed
  and checked as :mod:`agents.runs.rllib_checkpoints` says;
* ``final_policy.npz``: the learning module's deterministic actor as a numpy policy
  (:func:`~agents.runs.rllib_export.export_numpy`), which ``soccer-env eval``, the matches
  and the ratings read, as they read the stable-baselines3 backend's;
* ``summary.json``: steps, wall time, rate, the last iteration's metrics, the cluster's nodes
  and the environment steps each of them sampled in this run.

``resume`` continues from a checkpoint: the network, optimiser, observation statistics,
counters and self-play copy are the checkpoint's, the rest (environment keyword arguments,
hyperparameters, env runners, a fixed opponent) this configuration's, so a run can be moved
to a larger cluster. ``total_steps`` counts the checkpoint's steps too.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import platform
import shlex
import shutil
import socket
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from agents.common.checks import check_counts
from agents.policies.action_maps import ACTION_MAPS
from agents.runs.folders import (
    RunRefused,
    TrainingStopped,
    check_steps_left,
    occupied_run_files,
    run_folder,
)
from agents.runs.limits import resume_options
from agents.runs.rllib import (
    ENV_IDS,
    OPPONENT_NAMES,
    POLICY_MAPPINGS,
    MatchEnv,
    fixed_opponent_config,
    hyperparameter_names,
    keeper_env,
    match_policies,
    ppo_config,
)
from agents.runs.rllib_checkpoints import (
    CHECKPOINT_INFO,
    FINAL_CHECKPOINT,
    SIGNATURE_FILE,
    check_checkpoint,
    checkpoint_key_path,
    checkpoint_steps,
    is_rllib_checkpoint,
    load_checkpoint,
    save_checkpoint,
    sign_checkpoint,
)
from agents.runs.rllib_export import FINAL_POLICY, export_numpy
from agents.scripted import TEAMS
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_env.validation import check_fields

__all__ = ["RllibTrainConfig", "train", "check_env_kwargs", "sign_checkpoint",
           "check_checkpoint", "load_checkpoint", "checkpoint_key_path", "is_rllib_checkpoint",
           "checkpoint_steps", "save_checkpoint", "connect", "export_numpy", "CHECKPOINT_INFO",
           "SIGNATURE_FILE", "FINAL_CHECKPOINT", "FINAL_POLICY"]


@dataclass
class RllibTrainConfig:
    """Everything an RLlib training run needs (saved as ``config.json``).

    Attributes:
        env_id: ``"soccer_env/Goalkeeper-v0"`` or ``"soccer_env/Match-v0"``.
        env_kwargs: the environment's keyword arguments.
        total_steps: environment steps to train for (match steps for the match, however
            many robots play), in all: a resumed run counts the checkpoint's steps too.
        num_env_runners: RLlib env runners (Ray actors of 1 CPU each by default, placed on
            any node of the cluster); 0 samples in the driver.
        n_envs: environments per env runner.
        seed: seeds the environments, the networks and the sampling.
        out: the run's folder.
        hyperparams: RLlib PPO settings over :data:`agents.runs.rllib.DEFAULT_HYPERPARAMS`
            (:func:`agents.runs.rllib.apply_hyperparams`), e.g. ``{"lr": 1e-4, "model_config":
            {"fcnet_hiddens": [128, 128]}}``.
        checkpoint_every: environment steps between checkpoints (0: the final one only).
        policy_mapping: the match's modules (:data:`agents.runs.rllib.POLICY_MAPPINGS`).
        learner: the team of the learning module of ``"self-play"`` and ``"fixed-opponent"``.
        opponent: the fixed opponent of ``"fixed-opponent"`` (and of it only): ``"scripted"``,
            ``"idle"`` or the path of a numpy policy file (``.npz``), which the environment
            plays the other team with (:func:`agents.runs.rllib.fixed_opponent_config`).
        self_play_every: environment steps between copies of the learning module into the
            frozen opponent (``"self-play"``).
        actions, frame_stack: the keeper learner's action map and stacked observations, as
            in :class:`~agents.runs.training.config.TrainConfig` (Goalkeeper-v0 only).
        normalize_obs: observations pass through RLlib's ``MeanStdFilter``.
        torch_threads: torch's threads in the driver (the learner).
        progress: print a line per training iteration.
    """

    env_id: str = GOALKEEPER_ID
    env_kwargs: dict[str, Any] = field(default_factory=dict)
    total_steps: int = 1_000_000
    num_env_runners: int = 2
    n_envs: int = 8
    seed: int = 0
    out: str = "runs/keeper"
    hyperparams: dict[str, Any] = field(default_factory=dict)
    checkpoint_every: int = 250_000
    policy_mapping: str = "shared"
    learner: str = "blue"
    opponent: str | None = None
    self_play_every: int = 100_000
    actions: str = "native"
    frame_stack: int = 1
    normalize_obs: bool = True
    torch_threads: int = 1
    progress: bool = True

    def __post_init__(self) -> None:
        if self.env_id not in ENV_IDS:
            raise ValueError(f"env_id must be one of {list(ENV_IDS)}, got {self.env_id!r}")
        check_counts(self, (("total_steps", 1), ("num_env_runners", 0), ("n_envs", 1),
                            ("checkpoint_every", 0), ("self_play_every", 1),
                            ("frame_stack", 1), ("torch_threads", 1), ("seed", 0)))
        POLICY_MAPPINGS.check(self.policy_mapping)
        if self.learner not in TEAMS:
            raise ValueError(f"learner must be 'blue' or 'yellow', got {self.learner!r}")
        if self.env_id != MATCH_ID and self.policy_mapping != "shared":
            raise ValueError(f"policy_mapping {self.policy_mapping!r} is for {MATCH_ID}")
        self._check_opponent()
        if self.actions not in ACTION_MAPS:
            raise ValueError(f"actions must be one of {list(ACTION_MAPS)}, got "
                             f"{self.actions!r}")
        if self.env_id != GOALKEEPER_ID and (self.actions != "native" or self.frame_stack > 1):
            raise ValueError(f"actions and frame_stack are for {GOALKEEPER_ID} only")
        unknown = sorted(set(self.hyperparams) - set(hyperparameter_names()))
        if unknown:
            raise ValueError(f"unknown RLlib PPO hyperparameter(s) {unknown}; e.g. lr, gamma, "
                             "train_batch_size_per_learner, minibatch_size, num_epochs, "
                             "entropy_coeff, model_config, num_learners")

    def _check_opponent(self) -> None:
        """``ValueError`` unless :attr:`opponent` is given with ``"fixed-opponent"`` (only),
        and is one of its names or an existing ``.npz`` file."""
        fixed = self.policy_mapping == "fixed-opponent"
        if (self.opponent is not None) != fixed:
            raise ValueError(f"opponent is for policy mapping 'fixed-opponent' (and needed "
                             f"there), got opponent={self.opponent!r} with policy mapping "
                             f"{self.policy_mapping!r}")
        if fixed and self.opponent not in OPPONENT_NAMES and not (
                str(self.opponent).endswith(".npz") and Path(self.opponent).is_file()):
            raise ValueError(f"opponent must be one of {list(OPPONENT_NAMES)} or the path of a "
                             f"numpy policy file (.npz), got {self.opponent!r}"
                             + (" (no such file)" if str(self.opponent).endswith(".npz")
                                else ""))

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> RllibTrainConfig:
        check_fields(cls, data, "RLlib training config")
        return cls(**data)

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)

    def env_config(self) -> dict[str, Any]:
        """The ``env_config`` of the environment (:mod:`agents.runs.rllib_envs`); a fixed
        opponent joins it in :func:`agents.runs.rllib.ppo_config`."""
        if self.env_id == GOALKEEPER_ID:
            return {**self.env_kwargs, "actions": self.actions, "frame_stack": self.frame_stack}
        return dict(self.env_kwargs)

    def ppo_config(self) -> Any:
        """This run's RLlib ``PPOConfig`` (:func:`agents.runs.rllib.ppo_config`)."""
        return ppo_config(self.env_id, self.env_config(), policy_mapping=self.policy_mapping,
                          learner=self.learner, opponent=self.opponent,
                          num_env_runners=self.num_env_runners,
                          n_envs=self.n_envs, seed=self.seed, hyperparams=self.hyperparams,
                          normalize_obs=self.normalize_obs,
                          self_play_every=self.self_play_every)


def check_env_kwargs(cfg: RllibTrainConfig) -> None:
    """Build one environment of ``cfg`` here, so that bad keyword arguments fail before Ray
    starts, with the environment's own message (``TypeError`` or ``ValueError``); for the
    match also its policy mapping (:func:`agents.runs.rllib.match_policies`) and its fixed
    opponent (a numpy policy must read the match's observations)."""
    if cfg.env_id == MATCH_ID:
        match_policies(cfg.env_kwargs, cfg.policy_mapping, cfg.learner)
        if cfg.opponent is not None:
            MatchEnv(fixed_opponent_config(cfg.env_kwargs, cfg.learner, cfg.opponent)).close()
    else:
        keeper_env(cfg.env_config()).close()


# ------------------------------------------------------------------------------------------
# Training
# ------------------------------------------------------------------------------------------

def connect(address: str | None = None) -> bool:
    """Start Ray on this machine (``address`` None) or join the running cluster at
    ``address`` (``"HOST:PORT"`` or ``"auto"``), unless this process is already connected.
    Returns whether it connected (and so should disconnect, ``ray.shutdown()``).

    A ``HOST:PORT`` where nothing answers raises ``ConnectionError`` at once (Ray itself
    would retry for minutes)."""
    import logging

    import ray

    if ray.is_initialized():
        return False
    if address is not None and address not in ("auto", "local") and "://" not in address:
        host, _, port = address.rpartition(":")
        try:
            socket.create_connection((host, int(port)), timeout=10).close()
        except (OSError, ValueError) as err:
            raise ConnectionError(
                f"no Ray cluster answers at {address} ({err}); start its head with `ray "
                "start --head --port=6379` and give --address HEAD_HOST:6379") from None
    ray.init(address=address, logging_level=logging.WARNING)
    return True


#: The per-iteration metrics written to ``results.jsonl`` (result key path -> name).
_RESULT_KEYS = {
    ("training_iteration",): "iteration",
    ("num_env_steps_sampled_lifetime",): "steps",
    ("env_runners", "num_agent_steps_sampled_lifetime"): "agent_steps",
    ("time_this_iter_s",): "seconds",
    ("env_runners", "episode_return_mean"): "episode_return_mean",
    ("env_runners", "episode_len_mean"): "episode_len_mean",
    ("env_runners", "module_episode_return_mean"): "module_episode_return_mean",
    ("env_runners", "save_rate"): "save_rate",
    ("env_runners", "blue_goals"): "blue_goals",
    ("env_runners", "yellow_goals"): "yellow_goals",
    ("env_runners", "steps_by_node"): "steps_by_node",
    ("self_play_updates",): "self_play_updates",
}


def _plain(value: Any) -> Any:
    """``value`` with numpy scalars and mappings made JSON-ready."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if hasattr(value, "item"):
        return value.item()
    return value


def _metrics(result: Mapping[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for path, name in _RESULT_KEYS.items():
        value: Any = result
        for key in path:
            value = value.get(key) if isinstance(value, Mapping) else None
        if value is not None:
            out[name] = _plain(value)
    if isinstance(out.get("agent_steps"), Mapping):
        out["agent_steps"] = sum(out["agent_steps"].values())
    for name in ("steps", "agent_steps"):
        if name in out:
            out[name] = int(out[name])
    return out


def _line(m: Mapping[str, Any], rate: float) -> str:
    parts = [f"iteration {m.get('iteration', '?')}: {int(m.get('steps', 0)):,} steps "
             f"({rate:,.0f} steps/s)"]
    if "episode_return_mean" in m:
        parts.append(f"return {m['episode_return_mean']:.3f}")
    if "save_rate" in m:
        parts.append(f"save rate {100 * m['save_rate']:.1f} %")
    if "blue_goals" in m:
        parts.append(f"goals blue {m['blue_goals']:.2f} yellow {m['yellow_goals']:.2f}")
    if m.get("steps_by_node"):
        parts.append(f"{len(m['steps_by_node'])} node(s) sampled")
    return ", ".join(parts)


def _versions() -> dict[str, str]:
    import gymnasium
    import numpy as np
    import pettingzoo
    import ray
    import torch

    return {"python": platform.python_version(), "ray": ray.__version__,
            "torch": torch.__version__, "gymnasium": gymnasium.__version__,
            "pettingzoo": pettingzoo.__version__, "numpy": np.__version__}


def _resume_command(cfg: RllibTrainConfig, checkpoint: Path, steps: int) -> str:
    more = max(cfg.total_steps - steps, steps, 1)
    return shlex.join(["soccer-env", "train", "--backend", "rllib", "--resume", str(checkpoint),
                       "--steps", str(steps + more), *resume_options(cfg.to_dict())])


def train(cfg: RllibTrainConfig, resume: str | os.PathLike | None = None,
          command: list[str] | None = None, overwrite: bool = False, trust: bool = False,
          address: str | None = None, log: Callable[[str], None] = print) -> dict[str, Any]:
    """Train as ``cfg`` says with RLlib (continuing from the checkpoint ``resume`` if given)
    on Ray (this machine's, or the cluster at ``address``), writing the run folder
    ``cfg.out`` (see the module docstring). Returns the summary.

    Before anything is written :class:`~agents.runs.folders.RunRefused` is raised when
    ``cfg.out`` holds another run and ``overwrite`` is false (continuing a run in its own
    folder needs no ``overwrite``), when ``resume`` cannot be loaded safely (see
    :func:`check_checkpoint`; ``trust`` loads it anyway) or has already trained
    ``cfg.total_steps``, or when RLlib refuses the configuration.

    Ctrl-C ends training with :class:`~agents.runs.folders.TrainingStopped`, naming the last
    checkpoint and the command that continues from it."""
    out = Path(cfg.out)
    existing = occupied_run_files(out, resume, overwrite)
    done = 0
    if resume is not None:
        try:
            done = checkpoint_steps(resume, trust)
        except ValueError as err:  # UnsafeFileError included
            raise RunRefused(f"resume: {err}") from None
        check_steps_left(cfg.total_steps, done, resume)
    try:
        check_env_kwargs(cfg)
        config = cfg.ppo_config()
    except (ValueError, TypeError) as err:
        raise RunRefused(str(err)) from None

    import torch

    torch.set_num_threads(cfg.torch_threads)
    try:
        started = connect(address)
    except ConnectionError as err:
        raise RunRefused(str(err)) from None
    algo = None
    try:
        try:
            algo = config.build_algo()
            if resume is not None:
                algo.restore_from_path(str(Path(resume).resolve()))
        except Exception as err:
            what = f"resume from {os.fspath(resume)}" if resume is not None else "build"
            raise RunRefused(f"RLlib could not {what} PPO with this configuration: "
                             f"{type(err).__name__}: {err}") from err
        return _run(cfg, algo, out, existing, resume, command, log, done)
    finally:
        if algo is not None:
            algo.stop()
        if started:
            import ray

            ray.shutdown()


def _run(cfg: RllibTrainConfig, algo: Any, out: Path, existing: list[str],
         resume: str | os.PathLike | None, command: list[str] | None,
         log: Callable[[str], None], done: int) -> dict[str, Any]:
    """The training loop of :func:`train`, once the algorithm is built."""
    import ray

    for name in existing:  # overwrite: this run's files only, nothing else in the folder
        path = out / name
        if path.is_dir():
            shutil.rmtree(path)
        else:
            path.unlink()
    out.mkdir(parents=True, exist_ok=True)
    nodes = [n["NodeID"] for n in ray.nodes() if n.get("Alive")]
    (out / "config.json").write_text(json.dumps({
        "backend": "rllib", **cfg.to_dict(), "command": command,
        "resumed_from": None if resume is None else os.fspath(resume),
        "versions": _versions()}, indent=2))
    steps, last_ckpt, metrics, iterations = done, None, {}, 0
    # Steps sampled per node: RLlib's lifetime sums, less those at the start of this run (a
    # restored checkpoint brings its run's, under the node ids of its Ray session).
    start = _node_steps(algo.metrics.peek(("env_runners", "steps_by_node"), default={}))
    previous_by_node = dict(start)
    if resume is not None and run_folder(resume).resolve() == out.resolve():
        last_ckpt = Path(resume)
    t0 = time.perf_counter()
    try:
        with open(out / "results.jsonl", "a") as results:
            while steps < cfg.total_steps:
                t_iter = time.perf_counter()
                result = algo.train()
                metrics = _metrics(result)
                iterations += 1
                previous, steps = steps, int(metrics.get("steps", steps))
                lifetime = _node_steps(metrics.get("steps_by_node", {}))
                metrics["steps_by_node"] = _less(lifetime, previous_by_node)
                previous_by_node = lifetime
                metrics["wall_s"] = round(time.perf_counter() - t_iter, 3)
                results.write(json.dumps(metrics) + "\n")
                results.flush()
                if cfg.progress:
                    log(_line(metrics, (steps - previous) / max(metrics["wall_s"], 1e-9)))
                every = cfg.checkpoint_every
                if every and steps // every > previous // every and steps < cfg.total_steps:
                    last_ckpt = save_checkpoint(
                        algo, out / "checkpoints" / f"checkpoint_{steps}_steps",
                        _info(cfg, metrics))
    except KeyboardInterrupt as err:
        where = (f"the last checkpoint is {last_ckpt}\ncontinue with: "
                 f"{_resume_command(cfg, last_ckpt, checkpoint_steps(last_ckpt, True))}"
                 if last_ckpt is not None else "no checkpoint was saved")
        raise TrainingStopped(f"training interrupted at {steps:,} steps\n{where}",
                              "interrupted", last_ckpt, steps, None) from err
    seconds = time.perf_counter() - t0
    by_node = _less(previous_by_node, start)
    final = save_checkpoint(algo, out / FINAL_CHECKPOINT, _info(cfg, metrics))
    policy = _final_policy(final, out, log)
    summary = {
        "backend": "rllib", "steps": steps, "trained_steps": steps - done,
        "iterations": iterations, "seconds": seconds,
        "steps_per_s": (steps - done) / seconds if seconds > 0 else None,
        "last_iteration": metrics, "cluster_nodes": nodes, "steps_by_node": by_node,
        "final_checkpoint": str(final), "final_policy": policy,
        "resume_command": _resume_command(cfg, final, steps),
        "files": sorted(p.name for p in out.iterdir()),
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def _final_policy(final: Path, out: Path, log: Callable[[str], None]) -> str | None:
    """Write the final checkpoint's learning module as :data:`FINAL_POLICY` into ``out``;
    its path, or None (said through ``log``) for a network that numpy cannot copy."""
    try:
        export_numpy(final, out / FINAL_POLICY, trust=True)
    except ValueError as err:
        log(f"no {FINAL_POLICY}: {err}")
        return None
    return str(out / FINAL_POLICY)


def _node_steps(value: Any) -> dict[str, int]:
    """Steps by node id from RLlib's metric (empty if there is none)."""
    if not isinstance(value, Mapping):
        return {}
    return {str(k): int(v) for k, v in value.items()
            if isinstance(v, (int, float)) and math.isfinite(v)}


def _less(now: Mapping[str, int], before: Mapping[str, int]) -> dict[str, int]:
    """The nodes whose counts grew from ``before`` to ``now``, with the growth."""
    return {k: v - before.get(k, 0) for k, v in now.items() if v > before.get(k, 0)}


def _info(cfg: RllibTrainConfig, metrics: Mapping[str, Any]) -> dict[str, Any]:
    """A checkpoint's :data:`CHECKPOINT_INFO`."""
    return {"steps": int(metrics.get("steps", 0)),
            "agent_steps": int(metrics.get("agent_steps", 0)),
            "iteration": metrics.get("iteration"), "env_id": cfg.env_id,
            "policy_mapping": cfg.policy_mapping if cfg.env_id == MATCH_ID else None,
            "learner": cfg.learner, "opponent": cfg.opponent}
