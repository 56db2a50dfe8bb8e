"""Train policies with stable-baselines3 (``soccer-env train``).

A run is described by a :class:`~agents.runs.training.config.TrainConfig` and
:func:`~agents.runs.training.loop.train` writes into its folder:

* ``config.json``: the full configuration, the learner's action map (see
  :mod:`agents.policies.action_maps`), the command line and library versions;
* ``checkpoints/model_<steps>_steps.zip`` every ``checkpoint_every`` steps (resume from any);
* ``tb/``: TensorBoard logs (SB3's training statistics, episode returns and success rate,
  the periodic save-rate evaluation, and the rollout collection rate);
* ``evaluations.json``: the periodic evaluations; ``best_model.zip`` / ``best_policy.npz``: the
  best of them;
* ``final_model.zip`` and ``final_policy.npz`` (the numpy copy of the actor, see
  :class:`~agents.policies.numpy_policy.NumpyPolicy`), the ``VecNormalize`` statistics beside
  every model (``*_vecnormalize.npz``: arrays and JSON, no pickle, see
  :mod:`agents.sb3.normalization`), and
  ``summary.json`` (steps, wall time, rollout and overall steps per second, last and best
  evaluation).

``resume`` continues from a checkpoint with this configuration's environment and
hyperparameters (the network is the checkpoint's): the same run, or a fine-tuning, e.g. a
keeper trained on true observations continued on perceived ones. ``total_steps`` counts the
checkpoint's steps too: a resumed run trains ``total_steps`` minus the checkpoint's steps, and
one with nothing left to train is refused.

Memory, for observations that a single frame does not explain (perceived ones, with their
latency, noise and missed detections): ``algorithm="RECURRENTPPO"`` trains sb3-contrib's
RecurrentPPO (an LSTM in front of the actor's and the critic's networks; exported as a
:class:`~agents.policies.numpy_policy.NumpyRecurrentPolicy`), and ``frame_stack=N`` shows a
feed-forward learner its last ``N`` observations at once
(:func:`~agents.policies.wrappers.stack_frames`; the exported
:class:`~agents.policies.numpy_policy.NumpyPolicy` keeps the history itself). Both policies act on
the plain environment and need ``reset()`` at each episode start, which the evaluation does.

The package's modules, each with one job:

* :mod:`~agents.runs.training.config`: :class:`~agents.runs.training.config.TrainConfig`;
* :mod:`~agents.runs.training.environments`: the training VecEnv (the keeper in worker
  processes, the match through :mod:`agents.vec`), its normalisation, the early checks;
* :mod:`~agents.runs.training.callbacks`: the periodic evaluation, checkpoints, self-play;
* :mod:`~agents.runs.training.loop`: :func:`~agents.runs.training.loop.train`.

The names below are importable from ``agents.runs.training`` itself; importing it imports
neither stable-baselines3 nor torch (a run does).
"""

from __future__ import annotations

from agents.runs.training.config import CRITICS, EVAL_SEED_START, OPPONENTS, TrainConfig
from agents.runs.training.environments import check_env_kwargs, make_vec_env
from agents.runs.training.loop import checkpoint_steps, train

__all__ = ["TrainConfig", "train", "check_env_kwargs", "make_vec_env", "checkpoint_steps",
           "CRITICS", "OPPONENTS", "EVAL_SEED_START"]
