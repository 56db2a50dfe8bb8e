"""The loop of ``soccer-env play``: each frame the window's events, one environment step with
the held keys' action unless paused or holding an episode's start or end, and the drawing."""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable
from typing import Any

from soccer_lab.commands.play.games import Game
from soccer_lab.commands.play.keys import KeyState, key_action
from soccer_lab.commands.play.window import Window

__all__ = ["END_HOLD", "START_HOLD", "run"]

#: How long the window shows an episode's end before the next episode [s].
END_HOLD = 1.0
#: How long it shows an episode's start before play begins [s].
START_HOLD = 0.5


def run(game: Game, pg: Any, seed: int, fps: float,
        max_steps: int | None = None, events: Callable[[], Iterable[Any]] | None = None,
        out: Callable[[str], None] | None = None) -> int:
    """Play until the person quits or ``max_steps`` steps are taken.

    Opens the window (:class:`Window`) on the first episode's start. Each frame takes the
    window's events, steps the environment once with the held keys' action
    (:func:`key_action`) unless paused or holding, and draws. An episode's end holds
    its last frame for :data:`END_HOLD` seconds of play (``END_HOLD / control_dt`` frames),
    prints its result, and the next episode (the next seed) holds its first frame for
    :data:`START_HOLD` seconds. On quitting, an unfinished episode's line is printed.

    Args:
        game: the environment and its scripted robots, rendering ``rgb_array`` frames
            (:func:`make_game` with a ``render_width``).
        pg: the pygame module, its display initialised.
        seed: the first episode's seed (>= 0).
        fps: frames, and so steps, per second (0: as fast as it runs).
        max_steps: stop after this many environment steps (None: no limit).
        events: the frame's events (default ``pygame.event.get``).
        out: where the lines go (default: printed to stdout at once).

    Returns:
        The environment steps taken.
    """
    events = events or pg.event.get
    out = out or functools.partial(print, flush=True)
    keys = KeyState(pg)
    clock = pg.time.Clock()
    rate = 1.0 / game.unwrapped.world.control_dt
    start_hold, end_hold = round(START_HOLD * rate), round(END_HOLD * rate)
    game.reset(seed)
    window = Window(pg, game)
    hold, steps = start_hold, 0
    shown, shown_left = "", 0  # the last event's banner and its frames to go
    while max_steps is None or steps < max_steps:
        for event in events():
            keys.process_event(event)
        if not keys.running:
            break
        if keys.restart:
            keys.restart = False
            game.reset(game.seed)
            hold, shown_left = start_hold, 0
        elif hold > 0:
            hold -= 1
            if hold == 0 and game.over:
                game.reset(game.seed + 1)
                hold = start_hold
        elif not keys.paused:
            line = game.step(key_action(keys.pressed, game.spec, game.heading()))
            steps += 1
            if game.banner:
                shown, shown_left = game.banner, end_hold
            if line is not None:
                out(line)
                hold = end_hold
        if keys.paused:
            banner = "paused"
        elif shown_left > 0:
            banner = shown
        else:
            banner = "ready" if hold else ""
        shown_left = max(0, shown_left - 1)
        window.draw(game, banner)
        clock.tick(fps)
    if not game.over:
        out(game.stopped())
    return steps
