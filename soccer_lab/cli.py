"""The ``soccer-env`` command line."""

from __future__ import annotations

import argparse
import json
import sys

__all__ = ["main"]


def _cmd_demo(argv: list[str]) -> int:
    p = argparse.ArgumentParser(prog="soccer-env demo",
                                description="Run scripted-keeper episodes of Goalkeeper-v0 "
                                            "(an SSL keeper, then a humanoid one) and write "
                                            "their video and figures.")
    p.add_argument("--out", default="demo_output", help="output folder (default: demo_output)")
    p.add_argument("--episodes", type=int, default=3, help="number of episodes (default: 3)")
    p.add_argument("--seed", type=int, default=0, help="seed of the first episode")
    p.add_argument("--no-video", action="store_true", help="skip rendering the video")
    args = p.parse_args(argv)
    if args.episodes < 1:
        p.error("--episodes must be >= 1")
    from pathlib import Path

    from soccer_lab.demo import run_demo

    for robot, out, perception in (("ssl", Path(args.out), "realistic"),
                                   ("humanoid-2012", Path(args.out) / "humanoid", None)):
        summary = run_demo(out, args.episodes, args.seed, video=not args.no_video,
                           robot=robot, perception=perception)
        print(f"{robot} keeper:")
        for ep in summary["episodes"]:
            shot = ep["shot"]
            kind = "chip" if shot["chip"] else "flat"
            print(f"seed {ep['seed']}: {kind} shot at {shot['speed']:.1f} m/s -> "
                  f"{ep['outcome']} after {ep['steps']} steps (median ball estimate error "
                  f"{1000 * ep['ball_error_median_m']:.1f} mm)")
        for name, path in summary["files"].items():
            print(f"wrote {name}: {path}")
    return 0


def _cmd_list(argv: list[str]) -> int:
    p = argparse.ArgumentParser(prog="soccer-env list",
                                description="List environments and presets.")
    p.add_argument("--json", action="store_true")
    p.parse_args(argv)
    from soccer_env import presets
    from soccer_env.envs.registration import GYMNASIUM, PETTINGZOO
    from soccer_env.perception import options

    # Every family is a registry: its names and one-line descriptions.
    families = {
        "gymnasium": GYMNASIUM,
        "pettingzoo (also soccer_env.parallel_env, soccer_env.env)": PETTINGZOO,
        "fields": presets.FIELDS,
        "balls": presets.BALLS,
        "robots": presets.ROBOTS,
        "vision (SSL)": presets.VISION,
        "head cameras (humanoids)": presets.HEAD_CAMERAS,
        "radio (humanoids)": presets.RADIO_PRESETS,
        "overhead frames (pixels)": presets.OVERHEAD_FRAMES,
        "head frames (pixels)": presets.HEAD_FRAMES,
        "ball filters (SSL)": options.BALL_FILTERS,
        "localization (humanoids)": options.LOCALIZATIONS,
        "fusion (humanoids)": options.FUSIONS,
        "ball trackers (humanoids)": options.BALL_TRACKERS,
        "detectors": options.DETECTORS,
    }
    info = {key: family.descriptions() for key, family in families.items()}
    if "--json" in argv:
        print(json.dumps(info, indent=2))
    else:
        for key, val in info.items():
            print(f"{key}:")
            for item in val:
                extra = f"  ({val[item]})" if isinstance(val, dict) else ""
                print(f"  {item}{extra}")
    return 0


