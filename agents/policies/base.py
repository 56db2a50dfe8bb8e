"""The policy protocol: one observation in, one action out, and what runs policies needs
of them.

A policy maps one observation (a float32 vector) to one action; the numpy networks
(:class:`~agents.policies.numpy_policy.NumpyPolicy`) and :class:`IdlePolicy` also take a
batch ``(n, obs_dim) -> (n, act_dim)``. Policies with memory (a frame stack, an LSTM) act on
one episode at a time: whoever runs episodes calls :func:`reset_policy` at each episode start
(it calls the policy's ``reset()``, where there is one), as
:func:`~agents.runs.evaluation.evaluate` and :func:`~agents.runs.evaluation.record_video` do.
Policies are referred to by strings so that worker processes can rebuild them
(:func:`agents.runs.resolve.make_policy` resolves them); :func:`describe_policy` names a
reference in tables.
"""

from __future__ import annotations

import os
from typing import Any, Protocol

import numpy as np

__all__ = ["Policy", "reset_policy", "IdlePolicy", "describe_policy"]


class Policy(Protocol):
    """One observation in, one action out. A policy with memory also has ``reset()``, to be
    called at each episode start (see :func:`reset_policy`)."""

    def __call__(self, obs: np.ndarray) -> np.ndarray: ...


def reset_policy(policy: Any) -> None:
    """Start a new episode for ``policy``: call its ``reset()`` if it has one (policies with
    memory: a frame stack, an LSTM); stateless policies need nothing."""
    reset = getattr(policy, "reset", None)
    if callable(reset):
        reset()


class IdlePolicy:
    """All-zero actions: a robot that stands still and never kicks. Takes one observation or
    a batch ``(n, obs_dim)``."""

    def __init__(self, action_size: int) -> None:
        self.action_size = int(action_size)

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        obs = np.asarray(obs)
        shape = (len(obs), self.action_size) if obs.ndim == 2 else (self.action_size,)
        return np.zeros(shape, dtype=np.float32)


def describe_policy(policy: Any) -> str:
    """A policy reference as text for tables: the path or name given, else the callable's
    name."""
    if isinstance(policy, (str, os.PathLike)):
        return os.fspath(policy)
    return getattr(policy, "__name__", type(policy).__name__)
