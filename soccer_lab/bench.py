"""The benchmarks: step rates (``soccer-env bench``), the keepers' save rates and the rollout
collection rate of training.

**Step rates**: the environments against bare pymunk stepping the same bodies. Run
``soccer-env bench`` (or ``python benchmarks/bench_step.py``). Each figure is the median of
``repeats`` timed runs, each of ``steps`` steps with actions drawn beforehand from a seeded
generator (sampling is not timed); Goalkeeper-v0 runs through ``gymnasium.make`` with its
default wrappers and includes its resets, as a training loop would. The cost of perceived
observations is the median ratio of truth and perceived runs timed in alternation. With
``--batch N`` it also times the batched Goalkeeper-v0 and the batched 2 vs 2 match VecEnv
against single environments (:func:`bench_batched`).

Humanoids (Xu et al.'s 2012 ``humanoid-2012`` with its ``kidsize-2012`` head camera): the keeper
with its three watching team-mates (four robots, each with its camera, localization, radio,
fusion and tracker when perceived) and a 3 vs 3 match; their random actions neither kick nor
dive (a robot that dives at random lies blind most of the time, which would understate the
perception's cost).

**Save rates** (:func:`keeper_save_rates`, ``python benchmarks/keeper_save_rate.py``): the
scripted keeper and a keeper that stands still on Goalkeeper-v0's seeded shots
(:func:`agents.runs.evaluation.evaluate`).

**Rollout rates** (:func:`rollout_rate`, ``python benchmarks/rollout_rate.py``): environment
steps per second while stable-baselines3's PPO collects rollouts, in
:class:`~agents.vec.workers.WorkerVecEnv` against stable-baselines3's own vectorised environments.
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

import soccer_env  # noqa: F401  (registers the environments)
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["run_benchmarks", "bench_batched", "bench_frames", "format_table", "REFERENCE",
           "PERCEIVED_PRESETS", "parser", "main", "keeper_save_rates", "format_save_rates",
           "save_rate_main", "ROLLOUT_CONFIGS", "rollout_rate", "rollout_rates",
           "format_rollout_rates", "rollout_main"]

#: Sensor presets timed with ``obs_mode="perceived"`` (default EKF), against truth.
PERCEIVED_PRESETS = ("realistic", "ssl-2012")
#: The humanoid robot and head camera timed by ``soccer-env bench``.
HUMANOID, HUMANOID_CAMERA = "humanoid-2012", "kidsize-2012"

#: rSoccer (ODE, Gymnasium, ground truth only) on this kind of machine, for reference, and the
#: target step rates (about ten times rSoccer's).
REFERENCE = {
    "goalkeeper": {"rsoccer_task": "1-robot shooting task", "rsoccer_steps_per_s": 1700,
                   "target_steps_per_s": 15000},
    "match": {"rsoccer_task": "1 vs 6 task", "rsoccer_steps_per_s": 470,
              "target_steps_per_s": 3000},
}


def memory_per_item(prelude: str, build: str, n: int) -> float:
    """Bytes of resident memory per item that ``build`` (Python source making ``n`` items)
    adds in a fresh interpreter, after ``prelude`` (imports, and a small warm-up build so that
    imports and first-use caches are not counted): the growth of the process's resident set
    (``/proc/self/statm``) divided by ``n``."""
    import subprocess
    import sys

    code = (f"{prelude}\n"
            "def _rss():\n"
            "    return int(open('/proc/self/statm').read().split()[1]) * 4096\n"
            "_before = _rss()\n"
            f"{build}\n"
            f"print((_rss() - _before) / {n})\n")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True).stdout
    return float(out.strip().splitlines()[-1])


def _rate(run: Callable[[], None], steps: int) -> float:
    t0 = time.perf_counter()
    run()
    return steps / (time.perf_counter() - t0)


def _median_rate(run: Callable[[], None], steps: int, repeats: int) -> float:
    return statistics.median(_rate(run, steps) for _ in range(repeats))


def _actions(rng: np.random.Generator, shape: tuple[int, ...], robot: str) -> np.ndarray:
    """Uniform random actions; a humanoid's motion entry (kick, dive) zeroed."""
    a = rng.uniform(-1, 1, (*shape, 6))
    if robot.startswith("humanoid"):
        a[..., 3] = 0.0
    return a


