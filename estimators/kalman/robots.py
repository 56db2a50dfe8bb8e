"""Pose trackers for many robots: decoupled constant-velocity Kalman filters.

Each robot's state is ``(x, y, theta, vx, vy, omega)``. With the constant-velocity model of
:class:`~estimators.models.ConstantVelocityMotion` and the pose measurement of
:class:`~estimators.models.PoseMeasurement` (independent noise per axis), the three axes
decouple into independent two-state filters ``(p, v)`` with a scalar measurement of ``p``. The
heading axis wraps its residuals and estimates to ``[-pi, pi)``.

Per axis, predicting over ``T`` with white-noise acceleration density ``q``:

    ``p += v T``;  ``P00 += 2 T P01 + T^2 P11 + q T^3 / 3``;  ``P01 += T P11 + q T^2 / 2``;
    ``P11 += q T``

and updating with ``z`` of variance ``r``: ``y = z - p``, ``S = P00 + r``, ``K = (P00, P01) / S``,

    ``P00' = (1 - K0)^2 P00 + K0^2 r``;  ``P01' = (1 - K0)(P01 - K1 P00) + K0 K1 r``;
    ``P11' = P11 - 2 K1 P01 + K1^2 (P00 + r)``   (Joseph form).

These are a dozen multiply-adds per axis, so they run in plain Python floats: a camera frame
brings a handful of detections, sizes at which numpy's per-call overhead would cost more than
the arithmetic. ``tests/estimators/kalman/test_robots.py`` checks them against the 6-state
:class:`~estimators.kalman.KalmanFilter` to 1e-9.

Measurements carry their capture time; a robot is predicted to it before the update, so
delayed frames are handled. A detection older than the robot's latest update is dropped
(robots are slow next to the camera rate, so a replay is not worth its cost).

:class:`RobotTracker` follows the tracker protocol (:class:`~estimators.protocol.Tracker`) as a
multi-target tracker: ``update(t, z, index)`` fuses a batch of detections with their robots'
indices (checked), ``update_robot(t, z, i)`` one detection (unchecked, the per-detection fast
path), and ``estimate(t)`` answers for all ``n`` robots at once, an ``(n, 6)`` array that is
never None (robots never seen read as zeros; :attr:`~RobotTracker.seen` tells which).
"""

from __future__ import annotations

import math

import numpy as np

from ..checks import check_count
from ..exact import wrap_angles
from ..models.measurement import MIN_SIGMA_THETA, MIN_SIGMA_XY, PoseMeasurement
from ..protocol import check_order, check_time

__all__ = ["RobotTracker", "RobotTrackerBatch", "MAX_ROBOTS"]

#: The most robots one tracker follows (a whole league's worth).
MAX_ROBOTS = 10_000

_TWO_PI = 2.0 * math.pi


def _predict_update(axis: list, z: float, T: float, q: float, r: float, angle: bool) -> None:
    """One axis ``[p, v, P00, P01, P11]``: predict over ``T``, fuse ``z`` (in place)."""
    p, v, P00, P01, P11 = axis
    qT = q * T
    P00 += T * (2.0 * P01 + T * (P11 + qT / 3.0))
    P01 += T * (P11 + 0.5 * qT)
    P11 += qT
    p += v * T
    y = z - p
    if angle:
        y = math.remainder(y, _TWO_PI)
    S = P00 + r
    K0, K1 = P00 / S, P01 / S
    p += K0 * y
    axis[0] = math.remainder(p, _TWO_PI) if angle else p
    axis[1] = v + K1 * y
    c = 1.0 - K0
    axis[2] = c * c * P00 + K0 * K0 * r
    axis[3] = c * (P01 - K1 * P00) + K0 * K1 * r
    axis[4] = P11 - 2.0 * K1 * P01 + K1 * K1 * S


