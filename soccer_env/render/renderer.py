"""Top-down rendering with pygame: an RGB array or a live window (:class:`Renderer`).

A frame is the field view above an info bar. The field view draws the field to scale with its
lines, defense areas and goals (:mod:`~soccer_env.render.field`); robots in team colours with
their flat front (SSL) or as discs with their head camera's field of view (humanoids; a fallen
humanoid's body lies beside it), a heading mark and their number on a dark backing; the ball in
orange (with a shadow and a larger disc while it flies). Robots and the ball are drawn at least
:data:`~soccer_env.render.overlays.MIN_ROBOT_PX` and
:data:`~soccer_env.render.overlays.MIN_BALL_PX` of the frame's width, larger than to scale on
small frames. Over the truth it draws what the team believes, in cyan: the robots' outlines,
the ball with its velocity, 2-sigma ellipses of the position covariances, the particle
trackers' and the self-localization's particles (faint) and the latest ball sighting
(:mod:`~soccer_env.render.overlays`).

The info bar beneath lists the task's text (time, shot, score) and a legend of exactly the
overlays on screen (:mod:`~soccer_env.render.bar`). An episode starts with a title card (task,
seed, robots, observations and perception) over its first
:data:`~soccer_env.render.title.TITLE_SECONDS` and ends with a banner naming the outcome
(:mod:`~soccer_env.render.cards`). ``view="follow"`` crops a window around the ball and the
nearest robots and scales it up to the same frame size (:mod:`~soccer_env.render.view`).
Frames below :data:`~soccer_env.render.bar.BAR_MIN_WIDTH` pixels wide have no info bar (the
task's text is drawn over the field, and no legend). In ``human`` mode a window shows the
frames and takes keys (:mod:`~soccer_env.render.window`).

``rgb_array`` needs no display. pygame is an optional dependency
(``pip install soccer-env[render]``).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.render.bar import InfoBar
from soccer_env.render.cards import Banner, Cards
from soccer_env.render.field import draw_field
from soccer_env.render.legend import LEGEND_LABELS
from soccer_env.render.overlays import Overlays
from soccer_env.render.text import Texts, import_pygame
from soccer_env.render.view import View, check_view
from soccer_env.render.window import Window
from soccer_env.state import Belief, WorldState

__all__ = ["Renderer", "FrameContents", "RENDER_MODES"]

RENDER_MODES = ("human", "rgb_array")


class FrameContents(NamedTuple):
    """What the latest frame shows (:attr:`Renderer.contents`).

    Attributes:
        legend: the keys of the legend entries drawn, in order (see
            :data:`~soccer_env.render.legend.LEGEND_LABELS`; empty when the legend is hidden
            or the frame has no info bar).
        labels: their labels.
        overlays: the keys of everything drawn that the legend can list, whether or not the
            legend is shown.
        title: the title card's lines (empty when none is shown).
        banner: the outcome banner, or None.
        view: ``"field"`` or ``"follow"``.
        window: the part of the field shown, ``(x_min, x_max, y_min, y_max)`` [m].
        scale: pixels per metre of the field view.
        field_height: the field view's height [px] (the info bar is below it).
    """

    legend: tuple[str, ...]
    labels: tuple[str, ...]
    overlays: tuple[str, ...]
    title: tuple[str, ...]
    banner: Banner | None
    view: str
    window: tuple[float, float, float, float]
    scale: float
    field_height: int


class Renderer:
    """Draws :class:`~soccer_env.state.WorldState` snapshots (see the module docstring).

    Args:
        field: the field to draw.
        robot: the robots' spec, one for all robots or one per robot.
        ball: the ball's spec.
        mode: ``"rgb_array"`` or ``"human"``.
        width_px: width of the frame in pixels; the field view's height follows the field's
            aspect, and the info bar adds a fixed height below it (the same for every frame).
        fps: frame rate of the ``"human"`` window.
        view: ``"field"`` or ``"follow"`` (:data:`~soccer_env.render.view.RENDER_VIEWS`).
        teams: the legend's labels of the blue and the yellow team.
        owner: whose belief is drawn (the legend's caption of the belief's entries).
        caption: the ``"human"`` window's caption (the keys are added to it).

    Attributes:
        view: the present view (``z`` toggles it in the window).
        show_overlays: whether the belief and the camera views are drawn (``o``).
        show_legend: whether the legend is drawn (``l``).
        paused: whether the window holds its frame (``space``).
        frames_shown: frames shown in the window.
        contents: :class:`FrameContents` of the latest frame (None before the first).

    In ``"human"`` mode the window takes these keys
    (:data:`~soccer_env.render.bar.KEYS_HELP`, also in its caption and the info bar's last
    line): space pauses and resumes; while paused, ``n`` or the right arrow lets one more
    frame through; ``o`` toggles the overlays, ``l`` the legend, ``z`` the follow view (the
    frame is redrawn at once while paused); ``q``, Esc or closing the window closes it for good
    (later frames are not drawn).
    """

    def __init__(self, field: FieldSpec, robot: RobotSpec | Sequence[RobotSpec],
                 ball: BallSpec, mode: str, width_px: int = 960, fps: float = 60.0,
                 view: str = "field", teams: Sequence[str] = ("blue team", "yellow team"),
                 owner: str = "the team", caption: str = "soccer_env") -> None:
        if mode not in RENDER_MODES:
            raise ValueError(f"render_mode must be one of {list(RENDER_MODES)} or None, "
                             f"got {mode!r}")
        check_view(view)
        self.pg = pg = import_pygame()
        self._args = (field, robot, ball, mode, width_px, fps, view, tuple(teams), owner,
                      caption)
        self.field, self.robot, self.ball = field, robot, ball
        self.mode = mode
        self.fps = fps
        self._view = View(field, width_px)
        self.ox, self.oy = self._view.ox, self._view.oy
        self.scale = self._view.scale
        self.field_size = self._view.field_size
        w = self.field_size[0]
        self.teams = tuple(teams)
        self.owner = owner
        self.caption = caption
        self.view = view
        self.show_overlays = True
        self.show_legend = True
        self.contents: FrameContents | None = None
        self._held: tuple | None = None
        self._last: tuple | None = None
        self._texts = Texts(pg, w)
        self._overlays = Overlays(pg, self._view, self._texts, robot, ball)
        humanoids = any(s.kind == "humanoid" for s in self._overlays.specs)
        self._bar = InfoBar(pg, self._texts, w, self.field_size[1], humanoids,
                            mode == "human", self.teams, owner)
        self._cards = Cards(pg, self._texts, self.field_size)
        self.size = (w, self.field_size[1] + self._bar.height)
        self._window = Window(pg, self.size, fps, caption, self._redraw)
        self._background = None

    # ------------------------------------------------------------------------------------
    # Copies

    def __reduce__(self):
        # pygame's surfaces and fonts do not pickle; a copy draws its own (and opens its own
        # window in "human" mode on its first frame), with the same toggles and follow view.
        return (type(self), self._args, self._copied_state())

    def _copied_state(self) -> dict[str, Any]:
        follow = self._view.follow
        return {"view": self.view, "show_overlays": self.show_overlays,
                "show_legend": self.show_legend,
                "follow": None if follow is None else list(follow)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.view, self.show_overlays = state["view"], state["show_overlays"]
        self.show_legend = state["show_legend"]
        self._view.follow = state["follow"]

    # ------------------------------------------------------------------------------------
    # Reading

    @property
    def paused(self) -> bool:
        """Whether the window holds its frame (``space``)."""
        return self._window.paused

    @property
    def frames_shown(self) -> int:
        """Frames shown in the window."""
        return self._window.frames_shown

    @property
    def window_open(self) -> bool:
        """Whether the ``human`` window is open."""
        return self._window.open

    def pixel(self, x: float, y: float) -> tuple[int, int]:
        """The pixel ``(column, row)`` of the field point ``(x, y)`` [m] in the latest frame's
        field view (which the follow view moves and zooms)."""
        return self._view.px(x, y)

    def drawn_radius(self, i: int) -> float:
        """Robot ``i``'s radius as drawn in the latest frame [px]: to scale, or larger where
        that would be under :data:`~soccer_env.render.overlays.MIN_ROBOT_PX` of the frame's
        width."""
        return self._overlays.drawn_radius(i)

    # ------------------------------------------------------------------------------------
    # Drawing

    def draw(self, state: WorldState, hud: Sequence[str] = (), belief: Belief | None = None,
             heads: dict | None = None, *, title: Sequence[str] = (),
             title_alpha: float = 1.0, banner: Banner | None = None) -> np.ndarray | None:
        """Draw ``state`` and return the frame.

        Args:
            state: the truth.
            hud: the task's lines of text (the info bar's first line).
            belief: what the team believes (:class:`~soccer_env.state.Belief`, laid out like
                the state), drawn in cyan over the truth; with its ``spread``
                (:class:`~soccer_env.state.BeliefSpread`) the 2-sigma ellipses and particles,
                with its ``quality.ball_measured`` the latest ball sighting.
            heads: humanoid robot index -> ``(pan, hfov, range, lying)`` [rad, rad, m]: the
                camera's view is drawn as a cone, and a fallen robot's body (``lying``: its
                direction in the body frame [rad] and length [m], or None) beside it.
            title: the title card's lines (the first larger), or none.
            title_alpha: the title card's opacity in [0, 1].
            banner: the outcome banner, or None.

        Returns:
            An ``(H, W, 3)`` uint8 frame (``rgb_array``), or None (``human``: shown in the
            window, whose keys act here; see the class docstring).
        """
        args = (state, tuple(hud), belief, heads or {}, tuple(title), float(title_alpha),
                banner)
        if self.mode == "human":
            window = self._window
            if window.closed:
                return None
            self._last = args
            window.show(self._compose(*args))
            window.keys(banner is not None and self._held != (state.time, banner))
            if banner is not None:
                self._held = (state.time, banner)
            return None
        surf = self._compose(*args)
        h, w = self.size[1], self.size[0]
        return np.frombuffer(self.pg.image.tobytes(surf, "RGB"), np.uint8).reshape(h, w, 3).copy()

    def _compose(self, state: WorldState, hud: tuple, belief, heads: dict, title: tuple,
                 title_alpha: float, banner: Banner | None):
        """The frame's surface (see :meth:`draw`)."""
        pg = self.pg
        drawn: list[str] = []
        surf = pg.Surface(self.size)
        if self.view == "follow":
            self._view.follow_state(state)
            draw_field(pg, surf.subsurface((0, 0, *self.field_size)), self._view, self.field)
        else:
            self._view.whole()
            if self._background is None:
                self._background = pg.Surface(self.field_size)
                draw_field(pg, self._background, self._view, self.field)
            surf.blit(self._background, (0, 0))
        overlays = self._overlays
        field = surf.subsurface((0, 0, *self.field_size))
        overlays.robots(field, state, heads, self.show_overlays, drawn)
        if overlays.true_ball(field, state):
            drawn.append("ball" if state.ball[2] <= 1e-3 else "ball_flight")
        if self.show_overlays and belief is not None:
            overlays.belief(field, belief, drawn)
        overlays.ids(field, state)
        if title:
            self._cards.title(field, title, title_alpha)
        if banner is not None:
            self._cards.banner(field, banner)
        order = [k for k in LEGEND_LABELS if k in drawn]
        shown = self._bar.draw(surf, hud, order, self.show_legend, self._window.paused)
        self.contents = FrameContents(tuple(shown), tuple(self._bar.label(k) for k in shown),
                                      tuple(order), title, banner, self.view,
                                      self._view.window(), self._view.s, self.field_size[1])
        return surf

    # ------------------------------------------------------------------------------------
    # The window

    def _redraw(self, toggle: str | None) -> Any:
        """Toggle the overlays, the legend or the view (``toggle``; None: nothing) and draw
        the latest frame again for the open window (None when there is none)."""
        if toggle == "overlays":
            self.show_overlays = not self.show_overlays
        elif toggle == "legend":
            self.show_legend = not self.show_legend
        elif toggle == "view":
            self.view = "follow" if self.view == "field" else "field"
        if self._last is None or not self._window.open:
            return None
        return self._compose(*self._last)

    def close(self, for_good: bool = False) -> None:
        """Close the window, if any (``for_good``: and draw no more frames into one, as the
        ``q`` key does)."""
        self._window.close(for_good)
