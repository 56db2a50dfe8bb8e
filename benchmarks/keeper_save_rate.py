"""Save rate of the scripted keeper and of a keeper that stands still on Goalkeeper-v0.

Usage: ``python benchmarks/keeper_save_rate.py [--episodes N] [--field F] [--workers W]``.
Episodes use seeds 0..N-1 of the default shot distribution and truth observations; the
interval is Wilson's 95 % score interval. The benchmark is
:func:`soccer_lab.bench.keeper_save_rates`, an :func:`agents.runs.evaluation.evaluate` per keeper
(``soccer-env ablation`` compares observation and estimator configurations the same way).
"""

import sys

from soccer_lab.bench import save_rate_main

if __name__ == "__main__":
    sys.exit(save_rate_main())
