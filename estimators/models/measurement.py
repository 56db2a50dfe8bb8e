"""Measurement models shared by the sensors (to simulate) and the filters (to weigh).

A measurement model gives ``expected(x)``, ``jacobian(x)``, ``R``, ``residual(z, z_hat)``,
``log_likelihood(z, x)`` and ``simulate(truth, rng)``: the same object that a filter uses to
weigh a measurement is the one a sensor uses to produce it. Units: metres, radians.
"""

from __future__ import annotations

import math

import numpy as np

from .motion import wrap_angle

__all__ = ["PositionMeasurement", "PoseMeasurement", "MIN_SIGMA_XY", "MIN_SIGMA_THETA"]

#: Smallest measurement noise a filter assumes [m, rad], so that a noiseless sensor still
#: gives a well-conditioned update.
MIN_SIGMA_XY = 1e-3
MIN_SIGMA_THETA = 1e-3


class PositionMeasurement:
    """A position ``z = (x, y) + v``, ``v ~ N(0, sigma^2 I)``, of a state whose first two
    components are ``x, y`` (the overhead camera's ball detection)."""

    dim = 2

    def __init__(self, sigma: float, state_dim: int = 4) -> None:
        if not (math.isfinite(sigma) and sigma >= 0.0):
            raise ValueError(f"sigma must be finite and >= 0 m, got {sigma!r}")
        self.sigma = float(sigma)
        self.state_dim = state_dim
        self.H = np.zeros((2, state_dim))
        self.H[0, 0] = self.H[1, 1] = 1.0
        # A zero-noise sensor still needs a positive R for a filter: at least 1 mm.
        s2 = max(self.sigma, MIN_SIGMA_XY) ** 2
        self.R = s2 * np.eye(2)

    def expected(self, x: np.ndarray) -> np.ndarray:
        return x[:2]

    def jacobian(self, x: np.ndarray) -> np.ndarray:
        return self.H

    def residual(self, z: np.ndarray, z_hat: np.ndarray) -> np.ndarray:
        return z - z_hat

    def simulate(self, truth: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Noisy measurements of true positions ``(..., 2)``."""
        truth = np.asarray(truth, dtype=np.float64)
        return truth + self.sigma * rng.standard_normal(truth.shape)

    def perturb(self, x: float, y: float, n0: float, n1: float) -> tuple[float, float]:
        """One measurement of ``(x, y)`` from standard normal draws ``n0, n1`` (for sensors
        that draw their random numbers in bulk)."""
        return x + self.sigma * n0, y + self.sigma * n1

    def log_likelihood(self, z: np.ndarray, x: np.ndarray) -> float:
        y = z - x[:2]
        s2 = self.R[0, 0]
        return float(-0.5 * (y @ y) / s2 - math.log(2.0 * math.pi * s2))


class PoseMeasurement:
    """A pose ``z = (x, y, theta) + v`` with independent noise ``sigma_xy`` on the position and
    ``sigma_theta`` on the heading; residuals and samples wrap the heading to ``[-pi, pi)``
    (the overhead camera's robot detection)."""

    dim = 3

    def __init__(self, sigma_xy: float, sigma_theta: float, state_dim: int = 6) -> None:
        for name, v in (("sigma_xy", sigma_xy), ("sigma_theta", sigma_theta)):
            if not (math.isfinite(v) and v >= 0.0):
                raise ValueError(f"{name} must be finite and >= 0, got {v!r}")
        self.sigma_xy, self.sigma_theta = float(sigma_xy), float(sigma_theta)
        self.H = np.zeros((3, state_dim))
        self.H[0, 0] = self.H[1, 1] = self.H[2, 2] = 1.0
        self.R = np.diag([max(self.sigma_xy, MIN_SIGMA_XY) ** 2] * 2
                         + [max(self.sigma_theta, MIN_SIGMA_THETA) ** 2])

    def expected(self, x: np.ndarray) -> np.ndarray:
        return x[:3]

    def jacobian(self, x: np.ndarray) -> np.ndarray:
        return self.H

    def residual(self, z: np.ndarray, z_hat: np.ndarray) -> np.ndarray:
        y = z - z_hat
        y[..., 2] = wrap_angle(y[..., 2])
        return y

    def simulate(self, truth: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Noisy measurements of true poses ``(..., 3)``."""
        truth = np.asarray(truth, dtype=np.float64)
        noise = rng.standard_normal(truth.shape)
        z = truth + noise * np.array([self.sigma_xy, self.sigma_xy, self.sigma_theta])
        z[..., 2] = wrap_angle(z[..., 2])
        return z

    def perturb(self, x: float, y: float, theta: float, n0: float, n1: float, n2: float
                ) -> tuple[float, float, float]:
        """One measurement of pose ``(x, y, theta)`` from standard normal draws (for sensors
        that draw their random numbers in bulk); the heading is wrapped."""
        s, st = self.sigma_xy, self.sigma_theta
        return x + s * n0, y + s * n1, math.remainder(theta + st * n2, 2.0 * math.pi)

    def log_likelihood(self, z: np.ndarray, x: np.ndarray) -> float:
        y = self.residual(np.asarray(z, dtype=np.float64), x[:3])
        r = np.diag(self.R)
        return float(-0.5 * np.sum(y * y / r) - 0.5 * np.sum(np.log(2.0 * math.pi * r)))
