"""Policies as plain callables, and loading them by name or path.

A policy maps one observation (a float32 vector) to one action; :class:`NumpyPolicy` also
takes a batch ``(n, obs_dim) -> (n, act_dim)``. Policies are referred to by strings so that
evaluation workers can rebuild them in their own processes (see :func:`make_policy`):

* ``"scripted"``: :class:`~agents.ScriptedGoalkeeper`;
* ``"idle"``: a keeper that stands still (all-zero actions);
* ``"baseline:NAME"``: a policy shipped in the package (:data:`agents.baselines.BASELINES`);
* a path to a ``.npz`` written by :meth:`NumpyPolicy.save`;
* a path to a stable-baselines3 ``.zip`` (PPO, A2C, SAC, TD3, DDPG, sb3-contrib's
  RecurrentPPO; with the ``VecNormalize`` statistics saved beside it, see
  :func:`vecnormalize_path`, and the action map and frame stack recorded in its run's
  ``config.json``), or a training run's folder (its ``final_policy.npz``, else
  ``final_model.zip``).

Trained networks are evaluated through :class:`NumpyPolicy`, a numpy copy of the actor's
deterministic path: a stable-baselines3 ``predict`` costs about 0.3 ms per call on a 2-core
machine, more than the environment step it drives, while the numpy copy costs about 20 us and
needs neither torch nor stable-baselines3 (so the shipped baselines run without the training
extra).

Policies with memory (:class:`NumpyRecurrentPolicy`, the LSTM of a RecurrentPPO actor; a
:class:`NumpyPolicy` trained on stacked frames, which keeps its own history of
observations) act on one episode at a time: whoever runs episodes calls
:func:`reset_policy` at each episode start (it calls the policy's ``reset()``, where there
is one), as :func:`~agents.evaluation.evaluate` and
:func:`~agents.evaluation.record_video` do.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any, Protocol

import numpy as np

__all__ = ["Policy", "NumpyPolicy", "NumpyRecurrentPolicy", "SB3Policy", "IdlePolicy",
           "make_policy", "load_sb3", "reset_policy", "vecnormalize_path", "load_vecnormalize",
           "learner_spaces", "algorithm_name",
           "algorithm_class", "SB3_ALGORITHMS", "POLICY_NAMES"]

#: Algorithms that :func:`load_sb3` opens and training runs (canonical spellings, see
#: :func:`algorithm_name`): stable-baselines3's, and sb3-contrib's ``RecurrentPPO`` (PPO with
#: an LSTM in front of the actor's and the critic's networks; ``recurrent-ppo`` on the
#: command line).
SB3_ALGORITHMS = ("PPO", "SAC", "TD3", "A2C", "DDPG", "RECURRENTPPO")

#: The order in which :func:`load_sb3` tries the algorithms on a file of unknown algorithm:
#: RecurrentPPO first, because PPO opens a RecurrentPPO file without complaint (and then
#: acts without its memory), while RecurrentPPO refuses the others' files.
_LOAD_ORDER = ("RECURRENTPPO", "PPO", "SAC", "TD3", "A2C", "DDPG")

#: Policy names that :func:`make_policy` resolves without a file.
POLICY_NAMES = ("scripted", "idle")


class Policy(Protocol):
    """One observation in, one action out. A policy with memory also has ``reset()``, to be
    called at each episode start (see :func:`reset_policy`)."""

    def __call__(self, obs: np.ndarray) -> np.ndarray: ...


def reset_policy(policy: Any) -> None:
    """Start a new episode for ``policy``: call its ``reset()`` if it has one (policies with
    memory: a frame stack, an LSTM); stateless policies need nothing."""
    reset = getattr(policy, "reset", None)
    if callable(reset):
        reset()


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


def _is_recurrent(model: Any) -> bool:
    """Whether a stable-baselines3 model's policy is recurrent (sb3-contrib's LSTM policies)."""
    return hasattr(getattr(model, "policy", None), "lstm_actor")


class IdlePolicy:
    """All-zero actions: a robot that stands still and never kicks. Takes one observation or
    a batch ``(n, obs_dim)``."""

    def __init__(self, action_size: int) -> None:
        self.action_size = int(action_size)

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        obs = np.asarray(obs)
        shape = (len(obs), self.action_size) if obs.ndim == 2 else (self.action_size,)
        return np.zeros(shape, dtype=np.float32)


_ACTIVATIONS = {"Tanh": "tanh", "ReLU": "relu", "Hardtanh": "hardtanh", "Identity": None,
                "Flatten": None}


class NumpyPolicy:
    """A feed-forward actor evaluated with numpy: the deterministic action of a trained
    stable-baselines3 policy.

    ``layers`` is a list of ``("linear", W, b)`` (``y = W x + b``), ``("tanh",)``,
    ``("relu",)`` or ``("hardtanh", lo, hi)``. ``output`` is ``"clip"`` (PPO and A2C: the
    Gaussian's mean, clipped into the action box as stable-baselines3's ``predict`` does) or
    ``"tanh"`` (SAC: the squashed mean; TD3 and DDPG end in a Tanh layer, given as
    ``"scale"``), after which ``[-1, 1]`` is mapped onto ``[low, high]``.

    Args:
        layers: the network, input to output.
        output: ``"clip"``, ``"tanh"`` or ``"scale"``.
        low: the action box's lower bounds.
        high: the action box's upper bounds.
        meta: free-form description (algorithm, environment, training configuration), saved
            with the weights.
        normalize: ``(mean, var, clip, epsilon)`` of a policy trained behind
            stable-baselines3's ``VecNormalize``: the network's inputs become
            ``clip((x - mean) / sqrt(var + epsilon), -clip, clip)`` first.
        action_map: ``None`` (the network's output is the environment's action) or
            ``{"kind": ..., "params": {...}}`` for a keeper trained through one of the
            wrappers of :mod:`agents.wrappers`: its outputs become the native command with
            :func:`~agents.wrappers.action_to_command`, from the pose in the observation.
        frame_stack: the number of observations the network reads at once (a policy trained
            behind :func:`~agents.wrappers.stack_frames`): the policy keeps the last
            ``frame_stack`` observations it was called with and feeds the network their
            concatenation, oldest first, the episode's first observation repeated while there
            are fewer; call :meth:`reset` at each episode start. It is called with single
            observations of the plain environment; ``normalize`` applies to the concatenation.

    Attributes:
        obs_size: the size of one observation the policy is called with.
        input_size: the size of the network's input (``frame_stack * obs_size``).
        action_size: the size of the network's output.

    The policy owns copies of every array: it does not follow the model it was copied from.
    """

    def __init__(self, layers: list[tuple], output: str, low: np.ndarray, high: np.ndarray,
                 meta: dict[str, Any] | None = None,
                 normalize: tuple[np.ndarray, np.ndarray, float, float] | None = None,
                 action_map: dict[str, Any] | None = None, frame_stack: int = 1) -> None:
        from agents.wrappers import POLICY_MAPS

        if output not in ("clip", "tanh", "scale"):
            raise ValueError(f"output must be 'clip', 'tanh' or 'scale', got {output!r}")
        if action_map is not None and (action_map.get("kind") not in POLICY_MAPS):
            raise ValueError(f"action_map kind must be one of {list(POLICY_MAPS)}, got "
                             f"{action_map!r}")
        if isinstance(frame_stack, bool) or not isinstance(frame_stack, (int, np.integer)) \
                or frame_stack < 1:
            raise ValueError(f"frame_stack must be an integer >= 1, got {frame_stack!r}")
        if action_map is not None and action_map["kind"] == "native":
            action_map = None
        self.action_map = None if action_map is None else {
            "kind": action_map["kind"], "params": dict(action_map.get("params") or {})}
        self.layers = [(k, *(np.array(a, dtype=np.float32) for a in rest))
                       for k, *rest in layers]
        self.output = output
        self.low = np.array(low, dtype=np.float32)
        self.high = np.array(high, dtype=np.float32)
        self.meta = dict(meta or {})
        self.frame_stack = int(frame_stack)
        self.normalize = None
        if normalize is not None:
            mean, var, clip, eps = normalize
            # Float64, as VecNormalize keeps them: an entry that hardly varies in training
            # (variance near 0) would turn float32 rounding of its mean into large inputs.
            self.normalize = (np.array(mean, dtype=np.float64), np.array(var, dtype=np.float64),
                              float(clip), float(eps))
        linear = [layer for layer in self.layers if layer[0] == "linear"]
        if not linear:
            raise ValueError("a NumpyPolicy needs at least one linear layer")
        _check_layers(self.layers)
        for name, value in (("low", self.low), ("high", self.high)):
            if not np.all(np.isfinite(value)):
                raise ValueError(f"{name} must be finite, got {value}")
        self.input_size = self._input_size(linear)
        if self.input_size % self.frame_stack:
            raise ValueError(f"the network's input size {self.input_size} is not a multiple of "
                             f"frame_stack {self.frame_stack}")
        self.obs_size = self.input_size // self.frame_stack
        self.action_size = int(linear[-1][1].shape[0])
        if self.low.shape != (self.action_size,) or self.high.shape != (self.action_size,):
            raise ValueError(f"low and high must have shape ({self.action_size},)")
        if self.action_map is not None and \
                self.action_size != POLICY_MAPS[self.action_map["kind"]]:
            raise ValueError(f"a {self.action_map['kind']!r} policy has "
                             f"{POLICY_MAPS[self.action_map['kind']]} outputs, got "
                             f"{self.action_size}")
        if self.normalize is not None:
            mean, var, clip, eps = self.normalize
            if mean.shape != (self.input_size,) or var.shape != (self.input_size,):
                raise ValueError(f"normalize mean and var must have shape ({self.input_size},)")
            if not (np.all(np.isfinite(mean)) and np.all(np.isfinite(var)) and np.all(var >= 0)
                    and math.isfinite(clip) and clip > 0 and math.isfinite(eps) and eps >= 0):
                raise ValueError("normalize needs a finite mean, a finite variance >= 0, a "
                                 "finite clip > 0 and a finite epsilon >= 0")
            self._shift, self._scale = mean, 1.0 / np.sqrt(var + eps)
        # Transposed weights for row-vector products.
        self._ops = [(k, rest[0].T.copy(), rest[1]) if k == "linear" else (k, *rest)
                     for k, *rest in self.layers]
        self._history: np.ndarray | None = None

    def _input_size(self, linear: list[tuple]) -> int:
        """The size of the network's input (that of its first linear layer)."""
        return int(linear[0][1].shape[1])

    @property
    def stateful(self) -> bool:
        """Whether the policy remembers earlier calls (then :meth:`reset` starts an
        episode)."""
        return self.frame_stack > 1

    def reset(self) -> None:
        """Forget the episode so far (the history of a frame stack): call at each episode
        start. A policy without memory has nothing to forget."""
        self._history = None

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        x = np.asarray(obs, dtype=np.float32)
        if x.ndim not in (1, 2) or x.shape[-1] != self.obs_size:
            raise ValueError(f"obs must have shape ({self.obs_size},) or (n, {self.obs_size}), "
                             f"got {x.shape}")
        action = self.network_action(self._stack(x) if self.frame_stack > 1 else x)
        if self.action_map is not None:
            from agents.wrappers import action_to_command

            return action_to_command(self.action_map["kind"], obs, action,
                                     self.action_map["params"] or None)
        return action

    def _stack(self, obs: np.ndarray) -> np.ndarray:
        """Add ``obs`` (one observation or a batch) to the history; the network's input:
        the last ``frame_stack`` observations concatenated, oldest first."""
        history = self._history
        if history is None:
            history = np.repeat(obs[..., None, :], self.frame_stack, axis=-2)
        elif history.shape[:-2] != obs.shape[:-1]:
            raise ValueError(f"obs of shape {obs.shape} in an episode of observations of "
                             f"shape {history.shape[:-2] + (self.obs_size,)}: call reset() "
                             "at each episode start")
        else:
            history = np.concatenate([history[..., 1:, :], obs[..., None, :]], axis=-2)
        self._history = history
        return history.reshape(obs.shape[:-1] + (self.input_size,))

    def network_action(self, x: np.ndarray) -> np.ndarray:
        """The network's action for its input ``x`` (one input or a batch): the action the
        stable-baselines3 model predicts deterministically for that observation, before any
        action map turns it into the native command. The input is the observation, or for a
        frame-stacked policy the last ``frame_stack`` observations concatenated, oldest first,
        as the model saw them in training; for a policy without an action map or stack, what
        calling it returns."""
        return self._head(self._network_input(x))

    def _network_input(self, x: np.ndarray) -> np.ndarray:
        """``x`` checked and normalised (float32)."""
        x = np.asarray(x, dtype=np.float32)
        if x.ndim not in (1, 2) or x.shape[-1] != self.input_size:
            raise ValueError(f"the network's input must have shape ({self.input_size},) or "
                             f"(n, {self.input_size}), got {x.shape}")
        if self.normalize is not None:
            clip = self.normalize[2]
            x = np.clip((x - self._shift) * self._scale, -clip, clip).astype(np.float32)
        return x

    def _head(self, x: np.ndarray) -> np.ndarray:
        """The layers and the output map on ``x``: the action."""
        for op in self._ops:
            kind = op[0]
            if kind == "linear":
                x = x @ op[1] + op[2]
            elif kind == "tanh":
                x = np.tanh(x)
            elif kind == "relu":
                x = np.maximum(x, 0.0)
            else:  # hardtanh
                x = np.clip(x, op[1], op[2])
        if self.output == "clip":
            return np.clip(x, self.low, self.high).astype(np.float32)
        if self.output == "tanh":
            x = np.tanh(x)
        return (self.low + 0.5 * (x + 1.0) * (self.high - self.low)).astype(np.float32)

    # --------------------------------------------------------------------------------------

    @classmethod
    def from_sb3(cls, model: Any, meta: dict[str, Any] | None = None,
                 vec_normalize: Any = None, action_map: dict[str, Any] | None = None,
                 frame_stack: int = 1) -> NumpyPolicy:
        """Copy the deterministic actor of a stable-baselines3 model (MLP policies of PPO,
        A2C, SAC, TD3, DDPG on a flat Box observation; a RecurrentPPO LSTM policy gives a
        :class:`NumpyRecurrentPolicy`), with the observation statistics of
        ``vec_normalize`` (a ``VecNormalize`` it was trained behind) if given, the
        ``action_map`` it was trained through (see :mod:`agents.wrappers`) and the
        ``frame_stack`` of its observations (see :func:`~agents.wrappers.stack_frames`).
        Raises ``ValueError`` for anything else (image or dict observations, custom networks,
        squashed actor-critic policies). gSDE exploration does not change the deterministic
        action, so models trained with it copy too."""
        from torch import nn

        if _is_recurrent(model):
            return NumpyRecurrentPolicy.from_sb3(model, meta, vec_normalize, action_map,
                                                 frame_stack)
        policy = model.policy
        low, high = model.action_space.low, model.action_space.high
        name = type(model).__name__
        key = getattr(policy, "actor_key", None)  # a privileged critic's actor reads one key
        if hasattr(policy, "mlp_extractor"):  # PPO, A2C
            if getattr(policy, "squash_output", False):
                raise ValueError("squashed actor-critic policies are not supported")
            if key is None:
                _check_flatten(policy.pi_features_extractor if hasattr(
                    policy, "pi_features_extractor") else policy.features_extractor)
            mods = [*policy.mlp_extractor.policy_net, policy.action_net]
            output = "clip"
        elif hasattr(policy, "actor") and hasattr(policy.actor, "latent_pi"):  # SAC
            actor = policy.actor
            _check_flatten(actor.features_extractor)
            mu = actor.mu if isinstance(actor.mu, nn.Sequential) else [actor.mu]
            mods = [*actor.latent_pi, *mu]
            output = "tanh"
        elif hasattr(policy, "actor") and isinstance(getattr(policy.actor, "mu", None),
                                                     nn.Sequential):  # TD3, DDPG
            _check_flatten(policy.actor.features_extractor)
            mods = list(policy.actor.mu)
            if not mods or type(mods[-1]).__name__ != "Tanh":
                raise ValueError("expected a TD3/DDPG actor ending in Tanh")
            mods = mods[:-1]
            output = "tanh"
        else:
            raise ValueError(f"cannot copy the policy of a {name} model into numpy")
        return cls(_numpy_layers(mods, name), output, low, high,
                   {"algorithm": name, **(meta or {})}, _normalize_of(vec_normalize, key),
                   action_map, frame_stack)

    def save(self, path: str | os.PathLike) -> Path:
        """Write the weights and description to ``path`` (``.npz``: arrays and a JSON header,
        nothing pickled)."""
        path = Path(path)
        arrays: dict[str, np.ndarray] = {}
        spec = []
        for i, (kind, *rest) in enumerate(self.layers):
            if kind == "linear":
                arrays[f"W{i}"], arrays[f"b{i}"] = rest
                spec.append(["linear"])
            else:
                spec.append([kind, *(float(v) for v in rest)])
        header: dict[str, Any] = {"layers": spec, "output": self.output, "meta": self.meta,
                                  "action_map": self.action_map,
                                  "frame_stack": self.frame_stack}
        if self.normalize is not None:
            mean, var, clip, eps = self.normalize
            arrays["obs_mean"], arrays["obs_var"] = mean, var
            header["normalize"] = {"clip": clip, "epsilon": eps}
        self._save_extra(header, arrays)
        np.savez_compressed(path, header=np.array(json.dumps(header)), low=self.low,
                            high=self.high, **arrays)
        return path

    def _save_extra(self, header: dict[str, Any], arrays: dict[str, np.ndarray]) -> None:
        """Add what a subclass saves besides the layers to ``header`` and ``arrays``."""

    @classmethod
    def load(cls, path: str | os.PathLike) -> NumpyPolicy:
        """Read a policy written by :meth:`save` (a :class:`NumpyRecurrentPolicy` for a
        recurrent one): arrays and JSON only, nothing unpickled, every array's size checked
        from its header before it is read (:func:`agents.model_files.check_npz`). Raises
        ``ValueError`` naming the file for a damaged, foreign or inconsistent one."""
        from agents.model_files import UnsafeFileError, check_npz

        check_npz(path)
        try:
            return cls._load(path)
        except UnsafeFileError:
            raise
        except (KeyError, IndexError, TypeError, ValueError, AttributeError,
                json.JSONDecodeError) as err:
            raise ValueError(f"{os.fspath(path)} is not a policy written by NumpyPolicy.save "
                             f"({type(err).__name__}: {err})") from None

    @classmethod
    def _load(cls, path: str | os.PathLike) -> NumpyPolicy:
        with np.load(path, allow_pickle=False) as data:
            header = json.loads(str(data["header"]))
            layers: list[tuple] = []
            for i, (kind, *rest) in enumerate(header["layers"]):
                layers.append(("linear", data[f"W{i}"], data[f"b{i}"]) if kind == "linear"
                              else (kind, *rest))
            normalize = None
            if "normalize" in header:
                norm = header["normalize"]
                normalize = (data["obs_mean"], data["obs_var"], norm["clip"], norm["epsilon"])
            args = (layers, header["output"], data["low"], data["high"], header["meta"],
                    normalize, header.get("action_map"), int(header.get("frame_stack", 1)))
            if "lstm" in header:
                cells = [tuple(data[f"lstm_{part}{k}"] for part in ("w_ih", "w_hh", "b_ih",
                                                                      "b_hh"))
                         for k in range(int(header["lstm"]["layers"]))]
                return NumpyRecurrentPolicy(cells, *args)
            if cls is not NumpyPolicy:
                raise ValueError(f"{path} holds a feed-forward policy, not a {cls.__name__}")
            return cls(*args)


