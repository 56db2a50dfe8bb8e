"""``soccer-env ablation``: one keeper policy on the same seeded shots under every estimator
configuration and sensor preset (:func:`agents.studies.ablation.run_ablation`), or with ``--env
soccer_env/Match-v0`` pairs of configurations playing seeded matches against each other
(:func:`agents.studies.match_ablation.run_match_ablation`); the tables printed and written."""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence

from agents.studies.ablation import (
    DEFAULT_CHUNK_SIZE,
    DEFAULT_EPISODES,
    DEFAULT_HUMANOID,
    ESTIMATOR_CONFIGS,
    HUMANOID_CONFIGS,
    ROBOT_KINDS,
    RobotKind,
    parse_names,
    robot_kind,
    run_ablation,
    write_outputs,
)
from agents.studies.match_ablation import (
    DEFAULT_DURATION,
    DEFAULT_MATCH_PRESETS,
    DEFAULT_MATCHES,
    DEFAULT_PAIRS,
    DEFAULT_TEAM_SIZE,
    parse_pairs,
    run_match_ablation,
)
from agents.studies.match_ablation import write_outputs as write_match_outputs
from soccer_env.envs.registration import GOALKEEPER_ID, MATCH_ID
from soccer_env.presets import HEAD_CAMERAS, ROBOTS, VISION
from soccer_lab import extras
from soccer_lab.cli_args import HelpFormatter, add_trust_argument, key_values, preset_kind

__all__ = ["parser", "main"]


