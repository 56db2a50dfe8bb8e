"""Save rate of the scripted keeper and of a keeper that stands still on Goalkeeper-v0.

Usage: ``python benchmarks/keeper_save_rate.py [--episodes N] [--field F] [--workers W]``.
Episodes use seeds 0..N-1 of the default shot distribution and truth observations; the
interval is Wilson's 95 % score interval. The evaluation is :func:`agents.evaluation.evaluate`
(``soccer-env ablation`` compares observation and estimator configurations the same way).
"""

from __future__ import annotations

import argparse
import os

import soccer_env  # noqa: F401
from agents.evaluation import evaluate


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--episodes", type=int, default=300)
    p.add_argument("--field", default="ssl-div-b")
    p.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                   help="processes (default: all cores); the result does not depend on it")
    args = p.parse_args()
    if args.episodes < 1 or args.workers < 1:
        p.error("--episodes and --workers must be >= 1")
    for name in ("scripted", "idle"):
        res = evaluate(name, {"field": args.field}, args.episodes, workers=args.workers)
        outcomes = dict(sorted(res.outcomes.items(), key=lambda kv: (-kv[1], kv[0])))
        print(f"{name:9s} save rate {res.save_rate:6.1%} (95 % CI {res.ci_low:.1%}-"
              f"{res.ci_high:.1%}) over {res.episodes} shots: {outcomes}")


if __name__ == "__main__":
    main()
