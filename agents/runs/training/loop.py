"""The training loop of a stable-baselines3 run (``soccer-env train``): :func:`train` builds
the environments and the model (new, or a checkpoint to continue), writes the run folder,
learns, and saves the final model, its statistics and its numpy copy; an interrupted run
saves the model of its last completed update (:class:`~agents.runs.folders.TrainingStopped`).

stable-baselines3 and torch are imported when a run starts, not with this module.
"""

from __future__ import annotations

import json
import os
import platform
import shlex
import shutil
import time
from pathlib import Path
from typing import Any

import numpy as np

from agents.policies.files import UnsafeFileError
from agents.runs.folders import (
    RunRefused,
    TrainingStopped,
    check_steps_left,
    occupied_run_files,
)
from agents.runs.limits import resume_options
from agents.runs.resolve import load_sb3
from agents.runs.training.config import TrainConfig
from agents.runs.training.environments import check_env_kwargs, learner_action_map, training_env
from agents.sb3.algorithms import algorithm_class
from agents.sb3.model_files import model_data
from agents.sb3.normalization import save_vecnormalize, vecnormalize_path
from agents.sb3.policies import numpy_copy

__all__ = ["train", "checkpoint_steps"]


def train(cfg: TrainConfig, resume: str | os.PathLike | None = None,
          command: list[str] | None = None, overwrite: bool = False,
          trust: bool = False) -> dict[str, Any]:
    """Train as ``cfg`` says (continuing from the checkpoint ``resume`` if given) and write the
    run folder ``cfg.out``. Returns the summary.

    Nothing is written until the configuration, the environments and the algorithm with its
    hyperparameters have been built; before that :class:`~agents.runs.folders.RunRefused` is
    raised when ``resume`` has already trained ``cfg.total_steps`` steps or more
    (``total_steps`` includes its steps), when ``cfg.out`` holds another run
    (:func:`~agents.runs.folders.run_files`) and ``overwrite`` is false (with ``overwrite``
    its run files are deleted first; continuing a run in its own folder, ``resume`` inside
    ``cfg.out``, needs no ``overwrite``), or when the algorithm refuses the hyperparameters.

    A checkpoint is loaded without unpickling anything (see :mod:`agents.sb3.model_files`),
    with the ``.npz`` normalisation statistics beside it; ``trust=True`` loads a
    stable-baselines3 file as stable-baselines3 does (its pickled entries, a ``.pkl`` of
    statistics): only for files from a source you trust.

    Ctrl-C, or a rollout worker that dies, stops answering or whose environment raises, ends
    training with :class:`~agents.runs.folders.TrainingStopped` after saving the model of the last
    completed update in ``cfg.out/checkpoints/`` (its message has the ``--resume``
    command)."""
    import torch

    from agents.runs.training.callbacks import training_callbacks
    from agents.sb3.callbacks import last_update as last_update_callback
    from agents.vec.workers import WorkerError

    out = Path(cfg.out)
    existing = _refuse(cfg, out, resume, overwrite)
    check_env_kwargs(cfg)
    torch.set_num_threads(cfg.torch_threads)
    action_map = learner_action_map(cfg)
    venv, model, done_steps = _build(cfg, resume, out, trust)
    _start_folder(cfg, out, existing, action_map, command, resume)
    callbacks, timer, evaluator = training_callbacks(cfg, out, action_map)
    last_update = last_update_callback()
    remaining = max(0, cfg.total_steps - done_steps)
    t0 = time.perf_counter()
    try:
        model.learn(remaining, callback=[*callbacks, last_update],
                    progress_bar=cfg.progress_bar, reset_num_timesteps=resume is None,
                    tb_log_name=cfg.algorithm)
    except BaseException as err:
        if not isinstance(err, (KeyboardInterrupt, WorkerError)):
            raise
        stopped = _stop(cfg, model, out, last_update, done_steps, err)
        raise stopped from err
    finally:
        venv.close()
    seconds = time.perf_counter() - t0
    final_eval = _save_final(cfg, model, out, evaluator, action_map)
    summary = {
        "steps": int(model.num_timesteps), "trained_steps": remaining,
        "seconds": seconds, "steps_per_s": remaining / seconds if seconds > 0 else None,
        "rollout_steps_per_s": timer.rate,
        "last_evaluation": final_eval,
        "best_evaluation": max(evaluator.history, key=lambda e: e["save_rate"])
        if evaluator and evaluator.history else None,
        "files": sorted(p.name for p in out.iterdir()),
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def _refuse(cfg: TrainConfig, out: Path, resume: str | os.PathLike | None,
            overwrite: bool) -> list[str]:
    """Raise :class:`~agents.runs.folders.RunRefused` when ``out`` holds another run and
    ``overwrite`` is false, or when ``resume`` leaves nothing to train; return the run files
    in ``out`` that the run replaces (none when it continues its own run)."""
    existing = occupied_run_files(out, resume, overwrite)
    if resume is not None:
        check_steps_left(cfg.total_steps, checkpoint_steps(resume), resume)
    return existing


def _build(cfg: TrainConfig, resume: str | os.PathLike | None, out: Path, trust: bool
           ) -> tuple[Any, Any, int]:
    """The training VecEnv, the model on it (new, or the checkpoint ``resume``) and the steps
    it has trained; :class:`~agents.runs.folders.RunRefused` for statistics or a checkpoint
    that cannot be read safely or do not fit, and for hyperparameters the algorithm
    refuses."""
    try:
        venv, params = training_env(cfg, resume, trust)
    except ValueError as err:  # statistics that cannot be read safely, or do not fit
        raise RunRefused(f"resume: {err}") from None
    try:
        model, done_steps = _model(cfg, venv, params, resume, out, trust)
    except Exception as err:
        venv.close()
        if resume is not None:
            raise RunRefused(f"resume: {err}") from None
        raise RunRefused(f"{cfg.algorithm} could not be built with hyperparameters "
                         f"{params}: {type(err).__name__}: {err}") from err
    return venv, model, done_steps


def _start_folder(cfg: TrainConfig, out: Path, existing: list[str],
                  action_map: dict[str, Any] | None, command: list[str] | None,
                  resume: str | os.PathLike | None) -> None:
    """Delete the ``existing`` run files of ``out`` (an overwrite: this run's files only,
    nothing else in the folder) and write the run's ``config.json``."""
    for name in existing:
        path = out / name
        if path.is_dir():
            shutil.rmtree(path)
        else:
            path.unlink()
    out.mkdir(parents=True, exist_ok=True)
    (out / "config.json").write_text(json.dumps({
        **cfg.to_dict(), "action_map": action_map, "command": command,
        "resumed_from": None if resume is None else os.fspath(resume),
        "versions": _versions()}, indent=2))


def _stop(cfg: TrainConfig, model: Any, out: Path, last_update: Any, done_steps: int,
          err: BaseException) -> TrainingStopped:
    """Save the model of the last completed update as a checkpoint of the run (where
    ``--resume`` finds it) and describe how the run ended and how to continue it."""
    reason = "interrupted" if isinstance(err, KeyboardInterrupt) else "worker failed"
    what = "interrupted" if reason == "interrupted" else f"stopped: {err}"
    steps = last_update.restore()
    if steps is None or steps <= done_steps:
        return TrainingStopped(f"training {what}\nnothing trained since the start, so no "
                               "checkpoint was saved", reason, None, done_steps, None)
    folder = out / "checkpoints"
    folder.mkdir(parents=True, exist_ok=True)
    checkpoint = folder / f"model_{steps}_steps.zip"
    model.save(checkpoint)
    norm = model.get_vec_normalize_env()
    if norm is not None:
        save_vecnormalize(norm, vecnormalize_path(checkpoint))
    command = shlex.join(["soccer-env", "train", "--resume", str(checkpoint), "--steps",
                          str(cfg.total_steps), *resume_options(cfg.to_dict())])
    return TrainingStopped(f"training {what}\nsaved the model of the last completed update "
                           f"({steps:,} steps) to {checkpoint}\ncontinue with: {command}",
                           reason, checkpoint, steps, command)


def _model(cfg: TrainConfig, venv: Any, params: dict[str, Any],
           resume: str | os.PathLike | None, out: Path, trust: bool = False
           ) -> tuple[Any, int]:
    """A new model of ``cfg.algorithm`` on ``venv``, or the checkpoint ``resume`` loaded onto
    it; and the steps it has already trained."""
    algo = algorithm_class(cfg.algorithm)
    policy: Any = "MlpLstmPolicy" if cfg.algorithm == "RECURRENTPPO" else "MlpPolicy"
    if cfg.critic == "privileged":
        from agents.sb3.privileged import PrivilegedActorCriticPolicy

        policy = PrivilegedActorCriticPolicy
    if resume is not None:
        # The hyperparameters of this configuration replace the saved ones (so that a run
        # can be fine-tuned, e.g. with another entropy bonus or learning rate); the network
        # (policy_kwargs) is the saved model's. Nothing is unpickled unless trusted: the
        # spaces are the training environment's, the schedules this configuration's.
        saved_kwargs = params.pop("policy_kwargs", None)
        model = load_sb3(resume, cfg.algorithm, trust=trust,
                         observation_space=venv.observation_space,
                         action_space=venv.action_space,
                         policy_class=None if isinstance(policy, str) else policy,
                         hyperparams={**params, "policy_kwargs": saved_kwargs},
                         env=venv, device=cfg.device, tensorboard_log=str(out / "tb"),
                         **params)
        return model, int(model.num_timesteps)
    model = algo(policy, venv, seed=cfg.seed, device=cfg.device,
                 tensorboard_log=str(out / "tb"), verbose=0, **params)
    return model, 0


def _save_final(cfg: TrainConfig, model: Any, out: Path, evaluator: Any,
                action_map: dict[str, Any] | None) -> dict[str, Any] | None:
    """Save the final model, its ``VecNormalize`` statistics and its numpy copy; evaluate it
    unless the last periodic evaluation was at its step count. Returns the final
    evaluation (None without periodic evaluations)."""
    model.save(out / "final_model.zip")
    norm = model.get_vec_normalize_env()
    if norm is not None:
        save_vecnormalize(norm, out / "final_vecnormalize.npz")
    final_eval = None
    if evaluator is not None:
        if not evaluator.history or evaluator.history[-1]["steps"] != model.num_timesteps:
            evaluator.run()
        final_eval = evaluator.history[-1]
    try:
        policy = numpy_copy(model, cfg.policy_meta(final_eval), norm, action_map,
                            cfg.frame_stack)
        policy.save(out / "final_policy.npz")
    except ValueError:  # a network numpy cannot copy: the .zip is the model
        pass
    return final_eval


def checkpoint_steps(path: str | os.PathLike) -> int:
    """The environment steps a saved stable-baselines3 model has trained (its
    ``num_timesteps``), read from the JSON part of the ``.zip`` without loading (unpickling)
    anything, within the size budget of :func:`~agents.sb3.model_files.model_data`. Raises
    ``ValueError`` for a file that is not such a model,
    :class:`~agents.policies.files.UnsafeFileError` for one too large to read."""
    try:
        return int(model_data(Path(path))["num_timesteps"])
    except UnsafeFileError:
        raise
    except (KeyError, ValueError, TypeError) as err:
        raise ValueError(f"{os.fspath(path)} is not a stable-baselines3 model file with its "
                         f"trained steps ({err})") from None


def _versions() -> dict[str, str]:
    import gymnasium
    import stable_baselines3
    import torch

    versions = {"python": platform.python_version(),
                "stable_baselines3": stable_baselines3.__version__, "torch": torch.__version__,
                "gymnasium": gymnasium.__version__, "numpy": np.__version__}
    try:
        import sb3_contrib
    except ImportError:
        return versions
    return {**versions, "sb3_contrib": sb3_contrib.__version__}
