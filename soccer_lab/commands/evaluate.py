"""``soccer-env eval``: a keeper policy on Goalkeeper-v0's fixed shot suite
(:func:`agents.runs.evaluation.evaluate`), with a video of the first episodes
(:func:`agents.runs.evaluation.record_video`)."""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

from agents.runs.evaluation import evaluate, paired, record_video
from agents.runs.resolve import make_policy
from soccer_env.envs.registration import GOALKEEPER_ID
from soccer_lab import extras
from soccer_lab.cli_args import (
    HelpFormatter,
    add_env_arguments,
    add_trust_argument,
    env_kwargs_from_args,
)

__all__ = ["parser", "main"]


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env eval``."""
    p = argparse.ArgumentParser(
        prog="soccer-env eval", formatter_class=HelpFormatter,
        description="Evaluate a keeper policy on Goalkeeper-v0's fixed shot suite (seeds "
                    "START-SEED onwards): save rate with a Wilson 95 % interval, outcomes, "
                    "ball estimation error, and a video of the first episodes (the video "
                    "needs the render extra and is skipped without it).",
        epilog="example:\n  soccer-env eval --policy baseline:keeper-ppo-ssl2012 "
               "--obs-mode perceived --perception ssl-2012")
    p.add_argument("--policy", default="scripted",
                   help="scripted, idle, baseline:NAME, a .zip (stable-baselines3, needs the "
                        "train extra) or .npz model, or a training run folder")
    p.add_argument("--versus", default=None, metavar="POLICY",
                   help="another policy (as --policy) played on the same shots: the shots "
                        "only one of them saved, and the sign test's p-value (default: none)")
    add_env_arguments(p)
    p.add_argument("--episodes", type=int, default=1000, help="shots")
    p.add_argument("--start-seed", type=int, default=0, help="seed of the first shot")
    p.add_argument("--workers", type=int, default=None,
                   help="processes; the result does not depend on it (default: all cores)")
    p.add_argument("--video", type=int, default=3, metavar="N",
                   help="episodes to render into the video (0: none)")
    p.add_argument("--out", default="eval_output", help="folder for eval.json and the video")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    add_trust_argument(p)
    return p


def _describe(env_kwargs: dict) -> str:
    """The environment's settings as ``key=value`` (``truth`` if none)."""
    return ", ".join(f"{k}={v}" for k, v in env_kwargs.items()) or "truth"


def main(argv: list[str] | None = None) -> int:
    """``soccer-env eval``: a policy on the fixed shot suite, with video."""
    import gymnasium as gym

    p = parser()
    args = p.parse_args(argv)
    if args.workers is None:
        args.workers = os.cpu_count() or 1
    for name in ("episodes", "workers"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be >= 1, got {getattr(args, name)}")
    if args.video < 0:
        p.error(f"--video must be >= 0, got {args.video}")
    extras.require("eval")
    if str(args.policy).endswith(".zip"):
        extras.require("policy .zip", f"eval --policy {args.policy}")
    try:
        env_kwargs = env_kwargs_from_args(args)
        # Resolve the policy once here so that a bad reference fails with its own message.
        probe = gym.make(GOALKEEPER_ID, **env_kwargs)
        try:
            make_policy(args.policy, probe, trust=args.trust)
            if args.versus is not None:
                make_policy(args.versus, probe, trust=args.trust)
        finally:
            probe.close()
    except (ValueError, TypeError, FileNotFoundError) as err:
        p.error(str(err))
    video = args.video
    if video:
        why = extras.unavailable("video")
        if why:
            print(f"no video: {why}", file=sys.stderr)
            video = 0
    res = evaluate(args.policy, env_kwargs, args.episodes, args.start_seed, args.workers,
                   trust=args.trust)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    record = res.to_dict()
    if args.versus is not None:
        other = evaluate(args.versus, env_kwargs, args.episodes, args.start_seed, args.workers,
                         trust=args.trust)
        record["versus"] = {**other.to_dict(), **paired(res, other)}
    if video:
        seeds = range(args.start_seed, args.start_seed + min(video, args.episodes))
        record["video"] = str(record_video(args.policy, out / "eval.mp4", env_kwargs, seeds,
                                            trust=args.trust))
    (out / "eval.json").write_text(json.dumps(record, indent=1))
    if args.json:
        shown = {k: v for k, v in record.items() if k != "saved"}
        if "versus" in shown:
            shown["versus"] = {k: v for k, v in shown["versus"].items() if k != "saved"}
        print(json.dumps(shown, indent=1))
    else:
        print(f"{res.policy} on Goalkeeper-v0 ({_describe(env_kwargs)}): {res.summary()}")
        if args.versus is not None:
            v = record["versus"]
            print(f"versus {other.policy}: {other.summary()}\n"
                  f"saved by {res.policy} only: {v['a_only']}, by {other.policy} only: "
                  f"{v['b_only']}; difference {100 * v['difference']:+.1f} points, sign test "
                  f"p = {v['sign_test_p']:.3g}")
        print(f"wrote {out / 'eval.json'}" + (f" and {record['video']}" if video else ""))
    return 0
