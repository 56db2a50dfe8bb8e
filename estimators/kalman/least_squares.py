"""The least-squares trajectory predictor of Zhao, Wang and Li's (2012) comparison."""

from __future__ import annotations

import bisect
import math

import numpy as np

from ..checks import MAX_COORDINATE, check_positive
from ..protocol import check_order, check_time
from ..tracking import MAX_SPEED_CHANGE, TrackQualityMixin, TrackTimes

__all__ = ["LeastSquaresBall"]


class LeastSquaresBall(TrackQualityMixin):
    """The least-squares trajectory predictor of Zhao et al.'s (2012) comparison.

    Fits ``p(t) = p0 + v (t - t_last)`` to the last ``window`` detections by least squares
    (separately in ``x`` and ``y``) and extrapolates to the requested time. Of several
    detections in one frame it keeps the one nearest to the extrapolation.

    Its :meth:`covariance` at ``t`` is that of ordinary least squares with independent noise
    ``sigma_xy`` per axis: per axis ``var p(t) = s^2 (1/n + (t - tm)^2 / S)``,
    ``var v = s^2 / S`` and ``cov(p, v) = s^2 (t - tm) / S`` with ``tm`` the mean and ``S``
    the sum of squared deviations of the ``n`` detection times. With one detection the
    velocity is unknown: its variance is that of a ball anywhere up to
    :data:`~estimators.tracking.MAX_SPEED_CHANGE`.
    """

    def __init__(self, window: int = 6, sigma_xy: float = 0.01) -> None:
        if not isinstance(window, int) or window < 2:
            raise ValueError(f"window must be an integer >= 2, got {window!r}")
        self.window = window
        #: The detections' noise [m] (per axis) that :meth:`covariance` assumes.
        self.sigma_xy = check_positive("sigma_xy", sigma_xy, unit=" [m]", high=MAX_COORDINATE)
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._t: list[float] = []
        self._z: list[np.ndarray] = []

    @property
    def _track(self) -> TrackTimes:
        """The fit's times: its latest detection's, which is also the latest fused, and the
        detections in it (at most ``window``; the predictor never restarts)."""
        t = self._t[-1] if self._t else -math.inf
        return TrackTimes(t, t, len(self._t))

    def _covariance(self, t: float) -> np.ndarray:
        """The covariance extrapolated to ``t`` (see the class docstring)."""
        s2 = self.sigma_xy**2
        n = len(self._t)
        ts = np.asarray(self._t)
        tm = float(ts.mean())
        S = float(np.sum((ts - tm) ** 2))
        if n < 2 or S <= 0.0:
            var_v = (MAX_SPEED_CHANGE / 3.0) ** 2
            var_p, cov_pv = s2 + var_v * max(0.0, t - tm) ** 2, var_v * max(0.0, t - tm)
        else:
            d = t - tm
            var_p, cov_pv, var_v = s2 * (1.0 / n + d * d / S), s2 * d / S, s2 / S
        P = np.zeros((4, 4))
        for a in (0, 1):
            P[a, a], P[a, a + 2] = var_p, cov_pv
            P[a + 2, a], P[a + 2, a + 2] = cov_pv, var_v
        return P

    def update(self, t: float, detections, obstacles=None) -> None:
        """Process one frame captured at ``t`` with ball detections ``(k, 2)`` (k may be 0);
        ``obstacles`` is accepted for the protocol's sake and not used."""
        t = check_time(t)
        check_order(t, self.time)
        dets = np.asarray(detections, dtype=np.float64).reshape(-1, 2) if len(
            detections) else np.zeros((0, 2))
        if not np.isfinite(dets).all():
            raise ValueError("detections must be finite (NaN measurements are refused)")
        if not len(dets):
            return
        z = dets[0]
        if len(dets) > 1 and self._t:
            guess = self.estimate(t)[:2]
            z = dets[np.argmin(np.hypot(*(dets - guess).T))]
        i = bisect.bisect_right(self._t, t)
        self._t.insert(i, t)
        self._z.insert(i, z.copy())
        del self._t[: -self.window], self._z[: -self.window]

    def estimate(self, t: float) -> np.ndarray | None:
        """State ``(x, y, vx, vy)`` extrapolated to time ``t`` (None before the first
        detection)."""
        t = check_time(t)
        if not self._t:
            return None
        if len(self._t) == 1:
            z = self._z[0]
            return np.array([z[0], z[1], 0.0, 0.0])
        ts = np.asarray(self._t) - self._t[-1]
        zs = np.asarray(self._z)
        A = np.column_stack([np.ones_like(ts), ts])
        coef, *_ = np.linalg.lstsq(A, zs, rcond=None)  # rows: p0, v
        p0, v = coef
        dt = t - self._t[-1]
        return np.array([p0[0] + v[0] * dt, p0[1] + v[1] * dt, v[0], v[1]])
