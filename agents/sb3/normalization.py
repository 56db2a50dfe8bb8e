"""Normalisation statistics (stable-baselines3's ``VecNormalize``) written and read without
pickle, and found beside the models they belong to.

stable-baselines3 saves a ``VecNormalize`` with ``pickle`` (``*_vecnormalize.pkl``), which runs
code when loaded. Here the statistics are written as ``*_vecnormalize.npz`` (arrays and a
JSON header, :func:`save_vecnormalize`) and read back as plain arrays
(:func:`read_vecnormalize`), into a :class:`NormalizationStats` or onto a fresh
``VecNormalize`` (:func:`vecnormalize_on`); :func:`vecnormalize_path` says where a training
run keeps them beside a model and :func:`load_vecnormalize` finds them (the ``.pkl`` only when
trusted). Importing this module imports neither stable-baselines3 nor torch.
"""

from __future__ import annotations

import json
import math
import os
import pickle
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from agents.policies.files import (
    TRUST_HELP,
    UnsafeFileError,
    check_file_size,
    check_npz,
    parse_json,
)

__all__ = ["NormalizationStats", "save_vecnormalize", "read_vecnormalize", "vecnormalize_on",
           "vecnormalize_path", "load_vecnormalize"]


@dataclass
class _RunningStats:
    """A running mean and variance (the attributes of stable-baselines3's
    ``RunningMeanStd``)."""

    mean: np.ndarray
    var: np.ndarray
    count: float


@dataclass
class NormalizationStats:
    """A ``VecNormalize``'s statistics and settings without its environments, with the
    attribute names of ``VecNormalize`` (so that code reading one reads the other).

    Attributes:
        norm_obs, norm_reward: whether observations / rewards are normalised.
        obs_rms: the observations' running statistics (a dict of them per key for ``Dict``
            observations), None when not normalised.
        ret_rms: the discounted returns' running statistics.
        clip_obs, clip_reward: the clipping of normalised values.
        gamma, epsilon: the return discount and the variance floor.
        norm_obs_keys: the normalised keys of ``Dict`` observations (None: a ``Box``).
    """

    norm_obs: bool
    norm_reward: bool
    obs_rms: Any
    ret_rms: _RunningStats
    clip_obs: float
    clip_reward: float
    gamma: float
    epsilon: float
    norm_obs_keys: list[str] | None = None

    def normalize_obs(self, obs: np.ndarray) -> np.ndarray:
        """``obs`` (a ``Box`` observation or a batch of them) normalised as ``VecNormalize``
        does: ``clip((obs - mean) / sqrt(var + epsilon), -clip_obs, clip_obs)``."""
        if not self.norm_obs:
            return obs
        if isinstance(self.obs_rms, dict):
            raise TypeError("normalize_obs takes Box observations; these statistics are per "
                            "key of a Dict observation")
        rms = self.obs_rms
        return np.clip((obs - rms.mean) / np.sqrt(rms.var + self.epsilon), -self.clip_obs,
                       self.clip_obs)


def _stats_arrays(rms: Any, prefix: str, arrays: dict[str, np.ndarray]) -> dict[str, float]:
    arrays[f"{prefix}mean"] = np.asarray(rms.mean, dtype=np.float64)
    arrays[f"{prefix}var"] = np.asarray(rms.var, dtype=np.float64)
    return {"count": float(rms.count)}


def save_vecnormalize(norm: Any, path: str | os.PathLike) -> Path:
    """Write the statistics and settings of ``norm`` (a ``VecNormalize`` or
    :class:`NormalizationStats`) to ``path`` (``.npz``: arrays and a JSON header, nothing
    pickled)."""
    path = Path(path)
    arrays: dict[str, np.ndarray] = {}
    header: dict[str, Any] = {
        "format": "soccer_env vecnormalize 1", "norm_obs": bool(norm.norm_obs),
        "norm_reward": bool(norm.norm_reward), "clip_obs": float(norm.clip_obs),
        "clip_reward": float(norm.clip_reward), "gamma": float(norm.gamma),
        "epsilon": float(norm.epsilon),
        "norm_obs_keys": None if norm.norm_obs_keys is None else list(norm.norm_obs_keys)}
    header["ret"] = _stats_arrays(norm.ret_rms, "ret_", arrays)
    if norm.norm_obs:
        if isinstance(norm.obs_rms, dict):
            header["obs"] = {k: _stats_arrays(r, f"obs_{k}_", arrays)
                             for k, r in norm.obs_rms.items()}
        else:
            header["obs"] = _stats_arrays(norm.obs_rms, "obs_", arrays)
    np.savez(path, header=np.array(json.dumps(header)), **arrays)
    return path


