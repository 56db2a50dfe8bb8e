"""The batched Goalkeeper as a stable-baselines3 ``VecEnv``: :class:`BatchedVecEnv`.

:class:`~soccer_env.envs.batched.GoalkeeperVectorEnv` steps its episodes in one batch with
Gymnasium's vector API; stable-baselines3 expects its own ``VecEnv`` contract: automatic reset
within the step that ends an episode, the last observation in
``infos[i]["terminal_observation"]``, ``infos[i]["TimeLimit.truncated"]``, ``seed()`` before
``reset()``, one info dict per environment. This adapter runs the vector environment with
``SAME_STEP`` autoreset and translates, adding ``Monitor``'s episode statistics
(``infos[i]["episode"] = {"r", "l", "t"}``) and ``is_success`` / ``outcome`` at episode ends.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.vec_env.base_vec_env import (
    VecEnv,
    VecEnvIndices,
    VecEnvStepReturn,
)

from soccer_env.envs.batched import GoalkeeperVectorEnv

__all__ = ["BatchedVecEnv"]


class BatchedVecEnv(VecEnv):
    """``num_envs`` batched Goalkeeper-v0 episodes as a stable-baselines3 ``VecEnv``.

    Args:
        num_envs: environments.
        env_kwargs: Goalkeeper-v0's keyword arguments (what the batch supports: SSL keepers,
            truth observations).
        max_episode_steps: the time limit (Goalkeeper-v0's 480 by default).
    """

    def __init__(self, num_envs: int = 16, env_kwargs: dict[str, Any] | None = None,
                 max_episode_steps: int | None = 480) -> None:
        self.venv = GoalkeeperVectorEnv(num_envs, max_episode_steps=max_episode_steps,
                                        autoreset_mode=AutoresetMode.SAME_STEP,
                                        **(env_kwargs or {}))
        super().__init__(num_envs, self.venv.single_observation_space,
                         self.venv.single_action_space)
        self._seed: int | None = None
        self._actions: np.ndarray | None = None
        self._returns = np.zeros(num_envs)
        self._lengths = np.zeros(num_envs, dtype=np.int64)
        self._t0 = time.time()

    def seed(self, seed: int | None = None) -> Sequence[int | None]:
        """Seed the next :meth:`reset`: environment ``k`` gets ``seed + k``."""
        self._seed = seed
        return [None if seed is None else seed + k for k in range(self.num_envs)]

    def reset(self) -> np.ndarray:
        obs, _ = self.venv.reset(seed=self._seed)
        self._seed = None
        self._returns[:] = 0.0
        self._lengths[:] = 0
        self.reset_infos = [{} for _ in range(self.num_envs)]
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = np.asarray(actions)

    def step_wait(self) -> VecEnvStepReturn:
        if self._actions is None:
            raise RuntimeError("call step_async(actions) before step_wait()")
        actions, self._actions = self._actions, None
        obs, rewards, terminated, truncated, info = self.venv.step(actions)
        self._returns += rewards
        self._lengths += 1
        dones = terminated | truncated
        infos: list[dict[str, Any]] = [{"TimeLimit.truncated": bool(tr and not te)}
                                       for te, tr in zip(terminated.tolist(),
                                                         truncated.tolist())]
        if dones.any():
            final = info["final_info"]
            elapsed = round(time.time() - self._t0, 6)
            for k in np.nonzero(dones)[0].tolist():
                entry = infos[k]
                entry["terminal_observation"] = info["final_obs"][k]
                entry["outcome"] = final["outcome"][k]
                if terminated[k]:
                    entry["is_success"] = bool(final["is_success"][k])
                entry["episode"] = {"r": float(self._returns[k]), "l": int(self._lengths[k]),
                                    "t": elapsed}
            self._returns[dones] = 0.0
            self._lengths[dones] = 0
        return obs, rewards.astype(np.float32), dones, infos

    def close(self) -> None:
        self.venv.close()

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        return [getattr(self.venv, attr_name) for _ in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        setattr(self.venv, attr_name, value)

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        """Call the batched environment's ``method_name`` once; its result for each index."""
        result = getattr(self.venv, method_name)(*method_args, **method_kwargs)
        return [result for _ in self._get_indices(indices)]

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None
                       ) -> list[bool]:
        return [False for _ in self._get_indices(indices)]
