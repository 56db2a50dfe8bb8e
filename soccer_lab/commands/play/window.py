"""The window of ``soccer-env play``: the environment's frames with the person's robot ringed,
and beside them a panel with the task, what the game waits for, the results so far and the
keys."""

from __future__ import annotations

from typing import Any

from soccer_env.render import wrap_text
from soccer_lab.commands.play.games import USER, Game
from soccer_lab.commands.play.keys import key_map

__all__ = ["PANEL_WIDTH", "PANEL_HEIGHT", "Window"]

#: Width of the panel beside the frames, and the least height of the window [px].
PANEL_WIDTH, PANEL_HEIGHT = 300, 540
#: The panel's colour.
_PANEL = (20, 24, 28)


class Window:
    """The environment's frames and, beside them, the panel: the task, what the game waits
    for, the results so far and the keys. The person's robot is ringed where the renderer
    drew it (:meth:`~soccer_env.render.Renderer.pixel`,
    :meth:`~soccer_env.render.Renderer.drawn_radius`)."""

    def __init__(self, pg: Any, game: Game) -> None:
        self.pg = pg
        frame = game.env.render()
        self.frame_size = (frame.shape[1], frame.shape[0])
        self.screen = pg.display.set_mode((self.frame_size[0] + PANEL_WIDTH,
                                           max(self.frame_size[1], PANEL_HEIGHT)))
        pg.display.set_caption(f"soccer-env play: {game.task}")
        pg.font.init()
        self.font = pg.font.Font(None, 20)
        self.big = pg.font.Font(None, 36)
        self.help = key_map(game.spec)
        self.where = ("you defend the goal on the left" if game.task == "keeper"
                      else "you attack the goal on the right")

    def draw(self, game: Game, banner: str) -> None:
        """Draw the environment's frame with the person's robot ringed, and the panel with
        ``banner`` (what the game waits for, or the latest result)."""
        pg = self.pg
        frame = game.env.render()
        self.screen.fill(_PANEL)
        self.screen.blit(pg.surfarray.make_surface(frame.swapaxes(0, 1)), (0, 0))
        renderer = game.unwrapped.renderer
        x, y = game.unwrapped.world.robot_array()[USER, 0:2].tolist()
        ring = int(round(renderer.drawn_radius(USER))) + 5
        height = renderer.contents.field_height
        self.screen.set_clip(pg.Rect(0, 0, self.frame_size[0], height))  # the field's part
        pg.draw.circle(self.screen, (255, 255, 255), renderer.pixel(x, y), ring, 2)
        self.screen.set_clip(None)
        self._panel(game, banner)
        pg.display.flip()

    def _panel(self, game: Game, banner: str) -> None:
        x0, y = self.frame_size[0] + 12, 10
        width = PANEL_WIDTH - 20
        white, grey = (240, 240, 240), (170, 175, 180)
        you = "blue 0" if game.task == "match" else "blue"
        lines = [(f"soccer-env play: {game.task}, seed {game.seed}", white),
                 (f"you: {you} ({game.spec.name}), ringed in white", white),
                 (self.where, grey)]
        lines += [(text, white) for text in game.status()]
        for text, colour in lines:
            y = self._text(text, colour, x0, y, width)
        if banner:
            self.screen.blit(self.big.render(banner.upper(), True, (255, 215, 0)), (x0, y + 6))
        y += 46
        for keys, what in self.help:
            y = self._text(keys, white, x0, y, width)
            y = self._text(what, grey, x0 + 12, y, width - 12)

    def _text(self, text: str, colour: tuple[int, int, int], x: int, y: int, width: int
              ) -> int:
        """Draw ``text`` wrapped to ``width`` pixels from ``(x, y)``; the next line's y."""
        for part in wrap_text(self.font, text, width) if text else ():
            self.screen.blit(self.font.render(part, True, colour), (x, y))
            y += 18
        return y
