"""The gate: which of a frame's detections is the tracked ball, and whether a rejected one is
the ball kicked where it is.

Every ball tracker of the package takes, of a frame's detections, the one nearest its
prediction and fuses it only if it lies within a chi-square quantile of the squared
Mahalanobis distance; a detection outside that gate but near enough that the ball could have
got there by a kick or a bounce since the previous frame is a change of motion where the ball
is, not an outlier (each tracker handles it with its own model: a maneuver, a mode switch, a
new motion). :class:`Gate` holds both tests.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

__all__ = ["Gate", "CHI2_2DOF_999", "MAX_SPEED_CHANGE"]

#: 99.9 % quantile of the chi-square distribution with 2 degrees of freedom.
CHI2_2DOF_999 = 13.815510557964274

#: Largest change of the ball's velocity a kick or a bounce can make [m/s] (a 6.5 m/s ball
#: reversing off a robot moving towards it).
MAX_SPEED_CHANGE = 10.0


class Gate:
    """Nearest-neighbour gating on the squared Mahalanobis distance (see the module docstring).

    Args:
        threshold: the squared Mahalanobis distance ``d^2`` beyond which a detection is not
            the tracked ball (a chi-square quantile, e.g. :data:`CHI2_2DOF_999`); None admits
            every detection.
        kick_speed: the largest velocity change [m/s] a kick or a bounce makes, for
            :meth:`reaches`.
    """

    __slots__ = ("threshold", "kick_speed", "limit")

    def __init__(self, threshold: float | None, kick_speed: float = MAX_SPEED_CHANGE) -> None:
        self.threshold = threshold
        self.kick_speed = kick_speed
        #: The largest squared Mahalanobis distance admitted: ``threshold``, or ``inf``
        #: without one (a hot path may compare ``d2 <= limit`` instead of calling
        #: :meth:`admits`).
        self.limit = math.inf if threshold is None else threshold

    @staticmethod
    def nearest(px: float, py: float, S: tuple[float, float, float],
                detections: Sequence[Sequence[float]]
                ) -> tuple[Sequence[float], float, tuple[float, float, float, float]]:
        """``(z, d^2, S^-1)``: of ``detections`` (at least one ``(x, y)`` [m]), the one nearest
        the predicted position ``(px, py)`` [m] in the metric of the innovation covariance
        ``S = (s00, s01, s11)`` [m^2] (symmetric 2 x 2), its squared Mahalanobis distance
        ``d^2 = y^T S^-1 y``, ``y = z - p`` (the first of equals; ``inf`` when no distance is
        finite), and ``S^-1`` row-major [1/m^2]."""
        s0, s1, s3 = S
        det = s0 * s3 - s1 * s1
        i0, i1, i3 = s3 / det, -s1 / det, s0 / det
        best, d2 = detections[0], math.inf
        for z in detections:
            y0, y1 = z[0] - px, z[1] - py
            d = y0 * (i0 * y0 + i1 * y1) + y1 * (i1 * y0 + i3 * y1)
            if d < d2:
                best, d2 = z, d
        return best, d2, (i0, i1, i1, i3)

    def admits(self, d2: float) -> bool:
        """Whether a detection at squared Mahalanobis distance ``d2`` is the tracked ball:
        ``d2 <= limit`` (``threshold``; always without one)."""
        return d2 <= self.limit

    def reaches(self, distance: float, dt: float, sigma: float) -> bool:
        """Whether a detection ``distance`` [m] from the predicted position is near enough to
        be the ball kicked or bounced where it is: a velocity change of at most
        ``kick_speed`` over the ``dt`` seconds since the track's latest frame (none for
        ``dt <= 0``), plus three standard deviations ``sigma`` [m] of noise,
        ``distance <= kick_speed max(dt, 0) + 3 sigma``."""
        return distance <= self.kick_speed * max(dt, 0.0) + 3.0 * sigma
