"""The humanoids' bodies in the world, part of :class:`~soccer_env.sim.world.World`.

:class:`HumanoidBodies` holds the methods of the world that connect the walk engine
(:mod:`soccer_env.sim.walk`) to the physics: impacts that may fell a humanoid, a fallen
robot's body lying on the ground and its getting up, the timed kick's foot strike, and what
the humanoids' bodies report (:meth:`head_state`, :meth:`body_state`). They read and write the
world's own state; they live in their own module so that the world's module keeps to the
episodes, the stepping and the reading.
"""

from __future__ import annotations

import math

import numpy as np
import pymunk

from soccer_env.presets import GRAVITY
from soccer_env.sim.arena import HUMANOID
from soccer_env.state import BodyState, HeadState

__all__ = ["HumanoidBodies"]


class HumanoidBodies:
    """The humanoid methods of :class:`~soccer_env.sim.world.World` (see the module
    docstring)."""

    def _humanoid_impact(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        """``begin`` of a humanoid's contact with a robot or a wall: record the approach
        speed along the contact normal (the largest of the step per humanoid)."""
        a, b = arbiter.shapes
        n = arbiter.normal
        va, vb = a.body.velocity, b.body.velocity
        speed = abs((va.x - vb.x) * n.x + (va.y - vb.y) * n.y)
        for shape in (a, b):
            i = self._shape_index.get(shape)
            if i is not None and self.robot_specs[i].kind == "humanoid":
                self._impacts[i] = max(self._impacts.get(i, 0.0), speed)

    def _humanoid_events(self, t0: float) -> None:
        """After the substeps of a step that started at ``t0``: falls from this step's
        impacts, robots standing up (turned), and foot strikes of kicks."""
        walk = self.walk
        now = self.time
        if self._impacts:
            for i, speed in self._impacts.items():
                walk.maybe_fall(walk.indices.index(i), speed, now)
            self._impacts = {}
        # A fallen robot is held by its friction on the ground (force mu m g, torque about
        # the lying body's middle), not by its walk; standing, by the walk's limits again.
        for j, i in enumerate(walk.indices):
            if walk.fallen[j] == (i in self._grounded):
                continue
            spec = self.robot_specs[i]
            drive, turn = self._drives[i]
            if walk.fallen[j]:
                force = spec.surface_friction * spec.mass * GRAVITY
                drive.max_force = force
                turn.max_force = force * max(0.5 * spec.lying_length, spec.radius)
                self._grounded.add(i)
            else:
                drive.max_force = spec.mass * spec.max_acceleration
                turn.max_force = spec.moment_of_inertia * spec.max_angular_acceleration
                self._grounded.discard(i)
        for j, angle in walk.lying_due(now):
            i = walk.indices[j]
            spec = self.robot_specs[i]
            if spec.lying_length > 0.0:
                body = self._bodies[i]
                end = (spec.lying_length * math.cos(angle), spec.lying_length * math.sin(angle))
                shape = pymunk.Segment(body, (0.0, 0.0), end, 0.5 * spec.lying_width)
                shape.elasticity = spec.restitution
                shape.friction = spec.surface_friction
                shape.collision_type = HUMANOID
                self.space.add(shape)
                self._shape_index[shape] = i
                self._lying[i] = shape
        for j, turn in walk.stand_up_due(now):
            i = walk.indices[j]
            body = self._bodies[i]
            shape = self._lying.pop(i, None)
            if shape is not None:
                self.space.remove(shape)
                del self._shape_index[shape]
            body.angle = body.angle + turn
            body.angular_velocity = 0.0
        for j, speed in walk.kick_due(t0, now):
            i = walk.indices[j]
            spec = self.robot_specs[i]
            body = self._bodies[i]
            rx, ry = body.position
            bx, by = self._ball.position
            a = body.angle
            c, s = math.cos(a), math.sin(a)
            u = c * (bx - rx) + s * (by - ry)  # ahead of the robot's centre
            v = c * (by - ry) - s * (bx - rx)  # to its left
            r0 = spec.radius + self.ball_spec.radius
            if (self._z <= spec.height and r0 - 0.02 <= u <= r0 + spec.kick_reach
                    and abs(v) <= 0.5 * spec.kick_width):
                d = a + walk.kick_direction_noise(j)
                self._ball.velocity = (speed * math.cos(d), speed * math.sin(d))
                self._z = self._vz = 0.0
                self._airborne = False
                self._set_sliding(True, speed)
                walk.kicks[j] += 1
                self.kicked[i] = True
                self.touched[i] = True
                self.last_touch = i

    def _stand_all(self) -> None:
        """Take every lying body out of the space and give every grounded humanoid's drives
        their standing limits back: what a world restarting in a shared space must undo (a
        fresh world has neither)."""
        for shape in self._lying.values():
            self.space.remove(shape)
            del self._shape_index[shape]
        self._lying = {}
        for i in self._grounded:
            spec = self.robot_specs[i]
            drive, turn = self._drives[i]
            drive.max_force = spec.mass * spec.max_acceleration
            turn.max_force = spec.moment_of_inertia * spec.max_angular_acceleration
        self._grounded = set()

    def humanoid_state(self) -> dict[str, dict[str, object]]:
        """Per humanoid (by name): ``fallen``, ``kicking``, head ``pan`` and ``tilt`` [rad],
        ``sway`` ``(pan, tilt)`` [rad], ``odometry`` (the last step's ``dx, dy, dtheta`` in
        the body frame), ``falls`` and ``kicks`` since reset. Empty without humanoids."""
        walk = self.walk
        if walk is None:
            return {}
        return {self.names[i]: {
            "fallen": walk.fallen[j], "kicking": walk.kick_start[j] is not None,
            "pan": walk.pan[j], "tilt": walk.tilt[j],
            "sway": (walk.sway_pan[j], walk.sway_tilt[j]),
            "odometry": walk.odometry[j], "falls": walk.falls[j], "kicks": walk.kicks[j],
        } for j, i in enumerate(walk.indices)}

    def head_state(self) -> HeadState:
        """The :class:`~soccer_env.state.HeadState` of every robot (zeros and never blind for
        SSL robots)."""
        n = self.n_robots
        pan, tilt, sp, st = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
        blind = np.zeros(n, dtype=bool)
        walk = self.walk
        if walk is not None:
            idx = walk.indices
            pan[idx], tilt[idx] = walk.pan, walk.tilt
            sp[idx], st[idx] = walk.sway_pan, walk.sway_tilt
            blind[idx] = walk.fallen
        return HeadState(pan, tilt, sp, st, blind)

    def body_state(self) -> BodyState:
        """What every robot's body reports now (:class:`~soccer_env.state.BodyState`)."""
        n = self.n_robots
        still = (0.0, 0.0, 0.0)
        odometry, gait = [still] * n, [still] * n
        fallen: list[bool] = [False] * n
        lying: list[float | None] = [None] * n
        walk = self.walk
        if walk is not None:
            for j, i in enumerate(walk.indices):
                odometry[i] = walk.odometry[j]
                gait[i] = tuple(walk.gait[j])
                fallen[i] = walk.fallen[j]
                if walk.fallen[j] and walk.lie_at[j] is None:
                    lying[i] = walk.lie_angle[j]
        return BodyState(self.head_state(), tuple(odometry), tuple(gait), tuple(fallen),
                         tuple(lying))
