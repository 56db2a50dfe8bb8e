"""What both game controllers keep and show (:class:`RefereeState`): the match's specs and
robots, the referee state a team's software receives, and the steps of the flow that the
SSL rules and the Humanoid League laws share (issuing a command, who is on the field, a
goal counted, the end of the match).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec
from soccer_env.sim.ball import BallExit
from soccer_env.sim.game.types import Decision, GameEvent, TeamInfo

__all__ = ["RefereeState"]


class RefereeState:
    """What both game controllers (the SSL
    :class:`~soccer_env.sim.game.controller.GameController` and
    :class:`~soccer_env.sim.humanoid_game.HumanoidGameController`) keep and show: the
    match's specs and robots, and the referee state a team's software receives.

    Attributes:
        field, ball_spec: the match's specs.
        teams: ``(N,)`` team of each robot (0 blue, 1 yellow).
        radii: ``(N,)`` robot radii [m].
        duration: playing time of the match [s].
        keepers: robot index of each team's keeper (its first robot), -1 for a team without
            robots.
        team_info: each team's :class:`~soccer_env.sim.game.types.TeamInfo`.
        command, command_team: the present command and the team it is for (-1: none).
        designated: the position of the coming or present restart [m], or None.
        next_command: the command that follows the present stop or placement, or None.
        in_play: whether the ball is in play.
        time: the time of the last step [s].
        first_kickoff: the team that kicked off the match.
    """

    def _init_referee(self, field: FieldSpec, ball: BallSpec, teams: Sequence[int],
                      radii: Sequence[float], duration: float,
                      rng: np.random.Generator) -> None:
        """Check the robots and the duration; the state before the start."""
        if not 0.0 < duration < math.inf:
            raise ValueError(f"duration must be a positive number of seconds, got {duration}")
        self.field, self.ball_spec = field, ball
        self.teams = np.asarray(teams, dtype=int)
        self.radii = np.asarray(radii, dtype=float)
        if self.radii.shape != self.teams.shape:
            raise ValueError(f"radii must have one entry per robot ({len(self.teams)}), got "
                             f"{self.radii.shape}")
        self.duration = float(duration)
        self.rng = rng
        #: Robot index of each team's keeper (its first robot), -1 for a team without robots.
        self.keepers = [int(np.flatnonzero(self.teams == t)[0]) if np.any(self.teams == t)
                        else -1 for t in (0, 1)]
        self.team_info = [TeamInfo(), TeamInfo()]
        self.command = "stop"
        self.command_team = -1
        self.designated: tuple[float, float] | None = None
        self.next_command: tuple[str, int] | None = None
        self.in_play = False
        self.time = 0.0
        self.first_kickoff = 0
        self._command_time = 0.0

    def _set_command(self, command: str, team: int) -> None:
        """Issue ``command`` for ``team`` (-1: none); its timer starts."""
        self.command, self.command_team = command, team
        self._command_time = 0.0

    def _on_field(self, i: int) -> bool:
        """Whether robot ``i`` plays (is not off the field for a card or a penalty)."""
        t = int(self.teams[i])
        return i not in self.team_info[t].off

    def _score(self, scorer: int, last: int, ex: BallExit, d: Decision) -> None:
        """Count a valid goal of ``scorer`` (``last``: the robot that touched the ball last,
        -1 none; ``ex``: where the ball crossed the line)."""
        self.team_info[scorer].goals += 1
        d.scorer = scorer
        d.events.append(GameEvent("goal", scorer, last, ex.x, ex.y))

    def _end_match(self, d: Decision) -> None:
        """The match is over: stage ``post_game``, command ``stop``."""
        self.stage = "post_game"
        self._set_command("stop", -1)
        self.in_play = False
        d.over = True
