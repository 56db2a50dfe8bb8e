"""The SSL fouls and cards (8.4, 5.5) of :class:`~soccer_env.sim.game.GameController`.

:class:`FoulRules` holds the controller's foul detectors and the bookkeeping of fouls and
cards: each detector reads the step's truth and records its fouls as game events against a
team (:meth:`FoulRules._foul`: the grace period between two fouls of a kind, the foul counter,
a card every :attr:`~soccer_env.presets.rules.RuleSpec.fouls_per_card` fouls); a stopping
foul stops the game for a free kick of the other team through the restart flow's
:meth:`~soccer_env.sim.game.restarts.RestartRules._stop`.
"""

from __future__ import annotations

import math

import numpy as np

from soccer_env.sim.game.checks import contacts_started
from soccer_env.sim.game.geometry import (
    defense_distance,
    inside_defense,
    robot_gap,
    valid_free_kick,
)
from soccer_env.sim.game.state import RefereeState
from soccer_env.sim.game.types import CONTACT_SLACK, Decision, GameEvent

__all__ = ["FoulRules"]


class FoulRules(RefereeState):
    """The fouls and cards of the SSL game controller (see the module docstring): a part of
    :class:`~soccer_env.sim.game.GameController`, whose state (``rules``, ``options``, the
    restart's and the step's bookkeeping) it reads and writes, and whose ``_stop`` it calls.
    """

    # ------------------------------------------------------------------------------------
    # Counting fouls and giving cards
    # ------------------------------------------------------------------------------------

    def _foul(self, d: Decision, kind: str, team: int, robot: int, x: float, y: float,
              count: bool = True) -> bool:
        """Record a foul of ``team`` (unless one of the same kind by the team lies within
        the grace period); returns whether it counted."""
        key = (team, kind)
        if self.time - self._last_foul.get(key, -math.inf) < self.rules.grace_period:
            return False
        self._last_foul[key] = self.time
        d.events.append(GameEvent(kind, team, robot, x, y))
        if not count:
            return True
        info = self.team_info[team]
        info.fouls += 1
        if self.options.cards and info.fouls % self.rules.fouls_per_card == 0:
            self._card(d, team)
        return True

    def _card(self, d: Decision, team: int) -> None:
        """A yellow card for ``team`` (a red one when it has enough running; 5.5)."""
        info = self.team_info[team]
        red = len(info.yellow_cards) >= self.rules.cards_for_red
        if red:
            info.red_cards += 1
        else:
            info.yellow_cards.append(self.rules.yellow_card_time)
        d.events.append(GameEvent("red_card" if red else "yellow_card", team))
        if info.returning:  # a robot waiting to come back stays off instead
            info.off.append(info.returning.pop())
            return
        members = [int(i) for i in np.flatnonzero(self.teams == team) if int(i) not in info.off]
        candidates = [i for i in members if i != self.keepers[team]]
        if len(members) <= 1 or not candidates:
            return  # a team keeps at least one robot
        robot = max(candidates)
        info.off.append(robot)
        d.send_off.append(robot)

    def _stopping_foul(self, d: Decision, kind: str, team: int, robot: int, x: float,
                       y: float, ball: np.ndarray, indirect: bool = False) -> None:
        """A stopping foul of ``team``: stop, then a free kick for the other team from
        ``(x, y)`` (8.4.1)."""
        if self._foul(d, kind, team, robot, x, y):
            spot = valid_free_kick(self.field, self.rules, x, y)
            self._stop(d, ("direct_free", 1 - team), spot, 1 - team, ball,
                       indirect=indirect and self.options.free_kicks == "2019")

    def _nonstop_foul(self, d: Decision, kind: str, team: int, robot: int, x: float,
                      y: float) -> None:
        if self._foul(d, kind, team, robot, x, y):
            self._last_nonstop_foul[team] = self.time

    # ------------------------------------------------------------------------------------
    # The ball in play
    # ------------------------------------------------------------------------------------

    def _referee_touches(self, ball: np.ndarray, robots: np.ndarray, toucher: list[int],
                         d: Decision) -> bool:
        """Fouls of the robots that touched the ball; True if the game stopped."""
        bx, by = float(ball[0]), float(ball[1])
        for i in toucher:
            t = int(self.teams[i])
            x, y, rad = float(robots[i, 0]), float(robots[i, 1]), float(self.radii[i])
            if i != self.keepers[t] and inside_defense(self.field, x, y, t, margin=rad):
                d.events.append(GameEvent("defender_in_defense_area", t, i, bx, by))
                self._stop(d, ("prepare_penalty", 1 - t), None, placer=None)
                return True
            if defense_distance(self.field, x, y, 1 - t) < rad:
                self._nonstop_foul(d, "attacker_touched_ball_in_defense_area", t, i, bx, by)
        self._speed_fouls(ball, toucher, d)
        return False

    def _speed_fouls(self, ball: np.ndarray, toucher: list[int], d: Decision) -> None:
        """A robot that touched the ball this step and left it faster than the limit, in
        3-D (8.4.2)."""
        speed = math.sqrt(float(ball[3]) ** 2 + float(ball[4]) ** 2 + float(ball[5]) ** 2)
        if speed > self.rules.ball_speed_limit and speed > self._prev_ball_speed:
            for i in toucher:
                self._nonstop_foul(d, "bot_kicked_ball_too_fast", int(self.teams[i]), i,
                                   float(ball[0]), float(ball[1]))

    def _referee_crashes(self, robots: np.ndarray, d: Decision) -> None:
        """Crashing (8.4.2): robots of different teams that came into contact this step
        (the pairs found by :func:`~soccer_env.sim.game.checks.contacts_started`) and closed
        faster than :attr:`~RuleSpec.crash_speed`."""
        prev = self._prev_robots
        if prev is None or prev.shape != robots.shape:
            return
        r = self.rules
        on_field = np.ones(len(self.teams), dtype=np.bool_)
        for info in self.team_info:
            on_field[info.off] = False
        pairs = np.empty((len(self.teams) ** 2, 2), dtype=np.int64)
        n = contacts_started(robots, prev, self.teams, on_field, self.radii,
                             CONTACT_SLACK, pairs)
        for i, j in pairs[:n].tolist():
            if not (self._on_field(i) and self._on_field(j)):
                continue  # sent off by a card for an earlier pair of this step
            before = math.hypot(*(prev[j, 0:2] - prev[i, 0:2]))
            u = (prev[j, 0:2] - prev[i, 0:2]) / max(before, 1e-9)
            closing = float(np.dot(prev[i, 3:5] - prev[j, 3:5], u))
            if closing <= r.crash_speed:
                continue
            si, sj = math.hypot(*prev[i, 3:5]), math.hypot(*prev[j, 3:5])
            x, y = (robots[i, 0:2] + robots[j, 0:2]) / 2
            if abs(si - sj) < r.crash_both_margin:
                for k in (i, j):
                    self._nonstop_foul(d, "bot_crash_drawn", int(self.teams[k]), k, x, y)
            else:
                k = i if si > sj else j
                self._nonstop_foul(d, "bot_crash_unique", int(self.teams[k]), k, x, y)

    def _keeper_held(self, ball: np.ndarray, dt: float, d: Decision) -> bool:
        """The ball kept in a defense area too long (8.4.1); True if the game stopped."""
        bx, by = float(ball[0]), float(ball[1])
        for t in (0, 1):
            if inside_defense(self.field, bx, by, t):
                if t not in self._held_since:
                    self._held_since[t] = 0.0
                    self._held_start[t] = (bx, by)
                self._held_since[t] += dt
                if self._held_since[t] > self.rules.keeper_held_time:
                    x, y = self._held_start[t]
                    self._stopping_foul(d, "keeper_held_ball", t, self.keepers[t], x, y, ball)
                    return True
            else:
                self._held_since.pop(t, None)
        return False

    # ------------------------------------------------------------------------------------
    # The ball out of play
    # ------------------------------------------------------------------------------------

    def _kick_point_fouls(self, robots: np.ndarray, team: int, bx: float, by: float,
                          d: Decision) -> None:
        """Opponents of the kicking ``team`` nearer the kick point than
        :attr:`~RuleSpec.stop_distance` before the ball is in play (8.4.3; not at a penalty
        kick); each such foul restarts the kicking team's timer."""
        r = self.rules
        kx, ky = self._kick_point
        for i in range(len(self.teams)):
            if int(self.teams[i]) == team or not self._on_field(i):
                continue
            if robot_gap(robots, self.radii, i, kx, ky) < r.stop_distance and not self._penalty:
                if self._foul(d, "defender_too_close_to_kick_point", int(self.teams[i]),
                              i, bx, by):
                    self._command_time = 0.0  # the kicking team's timer restarts

    def _too_close_to_defense(self, ball: np.ndarray, robots: np.ndarray,
                              d: Decision) -> bool:
        """A robot too close to the opponent defense area during stop or a free kick
        (8.4.1, after the grace period); True if the game stopped."""
        for i in range(len(self.teams)):
            t = int(self.teams[i])
            if not self._on_field(i):
                continue
            gap = defense_distance(self.field, float(robots[i, 0]), float(robots[i, 1]), 1 - t) \
                - self.radii[i]
            if gap < self.rules.defense_area_distance:
                self._stopping_foul(d, "attacker_too_close_to_defense_area", t, i,
                                    float(ball[0]), float(ball[1]), ball)
                return True
        return False

    def _stop_speed_fouls(self, robots: np.ndarray, d: Decision) -> None:
        """Robots faster than :attr:`~RuleSpec.stop_speed` during stop (8.4.3), each counted
        once per stop."""
        r = self.rules
        for i in range(len(self.teams)):
            if i in self._stop_speed_fouled or not self._on_field(i):
                continue
            if math.hypot(float(robots[i, 3]), float(robots[i, 4])) > r.stop_speed:
                self._stop_speed_fouled.add(i)
                self._foul(d, "bot_too_fast_in_stop", int(self.teams[i]), i,
                           float(robots[i, 0]), float(robots[i, 1]))
