"""Top-down rendering with pygame: an RGB array or a live window.

The field is drawn to scale with its lines, defense areas and goals; robots in team colours
with their flat front (SSL) or as discs with their head camera's field of view (humanoids;
a fallen humanoid's body lies beside it), a heading mark and their number; the ball in orange
(with a shadow and a larger disc while it flies). ``rgb_array`` needs no display. pygame is
an optional dependency (``pip install soccer-env[render]``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.sim.ssl import robot_outline
from soccer_env.state import WorldState

__all__ = ["Renderer", "RenderingMixin", "RENDER_MODES", "TEAM_COLOURS"]

RENDER_MODES = ("human", "rgb_array")
TEAM_COLOURS = ((40, 100, 255), (245, 215, 0))
_CARPET = (24, 120, 48)
_SURROUND = (16, 88, 36)
_LINE = (235, 235, 235)
_GOAL = (60, 60, 60)
_BALL = (255, 120, 0)
_BELIEF = (0, 230, 255)


def _import_pygame():
    try:
        os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
        import pygame
    except ImportError as err:  # pragma: no cover - depends on the installation
        raise ImportError(
            "rendering needs pygame; install it with: pip install 'soccer-env[render]'"
        ) from err
    return pygame


class Renderer:
    """Draws :class:`~soccer_env.state.WorldState` snapshots.

    Args:
        field, robot, ball: the specs of the world to draw (``robot``: one spec for all robots
            or one per robot).
        mode: ``"rgb_array"`` or ``"human"``.
        width_px: width of the image in pixels (the height follows the field's aspect).
        fps: frame rate of the ``"human"`` window.
    """

    def __init__(self, field: FieldSpec, robot: RobotSpec | Sequence[RobotSpec],
                 ball: BallSpec, mode: str, width_px: int = 960, fps: float = 60.0) -> None:
        if mode not in RENDER_MODES:
            raise ValueError(f"render_mode must be one of {list(RENDER_MODES)} or None, "
                             f"got {mode!r}")
        self.pg = _import_pygame()
        self._args = (field, robot, ball, mode, width_px, fps)
        self.field, self.robot, self.ball = field, robot, ball
        self.mode = mode
        self.fps = fps
        self.ox = field.half_length + field.boundary
        self.oy = field.half_width + field.boundary
        self.scale = width_px / (2.0 * self.ox)
        self.size = (int(round(2 * self.ox * self.scale)), int(round(2 * self.oy * self.scale)))
        self._specs = list(robot) if isinstance(robot, (list, tuple)) else None
        self._outlines: dict[RobotSpec, np.ndarray] = {}
        self._window = None
        self._clock = None
        self.pg.font.init()
        self._font = self.pg.font.Font(None, max(12, int(0.16 * self.scale)))
        self._hud = self.pg.font.Font(None, 22)
        self._background = self._draw_field()

    def __reduce__(self):
        # pygame's surfaces and fonts do not pickle; a copy draws its own (and opens its own
        # window in "human" mode on its first frame).
        return (type(self), self._args)

    def _px(self, x: float, y: float) -> tuple[int, int]:
        return (int(round((x + self.ox) * self.scale)), int(round((self.oy - y) * self.scale)))

    def _draw_field(self):
        pg, f, s = self.pg, self.field, self.scale
        surf = pg.Surface(self.size)
        surf.fill(_SURROUND)
        hx, hy = f.half_length, f.half_width
        lw = max(1, int(round(f.line_width * s)))
        x0, y0 = self._px(-hx, hy)
        pg.draw.rect(surf, _CARPET, (0, 0, *self.size))
        pg.draw.rect(surf, _LINE, (x0, y0, int(2 * hx * s), int(2 * hy * s)), lw)
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
        pg.draw.rect(surf, (90, 60, 30), (0, 0, *self.size), 3)
        return surf

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

    def draw(self, state: WorldState, hud: Sequence[str] = (), belief=None,
             heads: dict | None = None) -> np.ndarray | None:
        """Draw ``state`` (and, if given, what the team believes: ``belief.ball`` and
        ``belief.robots`` in the layout of the state, drawn as outlines in cyan); ``heads``
        maps humanoid robot indices to ``(pan, hfov, range, lying)``: the camera's view is
        drawn as a cone, and a fallen robot's body (``lying``: its direction in the body
        frame and length, or None) beside it. Returns an ``(H, W, 3)`` uint8 frame
        (``rgb_array``) or None."""
        pg, s = self.pg, self.scale
        surf = self._background.copy()
        heads = heads or {}
        for i, ((x, y, th, *_), team, name) in enumerate(zip(state.robots, state.teams,
                                                             state.names)):
            spec = self._spec(i)
            c, sn = math.cos(th), math.sin(th)
            if i in heads:
                pan, hfov, reach, lying = heads[i]
                a0 = th + pan
                cone = [self._px(x, y)] + [
                    self._px(x + reach * math.cos(a0 + k * 0.5 * hfov),
                             y + reach * math.sin(a0 + k * 0.5 * hfov)) for k in (-1, 0, 1)]
                pg.draw.lines(surf, (200, 200, 200), True, cone, 1)
                if lying is not None:
                    la, length = lying
                    end = self._px(x + length * math.cos(th + la), y + length * math.sin(th + la))
                    pg.draw.line(surf, TEAM_COLOURS[team], self._px(x, y), end,
                                 max(2, int(0.12 * s)))
            pts = [self._px(x + c * u - sn * v, y + sn * u + c * v)
                   for u, v in self._outline(spec)]
            pg.draw.polygon(surf, TEAM_COLOURS[team], pts)
            pg.draw.polygon(surf, (0, 0, 0), pts, 1)
            d = getattr(spec, "front_distance", spec.radius)
            pg.draw.line(surf, (0, 0, 0), self._px(x, y), self._px(x + c * d, y + sn * d), 2)
            label = self._font.render(name.rsplit("_", 1)[1], True, (0, 0, 0))
            cx, cy = self._px(x - 0.35 * c * d, y - 0.35 * sn * d)
            surf.blit(label, label.get_rect(center=(cx, cy)))
        bx, by, bz = state.ball[0:3]
        # Drawn at least 4 px wide so that it stays visible on large fields.
        r = max(4, int(round(self.ball.radius * s)))
        centre = self._px(bx, by)
        if bz > 1e-3:  # in flight: shadow on the carpet, ball lifted and enlarged
            pg.draw.circle(surf, (10, 60, 20), centre, r)
            centre = self._px(bx, by + 0.5 * bz)
            r = int(r * (1.0 + min(bz, 2.0)))
        pg.draw.circle(surf, _BALL, centre, r)
        pg.draw.circle(surf, (60, 30, 0), centre, r, 1)
        if belief is not None:
            for i, (x, y, th, *_) in enumerate(belief.robots.tolist()):
                c, sn = math.cos(th), math.sin(th)
                pts = [self._px(x + c * u - sn * v, y + sn * u + c * v)
                       for u, v in self._outline(self._spec(i))]
                pg.draw.polygon(surf, _BELIEF, pts, 1)
            bx, by = belief.ball[0:2]
            pg.draw.circle(surf, _BELIEF, self._px(bx, by), max(4, int(round(
                self.ball.radius * s))) + 2, 2)
            ex, ey = bx + 0.2 * belief.ball[3], by + 0.2 * belief.ball[4]
            pg.draw.line(surf, _BELIEF, self._px(bx, by), self._px(ex, ey), 1)
        for row, text in enumerate(hud):
            surf.blit(self._hud.render(text, True, (255, 255, 255)), (8, 6 + 20 * row))
        if self.mode == "human":
            if self._window is None:
                pg.display.init()
                self._window = pg.display.set_mode(self.size)
                pg.display.set_caption("soccer_env")
                self._clock = pg.time.Clock()
            self._window.blit(surf, (0, 0))
            pg.event.pump()
            pg.display.flip()
            self._clock.tick(self.fps)
            return None
        return np.transpose(pg.surfarray.array3d(surf), (1, 0, 2)).copy()

    def close(self) -> None:
        """Close the window, if any."""
        if self._window is not None:
            self.pg.display.quit()
            self._window = None


class RenderingMixin:
    """``render()`` and ``close()`` for the environments.

    Expects ``render_mode``, ``field``, ``ball_spec``, ``world`` (its robot specs),
    ``metadata["render_fps"]`` and ``_render_width`` on the environment, a ``_scene()``
    method returning what to draw (the truth, the belief to draw over it or None, and the
    humanoids' camera views, as :meth:`Renderer.draw` takes them) and a ``_hud()`` method
    returning the lines of text to overlay. The renderer is created on first use.
    """

    _renderer: Renderer | None = None

    def _hud(self) -> list[str]:
        return []

    def render(self):
        """The current frame (``rgb_array``), or draw it in the window (``human``)."""
        if self.render_mode is None:
            import gymnasium

            gymnasium.logger.warn("render() called without a render_mode; pass render_mode= "
                                  "when creating the environment")
            return None
        if self._renderer is None:
            self._renderer = Renderer(self.field, list(self.world.robot_specs), self.ball_spec,
                                      self.render_mode, self._render_width,
                                      self.metadata["render_fps"])
        state, belief, heads = self._scene()
        return self._renderer.draw(state, self._hud(), belief, heads or None)

    def close(self) -> None:
        """Close the window, if any."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
