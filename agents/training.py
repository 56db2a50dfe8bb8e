"""Train policies with stable-baselines3 (``soccer-env train``).

A run is described by a :class:`TrainConfig` and writes into its folder:

* ``config.json``: the full configuration, the learner's action map (see
  :mod:`agents.wrappers`), the command line and library versions;
* ``checkpoints/model_<steps>_steps.zip`` every ``checkpoint_every`` steps (resume from any);
* ``tb/``: TensorBoard logs (SB3's training statistics, episode returns and success rate,
  the periodic save-rate evaluation, and the rollout collection rate);
* ``evaluations.json``: the periodic evaluations; ``best_model.zip`` / ``best_policy.npz``: the
  best of them;
* ``final_model.zip`` and ``final_policy.npz`` (the numpy copy of the actor, see
  :class:`~agents.policies.NumpyPolicy`), the ``VecNormalize`` statistics beside every model
  (``*_vecnormalize.npz``: arrays and JSON, no pickle, see :mod:`agents.model_files`), and
  ``summary.json`` (steps, wall time, rollout and overall steps per second, last and best
  evaluation).

``resume`` continues from a checkpoint with this configuration's environment and
hyperparameters (the network is the checkpoint's): the same run, or a fine-tuning, e.g. a
keeper trained on true observations continued on perceived ones. ``total_steps`` counts the
checkpoint's steps too: a resumed run trains ``total_steps`` minus the checkpoint's steps, and
one with nothing left to train is refused.

Memory, for observations that a single frame does not explain (perceived ones, with their
latency, noise and missed detections): ``algorithm="RECURRENTPPO"`` trains sb3-contrib's
RecurrentPPO (an LSTM in front of the actor's and the critic's networks; exported as a
:class:`~agents.policies.NumpyRecurrentPolicy`), and ``frame_stack=N`` shows a feed-forward
learner its last ``N`` observations at once (:func:`~agents.wrappers.stack_frames`; the
exported :class:`~agents.policies.NumpyPolicy` keeps the history itself). Both policies act on
the plain environment and need ``reset()`` at each episode start, which the evaluation does.

Goalkeeper-v0 runs in :class:`~agents.vec_env.WorkerVecEnv` (``n_envs`` environments over
``n_workers`` processes) or, with ``n_workers=0``, in-process. The match
(``soccer_env/Match-v0``) runs through :class:`~agents.multiagent.MatchVecEnv`: each learning
robot is a batch entry of one shared policy, against the ``opponent`` team; its ``n_envs``
matches are split over ``n_workers`` processes
(:class:`~agents.match_workers.MatchWorkerVecEnv`, the same batches whatever the number of
workers) or, with ``n_workers=0``, stepped in-process.

The periodic evaluation runs the current actor deterministically on ``eval_episodes`` shots
drawn from seeds ``EVAL_SEED_START`` onwards, apart from the fixed test suite (seeds 0 onwards)
that ``soccer-env eval`` and the ablation use, so that picking the best model does not bias
the reported save rate.
"""

from __future__ import annotations

import dataclasses
import inspect
import json
import os
import platform
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from agents.evaluation import check_full_infos, evaluate
from agents.model_files import save_vecnormalize, vecnormalize_on
from agents.policies import (
    NumpyPolicy,
    algorithm_class,
    algorithm_name,
    load_vecnormalize,
    vecnormalize_path,
)
from agents.wrappers import ACTION_MAPS, wrap_actions, wrap_learner
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_env.validation import check_fields

__all__ = ["TrainConfig", "train", "check_env_kwargs", "check_counts", "make_vec_env",
           "EVAL_SEED_START",
           "DEFAULT_HYPERPARAMS", "rollout_timer", "goalkeeper_env_fn",
           "checkpoint_steps", "CRITICS", "TrainingStopped", "RunRefused", "RUN_FILES",
           "run_files", "run_folder", "OPPONENTS", "merged_hyperparams"]

#: What a training run writes into its folder: a folder holding any of these holds a run,
#: which :func:`train` does not overwrite unless told to (and then deletes these, and only
#: these, first).
RUN_FILES = ("config.json", "summary.json", "evaluations.json", "final_model.zip",
             "final_policy.npz", "final_vecnormalize.npz", "best_model.zip", "best_policy.npz",
             "best_vecnormalize.npz", "checkpoints", "tb",
             # written by the RLlib backend (agents.rllib_runs):
             "results.jsonl", "final_checkpoint",
             # written by earlier versions:
             "final_vecnormalize.pkl", "best_vecnormalize.pkl")

#: The match opponents given by name (besides the path of a numpy policy file, ``.npz``).
OPPONENTS = ("scripted", "idle", "self")


class RunRefused(ValueError):
    """:func:`train` refused the run before writing anything: its folder holds another run,
    it has nothing to train, or the algorithm refused the hyperparameters."""


