"""Immutable snapshots of the true world state."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["WorldState", "state_dict", "BALL_FIELDS", "ROBOT_FIELDS"]

#: Columns of :attr:`WorldState.ball`.
BALL_FIELDS = ("x", "y", "z", "vx", "vy", "vz")
#: Columns of :attr:`WorldState.robots`.
ROBOT_FIELDS = ("x", "y", "theta", "vx", "vy", "omega")


class WorldState(NamedTuple):
    """The truth at one instant, in the field frame.

    Attributes:
        time: simulated time since the world was reset [s].
        ball: ``(6,)`` ball ``x, y`` [m], height ``z`` of its lowest point above the carpet
            [m], velocity ``vx, vy, vz`` [m/s].
        robots: ``(N, 6)`` robot poses ``x, y, theta`` [m, rad] and velocities
            ``vx, vy, omega`` [m/s, rad/s], field frame, one row per robot in ``names`` order.
        names: robot names (``blue_0``, ..., ``yellow_0``, ...).
        teams: ``(N,)`` 0 for blue, 1 for yellow.

    The arrays are read-only copies; holding a snapshot is safe while the world steps on.
    (A ``NamedTuple``: immutable, and several times cheaper to create than a frozen dataclass,
    which matters since every step makes one.)
    """

    time: float
    ball: np.ndarray
    robots: np.ndarray
    names: tuple[str, ...]
    teams: np.ndarray

    def truth_dict(self) -> dict[str, object]:
        """The ``info["truth"]`` entry: ball and every robot in field coordinates.

        Keys: ``time`` [s]; ``ball_position`` (x, y) [m]; ``ball_velocity`` (vx, vy) [m/s];
        ``ball_height`` [m]; ``robot_pose`` {name: (x, y, theta)}; ``robot_velocity``
        {name: (vx, vy, omega)}. ``info["estimate"]`` has the same keys.
        """
        return state_dict(self.time, self.ball, self.robots, self.names)


def state_dict(time: float, ball: np.ndarray, robots: np.ndarray, names: tuple[str, ...]
               ) -> dict[str, object]:
    """Ball and robot arrays (layouts :data:`BALL_FIELDS`, :data:`ROBOT_FIELDS`) as the dict of
    ``info["truth"]`` / ``info["estimate"]`` (values are views of the arrays)."""
    return {
        "time": time,
        "ball_position": ball[0:2],
        "ball_velocity": ball[3:5],
        "ball_height": float(ball[2]),
        "robot_pose": {n: robots[i, 0:3] for i, n in enumerate(names)},
        "robot_velocity": {n: robots[i, 3:6] for i, n in enumerate(names)},
    }
