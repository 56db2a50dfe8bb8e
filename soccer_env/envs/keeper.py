"""A scripted goalkeeper that intercepts the ball's predicted path in front of its goal."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from estimators import FrictionBallModel
from estimators.exact import hypots, wrap_angles
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec

__all__ = ["ScriptedGoalkeeper", "drive_command", "drive_commands", "turn_command",
           "turn_commands", "hypots", "wrap_angles", "TURN_GAIN"]

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


def drive_commands(px: np.ndarray, py: np.ndarray, c: np.ndarray, s: np.ndarray,
                   tx: np.ndarray | float, ty: np.ndarray | float, max_speed: float,
                   max_acceleration: float, speed_cap: np.ndarray | float | None = None,
                   hypot: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`drive_command` on arrays (broadcast): the body-frame velocities ``(vx, vy)``
    [m/s] that drive robots at ``(px, py)`` with headings ``(c, s)`` to ``(tx, ty)`` [m] and can
    still stop there; ``speed_cap`` [m/s] per robot (or one for all, or None: ``max_speed``).

    The same arithmetic in the same order as :func:`drive_command`, with :func:`hypots` for
    ``math.hypot``: the results equal it bit for bit (``hypot``: another length function,
    e.g. ``np.hypot``, faster, whose last bit differs now and then).
    """
    ex, ey = tx - np.asarray(px, dtype=np.float64), ty - np.asarray(py, dtype=np.float64)
    dist = (hypots if hypot is None else hypot)(ex, ey)
    stop = dist <= 1e-6
    cap = max_speed if speed_cap is None else np.minimum(speed_cap, max_speed)
    speed = np.minimum(cap, np.sqrt(2.0 * max_acceleration * dist))
    dist = np.where(stop, 1.0, dist)
    wx, wy = ex / dist * speed, ey / dist * speed
    # Frame -> body frame: rotate by -heading.
    return (np.where(stop, 0.0, c * wx + s * wy), np.where(stop, 0.0, -s * wx + c * wy))


def turn_commands(c: np.ndarray, s: np.ndarray, target: np.ndarray | float,
                  max_angular_speed: float, gain: float = TURN_GAIN) -> np.ndarray:
    """:func:`turn_command` on arrays (broadcast): normalised turn rates in ``[-1, 1]`` that
    turn robots with headings ``(c, s)`` towards the headings ``target`` [rad].

    The same arithmetic as :func:`turn_command`, with ``np.arctan2`` for ``math.atan2``:
    numpy's (vectorised) arctangent can differ from the C library's in the last bit, so a
    result can differ from :func:`turn_command`'s by about 1e-16 (and, after rounding to
    float32, in its last bit in very rare cases).
    """
    err = wrap_angles(target - np.arctan2(s, c))
    return np.clip(gain * err / max_angular_speed, -1.0, 1.0)


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
        self.obs_size = len(names)
        #: The length function of :meth:`act_batch` (None: :func:`hypots`, ``math.hypot``'s
        #: bits).
        self.hypot: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None

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

    def _guard_ys(self, bx: np.ndarray, by: np.ndarray, vx: np.ndarray, vy: np.ndarray
                  ) -> np.ndarray:
        """:meth:`_guard_y` for arrays of balls: the guard-line targets ``y`` [m, team
        frame], the same arithmetic row by row."""
        f = self.field
        half_goal = 0.5 * f.goal_width + self.ball.radius
        goal_x = -f.half_length
        state = np.stack([bx, by, vx, vy], axis=-1)
        t = self.model.time_to_line(state, self.guard_x)
        hit = (vx < -0.05) & np.isfinite(t)
        crossing = self.model.predict(state, np.where(hit, t, 0.0))[..., 1]
        frac = (self.guard_x - goal_x) / np.maximum(bx - goal_x, 1e-3)
        ty = np.where(hit, crossing, by * np.minimum(frac, 1.0))
        return np.clip(ty, -half_goal, half_goal)

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

    def act_batch(self, obs: np.ndarray) -> np.ndarray:
        """Actions ``(n, 6)`` float32 of ``n`` SSL keepers from their observations
        ``(n, obs_dim)`` (float32 or float64): ``np.stack([self(o) for o in obs])``, computed
        on whole arrays.

        The same arithmetic in the same order as :meth:`__call__`; ``np.arctan2`` stands for
        ``math.atan2`` (see :func:`turn_commands`), so a turn rate can differ in its last
        float32 bit in very rare cases. Humanoid keepers are not batched (``ValueError``).
        """
        if self.humanoid:
            raise ValueError("act_batch plays SSL keepers; call the policy on each "
                             "observation for a humanoid keeper")
        obs = np.asarray(obs)
        if obs.ndim != 2 or obs.shape[1] != self.obs_size:
            raise ValueError(f"obs must have shape (n, {self.obs_size}) (one observation per "
                             f"row), got {obs.shape}")
        r = self.robot
        px, py, ax, ay, dx, dy, bvx, bvy = np.asarray(obs[:, self._idx], np.float64).T
        c, s = ax, -ay  # cos and sin of the heading in the team frame
        bx, by = px + c * dx - s * dy, py + s * dx + c * dy
        vx, vy = c * bvx - s * bvy, s * bvx + c * bvy
        ty = self._guard_ys(bx, by, vx, vy)
        cmd_x, cmd_y = drive_commands(px, py, c, s, self.guard_x, ty, r.max_speed,
                                      r.max_acceleration, hypot=self.hypot)
        face = np.clip(np.arctan2(by - py, bx - px), -0.5 * math.pi, 0.5 * math.pi)
        out = np.empty((len(obs), 6), dtype=np.float32)
        out[:, 0] = cmd_x / r.max_speed
        out[:, 1] = cmd_y / r.max_speed
        out[:, 2] = turn_commands(c, s, face, r.max_angular_speed)
        out[:, 3] = (0.0 < dx) & (dx < r.front_distance + 0.1) & (np.abs(dy)
                                                                    < 0.5 * r.kicker_width)
        out[:, 4:] = -1.0
        return out

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
