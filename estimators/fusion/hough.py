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

:func:`~estimators.fusion.sightings.fuse_sightings` wraps this for a team's timestamped
sightings (some with an estimated range, some bearing-only), moves them to a common time with a
velocity estimate, falls back to the ranged point estimates when the lines do not cross well,
and estimates the fused point's error covariance for a tracker.

Two forms of the normal equations' sums remain, one solve: :func:`hough_fuse` (the array API,
any number of lines) sums with numpy (pairwise summation, which differs from a running sum in
the last bits from eight lines on), the compiled fusion of
:mod:`~estimators.fusion.line_kernels` sums in the lines' order; both solve with
:func:`~estimators.fusion.line_kernels.solve_normal`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..checks import MAX_COORDINATE, check_sigma
from ..registry import Registry
from .line_kernels import MIN_CONDITION, solve_normal

__all__ = ["hough_lines", "hough_fuse", "fusion_weights", "line_offset_variance",
           "weighting_power", "FUSION_WEIGHTINGS", "INVERSE_VARIANCE", "WEIGHTING_NAMES",
           "MIN_CROSSING_ANGLE", "MIN_CONDITION"]

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


#: The nearest a robot may be to what it sights [m]: closer, ``1 / L^p`` weights overflow.
MIN_DISTANCE = 1e-6


def _distances(distances: np.ndarray | Sequence[float]) -> np.ndarray:
    """``distances`` [m] as a 1-d array, each in [:data:`MIN_DISTANCE`,
    :data:`~estimators.checks.MAX_COORDINATE`]; ``ValueError`` otherwise."""
    L = np.asarray(distances, dtype=np.float64)
    if L.ndim != 1 or not (np.isfinite(L).all() and (L >= MIN_DISTANCE).all()
                           and (L <= MAX_COORDINATE).all()):
        raise ValueError(f"distances must be a 1-d array of finite numbers in "
                         f"[{MIN_DISTANCE:g}, {MAX_COORDINATE:g}] m, got {L}")
    return L


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
    L = _distances(distances)
    sb = check_sigma("bearing_sigma", bearing_sigma)
    sp = check_sigma("position_sigma", position_sigma)
    sh = check_sigma("heading_sigma", heading_sigma)
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
    L = _distances(distances)
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
    point = _solve(theta, rho, k)
    if point is None:
        raise ValueError("the lines are (nearly) parallel: no unique crossing point")
    return point


def _solve(theta: np.ndarray, rho: np.ndarray, k: np.ndarray) -> np.ndarray | None:
    """The weighted least-squares point of the lines (normals ``n = (cos theta,
    sin theta)``), None when the lines are (nearly) parallel: numpy's sums of the normal
    equations (pairwise, as for any number of lines), solved by
    :func:`~estimators.fusion.line_kernels.solve_normal`."""
    c, s = np.cos(theta), np.sin(theta)
    a11, a12, a22 = np.sum(k * c * c), np.sum(k * c * s), np.sum(k * s * s)
    b1, b2 = np.sum(k * c * rho), np.sum(k * s * rho)
    ok, x, y = solve_normal(float(a11), float(a12), float(a22), float(b1), float(b2))
    return np.array([x, y]) if ok else None
