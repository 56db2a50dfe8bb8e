"""Self-localization from the bearings of three known landmarks (Xu, Xie, Wang and Ni 2012).

A robot at ``R = (x, y)`` with heading ``theta`` measures the bearing ``phi_i`` of landmark
``P_i`` relative to its heading (counter-clockwise positive; with a panning head, the camera's
bearing plus the pan angle). Any two landmarks and ``R`` lie on a circle whose inscribed angle
at ``R`` is ``phi_j - phi_i`` (Xu et al.'s 2012 two circles through ``P1, P2`` and ``P2, P3``);
``R`` is the second intersection of those circles, and the heading follows from any bearing:
``theta = atan2(P_i - R) - phi_i`` (averaged over the three on the circle).

The intersection is computed with the ToTal algorithm (Pierlot and Van Droogenbroeck, IEEE
T-RO 2014), a closed form of exactly this two-circle construction that works in every landmark
order and avoids the paper's sign conventions; it is a handful of arithmetic operations, so
it is written out here.

Degenerate configurations are reported, not crashed on (:class:`Fix` with ``ok=False`` and a
``reason``):

* fewer than three landmarks: with two, the robot is anywhere on one circle;
* two bearings equal or opposite (the robot on the line through two landmarks): the inscribed
  angle is 0 or pi and its circle degenerates into that line;
* the robot on the circle through the three landmarks (or, for collinear landmarks, on their
  line): the two circles coincide.

**Ambiguous landmarks** (:func:`triangulate_sightings`): a robot sees *a* line corner or *a*
goal post of a colour, not which one, and a head-camera frame (51 degrees) rarely holds three
landmarks, so Xu et al. (2012) pans the head and combines the sightings of several frames. Given
sightings as points in the robot's present body frame (``(r cos b, r sin b)`` for range ``r``
and bearing ``b``; older frames' sightings moved by the odometry since) and each one's kind,
:func:`triangulate_sightings` tries the candidate assignments that a landmark table allows for
the best-spread triples of distinct sightings, triangulates each from the bearings alone, and
keeps the poses whose predicted sightings fit *all* the sightings best:

* an assignment is tried only if its landmarks' pairwise distances match the sightings'
  (``| |P_i - P_j| - |p_i - p_j| | <= 3 sqrt(sigma_i^2 + sigma_j^2) + 0.1 m``, ``p`` the
  body-frame points, ``sigma`` their range noise);
* geometry that is degenerate (reported by :func:`triangulate`) or nearly so is skipped: the
  position's standard deviation from bearing noise ``sigma_b``, ``sqrt(sum_i |dR/dphi_i|^2)
  sigma_b`` by finite differences, must be at most ``max_sigma``;
* a pose ``(x, y, theta)`` is scored by ``sum_j max(max_c l_jc, -floor^2 / 2)`` with
  ``l_jc = -((g_jc - r_j) / sigma_j)^2 / 2 - (wrap(a_jc - b_j) / sigma_b)^2 / 2``, ``g_jc``
  and ``a_jc`` the range and bearing of candidate ``c`` of sighting ``j``'s kind seen from the
  pose (nearest-neighbour association, as the particle filter's); it must explain at least
  three sightings within 3 sigma and lie inside ``bounds``;
* the poses within ``margin`` of the best score are kept (distinct by 0.3 m or 0.3 rad), best
  first: symmetric landmarks (the field turned by half a turn) give two poses of the same
  score, which only a landmark of known identity (a post's colour) tells apart.
"""

from __future__ import annotations

import itertools
import math
from collections import deque
from collections.abc import Hashable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..compiled import kernel

__all__ = ["Fix", "PoseHypotheses", "SightingMemory", "triangulate", "triangulate_sightings",
           "SEED_FAILURES", "append_sightings", "move_points"]

#: Below this |sin| of a bearing difference the two bearings are taken as parallel.
_MIN_SIN = 1e-9
#: Below this relative size of ToTal's determinant the circles are taken as the same.
_MIN_DET = 1e-12


@dataclass(frozen=True)
class Fix:
    """The result of :func:`triangulate`.

    Attributes:
        ok: whether ``position`` and ``heading`` are determined.
        position: ``(2,)`` robot position (NaN when not ``ok``) [m].
        heading: robot heading [rad] in ``(-pi, pi]`` (NaN when not ``ok``).
        reason: why not (empty when ``ok``).
    """

    ok: bool
    position: np.ndarray
    heading: float
    reason: str = ""


