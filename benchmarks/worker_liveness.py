"""Worker liveness: how long :class:`agents.vec.workers.WorkerVecEnv` takes to report a rollout
worker that is alive but stopped (``SIGSTOP``).

Usage: ``python benchmarks/worker_liveness.py [--timeout SECONDS] [--tries 10] [--envs 8]
[--steps 20] [--json FILE]``.

Each try starts a ``WorkerVecEnv`` of ``--envs`` Goalkeeper-v0 environments (the training
environments of ``soccer-env train``) in 2 worker processes with reply timeout ``--timeout``
(default: :data:`~agents.vec.workers.REPLY_TIMEOUT`), resets it, steps it ``--steps`` times,
stops one worker with ``SIGSTOP`` (worker 0 and worker 1 in turn) and times the next step
until it raises :class:`~agents.vec.workers.WorkerError`. A try counts as reported in time
when the error names the stopped worker within the timeout plus one poll interval
(:data:`~agents.vec.workers.POLL_SECONDS`, the granularity of the check); a step that has not
returned 30 s after the timeout is abandoned (counted as not reported). Then ``close()`` is
timed and the workers left alive are counted (0 expected).
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import time
from typing import Any

import numpy as np

#: Seconds past the timeout after which a try's step is abandoned.
ABANDON_AFTER = 30.0


def _expired(*_: Any) -> None:
    raise TimeoutError("no WorkerError")


def _try(victim: int, timeout: float, envs: int, steps: int) -> dict[str, Any]:
    """One try: stop worker ``victim`` after ``steps`` steps and time the report (seconds)."""
    from agents.vec.factories import goalkeeper_env_fn
    from agents.vec.workers import WorkerError, WorkerVecEnv

    venv = WorkerVecEnv([goalkeeper_env_fn({}) for _ in range(envs)], n_workers=2,
                        reply_timeout=timeout)
    actions = np.zeros((envs, 6), np.float32)
    venv.reset()
    for _ in range(steps):
        venv.step(actions)
    os.kill(venv.processes[victim].pid, signal.SIGSTOP)
    old = signal.signal(signal.SIGALRM, _expired)
    signal.setitimer(signal.ITIMER_REAL, timeout + ABANDON_AFTER)
    t0 = time.perf_counter()
    named = False
    try:
        venv.step(actions)
    except WorkerError as err:
        named = err.worker == victim and err.timeout == timeout
    except TimeoutError:
        pass
    finally:
        seconds = time.perf_counter() - t0
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    t1 = time.perf_counter()
    venv.close()
    closing = time.perf_counter() - t1
    left = sum(p.is_alive() for p in venv.processes)
    for proc in venv.processes:  # an abandoned try: end its workers before the next one
        if proc.is_alive():
            proc.kill()
            proc.join()
    return {"victim": victim, "reported": named, "seconds": seconds, "close_seconds": closing,
            "workers_left": left}


def main(argv: list[str] | None = None) -> int:
    from agents.vec.workers import POLL_SECONDS, REPLY_TIMEOUT

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--timeout", type=float, default=REPLY_TIMEOUT,
                   help=f"reply timeout in seconds ({REPLY_TIMEOUT:g})")
    p.add_argument("--tries", type=int, default=10)
    p.add_argument("--envs", type=int, default=8, help="environments over the 2 workers (8)")
    p.add_argument("--steps", type=int, default=20, help="steps before the stop (20)")
    p.add_argument("--json", default=None)
    args = p.parse_args(argv)
    bound = args.timeout + POLL_SECONDS
    print(f"reply timeout {args.timeout:g} s; in time: WorkerError naming the stopped worker "
          f"within {bound:g} s")
    print(f"{'try':>3} {'worker':>6} {'in time':>7} {'seconds':>8} {'close s':>8} "
          f"{'left':>4}")
    rows = []
    for i in range(args.tries):
        row = _try(i % 2, args.timeout, args.envs, args.steps)
        row["in_time"] = row["reported"] and row["seconds"] <= bound
        rows.append(row)
        print(f"{i + 1:>3} {row['victim']:>6} {'yes' if row['in_time'] else 'no':>7} "
              f"{row['seconds']:>8.3f} {row['close_seconds']:>8.3f} {row['workers_left']:>4}",
              flush=True)
    seconds = [r["seconds"] for r in rows]
    print(f"in time {sum(r['in_time'] for r in rows)}/{len(rows)}; seconds min "
          f"{min(seconds):.3f}, median {float(np.median(seconds)):.3f}, max {max(seconds):.3f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"timeout": args.timeout, "bound": bound, "tries": rows}, f, indent=1)
    return 0 if all(r["in_time"] and not r["workers_left"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
