"""The batched Goalkeeper-v0 against single environments: env-steps per second in one process,
and memory per environment.

Usage: ``python benchmarks/batched_keeper.py [--sizes 1 16 128 512 1024] [--steps 200]
[--rounds 3] [--memory 1000] [--obs-mode truth] [--perception P] [--robot R]
[--json FILE]``.

Every run steps uniform random actions (made before the clock starts) through
Goalkeeper-v0 episodes (an SSL keeper on truth observations unless ``--robot``,
``--obs-mode`` and ``--perception`` say otherwise, for the single environment and the batch
alike), autoresets included: ``single``
is ``gymnasium.make`` stepped in a loop (resetting at episode ends), ``batch N`` the vector
entry point (``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")``) with ``N``
environments. The runs alternate within each round; ratios are to the single environment of the
same round, and the median over rounds is printed. "Physics alone" is the rate the batch would
reach if nothing but Chipmunk's steps (``cpSpaceStep``, timed call by call within the same run)
cost anything: the ceiling of any batching on top of these physics. Memory: the growth of the
process's resident set when ``--memory`` environments are built and reset in a fresh process,
divided by their number.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time

import numpy as np


def _single(steps: int, kwargs: dict) -> float:
    import gymnasium as gym

    from soccer_env.envs.registration import GOALKEEPER_ID

    env = gym.make(GOALKEEPER_ID, **kwargs)
    env.reset(seed=0)
    actions = np.random.default_rng(0).uniform(-1, 1, (steps, 6)).astype(np.float32)
    t0 = time.perf_counter()
    for a in actions:
        _, _, terminated, truncated, _ = env.step(a)
        if terminated or truncated:
            env.reset()
    return steps / (time.perf_counter() - t0)


def _batch(n: int, steps: int, kwargs: dict) -> tuple[float, float]:
    """``(env-steps/s, physics ceiling)``: the batch's rate, and the rate it would reach if
    everything but Chipmunk's own steps (``cpSpaceStep``, timed call by call in the same run)
    cost nothing."""
    import gymnasium as gym

    from soccer_env.envs.registration import GOALKEEPER_ID

    env = gym.make_vec(GOALKEEPER_ID, num_envs=n, vectorization_mode="vector_entry_point",
                       **kwargs)
    env.reset(seed=0)
    actions = np.random.default_rng(0).uniform(-1, 1, (steps, n, 6)).astype(np.float32)
    env.step(actions[0])
    batch, clock = env.batch, time.perf_counter
    space_step, physics = batch._step_space, [0.0]

    def timed(handle, dt):
        t = clock()
        space_step(handle, dt)
        physics[0] += clock() - t

    batch._step_space = timed
    t0 = time.perf_counter()
    for a in actions:
        env.step(a)
    wall = time.perf_counter() - t0
    return steps * n / wall, steps * n / physics[0]


def _memory(n: int, kwargs: dict) -> float:
    """Bytes per environment of ``n`` batched environments, measured in a fresh process."""
    from soccer_lab.bench import memory_per_item

    def run(name: str, count: int) -> str:
        return (f"{name} = gym.make_vec('soccer_env/Goalkeeper-v0', num_envs={count}, "
                f"vectorization_mode='vector_entry_point', **{kwargs!r})\n"
                f"{name}.reset(seed=0)\n"
                f"for _ in range(20): {name}.step(np.zeros(({count}, 6), np.float32))")

    # The warm-up steps too: what a process loads once (the compiled kernels, numba's
    # compiler) is not the environments' memory.
    return memory_per_item("import gymnasium as gym, numpy as np, soccer_env\n" + run("warm", 2),
                           run("env", n), n)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[1, 16, 128, 512, 1024])
    p.add_argument("--steps", type=int, default=200, help="timed steps per batched run (200)")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--memory", type=int, default=1000,
                   help="environments for the memory figure (0: skip)")
    p.add_argument("--obs-mode", default="truth", help="observation mode (truth)")
    p.add_argument("--perception", default=None, help="perception preset (the default)")
    p.add_argument("--robot", default=None, help="robot preset (ssl)")
    p.add_argument("--json", default=None)
    args = p.parse_args(argv)
    kwargs: dict = {"obs_mode": args.obs_mode}
    if args.perception:
        kwargs["perception"] = args.perception
    if args.robot:
        kwargs["robot"] = args.robot
    single: list[float] = []
    rates: dict[int, list[float]] = {n: [] for n in args.sizes}
    ceilings: dict[int, list[float]] = {n: [] for n in args.sizes}
    for r in range(args.rounds):
        order = args.sizes if r % 2 == 0 else list(reversed(args.sizes))
        single.append(_single(max(2000, args.steps * 10), kwargs))
        for n in order:
            rate, ceiling = _batch(n, args.steps, kwargs)
            rates[n].append(rate)
            ceilings[n].append(ceiling)
    results: dict = {"kwargs": kwargs,
                     "single": {"env_steps_per_s": single, "median": statistics.median(single)}}
    print(f"{'single':>10}: {statistics.median(single):9,.0f} env-steps/s")
    for n in args.sizes:
        ratios = [a / b for a, b in zip(rates[n], single)]
        top = [a / b for a, b in zip(ceilings[n], single)]
        results[f"batch {n}"] = {"env_steps_per_s": rates[n], "median": statistics.median(rates[n]),
                                 "ratio_to_single": statistics.median(ratios),
                                 "physics_ceiling": statistics.median(ceilings[n]),
                                 "ceiling_to_single": statistics.median(top)}
        print(f"{'batch ' + str(n):>10}: {statistics.median(rates[n]):9,.0f} env-steps/s   "
              f"x{statistics.median(ratios):.2f}   physics alone "
              f"{statistics.median(ceilings[n]):9,.0f} (x{statistics.median(top):.2f})")
    if args.memory:
        per_env = _memory(args.memory, kwargs)
        results["bytes_per_env"] = per_env
        print(f"memory: {per_env:,.0f} bytes per environment ({args.memory} environments)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
