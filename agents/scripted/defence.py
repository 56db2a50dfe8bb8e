"""The defenders of a scripted SSL team: lines between the ball and the own goal; each single
and batched pair side by side.

Defender ``rank`` of ``n_def`` stands in line ``rank // 3`` (three per line:
:data:`~agents.scripted.roles.DEFENDERS_PER_LINE`), slot ``rank % 3``. The line lies across
the line from the own goal's centre to the ball, at

    ``min(max(defense_depth + r + 0.4, 0.45 d) + 0.9 line, max(d - 0.6, defense_depth + 0.3))``

from the goal centre (``d`` the ball's distance from it, ``r`` the robot radius, [m]), and the
slots of a line are ``defender_spacing (1 + line)`` apart across it, centred on it. A
defender walks round the ball to its slot, keeps out of the own defense area, faces the ball
and clears it forward when it reaches its kicker while facing the opponent half.

Positions are in the team frame [m], headings in radians, speeds in m/s.
"""

from __future__ import annotations

import math

import numpy as np

from agents.scripted.geometry import TeamGeometry
from agents.scripted.motion import drive_and_turn, drive_and_turn_rows
from agents.scripted.roles import DEFENDERS_PER_LINE
from agents.scripted.view import Frame

__all__ = ["Defence"]


class Defence:
    """The defenders' play (see the module docstring).

    Args:
        geometry: the team's geometry.
        team_size: robots in the team.
        spacing: lateral distance between defenders of one line [m].
        kick_power: the kicker power of a clearance (``(0, 1]``).
    """

    def __init__(self, geometry: TeamGeometry, team_size: int, spacing: float,
                 kick_power: float) -> None:
        self.geometry = geometry
        self.spacing = float(spacing)
        self.kick_power = kick_power
        #: Defenders of a full team: all robots but the keeper (of a team of two or more)
        #: and the attacker.
        self.count = int(team_size) - (2 if team_size >= 2 else 1)

    def target(self, bx: float, by: float, rank: int, n_def: int) -> tuple[float, float]:
        """Slot ``rank`` of ``n_def`` defenders between the ball ``(bx, by)`` and the own
        goal [m]."""
        g = self.geometry
        r = g.robot
        ox = -g.goal_x
        fx, fy = bx - ox, by
        d_ball = math.hypot(fx, fy) or 1e-3
        fx, fy = fx / d_ball, fy / d_ball  # own goal -> ball
        nx, ny = -fy, fx
        per_line = DEFENDERS_PER_LINE
        line, slot = divmod(rank, per_line)
        in_line = min(per_line, n_def - line * per_line)
        base = max(g.field.defense_depth + r.radius + 0.4, 0.45 * d_ball)
        dist = min(base + 0.9 * line, max(d_ball - 0.6, g.field.defense_depth + 0.3))
        offset = (slot - 0.5 * (in_line - 1)) * self.spacing * (1 + line)
        return ox + dist * fx + offset * nx, dist * fy + offset * ny

    def target_rows(self, bx: np.ndarray, by: np.ndarray, rank: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`target` on arrays, for the defenders of a full team (:attr:`count`) [m]."""
        g = self.geometry
        r = g.robot
        n_def = self.count
        ox = -g.goal_x
        fx, fy = bx - ox, by
        d_ball = g.hypot(fx, fy)
        d_ball = np.where(d_ball == 0.0, 1e-3, d_ball)
        fx, fy = fx / d_ball, fy / d_ball  # own goal -> ball
        nx, ny = -fy, fx
        per_line = DEFENDERS_PER_LINE
        line, slot = rank // per_line, rank % per_line
        in_line = np.minimum(per_line, n_def - line * per_line)
        base = np.maximum(g.field.defense_depth + r.radius + 0.4, 0.45 * d_ball)
        dist = np.minimum(base + 0.9 * line,
                          np.maximum(d_ball - 0.6, g.field.defense_depth + 0.3))
        offset = (slot - 0.5 * (in_line - 1)) * self.spacing * (1 + line)
        return ox + dist * fx + offset * nx, dist * fy + offset * ny

    def act(self, f: Frame, rank: int, n_def: int) -> list[float]:
        """Hold slot ``rank`` of ``n_def`` between the ball and the own goal."""
        g = self.geometry
        r = g.robot
        px, py, c, bx, by, dx, dy = f.px, f.py, f.c, f.bx, f.by, f.dx, f.dy
        tx, ty = self.target(bx, by, rank, n_def)
        tx, ty = g.around_ball(px, py, tx, ty, bx, by)
        tx, ty = g.outside_defense_area(tx, ty)
        tx, ty = g.within_walls(tx, ty)
        # Clear the ball forward if it reaches the kicker while we face the opponent half.
        in_front = 0.0 < dx < r.front_distance + 0.1 and abs(dy) < 0.5 * r.kicker_width
        kick = self.kick_power if in_front and c > 0.3 else 0.0
        return drive_and_turn(r, f, tx, ty, math.atan2(by - py, bx - px), kick=kick)

    def act_rows(self, f: Frame, rank: np.ndarray) -> np.ndarray:
        """:meth:`act` on arrays: actions ``(n, 6)`` for the defenders of ranks ``rank`` of a
        full team."""
        g = self.geometry
        r = g.robot
        px, py, c, bx, by, dx, dy = f.px, f.py, f.c, f.bx, f.by, f.dx, f.dy
        tx, ty = self.target_rows(bx, by, rank)
        tx, ty = g.around_ball_rows(px, py, tx, ty, bx, by)
        tx, ty = g.outside_defense_area_rows(tx, ty)
        tx, ty = g.within_walls_rows(tx, ty)
        in_front = (0.0 < dx) & (dx < r.front_distance + 0.1) & (np.abs(dy)
                                                                  < 0.5 * r.kicker_width)
        return drive_and_turn_rows(r, f, tx, ty, np.arctan2(by - py, bx - px),
                                   (in_front & (c > 0.3)) * self.kick_power)