class TrainingStopped(RuntimeError):
    """Training ended early: interrupted (Ctrl-C) or a rollout worker failed. The model of
    the last completed update is saved as a checkpoint to resume from.

    Attributes:
        reason: ``"interrupted"`` or ``"worker failed"``.
        checkpoint: the saved checkpoint (None when nothing had been trained yet).
        steps: the environment steps that checkpoint has trained.
        resume_command: the command line that continues the run.
    """

    def __init__(self, message: str, reason: str, checkpoint: Path | None, steps: int,
                 resume_command: str | None) -> None:
        super().__init__(message)
        self.reason = reason
        self.checkpoint = checkpoint
        self.steps = steps
        self.resume_command = resume_command

#: The critics of ``critic=``: ``"shared"`` (the actor's observation, stable-baselines3's
#: default) or ``"privileged"`` (also the true state, :mod:`agents.privileged`).
CRITICS = ("shared", "privileged")

#: First seed of the shots used for model selection during training.
EVAL_SEED_START = 1_000_000

#: Per-algorithm defaults, tuned on Goalkeeper-v0 only as far as "learns in minutes". A
#: configuration's ``policy_kwargs`` are merged key by key over the defaults' ones.
#: RecurrentPPO's LSTM has 64 units (sb3-contrib's default, 256, trains 2.5 times slower on a
#: 2-core machine) and its minibatches are twice PPO's (its gradient steps run the LSTM over
#: whole sequences and dominate the training time).
_PPO_DEFAULTS: dict[str, Any] = {
    "n_steps": 256, "batch_size": 512, "n_epochs": 10, "gamma": 0.99, "gae_lambda": 0.95,
    "learning_rate": 3e-4, "ent_coef": 0.0, "clip_range": 0.2}
DEFAULT_HYPERPARAMS: dict[str, dict[str, Any]] = {
    "PPO": _PPO_DEFAULTS,
    "RECURRENTPPO": {**_PPO_DEFAULTS, "batch_size": 1024,
                     "policy_kwargs": {"lstm_hidden_size": 64}},
    "A2C": {},
    "SAC": {"learning_starts": 5000, "batch_size": 256, "train_freq": 1, "gradient_steps": 1},
    "TD3": {"learning_starts": 5000, "batch_size": 256, "train_freq": 1, "gradient_steps": 1},
    "DDPG": {"learning_starts": 5000, "batch_size": 256},
}


def check_counts(config: Any, fields: tuple[tuple[str, int], ...]) -> None:
    """Raise ``ValueError`` naming the field unless each ``(name, low)`` of ``fields`` is an
    integer (not a bool) >= ``low`` on ``config``: the counts of a training configuration."""
    for name, low in fields:
        value = getattr(config, name)
        if not isinstance(value, (int, np.integer)) or isinstance(value, bool) or value < low:
            raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")