def _goalkeeper_runner(steps: int, seed: int = 0, obs_mode: str = "truth",
                       perception: str | None = None, robot: str = "ssl"):
    """A closure stepping ``gymnasium.make("soccer_env/Goalkeeper-v0")`` ``steps`` times with
    pre-drawn random actions (resetting when episodes end), and its environment."""
    env = gym.make(GOALKEEPER_ID, obs_mode=obs_mode, perception=perception,
                   robot=robot)
    actions = _actions(np.random.default_rng(seed), (steps,), robot).astype(np.float32)
    env.reset(seed=seed)

    def run() -> None:
        for a in actions:
            _, _, term, trunc, _ = env.step(a)
            if term or trunc:
                env.reset()

    return run, env


def _match_runner(steps: int, blue: int = 6, yellow: int = 6, field: str | None = None,
                  seed: int = 0, obs_mode: str = "truth", perception: str | None = None,
                  robot: str = "ssl"):
    """A closure stepping a match ``steps`` times with pre-drawn random actions."""
    from soccer_env import parallel_env

    env = parallel_env(blue=blue, yellow=yellow, field=field, match_duration=1e6,
                       obs_mode=obs_mode, perception=perception, robot=robot)
    env.reset(seed=seed)
    agents = list(env.agents)
    actions = _actions(np.random.default_rng(seed), (steps, len(agents)), robot)
    dicts = [dict(zip(agents, a)) for a in actions]

    def run() -> None:
        for d in dicts:
            env.step(d)

    return run, env


def bench_goalkeeper(steps: int, repeats: int, seed: int = 0) -> dict[str, Any]:
    """Steps per second of Goalkeeper-v0 (truth) and of bare pymunk on the same bodies."""
    run, env = _goalkeeper_runner(steps, seed)
    rate = _median_rate(run, steps, repeats)
    return {"steps_per_s": rate, "robots": 1,
            "bare_pymunk_steps_per_s": _bare_rate(env.unwrapped.world, steps, repeats)}


def bench_match(steps: int, repeats: int, seed: int = 0) -> dict[str, Any]:
    """Parallel steps per second of a 6 vs 6 Division B match (truth) and of bare pymunk."""
    run, env = _match_runner(steps, seed=seed)
    rate = _median_rate(run, steps, repeats)
    return {"steps_per_s": rate, "robots": 12, "field": "ssl-div-b",
            "bare_pymunk_steps_per_s": _bare_rate(env.world, steps, repeats)}


def bench_perceived_cost(make_runner: Callable, steps: int, repeats: int, preset: str
                         ) -> dict[str, float]:
    """Cost of a perceived step relative to a truth step, timed in alternation (truth,
    perceived, truth, ...) so that the machine's drift cancels; the median of the pairs'
    ratios."""
    truth, _ = make_runner(steps)
    perceived, _ = make_runner(steps, obs_mode="perceived", perception=preset)
    ratios, rates = [], []
    for _ in range(repeats):
        t = _rate(truth, steps)
        p = _rate(perceived, steps)
        ratios.append(t / p)
        rates.append(p)
    return {"steps_per_s": statistics.median(rates), "cost_vs_truth": statistics.median(ratios)}


