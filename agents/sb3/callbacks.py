"""stable-baselines3 callbacks that any run uses: the rollout collection rate
(:class:`RolloutTimer`) and the model as it was after the last completed update
(:class:`LastUpdate`, what an interrupted run saves)."""

from __future__ import annotations

import copy
import time
from typing import Any

from stable_baselines3.common.callbacks import BaseCallback

__all__ = ["RolloutTimer", "rollout_timer", "LastUpdate", "last_update"]


class RolloutTimer(BaseCallback):
    """Measures environment steps per second while collecting rollouts (policy forward passes
    included, gradient updates excluded), logged as ``time/rollout_fps``; :attr:`rate` is the
    mean over the run."""

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
        """Environment steps per second of rollout collection (nan before any rollout)."""
        return self.steps / self.seconds if self.seconds > 0 else float("nan")


def rollout_timer() -> RolloutTimer:
    """A :class:`RolloutTimer` (the callback that measures the rollout collection rate)."""
    return RolloutTimer()


class LastUpdate(BaseCallback):
    """Keeps a copy of the model's parameters (networks and optimisers) and observation
    statistics as they are when each rollout starts, i.e. after the last completed update, so
    that an interrupted run saves a consistent model rather than one caught in the middle of a
    gradient step (:meth:`restore`)."""

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
        """Put the copy back into the model; returns its step count (None: no rollout had
        started)."""
        if self.params is None:
            return None
        self.model.set_parameters(self.params, exact_match=True)
        self.model.num_timesteps = self.steps
        norm = self.model.get_vec_normalize_env()
        if norm is not None and self.norm is not None:
            norm.obs_rms, norm.ret_rms = self.norm
        return self.steps


def last_update() -> LastUpdate:
    """A :class:`LastUpdate` (the callback that keeps the model of the last completed
    update)."""
    return LastUpdate()