def _sigmoid(x: np.ndarray) -> np.ndarray:
    """The logistic function, without overflow for large ``|x|`` (keeps the dtype)."""
    return 0.5 * (1.0 + np.tanh(0.5 * x))


class NumpyRecurrentPolicy(NumpyPolicy):
    """The deterministic actor of a RecurrentPPO ``MlpLstmPolicy`` evaluated with numpy: the
    observation (normalised as for :class:`NumpyPolicy`) goes through the actor's LSTM, whose
    hidden state carries the episode so far, then through the feed-forward ``layers`` and the
    ``"clip"`` output, as sb3-contrib's ``predict(obs, state, episode_start,
    deterministic=True)`` does.

    Each LSTM layer ``k`` is ``(w_ih, w_hh, b_ih, b_hh)`` as torch's ``nn.LSTM`` keeps it
    (gates in the order input, forget, cell, output: ``w_ih`` is ``(4 H, n_in)``, ``w_hh``
    ``(4 H, H)``); per step, with ``z = w_ih x + b_ih + w_hh h + b_hh`` split into
    ``z_i, z_f, z_g, z_o``: ``c <- sigmoid(z_f) c + sigmoid(z_i) tanh(z_g)``,
    ``h <- sigmoid(z_o) tanh(c)``; layer ``k``'s ``h`` is layer ``k + 1``'s input and the last
    one's is the feed-forward layers' input.

    The state ``(h, c)`` starts at zero and is kept between calls: call :meth:`reset` at each
    episode start (sb3-contrib's ``episode_start``). A call takes one observation or a batch
    of ``n`` (one per environment, kept separately); the batch size stays fixed within an
    episode. The other arguments are :class:`NumpyPolicy`'s (``frame_stack`` must be 1: the
    LSTM is the memory).
    """

    def __init__(self, lstm: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]],
                 layers: list[tuple], output: str, low: np.ndarray, high: np.ndarray,
                 meta: dict[str, Any] | None = None,
                 normalize: tuple[np.ndarray, np.ndarray, float, float] | None = None,
                 action_map: dict[str, Any] | None = None, frame_stack: int = 1) -> None:
        if not lstm:
            raise ValueError("a NumpyRecurrentPolicy needs at least one LSTM layer")
        if frame_stack != 1:
            raise ValueError(f"a recurrent policy takes frame_stack 1 (its LSTM is the memory), "
                             f"got {frame_stack!r}")
        self.lstm = [tuple(np.array(a, dtype=np.float32) for a in cell) for cell in lstm]
        if not all(np.all(np.isfinite(a)) for cell in self.lstm for a in cell):
            raise ValueError("the LSTM holds non-finite numbers")
        hidden = self.lstm[0][1].shape[1]
        size = self.lstm[0][0].shape[1]
        for k, (w_ih, w_hh, b_ih, b_hh) in enumerate(self.lstm):
            if w_ih.shape != (4 * hidden, size) or w_hh.shape != (4 * hidden, hidden) or \
                    b_ih.shape != (4 * hidden,) or b_hh.shape != (4 * hidden,):
                raise ValueError(f"LSTM layer {k}: expected w_ih {(4 * hidden, size)}, w_hh "
                                 f"{(4 * hidden, hidden)} and biases ({4 * hidden},), got "
                                 f"{w_ih.shape}, {w_hh.shape}, {b_ih.shape}, {b_hh.shape}")
            size = hidden
        self.hidden_size = int(hidden)
        self.n_lstm_layers = len(self.lstm)
        super().__init__(layers, output, low, high, meta, normalize, action_map, frame_stack)
        first = next(layer for layer in self.layers if layer[0] == "linear")
        if first[1].shape[1] != self.hidden_size:
            raise ValueError(f"the layers after the LSTM must take its {self.hidden_size} "
                             f"outputs, got {first[1].shape[1]}")
        # One product per layer and step: [x, h] @ [w_ih; w_hh]^T + (b_ih + b_hh).
        self._cells = [(np.concatenate([w_ih, w_hh], axis=1).T.copy(), b_ih + b_hh)
                       for w_ih, w_hh, b_ih, b_hh in self.lstm]
        self._state: tuple[np.ndarray, np.ndarray] | None = None

    def _input_size(self, linear: list[tuple]) -> int:
        return int(self.lstm[0][0].shape[1])

    @property
    def stateful(self) -> bool:
        return True

    @property
    def state(self) -> tuple[np.ndarray, np.ndarray] | None:
        """The LSTM's ``(h, c)``, each ``(n_lstm_layers, n, hidden_size)``, as sb3-contrib's
        ``predict`` returns it (None at an episode start)."""
        return self._state

    def reset(self) -> None:
        """Start an episode: the LSTM's state back to zero."""
        super().reset()
        self._state = None

    def network_action(self, x: np.ndarray) -> np.ndarray:
        """The action for the observation ``x`` (one or a batch), advancing the LSTM's state
        by one step (see the class docstring), before any action map."""
        x = self._network_input(x)
        single = x.ndim == 1
        out = x[None] if single else x
        n = len(out)
        if self._state is None:
            zeros = np.zeros((self.n_lstm_layers, n, self.hidden_size), dtype=np.float32)
            h, c = zeros, zeros
        else:
            h, c = self._state
            if h.shape[1] != n:
                raise ValueError(f"a batch of {n} observations in an episode of batches of "
                                 f"{h.shape[1]}: call reset() at each episode start")
        new_h, new_c = np.empty_like(h), np.empty_like(c)
        H = self.hidden_size
        for k, (w, b) in enumerate(self._cells):
            z = np.concatenate([out, h[k]], axis=1) @ w + b
            ck = _sigmoid(z[:, H:2 * H]) * c[k] + _sigmoid(z[:, :H]) * np.tanh(z[:, 2 * H:3 * H])
            out = _sigmoid(z[:, 3 * H:]) * np.tanh(ck)
            new_h[k], new_c[k] = out, ck
        self._state = (new_h, new_c)
        action = self._head(out)
        return action[0] if single else action

    @classmethod
    def from_sb3(cls, model: Any, meta: dict[str, Any] | None = None,
                 vec_normalize: Any = None, action_map: dict[str, Any] | None = None,
                 frame_stack: int = 1) -> NumpyRecurrentPolicy:
        """Copy the deterministic actor of a RecurrentPPO model (``MlpLstmPolicy`` on a flat
        Box observation), with ``vec_normalize``'s observation statistics and the
        ``action_map`` as :meth:`NumpyPolicy.from_sb3`. Raises ``ValueError`` for anything
        else (other models, bidirectional or projected LSTMs, squashed outputs)."""
        name = type(model).__name__
        if not _is_recurrent(model):
            raise ValueError(f"a {name} model has no LSTM policy; use NumpyPolicy.from_sb3")
        policy = model.policy
        if getattr(policy, "squash_output", False):
            raise ValueError("squashed actor-critic policies are not supported")
        _check_flatten(policy.pi_features_extractor)
        lstm = policy.lstm_actor
        if lstm.bidirectional or getattr(lstm, "proj_size", 0) or lstm.batch_first:
            raise ValueError("only unidirectional LSTMs without projection are supported")
        cells = []
        for k in range(lstm.num_layers):
            w_ih = getattr(lstm, f"weight_ih_l{k}").detach().cpu().numpy()
            w_hh = getattr(lstm, f"weight_hh_l{k}").detach().cpu().numpy()
            if lstm.bias:
                b_ih = getattr(lstm, f"bias_ih_l{k}").detach().cpu().numpy()
                b_hh = getattr(lstm, f"bias_hh_l{k}").detach().cpu().numpy()
            else:
                b_ih = b_hh = np.zeros(w_ih.shape[0], dtype=np.float32)
            cells.append((w_ih, w_hh, b_ih, b_hh))
        layers = _numpy_layers([*policy.mlp_extractor.policy_net, policy.action_net], name)
        return cls(cells, layers, "clip", model.action_space.low, model.action_space.high,
                   {"algorithm": name, **(meta or {})}, _normalize_of(vec_normalize),
                   action_map, frame_stack)

    def _save_extra(self, header: dict[str, Any], arrays: dict[str, np.ndarray]) -> None:
        header["lstm"] = {"layers": self.n_lstm_layers, "hidden_size": self.hidden_size}
        for k, cell in enumerate(self.lstm):
            for part, a in zip(("w_ih", "w_hh", "b_ih", "b_hh"), cell):
                arrays[f"lstm_{part}{k}"] = a


