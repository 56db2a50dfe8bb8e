"""Self-play in the match's vectorised environments: :class:`SelfPlayCallback` copies the
learner into the opponent team as it trains (see :mod:`agents.vec.match`)."""

from __future__ import annotations

from collections import deque
from typing import Any

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.vec_env import VecEnv, VecEnvWrapper, VecNormalize

from agents.sb3.policies import numpy_copy
from agents.vec.match import MatchVecEnv
from agents.vec.match_workers import MatchWorkerVecEnv

__all__ = ["SelfPlayCallback"]


def _find_match_vec_env(env: VecEnv) -> tuple[Any, VecNormalize | None, dict | None]:
    """The :class:`MatchVecEnv` under ``env``'s wrappers, the outermost ``VecNormalize``
    that normalises observations, if any, and the action map of the outermost wrapper that
    maps the learner's actions (:class:`~agents.vec.team_residual.TeamResidualVecEnv`), if
    any."""
    norm = action_map = None
    while isinstance(env, VecEnvWrapper):
        if norm is None and isinstance(env, VecNormalize) and env.norm_obs:
            norm = env
        if action_map is None and hasattr(env, "action_map"):
            action_map = env.action_map
        env = env.venv
    if not isinstance(env, (MatchVecEnv, MatchWorkerVecEnv)):
        raise ValueError(f"SelfPlayCallback needs a model trained on a MatchVecEnv (possibly "
                         f"wrapped), got {type(env).__name__}")
    return env, norm, action_map


class SelfPlayCallback(BaseCallback):
    """Self-play: every ``update_every`` timesteps, copy the learner's current policy into
    the opponent team of the :class:`~agents.vec.match.MatchVecEnv` it trains on.

    The copy is a frozen :class:`~agents.policies.numpy_policy.NumpyPolicy` (the deterministic
    action, :func:`~agents.sb3.policies.numpy_copy`; it does not change while the learner
    trains). If the observations pass through ``VecNormalize``, the copy carries a frozen copy
    of its statistics; if the learner acts through an action map
    (:class:`~agents.vec.team_residual.TeamResidualVecEnv`), the copy acts through the same
    map. With ``pool_size > 1`` the callback keeps the last ``pool_size`` copies and each
    match draws one of them whenever it resets; with ``pool_size == 1`` the newest copy
    replaces the opponent of every match at once.

    Args:
        update_every: timesteps between copies, as SB3 counts them (``num_timesteps``: one
            per batch entry and step).
        pool_size: how many past copies to keep (>= 1).
        copy_at_start: also copy the initial policy when training starts (otherwise the
            VecEnv's own opponent plays until the first update).
        verbose: 1 prints a line at each copy.

    Attributes:
        n_updates: copies made so far.
        pool: the copies kept, oldest first.
    """

    def __init__(self, update_every: int = 10_000, pool_size: int = 1,
                 copy_at_start: bool = True, verbose: int = 0) -> None:
        super().__init__(verbose)
        if isinstance(update_every, bool) or not isinstance(update_every, (int, np.integer)) \
                or update_every < 1:
            raise ValueError(f"update_every must be an integer >= 1, got {update_every!r}")
        if isinstance(pool_size, bool) or not isinstance(pool_size, (int, np.integer)) \
                or pool_size < 1:
            raise ValueError(f"pool_size must be an integer >= 1, got {pool_size!r}")
        self.update_every = int(update_every)
        self.pool_size = int(pool_size)
        self.copy_at_start = bool(copy_at_start)
        self.pool: deque[Any] = deque(maxlen=self.pool_size)
        self.n_updates = 0
        self._last_update = 0

    def _init_callback(self) -> None:
        self._venv, self._norm, self._action_map = _find_match_vec_env(self.training_env)
        if self._venv.learner == "both":
            raise ValueError("SelfPlayCallback needs learner='blue' or 'yellow': with "
                             "learner='both' both teams already play the learning policy")
        if not self._venv.opponent_agents:
            raise ValueError("SelfPlayCallback: the match has no opponent team")

    def _on_training_start(self) -> None:
        self._last_update = self.num_timesteps
        if self.copy_at_start:
            self.update_opponent()

    def _on_step(self) -> bool:
        if self.num_timesteps - self._last_update >= self.update_every:
            self._last_update = self.num_timesteps
            self.update_opponent()
        return True

    def snapshot(self) -> Any:
        """A frozen copy of the learner's current deterministic policy."""
        return numpy_copy(self.model, {"timesteps": self.num_timesteps}, self._norm,
                          action_map=self._action_map)

    def update_opponent(self) -> None:
        """Copy the learner now and hand the copy (or the pool) to the VecEnv."""
        self.pool.append(self.snapshot())
        if self.pool_size == 1:
            self._venv.set_opponent(self.pool[-1])
        else:
            # The first copy replaces the VecEnv's own opponent at once; later ones join the
            # pool that matches draw from when they reset.
            self._venv.set_opponent_pool(list(self.pool), redraw_now=self.n_updates == 0)
        self.n_updates += 1
        if self.verbose:
            print(f"SelfPlayCallback: opponent updated at {self.num_timesteps} timesteps "
                  f"({len(self.pool)} in the pool)")