def _robots_of(kind: str) -> str:
    """The robot presets of robot kind ``kind``, comma-separated."""
    return ", ".join(name for name in ROBOTS if preset_kind(name) == kind)


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env ablation``."""
    p = argparse.ArgumentParser(
        prog="soccer-env ablation", formatter_class=HelpFormatter,
        description="Evaluate one keeper policy on the same seeded shots under every estimator "
                    "configuration and sensor preset: save rate with Wilson 95 % interval, "
                    "ball estimation RMSE and estimator compute per step.\n\nWith --env "
                    f"{MATCH_ID}: two teams with the same policy, each perceiving through "
                    "its own configuration, play seeded matches (colours swapped every "
                    "other match): wins, draws and losses with Wilson 95 % intervals, goals, "
                    "goal difference with a paired 95 % interval and each team's ball error.",
        epilog="examples:\n"
               "  soccer-env ablation --policy scripted --out ablation_output\n"
               "  soccer-env ablation --robot humanoid --episodes 500 --presets "
               "ideal,kidsize-2012\n"
               f"  soccer-env ablation --env {MATCH_ID} --pairs ekf:raw")
    p.add_argument("--env", default=GOALKEEPER_ID, choices=(GOALKEEPER_ID, MATCH_ID),
                   help=f"{GOALKEEPER_ID}: the keeper on seeded shots; {MATCH_ID}: matches "
                        "between pairs of configurations")
    p.add_argument("--policy", default="scripted",
                   help="policy reference: scripted, idle, baseline:NAME, a .zip (needs the "
                        "train extra) or .npz file, or a training run folder; in matches the "
                        "team policy of both teams: scripted, idle or a .npz file")
    p.add_argument("--episodes", type=int, default=None,
                   help="keeper only: shots per cell, seeds START-SEED onwards "
                        f"(default: {DEFAULT_EPISODES})")
    p.add_argument("--robot", default="ssl", choices=list(ROBOT_KINDS),
                   help=f"robot kind: ssl (overhead vision; robot presets {_robots_of('ssl')}) "
                        "or humanoid (head cameras, localization, team fusion; robot "
                        f"presets {_robots_of('humanoid')}; {DEFAULT_HUMANOID} unless "
                        "--env-kwarg robot=NAME names another)")
    p.add_argument("--presets", default=None,
                   help="comma-separated sensor presets, or all; ssl: "
                        f"{', '.join(VISION)}; humanoid: {', '.join(HEAD_CAMERAS)} (default: "
                        "all for the keeper; in matches ssl: "
                        f"{','.join(DEFAULT_MATCH_PRESETS['ssl'])}, humanoid: "
                        f"{','.join(DEFAULT_MATCH_PRESETS['humanoid'])})")
    p.add_argument("--configs", default=None,
                   help="keeper only: comma-separated estimator configurations, or all; ssl: "
                        f"{', '.join(ESTIMATOR_CONFIGS)}; humanoid: "
                        f"{', '.join(HUMANOID_CONFIGS)} (pixels needs the pixels extra) "
                        "(default: all)")
    p.add_argument("--pairs", default=None,
                   help="matches only: comma-separated pairs A:B of estimator configurations "
                        "(default: ssl " + ",".join(f"{a}:{b}" for a, b in DEFAULT_PAIRS["ssl"])
                        + "; humanoid " + ",".join(f"{a}:{b}" for a, b in
                                                   DEFAULT_PAIRS["humanoid"]) + ")")
    p.add_argument("--matches", type=int, default=None,
                   help="matches only: matches per pair and preset, seed START-SEED + k // 2 "
                        f"for match k, A blue when k is even (default: {DEFAULT_MATCHES})")
    p.add_argument("--team-size", type=int, default=None,
                   help=f"matches only: robots per team, 1..11 (default: {DEFAULT_TEAM_SIZE})")
    p.add_argument("--duration", type=float, default=None,
                   help="matches only: match length in seconds "
                        f"(default: {DEFAULT_DURATION:g})")
    p.add_argument("--workers", type=int, default=None,
                   help="processes; the results do not depend on it (default: all cores)")
    p.add_argument("--out", default="ablation_output", help="output folder")
    p.add_argument("--start-seed", type=int, default=0,
                   help="seed of the first shot or match")
    p.add_argument("--chunk-size", type=int, default=None,
                   help="keeper only: consecutive seeds per job "
                        f"(default: {DEFAULT_CHUNK_SIZE})")
    p.add_argument("--env-kwarg", action="append", default=[], metavar="KEY=VALUE",
                   help="environment keyword argument shared by all cells (value parsed as "
                        "JSON), repeatable, e.g. control_dt=0.04 or field=ssl-2012; obs_mode "
                        "and perception belong to the cells")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    add_trust_argument(p)
    return p


def _uses_pixels(kind: RobotKind, names: list[str]) -> bool:
    """Whether any of the configurations ``names`` finds the ball in rendered images."""
    return any(kind.configs[n].perception.get("detector") == "pixels" for n in names
               if n in kind.configs)


_KEEPER_ONLY = ("episodes", "configs", "chunk_size")
_MATCH_ONLY = ("pairs", "matches", "team_size", "duration")


def main(argv: Sequence[str] | None = None) -> int:
    """``soccer-env ablation``: run the ablation, write its outputs and print the table."""
    p = parser()
    args = p.parse_args(list(sys.argv[1:] if argv is None else argv))
    match = args.env == MATCH_ID
    wrong = [n for n in (_KEEPER_ONLY if match else _MATCH_ONLY)
             if getattr(args, n) is not None]
    if wrong:
        opts = ", ".join("--" + n.replace("_", "-") for n in wrong)
        verb = "applies" if len(wrong) == 1 else "apply"
        p.error(f"{opts} {verb} to {GOALKEEPER_ID if match else MATCH_ID} only, not to "
                f"--env {args.env}")
    if args.trust and match:
        p.error(f"--trust applies to {GOALKEEPER_ID} only: match teams load .npz files, "
                "which never unpickle")
    for name, default in (("episodes", DEFAULT_EPISODES), ("chunk_size", DEFAULT_CHUNK_SIZE),
                          ("matches", DEFAULT_MATCHES), ("team_size", DEFAULT_TEAM_SIZE)):
        value = getattr(args, name)
        if value is not None and value < 1:
            p.error(f"--{name.replace('_', '-')} must be >= 1, got {value}")
        setattr(args, name, default if value is None else value)
    if args.duration is None:
        args.duration = DEFAULT_DURATION
    elif not 0 < args.duration < float("inf"):
        p.error(f"--duration must be a positive number of seconds, got {args.duration}")
    if args.workers is not None and args.workers < 1:
        p.error(f"--workers must be >= 1, got {args.workers}")
    try:
        kind = robot_kind(args.robot)
        if match:
            presets = parse_names(args.presets or ",".join(DEFAULT_MATCH_PRESETS[args.robot]),
                                  kind.presets, "sensor preset(s)")
            configs = [name for pair in parse_pairs(args.pairs, kind.configs, args.robot)
                       for name in pair]
        else:
            presets = parse_names(args.presets, kind.presets, "sensor preset(s)")
            configs = parse_names(args.configs or "all", kind.configs,
                                  "estimator configuration(s)")
        env_kwargs = key_values(args.env_kwarg, "--env-kwarg")
    except ValueError as exc:
        p.error(str(exc))
    extras.require("ablation")
    if str(args.policy).endswith(".zip"):
        extras.require("policy .zip", f"ablation --policy {args.policy}")
    if _uses_pixels(kind, configs):
        extras.require("ablation pixels", "ablation with configuration pixels",
                       hint=f"or choose {'--pairs' if match else '--configs'} without it")
    t0 = time.perf_counter()

    def progress(done: int, total: int) -> None:
        unit = "matches" if match else "jobs"
        if not args.quiet and (done == total or done % max(1, total // 20) == 0):
            print(f"ablation: {done} of {total} {unit} done ({time.perf_counter() - t0:.0f} s)",
                  file=sys.stderr, flush=True)

    try:
        if match:
            res = run_match_ablation(args.pairs, presets, args.matches, args.robot,
                                     args.team_size, args.duration, args.start_seed,
                                     args.workers, args.policy, env_kwargs, progress)
        else:
            res = run_ablation(args.policy, args.episodes, presets, configs, args.start_seed,
                               args.workers, args.chunk_size, env_kwargs=env_kwargs,
                               progress=progress, robot=args.robot, trust=args.trust)
    except (ValueError, TypeError, FileNotFoundError) as exc:
        p.error(str(exc))
    files = (write_match_outputs if match else write_outputs)(res, args.out)
    print(res.markdown())
    for path in files.values():
        print(f"wrote {path}")
    size = f"{res.matches} matches" if match else f"{res.episodes} shots"
    print(f"{len(res.cells)} cells x {size} in {res.seconds:.0f} s")
    return 0
