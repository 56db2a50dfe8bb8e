"""Resolving a policy reference, a saved model or a training run's folder into a policy.

Policies are referred to by strings so that evaluation workers can rebuild them in their own
processes (see :func:`make_policy`):

* ``"scripted"``: :class:`~agents.ScriptedGoalkeeper`;
* ``"idle"``: a keeper that stands still (all-zero actions);
* ``"baseline:NAME"``: a policy shipped in the package (:data:`agents.baselines.BASELINES`);
* a path to a ``.npz`` written by :meth:`~agents.policies.numpy_policy.NumpyPolicy.save`;
* a path to a stable-baselines3 ``.zip`` (PPO, A2C, SAC, TD3, DDPG, sb3-contrib's
  RecurrentPPO; with the ``VecNormalize`` statistics saved beside it, see
  :func:`~agents.sb3.normalization.vecnormalize_path`, and the action map and frame stack
  recorded in its run's ``config.json``), or a training run's folder (its
  ``final_policy.npz``, else ``final_model.zip``).

A saved model is loaded in the spaces its training run's learner had: :func:`run_spaces`
rebuilds them from the run's ``config.json`` (environment, action map, frame stack, critic)
and :func:`load_sb3` hands them to the loader of :mod:`agents.sb3.model_files`. A
stable-baselines3 model is needed only for a ``.zip``; everything else runs with numpy alone.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agents.baselines import load_baseline
from agents.policies.base import IdlePolicy, Policy
from agents.policies.numpy_policy import NumpyPolicy
from agents.policies.wrappers import wrap_learner
from agents.runs.folders import run_config
from agents.sb3.algorithms import merged_hyperparams
from agents.sb3.model_files import load_model, model_data
from agents.sb3.normalization import load_vecnormalize
from agents.sb3.policies import SB3Policy, numpy_copy
from soccer_env.envs.keeper import ScriptedGoalkeeper
from soccer_env.envs.registration import MATCH_ID

__all__ = ["POLICY_NAMES", "make_policy", "load_sb3", "run_spaces", "run_hyperparams",
           "learner_spaces", "saved_model", "policy_for_jobs"]

#: Policy names that :func:`make_policy` resolves without a file.
POLICY_NAMES = ("scripted", "idle")


def make_policy(ref: str | os.PathLike | Callable, env: Any, trust: bool = False) -> Policy:
    """Resolve a policy reference (see the module docstring) for the environment ``env``
    (a Goalkeeper-v0, possibly wrapped). A callable is returned as it is. Policies with
    memory need :func:`reset_policy` at each episode start.

    Nothing in a file is unpickled unless ``trust`` (see :mod:`agents.sb3.model_files`): a
    ``.npz`` is arrays and JSON; a ``.zip`` is loaded by :func:`load_sb3` in the spaces of
    ``env`` as its run's ``config.json`` describes the learner, with the ``.npz``
    normalisation statistics beside it."""
    if callable(ref) and not isinstance(ref, (str, os.PathLike)):
        return ref
    ref = os.fspath(ref)
    if ref == "scripted":
        return ScriptedGoalkeeper.for_env(env)
    if ref == "idle":
        return IdlePolicy(int(np.prod(env.action_space.shape)))
    if ref.startswith("baseline:"):
        return load_baseline(ref.split(":", 1)[1])
    path = Path(ref)
    if path.is_dir():  # a training run: its numpy policy, else its model
        path = path / ("final_policy.npz" if (path / "final_policy.npz").exists()
                       else "final_model.zip")
    if path.suffix == ".npz":
        policy: Any = NumpyPolicy.load(path)
    elif path.suffix == ".zip":
        run = run_config(path)
        obs_space, act_space = learner_spaces(env, run)
        model = load_sb3(path, trust=trust, observation_space=obs_space,
                         action_space=act_space)
        norm = load_vecnormalize(path, trust)
        action_map = run.get("action_map")
        frame_stack = int(run.get("frame_stack", 1))
        try:
            policy = numpy_copy(model, vec_normalize=norm, action_map=action_map,
                                frame_stack=frame_stack)
        except ValueError:
            if norm is not None or action_map is not None or frame_stack > 1:
                raise ValueError(f"{path} was trained behind VecNormalize, an action map or a "
                                 "frame stack and its network cannot be copied into numpy; "
                                 "load it with load_sb3, "
                                 "agents.sb3.normalization.vecnormalize_on and "
                                 "agents.policies.wrappers") from None
            policy = SB3Policy(model)
    else:
        raise ValueError(f"policy must be one of {list(POLICY_NAMES)}, 'baseline:NAME', a "
                         f".npz or .zip file or a training run folder, got {ref!r}")
    size = getattr(policy, "obs_size", None)
    expected = env.observation_space.shape[0]
    if size is not None and size != expected:
        raise ValueError(f"policy {ref!r} takes observations of size {size}, the environment "
                         f"gives {expected}")
    return policy


def load_sb3(path: str | os.PathLike, algorithm: str | None = None, *, trust: bool = False,
             observation_space: Any = None, action_space: Any = None, policy_class: Any = None,
             hyperparams: dict[str, Any] | None = None, **kwargs: Any) -> Any:
    """Load a stable-baselines3 (or sb3-contrib RecurrentPPO) model, with what is not given
    taken from the training run it belongs to (:func:`~agents.sb3.model_files.load_model`
    loads it).

    By default nothing in the file is unpickled: the spaces are ``observation_space`` and
    ``action_space``, else those of ``kwargs["env"]``, else those of the training run whose
    ``config.json`` lies beside the file (or above ``checkpoints/``, :func:`run_spaces`); the
    policy class is ``policy_class``, else the run's (a privileged critic's), else the
    algorithm's ``MlpPolicy``; schedules come from ``hyperparams``, else the run's, else the
    defaults. With ``trust=True`` the file is loaded as stable-baselines3 loads it, unpickling
    its serialized entries: only for files from a source you trust.

    ``algorithm`` (one of :data:`~agents.sb3.algorithms.SB3_ALGORITHMS`, any spelling
    :func:`~agents.sb3.algorithms.algorithm_name` takes) is read from the run's
    ``config.json`` when not given, otherwise each is tried in turn (RecurrentPPO only where
    sb3-contrib is installed). Raises ``FileNotFoundError``,
    :class:`~agents.policies.files.UnsafeFileError` (the file needs unpickling, or is over the
    size limits) or ``ValueError`` (not a model of any algorithm, or not one acting in the
    given spaces)."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"no model at {path}")
    run = run_config(path)
    if algorithm is None:
        algorithm = run.get("algorithm")
    if not trust:
        model_data(path)  # size limits and format, before the run's environments are built
        env = kwargs.get("env")
        if observation_space is None and env is not None:
            observation_space, action_space = env.observation_space, env.action_space
        if observation_space is None and run:
            observation_space, action_space = run_spaces(run)
        if policy_class is None and run.get("critic") == "privileged":
            from agents.sb3.privileged import PrivilegedActorCriticPolicy

            policy_class = PrivilegedActorCriticPolicy
        if hyperparams is None:
            hyperparams = run_hyperparams(run)
    return load_model(path, algorithm, trust=trust, observation_space=observation_space,
                      action_space=action_space, policy_class=policy_class,
                      hyperparams=hyperparams, **kwargs)


