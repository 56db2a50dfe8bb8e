"""The fusion of a team's sighting lines as compiled kernels (Xu, Xie, Wang and Ni 2012):
steps 1 to 5 of :func:`~estimators.fusion.sightings.fuse_sightings` over the lines in one
pass (:func:`fuse_line_rows`), which :func:`~estimators.fusion.sightings.fuse_lines` (the
pipelines' hot path, every camera frame of every robot) and
:func:`~estimators.fusion.sightings.fuse_sightings` call.

* :func:`normal_sums`: the weighted normal equations ``M = sum K n n^T``,
  ``b = sum K n rho`` of the lines (``n = (nx, ny)`` the unit normals), summed in the lines'
  order.
* :func:`solve_normal`: their least-squares point, or none when the lines are (nearly)
  parallel (``det M <= MIN_CONDITION trace(M)^2``).
* :func:`crossing_covariance`: the fused point's covariance ``M^-1 (sum K^2 s^2 n n^T) M^-1``,
  inflated by ``max(1, chi^2 / (n - 2))`` for three or more lines.
* :func:`ranged_mean`: the weighted mean of the ranged sightings' point estimates, with its
  covariance.

Bit for bit with the plain-float code they replace: the same expressions in the same order,
sums in the lines' order (as Python 3.11's ``sum`` of floats), ``math.hypot`` as
:func:`~estimators.exact.hypot_exact`, and every power (Python's ``**``, the C library's
``pow``) as ``pow`` with an exponent that arrives at run time (``two`` = 2.0,
``-power``): a constant exponent would let the compiler fold ``x ** 2.0`` into ``x * x`` and
``x ** -1.0`` into ``1 / x``, which differ from ``pow`` in the last bit for about one
argument in a thousand. Python raises ``ValueError`` on the square root of a negative number
where a kernel gives NaN; the kernels report that case (status :data:`SQRT_NEGATIVE`) for the
caller to raise it.
"""

from __future__ import annotations

import math

import numpy as np

from ..compiled import kernel
from ..exact import hypot_exact

__all__ = ["fuse_line_rows", "normal_sums", "solve_normal", "crossing_covariance",
           "ranged_mean", "FUSED", "NO_POSITION", "SQRT_NEGATIVE", "MIN_CONDITION"]

#: Below this ratio ``det M / trace(M)^2`` of the normal matrix ``M = sum K n n^T`` the lines
#: are taken as parallel (no unique crossing point).
MIN_CONDITION = 1e-9
#: The smallest offset variance [m^2] the inverse-variance weighting divides by (a line whose
#: origin is at the fused point, with no position error, would have none).
MIN_OFFSET_VARIANCE = 1e-12
#: The smallest lateral standard deviation [m] a residual is divided by.
MIN_LINE_SIGMA = 1e-12

#: Status of :func:`fuse_line_rows`: a position was found.
FUSED = 1
#: Status: no position (a single bearing-only sighting, or bearing-only lines that are
#: parallel).
NO_POSITION = 0
#: Status: a covariance's trace came out negative (Python's ``math.sqrt`` would raise).
SQRT_NEGATIVE = -1


@kernel
def normal_sums(nx: np.ndarray, ny: np.ndarray, rho: np.ndarray, k: np.ndarray
                ) -> tuple[float, float, float, float, float]:
    """``(a11, a12, a22, b1, b2)``: the entries of ``M = sum K n n^T`` and
    ``b = sum K n rho`` over the lines (normals ``(nx, ny)``, offsets ``rho`` [m], weights
    ``k``), summed in the lines' order."""
    a11 = a12 = a22 = b1 = b2 = 0.0
    for i in range(nx.shape[0]):
        a, b, w = nx[i], ny[i], k[i]
        wa, wb = w * a, w * b
        a11 += wa * a
        a12 += wa * b
        a22 += wb * b
        b1 += wa * rho[i]
        b2 += wb * rho[i]
    return a11, a12, a22, b1, b2


