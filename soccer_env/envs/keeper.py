"""A scripted goalkeeper that intercepts the ball's predicted path in front of its goal.

Its rules are compiled kernels on floats (:func:`guard_line_y`, :func:`ssl_keeper`,
:func:`humanoid_keeper`, with the steering of :mod:`soccer_env.envs.steering`), written once:
:meth:`ScriptedGoalkeeper.__call__` calls them on one observation's floats and
:meth:`ScriptedGoalkeeper.act_batch` calls :func:`ssl_keeper_rows`, which runs
:func:`ssl_keeper` on each row, so both give the same actions bit for bit. Team frame (the own
goal at ``x = -L/2``), metres, seconds, radians.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from estimators import FrictionBallModel
from estimators.compiled import kernel
from soccer_env.envs.steering import TURN_GAIN, Action, command, drive_velocity, turn_rate
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec

__all__ = ["ScriptedGoalkeeper", "drive_command", "turn_command", "TURN_GAIN", "Guard",
           "SSLKeeper", "HumanoidKeeper", "line_time", "rolled_y", "guard_line_y", "team_frame",
           "ssl_keeper", "observed", "ssl_keeper_rows", "humanoid_keeper", "keeper_obs"]


def drive_command(px: float, py: float, c: float, s: float, tx: float, ty: float,
                  max_speed: float, max_acceleration: float, speed_cap: float | None = None
                  ) -> tuple[float, float]:
    """Body-frame velocity [m/s] that drives a robot at ``(px, py)`` with heading
    ``(cos, sin) = (c, s)`` to ``(tx, ty)`` (all in one frame, metres) and can still stop there:
    :func:`~soccer_env.envs.steering.drive_velocity` from Python, ``v = min(v_cap,
    sqrt(2 a_max d))`` (``v_cap`` is ``speed_cap`` or ``max_speed``)."""
    return drive_velocity(float(px), float(py), float(c), float(s), float(tx), float(ty),
                          float(max_speed), float(max_acceleration),
                          math.inf if speed_cap is None else float(speed_cap))


def turn_command(c: float, s: float, target: float, max_angular_speed: float,
                 gain: float = TURN_GAIN) -> float:
    """Normalised turn rate in ``[-1, 1]`` that turns a robot with heading
    ``(cos, sin) = (c, s)`` towards the heading ``target`` [rad]: proportional to the wrapped
    error with ``gain`` [1/s] (:func:`~soccer_env.envs.steering.turn_rate` from Python)."""
    return turn_rate(float(c), float(s), float(target), float(max_angular_speed), float(gain))


class Guard(NamedTuple):
    """The guard line's numbers that the keeper's kernels read."""

    #: The guard line ``x = -L/2 + r + guard_offset`` [m].
    guard_x: float
    #: The goal line ``x = -L/2`` [m].
    goal_x: float
    #: Half the goal mouth plus a ball radius [m]: the targets' bound and the dive's mouth.
    half_goal: float
    #: The ball's rolling deceleration [m/s^2] (:class:`~estimators.FrictionBallModel`).
    deceleration: float


class SSLKeeper(NamedTuple):
    """An SSL keeper's limits [m/s, m/s^2, rad/s] and kicker geometry [m]."""

    max_speed: float
    max_acceleration: float
    max_angular_speed: float
    front_distance: float
    kicker_width: float


class HumanoidKeeper(NamedTuple):
    """A humanoid keeper's numbers: body [m], fall [s], walking limits [m/s, m/s^2, rad/s],
    kick geometry [m], the ball's radius [m] and the dive's lead time [s]."""

    radius: float
    lying_length: float
    fall_time: float
    max_forward_speed: float
    max_backward_speed: float
    max_sideways_speed: float
    max_acceleration: float
    max_turn_speed: float
    kick_reach: float
    kick_width: float
    ball_radius: float
    dive_lead: float


@kernel
def line_time(deceleration: float, bx: float, vx: float, vy: float, x_line: float) -> float:
    """Seconds until a ball at ``x = bx`` [m] moving at ``(vx, vy)`` [m/s] reaches the line
    ``x = x_line``, ``inf`` if it stops first or moves away:
    :meth:`~estimators.FrictionBallModel.time_to_line`'s arithmetic, the smallest ``t`` in
    ``[0, v / a]`` with ``s = (x_line - bx) v / vx = v t - a t^2 / 2``, ``t = (v - sqrt(v^2 -
    2 a s)) / a``."""
    speed = math.sqrt(vx * vx + vy * vy)
    dist = x_line - bx
    if vx == 0.0:
        return math.inf
    s = dist * speed / vx
    disc = speed * speed - 2.0 * deceleration * s
    if not s >= 0.0 or (deceleration != 0.0 and not disc >= 0.0):
        return math.inf
    if dist == 0.0:
        return 0.0
    if deceleration == 0.0:
        return s / speed
    return (speed - math.sqrt(disc)) / deceleration


