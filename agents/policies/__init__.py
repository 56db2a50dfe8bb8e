"""Policies that run with numpy alone, and the learner's view of an environment (numpy and
gymnasium only: nothing here imports stable-baselines3, torch or Ray).

* :mod:`agents.policies.base`: the policy protocol, :func:`reset_policy`,
  :class:`IdlePolicy`, :func:`describe_policy`;
* :mod:`agents.policies.numpy_policy`: :class:`NumpyPolicy` and
  :class:`NumpyRecurrentPolicy`, trained actors evaluated with numpy and saved as ``.npz``;
* :mod:`agents.policies.action_maps`: the learners' action maps (``native``, ``velocity``,
  ``target``, ``guard``, ``guard-residual``, ``ball-residual``, ``team-residual``);
* :mod:`agents.policies.wrappers`: the maps, frame stacks and the privileged critic's
  observation as Gymnasium wrappers (:func:`~agents.policies.wrappers.wrap_learner`);
* :mod:`agents.policies.files`: reading files from strangers safely (size limits,
  :class:`~agents.policies.files.UnsafeFileError`).

The names below are importable from ``agents.policies`` itself.
"""

from __future__ import annotations

from agents.policies.base import IdlePolicy, Policy, describe_policy, reset_policy
from agents.policies.numpy_policy import NumpyPolicy, NumpyRecurrentPolicy

__all__ = ["Policy", "reset_policy", "IdlePolicy", "describe_policy", "NumpyPolicy",
           "NumpyRecurrentPolicy"]
