"""The geometry of what the renderer draws, without pygame: covariance ellipses and the
window of the follow view (field frame, metres and radians)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

__all__ = ["ellipse_axes", "ellipse_points", "follow_window", "clamp_centre", "FOLLOW_ZOOM",
           "FOLLOW_MARGIN"]

#: The follow view's window is between ``1 / FOLLOW_ZOOM[1]`` and ``1 / FOLLOW_ZOOM[0]`` of the
#: walled area's width (zoomed in 2 to 4 times).
FOLLOW_ZOOM = (2.0, 4.0)
#: Room left around the robots nearest the ball in the follow view [m].
FOLLOW_MARGIN = 0.4

_UNIT = np.linspace(0.0, 2.0 * math.pi, 40, endpoint=False)
_UNIT_CIRCLE = np.column_stack([np.cos(_UNIT), np.sin(_UNIT)])


def ellipse_axes(cov: np.ndarray, n_sigma: float = 2.0) -> tuple[float, float, float] | None:
    """The ``n_sigma`` ellipse of the ``2 x 2`` position covariance ``cov`` [m^2]: semi-axes
    ``a >= b`` [m], ``n_sigma sqrt(lambda)`` for the eigenvalues ``lambda`` of ``cov``, and
    the angle of the major axis from the x axis [rad]. For ``cov = [[p, q], [q, r]]``:
    ``lambda = (p + r) / 2 +- sqrt(((p - r) / 2)^2 + q^2)`` and the angle
    ``atan2(2 q, p - r) / 2``. None for a covariance that is not finite (unknown); a
    slightly negative eigenvalue (round-off) counts as 0.

    Args:
        cov: ``(2, 2)`` symmetric covariance of ``(x, y)`` [m^2].
        n_sigma: how many standard deviations the ellipse spans (> 0).

    Returns:
        ``(a, b, angle)`` in metres and radians, or None.
    """
    c = np.asarray(cov, dtype=np.float64)
    if c.shape != (2, 2) or not np.isfinite(c).all():
        return None
    p, q, r = float(c[0, 0]), 0.5 * float(c[0, 1] + c[1, 0]), float(c[1, 1])
    mid, half = 0.5 * (p + r), math.hypot(0.5 * (p - r), q)
    big, small = max(0.0, mid + half), max(0.0, mid - half)
    return (n_sigma * math.sqrt(big), n_sigma * math.sqrt(small),
            0.5 * math.atan2(2.0 * q, p - r))


def ellipse_points(centre: Sequence[float], axes: tuple[float, float, float]) -> np.ndarray:
    """``(40, 2)`` points [m] on the ellipse with ``axes`` ``(a, b, angle)`` (see
    :func:`ellipse_axes`) around ``centre`` ``(x, y)`` [m]."""
    a, b, angle = axes
    c, s = math.cos(angle), math.sin(angle)
    u = _UNIT_CIRCLE[:, 0] * a
    v = _UNIT_CIRCLE[:, 1] * b
    return np.column_stack([centre[0] + c * u - s * v, centre[1] + s * u + c * v])


def follow_window(ball: Sequence[float], robots: np.ndarray, teams: Sequence[int],
                  extent: tuple[float, float], aspect: float) -> tuple[float, float, float]:
    """The follow view's window: centred on the ball, wide enough to show the robot of each
    team nearest the ball with :data:`FOLLOW_MARGIN` around it, and zoomed in between
    :data:`FOLLOW_ZOOM` times; then moved (not shrunk) to stay inside the walled area.

    Args:
        ball: the ball's ``(x, y)`` [m].
        robots: ``(N, >=2)`` robot positions [m] (N may be 0).
        teams: every robot's team (0 or 1).
        extent: the walled area's half-length and half-width ``(ox, oy)`` [m].
        aspect: the view's width over its height (pixels).

    Returns:
        ``(cx, cy, half_width)``: the window's centre [m] and half its width [m] (its
        half-height is ``half_width / aspect``).
    """
    ox, oy = extent
    bx, by = float(ball[0]), float(ball[1])
    need = 0.0
    pos = np.asarray(robots, dtype=np.float64)
    if pos.ndim == 2 and len(pos):
        d = pos[:, 0:2] - (bx, by)
        dist = np.hypot(d[:, 0], d[:, 1])
        team = np.asarray(teams)
        for t in (0, 1):
            rows = np.flatnonzero(team == t)
            if len(rows):
                k = rows[np.argmin(dist[rows])]
                need = max(need, abs(d[k, 0]) + FOLLOW_MARGIN,
                           (abs(d[k, 1]) + FOLLOW_MARGIN) * aspect)
    lo, hi = ox / FOLLOW_ZOOM[1], ox / FOLLOW_ZOOM[0]
    half_w = min(hi, max(lo, need))
    return (*clamp_centre(bx, by, half_w, extent, aspect), half_w)


def clamp_centre(cx: float, cy: float, half_w: float, extent: tuple[float, float],
                 aspect: float) -> tuple[float, float]:
    """The window centre ``(cx, cy)`` [m] moved as little as needed for the window of
    half-width ``half_w`` [m] (half-height ``half_w / aspect``) to stay inside the walled
    area of half-extent ``extent`` [m]."""
    ox, oy = extent
    half_h = half_w / aspect
    cx = 0.0 if half_w >= ox else min(ox - half_w, max(-ox + half_w, cx))
    cy = 0.0 if half_h >= oy else min(oy - half_h, max(-oy + half_h, cy))
    return cx, cy
