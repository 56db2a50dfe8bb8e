"""Reading stable-baselines3 model files without running code from them.

Two of the formats that stable-baselines3 writes run code when loaded: a ``VecNormalize``
saved with ``pickle`` (``*_vecnormalize.pkl``; the statistics are written as ``.npz`` instead,
:mod:`agents.sb3.normalization`), and the ``":serialized:"`` entries of a model ``.zip``'s
``data`` (cloudpickled classes, spaces and schedules). A model ``.zip`` is opened by
:func:`load_sb3_safely`, which reads the ``data`` entry as JSON (:func:`model_data`), loads
the networks' weights with ``torch.load(weights_only=True)`` (as stable-baselines3 does), and
replaces every serialized entry with an object built here from what the caller knows (the
spaces of the environment it will act in, the algorithm's policy class, the
hyperparameters); a file with a serialized entry this module does not know how to replace is
refused with :class:`~agents.policies.files.UnsafeFileError`. :func:`load_model` tries the
algorithms on a file of unknown algorithm.

Every file is size-checked before it is read (:mod:`agents.policies.files`). Loading a pickle
needs ``trust=True`` (``--trust`` on the command line): only for files from a source you
trust, since unpickling runs whatever code the file names.
"""

from __future__ import annotations

import io
import math
import os
import pickle
import re
import zipfile
from pathlib import Path
from typing import Any

from agents.policies.files import (
    MAX_FILE_BYTES,
    MAX_JSON_BYTES,
    READ_METHODS,
    TRUST_HELP,
    UnsafeFileError,
    open_archive,
    parse_json,
    read_member,
)
from agents.sb3.algorithms import LOAD_ORDER, SB3_ALGORITHMS, algorithm_class, algorithm_name

__all__ = ["MAX_NETWORK_PARAMETERS", "model_data", "serialized_entries", "network_parameters",
           "check_weights", "load_sb3_safely", "load_model"]

#: The most parameters the networks built from a model file may have when it is loaded
#: without ``trust`` (the package's keepers have about 10,000, a 1,024 x 1,024 actor and critic
#: about 2 million; ``trust`` lifts the limit).
MAX_NETWORK_PARAMETERS = 4 * 2**20
#: Layer sizes stable-baselines3 builds when ``policy_kwargs`` names none (its on-policy
#: default; the off-policy algorithms' 256 x 256 is below the bound as well).
_DEFAULT_ARCH = [64, 64]


def model_data(path: Path) -> dict[str, Any]:
    """The JSON ``data`` entry of a stable-baselines3 model file (read, never unpickled;
    size-checked first, :func:`~agents.policies.files.open_archive`; the entry read with its size
    measured and parsed by :func:`~agents.policies.files.parse_json`)."""
    with open_archive(path) as archive:
        try:
            data = parse_json(read_member(archive, "data", MAX_JSON_BYTES, path),
                              f"{path}: member 'data'")
        except KeyError:
            raise ValueError(f"{path} is not a stable-baselines3 model file (it has no "
                             "'data' entry)") from None
        except UnsafeFileError:
            raise
        except (ValueError, zipfile.BadZipFile, OSError) as err:
            raise ValueError(f"{path} is not a stable-baselines3 model file ({err})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path} is not a stable-baselines3 model file (its 'data' entry is "
                         "not a JSON object)")
    return data


def _layers(arch: Any, path: Path) -> list[list[int]]:
    """The layer sizes of each network a ``net_arch`` describes (a list of sizes, a dict of
    them per network, or stable-baselines3's old list of shared sizes and a dict)."""
    def sizes(value: Any) -> list[int]:
        if not isinstance(value, list) or not all(
                isinstance(v, int) and not isinstance(v, bool) and v > 0 for v in value):
            raise ValueError(f"{path}: net_arch must be lists of layer sizes (positive "
                             f"integers), got {arch!r}")
        return list(value)

    if isinstance(arch, dict):
        return [sizes(v) for v in arch.values()] or [[]]
    if isinstance(arch, list) and arch and isinstance(arch[-1], dict):
        shared = sizes(arch[:-1])
        return [shared + sizes(v) for v in arch[-1].values()] or [shared]
    return [sizes(arch)]


