"""Kalman blocks: the filter arithmetic of the ball trackers in plain floats.

FilterPy exposes ``predict`` and ``update`` as functions beside its ``KalmanFilter`` class;
these are the same steps for the ball trackers' state ``x = (x, y, vx, vy)`` [m, m/s], a
position measurement ``z = H x + v``, ``H = [I 0]``, ``v ~ N(0, r I)``, and a motion whose
Jacobian is ``F = [[I, A], [0, B]]`` (:meth:`~estimators.models.FrictionBallMotion.step`
gives ``A`` and ``B``; constant velocity is ``A = T I``, ``B = I``).

**Plain floats.** A ball filter runs for every camera frame, often several times per
environment step, and a 4-state filter is a few dozen multiply-adds: numpy's per-call overhead
(about a microsecond per operation, some twenty operations per update) would cost ten times
the arithmetic. So the state is a 4-tuple (:data:`State`) and the covariance three 2 x 2
row-major blocks ``P = [[P11, P12], [P12^T, P22]]`` (:data:`Blocks`, each block a
:data:`Mat2`); with the ``F`` and ``H`` above the equations of
:class:`~estimators.kalman.KalmanFilter` reduce to the block forms written out below
(tests/estimators/kalman/test_ball.py checks them against that class to 1e-10):
:func:`predict_covariance`, :func:`innovation`, :func:`update` (Joseph form),
:func:`update_closed_form` (the standard form in closed form) and :func:`predict_jump` (the
constant-velocity prediction with a velocity jump within the step).

**Kernels.** Each block is written once, as a compiled ``numba`` kernel
(:func:`~estimators.compiled.kernel`): called from Python on float tuples it takes about half
the time of the same code interpreted; the ball EKF's kernels
(:mod:`~estimators.kalman.ball_kernels`) call them on each track, a single tracker's and every
row of a batch's alike, so a row rounds exactly as the single filter does. A track's
covariance is stored as a row of 12: the blocks P11, P12 and P22 row-major in columns 0-3, 4-7
and 8-11 (:func:`blocks_from_row` turns one row back into :data:`Blocks`). The blocks take
float tuples: a caller turns a detection into a ``(float, float)`` pair, so that one compiled
version serves every caller.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..compiled import kernel

__all__ = ["Mat2", "Blocks", "State", "transpose", "full_covariance", "blocks_from_row",
           "predict_covariance", "predict_jump", "innovation", "update", "update_closed_form"]


#: A 2 x 2 matrix as a row-major 4-tuple ``(m00, m01, m10, m11)``.
Mat2 = tuple[float, float, float, float]

#: A 4 x 4 covariance as its three 2 x 2 blocks ``(P11, P12, P22)`` (``P21 = P12^T``; the
#: symmetric blocks stored with equal off-diagonals).
Blocks = tuple[Mat2, Mat2, Mat2]

#: A ball state ``(x, y, vx, vy)`` [m, m/s].
State = tuple[float, float, float, float]


def transpose(a: Mat2) -> Mat2:
    """The transpose of a 2 x 2 block."""
    return (a[0], a[2], a[1], a[3])


def full_covariance(P: Blocks) -> np.ndarray:
    """The ``4 x 4`` array of a covariance in blocks."""
    P11, P12, P22 = P
    return np.block([[np.reshape(P11, (2, 2)), np.reshape(P12, (2, 2))],
                     [np.reshape(transpose(P12), (2, 2)), np.reshape(P22, (2, 2))]])


def blocks_from_row(P: np.ndarray) -> Blocks:
    """A ``(12,)`` covariance row as :data:`Blocks`."""
    v = P.tolist()
    return (tuple(v[0:4]), tuple(v[4:8]), tuple(v[8:12]))


@kernel
def predict_covariance(P: Blocks, A: Mat2, B: Mat2, q: float) -> Blocks:
    """``P = F P F^T + Q`` for ``F = [[I, A], [0, B]]``, ``Q = diag(0, 0, q, q)``.

    With ``P21 = P12^T``: ``P11' = P11 + A P21 + P12 A^T + A P22 A^T``,
    ``P12' = (P12 + A P22) B^T``, ``P22' = B P22 B^T + q I`` (written out element by element).
    """
    (p0, p1, _, p3), (m0, m1, m2, m3), (n0, n1, _, n3) = P
    a0, a1, a2, a3 = A
    b0, b1, b2, b3 = B
    # A P22 (P22 symmetric: n2 = n1)
    t0, t1 = a0 * n0 + a1 * n1, a0 * n1 + a1 * n3
    t2, t3 = a2 * n0 + a3 * n1, a2 * n1 + a3 * n3
    # A P21 with P21 = P12^T = (m0, m2, m1, m3)
    s0, s1 = a0 * m0 + a1 * m1, a0 * m2 + a1 * m3
    s2, s3 = a2 * m0 + a3 * m1, a2 * m2 + a3 * m3
    q00 = p0 + 2.0 * s0 + t0 * a0 + t1 * a1
    q01 = p1 + s1 + s2 + 0.5 * (t0 * a2 + t1 * a3 + t2 * a0 + t3 * a1)
    q11 = p3 + 2.0 * s3 + t2 * a2 + t3 * a3
    w0, w1, w2, w3 = m0 + t0, m1 + t1, m2 + t2, m3 + t3
    P12n = (w0 * b0 + w1 * b1, w0 * b2 + w1 * b3, w2 * b0 + w3 * b1, w2 * b2 + w3 * b3)
    u0, u1 = b0 * n0 + b1 * n1, b0 * n1 + b1 * n3
    u2, u3 = b2 * n0 + b3 * n1, b2 * n1 + b3 * n3
    r01 = 0.5 * (u0 * b2 + u1 * b3 + u2 * b0 + u3 * b1)
    return ((q00, q01, q01, q11), P12n,
            (u0 * b0 + u1 * b1 + q, r01, r01, u2 * b2 + u3 * b3 + q))


@kernel
def predict_jump(x: State, P: Blocks, dt: float, q: float) -> tuple[State, Blocks]:
    """``(x', P')`` over ``dt`` seconds at constant velocity (``A = dt I``, ``B = I``) with a
    velocity jump of variance ``q`` [m^2/s^2] per axis at a uniform time within the step (a
    kick or a bounce is an impulse), so per axis ``Q = q [[dt^2 / 3, dt / 2], [dt / 2, 1]]``:
    ``P11' = P11 + dt (P12 + P21) + dt^2 P22 + q dt^2 / 3 I``,
    ``P12' = P12 + dt P22 + q dt / 2 I``, ``P22' = P22 + q I``."""
    (p0, p1, _, p3), (m0, m1, m2, m3), (n0, n1, _, n3) = P
    qp, qc = q * dt * dt / 3.0, 0.5 * q * dt
    w0, w1, w2, w3 = m0 + dt * n0, m1 + dt * n1, m2 + dt * n1, m3 + dt * n3
    c01 = p1 + dt * (m1 + m2 + dt * n1)
    return ((x[0] + x[2] * dt, x[1] + x[3] * dt, x[2], x[3]),
            ((p0 + dt * (m0 + w0) + qp, c01, c01, p3 + dt * (m3 + w3) + qp),
             (w0 + qc, w1, w2, w3 + qc), (n0 + q, n1, n1, n3 + q)))


@kernel
def innovation(x: State, P: Blocks, z: Sequence[float], r: float
               ) -> tuple[tuple[float, float], Mat2, float]:
    """``(y, S^-1, d^2)`` of a position measurement ``z`` [m] with noise variance ``r``
    [m^2] (``H = [I 0]``, ``R = r I``): the innovation ``y = z - H x`` [m], the inverse of its
    covariance ``S = P11 + r I`` [1/m^2] and the squared Mahalanobis distance
    ``d^2 = y^T S^-1 y``."""
    P11 = P[0]
    s0, s1, s3 = P11[0] + r, P11[1], P11[3] + r
    det = s0 * s3 - s1 * s1
    Si = (s3 / det, -s1 / det, -s1 / det, s0 / det)
    y0, y1 = z[0] - x[0], z[1] - x[1]
    d2 = y0 * (Si[0] * y0 + Si[1] * y1) + y1 * (Si[2] * y0 + Si[3] * y1)
    return (y0, y1), Si, d2


@kernel
def update(x: State, P: Blocks, y: Sequence[float], Si: Mat2, r: float
           ) -> tuple[State, Blocks]:
    """Kalman gain, mean and Joseph-form covariance for ``H = [I 0]``, ``R = r I``.

    ``K1 = P11 S^-1``, ``K2 = P21 S^-1``; with ``M = I - K1``, ``N = -K2``:
    ``P11' = M P11 M^T + r K1 K1^T``, ``P12' = M P11 N^T + M P12 + r K1 K2^T``,
    ``P22' = (N P11 + P21) N^T + N P12 + P22 + r K2 K2^T`` (written out element by element;
    the symmetric blocks are stored with equal off-diagonals).
    """
    (p0, p1, _, p3), (m0, m1, m2, m3), (n0, n1, _, n3) = P
    i0, i1, _, i3 = Si
    y0, y1 = y
    # K1 = P11 S^-1, K2 = P21 S^-1 with P21 = (m0, m2, m1, m3).
    a0, a1, a2, a3 = p0 * i0 + p1 * i1, p0 * i1 + p1 * i3, p1 * i0 + p3 * i1, p1 * i1 + p3 * i3
    b0, b1, b2, b3 = m0 * i0 + m2 * i1, m0 * i1 + m2 * i3, m1 * i0 + m3 * i1, m1 * i1 + m3 * i3
    xn = (x[0] + a0 * y0 + a1 * y1, x[1] + a2 * y0 + a3 * y1,
          x[2] + b0 * y0 + b1 * y1, x[3] + b2 * y0 + b3 * y1)
    # M = I - K1 = (c0, c1, c2, c3); N = -K2.
    c0, c1, c2, c3 = 1.0 - a0, -a1, -a2, 1.0 - a3
    # M P11
    e0, e1 = c0 * p0 + c1 * p1, c0 * p1 + c1 * p3
    e2, e3 = c2 * p0 + c3 * p1, c2 * p1 + c3 * p3
    # P11' = (M P11) M^T + r K1 K1^T
    q00 = e0 * c0 + e1 * c1 + r * (a0 * a0 + a1 * a1)
    q01 = 0.5 * (e0 * c2 + e1 * c3 + e2 * c0 + e3 * c1) + r * (a0 * a2 + a1 * a3)
    q11 = e2 * c2 + e3 * c3 + r * (a2 * a2 + a3 * a3)
    # P12' = (M P11) N^T + M P12 + r K1 K2^T, N^T = -(b0, b2, b1, b3)
    f0 = -(e0 * b0 + e1 * b1) + c0 * m0 + c1 * m2 + r * (a0 * b0 + a1 * b1)
    f1 = -(e0 * b2 + e1 * b3) + c0 * m1 + c1 * m3 + r * (a0 * b2 + a1 * b3)
    f2 = -(e2 * b0 + e3 * b1) + c2 * m0 + c3 * m2 + r * (a2 * b0 + a3 * b1)
    f3 = -(e2 * b2 + e3 * b3) + c2 * m1 + c3 * m3 + r * (a2 * b2 + a3 * b3)
    # N P11 + P21, with N = -K2
    g0, g1 = -(b0 * p0 + b1 * p1) + m0, -(b0 * p1 + b1 * p3) + m2
    g2, g3 = -(b2 * p0 + b3 * p1) + m1, -(b2 * p1 + b3 * p3) + m3
    # P22' = (N P11 + P21) N^T + N P12 + P22 + r K2 K2^T
    h00 = -(g0 * b0 + g1 * b1) - (b0 * m0 + b1 * m2) + n0 + r * (b0 * b0 + b1 * b1)
    h01 = 0.5 * (-(g0 * b2 + g1 * b3) - (b0 * m1 + b1 * m3)
                 - (g2 * b0 + g3 * b1) - (b2 * m0 + b3 * m2)) + n1 + r * (b0 * b2 + b1 * b3)
    h11 = -(g2 * b2 + g3 * b3) - (b2 * m1 + b3 * m3) + n3 + r * (b2 * b2 + b3 * b3)
    return xn, ((q00, q01, q01, q11), (f0, f1, f2, f3), (h00, h01, h01, h11))


@kernel
def update_closed_form(x: State, P: Blocks, z: Sequence[float], y: Sequence[float], Si: Mat2,
                       r: float) -> tuple[State, Blocks]:
    """The update for ``H = [I 0]``, ``R = r I`` in closed form: the result of :func:`update`
    with fewer operations, in the standard rather than the Joseph form, for the innovation
    ``y`` and ``S^-1`` of :func:`innovation`. ``S = P11 + r I`` commutes with ``P11``, so
    ``K1 = P11 S^-1 = I - r S^-1`` and, with ``K2 = P21 S^-1``,
    ``x = (z - r S^-1 y, v + K2 y)``, ``P11' = r (I - r S^-1)``, ``P12' = r S^-1 P12``,
    ``P22' = P22 - K2 P12`` (``(I - K H) P``, symmetric by construction)."""
    (p0, p1, _, p3), (m0, m1, m2, m3), (n0, n1, _, n3) = P
    i0, i1, _, i3 = Si
    y0, y1 = y
    t0, t1 = i0 * y0 + i1 * y1, i1 * y0 + i3 * y1  # S^-1 y
    # K2 = P21 S^-1 with P21 = (m0, m2, m1, m3)
    b0, b1, b2, b3 = m0 * i0 + m2 * i1, m0 * i1 + m2 * i3, m1 * i0 + m3 * i1, m1 * i1 + m3 * i3
    c01 = n1 - 0.5 * (b0 * m1 + b1 * m3 + b2 * m0 + b3 * m2)
    return ((z[0] - r * t0, z[1] - r * t1, x[2] + b0 * y0 + b1 * y1, x[3] + b2 * y0 + b3 * y1),
            ((r - r * r * i0, -r * r * i1, -r * r * i1, r - r * r * i3),
             (r * (i0 * m0 + i1 * m2), r * (i0 * m1 + i1 * m3),
              r * (i1 * m0 + i3 * m2), r * (i1 * m1 + i3 * m3)),
             (n0 - b0 * m0 - b1 * m2, c01, c01, n3 - b2 * m1 - b3 * m3)))
