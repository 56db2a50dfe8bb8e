"""Step-rate benchmarks: the environments against bare pymunk stepping the same bodies.

Run ``soccer-env bench`` (or ``python benchmarks/bench_step.py``). Each figure is the median of
``repeats`` timed runs, each of ``steps`` steps with actions drawn beforehand from a seeded
generator (sampling is not timed); Goalkeeper-v0 runs through ``gymnasium.make`` with its
default wrappers and includes its resets, as a training loop would.
"""

from __future__ import annotations

import json
import platform
import statistics
import time
from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pymunk

__all__ = ["run_benchmarks", "format_table", "REFERENCE", "PERCEIVED_PRESETS"]

#: Sensor presets timed with ``obs_mode="perceived"`` (default EKF), against truth.
PERCEIVED_PRESETS = ("realistic", "ssl-2012")

#: rSoccer (ODE, Gymnasium, ground truth only) on this kind of machine, for reference, and the
#: aims of the foundation issue (ten times rSoccer).
REFERENCE = {
    "goalkeeper": {"rsoccer_task": "1-robot shooting task", "rsoccer_steps_per_s": 1700,
                   "aim_steps_per_s": 15000},
    "match": {"rsoccer_task": "1 vs 6 task", "rsoccer_steps_per_s": 470,
              "aim_steps_per_s": 3000},
}


def _median_rate(run: Callable[[], None], steps: int, repeats: int) -> float:
    rates = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        run()
        rates.append(steps / (time.perf_counter() - t0))
    return statistics.median(rates)


def bench_goalkeeper(steps: int, repeats: int, seed: int = 0, obs_mode: str = "truth",
                     perception: str | None = None) -> dict[str, Any]:
    """Steps per second of ``gymnasium.make("soccer_env/Goalkeeper-v0")``, random actions."""
    env = gym.make("soccer_env/Goalkeeper-v0", obs_mode=obs_mode, perception=perception)
    actions = np.random.default_rng(seed).uniform(-1, 1, (steps, 6)).astype(np.float32)
    env.reset(seed=seed)
    episodes = [0]

    def run() -> None:
        for a in actions:
            _, _, term, trunc, _ = env.step(a)
            if term or trunc:
                env.reset()
                episodes[0] += 1

    rate = _median_rate(run, steps, repeats)
    world = env.unwrapped.world
    bare = _bare_rate(world, steps, repeats)
    return {"steps_per_s": rate, "bare_pymunk_steps_per_s": bare,
            "episodes_per_run": episodes[0] / repeats, "robots": 1}


def bench_match(steps: int, repeats: int, blue: int = 6, yellow: int = 6,
                field: str = "ssl-div-b", seed: int = 0, obs_mode: str = "truth",
                perception: str | None = None) -> dict[str, Any]:
    """Parallel steps per second of ``soccer_env.parallel_env``, random actions."""
    from . import parallel_env

    env = parallel_env(blue=blue, yellow=yellow, field=field, match_duration=1e6,
                       obs_mode=obs_mode, perception=perception)
    env.reset(seed=seed)
    agents = list(env.agents)
    actions = np.random.default_rng(seed).uniform(-1, 1, (steps, len(agents), 6))
    dicts = [dict(zip(agents, a)) for a in actions]

    def run() -> None:
        for d in dicts:
            env.step(d)

    rate = _median_rate(run, steps, repeats)
    bare = _bare_rate(env.world, steps, repeats)
    return {"steps_per_s": rate, "bare_pymunk_steps_per_s": bare, "robots": blue + yellow,
            "field": field}


def _bare_rate(world, steps: int, repeats: int) -> float:
    """Control steps per second of ``pymunk.Space.step`` alone on the world's own space (same
    bodies, joints and substeps), robots driving at constant commands, no Python logic."""
    rng = np.random.default_rng(1)
    n = world.n_robots
    poses = np.column_stack([rng.uniform(-3, 3, n), rng.uniform(-2, 2, n), np.zeros(n)])
    world.reset(poses, (0.0, 0.0))
    for control in world._controls:
        control.velocity = tuple(rng.uniform(-2, 2, 2))
    world.set_ball(0.0, 0.0, 3.0, 1.0)
    space, h, k = world.space, world.substep_dt, world.n_substeps

    def run() -> None:
        for _ in range(steps):
            for _ in range(k):
                space.step(h)

    return _median_rate(run, steps, repeats)


