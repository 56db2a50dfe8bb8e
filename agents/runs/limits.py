"""Limits on the settings a resumed run reads from its ``config.json``.

A run folder may come from a stranger, and ``train --resume`` takes every setting the
command line does not give from the run's ``config.json``. Some settings decide what the run
costs: ``checkpoint_every: 1`` writes a model file every step (a 2,048-step resume wrote
173 MB), an evaluation of a million shots or a replay buffer of a billion transitions
allocates what the file asks. So a setting read from the file, not given on the command
line, must lie within :data:`RUN_SETTING_LIMITS` (and the hyperparameters within
:data:`HYPERPARAMETER_LIMITS`); ``--trust`` lifts the limits for a file one trusts, and an
option given on the command line is the user's own choice and is never limited. The limits
are several times what the package's own runs use (its keepers and teams checkpoint every
50,000-250,000 steps, evaluate 200-1,000 shots, run 8-64 environments).
"""

from __future__ import annotations

import json
import math
from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

from agents.sb3.model_files import MAX_NETWORK_PARAMETERS

__all__ = ["RUN_SETTING_LIMITS", "HYPERPARAMETER_LIMITS", "MIN_SAVE_INTERVAL",
           "SETTING_OPTIONS", "check_saved_settings", "resume_options"]

#: The fewest environment steps between two checkpoints, evaluations or self-play copies a
#: run's ``config.json`` may ask for (0, never, is allowed where the setting allows it).
MIN_SAVE_INTERVAL = 10_000

#: Setting -> (least, most) allowed when read from a run's ``config.json``; ``None``: no
#: bound on that side. Interval settings also allow 0 (off) where their run allows it.
RUN_SETTING_LIMITS: dict[str, tuple[float | None, float | None]] = {
    "checkpoint_every": (MIN_SAVE_INTERVAL, None),
    "eval_every": (MIN_SAVE_INTERVAL, None),
    "self_play_every": (MIN_SAVE_INTERVAL, None),
    "eval_episodes": (None, 10_000),
    "n_envs": (None, 256),
    "n_workers": (None, 32),
    "num_env_runners": (None, 32),
    "torch_threads": (None, 64),
    "frame_stack": (None, 32),
    # Seconds: a tiny reply timeout fails the run at once, a huge one turns liveness off.
    "worker_timeout": (1, 600),
}

#: Hyperparameter -> most allowed when read from a run's ``config.json`` (stable-baselines3's
#: and RLlib's names). ``buffer_size`` is stable-baselines3's default for its off-policy
#: algorithms; the rollout and batch sizes are 8 times the package's defaults (2,048 steps x
#: 16 environments).
HYPERPARAMETER_LIMITS: dict[str, int] = {
    "n_steps": 2**18,
    "batch_size": 2**18,
    "buffer_size": 1_000_000,
    "learning_starts": 1_000_000,
    "n_epochs": 1_000,
    "gradient_steps": 1_000,
    "train_batch_size_per_learner": 2**18,
    "minibatch_size": 2**18,
    "num_epochs": 1_000,
    "num_learners": 32,
}

#: The command-line option of ``soccer-env train`` that sets each limited setting (those
#: without one are lifted by ``--trust`` only).
SETTING_OPTIONS = {"checkpoint_every": "--checkpoint-every", "eval_every": "--eval-every",
                   "eval_episodes": "--eval-episodes", "n_envs": "--n-envs",
                   "n_workers": "--workers", "num_env_runners": "--num-env-runners",
                   "frame_stack": "--frame-stack", "worker_timeout": "--worker-timeout"}

