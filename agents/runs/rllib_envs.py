"""The environments of the RLlib backend (:mod:`agents.runs.rllib`).

RLlib builds environments on its *env runners*, Ray actors that the cluster places on any of
its nodes. The configurations of :func:`agents.runs.rllib.ppo_config` name the environment by
its class, :data:`ENV_CLASSES`:

* :class:`KeeperEnv`: the keeper task, ``env_config`` holding its keyword arguments
  (``obs_mode``, ``perception``, ``shaping``, ...) and, optionally, the learner's
  ``"actions"`` map and ``"frame_stack"`` as ``soccer-env train`` has them
  (:func:`~agents.policies.wrappers.wrap_learner`);
* :class:`MatchEnv`: the PettingZoo match (:func:`soccer_env.parallel_env`, ``env_config``
  its keyword arguments) as an RLlib ``MultiAgentEnv`` (:class:`MatchMultiAgentEnv` fixes two
  bugs of RLlib's ``ParallelPettingZooEnv``, see there). With ``"opponent"`` (and
  ``"learner"``, the learning team) in ``env_config`` the environment plays the other team
  itself with a fixed policy (:class:`FixedOpponentMatch`) and exposes only the learner's
  robots.

A checkpoint's configuration holds the class, which unpickling imports from this module, so a
checkpoint restores in a fresh process with ``Algorithm.from_checkpoint`` alone, on the
driver and on every env runner. :func:`register_envs` also registers the environments'
ids (``"soccer_env/Goalkeeper-v0"``, ``"soccer_env/Match-v0"``) in Ray's registry, for
configurations that name them (and checkpoints of version 0.1.0, which did).

The environments hand RLlib small infos (:data:`KEEPER_INFOS`, :data:`MATCH_INFOS`): the truth
and the belief of every step stay out of the episodes that env runners send to the learner.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from typing import Any

import gymnasium as gym
import numpy as np
from pettingzoo.utils.wrappers import BaseParallelWrapper
from ray.rllib.env.wrappers.pettingzoo_env import ParallelPettingZooEnv

from agents.policies.action_maps import ACTION_MAPS
from agents.policies.numpy_policy import NumpyPolicy
from agents.policies.wrappers import wrap_learner
from agents.scripted import TEAMS, scripted_team
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID

__all__ = ["ENV_IDS", "ENV_CLASSES", "KEEPER_INFOS", "MATCH_INFOS", "OPPONENT_NAMES",
           "MATCH_OPTIONS", "keeper_env", "match_env", "match_kwargs", "register_envs",
           "KeeperEnv", "MatchEnv", "MatchMultiAgentEnv", "FixedOpponentMatch",
           "opponent_team"]

#: The environments of the RLlib backend, by id.
ENV_IDS = (GOALKEEPER_ID, MATCH_ID)
#: What of the keeper's info RLlib gets.
KEEPER_INFOS = ("outcome", "reward_terms", "shot_fired", "keeper_touched")
#: What of every match agent's info RLlib gets.
MATCH_INFOS = ("score", "event", "reward_terms")
#: The fixed opponents given by name (besides a numpy policy or the path of its file).
OPPONENT_NAMES = ("scripted", "idle")
#: The entries of a match's ``env_config`` that are not keyword arguments of the match: the
#: fixed opponent and the team it plays against.
MATCH_OPTIONS = ("opponent", "learner")

_NO_MEMORY = ("a fixed opponent with memory (a recurrent or frame-stacked numpy policy) is not "
              "supported: the match does not reset an opponent's memory")


class _SlimInfos(gym.Wrapper):
    """The keeper with only :data:`KEEPER_INFOS` in its infos."""

    def reset(self, **kwargs: Any) -> tuple[Any, dict[str, Any]]:
        obs, info = self.env.reset(**kwargs)
        return obs, {k: info[k] for k in KEEPER_INFOS if k in info}

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        obs, reward, term, trunc, info = self.env.step(action)
        return obs, reward, term, trunc, {k: info[k] for k in KEEPER_INFOS if k in info}


class _SlimMatchInfos(BaseParallelWrapper):
    """The match with only :data:`MATCH_INFOS` in every agent's info."""

    @staticmethod
    def _slim(infos: Mapping[str, Mapping[str, Any]]) -> dict[str, dict[str, Any]]:
        return {a: {k: info[k] for k in MATCH_INFOS if k in info} for a, info in infos.items()}

    def reset(self, seed: int | None = None, options: dict | None = None):
        obs, infos = self.env.reset(seed=seed, options=options)
        return obs, self._slim(infos)

    def step(self, actions: Mapping[str, Any]):
        obs, rewards, terms, truncs, infos = self.env.step(actions)
        return obs, rewards, terms, truncs, self._slim(infos)

    def state(self) -> Any:
        return self.env.state()


