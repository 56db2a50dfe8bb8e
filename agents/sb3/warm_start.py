"""Start a stable-baselines3 model from a numpy policy: the inverse of
:func:`agents.sb3.policies.numpy_copy` for the actor of a PPO or A2C MLP policy
(:func:`load_actor`), and the actor held fixed while the fresh critic learns
(:class:`FreezeActor`).

A team or keeper trained in one setting continues in another whose observation only adds
entries at the end (the match's game block under the game flow adds the referee's state to
the truth-trained team's observation): the added entries' input weights start at zero, so
the model's deterministic action is the file's until training moves them.

torch is imported when a function runs, not with this module.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.running_mean_std import RunningMeanStd

from agents.policies.numpy_policy import NumpyPolicy, widen

__all__ = ["load_actor", "FreezeActor", "HeldRunningMeanStd", "actor_parameters"]


def actor_parameters(model: Any) -> list[Any]:
    """The torch parameters of a PPO or A2C model's actor: its policy network, its action
    head and the log standard deviation of its Gaussian."""
    policy = model.policy
    return [*policy.mlp_extractor.policy_net.parameters(),
            *policy.action_net.parameters(), policy.log_std]


class HeldRunningMeanStd(RunningMeanStd):
    """Running observation statistics whose first ``held`` entries stay at the values they
    are given: :meth:`update` moves only the entries after them. A network trained behind
    fixed statistics reads its inputs through them; statistics that follow a new setting's
    observations (another vision preset, the game flow's stoppages) change what the network
    computes from the same observation, a change no gradient chose."""

    def __init__(self, mean: np.ndarray, var: np.ndarray, held: int,
                 count: float = 1e6) -> None:
        mean, var = np.asarray(mean, np.float64), np.asarray(var, np.float64)
        if mean.shape != var.shape or mean.ndim != 1:
            raise ValueError(f"mean and var must be vectors of one size, got shapes "
                             f"{mean.shape} and {var.shape}")
        if not 0 <= held <= mean.size:
            raise ValueError(f"held must be within 0..{mean.size}, got {held}")
        super().__init__(shape=mean.shape)
        self.mean, self.var, self.count = mean.copy(), var.copy(), float(count)
        self.held = int(held)
        self.held_mean, self.held_var = mean[:held].copy(), var[:held].copy()

    def update(self, arr: np.ndarray) -> None:
        super().update(arr)
        self.mean[:self.held] = self.held_mean
        self.var[:self.held] = self.held_var


def load_actor(model: Any, policy: NumpyPolicy, vec_normalize: Any = None,
               count: float = 1e6, hold: bool = False) -> None:
    """Set the actor of ``model`` (PPO or A2C, an MLP policy on a flat Box observation, no
    action squashing) to the network of ``policy``, and with ``vec_normalize`` (the
    ``VecNormalize`` the model trains behind) its observation statistics to the policy's.

    The model's observation may be longer than the policy's (entries added at the end): the
    first layer's weights on the added entries are set to zero, and their statistics to mean 0
    and variance 1, so the model's deterministic action equals ``policy.network_action`` on the
    shared entries. ``count`` is the weight of the policy's statistics against the running
    statistics' updates (:class:`~stable_baselines3.common.running_mean_std.RunningMeanStd`
    counts observations: 1e6 lets a few million steps move them). With ``hold`` the policy's
    statistics stay as they are while training runs and only the added entries' move
    (:class:`HeldRunningMeanStd`). The critic and the log standard deviation are left as they
    are.

    Raises ``ValueError`` naming what differs: the layers (kinds, sizes, activations), the
    action size, the observation size (the model's shorter than the policy's), a frame stack,
    or a normalising policy without ``vec_normalize`` (or the reverse).
    """
    import torch

    net = getattr(model.policy, "mlp_extractor", None)
    if net is None or getattr(model.policy, "squash_output", False):
        raise ValueError(f"load_actor takes PPO or A2C models with an MLP policy, got a "
                         f"{type(model).__name__}")
    if policy.frame_stack != 1:
        raise ValueError(f"policy has frame_stack {policy.frame_stack}; load_actor takes "
                         "policies of single observations")
    mods = [*net.policy_net, model.policy.action_net]
    kinds = [type(m).__name__.lower() for m in mods]
    theirs = [layer[0] for layer in policy.layers]
    if kinds != theirs:
        raise ValueError(f"the model's actor has layers {kinds}, the policy {theirs}")
    n_obs = int(np.prod(model.observation_space.shape))
    if n_obs < policy.obs_size:
        raise ValueError(f"the model's observation has {n_obs} entries, fewer than the "
                         f"policy's {policy.obs_size}")
    n_held = policy.obs_size
    if (vec_normalize is None) != (policy.normalize is None):
        raise ValueError("a policy trained behind VecNormalize needs vec_normalize, and only "
                         "such a policy takes it")
    policy = widen(policy, n_obs)
    weights = [layer[1:] for layer in policy.layers if layer[0] == "linear"]
    linears = [m for m in mods if isinstance(m, torch.nn.Linear)]
    for k, (m, (w, b)) in enumerate(zip(linears, weights)):
        if tuple(m.weight.shape) != w.shape:
            raise ValueError(f"linear layer {k} of the model has shape "
                             f"{tuple(m.weight.shape)}, the policy's {w.shape}")
        with torch.no_grad():
            m.weight.copy_(torch.as_tensor(w))
            m.bias.copy_(torch.as_tensor(b))
    if vec_normalize is not None:
        mean, var, _, _ = policy.normalize
        if hold:
            vec_normalize.obs_rms = HeldRunningMeanStd(mean, var, n_held, count)
        else:
            rms = vec_normalize.obs_rms
            rms.mean, rms.var, rms.count = mean.copy(), var.copy(), float(count)


class FreezeActor(BaseCallback):
    """Hold the actor of a PPO or A2C model fixed for the updates on its first ``steps``
    steps (its parameters take no gradient), while the critic learns the value of the policy
    it starts from; from the first update on a rollout that ends past ``steps``, let it learn.
    A critic that starts from scratch under an actor that already plays would otherwise push
    the actor with advantages that are noise."""

    def __init__(self, steps: int) -> None:
        super().__init__()
        if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 0:
            raise ValueError(f"steps must be an integer >= 0, got {steps!r}")
        self.steps = int(steps)
        self.frozen = False

    def _set(self, frozen: bool) -> None:
        for p in actor_parameters(self.model):
            p.requires_grad_(not frozen)
            if frozen:
                p.grad = None
        self.frozen = frozen

    def _on_training_start(self) -> None:
        if self.num_timesteps < self.steps:
            self._set(True)

    def _on_rollout_end(self) -> None:
        if self.frozen and self.num_timesteps > self.steps:
            self._set(False)

    def _on_step(self) -> bool:
        return True
