"""The Humanoid League game flow: kick-offs, dropped balls, throw-ins, goal kicks, corner kicks
and removal penalties of the RoboCup Humanoid League Laws of the Game 2025, KidSize
(https://github.com/RoboCup-Humanoid-TC/Rules; law numbers below are the rule book's, "Section
II" its competition rules; where the physical and the virtual competition differ, the virtual
competition's rule is played, as the league's autonomous referee ``hlvs_webots`` plays it).
The numbers are :class:`~soccer_env.presets.rules.HumanoidRuleSpec`'s
(``RULES["humanoid-2025-kid"]``).

:class:`HumanoidGameController` has the public surface of the SSL
:class:`~soccer_env.sim.game.GameController` (the same :class:`~soccer_env.sim.game.Frame`,
:class:`~soccer_env.sim.game.Decision`, :class:`~soccer_env.sim.game.GameEvent` and
:class:`~soccer_env.sim.game.TeamInfo`, and the SSL command names where they fit), so that an
environment drives and observes either. It never touches the physics itself.

The flow:

* **Kick-off** (Law 8) at the start of each half and after a goal (by the team that conceded):
  both teams in their own halves and the ball on the centre mark. The READY and SET states
  (Section II, kick-off procedure) are not played: the simulation lines the teams up
  (``Decision.line_up``) and the game is PLAYING at once, command ``normal_start`` for the
  kicking team. Until the ball is in play the opponents of the kicking team must stay
  outside the centre circle (a robot's footprint, its centre minus its radius, nearer the
  centre mark than the circle's radius is inside it); one that enters it gets a removal
  penalty, as the league's virtual referee gives it. The ball is in play once it moved
  :attr:`~HumanoidRuleSpec.ball_in_play_distance` (5 cm) from the centre mark or
  :attr:`~HumanoidRuleSpec.in_play_time` (10 s) after the signal.
* **No goal directly from a kick-off** (Law 8): a goal by the kicking team counts only once
  the ball was touched by a player other than the kicker (of either team), or touched by
  anybody after it had entirely left the centre circle (a ball kicked from the centre
  straight into the goal leaves the circle on its way: the virtual referee's reading, which
  this follows). Otherwise the goal is disallowed (``invalid_goal``) and the opponents get a
  goal kick.
* **Dropped ball** (Law 8, virtual competition): when the ball in play has moved less than
  :attr:`~HumanoidRuleSpec.dropped_ball_distance` (5 cm) in
  :attr:`~HumanoidRuleSpec.dropped_ball_time` (2 minutes): event ``drop_ball``, the ball on
  the centre mark, every robot moved out of the centre circle (``Decision.clear``), and the
  ball in play at once (command ``force_start``); a goal may be scored directly.
* **Ball out of play** (Laws 9, 15-17): the restart goes to the opponents of the team that
  touched the ball last; if nobody touched it since the last restart, to the team defending
  the half (touch line) or the end (goal line) where it went out (the laws leave this case
  open; :func:`~soccer_env.sim.referee.restart_team`, as the SSL referee). The referee
  places the ball (``Decision.place_ball``, :attr:`~HumanoidRuleSpec.line_inset` inside the
  lines, as the virtual referee does):

  - **throw-in** (Law 15) over a touch line: on the touch line where the ball left the field;
    taken as an indirect free kick;
  - **goal kick** (Law 16) over a goal line, last touched by the attacking team: on the touch
    line at its intersection with the halfway line, on the side where the ball went out (the
    2025 text);
  - **corner kick** (Law 17) over a goal line, last touched by the defending team: at the
    corner on the side where the ball went out.

  These are game interruptions (Section II, game interruption procedure) with command
  ``direct_free`` for the team taking them: the opponents must stay at least
  :attr:`~HumanoidRuleSpec.opponent_distance` (0.75 m, measured between the centres of the
  ball and the robot, Section II) from the ball until it is in play. The positioning phase is
  not played: the simulation moves the opponents out (``Decision.clear``, to that distance
  plus a robot radius), and an opponent that comes nearer before the ball is in play gets a
  removal penalty (Law 13; event ``defender_too_close_to_kick_point``, the SSL game
  controller's name for it). The ball is in play once it moved 5 cm or 10 s after the restart
  (Law 13).
* **Indirect restarts** (Laws 13, 15): a goal cannot be scored directly from a throw-in: a
  goal by the throwing team counts only once the ball was touched by a player other than the
  thrower, or touched again after it was in play (Law 13: "kicked and clearly moves ... or
  touched by another player before being kicked into the goal"); otherwise the opponents get
  a goal kick. :attr:`HumanoidGameController.indirect` says whether a goal by the restarting
  team would not count yet (a throw-in, and a kick-off under the rule above).
* **Own goals from a restart** (Laws 13, 15-17; the virtual referee applies it to kick-offs
  too): a ball that the team taking a kick-off, throw-in, goal kick or corner kick puts
  directly into its own goal (before another player touched it or anybody touched it after it
  was in play) gives the opponents a corner kick instead of a goal.
* **Goals** (Law 10): the whole ball over the goal line between the posts and under the
  crossbar (:func:`~soccer_env.sim.referee.classify_exit`); blue attacks +x. The team that
  conceded kicks off.
* **Removal penalty** (Law 13; Section II, removal penalty): the robot is taken off the field
  (``Decision.send_off``) and comes back (``Decision.bring_on``) after
  :attr:`~HumanoidRuleSpec.removal_time` (10 s in 2025) of time. Each counts in the team's
  :attr:`~soccer_env.sim.game.TeamInfo.fouls`; the robots off are its ``off``.
* **Halves** (Law 7): two equal halves of ``duration / 2`` (10 minutes each in the laws), no
  half-time interval in the virtual competition, and the clock never stops (nor in READY and
  SET, Law 7). The second half is kicked off by the team that did not kick off the first
  (Law 8, virtual competition); the teams keep their ends (the simulated field is symmetric).
  The match ends after the second half (``Decision.over``). Extra time and penalty
  shoot-outs are not played.

Commands (SSL names): ``normal_start`` (a kick-off, before and after the ball is in play),
``direct_free`` (for a throw-in, goal kick or corner kick), ``force_start`` (after a dropped
ball) and ``stop`` (before the start and after the end). There is no next command and no ball
placement by the robots: :attr:`~HumanoidGameController.next_command` is always None and
:attr:`~HumanoidGameController.designated` is the spot of the current (or last) restart.

Not implemented: fouls in play (pushing, ball holding, Law 12), penalty kicks (Law 14),
fallen, inactive or off-turf robots (Section II, incapable players), cards and warnings,
players outside their own half at a kick-off, the kicking robot removed before its goal
(Law 10), and the referee's discretion.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec
from soccer_env.presets.rules import HumanoidRuleSpec
from soccer_env.sim.ball import BallExit
from soccer_env.sim.game.state import RefereeState
from soccer_env.sim.game.types import SITUATIONS, STAGES, Decision, Frame, GameEvent
from soccer_env.sim.referee import (
    ExitKind,
    classify_exit,
    defending_team,
    exit_end,
    exit_side,
    restart_team,
)

__all__ = ["HumanoidGameController", "HUMANOID_COMMANDS", "HUMANOID_FOULS", "RESTARTS"]

#: Commands the humanoid flow issues (a subset of :data:`~soccer_env.sim.game.COMMANDS`).
HUMANOID_COMMANDS = ("stop", "normal_start", "direct_free", "force_start")
#: The restarts (Laws 8, 15-17): the kinds of :attr:`HumanoidGameController.restart_kind`.
RESTARTS = ("kickoff", "throw_in", "goal_kick", "corner_kick", "drop_ball")
#: Game events that are fouls, each giving a removal penalty (Law 13, Section II).
HUMANOID_FOULS = ("defender_too_close_to_kick_point",)

# Timers compare with this slack, so that a sum of control steps reaches a limit (10 s, 120 s).
_TIME_EPS = 1e-9


class HumanoidGameController(RefereeState):
    """The autonomous referee of one Humanoid League match (see the module docstring).

    Args:
        field: the match's field.
        ball: the match's ball.
        teams: ``(N,)`` team of each robot (0 blue, 1 yellow), blue first.
        radii: ``(N,)`` robot footprint radii [m].
        rules: the rule preset (:class:`~soccer_env.presets.rules.HumanoidRuleSpec`).
        duration: playing time of the match [s] (two halves of half of it each).
        rng: the match's random generator (the humanoid flow draws nothing from it; kept for
            the interface of :class:`~soccer_env.sim.game.GameController`).

    Read-only state for the teams' observations: :attr:`command`, :attr:`command_team`,
    :attr:`designated`, :attr:`stage`, :attr:`stage_time_left`, :attr:`in_play`,
    :attr:`team_info`, :attr:`next_command` (always None), :attr:`restart_kind`.
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, teams: Sequence[int],
                 radii: Sequence[float], rules: HumanoidRuleSpec, duration: float,
                 rng: np.random.Generator) -> None:
        if not isinstance(rules, HumanoidRuleSpec):
            raise TypeError(f"rules must be a HumanoidRuleSpec, got {type(rules).__name__}")
        self._init_referee(field, ball, teams, radii, duration, rng)
        self.rules = rules
        self.stage = STAGES[0]
        self.stage_time_left = self.stage_duration
        #: The restart being taken, or the last one (one of :data:`RESTARTS`), None before
        #: the start.
        self.restart_kind: str | None = None
        self._started = False
        self._removed: dict[int, float] = {}  # robot -> removal time left [s]
        self._exit: ExitKind | None = None
        self._robot_reach = float(self.radii.max()) if self.radii.size else 0.0
        self._new_restart(None, -1, None)

    # ------------------------------------------------------------------------------------
    # Public
    # ------------------------------------------------------------------------------------

    def start(self, kickoff_team: int, time: float = 0.0) -> Decision:
        """Begin the match with ``kickoff_team``'s kick-off (the simulation has lined the
        teams up; Law 8): command ``normal_start`` at once."""
        if kickoff_team not in (0, 1):
            raise ValueError(f"kickoff_team must be 0 or 1, got {kickoff_team!r}")
        self.first_kickoff = int(kickoff_team)
        self.time = float(time)
        self._started = True
        d = Decision()
        self._kickoff(self.first_kickoff, d, line_up=False)
        return d

    @property
    def stage_duration(self) -> float:
        """Playing time of one half [s] (Law 7)."""
        return self.duration / 2.0

    @property
    def clock_running(self) -> bool:
        """Whether playing time passes: always during the halves (Law 7)."""
        return self._started and self.stage != "post_game"

    def robots_allowed(self, team: int) -> int:
        """How many robots ``team`` may have on the field: its robots less those serving a
        removal penalty."""
        return int(np.sum(self.teams == team)) - len(self.team_info[team].off)

    def situation(self) -> tuple[str, int]:
        """What the game state means for the teams: ``(kind, team)`` with ``kind`` one of
        :data:`~soccer_env.sim.game.SITUATIONS` (``"stop"`` before the start and after the
        end, ``"kickoff"`` or ``"free_kick"`` until the restart's ball is in play,
        ``"running"`` after) and ``team`` the team taking the restart (-1 otherwise)."""
        if not self._started or self.stage == "post_game":
            kind, team = "stop", -1
        elif not self.in_play:
            kind = "kickoff" if self.restart_kind == "kickoff" else "free_kick"
            team = self._kick_team
        else:
            kind, team = "running", -1
        assert kind in SITUATIONS
        return kind, team

    @property
    def restart_team(self) -> int:
        """The team whose restart waits to be taken (-1: none)."""
        kind, team = self.situation()
        return team if kind in ("kickoff", "free_kick") else -1

    @property
    def barred_robot(self) -> int:
        """Always -1: the humanoid laws have no double-touch rule."""
        return -1

    @property
    def indirect(self) -> bool:
        """Whether a goal by the team of the current restart would not count yet: a throw-in
        (Law 15) or a kick-off (Law 8) whose ball has not yet been played as those laws
        require."""
        return self.restart_kind in ("kickoff", "throw_in") and not self._direct_ok

    @property
    def playing_time_left(self) -> float:
        """Playing time left in the match [s] (this half's and the next's)."""
        if self.stage == "post_game":
            return 0.0
        later = self.stage_duration if self.stage == "first_half" else 0.0
        return self.stage_time_left + later

    def step(self, frame: Frame) -> Decision:
        """Referee one control step (see the module docstring). After the end of the match
        every step returns a decision with ``over`` set."""
        if not self._started:
            raise RuntimeError("call start() before step()")
        d = Decision()
        if self.stage == "post_game":
            d.over = True
            return d
        dt = max(0.0, float(frame.time) - self.time)
        self.time = float(frame.time)
        ball = np.asarray(frame.ball, dtype=float)
        robots = np.asarray(frame.robots, dtype=float)
        toucher = [i for i, t in enumerate(frame.touched) if t]
        self._command_time += dt
        self._run_clocks(dt, d)
        self._exit = (None if frame.exit is None else
                      classify_exit(frame.exit, self.field, self.ball_spec))
        if self._exit is not None:
            d.exit_kind = self._exit.kind
        self._note_touches(toucher, ball)
        if not self.in_play:
            self._before_in_play(ball, robots, d)
        if frame.exit is not None:
            if not self.in_play:  # the ball left the field: it moved
                self._set_in_play(ball)
            self._ball_out(frame.exit, d)
        elif self.in_play:
            self._dropped_ball(ball, d)
        if self.stage_time_left <= 0.0:
            self._end_stage(d)
        return d

    # ------------------------------------------------------------------------------------
    # Clocks, stages and removal penalties
    # ------------------------------------------------------------------------------------

    def _run_clocks(self, dt: float, d: Decision) -> None:
        """The half's clock (Law 7) and the removal penalties (Section II), which run
        always."""
        self.stage_time_left = max(0.0, self.stage_time_left - dt)
        for i in list(self._removed):
            left = self._removed[i] - dt
            if left <= _TIME_EPS:
                del self._removed[i]
                self.team_info[int(self.teams[i])].off.remove(i)
                d.bring_on.append(i)
            else:
                self._removed[i] = left

    def _end_stage(self, d: Decision) -> None:
        """End of a half (Law 7): the second half's kick-off by the team that did not kick
        off the first (Law 8), or the end of the match."""
        if self.stage == "first_half":
            self.stage = "second_half"
            self.stage_time_left = self.stage_duration
            d.events.append(GameEvent("stage_changed"))
            self._kickoff(1 - self.first_kickoff, d, line_up=True)
            return
        self._end_match(d)

    def _remove(self, i: int, kind: str, x: float, y: float, d: Decision) -> None:
        """A removal penalty for robot ``i`` (Law 13; Section II, removal penalty)."""
        t = int(self.teams[i])
        info = self.team_info[t]
        d.events.append(GameEvent(kind, t, i, x, y))
        info.fouls += 1
        info.off.append(i)
        self._removed[i] = self.rules.removal_time
        d.send_off.append(i)

    # ------------------------------------------------------------------------------------
    # Restarts
    # ------------------------------------------------------------------------------------

    def _new_restart(self, kind: str | None, team: int,
                     spot: tuple[float, float] | None) -> None:
        """Forget the previous restart and begin ``kind`` for ``team`` at ``spot``."""
        self.restart_kind = kind
        self._kick_team = team
        self._kick_point = spot
        self.designated = spot
        self._command_time = 0.0
        self._kicker = -1
        self._last_touch = -1
        self._left_circle = False
        # May the restart's team score in the opponents' goal, and in its own, yet?
        self._direct_ok = kind not in ("kickoff", "throw_in")
        self._own_ok = kind in (None, "drop_ball")
        self._progress_anchor: tuple[float, float] | None = None
        self._progress_time = self.time

    def _kickoff(self, team: int, d: Decision, line_up: bool) -> None:
        """A kick-off for ``team`` (Law 8); the teams lined up by the simulation."""
        self._new_restart("kickoff", team, (0.0, 0.0))
        self._set_command("normal_start", team)
        self.in_play = False
        if line_up:
            d.line_up = ("kickoff", team)

    def _interrupt(self, kind: str, team: int, spot: tuple[float, float], d: Decision
                   ) -> None:
        """A game interruption (throw-in, goal kick, corner kick) for ``team`` at ``spot``:
        the ball placed there, the opponents moved out to the distance they must keep
        (Section II, game interruption procedure)."""
        self._new_restart(kind, team, spot)
        self._set_command("direct_free", team)
        self.in_play = False
        d.place_ball = spot
        d.clear = (self.rules.opponent_distance + self._robot_reach, team)

    def _drop(self, d: Decision) -> None:
        """A dropped ball (Law 8): on the centre mark, every robot out of the centre circle,
        in play at once."""
        self._new_restart("drop_ball", -1, (0.0, 0.0))
        self._set_command("force_start", -1)
        d.place_ball = (0.0, 0.0)
        d.clear = (self.field.center_circle_radius + self._robot_reach, -1)
        self.in_play = True
        self._progress_anchor = (0.0, 0.0)
        self._progress_time = self.time

    def _set_in_play(self, ball: np.ndarray) -> None:
        self.in_play = True
        self._progress_anchor = (float(ball[0]), float(ball[1]))
        self._progress_time = self.time

    def _note_touches(self, toucher: list[int], ball: np.ndarray) -> None:
        """Who touched the ball, and whether that lifts the restart's restrictions on goals
        (Laws 8, 13, 15-17): a touch by a player other than the kicker, a touch after the
        ball was in play, and at a kick-off a touch after the ball left the centre circle.
        The state before this step decides ("after")."""
        kt = self._kick_team
        for i in toucher:
            self._last_touch = i
            if kt < 0:
                continue
            t = int(self.teams[i])
            if self._kicker < 0 and t == kt:
                self._kicker = i
                other = False
            else:
                other = t != kt or i != self._kicker
            if other or self.in_play:
                self._own_ok = True
            if other or (self.restart_kind == "throw_in" and self.in_play) or \
                    (self.restart_kind == "kickoff" and self._left_circle):
                self._direct_ok = True
        if self.restart_kind == "kickoff" and not self._left_circle and \
                math.hypot(float(ball[0]), float(ball[1])) > \
                self.field.center_circle_radius + self.ball_spec.radius:
            self._left_circle = True

    def _before_in_play(self, ball: np.ndarray, robots: np.ndarray, d: Decision) -> None:
        """A kick-off or game interruption before its ball is in play: opponents inside the
        centre circle (Law 8) or nearer the ball than they must be (Law 13) get a removal
        penalty; the ball is in play after it moved 5 cm or after 10 s (Laws 8, 13)."""
        r = self.rules
        bx, by = float(ball[0]), float(ball[1])
        team = self._kick_team
        if team >= 0:
            for i in range(len(self.teams)):
                if int(self.teams[i]) == team or not self._on_field(i):
                    continue
                x, y = float(robots[i, 0]), float(robots[i, 1])
                if self.restart_kind == "kickoff":
                    close = math.hypot(x, y) - self.radii[i] < self.field.center_circle_radius
                else:
                    close = math.hypot(x - bx, y - by) < r.opponent_distance
                if close:
                    self._remove(i, "defender_too_close_to_kick_point", bx, by, d)
        kx, ky = self._kick_point if self._kick_point is not None else (bx, by)
        if math.hypot(bx - kx, by - ky) >= r.ball_in_play_distance or \
                self._command_time >= r.in_play_time - _TIME_EPS:
            self._set_in_play(ball)

    def _dropped_ball(self, ball: np.ndarray, d: Decision) -> None:
        """Law 8 (virtual competition): the ball moved less than 5 cm in 2 minutes."""
        p = (float(ball[0]), float(ball[1]))
        a = self._progress_anchor
        if a is None or math.hypot(p[0] - a[0], p[1] - a[1]) >= self.rules.dropped_ball_distance:
            self._progress_anchor = p
            self._progress_time = self.time
            return
        if self.time - self._progress_time >= self.rules.dropped_ball_time - _TIME_EPS:
            d.events.append(GameEvent("drop_ball", -1, -1, p[0], p[1]))
            self._drop(d)

    # ------------------------------------------------------------------------------------
    # Ball out of play
    # ------------------------------------------------------------------------------------

    def _ball_out(self, ex: BallExit, d: Decision) -> None:
        """Goals (Laws 8, 10, 15) and the ball leaving the field (Laws 15-17)."""
        kind = self._exit
        f, inset = self.field, self.rules.line_inset
        hx, hy = f.half_length - inset, f.half_width - inset
        last = self._last_touch
        last_team = int(self.teams[last]) if last >= 0 else -1
        side = exit_side(ex)
        if kind.kind == "goal":
            s = kind.scorer
            kt = self._kick_team
            if kt < 0 or (self._direct_ok if s == kt else self._own_ok):
                self._goal(s, last, ex, d)
                return
            d.events.append(GameEvent("invalid_goal", s, last, ex.x, ex.y))
            if s == kt:  # directly into the opponents' goal: their goal kick (Laws 8, 15)
                self._interrupt("goal_kick", 1 - s, (0.0, side * hy), d)
            else:  # directly into its own goal: the opponents' corner kick (Laws 13, 15-17)
                self._interrupt("corner_kick", s, (kind.end * hx, side * hy), d)
            return
        if kind.kind == "touch":
            d.events.append(GameEvent("ball_left_field_touch_line", last_team, last, ex.x,
                                      ex.y))
            team = restart_team(last_team, ex, kind)
            x = float(np.clip(ex.x, -hx, hx))
            self._interrupt("throw_in", team, (x, side * hy), d)
            return
        # Over a goal line outside the goal, or over the crossbar.
        end = exit_end(ex, kind)
        defender = defending_team(end)
        d.events.append(GameEvent("ball_left_field_goal_line", last_team, last, ex.x, ex.y))
        if restart_team(last_team, ex, kind) != defender:  # the defenders' touch
            self._interrupt("corner_kick", 1 - defender, (end * hx, side * hy), d)
        else:  # the attackers' touch, or nobody's
            self._interrupt("goal_kick", defender, (0.0, side * hy), d)

    def _goal(self, scorer: int, last: int, ex: BallExit, d: Decision) -> None:
        """A valid goal (Law 10): the team that conceded kicks off (Law 8)."""
        self._score(scorer, last, ex, d)
        self._kickoff(1 - scorer, d, line_up=True)
