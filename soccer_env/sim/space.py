"""The world's bodies in a pymunk space, part of :class:`~soccer_env.sim.world.World`.

:class:`SpaceBodies` holds the methods of the world that build its arena, ball and robots in a
space (its own, or one shared with other worlds by :class:`~soccer_env.sim.batch.WorldBatch`),
take the raw Chipmunk handles the hot loop calls, drop what the space remembers of past
contacts, and copy the space with the world (:mod:`pickle`, :mod:`copy`).
"""

from __future__ import annotations

import copy
import functools
import math

import pymunk
import pymunk.batch as pbatch

from soccer_env.sim.arena import BALL, HUMANOID, ROBOT, add_walls
from soccer_env.sim.chipmunk import lib as cp
from soccer_env.sim.ssl import robot_outline

__all__ = ["SpaceBodies"]

#: Attributes of :class:`~soccer_env.sim.world.World` that are raw Chipmunk handles or hold
#: them: never pickled, rebuilt from the space by :meth:`SpaceBodies._bind_handles`.
_HANDLE_ATTRIBUTES = ("_buffer", "_space_step", "_ball_handle", "_control_handles",
                     "_body_handles")


class SpaceBodies:
    """The space methods of :class:`~soccer_env.sim.world.World` (see the module docstring).
    """

    # ------------------------------------------------------------------------------------
    # Building
    # ------------------------------------------------------------------------------------

    def _populate(self, space: pymunk.Space, static: pymunk.Body,
                  origin: tuple[float, float], shared: bool = False) -> None:
        """Build this world's arena, ball and robots in ``space``: the arena on ``static``
        (the space's static body, or a static body of this world's own at ``origin`` when
        several worlds share the space), every position offset by ``origin``. The collision
        handlers are the space owner's to register. ``shared``: the space belongs to a
        :class:`~soccer_env.sim.batch.WorldBatch`, which copies it (see
        :meth:`__getstate__`)."""
        self.space = space
        self.shares_space = bool(shared)
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

    def _bind_handles(self) -> None:
        """Take the raw Chipmunk handles of the hot loop from the present space."""
        space = self.space
        self._space_step = (functools.partial(cp.cpSpaceStep, space._space)
                            if self.direct_step else space.step)
        self._ball_handle = self._ball._body
        self._control_handles = [c._body for c in self._controls]
        self._body_handles = [self._ball._body] + [b._body for b in self._bodies]

    # ------------------------------------------------------------------------------------
    # Contacts
    # ------------------------------------------------------------------------------------

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

        A world in a space shared with other worlds (``shares_space``) leaves the rebuild to
        the :class:`~soccer_env.sim.batch.WorldBatch` that owns the space: rebuilding it here
        would copy the other worlds of the space (and, through the collision handlers, the
        batch) once per world, and leave the batch's handles on the old space. Such a world
        is copied with its batch, not on its own.
        """
        if self.space is not None and not self.shares_space:
            self._rebuild_space()
        return self._plain_state()

    def _plain_state(self) -> dict:
        """The attributes that :mod:`pickle` and :mod:`copy` carry: all but the raw Chipmunk
        handles, which :meth:`_bind_handles` takes again from the space."""
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
