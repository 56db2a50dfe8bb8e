"""The attacker of a scripted SSL team: take the ball, aim into an open part of the goal mouth
and shoot, or dribble past a blocker.

The attacker drives to a point behind the ball on the line from an open point of the opponent
goal mouth through the ball (the one needing the least repositioning), turns to face it,
drives through the ball and arms its kicker while its heading points into the goal mouth past
every opponent. When every shooting line is blocked by a nearby opponent it dribbles
diagonally past it instead. It predicts a moving ball's position with
:class:`~estimators.FrictionBallModel` and stays out of the own defense area (the keeper
clearing a ball excepted) and, with the game flow, out of the opponents' (touching the ball
partly inside it is a foul, 8.4.2).

Positions are in the team frame [m], headings in radians, speeds in m/s. The rules are
compiled kernels on floats, the team's numbers (:class:`~agents.scripted.geometry.Pitch`,
:class:`Striker`) and the opponents as an array ``(k, 2)``; :class:`Attack` holds the numbers
and calls them for the restarts' Python.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from agents.scripted.geometry import (
    Pitch,
    TeamGeometry,
    outside_defense_area,
    outside_opponent_defense,
    within_walls,
)
from agents.scripted.motion import Action, command
from agents.scripted.view import Frame
from estimators import FrictionBallModel
from estimators.compiled import kernel
from estimators.exact import hypot_exact, wrap_angle

__all__ = ["Attack", "Opponents", "Striker", "opponent_array", "roll", "ball_ahead",
           "clearance", "nearest_ahead", "aim", "on_target", "attacker_act"]

#: The opponents' positions ``[(x, y), ...]`` in the team frame [m].
Opponents = list[tuple[float, float]]


class Striker(NamedTuple):
    """The attacker's numbers that its kernels read."""

    #: Speed [m/s] at which the attacker drives through the ball.
    attack_speed: float
    #: The kicker power of a shot (``(0, 1]``).
    kick_power: float
    #: Keep out of the opponent defense area (the game flow's rules).
    avoid_opponent_defense: bool
    #: Sideways offset [m] over which the attacker's alignment with the ball fades out, and
    #: how far beyond the ball it drives when lined up [m].
    lateral_scale: float
    through: float
    #: Dribbling direction off the goal direction when every shot is blocked by a nearby
    #: opponent: ``(cos, sin)`` of 60 degrees.
    escape_cos: float
    escape_sin: float
    #: Aim points across the goal mouth, a ball radius and 5 cm inside the posts [m].
    aim_ys: tuple[float, float, float, float, float]
    #: The ball's rolling deceleration [m/s^2] (:class:`~estimators.FrictionBallModel`).
    deceleration: float
    #: The exponent of the alignment, 2: an argument rather than a constant so that the
    #: compiled ``align ** power`` is the C library's ``pow``, as Python's ``**`` is (a
    #: constant 2 is compiled as ``align * align``, which rounds differently now and then).
    power: float


def opponent_array(opps: Opponents) -> np.ndarray:
    """The opponents ``[(x, y), ...]`` as the kernels take them: float64 ``(k, 2)`` [m]."""
    return np.array(opps, dtype=np.float64).reshape(-1, 2)


@kernel
def roll(deceleration: float, bx: float, by: float, bvx: float, bvy: float, dt: float
         ) -> tuple[float, float]:
    """Where a ball at ``(bx, by)`` [m] moving at ``(bvx, bvy) != 0`` [m/s] is after ``dt``
    seconds: :meth:`~estimators.FrictionBallModel.predict`'s arithmetic, ``p + u (v t - a
    t^2 / 2)`` with ``t = min(dt, v / a)``."""
    speed = math.sqrt(bvx * bvx + bvy * bvy)
    t_stop = speed / deceleration if deceleration > 0.0 else math.inf
    t = min(dt, t_stop)
    travelled = speed * t - 0.5 * deceleration * t * t
    return bx + bvx / speed * travelled, by + bvy / speed * travelled


@kernel
def ball_ahead(p: Pitch, a: Striker, px: float, py: float, bx: float, by: float, bvx: float,
               bvy: float) -> tuple[float, float]:
    """Where the ball will be when the robot at ``(px, py)`` gets there, at most a second
    ahead [m]."""
    reach = min(hypot_exact(bx - px, by - py) / p.max_speed, 1.0)
    if bvx * bvx + bvy * bvy > 1e-4:
        return roll(a.deceleration, bx, by, bvx, bvy, reach)
    return bx, by


