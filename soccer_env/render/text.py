"""Text on a frame (pygame): the fonts of one frame size, rendered lines cached, and lines
wrapped to a width (:func:`wrap_text`)."""

from __future__ import annotations

import os
from typing import Any

from soccer_env.render.colours import TEXT, Colour

__all__ = ["Texts", "wrap_text", "import_pygame", "CACHE_SIZE"]

#: Rendered lines kept at most (the cache starts anew beyond).
CACHE_SIZE = 512


def import_pygame() -> Any:
    """The ``pygame`` module (its support prompt hidden); ``ImportError`` saying how to install
    it when it is missing."""
    try:
        os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
        import pygame
    except ImportError as err:  # pragma: no cover - depends on the installation
        raise ImportError(
            "rendering needs pygame; install it with: pip install 'soccer-env[render]'"
        ) from err
    return pygame


def wrap_text(face: Any, text: str, width: int) -> list[str]:
    """``text`` broken at spaces into lines no wider than ``width`` [px] in the pygame font
    ``face`` (a single word wider than that stays whole)."""
    if face.size(text)[0] <= width:
        return [text]
    lines, line = [], ""
    for word in text.split(" "):
        trial = f"{line} {word}" if line else word
        if line and face.size(trial)[0] > width:
            lines.append(line)
            line = word
        else:
            line = trial
    return lines + [line]


class Texts:
    """The fonts of a frame ``width`` [px] wide and the lines rendered in them.

    Fonts, by name: ``"text"`` (the info bar's and the cards' lines, 1/30 of the width, 12 px
    at least), ``"id"`` (the robots' numbers, the same size), ``"title"`` (the title card's
    first line, 1.3 times larger) and ``"banner"`` (the outcome banner's headline, 1/12 of the
    width, 18 px at least).

    Attributes:
        line_h: the height of a line of ``"text"`` [px].
        pad: padding around text [px].
        spacing: space between legend entries [px].
    """

    def __init__(self, pg: Any, width: int) -> None:
        self.pg = pg
        pg.font.init()
        size = max(12, int(round(width / 30)))
        self.fonts = {"text": pg.font.Font(None, size),
                      "id": pg.font.Font(None, size),
                      "title": pg.font.Font(None, int(round(1.3 * size))),
                      "banner": pg.font.Font(None, max(18, int(round(width / 12))))}
        self.font = self.fonts["text"]
        self._cache: dict[tuple, Any] = {}
        self.line_h = self.font.get_linesize()
        self.pad = max(3, self.line_h // 4)
        self.spacing = max(8, self.line_h)

    def width(self, text: str) -> int:
        """The width of ``text`` in the ``"text"`` font [px]."""
        return self.font.size(text)[0]

    def wrap(self, text: str, font: str, width: int) -> list[str]:
        """``text`` wrapped (:func:`wrap_text`) in the font named ``font``."""
        return wrap_text(self.fonts[font], text, width)

    def render(self, text: str, colour: Colour = TEXT, font: str = "text",
               outline: bool = False) -> Any:
        """``text`` rendered in the font named ``font`` (cached), with a dark outline
        (``outline``) for contrast on any background."""
        key = (text, colour, font, outline)
        surf = self._cache.get(key)
        if surf is None:
            pg = self.pg
            face_font = self.fonts[font]
            face = face_font.render(text, True, colour)
            if outline:
                edge = face_font.render(text, True, (0, 0, 0))
                w, h = face.get_size()
                surf = pg.Surface((w + 2, h + 2), pg.SRCALPHA)
                for dx in (0, 1, 2):
                    for dy in (0, 1, 2):
                        if dx != 1 or dy != 1:
                            surf.blit(edge, (dx, dy))
                surf.blit(face, (1, 1))
            else:
                surf = face
            if len(self._cache) > CACHE_SIZE:
                self._cache.clear()
            self._cache[key] = surf
        return surf
