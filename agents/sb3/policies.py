"""Policies from stable-baselines3 models: the numpy copy of a trained actor
(:func:`numpy_copy`, a :class:`~agents.policies.numpy_policy.NumpyPolicy` or
:class:`~agents.policies.numpy_policy.NumpyRecurrentPolicy` that runs without torch), and a
model's own ``predict`` as a policy (:class:`SB3Policy`, for networks numpy cannot copy).

The copy reads the model's torch modules (torch is imported when a copy is made, not with
this module).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from agents.policies.numpy_policy import NumpyPolicy, NumpyRecurrentPolicy
from agents.sb3.algorithms import is_recurrent

__all__ = ["numpy_copy", "recurrent_numpy_copy", "SB3Policy"]

#: The torch activations a copy takes and the :class:`~agents.policies.numpy_policy.NumpyPolicy`
#: layer kind each becomes (None: no layer).
_ACTIVATIONS = {"Tanh": "tanh", "ReLU": "relu", "Hardtanh": "hardtanh", "Identity": None,
                "Flatten": None}


def numpy_copy(model: Any, meta: dict[str, Any] | None = None, vec_normalize: Any = None,
               action_map: dict[str, Any] | None = None, frame_stack: int = 1) -> NumpyPolicy:
    """Copy the deterministic actor of a stable-baselines3 model (MLP policies of PPO,
    A2C, SAC, TD3, DDPG on a flat Box observation; a RecurrentPPO LSTM policy gives a
    :class:`~agents.policies.numpy_policy.NumpyRecurrentPolicy`), with the observation statistics of
    ``vec_normalize`` (a ``VecNormalize`` it was trained behind) if given, the
    ``action_map`` it was trained through (see :mod:`agents.policies.action_maps`) and the
    ``frame_stack`` of its observations (see :func:`~agents.policies.wrappers.stack_frames`).
    Raises ``ValueError`` for anything else (image or dict observations, custom networks,
    squashed actor-critic policies). gSDE exploration does not change the deterministic
    action, so models trained with it copy too."""
    from torch import nn

    if is_recurrent(model):
        return recurrent_numpy_copy(model, meta, vec_normalize, action_map, frame_stack)
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
    return NumpyPolicy(_numpy_layers(mods, name), output, low, high,
                       {"algorithm": name, **(meta or {})}, _normalize_of(vec_normalize, key),
                       action_map, frame_stack)


def recurrent_numpy_copy(model: Any, meta: dict[str, Any] | None = None,
                         vec_normalize: Any = None, action_map: dict[str, Any] | None = None,
                         frame_stack: int = 1) -> NumpyRecurrentPolicy:
    """Copy the deterministic actor of a RecurrentPPO model (``MlpLstmPolicy`` on a flat
    Box observation), with ``vec_normalize``'s observation statistics and the
    ``action_map`` as :func:`numpy_copy`. Raises ``ValueError`` for anything
    else (other models, bidirectional or projected LSTMs, squashed outputs)."""
    name = type(model).__name__
    if not is_recurrent(model):
        raise ValueError(f"a {name} model has no LSTM policy; use numpy_copy")
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
    return NumpyRecurrentPolicy(cells, layers, "clip", model.action_space.low,
                                model.action_space.high, {"algorithm": name, **(meta or {})},
                                _normalize_of(vec_normalize), action_map, frame_stack)


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
    :func:`numpy_copy` cannot copy). For a recurrent model (RecurrentPPO) it keeps the
    LSTM state between calls: call :meth:`reset` at each episode start."""

    def __init__(self, model: Any, deterministic: bool = True) -> None:
        self.model = model
        self.deterministic = deterministic
        self.recurrent = is_recurrent(model)
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
