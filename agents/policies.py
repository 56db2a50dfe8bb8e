"""Policies as plain callables, and loading them by name or path.

A policy maps one observation (a float32 vector) to one action; :class:`NumpyPolicy` also
takes a batch ``(n, obs_dim) -> (n, act_dim)``. Policies are referred to by strings so that
evaluation workers can rebuild them in their own processes (see :func:`make_policy`):

* ``"scripted"``: :class:`~agents.ScriptedGoalkeeper`;
* ``"idle"``: a keeper that stands still (all-zero actions);
* ``"baseline:NAME"``: a policy shipped in the package (:data:`agents.baselines.BASELINES`);
* a path to a ``.npz`` written by :meth:`NumpyPolicy.save`;
* a path to a stable-baselines3 ``.zip`` (PPO, A2C, SAC, TD3, DDPG; with the ``VecNormalize``
  statistics saved beside it, see :func:`vecnormalize_path`, and the action map recorded in
  its run's ``config.json``), or a training run's folder (its ``final_policy.npz``, else
  ``final_model.zip``).

Trained networks are evaluated through :class:`NumpyPolicy`, a numpy copy of the actor's
deterministic path: a stable-baselines3 ``predict`` costs about 0.3 ms per call on a 2-core
machine, more than the environment step it drives, while the numpy copy costs about 20 us and
needs neither torch nor stable-baselines3 (so the shipped baselines run without the training
extra).
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any, Protocol

import numpy as np

__all__ = ["Policy", "NumpyPolicy", "SB3Policy", "IdlePolicy", "make_policy", "load_sb3",
           "vecnormalize_path", "SB3_ALGORITHMS", "POLICY_NAMES"]

#: Algorithms whose saved models :func:`load_sb3` opens, in the order it tries them.
SB3_ALGORITHMS = ("PPO", "SAC", "TD3", "A2C", "DDPG")

#: Policy names that :func:`make_policy` resolves without a file.
POLICY_NAMES = ("scripted", "idle")


class Policy(Protocol):
    """One observation in, one action out."""

    def __call__(self, obs: np.ndarray) -> np.ndarray: ...


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
        low, high: the action box.
        meta: free-form description (algorithm, environment, training configuration), saved
            with the weights.
        normalize: ``(mean, var, clip, epsilon)`` of a policy trained behind
            stable-baselines3's ``VecNormalize``: observations become
            ``clip((obs - mean) / sqrt(var + epsilon), -clip, clip)`` first.
        action_map: ``None`` (the network's output is the environment's action) or
            ``{"kind": ..., "params": {...}}`` for a keeper trained through one of the
            wrappers of :mod:`agents.wrappers`: its outputs become the native command with
            :func:`~agents.wrappers.action_to_command`, from the pose in the observation.

    The policy owns copies of every array: it does not follow the model it was copied from.
    """

    def __init__(self, layers: list[tuple], output: str, low: np.ndarray, high: np.ndarray,
                 meta: dict[str, Any] | None = None,
                 normalize: tuple[np.ndarray, np.ndarray, float, float] | None = None,
                 action_map: dict[str, Any] | None = None) -> None:
        from agents.wrappers import ACTION_MAPS

        if output not in ("clip", "tanh", "scale"):
            raise ValueError(f"output must be 'clip', 'tanh' or 'scale', got {output!r}")
        if action_map is not None and (action_map.get("kind") not in ACTION_MAPS):
            raise ValueError(f"action_map kind must be one of {list(ACTION_MAPS)}, got "
                             f"{action_map!r}")
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
        self.obs_size = int(linear[0][1].shape[1])
        self.action_size = int(linear[-1][1].shape[0])
        if self.low.shape != (self.action_size,) or self.high.shape != (self.action_size,):
            raise ValueError(f"low and high must have shape ({self.action_size},)")
        if self.action_map is not None and \
                self.action_size != ACTION_MAPS[self.action_map["kind"]]:
            raise ValueError(f"a {self.action_map['kind']!r} policy has "
                             f"{ACTION_MAPS[self.action_map['kind']]} outputs, got "
                             f"{self.action_size}")
        if self.normalize is not None:
            mean, var, clip, eps = self.normalize
            if mean.shape != (self.obs_size,) or var.shape != (self.obs_size,):
                raise ValueError(f"normalize mean and var must have shape ({self.obs_size},)")
            self._shift, self._scale = mean, 1.0 / np.sqrt(var + eps)
        # Transposed weights for row-vector products.
        self._ops = [(k, rest[0].T.copy(), rest[1]) if k == "linear" else (k, *rest)
                     for k, *rest in self.layers]

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        action = self.network_action(obs)
        if self.action_map is not None:
            from agents.wrappers import action_to_command

            return action_to_command(self.action_map["kind"], obs, action,
                                     self.action_map["params"] or None)
        return action

    def network_action(self, obs: np.ndarray) -> np.ndarray:
        """The network's action for ``obs`` (one observation or a batch): the action the
        stable-baselines3 model predicts deterministically, before any action map turns it
        into the native command (for a policy without an action map, what calling it
        returns)."""
        x = np.asarray(obs, dtype=np.float32)
        if x.shape[-1:] != (self.obs_size,) or x.ndim > 2:
            raise ValueError(f"obs must have shape ({self.obs_size},) or (n, {self.obs_size}), "
                             f"got {x.shape}")
        if self.normalize is not None:
            clip = self.normalize[2]
            x = np.clip((x - self._shift) * self._scale, -clip, clip).astype(np.float32)
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
                 vec_normalize: Any = None, action_map: dict[str, Any] | None = None
                 ) -> NumpyPolicy:
        """Copy the deterministic actor of a stable-baselines3 model (MLP policies of PPO,
        A2C, SAC, TD3, DDPG on a flat Box observation), with the observation statistics of
        ``vec_normalize`` (a ``VecNormalize`` it was trained behind) if given, and the
        ``action_map`` it was trained through (see :mod:`agents.wrappers`). Raises
        ``ValueError`` for anything else (image or dict observations, custom networks,
        squashed actor-critic policies). gSDE exploration does not change the deterministic
        action, so models trained with it copy too."""
        from torch import nn

        policy = model.policy
        low, high = model.action_space.low, model.action_space.high
        name = type(model).__name__
        if hasattr(policy, "mlp_extractor"):  # PPO, A2C
            if getattr(policy, "squash_output", False):
                raise ValueError("squashed actor-critic policies are not supported")
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
        normalize = None
        if vec_normalize is not None and vec_normalize.norm_obs:
            rms = vec_normalize.obs_rms
            normalize = (rms.mean, rms.var, vec_normalize.clip_obs, vec_normalize.epsilon)
        return cls(layers, output, low, high, {"algorithm": name, **(meta or {})}, normalize,
                   action_map)

    def save(self, path: str | os.PathLike) -> Path:
        """Write the weights and description to ``path`` (``.npz``)."""
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
                                  "action_map": self.action_map}
        if self.normalize is not None:
            mean, var, clip, eps = self.normalize
            arrays["obs_mean"], arrays["obs_var"] = mean, var
            header["normalize"] = {"clip": clip, "epsilon": eps}
        np.savez_compressed(path, header=np.array(json.dumps(header)), low=self.low,
                            high=self.high, **arrays)
        return path

    @classmethod
    def load(cls, path: str | os.PathLike) -> NumpyPolicy:
        """Read a policy written by :meth:`save`."""
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
            return cls(layers, header["output"], data["low"], data["high"], header["meta"],
                       normalize, header.get("action_map"))