def keeper_env(env_config: Mapping[str, Any] | None = None) -> gym.Env:
    """Goalkeeper-v0 for RLlib: ``env_config`` holds its keyword arguments and, optionally,
    ``"actions"`` (the learner's action map, :data:`~agents.policies.action_maps.ACTION_MAPS`,
    default ``"native"``) and ``"frame_stack"`` (the last N observations side by side, default 1).
    Infos hold :data:`KEEPER_INFOS` only."""
    import soccer_env  # noqa: F401  (registers the environments in this process)

    kwargs = dict(env_config or {})
    actions = kwargs.pop("actions", "native")
    frame_stack = kwargs.pop("frame_stack", 1)
    if actions not in ACTION_MAPS:
        raise ValueError(f"actions must be one of {list(ACTION_MAPS)}, got {actions!r}")
    env = gym.make(GOALKEEPER_ID, **kwargs)
    return wrap_learner(_SlimInfos(env), actions, int(frame_stack))


class KeeperEnv(gym.Wrapper):
    """:func:`keeper_env` as a class, the environment that RLlib builds from ``env_config``
    (what the configurations of :func:`agents.runs.rllib.ppo_config` name)."""

    def __init__(self, env_config: Mapping[str, Any] | None = None) -> None:
        super().__init__(keeper_env(env_config))


