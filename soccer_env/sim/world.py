"""The physical world: a pymunk space with walls, goals, the ball, SSL and humanoid robots.

pymunk simulates the horizontal plane; this module adds what a top-down rigid-body engine
lacks:

* **Carpet friction.** The ball is tied to the static body by a pivot joint with zero bias and
  a maximum force of ``m a``: Coulomb friction that decelerates the ball at exactly ``a`` and
  stops it without ever reversing it (the "top-down friction" idiom of Chipmunk). ``a`` is the
  sliding deceleration after a kick until the speed falls to ``k_switch`` times the kick
  speed, then the rolling deceleration, and zero in flight.
* **Robot drive.** Each robot is driven by a kinematic control body whose velocity is the
  commanded one: a pivot joint and a gear joint with zero bias and maximum force
  ``m a_max`` / torque ``I alpha_max`` make the robot track that velocity with bounded
  acceleration, and push other bodies with bounded force, like wheels with limited traction.
* **Height of the ball.** A chipped ball flies ballistically (``z`` is the height of its lowest
  point); it passes over robots while higher than their height and bounces with the fixed-loss
  model. Walls stop it at any height, so it can never leave the walled area.
* **Kicker and dribbler** on the flat front of each SSL robot (see :class:`SSLRobotSpec`).
* **Humanoids** (:class:`HumanoidRobotSpec`) are discs moved by the walk engine of
  :mod:`soccer_env.sim.walk` through the same kind of drive (their pushing force is
  ``m a_max``); their kick is a timed motion that launches the ball only if it lies at a foot
  when the foot strikes, and contacts with robots or walls can fell them (the approach speed
  along the contact normal sets the probability), drawn from the generator given to
  :meth:`World.reset`.

The control step (``control_dt``) is split into equal physics substeps no longer than
``physics_dt``. Positions and velocities are read back in one batch per control step
(:mod:`pymunk.batch`), which keeps per-body Python calls out of the hot loop.

The world's methods are grouped by what they act on: :class:`~soccer_env.sim.space.SpaceBodies`
(building the bodies in a space, their contacts' memory, copying),
:class:`~soccer_env.sim.placement.Placement` (teleporting robots and the ball),
:class:`~soccer_env.sim.ball.BallPhysics` (friction phases, flight, touches and exits),
:class:`~soccer_env.sim.ssl.KickerDribbler` and
:class:`~soccer_env.sim.humanoid_bodies.HumanoidBodies`; this module keeps the world's
configuration, the start of an episode, the step and the reading of the state.
"""

from __future__ import annotations

import math

import numpy as np
import pymunk
import pymunk.batch as pbatch

from soccer_env.presets import (
    BallSpec,
    FieldSpec,
    HumanoidRobotSpec,
    RobotSpec,
    SSLRobotSpec,
)
from soccer_env.sim.arena import BALL, HUMANOID, OUT, ROBOT, WALL
from soccer_env.sim.ball import BallExit, BallPhysics
from soccer_env.sim.chipmunk import lib as cp
from soccer_env.sim.humanoid_bodies import HumanoidBodies
from soccer_env.sim.placement import Placement
from soccer_env.sim.space import SpaceBodies
from soccer_env.sim.ssl import MOUTH_TOLERANCE, KickerDribbler
from soccer_env.sim.walk import WalkEngine
from soccer_env.state import WorldState
from soccer_env.validation import check_int, check_range

__all__ = ["World", "COMMAND_FIELDS", "idle_commands", "BallExit", "MAX_TEAM_SIZE"]

_BODY_FIELDS = (
    pbatch.BodyFields.POSITION
    | pbatch.BodyFields.ANGLE
    | pbatch.BodyFields.VELOCITY
    | pbatch.BodyFields.ANGULAR_VELOCITY
)
#: pymunk contact slop [m]: penetration allowed before correction (pymunk's default is 0.1,
#: which is meant for pixels and far too large in metres).
COLLISION_SLOP = 5e-4
#: Up to this many robots the state is read body by body rather than in one batch.
DIRECT_READ_MAX_ROBOTS = 3
#: Largest team size (SSL Division A plays 11 vs 11).
MAX_TEAM_SIZE = 11


#: Columns of the ``(N, 6)`` command array of :meth:`World.step`: body-frame velocity ``vx, vy``
#: [m/s] (``+x`` forward) and ``omega`` [rad/s]; ``kick_speed`` [m/s] (a positive value arms
#: the kicker, which fires when the ball touches the front within the kicker width); ``chip``
#: (> 0: the armed kick is a chip); ``dribble`` (> 0: dribbler on).
COMMAND_FIELDS = ("vx", "vy", "omega", "kick_speed", "chip", "dribble")


def idle_commands(n: int) -> np.ndarray:
    """Commands that stop ``n`` robots and leave kickers and dribblers off."""
    return np.zeros((n, len(COMMAND_FIELDS)))