def _check_flatten(extractor: Any) -> None:
    if type(extractor).__name__ != "FlattenExtractor":
        raise ValueError(f"only flat Box observations (FlattenExtractor) are supported, got "
                         f"{type(extractor).__name__}")


class SB3Policy:
    """A stable-baselines3 model's ``predict`` as a policy (for networks that
    :class:`NumpyPolicy` cannot copy)."""

    def __init__(self, model: Any, deterministic: bool = True) -> None:
        self.model = model
        self.deterministic = deterministic

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        return self.model.predict(obs, deterministic=self.deterministic)[0]


def load_sb3(path: str | os.PathLike, algorithm: str | None = None, **kwargs: Any) -> Any:
    """Load a stable-baselines3 model. ``algorithm`` (one of :data:`SB3_ALGORITHMS`) is read
    from a training run's ``config.json`` beside the file when not given, otherwise each is
    tried in turn."""
    import stable_baselines3 as sb3

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"no model at {path}")
    if algorithm is None:
        cfg = path.parent / "config.json"
        if cfg.exists():
            algorithm = json.loads(cfg.read_text()).get("algorithm")
    if algorithm is not None:
        algorithm = algorithm.upper()
        if algorithm not in SB3_ALGORITHMS:
            raise ValueError(f"algorithm must be one of {list(SB3_ALGORITHMS)}, got "
                             f"{algorithm!r}")
        return getattr(sb3, algorithm).load(path, device="cpu", **kwargs)
    errors = []
    for name in SB3_ALGORITHMS:
        try:
            return getattr(sb3, name).load(path, device="cpu", **kwargs)
        except Exception as exc:  # wrong algorithm for this file: try the next
            errors.append(f"{name}: {type(exc).__name__}")
    raise ValueError(f"{path} is not a model of any of {list(SB3_ALGORITHMS)} ({errors})")


