"""Hough-space fusion of several robots' sightings of one target (Xu, Xie, Wang and Ni 2012).

Robot ``i`` at ``p_i`` sees the target along the direction ``psi_i`` (its estimated heading
plus the sighting's bearing). The line ``L_i`` through ``p_i`` along ``psi_i`` maps to the point
``(theta_i, rho_i)`` of Hough space, with ``theta_i = psi_i + pi/2`` the angle of the line's
normal and ``rho_i = x_i cos(theta_i) + y_i sin(theta_i)``. All lines through the target
``(X, Y)`` lie on the sinusoid ``rho = X cos(theta) + Y sin(theta)``; with noisy sightings they
do not, and the fused target is the least-squares fit

    J = sum_i K_i (rho_i - X cos(theta_i) - Y sin(theta_i))^2,

with weights ``K_i = 1`` (the paper's equal weights), ``1 / L_i`` (its weighted version, ``L_i``
robot ``i``'s distance to the target) or ``1 / L_i^2``. ``rho_i - X cos(theta_i) -
Y sin(theta_i)`` is the signed distance from ``(X, Y)`` to line ``i``, so this is the point
that minimises the weighted sum of squared perpendicular distances to the lines, the solution
of the 2 x 2 normal equations

    [sum K c^2, sum K c s; sum K c s, sum K s^2] [X, Y]^T = [sum K c rho, sum K s rho]^T,

``c = cos(theta_i)``, ``s = sin(theta_i)``. Positions in metres (any unit works), angles in
radians. Closed form, written out here because it is three sums and a 2 x 2 solve.

**Which weights are right: inverse variance of each line's offset.** Write line ``i`` as
``n_i . x = rho_i`` (``n_i`` its unit normal) and let ``e_i = rho_i - n_i . b`` be its signed
perpendicular offset at the true target ``b``. The weighted least-squares point is
``x = M^-1 sum K n rho`` with ``M = sum K n n^T``, so (to first order in the errors, the
normals' own errors moving the point only at second order) ``x - b = M^-1 sum K_i n_i e_i``
and, for independent zero-mean offsets of variance ``s_i^2``,

    Cov(x) = M^-1 (sum K_i^2 s_i^2 n_i n_i^T) M^-1,

which the Gauss-Markov theorem minimises (in the positive semi-definite order) with
``K_i = 1 / s_i^2``, giving ``Cov(x) = (sum n n^T / s^2)^-1``; any common factor of the
weights cancels. A robot that believes it stands at ``p + dp`` (``dp`` its position error,
``sigma_p`` per axis), and sees the target at distance ``D`` along the direction
``psi + db + dh`` (``db`` the sighting's bearing error, ``sigma_b``; ``dh`` its heading error,
``sigma_h``), draws a line whose offset at the target is, to first order,
``e = -(D (db + dh) + n . dp)``, so

    s^2 = D^2 (sigma_b^2 + sigma_h^2) + sigma_p^2                          [m^2]

(bearing and heading errors turn the line about the robot, moving it by ``D`` times the
angle; a position error shifts it by its component along the normal). The weight
``K = 1 / s^2`` (``"inverse_variance"``, :func:`line_offset_variance`) is therefore

* equal weights when only positions err (``sigma_b = sigma_h = 0``; also when each robot's
  estimate of the target has isotropic noise of ``sigma`` per axis, whose component across
  the line is the offset: ``s = sigma``),
* ``1 / D^2`` (``"inverse_square"``) when only angles err (pose position exact),
* in between otherwise, and never ``1 / D`` exactly (the paper's weighting is optimal only
  for an offset variance growing like ``D``, which none of these errors gives).

A range error lies along the line and does not move it. ``D`` is the distance from the
robot to the target, which the fusion knows only through an estimate: :func:`fuse_sightings`
takes it at a first fused point (weights ``1 / L``) and fuses again.

:func:`fuse_sightings` wraps this for a team's timestamped sightings (some with an estimated
range, some bearing-only), moves them to a common time with a velocity estimate, falls back
to the ranged point estimates when the lines do not cross well, and estimates the fused
point's error covariance for a tracker.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ..registry import Registry

__all__ = ["hough_lines", "hough_fuse", "fusion_weights", "fuse_sightings", "fuse_lines",
           "line_offset_variance", "weighting_power", "FusedSighting", "FUSION_WEIGHTINGS",
           "INVERSE_VARIANCE", "WEIGHTING_NAMES", "MIN_CROSSING_ANGLE"]

#: Weightings of :func:`fusion_weights` and :func:`fuse_sightings` by name: the power ``p`` of
#: the distance in ``K_i = 1 / L_i^p``.
FUSION_WEIGHTINGS: Registry[int] = Registry("fusion weighting", [
    ("equal", 0,
     "equal weights: every robot's sighting line counts the same (the plain Hough fusion of "
     "Xu, Xie, Wang and Ni 2012)"),
    ("inverse", 1,
     "weights 1 / distance: a robot's sighting counts in inverse proportion to its distance "
     "from the target (the weighted fusion of Xu, Xie, Wang and Ni 2012)"),
    ("inverse_square", 2,
     "weights 1 / distance^2: near sightings dominate, as a bearing error's effect grows "
     "with the distance"),
])

#: The weighting that is not a power of the distance: ``K_i = 1 / s_i^2``, the inverse
#: variance of line ``i``'s perpendicular offset at the fused point,
#: ``s_i^2 = D_i^2 (bearing_sigma^2 + heading_sigma^2) + position_sigma^2`` (module
#: docstring). It needs the observers' error model, so it is accepted by
#: :func:`fusion_weights`, :func:`fuse_sightings` and (``pose_sigmas``) :func:`fuse_lines`,
#: but is not one of the distance powers of :data:`FUSION_WEIGHTINGS`.
INVERSE_VARIANCE = "inverse_variance"
#: Every weighting name :func:`fusion_weights` and :func:`fuse_sightings` accept.
WEIGHTING_NAMES: tuple[str, ...] = (*FUSION_WEIGHTINGS, INVERSE_VARIANCE)

#: The shallowest crossing at which :func:`fuse_sightings` intersects lines by default [rad].
MIN_CROSSING_ANGLE = math.radians(5.0)

#: Below this ratio of the normal matrix's eigenvalues the lines are taken as parallel (no
#: unique crossing point).
_MIN_CONDITION = 1e-9


def _directions(origins: np.ndarray, directions: np.ndarray | None,
                angles: np.ndarray | Sequence[float] | None) -> np.ndarray:
    """Direction angles ``psi_i`` [rad] from unit-free direction vectors or angles."""
    if (directions is None) == (angles is None):
        raise ValueError("give exactly one of directions ((n, 2) vectors) and angles ((n,) "
                         "radians)")
    n = len(origins)
    if angles is not None:
        psi = np.asarray(angles, dtype=np.float64)
        if psi.shape != (n,):
            raise ValueError(f"angles must have shape ({n},), got {psi.shape}")
    else:
        d = np.asarray(directions, dtype=np.float64)
        if d.shape != (n, 2):
            raise ValueError(f"directions must have shape ({n}, 2), got {d.shape}")
        if (np.hypot(d[:, 0], d[:, 1]) <= 0.0).any():
            raise ValueError("directions must be non-zero vectors")
        psi = np.arctan2(d[:, 1], d[:, 0])
    if not np.isfinite(psi).all():
        raise ValueError("directions/angles must be finite")
    return psi


def hough_lines(origins: np.ndarray | Sequence[Sequence[float]],
                directions: np.ndarray | None = None,
                angles: np.ndarray | Sequence[float] | None = None
                ) -> tuple[np.ndarray, np.ndarray]:
    """The Hough-space points ``(theta_i, rho_i)`` of the lines through ``origins`` ((n, 2))
    along ``directions`` ((n, 2) vectors) or ``angles`` ((n,) radians):
    ``theta = psi + pi/2``, ``rho = x cos(theta) + y sin(theta)``."""
    p = np.asarray(origins, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"origins must have shape (n, 2), got {p.shape}")
    if not np.isfinite(p).all():
        raise ValueError("origins must be finite")
    theta = _directions(p, directions, angles) + 0.5 * np.pi
    rho = p[:, 0] * np.cos(theta) + p[:, 1] * np.sin(theta)
    return theta, rho


def _check_sigma(name: str, value: float) -> float:
    """``value`` as a float if it is finite and >= 0, else ``ValueError`` naming ``name``."""
    v = float(value)
    if not (math.isfinite(v) and v >= 0.0):
        raise ValueError(f"{name} must be finite and >= 0, got {value!r}")
    return v


def line_offset_variance(distances: np.ndarray | Sequence[float], bearing_sigma: float,
                         position_sigma: float = 0.0, heading_sigma: float = 0.0
                         ) -> np.ndarray:
    """The variance [m^2] of each sighting line's perpendicular offset at the target,
    ``s_i^2 = D_i^2 (bearing_sigma^2 + heading_sigma^2) + position_sigma^2`` (first order;
    derivation in the module docstring).

    Args:
        distances: ``(n,)`` distances ``D_i`` [m] from each robot to the target, > 0.
        bearing_sigma: standard deviation of a sighting's bearing [rad], >= 0.
        position_sigma: standard deviation of an observer's position, per axis [m], >= 0.
        heading_sigma: standard deviation of an observer's heading [rad], >= 0.

    Raises:
        ValueError: bad distances, a negative or non-finite sigma, or all three sigmas zero
            (no error: every variance 0 and the weights undefined).
    """
    L = np.asarray(distances, dtype=np.float64)
    if L.ndim != 1 or not np.isfinite(L).all() or (L <= 0.0).any():
        raise ValueError(f"distances must be a 1-d array of positive finite numbers, got {L}")
    sb = _check_sigma("bearing_sigma", bearing_sigma)
    sp = _check_sigma("position_sigma", position_sigma)
    sh = _check_sigma("heading_sigma", heading_sigma)
    if sb == 0.0 and sp == 0.0 and sh == 0.0:
        raise ValueError("bearing_sigma, position_sigma and heading_sigma are all 0: at least "
                         "one must be > 0")
    return L * L * (sb * sb + sh * sh) + sp * sp


def fusion_weights(distances: np.ndarray | Sequence[float], weighting: str = "inverse", *,
                   bearing_sigma: float | None = None, position_sigma: float = 0.0,
                   heading_sigma: float = 0.0) -> np.ndarray:
    """``K_i = 1 / L_i^p`` for the distances ``L_i`` [m] from each robot to the target, with
    ``p`` = 0, 1, 2 for ``weighting`` ``"equal"``, ``"inverse"`` (the paper's weighted
    fusion), ``"inverse_square"`` (the names and powers of :data:`FUSION_WEIGHTINGS`); or,
    for ``"inverse_variance"``, ``K_i = 1 / s_i^2`` [1/m^2] with ``s_i^2`` the
    :func:`line_offset_variance` of the sigmas (``bearing_sigma`` [rad] required,
    ``position_sigma`` [m], ``heading_sigma`` [rad]), which apply to that weighting only."""
    if weighting == INVERSE_VARIANCE:
        if bearing_sigma is None:
            raise ValueError("weighting 'inverse_variance' needs bearing_sigma (>= 0, rad)")
        return 1.0 / line_offset_variance(distances, bearing_sigma, position_sigma,
                                          heading_sigma)
    power = weighting_power(weighting)
    if bearing_sigma is not None or position_sigma != 0.0 or heading_sigma != 0.0:
        raise ValueError(f"bearing_sigma, position_sigma and heading_sigma apply to weighting "
                         f"'inverse_variance' only, not {weighting!r}")
    L = np.asarray(distances, dtype=np.float64)
    if L.ndim != 1 or not np.isfinite(L).all() or (L <= 0.0).any():
        raise ValueError(f"distances must be a 1-d array of positive finite numbers, got {L}")
    return L ** -float(power)


def weighting_power(weighting: str) -> int:
    """The distance power ``p`` of ``K = 1 / L^p`` that :func:`fuse_lines` takes for
    ``weighting`` (a name of :data:`WEIGHTING_NAMES`): :data:`FUSION_WEIGHTINGS`' power, or 1
    for ``"inverse_variance"`` (its first pass, and its weights of ranged points when lines
    do not cross). ``ValueError`` naming the weightings for an unknown one."""
    if weighting == INVERSE_VARIANCE:
        return 1
    power = FUSION_WEIGHTINGS.get(weighting)
    if power is None:
        _unknown_weighting(weighting)
    return power


def _unknown_weighting(weighting: object) -> None:
    """Raise ``ValueError`` naming every weighting of :data:`WEIGHTING_NAMES`."""
    raise ValueError(f"weighting must be one of {list(WEIGHTING_NAMES)}, got {weighting!r}")


def hough_fuse(origins: np.ndarray | Sequence[Sequence[float]],
               directions: np.ndarray | None = None,
               angles: np.ndarray | Sequence[float] | None = None,
               weights: np.ndarray | Sequence[float] | None = None) -> np.ndarray:
    """The fused target ``(X, Y)`` of the sighting lines (see the module docstring).

    Args:
        origins: ``(n, 2)`` positions of the robots (the lines' origins).
        directions: ``(n, 2)`` vectors from each robot towards its sighting, or
        angles: ``(n,)`` their direction angles [rad] (exactly one of the two).
        weights: ``(n,)`` non-negative weights ``K_i`` (default: equal), e.g.
            :func:`fusion_weights` of the sighting distances.

    Returns:
        ``(2,)`` array, the point minimising the weighted squared distances to the lines.

    Raises:
        ValueError: bad shapes or values, fewer than two lines with positive weight, or
            lines (nearly) parallel, which have no unique crossing point.
    """
    theta, rho = hough_lines(origins, directions, angles)
    n = len(theta)
    if weights is None:
        k = np.ones(n)
    else:
        k = np.asarray(weights, dtype=np.float64)
        if k.shape != (n,):
            raise ValueError(f"weights must have shape ({n},), got {k.shape}")
        if not np.isfinite(k).all() or (k < 0.0).any():
            raise ValueError("weights must be finite and non-negative")
    if np.count_nonzero(k > 0.0) < 2:
        raise ValueError(f"need at least two lines with positive weight to fuse, got "
                         f"{np.count_nonzero(k > 0.0)}")
    point, _ = _solve(theta, rho, k, _MIN_CONDITION)
    if point is None:
        raise ValueError("the lines are (nearly) parallel: no unique crossing point")
    return point


def _solve(theta: np.ndarray, rho: np.ndarray, k: np.ndarray, min_condition: float
           ) -> tuple[np.ndarray | None, np.ndarray]:
    """The weighted least-squares point of the lines and the normal matrix
    ``M = sum K n n^T`` (``n = (cos theta, sin theta)``); the point is None when
    ``det M / trace(M)^2 <= min_condition`` (the lines (nearly) parallel)."""
    c, s = np.cos(theta), np.sin(theta)
    a11, a12, a22 = np.sum(k * c * c), np.sum(k * c * s), np.sum(k * s * s)
    b1, b2 = np.sum(k * c * rho), np.sum(k * s * rho)
    M = np.array([[a11, a12], [a12, a22]])
    det = a11 * a22 - a12 * a12
    trace = a11 + a22
    # det / trace^2 is the product over the square of the sum of the eigenvalues: near 0
    # when every line has (nearly) the same normal.
    if trace <= 0.0 or det <= min_condition * trace * trace:
        return None, M
    return np.array([(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det]), M


# ------------------------------------------------------------------------------------------
# A team's timestamped sightings
# ------------------------------------------------------------------------------------------


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

    Why one long function: it is a hot path (every camera frame of every robot, on a handful
    of lines), written in plain floats because numpy's per-call overhead cost several times
    the arithmetic; the checks, steps 1 to 5 and their shared intermediate lists stay in one
    frame so that no extra calls or argument passing are added to it.
    """
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
        pose_sigmas = (_check_sigma("position_sigma", position_sigma),
                       _check_sigma("heading_sigma", heading_sigma))
    elif position_sigma != 0.0 or heading_sigma != 0.0:
            raise ValueError(f"position_sigma and heading_sigma apply to weighting "
                             f"'inverse_variance' only, not {weighting!r}")
    for name, value in (("bearing_sigma", bearing_sigma), ("range_sigma_rel", range_sigma_rel)):
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} must be finite and > 0, got {value!r}")
    if not 0.0 < min_angle <= 0.5 * math.pi:
        raise ValueError(f"min_angle must be in (0, pi/2], got {min_angle!r}")
    if velocity is not None and stamps is not None:
        v = np.asarray(velocity, dtype=np.float64)
        if v.shape != (2,) or not np.isfinite(v).all():
            raise ValueError(f"velocity must be a finite (2,) vector, got {velocity!r}")
        st = np.asarray(stamps, dtype=np.float64)
        if st.shape != (n,) or not np.isfinite(st).all():
            raise ValueError(f"stamps must be a finite ({n},) array, got {stamps!r}")
        t_now = float(st.max()) if now is None else float(now)
        if not math.isfinite(t_now):
            raise ValueError(f"now must be finite, got {now!r}")
        return fuse_lines(p.tolist(), psi.tolist(), r.tolist(), power, bearing_sigma,
                          range_sigma_rel, min_angle, st.tolist(), t_now,
                          (float(v[0]), float(v[1])), pose_sigmas=pose_sigmas)
    return fuse_lines(p.tolist(), psi.tolist(), r.tolist(), power, bearing_sigma,
                      range_sigma_rel, min_angle, pose_sigmas=pose_sigmas)


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
    if n >= 2 and crossing is not None:
        if pose_sigmas is not None:
            return _crossing_inverse_variance(crossing, P, nx, ny, rho, k, bearing_sigma,
                                              pose_sigmas)
        return _crossing(crossing, P, nx, ny, rho, k, bearing_sigma)
    raise ValueError("no position: need two crossing lines or a sighting with a range, got "
                     f"{n} bearing-only sighting(s)" + (" (parallel)" if n > 1 else ""))


def _solve_lines(nx: list[float], ny: list[float], rho: list[float], k: list[float],
                 normal_only: bool = False):
    """:func:`_solve` in plain floats: the weighted least-squares point ``(X, Y)`` and the
    normal matrix entries ``(a11, a12, a22)``; None when the lines are (nearly) parallel
    (with ``normal_only``, ``(None, (a11, a12, a22))``)."""
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
    if trace <= 0.0 or det <= _MIN_CONDITION * trace * trace:
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
