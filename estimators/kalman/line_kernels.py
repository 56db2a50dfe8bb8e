"""Compiled steps of the sighting-line ball tracker (:mod:`estimators.kalman.lines`) on one
track: the state ``x = (px, py, vx, vy, b_0x, b_0y, beta_0, b_1x, ...)`` (the ball [m, m/s]
and each observer's position bias [m] and heading bias [rad]) with its covariance ``P``.

Each step is one call where numpy would pay a call per matrix operation (the tracker runs for
every sighting of every robot of a team, about a hundred a second per robot). The maths is
stated in :mod:`estimators.kalman.lines`; each kernel says which part it is.
"""

from __future__ import annotations

import math

import numpy as np

from ..compiled import kernel

__all__ = ["rolled", "drift_predict", "kick_prior", "update_point", "update_bearing", "BALL",
           "SLOT"]

#: Entries of the ball's state ``(px, py, vx, vy)``, first in the state.
BALL = 4
#: Entries of an observer's bias ``(bx, by, beta)``.
SLOT = 3


@kernel
def rolled(x: np.ndarray, dt: float, deceleration: float, sliding: float,
           switch: float) -> np.ndarray:
    """The ball ``x[0:4] = (px, py, vx, vy)`` ``dt >= 0`` [s] later (a new ``(4,)`` array),
    decelerating uniformly along its motion: by ``sliding`` [m/s^2] while its speed exceeds
    ``switch`` [m/s] (a kicked ball slides; ``inf``: never), then by ``deceleration`` until
    it stops. Over a phase of ``tau`` seconds at deceleration ``a`` from speed ``s`` along
    ``u``: ``p' = p + u (s tau - a tau^2 / 2)``, ``v' = u (s - a tau)``; rolling lasts
    ``tau = min(dt, s / a)`` (constant velocity for ``a = 0``)."""
    px, py, vx, vy = x[0], x[1], x[2], x[3]
    out = np.empty(4)
    speed = math.sqrt(vx * vx + vy * vy)
    if sliding > 0.0 and speed > switch:
        t1 = (speed - switch) / sliding
        tau = min(dt, t1)
        k = tau - 0.5 * sliding * tau * tau / speed
        f = 1.0 - sliding * tau / speed
        px, py, vx, vy = px + k * vx, py + k * vy, f * vx, f * vy
        dt -= tau
        speed = speed * f
    if deceleration == 0.0 or speed == 0.0 or dt <= 0.0:
        out[0], out[1], out[2], out[3] = px + dt * vx, py + dt * vy, vx, vy
    else:
        tau = min(dt, speed / deceleration)
        k = tau - 0.5 * deceleration * tau * tau / speed
        f = max(1.0 - deceleration * tau / speed, 0.0)
        out[0], out[1], out[2], out[3] = px + k * vx, py + k * vy, f * vx, f * vy
    return out


