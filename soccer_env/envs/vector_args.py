"""The vector API's arguments of the batched environments (:mod:`soccer_env.envs.batched`),
read as Gymnasium's ``SyncVectorEnv`` reads them: the autoreset mode, ``reset``'s seeds and
``reset_mask``; and the fallback to a ``SyncVectorEnv`` of single environments for the
arguments a batch refuses (:class:`NotBatchable`), each argument passed where it belongs."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv

from soccer_env.validation import check_options, check_seed

__all__ = ["NotBatchable", "VECTOR_ARGUMENTS", "vector_or_sync", "check_autoreset_mode",
           "vector_seeds", "reset_mask"]

#: The arguments of ``make_vec`` that are the vector environment's, not the task's: where a
#: batch falls back to a ``SyncVectorEnv`` they go to it.
VECTOR_ARGUMENTS = ("autoreset_mode",)


class NotBatchable(ValueError):
    """The arguments ask for what the batch does not run yet."""


def vector_or_sync(cls: type, env_id: str, num_envs: int, max_episode_steps: int | None,
                   kwargs: dict[str, Any]) -> VectorEnv:
    """``cls(num_envs, ...)``, or a ``SyncVectorEnv`` of ``gymnasium.make(env_id, ...)`` with a
    warning when the batch refuses the arguments (:class:`NotBatchable`): the vector
    environment's arguments (:data:`VECTOR_ARGUMENTS`) go to the ``SyncVectorEnv``, the others
    and the time limit (steps; None: none) to ``gymnasium.make``."""
    try:
        return cls(num_envs, max_episode_steps=max_episode_steps, **kwargs)
    except NotBatchable as why:
        gym.logger.warn(f"{env_id.split('/')[-1]} runs {num_envs} single environments in a "
                        f"SyncVectorEnv: {why}")
    vector = {key: value for key, value in kwargs.items() if key in VECTOR_ARGUMENTS}
    task = {key: value for key, value in kwargs.items() if key not in VECTOR_ARGUMENTS}
    limit = -1 if max_episode_steps is None else max_episode_steps  # -1: no TimeLimit

    def make() -> gym.Env:
        return gym.make(env_id, max_episode_steps=limit, **task)

    return gym.vector.SyncVectorEnv([make for _ in range(num_envs)], **vector)


def check_autoreset_mode(value: Any) -> AutoresetMode:
    """``value`` (an :class:`~gymnasium.vector.AutoresetMode` or its value, such as
    ``"SameStep"``) as the mode; ``ValueError`` naming the modes otherwise."""
    try:
        return AutoresetMode(value)
    except (ValueError, TypeError):
        raise ValueError(f"autoreset_mode must be one of {[m.value for m in AutoresetMode]}, "
                         f"got {value!r}") from None


def vector_seeds(seed: int | list[int | None] | tuple | None, n: int) -> list[int | None]:
    """Each of ``n`` environments' seed (a Python int, or None), as ``SyncVectorEnv.reset``
    reads ``seed``: ``seed + k`` for an int (numpy's too), a list's own (None: that
    environment's generator goes on), None for every environment with None."""
    if isinstance(seed, (list, tuple)):
        if len(seed) != n:
            raise ValueError(f"seed must be an int, None or a list of {n} seeds, got a "
                             f"list of {len(seed)}")
        for s in seed:
            check_seed(s)
        return [None if s is None else int(s) for s in seed]
    check_seed(seed)
    return [None if seed is None else int(seed) + k for k in range(n)]


def reset_mask(options: Any, n: int, who: str) -> np.ndarray | None:
    """The ``reset_mask`` of ``reset``'s ``options`` for ``n`` environments (a copy; None:
    reset every environment), checked as ``SyncVectorEnv`` checks it (``TypeError`` or
    ``ValueError``); any other option is refused as the task ``who`` refuses it."""
    options = check_options(options, ("reset_mask",), who, strict=False)
    mask = options.pop("reset_mask", None)
    check_options(options, (), who)
    if mask is None:
        return None
    if not isinstance(mask, np.ndarray):
        raise TypeError(f"`options['reset_mask']` must be a numpy array, got {type(mask)}")
    if mask.shape != (n,):
        raise ValueError(f"`options['reset_mask']` must have shape `({n},)`, got {mask.shape}")
    if mask.dtype != np.bool_:
        raise TypeError(f"`options['reset_mask']` must have `dtype=np.bool_`, got {mask.dtype}")
    if not mask.any():
        raise ValueError("`options['reset_mask']` must contain a boolean array with at least "
                         f"one True value, got reset_mask={mask}")
    return mask.copy()
