"""Many worlds in a few pymunk spaces: :class:`WorldBatch`, the physics of the batched
environments.

Each world is a :class:`~soccer_env.sim.world.World` on its own patch of a grid in a shared
space (its arena on its own static body, so no shape of one world can touch another's), and
one Chipmunk step per substep advances all the worlds of a space. ``benchmarks/
batched_physics.py`` measured this against a loop over separate spaces: about half the physics
cost per environment from 16 to a few hundred worlds ("Batched simulation: the physics
layout" in ``docs/results/step-rates.md``). Past about a hundred worlds a space no longer
stays in the processor's caches over its substeps, so the batch spreads its worlds over spaces
of ``shard_size`` worlds and runs each space's substeps in turn.

The hot path is vectorised over the batch: the commands of every robot (clipping, the
body-to-field rotation at the mid-step heading) become the control bodies' velocities in one
:mod:`pymunk.batch` write per space, and the state of every body comes back in one batch read
per space into one array, of which each world's state is a view. What happens rarely stays
with the world it happens in, through the world's own methods: contacts (routed by shape to
their world: touches, kicker, dribbler restitution), kicks, the ball's flight after a chip,
the switch from sliding to rolling, dribbling, ball exits.

The worlds are the same physics as separate worlds, but not bit for bit: a world's coordinates
in the shared space are offset by its patch's origin, which rounds differently (differences of
1e-14 m to 1e-11 m after a few hundred steps without contacts; contacts amplify them).

A batch copies (:mod:`pickle`, :mod:`copy`) with its worlds and spaces, and the copy steps
as the original does, bit for bit (:meth:`WorldBatch.__getstate__`); a world of a batch is
copied with its batch, not on its own.

Humanoids step in the batch too, but their walk engines, falls, lying bodies and foot strikes
run world by world in Python (as :meth:`World.step <soccer_env.sim.world.World.step>` runs
them), so a batch of humanoid worlds saves only the physics; their contacts are routed to
their world by body, since a lying humanoid's shape changes.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pymunk
import pymunk.batch as pbatch

from estimators.exact import hypots
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.sim.arena import BALL, HUMANOID, OUT, ROBOT, WALL
from soccer_env.sim.chipmunk import lib as cp
from soccer_env.sim.ssl import MOUTH_TOLERANCE
from soccer_env.sim.world import COLLISION_SLOP, BallExit, World
from soccer_env.validation import check_int

__all__ = ["WorldBatch", "MAX_WORLDS", "SHARD_SIZE"]

#: Largest batch: memory and the broadphase grow with it, and past a few hundred worlds per
#: space the caches no longer hold them (see the physics-layout benchmark).
MAX_WORLDS = 65536
#: Margin between two worlds' patches [m], beyond their walls.
PATCH_MARGIN = 2.0
#: Worlds per space by default (see :class:`WorldBatch`'s ``shard_size``).
SHARD_SIZE = 128

_VELOCITIES = pbatch.BodyFields.VELOCITY | pbatch.BodyFields.ANGULAR_VELOCITY
_FIELDS = (pbatch.BodyFields.POSITION | pbatch.BodyFields.ANGLE | pbatch.BodyFields.VELOCITY
           | pbatch.BodyFields.ANGULAR_VELOCITY)
#: Attributes of :class:`WorldBatch` that hold raw Chipmunk handles or :mod:`pymunk.batch`
#: buffers: never copied, made again from the spaces by :meth:`WorldBatch._bind`.
_HANDLE_ATTRIBUTES = ("_shards", "_step_space")


class _Shard:
    """One space of a :class:`WorldBatch` and its worlds ``start .. stop - 1``: the space's
    Chipmunk handle, the rows of the worlds' bodies in :mod:`pymunk.batch`'s reads and the
    buffers of its reads and writes."""

    __slots__ = ("start", "stop", "space", "handle", "read_buffer", "commands", "write",
                 "state_rows", "control_rows")

    def __init__(self, start: int, stop: int, space: pymunk.Space, worlds: list[World]
                 ) -> None:
        self.start, self.stop = start, stop
        self.space, self.handle = space, space._space
        self.read_buffer = pbatch.Buffer()
        pbatch.get_space_bodies(space, pbatch.BodyFields.BODY_ID, self.read_buffer)
        ids = np.frombuffer(self.read_buffer.int_buf(), dtype=np.intp)
        row_of = {int(i): r for r, i in enumerate(ids.tolist())}
        #: ``(worlds, 1 + N)`` rows of each world's ball and robots.
        self.state_rows = np.array([[row_of[w._ball.id]] + [row_of[b.id] for b in w._bodies]
                                    for w in worlds], dtype=np.intp)
        #: ``(worlds, N)`` rows of each world's control bodies.
        self.control_rows = np.array([[row_of[c.id] for c in w._controls] for w in worlds],
                                     dtype=np.intp)
        # The velocities written each step (``vx, vy, omega`` of every body: the control
        # bodies' commands, the others' present velocities, zeros for the static bodies) go
        # through a second buffer over an array of our own: pymunk's ``set_float_buf`` makes
        # the buffer point at that memory, which a later read into the same buffer would try
        # to reallocate.
        self.commands = np.zeros((len(ids), 3))
        self.write = pbatch.Buffer()
        self.write.set_float_buf(self.commands)

    def read(self) -> np.ndarray:
        """Every body's ``x, y, angle, vx, vy, omega`` in the space, ``(bodies, 6)``."""
        self.read_buffer.clear()
        pbatch.get_space_bodies(self.space, _FIELDS, self.read_buffer)
        return np.frombuffer(self.read_buffer.float_buf(), dtype=np.float64).reshape(-1, 6)


