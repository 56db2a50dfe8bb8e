"""The ``human`` mode's window (pygame), :class:`Window`: it shows the frames at the frame
rate and takes keys (:data:`~soccer_env.render.bar.KEYS_HELP`): space pauses and resumes;
while paused, ``n`` or the right arrow lets one more frame through; ``o``, ``l`` and ``z``
toggle what the renderer draws (redrawn at once while paused); ``q``, Esc or closing the window
closes it for good."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from soccer_env.render.bar import KEYS_HELP

__all__ = ["Window", "BANNER_HOLD", "TOGGLE_KEYS"]

#: In ``human`` mode the frame with the outcome banner stays this long [s] (keys still act).
BANNER_HOLD = 1.0
#: The keys that toggle what is drawn, by the name of pygame's key constant: the overlays,
#: the legend, the follow view.
TOGGLE_KEYS = {"K_o": "overlays", "K_l": "legend", "K_z": "view"}


class Window:
    """A window of ``size`` [px] captioned ``caption`` (the keys added) showing frames at
    ``fps``, opened at its first frame.

    Args:
        pg: the pygame module.
        size: the frame's ``(width, height)`` [px].
        fps: the frame rate.
        caption: the window's caption.
        redraw: called with ``"overlays"``, ``"legend"`` or ``"view"`` when its key is
            pressed (None: when the window pauses or resumes) to toggle that and draw the
            latest frame again; returns the frame, or None when there is none.

    Attributes:
        paused: whether the window holds its frame (``space``).
        frames_shown: frames shown.
        closed: whether it was closed for good (no more frames are drawn into one).
    """

    def __init__(self, pg: Any, size: tuple[int, int], fps: float, caption: str,
                 redraw: Callable[[str | None], Any]) -> None:
        self.pg, self.size, self.fps, self.caption = pg, size, fps, caption
        self.redraw = redraw
        self.paused = False
        self.frames_shown = 0
        self.closed = False
        self.display: Any = None
        self._clock: Any = None
        self._step = False

    @property
    def open(self) -> bool:
        """Whether the window is open."""
        return self.display is not None

    def show(self, surf: Any) -> None:
        """Show the frame ``surf`` (opening the window first), at the frame rate."""
        pg = self.pg
        if self.display is None:
            pg.display.init()
            self.display = pg.display.set_mode(self.size)
            pg.display.set_caption(f"{self.caption}   [{KEYS_HELP}]")
            self._clock = pg.time.Clock()
        self.display.blit(surf, (0, 0))
        pg.display.flip()
        self.frames_shown += 1
        self._clock.tick(self.fps)

    def keys(self, hold: bool) -> None:
        """Act on the window's keys; while paused (or for :data:`BANNER_HOLD` after an
        outcome banner, ``hold``), wait for them."""
        pg = self.pg
        for event in pg.event.get():
            self._key(event)
        until = time.monotonic() + BANNER_HOLD if hold else 0.0
        while not self.closed:
            if self.paused:
                if self._step:
                    break
                wait = 100
            else:
                left = until - time.monotonic()
                if left <= 0.0:
                    break
                wait = max(1, int(1000 * left))
            event = pg.event.wait(wait)
            if event.type != pg.NOEVENT:
                self._key(event)
        self._step = False

    def _key(self, event: Any) -> None:
        """One window event: the keys of the module docstring."""
        pg = self.pg
        if event.type == pg.QUIT:
            self.close(for_good=True)
            return
        if event.type != pg.KEYDOWN:
            return
        key = event.key
        frame = None
        if key in (pg.K_q, pg.K_ESCAPE):
            self.close(for_good=True)
            return
        if key == pg.K_SPACE:
            self.paused = not self.paused
            self._step = False
            frame = self.redraw(None)
        elif key in (pg.K_n, pg.K_RIGHT):
            self._step = self.paused
        else:
            for name, what in TOGGLE_KEYS.items():
                if key == getattr(pg, name):
                    frame = self.redraw(what)
        if frame is not None:
            self.display.blit(frame, (0, 0))
            pg.display.flip()

    def close(self, for_good: bool = False) -> None:
        """Close the window, if open (``for_good``: and show no more frames, as the ``q`` key
        does)."""
        if self.display is not None:
            self.pg.display.quit()
            self.display = None
        if for_good:
            self.closed, self.paused = True, False
