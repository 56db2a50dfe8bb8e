"""How soon the humanoid keeper's belief knows a shot: camera frames from the kick until the
believed ball velocity holds within a quarter of the true speed, per humanoid ball tracker.

Usage: ``python benchmarks/keeper_lock_on.py [--episodes 200] [--trackers kick,mfbpf]``.

The scripted humanoid keeper (``humanoid-2012``, three team-mates, perceived ``kidsize-2012``)
plays seeded Goalkeeper-v0 shots (seeds 0 onwards). From the step the shot is fired, its
belief's velocity error over its allowance (:data:`soccer_lab.papers.team.LOCK_SHARE` of the
true speed, at least :data:`~soccer_lab.papers.team.LOCK_SPEED`) is scored with
:func:`soccer_lab.papers.common.lock_on`, the definition ``soccer-env paper team`` uses in
matches: locked on once within the allowance for
:data:`~soccer_lab.papers.team.HOLD_FRAMES` frames (25 Hz). The count includes the camera's
40 ms latency and the wait for the first frame after the kick (1.5 frames on average).
Printed: the median and mean over the shots that lock on before the episode ends, and how many
never do.
"""

from __future__ import annotations

import argparse
import math
import sys

import gymnasium as gym
import numpy as np

import soccer_env  # noqa: F401
from agents.runs.resolve import make_policy
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_lab.papers.common import lock_on
from soccer_lab.papers.team import FRAME, HOLD_FRAMES, LOCK_SHARE, LOCK_SPEED


def shot_lock_on(tracker: str, seed: int) -> float | None:
    """Frames from the shot until the keeper's belief locks on (None: never)."""
    env = gym.make(GOALKEEPER_ID, robot="humanoid-2012", obs_mode="perceived",
                   perception={"camera": "kidsize-2012", "ball_tracker": tracker})
    policy = make_policy("scripted", env)
    obs, _ = env.reset(seed=seed)
    off: list[float] = []
    fired = False
    while True:
        obs, _, terminated, truncated, info = env.step(policy(obs))
        fired = fired or info["shot_fired"]
        if fired:
            true = info["truth"]["ball_velocity"][:2]
            err = math.hypot(*(info["estimate"]["ball_velocity"][:2] - true))
            off.append(err / max(LOCK_SHARE * math.hypot(*true), LOCK_SPEED))
        if terminated or truncated:
            break
    dt = env.unwrapped.settings.control_dt
    k = lock_on(np.array(off), 0, len(off), 1.0, round(HOLD_FRAMES * FRAME / dt))
    return None if k is None else k * dt / FRAME


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--episodes", type=int, default=200)
    p.add_argument("--trackers", default="kick,mfbpf")
    args = p.parse_args(argv)
    print(f"| ball tracker | lock-on after the shot [frames], median (mean) | never "
          f"({args.episodes} shots) |")
    print("|---|---|---|")
    for tracker in args.trackers.split(","):
        frames = [shot_lock_on(tracker, seed) for seed in range(args.episodes)]
        locked = [f for f in frames if f is not None]
        summary = (f"{np.median(locked):.1f} ({np.mean(locked):.1f})" if locked else "-")
        print(f"| {tracker} | {summary} | {len(frames) - len(locked)} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
