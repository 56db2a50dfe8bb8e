"""The algorithms of stable-baselines3 (and sb3-contrib's RecurrentPPO) by name, their
classes and the hyperparameters a run starts from.

Importing this module imports neither stable-baselines3 nor torch: the names and defaults are
read by configurations and command lines that may run without the training extra;
:func:`algorithm_class` imports the library when asked for a class.
"""

from __future__ import annotations

import inspect
from typing import Any

__all__ = ["SB3_ALGORITHMS", "LOAD_ORDER", "algorithm_name", "algorithm_class", "is_recurrent",
           "is_sb3_model", "DEFAULT_HYPERPARAMS", "merged_hyperparams", "algorithm_parameters"]

#: Algorithms that :func:`~agents.sb3.model_files.load_model` opens and training runs
#: (canonical spellings, see :func:`algorithm_name`): stable-baselines3's, and sb3-contrib's
#: ``RecurrentPPO`` (PPO with an LSTM in front of the actor's and the critic's networks;
#: ``recurrent-ppo`` on the command line).
SB3_ALGORITHMS = ("PPO", "SAC", "TD3", "A2C", "DDPG", "RECURRENTPPO")

#: The order in which :func:`~agents.sb3.model_files.load_model` tries the algorithms on a file
#: of unknown algorithm: RecurrentPPO first, because PPO opens a RecurrentPPO file without
#: complaint (and then acts without its memory), while RecurrentPPO refuses the others' files.
LOAD_ORDER = ("RECURRENTPPO", "PPO", "SAC", "TD3", "A2C", "DDPG")


def algorithm_name(name: str) -> str:
    """The canonical spelling of an algorithm's name, one of :data:`SB3_ALGORITHMS`: case,
    ``-`` and ``_`` do not matter (``"ppo"``, ``"recurrent-ppo"``, ``"RecurrentPPO"``).
    Raises ``ValueError`` for any other name."""
    key = str(name).upper().replace("-", "").replace("_", "")
    if key not in SB3_ALGORITHMS:
        raise ValueError(f"algorithm must be one of {list(SB3_ALGORITHMS)} (or recurrent-ppo), "
                         f"got {name!r}")
    return key


def algorithm_class(name: str) -> type:
    """The class of algorithm ``name`` (see :func:`algorithm_name`): stable-baselines3's, or
    sb3-contrib's ``RecurrentPPO`` (``ImportError`` naming the package if it is missing)."""
    key = algorithm_name(name)
    if key == "RECURRENTPPO":
        try:
            from sb3_contrib import RecurrentPPO
        except ImportError as err:
            raise ImportError("RecurrentPPO needs sb3-contrib (pip install -e \".[train]\")"
                              ) from err
        return RecurrentPPO
    import stable_baselines3 as sb3

    return getattr(sb3, key)


def is_recurrent(model: Any) -> bool:
    """Whether a stable-baselines3 model's policy is recurrent (sb3-contrib's LSTM policies)."""
    return hasattr(getattr(model, "policy", None), "lstm_actor")


def is_sb3_model(obj: Any) -> bool:
    """Whether ``obj`` is a stable-baselines3 (or sb3-contrib) algorithm instance."""
    from stable_baselines3.common.base_class import BaseAlgorithm

    return isinstance(obj, BaseAlgorithm)


#: Per-algorithm defaults, tuned on Goalkeeper-v0 only as far as "learns in minutes". A
#: configuration's ``policy_kwargs`` are merged key by key over the defaults' ones.
#: RecurrentPPO's LSTM has 64 units (sb3-contrib's default, 256, trains 2.5 times slower on a
#: 2-core machine) and its minibatches are twice PPO's (its gradient steps run the LSTM over
#: whole sequences and dominate the training time).
_PPO_DEFAULTS: dict[str, Any] = {
    "n_steps": 256, "batch_size": 512, "n_epochs": 10, "gamma": 0.99, "gae_lambda": 0.95,
    "learning_rate": 3e-4, "ent_coef": 0.0, "clip_range": 0.2}
DEFAULT_HYPERPARAMS: dict[str, dict[str, Any]] = {
    "PPO": _PPO_DEFAULTS,
    "RECURRENTPPO": {**_PPO_DEFAULTS, "batch_size": 1024,
                     "policy_kwargs": {"lstm_hidden_size": 64}},
    "A2C": {},
    "SAC": {"learning_starts": 5000, "batch_size": 256, "train_freq": 1, "gradient_steps": 1},
    "TD3": {"learning_starts": 5000, "batch_size": 256, "train_freq": 1, "gradient_steps": 1},
    "DDPG": {"learning_starts": 5000, "batch_size": 256},
}


def merged_hyperparams(algorithm: str, given: dict[str, Any]) -> dict[str, Any]:
    """``given`` hyperparameters over :data:`DEFAULT_HYPERPARAMS` of ``algorithm`` (any
    spelling :func:`algorithm_name` takes), ``policy_kwargs`` merged key by key."""
    defaults = DEFAULT_HYPERPARAMS.get(algorithm_name(algorithm), {})
    merged = {**defaults, **given}
    if "policy_kwargs" in defaults and "policy_kwargs" in given:
        merged["policy_kwargs"] = {**defaults["policy_kwargs"], **given["policy_kwargs"]}
    return merged


def algorithm_parameters(name: str) -> set[str]:
    """The keyword arguments of algorithm ``name`` that a configuration may set."""
    sig = inspect.signature(algorithm_class(name).__init__)
    return {p for p in sig.parameters if p not in ("self", "policy", "env", "_init_setup_model",
                                                   "seed", "device", "tensorboard_log")}