def _fail(reason: str) -> Fix:
    return Fix(False, np.full(2, np.nan), math.nan, reason)


def triangulate(landmarks: np.ndarray | Sequence[Sequence[float]],
                bearings: np.ndarray | Sequence[float]) -> Fix:
    """Position and heading of a robot from the bearings [rad] of three landmarks ((3, 2)
    positions [m]); see the module docstring. Raises ``ValueError`` only for malformed input
    (shapes, non-finite values); degenerate geometry gives ``Fix(ok=False, reason=...)``."""
    P = np.asarray(landmarks, dtype=np.float64)
    phi = np.asarray(bearings, dtype=np.float64)
    if P.ndim != 2 or P.shape[1] != 2 or phi.shape != (len(P),):
        raise ValueError(f"landmarks must have shape (n, 2) and bearings (n,), got {P.shape} "
                         f"and {phi.shape}")
    if not (np.isfinite(P).all() and np.isfinite(phi).all()):
        raise ValueError("landmarks and bearings must be finite")
    if len(P) < 3:
        return _fail(f"{len(P)} landmark(s): three are needed (with two the robot lies "
                     "anywhere on a circle through them)")
    if len(P) > 3:
        raise ValueError(f"triangulate takes exactly three landmarks, got {len(P)}")
    if np.min(np.hypot(*(P[[0, 1, 2]] - P[[1, 2, 0]]).T)) <= 0.0:
        return _fail("two landmarks coincide")
    pos, heading, code = _total(P[None], phi[None])
    if code[0] != _OK:
        return _fail(_REASONS[int(code[0])])
    return Fix(True, pos[0], float(heading[0]))


#: Why :func:`triangulate_sightings` found no pose: fewer than three distinct sightings; every
#: assignment that fits the sightings' distances degenerate or ill-conditioned; no assignment
#: fits (none passes the distance test, or no pose explains three sightings inside the
#: bounds).
SEED_FAILURES = ("too_few", "degenerate", "no_fit")
#: Two sightings of one kind whose ranges differ by less than this [m] (or two range sigmas)
#: and bearings by less than three bearing sigmas are one landmark.
_MERGE_M = 0.4
#: Poses scored against every sighting: the best this many against the triples' sightings.
_SHORTLIST = 32
#: Kept poses closer than this [m, rad] to a better one are the same pose.
_SAME_M, _SAME_RAD = 0.3, 0.3


@dataclass(frozen=True)
class PoseHypotheses:
    """The result of :func:`triangulate_sightings`.

    Attributes:
        poses: ``(H, 3)`` poses ``(x, y, theta)`` [m, m, rad], best score first (``H = 0``
            when none).
        sigmas: ``(H, 2)`` their standard deviations from the bearing noise: position (per
            axis) [m] and heading [rad].
        scores: ``(H,)`` their fit to all the sightings (log-likelihood up to a constant).
        reason: one of :data:`SEED_FAILURES` when ``H = 0``, else empty.
        sightings: the distinct sightings used (after merging repeats).
    """

    poses: np.ndarray
    sigmas: np.ndarray
    scores: np.ndarray
    reason: str = ""
    sightings: int = 0

    @property
    def ok(self) -> bool:
        """Whether any pose was found."""
        return len(self.poses) > 0


def _no_pose(reason: str, sightings: int) -> PoseHypotheses:
    return PoseHypotheses(np.zeros((0, 3)), np.zeros((0, 2)), np.zeros(0), reason, sightings)


def _wrap(a: np.ndarray | float) -> np.ndarray:
    return np.remainder(np.asarray(a) + math.pi, 2.0 * math.pi) - math.pi


#: :func:`_total`'s outcome codes, and :func:`triangulate`'s reasons for the failures.
_OK, _PARALLEL, _INCONSISTENT, _CIRCLE = 0, 1, 2, 3
_REASONS = {
    _PARALLEL: "two bearings are equal or opposite: the robot is on the line through two "
               "landmarks",
    _INCONSISTENT: "the bearings are inconsistent (no third circle)",
    _CIRCLE: "the robot is on the circle through the three landmarks (or on their line): "
             "the position is not determined",
}


