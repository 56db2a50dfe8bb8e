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

The cameras of many fields alike capture in one array pass with
:class:`~soccer_env.sensors.overhead_batch.OverheadVisionBatch`; the occlusion test is
:class:`~soccer_env.sensors.occlusion.BallOcclusion`'s.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from estimators import PoseMeasurement, PositionMeasurement
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec, SSLRobotSpec
from soccer_env.presets.sensors import VisionSpec
from soccer_env.sensors.draws import BlockDraws
from soccer_env.sensors.occlusion import BallOcclusion
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
        #: How much of the ball the robots' bodies hide from a camera.
        self.occlusion = BallOcclusion(ball.radius, robot, specs)
        fronts = [getattr(rs, "front_distance", None) for rs in specs]
        #: Each robot's dribbler distance from its centre [m] (None: no dribbler); None when
        #: every robot's is ``robot``'s.
        self._fronts: list[float | None] | None = (
            None if all(f == robot.front_distance for f in fronts) else fronts)
        self.cameras = cameras or default_cameras(field, spec.camera_height,
                                                  spec.camera_overlap)
        self.ball_model = PositionMeasurement(spec.ball_sigma)
        self.robot_model = PoseMeasurement(spec.robot_sigma, spec.robot_sigma_theta)
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
        queue = self._queue
        for frame in new:
            heapq.heappush(queue, (frame.t_delivered, frame.t_capture, frame.camera, frame))
        out = []
        while queue and queue[0][0] <= now + 1e-12:
            out.append(heapq.heappop(queue)[3])
        return out

    # ------------------------------------------------------------------------------------

    def _interpolate(self, prev: WorldState, cur: WorldState, times: list[float]
                     ) -> tuple[list[float], list]:
        """The robots' poses at every capture time between ``prev`` and ``cur``: the
        interpolation weights and ``(frames, N)`` poses ``(x, y, theta)``, linear, headings
        on the short arc (plain Python for a few frames of a few robots, one array
        expression for many)."""
        F, N = len(times), self.n_robots
        span = cur.time - prev.time
        t0 = prev.time
        weights = [(t - t0) / span if span > 0 else 1.0 for t in times]
        if F * N <= 16:
            pr, cr = prev.robots.tolist(), cur.robots.tolist()
            moves = [(a[0], a[1], a[2], b[0] - a[0], b[1] - a[1],
                      math.remainder(b[2] - a[2], 2.0 * math.pi)) for a, b in zip(pr, cr)]
            interpolated = [[(x + w * dx, y + w * dy, th + w * dth)
                             for x, y, th, dx, dy, dth in moves] for w in weights]
        else:  # one array expression for many robots
            delta = cur.robots[:, 0:3] - prev.robots[:, 0:3]
            delta[:, 2] = np.remainder(delta[:, 2] + math.pi, 2.0 * math.pi) - math.pi
            interpolated = (prev.robots[None, :, 0:3]
                            + np.array(weights)[:, None, None] * delta).tolist()
        return weights, interpolated

    def _capture(self, prev: WorldState, cur: WorldState, cams: list[int],
                 times: list[float], emit_empty: bool = False) -> list[DetectionFrame]:
        """Frames of cameras ``cams`` captured at ``times`` (between ``prev`` and ``cur``).
        Frames that detected nothing are dropped unless ``emit_empty`` (they carry no
        information for a tracker; the warm-up frames at reset are always kept).

        Plain Python over cameras and robots, with random numbers drawn in blocks: a step has
        a handful of frames with a dozen robots each, sizes at which numpy's per-call overhead
        would dominate.
        """
        spec, rs = self.spec, self.robot_spec
        F, N = len(cams), self.n_robots
        r = self.ball_spec.radius
        pb, cb = prev.ball.tolist(), cur.ball.tolist()
        weights, interpolated = self._interpolate(prev, cur, times)
        # Noise and uniform draws for everything this call may need. Uniforms per frame:
        # robot detection (N), dribbler reflection (N), ball detection, spurious ball, its x
        # and y, latency jitter.
        draws = self._draws
        noise = draws.normals(F * (N + 2) * 3)
        u = draws.uniforms(F * (2 * N + 5))
        ball_noise, robot_noise = self.ball_model.perturb, self.robot_model.perturb
        period = self.period or 0.0
        p_dribbler = 1.0 - math.exp(-spec.dribbler_false_rate * period)
        p_random = 1.0 - math.exp(-spec.random_false_rate * period)
        fronts = self._fronts
        front = rs.front_distance + r
        frames = []
        nn, nu = 3 * (N + 2), 2 * N + 5
        for f, (cam, t) in enumerate(zip(cams, times)):
            cx, cy, h, x0, x1, y0, y1 = self.cameras[cam]
            w = weights[f]
            nf = noise[f * nn:(f + 1) * nn]  # 3 normals per robot, then 3 + 3 for balls
            uf = u[f * nu:(f + 1) * nu]
            robots = interpolated[f]
            ids, poses, balls = [], [], []
            for i, (x, y, th) in enumerate(robots):
                if not (x0 <= x <= x1 and y0 <= y <= y1):
                    continue
                if uf[i] < spec.robot_detection:
                    ids.append(i)
                    poses.append(robot_noise(x, y, th, nf[3 * i], nf[3 * i + 1], nf[3 * i + 2]))
                if uf[N + i] < p_dribbler:  # a spurious ball at this robot's dribbler
                    d = front if fronts is None else (
                        None if fronts[i] is None else fronts[i] + r)  # None: a humanoid
                    if d is not None:
                        balls.append(ball_noise(x + d * math.cos(th), y + d * math.sin(th),
                                                nf[3 * N], nf[3 * N + 1]))
            # The ball, where this camera's ray through it meets the resting-ball plane.
            bx = pb[0] + w * (cb[0] - pb[0])
            by = pb[1] + w * (cb[1] - pb[1])
            zc = r + pb[2] + w * (cb[2] - pb[2])
            k = (h - r) / (h - zc)
            sx, sy = cx + (bx - cx) * k, cy + (by - cy) * k
            if (x0 <= sx <= x1 and y0 <= sy <= y1 and uf[2 * N] < spec.ball_detection
                    and (spec.occlusion_threshold > 1.0
                         or self.occlusion.hidden(sx, sy, zc, robots, cx, cy, h)
                         < spec.occlusion_threshold)):
                balls.insert(0, ball_noise(sx, sy, nf[3 * N + 3], nf[3 * N + 4]))
            if uf[2 * N + 1] < p_random:  # a spurious ball anywhere in view
                balls.append((x0 + (x1 - x0) * uf[2 * N + 2], y0 + (y1 - y0) * uf[2 * N + 3]))
            if not (balls or ids) and not emit_empty:
                continue  # nothing seen: no frame to process downstream
            delay = spec.latency + spec.latency_jitter * uf[2 * N + 4]
            frames.append(DetectionFrame(cam, t, t + delay, tuple(balls), tuple(ids),
                                         tuple(poses)))
        return frames
