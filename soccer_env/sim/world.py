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
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pymunk
import pymunk.batch as pbatch

# Chipmunk's C functions, called directly in the hot loop: pymunk's property wrappers cost
# 0.6-0.8 microseconds per access against 0.2-0.3 for the C call, and a Goalkeeper step makes
# a dozen such accesses. The package pins pymunk 7, whose internals these are.
from pymunk._chipmunk import lib as _cp

from soccer_env.presets import (
    GRAVITY,
    BallSpec,
    FieldSpec,
    HumanoidRobotSpec,
    RobotSpec,
    SSLRobotSpec,
)
from soccer_env.sim.walk import WalkEngine
from soccer_env.state import BodyState, HeadState, WorldState
from soccer_env.validation import check_int, check_range

__all__ = ["World", "COMMAND_FIELDS", "idle_commands", "BallExit", "robot_outline"]

_BALL, _ROBOT, _WALL, _OUT, _HUMANOID = 1, 2, 3, 4, 5
_BODY_FIELDS = (
    pbatch.BodyFields.POSITION
    | pbatch.BodyFields.ANGLE
    | pbatch.BodyFields.VELOCITY
    | pbatch.BodyFields.ANGULAR_VELOCITY
)
#: Minimum thickness [m] of goal walls in the physics. Real SSL goal walls are 2 cm thick; a
#: wall that thin could be tunnelled by a fast ball in one substep, so walls are grown outward
#: (the goal keeps its inner size).
MIN_GOAL_WALL = 0.05
#: Thickness [m] of the boundary walls, grown outward from the walled area.
BOUNDARY_WALL = 1.0
#: pymunk contact slop [m]: penetration allowed before correction (pymunk's default is 0.1,
#: which is meant for pixels and far too large in metres).
COLLISION_SLOP = 5e-4
#: Up to this many robots the state is read body by body rather than in one batch.
_DIRECT_READ_MAX_ROBOTS = 3
#: Largest team size (SSL Division A plays 11 vs 11).
MAX_TEAM_SIZE = 11
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


#: Columns of the ``(N, 6)`` command array of :meth:`World.step`: body-frame velocity ``vx, vy``
#: [m/s] (``+x`` forward) and ``omega`` [rad/s]; ``kick_speed`` [m/s] (a positive value arms
#: the kicker, which fires when the ball touches the front within the kicker width); ``chip``
#: (> 0: the armed kick is a chip); ``dribble`` (> 0: dribbler on).
COMMAND_FIELDS = ("vx", "vy", "omega", "kick_speed", "chip", "dribble")


def idle_commands(n: int) -> np.ndarray:
    """Commands that stop ``n`` robots and leave kickers and dribblers off."""
    return np.zeros((n, len(COMMAND_FIELDS)))


@dataclass(frozen=True)
class BallExit:
    """First moment since :meth:`World.clear_exit` at which the whole ball was past a line.

    ``x, y`` [m] is the ball centre, ``z`` [m] its height and ``time`` [s] the instant, at the
    physics substep where the ball's centre first lay more than one radius beyond a goal line
    or a touch line.
    """

    x: float
    y: float
    z: float
    time: float


