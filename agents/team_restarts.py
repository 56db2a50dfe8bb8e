"""How :class:`~agents.team.ScriptedTeam` plays the game flow's restarts (SSL rules, 2025
edition; :mod:`soccer_env.sim.game`), from the referee state at the end of each robot's
observation (:data:`~soccer_env.envs.match.GAME_FLOW_NAMES`).

* **Stop**: every robot keeps ``stop_distance`` plus a robot radius and 10 cm from the ball
  (robots inside that circle leave it radially, the others go round it) and drives slower
  than 80 % of ``stop_speed``. The field players wait on their open-play spots, the one that
  would attack waiting behind the ball on the line to the goal it attacks (the own team's
  restart) or to the goal it defends (the opponents').
* **Ball placement by the own team**: the field player nearest the ball (the keeper when it
  is alone) fetches it: it stops between the designated position and the ball facing the
  ball, turns its dribbler on, and backs off to the designated position pulling the ball
  (which works against a wall too); with the ball there it turns the dribbler off and backs
  away, to the free kick's clearance when the free kick is its team's, else to the stop
  distance. The others keep the stop distance.
* **Ball placement by the opponents**: as stop, and also ``placement_interference_distance``
  plus a margin from the line between the ball and the designated position.
* **Kick-off, free kick or penalty kick of the own team**: the field player nearest the ball
  (the penalty kicker: the one the formation put behind the ball) takes it with one flat kick,
  no faster than the rules' ball speed limit: a shot when the goal is open, else a pass to the
  team-mate with the most open line, else a shot at the goal centre; the others hold their
  spots (at a kick-off outside the centre circle in the own
  half; at a penalty kick they stand still).
* **The opponents' kick-off, free kick or penalty kick**: every robot keeps the stop distance
  from the ball (at a kick-off also the own half); at a penalty kick only the keeper moves.
* **Open play**: as without the game flow, except that the robot that took a restart
  (``game.barred``) leaves the ball to the others until another robot has touched it (8.2).
* During stop and before a free kick is in play, every robot keeps ``defense_area_distance``
  plus a margin from the opponent defense area (8.4.1). Robots off the field stand still.

All positions are in the team frame [m], which attacks ``+x``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from soccer_env.envs.keeper import drive_command, turn_command

__all__ = ["RestartPlay", "SITUATION_NAMES"]

#: The situation one-hot's entries, in the order of the game block
#: (:data:`~soccer_env.envs.match.GAME_FLOW_NAMES`), as ``(kind, ours)``.
SITUATION_NAMES = {
    "game.stop": ("stop", None), "game.placement_ours": ("placement", True),
    "game.placement_theirs": ("placement", False), "game.kickoff_ours": ("kickoff", True),
    "game.kickoff_theirs": ("kickoff", False), "game.penalty_ours": ("penalty", True),
    "game.penalty_theirs": ("penalty", False), "game.free_kick_ours": ("free_kick", True),
    "game.free_kick_theirs": ("free_kick", False), "game.running": ("running", None),
}
#: The game block's entries that tell open play from the rest.
_RESTART_ENTRIES = ("game.running", "game.on_field", "game.barred")
#: Extra distance kept beyond what the rules ask [m].
MARGIN = 0.1
#: Fraction of the stop speed limit driven during stop.
STOP_SPEED_FRACTION = 0.8
#: Speed [m/s] at which the placer pulls the ball, and within how far of the designated
#: position it releases it [m].
PLACE_SPEED, PLACE_DONE = 0.8, 0.05
#: Speed [m/s] at which a pass from a restart reaches the team-mate (over the rolling
#: deceleration alone: the sliding phase after the kick makes it arrive a little slower).
PASS_SPEED = 1.5
#: Deceleration [m/s^2] of the placer carrying the ball, well within what the dribbler holds.
PLACE_DECELERATION = 1.0


class RestartPlay:
    """The restart play of :class:`~agents.team.ScriptedTeam` (see the module docstring).
    It reads the attributes the team sets up (geometry, robot, ``_game``: the game block's
    entry indices, ``_rules``)."""

    # The team sets these (declared for readers and type checkers).
    _game: dict[str, int] | None

    def _situation(self, o: Sequence[float]) -> tuple[str, bool | None]:
        """``(kind, ours)`` of the observation's situation one-hot."""
        g = self._game
        for name, value in SITUATION_NAMES.items():
            if o[g[name]] > 0.5:
                return value
        return "running", None

    def _needs_restart_play(self, o: np.ndarray | Sequence[float]) -> bool | np.ndarray:
        """Whether an observation (a sequence) or each observation row (an array
        ``(n, obs_dim)``) asks for more than open play."""
        g = self._game
        if isinstance(o, np.ndarray) and o.ndim == 2:
            running, on_field, barred = (o[:, g[n]] for n in _RESTART_ENTRIES)
        else:
            running, on_field, barred = (o[g[n]] for n in _RESTART_ENTRIES)
        return (running < 0.5) | (on_field < 0.5) | (barred > 0.5)

    # ------------------------------------------------------------------------------------

    def _restart(self, o: list[float], index: int, px: float, py: float, c: float, s: float,
                 bx: float, by: float, bvx: float, bvy: float, dx: float, dy: float,
                 xs: list[float], ys: list[float], opps: list[tuple[float, float]]
                 ) -> list[float]:
        """The action of robot ``index`` in a restart (the team frame's ``xs, ys`` hold every
        robot of the team, self included)."""
        g, rules, r = self._game, self._rules, self.robot
        if o[g["game.on_field"]] < 0.5:
            return [0.0] * 6
        kind, ours = self._situation(o)
        keeper = self.has_keeper and index == 0
        keep = rules.stop_distance + r.radius + MARGIN
        if kind == "running":
            barred = int(round(o[g["game.barred"]])) - 1
            return self._open_play(o, index, px, py, c, s, bx, by, bvx, bvy, dx, dy, xs, ys,
                                   opps, barred)
        nearest = self._nearest_to_ball(xs, ys, bx, by)
        if kind == "placement" and ours and index == nearest:
            return self._place(o, px, py, c, s, bx, by, bvx, bvy, dx, dy)
        if kind in ("kickoff", "free_kick", "penalty") and ours and index == nearest:
            return self._take_kick(index, px, py, c, s, bx, by, xs, ys, opps,
                                   shoot_only=kind == "penalty")
        if kind == "penalty":
            if keeper and not ours:
                action = self.keeper(o).tolist()
                action[3] = min(action[3], self._kick_power)
                return action
            return [0.0] * 6  # everybody else waits behind the ball
        # Everybody else: the open-play spot, kept clear of the ball.
        if keeper:
            action = list(self.keeper(o).tolist())
            if math.hypot(px - bx, py - by) >= keep and kind != "stop":
                return action
            tx, ty = px + action[0] * r.max_speed * c - action[1] * r.max_speed * s, \
                py + action[0] * r.max_speed * s + action[1] * r.max_speed * c
        else:
            role, rank, n_def = self._role(index, xs, ys, bx, by)
            if role == "attacker" or index == nearest:
                # Wait behind the ball: towards the goal we attack if the restart is ours.
                coming = o[g["game.next_team"]] if kind in ("stop", "placement") else (
                    1.0 if ours else -1.0)
                gx = self._goal_x if coming > 0.0 else -self._goal_x
                ex, ey = gx - bx, -by
                d = math.hypot(ex, ey) or 1.0
                tx, ty = bx - keep * ex / d, by - keep * ey / d
            else:
                tx, ty = self._defend_target(bx, by, rank, n_def)
        clear_kick = kind in ("stop", "placement") or (kind in ("kickoff", "free_kick")
                                                       and not ours)
        # The rules' distances last (they are fouls), the own defense area first (it is not).
        if not keeper:
            tx, ty = self._outside_defense_area(tx, ty)
        if kind in ("stop", "placement", "free_kick"):
            tx, ty = self._outside_opponent_defense(tx, ty)
        if kind == "kickoff":
            tx = min(tx, -r.radius - MARGIN)
        if clear_kick:
            tx, ty = self._clear_of(tx, ty, bx, by, keep)
        if kind == "placement" and not ours and o[g["game.target_set"]] > 0.5:
            gap = rules.placement_interference_distance + r.radius + MARGIN
            tx, ty = self._off_segment(tx, ty, bx, by, o[g["game.target_x"]],
                                       o[g["game.target_y"]], gap)
        tx = max(-self._lim_x, min(self._lim_x, tx))
        ty = max(-self._lim_y, min(self._lim_y, ty))
        # Inside the circle (or the placement's corridor): leave it; outside: go round it.
        if kind == "placement" and not ours and o[g["game.target_set"]] > 0.5:
            gap = rules.placement_interference_distance + r.radius + MARGIN
            qx, qy = o[g["game.target_x"]], o[g["game.target_y"]]
            if self._off_segment(px, py, bx, by, qx, qy, gap) != (px, py):
                tx, ty = self._off_segment(px, py, bx, by, qx, qy, gap + 0.05)
                clear_kick = False  # leaving the corridor sideways leaves the circle too
        if math.hypot(px - bx, py - by) < keep and clear_kick:
            tx, ty = self._clear_of(px, py, bx, by, keep + 0.05)
        else:
            tx, ty = self._around_ball(px, py, tx, ty, bx, by, keep if clear_kick else
                                       r.radius + self.ball.radius + 0.15, 0.05)
        cap = rules.stop_speed * STOP_SPEED_FRACTION if kind in ("stop", "placement") else None
        vx, vy = drive_command(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration, cap)
        omega = turn_command(c, s, math.atan2(by - py, bx - px), r.max_angular_speed)
        return [vx / r.max_speed, vy / r.max_speed, omega, 0.0, -1.0, -1.0]

    def _nearest_to_ball(self, xs: list[float], ys: list[float], bx: float, by: float) -> int:
        """The field player nearest the ball (the keeper when it is the only robot); ties to
        the lower index, so that every robot of the team picks the same one."""
        first = 1 if self.has_keeper else 0
        return min(range(first, self.team_size),
                   key=lambda k: (math.hypot(xs[k] - bx, ys[k] - by), k))

    def _kick_target(self, index: int, px: float, py: float, bx: float, by: float,
                     xs: list[float], ys: list[float], opps: list[tuple[float, float]]
                     ) -> tuple[float, float, float]:
        """Where a restart's kick goes and its kicker power: an open shot at the goal; else a
        pass, arriving at :data:`PASS_SPEED`, to the team-mate with the most open line
        (nearer the opponent goal breaking ties); else a shot at the goal centre."""
        (ax, ay), shoot = self._aim(px, py, bx, by, opps)
        if shoot:
            return ax, ay, self._kick_power
        best, best_gap = None, 0.0
        first = 1 if self.has_keeper else 0
        for k in range(first, self.team_size):
            if k == index:
                continue
            gap = min(self._clearance(bx, by, xs[k], ys[k], opps), 1.0) + 0.05 * xs[k]
            if gap > best_gap:
                best, best_gap = k, gap
        if best is None:
            return self._goal_x, 0.0, self._kick_power
        d = math.hypot(xs[best] - bx, ys[best] - by)
        speed = math.sqrt(PASS_SPEED ** 2 + 2.0 * self.ball.rolling_deceleration * d)
        return xs[best], ys[best], min(self._kick_power, speed / self.robot.kicker_max_speed)

    def _take_kick(self, index: int, px: float, py: float, c: float, s: float, bx: float,
                   by: float, xs: list[float], ys: list[float],
                   opps: list[tuple[float, float]], shoot_only: bool = False) -> list[float]:
        """Line up behind the ball facing the kick's target and kick once, flat, no faster
        than the rules allow (``shoot_only``: at the goal, as at a penalty kick)."""
        r = self.robot
        if shoot_only:
            (ax, ay), _ = self._aim(px, py, bx, by, opps)
            power = self._kick_power
        else:
            ax, ay, power = self._kick_target(index, px, py, bx, by, xs, ys, opps)
        ex, ey = ax - bx, ay - by
        d = math.hypot(ex, ey) or 1.0
        ex, ey = ex / d, ey / d
        nx, ny = -ey, ex
        along = (px - bx) * ex + (py - by) * ey
        lateral = (px - bx) * nx + (py - by) * ny
        face = math.atan2(ey, ex)
        heading_err = abs(math.remainder(face - math.atan2(s, c), 2.0 * math.pi))
        contact = self._contact
        kick = 0.0
        if along > -contact + 0.01 or abs(lateral) > 0.5 * r.kicker_width:
            # Not yet behind the ball: go to the waiting point (round the ball if needed).
            tx, ty = bx - (contact + 0.1) * ex, by - (contact + 0.1) * ey
            tx, ty = self._around_ball(px, py, tx, ty, bx, by,
                                       r.radius + self.ball.radius + 0.05, 0.05)
            cap = None
        elif heading_err > 0.1:
            tx, ty, cap = bx - (contact + 0.1) * ex, by - (contact + 0.1) * ey, 0.5
        else:
            # Lined up: drive slowly into the ball with the kicker armed.
            tx, ty, cap = bx + 0.1 * ex, by + 0.1 * ey, 0.5
            kick = power
        vx, vy = drive_command(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration, cap)
        omega = turn_command(c, s, face, r.max_angular_speed)
        return [vx / r.max_speed, vy / r.max_speed, omega, kick, -1.0, -1.0]

    def _place(self, o: Sequence[float], px: float, py: float, c: float, s: float, bx: float,
               by: float, bvx: float, bvy: float, dx: float, dy: float) -> list[float]:
        """Ball placement (see the module docstring): fetch the ball from the designated
        position's side and pull it there with the dribbler."""
        g, r, rules = self._game, self.robot, self._rules
        if o[g["game.target_set"]] < 0.5:
            return [0.0] * 6
        qx, qy = o[g["game.target_x"]], o[g["game.target_y"]]
        contact = self._contact
        to_ball = math.hypot(bx - qx, by - qy)
        if to_ball <= PLACE_DONE:
            # Placed: release and back off along the line from the ball through the robot.
            ours = o[g["game.next_team"]] > 0.0
            away = (rules.placement_clearance if ours else rules.stop_distance) + r.radius \
                + MARGIN
            tx, ty = self._away_from(px, py, bx, by, away)
            vx, vy = drive_command(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration, 0.5)
            omega = turn_command(c, s, math.atan2(by - py, bx - px), r.max_angular_speed)
            return [vx / r.max_speed, vy / r.max_speed, omega, 0.0, -1.0, -1.0]
        ux, uy = self._pick_up_direction(bx, by, (bx - qx) / to_ball, (by - qy) / to_ball)
        face = math.atan2(uy, ux)
        heading_err = abs(math.remainder(face - math.atan2(s, c), 2.0 * math.pi))
        held = (r.front_distance - 0.01 < dx < contact + 0.02
                and abs(dy) < 0.5 * r.kicker_width)
        if held:
            # Carry the ball to the designated position without turning: the robot moves
            # as the ball must (the dribbler holds it against the front and damps its
            # sideways slip), slowing down on the braking profile.
            ex, ey = qx - bx, qy - by
            speed = min(PLACE_SPEED, math.sqrt(2.0 * PLACE_DECELERATION * to_ball))
            wx, wy = ex / to_ball * speed, ey / to_ball * speed
            vx, vy = c * wx + s * wy, -s * wx + c * wy
            return [vx / r.max_speed, vy / r.max_speed, 0.0, 0.0, -1.0, 1.0]
        if bvx * bvx + bvy * bvy > 0.09:
            # A rolling ball: meet it half a second ahead.
            bx, by = bx + 0.5 * bvx, by + 0.5 * bvy
        # Stop between the designated position and the ball, facing the ball; then move in
        # until the ball is at the front.
        near = math.hypot(px - (bx - contact * ux), py - (by - contact * uy))
        if near < 0.08 and heading_err < 0.2:
            tx, ty, cap = bx - (contact - 0.01) * ux, by - (contact - 0.01) * uy, 0.3
        else:
            tx, ty = bx - (contact + 0.08) * ux, by - (contact + 0.08) * uy
            tx, ty = self._around_ball(px, py, tx, ty, bx, by,
                                       r.radius + self.ball.radius + 0.05, 0.05)
            cap = None
        lx = self.field.half_length + self.field.boundary - r.radius - 0.005
        ly = self.field.half_width + self.field.boundary - r.radius - 0.005
        tx = max(-lx, min(lx, tx))
        ty = max(-ly, min(ly, ty))
        vx, vy = drive_command(px, py, c, s, tx, ty, r.max_speed, r.max_acceleration, cap)
        omega = turn_command(c, s, face, r.max_angular_speed)
        return [vx / r.max_speed, vy / r.max_speed, omega, 0.0, -1.0, 1.0]

    def _pick_up_direction(self, bx: float, by: float, ux: float, uy: float
                           ) -> tuple[float, float]:
        """The direction ``(ux, uy)`` (unit) the placer faces to take the ball: from the
        designated position to the ball, turned by the least multiple of 15 degrees that
        lets the robot's centre, a contact distance behind the ball, stay off the walls (a
        ball against a wall or in a corner is taken facing the wall)."""
        f, r = self.field, self.robot
        wx = f.half_length + f.boundary - r.radius - 0.005
        wy = f.half_width + f.boundary - r.radius - 0.005
        contact = self._contact
        a0 = math.atan2(uy, ux)
        for k in range(13):
            for sign in ((1.0,) if k == 0 else (1.0, -1.0)):
                a = a0 + sign * k * math.pi / 12.0
                cx, cy = bx - contact * math.cos(a), by - contact * math.sin(a)
                if abs(cx) <= wx and abs(cy) <= wy:
                    return math.cos(a), math.sin(a)
        # Wedged in a corner: face into it.
        nx = math.copysign(1.0, bx) if abs(bx) > wx - contact else 0.0
        ny = math.copysign(1.0, by) if abs(by) > wy - contact else 0.0
        n = math.hypot(nx, ny) or 1.0
        return nx / n, ny / n

    # ------------------------------------------------------------------------------------
    # Geometry (team frame)

    @staticmethod
    def _away_from(x: float, y: float, bx: float, by: float, dist: float
                   ) -> tuple[float, float]:
        """``(x, y)`` pushed radially out of the circle of radius ``dist`` round ``(bx, by)``
        (away from the own goal if it lies on the centre)."""
        ex, ey = x - bx, y - by
        d = math.hypot(ex, ey)
        if d >= dist:
            return x, y
        if d < 1e-9:
            ex, ey, d = -1.0, 0.0, 1.0
        return bx + ex / d * dist, by + ey / d * dist

    def _clear_of(self, x: float, y: float, bx: float, by: float, dist: float
                  ) -> tuple[float, float]:
        """:meth:`_away_from` kept inside the walls: where the radial point lies beyond them
        (a ball near a corner), the nearest point of the circle inside them, turning the
        direction in steps of 15 degrees."""
        tx, ty = self._away_from(x, y, bx, by, dist)
        if abs(tx) <= self._lim_x and abs(ty) <= self._lim_y:
            return tx, ty
        a0 = math.atan2(ty - by, tx - bx)
        for k in range(1, 13):
            for sign in (1.0, -1.0):
                a = a0 + sign * k * math.pi / 12.0
                tx, ty = bx + dist * math.cos(a), by + dist * math.sin(a)
                if abs(tx) <= self._lim_x and abs(ty) <= self._lim_y:
                    return tx, ty
        return tx, ty

    @staticmethod
    def _off_segment(x: float, y: float, ax: float, ay: float, qx: float, qy: float,
                     dist: float) -> tuple[float, float]:
        """``(x, y)`` pushed at least ``dist`` from the segment from ``(ax, ay)`` to
        ``(qx, qy)``, sideways."""
        ex, ey = qx - ax, qy - ay
        n = ex * ex + ey * ey
        t = 0.0 if n < 1e-12 else max(0.0, min(1.0, ((x - ax) * ex + (y - ay) * ey) / n))
        cx, cy = ax + t * ex, ay + t * ey
        return RestartPlay._away_from(x, y, cx, cy, dist)

    def _outside_opponent_defense(self, x: float, y: float, margin: float | None = None
                                  ) -> tuple[float, float]:
        """Move a target nearer the opponent defense area than ``margin`` (default the
        rules' distance at restarts plus a robot radius and a margin) to the nearest point
        outside."""
        f = self.field
        m = self._rules.defense_area_distance + self.robot.radius + MARGIN \
            if margin is None else margin
        front = self._goal_x - f.defense_depth - m
        side = 0.5 * f.defense_width + m
        if x <= front or abs(y) >= side:
            return x, y
        if x - front <= side - abs(y):
            return front, y
        return x, math.copysign(side, y if y != 0.0 else 1.0)

    def _outside_opponent_defense_rows(self, x: np.ndarray, y: np.ndarray, margin: float
                                       ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_outside_opponent_defense` on arrays [m]."""
        f = self.field
        front = self._goal_x - f.defense_depth - margin
        side = 0.5 * f.defense_width + margin
        inside = (x > front) & (np.abs(y) < side)
        to_front = x - front <= side - np.abs(y)
        return (np.where(inside & to_front, front, x),
                np.where(inside & ~to_front, np.copysign(side, np.where(y != 0.0, y, 1.0)), y))
