"""The attacker of a scripted SSL team: take the ball, aim into an open part of the goal mouth
and shoot, or dribble past a blocker; each single and batched pair side by side.

The attacker drives to a point behind the ball on the line from an open point of the opponent
goal mouth through the ball (the one needing the least repositioning), turns to face it,
drives through the ball and arms its kicker while its heading points into the goal mouth past
every opponent. When every shooting line is blocked by a nearby opponent it dribbles
diagonally past it instead. It predicts a moving ball's position with
:class:`~estimators.FrictionBallModel` and stays out of the own defense area (the keeper
clearing a ball excepted) and, with the game flow, out of the opponents' (touching the ball
partly inside it is a foul, 8.4.2).

Positions are in the team frame [m], headings in radians, speeds in m/s.
"""

from __future__ import annotations

import math

import numpy as np

from agents.scripted.geometry import TeamGeometry
from agents.scripted.motion import drive_and_turn, drive_and_turn_rows
from agents.scripted.view import Frame
from estimators import FrictionBallModel
from soccer_env.envs.keeper import wrap_angles

__all__ = ["Attack", "Opponents", "OpponentRows"]

#: The opponents' positions ``[(x, y), ...]`` in the team frame [m].
Opponents = list[tuple[float, float]]
#: The opponents' positions ``(x, y)`` for observation rows, each ``(n_opps, n)`` [m].
OpponentRows = tuple[np.ndarray, np.ndarray]


