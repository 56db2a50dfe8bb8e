"""``soccer-env rate``: a rating round robin between match teams (SSL or humanoid)
(:func:`agents.studies.rating.rate`): every pair plays the same seeded matches, colours
swapped every other match, and one Elo rating per team is fitted to all the matches at once,
with bootstrap intervals over seeds.

Teams are ``scripted``, ``idle``, a shipped team by name (:data:`agents.baselines.TEAMS`) or
a numpy team file (``.npz``, arrays only); each may end in ``@truth`` or ``@perceived`` to
play on that observation mode instead of ``--obs-mode`` (so a team is rated under the
conditions it plays). The match (sizes, length, command rate, the game flow) is shared, and
so are the robots (``--robot``), the perceived SSL teams' vision preset and own-robot
prediction (``--robot-prediction``) and the perceived humanoid teams' head camera
(``--camera``, with team fusion).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

from soccer_env.perception.options import BALL_FILTERS, ROBOT_PREDICTIONS
from soccer_env.presets import HEAD_CAMERAS, ROBOTS
from soccer_lab.cli_args import HelpFormatter

__all__ = ["parser", "main", "parse_team"]

_EXAMPLE = ("soccer-env rate --team scripted --team idle --team ssl-team-2v2 --obs-mode truth "
            "--matches 40")
#: Observation modes a team may play on.
_MODES = ("truth", "perceived")


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env rate``."""
    p = argparse.ArgumentParser(
        prog="soccer-env rate", formatter_class=HelpFormatter,
        description="Play a rating round robin between match teams and print their Elo "
                    "ratings (the anchor team held at 1000) with 95 % bootstrap intervals "
                    "over seeds, and every pair's head-to-head.",
        epilog=f"example:\n  {_EXAMPLE}")
    p.add_argument("--team", action="append", required=True, metavar="TEAM[@MODE]",
                   help="a team: scripted, idle, a shipped team's name, or a numpy team file "
                        "(.npz); @truth or @perceived sets its observation mode; give two or "
                        "more (default: none)")
    p.add_argument("--obs-mode", choices=_MODES, default="truth",
                   help="the observation mode of teams without @MODE")
    p.add_argument("--robot", choices=list(ROBOTS), default="ssl",
                   help="the robots of both teams (a humanoid preset plays humanoid teams)")
    p.add_argument("--vision", default="ssl-2012",
                   help="the vision preset perceived SSL teams see through (soccer-env list)")
    p.add_argument("--camera", choices=list(HEAD_CAMERAS), default="kidsize-2012",
                   help="the head camera perceived humanoid teams see through, with team "
                        "fusion")
    p.add_argument("--ball-filter", choices=list(BALL_FILTERS), default="ekf",
                   help="the ball filter of perceived SSL teams")
    p.add_argument("--robot-prediction", choices=list(ROBOT_PREDICTIONS),
                   default="constant-velocity",
                   help="how perceived teams predict their own robots to when their commands "
                        "take effect: at constant velocity, or through the commands they sent")
    p.add_argument("--game", action="store_true",
                   help="play the game flow (the SSL Division B rules, or the humanoid laws) "
                        "instead of the simple referee")
    p.add_argument("--size", type=int, default=2, help="robots a side")
    p.add_argument("--duration", type=float, default=60.0, help="playing time of a match [s]")
    p.add_argument("--control-hz", type=float, default=30.0, help="commands per second")
    p.add_argument("--matches", type=int, default=40, help="matches per pair")
    p.add_argument("--start-seed", type=int, default=0, help="seed of every pair's first match")
    p.add_argument("--anchor", default=None,
                   help="the team held at 1000 (default: the first --team)")
    p.add_argument("--workers", type=int, default=None,
                   help="processes; the results do not depend on it (default: all cores)")
    p.add_argument("--json", default=None,
                   help="also write the ratings and every match here (default: none)")
    return p