class WorldBatch:
    """``n_worlds`` worlds of one configuration in shared spaces.

    Args:
        n_worlds: the number of worlds (1..:data:`MAX_WORLDS`).
        field, ball, robot, n_blue, n_yellow, control_dt, physics_dt: as
            :class:`~soccer_env.sim.world.World` takes them.
        shard_size: worlds per space (1..:data:`MAX_WORLDS`; default
            :data:`SHARD_SIZE`). Each space runs all its substeps before the next one
            starts, so that its bodies, shapes and contacts stay in the processor's caches
            (``benchmarks/batched_physics.py``: a space of 1,024 worlds costs twice as much
            per world as one of 128).

    Attributes:
        worlds: the worlds, each usable as a :class:`World` for reading (``snapshot``,
            ``robot_array``, ``ball_exit``, ``touched``, ``kicked``...) and for teleports.
        state: ``(n_worlds, 1 + N, 6)`` view of every world's ball and robots
            (``x, y, theta, vx, vy, omega``, field frame of each world), filled at the end of
            each :meth:`step`; ``worlds[k].robot_array()`` is a view of ``state[k, 1:]``.
        origins: ``(n_worlds, 2)`` each world's origin in its space [m].
        spaces: the spaces (after :meth:`reset`), world ``k`` in ``spaces[k // shard_size]``.
    """

    def __init__(self, n_worlds: int, field: FieldSpec, ball: BallSpec,
                 robot: RobotSpec | list[RobotSpec] | tuple[RobotSpec, ...], n_blue: int,
                 n_yellow: int, control_dt: float = 1.0 / 60.0,
                 physics_dt: float = 1.0 / 240.0, shard_size: int | None = None) -> None:
        n_worlds = check_int("n_worlds", n_worlds, 1, MAX_WORLDS)
        self.shard_size = check_int("shard_size", SHARD_SIZE if shard_size is None
                                    else shard_size, 1, MAX_WORLDS)
        self.worlds = [World(field, ball, robot, n_blue, n_yellow, control_dt, physics_dt)
                       for _ in range(n_worlds)]
        w0 = self.worlds[0]
        #: The humanoids' indices (their walk engines, falls and lying bodies run world by
        #: world, in Python: a batch with humanoids saves the physics, not their walk).
        self.humanoid_indices = list(w0.humanoid_indices)
        self._ssl_mask = np.array([s.kind == "ssl" for s in w0.robot_specs])
        self.n_worlds = n_worlds
        self.n_robots = w0.n_robots
        self.field = field
        self.control_dt, self.substep_dt, self.n_substeps = (w0.control_dt, w0.substep_dt,
                                                             w0.n_substeps)
        per = min(self.shard_size, n_worlds)
        cols = max(1, math.ceil(math.sqrt(per)))
        pitch_x = 2.0 * (field.half_length + field.boundary + PATCH_MARGIN) + 2.0
        pitch_y = 2.0 * (field.half_width + field.boundary + PATCH_MARGIN) + 2.0
        # A grid of patches in each space, the same in every space.
        self.origins = np.array([((j % cols) * pitch_x, (j // cols) * pitch_y)
                                 for j in (k % per for k in range(n_worlds))],
                                dtype=np.float64)
        limits = np.array([w0._limits[i] for i in range(self.n_robots)], dtype=np.float64)
        self._vmax, self._wmax, self._cap = limits[:, 0], limits[:, 1], limits[:, 2]
        # The kicker's and the dribbler's reach (see World._kick_resting_ball and
        # _dribble_candidates; humanoids have neither, their columns are masked).
        self._reach2 = np.array([(s.radius + ball.radius + MOUTH_TOLERANCE) ** 2
                                 for s in w0.robot_specs])
        self._front_reach = np.array([getattr(s, "front_distance", s.radius) + ball.radius
                                      for s in w0.robot_specs])
        self.state = np.zeros((n_worlds, 1 + self.n_robots, 6))
        for k, w in enumerate(self.worlds):
            w._state = self.state[k]
        self._shards: list[_Shard] = []

    @property
    def spaces(self) -> list[pymunk.Space]:
        """The spaces, in world order (empty before :meth:`reset` and after :meth:`close`)."""
        return [shard.space for shard in self._shards]

    # ------------------------------------------------------------------------------------
    # Construction and episodes
    # ------------------------------------------------------------------------------------

    def reset(self, robot_poses: np.ndarray, ball_positions: np.ndarray,
              rngs: list[np.random.Generator] | None = None) -> None:
        """Build the shared spaces with every world at rest.

        Args:
            robot_poses: ``(n_worlds, N, 3)`` initial ``x, y, theta`` of every robot of every
                world, each in its world's field frame.
            ball_positions: ``(n_worlds, 2)`` initial ball positions.
            rngs: each world's generator of the humanoids' random events (as
                :meth:`World.reset <soccer_env.sim.world.World.reset>` takes it; None:
                ``default_rng(0)`` for every world).
        """
        poses = np.asarray(robot_poses, dtype=np.float64)
        balls = np.asarray(ball_positions, dtype=np.float64)
        if poses.shape != (self.n_worlds, self.n_robots, 3):
            raise ValueError(f"robot_poses must have shape ({self.n_worlds}, {self.n_robots}, "
                             f"3), got {poses.shape}")
        if balls.shape != (self.n_worlds, 2):
            raise ValueError(f"ball_positions must have shape ({self.n_worlds}, 2), got "
                             f"{balls.shape}")
        if rngs is not None and len(rngs) != self.n_worlds:
            raise ValueError(f"rngs must hold {self.n_worlds} generators, got {len(rngs)}")
        self._owner: dict[pymunk.Shape, int] = {}
        # A humanoid's shapes change (its lying body): its contacts are routed by body.
        self._body_owner: dict[pymunk.Body, int] = {}
        spaces = []
        for start in range(0, self.n_worlds, self.shard_size):
            stop = min(start + self.shard_size, self.n_worlds)
            space = pymunk.Space()
            space.collision_slop = COLLISION_SLOP
            space.iterations = 10
            for k in range(start, stop):
                w = self.worlds[k]
                origin = tuple(self.origins[k].tolist())
                static = pymunk.Body(body_type=pymunk.Body.STATIC)
                static.position = origin
                space.add(static)
                w._populate(space, static, origin, shared=True)
                self._owner[next(iter(w._ball.shapes))] = k
                for shape in w._shape_index:
                    self._owner[shape] = k
                for body in w._bodies:
                    self._body_owner[body] = k
            space.on_collision(BALL, ROBOT, pre_solve=self._contact)
            space.on_collision(BALL, OUT, begin=self._out)
            if self.humanoid_indices:  # as World.reset registers them
                space.on_collision(BALL, HUMANOID, pre_solve=self._touch)
                for other in (ROBOT, HUMANOID, WALL):
                    space.on_collision(HUMANOID, other, begin=self._impact)
            spaces.append(space)
        for k, (w, p, b) in enumerate(zip(self.worlds, poses, balls.tolist())):
            w.restart(p, tuple(b), None if rngs is None else rngs[k])
        self._times = np.zeros(self.n_worlds)
        self._dirty: set[int] = set()
        n = self.n_robots
        self._rows_of_step: tuple[np.ndarray, np.ndarray, np.ndarray] = (
            np.zeros((self.n_worlds, n)), np.zeros((self.n_worlds, n), dtype=bool),
            np.zeros((self.n_worlds, n), dtype=bool))
        self._pending: list[int] = []
        self._bind(spaces)
        # ``state`` already holds every world's start exactly (the worlds' restarts write it
        # through their views); a read from the space would round it through the offsets.

    def restart(self, k: int, robot_poses: np.ndarray,
                ball_position: tuple[float, float] = (0.0, 0.0),
                rng: np.random.Generator | None = None) -> None:
        """Start a new episode in world ``k`` (the others go on), with nothing remembered of
        its last one (a humanoid's lying body and grounded drives, cached contacts, joint
        impulses), as in a fresh world; ``rng``: its humanoids' generator."""
        world = self.worlds[k]
        world._stand_all()
        world._forget_contacts()
        world.restart(robot_poses, ball_position, rng)
        self._times[k] = 0.0

    def close(self) -> None:
        """Free the spaces (the batch needs a :meth:`reset` to step again)."""
        self._shards = []

    def _bind(self, spaces: list[pymunk.Space]) -> None:
        """Take the raw handles of the hot loop from ``spaces`` (one per shard, in world
        order; none before :meth:`reset` and after :meth:`close`): each shard's Chipmunk
        handle, body rows and buffers; and every world's state as its view of :attr:`state`
        again (a copy of the batch copies the views as arrays of their own)."""
        for k, world in enumerate(self.worlds):
            world._state = self.state[k]
        size = self.shard_size
        self._shards = [_Shard(start, min(start + size, self.n_worlds), space,
                               self.worlds[start:start + size])
                        for start, space in zip(range(0, self.n_worlds, size), spaces)]
        self._step_space = cp.cpSpaceStep

    # ------------------------------------------------------------------------------------
    # Copying
    # ------------------------------------------------------------------------------------

    def __getstate__(self) -> dict:
        """The batch's state for :mod:`pickle` and :mod:`copy`: its attributes, its worlds
        and its spaces (pymunk pickles each space with its bodies, joints, cached contacts
        and collision handlers, the batch's own methods), the shards' raw Chipmunk handles
        and :mod:`pymunk.batch` buffers left out.

        As a world on its own does (:meth:`World.__getstate__
        <soccer_env.sim.world.World.__getstate__>`), the batch first replaces its own spaces
        with copies rebuilt from their state, as every copy's spaces are: a space rebuilt
        from its state steps differently in the last bits (Chipmunk's bounding-box trees are
        built anew, the joints' warm-start impulses restart at zero), so the original must
        be rebuilt too for it and every copy taken at that moment to step identically from
        then on. Its worlds share the spaces, so the batch rebuilds each space once, for
        all the worlds in it, and the worlds leave theirs alone.
        """
        if self._shards:
            self._rebuild_spaces()
        return self._plain_state()

    def _plain_state(self) -> dict:
        """The attributes that :mod:`pickle` and :mod:`copy` carry, with the spaces under
        ``"_spaces"`` in place of the shards that hold them."""
        state = {k: v for k, v in self.__dict__.items() if k not in _HANDLE_ATTRIBUTES}
        state["_spaces"] = self.spaces
        return state

    def __setstate__(self, state: dict) -> None:
        """Restore a state of :meth:`__getstate__` and take the handles from its spaces."""
        state = dict(state)
        spaces = state.pop("_spaces")
        self.__dict__.update(state)
        self._bind(spaces)

    def _rebuild_spaces(self) -> None:
        """Replace every space (and every object in it, with the worlds' and the batch's
        references to them) with a copy rebuilt from its state, in one deep copy of the
        batch's and the worlds' attributes. The memo maps the batch and its worlds to
        themselves, so that the collision handlers stay bound to this batch and
        :attr:`worlds` holds the same worlds."""
        worlds = self.worlds
        memo: dict[int, object] = {id(self): self}
        memo.update((id(w), w) for w in worlds)
        fresh, fresh_worlds = copy.deepcopy(
            (self._plain_state(), [w._plain_state() for w in worlds]), memo)
        spaces = fresh.pop("_spaces")
        self.__dict__.update(fresh)
        for world, state in zip(worlds, fresh_worlds):
            world.__dict__.update(state)
            world._bind_handles()
        self._bind(spaces)

    # ------------------------------------------------------------------------------------
    # Stepping
    # ------------------------------------------------------------------------------------

    def _enter(self, k: int) -> World:
        """World ``k`` brought up to date for its own methods: the clock of the present
        substep and this step's kicker and dribbler commands (kept in the batch's arrays and
        handed to a world only when something happens in it), its touch flags cleared at
        its first event of the step."""
        world = self.worlds[k]
        world.time = float(self._times[k])
        if k not in self._dirty:  # its first event this step (the rows it changes, e.g. a
            self._dirty.add(k)    # kicker disarmed when it fires, stay its own till the end)
            armed, chip, dribble = self._rows_of_step
            world._armed, world._chip = armed[k].tolist(), chip[k].tolist()
            world._dribble = dribble[k].tolist()
            n = self.n_robots
            world.touched = [False] * n
            world.kicked = [False] * n
        return world

    def _contact(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        k = self._owner[arbiter.shapes[0]]
        world = self._enter(k)
        world._ball_robot_contact(arbiter, space, data)
        if world._pending_kick >= 0:
            self._pending.append(k)

    def _touch(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        self._enter(self._owner[arbiter.shapes[0]])._ball_touch(arbiter, space, data)

    def _impact(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        world = self._enter(self._body_owner[arbiter.shapes[0].body])
        world._humanoid_impact(arbiter, space, data)

    def _out(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        self._enter(self._owner[arbiter.shapes[0]])._ball_out(arbiter, space, data)

    def step(self, commands: np.ndarray) -> None:
        """Advance every world by one control step.

        The steps: the commands become the control bodies' velocities (clipped and turned to
        the field frame at the mid-step heading, :meth:`_field_velocities`; the humanoids'
        from their walk engines, :meth:`_walk`), written in one batch per space
        (:meth:`_write_velocities`); the kickers that may fire at a ball already in their
        mouth and the dribblers that may hold it are found on the whole batch
        (:meth:`_kicks_and_dribbles`); each space runs its substeps (:meth:`_substeps`);
        then the clocks, the humanoids' events and the state read back.

        Args:
            commands: ``(n_worlds, N, 6)``: each world's command rows as
                :meth:`World.step <soccer_env.sim.world.World.step>` takes them (``vx, vy``
                body frame, ``omega``, ``kick_speed``, ``chip``, ``dribble``).
        """
        if not self._shards:
            raise RuntimeError("call WorldBatch.reset() before stepping")
        c = np.asarray(commands, dtype=np.float64)
        if c.shape != (self.n_worlds, self.n_robots, 6):
            raise ValueError(f"commands must have shape ({self.n_worlds}, {self.n_robots}, 6), "
                             f"got {c.shape}")
        field_vx, field_vy, w = self._field_velocities(c)
        kick = c[..., 3]
        ssl = self._ssl_mask
        armed = np.where(ssl & (kick > 0.0), np.minimum(kick, self._cap), 0.0)
        n = self.n_robots
        # Touch flags of the worlds that had events in the last step go back to False (the
        # others' are False already).
        for k in self._dirty:
            self.worlds[k].touched = [False] * n
            self.worlds[k].kicked = [False] * n
        self._dirty = set()
        chip_on, dribble_on = ssl & (c[..., 4] > 0.0), ssl & (c[..., 5] > 0.0)
        self._rows_of_step = (armed, chip_on, dribble_on)
        self._pending = []
        t0s = self._times.tolist()
        if self.humanoid_indices:
            field_vx, field_vy, w = self._walk(c, field_vx, field_vy, w, t0s)
        self._write_velocities(field_vx, field_vy, w)
        dribbling = self._kicks_and_dribbles(armed, dribble_on)
        self._substeps(dribbling)
        worlds = self.worlds
        for world, t in zip(worlds, self._times.tolist()):
            world.time = t
        if self.humanoid_indices:
            for world, t0 in zip(worlds, t0s):
                world._humanoid_events(t0)
        self.read_state()

    def _field_velocities(self, c: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The control bodies' field-frame velocities ``vx, vy`` [m/s] and turn rates
        ``omega`` [rad/s], ``(n_worlds, N)`` each, of the commands ``c``: the speed clipped
        to ``max_speed`` (as :meth:`World.step <soccer_env.sim.world.World.step>` rounds
        it: ``v * vmax / speed``), the turn rate to ``max_angular_speed``, the body frame
        turned by the heading expected at mid-step."""
        vx, vy, w = c[..., 0], c[..., 1], c[..., 2]
        speed = hypots(vx, vy)  # (World.step's math.hypot, bit for bit)
        fast = speed > self._vmax
        if fast.any():  # as World.step rounds it: v * vmax / speed
            safe = np.where(fast, speed, 1.0)
            vx = np.where(fast, vx * self._vmax / safe, vx)
            vy = np.where(fast, vy * self._vmax / safe, vy)
        w = np.clip(w, -self._wmax, self._wmax)
        heading = self.state[:, 1:, 2] + 0.5 * self.control_dt * w
        cos, sin = np.cos(heading), np.sin(heading)
        return cos * vx - sin * vy, sin * vx + cos * vy, w

    def _walk(self, c: np.ndarray, field_vx: np.ndarray, field_vy: np.ndarray,
              w: np.ndarray, t0s: list[float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The humanoids' walk engines, world by world (as World.step drives them), and
        every world entered for its humanoids' events: copies of the velocities
        ``field_vx, field_vy, w`` with the humanoids' columns from their engines."""
        hum = self.humanoid_indices
        rows, headings = c.tolist(), self.state[:, 1:, 2].tolist()
        field_vx, field_vy, w = field_vx.copy(), field_vy.copy(), w.copy()
        for k, world in enumerate(self.worlds):
            self._enter(k)
            moves = world.walk.command([rows[k][i] for i in hum],
                                       [headings[k][i] for i in hum], t0s[k])
            for i, (mx, my, mw) in zip(hum, moves):
                field_vx[k, i], field_vy[k, i], w[k, i] = mx, my, mw
        return field_vx, field_vy, w

    def _write_velocities(self, field_vx: np.ndarray, field_vy: np.ndarray, w: np.ndarray
                          ) -> None:
        """Write every body's velocity, one :mod:`pymunk.batch` call per space: the control
        bodies' commands, the others' present ones.

        Velocities only: the balls' and robots' are those of :attr:`state` (read at the end
        of the last step; every change between steps, a teleport or a shot, goes through
        the worlds' ``set_robot`` and ``set_ball``, which write it there too), so the step
        needs no read of the space before its write, and positions are left alone."""
        state = self.state
        for shard in self._shards:
            bodies = shard.commands
            sl = slice(shard.start, shard.stop)
            bodies[shard.state_rows] = state[sl, :, 3:6]
            rows = shard.control_rows
            bodies[rows, 0] = field_vx[sl]
            bodies[rows, 1] = field_vy[sl]
            bodies[rows, 2] = w[sl]
            pbatch.set_space_bodies(shard.space, _VELOCITIES, shard.write)

    def _kicks_and_dribbles(self, armed: np.ndarray, dribble_on: np.ndarray
                            ) -> dict[int, list[tuple[World, list[int]]]]:
        """Which worlds may fire a kicker at a ball already in its mouth, or dribble: the
        worlds' own first tests (the ball within reach of an armed kicker; of a running
        dribbler within this step), on the whole batch at once, with the same arithmetic,
        so that only those worlds run their full checks. Fires the resting balls' kicks;
        returns the dribbling robots by space: ``{shard: [(world, robots)]}``."""
        state = self.state
        dx = state[:, :1, 0] - state[:, 1:, 0]
        dy = state[:, :1, 1] - state[:, 1:, 1]
        d2 = dx * dx + dy * dy
        resting = np.nonzero(((armed > 0.0) & (d2 < self._reach2)).any(axis=1))[0].tolist()
        dribbling: dict[int, list[tuple[World, list[int]]]] = {}
        if dribble_on.any():
            ball_speed = np.hypot(state[:, 0, 3], state[:, 0, 4])[:, None]
            near = 0.05 + (ball_speed + 2.0 * self._vmax) * self.control_dt
            close = dribble_on & ~(d2 > (near + self._front_reach) ** 2)
            for k in np.nonzero(close.any(axis=1))[0].tolist():
                world = self._enter(k)
                candidates = world._dribble_candidates()
                if candidates:
                    dribbling.setdefault(k // self.shard_size, []).append((world, candidates))
        for k in resting:
            self._enter(k)._kick_resting_ball()
        return dribbling

    def _substeps(self, dribbling: dict[int, list[tuple[World, list[int]]]]) -> None:
        """Each space's substeps in turn: the dribblers' holds, one Chipmunk step for all
        its worlds, the clocks, the kicks fired in the substep, and the flights and the
        sliding-to-rolling switches of the worlds whose ball moves so."""
        h = self.substep_dt
        step, worlds, times = self._step_space, self.worlds, self._times
        get_velocity = cp.cpBodyGetVelocity
        for index, shard in enumerate(self._shards):
            handle, sl = shard.handle, slice(shard.start, shard.stop)
            shard_times = times[sl]
            drib = dribbling.get(index, ())
            # Worlds whose ball flies or slides: their per-substep updates (the others' have
            # none).
            moving = [k for k in range(shard.start, shard.stop)
                      if worlds[k]._airborne or worlds[k]._sliding]
            for _ in range(self.n_substeps):
                for world, candidates in drib:
                    for i in candidates:
                        world._apply_dribbler(i)
                step(handle, h)
                shard_times += h
                if self._pending:
                    for k in self._pending:
                        world = self._enter(k)
                        world._fire(world._pending_kick)
                        world._pending_kick = -1
                        if k not in moving:
                            moving.append(k)
                    self._pending = []
                for k in moving:
                    world = worlds[k]
                    if world._airborne:
                        world._fly(h)
                    elif world._sliding:
                        v = get_velocity(world._ball_handle)
                        if v.x * v.x + v.y * v.y <= world._v_switch * world._v_switch:
                            world._set_sliding(False, 0.0)

    @property
    def times(self) -> np.ndarray:
        """``(n_worlds,)`` every world's clock [s] (read only)."""
        view = self._times.view()
        view.flags.writeable = False
        return view

    def touched(self) -> np.ndarray:
        """``(n_worlds, N)`` bool: the robots that touched their ball during the last step
        (each world's ``touched``, read from the worlds that had events only)."""
        out = np.zeros((self.n_worlds, self.n_robots), dtype=bool)
        for k in self._dirty:
            out[k] = self.worlds[k].touched
        return out

    def exits(self) -> list[tuple[int, BallExit]]:
        """``(k, exit)`` of every world whose ball left the field during the last step (its
        :attr:`World.ball_exit <soccer_env.sim.world.World.ball_exit>`; only worlds that had
        events are looked at, so an exit left uncleared from an earlier step is not
        repeated)."""
        worlds = self.worlds
        return [(k, worlds[k].ball_exit) for k in sorted(self._dirty)
                if worlds[k].ball_exit is not None]

    def read_state(self) -> None:
        """Fill :attr:`state` (and so every world's state) from the spaces in one batch read
        per space, headings kept in ``[-pi, pi]`` as :meth:`World.read_state` keeps them."""
        state = self.state
        for shard in self._shards:
            state[shard.start:shard.stop] = shard.read()[shard.state_rows]
        state[:, :, 0] -= self.origins[:, None, 0]
        state[:, :, 1] -= self.origins[:, None, 1]
        th = state[:, 1:, 2]
        out = np.abs(th) > math.pi
        if out.any():
            for k, i in zip(*np.nonzero(out)):
                wrapped = math.remainder(float(th[k, i]), 2.0 * math.pi)
                self.worlds[k]._bodies[i].angle = wrapped
                th[k, i] = wrapped
