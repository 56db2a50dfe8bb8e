"""Kalman filter core: one set of equations for the linear filter and the EKF.

The state is Gaussian, ``x ~ N(x, P)``. A prediction maps it through the transition
``x' = f(x)`` with Jacobian ``F`` (``f(x) = F x`` for the linear filter) and adds process noise
``Q``; an update fuses a measurement ``z = h(x) + v``, ``v ~ N(0, R)``, with measurement
Jacobian ``H``. The extended filter is the same filter with ``f(x)``, ``h(x)`` and the Jacobians
supplied by a model (:mod:`estimators.models`), so there is one copy of the maths:

=====================  ===========================================================
predict                ``x = f(x)``; ``P = F P F^T + Q``
innovation             ``y = r(z, h(x))`` (``r`` is ``z - h(x)`` unless the model wraps
                       angles); ``S = H P H^T + R``
gate                   ``d^2 = y^T S^-1 y`` (squared Mahalanobis distance); reject if
                       ``d^2 > gate``
gain                   ``K = P H^T S^-1``
update                 ``x = x + K y``; ``P = (I - K H) P (I - K H)^T + K R K^T`` (Joseph
                       form: symmetric and positive definite whatever the rounding)
=====================  ===========================================================

The innovation ``y``, its covariance ``S`` and ``d^2`` of the last update are kept for
diagnostics and gating, as in FilterPy. ``update(None)`` records a missed detection and leaves
the state alone.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["KalmanFilter", "check_vector", "check_matrix"]


def _floats(name: str, value) -> np.ndarray:
    try:
        return np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of numbers, got {value!r}") from None


def check_vector(name: str, value, n: int) -> np.ndarray:
    """``value`` as a finite float array of shape ``(n,)``; ``ValueError`` naming ``name``
    otherwise."""
    arr = _floats(name, value)
    if arr.shape != (n,):
        raise ValueError(f"{name} must have shape ({n},), got {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} must be finite, got {arr}")
    return arr


def check_matrix(name: str, value, n: int, m: int | None = None) -> np.ndarray:
    """``value`` as a finite float array of shape ``(n, m)`` (``m = n`` by default)."""
    m = n if m is None else m
    arr = _floats(name, value)
    if arr.shape != (n, m):
        raise ValueError(f"{name} must have shape ({n}, {m}), got {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} must be finite")
    return arr


def _check_covariance(name: str, value, n: int) -> np.ndarray:
    """``value`` as a finite symmetric positive semi-definite ``(n, n)`` array (a noise
    covariance); ``ValueError`` naming ``name`` otherwise."""
    arr = check_matrix(name, value, n)
    scale = max(1.0, float(np.abs(arr).max()))
    if not np.allclose(arr, arr.T, rtol=1e-9, atol=1e-12 * scale):
        raise ValueError(f"{name} must be symmetric")
    if np.linalg.eigvalsh(0.5 * (arr + arr.T)).min() < -1e-9 * scale:
        raise ValueError(f"{name} must be positive semi-definite (a covariance: no negative "
                         "variances)")
    return arr


class KalmanFilter:
    """A Kalman filter (linear, or extended when ``f(x)`` / ``h(x)`` are supplied).

    Args:
        x: initial state mean, shape ``(n,)``.
        P: initial covariance, ``(n, n)``, symmetric positive definite.

    Attributes:
        x, P: the state mean and covariance.
        y, S, d2: innovation, its covariance and squared Mahalanobis distance of the last
            update (None before the first).
        missed: number of ``update(None)`` calls (missed detections) since the last accepted
            measurement.
        rejected: number of measurements rejected by the gate since the last accepted one.
    """

    def __init__(self, x: ArrayLike, P: ArrayLike) -> None:
        x = np.asarray(x, dtype=np.float64)
        if x.ndim != 1:
            raise ValueError(f"x must be a vector, got shape {x.shape}")
        self.dim = x.shape[0]
        self.x = check_vector("x", x, self.dim).copy()
        self.P = check_matrix("P", P, self.dim).copy()
        if not np.allclose(self.P, self.P.T) or np.linalg.eigvalsh(self.P).min() <= 0:
            raise ValueError("P must be symmetric positive definite")
        self._eye = np.eye(self.dim)
        self.y: np.ndarray | None = None
        self.S: np.ndarray | None = None
        self.d2: float | None = None
        self.missed = 0
        self.rejected = 0

    def predict(self, F: np.ndarray, Q: np.ndarray, x_pred: np.ndarray | None = None) -> None:
        """Time update: ``x = F x`` (or ``x_pred = f(x)`` for the EKF), ``P = F P F^T + Q``.
        ``F`` ``(n, n)`` and ``Q`` ``(n, n)`` must be finite, ``Q`` symmetric positive
        semi-definite, ``x_pred`` a finite ``(n,)``; otherwise ``ValueError`` naming the
        argument, with the filter unchanged."""
        n = self.dim
        F, Q = check_matrix("F", F, n), _check_covariance("Q", Q, n)
        x_pred = None if x_pred is None else check_vector("x_pred", x_pred, n)
        saved = self._saved()
        self.predict_unchecked(F, Q, x_pred)
        self._finite_or_restore(saved, "F, Q and x_pred")

    def predict_unchecked(self, F: np.ndarray, Q: np.ndarray,
                          x_pred: np.ndarray | None = None) -> None:
        """:meth:`predict` without checking ``F``, ``Q`` and ``x_pred``: for this package's
        trackers, whose matrices come from their own validated settings (the checks cost
        eight times the prediction itself)."""
        self.x = F @ self.x if x_pred is None else np.asarray(x_pred, dtype=np.float64)
        P = F @ self.P @ F.T + Q
        self.P = 0.5 * (P + P.T)

    def innovation(self, z: np.ndarray, H: np.ndarray, R: np.ndarray,
                   z_pred: np.ndarray | None = None,
                   residual: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None
                   ) -> tuple[np.ndarray, np.ndarray, float]:
        """``(y, S, d2)`` of measurement ``z`` without changing the filter."""
        return self._innovation(check_vector("z", z, np.shape(H)[0]), H, R, z_pred, residual)

    def _innovation(self, z: np.ndarray, H: np.ndarray, R: np.ndarray,
                    z_pred: np.ndarray | None = None,
                    residual: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None
                    ) -> tuple[np.ndarray, np.ndarray, float]:
        z_hat = H @ self.x if z_pred is None else z_pred
        y = z - z_hat if residual is None else residual(z, z_hat)
        S = H @ self.P @ H.T + R
        d2 = float(y @ np.linalg.solve(S, y))
        return y, S, d2

    def update(self, z: np.ndarray | None, H: np.ndarray, R: np.ndarray,
               z_pred: np.ndarray | None = None,
               residual: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
               gate: float | None = None) -> bool:
        """Measurement update; returns whether the measurement was fused.

        Args:
            z: the measurement ``(m,)``, or None for a missed detection.
            H: measurement Jacobian ``(m, n)``.
            R: measurement noise covariance ``(m, m)``, symmetric positive semi-definite
                (``R = 0``, an exact measurement, is allowed while ``S = H P H^T + R`` is
                positive definite; a singular ``S`` is refused naming ``R``).
            z_pred: ``h(x)`` for a nonlinear measurement (default ``H x``).
            residual: ``r(z, z_pred)`` replacing the subtraction (e.g. to wrap angles).
            gate: reject the measurement if ``d^2`` exceeds this (chi-square quantile).

        Matrices and vectors may be any array-likes of the right shape (lists included).
        Non-finite or mis-shaped arguments, and finite ones whose update overflows float64
        (a measurement of 1e308), raise ``ValueError`` naming them, with the filter
        unchanged.
        """
        H = _floats("H", H)
        if H.ndim != 2 or H.shape[1] != self.dim:
            raise ValueError(f"H must have shape (m, {self.dim}), got {H.shape}")
        m = H.shape[0]
        H = check_matrix("H", H, m, self.dim)
        R = _check_covariance("R", R, m)
        if gate is not None and not (isinstance(gate, (int, float, np.floating, np.integer))
                                     and gate >= 0 and np.isfinite(gate)):
            raise ValueError(f"gate must be None or a finite number >= 0, got {gate!r}")
        if z_pred is not None:
            z_pred = check_vector("z_pred", z_pred, m)
        saved = self._saved()
        try:
            fused = self.update_unchecked(z, H, R, z_pred, residual, gate)
        except np.linalg.LinAlgError:
            self._restore(saved)
            raise ValueError("R: the innovation covariance S = H P H^T + R is singular; R "
                             "(with H and P) must make it positive definite, e.g. R > 0 "
                             "where P is singular") from None
        self._finite_or_restore(saved, "z, H and R")
        return fused

    def _saved(self) -> tuple:
        return self.x, self.P, self.y, self.S, self.d2, self.missed, self.rejected

    def _restore(self, saved: tuple) -> None:
        self.x, self.P, self.y, self.S, self.d2, self.missed, self.rejected = saved

    def _finite_or_restore(self, saved: tuple, names: str) -> None:
        """Undo the step (the filter as ``saved``) and raise ``ValueError`` naming ``names``
        if it left a non-finite state, covariance or distance: inputs each finite whose
        products overflow float64 (e.g. a measurement of 1e308)."""
        if np.isfinite(self.x).all() and np.isfinite(self.P).all() and (
                self.d2 is None or math.isfinite(self.d2)):
            return
        self._restore(saved)
        raise ValueError(f"{names} must be small enough that the filter stays finite: this "
                         "step overflows float64 (the filter is left as it was)")

    def update_unchecked(self, z: np.ndarray | None, H: np.ndarray, R: np.ndarray,
                         z_pred: np.ndarray | None = None,
                         residual: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
                         gate: float | None = None) -> bool:
        """:meth:`update` checking only ``z``: for this package's trackers, whose ``H`` and
        ``R`` come from their own validated settings."""
        if z is None:
            self.missed += 1
            return False
        z = check_vector("z", z, H.shape[0])
        y, S, d2 = self._innovation(z, H, R, z_pred, residual)
        self.y, self.S, self.d2 = y, S, d2
        if gate is not None and d2 > gate:
            self.rejected += 1
            return False
        PHt = self.P @ H.T
        K = np.linalg.solve(S, PHt.T).T  # K = P H^T S^-1 (S is symmetric)
        self.x = self.x + K @ y
        I_KH = self._eye - K @ H
        P = I_KH @ self.P @ I_KH.T + K @ R @ K.T
        self.P = 0.5 * (P + P.T)
        self.missed = 0
        self.rejected = 0
        return True

    def copy(self) -> KalmanFilter:
        """An independent copy (state, covariance and diagnostics)."""
        other = object.__new__(type(self))
        other.__dict__.update(self.__dict__)
        other.x = self.x.copy()
        other.P = self.P.copy()
        return other

    # The former private spellings of the unchecked steps, for callers not yet moved to them.
    _predict = predict_unchecked
    _update = update_unchecked
