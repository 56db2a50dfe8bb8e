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
  :data:`CHECKPOINT_INFO` (its steps and iteration, JSON) and :data:`SIGNATURE_FILE`;
* ``summary.json``: steps, wall time, rate, the last iteration's metrics, the cluster's nodes
  and the environment steps each of them sampled in this run.

RLlib checkpoints are pickles (``class_and_ctor_args.pkl``, the state files; cloudpickle
underneath), and unpickling runs whatever code the file names. So every checkpoint a run
writes is signed: :func:`sign_checkpoint` writes the SHA-256 digest of each of its files with
an HMAC of them under a key kept in the user's configuration folder
(:func:`checkpoint_key_path`, created on first use, readable by the user only), and
:func:`check_checkpoint` loads (resumes from) only checkpoints signed with that key and not
changed since: the user's own runs. Any other checkpoint (someone else's, one from another
machine or account, or one edited since) raises :class:`~agents.policies.files.UnsafeFileError`
unless ``trust=True`` (``--trust``), as the stable-baselines3 files that need unpickling do.

``resume`` continues from a checkpoint: the network, optimiser, observation statistics,
counters and self-play copy are the checkpoint's, the rest (environment keyword arguments,
hyperparameters, env runners) this configuration's, so a run can be moved to a larger
cluster. ``total_steps`` counts the checkpoint's steps too.
"""

from __future__ import annotations

import dataclasses
import hashlib
import hmac
import json
import math
import os
import platform
import secrets
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
from agents.policies.files import TRUST_HELP, UnsafeFileError, read_json
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
    POLICY_MAPPINGS,
    hyperparameter_names,
    keeper_env,
    match_policies,
    ppo_config,
)
from agents.scripted import TEAMS
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_env.validation import check_fields

__all__ = ["RllibTrainConfig", "train", "check_env_kwargs", "sign_checkpoint",
           "check_checkpoint", "load_checkpoint", "checkpoint_key_path", "is_rllib_checkpoint",
           "checkpoint_steps", "save_checkpoint", "connect", "CHECKPOINT_INFO",
           "SIGNATURE_FILE", "FINAL_CHECKPOINT"]

#: The JSON file in each checkpoint with its steps and iteration.
CHECKPOINT_INFO = "soccer_env_checkpoint.json"
#: The JSON file in each checkpoint with its files' digests and their HMAC.
SIGNATURE_FILE = "soccer_env_signature.json"
#: The last checkpoint of a run, in its folder.
FINAL_CHECKPOINT = "final_checkpoint"
#: RLlib's own file in every checkpoint folder.
_RLLIB_METADATA = "rllib_checkpoint.json"


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
        learner: the team of ``"self-play"``'s learning module.
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

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> RllibTrainConfig:
        check_fields(cls, data, "RLlib training config")
        return cls(**data)

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)

    def env_config(self) -> dict[str, Any]:
        """The ``env_config`` of the registered environment (:mod:`agents.runs.rllib`)."""
        if self.env_id == GOALKEEPER_ID:
            return {**self.env_kwargs, "actions": self.actions, "frame_stack": self.frame_stack}
        return dict(self.env_kwargs)

    def ppo_config(self) -> Any:
        """This run's RLlib ``PPOConfig`` (:func:`agents.runs.rllib.ppo_config`)."""
        return ppo_config(self.env_id, self.env_config(), policy_mapping=self.policy_mapping,
                          learner=self.learner, num_env_runners=self.num_env_runners,
                          n_envs=self.n_envs, seed=self.seed, hyperparams=self.hyperparams,
                          normalize_obs=self.normalize_obs,
                          self_play_every=self.self_play_every)


def check_env_kwargs(cfg: RllibTrainConfig) -> None:
    """Build one environment of ``cfg`` here, so that bad keyword arguments fail before Ray
    starts, with the environment's own message (``TypeError`` or ``ValueError``); for the
    match also its policy mapping (:func:`agents.runs.rllib.match_policies`)."""
    if cfg.env_id == MATCH_ID:
        match_policies(cfg.env_kwargs, cfg.policy_mapping, cfg.learner)
    else:
        keeper_env(cfg.env_config()).close()


# ------------------------------------------------------------------------------------------
# Checkpoints
# ------------------------------------------------------------------------------------------

def checkpoint_key_path() -> Path:
    """The signing key's file: ``$XDG_CONFIG_HOME/soccer_env/checkpoint_key`` (by default
    ``~/.config/soccer_env/checkpoint_key``)."""
    base = os.environ.get("XDG_CONFIG_HOME") or Path.home() / ".config"
    return Path(base) / "soccer_env" / "checkpoint_key"


def _key(create: bool) -> bytes | None:
    path = checkpoint_key_path()
    if path.is_file():
        return path.read_bytes()
    if not create:
        return None
    path.parent.mkdir(parents=True, exist_ok=True)
    key = secrets.token_bytes(32)
    # Created readable and writable by the user only; never replaced once there.
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except FileExistsError:  # another process made it meanwhile
        return path.read_bytes()
    with os.fdopen(fd, "wb") as fh:
        fh.write(key)
    return key