@kernel
def rolled_y(deceleration: float, by: float, vx: float, vy: float, dt: float) -> float:
    """``y`` [m] of a ball at ``y = by`` moving at ``(vx, vy) != 0`` [m/s] after ``dt``
    seconds: :meth:`~estimators.FrictionBallModel.predict`'s arithmetic, ``y + u_y (v t -
    a t^2 / 2)`` with ``t = min(dt, v / a)``."""
    speed = math.sqrt(vx * vx + vy * vy)
    t_stop = speed / deceleration if deceleration > 0.0 else math.inf
    t = min(dt, t_stop)
    travelled = speed * t - 0.5 * deceleration * t * t
    return by + vy / speed * travelled


@kernel
def guard_line_y(g: Guard, bx: float, by: float, vx: float, vy: float) -> float:
    """Where on the guard line the keeper goes [m]: where a ball at ``(bx, by)`` moving
    towards the goal (``vx < -0.05`` m/s) crosses it, if it gets there before it stops
    (:func:`line_time`, :func:`rolled_y`), else where the line from the ball to the goal centre
    ``(goal_x, 0)`` crosses it, ``y = by min((x_g - goal_x) / max(bx - goal_x, 1 mm), 1)``;
    within ``+-half_goal``."""
    if vx < -0.05:
        t = line_time(g.deceleration, bx, vx, vy, g.guard_x)
        if math.isfinite(t):
            return max(-g.half_goal, min(g.half_goal, rolled_y(g.deceleration, by, vx, vy, t)))
    frac = (g.guard_x - g.goal_x) / max(bx - g.goal_x, 1e-3)
    return max(-g.half_goal, min(g.half_goal, by * min(frac, 1.0)))


@kernel
def team_frame(px: float, py: float, ax: float, ay: float, dx: float, dy: float, bvx: float,
               bvy: float) -> tuple[float, float, float, float, float, float]:
    """The heading ``(cos, sin) = (ax, -ay)`` and the ball's position and velocity in the team
    frame, ``(c, s, bx, by, vx, vy)``, from the keeper's observed pose ``(px, py)`` [m] and
    axis ``(ax, ay)``, the ball's egocentric offset ``(dx, dy)`` [m] and velocity ``(bvx,
    bvy)`` [m/s]: ``b = p + R(heading) d``, ``v = R(heading) bv``."""
    c, s = ax, -ay
    return (c, s, px + c * dx - s * dy, py + s * dx + c * dy, c * bvx - s * bvy,
            s * bvx + c * bvy)


@kernel
def ssl_keeper(g: Guard, k: SSLKeeper, px: float, py: float, ax: float, ay: float, dx: float,
               dy: float, bvx: float, bvy: float) -> Action:
    """The SSL keeper's action from its observation's floats (:func:`team_frame`'s inputs):
    drive to ``(x_g, guard_line_y)`` with the braking profile, face the ball (the heading to
    it clipped to ``[-pi/2, pi/2]``), kick when the ball sits in front of the kicker (``0 <
    dx < front_distance + 0.1``, ``|dy| < kicker_width / 2``); chip and dribbler off."""
    c, s, bx, by, vx, vy = team_frame(px, py, ax, ay, dx, dy, bvx, bvy)
    ty = guard_line_y(g, bx, by, vx, vy)
    face = max(-0.5 * math.pi, min(0.5 * math.pi, math.atan2(by - py, bx - px)))
    in_front = 0.0 < dx < k.front_distance + 0.1 and abs(dy) < 0.5 * k.kicker_width
    return command(k.max_speed, k.max_acceleration, k.max_angular_speed, px, py, c, s,
                   g.guard_x, ty, face, math.inf, 1.0 if in_front else 0.0, -1.0)


