"""The cards over the field view (pygame), :class:`Cards`: the title card across the top at an
episode's start (its words: :mod:`soccer_env.render.title`), and the outcome banner
(:class:`Banner`) across the middle at its end."""

from __future__ import annotations

from typing import Any, NamedTuple

from soccer_env.render.colours import Colour
from soccer_env.render.text import Texts

__all__ = ["Banner", "Cards", "TONES"]

#: The banner's colours by tone: a success, a failure, neither.
TONES: dict[str, Colour] = {"good": (20, 130, 50), "bad": (170, 30, 30),
                            "neutral": (60, 60, 70)}


class Banner(NamedTuple):
    """The banner of an episode's end: ``text`` (the headline, e.g. ``"SAVED"``), a
    ``detail`` line and its ``tone`` (``"good"``, ``"bad"`` or ``"neutral"``: green, red or
    grey, from the learner's side)."""

    text: str
    detail: str = ""
    tone: str = "neutral"


class Cards:
    """Draws the title card and the banner over a field view of ``field_size`` [px]."""

    def __init__(self, pg: Any, texts: Texts, field_size: tuple[int, int]) -> None:
        self.pg, self.texts = pg, texts
        self.field_size = field_size

    def _box(self, size: tuple[int, int], colour: Colour, alpha: int) -> Any:
        box = self.pg.Surface(size, self.pg.SRCALPHA)
        box.fill((*colour, alpha))
        return box

    def title(self, surf: Any, lines: tuple, alpha: float) -> None:
        """The title card: a dark box across the top of the field view (long lines
        wrapped; the first line larger), with opacity ``alpha`` in [0, 1]."""
        texts = self.texts
        pad = texts.pad * 2
        room = self.field_size[0] - 4 * pad
        rendered = [texts.render(part, font="title" if k == 0 else "text")
                    for k, line in enumerate(lines)
                    for part in texts.wrap(line, "title" if k == 0 else "text", room)]
        w = min(self.field_size[0] - 2 * pad, max(t.get_width() for t in rendered) + 2 * pad)
        h = sum(t.get_height() for t in rendered) + 2 * pad
        box = self._box((w, h), (0, 0, 0), 185)
        y = pad
        for t in rendered:
            box.blit(t, ((w - t.get_width()) // 2, y))
            y += t.get_height()
        box.set_alpha(int(255 * min(1.0, max(0.0, alpha))))
        surf.blit(box, ((self.field_size[0] - w) // 2, pad))

    def banner(self, surf: Any, banner: Banner) -> None:
        """The outcome banner: its headline large, its detail below, across the middle."""
        texts = self.texts
        head = texts.render(banner.text, font="banner")
        detail = texts.render(banner.detail) if banner.detail else None
        pad = texts.pad * 3
        w = max(head.get_width(), detail.get_width() if detail else 0) + 4 * pad
        h = head.get_height() + (detail.get_height() if detail else 0) + 2 * pad
        w = min(w, self.field_size[0])
        box = self._box((w, h), TONES.get(banner.tone, TONES["neutral"]), 215)
        box.blit(head, ((w - head.get_width()) // 2, pad))
        if detail is not None:
            box.blit(detail, ((w - detail.get_width()) // 2, pad + head.get_height()))
        fw, fh = self.field_size
        surf.blit(box, ((fw - w) // 2, (fh - h) // 2))
