"""PufferLib: the keeper and the match through PufferLib's emulation, stepped by its Serial and
Multiprocessing vector backends.

    pip install pufferlib-core==3.0.7   # (the clients extra) PufferLib's emulation and vectors
    python examples/pufferlib_envs.py [--tiny] [--check-stock]

``GymnasiumPufferEnv`` wraps the keeper and ``PettingZooPufferEnv`` the match (each robot one
row of the batch); ``pufferlib.vector.make`` steps several of them in this process (``Serial``)
or in worker processes (``Multiprocessing``, whose workers write observations, rewards and
flags into shared memory and send the infos through a pipe).

PufferLib's ``Multiprocessing`` backend hangs on a second ``reset()`` when the last reset or
step of a worker returned infos, as every reset and step of this package's environments does
(the default infos and ``info_mode="flat"`` alike): ``recv()`` reads a worker's infos from its
pipe but leaves the worker's flag at "infos waiting", and the next ``async_reset()`` reads the
pipe again for every such worker, waiting forever for a message already read. Dropping the
infos does not avoid it (a worker's reset always returns the list of its environments' reset
infos, empty dicts included). :class:`ResettableMultiprocessing` below clears the flag of the
workers whose infos ``recv()`` has read, and is passed to ``pufferlib.vector.make`` as the
backend. ``--check-stock`` shows the stock backend hanging (a reset given a few seconds).
"""

from __future__ import annotations

import argparse
import functools
import os
import signal
import time

import gymnasium as gym
import numpy as np
import pufferlib.emulation
import pufferlib.vector
from pufferlib.vector import INFO, MAIN

import soccer_env
from soccer_env.envs.registration import GOALKEEPER_ID


class ResettableMultiprocessing(pufferlib.vector.Multiprocessing):
    """PufferLib's ``Multiprocessing`` backend, safe to reset again: after each ``recv()``, the
    workers whose infos it read are flagged as having none waiting (``MAIN``), so that the next
    ``async_reset()`` does not wait on their pipes for infos already read."""

    def recv(self):
        batch = super().recv()
        flags = self.buf["semaphores"]
        returned = np.zeros(len(flags), dtype=bool)
        returned[self.w_slice] = True  # the workers of this batch: their infos have been read
        flags[returned & (flags == INFO)] = MAIN
        return batch


def keeper(buf=None, seed=0, obs_mode="truth", max_episode_steps=None):
    """One keeper, emulated (its default infos pass through unchanged)."""
    env = gym.make(GOALKEEPER_ID, obs_mode=obs_mode, max_episode_steps=max_episode_steps)
    return pufferlib.emulation.GymnasiumPufferEnv(env=env, buf=buf, seed=seed)


def match(buf=None, seed=0, max_cycles=None):
    """One 2 vs 2 match, emulated: its four robots are four rows of the batch."""
    env = soccer_env.parallel_env(blue=2, yellow=2, max_cycles=max_cycles)
    return pufferlib.emulation.PettingZooPufferEnv(env=env, buf=buf, seed=seed)


def drive(vecenv, steps: int, rounds: int = 2) -> str:
    """Reset ``vecenv`` and step it with random actions, ``rounds`` times; a summary."""
    rng = np.random.default_rng(0)
    space = vecenv.single_action_space
    ended, info_count = 0, 0
    for round_ in range(rounds):
        obs, infos = vecenv.reset(seed=round_)
        assert obs.shape == (vecenv.num_envs, *vecenv.single_observation_space.shape)
        for _ in range(steps):
            actions = rng.uniform(space.low, space.high,
                                  (vecenv.num_envs, *space.shape)).astype(space.dtype)
            obs, rewards, terminals, truncations, infos = vecenv.step(actions)
            ended += int(np.sum(terminals | truncations))
            info_count += len(infos)
    return (f"{vecenv.num_envs} rows, {rounds} resets x {steps} steps, {ended} agent "
            f"episode ends, {info_count} infos")


def check_stock(creator, seconds: float = 3.0) -> str:
    """Whether PufferLib's own ``Multiprocessing`` backend gets through a second reset within
    ``seconds`` (it does not: it waits on a pipe that will not be written)."""

    def give_up(signum, frame):
        raise TimeoutError

    vecenv = pufferlib.vector.make(creator, num_envs=2, num_workers=2,
                                   backend=pufferlib.vector.Multiprocessing)
    previous = signal.signal(signal.SIGALRM, give_up)
    try:
        vecenv.reset(seed=0)
        signal.setitimer(signal.ITIMER_REAL, seconds)
        vecenv.reset(seed=1)
        return "second reset passed"
    except TimeoutError:
        return f"second reset still waiting after {seconds:.0f} s (the known hang)"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        vecenv.close()  # terminates the workers


def main(args: argparse.Namespace) -> None:
    """Drive the keeper and the match through both backends; optionally the stock one."""
    envs = {"keeper": functools.partial(keeper, obs_mode=args.obs_mode,
                                        max_episode_steps=args.max_cycles),
            "match": functools.partial(match, max_cycles=args.max_cycles)}
    backends = {"Serial": {"backend": pufferlib.vector.Serial},
                "Multiprocessing": {"backend": ResettableMultiprocessing, "num_workers": 2}}
    for name, creator in envs.items():
        for label, options in backends.items():
            start = time.perf_counter()
            vecenv = pufferlib.vector.make(creator, num_envs=args.envs, **options)
            summary = drive(vecenv, args.steps)
            vecenv.close()
            print(f"{name}, {label}: {summary} ({time.perf_counter() - start:.1f} s)",
                  flush=True)
    if args.check_stock:
        print("stock Multiprocessing, keeper:", check_stock(envs["keeper"]), flush=True)


def parse(argv: list[str] | None = None) -> argparse.Namespace:
    """The command line; ``--tiny`` (or SOCCER_EXAMPLES_TINY=1) sets the CI sizes."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tiny", action="store_true",
                   default=bool(os.environ.get("SOCCER_EXAMPLES_TINY")),
                   help="a few steps only (CI; also SOCCER_EXAMPLES_TINY=1)")
    p.add_argument("--obs-mode", choices=("truth", "perceived"), default="truth")
    p.add_argument("--envs", type=int, default=4,
                   help="environments, shared by the 2 workers of Multiprocessing")
    p.add_argument("--steps", type=int, default=None, help="steps after each reset")
    p.add_argument("--check-stock", action="store_true",
                   help="also show PufferLib's own Multiprocessing backend hang on reset")
    args = p.parse_args(argv)
    args.steps = args.steps or (30 if args.tiny else 1_000)
    args.max_cycles = 20 if args.tiny else None  # the keeper's time limit, the match's length
    return args


if __name__ == "__main__":
    main(parse())
