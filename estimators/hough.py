"""Hough-space fusion of several robots' sightings of one target (paper 000, SPEC 1.1).

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
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["hough_lines", "hough_fuse", "fusion_weights", "WEIGHTINGS"]

#: Weightings of :func:`fusion_weights`: name -> power of the distance in ``K_i = 1 / L_i^p``.
WEIGHTINGS = {"equal": 0, "inverse": 1, "inverse_square": 2}

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
        if np.any(np.hypot(d[:, 0], d[:, 1]) <= 0.0):
            raise ValueError("directions must be non-zero vectors")
        psi = np.arctan2(d[:, 1], d[:, 0])
    if not np.all(np.isfinite(psi)):
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
    if not np.all(np.isfinite(p)):
        raise ValueError("origins must be finite")
    theta = _directions(p, directions, angles) + 0.5 * np.pi
    rho = p[:, 0] * np.cos(theta) + p[:, 1] * np.sin(theta)
    return theta, rho


def fusion_weights(distances: np.ndarray | Sequence[float], weighting: str = "inverse"
                   ) -> np.ndarray:
    """``K_i = 1 / L_i^p`` for the distances ``L_i`` [m] from each robot to the target, with
    ``p`` = 0, 1, 2 for ``weighting`` ``"equal"``, ``"inverse"`` (the paper's weighted
    fusion), ``"inverse_square"``."""
    if weighting not in WEIGHTINGS:
        raise ValueError(f"weighting must be one of {list(WEIGHTINGS)}, got {weighting!r}")
    L = np.asarray(distances, dtype=np.float64)
    if L.ndim != 1 or not np.all(np.isfinite(L)) or np.any(L <= 0.0):
        raise ValueError(f"distances must be a 1-d array of positive finite numbers, got {L}")
    return L ** -float(WEIGHTINGS[weighting])


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
        if not np.all(np.isfinite(k)) or np.any(k < 0.0):
            raise ValueError("weights must be finite and non-negative")
    if np.count_nonzero(k > 0.0) < 2:
        raise ValueError(f"need at least two lines with positive weight to fuse, got "
                         f"{np.count_nonzero(k > 0.0)}")
    c, s = np.cos(theta), np.sin(theta)
    a11, a12, a22 = np.sum(k * c * c), np.sum(k * c * s), np.sum(k * s * s)
    b1, b2 = np.sum(k * c * rho), np.sum(k * s * rho)
    det = a11 * a22 - a12 * a12
    trace = a11 + a22
    # det / trace^2 is the product over the square of the sum of the eigenvalues: near 0
    # when every line has (nearly) the same normal.
    if trace <= 0.0 or det <= _MIN_CONDITION * trace * trace:
        raise ValueError("the lines are (nearly) parallel: no unique crossing point")
    return np.array([(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det])
