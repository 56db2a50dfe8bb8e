"""The defenders of a scripted SSL team: lines between the ball and the own goal.

Defender ``rank`` of ``n_def`` stands in line ``rank // 3`` (three per line:
:data:`~agents.scripted.roles.DEFENDERS_PER_LINE`), slot ``rank % 3``. The line lies across
the line from the own goal's centre to the ball, at

    ``min(max(defense_depth + r + 0.4, 0.45 d) + 0.9 line, max(d - 0.6, defense_depth + 0.3))``

from the goal centre (``d`` the ball's distance from it, ``r`` the robot radius, [m]), and the
slots of a line are ``defender_spacing (1 + line)`` apart across it, centred on it. A
defender walks round the ball to its slot, keeps out of the own defense area, faces the ball
and clears it forward when it reaches its kicker while facing the opponent half.

Positions are in the team frame [m], headings in radians, speeds in m/s. The rules are
compiled kernels (:func:`defender_target`, :func:`defender_act`) on floats; :class:`Defence`
holds the team's numbers and calls them.
"""

from __future__ import annotations

import math

from agents.scripted.geometry import (
    Pitch,
    TeamGeometry,
    around_ball,
    outside_defense_area,
    within_walls,
)
from agents.scripted.motion import Action, command
from agents.scripted.roles import DEFENDERS_PER_LINE
from estimators.compiled import kernel
from estimators.exact import hypot_exact

__all__ = ["Defence", "defender_target", "defender_act"]


@kernel
def defender_target(p: Pitch, spacing: float, bx: float, by: float, rank: int, n_def: int
                    ) -> tuple[float, float]:
    """Slot ``rank`` of ``n_def`` defenders, ``spacing`` [m] apart in a line, between the ball
    ``(bx, by)`` and the own goal (the module docstring) [m]."""
    ox = -p.goal_x
    fx, fy = bx - ox, by
    d_ball = hypot_exact(fx, fy)
    if d_ball == 0.0:
        d_ball = 1e-3
    fx, fy = fx / d_ball, fy / d_ball  # own goal -> ball
    nx, ny = -fy, fx
    per_line = DEFENDERS_PER_LINE
    line, slot = rank // per_line, rank % per_line
    in_line = min(per_line, n_def - line * per_line)
    base = max(p.defense_depth + p.radius + 0.4, 0.45 * d_ball)
    dist = min(base + 0.9 * line, max(d_ball - 0.6, p.defense_depth + 0.3))
    offset = (slot - 0.5 * (in_line - 1)) * spacing * (1 + line)
    return ox + dist * fx + offset * nx, dist * fy + offset * ny


@kernel
def defender_act(p: Pitch, spacing: float, kick_power: float, px: float, py: float, c: float,
                 s: float, bx: float, by: float, dx: float, dy: float, rank: int, n_def: int
                 ) -> Action:
    """Hold slot ``rank`` of ``n_def`` (:func:`defender_target`): walk round the ball
    ``(bx, by)`` to it, out of the own defense area and inside the walls, facing the ball,
    and clear it with ``kick_power`` when it lies at the kicker (offset ``(dx, dy)`` in the
    body frame [m]) while the robot faces the opponent half (``c > 0.3``)."""
    tx, ty = defender_target(p, spacing, bx, by, rank, n_def)
    tx, ty = around_ball(px, py, tx, ty, bx, by, p.radius + p.ball_radius + 0.15, 0.0)
    tx, ty = outside_defense_area(p, tx, ty)
    tx, ty = within_walls(p, tx, ty)
    # Clear the ball forward if it reaches the kicker while we face the opponent half.
    in_front = 0.0 < dx < p.front_distance + 0.1 and abs(dy) < 0.5 * p.kicker_width
    kick = kick_power if in_front and c > 0.3 else 0.0
    return command(p.max_speed, p.max_acceleration, p.max_angular_speed, px, py, c, s, tx,
                   ty, math.atan2(by - py, bx - px), math.inf, kick, -1.0)


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
        self.kick_power = float(kick_power)
        #: Defenders of a full team: all robots but the keeper (of a team of two or more)
        #: and the attacker.
        self.count = int(team_size) - (2 if team_size >= 2 else 1)

    def target(self, bx: float, by: float, rank: int, n_def: int) -> tuple[float, float]:
        """:func:`defender_target`: slot ``rank`` of ``n_def`` defenders [m]."""
        return defender_target(self.geometry.pitch, self.spacing, bx, by, rank, n_def)
