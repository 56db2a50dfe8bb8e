"""Mean shift, the feature-restricted mean-shift particle filter (paper 003, SPEC 1.4) and the
Kalman-started mean shift with ego-motion compensation (paper 004, SPEC 1.5), on weight images.

**Images and coordinates.** Every image is a 2-D array of non-negative weights (float32 in
``[0, 1]`` in practice: a colour-probability image, i.e. the back-projection of a colour table
or a hue histogram, or a frame difference), so the filters do not depend on how the images were
made. A point is ``(x, y)`` [px], ``x`` the column to the right and ``y`` the row downwards,
pixel centres at integer coordinates (pixel ``image[r, c]`` is the point ``(c, r)``). A window
is ``(x, y, w, h)`` [px], integers: its top-left pixel and its size; it covers columns
``x .. x + w - 1`` and rows ``y .. y + h - 1`` and its centre is ``(x + (w - 1) / 2,
y + (h - 1) / 2)``. Windows are kept inside the image by shifting them (never by shrinking).
Velocities are in pixels per frame [px/frame]: the filters step once per image.

**Mean shift** (:func:`mean_shift`, flat kernel, as OpenCV's ``cv2.meanShift``): with
``m_00 = sum_W I``, ``m_10 = sum_W x I``, ``m_01 = sum_W y I`` the zeroth and first moments of
the weights inside the window ``W``, the window moves by
``round(m_10 / m_00 - c_x, m_01 / m_00 - c_y)`` (``c`` its centre, ``round`` half to even as
``cvRound``) until it moves less than ``eps`` pixels (or not at all), at most ``max_iter``
times, or stops where it holds no weight. The Epanechnikov option weights every pixel with
``k = max(0, 1 - r^2)``, ``r^2 = ((x - c_x) / (w / 2))^2 + ((y - c_y) / (h / 2))^2``, in the
moments (the kernel of Comaniciu et al.). OpenCV offsets the centroid by ``w / 2`` rather than
``(w - 1) / 2``, a bias of half a pixel towards the top left that changes where the rounded
steps stall (on a noisy background often by a pixel or two); ``opencv_compatible=True``
reproduces OpenCV's windows exactly.

Every tracker runs mean shift on all its windows at once: one gather of the ``N`` windows'
pixels through flat indices, ``(N, h w)``, and one matrix product with the ``(h w, 4)`` matrix
of ``[k, k x, k y, 1]`` per iteration, so a frame costs ``O(N iterations h w)``, independent
of the image size. Summed-area tables (integral images) make a window's sum ``O(1)`` but cost
``O(H W)`` per image and per moment (three tables per image for mean shift): they pay when
many targets share one image, and are used here only for the global search (one table, the
sum of every window position at once).

**Paper 003 (feature-restricted mean-shift particle filter).** State per particle
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
4. estimate: the weighted mean of the particles (position and velocity), then systematic
   resampling;
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

**Paper 004 (Kalman-started mean shift).** :class:`KalmanMeanShift` filters the image-plane
state ``X = (x, y, vx, vy)`` [px, px, px/frame, px/frame] of a target seen by a camera on a
moving robot: ``X_{k+1} = A X_k + B(u_k) + w_k``, ``A`` constant velocity over one frame, and
the robot's own motion ``u = (theta, s)`` over the last frame as control input (the paper's
linear angle-to-pixel model, a pixel column at angle ``(x - x_B / 2) gamma_x / x_B`` from the
optical axis):

* a rotation ``theta`` [rad] (positive counter-clockwise seen from above, i.e. a turn to the
  left) moves the scene to the right in the image: ``dx = +theta * x_B / gamma_x`` (``x_B``
  the image width [px], ``gamma_x`` the horizontal field of view [rad]);
* a forward motion ``s`` [m] towards the target (``d_{k+1} = d_k - s``, ``d`` its ground
  distance [m]) increases the angle of the line of sight below the horizon,
  ``alpha = arctan(h / d)`` (``h`` the camera's height above the target's centre [m]), which
  moves the target down (``y`` grows): ``dy = (arctan(h / d_{k+1}) - arctan(h / d_k)) *
  y_B / gamma_y``.

Mean shift on the weight image (the target's hue back-projection) starts at the prediction; its
converged centroid ``z`` is the measurement. By default the posterior's position is replaced by
``z`` (the paper; the velocity and covariance come from a standard Kalman update with ``z``);
``posterior="update"`` keeps the standard Kalman update. The mean-shift window is the target
size times ``window_scale`` (1 by default; 2 is the paper's back-projection region ``R``).
The track is lost in a frame when the converged window's mean weight is below ``min_fill``:
the filter then only predicts and reports ``lost``. :class:`PlainMeanShift` is the baseline:
mean shift from the last position, no prediction.

**Depth** from the target's known size (pinhole camera): ``d = f * size / apparent_size``, ``f``
the focal length [px] (:func:`focal_length_px`: ``f = (n / 2) / tan(fov / 2)`` for ``n``
pixels across a field of view ``fov``), and the apparent size measured by a shape histogram
(:func:`apparent_height`). :class:`KalmanMeanShift` uses it for ``d_k`` when given the
target's height.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from ..kalman.core import KalmanFilter
from ..particle.core import systematic_resample

__all__ = ["mean_shift", "MeanShiftParticleFilter", "ParticleFilterTracker", "KalmanMeanShift",
           "PlainMeanShift", "depth_from_size", "focal_length_px", "apparent_height",
           "ego_motion_shift"]

FeatureCheck = Callable[[np.ndarray, np.ndarray], np.ndarray]
KERNELS = ("flat", "epanechnikov")


# ------------------------------------------------------------------------------------------
# Argument checks
# ------------------------------------------------------------------------------------------

def _number(name: str, value, low: float = 0.0, allow_low: bool = False,
            high: float | None = None) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < low or (v == low and not allow_low) or (
            high is not None and v > high):
        rng = f"{'>=' if allow_low else '>'} {low}" + ("" if high is None else f", <= {high}")
        raise ValueError(f"{name} must be finite and {rng}, got {value!r}")
    return v


def _count(name: str, value, low: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


def _image(name: str, image, shape: tuple[int, int] | None = None,
           scan: bool = False) -> np.ndarray:
    """``image`` as a C-contiguous float32/float64 2-D array (a copy only if needed). Values
    are scanned (finite, non-negative) only when ``scan``: a per-frame scan of a 640 x 480
    image would cost as much as the tracking."""
    arr = np.asarray(image)
    if arr.ndim != 2 or arr.shape[0] < 1 or arr.shape[1] < 1:
        raise ValueError(f"{name} must be a 2-D image, got shape {arr.shape}")
    if arr.dtype not in (np.float32, np.float64):
        if not (np.issubdtype(arr.dtype, np.number) and not np.iscomplexobj(arr)):
            raise ValueError(f"{name} must be a real-valued image, got dtype {arr.dtype}")
        arr = arr.astype(np.float32)
    if shape is not None and arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    if scan and not (np.all(np.isfinite(arr)) and arr.min() >= 0.0):
        raise ValueError(f"{name} must be finite and non-negative")
    return np.ascontiguousarray(arr)


def _window_size(name: str, value) -> tuple[int, int]:
    try:
        w, h = value
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be (w, h) in pixels, got {value!r}") from None
    return _count(f"{name}[0] (w)", w), _count(f"{name}[1] (h)", h)


def _point(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64)
    if arr.shape != (2,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be a finite (x, y) pair, got {value!r}")
    return arr


# ------------------------------------------------------------------------------------------
# Batched mean shift on windows of one size
# ------------------------------------------------------------------------------------------

class _Windows:
    """Windows of one size ``(w, h)`` in images of one shape: flat pixel offsets and the
    moment matrix ``[k, k x, k y, 1]`` ((h w, 4), local coordinates) of the kernel ``k``."""

    def __init__(self, w: int, h: int, shape: tuple[int, int], kernel: str = "flat",
                 opencv: bool = False) -> None:
        if kernel not in KERNELS:
            raise ValueError(f"kernel must be one of {KERNELS}, got {kernel!r}")
        height, width = shape
        if w > width or h > height:
            raise ValueError(f"window size ({w}, {h}) must fit in the image ({width} x "
                             f"{height})")
        self.w, self.h, self.width, self.height = w, h, width, height
        ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
        self.cx, self.cy = 0.5 * (w - 1), 0.5 * (h - 1)
        # The point the centroid is compared with: the window's centre, or OpenCV's w / 2.
        self.ox, self.oy = (0.5 * w, 0.5 * h) if opencv else (self.cx, self.cy)
        if kernel == "flat":
            k = np.ones_like(xs)
        else:  # Epanechnikov profile k = 1 - r^2 on the ellipse inscribed in the window
            r2 = ((xs - self.cx) / (0.5 * w)) ** 2 + ((ys - self.cy) / (0.5 * h)) ** 2
            k = np.maximum(1.0 - r2, 0.0)
        self.moments = np.stack([k, k * xs, k * ys, np.ones_like(xs)], axis=-1).reshape(-1, 4)
        self.offsets = (np.arange(h)[:, None] * width + np.arange(w)[None, :]).ravel()
        self.area = w * h

    def corner(self, centres: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Top-left pixels of the windows centred (to the nearest pixel) at ``centres``
        ((N, 2)), shifted inside the image."""
        x0 = np.clip(np.rint(centres[:, 0] - self.cx), 0, self.width - self.w).astype(np.intp)
        y0 = np.clip(np.rint(centres[:, 1] - self.cy), 0, self.height - self.h).astype(np.intp)
        return x0, y0

    def gather(self, flat: np.ndarray, x0: np.ndarray, y0: np.ndarray) -> np.ndarray:
        """The windows' pixels, ``(N, h w)``."""
        return flat[(y0 * self.width + x0)[:, None] + self.offsets]

    def moments_of(self, flats: Sequence[tuple[np.ndarray, float]], x0: np.ndarray,
                   y0: np.ndarray) -> np.ndarray:
        """``(N, 4)`` kernel moments ``(m00, m10, m01, mass)`` (local coordinates; ``mass``
        the plain sum) of the image ``sum_j c_j I_j`` given as ``[(flat I_j, c_j)]``."""
        patch = None
        for flat, c in flats:
            p = self.gather(flat, x0, y0)
            part = p if c == 1.0 else c * p
            patch = part if patch is None else patch + part
        return patch.astype(np.float64, copy=False) @ self.moments

    def shift(self, flats: Sequence[tuple[np.ndarray, float]], x0: np.ndarray, y0: np.ndarray,
              max_iter: int, eps: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Mean shift of every window (see the module docstring). Returns the converged
        corners, the iteration counts and the moments at the converged windows."""
        x0, y0 = x0.copy(), y0.copy()
        n = len(x0)
        iters = np.zeros(n, dtype=np.intp)
        active = np.arange(n)
        eps2 = eps * eps
        for _ in range(max_iter):
            mom = self.moments_of(flats, x0[active], y0[active])
            m00 = mom[:, 0]
            has_mass = m00 > 1e-12
            safe = np.where(has_mass, m00, 1.0)
            dx = np.where(has_mass, np.rint(mom[:, 1] / safe - self.ox), 0.0).astype(np.intp)
            dy = np.where(has_mass, np.rint(mom[:, 2] / safe - self.oy), 0.0).astype(np.intp)
            nx = np.clip(x0[active] + dx, 0, self.width - self.w)
            ny = np.clip(y0[active] + dy, 0, self.height - self.h)
            mx, my = nx - x0[active], ny - y0[active]
            iters[active[has_mass]] += 1
            x0[active], y0[active] = nx, ny
            moving = has_mass & ((mx != 0) | (my != 0)) & (mx * mx + my * my >= eps2)
            active = active[moving]
            if active.size == 0:
                break
        return x0, y0, iters, self.moments_of(flats, x0, y0)

    def centroids(self, mom: np.ndarray, x0: np.ndarray, y0: np.ndarray) -> np.ndarray:
        """Image coordinates of the kernel-weighted centroids ((N, 2)); the window centre
        where the window holds no weight."""
        m00 = mom[:, 0]
        safe = np.where(m00 > 1e-12, m00, 1.0)
        cx = np.where(m00 > 1e-12, mom[:, 1] / safe, self.cx)
        cy = np.where(m00 > 1e-12, mom[:, 2] / safe, self.cy)
        return np.stack([x0 + cx, y0 + cy], axis=1)


def mean_shift(weight_image: np.ndarray, window: Sequence[int], max_iter: int = 10,
               eps: float = 0.5, kernel: str = "flat", opencv_compatible: bool = False
               ) -> tuple[np.ndarray, tuple[int, int, int, int], int, float]:
    """Mean shift of one window on a non-negative weight image (see the module docstring).

    Args:
        weight_image: ``(H, W)`` non-negative weights (e.g. a colour back-projection).
        window: ``(x, y, w, h)`` [px], the starting window (top-left pixel and size); shifted
            inside the image if it sticks out.
        max_iter: at most this many mean-shift steps.
        eps: stop when the window moves less than this [px] (or not at all).
        kernel: ``"flat"`` (as ``cv2.meanShift``) or ``"epanechnikov"``.
        opencv_compatible: compare the centroid with ``(w / 2, h / 2)`` as OpenCV does (its
            windows, exactly) instead of the window's centre ``((w - 1) / 2, (h - 1) / 2)``.

    Returns:
        ``(centre, window, iterations, mass)``: the centroid ``(x, y)`` [px] of the
        (kernel-weighted) weights in the converged window (its centre if it holds none), the
        converged window ``(x, y, w, h)``, the number of steps taken and the sum of the
        weights inside the converged window.
    """
    img = _image("weight_image", weight_image, scan=True)
    try:
        x, y, w, h = (int(v) for v in window)
        if any(float(a) != int(a) for a in window):
            raise TypeError
    except (TypeError, ValueError):
        raise ValueError(f"window must be four integers (x, y, w, h), got {window!r}") from None
    _count("window w", w)
    _count("window h", h)
    max_iter = _count("max_iter", max_iter)
    eps = _number("eps", eps, allow_low=True)
    win = _Windows(w, h, img.shape, kernel, bool(opencv_compatible))
    x0 = np.clip(np.array([x], dtype=np.intp), 0, img.shape[1] - w)
    y0 = np.clip(np.array([y], dtype=np.intp), 0, img.shape[0] - h)
    x0, y0, iters, mom = win.shift([(img.ravel(), 1.0)], x0, y0, max_iter, eps)
    centre = win.centroids(mom, x0, y0)[0]
    return centre, (int(x0[0]), int(y0[0]), w, h), int(iters[0]), float(mom[0, 3])


# ------------------------------------------------------------------------------------------
# Paper 003: particle filters on window likelihoods
# ------------------------------------------------------------------------------------------

class _WindowParticleFilter:
    """The motion model, likelihood and bookkeeping shared by the two particle trackers."""

    def __init__(self, position, window_size, rng: np.random.Generator, *, n_particles: int,
                 velocity=(0.0, 0.0), process_sigma: float = 4.0,
                 likelihood_sigma: float = 0.15, init_sigma: float = 2.0, v_ref: float = 20.0,
                 max_motion_weight: float = 0.5) -> None:
        if not isinstance(rng, np.random.Generator):
            raise ValueError(f"rng must be a numpy.random.Generator, got {type(rng).__name__}")
        self.rng = rng
        p = _point("position", position)
        v = _point("velocity", velocity)
        self.window_size = _window_size("window_size", window_size)
        self.n = _count("n_particles", n_particles, 2)
        self.process_sigma = _number("process_sigma", process_sigma, allow_low=True)
        self.likelihood_sigma = _number("likelihood_sigma", likelihood_sigma)
        self.init_sigma = _number("init_sigma", init_sigma, allow_low=True)
        self.v_ref = _number("v_ref", v_ref)
        self.max_motion_weight = _number("max_motion_weight", max_motion_weight,
                                         allow_low=True, high=1.0)
        self.estimate = np.concatenate([p, v])
        self._seed(p, v)
        self.frame = 0
        self.motion_weight = 0.0
        self._win: _Windows | None = None

    def _seed(self, p: np.ndarray, v: np.ndarray) -> None:
        """Particles ``N(p, init_sigma^2 I)`` with velocity ``v``, equal weights."""
        self.particles = np.empty((self.n, 4))
        self.particles[:, :2] = p + self.rng.normal(0.0, self.init_sigma, (self.n, 2))
        self.particles[:, 2:] = v
        self.weights = np.full(self.n, 1.0 / self.n)

    def _images(self, colour_image, motion_image):
        colour = _image("colour_image", colour_image)
        motion = None if motion_image is None else _image("motion_image", motion_image,
                                                          colour.shape)
        if self._win is None or (self._win.height, self._win.width) != colour.shape:
            self._win = self._make_windows(colour.shape)
        return colour, motion

    def _make_windows(self, shape: tuple[int, int]) -> _Windows:
        return _Windows(*self.window_size, shape)

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
        np.clip(self.particles[:, 0], 0.0, wd - 1.0, out=self.particles[:, 0])
        np.clip(self.particles[:, 1], 0.0, h - 1.0, out=self.particles[:, 1])

    def _log_likelihood(self, combined_mass: np.ndarray) -> np.ndarray:
        """``log w = -Dis^2 / (2 sigma^2)``, ``Dis^2 = 1 - M / M_t``."""
        dis2 = np.maximum(1.0 - combined_mass / self._win.area, 0.0)
        return -dis2 / (2.0 * self.likelihood_sigma ** 2)

    def _weigh_and_estimate(self, logw: np.ndarray, allowed: np.ndarray | None = None
                            ) -> np.ndarray:
        """Normalised weights (zero where not ``allowed``), weighted-mean estimate, then
        systematic resampling."""
        if allowed is not None:
            logw = np.where(allowed, logw, -np.inf)
        w = np.exp(logw - logw.max())
        w /= w.sum()
        self.weights = w
        self.estimate = w @ self.particles
        idx = systematic_resample(w, self.rng)
        self.particles = self.particles[idx]
        self.weights = np.full(self.n, 1.0 / self.n)
        return self.estimate.copy()

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
    """Plain particle filter on window likelihoods: paper 003's baseline (see the module
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

    def __init__(self, position, window_size, rng: np.random.Generator, *,
                 n_particles: int = 200, velocity=(0.0, 0.0), process_sigma: float = 4.0,
                 likelihood_sigma: float = 0.15, init_sigma: float = 2.0, v_ref: float = 20.0,
                 max_motion_weight: float = 0.5) -> None:
        super().__init__(position, window_size, rng, n_particles=n_particles,
                         velocity=velocity, process_sigma=process_sigma,
                         likelihood_sigma=likelihood_sigma, init_sigma=init_sigma,
                         v_ref=v_ref, max_motion_weight=max_motion_weight)

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
        mom = self._win.moments_of(flats, x0, y0)
        return self._weigh_and_estimate(self._log_likelihood(mom[:, 3]))


class MeanShiftParticleFilter(_WindowParticleFilter):
    """Feature-restricted mean-shift particle filter of paper 003 (Li, Wu and Kong 2010) for
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
        kernel: ``"flat"`` or ``"epanechnikov"``.
        area: the target's colour mass ``sum_W M_c`` with the window on it [px^2] (its patch
            area weighted by colour probability); None: measured on the first image,
            in the window that mean shift (colour only) reaches from ``position``.
        area_tolerance: a window is allowed when its colour mass is within
            ``area * (1 +- area_tolerance)``.
        feature_check: optional ``f(windows, colour_image) -> (N,) bool``, ``windows`` an
            ``(N, 4)`` int array of ``(x, y, w, h)``: further patch constraints (layout,
            heading, identity); also applied to the global search's candidate.

    Attributes:
        estimate: ``(x, y, vx, vy)`` [px, px/frame].
        lost: the track was lost in the last frame (the next update searches globally).
        occluded: the last frame placed the target at an occluding robot (ball rule).
        occluder: that robot's index, else None.
        lost_frames: frames reported lost so far.
        area: the target's colour mass in use [px^2].
        motion_weight: the last frame's ``a``.
    """

    def __init__(self, position, window_size, rng: np.random.Generator, *,
                 n_particles: int = 20, velocity=(0.0, 0.0), process_sigma: float = 4.0,
                 likelihood_sigma: float = 0.15, init_sigma: float = 2.0, v_ref: float = 20.0,
                 max_motion_weight: float = 0.5, mean_shift_iter: int = 5, eps: float = 0.5,
                 kernel: str = "flat", area: float | None = None, area_tolerance: float = 0.3,
                 feature_check: FeatureCheck | None = None) -> None:
        super().__init__(position, window_size, rng, n_particles=n_particles,
                         velocity=velocity, process_sigma=process_sigma,
                         likelihood_sigma=likelihood_sigma, init_sigma=init_sigma,
                         v_ref=v_ref, max_motion_weight=max_motion_weight)
        self.mean_shift_iter = _count("mean_shift_iter", mean_shift_iter, 0)
        self.eps = _number("eps", eps, allow_low=True)
        if kernel not in KERNELS:
            raise ValueError(f"kernel must be one of {KERNELS}, got {kernel!r}")
        self.kernel = kernel
        self.area = None if area is None else _number("area", area)
        self.area_tolerance = _number("area_tolerance", area_tolerance)
        if feature_check is not None and not callable(feature_check):
            raise ValueError("feature_check must be callable or None")
        self.feature_check = feature_check
        self.lost = False
        self.occluded = False
        self.occluder: int | None = None
        self.lost_frames = 0

    def _make_windows(self, shape: tuple[int, int]) -> _Windows:
        return _Windows(*self.window_size, shape, self.kernel)

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

    def occluded_by(self, robot_positions, robot_radius_px: float,
                    predicted=None) -> int | None:
        """Paper 003's ball occlusion test: the index of the robot nearest to the target's
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
        r = _number("robot_radius_px", robot_radius_px, allow_low=True)
        robots = np.asarray(robot_positions, dtype=np.float64).reshape(-1, 2) \
            if np.size(robot_positions) else np.empty((0, 2))
        if not np.all(np.isfinite(robots)):
            raise ValueError("robot_positions must be finite (x, y) rows")
        p = (self.estimate[:2] + self.estimate[2:] if predicted is None
             else _point("predicted", predicted))
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
        colour, _ = self._images(colour_image, None)
        win = self._win
        w, h = win.w, win.h
        s = np.zeros((colour.shape[0] + 1, colour.shape[1] + 1))
        np.cumsum(colour, axis=0, out=s[1:, 1:])
        np.cumsum(s[1:, 1:], axis=1, out=s[1:, 1:])
        box = s[h:, w:] - s[:-h, w:] - s[h:, :-w] + s[:-h, :-w]  # (H-h+1, W-w+1)
        area = self._area_in_use(colour)
        ok = np.abs(box - area) <= self.area_tolerance * area
        if not ok.any():
            return None
        score = np.where(ok, box, -np.inf).ravel()
        top = np.argsort(-score)[: 50 * candidates]
        picks: list[tuple[int, int]] = []
        for flat in top.tolist():  # greedy: the largest masses, a window apart
            if not math.isfinite(score[flat]) or len(picks) == candidates:
                break
            y, x = divmod(flat, box.shape[1])
            if all(abs(x - px) >= w or abs(y - py) >= h for px, py in picks):
                picks.append((x, y))
        x0 = np.array([p[0] for p in picks], dtype=np.intp)
        y0 = np.array([p[1] for p in picks], dtype=np.intp)
        flats = [(colour.ravel(), 1.0)]
        x0, y0, _, mom = win.shift(flats, x0, y0, max(self.mean_shift_iter, 1), self.eps)
        allowed = self._allowed(mom[:, 3], x0, y0, colour)
        if not allowed.any():
            return None
        return win.centroids(mom, x0, y0)[int(np.argmax(allowed))]

    def _area_in_use(self, colour: np.ndarray) -> float:
        if self.area is None:  # calibrate on the first image, mean shift from the start
            x0, y0 = self._win.corner(self.estimate[None, :2])
            _, _, _, mom = self._win.shift([(colour.ravel(), 1.0)], x0, y0,
                                           max(self.mean_shift_iter, 1), self.eps)
            mass = float(mom[0, 3])
            if mass <= 0.0:
                raise ValueError("area is None and the first colour image holds no weight in "
                                 "the initial window: pass area")
            self.area = mass
        return self.area

    def update(self, colour_image: np.ndarray, motion_image: np.ndarray | None = None,
               robots=None, robot_radius_px: float | None = None) -> np.ndarray:
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
            found = self.global_search(colour)
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
        if self.mean_shift_iter > 0:
            x0, y0, _, mom = win.shift(flats, x0, y0, self.mean_shift_iter, self.eps)
            moved = win.centroids(mom, x0, y0)
            shift = moved - self.particles[:, :2]
            self.particles[:, :2] = moved
            self.particles[:, 2:] += shift  # v_t = p_t - p_{t-1}
        else:
            mom = win.moments_of(flats, x0, y0)
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
        return self._weigh_and_estimate(self._log_likelihood(mom[:, 3]), allowed)


# ------------------------------------------------------------------------------------------
# Paper 004: Kalman-started mean shift with ego-motion compensation
# ------------------------------------------------------------------------------------------

def focal_length_px(pixels: float, fov: float) -> float:
    """Pinhole focal length [px] of ``pixels`` across a field of view ``fov`` [rad]:
    ``f = (pixels / 2) / tan(fov / 2)``."""
    n = _number("pixels", pixels)
    a = _number("fov", fov)
    if a >= math.pi:
        raise ValueError(f"fov must be < pi rad, got {fov!r}")
    return 0.5 * n / math.tan(0.5 * a)


def depth_from_size(size_m: float, apparent_size_px: float, focal_px: float) -> float:
    """Distance [m] of a target of known size ``size_m`` [m] that appears ``apparent_size_px``
    [px] large (pinhole): ``d = f * size / apparent_size``, ``f = focal_px`` [px]."""
    return (_number("focal_px", focal_px) * _number("size_m", size_m)
            / _number("apparent_size_px", apparent_size_px))


def apparent_height(weight_image: np.ndarray, window: Sequence[int], threshold: float = 0.5,
                    min_fraction: float = 0.2) -> float:
    """The target's height [px] in ``window`` ``(x, y, w, h)`` by a shape histogram (paper
    004): the foreground pixels (weight ``>= threshold``) are projected onto the vertical
    axis (a count per row); the target spans the rows from the first to the last whose count
    is at least ``min_fraction`` times the largest. Returns 0 when no pixel is foreground.
    The window is clipped to the image."""
    img = _image("weight_image", weight_image)
    try:
        x, y, w, h = (int(v) for v in window)
    except (TypeError, ValueError):
        raise ValueError(f"window must be four integers (x, y, w, h), got {window!r}") from None
    _count("window w", w)
    _count("window h", h)
    _number("threshold", threshold, allow_low=True)
    _number("min_fraction", min_fraction, allow_low=True, high=1.0)
    x1, y1 = max(x, 0), max(y, 0)
    x2, y2 = min(x + w, img.shape[1]), min(y + h, img.shape[0])
    if x2 <= x1 or y2 <= y1:
        return 0.0
    counts = (img[y1:y2, x1:x2] >= threshold).sum(axis=1)
    top = counts.max()
    if top == 0:
        return 0.0
    rows = np.flatnonzero(counts >= max(min_fraction * top, 1))
    return float(rows[-1] - rows[0] + 1)


def ego_motion_shift(rotation: float, advance: float, image_size: Sequence[int],
                     fov: Sequence[float], camera_height: float = 0.0,
                     distance: float | None = None) -> np.ndarray:
    """Image shift ``(dx, dy)`` [px] of a target caused by the robot's own motion over one
    frame (paper 004, see the module docstring):
    ``dx = theta * x_B / gamma_x`` (``theta = rotation`` [rad], positive counter-clockwise,
    i.e. a left turn, which moves the scene right) and
    ``dy = (arctan(h / (d - s)) - arctan(h / d)) * y_B / gamma_y`` (``s = advance`` [m]
    towards the target, ``d = distance`` [m] before the move, ``h = camera_height`` [m] above
    the target's centre; ``d - s`` floored at 1 mm). ``distance`` is needed when
    ``advance != 0``."""
    theta = float(rotation)
    s = float(advance)
    if not (math.isfinite(theta) and math.isfinite(s)):
        raise ValueError(f"rotation and advance must be finite, got {rotation!r}, {advance!r}")
    xb, yb = _window_size("image_size", image_size)
    try:
        gx, gy = (float(a) for a in fov)
    except (TypeError, ValueError):
        raise ValueError(f"fov must be (gamma_x, gamma_y) [rad], got {fov!r}") from None
    _number("fov[0] (gamma_x)", gx)
    _number("fov[1] (gamma_y)", gy)
    dx = theta * xb / gx
    dy = 0.0
    if s != 0.0:
        if distance is None:
            raise ValueError("distance is needed when advance != 0")
        d = _number("distance", distance)
        h = float(camera_height)
        if not math.isfinite(h):
            raise ValueError(f"camera_height must be finite, got {camera_height!r}")
        d1 = max(d - s, 1e-3)
        dy = (math.atan2(h, d1) - math.atan2(h, d)) * yb / gy
    return np.array([dx, dy])


class _MeanShiftTrack:
    """Shared by the two mean-shift trackers: the window, one mean shift, the lost test."""

    def __init__(self, window_size, window_scale: float, max_iter: int, eps: float,
                 kernel: str, min_fill: float) -> None:
        w, h = _window_size("window_size", window_size)
        self.window_scale = _number("window_scale", window_scale)
        self.target_size = (w, h)
        self.window_size = (max(int(round(w * self.window_scale)), 1),
                            max(int(round(h * self.window_scale)), 1))
        self.max_iter = _count("max_iter", max_iter)
        self.eps = _number("eps", eps, allow_low=True)
        if kernel not in KERNELS:
            raise ValueError(f"kernel must be one of {KERNELS}, got {kernel!r}")
        self.kernel = kernel
        self.min_fill = _number("min_fill", min_fill, allow_low=True, high=1.0)
        self._win: _Windows | None = None
        self.lost = False
        self.lost_frames = 0
        self.fill = 0.0
        self.window: tuple[int, int, int, int] | None = None

    def _shift_from(self, image, start: np.ndarray) -> tuple[np.ndarray | None, np.ndarray]:
        """Mean shift from the window centred at ``start``; returns the centroid (None if
        the converged window's mean weight is below ``min_fill``) and the flat image."""
        img = _image("weight_image", image)
        if self._win is None or (self._win.height, self._win.width) != img.shape:
            self._win = _Windows(*self.window_size, img.shape, self.kernel)
        win = self._win
        x0, y0 = win.corner(start[None, :])
        x0, y0, _, mom = win.shift([(img.ravel(), 1.0)], x0, y0, self.max_iter, self.eps)
        self.window = (int(x0[0]), int(y0[0]), win.w, win.h)
        self.fill = float(mom[0, 3]) / win.area
        if self.fill < self.min_fill:
            return None, img
        return win.centroids(mom, x0, y0)[0], img


class PlainMeanShift(_MeanShiftTrack):
    """Mean shift from the last position, no prediction: paper 004's baseline.

    Args:
        position: initial ``(x, y)`` [px].
        window_size: the target's size ``(w, h)`` [px].
        window_scale: the mean-shift window is ``window_scale`` times the target size.
        max_iter, eps, kernel: as :func:`mean_shift`.
        min_fill: the track is lost in a frame whose converged window's mean weight is below
            this (the position then stays).

    Attributes:
        position: ``(x, y)`` [px]; lost, lost_frames, fill (the last window's mean weight),
        window (the last converged window).
    """

    def __init__(self, position, window_size, *, window_scale: float = 1.0, max_iter: int = 10,
                 eps: float = 0.5, kernel: str = "flat", min_fill: float = 0.2) -> None:
        super().__init__(window_size, window_scale, max_iter, eps, kernel, min_fill)
        self.position = _point("position", position).copy()

    def update(self, weight_image: np.ndarray) -> np.ndarray:
        """One frame on the weight image ``(H, W)``; returns the position ``(x, y)`` [px]."""
        z, _ = self._shift_from(weight_image, self.position)
        self.lost = z is None
        if self.lost:
            self.lost_frames += 1
        else:
            self.position = z
        return self.position.copy()


class KalmanMeanShift(_MeanShiftTrack):
    """Kalman-started mean shift with ego-motion compensation, paper 004 (Yu, Wei and Zhang
    2010); see the module docstring for the model, the sign conventions and our readings.

    Args:
        position: initial ``(x, y)`` [px].
        window_size: the target's size ``(w, h)`` in the image [px].
        image_size: ``(x_B, y_B)``, the image's width and height [px].
        fov: ``(gamma_x, gamma_y)``, the horizontal and vertical fields of view [rad].
        camera_height: ``h``, the camera's height above the target's centre [m].
        distance: the target's ground distance ``d`` [m] now, if known (updated by dead
            reckoning ``d - s`` and, with ``target_height_m``, from the apparent size).
        target_height_m: the target's real height [m]: each frame's distance is then
            estimated from its apparent height (:func:`apparent_height` in a region twice the
            window, :func:`depth_from_size` with the vertical focal length).
        velocity: initial ``(vx, vy)`` [px/frame].
        accel_sigma: white-acceleration process noise [px/frame^2].
        measurement_sigma: mean shift's position noise [px].
        init_sigma: initial ``(position, velocity)`` standard deviations [px, px/frame].
        posterior: ``"replace"`` (the paper: the posterior position is the mean-shift
            position) or ``"update"`` (a standard Kalman update).
        window_scale: the mean-shift window is ``window_scale`` times the target size
            (1 by default; 2 is the paper's back-projection region ``R``).
        max_iter, eps, kernel: as :func:`mean_shift`.
        min_fill: the track is lost in a frame whose converged window's mean weight is below
            this.

    Attributes:
        kf: the :class:`~estimators.kalman.KalmanFilter` on ``(x, y, vx, vy)``.
        lost, lost_frames, fill, window: as :class:`PlainMeanShift`.
        prediction: the last predicted ``(x, y)`` [px] (where mean shift started).
        distance: the target's current distance estimate [m] (None if unknown).
    """

    def __init__(self, position, window_size, *, image_size: Sequence[int],
                 fov: Sequence[float], camera_height: float = 0.0,
                 distance: float | None = None, target_height_m: float | None = None,
                 velocity=(0.0, 0.0), accel_sigma: float = 2.0, measurement_sigma: float = 2.0,
                 init_sigma: Sequence[float] = (2.0, 5.0), posterior: str = "replace",
                 window_scale: float = 1.0, max_iter: int = 10, eps: float = 0.5,
                 kernel: str = "flat", min_fill: float = 0.2) -> None:
        super().__init__(window_size, window_scale, max_iter, eps, kernel, min_fill)
        self.image_size = _window_size("image_size", image_size)
        ego_motion_shift(0.0, 0.0, self.image_size, fov)  # validates fov
        self.fov = (float(fov[0]), float(fov[1]))
        self.camera_height = float(camera_height)
        if not math.isfinite(self.camera_height):
            raise ValueError(f"camera_height must be finite, got {camera_height!r}")
        self.distance = None if distance is None else _number("distance", distance)
        self.target_height_m = (None if target_height_m is None
                                else _number("target_height_m", target_height_m))
        self.focal_y = focal_length_px(self.image_size[1], self.fov[1])
        if posterior not in ("replace", "update"):
            raise ValueError(f"posterior must be 'replace' or 'update', got {posterior!r}")
        self.posterior = posterior
        sa = _number("accel_sigma", accel_sigma, allow_low=True)
        sm = _number("measurement_sigma", measurement_sigma)
        try:
            sp, sv = (float(v) for v in init_sigma)
        except (TypeError, ValueError):
            raise ValueError(f"init_sigma must be (position, velocity) standard deviations, "
                             f"got {init_sigma!r}") from None
        _number("init_sigma[0]", sp)
        _number("init_sigma[1]", sv)
        x = np.concatenate([_point("position", position), _point("velocity", velocity)])
        self.kf = KalmanFilter(x, np.diag([sp * sp, sp * sp, sv * sv, sv * sv]))
        self.F = np.array([[1.0, 0, 1, 0], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]])
        G = np.array([[0.5, 0], [0, 0.5], [1, 0], [0, 1]])
        self.Q = sa * sa * G @ G.T  # white acceleration over one frame
        self.H = np.eye(2, 4)
        self.R = sm * sm * np.eye(2)
        self.prediction = x[:2].copy()

    @property
    def state(self) -> np.ndarray:
        """``(x, y, vx, vy)`` [px, px/frame]."""
        return self.kf.x.copy()

    def predict(self, rotation: float = 0.0, advance: float = 0.0,
                distance: float | None = None) -> np.ndarray:
        """Time update with the robot's motion ``u = (rotation [rad], advance [m])`` over the
        last frame: ``X = A X + (dx, dy, 0, 0)`` with the ego-motion shift
        (:func:`ego_motion_shift`), ``P = A P A^T + Q``. ``distance`` [m] overrides the
        tracker's distance estimate (needed when ``advance != 0``). Returns the predicted
        ``(x, y)`` [px]."""
        d = self.distance if distance is None else _number("distance", distance)
        shift = ego_motion_shift(rotation, advance, self.image_size, self.fov,
                                 self.camera_height, d)
        x_pred = self.F @ self.kf.x
        x_pred[:2] += shift
        self.kf.predict(self.F, self.Q, x_pred)
        if d is not None:
            self.distance = max(d - float(advance), 1e-3)
        self.prediction = self.kf.x[:2].copy()
        return self.prediction.copy()

    def shift(self, du: float, dv: float) -> None:
        """Move the state by an image shift known from elsewhere [px], e.g. the head's servos:
        a pan by ``a`` [rad] (left positive) moves the scene by ``a x_B / gamma_x`` to the
        right, a tilt by ``b`` (down positive) by ``b y_B / gamma_y`` upwards (``dv < 0``)."""
        self.kf.x[0] += float(du)
        self.kf.x[1] += float(dv)

    def update(self, weight_image: np.ndarray, rotation: float = 0.0, advance: float = 0.0,
               distance: float | None = None) -> np.ndarray:
        """One frame: :meth:`predict` with the robot's motion, mean shift on ``weight_image``
        (the hue back-projection, ``(H, W)``) from the prediction, then the measurement
        update (or, when lost, the prediction alone). Returns ``(x, y, vx, vy)``."""
        start = self.predict(rotation, advance, distance)
        z, img = self._shift_from(weight_image, start)
        self.lost = z is None
        if self.lost:
            # A lost target is taken to stand where it was last predicted: its own velocity
            # is forgotten (extrapolating it would carry the window away for good), while
            # the robot's own motion still moves it in the image.
            self.lost_frames += 1
            self.kf.update(None, self.H, self.R)
            self.kf.x[2:] = 0.0
            return self.state
        self.kf.update(z, self.H, self.R)
        if self.posterior == "replace":
            self.kf.x[:2] = z
        if self.target_height_m is not None:
            w, h = self.window_size
            region = (int(round(z[0] - w)), int(round(z[1] - h)), 2 * w, 2 * h)
            size = apparent_height(img, region)
            if size > 0.0:
                self.distance = depth_from_size(self.target_height_m, size, self.focal_y)
        return self.state
