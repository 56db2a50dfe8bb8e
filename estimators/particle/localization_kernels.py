"""Compiled kernels of :class:`~estimators.KLDLocalizer`: the observation likelihood, the
weighting, the motion model, KLD-sampling's draws and bin count, and the estimates, each
over the rows of the particle array ``(N, 3)`` = ``(x, y, theta)`` [m, m, rad].

Written as ``numba`` kernels because the filter runs for every head-camera frame of every
robot on arrays of fifty to a few thousand rows, where a numpy version costs one call per
operation (some forty per update) rather than the arithmetic. The random draws stay with the
caller's ``numpy.random.Generator`` (the kernels take the draws as arrays), so a seeded
filter draws exactly the numbers it drew before.

The maths is the module docstring of :mod:`estimators.particle.localization`; each kernel
says which part it is.
"""

from __future__ import annotations

import math

import numpy as np

from ..compiled import kernel
from ..exact import floor_remainder, search_right

__all__ = ["best_log_likelihood", "weigh", "move_particles",
           "draw_rows", "kld_sample_count", "weighted_pose", "weighted_spread"]

_TWO_PI = 2.0 * math.pi


@kernel
def best_log_likelihood(particles: np.ndarray, lx: np.ndarray, ly: np.ndarray,
                        counts: np.ndarray, ranges: np.ndarray, bearings: np.ndarray,
                        sigmas: tuple[float, float, float], bearing_sigma: float
                        ) -> np.ndarray:
    """The log-likelihood (up to a constant) of every particle for ``m`` sightings:
    ``sum_j max_c [-(g_c - r_j)^2 / (2 sigma_j^2) - wrap(atan2(dy_c, dx_c) - theta -
    b_j)^2 / (2 sigma_b^2)]`` ((N,)).

    Args:
        particles: ``(N, 3)`` poses.
        lx: ``(C,)`` the candidate landmark positions' ``x`` [m], sighting ``j``'s
            ``counts[j]`` candidates in turn (one each for landmarks of known identity).
        ly: ``(C,)`` their ``y`` [m].
        counts: ``(m,)`` candidates per sighting.
        ranges: ``(m,)`` measured ranges ``r_j`` [m].
        bearings: ``(m,)`` bearings ``b_j`` [rad, relative to the heading]; ignored when
            ``bearing_sigma <= 0`` (the range term alone).
        sigmas: ``(range_sigma, range_sigma_rel, range_sigma_quad)``: ``sigma_j =
            range_sigma + (range_sigma_rel + range_sigma_quad r_j) r_j`` [m].
        bearing_sigma: ``sigma_b`` [rad], or 0 to leave bearings out.
    """
    n = particles.shape[0]
    m = counts.shape[0]
    out = np.zeros(n)
    s0, s1, s2 = sigmas
    use_b = bearing_sigma > 0.0
    for i in range(n):
        px, py, pt = particles[i, 0], particles[i, 1], particles[i, 2]
        total = 0.0
        c = 0
        for j in range(m):
            r = ranges[j]
            sigma = s0 + (s1 + s2 * r) * r
            # The bearing error wrap(atan2(dy, dx) - psi), psi = theta + b_j, as the angle of
            # the offset in the frame turned by psi: one atan2, no remainder.
            cp = sp = 0.0
            if use_b:
                cp, sp = math.cos(pt + bearings[j]), math.sin(pt + bearings[j])
            best = -np.inf
            for _ in range(counts[j]):
                dx = lx[c] - px
                dy = ly[c] - py
                e = (math.sqrt(dx * dx + dy * dy) - r) / sigma
                log = -0.5 * (e * e)
                if use_b:
                    a = math.atan2(dy * cp - dx * sp, dx * cp + dy * sp) / bearing_sigma
                    log -= 0.5 * (a * a)
                if log > best:
                    best = log
                c += 1
            total += best
        out[i] = total
    return out


@kernel
def weigh(weights: np.ndarray, log: np.ndarray, m: int) -> tuple[np.ndarray, float, float]:
    """The measurement update of the weights: ``w_i exp(log_i - max log)`` normalised (the
    shift against underflow; uniform when the total is zero or not finite), with the total
    before normalising and the mean likelihood per sighting ``sum_i w_i exp(log_i / m)``
    (the recovery's averages)."""
    n = weights.shape[0]
    top = -np.inf
    for i in range(n):
        if log[i] > top:
            top = log[i]
    new = np.empty(n)
    total = 0.0
    mean = 0.0
    for i in range(n):
        new[i] = weights[i] * math.exp(log[i] - top)
        total += new[i]
        mean += weights[i] * math.exp(log[i] / m)
    if total <= 0.0 or not math.isfinite(total):
        for i in range(n):
            new[i] = 1.0 / n
    else:
        for i in range(n):
            new[i] /= total
    return new, total, mean