def network_parameters(policy_kwargs: dict[str, Any], obs_size: int, act_size: int,
                       path: Path) -> int:
    """An upper estimate of the parameters of the networks stable-baselines3 builds from
    ``policy_kwargs`` for observations of ``obs_size`` and actions of ``act_size`` entries:
    every network of ``net_arch`` (two, actor and critic, when it names one list) from the
    observation and the action to its output, and the LSTM's of ``lstm_hidden_size``."""
    nets = _layers(policy_kwargs.get("net_arch", _DEFAULT_ARCH), path)
    if len(nets) == 1:
        nets = nets * 2
    count = 0
    for layers in nets:
        dims = [obs_size + act_size, *layers, max(act_size, 1)]
        count += sum((a + 1) * b for a, b in zip(dims, dims[1:]))
    hidden = policy_kwargs.get("lstm_hidden_size", 0)
    depth = policy_kwargs.get("n_lstm_layers", 1)
    for name, value in (("lstm_hidden_size", hidden), ("n_lstm_layers", depth)):
        if not isinstance(value, int) or isinstance(value, bool) or value < 0:
            raise ValueError(f"{path}: {name} must be a non-negative integer, got {value!r}")
    if hidden:
        count += 2 * depth * 4 * hidden * (obs_size + 2 * hidden + 2)
    return count


def check_weights(path: Path) -> None:
    """Check the weight records (``.pth`` entries, themselves zip archives) of the model file
    ``path`` before torch reads them: every record's members stored or deflate-compressed,
    and no stored member declaring more bytes than the record holds (torch allocates what a
    record declares). :class:`UnsafeFileError` naming the entry otherwise."""
    with open_archive(path) as archive:
        for info in archive.infolist():
            if not info.filename.endswith(".pth"):
                continue
            name = f"{path}: entry {info.filename!r}"
            data = read_member(archive, info.filename, MAX_FILE_BYTES, path)
            try:
                record = zipfile.ZipFile(io.BytesIO(data))
            except zipfile.BadZipFile:
                continue  # an old-style record: torch refuses it with its own message
            for member in record.infolist():
                if member.compress_type not in READ_METHODS or (
                        member.compress_type == zipfile.ZIP_STORED
                        and member.file_size > len(data)):
                    raise UnsafeFileError(
                        f"{name}: its member {member.filename!r} declares "
                        f"{member.file_size:,} bytes in a record of {len(data):,} (a crafted "
                        "record)" if member.compress_type in READ_METHODS else
                        f"{name}: its member {member.filename!r} is not stored or deflate")
            declared = sum(m.file_size for m in record.infolist())
            if declared > MAX_FILE_BYTES:
                raise UnsafeFileError(f"{name} unpacks to {declared:,} bytes, more than the "
                                      f"{MAX_FILE_BYTES:,} that are read")


def serialized_entries(path: str | os.PathLike) -> list[str]:
    """The entries of a stable-baselines3 model file that loading would unpickle (those
    with a ``":serialized:"`` value), read from its JSON without unpickling anything."""
    data = model_data(Path(path))
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
    path = Path(path)
    algorithm = algorithm_name(algorithm)
    algo = algorithm_class(algorithm)
    data = model_data(path)
    check_weights(path)
    params = dict(hyperparams or {})
    if policy_class is None:
        policy_class = algo.policy_aliases["MlpLstmPolicy" if algorithm == "RECURRENTPPO"
                                           else "MlpPolicy"]
    serialized = [k for k, v in data.items() if isinstance(v, dict) and ":serialized:" in v]
    replacements = _replacements(path, serialized, params, observation_space, action_space,
                                 policy_class)
    custom = {k: v for k, v in replacements.items() if k in serialized}
    kwargs_built = custom.get("policy_kwargs", data.get("policy_kwargs"))
    if isinstance(kwargs_built, dict):
        size = network_parameters(kwargs_built, _size(observation_space),
                                  _size(action_space), path)
        if size > MAX_NETWORK_PARAMETERS:
            raise UnsafeFileError(
                f"{path}: its networks would have about {size:,} parameters, more than the "
                f"{MAX_NETWORK_PARAMETERS:,} built from a file without --trust (trust=True)")
    try:
        return algo.load(path, device=kwargs.pop("device", "cpu"), custom_objects=custom,
                         **kwargs)
    except pickle.UnpicklingError as err:
        # torch.load(weights_only=True) refused a global: name it, not torch's advice to
        # load the file unsafely.
        found = re.search(r"Unsupported global: GLOBAL (\S+)", str(err))
        what = f"the global {found.group(1)}" if found else "objects other than tensors"
        raise UnsafeFileError(f"{path}: a weight entry (.pth) is a pickle that names {what}, "
                              f"not weights only; {TRUST_HELP}") from None
    except (RuntimeError, KeyError, TypeError, AssertionError, ValueError) as err:
        policy_name = getattr(policy_class, "__name__", policy_class)
        raise ValueError(f"{path} could not be loaded as a {algorithm} model acting on "
                         f"{observation_space} with {policy_name} ({type(err).__name__}: "
                         f"{err})") from None


