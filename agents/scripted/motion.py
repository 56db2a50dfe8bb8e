"""The command of a scripted SSL robot: drive to a target, turn to a heading, switch the kicker
and the dribbler; single and batched side by side.

The action is ``[vx, vy, omega, kick, chip, dribble]``: the body-frame velocity of
:func:`~soccer_env.envs.keeper.drive_command` (the braking profile ``v = min(v_cap,
sqrt(2 a_max d))``) and the turn rate of :func:`~soccer_env.envs.keeper.turn_command`, each
divided by the robot's limit; the kicker power in ``[0, 1]``; the chip off (``-1``); the
dribbler on (``1``) or off (``-1``).
"""

from __future__ import annotations

import numpy as np

from agents.scripted.geometry import Hypot
from agents.scripted.view import Frame
from soccer_env.envs.keeper import drive_command, drive_commands, turn_command, turn_commands
from soccer_env.presets import SSLRobotSpec

__all__ = ["drive_and_turn", "drive_and_turn_rows"]


def drive_and_turn(robot: SSLRobotSpec, f: Frame, tx: float, ty: float, face: float,
                   cap: float | None = None, kick: float = 0.0, dribble: float = -1.0
                   ) -> list[float]:
    """The action that drives the robot of ``f`` to ``(tx, ty)`` [m] (at most ``cap`` [m/s]),
    turns it to the heading ``face`` [rad] and sets the kicker to ``kick`` and the dribbler to
    ``dribble``."""
    vx, vy = drive_command(f.px, f.py, f.c, f.s, tx, ty, robot.max_speed,
                           robot.max_acceleration, cap)
    omega = turn_command(f.c, f.s, face, robot.max_angular_speed)
    return [vx / robot.max_speed, vy / robot.max_speed, omega, kick, -1.0, dribble]


def drive_and_turn_rows(robot: SSLRobotSpec, f: Frame, tx: np.ndarray, ty: np.ndarray,
                        face: np.ndarray, kick: np.ndarray,
                        cap: np.ndarray | float | None = None, hypot: Hypot | None = None
                        ) -> np.ndarray:
    """:func:`drive_and_turn` on arrays, the dribbler off: actions ``(n, 6)`` float64
    (``hypot``: the length function of :func:`~soccer_env.envs.keeper.drive_commands`)."""
    vx, vy = drive_commands(f.px, f.py, f.c, f.s, tx, ty, robot.max_speed,
                            robot.max_acceleration, cap, hypot=hypot)
    out = np.empty((len(f.px), 6))
    out[:, 0], out[:, 1] = vx / robot.max_speed, vy / robot.max_speed
    out[:, 2] = turn_commands(f.c, f.s, face, robot.max_angular_speed)
    out[:, 3] = kick
    out[:, 4:] = -1.0
    return out