@kernel
def move_particles(p: np.ndarray, d: tuple[float, float, float], noise: np.ndarray,
                   alphas: tuple[float, float, float, float]) -> None:
    """Move the particles ``p`` ((n, 3), in place) by the body-frame displacement ``d =
    (dx, dy, dtheta)`` [m, m, rad] with the odometry noise ``noise`` ((n, 3) standard normal
    draws): ``sigma_xy = a_trans |d| + a_rot_xy |dtheta|``, ``sigma_theta = a_rot |dtheta| +
    a_trans_theta |d|``, applied in each particle's frame at the mid-step heading
    ``alphas = (a_trans, a_rot_xy, a_rot, a_trans_theta)``."""
    a_trans, a_rot_xy, a_rot, a_trans_theta = alphas
    dist, turn = math.hypot(d[0], d[1]), abs(d[2])
    s_xy = a_trans * dist + a_rot_xy * turn
    s_th = a_rot * turn + a_trans_theta * dist
    for i in range(p.shape[0]):
        dx = d[0] + s_xy * noise[i, 0]
        dy = d[1] + s_xy * noise[i, 1]
        th = p[i, 2] + 0.5 * d[2]
        cs, sn = math.cos(th), math.sin(th)
        p[i, 0] += cs * dx - sn * dy
        p[i, 1] += sn * dx + cs * dy
        p[i, 2] = floor_remainder(p[i, 2] + d[2] + s_th * noise[i, 2] + math.pi,
                                  _TWO_PI) - math.pi


@kernel
def draw_rows(cumulative: np.ndarray, particles: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Multinomial draws by inverting the cumulative weights: the row of the first
    ``cumulative > u_k`` for every uniform draw ``u_k`` ((k, 3), a copy)."""
    n = particles.shape[0]
    out = np.empty((u.shape[0], 3))
    for k in range(u.shape[0]):
        i = min(search_right(cumulative, u[k]), n - 1)
        out[k, 0] = particles[i, 0]
        out[k, 1] = particles[i, 1]
        out[k, 2] = particles[i, 2]
    return out


@kernel
def kld_sample_count(rows: np.ndarray, bin_size: tuple[float, float, float],
                     bound: np.ndarray, low: int) -> int:
    """KLD-sampling's stopping rule over the draws ``rows`` ((k, 3)) in order: the first
    ``n >= low`` with ``n >= bound[k(n)]``, ``k(n)`` the number of distinct bins
    ``floor(row / bin_size)`` among the first ``n`` draws; 0 when no prefix qualifies."""
    # The distinct bins in an open-addressing hash table of int64 keys (a typed set would
    # do, but costs seconds to compile on a first run).
    k = rows.shape[0]
    size = 2
    while size < 2 * k:
        size <<= 1
    mask = size - 1
    table = np.empty(size, np.int64)
    used = np.zeros(size, np.bool_)
    distinct = 0
    for i in range(k):
        key = (np.int64(math.floor(rows[i, 0] / bin_size[0])) * np.int64(1 << 42)
               + np.int64(math.floor(rows[i, 1] / bin_size[1])) * np.int64(1 << 21)
               + np.int64(math.floor(rows[i, 2] / bin_size[2])))
        slot = (key ^ (key >> 21) ^ (key >> 42)) & mask
        while used[slot] and table[slot] != key:
            slot = (slot + 1) & mask
        if not used[slot]:
            used[slot] = True
            table[slot] = key
            distinct += 1
        n = i + 1
        if n >= low and n >= bound[distinct]:
            return n
    return 0


@kernel
def weighted_pose(weights: np.ndarray, p: np.ndarray) -> tuple[float, float, float, float]:
    """The weighted mean pose ``(x, y, theta)`` (the headings' circular mean) and the mean
    resultant length ``R = |sum_i w_i (cos theta_i, sin theta_i)|`` of the headings."""
    x = y = c = s = 0.0
    for i in range(p.shape[0]):
        w = weights[i]
        x += w * p[i, 0]
        y += w * p[i, 1]
        c += w * math.cos(p[i, 2])
        s += w * math.sin(p[i, 2])
    return x, y, math.atan2(s, c), math.hypot(c, s)


@kernel
def weighted_spread(weights: np.ndarray, p: np.ndarray, x: float, y: float) -> float:
    """The weighted RMS distance [m] of the particles from the point ``(x, y)``."""
    total = 0.0
    for i in range(p.shape[0]):
        total += weights[i] * ((p[i, 0] - x) ** 2 + (p[i, 1] - y) ** 2)
    return math.sqrt(total)