def vecnormalize_path(model_path: str | os.PathLike) -> Path:
    """Where a training run keeps the ``VecNormalize`` statistics of a saved model:
    ``final_model.zip`` -> ``final_vecnormalize.pkl`` (also ``best_``), and
    ``model_<N>_steps.zip`` -> ``model_vecnormalize_<N>_steps.pkl`` (checkpoints, as
    stable-baselines3's ``CheckpointCallback`` names them)."""
    path = Path(model_path)
    stem = path.stem
    if stem.endswith("_model"):
        name = stem[: -len("model")] + "vecnormalize"
    elif stem.startswith("model_") and stem.endswith("_steps"):
        name = "model_vecnormalize_" + stem[len("model_"):]
    else:
        name = stem + "_vecnormalize"
    return path.with_name(name + ".pkl")


def _load_vecnormalize(model_path: Path) -> Any:
    """The ``VecNormalize`` saved beside a model, if any (without its environments)."""
    import pickle

    stats = vecnormalize_path(model_path)
    if not stats.exists():
        return None
    with open(stats, "rb") as fh:
        return pickle.load(fh)


def _run_action_map(model_path: Path) -> dict[str, Any] | None:
    """The learner's action map recorded in the ``config.json`` of the training run that
    saved ``model_path`` (the model's folder or, for checkpoints, its parent)."""
    for folder in (model_path.parent, model_path.parent.parent):
        config = folder / "config.json"
        if config.is_file():
            return json.loads(config.read_text()).get("action_map")
    return None


def make_policy(ref: str | os.PathLike | Callable, env: Any) -> Policy:
    """Resolve a policy reference (see the module docstring) for the environment ``env``
    (a Goalkeeper-v0, possibly wrapped). A callable is returned as it is."""
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
        model = load_sb3(path)
        norm = _load_vecnormalize(path)
        action_map = _run_action_map(path)
        try:
            policy = NumpyPolicy.from_sb3(model, vec_normalize=norm, action_map=action_map)
        except ValueError:
            if norm is not None or action_map is not None:
                raise ValueError(f"{path} was trained behind VecNormalize or an action map "
                                 "and its network cannot be copied into numpy; load it with "
                                 "stable-baselines3, VecNormalize.load and agents.wrappers"
                                 ) from None
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
