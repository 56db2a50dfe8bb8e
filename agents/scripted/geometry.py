"""The field as a scripted SSL team sees it: its team frame, the zones it keeps out of and the
ways round the ball.

The team frame has the field's centre at the origin and attacks ``+x``: the own goal line is
at ``x = -goal_x``, the opponents' at ``x = +goal_x``. All positions are in metres.

Each rule is a compiled kernel (:func:`~estimators.compiled.kernel`) on floats and the team's
numbers (:class:`Pitch`), called alike by the kernels of the team's play (one robot or rows of
robots) and, through :class:`TeamGeometry`'s methods, by the restarts' Python.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from estimators.compiled import kernel
from estimators.exact import hypot_exact
from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec

__all__ = ["TeamGeometry", "Pitch", "MARGIN", "outside_defense_area",
           "outside_opponent_defense", "within_walls", "around_ball"]

#: Extra distance kept beyond what the rules ask [m].
MARGIN = 0.1


class Pitch(NamedTuple):
    """The numbers of the field, ball and robot that the team's kernels read [m, m/s, m/s^2,
    rad/s]."""

    #: The opponents' goal line; the own one is at ``-goal_x``.
    goal_x: float
    #: Half the goal mouth's width.
    half_goal: float
    #: Half the field's width.
    half_width: float
    #: The defense area's depth and width.
    defense_depth: float
    defense_width: float
    #: Kicker-centre to ball-centre distance with the ball touching the front.
    contact: float
    #: Keep-out rectangle of the own defense area for the robot centre: ``x < def_front``
    #: and ``|y| < def_side``.
    def_front: float
    def_side: float
    #: Walls minus a robot radius: targets are clipped into ``|x| <= lim_x``,
    #: ``|y| <= lim_y``.
    lim_x: float
    lim_y: float
    #: The robot's radius, the ball's radius, the robot's centre-to-front distance and its
    #: kicker's width.
    radius: float
    ball_radius: float
    front_distance: float
    kicker_width: float
    #: The robot's limits: speed [m/s], acceleration [m/s^2], turn rate [rad/s].
    max_speed: float
    max_acceleration: float
    max_angular_speed: float


@kernel
def outside_defense_area(p: Pitch, x: float, y: float) -> tuple[float, float]:
    """A target inside the own defense area (widened by a robot radius and 5 cm) moved to the
    nearest point on its edge [m]."""
    ox = -p.goal_x
    if x >= p.def_front or abs(y) >= p.def_side:
        return x, y
    to_front = p.def_front - x
    to_side = p.def_side - abs(y)
    if to_front <= to_side or x < ox:
        return p.def_front, y
    return x, math.copysign(p.def_side, y if y != 0.0 else 1.0)


@kernel
def outside_opponent_defense(p: Pitch, x: float, y: float, margin: float
                             ) -> tuple[float, float]:
    """A target nearer the opponent defense area than ``margin`` [m] moved to the nearest
    point outside [m]."""
    front = p.goal_x - p.defense_depth - margin
    side = 0.5 * p.defense_width + margin
    if x <= front or abs(y) >= side:
        return x, y
    if x - front <= side - abs(y):
        return front, y
    return x, math.copysign(side, y if y != 0.0 else 1.0)


@kernel
def within_walls(p: Pitch, x: float, y: float) -> tuple[float, float]:
    """A target clipped into the walls minus a robot radius [m]."""
    return max(-p.lim_x, min(p.lim_x, x)), max(-p.lim_y, min(p.lim_y, y))


@kernel
def around_ball(px: float, py: float, tx: float, ty: float, bx: float, by: float,
                clear: float, pad: float) -> tuple[float, float]:
    """A waypoint beside the ball, ``clear + pad`` from it, if the straight path from
    ``(px, py)`` to ``(tx, ty)`` passes within ``clear`` of the ball ``(bx, by)``, else the
    target [m] (a defender on its way to its slot must not knock the ball about)."""
    ux, uy = tx - px, ty - py
    length = hypot_exact(ux, uy)
    if length < 1e-6:
        return tx, ty
    ux, uy = ux / length, uy / length
    along = (bx - px) * ux + (by - py) * uy
    side = (px - bx) * -uy + (py - by) * ux  # the robot's side of the ball, along n
    if not 0.0 < along < length or abs(side) >= clear:
        return tx, ty
    sign = 1.0 if side >= 0.0 else -1.0
    return bx - sign * (clear + pad) * uy, by + sign * (clear + pad) * ux


class TeamGeometry:
    """The field, ball and robot of a scripted SSL team and the places they make.

    Args:
        field: the match's field.
        ball: the match's ball.
        robot: the team's robot spec.
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, robot: SSLRobotSpec) -> None:
        self.field, self.ball, self.robot = field, ball, robot
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
        #: These numbers for the kernels.
        self.pitch = Pitch(
            float(self.goal_x), float(self.half_goal), float(hy), float(field.defense_depth),
            float(field.defense_width), float(self.contact), float(self.def_front),
            float(self.def_side), float(self.lim_x), float(self.lim_y), float(r),
            float(ball.radius), float(robot.front_distance), float(robot.kicker_width),
            float(robot.max_speed), float(robot.max_acceleration),
            float(robot.max_angular_speed))

    # ------------------------------------------------------------------------------------
    # Keep-out zones and the way round the ball (the kernels, for the restarts)

    def outside_defense_area(self, x: float, y: float) -> tuple[float, float]:
        """:func:`outside_defense_area` [m]."""
        return outside_defense_area(self.pitch, x, y)

    def outside_opponent_defense(self, x: float, y: float, margin: float
                                 ) -> tuple[float, float]:
        """:func:`outside_opponent_defense` [m]."""
        return outside_opponent_defense(self.pitch, x, y, margin)

    def within_walls(self, x: float, y: float) -> tuple[float, float]:
        """:func:`within_walls` [m]."""
        return within_walls(self.pitch, x, y)

    def around_ball(self, px: float, py: float, tx: float, ty: float, bx: float, by: float,
                    clear: float | None = None, pad: float = 0.0) -> tuple[float, float]:
        """:func:`around_ball`, ``clear`` by default a robot radius, a ball radius and 15 cm
        [m]."""
        if clear is None:
            clear = self.robot.radius + self.ball.radius + 0.15
        return around_ball(px, py, tx, ty, bx, by, clear, pad)

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

    def leave_segment(self, x: float, y: float, ax: float, ay: float, qx: float, qy: float,
                      dist: float) -> tuple[float, float]:
        """:meth:`off_segment` kept inside the walls: where the sideways point lies beyond
        them (a robot between a wall and the segment), the nearest point inside them that is
        ``dist`` from the segment, searched on rings of 5 cm steps round ``(x, y)`` in 15
        degree steps (up to 1.5 m) [m]."""
        tx, ty = self.off_segment(x, y, ax, ay, qx, qy, dist)
        if abs(tx) <= self.lim_x and abs(ty) <= self.lim_y:
            return tx, ty
        for k in range(1, 31):
            for j in range(24):
                a = j * math.pi / 12.0
                cx, cy = x + 0.05 * k * math.cos(a), y + 0.05 * k * math.sin(a)
                if abs(cx) <= self.lim_x and abs(cy) <= self.lim_y and \
                        self.off_segment(cx, cy, ax, ay, qx, qy, dist) == (cx, cy):
                    return cx, cy
        return self.within_walls(tx, ty)

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