def _digests(folder: Path) -> dict[str, str]:
    """SHA-256 of every file under ``folder`` but the signature, by relative path (POSIX);
    a link is refused (``ValueError``): it could point anywhere."""
    out = {}
    for path in sorted(folder.rglob("*")):
        rel = path.relative_to(folder).as_posix()
        if path.is_symlink():
            raise ValueError(f"{folder} holds a link, {rel}: not a checkpoint this package "
                             "wrote")
        if path.is_file() and rel != SIGNATURE_FILE:
            h = hashlib.sha256()
            with open(path, "rb") as fh:
                for block in iter(lambda: fh.read(1 << 20), b""):
                    h.update(block)
            out[rel] = h.hexdigest()
    return out


def _mac(key: bytes, digests: Mapping[str, str]) -> str:
    message = json.dumps(digests, sort_keys=True).encode()
    return hmac.new(key, message, hashlib.sha256).hexdigest()


def sign_checkpoint(folder: str | os.PathLike) -> None:
    """Sign the checkpoint ``folder`` with this user's key (see the module docstring)."""
    folder = Path(folder)
    digests = _digests(folder)
    signature = {"scheme": "hmac-sha256 over the JSON of the files' sha256 digests",
                 "files": digests, "mac": _mac(_key(create=True), digests)}
    (folder / SIGNATURE_FILE).write_text(json.dumps(signature, indent=1))


def is_rllib_checkpoint(path: str | os.PathLike) -> bool:
    """Whether ``path`` is a folder holding an RLlib checkpoint."""
    return Path(path).is_dir() and (Path(path) / _RLLIB_METADATA).is_file()


def check_checkpoint(folder: str | os.PathLike, trust: bool = False) -> dict[str, Any]:
    """The :data:`CHECKPOINT_INFO` of checkpoint ``folder`` (``{"steps", "agent_steps",
    "iteration", ...}``), after checking that loading it is safe: signed with this user's
    key and unchanged since. Raises :class:`~agents.policies.files.UnsafeFileError` for any
    other checkpoint unless ``trust``, and ``ValueError`` for a folder that is not an RLlib
    checkpoint of this package."""
    folder = Path(folder)
    if not is_rllib_checkpoint(folder):
        raise ValueError(f"{folder} is not an RLlib checkpoint (a folder with "
                         f"{_RLLIB_METADATA})")
    if not trust:
        reason = None
        key = _key(create=False)
        try:
            signature = read_json(folder / SIGNATURE_FILE)
            digests = _digests(folder)
        except FileNotFoundError:
            reason = "it is not signed"
        except (ValueError, TypeError) as err:
            reason = f"its signature cannot be read ({err})"
        if reason is None and key is None:
            reason = f"this account has no signing key ({checkpoint_key_path()})"
        if reason is None and (not isinstance(signature, dict)
                               or signature.get("files") != digests
                               or not hmac.compare_digest(str(signature.get("mac")),
                                                          _mac(key, digests))):
            reason = ("its signature does not match: it was written under another key (by "
                      "someone else, or on another machine or account) or changed since")
        if reason is not None:
            raise UnsafeFileError(
                f"{folder} is not a checkpoint of your own runs: {reason}. RLlib checkpoints "
                f"are pickles (cloudpickle): {TRUST_HELP}")
    try:
        return read_json(folder / CHECKPOINT_INFO)
    except (OSError, ValueError) as err:
        raise ValueError(f"{folder} has no readable {CHECKPOINT_INFO} ({err}): not a "
                         "checkpoint of soccer-env train") from None


def checkpoint_steps(folder: str | os.PathLike, trust: bool = False) -> int:
    """The environment steps checkpoint ``folder`` has trained (:func:`check_checkpoint`)."""
    return int(check_checkpoint(folder, trust)["steps"])


def save_checkpoint(algo: Any, folder: str | os.PathLike, info: Mapping[str, Any]) -> Path:
    """Save ``algo`` (``Algorithm.save_to_path``) into ``folder`` (replacing one there) with
    ``info`` as :data:`CHECKPOINT_INFO`, and sign it."""
    folder = Path(folder)
    if folder.exists():
        shutil.rmtree(folder)
    algo.save_to_path(str(folder.resolve()))
    (folder / CHECKPOINT_INFO).write_text(json.dumps(dict(info), indent=1))
    sign_checkpoint(folder)
    return folder


def load_checkpoint(folder: str | os.PathLike, trust: bool = False) -> Any:
    """The RLlib algorithm of checkpoint ``folder`` (``Algorithm.from_checkpoint``), once
    :func:`check_checkpoint` finds it safe to load. Needs Ray running (``ray.init``)."""
    from ray.rllib.algorithms.algorithm import Algorithm

    from agents.runs.rllib import register_envs

    check_checkpoint(folder, trust)
    register_envs()
    return Algorithm.from_checkpoint(str(Path(folder).resolve()))


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
    summary = {
        "backend": "rllib", "steps": steps, "trained_steps": steps - done,
        "iterations": iterations, "seconds": seconds,
        "steps_per_s": (steps - done) / seconds if seconds > 0 else None,
        "last_iteration": metrics, "cluster_nodes": nodes, "steps_by_node": by_node,
        "final_checkpoint": str(final),
        "resume_command": _resume_command(cfg, final, steps),
        "files": sorted(p.name for p in out.iterdir()),
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary


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
            "learner": cfg.learner}
