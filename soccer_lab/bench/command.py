"""The ``soccer-env bench`` command: its options (:func:`parser`) and what runs (:func:`main`):
a profile, the camera-image renderers or the step rates."""

from __future__ import annotations

import json
from typing import Any

from soccer_lab.bench.compile_cost import bench_compile, format_compile
from soccer_lab.bench.profiling import PROFILE_CASES, format_profile, profile_perceived
from soccer_lab.bench.runners import HUMANOID_CAMERA
from soccer_lab.bench.steps import bench_frames, bench_pixels, run_benchmarks
from soccer_lab.bench.tables import format_table

__all__ = ["parser", "main"]


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
               "  soccer-env bench --pixels                  # pixels detector's step rates "
               "(pixels extra)\n"
               "  soccer-env bench --profile humanoid-goalkeeper\n"
               "  soccer-env bench --compile                 # kernels' compile and load "
               "times")
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
    p.add_argument("--pixels", action="store_true",
                   help="time a Goalkeeper-v0 and a 6 vs 6 match with the overhead pixels "
                        "detector instead, against truth (--steps / 10 and --match-steps / 25 "
                        "steps a run; needs the pixels extra)")
    p.add_argument("--profile", choices=sorted(PROFILE_CASES), default=None,
                   help="profile a perceived step of this case instead (cProfile: the top "
                        "functions by own time per step)")
    p.add_argument("--perception", type=sensor_preset, default=None, metavar="PRESET",
                   help=f"with --profile: the sensor preset ({sensor_presets_help()}) "
                        f"(default: {PROFILE_CASES['goalkeeper'][2]}, or "
                        f"{HUMANOID_CAMERA} for humanoids)")
    p.add_argument("--compile", action="store_true",
                   help="time the first import and first step of fresh interpreters instead, "
                        "with an empty kernel cache (cold) and a filled one (warm)")
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
    if args.pixels and not args.profile:
        extras.require("bench --pixels")
    elif args.frames and not args.profile:
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
    if args.compile:
        res = bench_compile()
        print(json.dumps(res, indent=2) if args.json else format_compile(res))
        return 0
    if args.pixels:
        res = bench_pixels(max(1, args.steps // 10), max(1, args.match_steps // 25),
                           args.repeats)
        print(json.dumps(res, indent=2) if args.json else "\n".join(
            f"{key}: {v['steps_per_s']:,.0f} steps/s, {v['cost_vs_truth']:.2f} times truth's "
            "step" for key, v in res.items()))
        return 0
    if args.frames:
        ms = bench_frames()
        print(json.dumps(ms, indent=2) if args.json else
              "\n".join(f"{key}: {v:.2f} ms" for key, v in ms.items()))
        return 0
    res = run_benchmarks(args.steps, args.match_steps, args.repeats, args.batch)
    print(json.dumps(res, indent=2) if args.json else format_table(res))
    return 0
