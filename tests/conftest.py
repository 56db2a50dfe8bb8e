import os

# One thread per test process: pytest-xdist already runs a process per core, and torch's
# (and the BLAS libraries') own thread pools on top of that oversubscribe the cores many
# times over. Set before anything imports torch or numpy; worker processes inherit it.
for _var in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

# Property tests draw the same examples on every run (reproducible CI); set
# HYPOTHESIS_PROFILE=explore to search with fresh random examples.
settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
settings.register_profile("explore", max_examples=500)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

from soccer_env import presets  # noqa: E402
from soccer_env.sim.world import World, idle_commands  # noqa: E402


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


@pytest.fixture
def world():
    return park(make_world())