class World(KickerDribbler, HumanoidBodies, BallPhysics, SpaceBodies, Placement):
    """Physics of one field with a ball and ``n_blue + n_yellow`` robots (SSL, humanoid or
    both).

    Robots are indexed ``0 .. N-1``, blue first; names are ``blue_i`` and ``yellow_i``.

    Args:
        field: field geometry.
        ball: ball model.
        robot: robot model shared by all robots, or a sequence of ``N`` models (blue first),
            SSL and humanoid mixed as needed.
        n_blue: number of blue robots (0..11).
        n_yellow: number of yellow robots (0..11).
        control_dt: duration of one :meth:`step` [s].
        physics_dt: longest physics substep [s].
        direct_step: advance the space with Chipmunk's ``cpSpaceStep`` directly (about 3
            microseconds a substep cheaper than pymunk's ``Space.step``, whose housekeeping
            this world never needs); False uses ``Space.step``. Both give identical
            trajectories.
    """

    def __init__(
        self,
        field: FieldSpec,
        ball: BallSpec,
        robot: RobotSpec | list[RobotSpec] | tuple[RobotSpec, ...],
        n_blue: int,
        n_yellow: int,
        control_dt: float = 1.0 / 60.0,
        physics_dt: float = 1.0 / 240.0,
        *,
        direct_step: bool = True,
    ) -> None:
        n_blue = check_int("n_blue", n_blue, 0, MAX_TEAM_SIZE)
        n_yellow = check_int("n_yellow", n_yellow, 0, MAX_TEAM_SIZE)
        if n_blue + n_yellow < 1:
            raise ValueError("the world needs at least one robot (n_blue + n_yellow >= 1)")
        control_dt = check_range("control_dt", control_dt, 1e-3, 0.5)
        physics_dt = check_range("physics_dt", physics_dt, 1e-4, control_dt)
        self.field = field
        self.ball_spec = ball
        self.n_blue = n_blue
        self.n_yellow = n_yellow
        self.n_robots = self.n_blue + self.n_yellow
        specs = (list(robot) if isinstance(robot, (list, tuple))
                 else [robot] * self.n_robots)
        if len(specs) != self.n_robots or not all(
                isinstance(s, (SSLRobotSpec, HumanoidRobotSpec)) for s in specs):
            raise ValueError(f"robot must be one robot spec or {self.n_robots} of them (blue "
                             f"first), got {robot!r}")
        #: Every robot's model, in robot order.
        self.robot_specs: tuple[RobotSpec, ...] = tuple(specs)
        #: The first robot's model (the model of every robot when they share one).
        self.robot_spec = specs[0]
        #: Indices of the SSL robots and of the humanoids.
        self.ssl_indices = [i for i, s in enumerate(specs) if s.kind == "ssl"]
        self.humanoid_indices = [i for i, s in enumerate(specs) if s.kind == "humanoid"]
        self.radii = np.array([s.radius for s in specs])
        self.radii.flags.writeable = False
        self.names: tuple[str, ...] = (tuple(f"blue_{i}" for i in range(self.n_blue))
                                       + tuple(f"yellow_{i}" for i in range(self.n_yellow)))
        self.teams = np.array([0] * self.n_blue + [1] * self.n_yellow, dtype=np.int64)
        self.teams.flags.writeable = False
        self.direct_step = bool(direct_step)
        self.control_dt = float(control_dt)
        self.n_substeps = max(1, math.ceil(self.control_dt / physics_dt - 1e-9))
        self.substep_dt = self.control_dt / self.n_substeps

        # Derived constants of the hot loop.
        self._walls_x = field.half_length + field.boundary
        self._walls_y = field.half_width + field.boundary
        self._roll_force = ball.mass * ball.rolling_deceleration
        self._slide_force = ball.mass * ball.sliding_deceleration
        # Per-robot constants of the SSL kicker and dribbler (unused for humanoids).
        front = [getattr(s, "front_distance", s.radius) for s in specs]
        self._mouth_lo = [d + ball.radius - 0.01 for d in front]
        self._mouth_hi = [d + ball.radius + MOUTH_TOLERANCE for d in front]
        self._mouth_half = [0.5 * getattr(s, "kicker_width", 0.0) for s in specs]
        self._heights = [s.height for s in specs]
        self._limits = [(s.max_speed, s.max_angular_speed, getattr(s, "kick_speed_cap", 0.0))
                        for s in specs]
        self.walk = (WalkEngine([specs[i] for i in self.humanoid_indices],
                                self.humanoid_indices, self.control_dt)
                     if self.humanoid_indices else None)

        self._buffer = pbatch.Buffer()
        self._state = np.zeros((1 + self.n_robots, 6))
        self.space: pymunk.Space | None = None
        #: Whether :attr:`space` is shared with other worlds: a
        #: :class:`~soccer_env.sim.batch.WorldBatch`'s, which copies it with its worlds.
        self.shares_space = False
        #: Where the field's centre lies in the space [m] (non-zero when several worlds
        #: share one space, each on its own patch).
        self.origin = (0.0, 0.0)
        self._shifted = False
        self.time = 0.0

    # ------------------------------------------------------------------------------------
    # Episodes
    # ------------------------------------------------------------------------------------

    def reset(self, robot_poses: np.ndarray, ball_position: tuple[float, float] = (0.0, 0.0),
              rng: np.random.Generator | None = None) -> None:
        """Build a fresh space (no cached contacts, so the same inputs give the same episode).

        Args:
            robot_poses: ``(N, 3)`` initial ``x, y, theta`` of every robot, field frame.
            ball_position: initial ball ``x, y`` [m], at rest on the carpet.
            rng: the generator of the humanoids' random events (falls, kick direction,
                odometry errors); None uses ``numpy.random.default_rng(0)``. SSL robots draw
                nothing.
        """
        poses = self._validated_poses(robot_poses)
        self._check_inside("ball", *ball_position, self.ball_spec.radius)
        space = pymunk.Space()
        space.collision_slop = COLLISION_SLOP
        space.iterations = 10
        self._populate(space, space.static_body, (0.0, 0.0))
        space.on_collision(BALL, ROBOT, pre_solve=self._ball_robot_contact)
        space.on_collision(BALL, OUT, begin=self._ball_out)
        if self.walk is not None:
            space.on_collision(BALL, HUMANOID, pre_solve=self._ball_touch)
            for other in (ROBOT, HUMANOID, WALL):
                space.on_collision(HUMANOID, other, begin=self._humanoid_impact)
        self._restart(poses, ball_position, rng)

    def restart(self, robot_poses: np.ndarray,
                ball_position: tuple[float, float] = (0.0, 0.0),
                rng: np.random.Generator | None = None) -> None:
        """Start a new episode in the present space: the clock at zero, kickers disarmed,
        every robot and the ball placed at rest. :meth:`reset` builds a fresh space first
        (so that no cached contact carries over); a world sharing a space with others
        (:class:`~soccer_env.sim.batch.WorldBatch`) restarts in place."""
        self._require_space()
        poses = self._validated_poses(robot_poses)
        self._check_inside("ball", *ball_position, self.ball_spec.radius)
        self._restart(poses, ball_position, rng)

    def _restart(self, poses: np.ndarray, ball_position: tuple[float, float],
                 rng: np.random.Generator | None) -> None:
        """:meth:`restart` with ``poses`` and ``ball_position`` already checked."""
        if self.walk is not None:
            self.walk.reset(rng if rng is not None else np.random.default_rng(0))
        self._impacts: dict[int, float] = {}
        self._lying: dict[int, pymunk.Shape] = {}
        self._grounded: set[int] = set()
        n = self.n_robots
        self.time = 0.0
        self._z = 0.0
        self._vz = 0.0
        self._airborne = False
        self._hops = 0
        self._sliding = False
        self._v_switch = 0.0
        self._armed = [0.0] * n
        self._chip = [False] * n
        self._dribble = [False] * n
        self._ready_at = [0.0] * n
        self._pending_kick = -1
        #: Robots that touched the ball during the last step (list of bool, robot order).
        self.touched = [False] * n
        #: Robots whose kicker fired during the last step.
        self.kicked = [False] * n
        self.last_touch = -1
        self.ball_exit: BallExit | None = None
        self.place_all(poses, ball_position)

    # ------------------------------------------------------------------------------------
    # Stepping
    # ------------------------------------------------------------------------------------

    def step(self, commands: np.ndarray) -> None:
        """Advance the world by one control step of :attr:`control_dt` seconds.

        Args:
            commands: ``(N, 6)`` array. SSL robots' rows have the columns
                :data:`COMMAND_FIELDS`: the translational velocity's norm is clipped to
                ``max_speed``, ``omega`` to ``max_angular_speed`` and the kick speed to
                ``kick_speed_cap``. Humanoids' rows have the columns
                :data:`~soccer_env.sim.walk.HUMANOID_COMMAND_FIELDS`, which their walk
                engine limits (see :mod:`soccer_env.sim.walk`).
        """
        half = 0.5 * self.control_dt
        self._require_space()
        commands = np.asarray(commands, dtype=np.float64)
        if commands.shape != (self.n_robots, 6):
            raise ValueError(f"commands must have shape ({self.n_robots}, 6), got "
                             f"{commands.shape}")
        rows = commands.tolist()
        armed, chip, dribble = self._armed, self._chip, self._dribble
        set_velocity, set_omega = cp.cpBodySetVelocity, cp.cpBodySetAngularVelocity
        headings = self._state[1:, 2].tolist()
        controls, limits = self._control_handles, self._limits
        # Plain-Python loop: at these sizes it is several times cheaper than numpy calls.
        for i in self.ssl_indices:
            vx, vy, w, kick, ch, dr = rows[i]
            vmax, wmax, cap = limits[i]
            control, th = controls[i], headings[i]
            speed = math.hypot(vx, vy)
            if speed > vmax:
                vx, vy = vx * vmax / speed, vy * vmax / speed
            w = wmax if w > wmax else (-wmax if w < -wmax else w)
            # Body frame -> field frame with the heading expected at mid-step.
            h = th + half * w
            c, s = math.cos(h), math.sin(h)
            set_velocity(control, (c * vx - s * vy, s * vx + c * vy))
            set_omega(control, w)
            armed[i] = (kick if kick < cap else cap) if kick > 0.0 else 0.0
            chip[i] = ch > 0.0
            dribble[i] = dr > 0.0
        walk = self.walk
        if walk is not None:
            hum = self.humanoid_indices
            t0 = self.time
            for i, (vx, vy, w) in zip(hum, walk.command([rows[i] for i in hum],
                                                        [headings[i] for i in hum], t0)):
                set_velocity(controls[i], (vx, vy))
                set_omega(controls[i], w)
        self.touched = [False] * self.n_robots
        self.kicked = [False] * self.n_robots
        if any(armed):
            self._kick_resting_ball()
        dribbling = self._dribble_candidates() if any(dribble) else ()

        ball = self._ball_handle
        get_velocity = cp.cpBodyGetVelocity
        h = self.substep_dt
        space_step = self._space_step
        for _ in range(self.n_substeps):
            for i in dribbling:
                self._apply_dribbler(i)
            space_step(h)
            self.time += h
            if self._pending_kick >= 0:
                self._fire(self._pending_kick)
                self._pending_kick = -1
            if self._airborne:
                self._fly(h)
            elif self._sliding:
                v = get_velocity(ball)
                if v.x * v.x + v.y * v.y <= self._v_switch * self._v_switch:
                    self._set_sliding(False, 0.0)

        if walk is not None:
            self._humanoid_events(t0)
        self.read_state()

    def read_state(self, batch: bool | None = None) -> None:
        """Read the ball's and robots' positions and velocities from the physics (every step
        does at its end; the arrays of :meth:`robot_array` and :meth:`snapshot` come from
        here).

        With many robots one :mod:`pymunk.batch` call is cheapest; with a few, reading each
        body through Chipmunk's getters costs less than the batch call's fixed overhead
        (about 3 against 6 microseconds for a keeper and the ball). ``batch=None`` chooses:
        body by body up to :data:`DIRECT_READ_MAX_ROBOTS` robots; True or False forces one
        way (both give identical numbers).
        """
        state = self._state
        if not (self.n_robots > DIRECT_READ_MAX_ROBOTS if batch is None else batch):
            pos, vel = cp.cpBodyGetPosition, cp.cpBodyGetVelocity
            ang, spin = cp.cpBodyGetAngle, cp.cpBodyGetAngularVelocity
            rows = []
            for handle in self._body_handles:
                p, v = pos(handle), vel(handle)
                rows.append((p.x, p.y, ang(handle), v.x, v.y, spin(handle)))
            state[:] = rows
        else:
            self._buffer.clear()
            pbatch.get_space_bodies(self.space, _BODY_FIELDS, self._buffer)
            state[:] = np.frombuffer(self._buffer.float_buf(), dtype=np.float64).reshape(
                -1, 6)[: 1 + self.n_robots]
        if self._shifted:
            state[:, 0] -= self.origin[0]
            state[:, 1] -= self.origin[1]
        # pymunk's angle is unbounded: keep bodies (and so the reported headings) in
        # [-pi, pi] by turning a body a full turn back when it leaves that range.
        for i, th in enumerate(state[1:, 2].tolist()):
            if th > math.pi or th < -math.pi:
                th = math.remainder(th, 2.0 * math.pi)
                self._bodies[i].angle = th
                state[1 + i, 2] = th

    # ------------------------------------------------------------------------------------
    # Reading
    # ------------------------------------------------------------------------------------

    def robot_array(self) -> np.ndarray:
        """``(N, 6)`` view of the robots' ``x, y, theta, vx, vy, omega`` (do not modify)."""
        return self._state[1:]

    def snapshot(self) -> WorldState:
        """An immutable :class:`WorldState` of the present truth."""
        robots = self._state[1:].copy()
        robots.setflags(write=False)  # (cheaper than through ``flags.writeable``)
        ball = self.ball_array()
        ball.setflags(write=False)
        return WorldState(self.time, ball, robots, self.names, self.teams)
