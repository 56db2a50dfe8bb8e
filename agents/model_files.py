"""Reading model files without running code from them.

Policies, checkpoints and run folders may come from strangers, and two of the formats that
stable-baselines3 writes run code when loaded: a ``VecNormalize`` saved with ``pickle``
(``*_vecnormalize.pkl``), and the ``":serialized:"`` entries of a model ``.zip``'s ``data``
(cloudpickled classes, spaces and schedules). This module reads both kinds of file without
unpickling anything:

* normalisation statistics are written as ``*_vecnormalize.npz`` (arrays and a JSON header,
  :func:`save_vecnormalize`) and read back as plain arrays (:func:`read_vecnormalize`), into a
  :class:`NormalizationStats` or onto a fresh ``VecNormalize`` (:func:`vecnormalize_on`);
* a model ``.zip`` is opened by :func:`load_sb3_safely`, which reads the ``data`` entry as
  JSON, loads the networks' weights with ``torch.load(weights_only=True)`` (as
  stable-baselines3 does), and replaces every serialized entry with an object built here from
  what the caller knows (the spaces of the environment it will act in, the algorithm's
  policy class, the hyperparameters); a file with a serialized entry this module does not
  know how to replace is refused with :class:`UnsafeFileError`.

Every file is size-checked before it is read (:data:`MAX_FILE_BYTES`, and each array of an
``.npz`` by its header, :data:`MAX_ARRAY_ELEMENTS`), so that a small crafted file cannot make
the loader allocate gigabytes. Loading a pickle (the ``.pkl`` statistics, a model ``.zip``
with its serialized entries) needs ``trust=True`` (``--trust`` on the command line): only for
files from a source you trust, since unpickling runs whatever code the file names.
"""

from __future__ import annotations

import json
import os
import zipfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["UnsafeFileError", "MAX_FILE_BYTES", "MAX_ARRAY_ELEMENTS", "check_npz",
           "serialized_entries", "load_sb3_safely", "NormalizationStats", "save_vecnormalize",
           "read_vecnormalize", "vecnormalize_on", "TRUST_HELP"]

#: The largest file (and the largest total unpacked size of an archive) that is read, bytes.
#: Policies of this package are tens of kB; a large stable-baselines3 model a few MB.
MAX_FILE_BYTES = 256 * 2**20
#: The most elements one array of an ``.npz`` may hold (a 4,096 x 4,096 weight matrix).
MAX_ARRAY_ELEMENTS = 4096 * 4096

#: What to tell a user whose file needs unpickling.
TRUST_HELP = ("unpickling runs whatever code the file names; pass --trust (trust=True) only "
              "for files from a source you trust")


class UnsafeFileError(ValueError):
    """A file that cannot be read without running code from it (or is too large to read
    safely), refused because loading it was not trusted."""


# ------------------------------------------------------------------------------------------
# Size checks
# ------------------------------------------------------------------------------------------

def _check_size(path: Path) -> None:
    if not path.is_file():
        raise FileNotFoundError(f"no file at {path}")
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise UnsafeFileError(f"{path} is {size:,} bytes, more than the {MAX_FILE_BYTES:,} "
                              "that are read")


def _open_archive(path: Path) -> zipfile.ZipFile:
    """``path`` as a zip archive whose members unpack to at most :data:`MAX_FILE_BYTES` in
    all; ``ValueError`` naming the file for anything that is not such an archive."""
    _check_size(path)
    try:
        archive = zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError) as err:
        raise ValueError(f"{path} is not a valid archive ({err}); the file is damaged or not "
                         "of this kind") from None
    unpacked = sum(info.file_size for info in archive.infolist())
    if unpacked > MAX_FILE_BYTES:
        archive.close()
        raise UnsafeFileError(f"{path} unpacks to {unpacked:,} bytes, more than the "
                              f"{MAX_FILE_BYTES:,} that are read")
    return archive


def check_npz(path: str | os.PathLike) -> None:
    """Check an ``.npz`` before ``np.load`` reads it: a valid archive of at most
    :data:`MAX_FILE_BYTES` unpacked, whose every member is a ``.npy`` array of at most
    :data:`MAX_ARRAY_ELEMENTS` elements of a plain (not object) dtype, read from its header
    only. Raises ``ValueError`` (:class:`UnsafeFileError` for a too-large one) naming the
    file and the member."""
    path = Path(path)
    with _open_archive(path) as archive:
        for info in archive.infolist():
            try:
                with archive.open(info) as fh:
                    version = np.lib.format.read_magic(fh)
                    if version == (1, 0):
                        shape, _, dtype = np.lib.format.read_array_header_1_0(fh)
                    else:
                        shape, _, dtype = np.lib.format.read_array_header_2_0(fh)
            except (ValueError, OSError, zipfile.BadZipFile, EOFError) as err:
                raise ValueError(f"{path}: member {info.filename!r} is not a readable array "
                                 f"({err})") from None
            if dtype.hasobject:
                raise UnsafeFileError(f"{path}: member {info.filename!r} holds Python objects "
                                      "(reading them would unpickle)")
            count = int(np.prod(shape, dtype=np.float64))
            if count > MAX_ARRAY_ELEMENTS:
                raise UnsafeFileError(f"{path}: member {info.filename!r} declares shape "
                                      f"{shape} ({count:,} elements), more than the "
                                      f"{MAX_ARRAY_ELEMENTS:,} that are read")
            if count * dtype.itemsize > info.file_size + 1024:
                raise ValueError(f"{path}: member {info.filename!r} declares shape {shape} "
                                 f"but holds {info.file_size:,} bytes (a truncated or crafted "
                                 "file)")


