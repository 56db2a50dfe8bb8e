"""The Kalman-started mean shift with ego-motion compensation of Yu, Wei and Zhang (2010),
plain mean shift from the last position, and depth from a target's apparent
size, on weight images (images, points, windows and mean shift as in
:mod:`estimators.image.meanshift`).

**Yu et al. (2010) (Kalman-started mean shift).** :class:`KalmanMeanShift` filters the image-plane
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

Two orders of a frame's steps, by ``order``:

* ``"paper"``, as printed in Yu et al. (2010): the back-projection's centroid in the region ``R``,
  ``region_scale`` (2) times the target's size, centred at the prediction, is the measurement
  ``z`` (pixels below ``region_floor`` dropped first: the paper's "simple filtering" of
  low-probability points; the value 0.1 is ours); the Kalman filter is updated with ``z``;
  mean shift (window: the target size times ``window_scale``) then starts from the
  posterior, and its converged position replaces the posterior's position for the next
  frame.
* ``"ours"`` (the default): mean shift starts at the prediction, and its converged centroid is
  both the measurement and (``posterior="replace"``) the posterior's position; the velocity
  and covariance come from a standard Kalman update with it. ``posterior="update"`` keeps the
  standard Kalman update instead. One mean shift per frame and no region pass; ``soccer-env
  paper following`` measures both orders side by side.

The track is lost in a frame when the converged window's mean weight is below ``min_fill``
(in the paper's order also when ``R`` holds no weight): the filter then only predicts and
reports ``lost``. :class:`PlainMeanShift` is the baseline: mean shift from the last position,
no prediction.

**Depth** from the target's known size (pinhole camera): ``d = f * size / apparent_size``, ``f``
the focal length [px] (:func:`focal_length_px`: ``f = (n / 2) / tan(fov / 2)`` for ``n``
pixels across a field of view ``fov``), and the apparent size measured by a shape histogram
(:func:`apparent_height`). :class:`KalmanMeanShift` uses it for ``d_k`` when given the
target's height.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..checks import MAX_PIXELS, check_reals
from ..kalman.core import KalmanFilter
from .checks import (
    MIN_SIGMA_PX,
    check_fits,
    check_image,
    check_int,
    check_number,
    check_point,
    check_window_size,
)
from .meanshift import MEAN_SHIFT_KERNELS, MeanShiftWindows

__all__ = ["KalmanMeanShift", "PlainMeanShift", "depth_from_size", "focal_length_px",
           "apparent_height", "ego_motion_shift"]


# ------------------------------------------------------------------------------------------
# Yu et al. (2010): Kalman-started mean shift with ego-motion compensation
# ------------------------------------------------------------------------------------------

def focal_length_px(pixels: float, fov: float) -> float:
    """Pinhole focal length [px] of ``pixels`` across a field of view ``fov`` [rad]:
    ``f = (pixels / 2) / tan(fov / 2)``."""
    n = check_number("pixels", pixels)
    a = check_number("fov", fov)
    if a >= math.pi:
        raise ValueError(f"fov must be < pi rad, got {fov!r}")
    return 0.5 * n / math.tan(0.5 * a)


def depth_from_size(size_m: float, apparent_size_px: float, focal_px: float) -> float:
    """Distance [m] of a target of known size ``size_m`` [m] that appears ``apparent_size_px``
    [px] large (pinhole): ``d = f * size / apparent_size``, ``f = focal_px`` [px]."""
    return (check_number("focal_px", focal_px) * check_number("size_m", size_m)
            / check_number("apparent_size_px", apparent_size_px))


def apparent_height(weight_image: np.ndarray, window: Sequence[int], threshold: float = 0.5,
                    min_fraction: float = 0.2) -> float:
    """The target's height [px] in ``window`` ``(x, y, w, h)`` by a shape histogram (Yu et
    al. 2010): the foreground pixels (weight ``>= threshold``) are projected onto the vertical
    axis (a count per row); the target spans the rows from the first to the last whose count
    is at least ``min_fraction`` times the largest. Returns 0 when no pixel is foreground.
    The window is clipped to the image."""
    img = check_image("weight_image", weight_image)
    try:
        x, y, w, h = (int(v) for v in window)
    except (TypeError, ValueError):
        raise ValueError(f"window must be four integers (x, y, w, h), got {window!r}") from None
    check_int("window w", w)
    check_int("window h", h)
    check_number("threshold", threshold, allow_low=True)
    check_number("min_fraction", min_fraction, allow_low=True, high=1.0)
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
    frame (Yu et al. 2010, see the module docstring):
    ``dx = theta * x_B / gamma_x`` (``theta = rotation`` [rad], positive counter-clockwise,
    i.e. a left turn, which moves the scene right) and
    ``dy = (arctan(h / (d - s)) - arctan(h / d)) * y_B / gamma_y`` (``s = advance`` [m]
    towards the target, ``d = distance`` [m] before the move, ``h = camera_height`` [m] above
    the target's centre; ``d - s`` floored at 1 mm). ``distance`` is needed when
    ``advance != 0``."""
    theta = check_number("rotation", rotation, -math.inf)
    s = check_number("advance", advance, -math.inf)
    xb, yb = check_window_size("image_size", image_size)
    gx, gy = check_reals("fov", fov, 2, what="(gamma_x, gamma_y) [rad]")
    check_number("fov[0] (gamma_x)", gx)
    check_number("fov[1] (gamma_y)", gy)
    dx = theta * xb / gx
    dy = 0.0
    if s != 0.0:
        if distance is None:
            raise ValueError("distance is needed when advance != 0")
        d = check_number("distance", distance)
        h = check_number("camera_height", camera_height, -math.inf)
        d1 = max(d - s, 1e-3)
        dy = (math.atan2(h, d1) - math.atan2(h, d)) * yb / gy
    return np.array([dx, dy])


