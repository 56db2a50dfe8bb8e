"""Mean shift on weight images: the building block of the image trackers of Li et al. (2010)
(Li, Wu, Kong 2010; :mod:`estimators.image.mspf`) and Yu, Wei and Zhang (2010;
:mod:`estimators.image.following`), with the window machinery and argument checks they share.

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
of the image size. The gather and the step are compiled kernels
(:mod:`~estimators.image.window_kernels`); the product stays numpy's (the BLAS library's
order of summation, which the results depend on in their last bits).
Summed-area tables (integral images) make a window's sum ``O(1)`` but cost
``O(H W)`` per image and per moment (three tables per image for mean shift): they pay when
many targets share one image, and are used here only for the global search (one table, the
sum of every window position at once).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..registry import Registry
from .checks import check_fits, check_image, check_int, check_number
from .window_kernels import gather_windows, mean_shift_step

__all__ = ["mean_shift", "MEAN_SHIFT_KERNELS", "RegionImage", "MeanShiftWindows",
           "check_moments"]


def _flat(xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """The flat kernel: every pixel of the window weighs 1."""
    return np.ones_like(xs)


def _epanechnikov(xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """The Epanechnikov profile ``k = max(0, 1 - r^2)`` on the ellipse inscribed in the
    window (see the module docstring)."""
    h, w = xs.shape
    cx, cy = 0.5 * (w - 1), 0.5 * (h - 1)
    r2 = ((xs - cx) / (0.5 * w)) ** 2 + ((ys - cy) / (0.5 * h)) ** 2
    return np.maximum(1.0 - r2, 0.0)


#: Mean-shift kernels by name: ``k(xs, ys) -> (h, w)`` weights of a window's pixels from their
#: local coordinates ``xs``, ``ys`` (``(h, w)`` arrays, ``0 .. w - 1`` and ``0 .. h - 1``).
MEAN_SHIFT_KERNELS = Registry("mean-shift kernel", [
    ("flat", _flat,
     "flat kernel: every pixel in the window counts the same (as OpenCV's cv2.meanShift)"),
    ("epanechnikov", _epanechnikov,
     "Epanechnikov kernel (Comaniciu et al.): pixels weighted by 1 - r^2 on the ellipse "
     "inscribed in the window, so those near its centre count most"),
])


class RegionImage:
    """An ``(H, W)`` weight image computed region by region, when a tracker asks for it.

    A colour look-up over a whole camera image costs more than tracking a few targets in it,
    which read only the pixels around their particles. The trackers that take a
    :class:`RegionImage` (:class:`~estimators.image.mspf.MeanShiftParticleFilter`) ask for
    every region they may read before reading it (:meth:`ensure`: the particles' windows
    widened by the longest way mean shift can take them), and for the whole image when they
    search all of it; the pixels of :attr:`array` outside the regions asked for stay 0 and are
    never read. So the results are those of the whole image, computed.

    Args:
        shape: ``(H, W)``.
        fill: ``fill(x0, y0, x1, y1)`` -> the ``(y1 - y0, x1 - x0)`` pixels of the box
            ``x0 <= x < x1``, ``y0 <= y < y1``.
        dtype: the image's type (float32 by default).
    """

    def __init__(self, shape: tuple[int, int], fill, dtype=np.float32) -> None:
        self.shape = (int(shape[0]), int(shape[1]))
        self.array = np.zeros(self.shape, dtype=dtype)
        self._fill = fill
        self._boxes: list[tuple[int, int, int, int]] = []

    def ensure(self, x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
        """Compute the pixels of the box ``x0 <= x < x1``, ``y0 <= y < y1`` (clipped to the
        image) unless a box computed before holds it; returns :attr:`array`."""
        h, w = self.shape
        a, b = max(0, int(math.floor(x0))), max(0, int(math.floor(y0)))
        c, d = min(w, int(math.ceil(x1))), min(h, int(math.ceil(y1)))
        if a >= c or b >= d:
            return self.array
        for p, q, r, t in self._boxes:
            if p <= a and q <= b and r >= c and t >= d:
                return self.array
        self.array[b:d, a:c] = self._fill(a, b, c, d)
        self._boxes.append((a, b, c, d))
        return self.array

    def refill(self, fill) -> RegionImage:
        """This region image started over on a new image of the same shape, ``fill`` its
        pixels' (as the constructor's): the regions computed so far are set back to 0 and
        forgotten, so the image reads as a new one would, without allocating (and zeroing)
        a whole image again. Returns itself."""
        for a, b, c, d in self._boxes:
            self.array[b:d, a:c] = 0
        self._boxes.clear()
        self._fill = fill
        return self

    def full(self) -> np.ndarray:
        """The whole image, computed."""
        return self.ensure(0, 0, self.shape[1], self.shape[0])


# ------------------------------------------------------------------------------------------
# Batched mean shift on windows of one size
# ------------------------------------------------------------------------------------------

class MeanShiftWindows:
    """Windows of one size ``(w, h)`` [px] in images of one shape ``(H, W)``: flat pixel
    offsets and the moment matrix ``[k, k x, k y, 1]`` ((h w, 4), local coordinates) of the
    kernel ``k``, and mean shift on many windows at once (see the module docstring): what
    :func:`mean_shift` and the image trackers (:mod:`estimators.image.mspf`,
    :mod:`estimators.image.following`) run.

    Args:
        w: the window's width [px], at most the image's.
        h: the window's height [px], at most the image's.
        shape: the images' ``(H, W)``.
        kernel: a name in :data:`MEAN_SHIFT_KERNELS`.
        opencv: compare the centroid with ``(w / 2, h / 2)`` as OpenCV does.
    """

    def __init__(self, w: int, h: int, shape: tuple[int, int], kernel: str = "flat",
                 opencv: bool = False) -> None:
        profile = MEAN_SHIFT_KERNELS[MEAN_SHIFT_KERNELS.check(kernel, "kernel")]
        height, width = shape
        check_fits("image", (w, h), shape)
        self.w, self.h, self.width, self.height = w, h, width, height
        ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
        self.cx, self.cy = 0.5 * (w - 1), 0.5 * (h - 1)
        # The point the centroid is compared with: the window's centre, or OpenCV's w / 2.
        self.ox, self.oy = (0.5 * w, 0.5 * h) if opencv else (self.cx, self.cy)
        k = profile(xs, ys)
        self.moments = np.stack([k, k * xs, k * ys, np.ones_like(xs)], axis=-1).reshape(-1, 4)
        self.offsets = (np.arange(h)[:, None] * width + np.arange(w)[None, :]).ravel()
        self.area = w * h

    def corner(self, centres: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Top-left pixels of the windows centred (to the nearest pixel) at ``centres``
        ((N, 2)), shifted inside the image."""
        # np.minimum(np.maximum(...)) is np.clip without its per-call dtype checks (this
        # runs for every window of every tracker of every frame).
        x0 = np.minimum(np.maximum(np.rint(centres[:, 0] - self.cx), 0),
                        self.width - self.w).astype(np.intp)
        y0 = np.minimum(np.maximum(np.rint(centres[:, 1] - self.cy), 0),
                        self.height - self.h).astype(np.intp)
        return x0, y0

    def gather(self, flat: np.ndarray, x0: np.ndarray, y0: np.ndarray) -> np.ndarray:
        """The windows' pixels, ``(N, h w)``."""
        return flat[(y0 * self.width + x0)[:, None] + self.offsets]

    def moments_of(self, flats: Sequence[tuple[np.ndarray, float]], x0: np.ndarray,
                   y0: np.ndarray, name: str = "weight_image") -> np.ndarray:
        """``(N, 4)`` kernel moments ``(m00, m10, m01, mass)`` (local coordinates; ``mass``
        the plain sum) of the image ``sum_j c_j I_j`` given as ``[(flat I_j, c_j)]``;
        ``ValueError`` naming the image ``name`` where they are not finite and non-negative
        (:func:`check_moments`)."""
        x0 = np.ascontiguousarray(x0, dtype=np.intp)
        y0 = np.ascontiguousarray(y0, dtype=np.intp)
        return check_moments(self._moments(flats, x0, y0, np.arange(len(x0)), len(x0)), name)

    def _moments(self, flats: Sequence[tuple[np.ndarray, float]], x0: np.ndarray,
                 y0: np.ndarray, active: np.ndarray, count: int) -> np.ndarray:
        """The moments of the windows ``active[:count]``: their pixels gathered and combined
        by :func:`~estimators.image.window_kernels.gather_windows` (one or two flat images of
        one dtype; more, or mixed dtypes, in numpy), then one matrix product with
        :attr:`moments`."""
        first = flats[0][0]
        if len(flats) <= 2 and all(f.dtype == first.dtype for f, _ in flats):
            second = flats[-1][0]
            scales = np.array([flats[0][1], flats[-1][1]], dtype=first.dtype)
            patch = np.empty((count, self.area))
            gather_windows(first, second, scales, len(flats) == 2, x0, y0, active, count,
                           self.width, self.offsets, patch)
            return patch @ self.moments
        rows = active[:count]
        patch = None
        for flat, c in flats:
            p = self.gather(flat, x0[rows], y0[rows])
            part = p if c == 1.0 else c * p
            patch = part if patch is None else patch + part
        return patch.astype(np.float64, copy=False) @ self.moments

    def shift(self, flats: Sequence[tuple[np.ndarray, float]], x0: np.ndarray, y0: np.ndarray,
              max_iter: int, eps: float, name: str = "weight_image"
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Mean shift of every window (see the module docstring): the moments of the
        windows still moving, then
        :func:`~estimators.image.window_kernels.mean_shift_step`, until none moves or
        ``max_iter`` steps. Returns the converged corners, the iteration counts and the
        moments at the converged windows; ``ValueError`` naming the image ``name`` where the
        first moments are not finite and non-negative (:func:`check_moments`)."""
        x0 = np.array(x0, dtype=np.intp)
        y0 = np.array(y0, dtype=np.intp)
        n = len(x0)
        iters = np.zeros(n, dtype=np.intp)
        active = np.arange(n)
        count = n
        origin = (float(self.ox), float(self.oy))
        for step in range(max_iter):
            mom = self._moments(flats, x0, y0, active, count)
            if step == 0:
                check_moments(mom, name)
            count = mean_shift_step(mom, x0, y0, active, count, iters, origin,
                                    self.width - self.w, self.height - self.h,
                                    float(eps * eps))
            if count == 0:
                break
        return x0, y0, iters, check_moments(self._moments(flats, x0, y0, np.arange(n), n), name)

    def centroids(self, mom: np.ndarray, x0: np.ndarray, y0: np.ndarray) -> np.ndarray:
        """Image coordinates of the kernel-weighted centroids ((N, 2)); the window centre
        where the window holds no weight."""
        m00 = mom[:, 0]
        safe = np.where(m00 > 1e-12, m00, 1.0)
        cx = np.where(m00 > 1e-12, mom[:, 1] / safe, self.cx)
        cy = np.where(m00 > 1e-12, mom[:, 2] / safe, self.cy)
        return np.stack([x0 + cx, y0 + cy], axis=1)


def check_moments(mom: np.ndarray, name: str) -> np.ndarray:
    """``mom`` (windows' moments, ``(N, 4)``, the last column the plain sum of the weights)
    unchanged; ``ValueError`` naming the image ``name`` unless every moment is finite and
    every window's weight non-negative. The trackers check the moments of the windows they
    read rather than scan whole frames (see :mod:`estimators.image.checks`): NaN, infinite or
    negative weights, or weights so large (about 1e300) that a window's sums overflow, are
    caught where they are read, before any state is changed by them."""
    bad = ~(np.isfinite(mom).all(axis=1) & (mom[:, -1] >= 0.0))
    if bad.any():
        raise ValueError(f"{name} must hold finite, non-negative weights (probabilities, or "
                         "weights small enough that a window's sum is finite): a window "
                         f"read from it sums to {float(mom[bad][0, -1])!r}")
    return mom


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
        kernel: a name in :data:`MEAN_SHIFT_KERNELS`: ``"flat"`` (as ``cv2.meanShift``) or
            ``"epanechnikov"``.
        opencv_compatible: compare the centroid with ``(w / 2, h / 2)`` as OpenCV does (its
            windows, exactly) instead of the window's centre ``((w - 1) / 2, (h - 1) / 2)``.

    Returns:
        ``(centre, window, iterations, mass)``: the centroid ``(x, y)`` [px] of the
        (kernel-weighted) weights in the converged window (its centre if it holds none), the
        converged window ``(x, y, w, h)``, the number of steps taken and the sum of the
        weights inside the converged window.
    """
    img = check_image("weight_image", weight_image, scan=True)
    try:
        x, y, w, h = (int(v) for v in window)
        if any(float(a) != int(a) for a in window):
            raise TypeError
    except (TypeError, ValueError):
        raise ValueError(f"window must be four integers (x, y, w, h), got {window!r}") from None
    check_int("window w", w)
    check_int("window h", h)
    max_iter = check_int("max_iter", max_iter)
    eps = check_number("eps", eps, allow_low=True)
    check_fits("weight_image", (w, h), img.shape, "the window size (window[2:4])")
    win = MeanShiftWindows(w, h, img.shape, kernel, bool(opencv_compatible))
    x0 = np.clip(np.array([x], dtype=np.intp), 0, img.shape[1] - w)
    y0 = np.clip(np.array([y], dtype=np.intp), 0, img.shape[0] - h)
    x0, y0, iters, mom = win.shift([(img.ravel(), 1.0)], x0, y0, max_iter, eps)
    centre = win.centroids(mom, x0, y0)[0]
    return centre, (int(x0[0]), int(y0[0]), w, h), int(iters[0]), float(mom[0, 3])