class Attack:
    """The attacker's play (see the module docstring).

    Args:
        geometry: the team's geometry.
        model: the ball's rolling model.
        attack_speed: speed [m/s] at which the attacker drives through the ball.
        kick_power: the kicker power of a shot (``(0, 1]``).
        avoid_opponent_defense: keep out of the opponent defense area (the game flow's
            rules).
    """

    def __init__(self, geometry: TeamGeometry, model: FrictionBallModel, attack_speed: float,
                 kick_power: float, avoid_opponent_defense: bool) -> None:
        self.geometry = geometry
        self.model = model
        self.attack_speed = float(attack_speed)
        self.kick_power = kick_power
        self.avoid_opponent_defense = avoid_opponent_defense
        #: Aim points across the goal mouth, a ball radius and 5 cm inside the posts [m].
        inner = geometry.half_goal - geometry.ball.radius - 0.05
        self.aim_ys = [inner * f for f in (-1.0, -0.5, 0.0, 0.5, 1.0)]
        #: Sideways offset [m] over which the attacker's alignment with the ball fades out,
        #: and how far beyond the ball it drives when lined up [m].
        self.lateral_scale = 0.06
        self.through = 0.4
        #: Dribbling direction off the goal direction when every shot is blocked by a nearby
        #: opponent: 60 degrees to either side.
        self.escape_cos, self.escape_sin = 0.5, math.sqrt(3.0) / 2.0

    # ------------------------------------------------------------------------------------
    # Where the ball will be

    def ball_ahead(self, f: Frame) -> tuple[float, float]:
        """Where the ball will be when the robot gets there, at most a second ahead [m]."""
        px, py, bx, by, bvx, bvy = f.px, f.py, f.bx, f.by, f.bvx, f.bvy
        reach = min(math.hypot(bx - px, by - py) / self.geometry.robot.max_speed, 1.0)
        if bvx * bvx + bvy * bvy > 1e-4:
            bx, by = (float(v) for v in self.model.predict(np.array([bx, by, bvx, bvy]),
                                                           reach)[0:2])
        return bx, by

    def ball_ahead_rows(self, f: Frame) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`ball_ahead` on arrays [m]."""
        px, py, bx, by, bvx, bvy = f.px, f.py, f.bx, f.by, f.bvx, f.bvy
        reach = np.minimum(self.geometry.hypot(bx - px, by - py)
                           / self.geometry.robot.max_speed, 1.0)
        moving = bvx * bvx + bvy * bvy > 1e-4
        if moving.any():
            ahead = self.model.predict(np.stack([bx, by, bvx, bvy], axis=-1)[moving],
                                       reach[moving])
            bx, by = bx.copy(), by.copy()
            bx[moving], by[moving] = ahead[:, 0], ahead[:, 1]
        return bx, by

    # ------------------------------------------------------------------------------------
    # The attacker's action

    def act(self, f: Frame, opps: Opponents, keeper: bool = False) -> list[float]:
        """Go behind the ball on the line from the aim point through the ball, face the aim,
        drive through the ball and shoot when the heading points into the open goal mouth.
        Only the ``keeper`` may enter the own defense area."""
        g = self.geometry
        r = g.robot
        px, py, c, s = f.px, f.py, f.c, f.s
        bx, by = self.ball_ahead(f)
        (ax, ay), shoot = self.aim(px, py, bx, by, opps)
        ex, ey = ax - bx, ay - by
        d_aim = math.hypot(ex, ey) or 1.0
        ex, ey = ex / d_aim, ey / d_aim  # ball -> aim point
        nx, ny = -ey, ex
        along = (px - bx) * ex + (py - by) * ey  # < 0: behind the ball
        lateral = (px - bx) * nx + (py - by) * ny
        face = math.atan2(ey, ex)
        heading_err = abs(math.remainder(face - math.atan2(s, c), 2.0 * math.pi))
        contact = g.contact
        cap = None
        if along > -contact and abs(lateral) < contact + r.radius + 0.05:
            # In front of or beside the ball: step round it on the near side first.
            side = 1.0 if lateral >= 0.0 else -1.0
            clear = r.radius + g.ball.radius + 0.12
            tx, ty = bx + side * clear * nx - 0.1 * ex, by + side * clear * ny - 0.1 * ey
        else:
            # Behind the ball: the better lined up (sideways offset and heading), the further
            # forward the target, from a waiting point behind the ball to a point beyond it.
            align = (max(0.0, 1.0 - abs(lateral) / self.lateral_scale)
                     * max(0.0, 1.0 - heading_err / 0.5)) ** 2
            back = contact + 0.12 - (contact + 0.12 + self.through) * align
            tx, ty = bx - back * ex, by - back * ey
            if align > 0.25:
                cap = self.attack_speed
        if not keeper:
            tx, ty = g.outside_defense_area(tx, ty)
        if self.avoid_opponent_defense:  # touching the ball partly inside it is a foul
            tx, ty = g.outside_opponent_defense(tx, ty, r.radius + 0.03)
        tx, ty = g.within_walls(tx, ty)
        kick = self.kick_power if shoot and f.dx > 0.0 and self.on_target(px, py, c, s, opps) \
            else 0.0
        return drive_and_turn(r, f, tx, ty, face, cap, kick)

    def act_rows(self, f: Frame, opps: OpponentRows, keeper: np.ndarray) -> np.ndarray:
        """:meth:`act` on arrays: actions ``(n, 6)``; ``keeper``: rows that may enter the
        own defense area."""
        g, hypot = self.geometry, self.geometry.hypot
        r = g.robot
        px, py, c, s = f.px, f.py, f.c, f.s
        bx, by = self.ball_ahead_rows(f)
        ax, ay, shoot = self.aim_rows(px, py, bx, by, opps)
        ex, ey = ax - bx, ay - by
        d_aim = hypot(ex, ey)
        d_aim = np.where(d_aim == 0.0, 1.0, d_aim)
        ex, ey = ex / d_aim, ey / d_aim  # ball -> aim point
        nx, ny = -ey, ex
        along = (px - bx) * ex + (py - by) * ey  # < 0: behind the ball
        lateral = (px - bx) * nx + (py - by) * ny
        face = np.arctan2(ey, ex)
        heading_err = np.abs(wrap_angles(face - np.arctan2(s, c)))
        contact = g.contact
        beside = (along > -contact) & (np.abs(lateral) < contact + r.radius + 0.05)
        # In front of or beside the ball: step round it on the near side first.
        side = np.where(lateral >= 0.0, 1.0, -1.0)
        clear = r.radius + g.ball.radius + 0.12
        tx_round = bx + side * clear * nx - 0.1 * ex
        ty_round = by + side * clear * ny - 0.1 * ey
        # Behind the ball: the better lined up, the further forward the target. Python's
        # ``** 2`` is the C library's pow, which np.float_power calls (x * x can differ).
        align = np.float_power(np.maximum(0.0, 1.0 - np.abs(lateral) / self.lateral_scale)
                               * np.maximum(0.0, 1.0 - heading_err / 0.5), 2.0)
        back = contact + 0.12 - (contact + 0.12 + self.through) * align
        tx = np.where(beside, tx_round, bx - back * ex)
        ty = np.where(beside, ty_round, by - back * ey)
        cap = np.where(~beside & (align > 0.25), self.attack_speed, r.max_speed)
        outside_x, outside_y = g.outside_defense_area_rows(tx, ty)
        tx, ty = np.where(keeper, tx, outside_x), np.where(keeper, ty, outside_y)
        if self.avoid_opponent_defense:  # touching the ball partly inside it is a foul
            tx, ty = g.outside_opponent_defense_rows(tx, ty, r.radius + 0.03)
        tx, ty = g.within_walls_rows(tx, ty)
        kick = (shoot & (f.dx > 0.0) & self.on_target_rows(px, py, c, s, opps)) \
            * self.kick_power
        return drive_and_turn_rows(r, f, tx, ty, face, kick, cap, hypot)

    # ------------------------------------------------------------------------------------
    # Where to send the ball

    def aim(self, px: float, py: float, bx: float, by: float, opps: Opponents
            ) -> tuple[tuple[float, float], bool]:
        """Where to send the ball: ``((x, y), shoot)``.

        Candidates are points spread across the opponent goal mouth; a candidate is open if
        no opponent stands within a robot radius plus a ball radius (and a margin growing
        with distance) of the line from the ball to it. Among the open ones the attacker
        takes the one needing the least repositioning (its current bearing from the ball).
        If none is open (``shoot`` False), it carries the ball towards the goal centre while
        the blockers are more than a metre away, and otherwise dribbles it 60 degrees off the
        goal direction, to the side with more room.
        """
        goal_x = self.geometry.goal_x
        best, best_cost = None, math.inf
        rbx, rby = bx - px, by - py  # robot -> ball, the current approach direction
        norm = math.hypot(rbx, rby) or 1.0
        rbx, rby = rbx / norm, rby / norm
        for ty in self.aim_ys:
            clearance = self.clearance(bx, by, goal_x, ty, opps)
            if clearance <= 0.0:
                continue
            ex, ey = goal_x - bx, ty - by
            d = math.hypot(ex, ey) or 1.0
            # Turning cost (1 - cos of the angle between approach and shot), minus a bonus
            # for clearance.
            cost = 1.0 - (rbx * ex + rby * ey) / d - 0.5 * min(clearance, 0.5)
            if cost < best_cost:
                best, best_cost = (goal_x, ty), cost
        if best is not None:
            return best, True
        # Blocked. With the blocker far away, carry the ball towards the goal centre (an
        # opening may appear); with it close, dribble diagonally forward on the side with
        # more room, preferring the side the robot already stands behind (so that it does
        # not hesitate between two equal sides).
        if self.nearest_ahead(bx, by, opps) > 1.0:
            return (goal_x, 0.0), False
        gx, gy = goal_x - bx, -by
        d = math.hypot(gx, gy) or 1.0
        gx, gy = gx / d, gy / d
        options = []
        for sign in (1.0, -1.0):
            cos_a, sin_a = self.escape_cos, sign * self.escape_sin
            ux, uy = gx * cos_a - gy * sin_a, gx * sin_a + gy * cos_a
            tx, ty = bx + ux, by + uy
            room = min(self.clearance(bx, by, tx, ty, opps), 0.3)
            inside = abs(ty) < self.geometry.field.half_width - 0.3
            behind = rbx * ux + rby * uy  # > 0: the robot is behind the ball for u
            options.append((room + (0.0 if inside else -1.0) + 0.5 * behind, (tx, ty)))
        return max(options)[1], False

    def aim_rows(self, px: np.ndarray, py: np.ndarray, bx: np.ndarray, by: np.ndarray,
                 opps: OpponentRows) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`aim` on arrays: ``(x, y, shoot)`` [m]."""
        goal_x, hypot = self.geometry.goal_x, self.geometry.hypot
        rbx, rby = bx - px, by - py  # robot -> ball, the current approach direction
        norm = hypot(rbx, rby)
        norm = np.where(norm == 0.0, 1.0, norm)
        rbx, rby = rbx / norm, rby / norm
        # All aim points at once, (5, n); the first open one of least cost.
        aim_ys = np.array(self.aim_ys)[:, None]
        ex, ey = np.broadcast_arrays(goal_x - bx, aim_ys - by)
        d = hypot(ex, ey)  # also the length of the shooting lines, for clearance_rows
        clearance = self.clearance_rows(bx, by, goal_x, aim_ys, opps, d)
        d = np.where(d == 0.0, 1.0, d)
        cost = 1.0 - (rbx * ex + rby * ey) / d - 0.5 * np.minimum(clearance, 0.5)
        open_ = clearance > 0.0
        shoot = open_.any(axis=0)
        ax = np.full(len(px), goal_x)
        ay = aim_ys[np.argmin(np.where(open_, cost, math.inf), axis=0), 0]
        blocked = np.flatnonzero(~shoot)
        if len(blocked) == 0:
            return ax, ay, shoot
        # Blocked: towards the goal centre while the blockers are far, else the escape side.
        bx, by, rbx, rby = bx[blocked], by[blocked], rbx[blocked], rby[blocked]
        opps = (opps[0][:, blocked], opps[1][:, blocked])
        gx, gy = goal_x - bx, -by
        d = hypot(gx, gy)
        d = np.where(d == 0.0, 1.0, d)
        gx, gy = gx / d, gy / d
        # Both sides at once, (2, n): sign +1 first.
        cos_a, sin_a = self.escape_cos, np.array([[1.0], [-1.0]]) * self.escape_sin
        ux, uy = gx * cos_a - gy * sin_a, gx * sin_a + gy * cos_a
        tx, ty = bx + ux, by + uy
        room = np.minimum(self.clearance_rows(bx, by, tx, ty, opps), 0.3)
        inside = np.abs(ty) < self.geometry.field.half_width - 0.3
        behind = rbx * ux + rby * uy  # > 0: the robot is behind the ball for u
        score = room + np.where(inside, 0.0, -1.0) + 0.5 * behind
        # max() of (score, (x, y)) tuples: the second side only if strictly greater.
        (s0, s1), (x0, x1), (y0, y1) = score, tx, ty
        second = (s1 > s0) | ((s1 == s0) & ((x1 > x0) | ((x1 == x0) & (y1 > y0))))
        far = self.nearest_ahead_rows(bx, by, opps) > 1.0
        ax[blocked] = np.where(far, goal_x, np.where(second, x1, x0))
        ay[blocked] = np.where(far, 0.0, np.where(second, y1, y0))
        return ax, ay, shoot

    def nearest_ahead(self, bx: float, by: float, opps: Opponents) -> float:
        """Distance [m] from the ball to the nearest opponent nearer the opponent goal."""
        return min((math.hypot(ox - bx, oy - by) for ox, oy in opps if ox > bx - 0.1),
                   default=math.inf)

    def nearest_ahead_rows(self, bx: np.ndarray, by: np.ndarray, opps: OpponentRows
                           ) -> np.ndarray:
        """:meth:`nearest_ahead` on arrays [m]."""
        ox, oy = opps
        d = np.where(ox > bx - 0.1, self.geometry.hypot(ox - bx, oy - by), math.inf)
        return np.min(d, axis=0, initial=math.inf)

    def clearance(self, bx: float, by: float, tx: float, ty: float, opps: Opponents
                  ) -> float:
        """Smallest gap [m] between the segment from the ball ``(bx, by)`` to ``(tx, ty)`` and
        an opponent, beyond a robot radius, a ball radius and a margin of 3 % of the
        opponent's distance along the segment (it can move while the ball travels); positive
        means open."""
        ex, ey = tx - bx, ty - by
        length = math.hypot(ex, ey) or 1e-9
        ex, ey = ex / length, ey / length
        reach = self.geometry.robot.radius + self.geometry.ball.radius
        gap = math.inf
        for ox, oy in opps:
            t = (ox - bx) * ex + (oy - by) * ey
            if t < -reach or t > length + reach:
                continue
            perp = abs((ox - bx) * ey - (oy - by) * ex)
            gap = min(gap, perp - reach - 0.02 - 0.03 * max(t, 0.0))
        return gap

    def clearance_rows(self, bx: np.ndarray, by: np.ndarray, tx: np.ndarray | float,
                       ty: np.ndarray | float, opps: OpponentRows,
                       length: np.ndarray | None = None) -> np.ndarray:
        """:meth:`clearance` on arrays [m], for ``k`` targets per row at once: ``tx``, ``ty``
        broadcast to ``(k, n)`` against the balls ``(n,)``; returns ``(k, n)``. ``length``:
        ``hypot(tx - bx, ty - by)`` if the caller has it."""
        ex, ey = np.broadcast_arrays(tx - bx, ty - by)
        length = self.geometry.hypot(ex, ey) if length is None else length
        length = np.where(length == 0.0, 1e-9, length)
        ex, ey = (ex / length)[:, None], (ey / length)[:, None]  # (k, 1, n)
        rx, ry = opps[0] - bx, opps[1] - by  # ball -> opponents, (n_opps, n)
        reach = self.geometry.robot.radius + self.geometry.ball.radius
        t = rx * ex + ry * ey  # (k, n_opps, n)
        perp = np.abs(rx * ey - ry * ex)
        near = (t >= -reach) & (t <= length[:, None] + reach)
        gap = perp - reach - 0.02 - 0.03 * np.maximum(t, 0.0)
        return np.min(np.where(near, gap, math.inf), axis=1, initial=math.inf)

    def on_target(self, px: float, py: float, c: float, s: float, opps: Opponents) -> bool:
        """Whether the robot's heading line crosses the opponent goal mouth (a ball radius
        plus 3 cm inside each post) with no opponent on the way."""
        g = self.geometry
        if c < 0.2:
            return False
        y_goal = py + s / c * (g.goal_x - px)
        if abs(y_goal) >= g.half_goal - g.ball.radius - 0.03:
            return False
        return self.clearance(px, py, g.goal_x, y_goal, opps) > 0.0

    def on_target_rows(self, px: np.ndarray, py: np.ndarray, c: np.ndarray, s: np.ndarray,
                       opps: OpponentRows) -> np.ndarray:
        """:meth:`on_target` on arrays."""
        g = self.geometry
        facing = c >= 0.2
        y_goal = py + s / np.where(facing, c, 1.0) * (g.goal_x - px)
        inside = np.abs(y_goal) < g.half_goal - g.ball.radius - 0.03
        open_ = self.clearance_rows(px, py, g.goal_x, y_goal[None], opps)[0] > 0.0
        return facing & inside & open_
