"""Compiled kernels of the particle filters (:mod:`estimators.particle.core`) and of the
particle ball tracker's model (:mod:`estimators.particle.ball`), each over the rows of a
particle array ``(N, d)``.

The filters run for every fused ball position of every robot on a hundred particles or so,
where a numpy version pays one call per operation (a few dozen per update) rather than the
arithmetic; these kernels do each step in one call. The random draws stay with the caller's
``numpy.random.Generator`` (the kernels take the draws as arrays), so a seeded filter draws
the numbers it drew before. The maths is stated in those modules' docstrings; each kernel
says which part it is.
"""

from __future__ import annotations

import math

import numpy as np

from ..compiled import kernel
from ..exact import stable_argsort

__all__ = ["weigh", "weighted_mean", "systematic_indices", "sfn_children", "sfn_apply",
           "roll", "drift", "transition", "position_likelihood", "position_moments"]


@kernel
def weigh(weights: np.ndarray, likelihood: np.ndarray) -> tuple[np.ndarray, float]:
    """``w_i = w_i p(y | x_i)`` ((N,), a new array) and its sum ``S``."""
    n = weights.shape[0]
    w = np.empty(n)
    total = 0.0
    for i in range(n):
        w[i] = weights[i] * likelihood[i]
        total += w[i]
    return w, total


@kernel
def weighted_mean(weights: np.ndarray, particles: np.ndarray, scale: float) -> np.ndarray:
    """``scale * sum_i w_i x_i`` ((d,)) of particles ``x`` ((N, d))."""
    n, d = particles.shape
    out = np.zeros(d)
    for i in range(n):
        w = weights[i]
        for k in range(d):
            out[k] += w * particles[i, k]
    for k in range(d):
        out[k] *= scale
    return out


@kernel
def systematic_indices(weights: np.ndarray, offset: float) -> np.ndarray:
    """Systematic resampling of normalised ``weights`` ((N,)): the indices of the ``N``
    evenly spaced pointers ``(offset + j) / N`` (``offset`` one uniform draw in [0, 1))
    into the cumulative weights (its last entry set to 1 against rounding)."""
    n = weights.shape[0]
    cumulative = np.empty(n)
    total = 0.0
    for i in range(n):  # np.cumsum's sums, in its order
        total += weights[i]
        cumulative[i] = total
    cumulative[n - 1] = 1.0
    out = np.empty(n, dtype=np.int64)
    i = 0
    for j in range(n):
        u = (offset + j) / n
        while i < n - 1 and cumulative[i] <= u:  # the first cumulative > u
            i += 1
        out[j] = i
    return out


