"""The feature-restricted mean-shift particle filter of Li, Wu and Kong (2010) and the plain
particle filter it is compared with, on weight images (images, points,
windows and mean shift as in :mod:`estimators.image.meanshift`).

**Li et al. (2010) (feature-restricted mean-shift particle filter).** State per particle
``(x, y, vx, vy)`` [px, px, px/frame, px/frame]; the heading ``phi`` of the paper's state is
left to the ``feature_check`` hook (it needs the patch layout, not the weight images). The
2nd-order autoregressive model ``S_t - S_{t-1} = S_{t-1} - S_{t-2} + w``,
``w ~ N(0, process_sigma^2 I)`` on ``(x, y)``, is the constant-velocity model with
``v_{t-1} = S_{t-1} - S_{t-2}``: ``p_t = p_{t-1} + v_{t-1} + w``, ``v_t = v_{t-1} + w``. Per
frame (:meth:`MeanShiftParticleFilter.update`):

1. propagate the particles with the AR model;
2. mean shift on every particle's window (size ``window_size``, from the target's patch) over
   the combined image ``M = (1 - a) M_c + a M_m`` (``M_c`` the colour probability, ``M_m``
   the frame difference); ``a = max_motion_weight * min(1, |v| / v_ref)``, ``|v|`` the
   previous estimate's speed. The paper has ``a`` proportional to the speed, normalised; we
   cap it at ``max_motion_weight`` (0.5) because a frame difference alone has two lobes, at
   the target's old and new position, and pure motion weight would pull windows back to the
   old one. The particle moves to the weights' centroid in its converged window, and its
   velocity takes the same shift (``v = p_t - p_{t-1}`` of the AR model);
3. reweight: ``Dis = sqrt(1 - M / M_t)`` with ``M`` the window's sum of the combined image and
   ``M_t`` its pixel count, ``w = exp(-Dis^2 / (2 sigma^2))`` (the paper's factor
   ``1 / (sqrt(2 pi) sigma)`` cancels in the normalisation);
4. estimate (``mean="weighted"``, the default, ours): the weighted mean of the particles
   (position and velocity), then systematic resampling. As printed (``mean="paper"``): the
   unweighted mean ``E[S_t] = (1/N) sum_i S_t^(i)`` and no resampling step; the weights of
   step 3 then play no part in the estimate (the paper gives them no other use). The particle
   set stays on the target through step 5 alone: the paper's set at ``t - 1`` is "the
   particles inside the target window obtained by the feature restriction", so here the
   particles the restriction rejects are replaced by copies of allowed ones, each drawn with
   equal probability (not by weight), and the mean is taken over that set.
   ``soccer-env paper meanshift`` measures both;
5. feature restriction (our reading of the paper's "the colour, area and relative position of
   the patches restrict the search to a region" and "the particle set inside the target
   window"): a particle is allowed when its window's colour mass ``sum_W M_c`` is within
   ``area * (1 +- area_tolerance)`` (``area`` the target's colour mass, i.e. its patch area
   [px^2] weighted by colour probability, measured on the first image when not given) and the
   user's ``feature_check(windows, colour_image)`` predicate (patch layout, heading, identity)
   accepts it. Particles that are not allowed get zero weight, so resampling replaces them by
   allowed ones: the particle set stays on windows that look like the target, which is what
   lets about 20 particles do. (Moving them back into the allowed region is what mean shift
   has already tried in step 2.)

**Lost track**: no particle is allowed (the target's colour mass is nowhere near the
particles). A robot then keeps its previous estimate (velocity set to zero) and is searched
globally in the next frame: the window position with the largest colour mass among those
allowed by the area restriction (a box filter of ``M_c`` through one integral image, so the
whole image costs ``O(H W)``), refined by mean shift and accepted if ``feature_check`` agrees;
the particles restart around it. The ball (pass ``robots=`` to ``update``): if a robot is in
the ball's search window (:meth:`MeanShiftParticleFilter.occluded_by`), the ball is occluded
and placed at that robot, and the particles restart there; otherwise as a robot.

:class:`ParticleFilterTracker` is the paper's baseline: the same motion model and likelihood,
no mean shift, no feature restriction, no lost-track handling.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..checks import MAX_PARTICLES, MAX_PIXELS, check_count
from ..particle.core import systematic_resample
from .checks import (
    check_fits,
    check_image,
    check_int,
    check_number,
    check_point,
    check_window_size,
)
from .meanshift import MEAN_SHIFT_KERNELS, MeanShiftWindows, RegionImage
from .window_kernels import window_mass_scores

__all__ = ["EmptyWindowError", "MeanShiftParticleFilter", "ParticleFilterTracker"]

FeatureCheck = Callable[[np.ndarray, np.ndarray], np.ndarray]


class EmptyWindowError(ValueError):
    """A :class:`MeanShiftParticleFilter` without ``area`` was given a first image that holds
    no weight where it starts: there is nothing to measure the target's area on (the target is
    not where the filter was started). The filter is left as it was before the update."""


# ------------------------------------------------------------------------------------------
# Li et al. (2010): particle filters on window likelihoods
# ------------------------------------------------------------------------------------------

def _image_names(flats: list[tuple[np.ndarray, float]]) -> str:
    """The arguments the combined image ``flats`` comes from, for error messages."""
    return "colour_image" if len(flats) == 1 else "colour_image and motion_image"


def _unchanged_on_error(update: Callable[..., np.ndarray]) -> Callable[..., np.ndarray]:
    """``update`` made all-or-nothing: an image refused part-way through the frame
    (``ValueError``: weights found not finite where a window reads them, see
    :func:`~estimators.image.meanshift.check_moments`) leaves the tracker, its particles
    and its random generator as they were before the call."""
    @functools.wraps(update)
    def wrapper(self: _WindowParticleFilter, *args: Any, **kwargs: Any) -> np.ndarray:
        saved = {k: v.copy() if isinstance(v, np.ndarray) else v for k, v in vars(self).items()}
        rng_state = self.rng.bit_generator.state
        try:
            return update(self, *args, **kwargs)
        except ValueError:
            self.__dict__.clear()
            self.__dict__.update(saved)
            self.rng.bit_generator.state = rng_state
            raise
    return wrapper


#: The range of the likelihood's ``sigma`` (``Dis`` is in ``[0, 1]``): ``Dis^2 / (2 sigma^2)``
#: stays finite and the weights distinguish windows.
LIKELIHOOD_SIGMA = (1e-6, 1e6)


class _WindowParticleFilter:
    """The motion model, likelihood and bookkeeping shared by the two particle trackers."""

    def __init__(self, position: ArrayLike, window_size: ArrayLike, rng: np.random.Generator, *,
                 n_particles: int,
                 velocity: ArrayLike = (0.0, 0.0), process_sigma: float = 4.0,
                 likelihood_sigma: float = 0.15, init_sigma: float = 2.0, v_ref: float = 20.0,
                 max_motion_weight: float = 0.5) -> None:
        if not isinstance(rng, np.random.Generator):
            raise ValueError(f"rng must be a numpy.random.Generator, got {type(rng).__name__}")
        self.rng = rng
        p = check_point("position", position)
        v = check_point("velocity", velocity)
        self.window_size = check_window_size("window_size", window_size)
        self.n = check_count("n_particles", n_particles, 2, MAX_PARTICLES)
        self.process_sigma = check_number("process_sigma", process_sigma, allow_low=True,
                                          high=MAX_PIXELS)
        self.likelihood_sigma = check_number("likelihood_sigma", likelihood_sigma,
                                             LIKELIHOOD_SIGMA[0], True, LIKELIHOOD_SIGMA[1])
        self.init_sigma = check_number("init_sigma", init_sigma, allow_low=True,
                                       high=MAX_PIXELS)
        self.v_ref = check_number("v_ref", v_ref)
        self.max_motion_weight = check_number("max_motion_weight", max_motion_weight,
                                         allow_low=True, high=1.0)
        self.estimate = np.concatenate([p, v])
        self._seed(p, v)
        self.frame = 0
        self.motion_weight = 0.0
        self._win: MeanShiftWindows | None = None

    def _seed(self, p: np.ndarray, v: np.ndarray) -> None:
        """Particles ``N(p, init_sigma^2 I)`` with velocity ``v``, equal weights."""
        self.particles = np.empty((self.n, 4))
        self.particles[:, :2] = p + self.rng.normal(0.0, self.init_sigma, (self.n, 2))
        self.particles[:, 2:] = v
        self.weights = np.full(self.n, 1.0 / self.n)

    def __getstate__(self) -> dict:
        # The region image of the latest update is of no use after it (and holds the
        # look-up that computes it): copies and pickles leave it out.
        return {**self.__dict__, "_source": None, "_motion_source": None}

    def _images(self, colour_image, motion_image):
        # A RegionImage is read only where it has been computed: the callers ask for the
        # regions first (see _reach).
        self._source = colour_image if isinstance(colour_image, RegionImage) else None
        self._motion_source = (motion_image if isinstance(motion_image, RegionImage)
                               else None)
        colour = (colour_image.array if self._source is not None
                  else check_image("colour_image", colour_image))
        check_fits("colour_image", self.window_size, colour.shape)
        if self._motion_source is not None:
            if self._motion_source.shape != colour.shape:
                raise ValueError(f"motion_image must have shape {colour.shape}, got "
                                 f"{self._motion_source.shape}")
            motion = self._motion_source.array
        else:
            motion = None if motion_image is None else check_image("motion_image", motion_image,
                                                              colour.shape)
        if self._win is None or (self._win.height, self._win.width) != colour.shape:
            self._win = self._make_windows(colour.shape)
        return colour, motion

    def _make_windows(self, shape: tuple[int, int]) -> MeanShiftWindows:
        return MeanShiftWindows(*self.window_size, shape)

    def _reach(self, x0: np.ndarray, y0: np.ndarray, steps: int) -> None:
        """Have :class:`RegionImage` colour and motion images computed wherever windows with
        top-left pixels ``x0, y0`` can read within ``steps`` mean-shift steps: a step moves a
        window to its centroid, at most ``w // 2 + 1`` pixels across (``h // 2 + 1``
        down)."""
        if self._source is None and self._motion_source is None:
            return
        w, h = self.window_size
        ax, ay = steps * (w // 2 + 1), steps * (h // 2 + 1)
        box = (float(x0.min()) - ax, float(y0.min()) - ay, float(x0.max()) + w + ax,
               float(y0.max()) + h + ay)
        for source in (self._source, self._motion_source):
            if source is not None:
                source.ensure(*box)

    def _flats(self, colour: np.ndarray, motion: np.ndarray | None
               ) -> list[tuple[np.ndarray, float]]:
        """The combined image ``(1 - a) M_c + a M_m`` as weighted flat images, with
        ``a = max_motion_weight * min(1, |v| / v_ref)`` from the previous estimate."""
        if motion is None:
            self.motion_weight = 0.0
            return [(colour.ravel(), 1.0)]
        speed = math.hypot(self.estimate[2], self.estimate[3])
        a = self.max_motion_weight * min(1.0, speed / self.v_ref)
        self.motion_weight = a
        if a == 0.0:
            return [(colour.ravel(), 1.0)]
        return [(colour.ravel(), 1.0 - a), (motion.ravel(), a)]

    def _propagate(self) -> None:
        """AR(2) model: ``p += v + w``, ``v += w``, ``w ~ N(0, process_sigma^2 I)``."""
        w = self.rng.normal(0.0, self.process_sigma, (self.n, 2)) if self.process_sigma else 0.0
        self.particles[:, 2:] += w
        self.particles[:, :2] += self.particles[:, 2:]
        h, wd = self._win.height, self._win.width
        xy = self.particles[:, :2]
        np.maximum(xy, 0.0, out=xy)  # np.clip without its per-call checks
        np.minimum(xy, (wd - 1.0, h - 1.0), out=xy)

    def _log_likelihood(self, combined_mass: np.ndarray) -> np.ndarray:
        """``log w = -Dis^2 / (2 sigma^2)``, ``Dis^2 = 1 - M / M_t``."""
        dis2 = np.maximum(1.0 - combined_mass / self._win.area, 0.0)
        return -dis2 / (2.0 * self.likelihood_sigma ** 2)

    def _weigh_and_estimate(self, logw: np.ndarray, allowed: np.ndarray | None = None
                            ) -> np.ndarray:
        """Normalised weights (zero where not ``allowed``), weighted-mean estimate, then
        systematic resampling."""
        w = self._normalised(logw, allowed)
        self.estimate = w @ self.particles
        idx = systematic_resample(w, self.rng)
        self.particles = self.particles[idx]
        self.weights = np.full(self.n, 1.0 / self.n)
        return self.estimate.copy()

    @staticmethod
    def _normalised(logw: np.ndarray, allowed: np.ndarray | None) -> np.ndarray:
        """The weights ``exp(logw)`` normalised, zero where not ``allowed`` (scaled by the
        largest against underflow)."""
        if allowed is not None:
            logw = np.where(allowed, logw, -np.inf)
        w = np.exp(logw - logw.max())
        w /= w.sum()
        return w

    def windows(self) -> np.ndarray:
        """The particles' current windows ``(N, 4)`` as ``(x, y, w, h)`` [px] (after the
        first update; before it, unclamped)."""
        w, h = self.window_size
        if self._win is None:
            x0 = np.rint(self.particles[:, 0] - 0.5 * (w - 1)).astype(np.intp)
            y0 = np.rint(self.particles[:, 1] - 0.5 * (h - 1)).astype(np.intp)
        else:
            x0, y0 = self._win.corner(self.particles)
        return np.stack([x0, y0, np.full_like(x0, w), np.full_like(x0, h)], axis=1)


class ParticleFilterTracker(_WindowParticleFilter):
    """Plain particle filter on window likelihoods: Li et al.'s (2010) baseline (see the module
    docstring): AR(2) motion, the likelihood ``exp(-Dis^2 / (2 sigma^2))`` of the combined
    colour/motion image over each particle's window, weighted-mean estimate, systematic
    resampling every frame; no mean shift, no feature restriction, no lost-track handling.

    Args:
        position: initial ``(x, y)`` [px].
        window_size: ``(w, h)`` of the search window [px] (from the target's patch).
        rng: the generator of every random draw.
        n_particles: number of particles (the paper: at least 200).
        velocity: initial ``(vx, vy)`` [px/frame].
        process_sigma: standard deviation of the AR noise ``w`` [px].
        likelihood_sigma: ``sigma`` of the likelihood (dimensionless, ``Dis`` is in
            ``[0, 1]``).
        init_sigma: spread of the initial particles [px].
        v_ref: speed [px/frame] at which the motion image's weight ``a`` saturates.
        max_motion_weight: the saturated ``a`` (0: colour only).
    """

    def __init__(self, position: ArrayLike, window_size: ArrayLike, rng: np.random.Generator, *,
                 n_particles: int = 200, velocity: ArrayLike = (0.0, 0.0),
                 process_sigma: float = 4.0,
                 likelihood_sigma: float = 0.15, init_sigma: float = 2.0, v_ref: float = 20.0,
                 max_motion_weight: float = 0.5) -> None:
        super().__init__(position, window_size, rng, n_particles=n_particles,
                         velocity=velocity, process_sigma=process_sigma,
                         likelihood_sigma=likelihood_sigma, init_sigma=init_sigma,
                         v_ref=v_ref, max_motion_weight=max_motion_weight)

    @_unchanged_on_error
    def update(self, colour_image: np.ndarray, motion_image: np.ndarray | None = None
               ) -> np.ndarray:
        """One frame: propagate, weigh, estimate, resample. ``colour_image`` ``(H, W)`` is the
        target's colour probability, ``motion_image`` (optional, same shape) the frame
        difference. Returns the estimate ``(x, y, vx, vy)`` [px, px/frame]."""
        colour, motion = self._images(colour_image, motion_image)
        flats = self._flats(colour, motion)
        self.frame += 1
        self._propagate()
        x0, y0 = self._win.corner(self.particles)
        self._reach(x0, y0, 0)
        mom = self._win.moments_of(flats, x0, y0, _image_names(flats))
        return self._weigh_and_estimate(self._log_likelihood(mom[:, 3]))


class MeanShiftParticleFilter(_WindowParticleFilter):
    """Feature-restricted mean-shift particle filter of Li, Wu and Kong (2010) for
    one target (see the module docstring for the maths and our readings).

    Args:
        position: initial ``(x, y)`` [px].
        window_size: ``(w, h)`` of the search window ``W`` [px] (from the target's patch).
        rng: the generator of every random draw.
        n_particles: number of particles (the paper: about 20).
        velocity: initial ``(vx, vy)`` [px/frame].
        process_sigma: standard deviation of the AR noise ``w`` [px].
        likelihood_sigma: ``sigma`` of the likelihood (``Dis`` is in ``[0, 1]``).
        init_sigma: spread of the particles at a (re-)start [px].
        v_ref: speed [px/frame] at which the motion image's weight ``a`` saturates.
        max_motion_weight: the saturated ``a`` (0: colour only).
        mean_shift_iter: mean-shift steps per particle and frame (at most).
        eps: mean shift stops when a window moves less than this [px].
        kernel: a name in :data:`~estimators.image.meanshift.MEAN_SHIFT_KERNELS` (``"flat"``
            or ``"epanechnikov"``).
        area: the target's colour mass ``sum_W M_c`` with the window on it [px^2] (its patch
            area weighted by colour probability); None: measured on the first image,
            in the window that mean shift (colour only) reaches from ``position``.
        area_tolerance: a window is allowed when its colour mass is within
            ``area * (1 +- area_tolerance)``.
        feature_check: optional ``f(windows, colour_image) -> (N,) bool``, ``windows`` an
            ``(N, 4)`` int array of ``(x, y, w, h)``: further patch constraints (layout,
            heading, identity); also applied to the global search's candidate.
        mean: step 4, ``"weighted"`` (weighted mean, then systematic resampling) or
            ``"paper"`` (as printed: the unweighted mean of the restricted set, no
            resampling); see the module docstring.

    Attributes:
        estimate: ``(x, y, vx, vy)`` [px, px/frame].
        lost: the track was lost in the last frame (the next update searches globally).
        occluded: the last frame placed the target at an occluding robot (ball rule).
        occluder: that robot's index, else None.
        lost_frames: frames reported lost so far.
        area: the target's colour mass in use [px^2].
        motion_weight: the last frame's ``a``.
    """

    def __init__(self, position: ArrayLike, window_size: ArrayLike, rng: np.random.Generator, *,
                 n_particles: int = 20, velocity: ArrayLike = (0.0, 0.0),
                 process_sigma: float = 4.0,
                 likelihood_sigma: float = 0.15, init_sigma: float = 2.0, v_ref: float = 20.0,
                 max_motion_weight: float = 0.5, mean_shift_iter: int = 5, eps: float = 0.5,
                 kernel: str = "flat", area: float | None = None, area_tolerance: float = 0.3,
                 feature_check: FeatureCheck | None = None, mean: str = "weighted") -> None:
        super().__init__(position, window_size, rng, n_particles=n_particles,
                         velocity=velocity, process_sigma=process_sigma,
                         likelihood_sigma=likelihood_sigma, init_sigma=init_sigma,
                         v_ref=v_ref, max_motion_weight=max_motion_weight)
        self.mean_shift_iter = check_int("mean_shift_iter", mean_shift_iter, 0)
        self.eps = check_number("eps", eps, allow_low=True)
        MEAN_SHIFT_KERNELS.check(kernel, "kernel")
        self.kernel = kernel
        self.area = None if area is None else check_number("area", area)
        self.area_tolerance = check_number("area_tolerance", area_tolerance)
        if feature_check is not None and not callable(feature_check):
            raise ValueError("feature_check must be callable or None")
        self.feature_check = feature_check
        if mean not in self.MEANS:
            raise ValueError(f"mean must be one of {self.MEANS}, got {mean!r}")
        self.mean = mean
        self.lost = False
        self.occluded = False
        self.occluder: int | None = None
        self.lost_frames = 0

    #: Step 4's choices (see the module docstring).
    MEANS = ("weighted", "paper")

    def _make_windows(self, shape: tuple[int, int]) -> MeanShiftWindows:
        return MeanShiftWindows(*self.window_size, shape, self.kernel)

    def _allowed(self, colour_mass: np.ndarray, x0: np.ndarray, y0: np.ndarray,
                 colour: np.ndarray) -> np.ndarray:
        """The feature restriction: colour mass within tolerance, and ``feature_check``."""
        ok = np.abs(colour_mass - self.area) <= self.area_tolerance * self.area
        if self.feature_check is not None and ok.any():
            w, h = self.window_size
            wins = np.stack([x0, y0, np.full_like(x0, w), np.full_like(x0, h)], axis=1)
            res = np.asarray(self.feature_check(wins, colour), dtype=bool)
            if res.shape != (len(x0),):
                raise ValueError(f"feature_check must return ({len(x0)},) booleans, got "
                                 f"shape {res.shape}")
            ok &= res
        return ok

    def occluded_by(self, robot_positions: ArrayLike, robot_radius_px: float,
                    predicted: ArrayLike | None = None) -> int | None:
        """Li et al.'s (2010) ball occlusion test: the index of the robot nearest to the target's
        predicted position among those inside its search window, else None. A robot (a square
        of half-side ``robot_radius_px`` [px] around its ``(x, y)``) is inside when it
        overlaps the search window (``window_size`` centred at the predicted position), which
        includes the robot's square containing the predicted position.

        Args:
            robot_positions: ``(R, 2)`` robot positions [px] (the robots' estimates).
            robot_radius_px: the robots' half-size in the image [px].
            predicted: the target's predicted ``(x, y)`` [px]; default: the estimate moved by
                its velocity (the AR model's mean prediction).
        """
        r = check_number("robot_radius_px", robot_radius_px, allow_low=True)
        robots = np.asarray(robot_positions, dtype=np.float64).reshape(-1, 2) \
            if np.size(robot_positions) else np.empty((0, 2))
        if not np.all(np.isfinite(robots)):
            raise ValueError("robot_positions must be finite (x, y) rows")
        p = (self.estimate[:2] + self.estimate[2:] if predicted is None
             else check_point("predicted", predicted))
        if len(robots) == 0:
            return None
        w, h = self.window_size
        d = np.abs(robots - p)
        inside = (d[:, 0] <= 0.5 * w + r) & (d[:, 1] <= 0.5 * h + r)
        if not inside.any():
            return None
        dist = np.where(inside, np.hypot(d[:, 0], d[:, 1]), np.inf)
        return int(np.argmin(dist))

    def global_search(self, colour_image: np.ndarray, candidates: int = 8
                      ) -> np.ndarray | None:
        """The target over the whole image: the ``candidates`` windows of largest colour mass
        (box sums from one integral image), each at least a window apart, refined by mean
        shift; the first that passes the feature restriction (colour mass and
        ``feature_check``: a look-alike, such as a team-mate, is passed over) gives the
        centroid ``(x, y)`` [px]; None if none does."""
        if isinstance(colour_image, RegionImage):
            colour_image.full()
        colour, _ = self._images(colour_image, None)
        win = self._win
        w, h = win.w, win.h
        area = self._area_in_use(colour)
        # The colour mass of every window position (one summed-area table), -inf where the
        # area restriction rejects it.
        score = np.empty((colour.shape[0] - h + 1, colour.shape[1] - w + 1))
        if not window_mass_scores(colour, w, h, area, self.area_tolerance * area, score):
            return None
        cols = score.shape[1]
        score = score.ravel()
        top = np.argsort(-score)[: 50 * candidates]
        picks: list[tuple[int, int]] = []
        for flat in top.tolist():  # greedy: the largest masses, a window apart
            if not math.isfinite(score[flat]) or len(picks) == candidates:
                break
            y, x = divmod(flat, cols)
            if all(abs(x - px) >= w or abs(y - py) >= h for px, py in picks):
                picks.append((x, y))
        x0 = np.array([p[0] for p in picks], dtype=np.intp)
        y0 = np.array([p[1] for p in picks], dtype=np.intp)
        flats = [(colour.ravel(), 1.0)]
        x0, y0, _, mom = win.shift(flats, x0, y0, max(self.mean_shift_iter, 1), self.eps,
                                   "colour_image")
        allowed = self._allowed(mom[:, 3], x0, y0, colour)
        if not allowed.any():
            return None
        return win.centroids(mom, x0, y0)[int(np.argmax(allowed))]

    def _area_in_use(self, colour: np.ndarray) -> float:
        if self.area is None:  # calibrate on the first image, mean shift from the start
            x0, y0 = self._win.corner(self.estimate[None, :2])
            self._reach(x0, y0, max(self.mean_shift_iter, 1))
            _, _, _, mom = self._win.shift([(colour.ravel(), 1.0)], x0, y0,
                                           max(self.mean_shift_iter, 1), self.eps,
                                           "colour_image")
            mass = float(mom[0, 3])
            if mass <= 0.0:
                raise EmptyWindowError("area is None and the first colour_image holds no "
                                       "weight in the window at position "
                                       f"{tuple(self.estimate[:2].tolist())}: pass area")
            self.area = mass
        return self.area

    @_unchanged_on_error
    def update(self, colour_image: np.ndarray, motion_image: np.ndarray | None = None,
               robots: ArrayLike | None = None, robot_radius_px: float | None = None) -> np.ndarray:
        """One frame (see the module docstring).

        Args:
            colour_image: ``(H, W)`` colour probability of the target's class, in ``[0, 1]``.
            motion_image: optional ``(H, W)`` frame difference in ``[0, 1]``.
            robots: for a ball, the robots' estimated positions ``(R, 2)`` [px]: when the
                track is lost and :meth:`occluded_by` finds a robot, the ball is placed at it.
            robot_radius_px: the robots' half-size [px] (needed with ``robots``).

        Returns:
            the estimate ``(x, y, vx, vy)`` [px, px/frame].
        """
        if robots is not None and robot_radius_px is None:
            raise ValueError("robot_radius_px is needed with robots")
        colour, motion = self._images(colour_image, motion_image)
        self._area_in_use(colour)
        self.frame += 1
        self.occluded, self.occluder = False, None
        if self.lost:  # re-initialise by a global search
            found = self.global_search(colour_image if self._source is not None else colour)
            if found is None:
                self.lost_frames += 1
                return self.estimate.copy()
            self.lost = False
            self.estimate = np.array([found[0], found[1], 0.0, 0.0])
            self._seed(found, np.zeros(2))
            return self.estimate.copy()
        prior = self.estimate.copy()
        flats = self._flats(colour, motion)
        self._propagate()
        win = self._win
        x0, y0 = win.corner(self.particles)
        self._reach(x0, y0, self.mean_shift_iter)
        if self.mean_shift_iter > 0:
            x0, y0, _, mom = win.shift(flats, x0, y0, self.mean_shift_iter, self.eps,
                                       _image_names(flats))
            moved = win.centroids(mom, x0, y0)
            shift = moved - self.particles[:, :2]
            self.particles[:, :2] = moved
            self.particles[:, 2:] += shift  # v_t = p_t - p_{t-1}
        else:
            mom = win.moments_of(flats, x0, y0, _image_names(flats))
        colour_mass = mom[:, 3] if len(flats) == 1 else win.gather(colour.ravel(), x0, y0).sum(1)
        allowed = self._allowed(colour_mass, x0, y0, colour)
        if not allowed.any():
            occ = None if robots is None else self.occluded_by(robots, robot_radius_px,
                                                               prior[:2] + prior[2:])
            if occ is not None:  # the ball is hidden by that robot
                at = np.asarray(robots, dtype=np.float64).reshape(-1, 2)[occ]
                self.occluded, self.occluder = True, occ
                self.estimate = np.array([at[0], at[1], 0.0, 0.0])
                self._seed(at, np.zeros(2))
            else:  # lost: keep the last estimate, search globally next frame
                self.lost = True
                self.lost_frames += 1
                self.estimate = np.array([prior[0], prior[1], 0.0, 0.0])
            return self.estimate.copy()
        if self.mean == "paper":
            return self._restricted_mean(self._log_likelihood(mom[:, 3]), allowed)
        return self._weigh_and_estimate(self._log_likelihood(mom[:, 3]), allowed)

    def _restricted_mean(self, logw: np.ndarray, allowed: np.ndarray) -> np.ndarray:
        """Li et al.'s (2010) steps 3-4 as printed: the weights (kept in :attr:`weights`, zero where
        not allowed), the particles the restriction rejects replaced by copies of allowed
        ones drawn with equal probability, and the unweighted mean of the set."""
        self.weights = self._normalised(logw, allowed)
        rejected = np.flatnonzero(~allowed)
        if len(rejected):
            keep = np.flatnonzero(allowed)
            self.particles[rejected] = self.particles[
                keep[self.rng.integers(0, len(keep), len(rejected))]]
        self.estimate = self.particles.mean(axis=0)
        return self.estimate.copy()
