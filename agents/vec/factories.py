"""Factories of the vectorised environments: the match's (:func:`make_match_vec_env`: in this
process or over worker processes, one match after the other or as a batch) and the keeper
learner's single environments (:func:`goalkeeper_env_fn`, for ``DummyVecEnv`` or
:class:`~agents.vec.workers.WorkerVecEnv`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from stable_baselines3.common.vec_env import VecEnv

from agents.common.processes import REPLY_TIMEOUT
from agents.policies.wrappers import wrap_learner
from agents.vec.batched import BatchedMatchVecEnv
from agents.vec.match import MatchVecEnv
from agents.vec.match_workers import MatchWorkerVecEnv
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["make_match_vec_env", "goalkeeper_env_fn"]


def make_match_vec_env(env_kwargs: Mapping[str, Any] | None = None, n_matches: int = 1,
                       learner: str = "blue", opponent: Any = None, seed: int | None = None,
                       workers: int = 0, pin: bool | None = None, batched: bool = False,
                       reply_timeout: float = REPLY_TIMEOUT) -> VecEnv:
    """A :class:`~agents.vec.match.MatchVecEnv` (``workers=0``: every match in this process) or
    a :class:`~agents.vec.match_workers.MatchWorkerVecEnv` (its matches split over ``workers``
    processes; ``pin`` and ``reply_timeout``, the seconds a worker may take to answer, as that
    class takes them), seeded so that its first ``reset()`` is reproducible (match ``k`` gets
    ``seed + k``, whatever the number of workers). With ``batched``, the matches of each
    process are stepped as one batch (:class:`~agents.vec.batched.BatchedMatchVecEnv`)."""
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 0:
        raise ValueError(f"workers must be an integer >= 0, got {workers!r}")
    if not isinstance(batched, (bool, np.bool_)):
        raise TypeError(f"batched must be True or False, got {batched!r}")
    if workers:
        venv: VecEnv = MatchWorkerVecEnv(env_kwargs, n_matches=n_matches, learner=learner,
                                         opponent=opponent, workers=int(workers), pin=pin,
                                         batched=bool(batched), reply_timeout=reply_timeout)
        if seed is not None:
            venv.seed(seed)
        return venv
    if batched:
        venv = BatchedMatchVecEnv(env_kwargs, n_matches=n_matches, learner=learner,
                                  opponent=opponent)
    else:
        venv = MatchVecEnv(env_kwargs, n_matches=n_matches, learner=learner,
                           opponent=opponent)
    if seed is not None:
        venv.seed(seed)
    return venv


def goalkeeper_env_fn(env_kwargs: dict[str, Any], actions: str = "native",
                      frame_stack: int = 1, critic: str = "shared"):
    """A picklable constructor of one training environment: Goalkeeper-v0 with
    ``env_kwargs``, the learner's action map ``actions`` and its last ``frame_stack``
    observations stacked (:func:`~agents.policies.wrappers.stack_frames`), with the true state
    beside the observation for a ``"privileged"`` critic
    (:class:`~agents.policies.wrappers.PrivilegedObservation`), behind SB3's ``Monitor``."""
    def make():
        import gymnasium as gym
        from stable_baselines3.common.monitor import Monitor

        import soccer_env  # noqa: F401

        return Monitor(wrap_learner(gym.make(GOALKEEPER_ID, **env_kwargs), actions,
                                    frame_stack, critic))

    return make
