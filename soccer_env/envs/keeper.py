"""A scripted goalkeeper that intercepts the ball's predicted path in front of its goal."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from estimators import FrictionBallModel
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec

__all__ = ["ScriptedGoalkeeper", "drive_command", "turn_command", "TURN_GAIN"]

#: Proportional gain of :func:`turn_command` [1/s].
TURN_GAIN = 8.0


def drive_command(px: float, py: float, c: float, s: float, tx: float, ty: float,
                  max_speed: float, max_acceleration: float, speed_cap: float | None = None
                  ) -> tuple[float, float]:
    """Body-frame velocity [m/s] that drives a robot at ``(px, py)`` with heading
    ``(cos, sin) = (c, s)`` to ``(tx, ty)`` (all in one frame, metres) and can still stop there.

    The speed follows the braking profile ``v = min(v_cap, sqrt(2 a_max d))`` for distance ``d``
    (``v_cap`` is ``speed_cap`` or ``max_speed``): the fastest approach that can still stop on
    the spot.
    """
    ex, ey = tx - px, ty - py
    dist = math.hypot(ex, ey)
    if dist <= 1e-6:
        return 0.0, 0.0
    cap = max_speed if speed_cap is None else min(speed_cap, max_speed)
    speed = min(cap, math.sqrt(2.0 * max_acceleration * dist))
    wx, wy = ex / dist * speed, ey / dist * speed
    # Frame -> body frame: rotate by -heading.
    return c * wx + s * wy, -s * wx + c * wy


def turn_command(c: float, s: float, target: float, max_angular_speed: float,
                 gain: float = TURN_GAIN) -> float:
    """Normalised turn rate in ``[-1, 1]`` that turns a robot with heading
    ``(cos, sin) = (c, s)`` towards the heading ``target`` [rad]: proportional to the wrapped
    error with ``gain`` [1/s]."""
    err = math.remainder(target - math.atan2(s, c), 2.0 * math.pi)
    return max(-1.0, min(1.0, gain * err / max_angular_speed))


class ScriptedGoalkeeper:
    """Keeps to a guard line in front of its goal and moves to where the ball will cross it.

    The policy reads only its observation vector (the layout of
    :mod:`soccer_env.observations`, found by entry name), so it runs on whatever the
    observation mode provides. Each step it:

    1. recovers the ball's position and velocity in its team frame from the egocentric
       entries;
    2. if the ball moves towards the goal, predicts with :class:`~estimators.FrictionBallModel`
       (closed-form constant deceleration) where it crosses the guard line
       ``x = -L/2 + r + guard_offset`` and goes there; otherwise it stands on the guard line
       where the line from the ball to the goal centre crosses it;
    3. drives there with the fastest profile its acceleration allows to stop on the spot
       (``v = min(v_max, sqrt(2 a_max d))``), turning to face the ball;
    4. kicks the ball away when it sits in front of its kicker.

    A humanoid keeper walks instead (sideways at most, facing the field, each axis scaled by
    its own speed limit) and, since walking is too slow for most shots, dives: when the ball
    will cross its line within ``dive_lead`` seconds plus the time its body takes to hit the
    ground, out of reach of its standing body but within its lying length, it throws itself
    to that side. It kicks a ball resting at its feet away.

    Args:
        field, ball, robot: the specs of the environment (goal geometry, the ball's rolling
            deceleration, speed limits).
        names: the observation's entry names (``env.unwrapped.builder.names``).
        guard_offset: distance of the guard line in front of the goal line, beyond the robot's
            radius [m].
    """

    def __init__(self, field: FieldSpec, ball: BallSpec, robot: RobotSpec,
                 names: Sequence[str], guard_offset: float = 0.05,
                 dive_lead: float = 0.15) -> None:
        self.field, self.ball, self.robot = field, ball, robot
        self.humanoid = robot.kind == "humanoid"
        self.dive_lead = dive_lead
        self.model = FrictionBallModel(ball.rolling_deceleration)
        index = {n: i for i, n in enumerate(names)}
        self._idx = [index[n] for n in ("self.x", "self.y", "self.ax", "self.ay", "ball.dx",
                                        "ball.dy", "ball.vx", "ball.vy")]
        self.guard_x = -field.half_length + robot.radius + guard_offset

    @classmethod
    def for_env(cls, env, **kwargs) -> ScriptedGoalkeeper:
        """Build the policy for a (possibly wrapped) Goalkeeper environment."""
        u = env.unwrapped
        return cls(u.field, u.ball_spec, u.robot_spec, u.builder.names, **kwargs)

    def _read(self, obs: np.ndarray) -> tuple[float, ...]:
        """Own position, heading ``(cos, sin)``, the ball's position and velocity and its
        egocentric offset, in the team frame, from the observation."""
        px, py, ax, ay, dx, dy, bvx, bvy = (float(obs[i]) for i in self._idx)
        c, s = ax, -ay  # cos and sin of the heading in the team frame
        bx, by = px + c * dx - s * dy, py + s * dx + c * dy
        vx, vy = c * bvx - s * bvy, s * bvx + c * bvy
        return px, py, c, s, bx, by, vx, vy, dx, dy

    def guard_y(self, obs: np.ndarray) -> float:
        """Where on the guard line the keeper goes [m, team frame] (step 2 of the class
        docstring): the predicted crossing of a ball moving towards the goal, else the
        crossing of the line from the ball to the goal centre; within the goal mouth."""
        _, _, _, _, bx, by, vx, vy, _, _ = self._read(obs)
        return self._guard_y(bx, by, vx, vy)

    def _guard_y(self, bx: float, by: float, vx: float, vy: float) -> float:
        f = self.field
        half_goal = 0.5 * f.goal_width + self.ball.radius
        goal_x = -f.half_length
        ty = None
        if vx < -0.05:
            t = float(self.model.time_to_line(np.array([bx, by, vx, vy]), self.guard_x))
            if math.isfinite(t):
                ty = float(self.model.predict(np.array([bx, by, vx, vy]), t)[1])
        if ty is None:
            frac = (self.guard_x - goal_x) / max(bx - goal_x, 1e-3)
            ty = by * min(frac, 1.0)
        return max(-half_goal, min(half_goal, ty))

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        r = self.robot
        px, py, c, s, bx, by, vx, vy, dx, dy = self._read(obs)
        ty = self._guard_y(bx, by, vx, vy)

        if self.humanoid:
            return self._humanoid(px, py, c, s, bx, by, vx, vy, dx, dy, ty)
        # Drive to (guard_x, ty) with a profile that can still stop there, facing the ball.
        cmd_x, cmd_y = drive_command(px, py, c, s, self.guard_x, ty, r.max_speed,
                                     r.max_acceleration)
        face = math.atan2(by - py, bx - px)
        face = max(-0.5 * math.pi, min(0.5 * math.pi, face))
        omega = turn_command(c, s, face, r.max_angular_speed)

        in_front = 0.0 < dx < r.front_distance + 0.1 and abs(dy) < 0.5 * r.kicker_width
        kick = 1.0 if in_front else 0.0
        return np.array([cmd_x / r.max_speed, cmd_y / r.max_speed, omega, kick, -1.0, -1.0],
                        dtype=np.float32)

    def _humanoid(self, px: float, py: float, c: float, s: float, bx: float, by: float,
                  vx: float, vy: float, dx: float, dy: float, ty: float) -> np.ndarray:
        """The humanoid keeper's action (see the class docstring), team frame."""
        r, f = self.robot, self.field
        # Dive if the ball will pass out of reach of the standing body but within the lying
        # body's, soon enough that waiting longer would be too late.
        if vx < -0.05 and bx > px:
            state = np.array([bx, by, vx, vy])
            t = float(self.model.time_to_line(state, px))
            if math.isfinite(t):
                y_cross = float(self.model.predict(state, t)[1])
                off = y_cross - py
                reach = r.radius + self.ball.radius
                mouth = 0.5 * f.goal_width + self.ball.radius
                if (abs(y_cross) <= mouth + reach and reach < abs(off)
                        <= r.lying_length + self.ball.radius
                        and t <= r.fall_time + self.dive_lead):
                    # Side in the body frame: left when the crossing is to the robot's left.
                    left = c * off >= 0.0
                    return np.array([0.0, 1.0 if left else -1.0, 0.0, -1.0, 0.0, 0.0],
                                    dtype=np.float32)
        cmd_x, cmd_y = drive_command(px, py, c, s, self.guard_x, ty, r.max_sideways_speed,
                                     r.max_acceleration)
        ax = cmd_x / (r.max_forward_speed if cmd_x >= 0.0 else r.max_backward_speed)
        ay = cmd_y / r.max_sideways_speed
        omega = turn_command(c, s, 0.0, r.max_turn_speed, gain=2.0)
        at_foot = (0.0 < dx < r.radius + self.ball.radius + r.kick_reach
                   and abs(dy) < 0.5 * r.kick_width and vx > -0.1)
        return np.array([ax, ay, omega, 1.0 if at_foot else 0.0, 0.0, 0.0], dtype=np.float32)
