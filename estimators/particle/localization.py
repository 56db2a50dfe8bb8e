"""Adaptive particle-filter self-localization with KLD-sampling (Guo and Li 2013).

State ``(x, y, theta)`` in the field frame [m, m, rad]; particles ``(N, 3)``.

* **Motion** (:meth:`KLDLocalizer.predict`): the odometry's body-frame displacement
  ``(dx, dy, dtheta)`` since the last call (from wheel encoders, as in Guo and Li (2013), or a walk
  engine), applied to every particle in its own frame with Gaussian noise whose standard
  deviation grows with the motion: ``sigma_xy = a_trans * |d| + a_rot_xy * |dtheta|`` and
  ``sigma_theta = a_rot * |dtheta| + a_trans_theta * |d|`` (turning slips most, as Guo and Li (2013)
  observed).
* **Observation** (:meth:`KLDLocalizer.update`): each sighted landmark of known position gives a
  measured range and bearing; ``p(z | chi) = N(range; g(chi), sigma_r^2) N(bearing; b(chi),
  sigma_b^2)`` multiplied over the landmarks (Guo and Li 2013 uses the range term only; the bearing
  term is optional, ``sigma_bearing=None`` turns it off), with ``sigma_r`` growing with the
  range (``sigma_r = range_sigma + range_sigma_rel * range + range_sigma_quad * range^2``:
  stereo depth error grows linearly, a monocular ground projection's with the square of the
  distance).
* **Ambiguous landmarks** (:meth:`KLDLocalizer.update_kinds`): a robot often sees *a* line
  corner or *a* goal post without knowing which. Each observation then names a kind, the field
  a table of the candidate positions of every kind, and each particle associates every
  observation with the candidate of its kind that explains it best (the largest likelihood:
  nearest-neighbour data association per particle, the usual RoboCup approach),
  ``log p(z_j | chi) = max_c log N(z_j; g_c(chi), Sigma)``. Particles in a symmetric
  position (the field turned by 180 degrees) explain the same observations equally well, so
  with symmetric landmarks alone the belief can settle on the mirror pose; a known start or
  a landmark of known identity must break the tie (the motion cannot: it looks the same from
  both).
* **Resampling by KLD-sampling** (Fox 2003): particles are drawn from the weighted set until
  ``n >= (k - 1) / (2 eps) * (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1))) z_{1-delta})^3``,
  ``k`` the number of histogram bins (``bin_size``) holding at least one drawn particle, between
  ``min_particles`` and ``max_particles``: many particles while the belief is spread, few once it
  has converged. Drawn in random order (multinomial), so every prefix is a fair sample. Where
  the bins are counted (``KLDConfig.binning``): ``"resampled"`` (the default, ours) resamples
  right after each measurement update and counts the bins of the drawn particles, before the
  next motion; ``"predicted"`` is Fox's KLD-sampling as published (Fox 2003, Table 1): the
  measurement update only weighs, and the next :meth:`~KLDLocalizer.predict` draws each
  particle from the weighted set, moves it by the motion model and counts the bin of the
  *predicted* sample, so the sample size follows the spread after the motion noise is added
  (larger by the motion's spread). ``soccer-env paper localization`` measures both.
* **Recovery** (augmented MCL, Thrun et al. 2005, section 8.3.5): short- and long-term averages
  ``w_fast``, ``w_slow`` of the observation likelihood per landmark (the geometric mean over
  the landmarks seen, so that landmarks entering or leaving the view do not look like a
  surprise); when the short-term one falls below ``recovery_ratio`` times the long-term one
  (the robot was picked up and placed elsewhere, or the belief is wrong), a fraction
  ``max(0, 1 - w_fast / (recovery_ratio w_slow))`` of the new particles is drawn uniformly
  over the field (``recovery_ratio = 1`` is the textbook rule, which also fires on ordinary
  fluctuations).
* **Recovery seed** (``recovery="triangulate"``, Xu et al.'s (2012) three-landmark self-localization
  put to use): the sightings of the last ``seed_memory`` updates are kept in the robot's body
  frame, moved by the odometry (:class:`~estimators.fusion.triangulation.SightingMemory`);
  when particles are injected, pose hypotheses are triangulated from them
  (:func:`~estimators.fusion.triangulation.triangulate_sightings`: the bearings of three
  landmarks, the candidate assignments the landmark kinds allow, the poses that fit every
  sighting best, degenerate geometry skipped), and a share ``seed_fraction`` of the injected
  particles is drawn around them, ``N(pose, diag(s_xy^2, s_xy^2, s_theta^2))`` with ``s_xy =
  max(0.1 m, sigma_pos)``, ``s_theta = max(0.05 rad, sigma_heading)`` (the hypothesis' own
  standard deviations from the bearing noise), a hypothesis picked uniformly per particle;
  the rest are uniform as before. With no hypothesis (fewer than three distinct landmarks,
  degenerate geometry, no fitting assignment) every injected particle is uniform. The
  default ``recovery="uniform"`` is the textbook rule alone, draw for draw.

Written here because KLD-sampling's variable sample size and the recovery bookkeeping are the
paper's method, not a library's; the arithmetic over the particles in compiled kernels
(:mod:`estimators.particle.localization_kernels`); every draw from the given generator.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..checks import MAX_COORDINATE, MAX_PARTICLES, check_count, check_real, check_reals
from ..fusion.triangulation import PoseHypotheses, SightingMemory, triangulate_sightings
from .kld import kld_table
from .landmarks import LandmarkTable
from .localization_kernels import (
    best_log_likelihood,
    draw_rows,
    kld_sample_count,
    move_particles,
    weigh,
    weighted_pose,
    weighted_spread,
)

__all__ = ["KLDConfig", "KLDLocalizer", "RECOVERIES", "MAX_ODOMETRY", "seed_poses"]

#: The largest odometry step a localizer takes, per entry (metres or radians): a robot moves
#: centimetres between updates; a step of a kilometre is corrupt data.
MAX_ODOMETRY = 1e3

#: How :class:`KLDLocalizer` draws the particles it injects when it is lost: uniformly over
#: the bounds (augmented MCL), or partly around poses triangulated from recent sightings.
RECOVERIES = ("uniform", "triangulate")
#: The least spread of a triangulated seed: position [m] and heading [rad].
_SEED_MIN_XY, _SEED_MIN_THETA = 0.1, 0.05
#: The bearing noise the seed assumes when the filter leaves bearings out [rad].
_SEED_BEARING_SIGMA = math.radians(5.0)

#: The smallest KLD ``delta``: ``1 - delta`` must differ from 1 (its normal quantile).
MIN_DELTA = 1e-12


def seed_poses(kinds: Sequence[str], points: np.ndarray, table: Mapping[str, np.ndarray],
               config: KLDConfig, bounds: tuple[float, float, float, float] | None = None
               ) -> PoseHypotheses:
    """:func:`~estimators.fusion.triangulation.triangulate_sightings` of body-frame sightings
    ``points`` ((m, 2) [m]) of ``kinds`` with the localization's noise model ``config``: each
    sighting's range sigma as in the likelihood (:meth:`KLDConfig.range_sigmas`), the bearing
    sigma ``bearing_sigma`` (5 degrees when bearings are left out)."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    sigma_b = (config.bearing_sigma if config.bearing_sigma is not None
               else _SEED_BEARING_SIGMA)
    return triangulate_sightings(kinds, pts, table, config.range_sigmas(np.hypot(
        pts[:, 0], pts[:, 1])), sigma_b, bounds)


