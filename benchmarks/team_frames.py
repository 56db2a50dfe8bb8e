"""Rendered frames of a goal a team scores against the scripted team: what the learned team
does that the scripted one does not, as the docs show it.

Usage: ``python benchmarks/team_frames.py --team FILE [--obs-mode perceived] [--game]
[--start-seed 70000] [--before 1 0.5 0] [--out docs/FILE.png]``.

The team plays blue (its ``blue_0``'s belief is what the frames draw in cyan) against the
scripted team, 2 vs 2, 60 s at 30 commands a second, both sides on the same observations
(perceived: ``ssl-2012`` vision with the own robots predicted through the commands, as in
``benchmarks/ssl_team_perceived.py``). Matches are played from ``--start-seed`` on until blue
scores; that match is played again from its seed (matches are deterministic for a seed) and
rendered ``--before`` seconds before the goal, the frames side by side in one image.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

import numpy as np

import soccer_env
from agents.studies.matches import Side, match_env_kwargs, match_steps

#: The match (the perceived team's benchmark's, with the game flow set by ``--game``).
ENV_KWARGS: dict[str, Any] = {"blue": 2, "yellow": 2, "match_duration": 60.0,
                              "control_dt": 1.0 / 30.0}
#: What each side perceives through with ``--obs-mode perceived``.
PERCEPTION = {"vision": "ssl-2012", "ball_filter": "kick", "robot_prediction": "commands"}


def play(kwargs: dict[str, Any], blue: Side, yellow: Side, seed: int,
         render_at: set[int] | None = None) -> tuple[list[int], dict[int, np.ndarray]]:
    """Play the match of ``seed``: the steps at which blue scored, and the frames rendered
    after each step in ``render_at``."""
    env = soccer_env.parallel_env(**match_env_kwargs(kwargs, blue, yellow),
                                  render_mode="rgb_array" if render_at else None,
                                  render_width=640)
    try:
        goals, frames, score = [], {}, 0
        for step, infos in enumerate(match_steps(env, blue, yellow, seed), start=1):
            blue_goals = next(iter(infos.values()))["score"]["blue"]
            if blue_goals > score:
                goals.append(step)
            score = blue_goals
            if render_at and step in render_at:
                frames[step] = env.render()
        return goals, frames
    finally:
        env.close()


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--team", required=True, help="the team's numpy file")
    p.add_argument("--obs-mode", choices=["truth", "perceived"], default="truth")
    p.add_argument("--game", action="store_true", help="under the SSL game flow")
    p.add_argument("--start-seed", type=int, default=70_000, help="first seed (70,000)")
    p.add_argument("--tries", type=int, default=20, help="matches to find a goal in (20)")
    p.add_argument("--before", type=float, nargs="+", default=[1.0, 0.5, 0.0],
                   help="seconds before the goal of each frame (1 0.5 0)")
    p.add_argument("--out", required=True, help="the PNG to write")
    args = p.parse_args(argv)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kwargs = {**ENV_KWARGS, "game": True} if args.game else dict(ENV_KWARGS)
    perception = PERCEPTION if args.obs_mode == "perceived" else None
    blue = Side(args.team, args.obs_mode, perception, label="team")
    yellow = Side("scripted", args.obs_mode, perception, label="scripted")
    t0 = time.perf_counter()
    for seed in range(args.start_seed, args.start_seed + args.tries):
        goals, _ = play(kwargs, blue, yellow, seed)
        if goals:
            break
    else:
        raise SystemExit(f"no goal by the team in {args.tries} matches from seed "
                         f"{args.start_seed}")
    dt = kwargs["control_dt"]
    # The goal's own step already shows the kick-off positions: the last frame before it.
    steps = [max(1, goals[0] - 1 - round(b / dt)) for b in args.before]
    _, frames = play(kwargs, blue, yellow, seed, set(steps))
    fig, axes = plt.subplots(1, len(steps), figsize=(6.4 * len(steps), 5.4))
    for ax, s, b in zip(np.atleast_1d(axes), steps, args.before):
        ax.imshow(frames[s])
        ax.set_title(f"{b:.2f} s before the goal" if b else "as the ball enters the goal",
                     fontsize=14, pad=8)
        ax.axis("off")
    fig.tight_layout(pad=1.5)
    fig.savefig(args.out, dpi=80, bbox_inches="tight")
    print(f"seed {seed}: blue scored at {goals[0] * dt:.2f} s; frames at steps {steps} -> "
          f"{Path(args.out)} [{time.perf_counter() - t0:.0f} s]")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
