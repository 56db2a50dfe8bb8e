"""``soccer-env eval``: a keeper policy on Goalkeeper-v0's fixed shot suite
(:func:`agents.evaluation.evaluate`), with a video of the first episodes
(:func:`agents.evaluation.record_video`)."""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

from agents.evaluation import GOALKEEPER_ID, evaluate, record_video
from agents.policies import make_policy
from soccer_lab.cli_args import add_env_arguments, add_trust_argument, env_kwargs_from_args

__all__ = ["parser", "main"]


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env eval``."""
    p = argparse.ArgumentParser(
        prog="soccer-env eval",
        description="Evaluate a keeper policy on Goalkeeper-v0's fixed shot suite (seeds "
                    "0..N-1): save rate with a Wilson 95 % interval, outcomes, estimation "
                    "error, and a video of the first episodes.",
        epilog="example: soccer-env eval --policy baseline:keeper-ppo-ssl2012 --obs-mode "
               "perceived --perception ssl-2012")
    p.add_argument("--policy", default="scripted",
                   help="scripted (default), idle, baseline:NAME, a .zip/.npz model or a run "
                        "folder")
    add_env_arguments(p)
    p.add_argument("--episodes", type=int, default=1000, help="shots (default 1000)")
    p.add_argument("--start-seed", type=int, default=0, help="first seed of the suite")
    p.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                   help="processes (default: all cores)")
    p.add_argument("--video", type=int, default=3, metavar="N",
                   help="episodes to render into the video (default 3; 0 for none)")
    p.add_argument("--out", default="eval_output", help="folder for eval.json and the video")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    add_trust_argument(p)
    return p


def main(argv: list[str] | None = None) -> int:
    """``soccer-env eval``: a policy on the fixed shot suite, with video."""
    import gymnasium as gym

    p = parser()
    args = p.parse_args(argv)
    for name in ("episodes", "workers"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be >= 1")
    if args.video < 0:
        p.error("--video must be >= 0")
    try:
        env_kwargs = env_kwargs_from_args(args)
        # Resolve the policy once here so that a bad reference fails with its own message.
        probe = gym.make(GOALKEEPER_ID, **env_kwargs)
        try:
            make_policy(args.policy, probe, trust=args.trust)
        finally:
            probe.close()
    except (ValueError, TypeError, FileNotFoundError) as err:
        p.error(str(err))
    res = evaluate(args.policy, env_kwargs, args.episodes, args.start_seed, args.workers,
                   trust=args.trust)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    record = res.to_dict()
    if args.video:
        seeds = range(args.start_seed, args.start_seed + min(args.video, args.episodes))
        record["video"] = str(record_video(args.policy, out / "eval.mp4", env_kwargs, seeds,
                                            trust=args.trust))
    (out / "eval.json").write_text(json.dumps(record, indent=1))
    if args.json:
        print(json.dumps({k: v for k, v in record.items() if k != "saved"}, indent=1))
    else:
        print(f"{res.policy} on {env_kwargs or 'truth'}: {res.summary()}")
        print(f"wrote {out / 'eval.json'}" + (f" and {record['video']}" if args.video else ""))
    return 0