def opponent_team(env: Any, team: str, opponent: Any
                  ) -> Callable[[Mapping[str, np.ndarray]], dict[str, np.ndarray]]:
    """A fixed policy of ``team`` in the PettingZoo match ``env``: a function from the match's
    observations to the actions of the team's agents among them. ``opponent`` is
    ``"scripted"`` (:func:`~agents.scripted.scripted_team`), ``"idle"`` (all-zero actions), a
    :class:`~agents.policies.numpy_policy.NumpyPolicy` without memory, or the path of its file
    (``.npz``, read without pickle). ``ValueError`` for anything else, or a policy whose
    observations are not the match's."""
    u = getattr(env, "unwrapped", env)
    agents = [a for a in u.possible_agents if a.split("_")[0] == team]
    if not agents:
        raise ValueError(f"the {team} team has no robots to play")
    if isinstance(opponent, str) and opponent == "scripted":
        return scripted_team(u, team)
    if isinstance(opponent, str) and opponent == "idle":
        zero = np.zeros(u.action_space(agents[0]).shape, dtype=np.float32)
        return lambda obs: {a: zero for a in agents if a in obs}
    if isinstance(opponent, (str, os.PathLike)) and os.fspath(opponent).endswith(".npz"):
        opponent = NumpyPolicy.load(opponent)
    if not isinstance(opponent, NumpyPolicy):
        raise ValueError(f"opponent must be one of {list(OPPONENT_NAMES)}, a numpy policy or "
                         f"the path of its file (.npz), got {opponent!r}")
    if opponent.stateful:
        raise ValueError(_NO_MEMORY)
    size = u.observation_space(agents[0]).shape[0]
    if opponent.obs_size != size:
        raise ValueError(f"the opponent policy takes observations of size "
                         f"{opponent.obs_size}, the match gives {size}")
    policy = opponent

    def act(obs: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        live = [a for a in agents if a in obs]
        if not live:
            return {}
        return dict(zip(live, np.asarray(policy(np.stack([obs[a] for a in live])),
                                         dtype=np.float32)))

    return act


class FixedOpponentMatch(BaseParallelWrapper):
    """The PettingZoo match with the team other than ``learner`` played by a fixed policy
    (:func:`opponent_team`) inside the environment: its agents are ``learner``'s robots only,
    and each step the opponent's robots act on their observations of the step before.

    Args:
        env: the match (:func:`soccer_env.parallel_env`).
        learner: the learning team, ``"blue"`` or ``"yellow"``.
        opponent: the other team's policy (``"scripted"``, ``"idle"``, a numpy policy or the
            path of its file).
    """

    def __init__(self, env: Any, learner: str, opponent: Any) -> None:
        super().__init__(env)
        if learner not in TEAMS:
            raise ValueError(f"learner must be 'blue' or 'yellow', got {learner!r}")
        self.learner = learner
        self.opponent_team = TEAMS[1 - TEAMS.index(learner)]
        self.possible_agents = [a for a in env.possible_agents if a.split("_")[0] == learner]
        if not self.possible_agents:
            raise ValueError(f"learner {learner!r}: the {learner} team has no robots")
        self.opponent = opponent_team(env, self.opponent_team, opponent)
        self._obs: Mapping[str, np.ndarray] = {}

    @property
    def agents(self) -> list[str]:
        """The learner's robots that are still playing."""
        return [a for a in self.env.agents if a.split("_")[0] == self.learner]

    def _mine(self, values: Mapping[str, Any]) -> dict[str, Any]:
        return {a: v for a, v in values.items() if a.split("_")[0] == self.learner}

    def reset(self, seed: int | None = None, options: dict | None = None):
        obs, infos = self.env.reset(seed=seed, options=options)
        self._obs = obs
        return self._mine(obs), self._mine(infos)

    def step(self, actions: Mapping[str, Any]):
        full = {**self.opponent(self._obs), **self._mine(actions)}
        obs, rewards, terms, truncs, infos = self.env.step(full)
        self._obs = obs
        return (self._mine(obs), self._mine(rewards), self._mine(terms), self._mine(truncs),
                self._mine(infos))


class MatchMultiAgentEnv(ParallelPettingZooEnv):
    """RLlib's ``ParallelPettingZooEnv`` with two of its bugs (Ray 2.60) fixed:

    * it builds ``possible_agents`` and ``agents`` from a ``set`` of the agent names, so their
      order differs from the environment's and from one process to the next (string hashes
      are salted per process), and it never updates ``agents`` after a reset or a step (they
      stay full after the match ended); here both follow the PettingZoo environment;
    * its ``render()`` calls the PettingZoo environment's ``render(self.render_mode)``,
      which takes no argument since PettingZoo's render API of 2022 (a ``TypeError``); here
      it calls ``render()``.
    """

    def __init__(self, env: Any) -> None:
        super().__init__(env)
        self.possible_agents = list(env.possible_agents)
        self.agents = list(env.agents)
        self.render_mode = getattr(env, "render_mode", None)

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        out = super().reset(seed=seed, options=options)
        self.agents = list(self.par_env.agents)
        return out

    def step(self, action_dict: Mapping[str, Any]):
        out = super().step(action_dict)
        self.agents = list(self.par_env.agents)
        return out

    def render(self) -> Any:
        return self.par_env.render()


def match_kwargs(env_config: Mapping[str, Any] | None) -> dict[str, Any]:
    """The keyword arguments of :func:`soccer_env.parallel_env` in a match's ``env_config``
    (all but :data:`MATCH_OPTIONS`)."""
    return {k: v for k, v in (env_config or {}).items() if k not in MATCH_OPTIONS}


class MatchEnv(MatchMultiAgentEnv):
    """The match for RLlib, built from ``env_config``: the keyword arguments of
    :func:`soccer_env.parallel_env` and, for a fixed opponent, ``"opponent"`` (see
    :func:`opponent_team`) and ``"learner"`` (the learning team, default ``"blue"``): the
    environment then plays the other team and its agents are the learner's robots
    (:class:`FixedOpponentMatch`). Infos hold :data:`MATCH_INFOS` only."""

    def __init__(self, env_config: Mapping[str, Any] | None = None) -> None:
        import soccer_env

        config = dict(env_config or {})
        env = soccer_env.parallel_env(**match_kwargs(config))
        if config.get("opponent") is not None:
            env = FixedOpponentMatch(env, config.get("learner", "blue"), config["opponent"])
        elif "learner" in config:
            raise ValueError("env_config's 'learner' is the team against a fixed 'opponent', "
                             "which is missing")
        super().__init__(_SlimMatchInfos(env))


def match_env(env_config: Mapping[str, Any] | None = None) -> MatchEnv:
    """The match for RLlib (:class:`MatchEnv`) of ``env_config``."""
    return MatchEnv(env_config)


#: The class RLlib builds each environment from, by id.
ENV_CLASSES: dict[str, type] = {GOALKEEPER_ID: KeeperEnv, MATCH_ID: MatchEnv}


def register_envs() -> None:
    """Register :data:`ENV_IDS` in Ray's registry (again is harmless), for configurations
    that name the environments by id: :func:`keeper_env` and :func:`match_env` build them.
    The configurations of :func:`agents.runs.rllib.ppo_config` name the classes and need
    no registration."""
    from ray.tune.registry import register_env

    register_env(GOALKEEPER_ID, keeper_env)
    register_env(MATCH_ID, match_env)
