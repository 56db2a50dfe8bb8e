"""The privileged critic's policy: an asymmetric actor-critic whose critic reads the true
state in training while the actor reads only what the robot perceives.

Under noisy, delayed perception the value of a state is hard to learn from the belief alone:
two beliefs that look alike may hide a shot that is about to go in and one that is going wide.
A critic is only needed in training, so it may read the truth (Pinto et al. 2018, "Asymmetric
actor critic for image-based robot learning"); the actor, which is all that is shipped, still
acts on the perceived observation alone.

* :class:`~agents.policies.wrappers.PrivilegedObservation` turns a single-agent environment's
  observation into a ``Dict`` with ``"actor"`` (the environment's own observation) and
  ``"critic"`` (the same layout built from the true state, followed by the actor's
  observation, so that the critic knows both the truth and what the actor believes).
* :class:`PrivilegedActorCriticPolicy` is a stable-baselines3 ``MultiInputActorCriticPolicy``
  whose actor network reads only ``"actor"`` and whose critic network reads only ``"critic"``
  (separate feature extractors and networks; nothing shared between them).

``soccer-env train --critic privileged`` trains PPO or A2C this way; the numpy copy of the
actor (:func:`agents.sb3.policies.numpy_copy`) takes the plain perceived observation, so the
shipped policy needs no truth. ``tests/agents/test_privileged.py`` checks that the actor's
output does not change when the critic's input does.

Imports torch and stable-baselines3 (the ``train`` extra).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import torch as th
from gymnasium import spaces
from stable_baselines3.common.policies import MultiInputActorCriticPolicy
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor, MlpExtractor
from torch import nn

from agents.policies.wrappers import ACTOR_KEY, CRITIC_KEY

__all__ = ["PrivilegedActorCriticPolicy", "KeyExtractor", "SplitMlpExtractor"]


class KeyExtractor(BaseFeaturesExtractor):
    """Features: one entry ``key`` of a ``Dict`` observation, as it is (a flat vector)."""

    def __init__(self, observation_space: spaces.Dict, key: str = ACTOR_KEY) -> None:
        super().__init__(observation_space, int(np.prod(observation_space[key].shape)))
        self.key = key

    def forward(self, observations: dict[str, th.Tensor]) -> th.Tensor:
        return th.flatten(observations[self.key], start_dim=1)


class SplitMlpExtractor(nn.Module):
    """Stable-baselines3's ``MlpExtractor`` with different input sizes for the policy network
    (``pi_dim``) and the value network (``vf_dim``); the two share nothing."""

    def __init__(self, pi_dim: int, vf_dim: int, net_arch: Any, activation_fn: type[nn.Module],
                 device: th.device | str = "auto") -> None:
        super().__init__()
        pi = MlpExtractor(pi_dim, net_arch, activation_fn, device)
        vf = MlpExtractor(vf_dim, net_arch, activation_fn, device)
        self.policy_net, self.value_net = pi.policy_net, vf.value_net
        self.latent_dim_pi, self.latent_dim_vf = pi.latent_dim_pi, vf.latent_dim_vf

    def forward(self, features: tuple[th.Tensor, th.Tensor]) -> tuple[th.Tensor, th.Tensor]:
        pi, vf = features
        return self.forward_actor(pi), self.forward_critic(vf)

    def forward_actor(self, features: th.Tensor) -> th.Tensor:
        return self.policy_net(features)

    def forward_critic(self, features: th.Tensor) -> th.Tensor:
        return self.value_net(features)


class PrivilegedActorCriticPolicy(MultiInputActorCriticPolicy):
    """An actor-critic policy on :class:`PrivilegedObservation`'s ``Dict``: the actor reads
    ``"actor"``, the critic ``"critic"`` (see the module docstring). Takes the keyword
    arguments of ``MultiInputActorCriticPolicy`` (``net_arch``, ``activation_fn``, ...) except
    the feature extractor's, which it fixes."""

    #: The observation entry the actor reads (what a numpy copy of the actor takes).
    actor_key = ACTOR_KEY

    def __init__(self, observation_space: spaces.Dict, action_space: spaces.Space,
                 lr_schedule: Any, **kwargs: Any) -> None:
        for fixed in ("features_extractor_class", "features_extractor_kwargs",
                      "share_features_extractor"):
            if fixed in kwargs:
                raise ValueError(f"the privileged policy fixes {fixed}; leave it out")
        super().__init__(observation_space, action_space, lr_schedule,
                         features_extractor_class=KeyExtractor,
                         features_extractor_kwargs={"key": ACTOR_KEY},
                         share_features_extractor=False, **kwargs)

    def _build_mlp_extractor(self) -> None:
        # Called by the base class's _build, after it made two actor extractors: the critic's
        # is replaced by one that reads the critic's entry.
        self.vf_features_extractor = KeyExtractor(self.observation_space, CRITIC_KEY)
        self.mlp_extractor = SplitMlpExtractor(
            self.features_dim, self.vf_features_extractor.features_dim, self.net_arch,
            self.activation_fn, self.device)
