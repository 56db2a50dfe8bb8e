"""What a live client plays: the learner of a single-robot task (:class:`TaskPlayer`) or a
match team (:class:`TeamPlayer`), each built on the package's environment of the policy, whose
perception pipeline, observation builder and robot model it lends to the client.

A player turns a belief (and, for a team, the referee's view: :class:`RefereeView`) into the
physical commands of its robots ``(k, 6)`` (body-frame ``vx, vy`` [m/s], ``omega`` [rad/s],
kick speed [m/s], chip, dribble), for the robots :attr:`ids` (numbers in the team).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any, NamedTuple

import gymnasium as gym
import numpy as np

import soccer_env
from agents.baselines import TEAMS as SHIPPED_TEAMS
from agents.baselines import team_path
from agents.policies.base import reset_policy
from agents.runs.resolve import make_policy
from agents.studies.matches import team_policy
from soccer_env.envs.game_rows import GameRows
from soccer_env.protocol.served import SERVED
from soccer_env.sim.commands import robot_model

__all__ = ["RefereeView", "TaskPlayer", "TeamPlayer", "TEAM_NAMES"]

#: The teams, in the world's order.
TEAM_NAMES = ("blue", "yellow")


class RefereeView(NamedTuple):
    """What a match team reads of the referee: the match ``time`` [s] (from the stage's
    time left), the ``score`` (blue's, yellow's goals) and the ``restart`` team (0 blue, 1
    yellow, -1 none: the team of a free kick not yet taken)."""

    time: float
    score: tuple[int, int]
    restart: int


def _check_ssl(env: Any) -> None:
    if env.unwrapped.world.humanoid_indices:
        env.close()
        raise ValueError("the client plays SSL robots; these env_kwargs make humanoids")


class TaskPlayer:
    """The learner (blue robot 0) of the task ``task`` made with ``env_kwargs``, played by
    ``policy`` (:func:`~agents.runs.resolve.make_policy`'s references)."""

    team = 0
    ids = [0]

    def __init__(self, task: str, env_kwargs: Mapping[str, Any], policy: Any,
                 trust: bool = False) -> None:
        self.env = gym.make(SERVED[task], **env_kwargs)
        _check_ssl(self.env)
        u = self.env.unwrapped
        self.world = u.world
        self.pipeline = u.pipelines[0]
        self.builder = u.builder
        self.model = u.robot_model
        try:
            self.policy = make_policy(policy, self.env, trust=trust)
        except BaseException:
            self.env.close()
            raise

    def restart(self) -> None:
        """A new shot: the policy's memory starts afresh."""
        reset_policy(self.policy)

    def commands(self, belief: Any, referee: RefereeView) -> np.ndarray:
        action = np.clip(np.asarray(self.policy(self.builder.build(belief)[0]),
                                    dtype=np.float64), -1.0, 1.0)
        return self.model.commands(action[None])

    def close(self) -> None:
        self.env.close()


class TeamPlayer:
    """The ``team`` (``"blue"`` or ``"yellow"``) of the match made with ``env_kwargs``
    (:func:`soccer_env.parallel_env`; without the game flow), played by ``policy``:
    ``"scripted"``, ``"idle"``, a shipped team's name (:data:`agents.baselines.TEAMS`) or a
    numpy team file, as :func:`agents.studies.matches.team_policy` plays them. Its
    observations' game block is read from the referee (:class:`RefereeView`)."""

    def __init__(self, team: str, env_kwargs: Mapping[str, Any], policy: Any) -> None:
        if team not in TEAM_NAMES:
            raise ValueError(f"team must be one of {list(TEAM_NAMES)}, got {team!r}")
        if env_kwargs.get("game"):
            raise ValueError("env_kwargs game: a team under the game flow needs the game "
                             "controller's state in its observation, which the client does "
                             "not read back from the referee messages; play without it")
        if isinstance(policy, (str, os.PathLike)) and os.fspath(policy) in SHIPPED_TEAMS:
            policy = str(team_path(os.fspath(policy)))
        self.env = soccer_env.parallel_env(**env_kwargs)
        _check_ssl(self.env)
        u = self.env.unwrapped
        self.world = w = u.world
        self.team = t = TEAM_NAMES.index(team)
        pipes = u.pipelines
        # One pipeline for both teams, or one each (blue's first).
        self.pipeline = pipes[0] if len(pipes) == 1 else pipes[t]
        self.builder = u.builder
        self.model = robot_model(u.team_specs[t])
        self.rows = GameRows(w.teams.tolist(), w.n_blue, float(u.match_duration))
        self.agents = [a for a in u.possible_agents if a.startswith(f"{team}_")]
        self.index = [u.possible_agents.index(a) for a in self.agents]
        first = 0 if t == 0 else w.n_blue
        self.ids = [i - first for i in self.index]
        try:
            self.act = team_policy(policy, self.env, team)
        except BaseException:
            self.env.close()
            raise

    def restart(self) -> None:
        """Nothing to forget: a team policy keeps no memory."""

    def commands(self, belief: Any, referee: RefereeView) -> np.ndarray:
        game = self.rows.simple(referee.time, list(referee.score), referee.restart)
        rows = self.builder.build(belief, game)
        actions = self.act({a: rows[i] for a, i in zip(self.agents, self.index)})
        act = np.clip(np.stack([np.asarray(actions[a], dtype=np.float64)
                                for a in self.agents]), -1.0, 1.0)
        return self.model.commands(act)

    def close(self) -> None:
        self.env.close()
