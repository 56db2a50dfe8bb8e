"""Placing the robots and the ball, part of :class:`~soccer_env.sim.world.World`.

:class:`Placement` holds the methods of the world that teleport its robots and its ball (at
the start of an episode, for the referee, in tests) after checking that the poses are finite
and inside the walls, and that forget a recorded ball exit.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["Placement"]


class Placement:
    """The placing methods of :class:`~soccer_env.sim.world.World` (see the module
    docstring)."""

    def _validated_poses(self, robot_poses: np.ndarray) -> np.ndarray:
        poses = np.asarray(robot_poses, dtype=np.float64)
        if poses.shape != (self.n_robots, 3):
            raise ValueError(f"robot_poses must have shape ({self.n_robots}, 3), got {poses.shape}")
        for i, (x, y, th) in enumerate(poses):
            self._check_inside(f"robot {self.names[i]}", x, y, self.robot_specs[i].radius)
            if not math.isfinite(th):
                raise ValueError(f"robot {self.names[i]} heading must be finite, got {th!r}")
        return poses

    def _check_inside(self, what: str, x: float, y: float, margin: float) -> None:
        lx, ly = self._walls_x - margin, self._walls_y - margin
        if not (math.isfinite(x) and math.isfinite(y) and abs(x) <= lx and abs(y) <= ly):
            raise ValueError(
                f"{what} position must be finite and inside the walls, |x| <= {lx:.3f} and "
                f"|y| <= {ly:.3f} m, got ({x!r}, {y!r})"
            )

    def _require_space(self) -> None:
        if self.space is None:
            raise RuntimeError("call World.reset() before placing or stepping")

    def set_robot(self, i: int, x: float, y: float, theta: float,
                  vx: float = 0.0, vy: float = 0.0, omega: float = 0.0) -> None:
        """Teleport robot ``i`` to pose ``(x, y, theta)`` with velocity ``(vx, vy, omega)``."""
        self._require_space()
        self._check_inside(f"robot {self.names[i]}", x, y, self.robot_specs[i].radius)
        vals = (theta, vx, vy, omega)
        if not all(math.isfinite(v) for v in vals):
            raise ValueError(f"robot {self.names[i]} state must be finite, got {vals}")
        body = self._bodies[i]
        ox, oy = self.origin
        body.position = (float(x) + ox, float(y) + oy)
        body.angle = float(theta)
        body.velocity = (float(vx), float(vy))
        body.angular_velocity = float(omega)
        self._controls[i].velocity = (float(vx), float(vy))
        self._controls[i].angular_velocity = float(omega)
        self._state[1 + i] = (x, y, math.remainder(theta, 2.0 * math.pi), vx, vy, omega)
        self.space.reindex_shapes_for_body(body)

    def set_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0,
                 z: float = 0.0, vz: float = 0.0, sliding: bool = False) -> None:
        """Teleport the ball.

        Args:
            x, y: position [m].
            vx, vy: horizontal velocity [m/s].
            z: height of the ball's lowest point [m] (0 on the carpet).
            vz: vertical velocity [m/s]; with ``z > 0`` or ``vz > 0`` the ball is in flight.
            sliding: start in the sliding phase (as right after a kick), switching to rolling
                at ``k_switch`` times the current speed.
        """
        self._require_space()
        self._check_inside("ball", x, y, self.ball_spec.radius)
        if not all(math.isfinite(v) for v in (vx, vy, z, vz)) or z < 0.0:
            raise ValueError(f"ball velocity and height must be finite with z >= 0, got "
                             f"{(vx, vy, z, vz)}")
        ball = self._ball
        ox, oy = self.origin
        ball.position = (float(x) + ox, float(y) + oy)
        ball.velocity = (float(vx), float(vy))
        self.space.reindex_shapes_for_body(ball)
        self._z, self._vz, self._hops = float(z), float(vz), 0
        self._airborne = z > 0.0 or vz > 0.0
        if self._airborne:
            self._sliding = False
            self._friction.max_force = 0.0
        else:
            self._z = self._vz = 0.0
            self._set_sliding(sliding, math.hypot(vx, vy))
        self._state[0] = (x, y, 0.0, vx, vy, 0.0)

    def place_all(self, robot_poses: np.ndarray, ball_position: tuple[float, float] = (0.0, 0.0)
                  ) -> None:
        """Teleport every robot (at rest) and the ball (at rest) without resetting the clock."""
        poses = self._validated_poses(robot_poses)
        self._check_inside("ball", *ball_position, self.ball_spec.radius)
        for i in range(self.n_robots):
            self.set_robot(i, *poses[i])
        self.set_ball(*ball_position)

    def clear_exit(self) -> None:
        """Forget the recorded :attr:`ball_exit` (after the referee has handled it)."""
        self.ball_exit = None