@dataclass
class TrainConfig:
    """Everything a training run needs (saved as ``config.json``).

    Attributes:
        env_id: ``"soccer_env/Goalkeeper-v0"`` or ``"soccer_env/Match-v0"``.
        env_kwargs: keyword arguments of the environment (``obs_mode``, ``perception``,
            ``shaping``, ...).
        algorithm: one of :data:`~agents.policies.SB3_ALGORITHMS` (any spelling
            :func:`~agents.policies.algorithm_name` takes, e.g. ``"recurrent-ppo"``; stored
            canonical, ``"RECURRENTPPO"``).
        total_steps: environment steps to train for (agent steps for the match), in all:
            a resumed run counts the checkpoint's steps too.
        n_envs: environments (matches for the match) stepped in parallel.
        n_workers: worker processes for them (0: in this process).
        seed: seeds the environments, the algorithm and torch.
        out: the run's folder.
        hyperparams: keyword arguments of the algorithm (over :data:`DEFAULT_HYPERPARAMS`),
            e.g. ``{"learning_rate": 1e-4, "policy_kwargs": {"net_arch": [64, 64]}}``.
        checkpoint_every, eval_every: in environment steps (0 turns them off).
        eval_episodes: shots per periodic evaluation.
        eval_env_kwargs: the evaluation environment's keyword arguments (default:
            ``env_kwargs``), e.g. to train on truth and select on perceived observations.
        learner, opponent: the match's learning team (``"blue"``, ``"yellow"``, ``"both"``)
            and the other team's policy (``"scripted"``, ``"idle"``, ``"self"`` for a frozen
            copy of the learner refreshed every ``self_play_every`` steps, or a model path).
        normalize_obs, normalize_reward: train behind stable-baselines3's ``VecNormalize``
            (running mean and variance of the observations, scaling of the rewards); the
            statistics are saved beside every model and carried by the numpy policies.
        actions: the keeper learner's action space (:data:`~agents.wrappers.ACTION_MAPS`):
            ``"native"`` (the robot's 6-number command), ``"velocity"`` (field-frame velocity
            and turn rate), ``"target"`` (where to stand, reached by a motion controller) or
            ``"guard"`` (where to stand on the guard line);
            the saved numpy policy includes the map, so it acts on the plain environment.
        frame_stack: the learner sees its last ``frame_stack`` observations concatenated,
            oldest first (:func:`~agents.wrappers.stack_frames`; 1: the observation alone);
            Goalkeeper-v0 and feed-forward algorithms only (RecurrentPPO's LSTM is its
            memory). The saved numpy policy keeps the history, so it acts on the plain
            environment's single observations.
        critic: ``"shared"`` (the critic reads the actor's observation) or ``"privileged"``
            (asymmetric actor-critic, :mod:`agents.privileged`: the critic also reads the true
            state, the actor only the observation); privileged for PPO and A2C on
            Goalkeeper-v0 without frame stacking. The saved numpy policy is the actor alone,
            acting on the plain environment.
        batched: step Goalkeeper-v0's ``n_envs`` environments as one batch in the learner's
            process (:class:`~agents.batched.BatchedVecEnv`, the
            ``vector_entry_point``): any keeper and observation mode but the pixels
            detector, with native actions, no frame stack, the shared critic and
            ``n_workers=0``. For the match: each process's matches as one batch
            (:class:`~agents.batched.BatchedMatchVecEnv`, in the learner's process or in each
            of ``n_workers`` workers).
        torch_threads: torch's intra-op threads in the learner process.
        device: torch device.
        progress_bar: show SB3's progress bar.
    """

    env_id: str = GOALKEEPER_ID
    env_kwargs: dict[str, Any] = field(default_factory=dict)
    algorithm: str = "PPO"
    total_steps: int = 1_000_000
    n_envs: int = 16
    n_workers: int = 2
    seed: int = 0
    out: str = "runs/keeper"
    hyperparams: dict[str, Any] = field(default_factory=dict)
    checkpoint_every: int = 250_000
    eval_every: int = 250_000
    eval_episodes: int = 200
    eval_env_kwargs: dict[str, Any] | None = None
    learner: str = "blue"
    opponent: str = "scripted"
    self_play_every: int = 100_000
    normalize_obs: bool = True
    normalize_reward: bool = False
    actions: str = "native"
    frame_stack: int = 1
    critic: str = "shared"
    batched: bool = False
    torch_threads: int = 1
    device: str = "cpu"
    progress_bar: bool = True

    def __post_init__(self) -> None:
        self.algorithm = algorithm_name(self.algorithm)
        if self.env_id not in (GOALKEEPER_ID, MATCH_ID):
            raise ValueError(f"env_id must be {GOALKEEPER_ID!r} or {MATCH_ID!r}, got "
                             f"{self.env_id!r}")
        check_counts(self, (("total_steps", 1), ("n_envs", 1), ("n_workers", 0),
                            ("checkpoint_every", 0), ("eval_every", 0), ("eval_episodes", 1),
                            ("self_play_every", 1), ("torch_threads", 1), ("frame_stack", 1)))
        known = _algorithm_parameters(self.algorithm)
        unknown = sorted(set(self.hyperparams) - known)
        if unknown:
            raise ValueError(f"unknown {self.algorithm} hyperparameter(s) {unknown}; allowed: "
                             f"{sorted(known)}")
        if self.actions not in ACTION_MAPS:
            raise ValueError(f"actions must be one of {list(ACTION_MAPS)}, got "
                             f"{self.actions!r}")
        if self.actions != "native" and self.env_id != GOALKEEPER_ID:
            raise ValueError(f"actions {self.actions!r} is for {GOALKEEPER_ID} only")
        if self.learner not in ("blue", "yellow", "both"):
            raise ValueError(f"learner must be 'blue', 'yellow' or 'both', got "
                             f"{self.learner!r}")
        if self.frame_stack > 1 and self.env_id != GOALKEEPER_ID:
            raise ValueError(f"frame_stack is for {GOALKEEPER_ID} only, got {self.frame_stack}")
        if self.frame_stack > 1 and self.algorithm == "RECURRENTPPO":
            raise ValueError("frame_stack is for the feed-forward algorithms: RecurrentPPO's "
                             "LSTM carries the memory")
        if self.critic not in CRITICS:
            raise ValueError(f"critic must be one of {list(CRITICS)}, got {self.critic!r}")
        if self.critic == "privileged" and (self.algorithm not in ("PPO", "A2C")
                                            or self.env_id != GOALKEEPER_ID
                                            or self.frame_stack > 1):
            raise ValueError(f"critic 'privileged' is for PPO and A2C on {GOALKEEPER_ID} "
                             f"without frame stacking, got {self.algorithm} on {self.env_id} "
                             f"with frame_stack {self.frame_stack}")
        if self.opponent not in OPPONENTS and not (str(self.opponent).endswith(".npz")
                                                   and Path(self.opponent).is_file()):
            raise ValueError(f"opponent must be one of {list(OPPONENTS)} or the path of a "
                             f"numpy policy file (.npz), got {self.opponent!r}"
                             + ("" if not str(self.opponent).endswith(".npz") else
                                " (no such file)"))
        if self.algorithm == "RECURRENTPPO" and self.env_id == MATCH_ID and \
                self.opponent == "self":
            raise ValueError("opponent 'self' takes feed-forward learners only: a recurrent "
                             "copy cannot play the opponent team (the match does not reset "
                             "an opponent's memory)")

        if self.batched and self.env_id == GOALKEEPER_ID:
            wrong = [(name, value) for name, value, ok in (
                ("actions", self.actions, self.actions == "native"),
                ("frame_stack", self.frame_stack, self.frame_stack == 1),
                ("critic", self.critic, self.critic == "shared"),
                ("n_workers", self.n_workers, self.n_workers == 0)) if not ok]
            if wrong:
                raise ValueError(f"batched runs {GOALKEEPER_ID} with native actions, no frame "
                                 "stack, the shared critic and n_workers=0 (the batch is one "
                                 f"process), got {', '.join(f'{n}={v!r}' for n, v in wrong)}")

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> TrainConfig:
        check_fields(cls, data, "training config")
        return cls(**data)

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


