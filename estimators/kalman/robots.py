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

These are a dozen multiply-adds per axis, written once as compiled ``numba`` kernels over
rows of poses (:func:`update_pose`, :func:`update_poses`, :func:`predict_poses`): a camera
frame brings a handful of detections per environment, sizes at which numpy's per-call overhead
would cost more than the arithmetic. :class:`RobotTracker` is one tracker of them and
:class:`RobotTrackerBatch` ``m``, so the two agree bit for bit.
``tests/estimators/kalman/test_robots.py`` checks them against the 6-state
:class:`~estimators.kalman.KalmanFilter` to 1e-9.

Measurements carry their capture time; a robot is predicted to it before the update, so
delayed frames are handled. A detection older than the robot's latest update is dropped
(robots are slow next to the camera rate, so a replay is not worth its cost).

:class:`RobotTracker` follows the tracker protocol (:class:`~estimators.protocol.Tracker`) as a
multi-target tracker: ``update(t, z, index)`` fuses a batch of detections with their robots'
indices (checked), ``update_robot(t, z, i)`` one detection and ``update_many(t, index, z)``
several (unchecked, the fast paths), and ``estimate(t)`` answers for all ``n`` robots at
once, an ``(n, 6)`` array that is never None (robots never seen read as zeros;
:attr:`~RobotTracker.seen` tells which).
"""

from __future__ import annotations

import math

import numpy as np

from ..checks import MAX_COORDINATE, MAX_SPEED, check_count, check_sigma
from ..compiled import kernel
from ..exact import wrap_angle
from ..models.measurement import MIN_SIGMA_THETA, MIN_SIGMA_XY, PoseMeasurement
from ..protocol import check_order, check_time
from .driven import CommandHistory

__all__ = ["RobotTracker", "RobotTrackerBatch", "MAX_ROBOTS", "update_pose", "update_poses",
           "predict_poses"]

#: The most robots one tracker follows (a whole league's worth).
MAX_ROBOTS = 10_000

_TWO_PI = 2.0 * math.pi


@kernel
def _axis(state: np.ndarray, a: int, z: float, T: float, q: float, r: float) -> None:
    """Axis ``a`` of one robot's ``state`` ``(5, 3)`` (rows ``p, v, P00, P01, P11``): predict
    over ``T`` [s], fuse ``z`` (in place); the heading (``a == 2``) wraps."""
    p, v, P00, P01, P11 = state[0, a], state[1, a], state[2, a], state[3, a], state[4, a]
    qT = q * T
    P00 += T * (2.0 * P01 + T * (P11 + qT / 3.0))
    P01 += T * (P11 + 0.5 * qT)
    P11 += qT
    p += v * T
    y = z - p
    if a == 2:
        y = wrap_angle(y)
    S = P00 + r
    K0, K1 = P00 / S, P01 / S
    p += K0 * y
    state[0, a] = wrap_angle(p) if a == 2 else p
    state[1, a] = v + K1 * y
    c = 1.0 - K0
    state[2, a] = c * c * P00 + K0 * K0 * r
    state[3, a] = c * (P01 - K1 * P00) + K0 * K1 * r
    state[4, a] = P11 - 2.0 * K1 * P01 + K1 * K1 * S


@kernel
def update_pose(state: np.ndarray, times: np.ndarray, seen: np.ndarray, k: int, i: int,
                t: float, z0: float, z1: float, z2: float, q: np.ndarray, r: np.ndarray,
                var_v0: float) -> bool:
    """Fuse the pose ``(z0, z1, z2)`` [m, m, rad] of robot ``i`` of tracker ``k`` captured at
    ``t`` [s] into ``state`` ``(m, n, 5, 3)``, ``times`` and ``seen`` ``(m, n)`` (in place):
    a first detection starts the robot at rest with variances ``r`` and ``var_v0``, a later
    one is predicted to and fused per axis (noise densities ``q``). Returns whether the
    detection was dropped (older than the robot's latest)."""
    z = (z0, z1, z2)
    if not seen[k, i]:
        for a in range(3):
            state[k, i, 0, a], state[k, i, 1, a] = z[a], 0.0
            state[k, i, 2, a], state[k, i, 3, a], state[k, i, 4, a] = r[a], 0.0, var_v0
        times[k, i] = t
        seen[k, i] = True
        return False
    T = t - times[k, i]
    if T < 0.0:
        return True
    times[k, i] = t
    for a in range(3):
        _axis(state[k, i], a, z[a], T, q[a], r[a])
    return False


@kernel
def update_poses(state: np.ndarray, times: np.ndarray, seen: np.ndarray, dropped: np.ndarray,
                 k: np.ndarray, i: np.ndarray, t: np.ndarray, z: np.ndarray, q: np.ndarray,
                 r: np.ndarray, var_v0: float) -> None:
    """:func:`update_pose` of each detection in order: trackers ``k``, robots ``i``, times
    ``t`` ``(d,)``, poses ``z`` ``(d, 3)``; ``dropped`` ``(m,)`` counts the dropped ones."""
    for j in range(k.shape[0]):
        if update_pose(state, times, seen, k[j], i[j], t[j], z[j, 0], z[j, 1], z[j, 2], q, r,
                       var_v0):
            dropped[k[j]] += 1


@kernel
def predict_poses(state: np.ndarray, times: np.ndarray, seen: np.ndarray, t: np.ndarray
                  ) -> np.ndarray:
    """``(m, n, 6)`` rows ``x, y, theta, vx, vy, omega`` of every robot predicted to its
    tracker's time ``t`` ``(m,)`` [s] at constant velocity (never backwards; robots never seen
    read as zeros)."""
    m, n = seen.shape
    out = np.zeros((m, n, 6))
    for k in range(m):
        for i in range(n):
            if not seen[k, i]:
                continue
            dt = t[k] - times[k, i] if t[k] > times[k, i] else 0.0
            for a in range(3):
                out[k, i, a] = state[k, i, 0, a] + state[k, i, 1, a] * dt
                out[k, i, 3 + a] = state[k, i, 1, a]
            out[k, i, 2] = wrap_angle(out[k, i, 2])
    return out


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
        big = MAX_COORDINATE
        q_xy = check_sigma("q_xy", q_xy, " [m^2/s^3]", big)
        q_theta = check_sigma("q_theta", q_theta, " [rad^2/s^3]", big)
        sigma_xy = check_sigma("sigma_xy", sigma_xy, " [m]", big)
        sigma_theta = check_sigma("sigma_theta", sigma_theta, " [rad]", big)
        sigma_v0 = check_sigma("sigma_v0", sigma_v0, " [m/s, rad/s]", MAX_SPEED)
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
        # Per robot: 3 axes (columns) of (p, v, P00, P01, P11), the time of the last update,
        # whether it was seen: one tracker of the kernels' (m, n, ...) arrays.
        self._q, self._r = np.array(self.q), np.array(self.r)
        self._state = np.zeros((1, n, 5, 3))
        self._times = np.full((1, n), -math.inf)
        self._seen = np.zeros((1, n), dtype=bool)
        self.dropped = 0

    @property
    def seen(self) -> np.ndarray:
        """``(n,)`` whether each robot has been detected."""
        return self._seen[0].copy()

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
        latest = float(self._times.max(initial=-math.inf))
        for ti in np.unique(t).tolist():
            check_order(check_time(ti), latest)
        if k and (index.min() < 0 or index.max() >= self.n):
            raise ValueError(f"index must be in 0..{self.n - 1}, got {index.tolist()}")
        self.update_many(t, index, z)

    def update_robot(self, t: float, z, i: int) -> None:
        """Fuse one pose detection ``z = (x, y, theta)`` of robot ``i`` captured at ``t``
        (the fast path, one call per detection without the array round trip of
        :meth:`update`: only that the numbers are finite and the robot exists is checked,
        ``ValueError`` otherwise, before any state changes)."""
        if not (0 <= i < self.n and math.isfinite(t) and math.isfinite(z[0])
                and math.isfinite(z[1]) and math.isfinite(z[2])):
            raise ValueError(f"update_robot needs a finite time and pose and a robot in "
                             f"0..{self.n - 1}, got t={t!r}, z={tuple(z)!r}, i={i!r}")
        if update_pose(self._state, self._times, self._seen, 0, i, t, z[0], z[1], z[2],
                       self._q, self._r, self.var_v0):
            self.dropped += 1

    def update_many(self, t, index, z) -> None:
        """Fuse pose detections ``z`` ``(d, 3)`` of robots ``index`` ``(d,)`` captured at
        times ``t`` ``(d,)`` [s], in order, in one kernel call: what :meth:`update_robot` of
        each in turn does, bit for bit (unchecked, like it: the fast path for a step's frames
        of validated data)."""
        index = np.asarray(index, dtype=np.int64).reshape(-1)
        d = len(index)
        if not d:
            return
        dropped = np.zeros(1, dtype=np.int64)
        update_poses(self._state, self._times, self._seen, dropped, np.zeros(d, np.int64),
                     index, np.ascontiguousarray(t, dtype=np.float64).reshape(-1),
                     np.ascontiguousarray(z, dtype=np.float64).reshape(-1, 3), self._q,
                     self._r, self.var_v0)
        self.dropped += int(dropped[0])

    def estimate(self, t: float) -> np.ndarray:
        """``(n, 6)`` rows ``x, y, theta, vx, vy, omega`` predicted to time ``t`` (robots never
        seen read as zeros; see :attr:`seen`)."""
        t = check_time(t)
        return predict_poses(self._state, self._times, self._seen, np.array([t]))[0]

    def estimate_driven(self, t: float, history: CommandHistory) -> np.ndarray:
        """:meth:`estimate` at ``t`` with the robots of ``history`` (a team's own) driven
        from their latest update through the commands sent to them
        (:func:`~estimators.kalman.driven.drive_poses`) instead of at constant velocity."""
        out = self.estimate(t)
        return history.drive(out, self._state[0], self._times[0], self._seen[0], t)

    @property
    def p(self) -> np.ndarray:
        """``(n, 3)`` poses at each robot's latest update."""
        return self._state[0, :, 0].copy()

    @property
    def v(self) -> np.ndarray:
        """``(n, 3)`` velocities at each robot's latest update."""
        return self._state[0, :, 1].copy()

    def pose_sigma(self, i: int, t: float) -> tuple[float, float]:
        """Standard deviations of robot ``i``'s pose predicted to ``t``: position
        ``sqrt((var x + var y) / 2)`` [m] and heading [rad], each axis's ``P00`` predicted as
        in the module docstring; ``(inf, inf)`` for a robot never seen."""
        self._check_index(i)
        if not self._seen[0, i]:
            return math.inf, math.inf
        T = max(0.0, t - float(self._times[0, i]))
        axes = self._state[0, i, 2:5].T.tolist()
        var = [P00 + T * (2.0 * P01 + T * (P11 + q * T / 3.0))
               for (P00, P01, P11), q in zip(axes, self.q)]
        return math.sqrt(0.5 * (var[0] + var[1])), math.sqrt(var[2])

    def _check_index(self, i: int) -> None:
        if isinstance(i, bool) or not isinstance(i, (int, np.integer)) or not 0 <= i < self.n:
            raise ValueError(f"robot index must be an integer in 0..{self.n - 1}, got {i!r}")

    def covariance(self, i: int) -> np.ndarray:
        """The 6 x 6 covariance of robot ``i`` (order ``x, y, theta, vx, vy, omega``)."""
        self._check_index(i)
        P = np.zeros((6, 6))
        if self._seen[0, i]:
            for ax, (P00, P01, P11) in enumerate(self._state[0, i, 2:5].T.tolist()):
                P[ax, ax] = P00
                P[ax, ax + 3] = P[ax + 3, ax] = P01
                P[ax + 3, ax + 3] = P11
        return P


class RobotTrackerBatch:
    """``m`` independent :class:`RobotTracker` of ``n`` robots each, as arrays: the pose
    filters of ``m`` environments updated in one array operation per batch of detections.

    The kernels are :class:`RobotTracker`'s (:func:`update_pose`, :func:`predict_poses`), so
    that tracker ``k`` of the batch gives what a :class:`RobotTracker` fed the same detections
    gives, bit for bit (``tests/estimators/kalman/test_robots.py``).

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
        ``(d,)``, captured at ``t`` ``(d,)`` [s], in order (each is one
        :meth:`RobotTracker.update_robot` call). Unchecked, like ``update_robot``."""
        k = np.ascontiguousarray(k, dtype=np.int64).reshape(-1)
        if not len(k):
            return
        update_poses(self._state, self._t, self.seen, self.dropped, k,
                     np.ascontiguousarray(i, dtype=np.int64).reshape(-1),
                     np.ascontiguousarray(t, dtype=np.float64).reshape(-1),
                     np.ascontiguousarray(z, dtype=np.float64).reshape(-1, 3),
                     self.q, self.r, self.var_v0)

    def estimate(self, t) -> np.ndarray:
        """``(m, n, 6)`` rows ``x, y, theta, vx, vy, omega`` of every tracker predicted to its
        time ``t`` (``(m,)`` [s], or one time for all); robots never seen read as zeros."""
        t = np.ascontiguousarray(np.broadcast_to(np.asarray(t, dtype=np.float64), (self.m,)))
        return predict_poses(self._state, self._t, self.seen, t)
