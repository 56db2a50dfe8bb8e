"""Worker processes: the one :mod:`multiprocessing` context of the package, pools of jobs
that leave Ctrl-C to their parent, and :func:`map_jobs`, which the evaluation, the ablations
and the matches spread their work with (the vectorised environments of :mod:`agents.vec`
start their rollout workers in the same context)."""

from __future__ import annotations

import multiprocessing as mp
import os
import signal
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from typing import Any

__all__ = ["process_context", "ignore_interrupts", "process_pool", "resolve_workers",
           "map_jobs", "stripes", "unstripe", "REPLY_TIMEOUT", "START_TIMEOUT"]

#: How long a rollout worker of :mod:`agents.vec` may take to answer a request before it
#: counts as no longer answering (seconds): the default of ``reply_timeout`` and of the
#: training configuration's ``worker_timeout``. A healthy step of a worker's block takes
#: milliseconds (at most 0.02 s over 200 steps of 32 six-a-side matches per worker on a
#: 2-core machine); one that compiles a numba kernel for the first time takes seconds.
REPLY_TIMEOUT = 60.0
#: The allowance of a rollout worker's replies until it has answered its first step
#: (seconds), when it is longer than the reply timeout: building the environments, importing
#: their libraries and, where numba's disk cache is empty, compiling their kernels. On a
#: 2-core machine with an empty cache the first reset of perceived Goalkeeper environments
#: took 11 s with 2 workers and 19 s with 4, the first step of six-a-side matches 9 s and
#: 15 s: it grows with the workers per core.
START_TIMEOUT = 300.0


def process_context(start_method: str | None = None) -> Any:
    """The :mod:`multiprocessing` context of ``start_method``, by default ``"forkserver"``
    where the platform has it (as stable-baselines3 does), else ``"spawn"``; never ``"fork"``
    by default, since a parent that has used torch deadlocks forked children. Workers import
    what they need afresh, so jobs must carry everything they use (functions at module level,
    picklable arguments). Pools of jobs (:func:`process_pool`, give it to
    ``ProcessPoolExecutor(mp_context=...)``) and rollout workers use it."""
    if start_method is None:
        start_method = "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"
    return mp.get_context(start_method)


def ignore_interrupts() -> None:
    """Make this process ignore Ctrl-C (``SIGINT``): the initializer of worker processes,
    whose parent handles the interrupt (a terminal sends it to the whole process group, and
    every worker would otherwise print its own traceback)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextmanager
def process_pool(workers: int) -> Iterator[ProcessPoolExecutor]:
    """A ``ProcessPoolExecutor`` of ``workers`` processes (:func:`process_context`) that
    leave Ctrl-C to this process. When the block raises (Ctrl-C included), queued jobs are
    cancelled and the workers terminated at once instead of running on to the end of every
    submitted job (what leaving an executor's ``with`` block does)."""
    pool = ProcessPoolExecutor(workers, mp_context=process_context(),
                               initializer=ignore_interrupts)
    try:
        yield pool
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        # No public way to stop running jobs before Python 3.14's terminate_workers().
        for proc in list((getattr(pool, "_processes", None) or {}).values()):
            proc.terminate()
        raise
    pool.shutdown(wait=True)


def resolve_workers(workers: Any) -> int:
    """``workers`` as a process count: None for every core, else an integer >= 1
    (``ValueError`` otherwise)."""
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    return workers


def map_jobs(fn: Callable[[Any], Any], jobs: Sequence[Any], workers: int | None = None,
             progress: Callable[[int, int], None] | None = None) -> list[Any]:
    """``[fn(job) for job in jobs]``, in job order, over ``workers`` processes (None: every
    core; with one, or a single job, in this process). ``fn`` must be a module-level
    function and the jobs must pickle (they reach fresh processes, see
    :func:`process_context`). ``progress(done, total)`` is called after each job."""
    workers = min(resolve_workers(workers), len(jobs))
    if workers <= 1:
        outs = []
        for job in jobs:
            outs.append(fn(job))
            if progress:
                progress(len(outs), len(jobs))
        return outs
    results: list[Any] = [None] * len(jobs)
    with process_pool(workers) as pool:
        futures = {pool.submit(fn, job): i for i, job in enumerate(jobs)}
        for done, fut in enumerate(as_completed(futures), 1):
            results[futures[fut]] = fut.result()
            if progress:
                progress(done, len(jobs))
    return results


def stripes(items: Sequence[Any], workers: int) -> list[list[Any]]:
    """``items`` dealt round-robin into ``min(workers, len(items))`` stripes (stripe ``i``
    holds ``items[i::n]``), one job each for :func:`map_jobs`; :func:`unstripe` puts the
    stripes' per-item results back in the items' order."""
    n = max(1, min(int(workers), len(items)))
    return [list(items[i::n]) for i in range(n)]


def unstripe(parts: Sequence[Sequence[Any]]) -> list[Any]:
    """The per-item results of :func:`stripes`' stripes (``parts[i]`` for stripe ``i``, in
    its order) in the order of the items they were dealt from."""
    out: list[Any] = [None] * sum(len(p) for p in parts)
    for i, part in enumerate(parts):
        out[i::len(parts)] = list(part)
    return out
