"""One implementation of the ball trackers' account of their own uncertainty.

:class:`~estimators.protocol.TrackQuality` is what the environments' belief features read:
``covariance(t)``, ``last_fused`` and ``since_start``; the trackers also say whether a track
exists (``initialized``) and the time of their latest frame (``time``).
:class:`TrackQualityMixin` gives them all from the tracker's current track times
(:class:`TrackTimes`) and one hook, the covariance of a started track.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from typing import Any, NamedTuple

import numpy as np

from ..protocol import check_time

__all__ = ["TrackTimes", "TrackQualityMixin"]


class TrackTimes(NamedTuple):
    """The times of a track: what :class:`TrackQualityMixin` reads.

    Attributes:
        t: the time of the tracker's latest frame (or prediction) [s]; ``-inf`` before the
            first.
        fused_at: the capture time of the latest detection fused into the track, the one that
            started it included [s]; ``-inf`` before the first.
        since_start: detections fused since the track's latest (re)start, the starting one
            included; 0 before the first.
    """

    t: float = -math.inf
    fused_at: float = -math.inf
    since_start: int = 0


class TrackQualityMixin(ABC):
    """:class:`~estimators.protocol.TrackQuality` (with ``initialized`` and ``time``) from a
    tracker's current track.

    A subclass keeps ``_track``, any object with the fields of :class:`TrackTimes` (``t``,
    ``fused_at``, ``since_start``): its immutable track state when that has them (the
    Kalman trackers'), or a property that builds a :class:`TrackTimes`; and implements
    :meth:`_covariance`. A track exists once a detection has started it, so
    ``initialized`` is ``since_start > 0``.
    """

    __slots__ = ()
    _track: Any

    @property
    def initialized(self) -> bool:
        """Whether a detection has started the track."""
        return self._track.since_start > 0

    @property
    def time(self) -> float:
        """The time of the latest frame processed [s] (``-inf`` before the first)."""
        return self._track.t

    @property
    def last_fused(self) -> float:
        """Capture time of the latest detection fused into the track, the one that started
        it included (``-inf`` before the first) [s]."""
        return self._track.fused_at

    @property
    def since_start(self) -> int:
        """Detections fused since the track's latest (re)start, the starting one included (0
        before the first)."""
        return self._track.since_start

    def covariance(self, t: float) -> np.ndarray | None:
        """The ``4 x 4`` covariance of ``(x, y, vx, vy)`` [m, m/s] at time ``t`` [s] (None
        before the first detection)."""
        t = check_time(t)
        if self._track.since_start == 0:
            return None
        return self._covariance(t)

    @abstractmethod
    def _covariance(self, t: float) -> np.ndarray:
        """The covariance at ``t`` (a checked time) of a started track."""
