"""The ``soccer-env`` command line: ``soccer-env <command> [options]``.

Each command parses its options, checks that what it imports is installed
(:mod:`soccer_lab.extras`: one line naming the extra to install, exit status 2) and runs.
:data:`COMMANDS` lists the commands with their one-line summaries; :func:`parsers` builds
every command's option parser (for ``paper``, one per paper), which is what ``--help`` prints.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import textwrap
from collections.abc import Callable
from typing import Any, NamedTuple

from soccer_lab import extras
from soccer_lab.cli_args import HelpFormatter

__all__ = ["main", "parsers", "paper_parser", "version", "COMMANDS"]


def version() -> str:
    """The installed distribution's version (``importlib.metadata``), or ``"unknown (not
    installed)"`` when the package runs from a source tree that was never installed."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as dist_version

    try:
        return dist_version("soccer-env")
    except PackageNotFoundError:
        return "unknown (not installed)"


# --------------------------------------------------------------------------------------------
# demo
# --------------------------------------------------------------------------------------------

def _demo_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="soccer-env demo", formatter_class=HelpFormatter,
        description="Run the scripted keeper of Goalkeeper-v0 on seeded shots, first an SSL "
                    "keeper perceiving through the realistic overhead vision, then a humanoid "
                    "keeper with three team-mates and head cameras, and write a video and "
                    "figures of each (trajectories, ball speed, estimation error) and a "
                    "summary.json. The two keepers run in two processes at once where the "
                    "machine has two cores or more.\n\nThe figures need matplotlib and the "
                    "video pygame and imageio (all in the render extra); without pygame or "
                    "imageio the video is skipped.")
    p.add_argument("--out", default="demo_output",
                   help="output folder (the humanoid keeper's files in its humanoid/ folder)")
    p.add_argument("--episodes", type=int, default=3,
                   help="episodes per keeper, seeds SEED onwards")
    p.add_argument("--seed", type=int, default=0, help="seed of the first episode")
    p.add_argument("--no-video", action="store_true",
                   help="skip the video: only the figures and the summary")
    return p


def _cmd_demo(argv: list[str]) -> int:
    p = _demo_parser()
    args = p.parse_args(argv)
    if args.episodes < 1:
        p.error(f"--episodes must be >= 1, got {args.episodes}")
    extras.require("demo")
    video = not args.no_video
    if video:
        why = extras.unavailable("video")
        if why:
            print(f"no video: {why}", file=sys.stderr)
            video = False
    from pathlib import Path

    keepers = (("ssl", Path(args.out), "realistic",
                "SSL keeper (robot ssl, realistic overhead vision)"),
               ("humanoid-2012", Path(args.out) / "humanoid", None,
                "Humanoid keeper (robot humanoid-2012, its head camera, three team-mates)"))
    summaries = _run_demos([{"out": out, "episodes": args.episodes, "seed": args.seed,
                             "video": video, "robot": robot, "perception": perception}
                            for robot, out, perception, _ in keepers])
    for (_, _, _, title), summary in zip(keepers, summaries):
        print(f"{title}:")
        for ep in summary["episodes"]:
            shot = ep["shot"]
            kind = "chip" if shot["chip"] else "flat"
            print(f"  seed {ep['seed']}: {kind} shot at {shot['speed']:.1f} m/s -> "
                  f"{ep['outcome']} after {ep['steps']} steps (median ball estimate error "
                  f"{1000 * ep['ball_error_median_m']:.1f} mm)")
        for name, path in summary["files"].items():
            print(f"  wrote {name.replace('_', ' ')}: {path}")
    return 0


def _run_demos(calls: list[dict]) -> list[dict]:
    """:func:`~soccer_lab.demo.run_demo` with each of ``calls``' keyword arguments, in that
    order; the keepers are independent, so where the machine has two cores or more they run
    in two fresh processes at once (each compiles or loads its own kernels and renders its
    own video)."""
    from soccer_lab.demo import run_demo

    if (os.cpu_count() or 1) < 2 or len(calls) < 2:
        return [run_demo(**c) for c in calls]
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=2,
                             mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = [pool.submit(run_demo, **c) for c in calls]
        return [f.result() for f in futures]


