"""Match collection over processes: env-steps/s of the match VecEnv with its matches in this
process (:class:`agents.vec.match.MatchVecEnv`) and in worker processes
(:class:`agents.vec.match_workers.MatchWorkerVecEnv`).

Usage: ``python benchmarks/match_workers.py [--matches 64] [--steps 300] [--rounds 3]
[--sizes 2 6] [--workers 0 2] [--opponent scripted] [--vmas-python PATH] [--json FILE]``.

For each team size (``N`` vs ``N`` SSL robots, truth observations, the blue team learning,
the yellow team the scripted opponent) and each worker count, one timed run steps
``--matches`` matches ``--steps`` times with uniform random learner actions (made before the
clock starts; no policy network, so the figure is the environment's own rate). Runs alternate
between the worker counts within each round, so that the machine's drift cancels in the
ratios; the ratio of each round is taken between runs of that round, and the median is
printed. An env-step is one match advancing by one control step (all its robots).
``workers 0`` is the in-process VecEnv, the baseline of the ratios; ``2:nopin`` is two
workers left to the scheduler (``pin=False``; the default pins workers to CPUs when they take
every CPU).

With ``--vmas-python`` (a Python with ``vmas`` and torch installed), each round also times
VMAS's football at the same team size, 512 environments batched on the CPU with torch's two
threads (``benchmarks/vmas_football.py``, run as a subprocess in the same alternation), and
prints the ratio of our best configuration to it.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def _rate(size: int, workers: str, matches: int, steps: int, opponent: str) -> float:
    from agents.vec.factories import make_match_vec_env

    count, _, option = workers.partition(":")
    venv = make_match_vec_env({"blue": size, "yellow": size}, n_matches=matches,
                              learner="blue", opponent=opponent, seed=0, workers=int(count),
                              pin=False if option == "nopin" else None)
    try:
        venv.reset()
        rng = np.random.default_rng(0)
        actions = rng.uniform(-1.0, 1.0, (steps, venv.num_envs, 6)).astype(np.float32)
        for a in actions[:5]:  # warm-up: first contacts, caches
            venv.step(a)
        t0 = time.perf_counter()
        for a in actions:
            venv.step(a)
        return matches * steps / (time.perf_counter() - t0)
    finally:
        venv.close()


def _vmas_rate(python: str, size: int) -> float:
    script = Path(__file__).with_name("vmas_football.py")
    out = subprocess.run([python, str(script), "--agents", str(size)], check=True,
                         capture_output=True, text=True).stdout
    return float(json.loads(out.strip().splitlines()[-1])["env_steps_per_s"])


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--matches", type=int, default=64, help="matches per run (64)")
    p.add_argument("--steps", type=int, default=300, help="timed steps per run (300)")
    p.add_argument("--rounds", type=int, default=3, help="rounds of alternation (3)")
    p.add_argument("--sizes", type=int, nargs="+", default=[2, 6], help="team sizes (2 6)")
    p.add_argument("--workers", nargs="+", default=["0", "2"],
                   help="worker counts, the first is the baseline; N:nopin leaves the N "
                        "workers unpinned (0 2)")
    p.add_argument("--opponent", default="scripted", help="the yellow team (scripted)")
    p.add_argument("--vmas-python", default=None,
                   help="a Python with vmas installed: also time VMAS football")
    p.add_argument("--json", default=None, help="also write the figures to this file")
    args = p.parse_args(argv)
    results: dict[str, dict] = {}
    for size in args.sizes:
        rates: dict[str, list[float]] = {w: [] for w in args.workers}
        vmas: list[float] = []
        for r in range(args.rounds):
            order = args.workers if r % 2 == 0 else list(reversed(args.workers))
            for w in order:
                rates[w].append(_rate(size, w, args.matches, args.steps, args.opponent))
            if args.vmas_python:
                vmas.append(_vmas_rate(args.vmas_python, size))
        base = args.workers[0]
        case = f"{size}v{size}"
        results[case] = {}
        print(f"{case}, {args.matches} matches, {args.opponent} opponent:")
        for w in args.workers:
            ratios = [a / b for a, b in zip(rates[w], rates[base])]
            med = statistics.median(rates[w])
            results[case][w] = {"env_steps_per_s": rates[w], "median": med,
                                "ratio_to_baseline": statistics.median(ratios)}
            count, _, option = w.partition(":")
            label = ("in-process" if count == "0" else
                     f"{count} worker{'s' * (int(count) > 1)}{', unpinned' * bool(option)}")
            print(f"  {label:>20}: {med:9,.0f} env-steps/s   x{statistics.median(ratios):.2f} "
                  f"(rounds: {', '.join(f'{x:,.0f}' for x in rates[w])})")
        if vmas:
            best = max(args.workers, key=lambda w: statistics.median(rates[w]))
            ratios = [a / b for a, b in zip(rates[best], vmas)]
            results[case]["vmas_512"] = {"env_steps_per_s": vmas,
                                         "median": statistics.median(vmas),
                                         "ours_best_over_vmas": statistics.median(ratios)}
            label = "VMAS, 512 batched"
            print(f"  {label:>20}: {statistics.median(vmas):9,.0f} env-steps/s   ours "
                  f"(workers {best}) / VMAS x{statistics.median(ratios):.2f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
