"""The step rates of ``soccer-env bench``: Goalkeeper-v0 and a 6 vs 6 match against bare
pymunk, the cost of perceived observations, humanoids, the batched environments against single
ones (:func:`run_benchmarks`), and the camera-image renderers (:func:`bench_frames`)."""

from __future__ import annotations

import platform
import statistics
import time
from collections.abc import Callable
from functools import partial
from typing import Any

import gymnasium as gym
import numpy as np
import pymunk

import soccer_env  # noqa: F401  (registers the environments)
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_lab.bench.runners import (
    HUMANOID,
    HUMANOID_CAMERA,
    bare_rate,
    goalkeeper_runner,
    match_runner,
    median_rate,
    run_rate,
)

__all__ = ["PERCEIVED_PRESETS", "PIXELS_CASES", "REFERENCE", "bench_goalkeeper", "bench_match",
           "bench_perceived_cost", "bench_frames", "bench_pixels", "bench_batched",
           "run_benchmarks"]

#: Sensor presets timed with ``obs_mode="perceived"`` (default EKF), against truth.
PERCEIVED_PRESETS = ("realistic", "ssl-2012")

#: rSoccer (ODE, Gymnasium, ground truth only) on this kind of machine, for reference, and the
#: target step rates (about ten times rSoccer's).
REFERENCE = {
    "goalkeeper": {"rsoccer_task": "1-robot shooting task", "rsoccer_steps_per_s": 1700,
                   "target_steps_per_s": 15000},
    "match": {"rsoccer_task": "1 vs 6 task", "rsoccer_steps_per_s": 470,
              "target_steps_per_s": 3000},
}


def bench_goalkeeper(steps: int, repeats: int, seed: int = 0) -> dict[str, Any]:
    """Steps per second of Goalkeeper-v0 (truth) and of bare pymunk on the same bodies."""
    run, env = goalkeeper_runner(steps, seed)
    rate = median_rate(run, steps, repeats)
    return {"steps_per_s": rate, "robots": 1,
            "bare_pymunk_steps_per_s": bare_rate(env.unwrapped.world, steps, repeats)}


def bench_match(steps: int, repeats: int, seed: int = 0) -> dict[str, Any]:
    """Parallel steps per second of a 6 vs 6 Division B match (truth) and of bare pymunk."""
    run, env = match_runner(steps, seed=seed)
    rate = median_rate(run, steps, repeats)
    return {"steps_per_s": rate, "robots": 12, "field": "ssl-div-b",
            "bare_pymunk_steps_per_s": bare_rate(env.world, steps, repeats)}


def bench_perceived_cost(make_runner: Callable, steps: int, repeats: int,
                         preset: str | dict[str, Any]) -> dict[str, float]:
    """Cost of a perceived step relative to a truth step, timed in alternation (truth,
    perceived, truth, ...) so that the machine's drift cancels; the median of the pairs'
    ratios."""
    truth, _ = make_runner(steps)
    perceived, _ = make_runner(steps, obs_mode="perceived", perception=preset)
    ratios, rates = [], []
    for _ in range(repeats):
        t = run_rate(truth, steps)
        p = run_rate(perceived, steps)
        ratios.append(t / p)
        rates.append(p)
    return {"steps_per_s": statistics.median(rates), "cost_vs_truth": statistics.median(ratios)}


#: The environments timed by ``soccer-env bench --pixels``: the overhead pixels detector (each
#: camera's image rendered, then every robot and the ball found in it by mean-shift particle
#: filters) behind the default EKF: a keeper on the 2012 league's field under its one 25 Hz
#: camera, and a 6 vs 6 Division B match under four 60 Hz cameras. Each: the runner (with its
#: keyword arguments), whether it is a match, the ``perception``.
PIXELS_CASES = {
    "Goalkeeper-v0, ssl-2012 field and vision (1 camera)": (
        partial(goalkeeper_runner, field="ssl-2012"), False,
        {"vision": "ssl-2012", "detector": "pixels"}),
    "6 vs 6 Division B, realistic vision (4 cameras)": (
        match_runner, True, {"vision": "realistic", "detector": "pixels"}),
}


