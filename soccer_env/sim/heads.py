"""Head control of humanoids: where their pan/tilt heads look.

A robot's head controller (:class:`HeadController`) turns what the robot believes, an
:class:`~soccer_env.state.Attention` from its perception (its pose, the ball, how old its
sightings are), into the targets of its head servos; :class:`HeadControl` does so for the
humanoids of a world whose heads are not the policy's to move and writes the targets into
their commands. :func:`aim_heads` turns every head to the ball at the start of an episode.
The heads' state for the cameras is :meth:`World.head_state
<soccer_env.sim.world.World.head_state>`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from soccer_env.presets import HumanoidRobotSpec
from soccer_env.presets.sensors import head_camera
from soccer_env.sim.commands import HumanoidRobot
from soccer_env.state import Attention

__all__ = ["HeadController", "HeadControl", "HEAD_MODES", "aim_heads", "look_at"]

#: Who aims a humanoid's head: the :class:`HeadController` (``"auto"``: at the believed ball,
#: scanning when it is lost or the localization needs landmarks), a fixed scan, or the
#: policy's action entries 4 and 5.
HEAD_MODES = ("auto", "scan", "action")


def look_at(spec: HumanoidRobotSpec, camera_height: float, pose: Sequence[float],
            x: float, y: float) -> tuple[float, float]:
    """Pan and tilt [rad] that centre the ground point ``(x, y)`` in the image of a robot at
    ``pose`` ``(x, y, theta)``: pan its bearing, tilt ``atan(h / d)``, both within the head's
    limits."""
    dx, dy = x - pose[0], y - pose[1]
    c, s = math.cos(pose[2]), math.sin(pose[2])
    pan = math.atan2(c * dy - s * dx, c * dx + s * dy)
    tilt = math.atan2(camera_height, max(math.hypot(dx, dy), 0.05))
    return (max(-spec.head_pan_limit, min(spec.head_pan_limit, pan)),
            max(spec.head_tilt_min, min(spec.head_tilt_max, tilt)))


def aim_heads(world: Any) -> None:
    """Turn every humanoid's head to the ball at the start of an episode (set-up, like placing
    the robots: play was going on before the episode and the robots were watching the ball;
    whether they see it is still up to their cameras)."""
    walk = world.walk
    if walk is None:
        return
    bx, by = world.ball_array()[0:2].tolist()
    robots = world.robot_array()
    for j, i in enumerate(walk.indices):
        spec = walk.specs[j]
        walk.pan[j], walk.tilt[j] = look_at(spec, head_camera(spec.camera).height,
                                            robots[i, 0:3].tolist(), bx, by)


class HeadController:
    """Aims a humanoid's head (pan and tilt targets [rad]).

    ``mode="scan"``: pan sweeps ``+-scan_pan`` sinusoidally with period ``scan_period`` [s]
    at a tilt that sees from about 0.4 m to 4 m. ``mode="auto"``: looks at the believed ball
    (centred in the image: pan its bearing, tilt ``atan(h / d)``) while the robot's own
    sighting of it is under ``ball_lost_after`` seconds old, or a team-mate's is; otherwise
    scans; and, when no landmark has been seen for ``landmark_period`` seconds and the ball
    is not coming at the robot, scans for ``glance`` seconds to find some (a ball starting to
    come at it ends the glance).
    """

    def __init__(self, spec: HumanoidRobotSpec, camera_height: float, mode: str = "auto",
                 scan_pan: float = math.radians(90.0), scan_period: float = 4.0,
                 ball_lost_after: float = 1.0, landmark_period: float = 3.0,
                 glance: float = 1.5) -> None:
        if mode not in ("auto", "scan"):
            raise ValueError(f"head mode must be 'auto' or 'scan', got {mode!r}")
        self.spec, self.h, self.mode = spec, camera_height, mode
        self.scan_pan = min(scan_pan, spec.head_pan_limit)
        self.scan_period = scan_period
        self.scan_tilt = min(max(math.radians(30.0), spec.head_tilt_min), spec.head_tilt_max)
        self.ball_lost_after = ball_lost_after
        self.landmark_period = landmark_period
        self.glance = glance
        self._glance_until = -math.inf

    def reset(self) -> None:
        self._glance_until = -math.inf

    def scan(self, now: float) -> tuple[float, float]:
        """The scan pattern at time ``now``."""
        return (self.scan_pan * math.sin(2.0 * math.pi * now / self.scan_period),
                self.scan_tilt)

    def targets(self, now: float, pose: np.ndarray, ball: np.ndarray | None,
                ball_age: float, landmark_age: float) -> tuple[float, float]:
        """Pan and tilt targets at ``now`` for a robot believing itself at ``pose`` (x, y,
        theta) and the ball at ``ball`` (x, y, vx, vy, or None), last seen ``ball_age``
        seconds ago, a landmark ``landmark_age`` seconds ago."""
        if self.mode == "scan" or ball is None:
            return self.scan(now)
        dx, dy = ball[0] - pose[0], ball[1] - pose[1]
        dist = math.hypot(dx, dy)
        coming = dist > 1e-6 and -(dx * ball[2] + dy * ball[3]) / dist > 0.3
        if coming:
            self._glance_until = -math.inf  # a ball coming at the robot ends a glance
        elif now < self._glance_until:
            return self.scan(now)
        elif landmark_age > self.landmark_period:
            self._glance_until = now + self.glance
            return self.scan(now)
        if ball_age > self.ball_lost_after:
            return self.scan(now)
        return look_at(self.spec, self.h, pose, ball[0], ball[1])


class HeadControl:
    """The head controllers of the humanoids ``robots`` of a world (robot indices), each
    aiming its robot's head from the robot's own :class:`~soccer_env.state.Attention`.

    Args:
        specs: every robot's model, in world order.
        robots: the humanoids whose heads this controls (not those the policy aims).
        camera_heights: the height [m] of each controlled robot's camera (the tilt that
            centres a ground point depends on it), in the order of ``robots``.
        mode: ``"auto"`` or ``"scan"`` (see :class:`HeadController`).
    """

    def __init__(self, specs: Sequence[Any], robots: Sequence[int],
                 camera_heights: Sequence[float], mode: str = "auto") -> None:
        if mode not in HEAD_MODES:
            raise ValueError(f"head must be one of {list(HEAD_MODES)}, got {mode!r}")
        self.robots = [int(i) for i in robots]
        self.controllers = {i: HeadController(specs[i], h, "scan" if mode == "scan" else "auto")
                            for i, h in zip(self.robots, camera_heights)}
        self._models = {i: HumanoidRobot(specs[i]) for i in self.robots}

    def reset(self) -> None:
        """Start an episode (no glance under way)."""
        for c in self.controllers.values():
            c.reset()

    def apply(self, commands: np.ndarray, now: float,
              attention: Callable[[int, float], Attention]) -> None:
        """Write the head targets at ``now`` of every controlled robot into its row of the
        world's ``commands`` (columns ``head_pan``, ``head_tilt``; in place), from
        ``attention(i, now)``, what robot ``i`` believes.

        The targets take the same normalised route as a policy's head action entries
        (:meth:`~soccer_env.sim.commands.HumanoidRobot.action_for_head`), so both command
        exactly the same angles."""
        for i in self.robots:
            a = attention(i, now)
            target = self.controllers[i].targets(now, a.pose, a.ball, a.ball_age, a.landmark_age)
            commands[i, 4:6] = self._models[i].head_command(*target)