#: The layer kinds of a :class:`NumpyPolicy` and the arguments each takes.
_LAYER_KINDS = {"linear": 2, "tanh": 0, "relu": 0, "hardtanh": 2}


def _check_layers(layers: list[tuple]) -> None:
    """Refuse layers that would fail or give NaN only when called: unknown kinds, weights
    that are not 2-D with a bias of their output size, consecutive linear layers whose sizes
    do not chain, non-finite numbers."""
    previous = None
    for i, (kind, *args) in enumerate(layers):
        if _LAYER_KINDS.get(kind) != len(args):
            raise ValueError(f"layer {i}: unknown kind {kind!r} with {len(args)} argument(s); "
                             f"known: {_LAYER_KINDS}")
        if not all(np.all(np.isfinite(a)) for a in args):
            raise ValueError(f"layer {i} ({kind}) holds non-finite numbers")
        if kind != "linear":
            continue
        weight, bias = args
        if weight.ndim != 2 or bias.shape != (weight.shape[0],):
            raise ValueError(f"layer {i}: a linear layer needs a 2-D weight and a bias of its "
                             f"output size, got {weight.shape} and {bias.shape}")
        if previous is not None and weight.shape[1] != previous:
            raise ValueError(f"layer {i}: takes {weight.shape[1]} inputs, the layer before "
                             f"gives {previous}")
        previous = weight.shape[0]