def _cmd_paper(argv: list[str]) -> int:
    from soccer_lab.papers import PAPERS

    p = argparse.ArgumentParser(prog="soccer-env paper",
                                description="Reproduce a source paper's claims.")
    p.add_argument("name", choices=sorted(PAPERS), help="; ".join(
        f"{k}: {v}" for k, v in PAPERS.descriptions().items()))
    p.add_argument("--out", default="paper_output", help="output folder")
    p.add_argument("--episodes", type=int, default=200, help="ekf: open-loop episodes")
    p.add_argument("--shots", type=int, default=1000, help="ekf: closed-loop shots per cell")
    p.add_argument("--runs", type=int, default=1000, help="ungm: simulated runs")
    p.add_argument("--particles", type=int, default=100, help="ungm: particles")
    p.add_argument("--trials", type=int, default=20,
                   help="hough: noise draws per ball position")
    p.add_argument("--matches", type=int, default=4, help="team: seeded matches per "
                   "configuration")
    p.add_argument("--duration", type=float, default=60.0, help="team: match length [s]")
    p.add_argument("--walks", type=int, default=5, help="localization: walking episodes")
    p.add_argument("--keeper-shots", type=int, default=500,
                   help="team: humanoid keeper shots per configuration")
    p.add_argument("--workers", type=int, default=None, help="processes (default: all cores)")
    p.add_argument("--no-closed-loop", action="store_true",
                   help="ekf: skip the closed loop; team: skip the keeper")
    p.add_argument("--seed", type=int, default=0)
    args = p.parse_args(argv)
    for name in ("episodes", "shots", "runs", "trials", "matches", "keeper_shots", "walks"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be >= 1")
    if args.particles < 2:
        p.error("--particles must be >= 2")
    if args.workers is not None and args.workers < 1:
        p.error("--workers must be >= 1")
    run = PAPERS[args.name]
    runs = {
        "ekf": lambda: run(args.out, args.episodes, args.shots, args.workers,
                           closed=not args.no_closed_loop, seed=args.seed),
        "hough": lambda: run(args.out, args.trials, seed=args.seed),
        "localization": lambda: run(args.out, seed=args.seed, episodes=args.walks,
                                    workers=args.workers),
        "ungm": lambda: run(args.out, args.runs, args.particles, seed=args.seed),
        "team": lambda: run(args.out, args.matches, args.duration, args.keeper_shots,
                            args.workers, seed=args.seed, keeper=not args.no_closed_loop),
        "meanshift": lambda: run(args.out, seed=args.seed, workers=args.workers),
        "following": lambda: run(args.out, seed=args.seed, workers=args.workers),
    }
    res = runs[args.name]()
    print(res["text"])
    for path in res["files"]:
        print(f"wrote {path}")
    print(f"tables and plots in {args.out}/ ({res['seconds']:.0f} s)")
    return 0


def _cmd_bench(argv: list[str]) -> int:
    from soccer_lab.bench import main as bench_main

    return bench_main(argv)


def _cmd_train(argv: list[str]) -> int:
    # Imported when run: training needs the ``train`` extra.
    from soccer_lab.commands.train import main as train_main

    return train_main(argv)


def _cmd_eval(argv: list[str]) -> int:
    from soccer_lab.commands.evaluate import main as eval_main

    return eval_main(argv)


def _cmd_ablation(argv: list[str]) -> int:
    from soccer_lab.commands.ablation import main as ablation_main

    return ablation_main(argv)


_COMMANDS = {
    "demo": (_cmd_demo, "run the goalkeeper demo and write its video and figures"),
    "bench": (_cmd_bench, "measure environment step rates against bare pymunk"),
    "paper": (_cmd_paper, "reproduce a source paper's claims (tables and plots)"),
    "train": (_cmd_train, "train a policy with stable-baselines3, or RLlib on a Ray cluster"),
    "eval": (_cmd_eval, "evaluate a keeper policy on the fixed shot suite"),
    "ablation": (_cmd_ablation, "compare estimators in closed loop, per sensor preset"),
    "list": (_cmd_list, "list environments and presets"),
}


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] in ("-h", "--help") or argv[0] not in _COMMANDS:
        lines = ["usage: soccer-env <command> [options]", "", "commands:"]
        lines += [f"  {name:8s} {help_}" for name, (_, help_) in _COMMANDS.items()]
        text = "\n".join(lines)
        if argv and argv[0] not in ("-h", "--help"):
            print(f"soccer-env: unknown command {argv[0]!r}\n\n{text}", file=sys.stderr)
            return 2
        print(text)
        return 0
    return _COMMANDS[argv[0]][0](argv[1:])


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