def bench_pixels(steps: int = 2000, match_steps: int = 200, repeats: int = 3
                 ) -> dict[str, dict[str, float]]:
    """Steps per second of the environments of :data:`PIXELS_CASES` and their cost against
    truth, timed in alternation (``soccer-env bench --pixels``; needs the ``pixels``
    extra)."""
    return {name: bench_perceived_cost(runner, match_steps if is_match else steps, repeats,
                                       perception)
            for name, (runner, is_match, perception) in PIXELS_CASES.items()}


def bench_frames(repeats: int = 200) -> dict[str, float]:
    """Milliseconds per frame of the camera-image renderers on a 6 vs 6 scene
    (``soccer-env bench --frames``; needs the ``pixels`` extra)."""
    from soccer_env import presets
    from soccer_env.presets.sensors import head_camera
    from soccer_env.sensors.images.head import HeadFrameRenderer
    from soccer_env.sensors.images.overhead import OverheadRenderer
    from soccer_env.state import HeadState, WorldState

    rng = np.random.default_rng(0)
    out = {}
    field = presets.field("ssl-div-b")
    n = 12
    teams = [0] * 6 + [1] * 6
    robots = np.column_stack([rng.uniform(-4, 4, n), rng.uniform(-2.8, 2.8, n),
                              rng.uniform(-3, 3, n), rng.uniform(-2, 2, (n, 2)),
                              rng.uniform(-3, 3, n)])
    state = WorldState(0.0, np.array([0.3, 0.2, 0.0, 4.0, 1.0, 0.0]), robots,
                       tuple(f"r{i}" for i in range(n)), np.array(teams))
    for name in ("clean", "realistic", "mirosot"):
        r = OverheadRenderer(name, field, presets.robot("ssl"), presets.ball("ssl"), teams)
        r.render(state, rng)
        t0 = time.perf_counter()
        for _ in range(repeats):
            r.render(state, rng)
        out[f"overhead {name} 640x480, 12 robots"] = (time.perf_counter() - t0) / repeats * 1e3
    hfield = presets.field("humanoid-kid")
    hrob = np.column_stack([rng.uniform(-4, 4, n), rng.uniform(-2.8, 2.8, n),
                            rng.uniform(-3, 3, n), np.zeros((n, 3))])
    hstate = WorldState(0.0, np.array([1.0, 0.2, 0.0, 0.0, 0.0, 0.0]), hrob, state.names,
                        np.array(teams))
    heads = HeadState.steady(n, 0.0, 0.3)
    for size in ((320, 240), (720, 625)):
        for name in ("clean", "realistic"):
            r = HeadFrameRenderer(head_camera("kidsize"), hfield, presets.robot("humanoid"),
                                  presets.ball("kidsize"), teams, name, size)
            r.render(hstate, heads, 0, rng)
            t0 = time.perf_counter()
            for _ in range(repeats):
                r.render(hstate, heads, 0, rng)
            out[f"head {name} {size[0]}x{size[1]}"] = (time.perf_counter() - t0) / repeats * 1e3
    return out


