"""The info bar beneath the field view (pygame), :class:`InfoBar`: the task's text, the legend
of exactly the overlays on screen (a swatch and a label each, in rows), and in a window its
keys. Frames below :data:`BAR_MIN_WIDTH` pixels wide have no info bar: the task's text is
drawn over the field, and no legend."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from soccer_env.render.colours import (
    BALL,
    BALL_PARTICLE,
    BAR,
    BELIEF,
    CONE,
    DIM,
    ELLIPSE,
    MEASURED,
    PAUSED,
    POSE_PARTICLE,
    SHADOW,
    TEAM_COLOURS,
)
from soccer_env.render.legend import BELIEF_KEYS, LEGEND_LABELS, flow, legend_keys
from soccer_env.render.text import Texts

__all__ = ["InfoBar", "BAR_MIN_WIDTH", "KEYS_HELP", "PAUSED_HELP"]

#: Narrower frames [px] have no info bar.
BAR_MIN_WIDTH = 320
#: The keys of the ``human`` window.
KEYS_HELP = ("space: pause/resume   n or right: one frame (paused)   o: overlays   "
             "l: legend   z: zoom   q or Esc: close")
#: The window's keys while it is paused.
PAUSED_HELP = "PAUSED   space: resume   n or right: one frame"


class InfoBar:
    """The info bar of frames ``width`` [px] wide below a field view ``top`` [px] high.

    Args:
        pg: the pygame module.
        texts: the frame's fonts.
        width: the frame's width [px].
        top: the field view's height [px] (the bar starts there).
        humanoids: whether the world has humanoids (the legend entries it may list).
        window: whether the frames are shown in a window (a last line with its keys).
        teams: the legend's labels of the blue and the yellow team.
        owner: whose belief is drawn (the caption of the belief's entries).

    Attributes:
        rows: the bar's lines of text (0: no bar), sized for every legend entry.
        height: its height [px].
    """

    def __init__(self, pg: Any, texts: Texts, width: int, top: int, humanoids: bool,
                 window: bool, teams: Sequence[str], owner: str) -> None:
        self.pg, self.texts = pg, texts
        self.width, self.top = width, top
        self.window = window
        self.teams = tuple(teams)
        self.owner = owner
        self.rows = 0
        if width >= BAR_MIN_WIDTH:
            widths = [it[2] for it in self._legend_items(legend_keys(humanoids))]
            rows = flow(widths, width - 2 * texts.pad, texts.spacing)[-1][0] + 1
            self.rows = 1 + rows + (1 if window else 0)
        self.height = self.rows * texts.line_h + (2 * texts.pad if self.rows else 0)

    def label(self, key: str) -> str:
        """The legend's label of the entry ``key``."""
        if key in ("team0", "team1"):
            return self.teams[int(key[-1])]
        return LEGEND_LABELS[key]

    def draw(self, surf: Any, hud: Sequence[str], order: list[str], show_legend: bool,
             paused: bool) -> list[str]:
        """The bar on the frame ``surf``: the task's text (``hud``), the legend of the entries
        ``order`` (with ``show_legend``), and in a window its keys (``paused``: the paused
        line). Returns the legend keys drawn."""
        texts = self.texts
        text = "     ".join(hud)
        if not self.rows:  # a small frame: the task's text over the field, no legend
            for row, line in enumerate(hud):
                surf.blit(texts.render(line, outline=True), (4, 3 + texts.line_h * row))
            return []
        pg = self.pg
        w, top = self.width, self.top
        pad, lh = texts.pad, texts.line_h
        pg.draw.rect(surf, BAR, (0, top, w, self.height))
        y = top + pad
        surf.blit(texts.render(text), (pad, y))
        shown = order if show_legend else []
        if shown:
            self._legend(surf, shown, y)
        if self.window:
            ry = top + pad + lh * (self.rows - 1)
            if paused:
                surf.blit(texts.render(PAUSED_HELP, PAUSED), (pad, ry))
            else:
                surf.blit(texts.render(KEYS_HELP, DIM), (pad, ry))
        return list(shown)

    def _legend(self, surf: Any, shown: list[str], y: int) -> None:
        """The legend's entries ``shown`` in rows below the line at ``y`` [px]."""
        texts, pg = self.texts, self.pg
        pad, lh = texts.pad, texts.line_h
        items = self._legend_items(shown)
        sw = self._swatch_width
        places = flow([it[2] for it in items], self.width - 2 * pad, texts.spacing)
        for (key, caption, _), (row, x) in zip(items, places):
            if row + 2 > self.rows - (1 if self.window else 0):
                break  # (the bar is sized for every entry; never reached)
            ry, x = y + lh * (row + 1), pad + x
            if caption is not None:
                text = texts.render(caption, DIM)
                surf.blit(text, (x, ry))
                x += text.get_width() + pad
            self._swatch(surf, key, pg.Rect(x, ry + 1, sw, lh - 2))
            surf.blit(texts.render(self.label(key)), (x + sw + 4, ry))

    @property
    def _swatch_width(self) -> int:
        return int(1.4 * self.texts.line_h)

    def _legend_items(self, keys: Sequence[str]) -> list[tuple[str, str | None, int]]:
        """The legend's items for the entries ``keys``: ``(key, caption, width [px])``; the
        first of the belief's entries carries the caption naming whose belief it is (kept on
        its row)."""
        sw, gap = self._swatch_width, self.texts.pad
        items, captioned = [], False
        for key in keys:
            caption = None
            if key in BELIEF_KEYS and not captioned:
                caption, captioned = f"{self.owner} believes:", True
            width = sw + 4 + self.texts.width(self.label(key))
            if caption is not None:
                width += self.texts.width(caption) + gap
            items.append((key, caption, width))
        return items

    def _swatch(self, surf: Any, key: str, rect: Any) -> None:
        """The legend's sample of the entry ``key`` in ``rect``."""
        pg = self.pg
        cx, cy = rect.center
        r = max(3, rect.height // 2 - 1)
        if key in ("team0", "team1"):
            pg.draw.circle(surf, TEAM_COLOURS[int(key[-1])], (cx, cy), r)
            pg.draw.circle(surf, (0, 0, 0), (cx, cy), r, 1)
        elif key == "ball":
            pg.draw.circle(surf, BALL, (cx, cy), max(2, r - 3))
        elif key == "ball_flight":
            pg.draw.circle(surf, SHADOW, (cx + 3, cy + 3), max(2, r - 3))
            pg.draw.circle(surf, BALL, (cx - 1, cy - 1), max(2, r - 2))
        elif key == "belief_robots":
            pg.draw.circle(surf, BELIEF, (cx, cy), r, 2)
        elif key == "belief_ball":
            pg.draw.circle(surf, BELIEF, (cx, cy), max(3, r - 2), 2)
        elif key == "belief_velocity":
            pg.draw.line(surf, BELIEF, (rect.left + 2, cy), (rect.right - 2, cy), 2)
        elif key == "ellipses":
            pg.draw.ellipse(surf, ELLIPSE, rect.inflate(-2, -4), 2)
        elif key in ("ball_particles", "pose_particles"):
            colour = BALL_PARTICLE if key == "ball_particles" else POSE_PARTICLE
            rng = np.random.default_rng(1)  # the same sample every frame
            for px, py in rng.integers((rect.left + 2, rect.top + 2),
                                       (rect.right - 3, rect.bottom - 3), (14, 2)).tolist():
                pg.draw.rect(surf, colour, (px, py, 2, 2))
        elif key == "measurement":
            k = max(3, r - 3)
            pg.draw.line(surf, MEASURED, (cx - k, cy - k), (cx + k, cy + k), 2)
            pg.draw.line(surf, MEASURED, (cx - k, cy + k), (cx + k, cy - k), 2)
        elif key == "camera":
            pg.draw.lines(surf, CONE, True, [(rect.left + 2, cy), (rect.right - 2, rect.top + 1),
                                             (rect.right - 2, rect.bottom - 1)], 1)
        elif key == "fallen":
            pg.draw.line(surf, TEAM_COLOURS[0], (rect.left + 2, cy), (rect.right - 2, cy), 4)