def _numpy_layers(mods: list[Any], name: str) -> list[tuple]:
    """The :class:`NumpyPolicy` layers of the torch modules ``mods`` (of a ``name`` model)."""
    from torch import nn

    layers: list[tuple] = []
    for m in mods:
        kind = type(m).__name__
        if isinstance(m, nn.Linear):
            layers.append(("linear", m.weight.detach().cpu().numpy(),
                           m.bias.detach().cpu().numpy()))
        elif kind in _ACTIVATIONS:
            act = _ACTIVATIONS[kind]
            if act == "hardtanh":
                layers.append(("hardtanh", np.float32(m.min_val), np.float32(m.max_val)))
            elif act is not None:
                layers.append((act,))
        else:
            raise ValueError(f"unsupported layer {kind} in the {name} actor")
    return layers


def _normalize_of(vec_normalize: Any, key: str | None = None
                  ) -> tuple[np.ndarray, np.ndarray, float, float] | None:
    """The observation statistics of a ``VecNormalize`` (None without one, or when it does
    not normalise observations); of the entry ``key`` of a ``Dict`` observation."""
    if vec_normalize is None or not vec_normalize.norm_obs:
        return None
    rms = vec_normalize.obs_rms if key is None else vec_normalize.obs_rms[key]
    return rms.mean, rms.var, vec_normalize.clip_obs, vec_normalize.epsilon