def read_vecnormalize(path: str | os.PathLike) -> NormalizationStats:
    """Read statistics written by :func:`save_vecnormalize` (no pickle; size-checked).
    Raises ``ValueError`` naming the file for a damaged or foreign one."""
    path = Path(path)
    check_npz(path)
    try:
        with np.load(path, allow_pickle=False) as data:
            header = parse_json(str(data["header"]), f"{path}: header")
            if header.get("format") != "soccer_env vecnormalize 1":
                raise ValueError(f"format {header.get('format')!r}")

            def rms(prefix: str, entry: dict[str, float]) -> _RunningStats:
                mean = np.array(data[f"{prefix}mean"], dtype=np.float64)
                var = np.array(data[f"{prefix}var"], dtype=np.float64)
                count = float(entry["count"])
                if not (np.isfinite(mean).all() and np.isfinite(var).all()
                        and (var >= 0.0).all() and math.isfinite(count) and count > 0.0):
                    raise ValueError(f"the statistics {prefix}mean, {prefix}var and count are "
                                     "not finite (NaN or infinite), or a variance or the "
                                     "count is not positive")
                return _RunningStats(mean, var, count)

            for name in ("clip_obs", "clip_reward", "epsilon"):
                value = float(header[name])
                if not (math.isfinite(value) and value > 0.0):
                    raise ValueError(f"{name} must be finite and > 0, got {value!r}")
            if not 0.0 <= float(header["gamma"]) <= 1.0:
                raise ValueError(f"gamma must be in [0, 1], got {header['gamma']!r}")
            obs: Any = None
            if header["norm_obs"]:
                obs = ({k: rms(f"obs_{k}_", e) for k, e in header["obs"].items()}
                       if header["norm_obs_keys"] is not None else rms("obs_", header["obs"]))
            return NormalizationStats(
                bool(header["norm_obs"]), bool(header["norm_reward"]), obs,
                rms("ret_", header["ret"]), float(header["clip_obs"]),
                float(header["clip_reward"]), float(header["gamma"]), float(header["epsilon"]),
                header["norm_obs_keys"])
    except (KeyError, TypeError, ValueError, json.JSONDecodeError) as err:
        raise ValueError(f"{path} is not a file of normalisation statistics written by "
                         f"save_vecnormalize ({type(err).__name__}: {err})") from None


def vecnormalize_on(stats: NormalizationStats, venv: Any) -> Any:
    """A stable-baselines3 ``VecNormalize`` around ``venv`` with the settings and statistics
    of ``stats`` (what ``VecNormalize.load`` gives, without unpickling). Raises
    ``ValueError`` when the statistics do not fit ``venv``'s observations."""
    from stable_baselines3.common.running_mean_std import RunningMeanStd
    from stable_baselines3.common.vec_env import VecNormalize

    norm = VecNormalize(venv, norm_obs=stats.norm_obs, norm_reward=stats.norm_reward,
                        clip_obs=stats.clip_obs, clip_reward=stats.clip_reward,
                        gamma=stats.gamma, epsilon=stats.epsilon,
                        norm_obs_keys=stats.norm_obs_keys)

    def copy(src: _RunningStats, dst: RunningMeanStd, what: str) -> None:
        if np.shape(src.mean) != np.shape(dst.mean):
            raise ValueError(f"the saved {what} statistics have shape {np.shape(src.mean)}, "
                             f"the environment's {np.shape(dst.mean)}")
        dst.mean, dst.var, dst.count = src.mean.copy(), src.var.copy(), src.count

    if stats.norm_obs:
        if isinstance(stats.obs_rms, dict):
            for key, rms in stats.obs_rms.items():
                copy(rms, norm.obs_rms[key], f"observation {key!r}")
        else:
            copy(stats.obs_rms, norm.obs_rms, "observation")
    copy(stats.ret_rms, norm.ret_rms, "return")
    return norm


def vecnormalize_path(model_path: str | os.PathLike, suffix: str = ".npz") -> Path:
    """Where a training run keeps the ``VecNormalize`` statistics of a saved model:
    ``final_model.zip`` -> ``final_vecnormalize.npz`` (also ``best_``), and
    ``model_<N>_steps.zip`` -> ``model_vecnormalize_<N>_steps.npz`` (checkpoints, as
    stable-baselines3's ``CheckpointCallback`` names them). ``suffix=".pkl"``: the name of
    the pickle stable-baselines3 itself writes (read only when trusted)."""
    path = Path(model_path)
    stem = path.stem
    if stem.endswith("_model"):
        name = stem[: -len("model")] + "vecnormalize"
    elif stem.startswith("model_") and stem.endswith("_steps"):
        name = "model_vecnormalize_" + stem[len("model_"):]
    else:
        name = stem + "_vecnormalize"
    return path.with_name(name + suffix)


def load_vecnormalize(model_path: str | os.PathLike, trust: bool = False) -> Any:
    """The normalisation statistics saved beside a model, if any: the ``.npz``
    (:func:`read_vecnormalize`, no pickle), else with ``trust=True`` stable-baselines3's
    pickled ``.pkl`` (a ``VecNormalize`` without its environments). A ``.pkl`` alone without
    ``trust`` raises :class:`~agents.policies.files.UnsafeFileError`; None when there are
    none."""
    stats = vecnormalize_path(model_path)
    if stats.exists():
        return read_vecnormalize(stats)
    pickled = vecnormalize_path(model_path, ".pkl")
    if not pickled.exists():
        return None
    if not trust:
        raise UnsafeFileError(f"the normalisation statistics of {model_path} are only in "
                              f"{pickled}, a pickle; {TRUST_HELP}")
    check_file_size(pickled)
    try:
        with open(pickled, "rb") as fh:
            return pickle.load(fh)
    except Exception as err:
        raise ValueError(f"{pickled} could not be read ({type(err).__name__}: {err})"
                         ) from None
