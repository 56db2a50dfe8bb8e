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

Positions are in the team frame [m] (:mod:`agents.scripted.geometry`). The rules are compiled
kernels on floats and the team's positions as arrays (:func:`role`,
:func:`keeper_should_clear`); :class:`Roles` holds the team's numbers and calls them.
"""

from __future__ import annotations

import math

import numpy as np

from agents.scripted.geometry import Pitch, TeamGeometry
from estimators.compiled import kernel
from estimators.exact import hypot_exact

__all__ = ["Roles", "DEFENDERS_PER_LINE", "role", "keeper_should_clear"]

#: Defenders in one line between the ball and the own goal.
DEFENDERS_PER_LINE = 3


@kernel
def role(p: Pitch, first: int, team_size: int, index: int, xs: np.ndarray, ys: np.ndarray,
         bx: float, by: float, barred: int) -> tuple[bool, int, int]:
    """``(attacker, rank, defenders)``: whether field player ``index`` is the attacker, else
    its rank among the defenders, and their number (the module docstring); the field players
    are ``first .. team_size - 1``, robot ``barred`` never attacks. ``xs``, ``ys``: the team's
    robots by index, ``(bx, by)``: the ball [m].

    The attacker is the first field player of least cost (a strict ``<``); the defenders are
    the others in index order, in lines of :data:`DEFENDERS_PER_LINE`, within a line ranked
    by ``(lateral position, index)``."""
    # Cost to take the ball [m]: distance to the point behind the ball on the line from the
    # opponent goal centre, plus a penalty for standing goal-side of the ball (the robot
    # would have to go round it). A robot passing the ball on its way elsewhere does not
    # steal the role from one already lined up behind it.
    ex, ey = p.goal_x - bx, -by
    d = hypot_exact(ex, ey)
    if d == 0.0:
        d = 1.0
    ex, ey = ex / d, ey / d
    back = p.contact + 0.12
    qx, qy = bx - back * ex, by - back * ey
    best, attacker = math.inf, -1
    for k in range(first, team_size):
        if k == barred:
            continue
        ahead = (xs[k] - bx) * ex + (ys[k] - by) * ey > p.contact
        cost = hypot_exact(xs[k] - qx, ys[k] - qy) + (0.5 if ahead else 0.0)
        if cost < best:
            best, attacker = cost, k
    if index == attacker:
        return True, 0, 0
    n_def = team_size - first - (1 if attacker >= 0 else 0)
    # Lines of up to three by robot index (so that a robot keeps its line); within a line,
    # slots by lateral position across the goal-ball line, so that defenders do not cross
    # each other's paths to their slots.
    per = DEFENDERS_PER_LINE
    position = index - first - (1 if 0 <= attacker < index else 0)
    start = position // per * per
    ox = -p.goal_x
    fx, fy = bx - ox, by
    norm = hypot_exact(fx, fy)
    if norm == 0.0:
        norm = 1.0
    nx, ny = -fy / norm, fx / norm
    mine = (xs[index] - ox) * nx + ys[index] * ny
    rank, j = start, 0
    for k in range(first, team_size):
        if k == attacker:
            continue
        if start <= j < start + per and k != index:
            lateral = (xs[k] - ox) * nx + ys[k] * ny
            if lateral < mine or (lateral == mine and k < index):
                rank += 1
        j += 1
    return False, rank, n_def


@kernel
def keeper_should_clear(p: Pitch, bx: float, by: float, bvx: float, bvy: float) -> bool:
    """A slow ball (under 0.5 m/s) inside the own defense area (position ``(bx, by)`` [m],
    velocity ``(bvx, bvy)`` [m/s]): only the keeper may fetch it."""
    inside = bx < -p.goal_x + p.defense_depth and abs(by) < 0.5 * p.defense_width
    return inside and bx > -p.goal_x and hypot_exact(bvx, bvy) < 0.5


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
        """``(role, rank, defenders)`` of :func:`role`: robot ``index``'s role
        (``"attacker"`` or ``"defender"``), its rank among the defenders and their number;
        robot ``barred`` is never the attacker [m]."""
        attacker, rank, n_def = role(self.geometry.pitch, self.first, self.team_size, index,
                                     np.array(xs, dtype=np.float64),
                                     np.array(ys, dtype=np.float64), bx, by, barred)
        return ("attacker", 0, 0) if attacker else ("defender", rank, n_def)

    def keeper_should_clear(self, bx: float, by: float, bvx: float, bvy: float) -> bool:
        """:func:`keeper_should_clear`."""
        return keeper_should_clear(self.geometry.pitch, bx, by, bvx, bvy)

    def nearest_to_ball(self, xs: list[float], ys: list[float], bx: float, by: float) -> int:
        """The field player nearest the ball (the keeper when it is the only robot); ties to
        the lower index, so that every robot of the team picks the same one."""
        return min(range(self.first, self.team_size),
                   key=lambda k: (math.hypot(xs[k] - bx, ys[k] - by), k))
