"""Pose trackers for many robots at once: a batched constant-velocity Kalman filter.

Each robot's state is ``(x, y, theta, vx, vy, omega)``. With the constant-velocity model of
:class:`~estimators.models.ConstantVelocityMotion` and the pose measurement of
:class:`~estimators.models.PoseMeasurement` (independent noise per axis), the three axes
decouple into independent two-state filters ``(p, v)`` with a scalar measurement of ``p``, so
every robot and every axis is updated together with a few element-wise array operations (the
equations below, Joseph form), rather than a 6 x 6 filter per robot. The heading axis wraps
its residuals and estimates to ``[-pi, pi)``.

Per axis, predicting over ``T`` with white-noise acceleration density ``q``:

    ``p += v T``;  ``P00 += 2 T P01 + T^2 P11 + q T^3 / 3``;  ``P01 += T P11 + q T^2 / 2``;
    ``P11 += q T``

and updating with ``z`` of variance ``r``: ``y = z - p``, ``S = P00 + r``, ``K = (P00, P01) / S``,

    ``P00' = (1 - K0)^2 P00 + K0^2 r``;  ``P01' = (1 - K0)(P01 - K1 P00) + K0 K1 r``;
    ``P11' = P11 - 2 K1 P01 + K1^2 (P00 + r)``.

Measurements carry their capture time; each robot is predicted to it before the update, so
delayed frames are handled. A frame older than a robot's latest update is dropped for that robot
(robots are many and slow next to the camera rate, so a replay is not worth its cost).
"""

from __future__ import annotations

import math

import numpy as np

from .models import wrap_angle

__all__ = ["RobotTracker"]


class RobotTracker:
    """Batched pose tracker for ``n`` robots.

    Args:
        n: number of robots (targets are indexed ``0 .. n-1``).
        q_xy: acceleration noise density on x and y [m^2/s^3].
        q_theta: angular acceleration noise density [rad^2/s^3].
        sigma_xy: position measurement noise [m].
        sigma_theta: heading measurement noise [rad].
        sigma_v0: initial velocity standard deviation [m/s and rad/s].
    """

    def __init__(self, n: int, q_xy: float = 4.0, q_theta: float = 20.0,
                 sigma_xy: float = 0.005, sigma_theta: float = 0.02,
                 sigma_v0: float = 2.0) -> None:
        if not isinstance(n, (int, np.integer)) or n < 0:
            raise ValueError(f"n must be a non-negative integer, got {n!r}")
        for name, v in (("q_xy", q_xy), ("q_theta", q_theta), ("sigma_xy", sigma_xy),
                        ("sigma_theta", sigma_theta), ("sigma_v0", sigma_v0)):
            if not (math.isfinite(v) and v >= 0.0):
                raise ValueError(f"{name} must be finite and >= 0, got {v!r}")
        self.n = int(n)
        self.q = np.array([q_xy, q_xy, q_theta])
        self.r = np.array([max(sigma_xy, 1e-4) ** 2] * 2 + [max(sigma_theta, 1e-4) ** 2])
        self.var_v0 = sigma_v0**2
        self.reset()

    def reset(self) -> None:
        """Forget all robots."""
        n = self.n
        self.p = np.zeros((n, 3))
        self.v = np.zeros((n, 3))
        self.P00 = np.zeros((n, 3))
        self.P01 = np.zeros((n, 3))
        self.P11 = np.zeros((n, 3))
        self.t = np.full(n, -np.inf)
        self.seen = np.zeros(n, dtype=bool)

    def update(self, index, t, z) -> None:
        """Fuse pose detections ``z`` ``(k, 3)`` of robots ``index`` ``(k,)`` captured at
        times ``t`` ``(k,)`` (or one time for all). Indices must be distinct within a call."""
        index = np.asarray(index, dtype=np.int64).reshape(-1)
        z = np.asarray(z, dtype=np.float64)
        k = len(index)
        if z.shape != (k, 3):
            raise ValueError(f"z must have shape ({k}, 3), got {z.shape}")
        t = np.broadcast_to(np.asarray(t, dtype=np.float64), (k,))
        if not (np.isfinite(z).all() and np.isfinite(t).all()):
            raise ValueError("z and t must be finite (NaN measurements are refused)")
        if k and (index.min() < 0 or index.max() >= self.n):
            raise ValueError(f"index must be in 0..{self.n - 1}, got {index.tolist()}")
        if len(np.unique(index)) != k:
            raise ValueError("index must not repeat within one update")
        new = ~self.seen[index]
        if new.any():
            i = index[new]
            self.p[i] = z[new]
            self.v[i] = 0.0
            self.P00[i] = self.r
            self.P01[i] = 0.0
            self.P11[i] = self.var_v0
            self.t[i] = t[new]
            self.seen[i] = True
        old = ~new & (t >= self.t[index])
        if not old.any():
            return
        i, zi = index[old], z[old]
        T = (t[old] - self.t[i])[:, None]
        q, r = self.q, self.r
        # Predict to the capture time.
        p = self.p[i] + self.v[i] * T
        P00 = self.P00[i] + 2.0 * T * self.P01[i] + T * T * self.P11[i] + q * T**3 / 3.0
        P01 = self.P01[i] + T * self.P11[i] + q * T * T / 2.0
        P11 = self.P11[i] + q * T
        # Update (Joseph form, per axis).
        y = zi - p
        y[:, 2] = wrap_angle(y[:, 2])
        S = P00 + r
        K0, K1 = P00 / S, P01 / S
        p = p + K0 * y
        p[:, 2] = wrap_angle(p[:, 2])
        self.p[i] = p
        self.v[i] = self.v[i] + K1 * y
        self.P00[i] = (1.0 - K0) ** 2 * P00 + K0 * K0 * r
        self.P01[i] = (1.0 - K0) * (P01 - K1 * P00) + K0 * K1 * r
        self.P11[i] = P11 - 2.0 * K1 * P01 + K1 * K1 * S
        self.t[i] = t[old]

    def estimate(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """Poses ``(n, 3)`` and velocities ``(n, 3)`` predicted to time ``t`` (robots never
        seen stay at zero; see :attr:`seen`)."""
        dt = np.where(self.seen, np.maximum(t - self.t, 0.0), 0.0)[:, None]
        pose = self.p + self.v * dt
        pose[:, 2] = wrap_angle(pose[:, 2])
        return pose, self.v.copy()

    def covariance(self, i: int) -> np.ndarray:
        """The 6 x 6 covariance of robot ``i`` (order ``x, y, theta, vx, vy, omega``)."""
        P = np.zeros((6, 6))
        for ax in range(3):
            P[ax, ax] = self.P00[i, ax]
            P[ax, ax + 3] = P[ax + 3, ax] = self.P01[i, ax]
            P[ax + 3, ax + 3] = self.P11[i, ax]
        return P