def run_spaces(run: dict[str, Any]) -> tuple[Any, Any]:
    """The observation and action spaces a training run's learner had (from its
    ``config.json``: environment, action map, frame stack, critic)."""
    from agents.vec.factories import goalkeeper_env_fn
    from agents.vec.match import MatchVecEnv

    env_kwargs = dict(run.get("env_kwargs") or {})
    if run.get("env_id") == MATCH_ID:
        venv = MatchVecEnv(env_kwargs, 1, run.get("learner", "blue"),
                           None if run.get("learner") == "both" else "idle")
    else:
        venv = goalkeeper_env_fn(env_kwargs, run.get("actions", "native"),
                                 int(run.get("frame_stack", 1)), run.get("critic", "shared"))()
    try:
        return venv.observation_space, venv.action_space
    finally:
        venv.close()


def run_hyperparams(run: dict[str, Any]) -> dict[str, Any]:
    """A training run's hyperparameters over the algorithm's defaults (``config.json``)."""
    given = dict(run.get("hyperparams") or {})
    algorithm = run.get("algorithm")
    return merged_hyperparams(algorithm, given) if algorithm else given


def learner_spaces(env: Any, run: dict[str, Any]) -> tuple[Any, Any]:
    """The spaces of the learner of training run ``run`` (its ``config.json``) acting in
    ``env`` (a Goalkeeper-v0): ``env``'s, behind the run's action map, frame stack and
    critic."""
    action_map = run.get("action_map")
    learner = wrap_learner(env, action_map["kind"] if action_map else "native",
                           int(run.get("frame_stack", 1)), run.get("critic", "shared"))
    return learner.observation_space, learner.action_space


def saved_model(ref: Any) -> bool:
    """Whether the policy reference ``ref`` names a saved stable-baselines3 model (a ``.zip``
    or a training run's folder): what is worth loading once, in the parent process, rather
    than in every worker."""
    return isinstance(ref, (str, os.PathLike)) and (
        os.fspath(ref).endswith(".zip") or Path(ref).is_dir())


def policy_for_jobs(policy: Any, env_id: str, env_kwargs: Mapping[str, Any],
                    trust: bool = False) -> Any:
    """Resolve ``policy`` once here (:func:`make_policy` on an environment ``env_id`` made
    with ``env_kwargs``), so that a bad reference fails before any work starts. Returns what
    jobs in worker processes get: the reference itself, or for a saved model
    (:func:`saved_model`) the loaded policy (its numpy copy pickles cheaply, where loading the
    model in every job would import torch in every worker)."""
    env = gym.make(env_id, **env_kwargs)
    try:
        resolved = make_policy(policy, env, trust=trust)
    finally:
        env.close()
    return resolved if saved_model(policy) else policy