def _check_flatten(extractor: Any) -> None:
    if type(extractor).__name__ != "FlattenExtractor":
        raise ValueError(f"only flat Box observations (FlattenExtractor) are supported, got "
                         f"{type(extractor).__name__}")


class SB3Policy:
    """A stable-baselines3 model's ``predict`` as a policy (for networks that
    :class:`NumpyPolicy` cannot copy). For a recurrent model (RecurrentPPO) it keeps the
    LSTM state between calls: call :meth:`reset` at each episode start."""

    def __init__(self, model: Any, deterministic: bool = True) -> None:
        self.model = model
        self.deterministic = deterministic
        self.recurrent = _is_recurrent(model)
        self._state: tuple[np.ndarray, ...] | None = None

    @property
    def stateful(self) -> bool:
        """Whether the policy remembers earlier calls (a recurrent model)."""
        return self.recurrent

    def reset(self) -> None:
        """Start an episode (the LSTM state back to zero)."""
        self._state = None

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        if not self.recurrent:
            return self.model.predict(obs, deterministic=self.deterministic)[0]
        action, self._state = self.model.predict(obs, state=self._state,
                                                 deterministic=self.deterministic)
        return action


def load_sb3(path: str | os.PathLike, algorithm: str | None = None, *, trust: bool = False,
             observation_space: Any = None, action_space: Any = None, policy_class: Any = None,
             hyperparams: dict[str, Any] | None = None, **kwargs: Any) -> Any:
    """Load a stable-baselines3 (or sb3-contrib RecurrentPPO) model.

    By default nothing in the file is unpickled (:func:`agents.model_files.load_sb3_safely`):
    the spaces are ``observation_space`` and ``action_space``, else those of ``kwargs["env"]``,
    else those of the training run whose ``config.json`` lies beside the file (or above
    ``checkpoints/``); the policy class is ``policy_class``, else the run's (a privileged
    critic's), else the algorithm's ``MlpPolicy``; schedules come from ``hyperparams``, else
    the run's, else the defaults. With ``trust=True`` the file is loaded as stable-baselines3
    loads it, unpickling its serialized entries: only for files from a source you trust.

    ``algorithm`` (one of :data:`SB3_ALGORITHMS`, any spelling :func:`algorithm_name` takes)
    is read from the run's ``config.json`` when not given, otherwise each is tried in turn
    (RecurrentPPO only where sb3-contrib is installed). Raises ``FileNotFoundError``,
    :class:`~agents.model_files.UnsafeFileError` (the file needs unpickling, or is over the
    size limits) or ``ValueError`` (not a model of any algorithm, or not one acting in the
    given spaces)."""
    from agents.model_files import UnsafeFileError, _model_data, load_sb3_safely

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"no model at {path}")
    run = _run_config(path)
    if algorithm is None:
        algorithm = run.get("algorithm")
    if not trust:
        _model_data(path)  # size limits and format, before anything else
        env = kwargs.get("env")
        if observation_space is None and env is not None:
            observation_space, action_space = env.observation_space, env.action_space
        if observation_space is None:
            if not run:
                raise UnsafeFileError(
                    f"{path}: without the training run's config.json beside it, loading "
                    "without unpickling needs the spaces it acts in (observation_space and "
                    "action_space, or env); or trust=True: unpickling runs whatever code the "
                    "file names, so only for files from a source you trust")
            observation_space, action_space = _run_spaces(run)
        if policy_class is None and run.get("critic") == "privileged":
            from agents.privileged import PrivilegedActorCriticPolicy

            policy_class = PrivilegedActorCriticPolicy
        if hyperparams is None:
            hyperparams = _run_hyperparams(run)
    device = kwargs.pop("device", "cpu")
    errors = []
    for name in ([algorithm] if algorithm is not None else _LOAD_ORDER):
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