@kernel
def observed(row: np.ndarray, idx: np.ndarray) -> tuple[float, float, float, float, float,
                                                        float, float, float]:
    """The entries ``idx`` of an observation ``row`` as float64 (exactly; numba's ``float()``
    of a float32 would stay float32)."""
    return (np.float64(row[idx[0]]), np.float64(row[idx[1]]), np.float64(row[idx[2]]),
            np.float64(row[idx[3]]), np.float64(row[idx[4]]), np.float64(row[idx[5]]),
            np.float64(row[idx[6]]), np.float64(row[idx[7]]))


@kernel
def ssl_keeper_rows(g: Guard, k: SSLKeeper, obs: np.ndarray, idx: np.ndarray,
                    out: np.ndarray) -> None:
    """:func:`ssl_keeper` on each row of the observations ``obs`` ``(n, obs_dim)``, whose
    entries ``idx`` ``(8,)`` are ``self.x, self.y, self.ax, self.ay, ball.dx, ball.dy,
    ball.vx, ball.vy`` (read as float64), written into ``out`` ``(n, 6)`` (rounded to its
    dtype)."""
    for i in range(obs.shape[0]):
        a = ssl_keeper(g, k, *observed(obs[i], idx))
        for j in range(6):
            out[i, j] = a[j]


@kernel
def humanoid_keeper(g: Guard, h: HumanoidKeeper, px: float, py: float, ax: float, ay: float,
                    dx: float, dy: float, bvx: float, bvy: float) -> Action:
    """The humanoid keeper's action ``(vx, vy, omega, motion, pan, tilt)`` from its
    observation's floats (:func:`team_frame`'s inputs).

    It dives (``(0, +-1, 0, -1, 0, 0)``, to the side of the crossing in the body frame) when
    the ball moving towards the goal will cross its line ``x = px`` within the goal mouth
    widened by its reach ``r + r_ball``, beyond that reach but within its lying length plus a
    ball radius, in at most ``fall_time + dive_lead`` seconds. Otherwise it walks to
    ``(x_g, guard_line_y)`` (the braking profile at most at its sideways speed; each axis
    divided by its own limit), turns to face the field (gain 2 /s) and kicks a ball resting
    at its feet (``0 < dx < r + r_ball + kick_reach``, ``|dy| < kick_width / 2``, ``vx >
    -0.1``)."""
    c, s, bx, by, vx, vy = team_frame(px, py, ax, ay, dx, dy, bvx, bvy)
    ty = guard_line_y(g, bx, by, vx, vy)
    if vx < -0.05 and bx > px:
        t = line_time(g.deceleration, bx, vx, vy, px)
        if math.isfinite(t):
            y_cross = rolled_y(g.deceleration, by, vx, vy, t)
            off = y_cross - py
            reach = h.radius + h.ball_radius
            if (abs(y_cross) <= g.half_goal + reach
                    and reach < abs(off) <= h.lying_length + h.ball_radius
                    and t <= h.fall_time + h.dive_lead):
                # Side in the body frame: left when the crossing is to the robot's left.
                return 0.0, 1.0 if c * off >= 0.0 else -1.0, 0.0, -1.0, 0.0, 0.0
    cmd_x, cmd_y = drive_velocity(px, py, c, s, g.guard_x, ty, h.max_sideways_speed,
                                  h.max_acceleration, math.inf)
    walk_x = cmd_x / (h.max_forward_speed if cmd_x >= 0.0 else h.max_backward_speed)
    omega = turn_rate(c, s, 0.0, h.max_turn_speed, 2.0)
    at_foot = (0.0 < dx < h.radius + h.ball_radius + h.kick_reach
               and abs(dy) < 0.5 * h.kick_width and vx > -0.1)
    return walk_x, cmd_y / h.max_sideways_speed, omega, 1.0 if at_foot else 0.0, 0.0, 0.0


