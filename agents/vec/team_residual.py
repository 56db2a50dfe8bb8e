"""The ``"team-residual"`` map in training: a match VecEnv whose learning team's actions are
corrections to the scripted team's commands (:mod:`agents.scripted.residual` has the map itself,
which a saved numpy policy uses without stable-baselines3)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from stable_baselines3.common.vec_env import VecEnv, VecEnvWrapper

from agents.scripted import ignored_rows, residual_command, scripted_team_from_params

__all__ = ["TeamResidualVecEnv"]


class TeamResidualVecEnv(VecEnvWrapper):
    """A match VecEnv (:func:`~agents.vec.factories.make_match_vec_env`) whose learning team acts
    through the ``"team-residual"`` map: the learner's action ``a`` in ``[-1, 1]^6`` becomes
    the scripted team's command from the entry's last observation plus ``a * residual``.

    Wrap it inside ``VecNormalize`` (the map reads the plain observations). ``params`` is
    what a :class:`~agents.policies.numpy_policy.NumpyPolicy` copy of the learner needs as its
    ``action_map`` (:attr:`action_map`).

    Every step's info says whether the entry's action was ignored
    (``info["correction_ignored"]``: the map played the scripted command, the robot being in a
    restart, off the field or barred; :func:`~agents.scripted.ignored_rows`), for
    :class:`~agents.sb3.masking.IgnoredActions` to keep those steps out of the policy's update.
    """

    def __init__(self, venv: VecEnv, params: Mapping[str, Any]) -> None:
        super().__init__(venv)
        self.params = dict(params)
        # Rebuilt once here, not at every step.
        self._team = scripted_team_from_params(self.params)
        size = self._team.team_size
        if venv.num_envs % size:
            raise ValueError(f"the VecEnv's {venv.num_envs} entries are not whole teams of "
                             f"{size} robots")
        if len(self.params["names"]) != venv.observation_space.shape[0]:
            raise ValueError(f"the map's observation layout has {len(self.params['names'])} "
                             f"entries, the VecEnv's {venv.observation_space.shape[0]}")
        self._obs: np.ndarray | None = None
        self._ignored = np.zeros(venv.num_envs, dtype=bool)

    @property
    def action_map(self) -> dict[str, Any]:
        """``{"kind": "team-residual", "params": ...}``, as a numpy policy stores it."""
        return {"kind": "team-residual", "params": dict(self.params)}

    def reset(self) -> np.ndarray:
        self._obs = self.venv.reset()
        return self._obs

    def step_async(self, actions: np.ndarray) -> None:
        if self._obs is None:
            raise RuntimeError("call reset() before step()")
        self._ignored = ignored_rows(self._team, self._obs)
        self.venv.step_async(residual_command(self._team, float(self.params["residual"]),
                                              self._obs, actions, self._ignored))

    def step_wait(self):
        obs, rewards, dones, infos = self.venv.step_wait()
        self._obs = obs
        for info, ignored in zip(infos, self._ignored):
            info["correction_ignored"] = bool(ignored)
        return obs, rewards, dones, infos
