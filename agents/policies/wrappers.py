"""The learner's view of an environment: its action map in front
(:mod:`agents.policies.action_maps`), its last observations stacked, and for a privileged
critic the true state beside the observation.

* the action wrappers (:class:`FieldVelocityActions`, :class:`TargetActions`,
  :class:`GuardActions`, :class:`GuardResidualActions`, :class:`BallResidualActions`, made by
  :func:`wrap_actions`) give Goalkeeper-v0 a learner's action space, mapped to the native
  command by :func:`~agents.policies.action_maps.action_to_command` from the plain
  observation;
* :func:`stack_frames` gives a feed-forward learner a short memory: it sees its last ``n``
  observations at once (``soccer-env train --frame-stack N``), and the exported numpy policy
  keeps that history itself;
* :class:`PrivilegedObservation` puts the true state beside the observation for a critic
  that reads it (``soccer-env train --critic privileged``); the actor, which is all that is
  shipped, still acts on the perceived observation alone;
* :func:`wrap_learner` puts them together as ``soccer-env train`` and the RLlib backend do.

Gymnasium and numpy only: both training backends (stable-baselines3 and RLlib) use them, and
the numpy policies mirror them (action map, frame stack) on the plain environment.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from agents.policies.action_maps import (
    ACTION_MAPS,
    SSL_MAPS,
    action_to_command,
    ball_residual_params,
    check_observation_layout,
    residual_params,
    target_params,
)

__all__ = ["FieldVelocityActions", "TargetActions", "GuardActions", "GuardResidualActions",
           "BallResidualActions", "wrap_actions", "stack_frames", "ACTOR_KEY", "CRITIC_KEY",
           "PrivilegedObservation", "wrap_learner"]

class _MappedActions(gym.Wrapper):
    """Goalkeeper-v0 with a learner's action space (see the module docstring); the
    observation, rewards and episode are the wrapped environment's."""

    kind = ""

    def __init__(self, env: gym.Env, params: Mapping[str, float] | None = None) -> None:
        super().__init__(env)
        native = env.action_space
        if not (isinstance(native, gym.spaces.Box) and native.shape == (6,)):
            raise ValueError(f"{type(self).__name__} wraps an environment with the SSL "
                             f"robot's (6,) action space, got {native}")
        if self.kind in SSL_MAPS and env.unwrapped.robot_spec.kind == "humanoid":
            raise ValueError(f"the {self.kind!r} actions drive an SSL robot; a humanoid keeper "
                             "takes 'native' or 'ball-residual' actions")
        check_observation_layout(env.unwrapped.builder.names)
        self.params = dict(params) if params is not None else None
        self.action_space = gym.spaces.Box(-1.0, 1.0, (ACTION_MAPS[self.kind],), np.float32)
        self._obs: np.ndarray | None = None

    def reset(self, **kwargs: Any):
        obs, info = self.env.reset(**kwargs)
        self._obs = obs
        return obs, info

    def step(self, action: Any):
        if self._obs is None:
            raise RuntimeError("call reset() before step()")
        act = np.asarray(action, dtype=np.float32)
        size = ACTION_MAPS[self.kind]
        if act.shape != (size,):
            raise ValueError(f"action must have shape ({size},), got {act.shape}")
        if not np.all(np.isfinite(act)):
            raise ValueError(f"action must be finite, got {act}")
        native = action_to_command(self.kind, self._obs, act, self.params)
        obs, reward, terminated, truncated, info = self.env.step(native)
        self._obs = obs
        return obs, reward, terminated, truncated, info


class FieldVelocityActions(_MappedActions):
    """``Box(-1, 1, (3,))``: field-frame ``(vx, vy)`` scaled to the top speed, and the turn
    rate; kicker off."""

    kind = "velocity"


class TargetActions(_MappedActions):
    """``Box(-1, 1, (2,))``: the point in front of the goal to drive to (see
    :func:`action_to_command` and :func:`target_params`); facing the field, kicker off."""

    kind = "target"

    def __init__(self, env: gym.Env, depth: float = 0.5) -> None:
        if not (math.isfinite(depth) and 0.0 <= depth <= 2.0):
            raise ValueError(f"depth must be in [0, 2] m, got {depth!r}")
        super().__init__(env, target_params(env, depth))


class GuardActions(_MappedActions):
    """``Box(-1, 1, (1,))``: where to stand on the guard line, ``y = a y_max`` (see
    :func:`action_to_command` and :func:`target_params`); facing the field, kicker off."""

    kind = "guard"

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env, target_params(env))


class GuardResidualActions(_MappedActions):
    """``Box(-1, 1, (1,))``: a correction ``a * residual`` to the point on the guard line the
    scripted keeper would choose (see :func:`scripted_guard_y` and :func:`residual_params`);
    facing the field, kicker off."""

    kind = "guard-residual"

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env, residual_params(env))


