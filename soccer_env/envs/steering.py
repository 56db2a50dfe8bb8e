"""How a scripted robot steers: drive to a target and stop there, turn to a heading.

Compiled kernels on floats, the one rule that the scripted keeper
(:mod:`soccer_env.envs.keeper`) and the scripted teams of :mod:`agents.scripted` call, for one
robot or over rows of robots. Positions are in one frame [m], headings [rad], speeds [m/s],
accelerations [m/s^2]; lengths and wrapped angles carry ``math.hypot``'s and
``math.remainder``'s bits (:func:`~estimators.exact.hypot_exact`,
:func:`~estimators.exact.wrap_angle`), so a kernel gives what the same expressions give in
Python floats.
"""

from __future__ import annotations

import math

from estimators.compiled import kernel
from estimators.exact import hypot_exact, wrap_angle

__all__ = ["TURN_GAIN", "drive_velocity", "turn_rate", "command", "Action"]

#: Proportional gain of :func:`turn_rate` in the SSL robots' :func:`command` [1/s].
TURN_GAIN = 8.0

#: A robot's action: ``(vx, vy, omega, kick, chip, dribble)``.
Action = tuple[float, float, float, float, float, float]


@kernel
def drive_velocity(px: float, py: float, c: float, s: float, tx: float, ty: float,
                   max_speed: float, max_acceleration: float, cap: float
                   ) -> tuple[float, float]:
    """Body-frame velocity ``(vx, vy)`` [m/s] that drives a robot at ``(px, py)`` with heading
    ``(cos, sin) = (c, s)`` to ``(tx, ty)`` [m] and can still stop there.

    The speed follows the braking profile ``v = min(v_cap, sqrt(2 a_max d))`` for the distance
    ``d = |t - p|`` (``v_cap = min(cap, max_speed)``; ``cap = inf``: no cap), the fastest
    approach that can still stop on the spot, along ``(t - p) / d``, rotated into the body
    frame by ``-heading``; ``(0, 0)`` within a micrometre of the target.
    """
    ex, ey = tx - px, ty - py
    dist = hypot_exact(ex, ey)
    if dist <= 1e-6:
        return 0.0, 0.0
    speed = min(min(cap, max_speed), math.sqrt(2.0 * max_acceleration * dist))
    wx, wy = ex / dist * speed, ey / dist * speed
    # Frame -> body frame: rotate by -heading.
    return c * wx + s * wy, -s * wx + c * wy


@kernel
def turn_rate(c: float, s: float, target: float, max_angular_speed: float, gain: float
              ) -> float:
    """Normalised turn rate in ``[-1, 1]`` that turns a robot with heading ``(cos, sin) =
    (c, s)`` towards the heading ``target`` [rad]: ``clip(gain err / omega_max, -1, 1)`` with
    ``err`` the heading error wrapped into ``[-pi, pi]``, ``gain`` [1/s] and ``omega_max =
    max_angular_speed`` [rad/s]."""
    err = wrap_angle(target - math.atan2(s, c))
    return max(-1.0, min(1.0, gain * err / max_angular_speed))


@kernel
def command(max_speed: float, max_acceleration: float, max_angular_speed: float, px: float,
            py: float, c: float, s: float, tx: float, ty: float, face: float, cap: float,
            kick: float, dribble: float) -> Action:
    """The action of an SSL robot at ``(px, py)`` with heading ``(cos, sin) = (c, s)`` that
    drives to ``(tx, ty)`` [m] at most at ``min(cap, max_speed)`` [m/s] (``cap = inf``: no
    cap), turns to the heading ``face`` [rad] and sets the kicker to ``kick`` and the dribbler
    to ``dribble``: :func:`drive_velocity`'s velocity divided by ``max_speed``,
    :func:`turn_rate`'s rate with :data:`TURN_GAIN`, the chip off (``-1``)."""
    vx, vy = drive_velocity(px, py, c, s, tx, ty, max_speed, max_acceleration, cap)
    omega = turn_rate(c, s, face, max_angular_speed, TURN_GAIN)
    return vx / max_speed, vy / max_speed, omega, kick, -1.0, dribble
