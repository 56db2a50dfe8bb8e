"""Helpers of the tests: small worlds, parked robots, idle stepping."""

import numpy as np

from soccer_env import presets
from soccer_env.sim.world import World, idle_commands


def make_world(n_blue=1, n_yellow=0, field="ssl-div-b", control_dt=1 / 60, physics_dt=1 / 240,
               robot="ssl", **robot_overrides):
    f = presets.field(field)
    w = World(f, presets.ball(f.ball), presets.robot(robot, **robot_overrides), n_blue,
              n_yellow, control_dt, physics_dt)
    return w


def park(world, poses=None, ball=(0.0, 0.0)):
    """Reset with robots parked along the bottom touch line (out of the way) by default."""
    if poses is None:
        y = -(world.field.half_width + 0.5 * world.field.boundary)
        poses = [(-2.5 + 0.4 * i, y, 0.0) for i in range(world.n_robots)]
    world.reset(np.array(poses, dtype=float), ball)
    return world


def run(world, steps, commands=None):
    cmd = idle_commands(world.n_robots) if commands is None else commands
    for _ in range(steps):
        world.step(cmd)