@kernel
def clearance(p: Pitch, bx: float, by: float, tx: float, ty: float, opps: np.ndarray
              ) -> float:
    """Smallest gap [m] between the segment from the ball ``(bx, by)`` to ``(tx, ty)`` and an
    opponent of ``opps`` ``(k, 2)``, beyond a robot radius, a ball radius and a margin of 3 %
    of the opponent's distance along the segment (it can move while the ball travels);
    positive means open."""
    ex, ey = tx - bx, ty - by
    length = hypot_exact(ex, ey)
    if length == 0.0:
        length = 1e-9
    ex, ey = ex / length, ey / length
    reach = p.radius + p.ball_radius
    gap = math.inf
    for j in range(opps.shape[0]):
        ox, oy = opps[j, 0], opps[j, 1]
        t = (ox - bx) * ex + (oy - by) * ey
        if t < -reach or t > length + reach:
            continue
        perp = abs((ox - bx) * ey - (oy - by) * ex)
        gap = min(gap, perp - reach - 0.02 - 0.03 * max(t, 0.0))
    return gap


@kernel
def nearest_ahead(bx: float, by: float, opps: np.ndarray) -> float:
    """Distance [m] from the ball to the nearest opponent nearer the opponent goal (``inf``:
    none)."""
    best = math.inf
    for j in range(opps.shape[0]):
        ox, oy = opps[j, 0], opps[j, 1]
        if ox > bx - 0.1:
            best = min(best, hypot_exact(ox - bx, oy - by))
    return best


@kernel
def aim(p: Pitch, a: Striker, px: float, py: float, bx: float, by: float, opps: np.ndarray
        ) -> tuple[float, float, bool]:
    """Where to send the ball: ``(x, y, shoot)`` [m].

    Candidates are points spread across the opponent goal mouth; a candidate is open if no
    opponent stands within a robot radius plus a ball radius (and a margin growing with
    distance) of the line from the ball to it. Among the open ones the attacker takes the one
    needing the least repositioning (its current bearing from the ball). If none is open
    (``shoot`` False), it carries the ball towards the goal centre while the blockers are
    more than a metre away, and otherwise dribbles it 60 degrees off the goal direction, to
    the side with more room.
    """
    goal_x = p.goal_x
    rbx, rby = bx - px, by - py  # robot -> ball, the current approach direction
    norm = hypot_exact(rbx, rby)
    if norm == 0.0:
        norm = 1.0
    rbx, rby = rbx / norm, rby / norm
    found, best_y, best_cost = False, 0.0, math.inf
    for ty in a.aim_ys:
        gap = clearance(p, bx, by, goal_x, ty, opps)
        if gap <= 0.0:
            continue
        ex, ey = goal_x - bx, ty - by
        d = hypot_exact(ex, ey)
        if d == 0.0:
            d = 1.0
        # Turning cost (1 - cos of the angle between approach and shot), minus a bonus for
        # clearance.
        cost = 1.0 - (rbx * ex + rby * ey) / d - 0.5 * min(gap, 0.5)
        if cost < best_cost:
            found, best_y, best_cost = True, ty, cost
    if found:
        return goal_x, best_y, True
    # Blocked. With the blocker far away, carry the ball towards the goal centre (an opening
    # may appear); with it close, dribble diagonally forward on the side with more room,
    # preferring the side the robot already stands behind (so that it does not hesitate
    # between two equal sides); of equal scores the first side (+60 degrees) unless the
    # second's point is greater, as ``max`` of ``(score, (x, y))`` tuples picks.
    if nearest_ahead(bx, by, opps) > 1.0:
        return goal_x, 0.0, False
    gx, gy = goal_x - bx, -by
    d = hypot_exact(gx, gy)
    if d == 0.0:
        d = 1.0
    gx, gy = gx / d, gy / d
    best_score, best_x, best_y = 0.0, 0.0, 0.0
    for sign in (1.0, -1.0):
        cos_a, sin_a = a.escape_cos, sign * a.escape_sin
        ux, uy = gx * cos_a - gy * sin_a, gx * sin_a + gy * cos_a
        tx, ty = bx + ux, by + uy
        room = min(clearance(p, bx, by, tx, ty, opps), 0.3)
        inside = abs(ty) < p.half_width - 0.3
        behind = rbx * ux + rby * uy  # > 0: the robot is behind the ball for u
        score = room + (0.0 if inside else -1.0) + 0.5 * behind
        if sign > 0.0 or score > best_score or (score == best_score and (
                tx > best_x or (tx == best_x and ty > best_y))):
            best_score, best_x, best_y = score, tx, ty
    return best_x, best_y, False


@kernel
def on_target(p: Pitch, px: float, py: float, c: float, s: float, opps: np.ndarray) -> bool:
    """Whether the heading line of a robot at ``(px, py)`` with heading ``(cos, sin) = (c,
    s)`` crosses the opponent goal mouth (a ball radius plus 3 cm inside each post) with no
    opponent on the way."""
    if c < 0.2:
        return False
    y_goal = py + s / c * (p.goal_x - px)
    if abs(y_goal) >= p.half_goal - p.ball_radius - 0.03:
        return False
    return clearance(p, px, py, p.goal_x, y_goal, opps) > 0.0


