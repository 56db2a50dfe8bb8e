"""The compiled kernels' disk cache: a new process (a test worker, an evaluation pool's
worker) loads what another compiled, and a read-only install without a cache location still
runs."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from estimators.particle.filter_kernels import drift, weigh
from estimators.particle.localization_kernels import best_log_likelihood

ROOT = Path(__file__).resolve().parents[1]

_CALL_KERNELS = """
import json
import numpy as np
from estimators.particle.filter_kernels import drift, weigh
from estimators.particle.localization_kernels import best_log_likelihood
drift(np.zeros((3, 4)), 0.1, 0.2)
weigh(np.full(3, 1 / 3), np.ones(3))
best_log_likelihood(np.zeros((2, 3)), np.ones(2), np.ones(2), np.array([1, 1]),
                    np.ones(2), np.zeros(2), (0.05, 0.05, 0.0), 0.1)
kernels = (drift, weigh, best_log_likelihood)
print(json.dumps([sum(k.stats.cache_hits.values()) for k in kernels]
                 + [sum(k.stats.cache_misses.values()) for k in kernels]))
"""


def _run(code: str, **env: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=300, cwd=ROOT,
                          env={**os.environ, "PYTHONPATH": str(ROOT), **env})


def test_a_new_process_loads_the_kernels_instead_of_compiling_them():
    # This process has the kernels (compiled and saved, or loaded); a new one loads them.
    drift(np.zeros((3, 4)), 0.1, 0.2)
    weigh(np.full(3, 1 / 3), np.ones(3))
    best_log_likelihood(np.zeros((2, 3)), np.ones(2), np.ones(2), np.array([1, 1]),
                        np.ones(2), np.zeros(2), (0.05, 0.05, 0.0), 0.1)
    out = _run(_CALL_KERNELS)
    assert out.returncode == 0, out.stderr
    counts = json.loads(out.stdout.strip().splitlines()[-1])
    assert counts == [1, 1, 1, 0, 0, 0]  # one cache hit each, nothing compiled


def test_without_a_cache_location_the_package_still_imports_and_runs():
    # Numba's cache locators restricted to one that never applies to a plain file: what a
    # read-only install without a writable user cache directory looks like to numba.
    code = """
import gymnasium as gym
import soccer_env
env = gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived", perception="ssl-2012")
env.reset(seed=0)
for _ in range(5):
    env.step(env.action_space.sample())
print("stepped")
"""
    out = _run(code, NUMBA_CACHE_LOCATOR_CLASSES="ZipCacheLocator")
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().endswith("stepped")