def _run_spaces(run: dict[str, Any]) -> tuple[Any, Any]:
    """The observation and action spaces a training run's learner had (from its
    ``config.json``: environment, action map, frame stack, critic)."""
    from agents.training import MATCH_ID, goalkeeper_env_fn

    env_kwargs = dict(run.get("env_kwargs") or {})
    if run.get("env_id") == MATCH_ID:
        from agents.multiagent import MatchVecEnv

        venv = MatchVecEnv(env_kwargs, 1, run.get("learner", "blue"),
                           None if run.get("learner") == "both" else "idle")
    else:
        venv = goalkeeper_env_fn(env_kwargs, run.get("actions", "native"),
                                 int(run.get("frame_stack", 1)), run.get("critic", "shared"))()
    try:
        return venv.observation_space, venv.action_space
    finally:
        venv.close()


def _run_hyperparams(run: dict[str, Any]) -> dict[str, Any]:
    """A training run's hyperparameters over the algorithm's defaults (``config.json``)."""
    from agents.training import merged_hyperparams

    given = dict(run.get("hyperparams") or {})
    algorithm = run.get("algorithm")
    return merged_hyperparams(algorithm, given) if algorithm else given


def learner_spaces(env: Any, run: dict[str, Any]) -> tuple[Any, Any]:
    """The spaces of the learner of training run ``run`` (its ``config.json``) acting in
    ``env`` (a Goalkeeper-v0): ``env``'s, behind the run's action map, frame stack and
    critic."""
    from agents.wrappers import wrap_learner

    action_map = run.get("action_map")
    learner = wrap_learner(env, action_map["kind"] if action_map else "native",
                           int(run.get("frame_stack", 1)), run.get("critic", "shared"))
    return learner.observation_space, learner.action_space


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
    (:func:`~agents.model_files.read_vecnormalize`, no pickle), else with ``trust=True``
    stable-baselines3's pickled ``.pkl`` (a ``VecNormalize`` without its environments).
    A ``.pkl`` alone without ``trust`` raises :class:`~agents.model_files.UnsafeFileError`;
    None when there are none."""
    from agents.model_files import TRUST_HELP, UnsafeFileError, read_vecnormalize

    stats = vecnormalize_path(model_path)
    if stats.exists():
        return read_vecnormalize(stats)
    pickled = vecnormalize_path(model_path, ".pkl")
    if not pickled.exists():
        return None
    if not trust:
        raise UnsafeFileError(f"the normalisation statistics of {model_path} are only in "
                              f"{pickled}, a pickle; {TRUST_HELP}")
    import pickle

    from agents.model_files import _check_size

    _check_size(pickled)
    try:
        with open(pickled, "rb") as fh:
            return pickle.load(fh)
    except Exception as err:
        raise ValueError(f"{pickled} could not be read ({type(err).__name__}: {err})"
                         ) from None


def _run_config(model_path: Path) -> dict[str, Any]:
    """The ``config.json`` of the training run that saved ``model_path`` (the model's folder
    or, for checkpoints, its parent); empty if there is none."""
    for folder in (model_path.parent, model_path.parent.parent):
        config = folder / "config.json"
        if config.is_file():
            try:
                data = json.loads(config.read_text())
            except (ValueError, UnicodeDecodeError) as err:
                raise ValueError(f"{config} is not valid JSON ({err})") from None
            if not isinstance(data, dict):
                raise ValueError(f"{config} is not a training run's configuration")
            return data
    return {}


def make_policy(ref: str | os.PathLike | Callable, env: Any, trust: bool = False) -> Policy:
    """Resolve a policy reference (see the module docstring) for the environment ``env``
    (a Goalkeeper-v0, possibly wrapped). A callable is returned as it is. Policies with
    memory need :func:`reset_policy` at each episode start.

    Nothing in a file is unpickled unless ``trust`` (see :mod:`agents.model_files`): a
    ``.npz`` is arrays and JSON; a ``.zip`` is loaded by :func:`load_sb3` in the spaces of
    ``env`` as its run's ``config.json`` describes the learner, with the ``.npz``
    normalisation statistics beside it."""
    if callable(ref) and not isinstance(ref, (str, os.PathLike)):
        return ref
    ref = os.fspath(ref)
    if ref == "scripted":
        from soccer_env.envs.keeper import ScriptedGoalkeeper

        return ScriptedGoalkeeper.for_env(env)
    if ref == "idle":
        return IdlePolicy(int(np.prod(env.action_space.shape)))
    if ref.startswith("baseline:"):
        from agents.baselines import load_baseline

        return load_baseline(ref.split(":", 1)[1])
    path = Path(ref)
    if path.is_dir():  # a training run: its numpy policy, else its model
        path = path / ("final_policy.npz" if (path / "final_policy.npz").exists()
                       else "final_model.zip")
    if path.suffix == ".npz":
        policy: Any = NumpyPolicy.load(path)
    elif path.suffix == ".zip":
        run = _run_config(path)
        obs_space, act_space = learner_spaces(env, run)
        model = load_sb3(path, trust=trust, observation_space=obs_space,
                         action_space=act_space)
        norm = load_vecnormalize(path, trust)
        action_map = run.get("action_map")
        frame_stack = int(run.get("frame_stack", 1))
        try:
            policy = NumpyPolicy.from_sb3(model, vec_normalize=norm, action_map=action_map,
                                          frame_stack=frame_stack)
        except ValueError:
            if norm is not None or action_map is not None or frame_stack > 1:
                raise ValueError(f"{path} was trained behind VecNormalize, an action map or a "
                                 "frame stack and its network cannot be copied into numpy; "
                                 "load it with load_sb3, agents.model_files.vecnormalize_on "
                                 "and agents.wrappers") from None
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
