"""The SSL restarts (5.1-5.3) of :class:`~soccer_env.sim.game.GameController`: stopping the
game, ball placement by the teams or the referee, and the kick-off, free kick or penalty
kick until its ball is in play.

:class:`RestartRules` holds what the controller does while the ball is out of play: it
issues the commands of a restart (:meth:`RestartRules._stop`, :meth:`RestartRules._issue`),
referees the stop and the ball placement, and puts the ball in play once it has moved or its
time is up (the fouls of those phases are :class:`~soccer_env.sim.game.fouls.FoulRules`').
"""

from __future__ import annotations

import math

import numpy as np

from soccer_env.sim.game.geometry import (
    defense_distance,
    penalty_mark,
    robot_gap,
    segment_distance,
)
from soccer_env.sim.game.state import RefereeState
from soccer_env.sim.game.types import STATIONARY_SPEED, Decision, Frame, GameEvent

__all__ = ["RestartRules"]


class RestartRules(RefereeState):
    """The restarts of the SSL game controller (see the module docstring): a part of
    :class:`~soccer_env.sim.game.GameController`, whose state it reads and writes, and
    whose fouls (``_foul``, ``_speed_fouls``, ``_kick_point_fouls``, ``_stop_speed_fouls``,
    ``_too_close_to_defense``) and ball-out handling (``_note_touches``, ``_ball_out``) it
    calls.
    """

    # ------------------------------------------------------------------------------------
    # Commands
    # ------------------------------------------------------------------------------------

    def _reset_restart(self) -> None:
        """Forget what belonged to the previous restart."""
        self._command_time = 0.0
        self._kick_point: tuple[float, float] | None = None
        self._kicker = -1
        self._kick_team = -1
        self._indirect = False
        self._indirect_ok = False
        self._penalty = False
        self._penalty_dir: np.ndarray | None = None
        self._placer = -1
        self._placement_left = 0.0
        self._placement_first: tuple[str, int] | None = None
        self._interference: dict[int, float] = {}
        self._interference_counted = False
        # Robots whose interference has extended this placement's timer (once each: a robot
        # that cannot get out of the way does not hold the game up for ever).
        self._extended: set[int] = set()
        self._stop_speed_fouled: set[int] = set()
        self._progress_anchor: np.ndarray | None = None
        self._progress_time = 0.0
        self._held_since: dict[int, float] = {}
        self._held_start: dict[int, tuple[float, float]] = {}
        self._last_touch = -1
        self._last_touch_point: tuple[float, float] | None = None
        self._crossed_half = False
        self._last_foul: dict[tuple[int, str], float] = {}
        self._touched_by_other = False
        self._prev_ball_speed = 0.0

    def _issue(self, command: str, team: int, position: tuple[float, float] | None,
               d: Decision, line_up: bool = True) -> None:
        """Issue a restart command (after stop or placement)."""
        self._reset_restart()
        self.designated = position
        self.next_command = None
        self.in_play = False
        if command == "prepare_kickoff":
            self._set_command("prepare_kickoff", team)
            if line_up:
                d.line_up = ("kickoff", team)
            self._kick_team = team
            self._kick_point = (0.0, 0.0)
        elif command == "prepare_penalty":
            self._set_command("prepare_penalty", team)
            d.line_up = ("penalty", team)
            self._kick_team = team
            self._penalty = True
            mark = penalty_mark(self.field, self.rules, team)
            self._kick_point = mark
            self.designated = mark
        elif command == "direct_free":
            self._set_command("direct_free", team)
            self._kick_team = team
            # Where the ball lies when the kick is issued (within the placement tolerance of
            # the designated position): read from the first frame.
            self._kick_point = None
            self._indirect = self._pending_indirect
        elif command == "force_start":
            self._set_command("force_start", -1)
            self.in_play = True
        else:  # pragma: no cover - programming error
            raise ValueError(f"cannot issue {command!r}")
        self._pending_indirect = False

    def _stop(self, d: Decision, next_command: tuple[str, int],
              position: tuple[float, float] | None, placer: int | None,
              ball: np.ndarray | None = None, indirect: bool = False,
              out: bool = False) -> None:
        """Stop the game; the ball goes to ``position`` (placed by ``placer``'s robots, or
        by the referee for None), then ``next_command`` follows. ``out``: the free kick
        follows the ball leaving the field (it goes to the other team when ``placer`` may not
        place; 5.2)."""
        self._reset_restart()
        self.in_play = False
        self.next_command = next_command
        self.designated = position
        self._pending_indirect = indirect
        for info in self.team_info:  # cards expired: back at this stop
            d.bring_on.extend(info.returning)
            info.returning = []
        if position is not None and placer is not None and ball is not None and \
                self.options.placement == "robots" and self._needs_placement(ball, position):
            if self.team_info[placer].can_place:
                self._start_placement(placer, next_command)
                return
            if out and self.team_info[1 - placer].can_place:
                # A team that may not place loses the free kick to the other (5.2).
                self.next_command = ("direct_free", 1 - placer)
                self._start_placement(1 - placer, self.next_command)
                return
        self._set_command("stop", -1)
        if position is not None and (ball is None or self._needs_placement(ball, position)):
            d.place_ball = position

    def _start_placement(self, team: int, next_command: tuple[str, int]) -> None:
        self._set_command("ball_placement", team)
        self._placer = team
        self._placement_left = self.rules.placement_time
        if self._placement_first is None:
            self._placement_first = next_command
        self._interference = {}
        self._interference_counted = False
        self._extended = set()

    def _needs_placement(self, ball: np.ndarray, position: tuple[float, float]) -> bool:
        """Whether the ball must be placed before the restart (5.2)."""
        r = self.rules
        bx, by = float(ball[0]), float(ball[1])
        near = math.hypot(bx - position[0], by - position[1]) < r.placement_skip_distance
        inside = abs(bx) <= self.field.half_length and abs(by) <= self.field.half_width
        clear = min(defense_distance(self.field, bx, by, t) for t in (0, 1)) >= \
            r.placement_skip_defense
        still = math.hypot(float(ball[3]), float(ball[4])) < STATIONARY_SPEED
        return not (near and inside and clear and still)

    # ------------------------------------------------------------------------------------
    # Ball out of play
    # ------------------------------------------------------------------------------------

    def _referee_restart(self, frame: Frame, ball: np.ndarray, robots: np.ndarray,
                         touched: list[bool], dt: float, d: Decision) -> None:
        cmd = self.command
        if cmd == "ball_placement":
            self._referee_placement(ball, robots, dt, d)
        elif cmd == "stop":
            self._referee_stop(ball, robots, d)
        elif cmd in ("prepare_kickoff", "prepare_penalty"):
            # The simulation lined the teams up: the normal start follows at once.
            self._set_command("normal_start", self.command_team)
            self._kick_point = (float(ball[0]), float(ball[1]))
        elif cmd in ("normal_start", "direct_free"):
            self._referee_kick(frame, ball, robots, touched, d)

    def _referee_kick(self, frame: Frame, ball: np.ndarray, robots: np.ndarray,
                      touched: list[bool], d: Decision) -> None:
        """A kick-off, free kick or penalty before the ball is in play."""
        r = self.rules
        bx, by = float(ball[0]), float(ball[1])
        team = self._kick_team
        if self._kick_point is None:
            self._kick_point = (bx, by)
        toucher = [i for i, t in enumerate(touched) if t]
        for i in toucher:
            if self._kicker < 0 and int(self.teams[i]) == team:
                self._kicker = i
        self._note_touches(toucher, bx, by)
        if self.options.fouls:
            self._speed_fouls(ball, toucher, d)
        moved = math.hypot(bx - self._kick_point[0], by - self._kick_point[1])
        limit = (r.penalty_time if self._penalty else
                 r.kickoff_time if self.command == "normal_start" else r.free_kick_time)
        if self.options.fouls and moved < r.ball_in_play_distance:
            self._kick_point_fouls(robots, team, bx, by, d)
            if self.command == "direct_free" and self._command_time > r.grace_period and \
                    self._too_close_to_defense(ball, robots, d):
                return
        if moved >= r.ball_in_play_distance or self._command_time > limit:
            self.in_play = True
            self._touched_by_other = False
            if moved < r.ball_in_play_distance:
                self._kicker = -1  # in play by time: nobody kicked
            self._progress_anchor = None
            if frame.exit is not None:
                self._ball_out(frame, ball, d)

    def _referee_stop(self, ball: np.ndarray, robots: np.ndarray, d: Decision) -> None:
        """Stop: the speed limit, then the next command once robots keep their distance."""
        r = self.rules
        if self.options.fouls and self._command_time > r.grace_period:
            self._stop_speed_fouls(robots, d)
            if self.next_command and self.next_command[0] == "direct_free" and \
                    self._too_close_to_defense(ball, robots, d):
                return
        if self.next_command is None:
            return
        bx, by = float(ball[0]), float(ball[1])
        ready = all(robot_gap(robots, self.radii, i, bx, by) >= r.stop_distance
                    for i in range(len(self.teams)) if self._on_field(i))
        if (ready and self._command_time >= r.placement_min_time) or \
                self._command_time >= r.stage_pause:
            cmd, team = self.next_command
            self._issue(cmd, team, self.designated, d)

    def _referee_placement(self, ball: np.ndarray, robots: np.ndarray, dt: float,
                           d: Decision) -> None:
        """Ball placement by ``self._placer`` (5.2, 8.4.3)."""
        r = self.rules
        team = self._placer
        target = self.designated
        bx, by = float(ball[0]), float(ball[1])
        self._placement_left -= dt
        # Interference: the other team near the segment from the ball to the target.
        for i in range(len(self.teams)):
            if int(self.teams[i]) == team or not self._on_field(i):
                self._interference.pop(i, None)
                continue
            gap = segment_distance(float(robots[i, 0]), float(robots[i, 1]), bx, by,
                                    *target) - self.radii[i]
            if gap < r.placement_interference_distance:
                self._interference[i] = self._interference.get(i, 0.0) + dt
                if self._interference[i] > r.grace_period:
                    self._interference[i] = 0.0
                    if i not in self._extended:
                        self._extended.add(i)
                        self._placement_left += r.placement_interference_penalty
                    if self.options.fouls and not self._interference_counted:
                        self._interference_counted = True
                        self._foul(d, "bot_interfered_placement", int(self.teams[i]), i,
                                   float(robots[i, 0]), float(robots[i, 1]))
            else:
                self._interference.pop(i, None)
        nxt = self.next_command
        clearance = (r.placement_clearance if nxt[0] == "direct_free" and nxt[1] == team
                     else r.stop_distance)
        placed = (math.hypot(bx - target[0], by - target[1]) <= r.placement_tolerance
                  and math.hypot(float(ball[3]), float(ball[4])) < STATIONARY_SPEED
                  and all(robot_gap(robots, self.radii, i, bx, by) >= clearance
                          for i in range(len(self.teams)) if self._on_field(i)))
        info = self.team_info[team]
        if placed and self._command_time >= r.placement_min_time:
            info.placement_failures = max(0, info.placement_failures - 1)
            d.events.append(GameEvent("placement_succeeded", team, -1, bx, by))
            self._issue(nxt[0], nxt[1], target, d)
            return
        if self._placement_left > 0.0:
            return
        info.placement_failures += 1
        if info.placement_failures >= r.max_placement_failures:
            info.can_place = False
        d.events.append(GameEvent("placement_failed", team, -1, bx, by))
        first = self._placement_first
        other = 1 - team
        if nxt[0] in ("direct_free", "force_start") and self.team_info[other].can_place and \
                first == nxt:
            # The free kick goes to the other team, which places in turn.
            self.next_command = ("direct_free", other)
            self._pending_indirect = self.options.free_kicks == "2019"
            self._start_placement(other, self.next_command)
            self._placement_first = first
            return
        # Both failed (or the other may not place): the referee places, and the original
        # command follows.
        self.next_command = first
        self._set_command("stop", -1)
        d.place_ball = target
