"""Who plays what in a scripted SSL team, decided by each robot from its observation alone.

All robots of a team read the same belief, so they agree:

* the **keeper** is robot 0 when the team has two or more robots; only it may fetch a slow
  ball lying in the own defense area (:meth:`Roles.keeper_should_clear`);
* the **attacker** is the field player of least cost to take the ball: its distance to the
  point behind the ball on the line from the opponent goal's centre, plus 0.5 m when it stands
  goal-side of the ball (ties to the lower index);
* the **defenders** are the others, in lines of up to :data:`DEFENDERS_PER_LINE` by robot
  index (so that a robot keeps its line), within a line in slots by their lateral position
  across the line from the own goal to the ball (so that they do not cross each other's
  paths).

Positions are in the team frame [m] (:mod:`agents.scripted.geometry`).
"""

from __future__ import annotations

import math

import numpy as np

from agents.scripted.geometry import TeamGeometry

__all__ = ["Roles", "DEFENDERS_PER_LINE"]

#: Defenders in one line between the ball and the own goal.
DEFENDERS_PER_LINE = 3


class Roles:
    """The roles of a scripted SSL team (see the module docstring).

    Args:
        geometry: the team's geometry.
        team_size: robots in the team.
    """

    def __init__(self, geometry: TeamGeometry, team_size: int) -> None:
        self.geometry = geometry
        self.team_size = int(team_size)
        #: Whether robot 0 keeps goal (a team of two or more).
        self.has_keeper = self.team_size >= 2
        #: The first field player's index.
        self.first = 1 if self.has_keeper else 0

    def role(self, index: int, xs: list[float], ys: list[float], bx: float, by: float,
             barred: int = -1) -> tuple[str, int, int]:
        """``(role, rank, defenders)``: robot ``index``'s role (``"attacker"`` or
        ``"defender"``), its rank among the defenders and their number; robot ``barred`` is
        never the attacker. ``xs``, ``ys``: the team's robots by index, ``(bx, by)``: the
        ball [m]."""
        g = self.geometry
        first = self.first
        field_players = range(first, self.team_size)
        # Cost to take the ball [m]: distance to the point behind the ball on the line from
        # the opponent goal centre, plus a penalty for standing goal-side of the ball (the
        # robot would have to go round it). A robot passing the ball on its way elsewhere
        # does not steal the role from one already lined up behind it.
        ex, ey = g.goal_x - bx, -by
        d = math.hypot(ex, ey) or 1.0
        ex, ey = ex / d, ey / d
        back = g.contact + 0.12
        qx, qy = bx - back * ex, by - back * ey
        best, attacker = math.inf, -1
        for k in field_players:
            if k == barred:
                continue
            ahead = (xs[k] - bx) * ex + (ys[k] - by) * ey > g.contact
            cost = math.hypot(xs[k] - qx, ys[k] - qy) + (0.5 if ahead else 0.0)
            if cost < best:
                best, attacker = cost, k
        if index == attacker:
            return "attacker", 0, 0
        defenders = [k for k in field_players if k != attacker]
        # Lines of up to three by robot index (so that a robot keeps its line); within a
        # line, slots by lateral position across the goal-ball line, so that defenders do not
        # cross each other's paths to their slots.
        per = DEFENDERS_PER_LINE
        start = defenders.index(index) // per * per
        line = defenders[start:start + per]
        ox = -g.goal_x
        fx, fy = bx - ox, by
        norm = math.hypot(fx, fy) or 1.0
        nx, ny = -fy / norm, fx / norm
        line.sort(key=lambda k: ((xs[k] - ox) * nx + ys[k] * ny, k))
        return "defender", start + line.index(index), len(defenders)

    def role_rows(self, index: np.ndarray, xs: np.ndarray, ys: np.ndarray, bx: np.ndarray,
                  by: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`role` for field-player rows: ``(attacker, rank)``, whether each row's robot
        is the attacker, and else its rank among the defenders. ``xs``, ``ys``: the team's
        robots in the team frame as each row sees them, ``(team_size, n)`` [m]."""
        g, hypot = self.geometry, self.geometry.hypot
        first = self.first
        ex, ey = g.goal_x - bx, -by
        d = hypot(ex, ey)
        d = np.where(d == 0.0, 1.0, d)
        ex, ey = ex / d, ey / d
        back = g.contact + 0.12
        qx, qy = bx - back * ex, by - back * ey
        # The first field player of least cost (role's strict "<" keeps the first).
        ahead = (xs[first:] - bx) * ex + (ys[first:] - by) * ey > g.contact
        cost = hypot(xs[first:] - qx, ys[first:] - qy) + np.where(ahead, 0.5, 0.0)
        attacker = first + np.argmin(cost, axis=0)
        is_attacker = index == attacker
        # Defenders: the field players but the attacker, by index; lines of up to three
        # (position // per), within a line slots by (lateral position, index).
        per = DEFENDERS_PER_LINE
        position = index - first - (attacker < index)
        ox = -g.goal_x
        fx, fy = bx - ox, by
        norm = hypot(fx, fy)
        norm = np.where(norm == 0.0, 1.0, norm)
        nx, ny = -fy / norm, fx / norm
        cols = np.arange(len(index))
        mine = (xs[index, cols] - ox) * nx + ys[index, cols] * ny
        rank = position // per * per
        for p in range(self.team_size - first - 1):
            k = first + p + (first + p >= attacker)
            lateral = (xs[k, cols] - ox) * nx + ys[k, cols] * ny
            before = (lateral < mine) | ((lateral == mine) & (k < index))
            rank = rank + (before & (p // per == position // per))
        return is_attacker, rank

    def keeper_should_clear(self, bx: float, by: float, bvx: float, bvy: float) -> bool:
        """A slow ball (under 0.5 m/s) inside the own defense area: only the keeper may fetch
        it."""
        g = self.geometry
        f = g.field
        inside = bx < -g.goal_x + f.defense_depth and abs(by) < 0.5 * f.defense_width
        return inside and bx > -g.goal_x and math.hypot(bvx, bvy) < 0.5

    def keeper_should_clear_rows(self, bx: np.ndarray, by: np.ndarray, bvx: np.ndarray,
                                 bvy: np.ndarray) -> np.ndarray:
        """:meth:`keeper_should_clear` on arrays."""
        g = self.geometry
        f = g.field
        inside = (bx < -g.goal_x + f.defense_depth) & (np.abs(by) < 0.5 * f.defense_width)
        return inside & (bx > -g.goal_x) & (g.hypot(bvx, bvy) < 0.5)

    def nearest_to_ball(self, xs: list[float], ys: list[float], bx: float, by: float) -> int:
        """The field player nearest the ball (the keeper when it is the only robot); ties to
        the lower index, so that every robot of the team picks the same one."""
        return min(range(self.first, self.team_size),
                   key=lambda k: (math.hypot(xs[k] - bx, ys[k] - by), k))
