"""Save rate of the scripted keeper and of a keeper that stands still on Goalkeeper-v0.

Usage: ``python benchmarks/keeper_save_rate.py [--episodes N] [--field F]``. Episodes use seeds
0..N-1 of the default shot distribution and truth observations; the interval is Wilson's 95 %
score interval.
"""

from __future__ import annotations

import argparse
import math
from collections import Counter

import gymnasium as gym
import numpy as np

import soccer_env  # noqa: F401
from agents import ScriptedGoalkeeper


def wilson(successes: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval for a binomial proportion."""
    p = successes / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return centre - half, centre + half


def evaluate(policy_name: str, episodes: int, field: str) -> tuple[int, Counter]:
    env = gym.make("soccer_env/Goalkeeper-v0", field=field)
    policy = ScriptedGoalkeeper.for_env(env) if policy_name == "scripted" else None
    outcomes: Counter = Counter()
    saves = 0
    for seed in range(episodes):
        obs, _ = env.reset(seed=seed)
        while True:
            action = policy(obs) if policy else np.zeros(6, np.float32)
            obs, reward, term, trunc, info = env.step(action)
            if term or trunc:
                break
        outcomes[info["outcome"] if term else "time limit"] += 1
        saves += bool(term and info["outcome"] != "goal")
    return saves, outcomes


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--episodes", type=int, default=300)
    p.add_argument("--field", default="ssl-div-b")
    args = p.parse_args()
    for name in ("scripted", "idle"):
        saves, outcomes = evaluate(name, args.episodes, args.field)
        lo, hi = wilson(saves, args.episodes)
        print(f"{name:9s} save rate {saves / args.episodes:6.1%} (95 % CI {lo:.1%}-{hi:.1%}) "
              f"over {args.episodes} shots: {dict(outcomes)}")


if __name__ == "__main__":
    main()