def _total(P: np.ndarray, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """ToTal's closed form (see the module docstring) for ``A`` triples at once: ``P``
    ``(A, 3, 2)`` landmarks [m], ``phi`` ``(A, 3)`` bearings [rad]; positions ``(A, 2)``,
    headings ``(A,)`` and an outcome code per triple (``_OK``, or the first degenerate case
    met: ``_PARALLEL``, ``_INCONSISTENT``, ``_CIRCLE``; positions and headings of failed
    triples are meaningless). :func:`triangulate` is this for one triple."""
    x1, y1 = P[:, 0, 0], P[:, 0, 1]
    x2, y2 = P[:, 1, 0], P[:, 1, 1]
    x3, y3 = P[:, 2, 0], P[:, 2, 1]
    a1, a2, a3 = phi[:, 0], phi[:, 1], phi[:, 2]
    s12, s23 = np.sin(a2 - a1), np.sin(a3 - a2)
    code = np.where((np.abs(s12) >= _MIN_SIN) & (np.abs(s23) >= _MIN_SIN), _OK, _PARALLEL)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t12 = np.cos(a2 - a1) / s12
        t23 = np.cos(a3 - a2) / s23
        code = np.where((code == _OK) & ~(np.abs(t12 + t23) >= _MIN_SIN), _INCONSISTENT,
                        code)
        t31 = (1.0 - t12 * t23) / (t12 + t23)
        x1p, y1p, x3p, y3p = x1 - x2, y1 - y2, x3 - x2, y3 - y2
        x12, y12 = x1p + t12 * y1p, y1p - t12 * x1p
        x23, y23 = x3p - t23 * y3p, y3p + t23 * x3p
        x31, y31 = (x3p + x1p) + t31 * (y3p - y1p), (y3p + y1p) - t31 * (x3p - x1p)
        k31 = x1p * x3p + y1p * y3p + t31 * (x1p * y3p - x3p * y1p)
        det = (x12 - x23) * (y23 - y31) - (y12 - y23) * (x23 - x31)
        scale = np.maximum(np.max(np.abs(np.stack([x12, y12, x23, y23, x31, y31])), axis=0),
                           1e-300) ** 2
        xr = x2 + k31 * (y12 - y23) / det
        yr = y2 + k31 * (x23 - x12) / det
    code = np.where((code == _OK) & ~((np.abs(det) >= _MIN_DET * scale) & np.isfinite(xr)
                                      & np.isfinite(yr)), _CIRCLE, code)
    ok = code == _OK
    xr, yr = np.where(ok, xr, 0.0), np.where(ok, yr, 0.0)
    ang = np.arctan2(P[:, :, 1] - yr[:, None], P[:, :, 0] - xr[:, None]) - phi
    heading = np.arctan2(np.mean(np.sin(ang), axis=1), np.mean(np.cos(ang), axis=1))
    return np.column_stack([xr, yr]), heading, code


def triangulate_sightings(kinds: Sequence[Hashable], points: np.ndarray | Sequence[Sequence[float]],
                          table: Mapping[Hashable, np.ndarray], range_sigma: np.ndarray | float,
                          bearing_sigma: float,
                          bounds: tuple[float, float, float, float] | None = None, *,
                          max_sigma: float = 0.5, max_sightings: int = 8,
                          max_triples: int = 12, margin: float = 2.0, floor: float = 4.0,
                          max_hypotheses: int = 4) -> PoseHypotheses:
    """Poses of a robot from sightings of landmarks known by kind only (see the module
    docstring).

    Args:
        kinds: ``m`` kinds (keys of ``table``), one per sighting, oldest first (of two
            sightings of one landmark, the later is kept).
        points: ``(m, 2)`` the sightings in the robot's present body frame [m] (``x`` ahead).
        table: kind -> ``(M_k, 2)`` positions of the landmarks of that kind [m].
        range_sigma: the sightings' range noise [m] (``(m,)`` or one for all, > 0).
        bearing_sigma: the bearing noise [rad], > 0.
        bounds: ``(x_min, x_max, y_min, y_max)`` [m] the robot is in (None: anywhere).
        max_sigma: the largest position standard deviation [m] (> 0) of a triple's pose
            from the bearing noise; worse-conditioned triples are degenerate.
        max_sightings: the most recent distinct sightings used (>= 3).
        max_triples: triples tried, the best-spread bearings first (>= 1).
        margin: poses whose score is within this of the best are kept (>= 0).
        floor: a sighting no candidate explains costs ``floor^2 / 2`` (> 0).
        max_hypotheses: the most poses kept (>= 1).

    Raises ``ValueError`` for malformed input; a scene with no determinable pose gives a
    result with no poses and a ``reason`` of :data:`SEED_FAILURES`.
    """
    P, kinds, sr = _check_sightings(kinds, points, table, range_sigma, bearing_sigma,
                                    max_sigma, max_sightings, max_triples, margin, floor,
                                    max_hypotheses)
    keep = _distinct(kinds, P, sr, bearing_sigma)
    n_distinct = len(keep)
    if n_distinct < 3:
        return _no_pose("too_few", n_distinct)
    n_use = len(keep[:max_sightings])
    cands = [np.asarray(table[kinds[j]], dtype=np.float64).reshape(-1, 2) for j in keep]
    rng_all = np.hypot(P[keep, 0], P[keep, 1])
    brg_all = np.arctan2(P[keep, 1], P[keep, 0])
    sr_all = sr[keep]
    scores = _SightingScores(cands, rng_all, brg_all, sr_all, bearing_sigma, floor)
    found = _assignments(P, keep, cands, brg_all, sr_all, n_use, max_triples)
    if found is None:
        return _no_pose("no_fit", n_distinct)
    poses, sigmas = _conditioned_poses(*found, bearing_sigma, max_sigma)
    if not len(poses):
        return _no_pose("degenerate", n_distinct)
    return _best_poses(poses, sigmas, scores, n_use, n_distinct, bounds, margin,
                       max_hypotheses)


def _check_sightings(kinds: Sequence[Hashable], points, table: Mapping[Hashable, np.ndarray],
                     range_sigma, bearing_sigma: float, max_sigma: float, max_sightings: int,
                     max_triples: int, margin: float, floor: float, max_hypotheses: int
                     ) -> tuple[np.ndarray, tuple, np.ndarray]:
    """:func:`triangulate_sightings`'s arguments checked: ``(points (m, 2), kinds,
    range sigmas (m,))``; ``ValueError`` naming what is wrong."""
    P = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    kinds = tuple(kinds)
    m = len(kinds)
    if len(P) != m or not np.isfinite(P).all():
        raise ValueError(f"points must be finite with shape (m, 2) for m = {m} kinds, got "
                         f"{np.shape(points)}")
    sr = np.broadcast_to(np.asarray(range_sigma, dtype=np.float64), (m,))
    if not (np.isfinite(sr).all() and (sr > 0.0).all()):
        raise ValueError("range_sigma must be finite and > 0")
    if not (math.isfinite(bearing_sigma) and bearing_sigma > 0.0):
        raise ValueError(f"bearing_sigma must be finite and > 0, got {bearing_sigma!r}")
    if not max_sigma > 0.0:
        raise ValueError(f"max_sigma must be > 0, got {max_sigma!r}")
    if max_sightings < 3 or max_triples < 1 or max_hypotheses < 1:
        raise ValueError("need max_sightings >= 3, max_triples >= 1 and max_hypotheses >= 1, "
                         f"got {max_sightings}, {max_triples}, {max_hypotheses}")
    if not (margin >= 0.0 and floor > 0.0):
        raise ValueError(f"need margin >= 0 and floor > 0, got {margin!r}, {floor!r}")
    for k in set(kinds):
        if k not in table:
            raise ValueError(f"unknown landmark kind {k!r}; the table has "
                             f"{sorted(map(str, table))}")
    return P, kinds, sr


def _distinct(kinds: tuple, P: np.ndarray, sr: np.ndarray, bearing_sigma: float) -> list[int]:
    """The distinct sightings, newest first: a later sighting of the same kind within 3
    bearing sigmas and 2 range sigmas of an older one replaces it (one landmark seen
    twice)."""
    m = len(kinds)
    rng_in, brg_in = np.hypot(P[:, 0], P[:, 1]), np.arctan2(P[:, 1], P[:, 0])
    index: dict[Hashable, int] = {}
    codes = np.array([index.setdefault(k, len(index)) for k in kinds])
    same = ((codes[:, None] == codes[None, :])
            & (np.abs(_wrap(brg_in[:, None] - brg_in[None, :])) < 3.0 * bearing_sigma)
            & (np.abs(rng_in[:, None] - rng_in[None, :])
               < np.maximum(_MERGE_M, sr[:, None] + sr[None, :])))
    keep: list[int] = []
    for j in range(m - 1, -1, -1):
        if not same[j, keep].any():
            keep.append(j)
    return keep


class _SightingScores:
    """How well poses fit the distinct sightings (ranges ``r`` [m], bearings ``b`` [rad], range
    sigmas, newest first) given their candidates ``cands``: per sighting the best candidate's
    log-likelihood, floored at ``-floor^2 / 2``, summed."""

    def __init__(self, cands: list[np.ndarray], r: np.ndarray, b: np.ndarray,
                 sr: np.ndarray, bearing_sigma: float, floor: float) -> None:
        # Every candidate of every distinct sighting, contiguous per sighting.
        self.counts = counts = np.array([len(c) for c in cands])
        self.flat = np.concatenate(cands)
        self.starts = np.cumsum(counts) - counts
        self.r, self.b = np.repeat(r, counts), np.repeat(b, counts)
        self.s = np.repeat(sr, counts)
        self.bearing_sigma, self.floor = bearing_sigma, floor

    def __call__(self, poses: np.ndarray, upto: int) -> tuple[np.ndarray, np.ndarray]:
        """Fit of ``(A, 3)`` poses to the ``upto`` most recent distinct sightings, and how
        many of them each explains."""
        starts, counts, floor = self.starts, self.counts, self.floor
        n = int(starts[upto - 1] + counts[upto - 1])
        F, r, b, sg = self.flat[:n], self.r[:n], self.b[:n], self.s[:n]
        c, s = np.cos(poses[:, 2:3]), np.sin(poses[:, 2:3])
        dx, dy = F[None, :, 0] - poses[:, 0:1], F[None, :, 1] - poses[:, 1:2]
        g = np.hypot(dx, dy)
        a = np.arctan2(-s * dx + c * dy, c * dx + s * dy)
        lik = -0.5 * ((g - r) / sg) ** 2 - 0.5 * (_wrap(a - b) / self.bearing_sigma) ** 2
        best = np.maximum.reduceat(lik, starts[:upto], axis=1)  # (A, upto)
        return (np.maximum(best, -0.5 * floor * floor).sum(axis=1),
                (best >= -4.5).sum(axis=1))


def _assignments(P: np.ndarray, keep: list[int], cands: list[np.ndarray], brg_all: np.ndarray,
                 sr_all: np.ndarray, n_use: int, max_triples: int
                 ) -> tuple[np.ndarray, np.ndarray] | None:
    """Triples of the ``n_use`` most recent distinct sightings, the best-spread bearings first
    (the smallest |sin| of their bearing differences largest), and for each the candidate
    assignments whose pairwise landmark distances match the sightings' distances: the
    landmarks ``(A, 3, 2)`` [m] and bearings ``(A, 3)`` [rad], or None when none match."""
    triples = list(itertools.combinations(range(n_use), 3))
    spread = [min(abs(math.sin(brg_all[a] - brg_all[b])) for a, b in
                  ((t[0], t[1]), (t[1], t[2]), (t[0], t[2]))) for t in triples]
    order = sorted(range(len(triples)), key=lambda i: -spread[i])[:max_triples]
    Ls: list[np.ndarray] = []
    phis: list[np.ndarray] = []
    for ti in order:
        t = triples[ti]
        C = [cands[i] for i in t]
        p = P[[keep[i] for i in t]]
        ok = np.ones((len(C[0]), len(C[1]), len(C[2])), dtype=bool)
        for a, b, axis in ((0, 1, 2), (1, 2, 0), (0, 2, 1)):  # axis: the one left out
            d_obs = math.hypot(*(p[a] - p[b]))
            tol = 3.0 * math.hypot(sr_all[t[a]], sr_all[t[b]]) + 0.1
            d = np.hypot(C[a][:, None, 0] - C[b][None, :, 0],
                         C[a][:, None, 1] - C[b][None, :, 1])
            ok &= np.expand_dims((np.abs(d - d_obs) <= tol) & (d > 0.0), axis)
        i0, i1, i2 = np.nonzero(ok)
        if len(i0):
            Ls.append(np.stack([C[0][i0], C[1][i1], C[2][i2]], axis=1))  # (A, 3, 2)
            phis.append(np.broadcast_to(brg_all[list(t)], (len(i0), 3)))
    if not Ls:
        return None
    return np.concatenate(Ls), np.concatenate(phis)


def _conditioned_poses(L: np.ndarray, phi: np.ndarray, bearing_sigma: float, max_sigma: float
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The poses ``(k, 3)`` triangulated from landmarks ``L`` and bearings ``phi`` that are
    determined and well-conditioned (each with one bearing moved by one sigma, the position
    moves by at most ``max_sigma``), and their position and heading standard deviations
    ``(k, 2)``."""
    eye = np.vstack([np.zeros(3), np.eye(3)]) * bearing_sigma
    pos, head, code = _total(np.repeat(L, 4, axis=0),
                             (phi[:, None, :] + eye[None, :, :]).reshape(-1, 3))
    pos, head, fine = pos.reshape(-1, 4, 2), head.reshape(-1, 4), (code == _OK).reshape(-1, 4)
    d2 = np.sum((pos[:, 1:] - pos[:, :1]) ** 2, axis=(1, 2))
    sig_pos = np.where(fine.all(axis=1), np.sqrt(0.5 * d2), np.inf)
    well = sig_pos <= max_sigma  # determined and well-conditioned
    if not well.any():
        return np.zeros((0, 3)), np.zeros((0, 2))
    sig_head = np.sqrt(np.sum(_wrap(head[well, 1:] - head[well, :1]) ** 2, axis=1))
    sig_pos = sig_pos[well]
    poses = np.column_stack([pos[well, 0], head[well, 0]])
    return poses, np.column_stack([sig_pos, sig_head])


def _best_poses(poses: np.ndarray, sigmas: np.ndarray, score: _SightingScores, n_use: int,
                n_distinct: int, bounds: tuple[float, float, float, float] | None,
                margin: float, max_hypotheses: int) -> PoseHypotheses:
    """Of the candidate ``poses`` (with ``sigmas``), those within ``bounds`` scored against
    the triples' sightings first, then the best few against all; those within ``margin`` of
    the best kept, at most ``max_hypotheses``, none twice."""
    good = np.ones(len(poses), dtype=bool)
    if bounds is not None:
        good &= ((bounds[0] <= poses[:, 0]) & (poses[:, 0] <= bounds[1])
                 & (bounds[2] <= poses[:, 1]) & (poses[:, 1] <= bounds[3]))
    sc = np.full(len(poses), -np.inf)
    sc_use, explained = score(poses[good], n_use)
    sc[good] = np.where(explained >= 3, sc_use, -np.inf)
    short = np.argsort(-sc, kind="stable")[:_SHORTLIST]
    short = short[np.isfinite(sc[short])]
    if not len(short):
        return _no_pose("no_fit", n_distinct)
    sc = np.full(len(poses), -np.inf)
    sc[short] = score(poses[short], n_distinct)[0]
    good = np.isfinite(sc)
    best_first = np.flatnonzero(good)[np.argsort(-sc[good], kind="stable")]
    top = sc[best_first[0]]
    kept: list[int] = []
    for i in best_first:
        if sc[i] < top - margin or len(kept) >= max_hypotheses:
            break
        if any(math.hypot(poses[i, 0] - poses[k, 0], poses[i, 1] - poses[k, 1]) < _SAME_M
               and abs(math.remainder(poses[i, 2] - poses[k, 2], 2.0 * math.pi)) < _SAME_RAD
               for k in kept):
            continue
        kept.append(int(i))
    return PoseHypotheses(poses[kept], sigmas[kept], sc[kept], "", n_distinct)


class SightingMemory:
    """The landmark sightings of the last ``frames`` frames, kept in the robot's present body
    frame by moving them with the odometry (Xu et al. 2012 pans the head and combines several
    frames' sightings, its 51-degree view rarely holding three landmarks).

    A sighting at range ``r`` and bearing ``b`` is the body-frame point ``p = r (cos b,
    sin b)``. A move by the body-frame displacement ``(dx, dy, dtheta)``, applied at the
    mid-step heading (:meth:`~estimators.KLDLocalizer.predict`'s convention: the robot moves by
    ``t = Rot(dtheta / 2) (dx, dy)`` in its old frame and turns by ``dtheta``), takes every
    point to ``p' = Rot(-dtheta) (p - t)``. The odometry's errors are not modelled, so keep
    ``frames`` to a second or two of walking.

    Args:
        frames: how many frames of sightings are kept (1..1000).
    """

    def __init__(self, frames: int) -> None:
        if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)) or not (
                1 <= frames <= 1000):
            raise ValueError(f"frames must be an integer in [1, 1000], got {frames!r}")
        self.frames = int(frames)
        # Every frame's kinds and how many sightings it has, oldest first, and all their
        # points in one (m, 2) array in the same order, so that a move is one kernel call.
        self._kinds: deque[tuple[Hashable, ...]] = deque()
        self._points = np.zeros((0, 2))

    def __len__(self) -> int:
        """The sightings kept (over all frames)."""
        return len(self._points)

    def clear(self) -> None:
        """Forget every sighting."""
        self._kinds.clear()
        self._points = np.zeros((0, 2))

    def add(self, kinds: Sequence[Hashable], ranges: np.ndarray, bearings: np.ndarray) -> None:
        """One frame's sightings: kinds, ranges [m] and bearings [rad, relative to the
        heading] (``(m,)`` each; an empty frame still counts as a frame)."""
        r = np.asarray(ranges, dtype=np.float64).reshape(-1)
        b = np.asarray(bearings, dtype=np.float64).reshape(-1)
        kinds = tuple(kinds)
        drop = len(self._kinds[0]) if len(self._kinds) == self.frames else 0
        points = (append_sightings(self._points, drop, r, b)
                  if len(kinds) == len(r) == len(b) else None)
        if points is None:
            raise ValueError(f"kinds ({len(kinds)}), ranges {r.shape} and bearings {b.shape} "
                             f"must match and be finite")
        if len(self._kinds) == self.frames:
            self._kinds.popleft()
        self._kinds.append(kinds)
        self._points = points

    def move(self, odometry: np.ndarray | Sequence[float]) -> None:
        """Move the kept sightings into the frame reached by the body-frame displacement
        ``(dx, dy, dtheta)`` [m, m, rad] (mid-step convention, see the class docstring)."""
        dx, dy, dth = (float(v) for v in odometry)
        if not len(self._points) or (dx == 0.0 and dy == 0.0 and dth == 0.0):
            return
        move_points(self._points, dx, dy, dth)

    def sightings(self) -> tuple[tuple[Hashable, ...], np.ndarray]:
        """Every kept sighting, oldest first: kinds and ``(m, 2)`` present body-frame points
        [m]."""
        kinds: tuple[Hashable, ...] = ()
        for k in self._kinds:
            kinds += k
        return kinds, self._points.copy()


@kernel
def append_sightings(points: np.ndarray, drop: int, ranges: np.ndarray,
                     bearings: np.ndarray) -> np.ndarray | None:
    """The body-frame points ``points[drop:]`` ((m, 2) [m]) followed by the sightings at
    ``ranges`` [m] and ``bearings`` [rad] (``(k,)`` each), ``r (cos b, sin b)``, as a new
    array; None if a range or bearing is not finite."""
    k = ranges.shape[0]
    for i in range(k):
        if not (math.isfinite(ranges[i]) and math.isfinite(bearings[i])):
            return None
    keep = points.shape[0] - drop
    out = np.empty((keep + k, 2))
    for i in range(keep):  # a loop, not a slice: a slice assignment costs seconds to compile
        out[i, 0] = points[drop + i, 0]
        out[i, 1] = points[drop + i, 1]
    for i in range(k):
        out[keep + i, 0] = ranges[i] * math.cos(bearings[i])
        out[keep + i, 1] = ranges[i] * math.sin(bearings[i])
    return out


@kernel
def move_points(points: np.ndarray, dx: float, dy: float, dth: float) -> None:
    """Body-frame points ``p`` ((m, 2) [m], in place) into the frame reached by the
    displacement ``(dx, dy, dtheta)`` at the mid-step heading: ``p' = Rot(-dtheta) (p -
    t)``, ``t = Rot(dtheta / 2) (dx, dy)`` (:class:`SightingMemory`). A kernel: a memory
    moves at every odometry step of every robot."""
    ch, sh = math.cos(0.5 * dth), math.sin(0.5 * dth)
    tx, ty = ch * dx - sh * dy, sh * dx + ch * dy
    c, s = math.cos(dth), math.sin(dth)
    for i in range(points.shape[0]):
        px, py = points[i, 0] - tx, points[i, 1] - ty
        points[i, 0] = px * c + py * s
        points[i, 1] = py * c - px * s
