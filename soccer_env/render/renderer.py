"""Top-down rendering with pygame: an RGB array or a live window.

A frame is the field view above an info bar. The field view draws the field to scale with its
lines, defense areas and goals; robots in team colours with their flat front (SSL) or as
discs with their head camera's field of view (humanoids; a fallen humanoid's body lies beside
it), a heading mark and their number on a dark backing; the ball in orange (with a shadow
and a larger disc while it flies). Robots and the ball are drawn at least
:data:`MIN_ROBOT_PX` and :data:`MIN_BALL_PX` of the frame's width, larger than to scale on
small frames. Over the truth it draws what the team believes, in cyan: the robots' outlines,
the ball with its velocity, 2-sigma ellipses of the position covariances, the particle
trackers' and the self-localization's particles (faint) and the latest ball sighting.

The info bar beneath lists the task's text (time, shot, score) and a legend of exactly the
overlays on screen. An episode starts with a title card (task, seed, robots, observations and
perception) over its first :data:`TITLE_SECONDS` and ends with a banner naming the outcome.
``view="follow"`` crops a window around the ball and the nearest robots and scales it up to
the same frame size. Frames below :data:`BAR_MIN_WIDTH` pixels wide have no info bar (the
task's text is drawn over the field, and no legend).

``rgb_array`` needs no display. pygame is an optional dependency
(``pip install soccer-env[render]``).
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.render.geometry import (
    clamp_centre,
    ellipse_axes,
    ellipse_points,
    follow_window,
)
from soccer_env.render.legend import BELIEF_KEYS, LEGEND_LABELS, flow, legend_keys
from soccer_env.sim.ssl import robot_outline
from soccer_env.state import Belief, WorldState

__all__ = ["Renderer", "RenderingMixin", "Banner", "FrameContents", "wrap_text",
           "RENDER_MODES", "RENDER_VIEWS", "TEAM_COLOURS", "OVERLAY_COLOURS", "TITLE_SECONDS",
           "KEYS_HELP", "check_view"]

RENDER_MODES = ("human", "rgb_array")
#: ``"field"``: the whole walled area; ``"follow"``: a window around the ball and the robots
#: nearest it, scaled up to the same frame size.
RENDER_VIEWS = ("field", "follow")
TEAM_COLOURS = ((40, 100, 255), (245, 215, 0))
#: The title card shows over an episode's first this many simulated seconds [s], fading out
#: over the last :data:`TITLE_FADE` of them.
TITLE_SECONDS = 1.0
TITLE_FADE = 0.3
#: In ``human`` mode the frame with the outcome banner stays this long [s] (keys still act).
BANNER_HOLD = 1.0
#: Smallest drawn robot radius and ball radius, as fractions of the frame's width.
MIN_ROBOT_PX = 1.0 / 80.0
MIN_BALL_PX = 1.0 / 130.0
#: Narrower frames [px] have no info bar.
BAR_MIN_WIDTH = 320
#: The keys of the ``human`` window.
KEYS_HELP = ("space: pause/resume   n or right: one frame (paused)   o: overlays   "
             "l: legend   z: zoom   q or Esc: close")

_CARPET = (24, 120, 48)
_WALL = (90, 60, 30)
_LINE = (235, 235, 235)
_GOAL = (60, 60, 60)
_BALL = (255, 120, 0)
_BALL_EDGE = (60, 30, 0)
_SHADOW = (10, 60, 20)
_BELIEF = (0, 230, 255)
#: The 2-sigma ellipses (a paler cyan than the belief's outlines).
_ELLIPSE = (160, 255, 250)
_BALL_PARTICLE = (0, 230, 255)
_POSE_PARTICLE = (255, 150, 235)
_MEASURED = (255, 40, 200)
_CONE = (205, 205, 205)
_BAR = (22, 26, 30)
_TEXT = (240, 240, 240)
_DIM = (170, 175, 180)
_PAUSED = (255, 210, 60)
_TONES = {"good": (20, 130, 50), "bad": (170, 30, 30), "neutral": (60, 60, 70)}
#: The colours of what is drawn over the field (RGB), by legend key (the belief's robots,
#: ball and velocity share ``"belief"``).
OVERLAY_COLOURS = {"ball": _BALL, "belief": _BELIEF, "ellipses": _ELLIPSE,
                   "ball_particles": _BALL_PARTICLE, "pose_particles": _POSE_PARTICLE,
                   "measurement": _MEASURED, "camera": _CONE}
#: Particles are blended over the frame with this opacity (ball tracker, localization).
_PARTICLE_ALPHA = (0.55, 0.4)
#: The believed velocity is drawn as the distance covered in this time [s].
_VELOCITY_TIME = 0.2


def _import_pygame():
    try:
        os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
        import pygame
    except ImportError as err:  # pragma: no cover - depends on the installation
        raise ImportError(
            "rendering needs pygame; install it with: pip install 'soccer-env[render]'"
        ) from err
    return pygame


def check_view(value: Any) -> str:
    """``value`` if it is one of :data:`RENDER_VIEWS`, else ``ValueError`` naming
    ``render_view`` and the allowed values."""
    if not isinstance(value, str) or value not in RENDER_VIEWS:
        raise ValueError(f"render_view must be one of {list(RENDER_VIEWS)}, got {value!r}")
    return value


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


class Banner(NamedTuple):
    """The banner of an episode's end: ``text`` (the headline, e.g. ``"SAVED"``), a
    ``detail`` line and its ``tone`` (``"good"``, ``"bad"`` or ``"neutral"``: green, red or
    grey, from the learner's side)."""

    text: str
    detail: str = ""
    tone: str = "neutral"


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
        view: ``"field"`` or ``"follow"`` (:data:`RENDER_VIEWS`).
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

    In ``"human"`` mode the window takes these keys (:data:`KEYS_HELP`, also in its caption and
    the info bar's last line): space pauses and resumes; while paused, ``n`` or the right
    arrow lets one more frame through; ``o`` toggles the overlays, ``l`` the legend, ``z``
    the follow view (the frame is redrawn at once while paused); ``q``, Esc or closing the
    window closes it for good (later frames are not drawn).
    """

    def __init__(self, field: FieldSpec, robot: RobotSpec | Sequence[RobotSpec],
                 ball: BallSpec, mode: str, width_px: int = 960, fps: float = 60.0,
                 view: str = "field", teams: Sequence[str] = ("blue team", "yellow team"),
                 owner: str = "the team", caption: str = "soccer_env") -> None:
        if mode not in RENDER_MODES:
            raise ValueError(f"render_mode must be one of {list(RENDER_MODES)} or None, "
                             f"got {mode!r}")
        check_view(view)
        self.pg = pg = _import_pygame()
        self._args = (field, robot, ball, mode, width_px, fps, view, tuple(teams), owner,
                      caption)
        self.field, self.robot, self.ball = field, robot, ball
        self.mode = mode
        self.fps = fps
        self.ox = field.half_length + field.boundary
        self.oy = field.half_width + field.boundary
        self.scale = width_px / (2.0 * self.ox)
        w = int(round(2 * self.ox * self.scale))
        self.field_size = (w, int(round(2 * self.oy * self.scale)))
        self._specs = list(robot) if isinstance(robot, (list, tuple)) else None
        specs = self._specs if self._specs is not None else [robot]
        self._outlines: dict[RobotSpec, np.ndarray] = {}
        self._min_robot = MIN_ROBOT_PX * w
        self._ball_px = max(3, int(round(MIN_BALL_PX * w)))
        self.teams = tuple(teams)
        self.owner = owner
        self.caption = caption
        self.view = view
        self.show_overlays = True
        self.show_legend = True
        self.paused = False
        self.frames_shown = 0
        self.contents: FrameContents | None = None
        self._window = None
        self._clock = None
        self._closed = False
        self._step = False
        self._held: tuple | None = None
        self._last: tuple | None = None
        # The follow view's smoothed half-width [m] and the time of its latest frame [s].
        self._follow: list[float] | None = None
        pg.font.init()
        size = max(12, int(round(w / 30)))
        self._fonts = {"text": pg.font.Font(None, size),
                       "id": pg.font.Font(None, size),
                       "title": pg.font.Font(None, int(round(1.3 * size))),
                       "banner": pg.font.Font(None, max(18, int(round(w / 12))))}
        self._font = self._fonts["text"]
        self._texts: dict[tuple, Any] = {}
        self._line_h = self._font.get_linesize()
        self._humanoids = any(s.kind == "humanoid" for s in specs)
        self._bar_rows = 0
        if w >= BAR_MIN_WIDTH:
            widths = [it[2] for it in self._legend_items(legend_keys(self._humanoids))]
            rows = flow(widths, w - 2 * self._pad, self._spacing)[-1][0] + 1
            self._bar_rows = 1 + rows + (1 if mode == "human" else 0)
        bar = self._bar_rows * self._line_h + (2 * self._pad if self._bar_rows else 0)
        self.size = (w, self.field_size[1] + bar)
        self._background = None
        self._set_view(0.0, 0.0, self.scale)

    # ------------------------------------------------------------------------------------
    # Copies

    def __reduce__(self):
        # pygame's surfaces and fonts do not pickle; a copy draws its own (and opens its own
        # window in "human" mode on its first frame), with the same toggles and follow view.
        return (type(self), self._args, self._copied_state())

    def _copied_state(self) -> dict[str, Any]:
        return {"view": self.view, "show_overlays": self.show_overlays,
                "show_legend": self.show_legend,
                "_follow": None if self._follow is None else list(self._follow)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        for key, value in state.items():
            setattr(self, key, value)

    # ------------------------------------------------------------------------------------
    # Geometry

    @property
    def _pad(self) -> int:
        return max(3, self._line_h // 4)

    @property
    def _spacing(self) -> int:
        return max(8, self._line_h)

    def _set_view(self, cx: float, cy: float, scale: float) -> None:
        """Draw with the point ``(cx, cy)`` [m] at the field view's centre, ``scale`` px/m."""
        w, h = self.field_size
        self._cx, self._cy, self._s = cx, cy, scale
        self._x0, self._y0 = 0.5 * w - cx * scale, 0.5 * h + cy * scale

    def _px(self, x: float, y: float) -> tuple[int, int]:
        return (int(round(self._x0 + x * self._s)), int(round(self._y0 - y * self._s)))

    def pixel(self, x: float, y: float) -> tuple[int, int]:
        """The pixel ``(column, row)`` of the field point ``(x, y)`` [m] in the latest frame's
        field view (which the follow view moves and zooms)."""
        return self._px(x, y)

    def drawn_radius(self, i: int) -> float:
        """Robot ``i``'s radius as drawn in the latest frame [px]: to scale, or larger where
        that would be under :data:`MIN_ROBOT_PX` of the frame's width."""
        spec = self._spec(i)
        return spec.radius * self._inflation(spec) * self._s

    def _px_array(self, xy: np.ndarray) -> np.ndarray:
        """``(K, 2)`` field points [m] as integer pixels."""
        return np.column_stack([np.rint(self._x0 + xy[:, 0] * self._s),
                                np.rint(self._y0 - xy[:, 1] * self._s)]).astype(np.int64)

    def _draw_field(self, surf) -> None:
        pg, f, s = self.pg, self.field, self._s
        hx, hy = f.half_length, f.half_width
        lw = max(1, int(round(f.line_width * s)))
        surf.fill(_CARPET)
        x0, y0 = self._px(-hx, hy)
        x1, y1 = self._px(hx, -hy)
        pg.draw.rect(surf, _LINE, (x0, y0, x1 - x0, y1 - y0), lw)
        pg.draw.line(surf, _LINE, self._px(0, hy), self._px(0, -hy), lw)
        pg.draw.circle(surf, _LINE, self._px(0, 0), int(f.center_circle_radius * s), lw)
        dw, dd = 0.5 * f.defense_width, f.defense_depth
        for sgn in (-1, 1):
            xa, xb = sgn * hx, sgn * (hx - dd)
            pts = [self._px(xa, dw), self._px(xb, dw), self._px(xb, -dw), self._px(xa, -dw)]
            pg.draw.lines(surf, _LINE, False, pts, lw)
            gw, gd = 0.5 * f.goal_width, f.goal_depth
            gx = sgn * (hx + gd)
            goal = [self._px(sgn * hx, gw), self._px(gx, gw), self._px(gx, -gw),
                    self._px(sgn * hx, -gw)]
            pg.draw.lines(surf, _GOAL, False, goal, max(2, int(f.goal_wall_thickness * s)))
        wx0, wy0 = self._px(-self.ox, self.oy)
        wx1, wy1 = self._px(self.ox, -self.oy)
        pg.draw.rect(surf, _WALL, (wx0, wy0, wx1 - wx0, wy1 - wy0), 3)

    def _spec(self, i: int) -> RobotSpec:
        return self.robot if self._specs is None else self._specs[i]

    def _outline(self, spec: RobotSpec) -> np.ndarray:
        """The footprint polygon of ``spec`` in its body frame."""
        key = spec  # (frozen dataclasses: equal specs share one outline)
        if key not in self._outlines:
            if spec.kind == "ssl":
                pts = robot_outline(spec, n_arc=12)
            else:
                a = np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False)
                pts = np.column_stack([spec.radius * np.cos(a), spec.radius * np.sin(a)])
            self._outlines[key] = np.asarray(pts)
        return self._outlines[key]

    def _inflation(self, spec: RobotSpec) -> float:
        """How much a robot is drawn larger than to scale: to at least :data:`MIN_ROBOT_PX`
        of the frame's width."""
        return max(1.0, self._min_robot / (spec.radius * self._s))

    def _footprint(self, i: int, x: float, y: float, th: float, grow: float = 1.0
                   ) -> list[tuple[int, int]]:
        """Robot ``i``'s drawn footprint at ``(x, y, th)`` [m, m, rad], ``grow`` times its
        drawn size."""
        spec = self._spec(i)
        k = self._inflation(spec) * grow
        c, sn = k * math.cos(th), k * math.sin(th)
        out = self._outline(spec)
        pts = np.column_stack([x + c * out[:, 0] - sn * out[:, 1],
                               y + sn * out[:, 0] + c * out[:, 1]])
        return [tuple(p) for p in self._px_array(pts).tolist()]

    # ------------------------------------------------------------------------------------
    # Text

    def _text(self, text: str, colour=_TEXT, font: str = "text", outline: bool = False):
        """``text`` rendered in the font named ``font`` (cached), with a dark outline
        (``outline``) for contrast on any background."""
        key = (text, colour, font, outline)
        surf = self._texts.get(key)
        if surf is None:
            pg = self.pg
            font = self._fonts[font]
            face = font.render(text, True, colour)
            if outline:
                edge = font.render(text, True, (0, 0, 0))
                w, h = face.get_size()
                surf = pg.Surface((w + 2, h + 2), pg.SRCALPHA)
                for dx in (0, 1, 2):
                    for dy in (0, 1, 2):
                        if dx != 1 or dy != 1:
                            surf.blit(edge, (dx, dy))
                surf.blit(face, (1, 1))
            else:
                surf = face
            if len(self._texts) > 512:
                self._texts.clear()
            self._texts[key] = surf
        return surf

    def _legend_items(self, keys: Sequence[str]) -> list[tuple[str, str | None, int]]:
        """The legend's items for the entries ``keys``: ``(key, caption, width [px])``; the
        first of the belief's entries carries the caption naming whose belief it is (kept on
        its row)."""
        sw, gap = self._swatch_width, self._pad
        items, captioned = [], False
        for key in keys:
            caption = None
            if key in BELIEF_KEYS and not captioned:
                caption, captioned = self._belief_caption, True
            width = sw + 4 + self._font.size(self._label(key))[0]
            if caption is not None:
                width += self._font.size(caption)[0] + gap
            items.append((key, caption, width))
        return items

    @property
    def _swatch_width(self) -> int:
        return int(1.4 * self._line_h)

    @property
    def _belief_caption(self) -> str:
        return f"{self.owner} believes:"

    def _label(self, key: str) -> str:
        if key in ("team0", "team1"):
            return self.teams[int(key[-1])]
        return LEGEND_LABELS[key]

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
            if self._closed:
                return None
            self._last = args
            self._show(self._compose(*args))
            self._keys(banner is not None and self._held != (state.time, banner))
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
            aspect = self.field_size[0] / self.field_size[1]
            cx, cy, half_w = follow_window(state.ball, state.robots, state.teams,
                                           (self.ox, self.oy), aspect)
            prev = self._follow
            if prev is not None and state.time >= prev[1]:  # (earlier: a new episode)
                # The window's size follows the robots smoothly (drawn again at the same
                # time, as a paused window does, it stays).
                half_w = (prev[0] + 0.15 * (half_w - prev[0]) if state.time > prev[1]
                          else prev[0])
                cx, cy = clamp_centre(float(state.ball[0]), float(state.ball[1]), half_w,
                                      (self.ox, self.oy), aspect)
            self._follow = [half_w, state.time]
            self._set_view(cx, cy, self.field_size[0] / (2.0 * half_w))
            field = surf.subsurface((0, 0, *self.field_size))
            self._draw_field(field)
        else:
            self._set_view(0.0, 0.0, self.scale)
            if self._background is None:
                self._background = pg.Surface(self.field_size)
                self._draw_field(self._background)
            surf.blit(self._background, (0, 0))
        overlays = self.show_overlays
        field = surf.subsurface((0, 0, *self.field_size))
        self._draw_robots(field, state, heads, overlays, drawn)
        if self._draw_ball(field, state):
            drawn.append("ball" if state.ball[2] <= 1e-3 else "ball_flight")
        if overlays and belief is not None:
            self._draw_belief(field, belief, drawn)
        self._draw_ids(field, state)
        if title:
            self._draw_title(field, title, title_alpha)
        if banner is not None:
            self._draw_banner(field, banner)
        order = [k for k in LEGEND_LABELS if k in drawn]
        shown = self._draw_bar(surf, hud, order)
        w, h = self.field_size
        s = self._s
        window = (self._cx - 0.5 * w / s, self._cx + 0.5 * w / s,
                  self._cy - 0.5 * h / s, self._cy + 0.5 * h / s)
        self.contents = FrameContents(tuple(shown), tuple(self._label(k) for k in shown),
                                      tuple(order), title, banner, self.view, window, s, h)
        return surf

    def _draw_robots(self, surf, state: WorldState, heads: dict, overlays: bool,
                     drawn: list[str]) -> None:
        pg, s = self.pg, self._s
        for i, ((x, y, th, *_), team) in enumerate(zip(state.robots.tolist(),
                                                       state.teams.tolist())):
            if i in heads:
                pan, hfov, reach, lying = heads[i]
                if overlays:
                    a0 = th + pan
                    cone = [self._px(x, y)] + [
                        self._px(x + reach * math.cos(a0 + k * 0.5 * hfov),
                                 y + reach * math.sin(a0 + k * 0.5 * hfov)) for k in (-1, 0, 1)]
                    pg.draw.lines(surf, _CONE, True, cone, 1)
                    if self._visible(cone):
                        drawn.append("camera")
                if lying is not None:
                    la, length = lying
                    end = self._px(x + length * math.cos(th + la),
                                   y + length * math.sin(th + la))
                    pg.draw.line(surf, TEAM_COLOURS[team], self._px(x, y), end,
                                 max(3, int(0.12 * s)))
                    if self._visible([self._px(x, y), end]):
                        drawn.append("fallen")
            spec = self._spec(i)
            pts = self._footprint(i, x, y, th)
            pg.draw.polygon(surf, TEAM_COLOURS[team], pts)
            pg.draw.polygon(surf, (0, 0, 0), pts, 1)
            d = getattr(spec, "front_distance", spec.radius) * self._inflation(spec)
            pg.draw.line(surf, (0, 0, 0), self._px(x, y),
                         self._px(x + math.cos(th) * d, y + math.sin(th) * d), 2)
            if self._visible(pts):
                drawn.append(f"team{team}")

    def _draw_ids(self, surf, state: WorldState) -> None:
        """Every robot's number beside it, above and outwards (blue's to the left, yellow's to
        the right: apart where the teams meet), white outlined in black."""
        for i, ((x, y, *_), name, team) in enumerate(zip(state.robots.tolist(), state.names,
                                                         state.teams.tolist())):
            spec = self._spec(i)
            r = spec.radius * self._s * self._inflation(spec)
            label = self._text(name.rsplit("_", 1)[-1], outline=True, font="id")
            cx, cy = self._px(x, y)
            off = 0.75 * r
            left = cx - off - label.get_width() if team == 0 else cx + off
            left = min(max(0, left), surf.get_width() - label.get_width())  # (on screen)
            surf.blit(label, (int(left), int(cy - off - label.get_height() + 2)))

    def _draw_ball(self, surf, state: WorldState) -> bool:
        """The true ball; returns whether it is in view."""
        pg = self.pg
        bx, by, bz = state.ball[0:3].tolist()
        r = max(self._ball_px, int(round(self.ball.radius * self._s)))
        centre = self._px(bx, by)
        if bz > 1e-3:  # in flight: shadow on the carpet, ball lifted and enlarged
            pg.draw.circle(surf, _SHADOW, centre, r)
            centre = self._px(bx, by + 0.5 * bz)
            r = int(r * (1.0 + min(bz, 2.0)))
        pg.draw.circle(surf, _BALL, centre, r)
        pg.draw.circle(surf, _BALL_EDGE, centre, r, 1)
        return self._visible([centre], r)

    def _draw_belief(self, surf, belief, drawn: list[str]) -> None:
        pg, s = self.pg, self._s
        spread = getattr(belief, "spread", None)
        width = 2 if self.field_size[0] >= 480 else 1
        if spread is not None:
            if spread.pose_particles is not None and len(spread.pose_particles):
                if self._dots(surf, spread.pose_particles[:, 0:2], _POSE_PARTICLE,
                              _PARTICLE_ALPHA[1]):
                    drawn.append("pose_particles")
            if spread.ball_particles is not None and len(spread.ball_particles):
                if self._dots(surf, spread.ball_particles, _BALL_PARTICLE,
                              _PARTICLE_ALPHA[0]):
                    drawn.append("ball_particles")
            ring = max(self._ball_px, int(round(self.ball.radius * s))) + 3
            ellipses = ([(belief.ball[0:2], spread.ball, ring)] if spread.ball is not None
                        else [])
            ellipses += [(row[0:2], cov, self._spec(i).radius * s * self._inflation(
                self._spec(i))) for i, (row, cov) in enumerate(zip(belief.robots,
                                                                    spread.robots))]
            for centre, cov, mark in ellipses:
                axes = ellipse_axes(cov)
                if axes is None or axes[0] * s <= mark:
                    continue  # unknown, or hidden under the mark it surrounds
                pts = [tuple(p) for p in self._px_array(ellipse_points(centre, axes)).tolist()]
                pg.draw.lines(surf, _ELLIPSE, True, pts, width)
                if "ellipses" not in drawn and self._visible(pts):
                    drawn.append("ellipses")
        for i, (x, y, th, *_) in enumerate(belief.robots.tolist()):
            # (a little larger than the robot: a belief on the truth leaves it visible)
            pts = self._footprint(i, x, y, th, 1.2)
            pg.draw.polygon(surf, _BELIEF, pts, 1)
            if "belief_robots" not in drawn and self._visible(pts):
                drawn.append("belief_robots")
        if spread is None or spread.ball is not None:  # (a ball never seen is not drawn)
            bx, by = belief.ball[0:2].tolist()
            centre = self._px(bx, by)
            r = max(self._ball_px, int(round(self.ball.radius * s))) + 3
            pg.draw.circle(surf, _BELIEF, centre, r, width)
            if self._visible([centre], r):
                drawn.append("belief_ball")
            vx, vy = belief.ball[3:5].tolist()
            end = self._px(bx + _VELOCITY_TIME * vx, by + _VELOCITY_TIME * vy)
            if math.hypot(end[0] - centre[0], end[1] - centre[1]) > r:
                pg.draw.line(surf, _BELIEF, centre, end, width)
                if self._visible([centre, end]):
                    drawn.append("belief_velocity")
        quality = getattr(belief, "quality", None)
        measured = None if quality is None else quality.ball_measured
        if measured is not None:
            mx, my = self._px(float(measured[0]), float(measured[1]))
            k = max(3, self._ball_px)
            pg.draw.line(surf, _MEASURED, (mx - k, my - k), (mx + k, my + k), 2)
            pg.draw.line(surf, _MEASURED, (mx - k, my + k), (mx + k, my - k), 2)
            if self._visible([(mx, my)], k):
                drawn.append("measurement")

    def _visible(self, pts: Sequence[tuple[int, int]], margin: float = 0.0) -> bool:
        """Whether the bounding box of the pixels ``pts``, grown by ``margin`` [px], meets the
        field view."""
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        w, h = self.field_size
        return (max(xs) + margin >= 0 and min(xs) - margin < w and max(ys) + margin >= 0
                and min(ys) - margin < h)

    def _dots(self, surf, xy: np.ndarray, colour: tuple[int, int, int], alpha: float) -> bool:
        """Blend 2 x 2 pixel dots of ``colour`` with opacity ``alpha`` at the field points
        ``xy`` ``(K, 2)`` [m]; returns whether any falls inside the view."""
        px = self._px_array(np.asarray(xy, dtype=np.float64))
        w, h = surf.get_size()
        inside = (px[:, 0] >= 0) & (px[:, 0] < w - 1) & (px[:, 1] >= 0) & (px[:, 1] < h - 1)
        px = px[inside]
        if not len(px):
            return False
        xs = np.concatenate([px[:, 0], px[:, 0] + 1, px[:, 0], px[:, 0] + 1])
        ys = np.concatenate([px[:, 1], px[:, 1], px[:, 1] + 1, px[:, 1] + 1])
        arr = self.pg.surfarray.pixels3d(surf)
        try:
            old = arr[xs, ys].astype(np.float32)
            arr[xs, ys] = (old + alpha * (np.asarray(colour, np.float32) - old)).astype(np.uint8)
        finally:
            del arr
        return True

    def _box(self, size: tuple[int, int], colour: tuple[int, int, int], alpha: int):
        box = self.pg.Surface(size, self.pg.SRCALPHA)
        box.fill((*colour, alpha))
        return box

    def _wrap(self, text: str, font: str, width: int) -> list[str]:
        """``text`` wrapped (:func:`wrap_text`) in the font named ``font``."""
        return wrap_text(self._fonts[font], text, width)

    def _draw_title(self, surf, lines: tuple, alpha: float) -> None:
        """The title card: a dark box across the top of the field view (long lines
        wrapped)."""
        pad = self._pad * 2
        room = self.field_size[0] - 4 * pad
        texts = [self._text(part, font="title" if k == 0 else "text")
                 for k, line in enumerate(lines)
                 for part in self._wrap(line, "title" if k == 0 else "text", room)]
        w = min(self.field_size[0] - 2 * pad, max(t.get_width() for t in texts) + 2 * pad)
        h = sum(t.get_height() for t in texts) + 2 * pad
        box = self._box((w, h), (0, 0, 0), 185)
        y = pad
        for t in texts:
            box.blit(t, ((w - t.get_width()) // 2, y))
            y += t.get_height()
        box.set_alpha(int(255 * min(1.0, max(0.0, alpha))))
        surf.blit(box, ((self.field_size[0] - w) // 2, pad))

    def _draw_banner(self, surf, banner: Banner) -> None:
        """The outcome banner: its headline large, its detail below, across the middle."""
        head = self._text(banner.text, font="banner")
        detail = self._text(banner.detail) if banner.detail else None
        pad = self._pad * 3
        w = max(head.get_width(), detail.get_width() if detail else 0) + 4 * pad
        h = head.get_height() + (detail.get_height() if detail else 0) + 2 * pad
        w = min(w, self.field_size[0])
        box = self._box((w, h), _TONES.get(banner.tone, _TONES["neutral"]), 215)
        box.blit(head, ((w - head.get_width()) // 2, pad))
        if detail is not None:
            box.blit(detail, ((w - detail.get_width()) // 2, pad + head.get_height()))
        fw, fh = self.field_size
        surf.blit(box, ((fw - w) // 2, (fh - h) // 2))

    def _draw_bar(self, surf, hud: tuple, order: list[str]) -> list[str]:
        """The info bar: the task's text, the legend of what is drawn, and in a window its
        keys. Returns the legend keys drawn."""
        text = "     ".join(hud)
        if not self._bar_rows:  # a small frame: the task's text over the field, no legend
            for row, line in enumerate(hud):
                surf.blit(self._text(line, outline=True), (4, 3 + self._line_h * row))
            return []
        pg = self.pg
        w, top = self.size[0], self.field_size[1]
        pad, lh = self._pad, self._line_h
        pg.draw.rect(surf, _BAR, (0, top, w, self.size[1] - top))
        y = top + pad
        surf.blit(self._text(text), (pad, y))
        shown = order if self.show_legend else []
        if shown:
            items = self._legend_items(shown)
            sw = self._swatch_width
            places = flow([it[2] for it in items], w - 2 * pad, self._spacing)
            for (key, caption, _), (row, x) in zip(items, places):
                if row + 2 > self._bar_rows - (1 if self.mode == "human" else 0):
                    break  # (the bar is sized for every entry; never reached)
                ry, x = y + lh * (row + 1), pad + x
                if caption is not None:
                    text = self._text(caption, _DIM)
                    surf.blit(text, (x, ry))
                    x += text.get_width() + pad
                self._swatch(surf, key, pg.Rect(x, ry + 1, sw, lh - 2))
                surf.blit(self._text(self._label(key)), (x + sw + 4, ry))
        if self.mode == "human":
            ry = top + pad + lh * (self._bar_rows - 1)
            if self.paused:
                surf.blit(self._text("PAUSED   space: resume   n or right: one frame",
                                     _PAUSED), (pad, ry))
            else:
                surf.blit(self._text(KEYS_HELP, _DIM), (pad, ry))
        return list(shown)

    def _swatch(self, surf, key: str, rect) -> None:
        """The legend's sample of the entry ``key`` in ``rect``."""
        pg = self.pg
        cx, cy = rect.center
        r = max(3, rect.height // 2 - 1)
        if key in ("team0", "team1"):
            pg.draw.circle(surf, TEAM_COLOURS[int(key[-1])], (cx, cy), r)
            pg.draw.circle(surf, (0, 0, 0), (cx, cy), r, 1)
        elif key == "ball":
            pg.draw.circle(surf, _BALL, (cx, cy), max(2, r - 3))
        elif key == "ball_flight":
            pg.draw.circle(surf, _SHADOW, (cx + 3, cy + 3), max(2, r - 3))
            pg.draw.circle(surf, _BALL, (cx - 1, cy - 1), max(2, r - 2))
        elif key == "belief_robots":
            pg.draw.circle(surf, _BELIEF, (cx, cy), r, 2)
        elif key == "belief_ball":
            pg.draw.circle(surf, _BELIEF, (cx, cy), max(3, r - 2), 2)
        elif key == "belief_velocity":
            pg.draw.line(surf, _BELIEF, (rect.left + 2, cy), (rect.right - 2, cy), 2)
        elif key == "ellipses":
            pg.draw.ellipse(surf, _ELLIPSE, rect.inflate(-2, -4), 2)
        elif key in ("ball_particles", "pose_particles"):
            colour = _BALL_PARTICLE if key == "ball_particles" else _POSE_PARTICLE
            rng = np.random.default_rng(1)  # the same sample every frame
            for px, py in rng.integers((rect.left + 2, rect.top + 2),
                                       (rect.right - 3, rect.bottom - 3), (14, 2)).tolist():
                pg.draw.rect(surf, colour, (px, py, 2, 2))
        elif key == "measurement":
            k = max(3, r - 3)
            pg.draw.line(surf, _MEASURED, (cx - k, cy - k), (cx + k, cy + k), 2)
            pg.draw.line(surf, _MEASURED, (cx - k, cy + k), (cx + k, cy - k), 2)
        elif key == "camera":
            pg.draw.lines(surf, _CONE, True, [(rect.left + 2, cy), (rect.right - 2, rect.top + 1),
                                              (rect.right - 2, rect.bottom - 1)], 1)
        elif key == "fallen":
            pg.draw.line(surf, TEAM_COLOURS[0], (rect.left + 2, cy), (rect.right - 2, cy), 4)

    # ------------------------------------------------------------------------------------
    # The window

    def _show(self, surf) -> None:
        pg = self.pg
        if self._window is None:
            pg.display.init()
            self._window = pg.display.set_mode(self.size)
            pg.display.set_caption(f"{self.caption}   [{KEYS_HELP}]")
            self._clock = pg.time.Clock()
        self._window.blit(surf, (0, 0))
        pg.display.flip()
        self.frames_shown += 1
        self._clock.tick(self.fps)

    def _keys(self, hold: bool) -> None:
        """Act on the window's keys; while paused (or for :data:`BANNER_HOLD` after an
        outcome banner, ``hold``), wait for them."""
        pg = self.pg
        for event in pg.event.get():
            self._key(event)
        until = time.monotonic() + BANNER_HOLD if hold else 0.0
        while not self._closed:
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

    def _key(self, event) -> None:
        """One window event: the keys of the class docstring."""
        pg = self.pg
        if event.type == pg.QUIT:
            self.close(for_good=True)
            return
        if event.type != pg.KEYDOWN:
            return
        key = event.key
        redraw = False
        if key in (pg.K_q, pg.K_ESCAPE):
            self.close(for_good=True)
            return
        if key == pg.K_SPACE:
            self.paused = not self.paused
            self._step = False
            redraw = True
        elif key in (pg.K_n, pg.K_RIGHT):
            self._step = self.paused
        elif key == pg.K_o:
            self.show_overlays, redraw = not self.show_overlays, True
        elif key == pg.K_l:
            self.show_legend, redraw = not self.show_legend, True
        elif key == pg.K_z:
            self.view, redraw = ("follow" if self.view == "field" else "field"), True
        if redraw and self._last is not None and self._window is not None:
            self._window.blit(self._compose(*self._last), (0, 0))
            pg.display.flip()

    def close(self, for_good: bool = False) -> None:
        """Close the window, if any (``for_good``: and draw no more frames into one, as the
        ``q`` key does)."""
        if self._window is not None:
            self.pg.display.quit()
            self._window = None
        if for_good:
            self._closed, self.paused = True, False


class RenderingMixin:
    """``render()`` and ``close()`` for the environments.

    Expects ``render_mode``, ``field``, ``ball_spec``, ``world`` (its robot specs),
    ``metadata["render_fps"]``, ``_render_width`` and ``_render_view`` on the environment, a
    ``_scene()`` method returning what to draw (the truth, the belief to draw over it or None,
    and the humanoids' camera views, as :meth:`Renderer.draw` takes them), and these, whose
    defaults draw nothing: ``_hud()`` (lines of text), ``_title_card()`` (the title card's
    lines), ``_banner()`` (the outcome banner or None), ``_team_labels()`` and
    ``_belief_owner()`` (the legend's words). The renderer is created on first use.
    """

    _renderer: Renderer | None = None
    _render_view: str = "field"

    def _hud(self) -> list[str]:
        return []

    def _title_card(self) -> list[str]:
        return []

    def _banner(self) -> Banner | None:
        return None

    def _team_labels(self) -> tuple[str, str]:
        return ("blue team", "yellow team")

    def _belief_owner(self) -> str:
        return "the team"

    def _caption(self) -> str:
        return "soccer_env"

    @property
    def renderer(self) -> Renderer | None:
        """The renderer (None before the first :meth:`render`): its view and toggles, and
        what the latest frame shows (:attr:`Renderer.contents`)."""
        return self._renderer

    def render(self):
        """The current frame (``rgb_array``), or draw it in the window (``human``).

        The frame is the field view (``render_view="field"``: the whole walled area;
        ``"follow"``: a window around the ball and the robots nearest it, zoomed 2-4 times)
        above an info bar with the task's text and a legend of the overlays on screen. The
        title card shows over an episode's first second; the outcome banner on frames after
        its end. In ``human`` mode the window's keys are: space pauses and resumes, ``n`` or
        the right arrow lets one frame through while paused, ``o`` toggles the overlays (the
        belief and the camera views), ``l`` the legend, ``z`` the follow view, ``q`` or Esc
        closes the window (see :class:`Renderer`).
        """
        if self.render_mode is None:
            import gymnasium

            gymnasium.logger.warn("render() called without a render_mode; pass render_mode= "
                                  "when creating the environment")
            return None
        if self._renderer is None:
            self._renderer = Renderer(self.field, list(self.world.robot_specs), self.ball_spec,
                                      self.render_mode, self._render_width,
                                      self.metadata["render_fps"], self._render_view,
                                      self._team_labels(), self._belief_owner(),
                                      self._caption())
        state, belief, heads = self._scene()
        t = state.time
        title: list[str] = []
        alpha = 1.0
        if t < TITLE_SECONDS - 1e-9:
            title = self._title_card()
            alpha = min(1.0, (TITLE_SECONDS - t) / TITLE_FADE)
        return self._renderer.draw(state, self._hud(), belief, heads or None, title=title,
                                   title_alpha=alpha, banner=self._banner())

    def close(self) -> None:
        """Close the window, if any."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