_OFF_ALLOWED = ("checkpoint_every", "eval_every")
_LIFT = "--trust (for a run you trust)"


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _is_real(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and \
        math.isfinite(value)


def _hidden_parameters(config: Path, hidden: Any) -> int:
    """The weights between the hidden layers of an RLlib ``fcnet_hiddens`` list (the input
    and output layers, which the spaces size, not counted)."""
    if not isinstance(hidden, list) or not all(_is_int(h) and h >= 0 for h in hidden):
        raise ValueError(f"{config}: model_config fcnet_hiddens must be a list of layer "
                         f"sizes (non-negative integers), got {hidden!r}")
    return sum((a + 1) * b for a, b in zip(hidden, hidden[1:]))


def _setting_beyond(name: str, value: Any) -> str | None:
    """Why ``value`` of setting ``name`` is beyond :data:`RUN_SETTING_LIMITS` (None if it is
    not, or is no finite number: the configuration's own check names the type it wants)."""
    low, high = RUN_SETTING_LIMITS[name]
    if not _is_real(value) or (name in _OFF_ALLOWED and value == 0):
        return None
    unit = " s" if name == "worker_timeout" else ""
    if low is not None and value < low:
        why = " (the steps between two saves)" if low == MIN_SAVE_INTERVAL else ""
        return (f"{name} {value:,}{unit} is below {low:,}{unit}, the least a run's config.json "
                f"may set{why}")
    if high is not None and value > high:
        return (f"{name} {value:,}{unit} is above {high:,}{unit}, the most a run's "
                "config.json may set")
    return None


def _hyperparameter_beyond(name: str, hyper: Mapping[str, Any], config: Path) -> str | None:
    """Why hyperparameter ``name`` of ``hyper`` is beyond :data:`HYPERPARAMETER_LIMITS` or,
    for ``model_config``, :data:`~agents.sb3.model_files.MAX_NETWORK_PARAMETERS` (None if
    it is not)."""
    value = hyper.get(name)
    if name == "model_config":
        if not isinstance(value, Mapping) or "fcnet_hiddens" not in value:
            return None
        count = _hidden_parameters(config, value["fcnet_hiddens"])
        if count <= MAX_NETWORK_PARAMETERS:
            return None
        return (f"hyperparameter model_config fcnet_hiddens {value['fcnet_hiddens']} has "
                f"{count:,} weights between its hidden layers, above the "
                f"{MAX_NETWORK_PARAMETERS:,} a run's config.json may ask for")
    high = HYPERPARAMETER_LIMITS[name]
    if not _is_int(value) or value <= high:
        return None
    return (f"hyperparameter {name} {value:,} is above {high:,}, the most a run's config.json "
            "may set")


def check_saved_settings(saved: Mapping[str, Any], config: Path, given: Collection[str] = (),
                         given_hyperparams: Collection[str] = (), trust: bool = False) -> None:
    """Refuse (``ValueError`` naming the file, the setting, the limit and what lifts it) a
    setting of the run configuration ``saved``, read from ``config`` and not given on the
    command line, beyond :data:`RUN_SETTING_LIMITS` or :data:`HYPERPARAMETER_LIMITS`.

    Args:
        saved: the configuration as read from the file.
        config: the file (named in the message).
        given: the configuration fields the command line sets (not limited).
        given_hyperparams: the hyperparameters the command line sets (``--hp``).
        trust: the file is trusted: nothing is limited.
    """
    if trust:
        return
    for name in RUN_SETTING_LIMITS:
        why = _setting_beyond(name, saved.get(name)) if name not in given else None
        if why:
            option = SETTING_OPTIONS.get(name)
            choose = (f"give {option} to choose it ({option} {saved[name]} keeps it), or "
                      if option else "lift it with ")
            raise ValueError(f"{config}: {why}; {choose}{_LIFT}")
    hyper = saved.get("hyperparams")
    if not isinstance(hyper, Mapping):
        return
    for name in (*HYPERPARAMETER_LIMITS, "model_config"):
        why = _hyperparameter_beyond(name, hyper, config) if name not in given_hyperparams \
            else None
        if why:
            raise ValueError(f"{config}: {why}; give --hp {name}=... to choose it, or {_LIFT}")


def resume_options(settings: Mapping[str, Any]) -> list[str]:
    """The command-line options that restate the settings of a run (its configuration as a
    dict) that are beyond the limits, so that the resume command a run prints for its own
    folder is not refused by :func:`check_saved_settings`: ``--checkpoint-every 512``,
    ``--hp n_steps=...``; ``--trust`` for a setting that has no option."""
    options: list[str] = []
    trust = False
    for name in RUN_SETTING_LIMITS:
        if _setting_beyond(name, settings.get(name)):
            option = SETTING_OPTIONS.get(name)
            if option:
                options += [option, str(settings[name])]
            else:
                trust = True
    hyper = settings.get("hyperparams")
    if isinstance(hyper, Mapping):
        for name in (*HYPERPARAMETER_LIMITS, "model_config"):
            if _hyperparameter_beyond(name, hyper, Path("config.json")):
                options += ["--hp", f"{name}={json.dumps(hyper[name], separators=(',', ':'))}"]
    return options + (["--trust"] if trust else [])
