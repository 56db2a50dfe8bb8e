"""The two goals as obstacles for a scripted SSL robot off the field of play: their walls as
segments (:class:`GoalWalls`), whether a robot's centre may stand somewhere, and a way round
them (:meth:`GoalWalls.route`).

A ball that leaves over a goal line can stop behind it, beside a goal; a robot fetching it
from the other side must go round the goal through the field (the run-off area behind a goal
is narrower than a robot on the league's fields). The route is the shortest path over a small
visibility graph: the robot, the target, two points in front of each goal's posts, and, for a
target inside a goal, the point in front of the mouth on the target's line.

All positions are in the team frame [m] (the goals at ``x = -goal_x`` and ``x = +goal_x``).
"""

from __future__ import annotations

import heapq
import math

from soccer_env.presets import FieldSpec
from soccer_env.sim.game.geometry import segment_distance

__all__ = ["GoalWalls", "segment_gap"]


def segment_gap(a: tuple[float, float], b: tuple[float, float], c: tuple[float, float],
                d: tuple[float, float]) -> float:
    """Shortest distance between the segments ``a``-``b`` and ``c``-``d`` [m] (0 where they
    cross)."""
    def orient(p, q, r) -> float:
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    o1, o2 = orient(a, b, c), orient(a, b, d)
    o3, o4 = orient(c, d, a), orient(c, d, b)
    if o1 * o2 < 0.0 and o3 * o4 < 0.0:
        return 0.0
    return min(segment_distance(*a, *c, *d), segment_distance(*b, *c, *d),
               segment_distance(*c, *a, *b), segment_distance(*d, *a, *b))


class GoalWalls:
    """The walls of both goals of ``field`` as segments along their middles, for a robot of
    radius ``radius`` [m] that keeps ``pad`` [m] beyond touching them.

    Args:
        field: the match's field.
        radius: the robot's radius [m].
        pad: the gap kept from a wall beyond touching it [m].
    """

    def __init__(self, field: FieldSpec, radius: float, pad: float = 0.03) -> None:
        hx, t = field.half_length, field.goal_wall_thickness
        half = 0.5 * field.goal_width + 0.5 * t
        back = hx + field.goal_depth + 0.5 * t
        self.goal_x, self.half_goal = hx, 0.5 * field.goal_width
        #: Centre-to-wall-middle distance a robot keeps [m].
        self.keep = radius + 0.5 * t + pad
        self.half_wall = 0.5 * t
        self.walls: list[tuple[tuple[float, float], tuple[float, float]]] = []
        for s in (-1.0, 1.0):
            self.walls += [((s * hx, half), (s * back, half)), ((s * hx, -half), (s * back, -half)),
                           ((s * back, -half), (s * back, half))]
        # Waypoints in front of each post, a robot's keep clear of it.
        out = half + self.keep + 0.02
        self.corners = [(s * (hx - self.keep - 0.02), sy * out) for s in (-1.0, 1.0)
                        for sy in (-1.0, 1.0)]
        self.radius = radius

    def gap(self, x: float, y: float) -> float:
        """Distance from ``(x, y)`` to the nearest goal wall's middle [m]."""
        return min(segment_distance(x, y, *a, *b) for a, b in self.walls)

    def free(self, x: float, y: float, pad: float | None = None) -> bool:
        """Whether a robot's centre at ``(x, y)`` keeps ``pad`` [m] (by default the route's)
        beyond touching every goal wall."""
        keep = self.keep if pad is None else self.radius + self.half_wall + pad
        return self.gap(x, y) >= keep

    def clear(self, a: tuple[float, float], b: tuple[float, float],
              keep: float | None = None) -> bool:
        """Whether a robot driving straight from ``a`` to ``b`` keeps ``keep`` [m] (by
        default :attr:`keep`) from every wall's middle."""
        k = self.keep if keep is None else keep
        return all(segment_gap(a, b, c, d) >= k for c, d in self.walls)

    def route(self, px: float, py: float, tx: float, ty: float) -> tuple[float, float]:
        """The next point on the way from ``(px, py)`` to ``(tx, ty)`` round the goals [m]:
        the target itself when the straight way is clear (or when no way round is found)."""
        start, goal = (px, py), (tx, ty)
        # A robot already nearer a wall than it should be (pushed there) may leave, and a
        # target that near may be reached: their edges keep what they have.
        ends = [min(self.keep, self.gap(px, py) - 1e-3), min(self.keep, self.gap(tx, ty) - 1e-3)]
        if self.clear(start, goal, min(ends)):
            return tx, ty
        nodes = [start, goal] + [c for c in self.corners if self.free(*c)]
        for x, y in (start, goal):
            if abs(x) > self.goal_x - self.keep and abs(y) < self.half_goal:
                # A start or a target inside a goal: through the mouth, from in front of it.
                nodes.append((math.copysign(self.goal_x - self.keep - 0.02, x), y))
        dist = [math.inf] * len(nodes)
        prev = [-1] * len(nodes)
        dist[0] = 0.0
        heap = [(0.0, 0)]
        while heap:
            d0, i = heapq.heappop(heap)
            if i == 1 or d0 > dist[i]:
                continue
            for j in range(1, len(nodes)):
                keep = min([self.keep] + [ends[k] for k in (i, j) if k < 2])
                if j == i or not self.clear(nodes[i], nodes[j], keep):
                    continue
                dj = d0 + math.dist(nodes[i], nodes[j])
                if dj < dist[j]:
                    dist[j], prev[j] = dj, i
                    heapq.heappush(heap, (dj, j))
        if prev[1] < 0:
            return tx, ty
        j = 1
        while prev[j] != 0:
            j = prev[j]
        return nodes[j]
