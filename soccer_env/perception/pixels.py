"""Perception from rendered images: the image trackers of Li et al. (2010) and Yu et al. (2010)
instead of geometric detections (``perception={"detector": "pixels", ...}``).

Overhead (:class:`OverheadPixelDetector`, SSL teams): the overhead camera
(:class:`~soccer_env.sensors.images.cameras.OverheadImageCamera`) delivers images with the
vision preset's timing; the detector finds the robots and the ball in each:

* the colour look-up table (:class:`~estimators.image.colour.ColourTable`, built offline from the
  nominal colours as MiroSot teams do) turns the image into class probabilities; the frame
  difference gives the motion image;
* every robot is tracked by Li et al.'s (2010) mean-shift particle filter
  (:class:`estimators.MeanShiftParticleFilter`, 20 particles) on its team colour, started at
  its kick-off pose (robots are placed by the referee); its heading is read from its player
  dots by matching the known dot layout of its number, rotated in 5-degree steps, against the
  dots' colour probabilities (the best sum wins; compiled kernels,
  :mod:`soccer_env.perception.pixel_kernels`);
* the ball is tracked the same way on orange; when its tracker loses it next to a robot it is
  taken as occluded by that robot (Li et al.'s 2010 rule) and not reported, so that the filters
  downstream predict it;
* a lost robot or ball tracker reports nothing and is searched for over the whole image on the
  next frame (Li et al.'s 2010 global search).

The detections then go through the same pipeline as the geometric ones (the EKF, the robot
filters). Robots of one team look alike except for their dots, so a tracker can swap to a
team-mate that passes close by: nothing in Li et al.'s (2010) method prevents it beyond the feature
restriction, and the pipeline sees the swap as the robot's own motion.

Head cameras (:class:`BallImageTracker`, humanoids): each robot finds the ball in its
rendered head-camera images with Yu et al.'s (2010) Kalman-started mean shift.

Every overhead camera of the field has its own trackers (one camera on fields up to 7 m long,
four on Division B and A): a camera starts tracking a robot or the ball where it was last found,
by any camera, once that is inside its view, and stops when its tracker has lost what another
camera has since found outside its view; in the overlaps both cameras report it, as the
geometric cameras do. A camera whose new tracker finds none of the target's colour where it
starts (the ball hidden by a robot, or already out of that camera's view) drops it and tries
again on its next frame.

Limitations: the rendered resolution, not the vision preset's noise figures, sets the detection
noise (the preset's detection probabilities, spurious balls and noise are not applied).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from estimators import (
    HeadCamera,
    KalmanMeanShift,
    MeanShiftParticleFilter,
    PoseMeasurement,
    PositionMeasurement,
)
from estimators.image import EmptyWindowError
from soccer_env.perception.pixel_kernels import best_heading, dot_pixels
from soccer_env.presets import BallSpec
from soccer_env.presets.images import CLASS_ALIASES, OVERHEAD_CLASSES
from soccer_env.presets.sensors import HeadCameraSpec, VisionSpec
from soccer_env.sensors.images.cameras import HEAD_IMAGE_SIZE, ImageFrame, OverheadImageCamera
from soccer_env.sensors.overhead import DetectionFrame
from soccer_env.state import WorldState

__all__ = ["OverheadPixelDetector", "BallImageTracker"]

#: Heading candidates of the dot-layout match [rad].
_HEADINGS = np.radians(np.arange(0.0, 360.0, 5.0))
#: Their cosines and sines.
_COS, _SIN = np.cos(_HEADINGS), np.sin(_HEADINGS)
#: Particles of the mean-shift particle filters (Li et al. 2010: about 20 suffice).
_PARTICLES = 20


class OverheadPixelDetector:
    """Finds the robots and the ball in the overhead camera's images (see the module
    docstring): the processing that turns an
    :class:`~soccer_env.sensors.images.cameras.ImageFrame` into a
    :class:`~soccer_env.sensors.overhead.DetectionFrame`.

    Args:
        camera: the image camera (its renderer is the camera's calibration: pixels to field
            coordinates and back, metres per pixel).
        spec: the vision preset (its noise figures floor the measurement models).

    Attributes:
        ball_model, robot_model: the detections' measurement models for the filters
            downstream: the image's resolution (a pixel) and the 5-degree heading steps, not
            the geometric preset's noise figures.
    """

    def __init__(self, camera: OverheadImageCamera, spec: VisionSpec) -> None:
        from estimators.image.colour import ColourTable, difference_image, grey
        from soccer_env.sensors.images.patterns import PATTERN, PATTERN_IDS

        #: Every camera's renderer (its calibration), in camera order.
        self.renderers = list(camera.renderers)
        self.teams = list(camera.teams)
        self.robot_specs = list(camera.robot_specs)
        self.n_robots = len(self.robot_specs)
        self.table = ColourTable(OVERHEAD_CLASSES, aliases=CLASS_ALIASES)
        self._difference, self._grey = difference_image, grey
        # Window sizes in each camera's pixels (the quadrant cameras of one field are alike).
        self._windows = []
        for r in self.renderers:
            m = r.metres_per_pixel
            self._windows.append((
                m, [max(5, int(round(2.2 * s.radius / m))) for s in self.robot_specs],
                max(5, int(round(4.0 * camera.ball_spec.radius / m))),
                [s.radius / m for s in self.robot_specs]))
        m = max(r.metres_per_pixel for r in self.renderers)
        self.ball_model = PositionMeasurement(max(spec.ball_sigma, m))
        self.robot_model = PoseMeasurement(max(spec.robot_sigma, m),
                                           max(spec.robot_sigma_theta, math.radians(5.0)))
        # The dots of every robot: positions in the body frame [m] and colour classes.
        self._dots = []
        index = {0: 0, 1: 0}
        for t, s in zip(self.teams, self.robot_specs):
            patches = PATTERN.patches(t, index[t], s.radius)
            names = list(PATTERN_IDS[index[t]])  # the dots' colours, in patch order
            index[t] += 1
            self._dots.append((np.array([(p.x, p.y) for p in patches[1:]], dtype=np.float64),
                               names, np.array([n == "green" for n in names])))

    def __getstate__(self) -> dict:
        # The region images are the last frame's scratch buffers (each holds a look-up of
        # that frame's image, which nothing reads again: the next frame refills them); a
        # copy starts with none and allocates its own, the same numbers.
        state = dict(self.__dict__)
        if "_regions" in state:
            state["_regions"] = [{} for _ in self._regions]
        return state

    def reset(self, state: WorldState, rng: np.random.Generator) -> None:
        """Start an episode whose robots and ball start as in ``state`` (placed by the
        referee: their poses are known); ``rng`` draws the trackers' particles."""
        self._track_rng = rng
        c = len(self.renderers)
        self._prev_image: list[np.ndarray | None] = [None] * c
        # Every camera's region images of the last frame, by class (and "motion").
        self._regions: list[dict[str, Any]] = [{} for _ in range(c)]
        # Every camera's trackers of every robot and of the ball (None: not tracking there).
        self._trackers: list[list[MeanShiftParticleFilter | None]] = [
            [None] * self.n_robots for _ in range(c)]
        self._ball_trackers: list[MeanShiftParticleFilter | None] = [None] * c
        # Where each robot and the ball were last found, by any camera [m] (the referee's
        # placement at the start): where a camera that has no tracker on it starts one.
        self._known = [tuple(p) for p in state.robots[:, 0:2].tolist()]
        self._known_ball = (float(state.ball[0]), float(state.ball[1]))

    def detections(self, frames: Sequence[ImageFrame]) -> list[DetectionFrame]:
        """The detection frames of the image ``frames`` (in capture order); frames in which
        nothing was found carry no information for a tracker and are dropped."""
        out = []
        for f in sorted(frames, key=lambda f: f.t_capture):
            balls, ids, poses = self._detect(f.camera, f.image)
            if balls or ids:
                out.append(DetectionFrame(f.camera, f.t_capture, f.t_delivered, tuple(balls),
                                          tuple(ids), tuple(poses)))
        return out

    def _detect(self, cam: int, image: np.ndarray) -> tuple[list, list, list]:
        """Track every robot and the ball in camera ``cam``'s ``image``; their field
        positions.

        Hand-over between cameras: a camera starts tracking a robot (or the ball) where it was
        last found, by any camera, once that is inside its view; a camera whose tracker has
        lost a robot that another camera has since found outside its view stops tracking it.
        (With one camera the trackers start at the referee's placement and are kept, lost or
        not: a lost one searches the whole image, Li et al.'s (2010) global search.)"""
        r = self.renderers[cam]
        x0, x1, y0, y1 = r.region
        mpp, robot_window, ball_window, radius_px = self._windows[cam]
        table = self.table
        # The frame difference (grey levels), computed where the trackers read it.
        # (The previous frame's region images are refilled: nothing reads them any more.)
        regions = self._regions[cam]
        prev, cur = self._prev_image[cam], self._grey(image)
        motion = None if prev is None else self._difference(prev, cur, regions.get("motion"))
        self._prev_image[cam] = cur
        # The class probabilities, looked up only where the trackers and the heading read
        # them (the same pixels as a look-up of the whole image).
        for c in ("blue", "yellow", "orange", "pink", "green"):
            regions[c] = table.region_image(image, c, regions.get(c))
        if motion is not None:
            regions["motion"] = motion
        colours = {c: regions[c] for c in ("blue", "yellow", "orange")}
        dots = {c: regions[c] for c in ("pink", "green")}
        trackers = self._trackers[cam]
        ids, poses, pixels = [], [], []
        for i in range(self.n_robots):
            tracker = trackers[i]
            kx, ky = self._known[i]
            inside = x0 <= kx <= x1 and y0 <= ky <= y1
            if tracker is None:
                if not inside:
                    continue
                size = robot_window[i]
                tracker = MeanShiftParticleFilter(r.to_pixel(kx, ky), (size, size),
                                                  self._track_rng, n_particles=_PARTICLES)
                trackers[i] = tracker
            elif tracker.lost and not inside:  # found elsewhere since: another camera's
                trackers[i] = None
                continue
            colour = colours["blue" if self.teams[i] == 0 else "yellow"]
            try:
                u, v, _, _ = tracker.update(colour, motion)
            except EmptyWindowError:  # a new tracker where nothing is seen: not started
                trackers[i] = None
                continue
            if tracker.lost:
                continue
            pixels.append((u, v))
            x, y = r.to_field(u, v)
            ids.append(i)
            poses.append((float(x), float(y), self._heading(cam, i, u, v, dots)))
            self._known[i] = (float(x), float(y))
        balls = []
        bt = self._ball_trackers[cam]
        kx, ky = self._known_ball
        inside = x0 <= kx <= x1 and y0 <= ky <= y1
        if bt is not None and (bt.lost or bt.occluded) and not inside:
            self._ball_trackers[cam] = bt = None
        if bt is None and inside:
            bt = MeanShiftParticleFilter(r.to_pixel(kx, ky), (ball_window, ball_window),
                                         self._track_rng, n_particles=_PARTICLES)
            self._ball_trackers[cam] = bt
        if bt is not None:
            robots_px = np.array(pixels) if pixels else None
            try:
                u, v, _, _ = bt.update(colours["orange"], motion, robots=robots_px,
                                       robot_radius_px=float(np.mean(radius_px)) if pixels
                                       else None)
            except EmptyWindowError:  # a new tracker where no ball is seen: not started
                self._ball_trackers[cam] = bt = None
            if bt is not None and not (bt.lost or bt.occluded):
                x, y = r.to_field(u, v)
                balls.append((float(x), float(y)))
                self._known_ball = (float(x), float(y))
        return balls, ids, poses

    def _heading(self, cam: int, i: int, u: float, v: float, dots: dict[str, Any]
                 ) -> float:
        """Robot ``i``'s heading [rad]: the rotation of its dot layout (5-degree steps) whose
        dots fall on the most probability of their colours."""
        layout, names, uses_green = self._dots[i]
        r = self.renderers[cam]
        cols = np.empty((len(_HEADINGS), len(layout)), dtype=np.int64)
        rows = np.empty_like(cols)
        box = dot_pixels(float(u), float(v), layout, _COS, _SIN, self._windows[cam][0],
                         r.spec.width, r.spec.height, cols, rows)
        for name in ("pink", "green"):
            if name in names:
                dots[name].ensure(*box)
        best = best_heading(dots["pink"].array, dots["green"].array, uses_green, cols, rows)
        return float(math.remainder(_HEADINGS[best], 2.0 * math.pi))


