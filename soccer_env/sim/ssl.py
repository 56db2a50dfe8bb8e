"""The SSL robots' kicker and dribbler, part of :class:`~soccer_env.sim.world.World`.

:class:`KickerDribbler` holds the methods of the world that act on the flat front of SSL
robots (see :class:`~soccer_env.presets.SSLRobotSpec`): the contact handler that arms a kick
or damps the ball's bounce, the mouth test (the kicker's light barrier), firing a flat or chip
kick, and the dribbler's hold. They read and write the world's own state; they live in their
own module so that the world's module keeps to the episodes, the stepping and the reading.
"""

from __future__ import annotations

import math

import numpy as np
import pymunk

from soccer_env.presets import SSLRobotSpec

__all__ = ["KickerDribbler", "robot_outline", "MOUTH_TOLERANCE"]

#: A resting ball counts as "in the mouth" of a robot if its surface is within this distance
#: [m] of the flat front (the kicker's light barrier), even without contact.
MOUTH_TOLERANCE = 5e-3


def robot_outline(spec: SSLRobotSpec, n_arc: int = 16) -> list[tuple[float, float]]:
    """Vertices of the robot's footprint in its body frame: a circle cut flat at the front.

    The arc runs counter-clockwise from ``+acos(d / r)`` to ``2 pi - acos(d / r)`` with
    ``n_arc`` segments; the polygon closes along the flat front at ``x = d``.
    """
    a0 = math.acos(spec.front_distance / spec.radius)
    return [
        (spec.radius * math.cos(a), spec.radius * math.sin(a))
        for a in np.linspace(a0, 2.0 * math.pi - a0, n_arc + 1)
    ]


class KickerDribbler:
    """The kicker and dribbler methods of :class:`~soccer_env.sim.world.World` (see the
    module docstring)."""

    def _ball_robot_contact(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        """pre_solve for ball-robot contacts: fly-over, touches, kicker and dribbler."""
        i = self._ball_touch(arbiter)
        if i < 0:
            return
        armed = self._armed[i] > 0.0 and self.time >= self._ready_at[i]
        if (armed or self._dribble[i]) and self._in_mouth(i):
            if armed:
                self._pending_kick = i
            else:
                # A spinning dribbler bar damps the ball's bounce off the front.
                arbiter.restitution = self.robot_specs[i].dribbler_restitution

    def _mouth_holds(self, i: int, rx: float, ry: float, a: float, bx: float, by: float
                     ) -> bool:
        """Whether a ball at ``(bx, by)`` is in the mouth of SSL robot ``i`` at pose
        ``(rx, ry, a)``: its surface within :data:`MOUTH_TOLERANCE` of the flat front (or
        pressed into it) and its centre within half the kicker width of the front's
        middle."""
        c, s = math.cos(a), math.sin(a)
        dx, dy = bx - rx, by - ry
        u = c * dx + s * dy  # along the heading
        v = c * dy - s * dx  # sideways
        return self._mouth_lo[i] <= u <= self._mouth_hi[i] and abs(v) <= self._mouth_half[i]

    def _in_mouth(self, i: int) -> bool:
        """:meth:`_mouth_holds` for robot ``i`` and the ball, from the live bodies."""
        body = self._bodies[i]
        rx, ry = body.position
        bx, by = self._ball.position
        return self._mouth_holds(i, rx, ry, body.angle, bx, by)

    def _kick_resting_ball(self) -> None:
        """Fire an armed kicker whose mouth already holds the ball (no new contact needed).

        Uses the state read at the end of the previous step.
        """
        rows = self._state.tolist()
        bx, by = rows[0][0:2]
        for i, ((rx, ry, a, *_), speed) in enumerate(zip(rows[1:], self._armed)):
            if speed <= 0.0 or self._z > self._heights[i]:
                continue
            reach2 = (self.robot_specs[i].radius + self.ball_spec.radius + MOUTH_TOLERANCE) ** 2
            if ((bx - rx) ** 2 + (by - ry) ** 2 < reach2
                    and self.time >= self._ready_at[i]
                    and self._mouth_holds(i, rx, ry, a, bx, by)):
                self._fire(i)
                return

    def _fire(self, i: int) -> None:
        rs = self.robot_specs[i]
        speed = self._armed[i]
        a = self._bodies[i].angle
        c, s = math.cos(a), math.sin(a)
        ball = self._ball
        if self._chip[i]:
            horizontal = speed * math.cos(rs.chip_angle)
            ball.velocity = (horizontal * c, horizontal * s)
            self._z = 0.0
            self._vz = speed * math.sin(rs.chip_angle)
            self._airborne = True
            self._hops = 0
            self._sliding = False
            self._friction.max_force = 0.0
        else:
            # A flat kick drives the ball along the carpet (a low bouncing ball included).
            ball.velocity = (speed * c, speed * s)
            self._z = self._vz = 0.0
            self._airborne = False
            self._set_sliding(True, speed)
        self._armed[i] = 0.0
        self._ready_at[i] = self.time + rs.kick_cooldown
        self.kicked[i] = True
        self.touched[i] = True
        self.last_touch = i

    def _dribble_candidates(self) -> list[int]:
        """Robots with the dribbler on whose mouth is near enough to the ball to reach it
        within this step (checked from the last state, so only these are checked per
        substep)."""
        bx, by, _, bvx, bvy, _ = self._state[0].tolist()
        out = []
        robots = self._state[1:, 0:3].tolist()
        for i, ((rx, ry, a), on) in enumerate(zip(robots, self._dribble)):
            if not on:
                continue
            rs = self.robot_specs[i]
            reach = rs.front_distance + self.ball_spec.radius
            near = 0.05 + (math.hypot(bvx, bvy) + 2.0 * rs.max_speed) * self.control_dt
            if (bx - rx) ** 2 + (by - ry) ** 2 > (near + reach) ** 2:
                continue
            mouth_x, mouth_y = rx + reach * math.cos(a), ry + reach * math.sin(a)
            if math.hypot(bx - mouth_x, by - mouth_y) < near:
                out.append(i)
        return out

    def _apply_dribbler(self, i: int) -> None:
        """Hold the ball against robot ``i``'s front for the next substep (see SSLRobotSpec).

        Acts while the ball is in the mouth (touching the flat front within the kicker width,
        or within the light barrier's tolerance of it) and on the carpet below the robot's
        height.
        """
        if self._z > self._heights[i] or not self._in_mouth(i):
            return
        body, ball = self._bodies[i], self._ball
        rx, ry = body.position
        bx, by = ball.position
        a = body.angle
        c, s = math.cos(a), math.sin(a)
        dx, dy = bx - rx, by - ry
        rvx, rvy = body.velocity
        w = body.angular_velocity
        bvx, bvy = ball.velocity
        # Sideways slip of the ball relative to the robot's surface point under it.
        slip = -s * (bvx - (rvx - w * dy)) + c * (bvy - (rvy + w * dx))
        force = self.robot_specs[i].dribbler_force
        lateral = max(-force, min(force, -self.ball_spec.mass * slip / self.substep_dt))
        fx = -force * c - lateral * s
        fy = -force * s + lateral * c
        ball.force = (fx, fy)
        body.force = (-fx, -fy)
        self.touched[i] = True
        self.last_touch = i