class World:
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
        self.time = 0.0

    # ------------------------------------------------------------------------------------
    # Construction
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
        self.space = space
        self._add_walls(space)

        bs = self.ball_spec
        ball = pymunk.Body(bs.mass, math.inf)
        ball_shape = pymunk.Circle(ball, bs.radius)
        ball_shape.elasticity = 1.0
        ball_shape.friction = bs.surface_friction
        ball_shape.collision_type = _BALL
        space.add(ball, ball_shape)
        friction = pymunk.PivotJoint(space.static_body, ball, (0.0, 0.0), (0.0, 0.0))
        friction.max_bias = 0.0
        friction.max_force = self._roll_force
        space.add(friction)
        self._ball, self._friction = ball, friction

        self._bodies: list[pymunk.Body] = []
        self._controls: list[pymunk.Body] = []
        self._drives: list[tuple[pymunk.PivotJoint, pymunk.GearJoint]] = []
        self._shape_index: dict[pymunk.Shape, int] = {}
        outlines: dict[int, list[tuple[float, float]]] = {}
        for i, rs in enumerate(self.robot_specs):
            body = pymunk.Body(rs.mass, rs.moment_of_inertia)
            if rs.kind == "ssl":
                outline = outlines.setdefault(id(rs), robot_outline(rs))
                shape = pymunk.Poly(body, outline)
                shape.collision_type = _ROBOT
            else:
                shape = pymunk.Circle(body, rs.radius)
                shape.collision_type = _HUMANOID
            shape.elasticity = rs.restitution
            shape.friction = rs.surface_friction
            space.add(body, shape)
            self._bodies.append(body)
            self._shape_index[shape] = i
        for rs, body in zip(self.robot_specs, self._bodies):
            control = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            drive = pymunk.PivotJoint(control, body, (0.0, 0.0), (0.0, 0.0))
            drive.max_bias = 0.0
            drive.max_force = rs.mass * rs.max_acceleration
            turn = pymunk.GearJoint(control, body, 0.0, 1.0)
            turn.max_bias = 0.0
            turn.max_force = rs.moment_of_inertia * rs.max_angular_acceleration
            space.add(control, drive, turn)
            self._controls.append(control)
            self._drives.append((drive, turn))
        space.on_collision(_BALL, _ROBOT, pre_solve=self._ball_robot_contact)
        space.on_collision(_BALL, _OUT, begin=self._ball_out)
        if self.walk is not None:
            space.on_collision(_BALL, _HUMANOID, pre_solve=self._ball_touch)
            for other in (_ROBOT, _HUMANOID, _WALL):
                space.on_collision(_HUMANOID, other, begin=self._humanoid_impact)
            self.walk.reset(rng if rng is not None else np.random.default_rng(0))
        self._impacts: dict[int, float] = {}
        self._lying: dict[int, pymunk.Shape] = {}
        self._grounded: set[int] = set()
        # ``Space.step`` spends about 3 microseconds per call on Python housekeeping (deferred
        # adds and removals, post-step callbacks) that this world never needs, because it
        # never adds or removes objects while stepping; Chipmunk's own step is equivalent
        # (tests/test_physics.py checks that both give identical trajectories).
        self._space_step = functools.partial(_cp.cpSpaceStep, space._space)
        self._ball_handle = ball._body
        self._control_handles = [c._body for c in self._controls]
        self._body_handles = [ball._body] + [b._body for b in self._bodies]

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

    def _validated_poses(self, robot_poses: np.ndarray) -> np.ndarray:
        poses = np.asarray(robot_poses, dtype=np.float64)
        if poses.shape != (self.n_robots, 3):
            raise ValueError(f"robot_poses must have shape ({self.n_robots}, 3), got {poses.shape}")
        for i, (x, y, th) in enumerate(poses):
            self._check_inside(f"robot {self.names[i]}", x, y, self.robot_specs[i].radius)
            if not math.isfinite(th):
                raise ValueError(f"robot {self.names[i]} heading must be finite, got {th!r}")
        return poses

    def _add_walls(self, space: pymunk.Space) -> None:
        f = self.field
        hx, hy = f.half_length, f.half_width
        wx, wy, t = self._walls_x, self._walls_y, BOUNDARY_WALL
        boxes = [
            (-wx - t, wy, wx + t, wy + t),  # top
            (-wx - t, -wy - t, wx + t, -wy),  # bottom
            (wx, -wy, wx + t, wy),  # right
            (-wx - t, -wy, -wx, wy),  # left
        ]
        side = max(f.goal_wall_thickness, MIN_GOAL_WALL)
        back = min(max(f.goal_wall_thickness, MIN_GOAL_WALL), f.boundary - f.goal_depth)
        gw = 0.5 * f.goal_width
        for s in (-1.0, 1.0):
            x0, x1 = s * hx, s * (hx + f.goal_depth)
            x2 = s * (hx + f.goal_depth + back)
            boxes.append((min(x1, x2), -gw - side, max(x1, x2), gw + side))  # back wall
            boxes.append((min(x0, x2), gw, max(x0, x2), gw + side))  # left side wall
            boxes.append((min(x0, x2), -gw - side, max(x0, x2), -gw))  # right side wall
        for x0, y0, x1, y1 in boxes:
            shape = pymunk.Poly(space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
            shape.elasticity = f.wall_restitution
            shape.friction = 1.0
            shape.collision_type = _WALL
            space.add(shape)
        # Sensors beyond the lines: the ball overlaps one exactly when its centre is more than
        # one radius past a goal line or touch line, i.e. the whole ball is out. Their "begin"
        # callback records the substep at which that first happens, at no cost per substep.
        d = 2.0 * self.ball_spec.radius
        for x0, y0, x1, y1 in [(hx + d, -wy, wx, wy), (-wx, -wy, -hx - d, wy),
                               (-wx, hy + d, wx, wy), (-wx, -wy, wx, -hy - d)]:
            sensor = pymunk.Poly(space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
            sensor.sensor = True
            sensor.collision_type = _OUT
            space.add(sensor)

    # ------------------------------------------------------------------------------------
    # Placement
    # ------------------------------------------------------------------------------------

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
        body.position = (float(x), float(y))
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
        ball.position = (float(x), float(y))
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

    def _set_sliding(self, sliding: bool, speed: float) -> None:
        self._sliding = bool(sliding) and speed > 0.0
        if self._sliding:
            self._v_switch = self.ball_spec.k_switch * speed
            self._friction.max_force = self._slide_force
        else:
            self._friction.max_force = self._roll_force

    def clear_exit(self) -> None:
        """Forget the recorded :attr:`ball_exit` (after the referee has handled it)."""
        self.ball_exit = None

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
        set_velocity, set_omega = _cp.cpBodySetVelocity, _cp.cpBodySetAngularVelocity
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
        get_velocity = _cp.cpBodyGetVelocity
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
        self._read_state()

    # ------------------------------------------------------------------------------------
    # Humanoids
    # ------------------------------------------------------------------------------------

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
                shape.collision_type = _HUMANOID
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

    def _read_state(self) -> None:
        """Copy the ball's and robots' positions and velocities into ``self._state``.

        With many robots one :mod:`pymunk.batch` call is cheapest; with a few, reading each
        body through Chipmunk's getters costs less than the batch call's fixed overhead
        (about 3 against 6 microseconds for a keeper and the ball).
        """
        state = self._state
        if self.n_robots <= _DIRECT_READ_MAX_ROBOTS:
            pos, vel = _cp.cpBodyGetPosition, _cp.cpBodyGetVelocity
            ang, spin = _cp.cpBodyGetAngle, _cp.cpBodyGetAngularVelocity
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
        # pymunk's angle is unbounded: keep bodies (and so the reported headings) in
        # [-pi, pi] by turning a body a full turn back when it leaves that range.
        for i, th in enumerate(state[1:, 2].tolist()):
            if th > math.pi or th < -math.pi:
                th = math.remainder(th, 2.0 * math.pi)
                self._bodies[i].angle = th
                state[1 + i, 2] = th

    def _ball_out(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        """``begin`` of the ball with a sensor beyond a line: record the first exit."""
        if self.ball_exit is None:
            x, y = self._ball.position
            # The callback runs inside the substep, before ``time`` is advanced past it.
            self.ball_exit = BallExit(x, y, self._z, self.time + self.substep_dt)

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

    def robot_array(self) -> np.ndarray:
        """``(N, 6)`` view of the robots' ``x, y, theta, vx, vy, omega`` (do not modify)."""
        return self._state[1:]

    def ball_array(self) -> np.ndarray:
        """``(6,)`` copy of the ball's ``x, y, z, vx, vy, vz``."""
        b = self._state[0].copy()
        b[2] = self._z
        b[5] = self._vz
        return b

    def snapshot(self) -> WorldState:
        """An immutable :class:`WorldState` of the present truth."""
        robots = self._state[1:].copy()
        robots.flags.writeable = False
        ball = self.ball_array()
        ball.flags.writeable = False
        return WorldState(self.time, ball, robots, self.names, self.teams)