# --------------------------------------------------------------------------------------------
# list
# --------------------------------------------------------------------------------------------

def _list_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="soccer-env list", formatter_class=HelpFormatter,
        description="List the environments, the presets (world, sensors) and the perception "
                    "options, each name with a one-line description.")
    p.add_argument("--json", action="store_true",
                   help="print them as JSON: family -> {name: description}")
    return p


def _families() -> list[tuple[str, list[tuple[str, str, Any]]]]:
    """The listed families in sections: (heading, [(JSON key, label, registry)])."""
    from soccer_env import presets
    from soccer_env.envs.registration import GYMNASIUM, PETTINGZOO
    from soccer_env.perception import options

    return [
        ("Environments", [
            ("gymnasium", "Gymnasium (gymnasium.make(ID))", GYMNASIUM),
            ("pettingzoo", "PettingZoo (soccer_env.parallel_env(), soccer_env.env())",
             PETTINGZOO)]),
        ("World presets (environment arguments)", [
            ("fields", "fields (field=NAME)", presets.FIELDS),
            ("balls", "balls (ball=NAME)", presets.BALLS),
            ("robots", "robots (robot=NAME)", presets.ROBOTS),
            ("rules", "game rules of Match-v0 (game=NAME)", presets.RULES)]),
        ("Sensor presets", [
            ("vision", "SSL overhead vision (perception=NAME)", presets.VISION),
            ("head_cameras", "humanoid head cameras (perception=NAME)", presets.HEAD_CAMERAS),
            ("radio", "humanoid radio (perception={\"radio\": NAME})", presets.RADIO_PRESETS),
            ("overhead_frames", "rendered overhead frames (pixels detector)",
             presets.OVERHEAD_FRAMES),
            ("head_frames", "rendered head-camera frames (pixels detector)",
             presets.HEAD_FRAMES)]),
        ("Perception options (perception={\"OPTION\": NAME, ...})", [
            ("ball_filters", "SSL ball filters (ball_filter)", options.BALL_FILTERS),
            ("robot_predictions", "SSL own-robot prediction (robot_prediction)",
             options.ROBOT_PREDICTIONS),
            ("localizations", "humanoid localization (localization)", options.LOCALIZATIONS),
            ("fusions", "humanoid ball fusion (fusion)", options.FUSIONS),
            ("ball_trackers", "humanoid ball trackers (ball_tracker)", options.BALL_TRACKERS),
            ("detectors", "detectors (detector)", options.DETECTORS)]),
    ]


def _cmd_list(argv: list[str]) -> int:
    args = _list_parser().parse_args(argv)
    extras.require("list")
    sections = _families()
    if args.json:
        print(json.dumps({key: family.descriptions() for _, items in sections
                          for key, _, family in items}, indent=2))
        return 0
    columns = max(60, shutil.get_terminal_size().columns - 1)
    lines: list[str] = []
    for heading, items in sections:
        lines += [""] if lines else []
        lines.append(heading)
        for _, label, family in items:
            lines.append(f"  {label}:")
            width = max(len(name) for name in family)
            for name, text in family.descriptions().items():
                lines += textwrap.wrap(text, columns, initial_indent=f"    {name:<{width}}  ",
                                       subsequent_indent=" " * (width + 6),
                                       break_on_hyphens=False)
    print("\n".join(lines))
    return 0


# --------------------------------------------------------------------------------------------
# paper
# --------------------------------------------------------------------------------------------

class _Paper(NamedTuple):
    """A reproduction's command line: what it does (the sub-parser's description), its
    options and how they become the arguments of its ``run``."""

    about: str
    options: Callable[[argparse.ArgumentParser], None]
    call: Callable[[Callable[..., dict[str, Any]], argparse.Namespace], dict[str, Any]]


def _workers(p: argparse.ArgumentParser) -> None:
    p.add_argument("--workers", type=int, default=None,
                   help="processes; the figures other than timings do not depend on it "
                        "(default: all cores)")