def run_benchmarks(steps: int = 20000, match_steps: int = 5000, repeats: int = 3
                   ) -> dict[str, Any]:
    """All figures of ``soccer-env bench`` as a dict."""
    gk = bench_goalkeeper(steps, repeats)
    match = bench_match(match_steps, repeats)
    for name, res in (("goalkeeper", gk), ("match", match)):
        res.update(REFERENCE[name])
        res["ratio_to_rsoccer"] = res["steps_per_s"] / res["rsoccer_steps_per_s"]
        res["ratio_to_bare_pymunk"] = res["steps_per_s"] / res["bare_pymunk_steps_per_s"]
    perceived = {}
    for preset in PERCEIVED_PRESETS:
        g = bench_goalkeeper(steps // 2, repeats, obs_mode="perceived", perception=preset)
        m = bench_match(match_steps // 2, repeats, obs_mode="perceived", perception=preset)
        perceived[preset] = {
            "goalkeeper_steps_per_s": g["steps_per_s"],
            "goalkeeper_cost_vs_truth": gk["steps_per_s"] / g["steps_per_s"],
            "match_steps_per_s": m["steps_per_s"],
            "match_cost_vs_truth": match["steps_per_s"] / m["steps_per_s"],
        }
    return {
        "goalkeeper": gk,
        "match_6v6_div_b": match,
        "perceived": perceived,
        "settings": {"steps": steps, "match_steps": match_steps, "repeats": repeats,
                     "statistic": "median of repeats"},
        "machine": {"python": platform.python_version(), "pymunk": pymunk.version,
                    "numpy": np.__version__, "processor": platform.machine()},
    }


def format_table(res: dict[str, Any]) -> str:
    """A plain-text table of :func:`run_benchmarks` results."""
    rows = [("task", "steps/s", "bare pymunk", "env/bare", "rSoccer ref", "x rSoccer", "aim")]
    for key, label in (("goalkeeper", "Goalkeeper-v0 (1 robot)"),
                       ("match_6v6_div_b", "match 6 vs 6, Div B")):
        r = res[key]
        rows.append((label, f"{r['steps_per_s']:,.0f}", f"{r['bare_pymunk_steps_per_s']:,.0f}",
                     f"{r['ratio_to_bare_pymunk']:.2f}", f"{r['rsoccer_steps_per_s']:,}",
                     f"{r['ratio_to_rsoccer']:.1f}", f"{r['aim_steps_per_s']:,}"))
    text = _table(rows)
    if res.get("perceived"):
        rows = [("obs_mode='perceived'", "Goalkeeper steps/s", "cost vs truth",
                 "6v6 steps/s", "cost vs truth")]
        for preset, r in res["perceived"].items():
            rows.append((f"perception={preset!r}", f"{r['goalkeeper_steps_per_s']:,.0f}",
                         f"{r['goalkeeper_cost_vs_truth']:.2f}", f"{r['match_steps_per_s']:,.0f}",
                         f"{r['match_cost_vs_truth']:.2f}"))
        text += "\n\n" + _table(rows)
    return text


def _table(rows: list[tuple[str, ...]]) -> str:
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in
                       enumerate(zip(row, widths))) for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``soccer-env bench``."""
    import argparse

    p = argparse.ArgumentParser(prog="soccer-env bench", description=__doc__.split("\n\n")[0])
    p.add_argument("--json", action="store_true", help="print the results as JSON")
    p.add_argument("--steps", type=int, default=20000, help="Goalkeeper steps per run")
    p.add_argument("--match-steps", type=int, default=5000, help="match steps per run")
    p.add_argument("--repeats", type=int, default=3, help="timed runs per figure (median)")
    args = p.parse_args(argv)
    for name in ("steps", "match_steps", "repeats"):
        if getattr(args, name) < 1:
            p.error(f"--{name.replace('_', '-')} must be >= 1")
    res = run_benchmarks(args.steps, args.match_steps, args.repeats)
    print(json.dumps(res, indent=2) if args.json else format_table(res))
    return 0