def _bare_rate(world, steps: int, repeats: int) -> float:
    """Control steps per second of ``pymunk.Space.step`` alone on the world's own space (same
    bodies, joints and substeps), robots driving at constant commands, no Python logic."""
    rng = np.random.default_rng(1)
    n = world.n_robots
    poses = np.column_stack([rng.uniform(-3, 3, n), rng.uniform(-2, 2, n), np.zeros(n)])
    world.reset(poses, (0.0, 0.0))
    commands = np.zeros((n, 6))
    commands[:, 0:2] = rng.uniform(-2, 2, (n, 2))
    world.step(commands)  # the drives take these velocities; the bare loop keeps them
    world.set_ball(0.0, 0.0, 3.0, 1.0)
    space, h, k = world.space, world.substep_dt, world.n_substeps

    def run() -> None:
        for _ in range(steps):
            for _ in range(k):
                space.step(h)

    return _median_rate(run, steps, repeats)


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
    single, _ = _goalkeeper_runner(steps, seed)

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
            ones.append(_rate(one, one_steps))
            manys.append(_rate(many, many_steps))
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
        g = bench_perceived_cost(_goalkeeper_runner, steps // 2, repeats, preset)
        m = bench_perceived_cost(_match_runner, match_steps // 2, repeats, preset)
        perceived[preset] = {
            "goalkeeper_steps_per_s": g["steps_per_s"],
            "goalkeeper_cost_vs_truth": g["cost_vs_truth"],
            "match_steps_per_s": m["steps_per_s"],
            "match_cost_vs_truth": m["cost_vs_truth"],
        }
    humanoid = {}
    for name, make in (("goalkeeper", _goalkeeper_runner),
                       ("match", lambda n, **kw: _match_runner(n, blue=3, yellow=3, **kw))):
        n = (steps if name == "goalkeeper" else match_steps) // 10
        truth, _ = make(n, robot=HUMANOID)
        r = bench_perceived_cost(lambda k, make=make, **kw: make(k, robot=HUMANOID, **kw), n,
                                 repeats, HUMANOID_CAMERA)
        humanoid[name] = {"truth_steps_per_s": _median_rate(truth, n, repeats),
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
    make = _goalkeeper_runner if kind == "goalkeeper" else _match_runner
    run, _ = make(steps, seed=seed, obs_mode="perceived", perception=preset, robot=robot)
    rate = _rate(run, steps)
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
    return head + "\n" + _table(rows)


def _short_path(name: str) -> str:
    """A profiled function's ``path:line(name)`` from its package on (an installed
    library's from below ``site-packages``)."""
    for root in ("/site-packages/", "/soccer_env/", "/estimators/", "/agents/"):
        head, sep, tail = name.partition(root)
        if sep:
            return tail if root == "/site-packages/" else root[1:] + tail
    return name


def format_table(res: dict[str, Any]) -> str:
    """A plain-text table of :func:`run_benchmarks` results."""
    rows = [("task", "steps/s", "bare pymunk", "env/bare", "rSoccer ref", "x rSoccer",
             "target")]
    for key, label in (("goalkeeper", "Goalkeeper-v0 (1 robot)"),
                       ("match_6v6_div_b", "match 6 vs 6, Div B")):
        r = res[key]
        rows.append((label, f"{r['steps_per_s']:,.0f}", f"{r['bare_pymunk_steps_per_s']:,.0f}",
                     f"{r['ratio_to_bare_pymunk']:.2f}", f"{r['rsoccer_steps_per_s']:,}",
                     f"{r['ratio_to_rsoccer']:.1f}", f"{r['target_steps_per_s']:,}"))
    text = _table(rows)
    if res.get("perceived"):
        rows = [("obs_mode='perceived'", "Goalkeeper steps/s", "cost vs truth",
                 "6v6 steps/s", "cost vs truth")]
        for preset, r in res["perceived"].items():
            rows.append((f"perception={preset!r}", f"{r['goalkeeper_steps_per_s']:,.0f}",
                         f"{r['goalkeeper_cost_vs_truth']:.2f}", f"{r['match_steps_per_s']:,.0f}",
                         f"{r['match_cost_vs_truth']:.2f}"))
        text += "\n\n" + _table(rows)
    if res.get("humanoid"):
        h = res["humanoid"]
        text += "\n\n" + _table(_rows(
            h, (f"humanoids ({h['robot']}, camera {h['camera']})", "truth steps/s",
                "perceived steps/s", "cost vs truth"),
            (("goalkeeper", "Goalkeeper-v0 + 3 team-mates (4 robots)"),
             ("match", "match 3 vs 3")),
            (("truth_steps_per_s", ",.0f"), ("perceived_steps_per_s", ",.0f"),
             ("cost_vs_truth", ".2f"))))
    if res.get("batched"):
        b = res["batched"]
        text += "\n\n" + _table(_rows(
            b, (f"batched ({b['batch']} environments, one process)", "single env-steps/s",
                "batched env-steps/s", "ratio"),
            (("goalkeeper", "Goalkeeper-v0, truth"),
             ("match_2v2_scripted", "match 2 vs 2 VecEnv, scripted yellow")),
            (("single_env_steps_per_s", ",.0f"), ("batched_env_steps_per_s", ",.0f"),
             ("ratio", ".2f"))))
    return text


def _rows(block: dict[str, Any], head: tuple[str, ...], cases: tuple[tuple[str, str], ...],
          fields: tuple[tuple[str, str], ...]) -> list[tuple[str, ...]]:
    """A table's rows: ``head``, then per ``(key, label)`` of ``cases`` the label and
    ``block[key]``'s ``fields`` (``(name, format spec)``)."""
    return [head] + [(label, *(format(block[key][name], spec) for name, spec in fields))
                     for key, label in cases]


def _table(rows: list[tuple[str, ...]]) -> str:
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in
                       enumerate(zip(row, widths))) for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def parser() -> Any:
    """The options of ``soccer-env bench`` (an ``argparse.ArgumentParser``)."""
    import argparse

    from soccer_lab.cli_args import HelpFormatter, sensor_preset, sensor_presets_help

    p = argparse.ArgumentParser(
        prog="soccer-env bench", formatter_class=HelpFormatter,
        description="Step rates of the environments against bare pymunk stepping the same "
                    "bodies: Goalkeeper-v0 and a 6 vs 6 match on truth, the cost of "
                    "perceived observations, humanoids; each figure the median of the timed "
                    "runs.",
        epilog="examples:\n"
               "  soccer-env bench --batch 128               # also the batched environments\n"
               "  soccer-env bench --frames                  # camera-image renderers (pixels "
               "extra)\n"
               "  soccer-env bench --profile humanoid-goalkeeper")
    p.add_argument("--json", action="store_true", help="print the results as JSON")
    p.add_argument("--steps", type=int, default=20000,
                   help="Goalkeeper-v0 steps per timed run")
    p.add_argument("--match-steps", type=int, default=5000, help="match steps per timed run")
    p.add_argument("--repeats", type=int, default=3, help="timed runs per figure (the median)")
    p.add_argument("--batch", type=int, default=0, metavar="N",
                   help="also time the batched Goalkeeper-v0 and 2 vs 2 match VecEnv with N "
                        "environments in this process against single ones (0: skip; needs "
                        "the train extra)")
    p.add_argument("--frames", action="store_true",
                   help="time the camera-image renderers instead (needs the pixels extra)")
    p.add_argument("--profile", choices=sorted(PROFILE_CASES), default=None,
                   help="profile a perceived step of this case instead (cProfile: the top "
                        "functions by own time per step)")
    p.add_argument("--perception", type=sensor_preset, default=None, metavar="PRESET",
                   help=f"with --profile: the sensor preset ({sensor_presets_help()}) "
                        f"(default: {PROFILE_CASES['goalkeeper'][2]}, or "
                        f"{HUMANOID_CAMERA} for humanoids)")
    p.add_argument("--top", type=int, default=25,
                   help="with --profile: how many functions to list")
    return p


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``soccer-env bench``."""
    from soccer_lab import extras

    p = parser()
    args = p.parse_args(argv)
    for name in ("steps", "match_steps", "repeats"):
        if getattr(args, name) < 1:
            p.error(f"--{name.replace('_', '-')} must be >= 1, got {getattr(args, name)}")
    if not 0 <= args.batch <= 65536:
        p.error(f"--batch must be in 0..65536, got {args.batch}")
    if args.top < 1:
        p.error(f"--top must be >= 1, got {args.top}")
    extras.require("bench")
    # What runs: --profile, else --frames, else the step rates (with --batch, batched too).
    if args.frames and not args.profile:
        extras.require("bench --frames")
    elif args.batch and not args.profile:
        extras.require("bench --batch", f"bench --batch {args.batch}")
    if args.profile:
        steps = args.steps if args.profile.endswith("goalkeeper") else args.match_steps
        try:
            prof = profile_perceived(args.profile, args.perception, min(steps, 5000),
                                     args.top)
        except (KeyError, ValueError) as why:
            p.error(str(why))
        print(json.dumps(prof, indent=2) if args.json else format_profile(prof))
        return 0
    if args.frames:
        ms = bench_frames()
        print(json.dumps(ms, indent=2) if args.json else
              "\n".join(f"{key}: {v:.2f} ms" for key, v in ms.items()))
        return 0
    res = run_benchmarks(args.steps, args.match_steps, args.repeats, args.batch)
    print(json.dumps(res, indent=2) if args.json else format_table(res))
    return 0


# ------------------------------------------------------------------------------------------
# Keepers' save rates
# ------------------------------------------------------------------------------------------

def keeper_save_rates(episodes: int = 300, field: str = "ssl-div-b", workers: int | None = None,
                      policies: tuple[str, ...] = ("scripted", "idle")) -> dict[str, Any]:
    """The evaluation (:class:`~agents.runs.evaluation.EvalResult`) of each of ``policies`` on
    Goalkeeper-v0's shots of seeds ``0 .. episodes - 1`` on ``field``, truth observations, in
    ``workers`` processes (default: all cores; the result does not depend on it)."""
    import os

    from agents.runs.evaluation import evaluate

    workers = workers or os.cpu_count() or 1
    return {name: evaluate(name, {"field": field}, episodes, workers=workers)
            for name in policies}


def format_save_rates(results: dict[str, Any]) -> str:
    """One line per policy: save rate, Wilson 95 % interval and outcomes (commonest first)."""
    lines = []
    for name, res in results.items():
        outcomes = dict(sorted(res.outcomes.items(), key=lambda kv: (-kv[1], kv[0])))
        lines.append(f"{name:9s} save rate {res.save_rate:6.1%} (95 % CI {res.ci_low:.1%}-"
                     f"{res.ci_high:.1%}) over {res.episodes} shots: {outcomes}")
    return "\n".join(lines)


def save_rate_main(argv: list[str] | None = None) -> int:
    """Entry point of ``benchmarks/keeper_save_rate.py``."""
    import argparse
    import os

    from soccer_env.presets import FIELDS
    from soccer_lab.cli_args import HelpFormatter

    p = argparse.ArgumentParser(description="Save rate of the scripted keeper and of a keeper "
                                            "that stands still on Goalkeeper-v0.",
                                formatter_class=HelpFormatter)
    p.add_argument("--episodes", type=int, default=300, help="shots, seeds 0 onwards")
    p.add_argument("--field", default="ssl-div-b", choices=list(FIELDS), help="field preset")
    p.add_argument("--workers", type=int, default=None,
                   help="processes; the result does not depend on it (default: all cores)")
    args = p.parse_args(argv)
    workers = (os.cpu_count() or 1) if args.workers is None else args.workers
    if args.episodes < 1 or workers < 1:
        p.error("--episodes and --workers must be >= 1")
    print(format_save_rates(keeper_save_rates(args.episodes, args.field, workers)))
    return 0


# ------------------------------------------------------------------------------------------
# Rollout collection rate
# ------------------------------------------------------------------------------------------

#: Vectorised environments compared by :func:`rollout_rates`: 16 environments in 2
#: :class:`~agents.vec.workers.WorkerVecEnv` processes (what ``soccer-env train`` uses), and
#: stable-baselines3's ``SubprocVecEnv`` and ``DummyVecEnv`` with 2 environments.
ROLLOUT_CONFIGS = ("worker-16x2", "subproc-2", "dummy-2")


def _rollout_venv(name: str, env_kwargs: dict[str, Any]) -> Any:
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    from agents.vec.factories import goalkeeper_env_fn
    from agents.vec.workers import WorkerVecEnv

    if name == "worker-16x2":
        return WorkerVecEnv([goalkeeper_env_fn(env_kwargs) for _ in range(16)], n_workers=2)
    if name == "subproc-2":
        return SubprocVecEnv([goalkeeper_env_fn(env_kwargs) for _ in range(2)])
    return DummyVecEnv([goalkeeper_env_fn(env_kwargs) for _ in range(2)])


def rollout_rate(name: str, env_kwargs: dict[str, Any], steps: int, seed: int = 0) -> float:
    """Steps per second spent collecting rollouts while PPO (default MLP policy, ``n_steps *
    n_envs`` about 4096 per rollout) trains ``steps`` steps on Goalkeeper-v0 in the
    vectorised environment ``name`` of :data:`ROLLOUT_CONFIGS`."""
    import torch
    from stable_baselines3 import PPO

    from agents.sb3.callbacks import rollout_timer

    torch.set_num_threads(1)
    venv = _rollout_venv(name, env_kwargs)
    venv.seed(seed)
    try:
        n_steps = max(64, 4096 // venv.num_envs)
        model = PPO("MlpPolicy", venv, n_steps=n_steps, batch_size=512, seed=seed,
                    device="cpu")
        timer = rollout_timer()
        model.learn(steps, callback=timer)
    finally:
        venv.close()
    return timer.rate


def rollout_rates(env_kwargs: dict[str, Any], steps: int, repeats: int
                  ) -> dict[str, list[float]]:
    """:func:`rollout_rate` of every configuration, ``repeats`` times in alternation (seed
    ``r`` in round ``r``), so that the machine's drift cancels in their ratios."""
    rates: dict[str, list[float]] = {c: [] for c in ROLLOUT_CONFIGS}
    for r in range(repeats):
        for name in ROLLOUT_CONFIGS:
            rates[name].append(rollout_rate(name, env_kwargs, steps, seed=r))
    return rates


def format_rollout_rates(rates: dict[str, list[float]], env_kwargs: dict[str, Any]) -> str:
    """The median rate of each configuration, its range and its ratio to ``dummy-2``."""
    base = statistics.median(rates["dummy-2"])
    lines = [f"Goalkeeper-v0 {env_kwargs}, PPO rollouts, median of "
             f"{len(rates['dummy-2'])}:"]
    for name in ROLLOUT_CONFIGS:
        med = statistics.median(rates[name])
        spread = f"{min(rates[name]):,.0f}-{max(rates[name]):,.0f}"
        lines.append(f"  {name:12s} {med:8,.0f} steps/s ({spread})  x{med / base:.2f} vs "
                     "dummy-2")
    return "\n".join(lines)


def rollout_main(argv: list[str] | None = None) -> int:
    """Entry point of ``benchmarks/rollout_rate.py``."""
    import argparse

    from soccer_env.presets import VISION
    from soccer_lab.cli_args import HelpFormatter

    p = argparse.ArgumentParser(description="PPO rollout collection rate on Goalkeeper-v0: "
                                            "environment steps per second while "
                                            "stable-baselines3 collects rollouts (policy "
                                            "forward passes included, gradient updates "
                                            "excluded).",
                                formatter_class=HelpFormatter)
    p.add_argument("--obs-mode", default="perceived", choices=("truth", "raw", "perceived"),
                   help="observation mode")
    p.add_argument("--perception", default="ssl-2012", choices=list(VISION),
                   help="SSL vision preset")
    p.add_argument("--steps", type=int, default=40_000,
                   help="environment steps per timed training run, >= 4096")
    p.add_argument("--repeats", type=int, default=3,
                   help="timed runs per configuration, in alternation")
    args = p.parse_args(argv)
    if args.steps < 4096 or args.repeats < 1:
        p.error("--steps must be >= 4096 and --repeats >= 1")
    env_kwargs = {"obs_mode": args.obs_mode, "perception": args.perception}
    rates = rollout_rates(env_kwargs, args.steps, args.repeats)
    print(format_rollout_rates(rates, env_kwargs))
    return 0