def _ekf_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--episodes", type=int, default=200,
                   help="open-loop shots, seeds SEED onwards")
    p.add_argument("--shots", type=int, default=1000,
                   help="closed-loop shots per sensor preset and estimator, seeds 0 onwards")
    p.add_argument("--no-closed-loop", action="store_true",
                   help="skip the closed loop (the scripted keeper's save rates)")
    _workers(p)
    p.add_argument("--seed", type=int, default=0, help="seed of the first open-loop shot")


def _ungm_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--runs", type=int, default=1000, help="simulated trajectories")
    p.add_argument("--particles", type=int, default=100, help="particles per filter, >= 2")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the trajectories and the filters' initial particles")


def _localization_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--walks", type=int, default=5,
                   help="walking episodes of 60 s, seeds SEED onwards")
    _workers(p)
    p.add_argument("--seed", type=int, default=0, help="seed of the first walk")


def _hough_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--trials", type=int, default=20, help="noise draws per ball position")
    p.add_argument("--seed", type=int, default=0, help="seed of the noise")


def _team_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--matches", type=int, default=4,
                   help="seeded matches per ball estimation, seeds SEED onwards")
    p.add_argument("--duration", type=float, default=60.0,
                   help="match length in seconds, 1..3600")
    p.add_argument("--keeper-shots", type=int, default=500,
                   help="the humanoid keeper's shots per ball estimation")
    p.add_argument("--no-keeper", "--no-closed-loop", dest="no_keeper", action="store_true",
                   help="skip the keeper's shots: the matches only")
    _workers(p)
    p.add_argument("--seed", type=int, default=0, help="seed of the first match")


def _image_options(what: str) -> Callable[[argparse.ArgumentParser], None]:
    def options(p: argparse.ArgumentParser) -> None:
        p.add_argument("--episodes", type=int, default=10, help=what)
        _workers(p)
        p.add_argument("--seed", type=int, default=0, help="seed of the episodes")

    return options


#: The reproductions' command lines, by the names of :data:`soccer_lab.papers.PAPERS`.
_PAPERS: dict[str, _Paper] = {
    "ekf": _Paper(
        "Ball prediction with latency compensation as in Zhao et al. (2012): in the open "
        "loop (the paper's setting) every estimator's error, lock-on and the floor the "
        "paper's noise figures imply; in the closed loop the scripted keeper's save rate "
        "per sensor preset and estimator.",
        _ekf_options,
        lambda run, a: run(a.out, a.episodes, a.shots, a.workers, closed=not a.no_closed_loop,
                           seed=a.seed)),
    "ungm": _Paper(
        "Xu et al.'s (2012) particle filters (bootstrap PF, FBPF, MFBPF) on the univariate "
        "nonstationary growth model: RMSE over many runs, paired differences and time per "
        "step.",
        _ungm_options,
        lambda run, a: run(a.out, a.runs, a.particles, seed=a.seed)),
    "localization": _Paper(
        "Guo and Li's (2013) KLD-sampling localization of a walking humanoid against "
        "fixed-size particle filters: errors, particle counts, time per update, recovery "
        "after a kidnapping.",
        _localization_options,
        lambda run, a: run(a.out, seed=a.seed, episodes=a.walks, workers=a.workers)),
    "hough": _Paper(
        "Xu et al.'s (2012) Hough-space fusion of several robots' ball sightings on the "
        "geometry of its Table 1: each weighting's error under several noise models.",
        _hough_options,
        lambda run, a: run(a.out, a.trials, seed=a.seed)),
    "team": _Paper(
        "Xu et al.'s (2012) team ball estimation in the closed loop: humanoid matches with "
        "each robot alone, team fusion and particle tracking, and the humanoid keeper's "
        "save rates.",
        _team_options,
        lambda run, a: run(a.out, a.matches, a.duration, a.keeper_shots, a.workers,
                           seed=a.seed, keeper=not a.no_keeper)),
    "meanshift": _Paper(
        "Li et al.'s (2010) feature-restricted mean-shift particle filter against plain "
        "particle filters, tracking manoeuvring robots in rendered overhead images (needs "
        "the pixels extra).",
        _image_options("seeded episodes of 10 s, seeds SEED onwards"),
        lambda run, a: run(a.out, seed=a.seed, workers=a.workers, episodes=a.episodes)),
    "following": _Paper(
        "Yu et al.'s (2010) Kalman-started mean shift against plain mean shift, following "
        "the ball in a turning humanoid's head-camera images (needs the pixels extra).",
        _image_options("episodes of 20 s in each scenario (turning in place, walking "
                       "towards the ball)"),
        lambda run, a: run(a.out, seed=a.seed, workers=a.workers, episodes=a.episodes)),
}