def parse_team(text: str, obs_mode: str, vision: str,
               robot_prediction: str = "constant-velocity", camera: str | None = None,
               ball_filter: str = "ekf") -> Any:
    """The :class:`~agents.studies.matches.Side` of a ``--team`` value (see the module
    docstring), labelled with the text itself.

    Raises:
        ValueError: an unknown mode, team name or a missing file.
    """
    from agents.baselines import TEAMS, team_path
    from agents.studies.matches import TEAM_POLICIES, Side

    name, _, mode = text.partition("@")
    mode = mode or obs_mode
    if mode not in _MODES:
        raise ValueError(f"--team {text!r}: the mode after @ must be one of {list(_MODES)}")
    if name in TEAM_POLICIES:
        policy = name
    elif name in TEAMS:
        policy = str(team_path(name))
    elif name.endswith(".npz"):
        if not Path(name).is_file():
            raise ValueError(f"--team {text!r}: no such file")
        policy = name
    else:
        raise ValueError(f"--team {text!r}: must be one of {list(TEAM_POLICIES)}, a shipped "
                         f"team {sorted(TEAMS)} or a numpy team file (.npz)")
    if mode != "perceived":
        perception = None
    elif camera is not None:  # humanoids: the head camera, with the default team fusion
        perception = {"camera": camera}
    else:
        perception = {"vision": vision, "ball_filter": ball_filter,
                      "robot_prediction": robot_prediction}
    return Side(policy, mode, perception, label=text)


def check_sizes(sides: list[Any], env_kwargs: dict[str, Any]) -> None:
    """Refuse a numpy team whose observations are not the match's (another team size, or
    trained with the game flow for a match without it). A team trained without the game flow
    plays a match with it, its network reading the entries it knows
    (:func:`agents.studies.matches.widened_team`)."""
    import soccer_env
    from agents.policies import NumpyPolicy
    from agents.studies.matches import widened_team

    env = soccer_env.parallel_env(**env_kwargs)
    try:
        size = env.observation_space(env.possible_agents[0]).shape[0]
        for side in sides:
            if isinstance(side.policy, str) and side.policy.endswith(".npz"):
                team = widened_team(NumpyPolicy.load(side.policy), env, "blue")
                if team.obs_size != size:
                    game = "with" if env_kwargs.get("game") else "without"
                    raise ValueError(f"--team {side.label!r} takes observations of "
                                     f"{team.obs_size} entries; a {env_kwargs['blue']} vs "
                                     f"{env_kwargs['yellow']} match {game} the game flow "
                                     f"gives {size} (was it trained for another team size or "
                                     "game flow setting?)")
    finally:
        env.close()


def main(argv: list[str] | None = None) -> int:
    """``soccer-env rate``: check the teams, play the round robin, print the tables."""
    p = parser()
    args = p.parse_args(argv)
    from agents.studies.rating import rate, rating_table

    if len(set(args.team)) < 2 or len(set(args.team)) != len(args.team):
        p.error(f"--team: give two or more different teams, got {args.team}")
    for name, value, low in (("--size", args.size, 1), ("--matches", args.matches, 1),
                             ("--start-seed", args.start_seed, 0)):
        if value < low:
            p.error(f"{name} must be >= {low}, got {value}")
    if not 1.0 <= args.duration <= 3600.0:
        p.error(f"--duration must be in [1, 3600] s, got {args.duration}")
    if not 1.0 <= args.control_hz <= 240.0:
        p.error(f"--control-hz must be in [1, 240], got {args.control_hz}")
    if args.anchor is not None and args.anchor not in args.team:
        p.error(f"--anchor must be one of the teams {args.team}, got {args.anchor!r}")
    try:
        humanoid = ROBOTS[args.robot].kind == "humanoid"
        sides = [parse_team(t, args.obs_mode, args.vision, args.robot_prediction,
                            args.camera if humanoid else None, args.ball_filter)
                 for t in args.team]
    except ValueError as err:
        p.error(str(err))
    env_kwargs: dict[str, Any] = {"blue": args.size, "yellow": args.size, "robot": args.robot,
                                  "match_duration": args.duration,
                                  "control_dt": 1.0 / args.control_hz}
    if args.game:
        env_kwargs["game"] = True
    try:
        check_sizes(sides, env_kwargs)
    except ValueError as err:
        p.error(str(err))
    t0 = time.perf_counter()
    ratings, results = rate(sides, args.matches, anchor=args.anchor, start_seed=args.start_seed,
                            env_kwargs=env_kwargs, workers=args.workers, progress=print)
    print(rating_table(ratings))
    print(f"[{len(results)} pairs, {args.matches} matches each, "
          f"{time.perf_counter() - t0:.0f} s]")
    if args.json:
        report = {"env_kwargs": env_kwargs, "teams": args.team,
                  "ratings": [r.__dict__ for r in ratings],
                  "head_to_head": [h.to_dict() for h in results]}
        Path(args.json).write_text(json.dumps(report, indent=1))
    return 0
