"""Batched matches against VMAS football on the CPU: env-steps per second for batch sizes 1 to
1,024, in one and two processes, ours and VMAS's from one run; and memory per match.

Usage: ``python benchmarks/batched_match.py [--size 2] [--batches 1 16 64 128 256 512 1024]
[--target 40000] [--rounds 3] [--vmas-python PATH] [--memory 1000] [--obs-mode truth]
[--perception P] [--json FILE]``.

Ours: ``N`` vs ``N`` SSL robots on truth observations (``--size``, default 2 vs 2; or
``--obs-mode`` and ``--perception``), the blue
team learning, the yellow team the scripted opponent, as
:func:`agents.vec.factories.make_match_vec_env` steps them for training with ``batched=True``:
``1 process`` is every match in one batch in this process, ``2 processes`` the matches
split over two worker processes (each stepping its half as one batch, pinned to its CPU).
``unbatched 1`` is one match stepped alone (:class:`~agents.vec.match.MatchVecEnv`), the
single-environment rate. Learner actions are uniform random, made before the clock starts.

VMAS (``--vmas-python``, a Python with ``vmas`` and torch installed: ``pip install
torch==2.13.0 vmas``): its ``football`` scenario at the same team size and batch sizes, blue
random actions against its scripted red AI (``benchmarks/vmas_football.py``), with torch on
one thread (``1 process``) and on two threads (``2 processes``: VMAS uses the second core
through torch's threads in one process). VMAS steps 0.1 s of simulated time per step (ours
1/60 s) with far simpler physics: point-mass agents, no kicker, dribbler or chip.

An env-step is one match (one VMAS environment) advancing by one step. Each timed run steps
``--target`` env-steps (between 20 and 300 steps whatever the batch). Within each round the
cases run in turn (the order reversed every other round), and the median over rounds is
printed; the ratios ours / VMAS are taken within each round. Memory: the growth of the
resident set when ``--memory`` matches are built, reset and stepped in a fresh process,
divided by their number.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def _steps(batch: int, target: int) -> int:
    return max(20, min(300, -(-target // batch)))


def _ours(size: int, batch: int, processes: int, target: int, batched: bool = True,
          extra: dict | None = None) -> float:
    from agents.vec.factories import make_match_vec_env

    venv = make_match_vec_env({"blue": size, "yellow": size, **(extra or {})}, n_matches=batch,
                              learner="blue",
                              opponent="scripted", seed=0,
                              workers=0 if processes == 1 else processes, batched=batched)
    try:
        venv.reset()
        steps = _steps(batch, target)
        rng = np.random.default_rng(0)
        actions = rng.uniform(-1.0, 1.0, (steps + 5, venv.num_envs, 6)).astype(np.float32)
        for a in actions[:5]:  # warm-up: first contacts, caches
            venv.step(a)
        t0 = time.perf_counter()
        for a in actions[5:]:
            venv.step(a)
        return batch * steps / (time.perf_counter() - t0)
    finally:
        venv.close()


def _vmas(python: str, size: int, batches: list[int], threads: int, target: int
          ) -> dict[int, float]:
    script = Path(__file__).with_name("vmas_football.py")
    out = subprocess.run([python, str(script), "--agents", str(size), "--envs",
                          *map(str, batches), "--target", str(target), "--steps", "300",
                          "--threads", str(threads)],
                         check=True, capture_output=True, text=True).stdout
    rows = [json.loads(line) for line in out.strip().splitlines() if line.startswith("{")]
    return {int(r["envs"]): float(r["env_steps_per_s"]) for r in rows}


def _memory(size: int, n: int, extra: dict | None = None) -> float:
    """Bytes per match of ``n`` batched matches, measured in a fresh process."""
    from soccer_lab.bench import memory_per_item

    kwargs = {"blue": size, "yellow": size, **(extra or {})}

    def run(name: str, count: int) -> str:
        return (f"{name} = MatchBatch({count}, **{kwargs!r})\n{name}.reset(seed=0)\n"
                f"for _ in range(20): {name}.step(np.zeros(({count}, {2 * size}, 6)))")

    # The warm-up steps too: what a process loads once (the compiled kernels, numba's
    # compiler) is not the matches' memory.
    return memory_per_item(
        "import numpy as np\nfrom soccer_env.envs.batched_match import MatchBatch\n"
        + run("warm", 2), run("b", n), n)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size", type=int, default=2, help="robots per team (2)")
    p.add_argument("--batches", type=int, nargs="+",
                   default=[1, 16, 64, 128, 256, 512, 1024], help="batch sizes")
    p.add_argument("--target", type=int, default=40_000,
                   help="env-steps per timed run (40000; 20 to 300 steps)")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--vmas-python", default=None,
                   help="a Python with vmas installed: also time VMAS football")
    p.add_argument("--memory", type=int, default=1000,
                   help="matches for the memory figure (0: skip)")
    p.add_argument("--obs-mode", default="truth", help="our matches' observation mode (truth)")
    p.add_argument("--perception", default=None,
                   help="our matches' perception preset (the mode's default)")
    p.add_argument("--json", default=None)
    args = p.parse_args(argv)
    extra: dict = {"obs_mode": args.obs_mode}
    if args.perception:
        extra["perception"] = args.perception
    cases = [("ours", 1), ("ours", 2)] + ([("vmas", 1), ("vmas", 2)] if args.vmas_python
                                          else [])
    rates: dict[tuple[str, int, int], list[float]] = {}
    single: list[float] = []
    for r in range(args.rounds):
        order = cases if r % 2 == 0 else list(reversed(cases))
        single.append(_ours(args.size, 1, 1, min(args.target, 3000), batched=False,
                            extra=extra))
        for who, procs in order:
            if who == "vmas":
                got = _vmas(args.vmas_python, args.size, args.batches, procs, args.target)
                for b in args.batches:
                    rates.setdefault((who, procs, b), []).append(got[b])
            else:
                for b in args.batches:
                    rates.setdefault((who, procs, b), []).append(
                        _ours(args.size, b, procs, args.target, extra=extra))
    med = {k: statistics.median(v) for k, v in rates.items()}
    results: dict[str, object] = {"size": args.size, "kwargs": extra, "unbatched_1": single,
                                  "rates": {f"{w}:{p}:{b}": v for (w, p, b), v in rates.items()}}
    case = f"{args.size} vs {args.size}"
    print(f"{case}, env-steps/s (median of {args.rounds} rounds); one match unbatched: "
          f"{statistics.median(single):,.0f}")
    head = f"{'batch':>6} {'ours 1 proc':>12} {'ours 2 proc':>12}"
    if args.vmas_python:
        head += f" {'VMAS 1 thr':>11} {'VMAS 2 thr':>11} {'ours/VMAS':>10}"
    print(head)
    for b in args.batches:
        line = f"{b:>6} {med[('ours', 1, b)]:>12,.0f} {med[('ours', 2, b)]:>12,.0f}"
        if args.vmas_python:
            ours_best = [max(x, y) for x, y in zip(rates[("ours", 1, b)], rates[("ours", 2, b)])]
            vmas_best = [max(x, y) for x, y in zip(rates[("vmas", 1, b)], rates[("vmas", 2, b)])]
            ratio = statistics.median([o / v for o, v in zip(ours_best, vmas_best)])
            line += (f" {med[('vmas', 1, b)]:>11,.0f} {med[('vmas', 2, b)]:>11,.0f} "
                     f"{ratio:>10.2f}")
        print(line)
    if args.vmas_python:
        ours_top = max(med[("ours", p, b)] for p in (1, 2) for b in args.batches)
        vmas_512 = med.get(("vmas", 2, 512))
        results["ours_best"] = ours_top
        print(f"best of ours: {ours_top:,.0f} env-steps/s", end="")
        if vmas_512:
            results["vmas_512_two_threads"] = vmas_512
            print(f"; VMAS, 512 environments on two threads: {vmas_512:,.0f} "
                  f"(ours best / VMAS 512 = {ours_top / vmas_512:.2f})")
        else:
            print()
    if args.memory:
        per = _memory(args.size, args.memory, extra)
        results["bytes_per_match"] = per
        print(f"memory: {per:,.0f} bytes per match ({args.memory} matches in one batch)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