#: The counting options of the papers and their least values.
_PAPER_COUNTS = {"episodes": 1, "shots": 1, "runs": 1, "trials": 1, "matches": 1,
                 "keeper_shots": 1, "walks": 1, "particles": 2, "workers": 1}


def paper_parser() -> tuple[argparse.ArgumentParser, dict[str, argparse.ArgumentParser]]:
    """The parser of ``soccer-env paper`` and its sub-parsers, one per paper of
    :data:`soccer_lab.papers.PAPERS` (by name), each with ``--out`` and that paper's own
    options."""
    from soccer_lab.papers import PAPERS

    width = max(len(name) for name in PAPERS)
    listing = "\n".join(f"  {name:<{width}}  {PAPERS.description(name)}" for name in PAPERS)
    p = argparse.ArgumentParser(
        prog="soccer-env paper", formatter_class=HelpFormatter,
        description="Reproduce a source paper's claims: simulate its setting, print its "
                    "figures beside ours, and write tables (Markdown, CSV), a JSON summary "
                    f"and plots (PNG; the render extra) to --out.\n\npapers:\n{listing}",
        epilog="run 'soccer-env paper NAME --help' for a paper's options")
    subs = p.add_subparsers(dest="name", metavar="NAME", required=True,
                            help="the paper to reproduce, one of those above")
    parsers = {}
    for name, paper in _PAPERS.items():
        sub = subs.add_parser(name, formatter_class=HelpFormatter, description=paper.about)
        sub.add_argument("--out", default="paper_output",
                         help="output folder of the tables, summary and plots")
        paper.options(sub)
        parsers[name] = sub
    return p, parsers


def _cmd_paper(argv: list[str]) -> int:
    from soccer_lab.papers import PAPERS

    p, subs = paper_parser()
    args, unknown = p.parse_known_args(argv)
    sub = subs[args.name]
    if unknown:
        sub.error(f"unrecognized arguments: {' '.join(unknown)} (this paper's options: "
                  f"soccer-env paper {args.name} --help)")
    for name, least in _PAPER_COUNTS.items():
        value = getattr(args, name, None)
        if value is not None and value < least:
            sub.error(f"--{name.replace('_', '-')} must be >= {least}, got {value}")
    duration = getattr(args, "duration", None)
    if duration is not None and not 1.0 <= duration <= 3600.0:
        sub.error(f"--duration must be in 1..3600 seconds, got {duration}")
    extras.require(f"paper {args.name}")
    res = _PAPERS[args.name].call(PAPERS[args.name], args)
    print(res["text"])
    for path in res["files"]:
        print(f"wrote {path}")
    print(f"tables and plots in {args.out}/ ({res['seconds']:.0f} s)")
    return 0


# --------------------------------------------------------------------------------------------
# The commands
# --------------------------------------------------------------------------------------------

def _cmd_bench(argv: list[str]) -> int:
    from soccer_lab.bench import main as bench_main

    return bench_main(argv)


def _cmd_train(argv: list[str]) -> int:
    from soccer_lab.commands.train import main as train_main

    return train_main(argv)


def _cmd_imitate(argv: list[str]) -> int:
    from soccer_lab.commands.imitate import main as imitate_main

    return imitate_main(argv)


def _cmd_eval(argv: list[str]) -> int:
    from soccer_lab.commands.evaluate import main as eval_main

    return eval_main(argv)


def _cmd_ablation(argv: list[str]) -> int:
    from soccer_lab.commands.ablation import main as ablation_main

    return ablation_main(argv)


def _cmd_rate(argv: list[str]) -> int:
    from soccer_lab.commands.rate import main as rate_main

    return rate_main(argv)


