"""The tracker protocol: one verb pair for every time-stamped tracker.

A time-stamped tracker takes measurements with the time they were captured and answers for any
time asked, so a caller never has to know how the tracker keeps its state (a Kalman filter, a
particle set, a least-squares fit) or how it handles late measurements:

* ``update(t, z, ...)``: fuse the measurement ``z`` captured at time ``t`` [s]; the further
  arguments are the tracker's own (the robots seen in the same frame, the measurement noise, a
  robot index);
* ``estimate(t)``: the state predicted to time ``t`` [s] (the present, or the present plus the
  actuation latency), without changing the tracker; None before the first measurement;
* ``reset()``: forget everything (a new episode).

The classes that follow it are listed in the package docstring (:mod:`estimators`).

Ball trackers also say how sure they are (:class:`TrackQuality`, what the environments' belief
features read): ``covariance(t)`` of ``(x, y, vx, vy)`` predicted to ``t``, ``last_fused`` (the
time stamp of the latest measurement fused) and ``since_start`` (measurements fused since the
track last (re)started).
"""

from __future__ import annotations

import math
from typing import Any, Protocol, runtime_checkable

import numpy as np

__all__ = ["Tracker", "TrackQuality", "check_time", "check_order", "MAX_TIME", "MAX_REWIND"]

#: The largest time stamp a tracker takes, in absolute value [s]: 10^12 s covers clocks
#: counted from the episode's start and Unix time alike (and still resolves 0.1 ms), while the
#: motion models' squared time steps stay far from overflowing (a frame stamped 1e155 s turned
#: a track into NaN).
MAX_TIME = 1e12

#: How far a measurement may lag the tracker's latest one [s]. Late frames within a
#: tracker's own window are replayed or counted as late (network and camera latency: tens of
#: milliseconds); one older by more than this is no late frame but a clock that went back,
#: usually a new episode fed without ``reset()``, and is refused.
MAX_REWIND = 10.0


def check_time(t: Any, name: str = "t") -> float:
    """``t`` as a float time stamp [s]; ``ValueError`` naming ``name`` unless it is a finite
    number (not a string or a bool) within ``[-MAX_TIME, MAX_TIME]``."""
    if isinstance(t, (str, bytes, bool, np.bool_)):
        raise ValueError(f"{name} must be a time in seconds, a number, got {t!r}")
    try:
        value = float(t)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a time in seconds, a number, got {t!r}") from None
    if not (math.isfinite(value) and -MAX_TIME <= value <= MAX_TIME):
        raise ValueError(f"{name} must be a finite time in [-{MAX_TIME:g}, {MAX_TIME:g}] s, "
                         f"got {t!r}")
    return value


@runtime_checkable
class Tracker(Protocol):
    """A time-stamped tracker (see the module docstring). ``isinstance(x, Tracker)`` checks
    that ``x`` has the three methods, not their signatures."""

    def update(self, t: float, z: Any, /, *args: Any, **kwargs: Any) -> None:
        """Fuse the measurement ``z`` captured at time ``t`` [s]."""

    def estimate(self, t: float) -> np.ndarray | None:
        """The state predicted to time ``t`` [s]; None before the first measurement."""

    def reset(self) -> None:
        """Forget everything (a new episode)."""


@runtime_checkable
class TrackQuality(Protocol):
    """A ball tracker's account of its own uncertainty (see the module docstring)."""

    @property
    def last_fused(self) -> float:
        """Time stamp of the latest fused measurement [s] (``-inf`` before the first)."""

    @property
    def since_start(self) -> int:
        """Measurements fused since the track's latest (re)start (0 before the first)."""

    def covariance(self, t: float) -> np.ndarray | None:
        """``4 x 4`` covariance of ``(x, y, vx, vy)`` at ``t``; None before the first
        measurement."""


def check_order(t: float, latest: float, name: str = "t") -> None:
    """Raise ``ValueError`` when the time stamp ``t`` lies more than :data:`MAX_REWIND`
    before ``latest``, the tracker's latest measurement time (``-inf`` before the first)."""
    if t < latest - MAX_REWIND:
        raise ValueError(f"{name} = {t:g} s is {latest - t:g} s before the latest measurement "
                         f"({latest:g} s): measurements may arrive out of order by at most "
                         f"{MAX_REWIND:g} s; call reset() to start a new episode")