@kernel
def attacker_act(p: Pitch, a: Striker, px: float, py: float, c: float, s: float, bx: float,
                 by: float, bvx: float, bvy: float, dx: float, opps: np.ndarray, keeper: bool
                 ) -> Action:
    """Go behind the ball on the line from the aim point through the ball, face the aim,
    drive through the ball and shoot when the heading points into the open goal mouth; only
    the ``keeper`` may enter the own defense area. The robot at ``(px, py)`` with heading
    ``(c, s)``; the ball at ``(bx, by)`` [m] moving at ``(bvx, bvy)`` [m/s], ``dx`` ahead of
    the robot in its body frame [m].

    Beside or in front of the ball it steps round it on its near side; behind it its target
    moves from a waiting point ``contact + 0.12`` behind the ball to ``through`` beyond it as
    the alignment ``(max(0, 1 - |lateral| / lateral_scale) max(0, 1 - |heading error| /
    0.5))^2`` grows, at most at ``attack_speed`` once the alignment exceeds 0.25."""
    bx, by = ball_ahead(p, a, px, py, bx, by, bvx, bvy)
    ax, ay, shoot = aim(p, a, px, py, bx, by, opps)
    ex, ey = ax - bx, ay - by
    d_aim = hypot_exact(ex, ey)
    if d_aim == 0.0:
        d_aim = 1.0
    ex, ey = ex / d_aim, ey / d_aim  # ball -> aim point
    nx, ny = -ey, ex
    along = (px - bx) * ex + (py - by) * ey  # < 0: behind the ball
    lateral = (px - bx) * nx + (py - by) * ny
    face = math.atan2(ey, ex)
    heading_err = abs(wrap_angle(face - math.atan2(s, c)))
    contact = p.contact
    cap = math.inf
    if along > -contact and abs(lateral) < contact + p.radius + 0.05:
        # In front of or beside the ball: step round it on the near side first.
        side = 1.0 if lateral >= 0.0 else -1.0
        clear = p.radius + p.ball_radius + 0.12
        tx, ty = bx + side * clear * nx - 0.1 * ex, by + side * clear * ny - 0.1 * ey
    else:
        # Behind the ball: the better lined up (sideways offset and heading), the further
        # forward the target, from a waiting point behind the ball to a point beyond it.
        align = (max(0.0, 1.0 - abs(lateral) / a.lateral_scale)
                 * max(0.0, 1.0 - heading_err / 0.5)) ** a.power
        back = contact + 0.12 - (contact + 0.12 + a.through) * align
        tx, ty = bx - back * ex, by - back * ey
        if align > 0.25:
            cap = a.attack_speed
    if not keeper:
        tx, ty = outside_defense_area(p, tx, ty)
    if a.avoid_opponent_defense:  # touching the ball partly inside it is a foul
        tx, ty = outside_opponent_defense(p, tx, ty, p.radius + 0.03)
    tx, ty = within_walls(p, tx, ty)
    kick = a.kick_power if shoot and dx > 0.0 and on_target(p, px, py, c, s, opps) else 0.0
    return command(p.max_speed, p.max_acceleration, p.max_angular_speed, px, py, c, s, tx, ty,
                   face, cap, kick, -1.0)


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
        inner = geometry.half_goal - geometry.ball.radius - 0.05
        #: The attacker's numbers for the kernels.
        self.striker = Striker(
            self.attack_speed, float(kick_power), bool(avoid_opponent_defense), 0.06, 0.4,
            0.5, math.sqrt(3.0) / 2.0, tuple(float(inner * f) for f in (-1.0, -0.5, 0.0, 0.5,
                                                                        1.0)),
            float(model.deceleration), 2.0)
        #: Aim points across the goal mouth, a ball radius and 5 cm inside the posts [m].
        self.aim_ys = list(self.striker.aim_ys)

    def act(self, f: Frame, opps: Opponents, keeper: bool = False) -> list[float]:
        """:func:`attacker_act` for the robot of ``f``; only the ``keeper`` may enter the
        own defense area."""
        return list(attacker_act(self.geometry.pitch, self.striker, f.px, f.py, f.c, f.s,
                                 f.bx, f.by, f.bvx, f.bvy, f.dx, opponent_array(opps),
                                 keeper))

    def ball_ahead(self, f: Frame) -> tuple[float, float]:
        """:func:`ball_ahead`: where the ball will be when the robot gets there [m]."""
        return ball_ahead(self.geometry.pitch, self.striker, f.px, f.py, f.bx, f.by, f.bvx,
                          f.bvy)

    def aim(self, px: float, py: float, bx: float, by: float, opps: Opponents
            ) -> tuple[tuple[float, float], bool]:
        """:func:`aim`: where to send the ball, ``((x, y), shoot)`` [m]."""
        ax, ay, shoot = aim(self.geometry.pitch, self.striker, px, py, bx, by,
                            opponent_array(opps))
        return (ax, ay), shoot

    def clearance(self, bx: float, by: float, tx: float, ty: float, opps: Opponents
                  ) -> float:
        """:func:`clearance` of the segment from ``(bx, by)`` to ``(tx, ty)`` [m]."""
        return clearance(self.geometry.pitch, bx, by, tx, ty, opponent_array(opps))
