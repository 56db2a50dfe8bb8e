"""``soccer-env connect``: a policy on live SSL protocols (:class:`agents.live.SSLClient`):
SSL-Vision and referee messages from any source (``soccer-env serve``, grSim, the ER-Force
simulator, a field) through the package's perception to the policy, and its commands back
through the simulation protocol's robot control.

Addresses are ``HOST:PORT`` with the league's defaults: vision from the multicast group
224.5.23.2:10006, referee messages from 224.5.23.1:10003, robot control to 127.0.0.1:10301
(the blue team's port of a simulator on this machine). ``--loopback`` receives on 127.0.0.1.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

from soccer_lab.cli_args import (
    HelpFormatter,
    add_env_arguments,
    add_trust_argument,
    env_kwargs_from_args,
)
from soccer_lab.commands.serve import parse_addresses

__all__ = ["parser", "main"]

_EXAMPLE = ("soccer-env serve --loopback --task goalkeeper --vision ssl-2012 --control-hz 25 "
            "--stepped --wait-for blue &\n  soccer-env connect --loopback --stepped "
            "--policy baseline:keeper-ppo-residual-ssl2012 --duration 60")


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env connect``."""
    p = argparse.ArgumentParser(
        prog="soccer-env connect", formatter_class=HelpFormatter,
        description="Play a policy on live SSL protocols: read SSL-Vision and the referee, "
                    "run the package's perception (the environment's, as its options and "
                    "a baseline's own settings make it) and the policy, send robot control. "
                    "A shipped baseline brings the settings it was trained with.",
        epilog=f"example:\n  {_EXAMPLE}")
    p.add_argument("--policy", default="scripted",
                   help="a task's: scripted, idle, baseline:NAME, a .npz model or a training "
                        "run folder; a match team's: scripted, idle, a shipped team "
                        "(ssl-team-2v2) or a .npz team file")
    p.add_argument("--task", choices=["goalkeeper", "shootout", "match"], default="goalkeeper",
                   help="what the policy plays: a task's learner (blue robot 0), or every "
                        "robot of --team in a match without the game flow")
    p.add_argument("--team", choices=["blue", "yellow"], default="blue",
                   help="the team played in a match")
    add_env_arguments(p)
    p.add_argument("--duration", type=float, default=60.0,
                   help="seconds of the source's time to play")
    p.add_argument("--stepped", action="store_true",
                   help="act once per referee message, in lock step with a stepped "
                        "soccer-env serve, instead of every control step of wall time")
    p.add_argument("--timeout", type=float, default=5.0,
                   help="seconds to wait for the source before giving up")
    p.add_argument("--loopback", action="store_true",
                   help="receive on 127.0.0.1 with the league's ports (overridden by the "
                        "address options)")
    p.add_argument("--vision-address", default=None,
                   help="where vision packets are received (default: 224.5.23.2:10006)")
    p.add_argument("--referee-address", default=None,
                   help="where referee messages are received (default: 224.5.23.1:10003)")
    p.add_argument("--control-address", default=None,
                   help="where robot control is sent (default: 127.0.0.1:10301 for blue, "
                        "127.0.0.1:10302 for yellow)")
    add_trust_argument(p)
    return p


def _addresses(args: argparse.Namespace) -> dict[str, Any]:
    from soccer_env.protocol import udp

    host = "127.0.0.1" if args.loopback else None
    defaults = {"vision_address": (host or udp.VISION_ADDRESS[0], udp.VISION_ADDRESS[1]),
                "referee_address": (host or udp.REFEREE_ADDRESS[0], udp.REFEREE_ADDRESS[1]),
                "control_address": ("127.0.0.1", udp.BLUE_CONTROL_PORT if args.team == "blue"
                                    else udp.YELLOW_CONTROL_PORT)}
    return parse_addresses(args, defaults, send=("control_address",))


def _env_kwargs(args: argparse.Namespace) -> dict:
    """The environment's settings: a baseline's or a shipped team's own, under the options
    given."""
    from agents.baselines import TEAMS, baseline_env_kwargs, team_path

    base: dict = {}
    if str(args.policy).startswith("baseline:"):
        base = baseline_env_kwargs(args.policy.split(":", 1)[1])
    elif args.task == "match" and args.policy in TEAMS:
        from agents.policies import NumpyPolicy

        base = dict(NumpyPolicy.load(team_path(args.policy)).meta.get("eval_kwargs", {}))
    return env_kwargs_from_args(args, base)


def main(argv: list[str] | None = None) -> int:
    """``soccer-env connect``: check the options, play until the duration is over."""
    p = parser()
    args = p.parse_args(argv)
    from soccer_lab import extras

    if not 0.1 <= args.duration <= 360_000.0:
        p.error(f"--duration must be in [0.1, 360000] s, got {args.duration}")
    if not 0.001 <= args.timeout <= 3600.0:
        p.error(f"--timeout must be in [0.001, 3600] s, got {args.timeout}")
    try:
        addresses = _addresses(args)
    except ValueError as exc:
        p.error(str(exc))
    extras.require("connect")
    from agents.live import SSLClient

    try:
        client = SSLClient(args.policy, args.task, _env_kwargs(args),
                           addresses["vision_address"], addresses["referee_address"],
                           addresses["control_address"], trust=args.trust, team=args.team)
    except (ValueError, TypeError, KeyError, OSError, FileNotFoundError) as exc:
        p.error(str(exc))
    try:
        what = f"{args.task}, {args.team}" if args.task == "match" else args.task
        print(f"playing {args.policy} ({what}): vision from "
              f"{addresses['vision_address']}, referee from {addresses['referee_address']}, "
              f"robot control to {addresses['control_address']}; "
              f"{'stepped' if args.stepped else 'real time'}", flush=True)
        t0 = time.perf_counter()
        acted = client.run(args.duration, realtime=not args.stepped, timeout=args.timeout)
        seconds = time.perf_counter() - t0
        shots = f"{client.shots} shots, " if args.task != "match" else ""
        print(f"acted {acted} times in {seconds:.1f} s; {shots}score "
              f"{client.score[0]}:{client.score[1]} (blue:yellow); {client.vision.frames} "
              f"frames; refused {dict(client.errors) or 'none'}; dropped "
              f"{dict(client.vision.dropped + client.referee.dropped) or 'none'}")
        if not acted:
            print(f"nothing came from {addresses['referee_address']} within "
                  f"{args.timeout:g} s: is the source running?")
            return 1
    except KeyboardInterrupt:
        print("stopped")
    finally:
        client.close()
    return 0