def merged_hyperparams(algorithm: str, given: dict[str, Any]) -> dict[str, Any]:
    """``given`` hyperparameters over :data:`DEFAULT_HYPERPARAMS` of ``algorithm`` (any
    spelling :func:`~agents.policies.algorithm_name` takes), ``policy_kwargs`` merged key by
    key."""
    defaults = DEFAULT_HYPERPARAMS.get(algorithm_name(algorithm), {})
    merged = {**defaults, **given}
    if "policy_kwargs" in defaults and "policy_kwargs" in given:
        merged["policy_kwargs"] = {**defaults["policy_kwargs"], **given["policy_kwargs"]}
    return merged


def _algorithm_parameters(name: str) -> set[str]:
    """The keyword arguments of algorithm ``name`` that a configuration may set."""
    sig = inspect.signature(algorithm_class(name).__init__)
    return {p for p in sig.parameters if p not in ("self", "policy", "env", "_init_setup_model",
                                                   "seed", "device", "tensorboard_log")}


# ------------------------------------------------------------------------------------------
# Environments
# ------------------------------------------------------------------------------------------

def goalkeeper_env_fn(env_kwargs: dict[str, Any], actions: str = "native",
                      frame_stack: int = 1, critic: str = "shared"):
    """A picklable constructor of one training environment: Goalkeeper-v0 with
    ``env_kwargs``, the learner's action map ``actions`` and its last ``frame_stack``
    observations stacked (:func:`~agents.wrappers.stack_frames`), with the true state beside
    the observation for a ``"privileged"`` critic
    (:class:`~agents.privileged.PrivilegedObservation`), behind SB3's ``Monitor``."""
    def make():
        import gymnasium as gym
        from stable_baselines3.common.monitor import Monitor

        import soccer_env  # noqa: F401

        return Monitor(wrap_learner(gym.make(GOALKEEPER_ID, **env_kwargs), actions,
                                    frame_stack, critic))

    return make


def make_vec_env(cfg: TrainConfig):
    """The training VecEnv of ``cfg`` (seeded with ``cfg.seed``), without normalisation."""
    if cfg.env_id == MATCH_ID:
        from agents.multiagent import make_match_vec_env

        opponent = cfg.opponent
        return make_match_vec_env(cfg.env_kwargs, cfg.n_envs, cfg.learner,
                                  "idle" if opponent == "self" else opponent, cfg.seed,
                                  workers=cfg.n_workers, batched=cfg.batched)
    if cfg.batched:
        from agents.batched import BatchedVecEnv

        venv = BatchedVecEnv(cfg.n_envs, cfg.env_kwargs)
        venv.seed(cfg.seed)
        return venv
    fns = [goalkeeper_env_fn(cfg.env_kwargs, cfg.actions, cfg.frame_stack, cfg.critic)
           for _ in range(cfg.n_envs)]
    if cfg.n_workers == 0:
        from stable_baselines3.common.vec_env import DummyVecEnv

        venv = DummyVecEnv(fns)
    else:
        from agents.vec_env import WorkerVecEnv

        venv = WorkerVecEnv(fns, n_workers=cfg.n_workers)
    venv.seed(cfg.seed)
    return venv


def _action_map(cfg: TrainConfig) -> dict[str, Any] | None:
    """The map from the learner's actions to the environment's (for numpy policies)."""
    if cfg.actions == "native":
        return None
    import gymnasium as gym

    env = wrap_actions(gym.make(GOALKEEPER_ID, **cfg.env_kwargs), cfg.actions)
    params = getattr(env, "params", None)
    env.close()
    return {"kind": cfg.actions, "params": params or {}}