class BallImageTracker:
    """One robot's ball finder in its head-camera images: Yu et al.'s (2010) Kalman-started mean
    shift (:class:`estimators.KalmanMeanShift`) on the back-projection of the ball's hue
    histogram, its prediction moved by the robot's own turning (odometry and the pan servo)
    and the tilt servo; when it has no track, a search of the whole image (the largest blob of
    ball colour) starts one. Returns ball detections with their ground projection through the
    rendered image's pinhole camera and the angles the robot believes (the layout of
    :data:`~soccer_env.sensors.headcam.BALL_DETECTION_FIELDS`; pixels scaled to the camera spec's
    width).

    Args:
        spec: the head camera (its pixels and believed-angle ground projection).
        ball: the ball (its radius: the plane of its centre, its apparent size).
        size: the rendered images' size ``(width, height)`` [px].
    """

    #: The Kalman-started mean shift's order of steps and window (times the ball's size):
    #: Yu et al.'s (2010) order (the centroid in the region R of twice the ball's size updates the
    #: Kalman filter, mean shift starts from the posterior) with a window of twice the ball's
    #: size, ``kalman-paper x2`` in ``soccer-env paper following``: off target in 0.0 % of its
    #: frames against 35 % for our order with a window of the ball's size (``kalman x1``, the
    #: choice before) and 0.1 % for our order at twice the size. The lost test scales with the
    #: window's area, so the same amount of ball must be in it (0.2 of a ball-sized window).
    ORDER = "paper"
    WINDOW_SCALE = 2.0
    MIN_FILL = 0.2 / WINDOW_SCALE**2

    def __init__(self, spec: HeadCameraSpec, ball: BallSpec,
                 size: tuple[int, int] = HEAD_IMAGE_SIZE) -> None:
        from estimators.image.colour import back_project, hue_histogram
        from soccer_env.presets.images import COLOURS

        self.spec, self.ball = spec, ball
        self.size = (int(size[0]), int(size[1]))
        # The rendered image's camera: the spec's field of view at the rendered size.
        self.camera = HeadCamera(spec.height, spec.hfov, self.size[0], self.size[1])
        self.scale = spec.width / self.size[0]
        self.fov = (self.camera.hfov, self.camera.vfov)
        patch = np.zeros((8, 8, 3), dtype=np.uint8)
        patch[:] = COLOURS["orange"]
        self._hist = hue_histogram(patch)  # the ball's colour, known offline
        self._back_project = back_project
        self.tracker: KalmanMeanShift | None = None
        self._last: tuple[float, float] | None = None  # camera yaw and tilt at the last frame

    def reset(self) -> None:
        self.tracker = None
        self._last = None

    def detect(self, image: np.ndarray, yaw: float, tilt: float, pan: float) -> tuple:
        """Ball detections in ``image`` taken with the camera at ``yaw`` (robot heading plus
        pan, as the robot believes it) and ``tilt``, the head's ``pan``: ``()`` or one
        ``(u, v, x, y, bearing)``."""
        import cv2

        weight = self._back_project(image, self._hist)
        tr = self.tracker
        if tr is not None and self._last is not None:
            d_yaw = math.remainder(yaw - self._last[0], 2.0 * math.pi)
            tr.shift(0.0, -(tilt - self._last[1]) * self.size[1] / self.fov[1])
            x, y, _, _ = tr.update(weight, rotation=d_yaw)
            if tr.lost and tr.lost_frames > 2:
                self.tracker = tr = None
        self._last = (yaw, tilt)
        if tr is None:  # search the whole image: the largest blob of ball colour
            n, _, stats, centroids = cv2.connectedComponentsWithStats(
                (weight > 0.5).astype(np.uint8), connectivity=8)
            if n <= 1:
                return ()
            k = 1 + int(np.argmax(stats[1:, cv2.CC_STAT_AREA]))
            if stats[k, cv2.CC_STAT_AREA] < 3:
                return ()
            # The target's size, at most what keeps its search window inside the image (a
            # robot right in front of the camera fills more than half of it).
            w = min(max(5, int(stats[k, cv2.CC_STAT_WIDTH])),
                    int(self.size[0] / self.WINDOW_SCALE))
            h = min(max(5, int(stats[k, cv2.CC_STAT_HEIGHT])),
                    int(self.size[1] / self.WINDOW_SCALE))
            self.tracker = tr = KalmanMeanShift(tuple(centroids[k]), (w, h),
                                                image_size=self.size, fov=self.fov,
                                                order=self.ORDER,
                                                window_scale=self.WINDOW_SCALE,
                                                min_fill=self.MIN_FILL)
            x, y = centroids[k]
        elif tr.lost:
            return ()
        g = self.camera.ground_point(np.array([[x + 0.5, y + 0.5]]), pan, tilt,
                                     plane_height=self.ball.radius)[0]
        if not np.isfinite(g).all():
            return ()
        return ((float((x + 0.5) * self.scale), float((y + 0.5) * self.scale), float(g[0]),
                 float(g[1]), float(math.atan2(g[1], g[0]))),)
