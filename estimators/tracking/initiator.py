"""The track initiator: a new track from gated-out detections that agree with each other.

A detection outside a tracker's gate is either spurious (a false detection, a second ball
at the edge of the field) or the ball somewhere the track did not expect (kicked hard, moved
by the referee, seen again after a long gap). One such detection never moves a track; when
the next gated-out detection agrees with it, the ball is elsewhere and the track restarts
from the two (:class:`TrackInitiator`). The velocity of the new track is their finite
difference, which is noisy when the two are close in time, combined with a prior on the
ball's speed (:func:`prior_gain`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from .gate import MAX_SPEED_CHANGE

__all__ = ["TrackInitiator", "Candidates", "prior_gain"]

#: Gated-out detections that may start a track, oldest first: ``((t, (x, y)), ...)`` [s, m].
#: Immutable, so that a track state that holds them needs no copy for a replay.
Candidates = tuple[tuple[float, Sequence[float]], ...]


def prior_gain(prior_var: float, var_fd: float) -> float:
    """The gain ``g = s0^2 / (s0^2 + var_fd)`` that combines a finite-difference velocity of
    variance ``var_fd`` [m^2/s^2] per axis with the prior ``v ~ N(0, s0^2)``
    (``prior_var = s0^2``): the posterior is ``v = g v_fd`` with variance ``g var_fd``, so
    detections a moment apart (``var_fd`` unbounded) give a velocity near zero rather than an
    explosion."""
    return prior_var / (prior_var + var_fd)


class TrackInitiator:
    """Restart a track from ``count`` gated-out detections that agree (see the module
    docstring).

    A gated-out detection ``z`` at ``t`` is offered to the candidates (:meth:`offer`): it
    agrees with the latest candidate ``(t0, z0)`` if a ball at most ``max_speed`` fast could
    connect them, ``|z - z0| <= max_speed (t - t0) + 5 sigma_xy`` (:meth:`agrees`), and is
    appended; otherwise the older candidates were spurious and are dropped, and ``z`` is the
    only one. A detection at or before the latest candidate's time that agrees with it (a
    second camera's view of the same instant) adds nothing. Once there are ``count``
    candidates (:meth:`ready`) the tracker starts a new track from the first and the latest.

    Args:
        sigma_xy: the detections' noise per axis [m].
        count: candidates that start a track (2: a detection and one that agrees).
        max_speed: the fastest the ball moves [m/s]; its third is the prior's standard
            deviation of the new track's velocity (:attr:`prior_var`).
    """

    __slots__ = ("sigma_xy", "count", "max_speed", "prior_var")

    def __init__(self, sigma_xy: float, count: int = 2,
                 max_speed: float = MAX_SPEED_CHANGE) -> None:
        self.sigma_xy = sigma_xy
        self.count = count
        self.max_speed = max_speed
        #: The prior variance of the new track's velocity per axis, ``(max_speed / 3)^2``
        #: [m^2/s^2].
        self.prior_var = (max_speed / 3.0) ** 2

    def agrees(self, t0: float, z0: Sequence[float], t: float, z: Sequence[float]) -> bool:
        """Whether detection ``z`` at ``t`` and ``z0`` at ``t0`` [s, m] can be one moving
        ball: ``|z - z0| <= max_speed max(t - t0, 0) + 5 sigma_xy``."""
        return (math.hypot(z[0] - z0[0], z[1] - z0[1])
                <= self.max_speed * max(t - t0, 0.0) + 5.0 * self.sigma_xy)

    def offer(self, candidates: Candidates, t: float, z: Sequence[float]) -> Candidates:
        """The candidates after the gated-out detection ``z`` at ``t`` (see the class
        docstring); ``candidates`` is not changed."""
        if candidates:
            t0, z0 = candidates[-1]
            if not self.agrees(t0, z0, t, z):
                candidates = ()
            elif t <= t0:  # a second camera's view of the same instant: no new information
                return candidates
        return (*candidates, (t, z))

    def ready(self, candidates: Candidates) -> bool:
        """Whether ``candidates`` start a new track."""
        return len(candidates) >= self.count