class BallResidualActions(_MappedActions):
    """``Box(-1, 1, (2,))``: a correction ``a * residual`` (team frame, m/s) to the ball
    velocity the scripted keeper believes, which then acts (see :func:`action_to_command`
    and :func:`ball_residual_params`); for SSL and humanoid keepers."""

    kind = "ball-residual"

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env, ball_residual_params(env))


def wrap_actions(env: gym.Env, kind: str) -> gym.Env:
    """``env`` with the learner's action space ``kind`` (``"native"`` returns it as is)."""
    if kind == "native":
        return env
    if kind == "velocity":
        return FieldVelocityActions(env)
    if kind == "target":
        return TargetActions(env)
    if kind == "guard":
        return GuardActions(env)
    if kind == "guard-residual":
        return GuardResidualActions(env)
    if kind == "ball-residual":
        return BallResidualActions(env)
    raise ValueError(f"actions must be one of {list(ACTION_MAPS)}, got {kind!r}")


def stack_frames(env: gym.Env, n: int) -> gym.Env:
    """``env`` whose observation is its last ``n`` observations concatenated, oldest first
    (``Box`` of ``n`` times the size); after a reset the episode's first observation fills
    the stack (``n = 1`` returns ``env`` as it is).

    Gymnasium's ``FrameStackObservation`` (with ``padding_type="reset"``: the first
    observation repeated, not zeros, so that a stacked observation never shows a state that
    did not happen) followed by ``FlattenObservation`` (the ``(n, k)`` stack as one vector,
    as stable-baselines3's MLP policies take it). Wrap it outside any action map of
    :func:`wrap_actions`, which reads the pose from the plain observation.
    :class:`~agents.policies.numpy_policy.NumpyPolicy` with ``frame_stack=n`` does the same stacking
    itself, so a policy trained on stacked frames acts on the plain environment.
    """
    from gymnasium.wrappers import FlattenObservation, FrameStackObservation

    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be an integer >= 1, got {n!r}")
    if n == 1:
        return env
    space = env.observation_space
    if not (isinstance(space, gym.spaces.Box) and len(space.shape) == 1):
        raise ValueError(f"stack_frames takes a flat Box observation, got {space}")
    return FlattenObservation(FrameStackObservation(env, int(n), padding_type="reset"))


#: The actor's part of the observation.
ACTOR_KEY = "actor"
#: The critic's part.
CRITIC_KEY = "critic"


class PrivilegedObservation(gym.ObservationWrapper):
    """The observation as ``Dict(actor=..., critic=...)`` for an asymmetric actor-critic: in
    training the critic reads the true state, the actor only what the robot perceives
    (Pinto et al. 2018, "Asymmetric actor critic for image-based robot learning";
    :class:`~agents.sb3.privileged.PrivilegedActorCriticPolicy` is the policy that reads it).

    The critic's part is ``[truth (n), actor (n)]``: the environment's observation builder
    applied to the world's true state (a truth-mode observation of the same layout, belief
    features reading a perfect sensor) and the actor's observation. Works on the
    single-agent tasks (``Goalkeeper-v0``, ``Shootout-v0``), whose ``builder`` lays out robot
    0's observation.
    """

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env)
        base = env.unwrapped
        if not (hasattr(base, "builder") and hasattr(base, "world")):
            raise TypeError(f"a privileged critic needs a single-agent soccer_env task (with "
                            f"a builder and a world), got {type(base).__name__}")
        box = env.observation_space
        if not isinstance(box, spaces.Box) or len(box.shape) != 1:
            raise TypeError(f"a privileged critic needs a flat Box observation, got {box}")
        self._builder, self._world = base.builder, base.world
        critic = spaces.Box(np.concatenate([self._builder.low, box.low]),
                            np.concatenate([self._builder.high, box.high]), dtype=np.float32)
        self.observation_space = spaces.Dict({ACTOR_KEY: box, CRITIC_KEY: critic})

    def observation(self, observation: np.ndarray) -> dict[str, np.ndarray]:
        truth = self._builder.build(self._world.snapshot())[0]
        return {ACTOR_KEY: observation,
                CRITIC_KEY: np.concatenate([truth, observation]).astype(np.float32)}


def wrap_learner(env: gym.Env, actions: str = "native", frame_stack: int = 1,
                 critic: str = "shared") -> gym.Env:
    """``env`` as a keeper learner of ``soccer-env train`` sees it: behind the action map
    ``actions`` (:func:`wrap_actions`; inside, since the maps read the pose from the plain
    observation), with the true state beside the observation for a ``"privileged"`` critic
    (:class:`PrivilegedObservation`) and the last ``frame_stack``
    observations stacked (:func:`stack_frames`)."""
    env = wrap_actions(env, actions)
    if critic == "privileged":
        env = PrivilegedObservation(env)
    return stack_frames(env, frame_stack)