class _MeanShiftTrack:
    """Shared by the two mean-shift trackers: the window, one mean shift, the lost test."""

    def __init__(self, window_size, window_scale: float, max_iter: int, eps: float,
                 kernel: str, min_fill: float) -> None:
        w, h = check_window_size("window_size", window_size)
        self.window_scale = check_number("window_scale", window_scale, high=MAX_PIXELS)
        self.target_size = (w, h)
        self.window_size = (max(int(round(w * self.window_scale)), 1),
                            max(int(round(h * self.window_scale)), 1))
        self.max_iter = check_int("max_iter", max_iter)
        self.eps = check_number("eps", eps, allow_low=True)
        MEAN_SHIFT_KERNELS.check(kernel, "kernel")
        self.kernel = kernel
        self.min_fill = check_number("min_fill", min_fill, allow_low=True, high=1.0)
        self._win: MeanShiftWindows | None = None
        #: The weight images' ``(H, W)`` where the tracker knows it (None: any).
        self._image_shape: tuple[int, int] | None = None
        self.lost = False
        self.lost_frames = 0
        self.fill = 0.0
        self.window: tuple[int, int, int, int] | None = None

    def _shift_from(self, image, start: np.ndarray) -> tuple[np.ndarray | None, np.ndarray]:
        """Mean shift from the window centred at ``start``; returns the centroid (None if
        the converged window's mean weight is below ``min_fill``) and the flat image."""
        img = check_image("weight_image", image, self._image_shape, window=self.window_size)
        if self._win is None or (self._win.height, self._win.width) != img.shape:
            self._win = MeanShiftWindows(*self.window_size, img.shape, self.kernel)
        win = self._win
        x0, y0 = win.corner(start[None, :])
        x0, y0, _, mom = win.shift([(img.ravel(), 1.0)], x0, y0, self.max_iter, self.eps)
        self.window = (int(x0[0]), int(y0[0]), win.w, win.h)
        self.fill = float(mom[0, 3]) / win.area
        if self.fill < self.min_fill:
            return None, img
        return win.centroids(mom, x0, y0)[0], img


