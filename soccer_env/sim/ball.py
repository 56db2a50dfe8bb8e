"""The ball in the world, part of :class:`~soccer_env.sim.world.World`.

:class:`BallPhysics` holds the methods of the world that the ball's own physics needs beyond
pymunk's plane: the carpet friction's two phases (sliding after a kick, then rolling; the
friction joint's maximum force), the flight of a chipped ball with its bounces, and the
records its contacts leave (which robots touched it, the first moment it lay wholly beyond a
line: :class:`BallExit`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pymunk

from soccer_env.presets import GRAVITY

__all__ = ["BallPhysics", "BallExit"]


@dataclass(frozen=True)
class BallExit:
    """First moment since :meth:`~soccer_env.sim.world.World.clear_exit` at which the whole
    ball was past a line.

    ``x, y`` [m] is the ball centre, ``z`` [m] its height and ``time`` [s] the instant, at the
    physics substep where the ball's centre first lay more than one radius beyond a goal line
    or a touch line.
    """

    x: float
    y: float
    z: float
    time: float


class BallPhysics:
    """The ball methods of :class:`~soccer_env.sim.world.World` (see the module docstring).
    """

    # ------------------------------------------------------------------------------------
    # Friction and flight
    # ------------------------------------------------------------------------------------

    def _set_sliding(self, sliding: bool, speed: float) -> None:
        self._sliding = bool(sliding) and speed > 0.0
        if self._sliding:
            self._v_switch = self.ball_spec.k_switch * speed
            self._friction.max_force = self._slide_force
        else:
            self._friction.max_force = self._roll_force

    def _fly(self, h: float) -> None:
        """Ballistic height update over one substep, with fixed-loss bounces."""
        z = self._z + self._vz * h - 0.5 * GRAVITY * h * h
        vz = self._vz - GRAVITY * h
        if z > 0.0:
            self._z, self._vz = z, vz
            return
        # Touchdown inside this substep: bounce with the vertical speed at impact.
        bs = self.ball_spec
        impact = math.sqrt(self._vz * self._vz + 2.0 * GRAVITY * self._z)
        damp = bs.chip_damping_xy_first if self._hops == 0 else bs.chip_damping_xy_other
        self._hops += 1
        vx, vy = self._ball.velocity
        self._ball.velocity = (vx * damp, vy * damp)
        vz = impact * bs.chip_damping_z
        if vz * vz / (2.0 * GRAVITY) < bs.min_hop_height:
            self._z = self._vz = 0.0
            self._airborne = False
            self._set_sliding(False, 0.0)
        else:
            self._z, self._vz = 0.0, vz

    # ------------------------------------------------------------------------------------
    # Contacts
    # ------------------------------------------------------------------------------------

    def _ball_touch(self, arbiter: pymunk.Arbiter, space: pymunk.Space = None, data=None
                    ) -> int:
        """pre_solve for ball-humanoid contacts (and the first part of the SSL robots'): a
        ball in flight above the robot passes over it; otherwise record the touch. Returns
        the robot's index, or -1 when the ball passes over."""
        i = self._shape_index[arbiter.shapes[1]]
        if self._z > self._heights[i]:
            arbiter.process_collision = False
            return -1
        self.touched[i] = True
        self.last_touch = i
        return i

    def _ball_out(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        """``begin`` of the ball with a sensor beyond a line: record the first exit."""
        if self.ball_exit is None:
            x, y = self._ball.position
            x, y = x - self.origin[0], y - self.origin[1]
            # The callback runs inside the substep, before ``time`` is advanced past it.
            self.ball_exit = BallExit(x, y, self._z, self.time + self.substep_dt)

    # ------------------------------------------------------------------------------------
    # Reading
    # ------------------------------------------------------------------------------------

    @property
    def ball_height(self) -> float:
        """Height of the ball's lowest point above the carpet [m]."""
        return self._z

    @property
    def ball_airborne(self) -> bool:
        """Whether the ball is in flight after a chip."""
        return self._airborne

    @property
    def ball_sliding(self) -> bool:
        """Whether the ball is in its sliding phase."""
        return self._sliding

    def ball_array(self) -> np.ndarray:
        """``(6,)`` copy of the ball's ``x, y, z, vx, vy, vz``."""
        b = self._state[0].copy()
        b[2] = self._z
        b[5] = self._vz
        return b
