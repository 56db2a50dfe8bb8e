"""The field view's world-to-pixel transform (:class:`View`): the whole walled area, or the
follow view's window around the ball and the robots nearest it, scaled to the same frame
(field frame in metres; pixels with rows growing downwards)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from soccer_env.presets import FieldSpec
from soccer_env.render.geometry import clamp_centre, follow_window
from soccer_env.state import WorldState

__all__ = ["View", "RENDER_VIEWS", "check_view", "FOLLOW_SMOOTHING"]

#: ``"field"``: the whole walled area; ``"follow"``: a window around the ball and the robots
#: nearest it, scaled up to the same frame size.
RENDER_VIEWS = ("field", "follow")
#: The follow view's window size moves this fraction of the way to its target each frame.
FOLLOW_SMOOTHING = 0.15


def check_view(value: Any) -> str:
    """``value`` if it is one of :data:`RENDER_VIEWS`, else ``ValueError`` naming
    ``render_view`` and the allowed values."""
    if not isinstance(value, str) or value not in RENDER_VIEWS:
        raise ValueError(f"render_view must be one of {list(RENDER_VIEWS)}, got {value!r}")
    return value


class View:
    """Where the field view puts field points: the point ``(cx, cy)`` [m] at its centre,
    ``s`` pixels per metre.

    Args:
        field: the field drawn (its walled area is the whole view).
        width_px: the view's width [px]; its height follows the walled area's aspect.

    Attributes:
        ox, oy: half the walled area's length and width [m].
        scale: pixels per metre of the whole field.
        field_size: the view's ``(width, height)`` [px].
        follow: the follow view's smoothed half-width [m] and the time of its latest frame
            [s] (None before its first frame).
    """

    def __init__(self, field: FieldSpec, width_px: int) -> None:
        self.ox = field.half_length + field.boundary
        self.oy = field.half_width + field.boundary
        self.scale = width_px / (2.0 * self.ox)
        w = int(round(2 * self.ox * self.scale))
        self.field_size = (w, int(round(2 * self.oy * self.scale)))
        self.follow: list[float] | None = None
        self.set(0.0, 0.0, self.scale)

    def set(self, cx: float, cy: float, scale: float) -> None:
        """Draw with the point ``(cx, cy)`` [m] at the field view's centre, ``scale`` px/m."""
        w, h = self.field_size
        self.cx, self.cy, self.s = cx, cy, scale
        self.x0, self.y0 = 0.5 * w - cx * scale, 0.5 * h + cy * scale

    def whole(self) -> None:
        """The whole walled area."""
        self.set(0.0, 0.0, self.scale)

    def follow_state(self, state: WorldState) -> None:
        """The follow view of ``state``: :func:`~soccer_env.render.geometry.follow_window`,
        its size smoothed from frame to frame (:data:`FOLLOW_SMOOTHING`; drawn again at the
        same time, as a paused window does, it stays; an earlier time starts anew)."""
        aspect = self.field_size[0] / self.field_size[1]
        cx, cy, half_w = follow_window(state.ball, state.robots, state.teams,
                                       (self.ox, self.oy), aspect)
        prev = self.follow
        if prev is not None and state.time >= prev[1]:  # (earlier: a new episode)
            half_w = (prev[0] + FOLLOW_SMOOTHING * (half_w - prev[0]) if state.time > prev[1]
                      else prev[0])
            cx, cy = clamp_centre(float(state.ball[0]), float(state.ball[1]), half_w,
                                  (self.ox, self.oy), aspect)
        self.follow = [half_w, state.time]
        self.set(cx, cy, self.field_size[0] / (2.0 * half_w))

    def px(self, x: float, y: float) -> tuple[int, int]:
        """The pixel ``(column, row)`` of the field point ``(x, y)`` [m]."""
        return (int(round(self.x0 + x * self.s)), int(round(self.y0 - y * self.s)))

    def px_array(self, xy: np.ndarray) -> np.ndarray:
        """``(K, 2)`` field points [m] as integer pixels."""
        return np.column_stack([np.rint(self.x0 + xy[:, 0] * self.s),
                                np.rint(self.y0 - xy[:, 1] * self.s)]).astype(np.int64)

    def visible(self, pts: Sequence[tuple[int, int]], margin: float = 0.0) -> bool:
        """Whether the bounding box of the pixels ``pts``, grown by ``margin`` [px], meets the
        field view."""
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        w, h = self.field_size
        return (max(xs) + margin >= 0 and min(xs) - margin < w and max(ys) + margin >= 0
                and min(ys) - margin < h)

    def window(self) -> tuple[float, float, float, float]:
        """The part of the field shown, ``(x_min, x_max, y_min, y_max)`` [m]."""
        w, h = self.field_size
        s = self.s
        return (self.cx - 0.5 * w / s, self.cx + 0.5 * w / s,
                self.cy - 0.5 * h / s, self.cy + 0.5 * h / s)