class RobotTracker:
    """Pose tracker for ``n`` robots.

    Args:
        n: number of robots (targets are indexed ``0 .. n-1``).
        q_xy: acceleration noise density on x and y [m^2/s^3].
        q_theta: angular acceleration noise density [rad^2/s^3].
        sigma_xy: position measurement noise [m].
        sigma_theta: heading measurement noise [rad].
        sigma_v0: initial velocity standard deviation [m/s and rad/s].
        measurement: the sensor's :class:`~estimators.models.PoseMeasurement`; its ``R``
            replaces ``sigma_xy`` and ``sigma_theta``.

    Attributes:
        seen: ``(n,)`` whether each robot has been detected.
        dropped: detections older than their robot's latest update.
    """

    def __init__(self, n: int, q_xy: float = 4.0, q_theta: float = 20.0,
                 sigma_xy: float = 0.005, sigma_theta: float = 0.02,
                 sigma_v0: float = 2.0, measurement: PoseMeasurement | None = None) -> None:
        check_count("n", n, 0, MAX_ROBOTS)
        for name, v in (("q_xy", q_xy), ("q_theta", q_theta), ("sigma_xy", sigma_xy),
                        ("sigma_theta", sigma_theta), ("sigma_v0", sigma_v0)):
            if not (math.isfinite(v) and v >= 0.0):
                raise ValueError(f"{name} must be finite and >= 0, got {v!r}")
        self.n = int(n)
        self.q = (float(q_xy), float(q_xy), float(q_theta))
        if measurement is not None:  # the sensor's own model: its R, not a copy of numbers
            self.r = tuple(float(v) for v in np.diag(measurement.R))
        else:
            self.r = (max(sigma_xy, MIN_SIGMA_XY) ** 2,) * 2 + (max(sigma_theta,
                                                                   MIN_SIGMA_THETA) ** 2,)
        self.var_v0 = float(sigma_v0) ** 2
        self.reset()

    def reset(self) -> None:
        """Forget all robots."""
        n = self.n
        # Per robot: 3 axes of (p, v, P00, P01, P11), and the time of the last update.
        self._axes: list[list[list[float]] | None] = [None] * n
        self._t = [-math.inf] * n
        self.dropped = 0

    @property
    def seen(self) -> np.ndarray:
        """``(n,)`` whether each robot has been detected."""
        return np.array([a is not None for a in self._axes], dtype=bool)

    def update(self, t, z, index) -> None:
        """Fuse pose detections ``z`` ``(k, 3)`` of robots ``index`` ``(k,)`` captured at
        times ``t`` (``(k,)`` or one time for all), in the given order (checked; see
        :meth:`update_robot` for one detection of validated data)."""
        try:
            index = np.asarray(index).reshape(-1)
        except (TypeError, ValueError):
            raise ValueError(f"index must be robot indices, got {index!r}") from None
        if index.dtype.kind not in "iu":
            if index.size or index.dtype.kind not in "fb":
                raise ValueError(f"index must be integer robot indices, got {index!r}")
            index = index.astype(np.int64)
        try:
            z = np.asarray(z, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"z must be (k, 3) poses, got {z!r}") from None
        k = len(index)
        if z.shape != (k, 3):
            raise ValueError(f"z must have shape ({k}, 3), got {z.shape}")
        try:
            t = np.broadcast_to(np.asarray(t, dtype=np.float64), (k,))
        except (TypeError, ValueError):
            raise ValueError(f"t must be a time in seconds or one per detection ({k},), got "
                             f"{t!r}") from None
        if not np.isfinite(z).all():
            raise ValueError("z must be finite (NaN measurements are refused)")
        latest = max(self._t, default=-math.inf)
        for ti in np.unique(t).tolist():
            check_order(check_time(ti), latest)
        if k and (index.min() < 0 or index.max() >= self.n):
            raise ValueError(f"index must be in 0..{self.n - 1}, got {index.tolist()}")
        for i, ti, zi in zip(index.tolist(), t.tolist(), z.tolist()):
            self.update_robot(ti, zi, i)

    def update_robot(self, t: float, z, i: int) -> None:
        """Fuse one pose detection ``z = (x, y, theta)`` of robot ``i`` captured at ``t``
        (unchecked: the fast path for callers with validated data, one call per detection
        without the array round trip of :meth:`update`)."""
        axes = self._axes[i]
        if axes is None:
            self._axes[i] = [[z[a], 0.0, self.r[a], 0.0, self.var_v0] for a in range(3)]
            self._t[i] = t
            return
        T = t - self._t[i]
        if T < 0.0:
            self.dropped += 1
            return
        self._t[i] = t
        for a in (0, 1, 2):
            _predict_update(axes[a], z[a], T, self.q[a], self.r[a], a == 2)

    def estimate(self, t: float) -> np.ndarray:
        """``(n, 6)`` rows ``x, y, theta, vx, vy, omega`` predicted to time ``t`` (robots never
        seen read as zeros; see :attr:`seen`)."""
        t = check_time(t)
        rows = []
        for axes, ti in zip(self._axes, self._t):
            if axes is None:
                rows.append((0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
                continue
            dt = t - ti if t > ti else 0.0
            (px, vx, *_), (py, vy, *_), (pt, vt, *_) = axes
            rows.append((px + vx * dt, py + vy * dt, math.remainder(pt + vt * dt, _TWO_PI),
                         vx, vy, vt))
        return np.array(rows).reshape(-1, 6)

    @property
    def p(self) -> np.ndarray:
        """``(n, 3)`` poses at each robot's latest update."""
        return np.array([[a[0] for a in axes] if axes else [0.0] * 3
                         for axes in self._axes]).reshape(-1, 3)

    @property
    def v(self) -> np.ndarray:
        """``(n, 3)`` velocities at each robot's latest update."""
        return np.array([[a[1] for a in axes] if axes else [0.0] * 3
                         for axes in self._axes]).reshape(-1, 3)

    def pose_sigma(self, i: int, t: float) -> tuple[float, float]:
        """Standard deviations of robot ``i``'s pose predicted to ``t``: position
        ``sqrt((var x + var y) / 2)`` [m] and heading [rad], each axis's ``P00`` predicted as
        in the module docstring; ``(inf, inf)`` for a robot never seen."""
        axes = self._axes[i]
        if axes is None:
            return math.inf, math.inf
        T = max(0.0, t - self._t[i])
        var = [P00 + T * (2.0 * P01 + T * (P11 + q * T / 3.0))
               for (_, _, P00, P01, P11), q in zip(axes, self.q)]
        return math.sqrt(0.5 * (var[0] + var[1])), math.sqrt(var[2])

    def covariance(self, i: int) -> np.ndarray:
        """The 6 x 6 covariance of robot ``i`` (order ``x, y, theta, vx, vy, omega``)."""
        P = np.zeros((6, 6))
        for ax, (_, _, P00, P01, P11) in enumerate(self._axes[i] or []):
            P[ax, ax] = P00
            P[ax, ax + 3] = P[ax + 3, ax] = P01
            P[ax + 3, ax + 3] = P11
        return P


class RobotTrackerBatch:
    """``m`` independent :class:`RobotTracker` of ``n`` robots each, as arrays: the pose
    filters of ``m`` environments updated in one array operation per batch of detections.

    The arithmetic is :class:`RobotTracker`'s, operation for operation (the heading's
    ``math.remainder`` by :func:`~estimators.exact.wrap_angles`), so that tracker ``k`` of the
    batch gives what a :class:`RobotTracker` fed the same detections gives, bit for bit
    (``tests/estimators/kalman/test_robots.py``).

    Args:
        m: trackers (environments).
        n: robots per tracker.
        q_xy: as :class:`RobotTracker`'s.
        q_theta: as :class:`RobotTracker`'s.
        sigma_xy: as :class:`RobotTracker`'s.
        sigma_theta: as :class:`RobotTracker`'s.
        sigma_v0: as :class:`RobotTracker`'s.
        measurement: as :class:`RobotTracker`'s.

    Attributes:
        seen: ``(m, n)`` whether each robot has been detected.
        dropped: ``(m,)`` detections older than their robot's latest update.
    """

    def __init__(self, m: int, n: int, q_xy: float = 4.0, q_theta: float = 20.0,
                 sigma_xy: float = 0.005, sigma_theta: float = 0.02, sigma_v0: float = 2.0,
                 measurement: PoseMeasurement | None = None) -> None:
        check_count("m", m, 1, 1 << 20)
        one = RobotTracker(n, q_xy, q_theta, sigma_xy, sigma_theta, sigma_v0, measurement)
        self.m, self.n = int(m), one.n
        self.q = np.array(one.q)
        self.r = np.array(one.r)
        self.var_v0 = one.var_v0
        self._state = np.zeros((self.m, self.n, 5, 3))  # p, v, P00, P01, P11 of x, y, theta
        self._t = np.full((self.m, self.n), -math.inf)
        self.seen = np.zeros((self.m, self.n), dtype=bool)
        self.dropped = np.zeros(self.m, dtype=np.int64)

    def reset(self, rows=None) -> None:
        """Forget every robot of trackers ``rows`` (all by default)."""
        rows = slice(None) if rows is None else np.asarray(rows, dtype=np.int64)
        self._state[rows] = 0.0
        self._t[rows] = -math.inf
        self.seen[rows] = False
        self.dropped[rows] = 0

    def update(self, k, i, t, z) -> None:
        """Fuse pose detections ``z`` ``(d, 3)`` of robots ``i`` ``(d,)`` of trackers ``k``
        ``(d,)``, captured at ``t`` ``(d,)`` [s]. The pairs ``(k, i)`` must be distinct (each
        is one :meth:`RobotTracker.update_robot` call; a robot's successive detections go in
        successive calls). Unchecked, like ``update_robot``."""
        k = np.asarray(k, dtype=np.int64)
        i = np.asarray(i, dtype=np.int64)
        t = np.asarray(t, dtype=np.float64)
        z = np.asarray(z, dtype=np.float64)
        if not len(k):
            return
        seen = self.seen[k, i]
        new = ~seen
        if new.any():
            kn, in_ = k[new], i[new]
            rows = np.zeros((len(kn), 5, 3))
            rows[:, 0] = z[new]
            rows[:, 2] = self.r
            rows[:, 4] = self.var_v0
            self._state[kn, in_] = rows
            self._t[kn, in_] = t[new]
            self.seen[kn, in_] = True
        if not seen.any():
            return
        k, i, t, z = k[seen], i[seen], t[seen], z[seen]
        T = t - self._t[k, i]
        late = T < 0.0
        if late.any():
            np.add.at(self.dropped, k[late], 1)
            keep = ~late
            k, i, t, z, T = k[keep], i[keep], t[keep], z[keep], T[keep]
        self._t[k, i] = t
        s = self._state[k, i]  # (d, 5, 3)
        p, v, P00, P01, P11 = s[:, 0], s[:, 1], s[:, 2], s[:, 3], s[:, 4]
        T = T[:, None]
        q, r = self.q, self.r
        # RobotTracker's _predict_update, axis by axis in columns.
        qT = q * T
        P00 = P00 + T * (2.0 * P01 + T * (P11 + qT / 3.0))
        P01 = P01 + T * (P11 + 0.5 * qT)
        P11 = P11 + qT
        p = p + v * T
        y = z - p
        y[:, 2] = wrap_angles(y[:, 2])
        S = P00 + r
        K0, K1 = P00 / S, P01 / S
        p = p + K0 * y
        p[:, 2] = wrap_angles(p[:, 2])
        c = 1.0 - K0
        out = np.empty_like(s)
        out[:, 0] = p
        out[:, 1] = v + K1 * y
        out[:, 2] = c * c * P00 + K0 * K0 * r
        out[:, 3] = c * (P01 - K1 * P00) + K0 * K1 * r
        out[:, 4] = P11 - 2.0 * K1 * P01 + K1 * K1 * S
        self._state[k, i] = out

    def estimate(self, t) -> np.ndarray:
        """``(m, n, 6)`` rows ``x, y, theta, vx, vy, omega`` of every tracker predicted to its
        time ``t`` (``(m,)`` [s], or one time for all); robots never seen read as zeros."""
        t = np.broadcast_to(np.asarray(t, dtype=np.float64), (self.m,))
        later = self.seen & (t[:, None] > self._t)
        dt = np.where(later, t[:, None] - np.where(later, self._t, 0.0), 0.0)[..., None]
        p, v = self._state[:, :, 0], self._state[:, :, 1]
        out = np.empty((self.m, self.n, 6))
        out[..., 0:3] = p + v * dt
        out[..., 2] = wrap_angles(out[..., 2])
        out[..., 3:6] = v
        out[~self.seen] = 0.0
        return out
