"""The perceived SSL team under the game flow: its head-to-heads, fouls and ratings.

Usage: ``python benchmarks/ssl_team_perceived.py --team FILE [--matches 200] [--idle 40]
[--round-robin 20] [--start-seed 50000] [--ball-filter kick] [--robot-prediction commands]
[--workers N] [--out FILE]``.

Every match is 2 vs 2, 60 s of playing time at 30 commands a second, under the SSL game flow
(Division B rules), each team perceiving through its own ``ssl-2012`` cameras and filters,
the ball tracked by ``--ball-filter`` (the kick-aware tracker by default), its own robots
predicted through the commands it sent (``--robot-prediction``; the match of
``examples/train_ssl_team.py --setting perceived-game``'s evaluations), on seeds from
``--start-seed`` (held out: training drew its matches' seeds from 0 and evaluated its
copies from 10,000):

1. the team (a numpy team file, e.g. ``OUT/final_team.npz`` of the training) against the
   scripted team, ``--matches`` matches (each seed from both sides): wins, draws, losses with Wilson
   intervals, the goal difference per match with its interval paired by seed;
2. the team and the scripted team each against the idle team, ``--idle`` matches;
3. fouls and cards per match of every side in those matches;
4. with ``--round-robin N``: Elo ratings (:func:`agents.studies.rating.fit_ratings`, the
   scripted team at 1000) from the matches above and ``N`` more per other pair of the team,
   its training's copies (the ``checkpoints/`` folder beside the file), the scripted and the
   idle team.
"""

from __future__ import annotations

import argparse
import itertools
import json
import time
from pathlib import Path

from agents.studies.matches import HeadToHead, Side, checkpoint_sides, head_to_head
from agents.studies.rating import fit_ratings, rating_table, round_robin
from soccer_env.perception.options import BALL_FILTERS, ROBOT_PREDICTIONS

#: The match: the one the training evaluated its copies in.
ENV_KWARGS = {"blue": 2, "yellow": 2, "match_duration": 60.0, "control_dt": 1.0 / 30.0,
              "game": True}
#: What every side perceives through (the own-robot prediction set by ``--robot-prediction``).
PERCEPTION = {"vision": "ssl-2012", "ball_filter": "kick", "robot_prediction": "commands"}


def side(policy: str, label: str, perception: dict) -> Side:
    """A side on perceived ``ssl-2012`` observations through ``perception``."""
    return Side(policy, "perceived", perception, label=label)


def outcome_rows(h: HeadToHead) -> list[str]:
    """Markdown rows: wins, draws, losses and the goal difference of ``h``."""
    rows = []
    for outcome in ("wins", "draws", "losses"):
        r, lo, hi = h.rate(outcome)
        rows.append(f"| {h.a.label} vs {h.b.label} | {outcome} | {100 * r:.1f} % | "
                    f"{100 * lo:.1f} to {100 * hi:.1f} % |")
    gd, lo, hi = h.goal_difference()
    rows.append(f"| {h.a.label} vs {h.b.label} | goal difference per match "
                f"({h.goals_for}:{h.goals_against}) | {gd:+.2f} | {lo:+.2f} to {hi:+.2f} |")
    return rows


def foul_rows(h: HeadToHead) -> list[str]:
    """Markdown rows: each side's fouls, yellow and red cards per match in ``h``."""
    rows = []
    for k, s in enumerate((h.a, h.b)):
        cells = []
        for what in ("fouls", "yellow_cards", "red_cards"):
            m, lo, hi = h.per_match(what, k)
            cells.append(f"{m:.2f} ({max(lo, 0.0):.2f} to {hi:.2f})")
        rows.append(f"| {s.label} | against {(h.b, h.a)[k].label} | " + " | ".join(cells) + " |")
    return rows


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--team", required=True, help="the team's numpy file")
    p.add_argument("--matches", type=int, default=200, help="against the scripted team (200)")
    p.add_argument("--idle", type=int, default=40, help="against the idle team (40)")
    p.add_argument("--round-robin", type=int, default=20,
                   help="matches per other pair of the rating table (20; 0: no table)")
    p.add_argument("--start-seed", type=int, default=50_000, help="first seed (50,000)")
    p.add_argument("--ball-filter", choices=list(BALL_FILTERS), default="kick",
                   help="every side's ball filter (kick)")
    p.add_argument("--robot-prediction", choices=list(ROBOT_PREDICTIONS), default="commands",
                   help="how every side predicts its own robots (commands)")
    p.add_argument("--workers", type=int, default=None, help="processes (default: all cores)")
    p.add_argument("--out", default=None, help="a JSON file for the results")
    args = p.parse_args(argv)
    path = Path(args.team)
    t0 = time.perf_counter()
    perception = {**PERCEPTION, "ball_filter": args.ball_filter,
                  "robot_prediction": args.robot_prediction}
    team, scripted, idle = (side(str(path), "perceived team", perception),
                            side("scripted", "scripted", perception),
                            side("idle", "idle", perception))
    kw = {"env_kwargs": ENV_KWARGS, "workers": args.workers}
    results = []
    for a, b, n in ((team, scripted, args.matches), (team, idle, args.idle),
                    (scripted, idle, args.idle)):
        results.append(head_to_head(a, b, n, args.start_seed, **kw))
        print(f"{results[-1].summary()}  [{time.perf_counter() - t0:.0f} s]", flush=True)
    print("\n| match | outcome | rate | 95 % interval |\n|---|---|---|---|")
    for h in results:
        print("\n".join(outcome_rows(h)))
    print("\n| side | opponent | fouls | yellow cards | red cards |\n|---|---|---|---|---|")
    for h in results:
        print("\n".join(foul_rows(h)))
    report = {"env_kwargs": ENV_KWARGS, "perception": perception, "team": str(path),
              "head_to_head": [h.to_dict() for h in results]}
    if args.round_robin:
        players = [team, *checkpoint_sides(path.parent / "checkpoints", "perceived",
                                           perception)]
        pairs = [*itertools.combinations(players, 2),
                 *((c, other) for c in players[1:] for other in (scripted, idle))]
        more = round_robin([*players, scripted, idle], args.round_robin,
                           start_seed=args.start_seed + 1000, progress=print, pairs=pairs,
                           **kw)
        ratings = fit_ratings([*results, *more], anchor="scripted")
        print(rating_table(ratings))
        report["ratings"] = [r.__dict__ for r in ratings]
        report["round_robin"] = [h.to_dict() for h in more]
    print(f"[{time.perf_counter() - t0:.0f} s in all]")
    if args.out:
        Path(args.out).write_text(json.dumps(report, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
