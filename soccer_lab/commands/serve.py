"""``soccer-env serve``: an SSL match, or the keeper's or the shootout's task, served over the
league's protocols (:class:`soccer_env.protocol.server.SSLServer`): the vision preset's cameras
as SSL-Vision packets, the referee's ``Referee`` messages (the game controller's with
``--game``), and the robots driven by the simulation protocol's robot control, answered with
feedback.

Addresses are ``HOST:PORT`` with the league's defaults: vision to the multicast group
224.5.23.2:10006, referee messages to 224.5.23.1:10003, robot control read on port 10301 (blue)
and 10302 (yellow) and simulator control on port 10300 of every interface. To keep everything
on one machine, give 127.0.0.1 addresses (``--loopback``).
"""

from __future__ import annotations

import argparse
import time
from collections import Counter
from collections.abc import Sequence
from typing import Any

from soccer_lab.cli_args import HelpFormatter

__all__ = ["parser", "main", "parse_address", "parse_addresses"]

_EXAMPLE = ("soccer-env serve --loopback --blue 2 --yellow 2 --game --vision ssl-2012 "
            "--duration 60")


def parse_address(text: str, option: str, bind: bool = True) -> tuple[str, int]:
    """``HOST:PORT`` as ``(host, port)`` (port 0, any free port, only for an address to
    bind); ``ValueError`` naming ``option`` otherwise."""
    from soccer_env.protocol.udp import check_address

    host, sep, port = text.rpartition(":")
    if not sep or not port.isdigit():
        raise ValueError(f"{option} must be HOST:PORT (an IPv4 host), got {text!r}")
    try:
        return check_address((host, int(port)), option, bind)
    except ValueError as exc:
        raise ValueError(f"{exc} (from {text!r})") from None


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env serve``."""
    p = argparse.ArgumentParser(
        prog="soccer-env serve", formatter_class=HelpFormatter,
        description="Serve an SSL match (or the keeper's or the shootout's task, one shot "
                    "after another) over the league's protocols: SSL-Vision packets of the "
                    "vision preset's cameras (rate, latency, noise, drops, occlusion), the "
                    "referee's messages, and robot control through the simulation protocol. "
                    "Real time by default; --stepped steps as fast as the teams of --wait-for "
                    "send commands (the same episode for the same seed and commands), with a "
                    "referee message after every step carrying its time.",
        epilog=f"example:\n  {_EXAMPLE}")
    p.add_argument("--task", choices=["match", "goalkeeper", "shootout"], default="match",
                   help="what is served: a match, or a task whose learner (blue robot 0) the "
                        "blue robot control commands")
    p.add_argument("--episodes", type=int, default=1000,
                   help="shots a task serves (seeds SEED onwards)")
    p.add_argument("--blue", type=int, default=2, help="robots of the blue team")
    p.add_argument("--yellow", type=int, default=2, help="robots of the yellow team")
    p.add_argument("--field", default=None,
                   help="the field preset (default: the match's default)")
    p.add_argument("--game", action="store_true",
                   help="play the SSL game flow (Division B rules) and send referee messages")
    p.add_argument("--vision", default="ssl-2012", help="the cameras' vision preset")
    p.add_argument("--duration", type=float, default=300.0,
                   help="playing time of the match [s]")
    p.add_argument("--control-hz", type=float, default=60.0,
                   help="physics steps (and command reads) per second")
    p.add_argument("--seed", type=int, default=0, help="the match's seed")
    p.add_argument("--stepped", action="store_true",
                   help="step as fast as the teams of --wait-for send commands instead of in "
                        "real time")
    p.add_argument("--wait-for", action="append", choices=["blue", "yellow"], default=[],
                   help="with --stepped, a team whose command each step waits for (repeatable;"
                        " none: step as fast as possible)")
    p.add_argument("--timeout", type=float, default=1.0,
                   help="seconds a stepped step waits for the commands before it goes on")
    p.add_argument("--loopback", action="store_true",
                   help="every address on 127.0.0.1 with the league's ports (overridden by "
                        "the address options)")
    p.add_argument("--vision-address", action="append", default=None,
                   help="where vision packets go; repeatable, each gets every packet (e.g. "
                        "one per team's software on loopback) (default: 224.5.23.2:10006)")
    p.add_argument("--referee-address", action="append", default=None,
                   help="where referee messages go; repeatable (default: 224.5.23.1:10003)")
    p.add_argument("--blue-control", default=None,
                   help="where blue's robot control is read (default: 0.0.0.0:10301)")
    p.add_argument("--yellow-control", default=None,
                   help="where yellow's robot control is read (default: 0.0.0.0:10302)")
    p.add_argument("--simulator-control", default=None,
                   help="where simulator control (teleporting the ball and robots) is read "
                        "(default: 0.0.0.0:10300)")
    return p


def _addresses(args: argparse.Namespace) -> dict[str, Any]:
    from soccer_env.protocol import udp

    host = "127.0.0.1" if args.loopback else None
    defaults = {"vision_address": (host or udp.VISION_ADDRESS[0], udp.VISION_ADDRESS[1]),
                "referee_address": (host or udp.REFEREE_ADDRESS[0], udp.REFEREE_ADDRESS[1]),
                "blue_control": (host or "0.0.0.0", udp.BLUE_CONTROL_PORT),
                "yellow_control": (host or "0.0.0.0", udp.YELLOW_CONTROL_PORT),
                "simulator_control": (host or "0.0.0.0", udp.SIMULATION_CONTROL_PORT)}
    return parse_addresses(args, defaults, send=("vision_address", "referee_address"))


def parse_addresses(args: argparse.Namespace, defaults: dict[str, Any],
                    send: Sequence[str]) -> dict[str, Any]:
    """The address options ``defaults`` names (option ``--a-b`` for name ``a_b``), each
    parsed by :func:`parse_address` (those of ``send`` as addresses to send to, the others
    to bind), else its default; a repeatable option given several times gives a list."""
    out: dict = {}
    for name, default in defaults.items():
        given = getattr(args, name)
        option = "--" + name.replace("_", "-")
        texts = given if isinstance(given, list) else [given] if given else []
        parsed = [parse_address(text, option, bind=name not in send) for text in texts]
        out[name] = default if not parsed else parsed[0] if len(parsed) == 1 else parsed
    return out


def main(argv: list[str] | None = None) -> int:
    """``soccer-env serve``: check the options, serve until the match ends."""
    p = parser()
    args = p.parse_args(argv)
    from soccer_lab import extras

    for name, value, low, high in (("--blue", args.blue, 0, 11), ("--yellow", args.yellow, 0, 11)):
        if not low <= value <= high:
            p.error(f"{name} must be in {low}..{high}, got {value}")
    if not 1.0 <= args.duration <= 36_000.0:
        p.error(f"--duration must be in [1, 36000] s, got {args.duration}")
    if not 10.0 <= args.control_hz <= 1000.0:
        p.error(f"--control-hz must be in [10, 1000], got {args.control_hz}")
    if not 1 <= args.episodes <= 10_000_000:
        p.error(f"--episodes must be in 1..10000000, got {args.episodes}")
    if not 0.001 <= args.timeout <= 3600.0:
        p.error(f"--timeout must be in [0.001, 3600] s, got {args.timeout}")
    if args.wait_for and not args.stepped:
        p.error("--wait-for needs --stepped (in real time the server keeps the wall clock)")
    try:
        addresses = _addresses(args)
    except ValueError as exc:
        p.error(str(exc))
    extras.require("serve")
    from soccer_env.protocol.server import SSLServer

    kwargs: dict = {"control_dt": 1.0 / args.control_hz}
    if args.task == "match":
        kwargs.update(blue=args.blue, yellow=args.yellow, game=args.game,
                      match_duration=args.duration)
    if args.field:
        kwargs["field"] = args.field
    try:
        server = SSLServer(kwargs, args.vision, addresses["vision_address"],
                           addresses["referee_address"],
                           (addresses["blue_control"], addresses["yellow_control"]),
                           addresses["simulator_control"], task=args.task)
    except (ValueError, KeyError, OSError) as exc:
        p.error(str(exc))
    try:
        server.reset(seed=args.seed)
        print(f"serving: vision to {addresses['vision_address']}, referee to "
              f"{addresses['referee_address']}, robot control on "
              f"{server.control_addresses[0]} (blue) and {server.control_addresses[1]} "
              f"(yellow), simulator control on {server.simulator_address}; "
              f"{'stepped' if args.stepped else 'real time'}", flush=True)
        t0 = time.perf_counter()
        steps = server.run(realtime=not args.stepped,
                           episodes=args.episodes if args.task != "match" else None,
                           wait_for=args.wait_for, timeout=args.timeout)
        seconds = time.perf_counter() - t0
        if server.outcomes:
            goals = server.outcomes.count("goal")
            print(f"{len(server.outcomes)} shots: {goals} goals; outcomes "
                  f"{dict(Counter(server.outcomes))}")
        played = f" ({server.time:.1f} s of match time)" if args.task == "match" else ""
        print(f"served {steps} steps{played} in {seconds:.1f} s; "
              f"{server.vision.sent} vision packets, {server.referee.sent} referee messages; "
              f"commands received {server.received}, refused {server.refused}; dropped "
              f"{dict(server.dropped) or 'none'}")
    except KeyboardInterrupt:
        print(f"stopped at {server.time:.1f} s of match time")
    finally:
        server.close()
    return 0