@kernel
def drift_predict(x: np.ndarray, P: np.ndarray, dt: float, deceleration: float,
                  sliding: float, switch: float, q: float, q_xy: float, q_theta: float
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The time update over ``dt >= 0`` [s] (new arrays).

    The ball's mean by :func:`rolled`; its covariance by the constant-velocity model with white
    acceleration noise of variance ``q`` [m^2/s^4]: ``A P A^T + q B B^T``,
    ``A = [[I, dt I], [0, I]]``, ``B = [dt^2/2 I; dt I]`` on the ball's block (and its rows
    of the cross-covariances). The biases walk: ``q_xy dt`` [m^2] per position axis and
    ``q_theta dt`` [rad^2] per heading."""
    n = x.shape[0]
    xn = x.copy()
    ball = rolled(x, dt, deceleration, sliding, switch)
    for i in range(4):
        xn[i] = ball[i]
    Pn = P.copy()
    for j in range(n):  # rows: A P
        Pn[0, j] = P[0, j] + dt * P[2, j]
        Pn[1, j] = P[1, j] + dt * P[3, j]
    for i in range(n):  # columns: (A P) A^T
        Pn[i, 0] = Pn[i, 0] + dt * Pn[i, 2]
        Pn[i, 1] = Pn[i, 1] + dt * Pn[i, 3]
    h = 0.5 * dt * dt
    for a in range(2):
        Pn[a, a] += q * h * h
        Pn[a, a + 2] += q * h * dt
        Pn[a + 2, a] += q * h * dt
        Pn[a + 2, a + 2] += q * dt * dt
    for s in range(BALL, n, SLOT):
        Pn[s, s] += q_xy * dt
        Pn[s + 1, s + 1] += q_xy * dt
        Pn[s + 2, s + 2] += q_theta * dt
    return xn, Pn


@kernel
def kick_prior(P: np.ndarray, elapsed: float, kick_var: float) -> np.ndarray:
    """The covariance of a track kicked ``elapsed`` [s] ago (a new array): a velocity jump
    ``dv ~ N(0, kick_var I)`` [m^2/s^2] at the kick moves the position by ``elapsed dv`` since,
    so the ball's block gains ``[[e^2 J I, e J I], [e J I, J I]]`` with ``e = elapsed``,
    ``J = kick_var``."""
    Pn = P.copy()
    for a in range(2):
        Pn[a, a] += elapsed * elapsed * kick_var
        Pn[a, a + 2] += elapsed * kick_var
        Pn[a + 2, a] += elapsed * kick_var
        Pn[a + 2, a + 2] += kick_var
    return Pn


@kernel
def update_point(x: np.ndarray, P: np.ndarray, zx: float, zy: float, r00: float, r01: float,
                 r11: float, slot: int, r: float, nx: float, ny: float
                 ) -> tuple[float, float, np.ndarray, np.ndarray]:
    """The update with a sighted position ``z`` [m] of white-noise covariance
    ``R = [[r00, r01], [r01, r11]]`` [m^2] by the observer whose bias starts at entry ``slot``
    of the state, at range ``r`` [m] along a line of unit normal ``n``:
    ``h(x) = p + b + r beta n`` (``H`` the ball's position, the observer's position bias and
    ``r n`` on its heading bias). Returns ``(d2, log det S, x', P')`` with ``y = z - h(x)``,
    ``S = H P H^T + R``, ``d2 = y^T S^-1 y``, ``K = P H^T S^-1``, ``x' = x + K y``,
    ``P' = P - K (P H^T)^T`` (symmetrised; new arrays)."""
    m = x.shape[0]
    bx, by, bt = slot, slot + 1, slot + 2
    PH = np.empty((m, 2))  # P H^T
    for i in range(m):
        PH[i, 0] = P[i, 0] + P[i, bx] + r * nx * P[i, bt]
        PH[i, 1] = P[i, 1] + P[i, by] + r * ny * P[i, bt]
    # S = H (P H^T) + R
    s0 = PH[0, 0] + PH[bx, 0] + r * nx * PH[bt, 0] + r00
    s1 = PH[1, 0] + PH[by, 0] + r * ny * PH[bt, 0] + r01
    s3 = PH[1, 1] + PH[by, 1] + r * ny * PH[bt, 1] + r11
    det = s0 * s3 - s1 * s1
    i0, i1, i3 = s3 / det, -s1 / det, s0 / det
    y0 = zx - (x[0] + x[bx] + r * nx * x[bt])
    y1 = zy - (x[1] + x[by] + r * ny * x[bt])
    d2 = y0 * (i0 * y0 + i1 * y1) + y1 * (i1 * y0 + i3 * y1)
    xn = np.empty(m)
    K = np.empty((m, 2))
    for i in range(m):
        K[i, 0] = PH[i, 0] * i0 + PH[i, 1] * i1
        K[i, 1] = PH[i, 0] * i1 + PH[i, 1] * i3
        xn[i] = x[i] + K[i, 0] * y0 + K[i, 1] * y1
    Pn = np.empty((m, m))
    for i in range(m):
        for j in range(i, m):
            v = P[i, j] - (K[i, 0] * PH[j, 0] + K[i, 1] * PH[j, 1])
            Pn[i, j] = v
            Pn[j, i] = v
    return d2, math.log(det), xn, Pn


@kernel
def update_bearing(x: np.ndarray, P: np.ndarray, ox: float, oy: float, nx: float, ny: float,
                   var: float, slot: int, d: float) -> tuple[float, float, np.ndarray, np.ndarray]:
    """The update with a bearing-only sighting from ``o`` [m] along a line of unit normal
    ``n``, by the observer whose bias starts at ``slot``, the ball about ``d`` [m] away:
    ``h(x) = n . (p + b - o) + d beta``, measured as 0 with white variance ``var`` [m^2].
    Returns ``(d2, log S, x', P')`` with ``y = -h(x)``, ``S = H P H^T + var``,
    ``d2 = y^2 / S``, ``K = P H^T / S``, ``x' = x + K y``, ``P' = P - K (P H^T)^T``
    (symmetrised; new arrays)."""
    m = x.shape[0]
    bx, by, bt = slot, slot + 1, slot + 2
    y = -(nx * (x[0] + x[bx] - ox) + ny * (x[1] + x[by] - oy) + d * x[bt])
    PH = np.empty(m)
    for i in range(m):
        PH[i] = nx * (P[i, 0] + P[i, bx]) + ny * (P[i, 1] + P[i, by]) + d * P[i, bt]
    S = nx * (PH[0] + PH[bx]) + ny * (PH[1] + PH[by]) + d * PH[bt] + var
    xn = np.empty(m)
    for i in range(m):
        xn[i] = x[i] + PH[i] / S * y
    Pn = np.empty((m, m))
    for i in range(m):
        for j in range(i, m):
            v = P[i, j] - PH[i] * PH[j] / S
            Pn[i, j] = v
            Pn[j, i] = v
    return y * y / S, math.log(S), xn, Pn