@dataclass(frozen=True)
class KLDConfig:
    """Settings of :class:`KLDLocalizer` (SI units, radians).

    Attributes:
        min_particles, max_particles: bounds of the adaptive sample size.
        epsilon, delta: KLD-sampling's error bound and confidence (Fox 2003: 0.05, 0.01).
        bin_size: histogram bins ``(m, m, rad)``.
        a_trans, a_rot_xy, a_rot, a_trans_theta: odometry noise (see the module docstring).
        range_sigma, range_sigma_rel, range_sigma_quad: range noise ``sigma_r = range_sigma
            + range_sigma_rel * range + range_sigma_quad * range^2`` [m, 1, 1/m].
        bearing_sigma: bearing noise [rad]; None leaves bearings out (Guo and Li 2013: ranges only).
        alpha_slow, alpha_fast: averaging rates of the recovery's likelihood averages
            (``0 <= alpha_slow < alpha_fast <= 1``; ``alpha_fast = 0`` turns recovery off).
        recovery_ratio: how far (``0 < ratio <= 1``) the short-term average must fall below
            the long-term one before particles are injected.
        binning: where KLD-sampling counts its bins: ``"resampled"`` (ours, the default) or
            ``"predicted"`` (Fox 2003), see the module docstring.
    """

    min_particles: int = 50
    max_particles: int = 5000
    epsilon: float = 0.05
    delta: float = 0.01
    bin_size: tuple[float, float, float] = (0.2, 0.2, math.radians(15.0))
    a_trans: float = 0.1
    a_rot_xy: float = 0.02
    a_rot: float = 0.2
    a_trans_theta: float = 0.05
    range_sigma: float = 0.05
    range_sigma_rel: float = 0.05
    range_sigma_quad: float = 0.0
    bearing_sigma: float | None = math.radians(5.0)
    alpha_slow: float = 0.01
    alpha_fast: float = 0.2
    recovery_ratio: float = 0.5
    binning: str = "resampled"

    #: Where KLD-sampling counts its bins (see the module docstring).
    BINNINGS = ("resampled", "predicted")

    def range_sigmas(self, r: np.ndarray) -> np.ndarray:
        """The range noise ``sigma_r = range_sigma + range_sigma_rel r + range_sigma_quad r^2``
        [m] of sightings at ranges ``r`` [m]."""
        return self.range_sigma + (self.range_sigma_rel + self.range_sigma_quad * r) * r

    def __post_init__(self) -> None:
        if self.binning not in self.BINNINGS:
            raise ValueError(f"binning must be one of {self.BINNINGS}, got {self.binning!r}")
        check_count("min_particles", self.min_particles, 1, MAX_PARTICLES)
        check_count("max_particles", self.max_particles, 1, MAX_PARTICLES)
        if not self.min_particles <= self.max_particles:
            raise ValueError("need min_particles <= max_particles, got "
                             f"{self.min_particles}, {self.max_particles}")
        for name in ("epsilon", "delta", "a_trans", "a_rot_xy", "a_rot", "a_trans_theta",
                     "range_sigma", "range_sigma_rel", "range_sigma_quad", "alpha_slow",
                     "alpha_fast", "recovery_ratio"):
            check_real(name, getattr(self, name))
        if self.bearing_sigma is not None:
            check_real("bearing_sigma", self.bearing_sigma)
        if not (isinstance(self.bin_size, (tuple, list)) and len(self.bin_size) == 3):
            raise ValueError(f"bin_size must be three positive sizes (m, m, rad), got "
                             f"{self.bin_size!r}")
        for size in self.bin_size:
            check_real("bin_size", size, 0.0, low_open=True)
        if self.delta < MIN_DELTA:
            raise ValueError(f"delta must be >= {MIN_DELTA:g} (1 - delta < 1), got "
                             f"{self.delta!r}")
        if not (0.0 < self.epsilon < 1.0 and 0.0 < self.delta < 1.0):
            raise ValueError(f"epsilon and delta must be in (0, 1), got {self.epsilon}, "
                             f"{self.delta}")
        if len(self.bin_size) != 3 or min(self.bin_size) <= 0.0:
            raise ValueError(f"bin_size must be three positive sizes, got {self.bin_size}")
        for name in ("a_trans", "a_rot_xy", "a_rot", "a_trans_theta", "range_sigma_rel",
                     "range_sigma_quad"):
            if not getattr(self, name) >= 0.0:
                raise ValueError(f"{name} must be >= 0, got {getattr(self, name)!r}")
        if not self.range_sigma > 0.0:
            raise ValueError(f"range_sigma must be > 0, got {self.range_sigma!r}")
        if self.bearing_sigma is not None and not self.bearing_sigma > 0.0:
            raise ValueError(f"bearing_sigma must be > 0 or None, got {self.bearing_sigma!r}")
        if not 0.0 <= self.alpha_slow <= 1.0 or not 0.0 <= self.alpha_fast <= 1.0 or (
                self.alpha_fast > 0.0 and self.alpha_slow >= self.alpha_fast):
            raise ValueError("need 0 <= alpha_slow < alpha_fast <= 1 (or alpha_fast = 0), got "
                             f"{self.alpha_slow}, {self.alpha_fast}")
        if not 0.0 < self.recovery_ratio <= 1.0:
            raise ValueError(f"recovery_ratio must be in (0, 1], got {self.recovery_ratio!r}")


