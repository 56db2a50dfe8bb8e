"""``soccer-env play``: a person drives one robot with the keyboard against scripted robots.

As :func:`gymnasium.utils.play.play` does for Atari games, the environment's ``rgb_array``
frames are blitted to a pygame window, the held keys make the action and a frame rate paces
the steps; unlike it, the action is continuous and depends on the robot's heading (the arrows
drive an SSL robot in the field frame), the environment may be the PettingZoo match, and a
panel beside the frames shows the keys and the results.

* ``--task match``: the person plays ``blue_0`` of Match-v0 (the keeper slot of the kick-off
  formation); the other blue robots and the yellow team are the scripted teams of
  :func:`agents.studies.matches.team_policy` (:class:`~agents.scripted.team.ScriptedTeam`,
  :class:`~agents.scripted.humanoid.HumanoidTeam` for humanoids);
* ``--task shootout``: the striker of Shootout-v0 against its scripted keeper;
* ``--task keeper``: the keeper of Goalkeeper-v0 facing its seeded shots.

The frames show the field as the environments draw it: ``+x`` to the right (the goal blue
attacks), ``+y`` up. Keys (:func:`key_action`, :func:`key_map`): for an SSL robot the arrows or
WASD drive in that field frame, each the way it points on the screen (right: towards the
opponents' goal), at the robot's top speed; Q and E turn it at :data:`KEY_TURN_RATE`, space
arms the kicker (a kick when the ball reaches it), shift+space a chip, F the dribbler. A
humanoid walks in its body frame (up: forward, down: back, left and right: sideways), Q and E
turn it, space kicks, shift with left or right dives to that side; its head follows the ball
by itself. P pauses, R restarts the episode, Esc or closing the window quits.

Each episode's result is printed when it ends, and the next one starts with the next seed.

**Code.** :mod:`.keys` (the held keys to an action, the key map, the window's key state),
:mod:`.games` (the environment and its scripted robots), :mod:`.window` (the frames and the
panel), :mod:`.loop` (the frames, steps and episodes); :func:`main` checks the options, makes
the game and runs the loop.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import textwrap
from typing import Any

from soccer_lab.cli_args import (
    DEFAULT_ROBOT,
    HelpFormatter,
    add_env_arguments,
    env_kwargs_from_args,
)
from soccer_lab.commands.play.games import TASKS, make_game
from soccer_lab.commands.play.keys import (
    ACTION_KEYS,
    KEY_TURN_RATE,
    KeyState,
    key_action,
    key_map,
    key_text,
)
from soccer_lab.commands.play.loop import END_HOLD, START_HOLD, run
from soccer_lab.commands.play.window import PANEL_HEIGHT, PANEL_WIDTH, Window
from soccer_lab.extras import message

__all__ = ["parser", "main", "key_action", "key_map", "KeyState", "make_game", "run",
           "TASKS", "ACTION_KEYS", "KEY_TURN_RATE", "START_HOLD", "END_HOLD", "NEEDS_PYGAME",
           "PANEL_WIDTH", "PANEL_HEIGHT", "Window"]

#: What the command says when pygame does not import (it then exits with 2).
NEEDS_PYGAME = "soccer-env play needs the render extra: pip install 'soccer-env[render]'"


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env play``."""
    from soccer_env import MAX_TEAM_SIZE, presets

    ssl, humanoid = presets.ROBOTS["ssl"], presets.ROBOTS["humanoid"]
    p = argparse.ArgumentParser(
        prog="soccer-env play",
        formatter_class=HelpFormatter,
        description=textwrap.fill(
            "Drive a robot with the keyboard against the scripted robots, in a window (needs "
            "the render extra). You play blue, whose goal to attack is on the right; your "
            "robot is ringed in white. With --obs-mode raw or perceived, what your team "
            "believes is drawn in cyan over the truth. Each episode's result is printed when "
            "it ends; the next one starts with the next seed.", 79),
        epilog=f"keys, SSL robots:\n{key_text(ssl)}\n\nkeys, humanoids:\n"
               f"{key_text(humanoid)}\n\nexamples:\n"
               "  soccer-env play\n"
               "  soccer-env play --task keeper --robot humanoid\n"
               "  soccer-env play --task shootout --obs-mode perceived --perception realistic")
    p.add_argument("--task", choices=list(TASKS), default="match",
                   help="; ".join(f"{k}: {v}" for k, v in TASKS.items()))
    p.add_argument("--team-size", type=int, default=None,
                   help=f"robots per team in the match, 1..{MAX_TEAM_SIZE} (default: 3)")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the first episode; each next episode takes the next")
    p.add_argument("--fps", type=float, default=60,
                   help="frames and steps per second, 0 for as fast as it runs; 60 is real "
                        "time at the environments' 60 Hz control rate")
    p.add_argument("--width", type=int, default=800,
                   help="width of the environment's frames in pixels, 200..3840 (the height "
                        "follows the field's; a panel with the keys is beside them)")
    add_env_arguments(p)
    p.add_argument("--max-steps", type=int, default=None, metavar="N",
                   help="stop after N environment steps (default: play until you quit)")
    p.add_argument("--keys", action="store_true",
                   help="print the keys of --robot and exit")
    return p


def main(argv: list[str] | None = None) -> int:
    """``soccer-env play``: drive a robot with the keyboard (see the module docstring).

    Returns:
        0 after playing (or ``--keys``), 2 when pygame is missing.
    """
    from soccer_env import MAX_TEAM_SIZE, presets

    p = parser()
    args = p.parse_args(argv)
    robot = args.robot or DEFAULT_ROBOT
    if args.keys:
        print(f"keys for robot {robot}:\n{key_text(presets.ROBOTS[robot])}")
        return 0
    if args.team_size is not None and args.task != "match":
        p.error("--team-size applies to --task match only")
    team_size = 3 if args.team_size is None else args.team_size
    if not 1 <= team_size <= MAX_TEAM_SIZE:
        p.error(f"--team-size must be in 1..{MAX_TEAM_SIZE}, got {team_size}")
    if args.seed < 0:
        p.error(f"--seed must be >= 0, got {args.seed}")
    if not (math.isfinite(args.fps) and 0.0 <= args.fps <= 1000.0):
        p.error(f"--fps must be in [0, 1000] (0: as fast as it runs), got {args.fps}")
    if not 200 <= args.width <= 3840:
        p.error(f"--width must be in 200..3840 pixels, got {args.width}")
    if args.max_steps is not None and args.max_steps < 1:
        p.error(f"--max-steps must be >= 1, got {args.max_steps}")
    try:
        env_kwargs = env_kwargs_from_args(args)
    except ValueError as err:
        p.error(str(err))
    pygame, missing = _import_pygame()
    if pygame is None:
        print(missing, file=sys.stderr)
        return 2
    robot = env_kwargs.pop("robot", robot)  # --robot, else an --env-kwarg robot=...
    try:
        game = make_game(args.task, robot, team_size, env_kwargs, args.width)
    except (ValueError, TypeError) as err:
        p.error(str(err))
    pygame.display.init()
    try:
        run(game, pygame, args.seed, args.fps, args.max_steps)
    finally:
        game.close()
        pygame.display.quit()
    return 0


def _import_pygame() -> tuple[Any, str]:
    """The pygame module and ``""``, or None and the line saying how to install it
    (:func:`soccer_lab.extras.message`, or :data:`NEEDS_PYGAME` when pygame is there but
    does not import)."""
    text = message("play")
    if text is None:
        os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
        try:
            import pygame
        except ImportError:
            return None, NEEDS_PYGAME
        return pygame, ""
    return None, text
