"""The field as a scripted SSL team sees it: its team frame, the zones it keeps out of and the
ways round the ball, each single and batched pair side by side.

The team frame has the field's centre at the origin and attacks ``+x``: the own goal line is
at ``x = -goal_x``, the opponents' at ``x = +goal_x``. All positions are in metres.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from soccer_env.envs.keeper import hypots
from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec

__all__ = ["TeamGeometry", "Hypot", "MARGIN"]

#: Extra distance kept beyond what the rules ask [m].
MARGIN = 0.1

#: A length function on arrays: ``hypot(x, y)`` (:func:`~soccer_env.envs.keeper.hypots`, bit
#: for bit ``math.hypot``, or ``np.hypot``).
Hypot = Callable[[np.ndarray, np.ndarray], np.ndarray]


class TeamGeometry:
    """The field, ball and robot of a scripted SSL team and the places they make.

    Args:
        field: the match's field.
        ball: the match's ball.
        robot: the team's robot spec.
        hypot: the length function of the batched (``*_rows``) methods.
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, robot: SSLRobotSpec,
                 hypot: Hypot = hypots) -> None:
        self.field, self.ball, self.robot = field, ball, robot
        self.hypot = hypot
        hx, hy = field.half_length, field.half_width
        r = robot.radius
        #: The opponents' goal line; the own one is at ``-goal_x`` [m].
        self.goal_x = hx
        #: Half the goal mouth's width [m].
        self.half_goal = 0.5 * field.goal_width
        #: Kicker-centre to ball-centre distance with the ball touching the front [m].
        self.contact = robot.front_distance + ball.radius
        #: Keep-out rectangle of the own defense area for the robot centre: ``x <
        #: def_front`` and ``|y| < def_side`` [m].
        self.def_front = -hx + field.defense_depth + r + 0.05
        self.def_side = 0.5 * field.defense_width + r + 0.05
        #: Walls minus a robot radius: targets are clipped into ``|x| <= lim_x``, ``|y| <=
        #: lim_y`` [m].
        self.lim_x = hx + field.boundary - r - 0.02
        self.lim_y = hy + field.boundary - r - 0.02

    # ------------------------------------------------------------------------------------
    # Keep-out zones

    def outside_defense_area(self, x: float, y: float) -> tuple[float, float]:
        """Move a target inside the own defense area (widened by a robot radius and 5 cm) to
        the nearest point on its edge."""
        ox = -self.goal_x
        if x >= self.def_front or abs(y) >= self.def_side:
            return x, y
        to_front = self.def_front - x
        to_side = self.def_side - abs(y)
        if to_front <= to_side or x < ox:
            return self.def_front, y
        return x, math.copysign(self.def_side, y if y != 0.0 else 1.0)

    def outside_defense_area_rows(self, x: np.ndarray, y: np.ndarray
                                  ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`outside_defense_area` on arrays [m]."""
        ox = -self.goal_x
        inside = (x < self.def_front) & (np.abs(y) < self.def_side)
        to_front = self.def_front - x
        to_side = self.def_side - np.abs(y)
        front = (to_front <= to_side) | (x < ox)
        return (np.where(inside & front, self.def_front, x),
                np.where(inside & ~front,
                         np.copysign(self.def_side, np.where(y != 0.0, y, 1.0)), y))

    def outside_opponent_defense(self, x: float, y: float, margin: float
                                 ) -> tuple[float, float]:
        """Move a target nearer the opponent defense area than ``margin`` [m] to the nearest
        point outside."""
        f = self.field
        front = self.goal_x - f.defense_depth - margin
        side = 0.5 * f.defense_width + margin
        if x <= front or abs(y) >= side:
            return x, y
        if x - front <= side - abs(y):
            return front, y
        return x, math.copysign(side, y if y != 0.0 else 1.0)

    def outside_opponent_defense_rows(self, x: np.ndarray, y: np.ndarray, margin: float
                                      ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`outside_opponent_defense` on arrays [m]."""
        f = self.field
        front = self.goal_x - f.defense_depth - margin
        side = 0.5 * f.defense_width + margin
        inside = (x > front) & (np.abs(y) < side)
        to_front = x - front <= side - np.abs(y)
        return (np.where(inside & to_front, front, x),
                np.where(inside & ~to_front, np.copysign(side, np.where(y != 0.0, y, 1.0)), y))

    def within_walls(self, x: float, y: float) -> tuple[float, float]:
        """A target clipped into the walls minus a robot radius [m]."""
        return max(-self.lim_x, min(self.lim_x, x)), max(-self.lim_y, min(self.lim_y, y))

    def within_walls_rows(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`within_walls` on arrays [m]."""
        return np.clip(x, -self.lim_x, self.lim_x), np.clip(y, -self.lim_y, self.lim_y)

    # ------------------------------------------------------------------------------------
    # Round the ball

    def around_ball(self, px: float, py: float, tx: float, ty: float, bx: float, by: float,
                    clear: float | None = None, pad: float = 0.0) -> tuple[float, float]:
        """A waypoint beside the ball, ``clear + pad`` from it, if the straight path from
        ``(px, py)`` to ``(tx, ty)`` passes within ``clear`` of the ball (default a robot
        radius, a ball radius and 15 cm), else the target (a defender on its way to its slot
        must not knock the ball about)."""
        ux, uy = tx - px, ty - py
        length = math.hypot(ux, uy)
        if length < 1e-6:
            return tx, ty
        ux, uy = ux / length, uy / length
        if clear is None:
            clear = self.robot.radius + self.ball.radius + 0.15
        along = (bx - px) * ux + (by - py) * uy
        side = (px - bx) * -uy + (py - by) * ux  # the robot's side of the ball, along n
        if not 0.0 < along < length or abs(side) >= clear:
            return tx, ty
        sign = 1.0 if side >= 0.0 else -1.0
        return bx - sign * (clear + pad) * uy, by + sign * (clear + pad) * ux

    def around_ball_rows(self, px: np.ndarray, py: np.ndarray, tx: np.ndarray,
                         ty: np.ndarray, bx: np.ndarray, by: np.ndarray
                         ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`around_ball` on arrays, with the default clearance and no pad [m]."""
        ux, uy = tx - px, ty - py
        length = self.hypot(ux, uy)
        short = length < 1e-6
        safe = np.where(short, 1.0, length)
        ux, uy = ux / safe, uy / safe
        clear = self.robot.radius + self.ball.radius + 0.15
        along = (bx - px) * ux + (by - py) * uy
        side = (px - bx) * -uy + (py - by) * ux  # the robot's side of the ball, along n
        detour = ~short & (0.0 < along) & (along < length) & (np.abs(side) < clear)
        sign = np.where(side >= 0.0, 1.0, -1.0)
        return (np.where(detour, bx - sign * clear * uy, tx),
                np.where(detour, by + sign * clear * ux, ty))

    # ------------------------------------------------------------------------------------
    # Off a circle or a corridor (restarts; single robots only)

    @staticmethod
    def away_from(x: float, y: float, bx: float, by: float, dist: float
                  ) -> tuple[float, float]:
        """``(x, y)`` pushed radially out of the circle of radius ``dist`` round ``(bx, by)``
        (towards ``-x`` if it lies on the centre) [m]."""
        ex, ey = x - bx, y - by
        d = math.hypot(ex, ey)
        if d >= dist:
            return x, y
        if d < 1e-9:
            ex, ey, d = -1.0, 0.0, 1.0
        return bx + ex / d * dist, by + ey / d * dist

    def clear_of(self, x: float, y: float, bx: float, by: float, dist: float
                 ) -> tuple[float, float]:
        """:meth:`away_from` kept inside the walls: where the radial point lies beyond them
        (a ball near a corner), the nearest point of the circle inside them, turning the
        direction in steps of 15 degrees [m]."""
        tx, ty = self.away_from(x, y, bx, by, dist)
        if abs(tx) <= self.lim_x and abs(ty) <= self.lim_y:
            return tx, ty
        a0 = math.atan2(ty - by, tx - bx)
        for k in range(1, 13):
            for sign in (1.0, -1.0):
                a = a0 + sign * k * math.pi / 12.0
                tx, ty = bx + dist * math.cos(a), by + dist * math.sin(a)
                if abs(tx) <= self.lim_x and abs(ty) <= self.lim_y:
                    return tx, ty
        return tx, ty

    @staticmethod
    def off_segment(x: float, y: float, ax: float, ay: float, qx: float, qy: float,
                    dist: float) -> tuple[float, float]:
        """``(x, y)`` pushed at least ``dist`` from the segment from ``(ax, ay)`` to
        ``(qx, qy)``, sideways [m]."""
        ex, ey = qx - ax, qy - ay
        n = ex * ex + ey * ey
        t = 0.0 if n < 1e-12 else max(0.0, min(1.0, ((x - ax) * ex + (y - ay) * ey) / n))
        cx, cy = ax + t * ex, ay + t * ey
        return TeamGeometry.away_from(x, y, cx, cy, dist)