@kernel
def sfn_children(weights: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """SFN's sorting and offspring count: the particles by decreasing weight (a stable
    order), ``max(floor(N w) - 1, 0)`` children of each in that order, and their total."""
    n = weights.shape[0]
    negated = np.empty(n)
    for i in range(n):
        negated[i] = -weights[i]
    order = stable_argsort(negated)
    children = np.empty(n, dtype=np.int64)
    total = 0
    for j in range(n):
        c = int(math.floor(n * weights[order[j]])) - 1
        children[j] = c if c > 0 else 0
        total += children[j]
    return order, children, total


@kernel
def sfn_apply(particles: np.ndarray, weights: np.ndarray, order: np.ndarray,
              children: np.ndarray, noise: np.ndarray, scale: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """SFN's fission and normalising (:func:`~estimators.particle.core.sfn`): the sorted
    particles, the ``n_c`` lightest replaced by the children of the heavier ones in order
    (``parent + noise * scale``, ``noise`` ``(n_c, d)`` standard normal draws, ``scale``
    ``(d,)`` standard deviations), each parent's weight shared among it and its children,
    normalised. Returns the particles, the weights and the mask of the children."""
    n, d = particles.shape
    n_c = noise.shape[0]
    p = np.empty((n, d))
    w = np.empty(n)
    for j in range(n):
        for k in range(d):
            p[j, k] = particles[order[j], k]
        w[j] = weights[order[j]] / (children[j] + 1)
    born = np.zeros(n, dtype=np.bool_)
    row = n - n_c
    c = 0
    for j in range(n):
        for _ in range(children[j]):
            for k in range(d):
                p[row, k] = p[j, k] + noise[c, k] * scale[k]
            w[row] = w[j]
            born[row] = True
            row += 1
            c += 1
    total = 0.0
    for j in range(n):
        total += w[j]
    for j in range(n):
        w[j] /= total
    return p, w, born


@kernel
def roll(px: float, py: float, vx: float, vy: float, speed: float, dt: float,
         deceleration: float) -> tuple[float, float, float, float]:
    """One ball ``(px, py, vx, vy)`` of speed ``speed`` (its velocity's norm, as the caller
    computes it) ``dt >= 0`` [s] later: constant velocity for ``deceleration = 0`` or a ball
    at rest, else uniform deceleration ``a`` along the motion until the ball stops:
    ``tau = min(dt, s / a)``, ``p' = p + v (tau - a tau^2 / (2 s))``,
    ``v' = v max(1 - a tau / s, 0)``."""
    if deceleration == 0.0 or speed == 0.0:
        return px + dt * vx, py + dt * vy, vx, vy
    tau = min(dt, speed / deceleration)
    k = tau - 0.5 * deceleration * tau * tau / speed
    f = max(1.0 - deceleration * tau / speed, 0.0)
    return px + k * vx, py + k * vy, f * vx, f * vy


@kernel
def drift(x: np.ndarray, dt: float, deceleration: float) -> np.ndarray:
    """The deterministic ball motion of states ``x = (px, py, vx, vy)`` ((N, 4)) over
    ``dt`` [s] (a new array): :func:`roll` on each row."""
    out = x.copy()
    for i in range(x.shape[0]):
        vx, vy = x[i, 2], x[i, 3]
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = roll(
            x[i, 0], x[i, 1], vx, vy, math.hypot(vx, vy), dt, deceleration)
    return out


@kernel
def transition(x: np.ndarray, dt: float, deceleration: float, w: np.ndarray) -> np.ndarray:
    """``X_t = drift(X_{t-1}) + B W_t`` ((N, 4), a new array), ``B = [dt^2 / 2 I; dt I]``,
    ``w`` the ``(N, 2)`` accelerations ``W_t`` [m/s^2]."""
    out = drift(x, dt, deceleration)
    h = 0.5 * dt * dt
    for i in range(x.shape[0]):
        out[i, 0] += h * w[i, 0]
        out[i, 1] += h * w[i, 1]
        out[i, 2] += dt * w[i, 0]
        out[i, 3] += dt * w[i, 1]
    return out


@kernel
def position_likelihood(x: np.ndarray, z: tuple[float, float], lag: float,
                        rinv: tuple[float, float, float]) -> np.ndarray:
    """``N(z; p_i, R)`` up to a constant factor ((N,)): ``exp(-(m_i - min m) / 2)``, ``m_i
    = d^T R^-1 d``, ``d = p_i - lag v_i - z`` (the particle's position ``lag`` seconds
    back), ``rinv = (a, b, c)`` the entries of ``R^-1 = [[a, b], [b, c]]``."""
    n = x.shape[0]
    a, b, c = rinv
    m = np.empty(n)
    low = np.inf
    for i in range(n):
        d0 = x[i, 0] - lag * x[i, 2] - z[0]
        d1 = x[i, 1] - lag * x[i, 3] - z[1]
        m[i] = a * d0 * d0 + 2.0 * b * d0 * d1 + c * d1 * d1
        if m[i] < low:
            low = m[i]
    for i in range(n):
        m[i] = math.exp(-0.5 * (m[i] - low))
    return m


@kernel
def position_moments(x: np.ndarray, weights: np.ndarray, lag: float
                     ) -> tuple[float, float, float, float, float]:
    """The weighted mean ``(m_x, m_y)`` and covariance ``(c_xx, c_xy, c_yy)`` of the
    particles' positions ``lag`` seconds back, ``p_i - lag v_i``, for weights summing to
    any positive total (normalised here)."""
    n = x.shape[0]
    total = 0.0
    for i in range(n):
        total += weights[i]
    mx = my = 0.0
    for i in range(n):
        w = weights[i] / total
        mx += w * (x[i, 0] - lag * x[i, 2])
        my += w * (x[i, 1] - lag * x[i, 3])
    cxx = cxy = cyy = 0.0
    for i in range(n):
        w = weights[i] / total
        dx = x[i, 0] - lag * x[i, 2] - mx
        dy = x[i, 1] - lag * x[i, 3] - my
        cxx += w * dx * dx
        cxy += w * dx * dy
        cyy += w * dy * dy
    return mx, my, cxx, cxy, cyy
