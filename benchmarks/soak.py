"""Soak test: the resident memory of a long run, per million steps.

Steps a match (6 vs 6 SSL on Division B by default, random actions, resets at the end of
each match) for ``--steps`` steps and samples the process's resident set size (RSS, from
``/proc/self/status``) and, with ``--tracemalloc``, the Python heap every ``--every``
steps. Reports the growth after ``--warmup`` steps as MB per million steps (least-squares
slope over the samples), and the final RSS. A steady run grows by well under 1 MB per
million steps; a leak shows as a slope that does not fall with longer runs.

    python benchmarks/soak.py --steps 1000000            # about 4 minutes on 2 cores
    python benchmarks/soak.py --env goalkeeper --obs-mode perceived --steps 500000

Not a timed test: the figures go in docs/results/step-rates.md with the command that produced them.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np


def rss_mb() -> float:
    """This process's resident set size [MB] (Linux ``/proc``; ``nan`` elsewhere)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return float("nan")


def slope_per_million(steps: list[int], values: list[float]) -> float:
    """Least-squares slope of ``values`` against ``steps``, per million steps."""
    if len(steps) < 2:
        return float("nan")
    return float(np.polyfit(np.asarray(steps, float), np.asarray(values, float), 1)[0] * 1e6)


def _match(args: argparse.Namespace):
    import soccer_env

    env = soccer_env.parallel_env(blue=args.team, yellow=args.team, obs_mode=args.obs_mode,
                                  field=args.field)
    rng = np.random.default_rng(args.seed)
    obs, _ = env.reset(seed=args.seed)

    def step() -> None:
        nonlocal obs
        if not env.agents:
            obs, _ = env.reset()
        actions = {a: rng.uniform(-1.0, 1.0, 6) for a in env.agents}
        obs, *_ = env.step(actions)

    return step, 2 * args.team


def _goalkeeper(args: argparse.Namespace):
    import gymnasium as gym

    from soccer_env.envs.registration import GOALKEEPER_ID

    env = gym.make(GOALKEEPER_ID, obs_mode=args.obs_mode).unwrapped
    rng = np.random.default_rng(args.seed)
    env.reset(seed=args.seed)

    def step() -> None:
        _, _, term, trunc, _ = env.step(rng.uniform(-1.0, 1.0, 6))
        if term or trunc:
            env.reset()

    return step, 1


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--env", choices=("match", "goalkeeper"), default="match")
    p.add_argument("--team", type=int, default=6, help="robots per team (match)")
    p.add_argument("--field", default="ssl-div-b")
    p.add_argument("--obs-mode", default="truth", choices=("truth", "raw", "perceived"))
    p.add_argument("--steps", type=int, default=1_000_000, help="environment steps")
    p.add_argument("--every", type=int, default=50_000, help="steps between samples")
    p.add_argument("--warmup", type=int, default=200_000,
                   help="steps left out of the slope (caches, allocator arenas filling)")
    p.add_argument("--tracemalloc", action="store_true",
                   help="also sample the Python heap (slows the run)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--json", action="store_true")
    args = p.parse_args(argv)
    for name in ("steps", "every", "team"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be >= 1")
    if args.warmup < 0:
        p.error("--warmup must be >= 0")
    step, robots = (_match if args.env == "match" else _goalkeeper)(args)
    if args.tracemalloc:
        tracemalloc.start()
    samples: list[dict[str, float]] = []
    t0 = time.perf_counter()
    for k in range(1, args.steps + 1):
        step()
        if k % args.every == 0 or k == args.steps:
            heap = tracemalloc.get_traced_memory()[0] / 2**20 if args.tracemalloc else None
            samples.append({"steps": k, "rss_mb": rss_mb(), "heap_mb": heap,
                            "seconds": time.perf_counter() - t0})
            if not args.json:
                print(f"{k:>10,} steps  RSS {samples[-1]['rss_mb']:8.1f} MB"
                      + ("" if heap is None else f"  Python heap {heap:7.1f} MB"),
                      file=sys.stderr, flush=True)
    after = [s for s in samples if s["steps"] >= args.warmup]
    result = {
        "env": args.env, "robots": robots, "obs_mode": args.obs_mode, "steps": args.steps,
        "warmup": args.warmup, "steps_per_s": args.steps / (time.perf_counter() - t0),
        "rss_final_mb": samples[-1]["rss_mb"],
        "rss_mb_per_million_steps": slope_per_million([s["steps"] for s in after],
                                                      [s["rss_mb"] for s in after]),
        "heap_mb_per_million_steps": (slope_per_million(
            [s["steps"] for s in after], [s["heap_mb"] for s in after])
            if args.tracemalloc else None),
        "samples": samples}
    if args.json:
        print(json.dumps(result, indent=1))
    else:
        print(f"{args.env} ({robots} robots, {args.obs_mode}), {args.steps:,} steps at "
              f"{result['steps_per_s']:,.0f} steps/s: RSS {result['rss_final_mb']:.1f} MB, "
              f"growth after {args.warmup:,} steps {result['rss_mb_per_million_steps']:+.2f} "
              "MB per million steps"
              + ("" if result["heap_mb_per_million_steps"] is None else
                 f" (Python heap {result['heap_mb_per_million_steps']:+.2f})"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
