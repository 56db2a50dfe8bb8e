"""Self-localization from the bearings of three known landmarks (paper 000, Xu, Xie, Wang, Ni
2012, SPEC 1.1).

A robot at ``R = (x, y)`` with heading ``theta`` measures the bearing ``phi_i`` of landmark
``P_i`` relative to its heading (counter-clockwise positive; with a panning head, the camera's
bearing plus the pan angle). Any two landmarks and ``R`` lie on a circle whose inscribed angle
at ``R`` is ``phi_j - phi_i`` (paper 000's two circles through ``P1, P2`` and ``P2, P3``); ``R``
is the second intersection of those circles, and the heading follows from any bearing:
``theta = atan2(P_i - R) - phi_i`` (averaged over the three on the circle).

The intersection is computed with the ToTal algorithm (Pierlot and Van Droogenbroeck, IEEE
T-RO 2014), a closed form of exactly this two-circle construction that works in every landmark
order and avoids the paper's sign conventions; it is a handful of arithmetic operations, so
it is written out here.

Degenerate configurations are reported, not crashed on (:class:`Fix` with ``ok=False`` and a
``reason``):

* fewer than three landmarks: with two, the robot is anywhere on one circle;
* two bearings equal or opposite (the robot on the line through two landmarks): the inscribed
  angle is 0 or pi and its circle degenerates into that line;
* the robot on the circle through the three landmarks (or, for collinear landmarks, on their
  line): the two circles coincide.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["Fix", "triangulate"]

#: Below this |sin| of a bearing difference the two bearings are taken as parallel.
_MIN_SIN = 1e-9
#: Below this relative size of ToTal's determinant the circles are taken as the same.
_MIN_DET = 1e-12


@dataclass(frozen=True)
class Fix:
    """The result of :func:`triangulate`.

    Attributes:
        ok: whether ``position`` and ``heading`` are determined.
        position: ``(2,)`` robot position (NaN when not ``ok``) [m].
        heading: robot heading [rad] in ``(-pi, pi]`` (NaN when not ``ok``).
        reason: why not (empty when ``ok``).
    """

    ok: bool
    position: np.ndarray
    heading: float
    reason: str = ""


def _fail(reason: str) -> Fix:
    return Fix(False, np.full(2, np.nan), math.nan, reason)


def triangulate(landmarks: np.ndarray | Sequence[Sequence[float]],
                bearings: np.ndarray | Sequence[float]) -> Fix:
    """Position and heading of a robot from the bearings [rad] of three landmarks ((3, 2)
    positions [m]); see the module docstring. Raises ``ValueError`` only for malformed input
    (shapes, non-finite values); degenerate geometry gives ``Fix(ok=False, reason=...)``."""
    P = np.asarray(landmarks, dtype=np.float64)
    phi = np.asarray(bearings, dtype=np.float64)
    if P.ndim != 2 or P.shape[1] != 2 or phi.shape != (len(P),):
        raise ValueError(f"landmarks must have shape (n, 2) and bearings (n,), got {P.shape} "
                         f"and {phi.shape}")
    if not (np.isfinite(P).all() and np.isfinite(phi).all()):
        raise ValueError("landmarks and bearings must be finite")
    if len(P) < 3:
        return _fail(f"{len(P)} landmark(s): three are needed (with two the robot lies "
                     "anywhere on a circle through them)")
    if len(P) > 3:
        raise ValueError(f"triangulate takes exactly three landmarks, got {len(P)}")
    if np.min(np.hypot(*(P[[0, 1, 2]] - P[[1, 2, 0]]).T)) <= 0.0:
        return _fail("two landmarks coincide")
    (x1, y1), (x2, y2), (x3, y3) = P
    a1, a2, a3 = phi
    sins = [math.sin(a2 - a1), math.sin(a3 - a2)]
    if min(abs(s) for s in sins) < _MIN_SIN:
        return _fail("two bearings are equal or opposite: the robot is on the line through "
                     "two landmarks")
    t12 = math.cos(a2 - a1) / sins[0]
    t23 = math.cos(a3 - a2) / sins[1]
    if abs(t12 + t23) < _MIN_SIN:
        return _fail("the bearings are inconsistent (no third circle)")
    t31 = (1.0 - t12 * t23) / (t12 + t23)
    x1p, y1p, x3p, y3p = x1 - x2, y1 - y2, x3 - x2, y3 - y2
    x12, y12 = x1p + t12 * y1p, y1p - t12 * x1p
    x23, y23 = x3p - t23 * y3p, y3p + t23 * x3p
    x31, y31 = (x3p + x1p) + t31 * (y3p - y1p), (y3p + y1p) - t31 * (x3p - x1p)
    k31 = x1p * x3p + y1p * y3p + t31 * (x1p * y3p - x3p * y1p)
    det = (x12 - x23) * (y23 - y31) - (y12 - y23) * (x23 - x31)
    scale = max(abs(x12), abs(y12), abs(x23), abs(y23), abs(x31), abs(y31), 1e-300) ** 2
    if abs(det) < _MIN_DET * scale:
        return _fail("the robot is on the circle through the three landmarks (or on their "
                     "line): the position is not determined")
    xr = x2 + k31 * (y12 - y23) / det
    yr = y2 + k31 * (x23 - x12) / det
    pos = np.array([xr, yr])
    angles = np.arctan2(P[:, 1] - yr, P[:, 0] - xr) - phi
    heading = math.atan2(float(np.mean(np.sin(angles))), float(np.mean(np.cos(angles))))
    return Fix(True, pos, heading)
