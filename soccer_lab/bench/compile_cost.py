"""``soccer-env bench --compile``: what the compiled kernels cost a new process
(:func:`bench_compile`, :func:`format_compile`).

Each case runs in a fresh interpreter, twice: first with an empty kernel cache (numba's
``NUMBA_CACHE_DIR`` pointed at a new folder, which it then prefers to the cache beside the
sources), so every kernel the case uses is compiled and saved; then again with that folder,
so every kernel is loaded. Timed: ``import soccer_env`` (which registers the environments),
then ``gymnasium.make``, ``reset`` and the first step, then the next ``steps`` steps (the rate
once everything is loaded); counted: the kernel specializations compiled and those loaded from
the cache. A user's first run pays the cold figures once per install (the
cache beside the sources is kept); every later process, test workers and evaluation or
training workers included, pays the warm ones.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from typing import Any

from soccer_lab.bench.runners import HUMANOID, HUMANOID_CAMERA
from soccer_lab.bench.tables import table

__all__ = ["COMPILE_CASES", "bench_compile", "format_compile"]

#: The cases timed: Goalkeeper-v0's keyword arguments.
COMPILE_CASES = {
    "Goalkeeper-v0, truth": {"obs_mode": "truth"},
    "Goalkeeper-v0, perceived ssl-2012": {"obs_mode": "perceived", "perception": "ssl-2012"},
    f"Goalkeeper-v0 {HUMANOID} + 3 mates, perceived {HUMANOID_CAMERA}": {
        "robot": HUMANOID, "obs_mode": "perceived", "perception": HUMANOID_CAMERA},
}

_SCRIPT = """
import json, sys, time
t0 = time.perf_counter()
import gymnasium as gym
import soccer_env
t1 = time.perf_counter()
env = gym.make("soccer_env/Goalkeeper-v0", **json.loads(sys.argv[1]))
env.reset(seed=0)
action = env.action_space.sample() * 0.0
env.step(action)
t2 = time.perf_counter()
steps = int(sys.argv[2])
for _ in range(steps):
    _, _, term, trunc, _ = env.step(action)
    if term or trunc:
        env.reset()
t3 = time.perf_counter()
from numba.core.registry import CPUDispatcher
kernels = {id(v): v for name, m in list(sys.modules.items())
           if name.split(".")[0] in ("soccer_env", "estimators", "agents")
           for v in list(vars(m).values()) if isinstance(v, CPUDispatcher)}.values()
print(json.dumps({"import_s": t1 - t0, "first_step_s": t2 - t1,
                  "steps_per_s": steps / (t3 - t2),
                  "compiled": sum(sum(k.stats.cache_misses.values()) for k in kernels),
                  "loaded": sum(sum(k.stats.cache_hits.values()) for k in kernels)}))
"""


def _timed(kwargs: dict[str, Any], steps: int, cache: str) -> dict[str, float]:
    """One fresh interpreter running :data:`_SCRIPT` with the kernel cache in ``cache``."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache}
    res = subprocess.run([sys.executable, "-c", _SCRIPT, json.dumps(kwargs), str(steps)],
                         capture_output=True, text=True, timeout=900, env=env)
    if res.returncode != 0:
        raise RuntimeError(f"the timed process failed:\n{res.stderr[-2000:]}")
    return json.loads(res.stdout.strip().splitlines()[-1])


def bench_compile(cases: list[str] | None = None, steps: int = 200) -> dict[str, Any]:
    """For each case of :data:`COMPILE_CASES` (all by default): the cold and the warm
    figures of a fresh interpreter (see the module docstring), ``{case: {"cold": {...},
    "warm": {...}}}`` with ``import_s``, ``first_step_s``, ``steps_per_s`` and the kernel
    specializations ``compiled`` and ``loaded``."""
    names = list(COMPILE_CASES) if cases is None else cases
    for name in names:
        if name not in COMPILE_CASES:
            raise ValueError(f"case must be one of {list(COMPILE_CASES)}, got {name!r}")
    out: dict[str, Any] = {}
    for name in names:
        with tempfile.TemporaryDirectory(prefix="soccer-env-kernels-") as cache:
            cold = _timed(COMPILE_CASES[name], steps, cache)
            warm = _timed(COMPILE_CASES[name], steps, cache)
        out[name] = {"cold": cold, "warm": warm}
    return out


def format_compile(res: dict[str, Any]) -> str:
    """The plain-text table of :func:`bench_compile`'s results."""
    head = ("case", "cold import", "cold first step", "warm import", "warm first step",
            "then steps/s", "kernels compiled")
    rows = [(name, f"{r['cold']['import_s']:.2f}", f"{r['cold']['first_step_s']:.2f}",
             f"{r['warm']['import_s']:.2f}", f"{r['warm']['first_step_s']:.2f}",
             f"{r['warm']['steps_per_s']:,.0f}", f"{r['cold']['compiled']}")
            for name, r in res.items()]
    return ("fresh interpreter: import soccer_env, then make + reset + first step [s]; "
            "cold: empty kernel cache, warm: cache loaded\n" + table([head, *rows]))
