"""Motion models shared by the filters: the ball on carpet and constant velocity.

A motion model gives ``transition(x, dt) -> (f(x), F, Q)``: the propagated mean, the Jacobian
used for the covariance and the process noise (the measurement models that go with them are in
:mod:`estimators.models.measurement`). Units: metres, seconds, radians.
"""

from __future__ import annotations

import math

import numpy as np

from ..checks import check_positive
from ..compiled import kernel
from ..exact import hypot_exact

__all__ = [
    "FrictionBallMotion",
    "friction_step",
    "rk4_friction",
    "ConstantVelocityMotion",
    "wrap_angle",
    "PAPER_CYCLE",
]

#: The decision cycle of Zhao, Wang and Li (2012) [s]. The paper's velocity noise
#: ``sigma_v`` is per cycle; for other step lengths its variance scales with
#: ``dt / PAPER_CYCLE`` (a velocity random walk), so that the filter's behaviour does not
#: depend on how often it is predicted.
PAPER_CYCLE = 0.04


def wrap_angle(a):
    """Angles wrapped to ``[-pi, pi)`` (scalars or arrays)."""
    return (np.asarray(a) + math.pi) % (2.0 * math.pi) - math.pi


class FrictionBallMotion:
    """Ball state ``(x, y, vx, vy)`` decelerated by carpet friction (Zhao et al. 2012).

    Over a step ``T`` the paper's discrete model (eq. 14) is

        ``x' = M x + [a_x T^2 / 2, a_y T^2 / 2, a_x T, a_y T]``,
        ``a = -a_f u`` if ``|v| > a_f T``, else ``a = -v / T`` (the ball stops),

    with ``M`` the constant-velocity matrix of step ``T`` and ``u = v / |v|``. Two ways to
    propagate it:

    * ``"jacobian"`` (the paper's basic EKF): the mean by eq. 14, the covariance with its
      analytic Jacobian ``F = [[I, T I - a_f T^2 G / 2], [0, I - a_f T G]]``,
      ``G = (I - u u^T) / |v|`` (``[[I, T I / 2], [0, 0]]`` when the ball stops);
    * ``"rk"`` (the paper's "improved" EKF): the mean by a classical fourth-order Runge-Kutta
      step of ``dx/dt = v``, ``dv/dt = -a_f u`` (a combination of ``f`` evaluations in place of
      derivatives), stopped rather than reversed; the covariance with ``F = M`` (eq. 17,
      ``A_k = M``), so no Jacobian is derived.

    Process noise enters the velocities only (eq. 17-18): ``Q = W diag(s^2, s^2) W^T`` with
    ``W = [0 I]^T`` and ``s^2 = sigma_v^2 T / PAPER_CYCLE``. With ``deceleration = 0`` this is a
    constant-velocity model with the same noise.

    Args:
        deceleration: ``a_f`` [m/s^2] (Zhao et al. 2012: 0.23).
        propagation: ``"jacobian"`` or ``"rk"``.
    """

    dim = 4

    def __init__(self, deceleration: float, propagation: str = "jacobian") -> None:
        deceleration = check_positive("deceleration", deceleration, allow_zero=True,
                                      unit=" m/s^2")
        if not isinstance(propagation, str) or propagation not in ("jacobian", "rk"):
            raise ValueError(f"propagation must be one of ['jacobian', 'rk'], got "
                             f"{propagation!r}")
        self.deceleration = float(deceleration)
        self.propagation = propagation

    def step(self, px: float, py: float, vx: float, vy: float, T: float,
             deceleration: float | None = None
             ) -> tuple[tuple[float, float, float, float], tuple[float, float, float, float],
                        tuple[float, float, float, float]]:
        """The mean after ``T`` seconds and the Jacobian blocks, in plain floats.

        Returns ``(x', A, B)`` with ``F = [[I, A], [0, B]]``; ``A`` and ``B`` are 2 x 2
        row-major tuples (:func:`friction_step`, the compiled kernel the ball filters' own
        kernels call).
        """
        a = self.deceleration if deceleration is None else deceleration
        return friction_step(px, py, vx, vy, T, float(a), self.propagation == "rk")

    @staticmethod
    def velocity_noise(T: float, sigma_v: float) -> float:
        """Variance added to each velocity component over ``T`` seconds."""
        return sigma_v * sigma_v * T / PAPER_CYCLE

    def transition(self, x: np.ndarray, dt: float, sigma_v: float,
                   deceleration: float | None = None
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(f(x), F, Q)`` over ``dt`` seconds with velocity noise ``sigma_v`` [m/s per
        paper cycle]; ``deceleration`` overrides ``a_f`` for this step (two-phase model)."""
        mean, A, B = self.step(*(float(v) for v in x), dt, deceleration)
        F = np.eye(4)
        F[0:2, 2:4] = np.reshape(A, (2, 2))
        F[2:4, 2:4] = np.reshape(B, (2, 2))
        Q = np.zeros((4, 4))
        Q[2, 2] = Q[3, 3] = self.velocity_noise(dt, sigma_v)
        return np.array(mean), F, Q


@kernel
def friction_step(px: float, py: float, vx: float, vy: float, T: float, a: float, rk: bool
                  ) -> tuple[tuple[float, float, float, float], tuple[float, float, float, float],
                             tuple[float, float, float, float]]:
    """``(x', A, B)`` of :meth:`FrictionBallMotion.step`: the state ``(px, py, vx, vy)``
    [m, m/s] after ``T`` [s] at deceleration ``a`` [m/s^2] and the Jacobian blocks of
    ``F = [[I, A], [0, B]]`` (2 x 2 row-major), by eq. 14 with the analytic Jacobian, or with
    ``rk`` by :func:`rk4_friction` with ``F = M`` (``A = T I``, ``B = I``). Plain-float
    arithmetic in Python's order (``math.hypot`` by :func:`~estimators.exact.hypot_exact`)."""
    if rk:
        return rk4_friction(px, py, vx, vy, a, T), (T, 0.0, 0.0, T), (1.0, 0.0, 0.0, 1.0)
    speed = hypot_exact(vx, vy)
    if a == 0.0 or speed == 0.0:
        return (px + vx * T, py + vy * T, vx, vy), (T, 0.0, 0.0, T), (1.0, 0.0, 0.0, 1.0)
    if speed > a * T:
        ux, uy = vx / speed, vy / speed
        half = 0.5 * a * T * T
        mean = (px + vx * T - half * ux, py + vy * T - half * uy,
                vx - a * T * ux, vy - a * T * uy)
        # G = (I - u u^T) / |v|
        g00, g01, g11 = (1.0 - ux * ux) / speed, -ux * uy / speed, (1.0 - uy * uy) / speed
        A = (T - half * g00, -half * g01, -half * g01, T - half * g11)
        B = (1.0 - a * T * g00, -a * T * g01, -a * T * g01, 1.0 - a * T * g11)
        return mean, A, B
    # Stops within the step: a = -v / T (eq. 14).
    return ((px + 0.5 * vx * T, py + 0.5 * vy * T, 0.0, 0.0), (0.5 * T, 0.0, 0.0, 0.5 * T),
            (0.0, 0.0, 0.0, 0.0))


@kernel
def _friction_accel(a: float, wx: float, wy: float) -> tuple[float, float]:
    """The friction acceleration ``-a w / |w|`` of a ball at velocity ``w`` (zero at rest)."""
    s = hypot_exact(wx, wy)
    if s > 0.0:
        return (-a * wx / s, -a * wy / s)
    return (0.0, 0.0)


@kernel
def rk4_friction(px: float, py: float, vx: float, vy: float, a: float, T: float
                 ) -> tuple[float, float, float, float]:
    """One RK4 step of ``dp/dt = v``, ``dv/dt = -a v / |v|`` over ``T`` [s]; a ball that would
    stop within the step is stopped where it comes to rest instead of reversing."""
    speed = hypot_exact(vx, vy)
    if a > 0.0 and speed <= a * T:
        if speed == 0.0:
            return (px, py, 0.0, 0.0)
        d = speed / (2.0 * a)  # rest point along the direction of motion
        return (px + vx * d, py + vy * d, 0.0, 0.0)
    h = 0.5 * T
    a1 = _friction_accel(a, vx, vy)
    v2 = (vx + h * a1[0], vy + h * a1[1])
    a2 = _friction_accel(a, v2[0], v2[1])
    v3 = (vx + h * a2[0], vy + h * a2[1])
    a3 = _friction_accel(a, v3[0], v3[1])
    v4 = (vx + T * a3[0], vy + T * a3[1])
    a4 = _friction_accel(a, v4[0], v4[1])
    w = T / 6.0
    return (px + w * (vx + 2.0 * v2[0] + 2.0 * v3[0] + v4[0]),
            py + w * (vy + 2.0 * v2[1] + 2.0 * v3[1] + v4[1]),
            vx + w * (a1[0] + 2.0 * a2[0] + 2.0 * a3[0] + a4[0]),
            vy + w * (a1[1] + 2.0 * a2[1] + 2.0 * a3[1] + a4[1]))


class ConstantVelocityMotion:
    """State ``(p_1 .. p_d, v_1 .. v_d)`` moving at constant velocity, with continuous white
    noise acceleration of spectral density ``q`` [units^2/s^3] on every axis:
    ``F = [[I, T I], [0, I]]``, ``Q = q [[T^3/3 I, T^2/2 I], [T^2/2 I, T I]]``. Axes listed in
    ``angle_axes`` are wrapped to ``[-pi, pi)`` after each prediction."""

    def __init__(self, dims: int, q: float | np.ndarray, angle_axes: tuple[int, ...] = ()) -> None:
        self.dims = dims
        self.dim = 2 * dims
        self.q = np.broadcast_to(np.asarray(q, dtype=np.float64), (dims,)).copy()
        if not (np.isfinite(self.q).all() and (self.q >= 0).all()):
            raise ValueError(f"q must be finite and >= 0, got {q!r}")
        self.angle_axes = tuple(angle_axes)

    def transition(self, x: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        d, T = self.dims, dt
        F = np.eye(2 * d)
        F[:d, d:] = T * np.eye(d)
        x_new = F @ x
        for ax in self.angle_axes:
            x_new[ax] = wrap_angle(x_new[ax])
        qd = np.diag(self.q)
        Q = np.block([[qd * T**3 / 3.0, qd * T**2 / 2.0], [qd * T**2 / 2.0, qd * T]])
        return x_new, F, Q
