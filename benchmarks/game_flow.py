"""Scripted matches under the game flow: how long a match takes beside its playing time, how
ball placements end, and the fouls each team commits.

Usage: ``python benchmarks/game_flow.py [--robot ssl|humanoid] [--size 2] [--matches 10]
[--duration 60] [--start-seed 0] [--team FILE] [--json FILE]``.

``--matches`` seeded matches (seeds ``--start-seed`` onwards) of the scripted team against
itself (:class:`agents.scripted.ScriptedTeam`, or :class:`agents.scripted.HumanoidTeam` with
``--robot humanoid``), ``--size`` robots a side, ``game=True`` (the league's rules, robots
placing the ball), truth observations, ``--duration`` seconds of playing time. Per match:

* **match time over playing time**: the simulated seconds the match took (stops, placements
  and restarts included) divided by its playing time, which runs only while a team may play
  the ball (the rule book's clock); a match still going after :data:`MAX_RATIO` times its
  playing time is stopped there and listed as not over;
* **placements**: ball placements that succeeded and that failed (SSL; the humanoid referee
  places the ball itself);
* **fouls** per match by kind (:data:`soccer_env.sim.game.types.FOULS`; the humanoid laws'
  removal penalties count as ``defender_too_close_to_kick_point``), and yellow and red cards.

With ``--team FILE`` (a numpy team file) that team plays the scripted team instead, at 30
commands a second as the shipped teams do, match ``k`` on seed ``--start-seed + k // 2`` with
the file's team blue when ``k`` is even, and each foul is also counted for the team that
committed it (``team`` or ``scripted``).

Means per match with a 95 % interval (Student-t over matches) are printed as a table.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections import Counter
from pathlib import Path
from typing import Any

import soccer_env
from agents.common.stats import mean_interval
from agents.scripted import TEAMS, HumanoidTeam, ScriptedTeam
from agents.studies.matches import team_policy
from soccer_env.sim.game.types import FOULS

#: Game events counted besides the fouls.
COUNTED = ("placement_succeeded", "placement_failed", "yellow_card", "red_card")


#: The control step of a ``--team`` match [s]: the shipped teams' 30 commands a second.
TEAM_CONTROL_DT = 1.0 / 30.0

#: A match is stopped (and counted as unfinished) after this many times its playing time.
MAX_RATIO = 10.0


def play(robot: str, size: int, duration: float, seed: int, team_file: str | None = None,
         team_blue: bool = True) -> dict[str, Any]:
    """One match under the game flow, scripted against scripted or ``team_file``'s team
    (blue if ``team_blue``) against the scripted team: its match time [s], playing time [s],
    whether it ended within :data:`MAX_RATIO` times its playing time, the count of each game
    event (both teams together) and, with ``team_file``, of each foul per team
    (``"team:<kind>"``, ``"scripted:<kind>"``)."""
    kwargs: dict[str, Any] = {"blue": size, "yellow": size, "game": True,
                              "match_duration": duration}
    if robot == "humanoid":
        kwargs["robot"] = "humanoid"
    if team_file is not None:
        kwargs["control_dt"] = TEAM_CONTROL_DT
    env = soccer_env.parallel_env(**kwargs)
    obs, _ = env.reset(seed=seed)
    team = HumanoidTeam if robot == "humanoid" else ScriptedTeam
    teams = [team.for_env(env, side) for side in TEAMS]
    ours = 0 if team_blue else 1
    if team_file is not None:
        teams[ours] = team_policy(team_file, env, TEAMS[ours])
    events: Counter = Counter()
    by_team: Counter = Counter()
    steps, limit = 0, int(MAX_RATIO * duration / env.world.control_dt)
    while env.agents and steps < limit:
        actions: dict[str, Any] = {}
        for t in teams:
            actions.update(t(obs))
        obs, _, _, _, infos = env.step(actions)
        steps += 1
        info = next(iter(infos.values()), None)
        if info is None:
            continue
        for e in info["game"]["events"]:
            events[e["kind"]] += 1
            if team_file is not None and e["kind"] in FOULS and e.get("team") in TEAMS:
                who = "team" if TEAMS.index(e["team"]) == ours else "scripted"
                by_team[f"{who}:{e['kind']}"] += 1
    seconds = steps * env.world.control_dt
    finished = not env.agents
    env.close()
    return {"seed": seed, "match_seconds": seconds, "playing_seconds": duration,
            "finished": finished, "events": dict(events), "by_team": dict(by_team)}


def _mean_ci(values: list[float]) -> str:
    """``mean (low to high)``, Student-t 95 % over matches (:func:`mean_interval`)."""
    m, lo, hi = mean_interval(values)
    return f"{m:.2f} ({lo:.2f} to {hi:.2f})" if math.isfinite(lo) else f"{m:.2f}"


def report(rows: list[dict[str, Any]]) -> None:
    """The table of means per match."""
    kinds = sorted({k for r in rows for k in r["events"]
                    if k in FOULS or k in COUNTED})
    print(f"| per match ({len(rows)} matches) | mean (95 % CI) |")
    print("|---|---|")
    ratio = [r["match_seconds"] / r["playing_seconds"] for r in rows]
    unfinished = [r["seed"] for r in rows if not r["finished"]]
    print(f"| match time / playing time | {_mean_ci(ratio)} |")
    print(f"| matches not over after {MAX_RATIO:g} times their playing time | "
          f"{len(unfinished)} (seeds {unfinished}) |")
    fouls = [sum(v for k, v in r["events"].items() if k in FOULS) for r in rows]
    print(f"| fouls, all kinds | {_mean_ci(fouls)} |")
    for kind in kinds:
        print(f"| {kind} | {_mean_ci([float(r['events'].get(kind, 0)) for r in rows])} |")
    split = sorted({k for r in rows for k in r.get("by_team", {})})
    for who in ("team", "scripted") if split else ():
        total = [float(sum(v for k, v in r["by_team"].items() if k.startswith(who + ":")))
                 for r in rows]
        print(f"| fouls, {who} | {_mean_ci(total)} |")
        for key in (k for k in split if k.startswith(who + ":")):
            print(f"| {key.split(':', 1)[1]}, {who} | "
                  f"{_mean_ci([float(r['by_team'].get(key, 0)) for r in rows])} |")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--robot", choices=("ssl", "humanoid"), default="ssl")
    p.add_argument("--size", type=int, default=2, help="robots a side")
    p.add_argument("--matches", type=int, default=10)
    p.add_argument("--duration", type=float, default=60.0, help="playing time [s]")
    p.add_argument("--start-seed", type=int, default=0)
    p.add_argument("--team", default=None,
                   help="a numpy team file to play the scripted team (default: scripted "
                        "against scripted)")
    p.add_argument("--json", default=None, help="also write every match's counts here")
    args = p.parse_args(argv)
    for name in ("size", "matches"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be >= 1, got {getattr(args, name)}")
    if not (math.isfinite(args.duration) and args.duration > 0):
        p.error(f"--duration must be a finite number > 0, got {args.duration}")
    if args.team is not None and not Path(args.team).is_file():
        p.error(f"--team: no such file {args.team!r}")
    if args.team is None:
        rows = [play(args.robot, args.size, args.duration, args.start_seed + k)
                for k in range(args.matches)]
    else:
        rows = [play(args.robot, args.size, args.duration, args.start_seed + k // 2,
                     args.team, k % 2 == 0) for k in range(args.matches)]
    report(rows)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
