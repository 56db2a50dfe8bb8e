"""Occlusion of the ball by robots, seen from an overhead camera: what fraction of the
ball's disc a camera cannot see past the robots' bodies
(:class:`BallOcclusion`, used by :class:`~soccer_env.sensors.overhead.OverheadVision` and
:class:`~soccer_env.sensors.overhead_batch.OverheadVisionBatch`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from soccer_env.presets import RobotSpec

__all__ = ["BallOcclusion", "RING"]

#: Points on the ball's disc (centre and two rings), in radii, for the hidden fraction.
RING = ([(0.0, 0.0)]
        + [(0.5 * math.cos(2 * math.pi * i / 6), 0.5 * math.sin(2 * math.pi * i / 6))
           for i in range(6)]
        + [(0.9 * math.cos(2 * math.pi * i / 12), 0.9 * math.sin(2 * math.pi * i / 12))
           for i in range(12)])


class BallOcclusion:
    """The hidden fraction of a ball of radius ``ball_radius`` among robots of the bodies of
    ``robots`` (every robot's spec, in world order: its footprint radius and height).

    Args:
        ball_radius: the ball's radius [m].
        robot: the common robot model (the only body when every robot has it).
        robots: every robot's spec, in world order.
    """

    def __init__(self, ball_radius: float, robot: RobotSpec, robots: Sequence[RobotSpec]
                 ) -> None:
        self.ball_radius = ball_radius
        self.robot_spec = robot
        shapes: dict[tuple[float, float], list[int]] = {}
        for i, rs in enumerate(robots):
            shapes.setdefault((float(rs.height), float(rs.radius)), []).append(i)
        #: Robots grouped by body ``((height, radius), indices)``; None when every robot has
        #: ``robot``'s body (the common case, one group without an index list).
        self.shapes: list[tuple[tuple[float, float], list[int]]] | None = (
            None if list(shapes) == [(float(robot.height), float(robot.radius))]
            else list(shapes.items()))

    def hidden(self, bx: float, by: float, zc: float, robots: list, cx: float, cy: float,
               h: float) -> float:
        """Fraction of the ball's disc (centre ``bx, by`` as seen, centre height ``zc``) that
        the camera at ``(cx, cy, h)`` cannot see past the robots.

        A robot of radius ``R`` and height ``H`` (its own spec's) hides, in the horizontal
        plane through the ball's centre, the region swept by its cross-section from its own
        position to the projection of its top, ``c + (p - c) (h - zc) / (h - H)``, whose radius
        grows to ``R (h - zc) / (h - H)``: a capsule of the larger radius (3 % at most larger
        than the true shape of an SSL robot under a 4 m camera). A ball above a robot cannot be
        hidden by it.
        """
        if self.shapes is None:
            hidden = self._hidden_by(bx, by, zc, robots, cx, cy, h, self.robot_spec.height,
                                     self.robot_spec.radius, None)
        else:
            hidden = None
            for (H, R), members in self.shapes:
                hidden = self._hidden_by(bx, by, zc, [robots[i] for i in members], cx, cy, h,
                                         H, R, hidden)
        return 0.0 if hidden is None else sum(hidden) / len(hidden)

    def _hidden_by(self, bx: float, by: float, zc: float, robots: list, cx: float, cy: float,
                   h: float, H: float, R: float, hidden: list[bool] | None
                   ) -> list[bool] | None:
        """:meth:`hidden` for ``robots`` of one body (height ``H``, radius ``R``): the ring
        points of the ball's disc they cover added to ``hidden`` (None: none covered yet)."""
        r = self.ball_radius
        if zc >= H:
            return hidden
        k = (h - zc) / (h - H)
        radius = R * k
        reach2 = (radius + r) ** 2
        # No robot farther than this from the ball can cover it: its capsule reaches
        # ``radius + |top - p|`` from it, and ``|top - p| = (k - 1) |p - c|`` with the
        # robot's distance to the camera's foot, under 10 m on any field.
        near2 = (radius + r + 10.0 * (k - 1.0) + 0.01) ** 2
        for x, y, _ in robots:
            if (x - bx) ** 2 + (y - by) ** 2 > near2:
                continue
            tx, ty = cx + (x - cx) * k, cy + (y - cy) * k
            sx, sy = tx - x, ty - y
            seg2 = sx * sx + sy * sy
            # Skip robots whose capsule cannot reach the ball.
            s = ((bx - x) * sx + (by - y) * sy) / seg2 if seg2 > 1e-12 else 0.0
            s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
            dx, dy = bx - x - s * sx, by - y - s * sy
            if dx * dx + dy * dy > reach2:
                continue
            if hidden is None:
                hidden = [False] * len(RING)
            for j, (ox, oy) in enumerate(RING):
                if hidden[j]:
                    continue
                px, py = bx + r * ox - x, by + r * oy - y
                s = (px * sx + py * sy) / seg2 if seg2 > 1e-12 else 0.0
                s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
                qx, qy = px - s * sx, py - s * sy
                hidden[j] = qx * qx + qy * qy <= radius * radius
        return hidden