# ------------------------------------------------------------------------------------------
# Normalisation statistics
# ------------------------------------------------------------------------------------------

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
            header = json.loads(str(data["header"]))
            if header.get("format") != "soccer_env vecnormalize 1":
                raise ValueError(f"format {header.get('format')!r}")

            def rms(prefix: str, entry: dict[str, float]) -> _RunningStats:
                return _RunningStats(np.array(data[f"{prefix}mean"]),
                                     np.array(data[f"{prefix}var"]), float(entry["count"]))

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


# ------------------------------------------------------------------------------------------
# stable-baselines3 model files
# ------------------------------------------------------------------------------------------

def _model_data(path: Path) -> dict[str, Any]:
    """The JSON ``data`` entry of a stable-baselines3 model file (read, never unpickled)."""
    with _open_archive(path) as archive:
        try:
            data = json.loads(archive.read("data"))
        except KeyError:
            raise ValueError(f"{path} is not a stable-baselines3 model file (it has no "
                             "'data' entry)") from None
        except (ValueError, zipfile.BadZipFile, OSError) as err:
            raise ValueError(f"{path} is not a stable-baselines3 model file ({err})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path} is not a stable-baselines3 model file (its 'data' entry is "
                         "not a JSON object)")
    return data


def serialized_entries(path: str | os.PathLike) -> list[str]:
    """The entries of a stable-baselines3 model file that loading would unpickle (those
    with a ``":serialized:"`` value), read from its JSON without unpickling anything."""
    data = _model_data(Path(path))
    return sorted(k for k, v in data.items() if isinstance(v, dict) and ":serialized:" in v)


#: Serialized entries that hold the state of an unfinished rollout or the episode
#: statistics: a loaded model starts them afresh (``learn`` resets them when they are None).
_RUNTIME_STATE = ("_last_obs", "_last_episode_starts", "_last_original_obs", "ep_info_buffer",
                  "ep_success_buffer", "_last_lstm_states")


def load_sb3_safely(path: str | os.PathLike, algorithm: str, observation_space: Any,
                    action_space: Any, policy_class: Any = None,
                    hyperparams: dict[str, Any] | None = None, **kwargs: Any) -> Any:
    """Load a stable-baselines3 (or sb3-contrib RecurrentPPO) model without unpickling.

    The ``data`` entry is read as JSON and every serialized entry is replaced: the spaces by
    ``observation_space`` and ``action_space`` (those of the environment the model will act
    in, as it was trained: action map, frame stack, privileged critic included), the policy
    class by ``policy_class`` (default: the algorithm's ``MlpPolicy``, ``MlpLstmPolicy`` for
    RecurrentPPO), schedules by the constants of ``hyperparams`` (or the algorithm's
    defaults; the model rebuilds its schedules from them), the rollout buffer and replay
    buffer classes by the algorithm's defaults, the state of an unfinished rollout by
    nothing. The weights come from the ``.pth`` entries, which stable-baselines3 reads with
    ``torch.load(weights_only=True)``. ``kwargs`` go to the algorithm's ``load`` (``env``,
    hyperparameters).

    Raises :class:`UnsafeFileError` for a serialized entry it cannot replace (and for a file
    over the size limits), ``ValueError`` for a file that is not a model of ``algorithm`` or
    whose network does not fit the spaces and policy class."""
    from agents.policies import algorithm_class, algorithm_name

    path = Path(path)
    algorithm = algorithm_name(algorithm)
    algo = algorithm_class(algorithm)
    data = _model_data(path)
    params = dict(hyperparams or {})
    if policy_class is None:
        policy_class = algo.policy_aliases["MlpLstmPolicy" if algorithm == "RECURRENTPPO"
                                           else "MlpPolicy"]

    def constant(name: str, default: Any) -> Any:
        value = params.get(name, default)
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            raise UnsafeFileError(f"{path}: {name} must be a number to replace the file's "
                                  f"serialized schedule, got {value!r}")
        return float(value)

    replacements: dict[str, Any] = {
        "observation_space": observation_space, "action_space": action_space,
        "policy_class": policy_class, "lr_schedule": None,
        "rollout_buffer_class": None, "replay_buffer_class": None,
        "action_noise": None,
        **{name: None for name in _RUNTIME_STATE}}
    serialized = [k for k, v in data.items() if isinstance(v, dict) and ":serialized:" in v]
    for name in serialized:
        if name in replacements:
            continue
        if name == "learning_rate":
            replacements[name] = constant("learning_rate", 3e-4)
        elif name == "clip_range":
            replacements[name] = constant("clip_range", 0.2)
        elif name == "clip_range_vf":
            value = params.get("clip_range_vf")
            replacements[name] = None if value is None else constant("clip_range_vf", value)
        elif name == "train_freq":
            replacements[name] = params.get("train_freq", 1)
        elif name in ("rollout_buffer_kwargs", "replay_buffer_kwargs"):
            replacements[name] = {}
        elif name == "policy_kwargs" and isinstance(params.get("policy_kwargs"), dict):
            replacements[name] = params["policy_kwargs"]
        else:
            raise UnsafeFileError(f"{path}: the entry {name!r} can only be read by unpickling "
                                  f"it; {TRUST_HELP}")
    custom = {k: v for k, v in replacements.items() if k in serialized}
    try:
        return algo.load(path, device=kwargs.pop("device", "cpu"), custom_objects=custom,
                         **kwargs)
    except (RuntimeError, KeyError, TypeError, AssertionError, ValueError) as err:
        policy_name = getattr(policy_class, "__name__", policy_class)
        raise ValueError(f"{path} could not be loaded as a {algorithm} model acting on "
                         f"{observation_space} with {policy_name} ({type(err).__name__}: "
                         f"{err})") from None
