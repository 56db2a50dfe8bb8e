"""``soccer-env bench --profile``: a perceived step of Goalkeeper-v0 or a match under
:mod:`cProfile`, the top functions by their own time per step (:func:`profile_perceived`,
:func:`format_profile`)."""

from __future__ import annotations

import time
from typing import Any

from soccer_lab.bench.runners import (
    HUMANOID,
    HUMANOID_CAMERA,
    goalkeeper_runner,
    match_runner,
    run_rate,
)
from soccer_lab.bench.tables import table

__all__ = ["PROFILE_CASES", "profile_perceived", "format_profile"]

#: The cases ``soccer-env bench --profile`` profiles: (runner, robot, default perception).
PROFILE_CASES = {
    "goalkeeper": ("goalkeeper", "ssl", "ssl-2012"),
    "match": ("match", "ssl", "ssl-2012"),
    "humanoid-goalkeeper": ("goalkeeper", HUMANOID, HUMANOID_CAMERA),
    "humanoid-match": ("match", HUMANOID, HUMANOID_CAMERA),
}


def profile_perceived(case: str, perception: str | None = None, steps: int = 2000,
                      top: int = 25, seed: int = 0) -> dict[str, Any]:
    """Profile ``steps`` perceived steps of ``case`` (a key of :data:`PROFILE_CASES`: the
    Goalkeeper-v0 or the match of :func:`run_benchmarks`) with :mod:`cProfile`: the ``top``
    functions by their own time, per environment step (calls, own and cumulative
    microseconds), and the step rates with and without the profiler."""
    import cProfile
    import pstats

    if case not in PROFILE_CASES:
        raise ValueError(f"case must be one of {sorted(PROFILE_CASES)}, got {case!r}")
    kind, robot, default = PROFILE_CASES[case]
    preset = perception or default
    make = goalkeeper_runner if kind == "goalkeeper" else match_runner
    run, _ = make(steps, seed=seed, obs_mode="perceived", perception=preset, robot=robot)
    rate = run_rate(run, steps)
    run, _ = make(steps, seed=seed, obs_mode="perceived", perception=preset, robot=robot)
    profiler = cProfile.Profile()
    t0 = time.perf_counter()
    profiler.runcall(run)
    profiled = steps / (time.perf_counter() - t0)
    stats = pstats.Stats(profiler).stats  # (file, line, name) -> (cc, nc, tt, ct, callers)
    rows = sorted(stats.items(), key=lambda item: -item[1][2])[:top]
    functions = [{"function": f"{file}:{line}({name})" if line else name,
                  "calls_per_step": nc / steps, "own_us_per_step": tt / steps * 1e6,
                  "total_us_per_step": ct / steps * 1e6}
                 for (file, line, name), (_, nc, tt, ct, _) in rows]
    return {"case": case, "perception": preset, "steps": steps, "steps_per_s": rate,
            "profiled_steps_per_s": profiled, "functions": functions}


def format_profile(res: dict[str, Any]) -> str:
    """A plain-text table of :func:`profile_perceived`'s results (paths shortened to the
    package)."""
    head = (f"{res['case']}, perceived ({res['perception']}): {res['steps_per_s']:,.0f} steps/s "
            f"({res['profiled_steps_per_s']:,.0f} under the profiler); top functions by own "
            f"time per step")
    rows = [("function", "calls/step", "own us/step", "total us/step")]
    for f in res["functions"]:
        rows.append((_short_path(f["function"]), f"{f['calls_per_step']:.2f}",
                     f"{f['own_us_per_step']:.1f}", f"{f['total_us_per_step']:.1f}"))
    return head + "\n" + table(rows)


def _short_path(name: str) -> str:
    """A profiled function's ``path:line(name)`` from its package on (an installed
    library's from below ``site-packages``)."""
    for root in ("/site-packages/", "/soccer_env/", "/estimators/", "/agents/"):
        head, sep, tail = name.partition(root)
        if sep:
            return tail if root == "/site-packages/" else root[1:] + tail
    return name
