"""The environments of a stable-baselines3 training run: the training VecEnv
(:func:`make_vec_env`, behind ``VecNormalize`` in :func:`training_env`), the check that the
configuration's environments can be built before anything starts (:func:`check_env_kwargs`),
and the learner's action map as a numpy policy stores it (:func:`learner_action_map`).

Goalkeeper-v0 runs in :class:`~agents.vec.workers.WorkerVecEnv` (``n_envs`` environments over
``n_workers`` processes) or, with ``n_workers=0``, in-process. The match
(``soccer_env/Match-v0``) runs through :class:`~agents.vec.match.MatchVecEnv`: each learning
robot is a batch entry of one shared policy, against the ``opponent`` team; its ``n_envs``
matches are split over ``n_workers`` processes
(:class:`~agents.vec.match_workers.MatchWorkerVecEnv`, the same batches whatever the number of
workers) or, with ``n_workers=0``, stepped in-process. A worker that gives no reply within
``worker_timeout`` seconds fails the run as one that died. The vectorised environments (and
stable-baselines3) are imported when a VecEnv is made, not with this module.
"""

from __future__ import annotations

import os
from typing import Any

import gymnasium as gym

import soccer_env
from agents.common.checks import check_full_infos
from agents.policies.wrappers import wrap_actions
from agents.runs.training.config import TrainConfig
from agents.sb3.algorithms import merged_hyperparams
from agents.sb3.normalization import load_vecnormalize, vecnormalize_on
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID

__all__ = ["make_vec_env", "training_env", "check_env_kwargs", "learner_action_map"]


def make_vec_env(cfg: TrainConfig) -> Any:
    """The training VecEnv of ``cfg`` (seeded with ``cfg.seed``), without normalisation."""
    from agents.vec import factories

    if cfg.env_id == MATCH_ID:
        opponent = cfg.opponent
        return factories.make_match_vec_env(cfg.env_kwargs, cfg.n_envs, cfg.learner,
                                            "idle" if opponent == "self" else opponent,
                                            cfg.seed, workers=cfg.n_workers,
                                            batched=cfg.batched,
                                            reply_timeout=cfg.worker_timeout)
    if cfg.batched:
        from agents.vec.batched import BatchedVecEnv

        venv = BatchedVecEnv(cfg.n_envs, cfg.env_kwargs)
        venv.seed(cfg.seed)
        return venv
    fns = [factories.goalkeeper_env_fn(cfg.env_kwargs, cfg.actions, cfg.frame_stack, cfg.critic)
           for _ in range(cfg.n_envs)]
    if cfg.n_workers == 0:
        from stable_baselines3.common.vec_env import DummyVecEnv

        venv = DummyVecEnv(fns)
    else:
        from agents.vec.workers import WorkerVecEnv

        venv = WorkerVecEnv(fns, n_workers=cfg.n_workers, reply_timeout=cfg.worker_timeout)
    venv.seed(cfg.seed)
    return venv


def training_env(cfg: TrainConfig, resume: str | os.PathLike | None, trust: bool = False
                 ) -> tuple[Any, dict[str, Any]]:
    """The training VecEnv of ``cfg`` behind ``VecNormalize`` if asked (the statistics of
    the checkpoint ``resume`` where it has them: the ``.npz``, or with ``trust`` a
    stable-baselines3 ``.pkl``), and the algorithm's keyword arguments."""
    from stable_baselines3.common.vec_env import VecNormalize

    stats = None
    if resume is not None and (cfg.normalize_obs or cfg.normalize_reward):
        stats = load_vecnormalize(resume, trust)  # before any process starts
    venv = make_vec_env(cfg)
    params = merged_hyperparams(cfg.algorithm, cfg.hyperparams)
    if cfg.algorithm in ("PPO", "RECURRENTPPO"):
        # Keep one rollout at about n_steps * n_envs and a whole number of minibatches.
        params["batch_size"] = min(params["batch_size"], params["n_steps"] * venv.num_envs)
    if cfg.normalize_obs or cfg.normalize_reward:
        if isinstance(stats, VecNormalize):  # unpickled (trusted): as VecNormalize.load does
            stats.set_venv(venv)
            venv = stats
        elif stats is not None:
            try:
                venv = vecnormalize_on(stats, venv)
            except ValueError:
                venv.close()
                raise
        else:
            venv = VecNormalize(venv, norm_obs=cfg.normalize_obs,
                                norm_reward=cfg.normalize_reward,
                                gamma=params.get("gamma", 0.99))
    return venv, params


def check_env_kwargs(cfg: TrainConfig) -> None:
    """Build one environment of ``cfg`` (and its evaluation environment) here, so that bad
    keyword arguments fail before any process starts, with the environment's own message
    (``TypeError`` or ``ValueError``)."""
    check_full_infos(cfg.env_kwargs, "training")
    if cfg.eval_env_kwargs is not None:
        check_full_infos(cfg.eval_env_kwargs, "training's evaluation")
    if cfg.env_id == MATCH_ID:
        soccer_env.parallel_env(**cfg.env_kwargs).close()
        if cfg.batched:  # what the batch supports (SSL, the geometric detector, no rendering)
            from soccer_env.envs.batched_match import MatchBatch

            MatchBatch(1, **cfg.env_kwargs).close()
    else:
        gym.make(GOALKEEPER_ID, **cfg.env_kwargs).close()
        if cfg.batched:  # what the batch supports (no pixels detector, no rendering)
            from soccer_env.envs.batched import GoalkeeperVectorEnv

            GoalkeeperVectorEnv(1, **cfg.env_kwargs).close()
        if cfg.eval_env_kwargs is not None:
            gym.make(GOALKEEPER_ID, **cfg.eval_env_kwargs).close()


def learner_action_map(cfg: TrainConfig) -> dict[str, Any] | None:
    """The map from the learner's actions to the environment's, as a numpy policy stores it
    (``{"kind": ..., "params": {...}}``; None for native actions)."""
    if cfg.actions == "native":
        return None
    env = wrap_actions(gym.make(GOALKEEPER_ID, **cfg.env_kwargs), cfg.actions)
    params = getattr(env, "params", None)
    env.close()
    return {"kind": cfg.actions, "params": params or {}}