def _cmd_serve(argv: list[str]) -> int:
    from soccer_lab.commands.serve import main as serve_main

    return serve_main(argv)


def _cmd_connect(argv: list[str]) -> int:
    from soccer_lab.commands.connect import main as connect_main

    return connect_main(argv)


def _cmd_play(argv: list[str]) -> int:
    # pygame first: the command's module draws with it.
    extras.require("play")
    from soccer_lab.commands.play import main as play_main

    return play_main(argv)


#: The commands of ``soccer-env``, in the order ``soccer-env --help`` lists them: name ->
#: (the function that runs it on the arguments after its name and returns the exit status,
#: its one-line summary).
COMMANDS: dict[str, tuple[Callable[[list[str]], int], str]] = {
    "demo": (_cmd_demo, "run the goalkeeper demo and write its video and figures"),
    "bench": (_cmd_bench, "measure environment step rates against bare pymunk"),
    "paper": (_cmd_paper, "reproduce a source paper's claims (tables and plots)"),
    "train": (_cmd_train, "train a policy with stable-baselines3, or RLlib on a Ray cluster"),
    "imitate": (_cmd_imitate, "train a keeper by DAgger with a privileged teacher"),
    "eval": (_cmd_eval, "evaluate a keeper policy on the fixed shot suite"),
    "ablation": (_cmd_ablation, "compare estimators in closed loop, per sensor preset"),
    "rate": (_cmd_rate, "rate SSL match teams by a round robin of seeded matches"),
    "serve": (_cmd_serve, "serve an SSL match over the league's protocols (vision, referee, "
                          "robot control)"),
    "connect": (_cmd_connect, "play a policy on live SSL vision and referee, sending robot "
                              "control"),
    "play": (_cmd_play, "drive a robot with the keyboard against the scripted team"),
    "list": (_cmd_list, "list environments, presets and perception options"),
}


def parsers() -> dict[str, argparse.ArgumentParser]:
    """Every command's option parser by its command line (``"paper ekf"`` for each paper's)."""
    from soccer_lab.bench import parser as bench_parser
    from soccer_lab.commands import (
        ablation,
        connect,
        evaluate,
        imitate,
        play,
        rate,
        serve,
        train,
    )

    paper, papers = paper_parser()
    return {"demo": _demo_parser(), "bench": bench_parser(), "paper": paper,
            **{f"paper {name}": sub for name, sub in papers.items()},
            "train": train.parser(), "imitate": imitate.parser(), "eval": evaluate.parser(),
            "ablation": ablation.parser(), "rate": rate.parser(), "list": _list_parser(),
            "serve": serve.parser(), "connect": connect.parser(), "play": play.parser()}


def _usage() -> str:
    lines = ["usage: soccer-env [-h] [-V] <command> [options]", "",
             "Robot-soccer environments (RoboCup SSL and humanoid): demo, benchmarks, "
             "training,", "evaluation and the source papers' reproductions.", "",
             "commands:"]
    lines += [f"  {name:8s}  {help_}" for name, (_, help_) in COMMANDS.items()]
    lines += ["", "options:", "  -h, --help     show this help and exit",
              "  -V, --version  print the version and exit", "",
              "run 'soccer-env <command> --help' for a command's options"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Run ``soccer-env`` with the arguments ``argv`` (default: the command line's); returns
    the exit status (a command-line error or a missing extra exits with status 2)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in ("-V", "--version"):
        print(f"soccer-env {version()}")
        return 0
    if not argv or argv[0] in ("-h", "--help"):
        print(_usage())
        return 0
    if argv[0] not in COMMANDS:
        from difflib import get_close_matches

        close = get_close_matches(argv[0], list(COMMANDS), n=1)
        guess = f" (did you mean {close[0]!r}?)" if close else ""
        print(f"soccer-env: unknown command {argv[0]!r}{guess}\n\n{_usage()}", file=sys.stderr)
        return 2
    try:
        return COMMANDS[argv[0]][0](argv[1:])
    except BrokenPipeError:  # the reader went away (soccer-env list | head): stop quietly
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
