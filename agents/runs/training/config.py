"""The configuration of a stable-baselines3 training run (``soccer-env train``):
:class:`TrainConfig`, checked as a whole when made, saved as the run's ``config.json``.

Adding a training option is a field here (with its documentation and its check in
:meth:`TrainConfig.__post_init__`), its use where the run needs it
(:mod:`~agents.runs.training.environments`, :mod:`~agents.runs.training.callbacks` or
:mod:`~agents.runs.training.loop`) and its option in :mod:`soccer_lab.commands.train_options`.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from agents.common.checks import check_counts, positive_seconds
from agents.common.processes import REPLY_TIMEOUT
from agents.policies.action_maps import ACTION_MAPS
from agents.sb3.algorithms import algorithm_name, algorithm_parameters
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_env.validation import check_fields

__all__ = ["TrainConfig", "OPPONENTS", "CRITICS", "EVAL_SEED_START"]

#: The match opponents given by name (besides the path of a numpy policy file, ``.npz``).
OPPONENTS = ("scripted", "idle", "self")

#: The critics of ``critic=``: ``"shared"`` (the actor's observation, stable-baselines3's
#: default) or ``"privileged"`` (also the true state, :mod:`agents.sb3.privileged`).
CRITICS = ("shared", "privileged")

#: First seed of the shots used for model selection during training.
EVAL_SEED_START = 1_000_000


@dataclass
class TrainConfig:
    """Everything a training run needs (saved as ``config.json``).

    Attributes:
        env_id: ``"soccer_env/Goalkeeper-v0"`` or ``"soccer_env/Match-v0"``.
        env_kwargs: keyword arguments of the environment (``obs_mode``, ``perception``,
            ``shaping``, ...).
        algorithm: one of :data:`~agents.sb3.algorithms.SB3_ALGORITHMS` (any spelling
            :func:`~agents.sb3.algorithms.algorithm_name` takes, e.g. ``"recurrent-ppo"``; stored
            canonical, ``"RECURRENTPPO"``).
        total_steps: environment steps to train for (agent steps for the match), in all:
            a resumed run counts the checkpoint's steps too.
        n_envs: environments (matches for the match) stepped in parallel.
        n_workers: worker processes for them (0: in this process).
        worker_timeout: seconds a worker process may take to answer before training stops as
            for a worker that died (finite, > 0; a worker stopped with ``SIGSTOP``,
            deadlocked or in an endless loop): a checkpoint of the last completed update and
            the command that resumes. Until its first step a worker gets at least
            :data:`~agents.common.processes.START_TIMEOUT` (300 s) to start.
        seed: seeds the environments, the algorithm and torch.
        out: the run's folder.
        hyperparams: keyword arguments of the algorithm (over
            :data:`~agents.sb3.algorithms.DEFAULT_HYPERPARAMS`),
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
        actions: the keeper learner's action space
            (:data:`~agents.policies.action_maps.ACTION_MAPS`):
            ``"native"`` (the robot's 6-number command), ``"velocity"`` (field-frame velocity
            and turn rate), ``"target"`` (where to stand, reached by a motion controller) or
            ``"guard"`` (where to stand on the guard line);
            the saved numpy policy includes the map, so it acts on the plain environment.
        frame_stack: the learner sees its last ``frame_stack`` observations concatenated,
            oldest first (:func:`~agents.policies.wrappers.stack_frames`; 1: the observation
            alone);
            Goalkeeper-v0 and feed-forward algorithms only (RecurrentPPO's LSTM is its
            memory). The saved numpy policy keeps the history, so it acts on the plain
            environment's single observations.
        critic: ``"shared"`` (the critic reads the actor's observation) or ``"privileged"``
            (asymmetric actor-critic, :mod:`agents.sb3.privileged`: the critic also reads the true
            state, the actor only the observation); privileged for PPO and A2C on
            Goalkeeper-v0 without frame stacking. The saved numpy policy is the actor alone,
            acting on the plain environment.
        batched: step Goalkeeper-v0's ``n_envs`` environments as one batch in the learner's
            process (:class:`~agents.vec.batched.BatchedVecEnv`, the
            ``vector_entry_point``): any keeper and observation mode but the pixels
            detector, with native actions, no frame stack, the shared critic and
            ``n_workers=0``. For the match: each process's matches as one batch
            (:class:`~agents.vec.batched.BatchedMatchVecEnv`, in the learner's process or in each
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
    worker_timeout: float = REPLY_TIMEOUT
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
        self.worker_timeout = positive_seconds(self.worker_timeout, "worker_timeout")
        known = algorithm_parameters(self.algorithm)
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

    def policy_meta(self, evaluation: dict[str, Any] | None = None) -> dict[str, Any]:
        """What a saved numpy policy of this run records in its ``meta``: the environment,
        the algorithm, the learner's action map, frame stack and critic, the hyperparameters,
        the steps and the seed, and ``evaluation`` if given."""
        meta = {"env_id": self.env_id, "env_kwargs": self.env_kwargs, "algorithm": self.algorithm,
                "actions": self.actions, "frame_stack": self.frame_stack, "critic": self.critic,
                "hyperparams": self.hyperparams,
                "total_steps": self.total_steps, "seed": self.seed}
        if evaluation is not None:
            meta["evaluation"] = evaluation
        return meta