def _replacements(path: Path, serialized: list[str], params: dict[str, Any],
                  observation_space: Any, action_space: Any, policy_class: Any
                  ) -> dict[str, Any]:
    """What replaces each serialized entry of a model file (see :func:`load_sb3_safely`);
    :class:`UnsafeFileError` for an entry only unpickling could read."""
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
    return replacements


def _size(space: Any) -> int:
    """The entries of a space's samples (a dict space's summed)."""
    spaces = getattr(space, "spaces", None)
    if isinstance(spaces, dict):
        return sum(_size(s) for s in spaces.values())
    shape = getattr(space, "shape", None) or (1,)
    return int(math.prod(shape))


def load_model(path: str | os.PathLike, algorithm: str | None = None, *, trust: bool = False,
               observation_space: Any = None, action_space: Any = None, policy_class: Any = None,
               hyperparams: dict[str, Any] | None = None, **kwargs: Any) -> Any:
    """Load a stable-baselines3 (or sb3-contrib RecurrentPPO) model.

    By default nothing in the file is unpickled (:func:`load_sb3_safely`): the spaces are
    ``observation_space`` and ``action_space``, else those of ``kwargs["env"]``; the policy
    class is ``policy_class``, else the algorithm's ``MlpPolicy``; schedules come from
    ``hyperparams``, else the defaults. With ``trust=True`` the file is loaded as
    stable-baselines3 loads it, unpickling its serialized entries: only for files from a
    source you trust. :func:`agents.runs.resolve.load_sb3` finds what is not given in the
    training run the file belongs to.

    ``algorithm`` (one of :data:`~agents.sb3.algorithms.SB3_ALGORITHMS`, any spelling
    :func:`~agents.sb3.algorithms.algorithm_name` takes): when not given each is tried in
    turn (:data:`~agents.sb3.algorithms.LOAD_ORDER`; RecurrentPPO only where sb3-contrib is
    installed). Raises ``FileNotFoundError``,
    :class:`~agents.policies.files.UnsafeFileError` (the file needs unpickling, or is over the
    size limits) or ``ValueError`` (not a model of any algorithm, or not one acting in the
    given spaces)."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"no model at {path}")
    # The budgets, trusted or not: size, compression, JSON (and, untrusted, the weight
    # records, which load_sb3_safely checks itself).
    model_data(path)
    if trust:
        check_weights(path)
    else:
        env = kwargs.get("env")
        if observation_space is None and env is not None:
            observation_space, action_space = env.observation_space, env.action_space
        if observation_space is None:
            raise UnsafeFileError(
                f"{path}: without the training run's config.json beside it, loading "
                "without unpickling needs the spaces it acts in (observation_space and "
                "action_space, or env); or trust=True: unpickling runs whatever code the "
                "file names, so only for files from a source you trust")
    device = kwargs.pop("device", "cpu")
    errors = []
    for name in ([algorithm] if algorithm is not None else LOAD_ORDER):
        try:
            algo = algorithm_class(name)
        except ImportError:
            if algorithm is not None:
                raise
            continue
        try:
            if trust:
                return algo.load(path, device=device, **kwargs)
            return load_sb3_safely(path, name, observation_space, action_space, policy_class,
                                   hyperparams, device=device, **kwargs)
        except UnsafeFileError:
            raise
        except Exception as exc:  # wrong algorithm for this file: try the next
            if algorithm is not None:
                raise ValueError(f"{path} could not be loaded as a {algorithm_name(name)} "
                                 f"model: {exc}") from None
            errors.append(f"{name}: {type(exc).__name__}")
    raise ValueError(f"{path} is not a model of any of {list(SB3_ALGORITHMS)} ({errors})")
