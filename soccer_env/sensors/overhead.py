"""Overhead vision: SSL-Vision-like cameras producing late, noisy, incomplete detection frames.

Each camera hangs at ``camera_height`` above the centre of its area (one camera on fields up to
7 m long, one per quadrant on larger fields) and sees its area plus ``camera_overlap`` metres
beyond it, so cameras overlap near their borders and both report an object there. Cameras run
at ``frame_rate`` with independent phases drawn per episode; each frame carries its capture
time and is delivered ``latency`` (plus up to ``latency_jitter``) seconds later, so frames of
different cameras can arrive out of order.

In a frame, every robot inside the camera's view is detected with probability
``robot_detection`` (pose noise from :class:`~estimators.models.PoseMeasurement`), and the ball
with probability ``ball_detection`` (position noise from
:class:`~estimators.models.PositionMeasurement`, the same objects the filters use) unless it is
occluded: the ball is hidden when at least ``occlusion_threshold`` of its disc, seen from the
camera, is covered by a robot's body, each robot with its own footprint radius and height (an
SSL robot is a wide, low cylinder; a humanoid a narrow, tall one that hides a ball farther
behind it). A ball in flight is reported where the camera ray through it meets the plane of a
ball lying on the carpet, not above its ground position. Spurious balls appear at SSL robots'
fronts (dribbler reflections, ``dribbler_false_rate`` per second per SSL robot in view;
humanoids have no dribbler) and anywhere in a camera's view (``random_false_rate`` per second
per camera).

Between two environment steps the truth is interpolated linearly to each capture time.

The capture itself (interpolation, visibility, detection, noise, occlusion, spurious balls,
delivery times) is the compiled kernel
:func:`~soccer_env.sensors.overhead_kernels.capture_frames`, which the cameras of many fields
alike (:class:`~soccer_env.sensors.overhead_batch.OverheadVisionBatch`) call too: one field is
a batch of one.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from itertools import compress
from typing import NamedTuple

import numpy as np

from estimators import PoseMeasurement, PositionMeasurement
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec, SSLRobotSpec
from soccer_env.presets.sensors import VisionSpec
from soccer_env.sensors.draws import BlockDraws
from soccer_env.sensors.overhead_kernels import PARAMS, capture_frames, frame_columns
from soccer_env.state import WorldState

__all__ = ["Camera", "DetectionFrame", "OverheadVision", "default_cameras"]


class Camera(NamedTuple):
    """A camera at ``(x, y, height)`` seeing ``x_min <= x <= x_max``, ``y_min <= y <= y_max``."""

    x: float
    y: float
    height: float
    x_min: float
    x_max: float
    y_min: float
    y_max: float


def default_cameras(field: FieldSpec, height: float, overlap: float) -> list[Camera]:
    """One camera over the whole walled area for fields up to 7 m long, otherwise one per
    quadrant (each seeing ``overlap`` beyond its quadrant)."""
    wx, wy = field.half_length + field.boundary, field.half_width + field.boundary
    if field.length <= 7.0:
        return [Camera(0.0, 0.0, height, -wx, wx, -wy, wy)]
    cams = []
    for sx in (-1.0, 1.0):
        for sy in (-1.0, 1.0):
            xs = sorted((0.0, sx * wx))
            ys = sorted((0.0, sy * wy))
            cams.append(Camera(sx * wx / 2, sy * wy / 2, height, xs[0] - overlap,
                               xs[1] + overlap, ys[0] - overlap, ys[1] + overlap))
    return cams


class DetectionFrame(NamedTuple):
    """One camera frame, as a team's software receives it.

    Detections are tuples (cheap to build for every frame; ``np.reshape(frame.balls, (-1,
    2))`` gives an array).

    Attributes:
        camera: camera index.
        t_capture: when the image was taken [s, episode time].
        t_delivered: when the frame reaches the team's software [s].
        balls: ball detections ``(x, y)`` [m] (true and spurious; may be empty).
        robot_ids: indices of the detected robots (blue first, as in the world).
        robots: detected poses ``(x, y, theta)``, in the order of ``robot_ids``.
    """

    camera: int
    t_capture: float
    t_delivered: float
    balls: tuple
    robot_ids: tuple
    robots: tuple




class OverheadVision:
    """The overhead camera system of one field (see the module docstring).

    Args:
        spec: sensor characteristics.
        field: the world's field (the camera layout).
        robot: the common robot model (footprint, height, dribbler).
        ball: the world's ball (its radius).
        n_robots: number of robots in the world.
        cameras: override :func:`default_cameras`.
        robots: every robot's spec, in world order (its radius and height for occlusion,
            whether it has a dribbler); default: ``robot`` for all ``n_robots``.
    """

    def __init__(self, spec: VisionSpec, field: FieldSpec, robot: SSLRobotSpec, ball: BallSpec,
                 n_robots: int, cameras: list[Camera] | None = None,
                 robots: Sequence[RobotSpec] | None = None) -> None:
        self.spec = spec
        self.field, self.robot_spec, self.ball_spec = field, robot, ball
        self.n_robots = n_robots
        specs = [robot] * n_robots if robots is None else list(robots)
        if len(specs) != n_robots:
            raise ValueError(f"robots must hold one spec per robot ({n_robots}), got "
                             f"{len(specs)}")
        #: Every robot's spec (occlusion by its own footprint and height).
        self.robot_specs = specs
        self.cameras = cameras or default_cameras(field, spec.camera_height,
                                                  spec.camera_overlap)
        self.ball_model = PositionMeasurement(spec.ball_sigma)
        self.robot_model = PoseMeasurement(spec.robot_sigma, spec.robot_sigma_theta)
        #: The cameras as ``(C, 7)`` rows ``(x, y, height, x_min, x_max, y_min, y_max)`` [m].
        self.camera_rows = np.array(self.cameras, dtype=np.float64).reshape(-1, 7)
        #: Every robot's body for the capture kernel, ``(N, 3)``: its dribbler's distance
        #: from its centre plus the ball's radius (NaN: no dribbler, a humanoid), its height
        #: and its footprint radius [m].
        self.bodies = np.array([[math.nan if getattr(rs, "front_distance", None) is None
                                 else rs.front_distance + ball.radius,
                                 float(rs.height), float(rs.radius)] for rs in specs],
                               dtype=np.float64).reshape(n_robots, 3)
        period = self.period or 0.0
        figures = {"ball_radius": ball.radius, "robot_detection": spec.robot_detection,
                   "ball_detection": spec.ball_detection,
                   "p_dribbler": 1.0 - math.exp(-spec.dribbler_false_rate * period),
                   "p_random": 1.0 - math.exp(-spec.random_false_rate * period),
                   "robot_sigma": self.robot_model.sigma_xy,
                   "robot_sigma_theta": self.robot_model.sigma_theta,
                   "ball_sigma": self.ball_model.sigma,
                   "occlusion_threshold": spec.occlusion_threshold, "latency": spec.latency,
                   "latency_jitter": spec.latency_jitter}
        #: The capture kernel's figures, in the order of
        #: :data:`~soccer_env.sensors.overhead_kernels.PARAMS` (probabilities per frame).
        self.capture_params = np.array([figures[k] for k in PARAMS], dtype=np.float64)
        #: Where the capture kernel writes a frame in its row (:func:`frame_columns`).
        self.columns = frame_columns(n_robots)
        # The capture kernel's buffers: each frame's state (all 0, a call has one state) and
        # its output rows, grown when a step captures more frames.
        self._rows = np.zeros(16, dtype=np.int64)
        self._out = np.zeros((16, self.columns[4]))
        self._cam_arrays: dict[tuple[int, ...], np.ndarray] = {}  # camera lists as arrays
        # Frames in flight, a heap ordered by delivery time.
        self._queue: list[tuple[float, float, int, DetectionFrame]] = []
        self._prev: WorldState | None = None
        self._rng: np.random.Generator | None = None

    # ------------------------------------------------------------------------------------

    def reset(self, state: WorldState, rng: np.random.Generator) -> list[DetectionFrame]:
        """Start an episode at ``state``. The cameras have been running while the scene stood
        still: one frame per camera, captured ``latency`` ago of the initial (static) scene,
        is delivered at once and returned."""
        self._rng = rng
        self._draws = BlockDraws(rng)
        self._queue = []
        self._prev = state
        period = self.period
        n = len(self.cameras)
        # Capture schedule per camera ("ideal" captures in step(), not on a schedule).
        self._next = ((rng.uniform(0.0, period, n) + state.time).tolist() if period is not None
                      else [math.inf] * n)
        warm = self._capture(state, state, list(range(n)), [state.time] * n, emit_empty=True)
        return [f._replace(t_capture=state.time - self.spec.latency, t_delivered=state.time)
                for f in warm]

    @property
    def period(self) -> float | None:
        """The cameras' frame period [s] (None: a frame at every step)."""
        return None if self.spec.frame_rate is None else 1.0 / self.spec.frame_rate

    def step(self, state: WorldState) -> list[DetectionFrame]:
        """Capture the frames due since the last call and return those delivered by
        ``state.time``, ordered by delivery time."""
        now = state.time
        queue = self._queue
        for frame in self.capture(state):
            heapq.heappush(queue, (frame.t_delivered, frame.t_capture, frame.camera, frame))
        out = []
        while queue and queue[0][0] <= now + 1e-12:
            out.append(heapq.heappop(queue)[3])
        return out

    def capture(self, state: WorldState) -> list[DetectionFrame]:
        """Capture the frames due since the last call and return them at once, before their
        delivery (``t_delivered`` says when): for a caller that delivers them itself, as a
        served camera system does at the wall time of delivery. Call this or :meth:`step`,
        not both, after a reset."""
        prev, now = self._prev, state.time
        period = self.period
        if period is None:
            n = len(self.cameras)
            new = self._capture(prev, state, list(range(n)), [now] * n)
        else:
            cams, times = [], []
            nxt = self._next
            for c in range(len(nxt)):
                while nxt[c] <= now + 1e-12:
                    cams.append(c)
                    times.append(nxt[c])
                    nxt[c] += period
            new = self._capture(prev, state, cams, times) if cams else []
        self._prev = state
        return new

    # ------------------------------------------------------------------------------------

    def _capture(self, prev: WorldState, cur: WorldState, cams: list[int],
                 times: list[float], emit_empty: bool = False) -> list[DetectionFrame]:
        """Frames of cameras ``cams`` captured at ``times`` (between ``prev`` and ``cur``).
        Frames that detected nothing are dropped unless ``emit_empty`` (they carry no
        information for a tracker; the warm-up frames at reset are always kept).

        The frames are :func:`~soccer_env.sensors.overhead_kernels.capture_frames`' (a batch
        of one field's frames, one state), from numbers drawn in blocks: per frame
        ``3 (N + 2)`` normals and ``2 N + 5`` uniforms (the kernel's layout).
        """
        F, N = len(cams), self.n_robots
        draws = self._draws
        normals = draws.normals(F * (N + 2) * 3)
        uniforms = draws.uniforms(F * (2 * N + 5))
        key = tuple(cams)
        cam_rows = self._cam_arrays.get(key)
        if cam_rows is None:
            cam_rows = np.array(cams, dtype=np.int64)
            if len(self._cam_arrays) < 256:  # the few patterns of a step's cameras
                self._cam_arrays[key] = cam_rows
        if F > len(self._rows):  # (room for every frame of the step)
            self._rows = np.zeros(F, dtype=np.int64)
            self._out = np.zeros((F, self.columns[4]))
        out = self._out
        capture_frames(self._rows[:F], cam_rows, np.array(times),
                       np.array(((prev.time, cur.time - prev.time),)), prev.ball[None],
                       cur.ball[None], prev.robots[None], cur.robots[None], normals, uniforms,
                       self.camera_rows, self.bodies, self.capture_params, out)
        _, b, r, p, _ = self.columns
        ids = range(N)
        frames = []
        for cam, t, row in zip(cams, times, out[:F].tolist()):
            seen_b, seen_r = row[1:b], row[r:p]
            if emit_empty or 1.0 in seen_b or 1.0 in seen_r:  # else no frame to process
                xy, pose = iter(row[b:r]), iter(row[p:])
                frames.append(DetectionFrame(cam, t, row[0],
                                             tuple(compress(zip(xy, xy), seen_b)),
                                             tuple(compress(ids, seen_r)),
                                             tuple(compress(zip(pose, pose, pose), seen_r))))
        return frames