def check_env_kwargs(cfg: TrainConfig) -> None:
    """Build one environment of ``cfg`` (and its evaluation environment) here, so that bad
    keyword arguments fail before any process starts, with the environment's own message
    (``TypeError`` or ``ValueError``)."""
    check_full_infos(cfg.env_kwargs, "training")
    if cfg.eval_env_kwargs is not None:
        check_full_infos(cfg.eval_env_kwargs, "training's evaluation")
    if cfg.env_id == MATCH_ID:
        import soccer_env

        soccer_env.parallel_env(**cfg.env_kwargs).close()
        if cfg.batched:  # what the batch supports (SSL, the geometric detector, no rendering)
            from soccer_env.envs.batched_match import MatchBatch

            MatchBatch(1, **cfg.env_kwargs).close()
    else:
        import gymnasium as gym

        import soccer_env  # noqa: F401

        gym.make(GOALKEEPER_ID, **cfg.env_kwargs).close()
        if cfg.batched:  # what the batch supports (no pixels detector, no rendering)
            from soccer_env.envs.batched import GoalkeeperVectorEnv

            GoalkeeperVectorEnv(1, **cfg.env_kwargs).close()
        if cfg.eval_env_kwargs is not None:
            gym.make(GOALKEEPER_ID, **cfg.eval_env_kwargs).close()


# ------------------------------------------------------------------------------------------
# Callbacks
# ------------------------------------------------------------------------------------------

