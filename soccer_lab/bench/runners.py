"""What the step-rate benchmarks time and how: a closure stepping Goalkeeper-v0 or a match with
random actions drawn beforehand (:func:`goalkeeper_runner`, :func:`match_runner`), bare pymunk
on a world's own space (:func:`bare_rate`), the rate of a run and the median of several, and
the memory per item of what a build makes (:func:`memory_per_item`)."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable

import gymnasium as gym
import numpy as np

import soccer_env  # noqa: F401  (registers the environments)
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["HUMANOID", "HUMANOID_CAMERA", "memory_per_item", "run_rate", "median_rate",
           "random_actions", "goalkeeper_runner", "match_runner", "bare_rate"]

#: The humanoid robot and head camera timed by ``soccer-env bench``.
HUMANOID, HUMANOID_CAMERA = "humanoid-2012", "kidsize-2012"


def memory_per_item(prelude: str, build: str, n: int) -> float:
    """Bytes of resident memory per item that ``build`` (Python source making ``n`` items)
    adds in a fresh interpreter, after ``prelude`` (imports, and a small warm-up build so that
    imports and first-use caches are not counted): the growth of the process's resident set
    (``/proc/self/statm``) divided by ``n``."""
    import subprocess
    import sys

    code = (f"{prelude}\n"
            "def _rss():\n"
            "    return int(open('/proc/self/statm').read().split()[1]) * 4096\n"
            "_before = _rss()\n"
            f"{build}\n"
            f"print((_rss() - _before) / {n})\n")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True).stdout
    return float(out.strip().splitlines()[-1])


def run_rate(run: Callable[[], None], steps: int) -> float:
    """Steps per second of one call of ``run``, which takes ``steps`` steps."""
    t0 = time.perf_counter()
    run()
    return steps / (time.perf_counter() - t0)


def median_rate(run: Callable[[], None], steps: int, repeats: int) -> float:
    """The median of :func:`run_rate` over ``repeats`` calls of ``run``."""
    return statistics.median(run_rate(run, steps) for _ in range(repeats))


def random_actions(rng: np.random.Generator, shape: tuple[int, ...], robot: str) -> np.ndarray:
    """Uniform random actions; a humanoid's motion entry (kick, dive) zeroed."""
    a = rng.uniform(-1, 1, (*shape, 6))
    if robot.startswith("humanoid"):
        a[..., 3] = 0.0
    return a


def goalkeeper_runner(steps: int, seed: int = 0, obs_mode: str = "truth",
                      perception: str | dict | None = None, robot: str = "ssl",
                      field: str | None = None):
    """A closure stepping ``gymnasium.make("soccer_env/Goalkeeper-v0")`` ``steps`` times with
    pre-drawn random actions (resetting when episodes end), and its environment."""
    env = gym.make(GOALKEEPER_ID, obs_mode=obs_mode, perception=perception,
                   robot=robot, field=field)
    actions = random_actions(np.random.default_rng(seed), (steps,), robot).astype(np.float32)
    env.reset(seed=seed)

    def run() -> None:
        for a in actions:
            _, _, term, trunc, _ = env.step(a)
            if term or trunc:
                env.reset()

    return run, env


def match_runner(steps: int, blue: int = 6, yellow: int = 6, field: str | None = None,
                 seed: int = 0, obs_mode: str = "truth", perception: str | dict | None = None,
                 robot: str = "ssl"):
    """A closure stepping a match ``steps`` times with pre-drawn random actions."""
    from soccer_env import parallel_env

    env = parallel_env(blue=blue, yellow=yellow, field=field, match_duration=1e6,
                       obs_mode=obs_mode, perception=perception, robot=robot)
    env.reset(seed=seed)
    agents = list(env.agents)
    actions = random_actions(np.random.default_rng(seed), (steps, len(agents)), robot)
    dicts = [dict(zip(agents, a)) for a in actions]

    def run() -> None:
        for d in dicts:
            env.step(d)

    return run, env


def bare_rate(world, steps: int, repeats: int) -> float:
    """Control steps per second of ``pymunk.Space.step`` alone on the world's own space (same
    bodies, joints and substeps), robots driving at constant commands, no Python logic."""
    rng = np.random.default_rng(1)
    n = world.n_robots
    poses = np.column_stack([rng.uniform(-3, 3, n), rng.uniform(-2, 2, n), np.zeros(n)])
    world.reset(poses, (0.0, 0.0))
    commands = np.zeros((n, 6))
    commands[:, 0:2] = rng.uniform(-2, 2, (n, 2))
    world.step(commands)  # the drives take these velocities; the bare loop keeps them
    world.set_ball(0.0, 0.0, 3.0, 1.0)
    space, h, k = world.space, world.substep_dt, world.n_substeps

    def run() -> None:
        for _ in range(steps):
            for _ in range(k):
                space.step(h)

    return median_rate(run, steps, repeats)
