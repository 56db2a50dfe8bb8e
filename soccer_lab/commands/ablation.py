"""``soccer-env ablation``: one keeper policy on the same seeded shots under every estimator
configuration and sensor preset (:func:`agents.ablation.run_ablation`), its tables printed and
written (:func:`agents.ablation.write_outputs`)."""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence

from agents.ablation import (
    DEFAULT_CHUNK_SIZE,
    ESTIMATOR_CONFIGS,
    HUMANOID_CONFIGS,
    ROBOT_KINDS,
    parse_names,
    robot_kind,
    run_ablation,
    write_outputs,
)
from soccer_env.presets.sensors import HEAD_CAMERAS, VISION
from soccer_lab.cli_args import add_trust_argument, key_values

__all__ = ["parser", "main"]


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env ablation``."""
    p = argparse.ArgumentParser(
        prog="soccer-env ablation",
        description="Evaluate one keeper policy on the same seeded shots under every estimator "
                    "configuration and sensor preset: save rate with Wilson 95 % interval, "
                    "ball estimation RMSE and estimator compute per step.")
    p.add_argument("--policy", default="scripted",
                   help="policy reference: scripted, idle, baseline:NAME, a .zip/.npz file or "
                        "a training run folder (default: scripted)")
    p.add_argument("--episodes", type=int, default=1000,
                   help="shots per cell, seeds start-seed onwards (default: 1000)")
    p.add_argument("--robot", default="ssl", choices=list(ROBOT_KINDS),
                   help="the keeper's robot kind: ssl (overhead vision) or humanoid (head "
                        "cameras, localization, team fusion; robot humanoid-2012 unless "
                        "--env-kwarg robot=... names another) (default: ssl)")
    p.add_argument("--presets", default=None,
                   help=f"comma-separated sensor presets (default: all; ssl: "
                        f"{','.join(VISION)}; humanoid: {','.join(HEAD_CAMERAS)})")
    p.add_argument("--configs", default="all",
                   help="comma-separated estimator configurations (default: all; ssl: "
                        f"{','.join(ESTIMATOR_CONFIGS)}; humanoid: "
                        f"{','.join(HUMANOID_CONFIGS)})")
    p.add_argument("--workers", type=int, default=None,
                   help="processes (default: all cores); the results do not depend on it")
    p.add_argument("--out", default="ablation_output",
                   help="output folder (default: ablation_output)")
    p.add_argument("--start-seed", type=int, default=0, help="seed of the first shot")
    p.add_argument("--chunk-size", type=int, default=DEFAULT_CHUNK_SIZE,
                   help=f"consecutive seeds per job (default: {DEFAULT_CHUNK_SIZE})")
    p.add_argument("--env-kwarg", action="append", default=[], metavar="KEY=VALUE",
                   help="environment keyword argument shared by all cells (value parsed as "
                        "JSON), repeatable, e.g. control_dt=0.04 or field=ssl-2012; obs_mode "
                        "and perception belong to the cells")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    add_trust_argument(p)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """``soccer-env ablation``: run the ablation, write its outputs and print the table."""
    p = parser()
    args = p.parse_args(list(sys.argv[1:] if argv is None else argv))
    for name in ("episodes", "chunk_size"):
        if getattr(args, name) < 1:
            p.error(f"--{name.replace('_', '-')} must be >= 1, got {getattr(args, name)}")
    if args.workers is not None and args.workers < 1:
        p.error(f"--workers must be >= 1, got {args.workers}")
    try:
        kind = robot_kind(args.robot)
        presets = parse_names(args.presets, kind.presets, "sensor preset(s)")
        configs = parse_names(args.configs, kind.configs, "estimator configuration(s)")
        env_kwargs = key_values(args.env_kwarg, "--env-kwarg")
    except ValueError as exc:
        p.error(str(exc))
    t0 = time.perf_counter()

    def progress(done: int, total: int) -> None:
        if not args.quiet and (done == total or done % max(1, total // 20) == 0):
            print(f"ablation: {done}/{total} jobs ({time.perf_counter() - t0:.0f} s)",
                  file=sys.stderr, flush=True)

    try:
        res = run_ablation(args.policy, args.episodes, presets, configs, args.start_seed,
                           args.workers, args.chunk_size, env_kwargs=env_kwargs,
                           progress=progress, robot=args.robot, trust=args.trust)
    except (ValueError, TypeError, FileNotFoundError) as exc:
        p.error(str(exc))
    files = write_outputs(res, args.out)
    print(res.markdown())
    for path in files.values():
        print(f"wrote {path}")
    print(f"{len(res.cells)} cells x {res.episodes} shots in {res.seconds:.0f} s")
    return 0