def rollout_timer() -> Any:
    """A stable-baselines3 callback that measures environment steps per second while
    collecting rollouts (policy forward passes included, gradient updates excluded), logged as
    ``time/rollout_fps``; its ``rate`` is the mean over the run."""
    from stable_baselines3.common.callbacks import BaseCallback

    class RolloutTimer(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.seconds, self.steps = 0.0, 0

        def _on_rollout_start(self) -> None:
            self._t0, self._n0 = time.perf_counter(), self.num_timesteps

        def _on_rollout_end(self) -> None:
            self.seconds += time.perf_counter() - self._t0
            self.steps += self.num_timesteps - self._n0
            if self.seconds > 0:
                self.logger.record("time/rollout_fps", self.steps / self.seconds)

        def _on_step(self) -> bool:
            return True

        @property
        def rate(self) -> float:
            return self.steps / self.seconds if self.seconds > 0 else float("nan")

    return RolloutTimer()


def _callbacks(cfg: TrainConfig, out: Path, action_map: dict[str, Any] | None):
    from stable_baselines3.common.callbacks import BaseCallback

    class SaveRateEval(BaseCallback):
        """Every ``eval_every`` steps: the actor's save rate on ``eval_episodes`` shots, logged
        as ``eval/save_rate``; the best model is kept."""

        def __init__(self) -> None:
            super().__init__()
            self.history: list[dict[str, Any]] = []
            self.best = -1.0
            self._next = cfg.eval_every

        def _on_training_start(self) -> None:
            # A resumed run starts at the checkpoint's step count: the next evaluation is the
            # next multiple of eval_every after it.
            self._next = (self.num_timesteps // cfg.eval_every + 1) * cfg.eval_every

        def _on_step(self) -> bool:
            if self.num_timesteps >= self._next:
                self._next += cfg.eval_every
                self.run()
            return True

        def run(self) -> dict[str, Any]:
            norm = self.model.get_vec_normalize_env()
            policy = NumpyPolicy.from_sb3(self.model, vec_normalize=norm,
                                          action_map=action_map, frame_stack=cfg.frame_stack)
            kwargs = cfg.env_kwargs if cfg.eval_env_kwargs is None else cfg.eval_env_kwargs
            res = evaluate(policy, kwargs, episodes=cfg.eval_episodes,
                           start_seed=EVAL_SEED_START, workers=max(1, cfg.n_workers))
            entry = {"steps": int(self.num_timesteps), "save_rate": res.save_rate,
                     "ci_low": res.ci_low, "ci_high": res.ci_high,
                     "outcomes": res.outcomes, "ball_rmse_m": res.ball_rmse_m}
            self.history.append(entry)
            self.logger.record("eval/save_rate", res.save_rate)
            self.logger.record("eval/mean_steps", res.mean_steps)
            (out / "evaluations.json").write_text(json.dumps(self.history, indent=1))
            if res.save_rate > self.best:
                self.best = res.save_rate
                self.model.save(out / "best_model.zip")
                if norm is not None:
                    save_vecnormalize(norm, out / "best_vecnormalize.npz")
                policy.meta.update(_meta(cfg, entry))
                policy.save(out / "best_policy.npz")
            return entry

    timer = rollout_timer()
    callbacks: list[Any] = [timer]
    class Checkpoints(BaseCallback):
        """Every ``checkpoint_every`` steps: the model as ``checkpoints/model_<N>_steps.zip``
        (stable-baselines3's ``CheckpointCallback`` names) and its normalisation statistics
        beside it as ``.npz`` (no pickle)."""

        def __init__(self) -> None:
            super().__init__()
            self.every = max(1, cfg.checkpoint_every // cfg.n_envs)

        def _on_step(self) -> bool:
            if self.n_calls % self.every == 0:
                folder = out / "checkpoints"
                folder.mkdir(parents=True, exist_ok=True)
                path = folder / f"model_{self.num_timesteps}_steps.zip"
                self.model.save(path)
                norm = self.model.get_vec_normalize_env()
                if norm is not None:
                    save_vecnormalize(norm, vecnormalize_path(path))
            return True

    if cfg.checkpoint_every:
        callbacks.append(Checkpoints())
    evaluator = None
    if cfg.eval_every and cfg.env_id == GOALKEEPER_ID:
        evaluator = SaveRateEval()
        callbacks.append(evaluator)
    if cfg.env_id == MATCH_ID and cfg.opponent == "self":
        from agents.multiagent import SelfPlayCallback

        callbacks.append(SelfPlayCallback(update_every=cfg.self_play_every))
    return callbacks, timer, evaluator


def _meta(cfg: TrainConfig, evaluation: dict[str, Any] | None = None) -> dict[str, Any]:
    meta = {"env_id": cfg.env_id, "env_kwargs": cfg.env_kwargs, "algorithm": cfg.algorithm,
            "actions": cfg.actions, "frame_stack": cfg.frame_stack, "critic": cfg.critic,
            "hyperparams": cfg.hyperparams,
            "total_steps": cfg.total_steps, "seed": cfg.seed}
    if evaluation is not None:
        meta["evaluation"] = evaluation
    return meta


# ------------------------------------------------------------------------------------------
# Training
# ------------------------------------------------------------------------------------------

def run_folder(checkpoint: str | os.PathLike) -> Path:
    """The run folder a saved model belongs to: its folder, or the one above for a model in
    ``checkpoints/``."""
    path = Path(checkpoint)
    return path.parent.parent if path.parent.name == "checkpoints" else path.parent


def run_files(folder: str | os.PathLike) -> list[str]:
    """The names of :data:`RUN_FILES` present in ``folder`` (empty: it holds no run)."""
    folder = Path(folder)
    return [name for name in RUN_FILES if (folder / name).exists()]


def train(cfg: TrainConfig, resume: str | os.PathLike | None = None,
          command: list[str] | None = None, overwrite: bool = False,
          trust: bool = False) -> dict[str, Any]:
    """Train as ``cfg`` says (continuing from the checkpoint ``resume`` if given) and write the
    run folder ``cfg.out``. Returns the summary.

    Nothing is written until the configuration, the environments and the algorithm with its
    hyperparameters have been built; before that :class:`RunRefused` is raised when
    ``resume`` has already trained ``cfg.total_steps`` steps or more (``total_steps``
    includes its steps), when ``cfg.out`` holds another run (:func:`run_files`) and
    ``overwrite`` is false (with ``overwrite`` its run files are deleted first; continuing
    a run in its own folder, ``resume`` inside ``cfg.out``, needs no ``overwrite``), or when
    the algorithm refuses the hyperparameters.

    A checkpoint is loaded without unpickling anything (see :mod:`agents.model_files`), with
    the ``.npz`` normalisation statistics beside it; ``trust=True`` loads a
    stable-baselines3 file as stable-baselines3 does (its pickled entries, a ``.pkl`` of
    statistics): only for files from a source you trust.

    Ctrl-C, or a rollout worker that dies or whose environment raises, ends training with
    :class:`TrainingStopped` after saving the model of the last completed update in
    ``cfg.out/checkpoints/`` (its message has the ``--resume`` command)."""
    import torch

    out = Path(cfg.out)
    continuing = resume is not None and run_folder(resume).resolve() == out.resolve()
    existing = [] if continuing else run_files(out)
    if existing and not overwrite:
        raise RunRefused(f"out {os.fspath(out)} already holds a training run "
                         f"({', '.join(existing)}); choose another folder, or overwrite "
                         "it (--force; its run files are deleted first)")
    if resume is not None:
        done = checkpoint_steps(resume)
        if cfg.total_steps <= done:
            raise RunRefused(f"total_steps {cfg.total_steps:,} leaves nothing to train: the "
                             f"checkpoint {os.fspath(resume)} has trained {done:,} steps and "
                             "total_steps counts them too")
    check_env_kwargs(cfg)
    torch.set_num_threads(cfg.torch_threads)
    action_map = _action_map(cfg)
    try:
        venv, params = _training_env(cfg, resume, trust)
    except ValueError as err:  # statistics that cannot be read safely, or do not fit
        raise RunRefused(f"resume: {err}") from None
    try:
        model, done_steps = _model(cfg, venv, params, resume, out, trust)
    except Exception as err:
        venv.close()
        if resume is not None:
            raise RunRefused(f"resume: {err}") from None
        raise RunRefused(f"{cfg.algorithm} could not be built with hyperparameters "
                         f"{params}: {type(err).__name__}: {err}") from err
    for name in existing:  # overwrite: this run's files only, nothing else in the folder
        path = out / name
        if path.is_dir():
            shutil.rmtree(path)
        else:
            path.unlink()
    out.mkdir(parents=True, exist_ok=True)
    (out / "config.json").write_text(json.dumps({
        **cfg.to_dict(), "action_map": action_map, "command": command,
        "resumed_from": None if resume is None else os.fspath(resume),
        "versions": _versions()}, indent=2))
    callbacks, timer, evaluator = _callbacks(cfg, out, action_map)
    last_update = _last_update()
    remaining = max(0, cfg.total_steps - done_steps)
    t0 = time.perf_counter()
    try:
        model.learn(remaining, callback=[*callbacks, last_update],
                    progress_bar=cfg.progress_bar, reset_num_timesteps=resume is None,
                    tb_log_name=cfg.algorithm)
    except BaseException as err:
        from agents.vec_env import WorkerError

        if not isinstance(err, (KeyboardInterrupt, WorkerError)):
            raise
        stopped = _stop(cfg, model, out, last_update, done_steps, err)
        raise stopped from err
    finally:
        venv.close()
    seconds = time.perf_counter() - t0
    final_eval = _save_final(cfg, model, out, evaluator, action_map)
    summary = {
        "steps": int(model.num_timesteps), "trained_steps": remaining,
        "seconds": seconds, "steps_per_s": remaining / seconds if seconds > 0 else None,
        "rollout_steps_per_s": timer.rate,
        "last_evaluation": final_eval,
        "best_evaluation": max(evaluator.history, key=lambda e: e["save_rate"])
        if evaluator and evaluator.history else None,
        "files": sorted(p.name for p in out.iterdir()),
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def _last_update() -> Any:
    """A stable-baselines3 callback that keeps a copy of the model's parameters (networks and
    optimisers) and observation statistics as they are when each rollout starts, i.e. after
    the last completed update, so that an interrupted run saves a consistent model rather
    than one caught in the middle of a gradient step."""
    import copy

    from stable_baselines3.common.callbacks import BaseCallback

    class LastUpdate(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.steps: int | None = None
            self.params: dict[str, Any] | None = None
            self.norm: tuple[Any, Any] | None = None

        def _on_rollout_start(self) -> None:
            self.steps = int(self.model.num_timesteps)
            self.params = copy.deepcopy(self.model.get_parameters())
            norm = self.model.get_vec_normalize_env()
            self.norm = None if norm is None else copy.deepcopy((norm.obs_rms, norm.ret_rms))

        def _on_step(self) -> bool:
            return True

        def restore(self) -> int | None:
            """Put the copy back into the model; returns its step count (None: no rollout
            had started)."""
            if self.params is None:
                return None
            self.model.set_parameters(self.params, exact_match=True)
            self.model.num_timesteps = self.steps
            norm = self.model.get_vec_normalize_env()
            if norm is not None and self.norm is not None:
                norm.obs_rms, norm.ret_rms = self.norm
            return self.steps

    return LastUpdate()


def _stop(cfg: TrainConfig, model: Any, out: Path, last_update: Any, done_steps: int,
          err: BaseException) -> TrainingStopped:
    """Save the model of the last completed update as a checkpoint of the run (where
    ``--resume`` finds it) and describe how the run ended and how to continue it."""
    reason = "interrupted" if isinstance(err, KeyboardInterrupt) else "worker failed"
    what = "interrupted" if reason == "interrupted" else f"stopped: {err}"
    steps = last_update.restore()
    if steps is None or steps <= done_steps:
        return TrainingStopped(f"training {what}\nnothing trained since the start, so no "
                               "checkpoint was saved", reason, None, done_steps, None)
    folder = out / "checkpoints"
    folder.mkdir(parents=True, exist_ok=True)
    checkpoint = folder / f"model_{steps}_steps.zip"
    model.save(checkpoint)
    norm = model.get_vec_normalize_env()
    if norm is not None:
        save_vecnormalize(norm, vecnormalize_path(checkpoint))
    command = (f"soccer-env train --resume {checkpoint} --steps {cfg.total_steps}")
    return TrainingStopped(f"training {what}\nsaved the model of the last completed update "
                           f"({steps:,} steps) to {checkpoint}\ncontinue with: {command}",
                           reason, checkpoint, steps, command)


def _training_env(cfg: TrainConfig, resume: str | os.PathLike | None, trust: bool = False
                  ) -> tuple[Any, dict[str, Any]]:
    """The training VecEnv of ``cfg`` behind ``VecNormalize`` if asked (the statistics of
    the checkpoint ``resume`` where it has them: the ``.npz``, or with ``trust`` a
    stable-baselines3 ``.pkl``), and the algorithm's keyword arguments."""
    from stable_baselines3.common.vec_env import VecNormalize

    stats = None
    if resume is not None and (cfg.normalize_obs or cfg.normalize_reward):
        stats = load_vecnormalize(resume, trust)  # before any process starts
    venv = make_vec_env(cfg)
    params = merged_hyperparams(cfg.algorithm, cfg.hyperparams)
    if cfg.algorithm in ("PPO", "RECURRENTPPO"):
        # Keep one rollout at about n_steps * n_envs and a whole number of minibatches.
        params["batch_size"] = min(params["batch_size"], params["n_steps"] * venv.num_envs)
    if cfg.normalize_obs or cfg.normalize_reward:
        if isinstance(stats, VecNormalize):  # unpickled (trusted): as VecNormalize.load does
            stats.set_venv(venv)
            venv = stats
        elif stats is not None:
            try:
                venv = vecnormalize_on(stats, venv)
            except ValueError:
                venv.close()
                raise
        else:
            venv = VecNormalize(venv, norm_obs=cfg.normalize_obs,
                                norm_reward=cfg.normalize_reward,
                                gamma=params.get("gamma", 0.99))
    return venv, params


def _model(cfg: TrainConfig, venv: Any, params: dict[str, Any],
           resume: str | os.PathLike | None, out: Path, trust: bool = False
           ) -> tuple[Any, int]:
    """A new model of ``cfg.algorithm`` on ``venv``, or the checkpoint ``resume`` loaded onto
    it; and the steps it has already trained."""
    algo = algorithm_class(cfg.algorithm)
    policy: Any = "MlpLstmPolicy" if cfg.algorithm == "RECURRENTPPO" else "MlpPolicy"
    if cfg.critic == "privileged":
        from agents.privileged import PrivilegedActorCriticPolicy

        policy = PrivilegedActorCriticPolicy
    if resume is not None:
        # The hyperparameters of this configuration replace the saved ones (so that a run
        # can be fine-tuned, e.g. with another entropy bonus or learning rate); the network
        # (policy_kwargs) is the saved model's. Nothing is unpickled unless trusted: the
        # spaces are the training environment's, the schedules this configuration's.
        from agents.policies import load_sb3

        saved_kwargs = params.pop("policy_kwargs", None)
        model = load_sb3(resume, cfg.algorithm, trust=trust,
                         observation_space=venv.observation_space,
                         action_space=venv.action_space,
                         policy_class=None if isinstance(policy, str) else policy,
                         hyperparams={**params, "policy_kwargs": saved_kwargs},
                         env=venv, device=cfg.device, tensorboard_log=str(out / "tb"),
                         **params)
        return model, int(model.num_timesteps)
    model = algo(policy, venv, seed=cfg.seed, device=cfg.device,
                 tensorboard_log=str(out / "tb"), verbose=0, **params)
    return model, 0


def _save_final(cfg: TrainConfig, model: Any, out: Path, evaluator: Any,
                action_map: dict[str, Any] | None) -> dict[str, Any] | None:
    """Save the final model, its ``VecNormalize`` statistics and its numpy copy; evaluate it
    unless the last periodic evaluation was at its step count. Returns the final
    evaluation (None without periodic evaluations)."""
    model.save(out / "final_model.zip")
    norm = model.get_vec_normalize_env()
    if norm is not None:
        save_vecnormalize(norm, out / "final_vecnormalize.npz")
    final_eval = None
    if evaluator is not None:
        if not evaluator.history or evaluator.history[-1]["steps"] != model.num_timesteps:
            evaluator.run()
        final_eval = evaluator.history[-1]
    try:
        policy = NumpyPolicy.from_sb3(model, _meta(cfg, final_eval), norm, action_map,
                                      cfg.frame_stack)
        policy.save(out / "final_policy.npz")
    except ValueError:  # a network numpy cannot copy: the .zip is the model
        pass
    return final_eval


def checkpoint_steps(path: str | os.PathLike) -> int:
    """The environment steps a saved stable-baselines3 model has trained (its
    ``num_timesteps``), read from the JSON part of the ``.zip`` without loading (unpickling)
    anything. Raises ``ValueError`` for a file that is not such a model."""
    import zipfile

    try:
        with zipfile.ZipFile(path) as archive:
            data = json.loads(archive.read("data"))
        return int(data["num_timesteps"])
    except (zipfile.BadZipFile, KeyError, ValueError, TypeError) as err:
        raise ValueError(f"{os.fspath(path)} is not a stable-baselines3 model file ({err})"
                         ) from None


def _versions() -> dict[str, str]:
    import gymnasium
    import stable_baselines3
    import torch

    versions = {"python": platform.python_version(),
                "stable_baselines3": stable_baselines3.__version__, "torch": torch.__version__,
                "gymnasium": gymnasium.__version__, "numpy": np.__version__}
    try:
        import sb3_contrib
    except ImportError:
        return versions
    return {**versions, "sb3_contrib": sb3_contrib.__version__}
