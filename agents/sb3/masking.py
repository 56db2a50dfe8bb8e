"""Steps whose action the environment ignored kept out of PPO's policy update
(:class:`IgnoredActions`).

Under the game flow the ``"team-residual"`` map plays the scripted team's command at every
restart, whatever the learner's correction (:class:`~agents.vec.team_residual.TeamResidualVecEnv`
flags those steps ``info["correction_ignored"]``); a match spends about half its time there.
Their advantages say nothing about the action taken, yet PPO's policy gradient still follows
them: noise that the network, shared with open play, carries over. The callback zeroes those
advantages after each rollout (the critic still learns their returns) and normalises the rest
itself, over the rollout, in place of PPO's per-batch normalisation
(``normalize_advantage=False``), which would turn the zeros into shifts.
"""

from __future__ import annotations

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback

__all__ = ["IgnoredActions"]


class IgnoredActions(BaseCallback):
    """Zero the advantages of the steps whose info says ``key`` (their action was ignored) and
    normalise the others over the rollout (mean 0, standard deviation 1); see the module
    docstring. The model must be PPO with ``normalize_advantage=False``.

    Attributes:
        ignored_fraction: the fraction of the last rollout's steps that were ignored.
    """

    def __init__(self, key: str = "correction_ignored") -> None:
        super().__init__()
        self.key = key
        self.ignored_fraction = 0.0
        self._mask: np.ndarray | None = None

    def _on_training_start(self) -> None:
        if getattr(self.model, "normalize_advantage", None) is not False:
            raise ValueError("IgnoredActions normalises the advantages itself: give PPO "
                             "normalize_advantage=False")

    def _on_rollout_start(self) -> None:
        buf = self.model.rollout_buffer
        self._mask = np.zeros((buf.buffer_size, buf.n_envs), dtype=bool)

    def _on_step(self) -> bool:
        # Called after the environment's step and before the rollout buffer stores it: the
        # step lands at the buffer's present position.
        pos = self.model.rollout_buffer.pos
        if self._mask is not None and pos < len(self._mask):
            self._mask[pos] = [bool(info.get(self.key, False))
                               for info in self.locals["infos"]]
        return True

    def _on_rollout_end(self) -> None:
        if self._mask is None:
            return
        adv = self.model.rollout_buffer.advantages
        live = ~self._mask
        self.ignored_fraction = float(self._mask.mean())
        self.logger.record("train/ignored_fraction", self.ignored_fraction)
        if live.any():
            values = adv[live]
            adv[live] = (values - values.mean()) / (values.std() + 1e-8)
        adv[self._mask] = 0.0
