"""What an :class:`~soccer_env.protocol.server.SSLServer` serves: a match
(:class:`ServedMatch`) or a single-robot task, the keeper's or the shootout's
(:class:`ServedTask`).

Either is the package's own environment with true observations (what a team sees comes out of
the served cameras, not the environment's observation) and the vision preset as its
``perception``, so that the robots' commands take effect after the preset's actuation latency
and are lost at its command-loss rate, as they are in process. Each says which robots a
team's robot control may command (:attr:`sizes`), steps with the commanded robots' actions,
and gives the referee's state for the ``Referee`` messages: a match with the game flow its
game controller; otherwise a :class:`~soccer_env.protocol.referee.PlainGame` (a match: one
half of ``FORCE_START``, with a ``DIRECT_FREE`` for the team of a restart of the simple
referee until its first touch; a task: a ``PENALTY_SHOOTOUT`` whose every shot starts with
``PREPARE_PENALTY`` for the attacking team, goes on with ``NORMAL_START`` once the shot is
taken, and scores the attackers' goals).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import gymnasium as gym
import numpy as np

import soccer_env
from soccer_env.envs.registration import GOALKEEPER_ID, GYMNASIUM, SHOOTOUT_ID
from soccer_env.presets import VisionSpec
from soccer_env.protocol.referee import PlainGame

__all__ = ["SERVED", "ServedMatch", "ServedTask", "served"]

#: What a server can serve: name -> the Gymnasium id of a task (None: the match).
SERVED: dict[str, str | None] = {"match": None, "goalkeeper": GOALKEEPER_ID,
                                 "shootout": SHOOTOUT_ID}
#: The team that attacks in each task (0 blue, 1 yellow): the invisible shooter of the keeper
#: task is yellow; the shootout's attacker is the blue learner.
_ATTACKERS = {"goalkeeper": 1, "shootout": 0}


class ServedMatch:
    """A match (:func:`soccer_env.parallel_env` with ``env_kwargs``): every robot of both
    teams is commanded over the protocol."""

    kind = "match"

    def __init__(self, env_kwargs: Mapping[str, Any], vision: VisionSpec) -> None:
        self.env = soccer_env.parallel_env(**env_kwargs, perception=vision)
        u = self.env.unwrapped
        self.world = u.world
        #: Robots each team's robot control may command ``(blue, yellow)``.
        self.sizes = (int(self.world.n_blue), int(self.world.n_yellow))
        self._plain = PlainGame()

    def reset(self, seed: int | None) -> None:
        self.env.reset(seed=seed)

    @property
    def running(self) -> bool:
        return bool(self.env.agents)

    def step(self, actions: np.ndarray) -> str | None:
        """Step with every robot's actions ``(N, 6)``; ``"full time"`` once the match is
        over, else None."""
        names = self.env.unwrapped.possible_agents
        self.env.step({a: actions[i] for i, a in enumerate(names) if a in self.env.agents})
        return None if self.env.agents else "full time"

    def referee(self) -> tuple[Any, tuple[int, int]]:
        """The referee's state (the game controller, or one half of ``FORCE_START`` and
        ``DIRECT_FREE`` restarts) and the score."""
        u = self.env.unwrapped
        if u.game is not None:
            return u.game, tuple(u.score)
        plain = self._plain
        plain.stage_time_left = max(0.0, float(u.match_duration) - float(u.world.time))
        # The simple referee's restart (after a goal or the ball out, until its first touch)
        # as a direct free kick for the team that takes it.
        restart = int(u.restart_team)
        plain.command, plain.command_team = ("direct_free", restart) if restart >= 0 else \
            ("force_start", 0)
        return plain, tuple(u.score)


class ServedTask:
    """A single-robot task (``task``: ``"goalkeeper"`` or ``"shootout"``, made with
    ``env_kwargs`` as ``gymnasium.make`` makes it, with its time limit): its learner, blue
    robot 0, is commanded over the protocol; the task plays its other robots and its shots.
    Each episode is a shot; :attr:`score` counts the attackers' goals."""

    kind = "task"

    def __init__(self, task: str, env_kwargs: Mapping[str, Any], vision: VisionSpec) -> None:
        self.task = task
        self.env = gym.make(SERVED[task], **env_kwargs, obs_mode="truth", perception=vision)
        u = self.env.unwrapped
        self.world = u.world
        self.sizes = (1, 0)
        self.attacker = _ATTACKERS[task]
        self.limit = GYMNASIUM[SERVED[task]].max_episode_steps
        self.score = [0, 0]
        self._running = False
        self._game = PlainGame()

    def reset(self, seed: int | None) -> None:
        self.env.reset(seed=seed)
        self._running = True
        self._game = PlainGame("penalty_shootout", self._time_left(), "prepare_penalty",
                               self.attacker)

    def _time_left(self) -> float:
        w = self.world
        return max(0.0, (self.limit or 0) * float(w.control_dt) - float(w.time))

    @property
    def running(self) -> bool:
        return self._running

    def step(self, actions: np.ndarray) -> str | None:
        """Step with the learner's action ``actions[0]``; the outcome once the shot is over
        (the task's, or ``"time limit"``), else None."""
        _, _, terminated, truncated, info = self.env.step(actions[0])
        # Taken: the keeper task's shot once fired (it stays fired), the shootout's at once.
        if self._game.command == "prepare_penalty" and info.get("shot_fired", True):
            self._game.command = "normal_start"
        self._game.stage_time_left = self._time_left()
        if not (terminated or truncated):
            return None
        self._running = False
        outcome = info["outcome"] if terminated else "time limit"
        if outcome == "goal":
            self.score[self.attacker] += 1
        return str(outcome)

    def finish(self) -> None:
        """The series is over: the referee's command is ``STOP``."""
        self._running = False
        self._game.command = "stop"

    def referee(self) -> tuple[Any, tuple[int, int]]:
        return self._game, (self.score[0], self.score[1])


def served(task: str, env_kwargs: Mapping[str, Any], vision: VisionSpec
           ) -> ServedMatch | ServedTask:
    """What serves ``task`` (:data:`SERVED`)."""
    if task not in SERVED:
        raise ValueError(f"task must be one of {list(SERVED)}, got {task!r}")
    out = ServedMatch(env_kwargs, vision) if SERVED[task] is None else \
        ServedTask(task, env_kwargs, vision)
    if out.world.humanoid_indices:
        out.env.close()
        raise ValueError(f"the SSL protocols serve SSL robots; this {task} has humanoids")
    return out