class KLDLocalizer:
    """Self-localization of one robot on a field with known landmarks (see the module
    docstring).

    Args:
        bounds: ``(x_min, x_max, y_min, y_max)`` of the region the robot can be in [m]
            (global initialisation and recovery draw from it).
        rng: the generator of every draw.
        config: :class:`KLDConfig`.
        pose: a known start ``(x, y, theta)`` (particles drawn around it with ``pose_sigma``),
            or None for global localization (uniform over ``bounds``, ``max_particles``).
        recovery: how injected particles are drawn, one of :data:`RECOVERIES`: ``"uniform"``
            (the default) or ``"triangulate"`` (a share around poses triangulated from the
            recent sightings, see the module docstring; it needs bearings, and with
            :meth:`update_kinds` a ``bearing_sigma``, else every draw stays uniform).
        seed_fraction: with ``"triangulate"``, the share of the injected particles drawn
            around the hypotheses, in [0, 1].
        seed_memory: with ``"triangulate"``, how many updates' sightings are kept for it
            (1..1000; at 25 frames/s, 25 is one to two seconds of a scanning head).
    """

    def __init__(self, bounds: tuple[float, float, float, float], rng: np.random.Generator,
                 config: KLDConfig | None = None, pose: np.ndarray | None = None,
                 pose_sigma: tuple[float, float, float] = (0.1, 0.1, 0.1), *,
                 recovery: str = "uniform", seed_fraction: float = 0.5,
                 seed_memory: int = 25) -> None:
        if not isinstance(rng, np.random.Generator):
            raise TypeError("rng must be a numpy.random.Generator")
        if recovery not in RECOVERIES:
            raise ValueError(f"recovery must be one of {RECOVERIES}, got {recovery!r}")
        if isinstance(seed_fraction, bool) or not (isinstance(seed_fraction, (int, float))
                                                   and 0.0 <= seed_fraction <= 1.0):
            raise ValueError(f"seed_fraction must be in [0, 1], got {seed_fraction!r}")
        if isinstance(seed_memory, bool) or not isinstance(seed_memory, (int, np.integer)) \
                or not 1 <= seed_memory <= 1000:
            raise ValueError(f"seed_memory must be an integer in [1, 1000] (updates), got "
                             f"{seed_memory!r}")
        self.recovery = recovery
        self.seed_fraction = float(seed_fraction)
        #: The recent sightings (``recovery="triangulate"`` only, else None).
        self.memory = (SightingMemory(seed_memory) if recovery == "triangulate" else None)
        #: The landmark table of the sightings in :attr:`memory` (kind -> positions [m]).
        self._seed_table: dict = {}
        #: The latest recovery seed's hypotheses (None: none computed yet).
        self.last_seed: PoseHypotheses | None = None
        box = "(x_min, x_max, y_min, y_max) [m] with min < max"
        x0, x1, y0, y1 = check_reals("bounds", bounds, 4, -MAX_COORDINATE, MAX_COORDINATE,
                                     box).tolist()
        if not (x0 < x1 and y0 < y1):
            raise ValueError(f"bounds must be {box}, got {bounds!r}")
        self.bounds = (x0, x1, y0, y1)
        self.rng = rng
        self.cfg = config or KLDConfig()
        self.w_slow = self.w_fast = 0.0
        sigma = check_reals("pose_sigma", pose_sigma, 3, 0.0, what="(m, m, rad)")
        if pose is None:
            self.particles = self._uniform(self.cfg.max_particles)
        else:
            p = check_reals("pose", pose, 3, -MAX_COORDINATE, MAX_COORDINATE,
                            "(x, y, theta) [m, m, rad]")
            n = self.cfg.min_particles
            self.particles = p + rng.normal(0.0, 1.0, (n, 3)) * sigma
        self.weights = np.full(len(self.particles), 1.0 / len(self.particles))
        self._hypotheses: PoseHypotheses | None = None
        #: Weighted by a measurement and not yet resampled (``binning="predicted"``: the
        #: next predict resamples).
        self._pending = False
        #: KLD-sampling's bound per number of occupied bins (:func:`kld_table` as an array).
        c = self.cfg
        self._bound = np.asarray(kld_table(c.epsilon, c.delta, c.max_particles))
        self._bin_size = tuple(float(v) for v in c.bin_size)

    @property
    def n(self) -> int:
        """The current number of particles."""
        return len(self.particles)

    def _uniform(self, n: int) -> np.ndarray:
        x0, x1, y0, y1 = self.bounds
        u = self.rng.random((n, 3))
        return np.column_stack([x0 + u[:, 0] * (x1 - x0), y0 + u[:, 1] * (y1 - y0),
                                (u[:, 2] * 2.0 - 1.0) * math.pi])

    def predict(self, odometry: np.ndarray | tuple[float, float, float]) -> None:
        """Move every particle by the body-frame displacement ``(dx, dy, dtheta)`` [m, m,
        rad] with the odometry noise."""
        d = np.asarray(odometry, dtype=np.float64)
        if d.shape != (3,) or not np.isfinite(d).all() or np.abs(d).max() > MAX_ODOMETRY:
            raise ValueError(f"odometry must be a finite (dx, dy, dtheta), each within "
                             f"{MAX_ODOMETRY:g} (m, rad) of 0, got {odometry!r}")
        if self._pending:  # Fox's KLD-sampling: draw, move and bin the predicted samples
            self._pending = False
            self._resample(d)
        else:
            self._move(self.particles, d, self.rng.normal(0.0, 1.0, (self.n, 3)))
        if self.memory is not None:
            self.memory.move(d)
            self._hypotheses = None

    def likelihood(self, landmarks: np.ndarray, ranges: np.ndarray,
                   bearings: np.ndarray | None = None) -> np.ndarray:
        """``p(z | chi)`` of every particle for landmarks at ``landmarks`` ((m, 2)) seen at
        ``ranges`` ((m,)) [m] and ``bearings`` ((m,)) [rad, relative to the heading]."""
        return np.exp(self._log_likelihood(landmarks, ranges, bearings))

    def _log_likelihood(self, landmarks: np.ndarray, ranges: np.ndarray,
                        bearings: np.ndarray | None = None) -> np.ndarray:
        L = np.asarray(landmarks, dtype=np.float64).reshape(-1, 2)
        r = np.asarray(ranges, dtype=np.float64).reshape(-1)
        if len(r) != len(L) or not (np.isfinite(L).all() and np.isfinite(r).all()):
            raise ValueError(f"landmarks ((m, 2)) and ranges ((m,)) must match and be finite, "
                             f"got {L.shape} and {r.shape}")
        if (r < 0.0).any():
            raise ValueError(f"ranges must be >= 0 [m], got {r!r}")
        return self._best_log_likelihood(np.ascontiguousarray(L[:, 0]),
                                         np.ascontiguousarray(L[:, 1]),
                                         np.ones(len(r), dtype=np.int64), r,
                                         self._check_bearings(bearings, r))

    def _check_bearings(self, bearings: np.ndarray | None, r: np.ndarray) -> np.ndarray | None:
        """The bearings as a checked array, or None when they are not used."""
        if bearings is None or self.cfg.bearing_sigma is None:
            return None
        b = np.asarray(bearings, dtype=np.float64).reshape(-1)
        if b.shape != r.shape or not np.isfinite(b).all():
            raise ValueError("bearings must be finite and match ranges")
        return b

    def _best_log_likelihood(self, Lx: np.ndarray, Ly: np.ndarray, counts: np.ndarray,
                             r: np.ndarray, b: np.ndarray | None) -> np.ndarray:
        """``(N,)`` log-likelihood (up to a constant) of every particle for ``m`` sightings
        at ranges ``r`` ((m,)) and bearings ``b`` ((m,) or None), sighting ``j`` of the
        best of its ``counts[j]`` candidate positions ``(Lx, Ly)`` (every sighting's in
        turn): :func:`~estimators.particle.localization_kernels.best_log_likelihood`."""
        c = self.cfg
        return best_log_likelihood(
            self.particles, Lx, Ly, counts, r, r if b is None else b,
            (c.range_sigma, c.range_sigma_rel, c.range_sigma_quad),
            0.0 if b is None else float(c.bearing_sigma))

    def update(self, landmarks: np.ndarray, ranges: np.ndarray,
               bearings: np.ndarray | None = None) -> None:
        """Weight by the sightings (none: nothing to do), then KLD-resample."""
        m = len(np.asarray(ranges).reshape(-1))
        if m == 0:
            return
        log = self._log_likelihood(landmarks, ranges, bearings)
        if self.memory is not None and bearings is not None:
            # Known landmarks: each its own kind, named by its position.
            L = np.asarray(landmarks, dtype=np.float64).reshape(-1, 2)
            kinds = tuple((float(x), float(y)) for x, y in L)
            for k, pos in zip(kinds, L):
                self._seed_table.setdefault(k, pos[None, :])
            self._remember(kinds, ranges, bearings)
        self._weigh(log, m)

    def update_kinds(self, kinds: Sequence[str], ranges: np.ndarray,
                     bearings: np.ndarray | None,
                     table: Mapping[str, np.ndarray] | LandmarkTable) -> None:
        """Weight by sightings of landmarks known by kind only, then KLD-resample.

        Args:
            kinds: ``m`` kinds (keys of ``table``), one per observation.
            ranges: ``(m,)`` measured ranges [m].
            bearings: ``(m,)`` bearings [rad, relative to the heading], or None.
            table: kind -> ``(M_k, 2)`` positions of the landmarks of that kind [m], or a
                :class:`LandmarkTable` of them (validated once, its layouts cached: what a
                caller updating every frame passes).

        Per observation ``j`` and particle, the log-likelihood is the largest over the
        candidates of its kind (nearest-neighbour association, see the module docstring);
        the weighting, recovery bookkeeping and resampling are :meth:`update`'s. One kernel
        pass over particles x candidates.
        """
        kinds = (kinds,) if isinstance(kinds, str) else tuple(kinds)
        r = np.asarray(ranges, dtype=np.float64).reshape(-1)
        m = len(kinds)
        if len(r) != m or not np.isfinite(r).all():
            raise ValueError(f"kinds ({m}) and ranges ({r.shape}) must match and ranges be "
                             f"finite")
        if m == 0:
            return
        b = self._check_bearings(bearings, r)
        if not isinstance(table, LandmarkTable):
            table = LandmarkTable({k: table[k] for k in set(kinds) if k in table})
        self.update_sightings(kinds, r, b, table)

    def update_sightings(self, kinds: tuple[str, ...], ranges: np.ndarray,
                         bearings: np.ndarray | None, table: LandmarkTable) -> None:
        """:meth:`update_kinds` without its argument checks, for callers with validated data
        (a pipeline's own frames): ``kinds`` a non-empty tuple, ``ranges`` and ``bearings``
        finite float arrays of its length (``bearings`` None when not used)."""
        Lx, Ly, counts = table.layout(kinds)
        m = len(kinds)
        b = bearings if self.cfg.bearing_sigma is not None else None
        # Each sighting's best candidate per particle, summed over the sightings.
        log = self._best_log_likelihood(Lx, Ly, counts, ranges, b)
        if self.memory is not None and bearings is not None:
            for k in kinds:
                self._seed_table[k] = table[k]
            self._remember(kinds, ranges, bearings)
        self._weigh(log, m)

    def _move(self, p: np.ndarray, d: np.ndarray, noise: np.ndarray) -> None:
        """Move the particles ``p`` ((n, 3), in place) by the body-frame displacement ``d``
        with the odometry noise, ``noise`` ((n, 3)) standard normal draws
        (:func:`~estimators.particle.localization_kernels.move_particles`)."""
        c = self.cfg
        move_particles(p, (float(d[0]), float(d[1]), float(d[2])), noise,
                       (c.a_trans, c.a_rot_xy, c.a_rot, c.a_trans_theta))

    def _remember(self, kinds: tuple, ranges: np.ndarray, bearings: np.ndarray) -> None:
        """Keep one update's sightings for the recovery seed (the memory drops the oldest)."""
        assert self.memory is not None
        self.memory.add(kinds, ranges, bearings)
        self._hypotheses = None  # new sightings: triangulate afresh when next needed

    def seed_hypotheses(self) -> PoseHypotheses:
        """The poses triangulated from the remembered sightings (see the module docstring),
        with the filter's noise model: range sigma per sighting as in the likelihood,
        bearing sigma ``bearing_sigma`` (5 degrees when bearings are left out), inside the
        bounds. Raises ``ValueError`` unless ``recovery="triangulate"``."""
        if self.memory is None:
            raise ValueError("seed_hypotheses needs recovery='triangulate'")
        kinds, pts = self.memory.sightings()
        return seed_poses(kinds, pts, self._seed_table, self.cfg, self.bounds)

    def _recovery_draws(self, k: int) -> np.ndarray:
        """``k`` injected particles: with ``recovery="triangulate"`` a share
        ``seed_fraction`` around the triangulated hypotheses (computed once per set of
        sightings), the rest uniform."""
        if self.memory is None:
            return self._uniform(k)
        if self._hypotheses is None:
            self._hypotheses = self.last_seed = self.seed_hypotheses()
        hyp = self._hypotheses
        if not hyp.ok:
            return self._uniform(k)
        seeded = self.rng.random(k) < self.seed_fraction
        ns = int(seeded.sum())
        out = np.empty((k, 3))
        out[~seeded] = self._uniform(k - ns)
        pick = self.rng.integers(0, len(hyp.poses), ns)
        spread = np.column_stack([np.maximum(hyp.sigmas[pick, 0], _SEED_MIN_XY),
                                  np.maximum(hyp.sigmas[pick, 0], _SEED_MIN_XY),
                                  np.maximum(hyp.sigmas[pick, 1], _SEED_MIN_THETA)])
        seed = hyp.poses[pick] + self.rng.normal(0.0, 1.0, (ns, 3)) * spread
        seed[:, 2] = np.remainder(seed[:, 2] + math.pi, 2.0 * math.pi) - math.pi
        out[seeded] = seed
        return out

    def _weigh(self, log: np.ndarray, m: int) -> None:
        """Weights times ``exp(log)`` for ``m`` observations, the recovery averages, then
        KLD resampling."""
        w, _, mean_lik = weigh(self.weights, log, m)
        c = self.cfg
        if c.alpha_fast > 0.0:
            if self.w_slow == 0.0:
                self.w_slow = self.w_fast = mean_lik
            self.w_slow += c.alpha_slow * (mean_lik - self.w_slow)
            self.w_fast += c.alpha_fast * (mean_lik - self.w_fast)
        self.weights = w
        if c.binning == "predicted":
            self._pending = True  # resampled by the next predict, on the predicted samples
        else:
            self._resample()

    def _resample(self, odometry: np.ndarray | None = None) -> None:
        """KLD-sampling from the weighted set; with ``odometry`` (Fox's order) every drawn
        particle is moved by it before its bin is counted."""
        c = self.cfg
        inject = 0.0
        if c.alpha_fast > 0.0 and self.w_slow > 0.0:
            inject = max(0.0, 1.0 - self.w_fast / (c.recovery_ratio * self.w_slow))
        cumulative = np.cumsum(self.weights)
        cumulative /= cumulative[-1]
        # Draw in batches (doubling from about the current size) until the KLD bound holds for
        # the draws so far, rather than max_particles candidates every time; the bins are
        # counted over all the draws so far (kld_sample_count, a kernel), once per batch.
        batch = min(c.max_particles, max(c.min_particles, 2 * self.n))
        parts: list[np.ndarray] = []
        drawn = 0
        n = 0
        while not n:
            take = min(batch, c.max_particles - drawn)
            new = draw_rows(cumulative, self.particles, self.rng.random(take))
            if inject > 0.0:
                fresh = self.rng.random(take) < inject
                new[fresh] = self._recovery_draws(int(fresh.sum()))
            if odometry is not None:
                self._move(new, odometry, self.rng.normal(0.0, 1.0, (take, 3)))
            parts.append(new)
            drawn += take
            cand = parts[0] if len(parts) == 1 else np.concatenate(parts)
            n = kld_sample_count(cand, self._bin_size, self._bound, c.min_particles)
            if not n and drawn >= c.max_particles:
                n = c.max_particles
            batch *= 2
        self.particles = cand[:n].copy()
        self.weights = np.full(n, 1.0 / n)

    def estimate(self) -> np.ndarray:
        """The weighted mean pose ``(x, y, theta)`` (circular mean of the headings)."""
        x, y, theta, _ = weighted_pose(self.weights, self.particles)
        return np.array([x, y, theta])

    def pose_sigma(self) -> tuple[float, float]:
        """The particles' spread as standard deviations: position ``sqrt(tr C / 2)`` [m] (per
        axis, ``C`` the weighted position covariance) and heading ``sqrt(-2 ln R)`` [rad],
        the circular standard deviation of the weighted mean resultant length ``R``."""
        x, y, _, r = weighted_pose(self.weights, self.particles)
        return (weighted_spread(self.weights, self.particles, x, y) / math.sqrt(2.0),
                math.sqrt(-2.0 * math.log(min(1.0, max(r, 1e-300)))))

    def spread(self) -> float:
        """Weighted RMS distance of the particles from the mean position [m]."""
        x, y, _, _ = weighted_pose(self.weights, self.particles)
        return weighted_spread(self.weights, self.particles, x, y)
