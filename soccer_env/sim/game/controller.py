"""The SSL game controller itself (:class:`GameController`): the public surface an
environment drives and observes, the match clock and its stages, and the referee of the ball
in play (touches, goals and the ball leaving the field, the penalty kick in play, no
progress); the rules are described in :mod:`soccer_env.sim.game`. Its fouls and cards are
:class:`~soccer_env.sim.game.fouls.FoulRules`', its restarts
:class:`~soccer_env.sim.game.restarts.RestartRules`'.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec
from soccer_env.presets.rules import RuleSpec
from soccer_env.sim.ball import BallExit
from soccer_env.sim.game.fouls import FoulRules
from soccer_env.sim.game.geometry import valid_free_kick
from soccer_env.sim.game.restarts import RestartRules
from soccer_env.sim.game.types import (
    EARLY_END_GOALS,
    EARLY_END_LEAD,
    STAGES,
    STATIONARY_SPEED,
    Decision,
    Frame,
    GameEvent,
    GameOptions,
)
from soccer_env.sim.referee import (
    ExitKind,
    classify_exit,
    defending_team,
    exit_end,
    exit_side,
    free_kick_spot,
    restart_team,
)

__all__ = ["GameController"]


class GameController(FoulRules, RestartRules):
    """The referee and game controller of one SSL match (the rules:
    :mod:`soccer_env.sim.game`).

    Args:
        field: the match's field.
        ball: the match's ball.
        teams: ``(N,)`` team of each robot (0 blue, 1 yellow), blue first.
        radii: ``(N,)`` robot radii [m].
        rules: the rule preset.
        options: what is played.
        duration: playing time of the match [s] (two halves of half of it each).
        rng: draws the team that places the ball before a force start.

    Read-only state for the teams' observations: :attr:`command`, :attr:`command_team`,
    :attr:`designated`, :attr:`stage`, :attr:`stage_time_left`, :attr:`in_play`,
    :attr:`team_info`, :attr:`next_command`.
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, teams: Sequence[int],
                 radii: Sequence[float], rules: RuleSpec, options: GameOptions,
                 duration: float, rng: np.random.Generator) -> None:
        self._init_referee(field, ball, teams, radii, duration, rng)
        self.rules, self.options = rules, options
        hx = field.half_length
        mark = hx - rules.penalty_mark_distance
        if not -hx < mark < hx:
            raise ValueError(f"rules {rules.name!r}: the penalty mark lies "
                             f"{rules.penalty_mark_distance} m from the goal, outside field "
                             f"{field.name!r} ({field.length} m long)")
        self._stages = list(STAGES) if options.half_time else ["first_half", "post_game"]
        self.stage = self._stages[0]
        self.stage_time_left = self.stage_duration
        # Kept across restarts: the ball's height since each team's last touch (7), each
        # team's last non-stopping foul (7), the last frame's robots (crashing), and whether
        # the coming free kick is indirect.
        self._after_touch: dict[int, float] = {0: 0.0, 1: 0.0}
        self._last_nonstop_foul = [-math.inf, -math.inf]
        self._prev_robots: np.ndarray | None = None
        self._pending_indirect = False
        self._exit: ExitKind | None = None
        self._reset_restart()

    # ------------------------------------------------------------------------------------
    # Public
    # ------------------------------------------------------------------------------------

    def start(self, kickoff_team: int, time: float = 0.0) -> Decision:
        """Begin the match with ``kickoff_team``'s kick-off (the simulation has lined the
        teams up)."""
        self.first_kickoff = int(kickoff_team)
        self.time = float(time)
        d = Decision()
        self._issue("prepare_kickoff", self.first_kickoff, (0.0, 0.0), d, line_up=False)
        return d

    @property
    def clock_running(self) -> bool:
        """Whether playing time passes: a team may play the ball (4.4.1)."""
        return self.command in ("normal_start", "force_start", "direct_free")

    def robots_allowed(self, team: int) -> int:
        """How many robots ``team`` may have on the field."""
        info = self.team_info[team]
        return int(np.sum(self.teams == team)) - len(info.yellow_cards) - info.red_cards

    def situation(self) -> tuple[str, int]:
        """What the command means for the teams: ``(kind, team)`` with ``kind`` one of
        :data:`SITUATIONS` and ``team`` the team taking the restart or placing the ball (-1
        for stop and open play). A penalty kick stays ``"penalty"`` while its ball is in
        play (only the kicker and the keeper may play it)."""
        cmd = self.command
        if cmd == "stop":
            return "stop", -1
        if cmd == "ball_placement":
            return "placement", self.command_team
        if cmd == "prepare_kickoff":
            return "kickoff", self.command_team
        if cmd == "prepare_penalty" or (self._penalty and cmd == "normal_start"):
            return "penalty", self._kick_team
        if not self.in_play and cmd == "normal_start":
            return "kickoff", self._kick_team
        if not self.in_play and cmd == "direct_free":
            return "free_kick", self._kick_team
        return "running", -1

    @property
    def restart_team(self) -> int:
        """The team whose restart is being prepared or waits to be taken (-1: none, open
        play or a force start)."""
        kind, team = self.situation()
        if kind in ("kickoff", "penalty", "free_kick"):
            return -1 if kind == "penalty" and self.in_play else team
        if self.next_command is not None:
            return self.next_command[1]
        return -1

    @property
    def barred_robot(self) -> int:
        """The robot that may not touch the ball until another robot has (the kicker of a
        kick-off or free kick once the ball is in play, 8.2), or -1."""
        if self.in_play and self._kicker >= 0 and not self._touched_by_other:
            return self._kicker
        return -1

    @property
    def indirect(self) -> bool:
        """Whether the coming or running free kick is indirect and a goal by its team would
        not count yet (2019 rules)."""
        if self.next_command is not None:
            return self._pending_indirect
        return self._indirect and not self._indirect_ok

    @property
    def playing_time_left(self) -> float:
        """Playing time left in the match [s] (this stage's and the stages after it)."""
        stages = self._stages[self._stages.index(self.stage) + 1:]
        return self.stage_time_left + self.stage_duration * sum(
            s != "post_game" for s in stages)

    def step(self, frame: Frame) -> Decision:
        """Referee one control step (see the module docstring)."""
        d = Decision()
        dt = max(0.0, float(frame.time) - self.time)
        self.time = float(frame.time)
        ball = np.asarray(frame.ball, dtype=float)
        robots = np.asarray(frame.robots, dtype=float)
        touched = [bool(t) for t in frame.touched]
        self._command_time += dt
        if self.clock_running:
            self._run_clocks(dt, d)
        # How the ball left the field this step, classified once for every rule that asks.
        self._exit = (None if frame.exit is None else
                      classify_exit(frame.exit, self.field, self.ball_spec))
        if self._exit is not None:
            d.exit_kind = self._exit.kind
        if self.in_play or self.command == "force_start":
            self._referee_play(frame, ball, robots, touched, dt, d)
        else:
            self._referee_restart(frame, ball, robots, touched, dt, d)
        # After the simulation moves robots or the ball for the referee, the next frame's
        # motion is not theirs.
        self._prev_robots = None if (d.line_up or d.send_off or d.bring_on) else robots
        self._prev_ball_speed = math.sqrt(float(ball[3]) ** 2 + float(ball[4]) ** 2
                                          + float(ball[5]) ** 2)
        if not d.over and self.clock_running and self.stage_time_left <= 0.0 \
                and not (self._penalty and self.in_play):
            self._end_stage(d)
        return d

    # ------------------------------------------------------------------------------------
    # Clocks and stages
    # ------------------------------------------------------------------------------------

    @property
    def stage_duration(self) -> float:
        """Playing time of one stage [s]."""
        return self.duration / 2.0 if self.options.half_time else self.duration

    def _run_clocks(self, dt: float, d: Decision) -> None:
        self.stage_time_left = max(0.0, self.stage_time_left - dt)
        for info in self.team_info:
            left = [c - dt for c in info.yellow_cards]
            expired = sum(c <= 0.0 for c in left)
            info.yellow_cards = [c for c in left if c > 0.0]
            for _ in range(expired):
                if info.off:
                    info.returning.append(info.off.pop())

    def _end_stage(self, d: Decision) -> None:
        k = self._stages.index(self.stage) + 1
        if self._stages[k] == "post_game":
            self._end_match(d)
            return
        self.stage = self._stages[k]
        self.stage_time_left = self.stage_duration
        for info in self.team_info:  # placement rights are per half (5.2)
            info.can_place = True
            info.placement_failures = 0
        d.events.append(GameEvent("stage_changed"))
        self._stop(d, ("prepare_kickoff", 1 - self.first_kickoff), (0.0, 0.0), placer=None)

    # ------------------------------------------------------------------------------------
    # Ball in play
    # ------------------------------------------------------------------------------------

    def _referee_play(self, frame: Frame, ball: np.ndarray, robots: np.ndarray,
                      touched: list[bool], dt: float, d: Decision) -> None:
        bx, by, bz = float(ball[0]), float(ball[1]), float(ball[2])
        fouls = self.options.fouls
        toucher = [i for i, t in enumerate(touched) if t]
        # The ball's height since each team's last touch (7), and who touched it last.
        for t in (0, 1):
            self._after_touch[t] = max(self._after_touch[t], bz)
        for i in toucher:
            self._after_touch[int(self.teams[i])] = bz
        if self._indirect and any(int(self.teams[i]) == self._kick_team and
                                  (i != self._kicker or self._touched_by_other)
                                  for i in toucher):
            self._indirect_ok = True
        # Double touch (8.2): the kicker again before anyone else.
        if self._kicker >= 0 and toucher:
            others = [i for i in toucher if i != self._kicker]
            if self._kicker in toucher and not self._touched_by_other and not others:
                if fouls:
                    self._stopping_foul(d, "attacker_double_touched_ball",
                                        int(self.teams[self._kicker]), self._kicker, bx, by,
                                        ball, indirect=True)
                    return
            if others:
                self._touched_by_other = True
                self._kicker = -1
        if self._penalty and self._referee_penalty(frame, ball, toucher, d):
            return
        self._note_touches(toucher, bx, by)
        if frame.exit is not None:
            self._ball_out(frame, ball, d)
            return
        if fouls and self._referee_touches(ball, robots, toucher, d):
            return
        if fouls:
            self._referee_crashes(robots, d)
        if self._penalty:
            return
        if fouls and self._keeper_held(ball, dt, d):
            return
        self._no_progress(ball, d)

    def _note_touches(self, toucher: list[int], bx: float, by: float) -> None:
        """Who touched the ball last and where, and whether the ball crossed the halfway
        line since (for aimless kicks; a ball touched on the halfway line, as at a kick-off,
        does not cross it)."""
        if toucher:
            self._last_touch = toucher[-1]
            self._last_touch_point = (bx, by)
            self._crossed_half = False
        elif self._last_touch_point is not None:
            tx = self._last_touch_point[0]
            if abs(tx) > self.ball_spec.radius and (bx > 0.0) != (tx > 0.0):
                self._crossed_half = True

    def _no_progress(self, ball: np.ndarray, d: Decision) -> None:
        """No progress (8.1): the ball making no headway for too long."""
        p = np.asarray(ball[0:2], dtype=float)
        if self._progress_anchor is None or \
                math.hypot(*(p - self._progress_anchor)) > self.rules.no_progress_distance:
            self._progress_anchor = p
            self._progress_time = self.time
            return
        if self.time - self._progress_time > self.rules.no_progress_time:
            d.events.append(GameEvent("no_progress_in_game", -1, -1, float(p[0]),
                                      float(p[1])))
            spot = valid_free_kick(self.field, self.rules, float(p[0]), float(p[1]))
            placer = int(self.rng.integers(2))
            self._stop(d, ("force_start", -1), spot, placer, ball)

    def _ball_out(self, frame: Frame, ball: np.ndarray, d: Decision) -> None:
        """Goals and the ball leaving the field (6, 7)."""
        ex = frame.exit
        kind = self._exit
        last = self._last_touch
        last_team = int(self.teams[last]) if last >= 0 else -1
        if kind.kind == "goal":
            s = kind.scorer
            valid = (self._after_touch[s] <= self.rules.goal_ball_height
                     and self.time - self._last_nonstop_foul[s] > self.rules.goal_foul_window
                     and not (self._indirect and not self._indirect_ok
                              and self._kick_team == s))
            if valid:
                self._goal(s, ex, d)
                return
            d.events.append(GameEvent("invalid_goal", s, -1, ex.x, ex.y))
        if kind.kind == "touch":
            d.events.append(GameEvent("ball_left_field_touch_line", last_team, last, ex.x,
                                      ex.y))
            team = restart_team(last_team, ex, kind)
            spot = free_kick_spot(ex, kind, self.field, self.rules.line_margin)
            self._stop(d, ("direct_free", team), valid_free_kick(self.field, self.rules, *spot),
                       team, ball, indirect=self.options.free_kicks == "2019", out=True)
            return
        # Over a goal line outside the goal (or an invalid goal / over the bar).
        end = exit_end(ex, kind)
        defender = defending_team(end)
        side = exit_side(ex)
        hy = self.field.half_width - self.rules.line_margin
        aimless = (self.rules.division == "B" and last_team == 1 - defender
                   and self._crossed_half and self._last_touch_point is not None)
        if aimless:
            d.events.append(GameEvent("aimless_kick", last_team, last, ex.x, ex.y))
            spot = valid_free_kick(self.field, self.rules, *self._last_touch_point)
            self._stop(d, ("direct_free", defender), spot, defender, ball,
                       indirect=self.options.free_kicks == "2019", out=True)
            return
        d.events.append(GameEvent("ball_left_field_goal_line", last_team, last, ex.x, ex.y))
        team = restart_team(last_team, ex, kind)
        if team != defender:  # the defenders' touch: corner kick for the attackers
            x = end * (self.field.half_length - self.rules.line_margin)
        else:  # goal kick (the attackers' touch, or nobody's)
            x = end * (self.field.half_length - self.rules.goal_kick_distance)
        self._stop(d, ("direct_free", team), valid_free_kick(self.field, self.rules, x, side * hy),
                   team, ball, out=True)

    def _goal(self, scorer: int, ex: BallExit, d: Decision) -> None:
        """A valid goal: the match ends early (4.4.3) or the other team kicks off."""
        self._score(scorer, self._last_touch, ex, d)
        info = self.team_info[scorer]
        other = self.team_info[1 - scorer].goals
        if info.goals >= EARLY_END_GOALS and info.goals - other > EARLY_END_LEAD:
            self._end_match(d)
            return
        self._stop(d, ("prepare_kickoff", 1 - scorer), (0.0, 0.0), placer=None)

    def _referee_penalty(self, frame: Frame, ball: np.ndarray, toucher: list[int],
                         d: Decision) -> bool:
        """A penalty kick in play (5.3.5); True if it ended this step without a goal
        (a goal is :meth:`_ball_out`'s)."""
        team = self._kick_team
        if frame.exit is not None:
            kind = self._exit
            if kind.kind == "goal" and kind.scorer == team:
                self._goal(team, frame.exit, d)
                return True
        goal_dir = 1.0 if team == 0 else -1.0
        v = np.asarray(ball[3:5], dtype=float)
        defender = 1 - team
        keeper = self.keepers[defender]
        over = False
        if v @ v > STATIONARY_SPEED ** 2:
            if self._penalty_dir is not None and keeper in toucher and \
                    float(v @ self._penalty_dir) <= 0.0:
                over = True  # turned back by the keeper
            elif v[0] * goal_dir < -STATIONARY_SPEED:
                over = True  # the ball moved away from the goal
            self._penalty_dir = v / math.sqrt(float(v @ v))
        if self._command_time > self.rules.penalty_time or frame.exit is not None:
            over = True
        if over:
            hx = self.field.half_length - self.rules.goal_kick_distance
            spot = valid_free_kick(self.field, self.rules, goal_dir * hx, self.field.half_width
                                         - self.rules.line_margin)
            d.events.append(GameEvent("penalty_kick_failed", team, -1, float(ball[0]),
                                      float(ball[1])))
            self._stop(d, ("direct_free", defender), spot, defender, ball)
            return True
        return False
