"""Fusion of a team's timestamped sightings of one target, with an error covariance for a
tracker (Xu, Xie, Wang and Ni 2012): the Hough-space fusion of :mod:`estimators.fusion.hough`
for lines seen at different times, some with an estimated range, some bearing-only
(:func:`fuse_sightings`; :func:`fuse_lines` without its checks, the pipelines' hot path)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ..checks import check_sigma
from .hough import (
    INVERSE_VARIANCE,
    MIN_CONDITION,
    MIN_CROSSING_ANGLE,
    weighting_power,
)

__all__ = ["FusedSighting", "fuse_sightings", "fuse_lines"]


class FusedSighting(NamedTuple):
    """The result of :func:`fuse_sightings`.

    Attributes:
        point: ``(2,)`` the fused target position (at time ``now``).
        n_lines: number of sightings used (all lines when ``fused``, else those with a range).
        fused: True for the Hough fusion of crossing lines, False for the weighted mean of
            the ranged point estimates.
        sigma: error scale, ``sqrt(trace(cov) / 2)`` (the RMS standard deviation per axis),
            in the positions' unit: a measurement sigma for a tracker.
        cov: ``(2, 2)`` error covariance of ``point`` (see :func:`fuse_sightings`).
    """

    point: np.ndarray
    n_lines: int
    fused: bool
    sigma: float
    cov: np.ndarray


def fuse_sightings(origins: np.ndarray | Sequence[Sequence[float]],
                   angles: np.ndarray | Sequence[float],
                   ranges: np.ndarray | Sequence[float],
                   stamps: np.ndarray | Sequence[float] | None = None,
                   now: float | None = None,
                   velocity: np.ndarray | Sequence[float] | None = None,
                   weighting: str = "inverse", *,
                   bearing_sigma: float = math.radians(3.0),
                   range_sigma_rel: float = 0.1,
                   min_angle: float = MIN_CROSSING_ANGLE,
                   position_sigma: float = 0.0,
                   heading_sigma: float = 0.0) -> FusedSighting:
    """Fuse a team's sightings of one target (the ball).

    Robot ``i`` at ``origins[i]`` saw the target along the field-frame direction ``angles[i]``
    [rad] at the estimated range ``ranges[i]`` (NaN, or any non-finite value: bearing only) at
    time ``stamps[i]`` [s].

    1. *Common time*: with ``velocity`` ``v`` (``(2,)``, the target's, e.g. a tracker's
       estimate) and ``stamps``, every sighting is moved by ``v (now - stamps[i])`` (the
       target moved since; ``now`` defaults to the latest stamp). Without either, no shift.
    2. *Weights* ``K_i = 1 / L_i^p`` (:func:`fusion_weights` with ``weighting``), ``L_i`` the
       range; a bearing-only sighting counts as twice the largest known range (all equal when
       none is known).
    3. *Hough fusion* (:func:`hough_fuse`) of all the lines when there are two or more that
       cross at ``min_angle`` [rad] or more (``det M0 / trace(M0)^2 > sin(min_angle)^2 / 4``
       with ``M0 = sum n n^T`` the unweighted normal matrix; for two lines this is their
       crossing angle). Error model: line ``i`` lies ``bearing_sigma * D_i`` off the target
       (standard deviation, ``D_i`` its origin's distance to the fused point), so with
       ``M = sum K n n^T`` the weighted least-squares point has covariance
       ``M^-1 (sum K^2 (bearing_sigma D)^2 n n^T) M^-1``, multiplied by
       ``max(1, chi^2 / (n - 2))`` when ``n >= 3`` lines disagree more than that
       (``chi^2 = sum e_i^2 / (bearing_sigma D_i)^2``, ``e_i`` the perpendicular residuals:
       poses worse than the model says).

       With ``weighting="inverse_variance"`` the lines are first fused with ``1 / L`` weights
       (as ``"inverse"``), then fused again with ``K_i = 1 / s_i^2``,
       ``s_i^2 = D_i^2 (bearing_sigma^2 + heading_sigma^2) + position_sigma^2`` at that first
       point (:func:`line_offset_variance`; ``position_sigma`` [m] per axis and
       ``heading_sigma`` [rad] the observers' pose errors), and ``s_i`` replaces
       ``bearing_sigma * D_i`` in the error model (the covariance is then ``M^-1``, times the
       same ``chi^2`` factor). ``position_sigma`` and ``heading_sigma`` apply to this
       weighting only.
    4. *Otherwise* (one line, or lines crossing at a shallower angle) the weighted mean
       ``sum K q / sum K`` of the point estimates ``q_i = origin_i + range_i (cos, sin)`` of
       the sightings that have a range, each with covariance
       ``range_i^2 (range_sigma_rel^2 u u^T + bearing_sigma^2 u_perp u_perp^T)`` (``u`` the
       line's direction), so ``cov = sum (K / sum K)^2 cov_i``, multiplied by
       ``max(1, chi^2 / (2 (m - 1)))`` when ``m >= 2`` points disagree more than that
       (``"inverse_variance"`` weights these points as ``"inverse"``).
    5. With no range either, lines that cross at a shallow angle but do cross are still
       fused (their covariance is then long along the lines).

    Returns:
        :class:`FusedSighting` ``(point, n_lines, fused, sigma, cov)``.

    Raises:
        ValueError: bad shapes or values, or no position (a single bearing-only sighting,
            or bearing-only lines that are parallel).

    Steps 1 to 5 are :func:`fuse_lines`, in plain floats on lists: the hot path (every
    camera frame of every robot, on a handful of lines), where numpy's per-call overhead
    would cost several times the arithmetic; a pipeline with checked data calls it directly.
    """
    p, psi, r, power, pose_sigmas, shift = _check_sightings(
        origins, angles, ranges, stamps, now, velocity, weighting, bearing_sigma,
        range_sigma_rel, min_angle, position_sigma, heading_sigma)
    if shift is not None:
        st, t_now, v = shift
        return fuse_lines(p.tolist(), psi.tolist(), r.tolist(), power, bearing_sigma,
                          range_sigma_rel, min_angle, st.tolist(), t_now,
                          (float(v[0]), float(v[1])), pose_sigmas=pose_sigmas)
    return fuse_lines(p.tolist(), psi.tolist(), r.tolist(), power, bearing_sigma,
                      range_sigma_rel, min_angle, pose_sigmas=pose_sigmas)


def _check_sightings(origins, angles, ranges, stamps, now, velocity, weighting: str,
                     bearing_sigma: float, range_sigma_rel: float, min_angle: float,
                     position_sigma: float, heading_sigma: float) -> tuple:
    """:func:`fuse_sightings`'s sightings and settings checked: ``(origins (n, 2), angles
    (n,), ranges (n,), power, pose_sigmas, shift)`` (``pose_sigmas`` only for
    ``"inverse_variance"``; ``shift`` ``(stamps (n,), now, velocity (2,))`` when both stamps
    and a velocity are given, else None); ``ValueError`` naming what is wrong."""
    p = np.asarray(origins, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) == 0:
        raise ValueError(f"origins must have shape (n, 2) with n >= 1, got {p.shape}")
    if not np.isfinite(p).all():
        raise ValueError("origins must be finite")
    n = len(p)
    psi = np.asarray(angles, dtype=np.float64)
    if psi.shape != (n,) or not np.isfinite(psi).all():
        raise ValueError(f"angles must be a finite ({n},) array, got {angles!r}")
    r = np.asarray(ranges, dtype=np.float64)
    if r.shape != (n,):
        raise ValueError(f"ranges must have shape ({n},), got {r.shape}")
    known = np.isfinite(r)
    if (r[known] <= 0.0).any():
        raise ValueError(f"ranges must be > 0 (or NaN for bearing only), got {ranges!r}")
    pose_sigmas: tuple[float, float] | None = None
    power = weighting_power(weighting)
    if weighting == INVERSE_VARIANCE:
        pose_sigmas = (check_sigma("position_sigma", position_sigma),
                       check_sigma("heading_sigma", heading_sigma))
    elif position_sigma != 0.0 or heading_sigma != 0.0:
            raise ValueError(f"position_sigma and heading_sigma apply to weighting "
                             f"'inverse_variance' only, not {weighting!r}")
    for name, value in (("bearing_sigma", bearing_sigma), ("range_sigma_rel", range_sigma_rel)):
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} must be finite and > 0, got {value!r}")
    if not 0.0 < min_angle <= 0.5 * math.pi:
        raise ValueError(f"min_angle must be in (0, pi/2], got {min_angle!r}")
    if velocity is None or stamps is None:
        return p, psi, r, power, pose_sigmas, None
    v = np.asarray(velocity, dtype=np.float64)
    if v.shape != (2,) or not np.isfinite(v).all():
        raise ValueError(f"velocity must be a finite (2,) vector, got {velocity!r}")
    st = np.asarray(stamps, dtype=np.float64)
    if st.shape != (n,) or not np.isfinite(st).all():
        raise ValueError(f"stamps must be a finite ({n},) array, got {stamps!r}")
    t_now = float(st.max()) if now is None else float(now)
    if not math.isfinite(t_now):
        raise ValueError(f"now must be finite, got {now!r}")
    return p, psi, r, power, pose_sigmas, (st, t_now, v)


def fuse_lines(P: list[list[float]], angles: list[float], R: list[float], power: float,
               bearing_sigma: float, range_sigma_rel: float, min_angle: float,
               stamps: list[float] | None = None, now: float = 0.0,
               velocity: tuple[float, float] | None = None, *,
               pose_sigmas: tuple[float, float] | None = None) -> FusedSighting:
    """Steps 1 to 5 of :func:`fuse_sightings` without its checks, on plain lists, for
    callers with validated data (a pipeline's own sighting lines): ``P`` the origins
    ``[x, y]`` [m], ``angles`` [rad], ``R`` the ranges [m] (NaN: bearing only, else > 0),
    ``power`` the weighting's (``K = 1 / L^power``); with ``stamps`` [s] and ``velocity``
    ``(vx, vy)`` [m/s], every origin is first moved by ``velocity (now - stamp)``. With
    ``pose_sigmas`` ``(position_sigma [m], heading_sigma [rad])``, crossing lines are fused
    again with the inverse variances of their offsets at the first fused point
    (``fuse_sightings(weighting="inverse_variance")``, which passes ``power`` 1); None (the
    default): ``K = 1 / L^power`` only.

    Raises:
        ValueError: no position (see :func:`fuse_sightings`).
    """
    # Plain floats: a handful of lines, where numpy's per-call overhead would cost several
    # times the arithmetic (this runs at every camera frame of every robot).
    if stamps is not None and velocity is not None:
        vx, vy = velocity  # each line moved with the target since its stamp
        P = [[x + (now - t) * vx, y + (now - t) * vy] for (x, y), t in zip(P, stamps)]
    n = len(P)
    ux = [math.cos(a) for a in angles]
    uy = [math.sin(a) for a in angles]
    has = [math.isfinite(v) for v in R]
    if n >= 2:
        far = 2.0 * max((v for v, h in zip(R, has) if h), default=0.5)
        k = [(v if h else far) ** -power for v, h in zip(R, has)]
        # Line normals n = (cos theta, sin theta) = (-sin psi, cos psi), rho = p . n.
        nx, ny = [-v for v in uy], ux
        rho = [x * a + y * b for (x, y), a, b in zip(P, nx, ny)]
        crossing = _solve_lines(nx, ny, rho, k)
        if crossing is not None:
            _, M0 = _solve_lines(nx, ny, rho, [1.0] * n, normal_only=True)
            a11, a12, a22 = M0
            if (a11 * a22 - a12 * a12) / (a11 + a22) ** 2 > 0.25 * math.sin(min_angle) ** 2:
                if pose_sigmas is not None:
                    return _crossing_inverse_variance(crossing, P, nx, ny, rho, k,
                                                      bearing_sigma, pose_sigmas)
                return _crossing(crossing, P, nx, ny, rho, k, bearing_sigma)
    if any(has):
        return _ranged_mean(P, R, ux, uy, has, power, bearing_sigma, range_sigma_rel)
    if n >= 2 and crossing is not None:
        if pose_sigmas is not None:
            return _crossing_inverse_variance(crossing, P, nx, ny, rho, k, bearing_sigma,
                                              pose_sigmas)
        return _crossing(crossing, P, nx, ny, rho, k, bearing_sigma)
    raise ValueError("no position: need two crossing lines or a sighting with a range, got "
                     f"{n} bearing-only sighting(s)" + (" (parallel)" if n > 1 else ""))


def _ranged_mean(P: list[list[float]], R: list[float], ux: list[float], uy: list[float],
                 has: list[bool], power: float, bearing_sigma: float, range_sigma_rel: float
                 ) -> FusedSighting:
    """Step 4 of :func:`fuse_sightings`: the weighted mean of the point estimates of the
    sightings that have a range (``has``), with its covariance."""
    n = len(P)
    idx = [i for i in range(n) if has[i]]
    kq = [R[i] ** -power for i in idx]
    total = sum(kq)
    wq = [v / total for v in kq]
    qx = [P[i][0] + R[i] * ux[i] for i in idx]
    qy = [P[i][1] + R[i] * uy[i] for i in idx]
    px_ = sum(w * x for w, x in zip(wq, qx))
    py_ = sum(w * y for w, y in zip(wq, qy))
    b2, rel2 = bearing_sigma**2, range_sigma_rel**2
    # cov_i = r^2 (b^2 I + (rel^2 - b^2) u u^T); cov = sum w^2 cov_i.
    c00 = c01 = c11 = 0.0
    covs = []
    for w, i in zip(wq, idx):
        r2, a, b = R[i] ** 2, ux[i], uy[i]
        d = rel2 - b2
        ci = (r2 * (b2 + d * a * a), r2 * d * a * b, r2 * (b2 + d * b * b))
        covs.append(ci)
        c00 += w * w * ci[0]
        c01 += w * w * ci[1]
        c11 += w * w * ci[2]
    m = len(idx)
    if m >= 2:
        chi2 = 0.0
        for (s00, s01, s11), x, y in zip(covs, qx, qy):
            ex, ey = x - px_, y - py_
            chi2 += (s11 * ex * ex - 2.0 * s01 * ex * ey + s00 * ey * ey) / (
                s00 * s11 - s01 * s01)
        f = max(1.0, chi2 / (2.0 * (m - 1)))
        c00, c01, c11 = c00 * f, c01 * f, c11 * f
    cov = np.array([[c00, c01], [c01, c11]])
    return FusedSighting(np.array([px_, py_]), m, False, math.sqrt(0.5 * (c00 + c11)), cov)


def _solve_lines(nx: list[float], ny: list[float], rho: list[float], k: list[float],
                 normal_only: bool = False):
    """:func:`~estimators.fusion.hough.hough_fuse`'s solve in plain floats: the weighted
    least-squares point ``(X, Y)`` and the normal matrix entries ``(a11, a12, a22)``; None
    when the lines are (nearly) parallel (with ``normal_only``, ``(None, (a11, a12, a22))``)."""
    a11 = a12 = a22 = b1 = b2 = 0.0
    for a, b, q, w in zip(nx, ny, rho, k):
        wa, wb = w * a, w * b
        a11 += wa * a
        a12 += wa * b
        a22 += wb * b
        b1 += wa * q
        b2 += wb * q
    if normal_only:
        return None, (a11, a12, a22)
    det = a11 * a22 - a12 * a12
    trace = a11 + a22
    if trace <= 0.0 or det <= MIN_CONDITION * trace * trace:
        return None
    return ((a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det), (a11, a12, a22)


#: The smallest offset variance [m^2] :func:`_crossing_inverse_variance` divides by (a line
#: whose origin is at the fused point, with no position error, would have none).
_MIN_OFFSET_VARIANCE = 1e-12


def _crossing_inverse_variance(crossing: tuple, P: list, nx: list[float], ny: list[float],
                               rho: list[float], k: list[float], bearing_sigma: float,
                               pose_sigmas: tuple[float, float]) -> FusedSighting:
    """Step 3 of :func:`fuse_sightings` with ``weighting="inverse_variance"``: from the first
    fused point ``crossing`` (weights ``k``), the offset variances
    ``s_i^2 = D_i^2 (bearing_sigma^2 + heading_sigma^2) + position_sigma^2`` and the point
    fused with ``K_i = 1 / s_i^2`` (the first one if those weights make the lines
    degenerate), with its covariance (:func:`_crossing` with ``s_i`` as the lines' sigmas)."""
    position_sigma, heading_sigma = pose_sigmas
    a = bearing_sigma * bearing_sigma + heading_sigma * heading_sigma
    c = position_sigma * position_sigma

    def variances(point: tuple[float, float]) -> list[float]:
        X, Y = point  # plain floats, as line_offset_variance's formula
        return [max(((X - x) ** 2 + (Y - y) ** 2) * a + c, _MIN_OFFSET_VARIANCE)
                for x, y in P]

    var = variances(crossing[0])
    kv = [1.0 / v for v in var]
    again = _solve_lines(nx, ny, rho, kv)
    if again is None:
        return _crossing(crossing, P, nx, ny, rho, k, bearing_sigma,
                         [math.sqrt(v) for v in var])
    return _crossing(again, P, nx, ny, rho, kv, bearing_sigma,
                     [math.sqrt(v) for v in variances(again[0])])


def _crossing(crossing: tuple, P: list, nx: list[float], ny: list[float], rho: list[float],
              k: list[float], bearing_sigma: float, sigmas: list[float] | None = None
              ) -> FusedSighting:
    """Step 3 of :func:`fuse_sightings`: the fused point with its covariance
    ``M^-1 (sum K^2 s^2 n n^T) M^-1``, inflated by ``chi^2 / (n - 2)`` for three or more
    lines that disagree more than the model says; ``s_i`` is ``bearing_sigma * D_i``, or
    ``sigmas[i]`` [m] when given."""
    (X, Y), (a11, a12, a22) = crossing
    det = a11 * a22 - a12 * a12
    i00, i01, i11 = a22 / det, -a12 / det, a11 / det  # M^-1
    s00 = s01 = s11 = 0.0
    # The lines' lateral standard deviations at the fused point.
    sig = [bearing_sigma * math.hypot(X - x, Y - y) for x, y in P] if sigmas is None \
        else sigmas
    for a, b, w, sd in zip(nx, ny, k, sig):
        g = (w * sd) ** 2
        s00 += g * a * a
        s01 += g * a * b
        s11 += g * b * b
    # cov = Minv S Minv (all symmetric 2 x 2).
    t00, t01 = i00 * s00 + i01 * s01, i00 * s01 + i01 * s11
    t10, t11 = i01 * s00 + i11 * s01, i01 * s01 + i11 * s11
    c00 = t00 * i00 + t01 * i01
    c01 = 0.5 * ((t00 * i01 + t01 * i11) + (t10 * i00 + t11 * i01))
    c11 = t10 * i01 + t11 * i11
    n = len(rho)
    if n >= 3:
        chi2 = sum(((q - a * X - b * Y) / max(sd, 1e-12)) ** 2
                   for q, a, b, sd in zip(rho, nx, ny, sig))
        f = max(1.0, chi2 / (n - 2))
        c00, c01, c11 = c00 * f, c01 * f, c11 * f
    cov = np.array([[c00, c01], [c01, c11]])
    return FusedSighting(np.array([X, Y]), n, True, math.sqrt(0.5 * (c00 + c11)), cov)
