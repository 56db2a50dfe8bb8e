"""The command of a scripted SSL robot: drive to a target, turn to a heading, switch the kicker
and the dribbler.

The action is ``[vx, vy, omega, kick, chip, dribble]``: the body-frame velocity of the braking
profile ``v = min(v_cap, sqrt(2 a_max d))`` and the turn rate towards a heading, each divided
by the robot's limit; the kicker power in ``[0, 1]``; the chip off (``-1``); the dribbler on
(``1``) or off (``-1``). :func:`command` is the rule, the compiled kernel of
:mod:`soccer_env.envs.steering` that the scripted keeper plays too (re-exported here);
:func:`drive_and_turn` calls it for one robot from Python.
"""

from __future__ import annotations

import math

from agents.scripted.view import Frame
from soccer_env.envs.steering import Action, command
from soccer_env.presets import SSLRobotSpec

__all__ = ["command", "drive_and_turn", "Action"]


def drive_and_turn(robot: SSLRobotSpec, f: Frame, tx: float, ty: float, face: float,
                   cap: float | None = None, kick: float = 0.0, dribble: float = -1.0
                   ) -> list[float]:
    """:func:`command` for the robot of ``f``: to ``(tx, ty)`` [m] at most at ``cap`` [m/s]
    (None: no cap), facing ``face`` [rad], the kicker at ``kick``, the dribbler at
    ``dribble``."""
    return list(command(float(robot.max_speed), float(robot.max_acceleration),
                        float(robot.max_angular_speed), f.px, f.py, f.c, f.s, tx, ty, face,
                        math.inf if cap is None else cap, kick, dribble))
