"""Physics layouts for a batch of environments, measured before choosing one.

Usage: ``python benchmarks/batched_physics.py [--sizes 1 16 128 1024] [--steps 200]
[--robots 1]``.

Each environment is the physical world of a Goalkeeper-v0 episode (SSL Division B field:
walls, goals, out-of-play sensors; the ball on its carpet-friction joint; ``--robots`` SSL
robots with their drive joints), stepped at 60 Hz in 4 substeps while the robots drive at
random commanded velocities and the balls roll. Two layouts:

* ``spaces``: one pymunk space per environment (today's :class:`~soccer_env.sim.world.World`),
  advanced by a Python loop of Chipmunk ``cpSpaceStep`` calls, commands written and state read
  body by body through Chipmunk's accessors;
* ``shared``: every environment in one space, each on its own patch of a grid (its static
  shapes on its own static body, so no shape of one environment can touch another's), advanced
  by one ``cpSpaceStep`` per substep, commands written and state read for all bodies at once
  with :mod:`pymunk.batch`.

Prints microseconds of physics per environment step (commands, substeps, state read) for each
batch size and layout, and whether the shared layout reproduces the separate spaces bit for bit
(it cannot in general: coordinates offset by the patch's origin round differently).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import pymunk
import pymunk.batch as pbatch

from soccer_env.presets import BALLS, FIELDS, ROBOTS
from soccer_env.sim.chipmunk import lib as cp
from soccer_env.sim.ssl import robot_outline

FIELD, BALL, ROBOT = FIELDS["ssl-div-b"], BALLS["ssl"], ROBOTS["ssl"]
SUBSTEPS, DT = 4, 1.0 / 240.0
_FIELDS = (pbatch.BodyFields.POSITION | pbatch.BodyFields.ANGLE | pbatch.BodyFields.VELOCITY
           | pbatch.BodyFields.ANGULAR_VELOCITY)


def _box(body: pymunk.Body, x0: float, y0: float, x1: float, y1: float) -> pymunk.Poly:
    return pymunk.Poly(body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])


def build(space: pymunk.Space, origin: tuple[float, float], robots: int
          ) -> tuple[pymunk.Body, list[pymunk.Body], list[pymunk.Body]]:
    """One environment's world in ``space`` around ``origin``: the static arena on a static
    body at ``origin`` (shapes in local coordinates), the ball and the robots."""
    ox, oy = origin
    static = space.static_body if origin == (0.0, 0.0) else pymunk.Body(
        body_type=pymunk.Body.STATIC)
    if static is not space.static_body:
        static.position = origin
        space.add(static)
    f = FIELD
    hx, hy = f.half_length, f.half_width
    wx, wy = hx + f.boundary, hy + f.boundary
    for x0, y0, x1, y1 in [(-wx - 1, wy, wx + 1, wy + 1), (-wx - 1, -wy - 1, wx + 1, -wy),
                           (wx, -wy, wx + 1, wy), (-wx - 1, -wy, -wx, wy)]:
        shape = _box(static, x0, y0, x1, y1)
        shape.elasticity, shape.friction = f.wall_restitution, 1.0
        space.add(shape)
    ball = pymunk.Body(BALL.mass, math.inf)
    ball.position = (ox, oy)
    circle = pymunk.Circle(ball, BALL.radius)
    circle.elasticity, circle.friction = 1.0, BALL.surface_friction
    space.add(ball, circle)
    friction = pymunk.PivotJoint(static, ball, (0.0, 0.0), (0.0, 0.0))
    friction.max_bias, friction.max_force = 0.0, BALL.mass * BALL.rolling_deceleration
    space.add(friction)
    bodies, controls = [], []
    outline = robot_outline(ROBOT)
    for i in range(robots):
        body = pymunk.Body(ROBOT.mass, ROBOT.moment_of_inertia)
        body.position = (ox - 1.0 - 0.5 * i, oy + 0.3 * i)
        shape = pymunk.Poly(body, outline)
        shape.elasticity, shape.friction = ROBOT.restitution, ROBOT.surface_friction
        control = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        control.position = body.position
        drive = pymunk.PivotJoint(control, body, (0.0, 0.0), (0.0, 0.0))
        drive.max_bias, drive.max_force = 0.0, ROBOT.mass * ROBOT.max_acceleration
        turn = pymunk.GearJoint(control, body, 0.0, 1.0)
        turn.max_bias = 0.0
        turn.max_force = ROBOT.moment_of_inertia * ROBOT.max_angular_acceleration
        space.add(body, shape, control, drive, turn)
        bodies.append(body)
        controls.append(control)
    return ball, bodies, controls


def _space() -> pymunk.Space:
    space = pymunk.Space()
    space.collision_slop = 5e-4
    space.iterations = 10
    return space


class Spaces:
    """One space per environment."""

    def __init__(self, n: int, robots: int) -> None:
        self.spaces, self.balls, self.bodies, self.controls = [], [], [], []
        for _ in range(n):
            space = _space()
            ball, bodies, controls = build(space, (0.0, 0.0), robots)
            self.spaces.append(space)
            self.balls.append(ball._body)
            self.bodies.append([b._body for b in bodies])
            self.controls.append([c._body for c in controls])
        self.handles = [s._space for s in self.spaces]

    def kick(self, v: np.ndarray) -> None:
        for ball, (vx, vy) in zip(self.balls, v.tolist()):
            cp.cpBodySetVelocity(ball, (vx, vy))

    def step(self, commands: np.ndarray) -> np.ndarray:
        set_v, set_w = cp.cpBodySetVelocity, cp.cpBodySetAngularVelocity
        for controls, rows in zip(self.controls, commands.tolist()):
            for c, (vx, vy, w) in zip(controls, rows):
                set_v(c, (vx, vy))
                set_w(c, w)
        step = cp.cpSpaceStep
        for handle in self.handles:
            for _ in range(SUBSTEPS):
                step(handle, DT)
        pos, vel = cp.cpBodyGetPosition, cp.cpBodyGetVelocity
        ang, spin = cp.cpBodyGetAngle, cp.cpBodyGetAngularVelocity
        rows = []
        for ball, bodies in zip(self.balls, self.bodies):
            for h in [ball, *bodies]:
                p, v = pos(h), vel(h)
                rows.append((p.x, p.y, ang(h), v.x, v.y, spin(h)))
        return np.array(rows)


class Shared:
    """Every environment in one space, on a grid of patches."""

    def __init__(self, n: int, robots: int) -> None:
        self.space = _space()
        cols = max(1, math.ceil(math.sqrt(n)))
        pitch_x = 2 * (FIELD.half_length + FIELD.boundary + 2.0)
        pitch_y = 2 * (FIELD.half_width + FIELD.boundary + 2.0)
        self.origins = np.array([((k % cols) * pitch_x, (k // cols) * pitch_y)
                                 for k in range(n)])
        self.n, self.robots = n, robots
        for origin in self.origins.tolist():
            build(self.space, tuple(origin), robots)
        # Bodies in the order pymunk.batch reads them: per environment the ball, then each
        # robot's body and control body.
        self.buffer = pbatch.Buffer()
        per_env = 1 + 2 * robots
        self.per_env = per_env
        self.ball_rows = np.arange(n) * per_env
        self.body_rows = (np.arange(n)[:, None] * per_env + 1 + 2 * np.arange(robots)).ravel()
        self.control_rows = self.body_rows + 1

    def _read(self) -> np.ndarray:
        self.buffer.clear()
        pbatch.get_space_bodies(self.space, _FIELDS, self.buffer)
        return np.frombuffer(self.buffer.float_buf(), dtype=np.float64).reshape(-1, 6).copy()

    def _write(self, state: np.ndarray) -> None:
        buf = pbatch.Buffer()
        buf.set_float_buf(np.ascontiguousarray(state).tobytes())
        pbatch.set_space_bodies(self.space, _FIELDS, buf)

    def kick(self, v: np.ndarray) -> None:
        state = self._read()
        state[self.ball_rows, 3:5] = v
        self._write(state)

    def step(self, commands: np.ndarray) -> np.ndarray:
        state = self._read()
        state[self.control_rows, 3:5] = commands[:, :, :2].reshape(-1, 2)
        state[self.control_rows, 5] = commands[:, :, 2].ravel()
        self._write(state)
        step, handle = cp.cpSpaceStep, self.space._space
        for _ in range(SUBSTEPS):
            step(handle, DT)
        state = self._read()
        rows = np.sort(np.concatenate([self.ball_rows, self.body_rows]))
        out = state[rows]
        env = rows // self.per_env
        out[:, :2] -= self.origins[env]
        return out


def measure(layout: type, n: int, robots: int, steps: int) -> tuple[float, np.ndarray]:
    """Microseconds of physics per environment step, and the final state."""
    world = layout(n, robots)
    rng = np.random.default_rng(0)
    world.kick(rng.uniform(-4.0, 4.0, (n, 2)))
    commands = rng.uniform(-2.0, 2.0, (steps, n, robots, 3))
    t0 = time.perf_counter()
    for c in commands:
        state = world.step(c)
    return (time.perf_counter() - t0) / (steps * n) * 1e6, state


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[1, 16, 128, 1024])
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--robots", type=int, default=1)
    args = p.parse_args(argv)
    print(f"physics per environment step [us], {args.robots} robot(s) per environment, "
          f"{SUBSTEPS} substeps")
    print(f"{'batch':>6} {'spaces':>8} {'shared':>8} {'ratio':>6}  max |difference| [m]")
    for n in args.sizes:
        t_sep, s_sep = measure(Spaces, n, args.robots, args.steps)
        t_sh, s_sh = measure(Shared, n, args.robots, args.steps)
        diff = float(np.max(np.abs(s_sep[:, :2] - s_sh[:, :2])))
        print(f"{n:>6} {t_sep:>8.2f} {t_sh:>8.2f} {t_sep / t_sh:>6.2f}  {diff:.1e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
