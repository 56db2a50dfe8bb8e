"""The shipped SSL match team against the scripted team, and an Elo table.

    python benchmarks/ssl_team.py                       # the figures of docs/results/learning.md
    python benchmarks/ssl_team.py --matches 40 --round-robin 20   # a quick look

1. ``--matches`` seeded 2 vs 2 matches (60 s, 30 commands a second, truth observations, the
   simple referee) between the shipped team (``agents/baselines/ssl_team_2v2.npz``) and the
   scripted team, colours swapped every other match (:func:`agents.studies.matches.head_to_head`):
   wins, draws and losses with Wilson 95 % intervals, goals, and the goal difference per
   match with its paired 95 % interval.
2. ``--round-robin`` matches per pair between the scripted team, the idle team (zero
   actions), the shipped team and the copies its training saved on the way
   (``agents/baselines/ssl_team_2v2_checkpoints/``), and their Elo ratings with bootstrap
   95 % intervals, the scripted team held at 1000 (:mod:`agents.studies.rating`). The idle team
   meets only the scripted and the shipped teams (it loses every match against either,
   which places it below them as far as the prior of one virtual draw lets), and the shipped
   team's matches against the scripted team are those of 1.

``--out`` writes both as JSON (every match's record included).
"""

from __future__ import annotations

import argparse
import itertools
import json
import time
from pathlib import Path

from agents.baselines import SSL_TEAM_2V2, SSL_TEAM_CHECKPOINTS, load_team
from agents.studies.matches import Side, checkpoint_sides, head_to_head
from agents.studies.rating import fit_ratings, rating_table, round_robin


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--matches", type=int, default=300,
                   help="matches of the shipped team against the scripted team (300)")
    p.add_argument("--round-robin", type=int, default=40,
                   help="matches per other pair of the rating table (40; 0: no table)")
    p.add_argument("--workers", type=int, default=None, help="processes (default: all cores)")
    p.add_argument("--out", default=None, help="a JSON file for the results")
    args = p.parse_args(argv)
    t0 = time.perf_counter()
    # The match of the figures: the one the team's training evaluated its copies in.
    eval_kwargs = load_team().meta["eval_kwargs"]
    team = Side(str(SSL_TEAM_2V2), "truth", label="shipped team")
    scripted = Side("scripted", "truth", label="scripted")
    h = head_to_head(team, scripted, args.matches, start_seed=0, env_kwargs=eval_kwargs,
                     workers=args.workers)
    gd = h.goal_difference()
    print(f"{h.summary()}  [{time.perf_counter() - t0:.0f} s]")
    print("| | rate | 95 % interval |\n|---|---|---|")
    for outcome in ("wins", "draws", "losses"):
        r, lo, hi = h.rate(outcome)
        print(f"| {outcome} | {100 * r:.1f} % | {100 * lo:.1f} to {100 * hi:.1f} % |")
    print(f"| goal difference per match | {gd[0]:+.2f} | {gd[1]:+.2f} to {gd[2]:+.2f} |")
    report = {"env_kwargs": eval_kwargs, "head_to_head": h.to_dict()}
    if args.round_robin:
        idle = Side("idle", "truth", label="idle")
        players = [scripted, team, *checkpoint_sides(SSL_TEAM_CHECKPOINTS, "truth")]
        pairs = [(scripted, idle), (team, idle),
                 *((a, b) for a, b in itertools.combinations(players, 2)
                   if (a, b) != (scripted, team))]
        results = [h, *round_robin([*players, idle], args.round_robin, start_seed=1000,
                                   env_kwargs=eval_kwargs, workers=args.workers,
                                   progress=print, pairs=pairs)]
        ratings = fit_ratings(results, anchor="scripted")
        print(rating_table(ratings))
        report["ratings"] = [r.__dict__ for r in ratings]
        report["round_robin"] = [x.to_dict() for x in results]
    print(f"[{time.perf_counter() - t0:.0f} s in all]")
    if args.out:
        Path(args.out).write_text(json.dumps(report, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