def bench_batched(batch: int, steps: int, repeats: int, seed: int = 0) -> dict[str, Any]:
    """Env-steps per second of the batched environments with ``batch`` environments in this
    process against their single counterparts, timed in alternation (the ratio is the median
    of the ratios within each repeat): Goalkeeper-v0 on truth
    (``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")`` against
    ``gymnasium.make``), and the 2 vs 2 match VecEnv with the scripted yellow team
    (``make_match_vec_env(..., batched=True)`` against one unbatched match). Random actions
    drawn beforehand; ``steps`` env-steps per timed run (at least 20 batched steps)."""
    from agents.vec.factories import make_match_vec_env

    rng = np.random.default_rng(seed)
    vec = gym.make_vec(GOALKEEPER_ID, num_envs=batch,
                       vectorization_mode="vector_entry_point")
    vec.reset(seed=seed)
    n_steps = max(20, steps // batch)
    keeper_actions = rng.uniform(-1, 1, (n_steps, batch, 6)).astype(np.float32)
    single, _ = goalkeeper_runner(steps, seed)

    def keeper_batch() -> None:
        for a in keeper_actions:
            vec.step(a)

    def match(n: int, batched: bool) -> tuple[Callable[[], None], int]:
        venv = make_match_vec_env({"blue": 2, "yellow": 2}, n, "blue", "scripted", seed=seed,
                                  batched=batched)
        venv.reset()
        k = max(20, steps // n) if batched else steps
        acts = rng.uniform(-1, 1, (k, venv.num_envs, 6)).astype(np.float32)

        def run() -> None:
            for a in acts:
                venv.step(a)

        return run, k * n

    match_single, match_single_steps = match(1, False)
    match_batch, match_batch_steps = match(batch, True)
    out: dict[str, Any] = {"batch": batch}
    for name, (one, one_steps), (many, many_steps) in (
            ("goalkeeper", (single, steps), (keeper_batch, n_steps * batch)),
            ("match_2v2_scripted", (match_single, match_single_steps),
             (match_batch, match_batch_steps))):
        ones, manys = [], []
        for _ in range(repeats):
            ones.append(run_rate(one, one_steps))
            manys.append(run_rate(many, many_steps))
        out[name] = {"single_env_steps_per_s": statistics.median(ones),
                     "batched_env_steps_per_s": statistics.median(manys),
                     "ratio": statistics.median(m / o for m, o in zip(manys, ones))}
    return out


def run_benchmarks(steps: int = 20000, match_steps: int = 5000, repeats: int = 3,
                   batch: int = 0) -> dict[str, Any]:
    """All figures of ``soccer-env bench`` as a dict (``batch > 0``: also
    :func:`bench_batched` with that many environments)."""
    gk = bench_goalkeeper(steps, repeats)
    match = bench_match(match_steps, repeats)
    for name, res in (("goalkeeper", gk), ("match", match)):
        res.update(REFERENCE[name])
        res["ratio_to_rsoccer"] = res["steps_per_s"] / res["rsoccer_steps_per_s"]
        res["ratio_to_bare_pymunk"] = res["steps_per_s"] / res["bare_pymunk_steps_per_s"]
    perceived = {}
    for preset in PERCEIVED_PRESETS:
        g = bench_perceived_cost(goalkeeper_runner, steps // 2, repeats, preset)
        m = bench_perceived_cost(match_runner, match_steps // 2, repeats, preset)
        perceived[preset] = {
            "goalkeeper_steps_per_s": g["steps_per_s"],
            "goalkeeper_cost_vs_truth": g["cost_vs_truth"],
            "match_steps_per_s": m["steps_per_s"],
            "match_cost_vs_truth": m["cost_vs_truth"],
        }
    humanoid = {}
    for name, make in (("goalkeeper", goalkeeper_runner),
                       ("match", lambda n, **kw: match_runner(n, blue=3, yellow=3, **kw))):
        n = (steps if name == "goalkeeper" else match_steps) // 10
        truth, _ = make(n, robot=HUMANOID)
        r = bench_perceived_cost(lambda k, make=make, **kw: make(k, robot=HUMANOID, **kw), n,
                                 repeats, HUMANOID_CAMERA)
        humanoid[name] = {"truth_steps_per_s": median_rate(truth, n, repeats),
                          "perceived_steps_per_s": r["steps_per_s"],
                          "cost_vs_truth": r["cost_vs_truth"]}
    batched = bench_batched(batch, steps, repeats) if batch else None
    return {
        **({"batched": batched} if batched else {}),
        "goalkeeper": gk,
        "match_6v6_div_b": match,
        "perceived": perceived,
        "humanoid": {"robot": HUMANOID, "camera": HUMANOID_CAMERA, **humanoid},
        "settings": {"steps": steps, "match_steps": match_steps, "repeats": repeats,
                     "statistic": "median of repeats; perceived cost: median ratio of "
                                  "alternating truth/perceived runs"},
        "machine": {"python": platform.python_version(), "pymunk": pymunk.version,
                    "numpy": np.__version__, "processor": platform.machine()},
    }