class PlainMeanShift(_MeanShiftTrack):
    """Mean shift from the last position, no prediction: Yu et al.'s (2010) baseline.

    Args:
        position: initial ``(x, y)`` [px].
        window_size: the target's size ``(w, h)`` [px].
        window_scale: the mean-shift window is ``window_scale`` times the target size.
        max_iter: as :func:`mean_shift`.
        eps: as :func:`mean_shift`.
        kernel: as :func:`mean_shift`.
        min_fill: the track is lost in a frame whose converged window's mean weight is below
            this (the position then stays).

    Attributes:
        position: ``(x, y)`` [px].
        lost: whether the last frame lost the track.
        lost_frames: frames in which the track was lost.
        fill: the last converged window's mean weight.
        window: the last converged window.
    """

    def __init__(self, position: ArrayLike, window_size: ArrayLike, *,
                 window_scale: float = 1.0, max_iter: int = 10, eps: float = 0.5,
                 kernel: str = "flat", min_fill: float = 0.2) -> None:
        super().__init__(window_size, window_scale, max_iter, eps, kernel, min_fill)
        self.position = check_point("position", position).copy()

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
    """Kalman-started mean shift with ego-motion compensation of Yu, Wei and Zhang (2010); see
    the module docstring for the model, the sign conventions and our readings.

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
            position) or ``"update"`` (a standard Kalman update; ``order="ours"`` only).
        window_scale: the mean-shift window is ``window_scale`` times the target size
            (1 by default).
        order: ``"ours"`` or ``"paper"`` (see the module docstring).
        region_scale: the paper's region ``R`` over the target size (``order="paper"``; the
            paper: 2).
        region_floor: weights below this are dropped before ``R``'s centroid
            (``order="paper"``).
        max_iter: as :func:`mean_shift`.
        eps: as :func:`mean_shift`.
        kernel: as :func:`mean_shift`.
        min_fill: the track is lost in a frame whose converged window's mean weight is below
            this.

    Attributes:
        kf: the :class:`~estimators.kalman.KalmanFilter` on ``(x, y, vx, vy)``.
        lost: as :class:`PlainMeanShift`.
        lost_frames: as :class:`PlainMeanShift`.
        fill: as :class:`PlainMeanShift`.
        window: as :class:`PlainMeanShift`.
        prediction: the last predicted ``(x, y)`` [px] (where mean shift started).
        distance: the target's current distance estimate [m] (None if unknown).
    """

    def __init__(self, position: ArrayLike, window_size: ArrayLike, *, image_size: Sequence[int],
                 fov: Sequence[float], camera_height: float = 0.0,
                 distance: float | None = None, target_height_m: float | None = None,
                 velocity: ArrayLike = (0.0, 0.0), accel_sigma: float = 2.0,
                 measurement_sigma: float = 2.0,
                 init_sigma: Sequence[float] = (2.0, 5.0), posterior: str = "replace",
                 window_scale: float = 1.0, max_iter: int = 10, eps: float = 0.5,
                 kernel: str = "flat", min_fill: float = 0.2, order: str = "ours",
                 region_scale: float = 2.0, region_floor: float = 0.1) -> None:
        super().__init__(window_size, window_scale, max_iter, eps, kernel, min_fill)
        if order not in self.ORDERS:
            raise ValueError(f"order must be one of {self.ORDERS}, got {order!r}")
        if order == "paper" and posterior != "replace":
            raise ValueError("posterior must be 'replace' with order='paper' (the paper "
                             f"replaces the posterior by mean shift's position), got "
                             f"{posterior!r}")
        self.order = order
        self.region_scale = check_number("region_scale", region_scale, high=MAX_PIXELS)
        self.region_floor = check_number("region_floor", region_floor, allow_low=True, high=1.0)
        tw, th = self.target_size
        self.region_size = (max(int(round(tw * self.region_scale)), 1),
                            max(int(round(th * self.region_scale)), 1))
        self.image_size = check_window_size("image_size", image_size)
        self._image_shape = (self.image_size[1], self.image_size[0])
        check_fits("image_size", self.window_size, self._image_shape,
                   "the window (window_size x window_scale)")
        ego_motion_shift(0.0, 0.0, self.image_size, fov)  # validates fov
        self.fov = (float(fov[0]), float(fov[1]))
        self.camera_height = check_number("camera_height", camera_height, -math.inf)
        self.distance = None if distance is None else check_number("distance", distance)
        self.target_height_m = (None if target_height_m is None
                                else check_number("target_height_m", target_height_m))
        self.focal_y = focal_length_px(self.image_size[1], self.fov[1])
        if posterior not in ("replace", "update"):
            raise ValueError(f"posterior must be 'replace' or 'update', got {posterior!r}")
        self.posterior = posterior
        sa = check_number("accel_sigma", accel_sigma, allow_low=True, high=MAX_PIXELS)
        sm = check_number("measurement_sigma", measurement_sigma, high=MAX_PIXELS)
        sp, sv = check_reals("init_sigma", init_sigma, 2, MIN_SIGMA_PX, MAX_PIXELS,
                             "(position, velocity) standard deviations [px, px/frame]")
        x = np.concatenate([check_point("position", position), check_point("velocity", velocity)])
        self.kf = KalmanFilter(x, np.diag([sp * sp, sp * sp, sv * sv, sv * sv]))
        self.F = np.array([[1.0, 0, 1, 0], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]])
        G = np.array([[0.5, 0], [0, 0.5], [1, 0], [0, 1]])
        self.Q = sa * sa * G @ G.T  # white acceleration over one frame
        self.H = np.eye(2, 4)
        self.R = sm * sm * np.eye(2)
        self.prediction = x[:2].copy()

    #: The orders of a frame's steps (see the module docstring).
    ORDERS = ("ours", "paper")

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
        d = self.distance if distance is None else check_number("distance", distance)
        shift = ego_motion_shift(rotation, advance, self.image_size, self.fov,
                                 self.camera_height, d)
        x_pred = self.F @ self.kf.x
        x_pred[:2] += shift
        self.kf.predict_unchecked(self.F, self.Q, x_pred)
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
        (the hue back-projection, ``(H, W)`` = ``image_size`` reversed) from the prediction,
        then the measurement update (or, when lost, the prediction alone). Returns
        ``(x, y, vx, vy)``. A refused image (``ValueError``: another shape, weights that are
        not finite and non-negative) leaves the tracker as it was."""
        img = check_image("weight_image", weight_image, self._image_shape,
                          window=self.window_size)
        before = (self.kf.x.copy(), self.kf.P.copy(), self.prediction.copy(), self.distance)
        start = self.predict(rotation, advance, distance)
        try:
            if self.order == "paper":
                z, img = self._paper_order(img, start)
            else:
                z, img = self._shift_from(img, start)
        except ValueError:
            self.kf.x, self.kf.P, self.prediction, self.distance = before
            raise
        self.lost = z is None
        if self.lost:
            # A lost target is taken to stand where it was last predicted: its own velocity
            # is forgotten (extrapolating it would carry the window away for good), while
            # the robot's own motion still moves it in the image.
            self.lost_frames += 1
            self.kf.update_unchecked(None, self.H, self.R)
            self.kf.x[2:] = 0.0
            return self.state
        if self.order == "ours":
            self.kf.update_unchecked(z, self.H, self.R)
        if self.posterior == "replace":
            self.kf.x[:2] = z
        if self.target_height_m is not None:
            w, h = self.window_size
            region = (int(round(z[0] - w)), int(round(z[1] - h)), 2 * w, 2 * h)
            size = apparent_height(img, region)
            if size > 0.0:
                self.distance = depth_from_size(self.target_height_m, size, self.focal_y)
        return self.state

    def _paper_order(self, weight_image, start: np.ndarray
                     ) -> tuple[np.ndarray | None, np.ndarray]:
        """Yu et al.'s (2010) order: ``z`` = the centroid of the weights (those at least
        ``region_floor``) in the region ``R`` centred at ``start``, clipped to the image; the
        Kalman update with ``z``; mean shift from the posterior. Returns mean shift's
        converged centroid (None when ``R`` holds no weight or the converged window's mean
        weight is below ``min_fill``; the Kalman filter is then left at the prediction) and
        the image."""
        img = check_image("weight_image", weight_image)
        rw, rh = self.region_size
        x1 = max(int(round(start[0] - 0.5 * (rw - 1))), 0)
        y1 = max(int(round(start[1] - 0.5 * (rh - 1))), 0)
        x2, y2 = min(x1 + rw, img.shape[1]), min(y1 + rh, img.shape[0])
        if x2 <= x1 or y2 <= y1:
            return None, img
        patch = img[y1:y2, x1:x2]
        mass = float(patch.sum())
        if not (math.isfinite(mass) and patch.min() >= 0.0):
            raise ValueError("weight_image must hold finite, non-negative weights "
                             f"(probabilities, or weights small enough that a region's sum "
                             f"is finite): the region R sums to {mass!r}")
        patch = np.where(patch >= self.region_floor, patch, 0.0)
        mass = float(patch.sum())
        if mass <= 0.0:
            return None, img
        z = np.array([x1 + float(patch.sum(axis=0) @ np.arange(x2 - x1)) / mass,
                      y1 + float(patch.sum(axis=1) @ np.arange(y2 - y1)) / mass])
        x, P = self.kf.x.copy(), self.kf.P.copy()
        self.kf.update_unchecked(z, self.H, self.R)
        moved, _ = self._shift_from(img, self.kf.x[:2])
        if moved is None:
            self.kf.x, self.kf.P = x, P  # lost: back to the prediction
        return moved, img
