"""A keeper through the SSL protocols against the same keeper in process: the server, in a
process of its own, serves the keeper task over loopback (127.0.0.1); the client
(:class:`agents.live.SSLClient`) runs the keeper's perception on the packets and sends its
commands back.

Usage: ``python benchmarks/ssl_closed_loop.py [--policy baseline:keeper-ppo-residual-ssl2012]
[--shots 1000] [--start-seed 0] [--realtime-seconds 20] [--matches 0] [--team ssl-team-2v2]
[--vision realistic]``.

1. **Stepped.** The server waits for the client's command every step (``--wait-for blue``)
   and sends a referee message after it; ``--shots`` shots, seeds ``--start-seed`` onwards.
   The save rate with its Wilson 95 % interval beside :func:`agents.runs.evaluation.evaluate`
   of the same policy on the same seeds in process, and the closed loop's steps per second.
   The served cameras draw their noise from their own stream, so the two are the same
   experiment with different camera noise.
2. **Real time.** The server keeps the wall clock (a step every control step, each packet
   sent at its delivery time) and the client acts every control step at the present, for
   ``--realtime-seconds``: the shots played and saved, the actions per second, and the
   client's compute time per action.

3. **Matches** (``--matches N``): the shipped team (``--team``) against the scripted team, both
   perceiving through ``--vision`` cameras, each team played by a client of its own through
   the sockets (server and clients in one process, in lock step), ``N`` matches of the
   team's own settings (2 vs 2, 60 s, 30 commands a second) with seeds ``--start-seed``
   onwards, the team blue in each; the goal difference per match with its 95 % interval
   beside :func:`agents.studies.matches.play_match` of the same sides and seeds in process.

The policy's environment settings are a baseline's own (``control_dt``, vision preset); for
another policy give them with ``--env-kwarg`` as ``soccer-env eval`` takes them.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import time
from typing import Any

import numpy as np

from agents.baselines import baseline_env_kwargs
from agents.common.stats import wilson
from agents.live import SSLClient, locked_match
from agents.runs.evaluation import evaluate

LOOPBACK = ("127.0.0.1", 0)


def _serve(kwargs: dict[str, Any], vision: str, addresses: tuple, seed: int, shots: int,
           realtime: float | None, pipe: Any) -> None:
    """The server's process: serve ``shots`` shots (stepped) or ``realtime`` seconds."""
    from soccer_env.protocol.server import SSLServer

    server = SSLServer(kwargs, vision, addresses[0], addresses[1], (LOOPBACK, LOOPBACK),
                       LOOPBACK, task="goalkeeper")
    pipe.send(server.control_addresses[0])
    pipe.recv()  # the client is ready
    try:
        server.reset(seed=seed, clock=0.0 if realtime is None else None)
        t0 = time.perf_counter()
        if realtime is None:
            steps = server.run(realtime=False, episodes=shots, wait_for=("blue",), timeout=5.0)
        else:
            steps = server.run(duration=realtime, realtime=True)
        pipe.send({"outcomes": server.outcomes, "steps": steps, "missed": server.missed,
                   "seconds": time.perf_counter() - t0, "refused": server.refused})
    finally:
        server.close()


def closed_loop(policy: str, env_kwargs: dict[str, Any], shots: int, seed: int,
                realtime: float | None = None) -> dict[str, Any]:
    """The keeper ``policy`` through the sockets: stepped for ``shots`` shots, or in real
    time for ``realtime`` seconds."""
    vision = env_kwargs.get("perception", "realistic")
    if not isinstance(vision, str):
        vision = vision["vision"]
    client = SSLClient(policy, "goalkeeper", env_kwargs, LOOPBACK, LOOPBACK, ("127.0.0.1", 9))
    served = {k: v for k, v in env_kwargs.items() if k not in ("obs_mode", "perception")}
    ours, theirs = mp.Pipe()
    proc = mp.get_context("spawn").Process(
        target=_serve, args=(served, vision, (client.vision.address, client.referee.address),
                             seed, shots, realtime, theirs))
    proc.start()
    compute = 0.0
    try:
        client.control_address = ours.recv()
        ours.send("ready")
        t0 = time.perf_counter()
        if realtime is None:
            acted = 0
            while not ours.poll():
                acted += client.step(timeout=0.2)
        else:
            c0 = time.process_time()
            acted = client.run(realtime, realtime=True, timeout=10.0)
            compute = time.process_time() - c0
        seconds = time.perf_counter() - t0
        result = ours.recv()
    finally:
        proc.join(timeout=30)
        client.close()
    outcomes = result["outcomes"]
    saves = sum(o not in ("goal", "time limit") for o in outcomes)
    return {"shots": len(outcomes), "saves": saves, "outcomes": outcomes,
            "interval": wilson(saves, len(outcomes)) if outcomes else (0.0, 0.0),
            "steps": result["steps"], "missed": result["missed"], "acted": acted,
            "seconds": seconds, "client_cpu_per_action_ms": 1e3 * compute / max(acted, 1)}


