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

import copy
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
from soccer_env.sim.arena import BALL, HUMANOID, OUT, ROBOT, WALL, add_walls
from soccer_env.sim.humanoid_bodies import HumanoidBodies
from soccer_env.sim.ssl import MOUTH_TOLERANCE, KickerDribbler, robot_outline
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
#: Attributes of :class:`World` that are raw Chipmunk handles or hold them: never pickled,
#: rebuilt from the space by :meth:`World._bind_handles`.
_HANDLE_ATTRIBUTES = ("_buffer", "_space_step", "_ball_handle", "_control_handles",
                      "_body_handles")


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


class World(KickerDribbler, HumanoidBodies):
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
        #: Where the field's centre lies in the space [m] (non-zero when several worlds
        #: share one space, each on its own patch).
        self.origin = (0.0, 0.0)
        self._shifted = False
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
        self._populate(space, space.static_body, (0.0, 0.0))
        space.on_collision(BALL, ROBOT, pre_solve=self._ball_robot_contact)
        space.on_collision(BALL, OUT, begin=self._ball_out)
        if self.walk is not None:
            space.on_collision(BALL, HUMANOID, pre_solve=self._ball_touch)
            for other in (ROBOT, HUMANOID, WALL):
                space.on_collision(HUMANOID, other, begin=self._humanoid_impact)
        self._restart(poses, ball_position, rng)

    def _populate(self, space: pymunk.Space, static: pymunk.Body,
                  origin: tuple[float, float]) -> None:
        """Build this world's arena, ball and robots in ``space``: the arena on ``static``
        (the space's static body, or a static body of this world's own at ``origin`` when
        several worlds share the space), every position offset by ``origin``. The collision
        handlers are the space owner's to register."""
        self.space = space
        self.origin = (float(origin[0]), float(origin[1]))
        self._shifted = self.origin != (0.0, 0.0)
        self._static = static
        add_walls(space, self.field, self.ball_spec.radius, static)
        self._add_ball(space)
        self._add_robots(space)
        # ``Space.step`` spends about 3 microseconds per call on Python housekeeping (deferred
        # adds and removals, post-step callbacks) that this world never needs, because it
        # never adds or removes objects while stepping; Chipmunk's own step is equivalent
        # (the tests check that both give identical trajectories).
        self._bind_handles()

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

    def _forget_contacts(self) -> None:
        """Drop what the space remembers of this world's past, as a fresh space would not
        have it: the bodies' bias velocities, the cached contacts of its ball and robots
        (Chipmunk's arbiters, whose accumulated impulses warm-start the next solve) and the
        accumulated impulses of its joints (the ball's carpet friction, the drives). Shapes
        are taken out and put back (which drops their arbiters); joints, whose impulses
        pymunk cannot reset, are replaced by fresh ones with the same parameters, in the
        order they were made.
        :class:`~soccer_env.sim.batch.WorldBatch` calls it when a world restarts in a shared
        space; a world on its own builds a fresh space instead (:meth:`reset`)."""
        space = self.space
        # Chipmunk moves a body at the start of a step by its velocity plus the bias
        # velocity the last contact solve left (position correction), which pymunk cannot
        # set; integrating the position over zero seconds clears it and moves nothing.
        for body in (self._ball, *self._bodies):
            pymunk.Body.update_position(body, 0.0)
        shapes = [*self._ball.shapes, *self._shape_index]
        space.remove(*shapes)
        space.add(*shapes)

        def fresh(joint: pymunk.Constraint) -> pymunk.Constraint:
            if isinstance(joint, pymunk.PivotJoint):
                new: pymunk.Constraint = pymunk.PivotJoint(joint.a, joint.b, joint.anchor_a,
                                                           joint.anchor_b)
            else:
                new = pymunk.GearJoint(joint.a, joint.b, joint.phase, joint.ratio)
            new.max_force, new.max_bias = joint.max_force, joint.max_bias
            new.error_bias, new.collide_bodies = joint.error_bias, joint.collide_bodies
            return new

        old = [self._friction, *(j for pair in self._drives for j in pair)]
        space.remove(*old)
        self._friction = fresh(self._friction)
        self._drives = [(fresh(d), fresh(t)) for d, t in self._drives]
        space.add(self._friction, *(j for pair in self._drives for j in pair))

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

    def _bind_handles(self) -> None:
        """Take the raw Chipmunk handles of the hot loop from the present space."""
        space = self.space
        self._space_step = (functools.partial(_cp.cpSpaceStep, space._space)
                            if self.direct_step else space.step)
        self._ball_handle = self._ball._body
        self._control_handles = [c._body for c in self._controls]
        self._body_handles = [self._ball._body] + [b._body for b in self._bodies]

    # ------------------------------------------------------------------------------------
    # Copying
    # ------------------------------------------------------------------------------------

    def __getstate__(self) -> dict:
        """The world's state for :mod:`pickle` and :mod:`copy` (the raw Chipmunk handles
        left out; pymunk pickles the space with its bodies, joints and cached contacts).

        A space rebuilt from its pickled state is not bit for bit the space it came from:
        Chipmunk's dynamic bounding-box tree (whose shape depends on the whole history of
        motion, and sets the order in which the solver visits contacts) is rebuilt from
        scratch, and the joints' accumulated impulses (the solver's warm start, which pymunk
        cannot read) start at zero. Both change the next steps in the last bits, and contacts
        amplify such differences. So that a copy's future is exactly the original's, the
        original first replaces its own space with one rebuilt the same way: copying a world
        perturbs its trajectory in the last bits (a world that is never copied is not
        affected), and from then on the original and every copy taken at that moment step
        identically under the same commands.
        """
        if self.space is not None:
            self._rebuild_space()
        return self._plain_state()

    def _plain_state(self) -> dict:
        return {k: v for k, v in self.__dict__.items() if k not in _HANDLE_ATTRIBUTES}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        self._buffer = pbatch.Buffer()
        if self.space is not None:
            self._bind_handles()

    def _rebuild_space(self) -> None:
        """Replace the space (and every object in it) with a copy rebuilt from its state."""
        # The memo maps this world to itself, so the collision handlers (bound methods of
        # this world) stay bound to it instead of copying it.
        fresh = copy.deepcopy(self._plain_state(), {id(self): self})
        self.__dict__.update(fresh)
        self._bind_handles()

    def _add_ball(self, space: pymunk.Space) -> None:
        """The ball and its carpet friction (a pivot joint to the static body)."""
        bs = self.ball_spec
        ball = pymunk.Body(bs.mass, math.inf)
        ball_shape = pymunk.Circle(ball, bs.radius)
        ball_shape.elasticity = 1.0
        ball_shape.friction = bs.surface_friction
        ball_shape.collision_type = BALL
        space.add(ball, ball_shape)
        friction = pymunk.PivotJoint(self._static, ball, (0.0, 0.0), (0.0, 0.0))
        friction.max_bias = 0.0
        friction.max_force = self._roll_force
        space.add(friction)
        self._ball, self._friction = ball, friction

    def _add_robots(self, space: pymunk.Space) -> None:
        """Every robot's body and shape (SSL: the flat-front polygon; humanoid: a disc), then
        its kinematic control body with the drive joints (pivot and gear, bounded force)."""
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
                shape.collision_type = ROBOT
            else:
                shape = pymunk.Circle(body, rs.radius)
                shape.collision_type = HUMANOID
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

    def _validated_poses(self, robot_poses: np.ndarray) -> np.ndarray:
        poses = np.asarray(robot_poses, dtype=np.float64)
        if poses.shape != (self.n_robots, 3):
            raise ValueError(f"robot_poses must have shape ({self.n_robots}, 3), got {poses.shape}")
        for i, (x, y, th) in enumerate(poses):
            self._check_inside(f"robot {self.names[i]}", x, y, self.robot_specs[i].radius)
            if not math.isfinite(th):
                raise ValueError(f"robot {self.names[i]} heading must be finite, got {th!r}")
        return poses

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
        self.read_state()

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

    def _ball_out(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        """``begin`` of the ball with a sensor beyond a line: record the first exit."""
        if self.ball_exit is None:
            x, y = self._ball.position
            x, y = x - self.origin[0], y - self.origin[1]
            # The callback runs inside the substep, before ``time`` is advanced past it.
            self.ball_exit = BallExit(x, y, self._z, self.time + self.substep_dt)

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
        robots.setflags(write=False)  # (cheaper than through ``flags.writeable``)
        ball = self.ball_array()
        ball.setflags(write=False)
        return WorldState(self.time, ball, robots, self.names, self.teams)
