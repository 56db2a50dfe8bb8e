"""Trained networks evaluated with numpy: :class:`NumpyPolicy` (feed-forward, with an optional
frame stack) and :class:`NumpyRecurrentPolicy` (an LSTM in front), saved and loaded as
``.npz`` files of arrays and a JSON header (nothing pickled).

Trained networks are evaluated through these numpy copies of the actor's deterministic path
(:func:`agents.sb3.policies.numpy_copy` makes them from stable-baselines3 models): a
stable-baselines3 ``predict`` costs about 0.3 ms per call on a 2-core machine, more than the
environment step it drives, while the numpy copy costs about 20 us and needs neither torch nor
stable-baselines3 (so the shipped baselines run without the training extra).

Policies with memory (:class:`NumpyRecurrentPolicy`; a :class:`NumpyPolicy` trained on
stacked frames, which keeps its own history of observations) act on one episode at a time:
call :func:`~agents.policies.base.reset_policy` at each episode start.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from agents.policies.action_maps import POLICY_MAPS, action_to_command
from agents.policies.files import UnsafeFileError, check_npz, parse_json

__all__ = ["NumpyPolicy", "NumpyRecurrentPolicy", "widen"]


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
            wrappers of :mod:`agents.policies.wrappers`: its outputs become the native command
            with :func:`~agents.policies.action_maps.action_to_command`, from the pose in the
            observation.
        frame_stack: the number of observations the network reads at once (a policy trained
            behind :func:`~agents.policies.wrappers.stack_frames`): the policy keeps the last
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
        from its header before it is read (:func:`agents.policies.files.check_npz`). Raises
        ``ValueError`` naming the file for a damaged, foreign or inconsistent one."""
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
            header = parse_json(str(data["header"]), f"{path}: header")
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


def widen(policy: NumpyPolicy, obs_size: int, action_map: dict[str, Any] | None = None
          ) -> NumpyPolicy:
    """``policy`` reading observations of ``obs_size`` entries whose first
    ``policy.obs_size`` are the ones it was trained on: the first linear layer weighs the added
    entries by zero and their statistics are mean 0, variance 1, so
    ``widen(p, n).network_action(x) == p.network_action(x[:, :p.obs_size])`` whatever the added
    entries hold. A team trained without the game flow so reads the game flow's observation,
    whose game block comes last. ``action_map`` replaces the policy's (the map's parameters of
    the new observation); the meta is copied.

    Raises ``ValueError`` for a policy with memory (recurrent or frame-stacked), or an
    ``obs_size`` smaller than the policy's.
    """
    if type(policy) is not NumpyPolicy or policy.frame_stack != 1:
        raise ValueError("widen takes feed-forward policies of single observations")
    if isinstance(obs_size, bool) or not isinstance(obs_size, (int, np.integer)) \
            or obs_size < policy.obs_size:
        raise ValueError(f"obs_size must be an integer >= the policy's {policy.obs_size}, got "
                         f"{obs_size!r}")
    extra = int(obs_size) - policy.obs_size
    layers, first = [], True
    for kind, *rest in policy.layers:
        if kind == "linear" and first:
            w, b = rest
            rest = [np.concatenate([w, np.zeros((w.shape[0], extra), w.dtype)], 1), b]
            first = False
        layers.append((kind, *rest))
    normalize = None
    if policy.normalize is not None:
        mean, var, clip, eps = policy.normalize
        normalize = (np.concatenate([mean, np.zeros(extra)]),
                     np.concatenate([var, np.ones(extra)]), clip, eps)
    return NumpyPolicy(layers, policy.output, policy.low, policy.high, meta=policy.meta,
                       normalize=normalize,
                       action_map=policy.action_map if action_map is None else action_map)


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
