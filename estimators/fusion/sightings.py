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
    MIN_CROSSING_ANGLE,
    weighting_power,
)
from .line_kernels import NO_POSITION, SQRT_NEGATIVE, fuse_line_rows

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

    Steps 1 to 5 are :func:`fuse_lines`, one compiled pass over the lines (the hot path:
    every camera frame of every robot, on a handful of lines); a pipeline with checked data
    calls it directly.
    """
    p, psi, r, power, pose_sigmas, shift = _check_sightings(
        origins, angles, ranges, stamps, now, velocity, weighting, bearing_sigma,
        range_sigma_rel, min_angle, position_sigma, heading_sigma)
    if shift is not None:
        st, t_now, v = shift
        return fuse_lines(p, psi, r, power, bearing_sigma, range_sigma_rel, min_angle, st,
                          t_now, (float(v[0]), float(v[1])), pose_sigmas=pose_sigmas)
    return fuse_lines(p, psi, r, power, bearing_sigma, range_sigma_rel, min_angle,
                      pose_sigmas=pose_sigmas)


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


def fuse_lines(P: list[list[float]] | np.ndarray, angles: list[float] | np.ndarray,
               R: list[float] | np.ndarray, power: float, bearing_sigma: float,
               range_sigma_rel: float, min_angle: float,
               stamps: list[float] | np.ndarray | None = None, now: float = 0.0,
               velocity: tuple[float, float] | None = None, *,
               pose_sigmas: tuple[float, float] | None = None) -> FusedSighting:
    """Steps 1 to 5 of :func:`fuse_sightings` without its checks, for callers with validated
    data (a pipeline's own sighting lines): ``P`` the origins ``[x, y]`` [m], ``angles``
    [rad], ``R`` the ranges [m] (NaN: bearing only, else > 0), as lists or arrays;
    ``power`` the weighting's (``K = 1 / L^power``); with ``stamps`` [s] and ``velocity``
    ``(vx, vy)`` [m/s], every origin is first moved by ``velocity (now - stamp)``. With
    ``pose_sigmas`` ``(position_sigma [m], heading_sigma [rad])``, crossing lines are fused
    again with the inverse variances of their offsets at the first fused point
    (``fuse_sightings(weighting="inverse_variance")``, which passes ``power`` 1); None (the
    default): ``K = 1 / L^power`` only.

    The maths is one compiled pass over the lines
    (:func:`~estimators.fusion.line_kernels.fuse_line_rows`): this runs at every camera
    frame of every robot, on a handful of lines.

    Raises:
        ValueError: no position (see :func:`fuse_sightings`).
    """
    p = np.ascontiguousarray(P, dtype=np.float64).reshape(-1, 2)
    n = len(p)
    psi = np.ascontiguousarray(angles, dtype=np.float64)
    if stamps is not None and velocity is not None:
        st = np.ascontiguousarray(stamps, dtype=np.float64)
        shift = (1.0, float(now), float(velocity[0]), float(velocity[1]))
    else:
        st, shift = psi, (0.0, 0.0, 0.0, 0.0)  # stamps unused
    position_sigma, heading_sigma = (0.0, 0.0) if pose_sigmas is None else pose_sigmas
    settings = (float(bearing_sigma), float(range_sigma_rel), float(min_angle),
                float(position_sigma), float(heading_sigma),
                0.0 if pose_sigmas is None else 1.0, float(power), 2.0)
    point, cov = np.empty(2), np.empty((2, 2))
    status, n_lines, fused, sigma = fuse_line_rows(
        p, psi, np.ascontiguousarray(R, dtype=np.float64), st, shift, settings, point, cov)
    if status == NO_POSITION:
        raise ValueError("no position: need two crossing lines or a sighting with a range, "
                         f"got {n} bearing-only sighting(s)" + (" (parallel)" if n > 1 else ""))
    if status == SQRT_NEGATIVE:
        raise ValueError("math domain error")
    return FusedSighting(point, n_lines, fused, sigma, cov)
