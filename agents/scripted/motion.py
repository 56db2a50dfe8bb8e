"""The command of a scripted SSL robot: drive to a target, turn to a heading, switch the kicker
and the dribbler.

The action is ``[vx, vy, omega, kick, chip, dribble]``: the body-frame velocity of
:func:`~soccer_env.envs.keeper.drive_command` (the braking profile ``v = min(v_cap,
sqrt(2 a_max d))``) and the turn rate of :func:`~soccer_env.envs.keeper.turn_command`, each
divided by the robot's limit; the kicker power in ``[0, 1]``; the chip off (``-1``); the
dribbler on (``1``) or off (``-1``). :func:`command` is the rule, a compiled kernel;
:func:`drive_and_turn` calls it for one robot from Python.
"""

from __future__ import annotations

import math

from agents.scripted.view import Frame
from estimators.compiled import kernel
from estimators.exact import hypot_exact, wrap_angle
from soccer_env.envs.keeper import TURN_GAIN
from soccer_env.presets import SSLRobotSpec

__all__ = ["command", "drive_and_turn", "Action"]

#: A robot's action: ``(vx, vy, omega, kick, chip, dribble)``.
Action = tuple[float, float, float, float, float, float]


@kernel
def command(max_speed: float, max_acceleration: float, max_angular_speed: float, px: float,
            py: float, c: float, s: float, tx: float, ty: float, face: float, cap: float,
            kick: float, dribble: float) -> Action:
    """The action that drives a robot at ``(px, py)`` with heading ``(cos, sin) = (c, s)`` to
    ``(tx, ty)`` [m] at most at ``min(cap, max_speed)`` [m/s] (``cap = inf``: no cap), turns
    it to the heading ``face`` [rad] and sets the kicker to ``kick`` and the dribbler to
    ``dribble``.

    The velocity is :func:`~soccer_env.envs.keeper.drive_command`'s, ``v = min(v_cap,
    sqrt(2 a_max d))`` towards the target rotated into the body frame, the turn rate
    :func:`~soccer_env.envs.keeper.turn_command`'s, ``clip(TURN_GAIN err / omega_max, -1,
    1)`` with ``err`` the heading error wrapped into ``[-pi, pi]``: the same arithmetic,
    ``math.hypot``'s and ``math.remainder``'s bits (:func:`~estimators.exact.hypot_exact`,
    :func:`~estimators.exact.wrap_angle`).
    """
    ex, ey = tx - px, ty - py
    dist = hypot_exact(ex, ey)
    vx, vy = 0.0, 0.0
    if dist > 1e-6:
        speed = min(min(cap, max_speed), math.sqrt(2.0 * max_acceleration * dist))
        wx, wy = ex / dist * speed, ey / dist * speed
        # Frame -> body frame: rotate by -heading.
        vx, vy = c * wx + s * wy, -s * wx + c * wy
    err = wrap_angle(face - math.atan2(s, c))
    omega = max(-1.0, min(1.0, TURN_GAIN * err / max_angular_speed))
    return vx / max_speed, vy / max_speed, omega, kick, -1.0, dribble


def drive_and_turn(robot: SSLRobotSpec, f: Frame, tx: float, ty: float, face: float,
                   cap: float | None = None, kick: float = 0.0, dribble: float = -1.0
                   ) -> list[float]:
    """:func:`command` for the robot of ``f``: to ``(tx, ty)`` [m] at most at ``cap`` [m/s]
    (None: no cap), facing ``face`` [rad], the kicker at ``kick``, the dribbler at
    ``dribble``."""
    return list(command(float(robot.max_speed), float(robot.max_acceleration),
                        float(robot.max_angular_speed), f.px, f.py, f.c, f.s, tx, ty, face,
                        math.inf if cap is None else cap, kick, dribble))