@kernel
def keeper_obs(numbers: np.ndarray, obs: np.ndarray, idx: np.ndarray, out: np.ndarray
               ) -> None:
    """One keeper's action into ``out`` ``(6,)`` (rounded to its dtype) from its observation
    ``obs`` (the entries ``idx`` as in :func:`ssl_keeper_rows`): :func:`ssl_keeper`, or
    :func:`humanoid_keeper` where ``numbers`` ``(4 + 12,)`` holds a :class:`Guard` and a
    :class:`HumanoidKeeper` (``(4 + 5,)``: a :class:`Guard` and an :class:`SSLKeeper`). The
    numbers travel as an array: a call passes it faster than the named tuples."""
    g = Guard(numbers[0], numbers[1], numbers[2], numbers[3])
    px, py, ax, ay, dx, dy, bvx, bvy = observed(obs, idx)
    if numbers.shape[0] == 16:
        h = HumanoidKeeper(numbers[4], numbers[5], numbers[6], numbers[7], numbers[8],
                           numbers[9], numbers[10], numbers[11], numbers[12], numbers[13],
                           numbers[14], numbers[15])
        a = humanoid_keeper(g, h, px, py, ax, ay, dx, dy, bvx, bvy)
    else:
        k = SSLKeeper(numbers[4], numbers[5], numbers[6], numbers[7], numbers[8])
        a = ssl_keeper(g, k, px, py, ax, ay, dx, dy, bvx, bvy)
    for j in range(6):
        out[j] = a[j]


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
        dive_lead: a humanoid keeper dives when the ball will cross its line within this many
            seconds plus its fall time [s].
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
        #: The guard line's numbers (:class:`Guard`) and the body's (:class:`SSLKeeper` or
        #: :class:`HumanoidKeeper`) that the kernels read.
        self.guard = Guard(float(self.guard_x), float(-field.half_length),
                           float(0.5 * field.goal_width + ball.radius),
                           float(self.model.deceleration))
        r = robot
        self.body: SSLKeeper | HumanoidKeeper = (
            HumanoidKeeper(*(float(v) for v in (
                r.radius, r.lying_length, r.fall_time, r.max_forward_speed,
                r.max_backward_speed, r.max_sideways_speed, r.max_acceleration,
                r.max_turn_speed, r.kick_reach, r.kick_width, ball.radius, dive_lead)))
            if self.humanoid else
            SSLKeeper(*(float(v) for v in (r.max_speed, r.max_acceleration,
                                           r.max_angular_speed, r.front_distance,
                                           r.kicker_width))))
        self._numbers = np.array(self.guard + self.body, dtype=np.float64)
        self._cols = np.array(self._idx, dtype=np.int64)

    @classmethod
    def for_env(cls, env, **kwargs) -> ScriptedGoalkeeper:
        """Build the policy for a (possibly wrapped) Goalkeeper environment."""
        u = env.unwrapped
        return cls(u.field, u.ball_spec, u.robot_spec, u.builder.names, **kwargs)

    def _read(self, obs: np.ndarray) -> tuple[float, ...]:
        """The kernels' inputs from the observation: own position [m] and axis ``(ax, ay)``,
        the ball's egocentric offset [m] and velocity [m/s]."""
        return tuple(np.float64(obs[i]) for i in self._idx)

    def guard_y(self, obs: np.ndarray) -> float:
        """Where on the guard line the keeper goes [m, team frame] (step 2 of the class
        docstring, :func:`guard_line_y`): the predicted crossing of a ball moving towards the
        goal, else the crossing of the line from the ball to the goal centre; within the goal
        mouth."""
        _, _, bx, by, vx, vy = team_frame(*self._read(obs))
        return guard_line_y(self.guard, bx, by, vx, vy)

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        """The action ``(6,)`` float32 from one observation: :func:`ssl_keeper` or
        :func:`humanoid_keeper` on its floats (through :func:`keeper_obs`)."""
        out = np.empty(6, dtype=np.float32)
        keeper_obs(self._numbers, obs if isinstance(obs, np.ndarray) else np.asarray(obs),
                   self._cols, out)
        return out

    def act_batch(self, obs: np.ndarray) -> np.ndarray:
        """Actions ``(n, 6)`` float32 of ``n`` SSL keepers from their observations
        ``(n, obs_dim)`` (float32 or float64): ``np.stack([self(o) for o in obs])`` bit for
        bit, one call of :func:`ssl_keeper_rows`, which runs :func:`ssl_keeper` on each row.
        Humanoid keepers are not batched (``ValueError``).
        """
        if self.humanoid:
            raise ValueError("act_batch plays SSL keepers; call the policy on each "
                             "observation for a humanoid keeper")
        obs = np.asarray(obs)
        if obs.ndim != 2 or obs.shape[1] != self.obs_size:
            raise ValueError(f"obs must have shape (n, {self.obs_size}) (one observation per "
                             f"row), got {obs.shape}")
        out = np.empty((len(obs), 6), dtype=np.float32)
        ssl_keeper_rows(self.guard, self.body, np.ascontiguousarray(obs), self._cols, out)
        return out