def matches(team: str, vision: str, n: int, seed: int, seconds: float | None = None
            ) -> dict[str, Any]:
    """``n`` matches of ``team`` against the scripted team through the sockets and in
    process (``seconds`` long, default the team's own settings): the goal differences and
    their mean with a normal 95 % interval."""
    from agents.baselines import TEAMS, team_path
    from agents.policies import NumpyPolicy
    from agents.studies.matches import Side, play_match

    path = str(team_path(team)) if team in TEAMS else team
    base = dict(NumpyPolicy.load(path).meta.get("eval_kwargs") or
                {"blue": 2, "yellow": 2, "match_duration": 60.0, "control_dt": 1 / 30})
    if seconds is not None:
        base["match_duration"] = float(seconds)
    side = {"obs_mode": "perceived", "perception": {"vision": vision}}
    out: dict[str, Any] = {}
    t0 = time.perf_counter()
    served = [locked_match(path, "scripted", base, vision, seed + k).score for k in range(n)]
    out["served_seconds"] = time.perf_counter() - t0
    local = [play_match(base, Side(path, **side), Side("scripted", **side), seed + k)["goals"]
             for k in range(n)]
    for name, scores in (("served", served), ("local", local)):
        gd = np.array([a - b for a, b in scores], dtype=float)
        half = 1.96 * gd.std(ddof=1) / np.sqrt(n) if n > 1 else float("nan")
        out[name] = {"goals": (sum(a for a, _ in scores), sum(b for _, b in scores)),
                     "gd": float(gd.mean()), "interval": (gd.mean() - half, gd.mean() + half)}
    out["steps"] = n * round(base["match_duration"] / base["control_dt"])
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--policy", default="baseline:keeper-ppo-residual-ssl2012")
    p.add_argument("--env-kwarg", action="append", default=[], metavar="KEY=JSON")
    p.add_argument("--shots", type=int, default=1000)
    p.add_argument("--start-seed", type=int, default=0)
    p.add_argument("--realtime-seconds", type=float, default=20.0)
    p.add_argument("--matches", type=int, default=0)
    p.add_argument("--team", default="ssl-team-2v2")
    p.add_argument("--vision", default="realistic")
    p.add_argument("--match-seconds", type=float, default=None)
    args = p.parse_args(argv)
    kwargs: dict[str, Any] = {}
    if args.policy.startswith("baseline:"):
        kwargs.update(baseline_env_kwargs(args.policy.split(":", 1)[1]))
    for item in args.env_kwarg:
        key, _, value = item.partition("=")
        kwargs[key] = json.loads(value)
    s = closed_loop(args.policy, kwargs, args.shots, args.start_seed)
    local = evaluate(args.policy, kwargs, args.shots, args.start_seed)
    lo, hi = s["interval"]
    print(f"{args.policy} on Goalkeeper-v0 ({kwargs}), shots seeded {args.start_seed} onwards")
    print(f"  in process:          {100 * local.save_rate:.1f} % of {local.episodes} "
          f"(95 %: {100 * local.ci_low:.1f}-{100 * local.ci_high:.1f})")
    print(f"  through the sockets: {100 * s['saves'] / s['shots']:.1f} % of {s['shots']} "
          f"(95 %: {100 * lo:.1f}-{100 * hi:.1f}); {s['steps']} steps in {s['seconds']:.1f} s, "
          f"{s['steps'] / s['seconds']:.0f} steps/s in lock step, {s['missed']} steps missed")
    if args.realtime_seconds > 0:
        r = closed_loop(args.policy, kwargs, 0, args.start_seed, args.realtime_seconds)
        print(f"  real time, {args.realtime_seconds:g} s: {r['shots']} shots, {r['saves']} "
              f"saved; {r['acted'] / r['seconds']:.1f} actions/s; the client's CPU "
              f"{r['client_cpu_per_action_ms']:.2f} ms per action")
    if args.matches > 0:
        m = matches(args.team, args.vision, args.matches, args.start_seed, args.match_seconds)
        print(f"{args.team} (blue) against the scripted team, {args.matches} matches, "
              f"{args.vision} cameras, seeds {args.start_seed} onwards: goal difference per "
              "match (95 %)")
        for name, label in (("local", "in process"), ("served", "through the sockets")):
            r = m[name]
            lo, hi = r["interval"]
            print(f"  {label + ':':21s}{r['gd']:+.2f} ({lo:+.2f} to {hi:+.2f}), goals "
                  f"{r['goals'][0]}:{r['goals'][1]}")
        print(f"  served: {m['steps']} steps in {m['served_seconds']:.1f} s, "
              f"{m['steps'] / m['served_seconds']:.0f} steps/s with both teams' clients")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
