"""Run folders: what a training run writes into its folder (:data:`RUN_FILES`), finding the
run a saved model belongs to (:func:`run_folder`, :func:`run_config`), and how a run is
refused or stopped (:class:`RunRefused`, :class:`TrainingStopped`). Both training backends
(stable-baselines3, :mod:`agents.runs.training`; RLlib, :mod:`agents.runs.rllib_runs`) share
them."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from agents.policies.files import read_json

__all__ = ["RUN_FILES", "run_files", "run_folder", "run_config", "read_run_config",
           "occupied_run_files",
           "check_steps_left", "RunRefused",
           "TrainingStopped"]

#: What a training run writes into its folder: a folder holding any of these holds a run,
#: which :func:`~agents.runs.training.loop.train` does not overwrite unless told to (and then
#: deletes these, and only these, first).
RUN_FILES = ("config.json", "summary.json", "evaluations.json", "final_model.zip",
             "final_policy.npz", "final_vecnormalize.npz", "best_model.zip", "best_policy.npz",
             "best_vecnormalize.npz", "checkpoints", "tb",
             # written by the RLlib backend (agents.runs.rllib_runs):
             "results.jsonl", "final_checkpoint",
             # written by earlier versions:
             "final_vecnormalize.pkl", "best_vecnormalize.pkl")


class RunRefused(ValueError):
    """:func:`~agents.runs.training.loop.train` (or the RLlib backend's) refused the run before
    writing anything: its folder holds another run, it has nothing to train, or the algorithm
    refused the hyperparameters."""


class TrainingStopped(RuntimeError):
    """Training ended early: interrupted (Ctrl-C) or a rollout worker failed. The model of
    the last completed update is saved as a checkpoint to resume from.

    Attributes:
        reason: ``"interrupted"`` or ``"worker failed"``.
        checkpoint: the saved checkpoint (None when nothing had been trained yet).
        steps: the environment steps that checkpoint has trained.
        resume_command: the command line that continues the run.
    """

    def __init__(self, message: str, reason: str, checkpoint: Path | None, steps: int,
                 resume_command: str | None) -> None:
        super().__init__(message)
        self.reason = reason
        self.checkpoint = checkpoint
        self.steps = steps
        self.resume_command = resume_command


def run_folder(checkpoint: str | os.PathLike) -> Path:
    """The run folder a saved model belongs to: its folder, or the one above for a model in
    ``checkpoints/``."""
    path = Path(checkpoint)
    return path.parent.parent if path.parent.name == "checkpoints" else path.parent


def run_files(folder: str | os.PathLike) -> list[str]:
    """The names of :data:`RUN_FILES` present in ``folder`` (empty: it holds no run)."""
    folder = Path(folder)
    return [name for name in RUN_FILES if (folder / name).exists()]


def occupied_run_files(out: str | os.PathLike, resume: str | os.PathLike | None,
                       overwrite: bool) -> list[str]:
    """The run files of ``out`` that a new run would replace: none when ``resume`` continues
    the run in ``out``; :class:`RunRefused` when there are some and ``overwrite`` is false."""
    out = Path(out)
    continuing = resume is not None and run_folder(resume).resolve() == out.resolve()
    existing = [] if continuing else run_files(out)
    if existing and not overwrite:
        raise RunRefused(f"out {os.fspath(out)} already holds a training run "
                         f"({', '.join(existing)}); choose another folder, or overwrite "
                         "it (--force; its run files are deleted first)")
    return existing


def check_steps_left(total_steps: int, done: int, resume: str | os.PathLike) -> None:
    """:class:`RunRefused` when the checkpoint ``resume`` has trained ``done`` steps of
    ``total_steps`` (which count them) or more: nothing is left to train."""
    if total_steps <= done:
        raise RunRefused(f"total_steps {total_steps:,} leaves nothing to train: the "
                         f"checkpoint {os.fspath(resume)} has trained {done:,} steps and "
                         "total_steps counts them too")


def run_config(model_path: Path) -> dict[str, Any]:
    """The ``config.json`` of the training run that saved ``model_path`` (the model's folder
    or, for checkpoints, its parent); empty if there is none. Raises ``ValueError`` for one
    that is not a JSON object, not a regular file or beyond the JSON budgets
    (:func:`~agents.policies.files.read_json`)."""
    for folder in (model_path.parent, model_path.parent.parent):
        config = folder / "config.json"
        if config.exists() or config.is_symlink():  # a device or a dangling link: refused
            return read_run_config(config)
    return {}


def read_run_config(config: Path) -> dict[str, Any]:
    """A run's ``config.json`` at ``config``, read within the JSON budgets
    (:func:`~agents.policies.files.read_json`); ``ValueError`` for one that is not a JSON
    object, ``FileNotFoundError`` if there is none."""
    data = read_json(config)
    if not isinstance(data, dict):
        raise ValueError(f"{config} is not a training run's configuration")
    return data
