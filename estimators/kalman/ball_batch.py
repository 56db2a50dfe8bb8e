"""The EKF ball tracker of many environments as arrays (:class:`BallTrackerBatch`)."""

from __future__ import annotations

import numpy as np

from ..models.measurement import PositionMeasurement
from .ball import BallFilterConfig, BallTracker
from .ball_kernels import FUSED, MANEUVERS, REJECTED, RESETS, ball_estimates, ball_frames

__all__ = ["BallTrackerBatch"]

class BallTrackerBatch:
    """``m`` independent :class:`BallTracker` with one configuration, as arrays: the ball
    filters of ``m`` environments updated by one kernel call per batch of frames.

    Each tracker is a row of the compiled kernels of :mod:`~estimators.kalman.ball_kernels`
    that :class:`BallTracker` runs as a batch of one, so tracker ``k`` gives what a
    :class:`BallTracker` fed the same frames gives, bit for bit
    (``tests/estimators/kalman/test_ball.py``).

    Frames must come in capture-time order per tracker (``update`` raises ``ValueError``
    otherwise): the single tracker's replay of out-of-order frames is not batched, so a sensor
    whose latency jitters needs :class:`BallTracker`.

    Args:
        m: trackers (environments).
        config: as :class:`BallTracker`'s.
        measurement: as :class:`BallTracker`'s.

    Attributes:
        fused, rejected, resets, maneuvers: ``(m,)`` counters, as :class:`BallTracker`'s.
    """

    def __init__(self, m: int, config: BallFilterConfig | None = None,
                 measurement: PositionMeasurement | None = None) -> None:
        if not isinstance(m, (int, np.integer)) or m < 1:
            raise ValueError(f"m must be a positive integer, got {m!r}")
        one = BallTracker(config, measurement)
        self.config, self.motion, self.r = one.config, one.motion, one.r
        self._p = one.parameters
        self.m = m = int(m)
        self._tracks = np.empty((m, one.width))  # the kernels' track rows
        self._counts = np.zeros((m, 4), dtype=np.int64)
        self.fused, self.rejected, self.resets, self.maneuvers = (
            self._counts[:, FUSED], self._counts[:, REJECTED], self._counts[:, RESETS],
            self._counts[:, MANEUVERS])
        self._empty = one.empty_track().row
        self.reset()

    def reset(self, rows=None) -> None:
        """Forget trackers ``rows`` (all by default)."""
        rows = slice(None) if rows is None else np.asarray(rows, dtype=np.int64)
        self._tracks[rows] = self._empty
        self._counts[rows] = 0

    @property
    def _x(self) -> np.ndarray:
        """``(m, 4)`` states ``(x, y, vx, vy)`` at each tracker's latest frame (a view)."""
        return self._tracks[:, 1:5]

    @property
    def _P(self) -> np.ndarray:
        """``(m, 12)`` covariance blocks ``P11, P12, P22`` row-major (a view)."""
        return self._tracks[:, 5:17]

    @property
    def initialized(self) -> np.ndarray:
        """``(m,)`` whether a detection has started each tracker's track."""
        return self._tracks[:, 19] > 0.0

    @property
    def last_fused(self) -> np.ndarray:
        """``(m,)`` capture times of the latest detections fused [s] (``-inf`` before)."""
        return self._tracks[:, 18].copy()

    @property
    def since_start(self) -> np.ndarray:
        """``(m,)`` detections fused since each track's latest (re)start."""
        return self._tracks[:, 19].astype(np.int64)

    # ------------------------------------------------------------------------------------

    def update(self, rows, t, detections, detected, obstacles=None, obstacle_seen=None
               ) -> None:
        """Process one frame of each tracker in ``rows`` ``(d,)`` (distinct), captured at
        ``t`` ``(d,)`` [s]: ball detections ``detections`` ``(d, k, 2)`` [m] of which
        ``detected`` ``(d, k)`` are real (in their frame's order), and the robots seen in the
        frame ``obstacles`` ``(d, j, 2+)`` of which ``obstacle_seen`` ``(d, j)`` are real.
        Unchecked values (the batch's fast path), but times before a tracker's latest frame
        raise ``ValueError``. Each row is one
        :func:`~estimators.kalman.ball_kernels.ball_frame`, :meth:`BallTracker.process`'s
        kernel."""
        rows = np.ascontiguousarray(rows, dtype=np.int64).reshape(-1)
        d = len(rows)
        if not d:
            return
        t = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
        z = np.ascontiguousarray(detections, dtype=np.float64).reshape(d, -1, 2)
        has = np.ascontiguousarray(detected, dtype=bool).reshape(d, -1)
        if obstacles is None:
            obstacles, obstacle_seen = np.zeros((d, 0, 2)), np.zeros((d, 0), dtype=bool)
        obstacles = np.ascontiguousarray(obstacles, dtype=np.float64)
        obstacle_seen = np.ascontiguousarray(obstacle_seen, dtype=bool)
        if (t < self._tracks[rows, 0]).any():
            raise ValueError("frames must come in capture-time order per tracker "
                             "(BallTracker replays late frames; BallTrackerBatch does not)")
        ball_frames(self._tracks, self._counts, rows, t, z, has, obstacles, obstacle_seen,
                    self._p)

    def estimate(self, t) -> tuple[np.ndarray, np.ndarray]:
        """``(x, known)``: ``(m, 4)`` states ``(x, y, vx, vy)`` of every tracker predicted to
        its time ``t`` (``(m,)`` [s], or one time for all; zeros where ``known`` is False,
        before a tracker's first frame)."""
        t = np.ascontiguousarray(np.broadcast_to(np.asarray(t, dtype=np.float64), (self.m,)))
        out = np.empty((self.m, 4))
        ball_estimates(self._tracks, t, out, self._p)
        return out, self.initialized