@kernel
def solve_normal(a11: float, a12: float, a22: float, b1: float, b2: float
                 ) -> tuple[bool, float, float]:
    """``(ok, X, Y)``: the solution of ``M (X, Y)^T = b`` [m] (:func:`normal_sums`); ``ok``
    False when ``trace M <= 0`` or ``det M <= MIN_CONDITION trace(M)^2`` (the lines
    (nearly) parallel)."""
    det = a11 * a22 - a12 * a12
    trace = a11 + a22
    if trace <= 0.0 or det <= MIN_CONDITION * trace * trace:
        return False, 0.0, 0.0
    return True, (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det


@kernel
def crossing_covariance(X: float, Y: float, a11: float, a12: float, a22: float,
                        nx: np.ndarray, ny: np.ndarray, rho: np.ndarray, k: np.ndarray,
                        sig: np.ndarray, two: float, point: np.ndarray, cov: np.ndarray
                        ) -> tuple[int, float]:
    """Step 3 of :func:`~estimators.fusion.sightings.fuse_sightings`: the fused point
    ``(X, Y)`` [m] of the lines (weights ``k``, normal matrix entries ``a11, a12, a22``)
    into ``point`` (2,) and its covariance ``M^-1 (sum K^2 s^2 n n^T) M^-1`` [m^2] into
    ``cov`` (2, 2), ``s_i = sig[i]`` the lines' lateral standard deviations [m], multiplied
    by ``max(1, chi^2 / (n - 2))`` for ``n >= 3`` lines (``chi^2 = sum (e_i / s_i)^2``,
    ``e_i`` the perpendicular residuals); ``two`` is 2.0 (module docstring). Returns
    ``(status, sigma)``, ``sigma = sqrt(trace(cov) / 2)`` [m]."""
    det = a11 * a22 - a12 * a12
    i00, i01, i11 = a22 / det, -a12 / det, a11 / det  # M^-1
    s00 = s01 = s11 = 0.0
    n = nx.shape[0]
    for i in range(n):
        a, b = nx[i], ny[i]
        g = (k[i] * sig[i]) ** two
        s00 += g * a * a
        s01 += g * a * b
        s11 += g * b * b
    # cov = Minv S Minv (all symmetric 2 x 2).
    t00, t01 = i00 * s00 + i01 * s01, i00 * s01 + i01 * s11
    t10, t11 = i01 * s00 + i11 * s01, i01 * s01 + i11 * s11
    c00 = t00 * i00 + t01 * i01
    c01 = 0.5 * ((t00 * i01 + t01 * i11) + (t10 * i00 + t11 * i01))
    c11 = t10 * i01 + t11 * i11
    if n >= 3:
        chi2 = 0.0
        for i in range(n):
            sd = sig[i]
            if MIN_LINE_SIGMA > sd:
                sd = MIN_LINE_SIGMA
            chi2 += ((rho[i] - nx[i] * X - ny[i] * Y) / sd) ** two
        f = chi2 / float(n - 2)
        if not f > 1.0:
            f = 1.0
        c00, c01, c11 = c00 * f, c01 * f, c11 * f
    return _store(X, Y, c00, c01, c11, point, cov)


@kernel
def _store(X: float, Y: float, c00: float, c01: float, c11: float, point: np.ndarray,
           cov: np.ndarray) -> tuple[int, float]:
    """Write the point and the symmetric covariance; ``(status, sqrt(trace / 2))``."""
    point[0], point[1] = X, Y
    cov[0, 0], cov[0, 1], cov[1, 0], cov[1, 1] = c00, c01, c01, c11
    half = 0.5 * (c00 + c11)
    if half < 0.0:
        return SQRT_NEGATIVE, 0.0
    return FUSED, math.sqrt(half)


@kernel
def ranged_mean(px: np.ndarray, py: np.ndarray, ranges: np.ndarray, ux: np.ndarray,
                uy: np.ndarray, power: float, bearing_sigma: float, range_sigma_rel: float,
                two: float, point: np.ndarray, cov: np.ndarray) -> tuple[int, int, float]:
    """Step 4 of :func:`~estimators.fusion.sightings.fuse_sightings`: the mean of the
    ranged sightings' points ``p_i + R_i u_i`` [m] (the lines with a finite range ``R_i``,
    origins ``(px, py)``, unit directions ``(ux, uy)``) weighted by ``R_i^-power``, into
    ``point``; its covariance ``sum w_i^2 R_i^2 (b^2 I + (rel^2 - b^2) u u^T)`` [m^2]
    (``b`` = ``bearing_sigma`` [rad], ``rel`` = ``range_sigma_rel``), multiplied by
    ``max(1, chi^2 / (2 (m - 1)))`` for ``m >= 2`` points, into ``cov``. Returns
    ``(status, m, sigma)``."""
    n = px.shape[0]
    idx = np.empty(n, dtype=np.int64)
    m = 0
    for i in range(n):
        if math.isfinite(ranges[i]):
            idx[m] = i
            m += 1
    wq = np.empty(m)
    total = 0.0
    for j in range(m):
        wq[j] = ranges[idx[j]] ** -power
        total += wq[j]
    qx, qy = np.empty(m), np.empty(m)
    mx = my = 0.0
    for j in range(m):
        i = idx[j]
        wq[j] = wq[j] / total
        qx[j] = px[i] + ranges[i] * ux[i]
        qy[j] = py[i] + ranges[i] * uy[i]
    for j in range(m):
        mx += wq[j] * qx[j]
    for j in range(m):
        my += wq[j] * qy[j]
    b2, rel2 = bearing_sigma ** two, range_sigma_rel ** two
    # cov_i = r^2 (b^2 I + (rel^2 - b^2) u u^T); cov = sum w^2 cov_i.
    ci = np.empty((m, 3))
    c00 = c01 = c11 = 0.0
    for j in range(m):
        i = idx[j]
        w, r2, a, b = wq[j], ranges[i] ** two, ux[i], uy[i]
        d = rel2 - b2
        ci[j, 0], ci[j, 1], ci[j, 2] = r2 * (b2 + d * a * a), r2 * d * a * b, \
            r2 * (b2 + d * b * b)
        c00 += w * w * ci[j, 0]
        c01 += w * w * ci[j, 1]
        c11 += w * w * ci[j, 2]
    if m >= 2:
        chi2 = 0.0
        for j in range(m):
            s00, s01, s11 = ci[j, 0], ci[j, 1], ci[j, 2]
            ex, ey = qx[j] - mx, qy[j] - my
            chi2 += (s11 * ex * ex - 2.0 * s01 * ex * ey + s00 * ey * ey) / (
                s00 * s11 - s01 * s01)
        f = chi2 / (2.0 * float(m - 1))
        if not f > 1.0:
            f = 1.0
        c00, c01, c11 = c00 * f, c01 * f, c11 * f
    status, sigma = _store(mx, my, c00, c01, c11, point, cov)
    return status, m, sigma


@kernel
def _inverse_variance(X: float, Y: float, normal: tuple[float, float, float],
                      px: np.ndarray, py: np.ndarray, nx: np.ndarray, ny: np.ndarray,
                      rho: np.ndarray, k: np.ndarray, pose: tuple[float, float, float],
                      two: float, point: np.ndarray, cov: np.ndarray) -> tuple[int, float]:
    """Step 3 with ``weighting="inverse_variance"``: from the first fused point ``(X, Y)``
    (weights ``k``, normal matrix ``normal``), the offset variances
    ``s_i^2 = D_i^2 (bearing_sigma^2 + heading_sigma^2) + position_sigma^2`` (``pose`` =
    ``(bearing_sigma, position_sigma, heading_sigma)``) and the point fused again with
    ``K_i = 1 / s_i^2`` (the first one if those weights make the lines degenerate), with its
    covariance (:func:`crossing_covariance` with ``s_i`` as the lines' sigmas)."""
    bearing_sigma, position_sigma, heading_sigma = pose
    a = bearing_sigma * bearing_sigma + heading_sigma * heading_sigma
    c = position_sigma * position_sigma
    n = px.shape[0]
    kv, sig = np.empty(n), np.empty(n)
    _offset_sigmas(X, Y, px, py, a, c, two, sig)
    for i in range(n):
        kv[i] = 1.0 / sig[i]
        sig[i] = math.sqrt(sig[i])
    a11, a12, a22, b1, b2 = normal_sums(nx, ny, rho, kv)
    ok, X2, Y2 = solve_normal(a11, a12, a22, b1, b2)
    if not ok:
        return crossing_covariance(X, Y, normal[0], normal[1], normal[2], nx, ny, rho, k,
                                   sig, two, point, cov)
    _offset_sigmas(X2, Y2, px, py, a, c, two, sig)
    for i in range(n):
        sig[i] = math.sqrt(sig[i])
    return crossing_covariance(X2, Y2, a11, a12, a22, nx, ny, rho, kv, sig, two, point, cov)


@kernel
def _offset_sigmas(X: float, Y: float, px: np.ndarray, py: np.ndarray, a: float, c: float,
                   two: float, out: np.ndarray) -> None:
    """The offset variances ``max(((X - x)^2 + (Y - y)^2) a + c, MIN_OFFSET_VARIANCE)``
    [m^2] of the lines from ``(px, py)`` at the point ``(X, Y)`` into ``out``."""
    for i in range(px.shape[0]):
        v = ((X - px[i]) ** two + (Y - py[i]) ** two) * a + c
        out[i] = MIN_OFFSET_VARIANCE if MIN_OFFSET_VARIANCE > v else v


@kernel
def _crossing(X: float, Y: float, normal: tuple[float, float, float], px: np.ndarray,
              py: np.ndarray, nx: np.ndarray, ny: np.ndarray, rho: np.ndarray, k: np.ndarray,
              bearing_sigma: float, pose: tuple[float, float, float], inverse_variance: bool,
              two: float, point: np.ndarray, cov: np.ndarray) -> tuple[int, float]:
    """The crossing's result: :func:`_inverse_variance`, or :func:`crossing_covariance`
    with the sigmas ``bearing_sigma * D_i`` (``D_i`` line ``i``'s origin's distance to the
    point)."""
    if inverse_variance:
        return _inverse_variance(X, Y, normal, px, py, nx, ny, rho, k, pose, two, point, cov)
    sig = np.empty(px.shape[0])
    for i in range(px.shape[0]):
        sig[i] = bearing_sigma * hypot_exact(X - px[i], Y - py[i])
    return crossing_covariance(X, Y, normal[0], normal[1], normal[2], nx, ny, rho, k, sig,
                               two, point, cov)


@kernel
def fuse_line_rows(origins: np.ndarray, angles: np.ndarray, ranges: np.ndarray,
                   stamps: np.ndarray, shift: tuple[float, float, float, float],
                   settings: tuple[float, float, float, float, float, float, float, float],
                   point: np.ndarray, cov: np.ndarray) -> tuple[int, int, bool, float]:
    """Steps 1 to 5 of :func:`~estimators.fusion.sightings.fuse_sightings` over ``n`` lines:
    ``origins`` (n, 2) [m], ``angles`` (n,) [rad], ``ranges`` (n,) [m] (non-finite: bearing
    only); with ``shift`` ``(moved, now, vx, vy)`` and ``moved`` 1.0, every origin is first
    moved by ``v (now - stamps[i])`` (``stamps`` (n,) [s], else unused); ``settings``
    ``(bearing_sigma, range_sigma_rel, min_angle, position_sigma, heading_sigma,
    inverse_variance, power, two)``: weights ``K = R^-power``, ``inverse_variance`` 1.0 to
    fuse crossing lines again with their offsets' inverse variances, ``two`` 2.0 (module
    docstring). Writes ``point`` (2,) and ``cov`` (2, 2); returns ``(status, n_lines, fused,
    sigma)``, status :data:`FUSED`, :data:`NO_POSITION` or :data:`SQRT_NEGATIVE`."""
    n = origins.shape[0]
    bearing_sigma, range_sigma_rel, min_angle = settings[0], settings[1], settings[2]
    pose = (bearing_sigma, settings[3], settings[4])
    inverse_variance, power, two = settings[5] != 0.0, settings[6], settings[7]
    px, py, ux, uy = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    any_range = False
    far = 0.5
    first = True
    for i in range(n):
        px[i], py[i] = origins[i, 0], origins[i, 1]
        if shift[0] != 0.0:  # each line moved with the target since its stamp
            dt = shift[1] - stamps[i]
            px[i], py[i] = px[i] + dt * shift[2], py[i] + dt * shift[3]
        ux[i], uy[i] = math.cos(angles[i]), math.sin(angles[i])
        if math.isfinite(ranges[i]):
            any_range = True
            if first or ranges[i] > far:
                far, first = ranges[i], False
    # Line normals n = (cos theta, sin theta) = (-sin psi, cos psi), rho = p . n.
    far = 2.0 * far
    nx, ny, rho, k = -uy, ux, np.empty(n), np.empty(n)
    for i in range(n):
        rho[i] = px[i] * nx[i] + py[i] * ny[i]
        k[i] = (ranges[i] if math.isfinite(ranges[i]) else far) ** -power
    crossed, X, Y = False, 0.0, 0.0
    a11 = a12 = a22 = 0.0
    if n >= 2:
        a11, a12, a22, b1, b2 = normal_sums(nx, ny, rho, k)
        crossed, X, Y = solve_normal(a11, a12, a22, b1, b2)
        if crossed:
            e11, e12, e22, _, _ = normal_sums(nx, ny, rho, np.ones(n))
            if ((e11 * e22 - e12 * e12) / (e11 + e22) ** two
                    > 0.25 * math.sin(min_angle) ** two):
                status, sigma = _crossing(X, Y, (a11, a12, a22), px, py, nx, ny, rho, k,
                                          bearing_sigma, pose, inverse_variance, two,
                                          point, cov)
                return status, n, True, sigma
    if any_range:
        status, m, sigma = ranged_mean(px, py, ranges, ux, uy, power, bearing_sigma,
                                       range_sigma_rel, two, point, cov)
        return status, m, False, sigma
    if crossed:
        status, sigma = _crossing(X, Y, (a11, a12, a22), px, py, nx, ny, rho, k,
                                  bearing_sigma, pose, inverse_variance, two, point, cov)
        return status, n, True, sigma
    return NO_POSITION, 0, False, 0.0
