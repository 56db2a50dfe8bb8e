"""Step rates of Goalkeeper-v0 and a 6 vs 6 match against bare pymunk (same as
``soccer-env bench``). Usage: ``python benchmarks/bench_step.py [--json] [--steps N]``."""

import sys

from soccer_lab.bench import main

if __name__ == "__main__":
    sys.exit(main())
