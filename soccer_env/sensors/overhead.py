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
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from estimators import PoseMeasurement, PositionMeasurement
from estimators.exact import wrap_angles
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec, SSLRobotSpec
from soccer_env.presets.sensors import VisionSpec
from soccer_env.state import WorldState

__all__ = ["Camera", "DetectionFrame", "FrameBatch", "OverheadVision", "OverheadVisionBatch",
           "default_cameras"]


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


# Points on the ball's disc (centre and two rings), in radii, for the hidden fraction.
_RING = ([(0.0, 0.0)]
         + [(0.5 * math.cos(2 * math.pi * i / 6), 0.5 * math.sin(2 * math.pi * i / 6))
            for i in range(6)]
         + [(0.9 * math.cos(2 * math.pi * i / 12), 0.9 * math.sin(2 * math.pi * i / 12))
            for i in range(12)])


class OverheadVision:
    """The overhead camera system of one field (see the module docstring).

    Args:
        spec: sensor characteristics.
        field, robot, ball: the world's specs (camera layout, robot footprint and height, ball
            radius).
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
        shapes: dict[tuple[float, float], list[int]] = {}
        for i, rs in enumerate(specs):
            shapes.setdefault((float(rs.height), float(rs.radius)), []).append(i)
        #: Robots grouped by body ``((height, radius), indices)``; None when every robot has
        #: ``robot``'s body (the common case, one group without an index list).
        self._shapes: list[tuple[tuple[float, float], list[int]]] | None = (
            None if list(shapes) == [(float(robot.height), float(robot.radius))]
            else list(shapes.items()))
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
        self._draws = _Draws(rng)
        self._queue = []
        self._prev = state
        period = self._period()
        n = len(self.cameras)
        # Capture schedule per camera ("ideal" captures in step(), not on a schedule).
        self._next = ((rng.uniform(0.0, period, n) + state.time).tolist() if period is not None
                      else [math.inf] * n)
        warm = self._capture(state, state, list(range(n)), [state.time] * n, emit_empty=True)
        return [f._replace(t_capture=state.time - self.spec.latency, t_delivered=state.time)
                for f in warm]

    def _period(self) -> float | None:
        return None if self.spec.frame_rate is None else 1.0 / self.spec.frame_rate

    def step(self, state: WorldState) -> list[DetectionFrame]:
        """Capture the frames due since the last call and return those delivered by
        ``state.time``, ordered by delivery time."""
        prev, now = self._prev, state.time
        period = self._period()
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
        span = cur.time - prev.time
        pb, cb = prev.ball.tolist(), cur.ball.tolist()
        # Robot poses at every capture time (linear interpolation, headings on the short
        # arc).
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
        # Noise and uniform draws for everything this call may need. Uniforms per frame:
        # robot detection (N), dribbler reflection (N), ball detection, spurious ball, its x
        # and y, latency jitter.
        draws = self._draws
        noise = draws.normals(F * (N + 2) * 3)
        u = draws.uniforms(F * (2 * N + 5))
        ball_noise, robot_noise = self.ball_model.perturb, self.robot_model.perturb
        period = self._period() or 0.0
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
                         or self._hidden(sx, sy, zc, robots, cx, cy, h)
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

    def _hidden(self, bx: float, by: float, zc: float, robots: list, cx: float, cy: float,
                h: float) -> float:
        """Fraction of the ball's disc (centre ``bx, by`` as seen, centre height ``zc``) that
        the camera at ``(cx, cy, h)`` cannot see past the robots.

        A robot of radius ``R`` and height ``H`` (its own spec's) hides, in the horizontal
        plane through the ball's centre, the region swept by its cross-section from its own
        position to the projection of its top, ``c + (p - c) (h - zc) / (h - H)``, whose radius
        grows to ``R (h - zc) / (h - H)``: a capsule of the larger radius (3 % at most larger
        than the true shape of an SSL robot under a 4 m camera). A ball above a robot cannot be
        hidden by it.
        """
        if self._shapes is None:
            hidden = self._hidden_by(bx, by, zc, robots, cx, cy, h, self.robot_spec.height,
                                     self.robot_spec.radius, None)
        else:
            hidden = None
            for (H, R), members in self._shapes:
                hidden = self._hidden_by(bx, by, zc, [robots[i] for i in members], cx, cy, h,
                                         H, R, hidden)
        return 0.0 if hidden is None else sum(hidden) / len(hidden)

    def _hidden_by(self, bx: float, by: float, zc: float, robots: list, cx: float, cy: float,
                   h: float, H: float, R: float, hidden: list[bool] | None
                   ) -> list[bool] | None:
        """:meth:`_hidden` for ``robots`` of one body (height ``H``, radius ``R``): the ring
        points of the ball's disc they cover added to ``hidden`` (None: none covered yet)."""
        r = self.ball_spec.radius
        if zc >= H:
            return hidden
        k = (h - zc) / (h - H)
        radius = R * k
        reach2 = (radius + r) ** 2
        # No robot farther than this from the ball can cover it: its capsule reaches
        # ``radius + |top - p|`` from it, and ``|top - p| = (k - 1) |p - c|`` with the
        # robot's distance to the camera's foot, under 10 m on any field.
        near2 = (radius + r + 10.0 * (k - 1.0) + 0.01) ** 2
        for x, y, _ in robots:
            if (x - bx) ** 2 + (y - by) ** 2 > near2:
                continue
            tx, ty = cx + (x - cx) * k, cy + (y - cy) * k
            sx, sy = tx - x, ty - y
            seg2 = sx * sx + sy * sy
            # Skip robots whose capsule cannot reach the ball.
            s = ((bx - x) * sx + (by - y) * sy) / seg2 if seg2 > 1e-12 else 0.0
            s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
            dx, dy = bx - x - s * sx, by - y - s * sy
            if dx * dx + dy * dy > reach2:
                continue
            if hidden is None:
                hidden = [False] * len(_RING)
            for j, (ox, oy) in enumerate(_RING):
                if hidden[j]:
                    continue
                px, py = bx + r * ox - x, by + r * oy - y
                s = (px * sx + py * sy) / seg2 if seg2 > 1e-12 else 0.0
                s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
                qx, qy = px - s * sx, py - s * sy
                hidden[j] = qx * qx + qy * qy <= radius * radius
        return hidden


class _Draws:
    """Random numbers drawn from a generator in blocks and handed out as Python floats: a
    frame needs a few dozen, and one numpy call per frame would cost more than using them.
    The sequence is a function of the generator's state and the requests alone, so runs stay
    reproducible."""

    BLOCK = 4096

    def __init__(self, rng: np.random.Generator) -> None:
        self._rng = rng
        self._normal: list[float] = []
        self._n = 0
        self._uniform: list[float] = []
        self._u = 0

    def normals(self, k: int) -> list[float]:
        if self._n + k > len(self._normal):
            self._normal = self._normal[self._n:] + self._rng.standard_normal(
                max(k, self.BLOCK)).tolist()
            self._n = 0
        self._n += k
        return self._normal[self._n - k:self._n]

    def uniforms(self, k: int) -> list[float]:
        if self._u + k > len(self._uniform):
            self._uniform = self._uniform[self._u:] + self._rng.random(
                max(k, self.BLOCK)).tolist()
            self._u = 0
        self._u += k
        return self._uniform[self._u - k:self._u]


class FrameBatch(NamedTuple):
    """Detection frames of many fields (:class:`OverheadVisionBatch`) as arrays, one row per
    frame, the rows of each field in delivery order and the fields in ascending order.

    Attributes:
        env: ``(F,)`` the field (environment) of each frame.
        camera, t_capture, t_delivered: ``(F,)`` as :class:`DetectionFrame`'s.
        balls: ``(F, N + 2, 2)`` ball detections [m] in fixed slots: the ball, the spurious
            balls at robots ``0 .. N-1``'s dribblers, the spurious ball anywhere in view (the
            order of :class:`DetectionFrame`'s ``balls`` once the empty slots are dropped).
        ball_seen: ``(F, N + 2)`` which slots hold a detection.
        robots: ``(F, N, 3)`` detected poses ``(x, y, theta)`` by robot index.
        robot_seen: ``(F, N)`` which robots were detected.
    """

    env: np.ndarray
    camera: np.ndarray
    t_capture: np.ndarray
    t_delivered: np.ndarray
    balls: np.ndarray
    ball_seen: np.ndarray
    robots: np.ndarray
    robot_seen: np.ndarray

    @property
    def count(self) -> int:
        """The number of frames."""
        return len(self.env)

    def take(self, index: np.ndarray) -> FrameBatch:
        """The frames at ``index`` (an index array or a boolean mask)."""
        if index.dtype == bool:  # (one scan of the mask instead of one per column)
            index = np.flatnonzero(index)
        return FrameBatch(*[a[index] for a in self])

    def frames(self, k: int) -> list[DetectionFrame]:
        """Field ``k``'s frames as :class:`DetectionFrame` (for tests and inspection)."""
        out = []
        for f in np.nonzero(self.env == k)[0].tolist():
            ids = np.nonzero(self.robot_seen[f])[0].tolist()
            out.append(DetectionFrame(
                int(self.camera[f]), float(self.t_capture[f]), float(self.t_delivered[f]),
                tuple(tuple(b) for b in self.balls[f][self.ball_seen[f]].tolist()), tuple(ids),
                tuple(tuple(p) for p in self.robots[f][ids].tolist())))
        return out

    @staticmethod
    def join(parts: list[FrameBatch]) -> FrameBatch:
        """The frames of ``parts`` one after another."""
        return FrameBatch(*(np.concatenate(column) for column in zip(*parts)))


class OverheadVisionBatch:
    """The overhead cameras of ``m`` fields alike (one :class:`OverheadVision` each), every
    field's frames captured in one array pass per step.

    Field ``k`` fed field ``k``'s truth gives the frames a single :class:`OverheadVision` on
    that field gives, bit for bit, from the same generator: the same capture schedule, the
    random numbers drawn in the same blocks and handed out in the same order
    (``_Draws``), the same arithmetic (``math.remainder`` by
    :func:`~estimators.exact.wrap_angles`). What happens rarely runs frame by frame in the
    single sensor's code: the occlusion test of a ball near a robot, the spurious balls at
    dribblers (their sine and cosine from the C library, as the single sensor's).
    ``tests/soccer_env/sensors/test_overhead.py`` compares them.

    Args:
        spec, field, robot, ball, n_robots, cameras: as :class:`OverheadVision`'s.
        m: fields.
    """

    def __init__(self, spec: VisionSpec, field: FieldSpec, robot: SSLRobotSpec, ball: BallSpec,
                 n_robots: int, m: int, cameras: list[Camera] | None = None) -> None:
        self._one = OverheadVision(spec, field, robot, ball, n_robots, cameras)
        self.spec, self.cameras = spec, self._one.cameras
        self.ball_model, self.robot_model = self._one.ball_model, self._one.robot_model
        self.n_robots, self.m = n_robots, int(m)
        c = len(self.cameras)
        self._cams = np.array(self.cameras, dtype=np.float64).reshape(c, 7)
        self._next = np.full((self.m, c), math.inf)
        self._prev_t = np.zeros(self.m)
        self._prev_ball = np.zeros((self.m, 3))
        self._prev_robots = np.zeros((self.m, n_robots, 3))
        self._rngs: list[np.random.Generator | None] = [None] * self.m
        self._normals = _BatchDraws(self.m, "normal")
        self._uniforms = _BatchDraws(self.m, "uniform")
        N = n_robots
        #: Frames in flight: the frames captured in each step, in the order of the steps.
        self._queue: list[FrameBatch] = []
        self._empty = FrameBatch(np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64),
                                 np.zeros(0), np.zeros(0), np.zeros((0, N + 2, 2)),
                                 np.zeros((0, N + 2), dtype=bool), np.zeros((0, N, 3)),
                                 np.zeros((0, N), dtype=bool))

    def _period(self) -> float | None:
        return self._one._period()

    def reset(self, rows, times, balls, robots, rngs: list[np.random.Generator]
              ) -> FrameBatch:
        """Start an episode on fields ``rows`` ``(d,)`` at times ``times`` ``(d,)`` with the
        ball at ``balls`` ``(d, 3)`` (``x, y, z``) and the robots at ``robots`` ``(d, N, 3)``
        (poses), each drawing from its generator in ``rngs``; returns their warm-up frames
        (:meth:`OverheadVision.reset`)."""
        return self.advance(start=(rows, times, balls, robots, rngs))[1]

    def step(self, rows, times, balls, robots) -> FrameBatch:
        """Advance fields ``rows`` ``(d,)`` to times ``times`` with their truth (as
        :meth:`reset`): capture the frames due since their last step and return the frames
        delivered by now (:meth:`OverheadVision.step`)."""
        return self.advance(step=(rows, times, balls, robots))[0]

    def advance(self, step: tuple | None = None, start: tuple | None = None
                ) -> tuple[FrameBatch, FrameBatch]:
        """:meth:`step` the fields of ``step`` (``(rows, times, balls, robots)``) and
        :meth:`reset` those of ``start`` (``(rows, times, balls, robots, rngs)``) with one
        capture pass; returns ``(frames delivered to the stepped fields, warm-up frames of the
        started ones)``. The two sets of fields must not meet."""
        c = len(self.cameras)
        period = self._period()
        parts = []  # (env, cams, times, counts, t0, span, prev ball, ball, prev robots, robots)
        horizon = None  # each field's delivery horizon [s], when fields step
        if step is not None and len(step[0]):
            rows, now, balls, robots = step
            rows = np.asarray(rows, dtype=np.int64)
            now = np.asarray(now, dtype=np.float64)
            balls = np.asarray(balls, dtype=np.float64)
            robots = np.asarray(robots, dtype=np.float64)
            horizon = np.full(self.m, -math.inf)
            horizon[rows] = now + 1e-12
            if period is None:
                r = np.repeat(np.arange(len(rows)), c)
                cam = np.tile(np.arange(c), len(rows))
                t = now[r]
            else:
                nxt = self._next[rows]
                limit = (now + 1e-12)[:, None]
                found = []
                rounds = 0
                while True:
                    due = nxt <= limit
                    if not due.any():
                        break
                    r, cam = np.nonzero(due)
                    found.append((r, cam, nxt[r, cam], np.full(len(r), rounds)))
                    nxt[due] += period
                    rounds += 1
                self._next[rows] = nxt
                r = cam = np.zeros(0, dtype=np.int64)
                t = np.zeros(0)
                if found:
                    r, cam, t, it = (np.concatenate(col) for col in zip(*found))
                    order = np.lexsort((it, cam, r))  # field, then camera, then time
                    r, cam, t = r[order], cam[order], t[order]
            if len(r):
                env = rows[r]
                counts = np.bincount(r, minlength=len(rows))[r]
                t0 = self._prev_t[env]
                parts.append((env, cam, t, counts, t0, now[r] - t0, self._prev_ball[env],
                              balls[r], self._prev_robots[env], robots[r]))
            self._prev_t[rows], self._prev_ball[rows] = now, balls
            self._prev_robots[rows] = robots
        n_step = sum(len(p[0]) for p in parts)
        if start is not None and len(start[0]):
            rows, times, balls, robots, rngs = start
            rows = np.asarray(rows, dtype=np.int64)
            times = np.asarray(times, dtype=np.float64)
            balls = np.asarray(balls, dtype=np.float64)
            robots = np.asarray(robots, dtype=np.float64)
            queue = []
            for chunk in self._queue:
                drop = np.isin(chunk.env, rows)
                if drop.all():
                    continue
                queue.append(chunk.take(~drop) if drop.any() else chunk)
            self._queue = queue
            for j, k in enumerate(rows.tolist()):
                rng = rngs[j]
                self._rngs[k] = rng
                self._normals.clear(k)
                self._uniforms.clear(k)
                self._next[k] = (rng.uniform(0.0, period, c) + times[j] if period is not None
                                 else math.inf)
            self._prev_t[rows], self._prev_ball[rows] = times, balls
            self._prev_robots[rows] = robots
            # Every camera at once, of a scene standing still.
            r = np.repeat(np.arange(len(rows)), c)
            t = times[r]
            parts.append((rows[r], np.tile(np.arange(c), len(rows)), t, np.full(len(r), c), t,
                          np.zeros(len(r)), balls[r], balls[r], robots[r], robots[r]))
        if not parts:
            return self._empty, self._empty
        columns = parts[0] if len(parts) == 1 else [np.concatenate(col) for col in zip(*parts)]
        frames = self._capture(*columns)
        warm = frames.take(np.arange(n_step, frames.count))
        warm = warm._replace(t_capture=warm.t_capture - self.spec.latency,
                             t_delivered=warm.t_capture.copy())
        if n_step:
            new = frames.take(np.arange(n_step))
            new = new.take(new.ball_seen.any(axis=1) | new.robot_seen.any(axis=1))
            if new.count:
                self._queue.append(new)
        if horizon is None:
            return self._empty, warm
        delivered, queue = [], []
        for chunk in self._queue:
            out = chunk.t_delivered <= horizon[chunk.env]
            if out.all():
                delivered.append(chunk)
            elif out.any():
                delivered.append(chunk.take(out))
                queue.append(chunk.take(~out))
            else:
                queue.append(chunk)
        self._queue = queue
        if not delivered:
            return self._empty, warm
        got = delivered[0] if len(delivered) == 1 else FrameBatch.join(delivered)
        order = np.lexsort((got.camera, got.t_capture, got.t_delivered, got.env))
        return got.take(order), warm

    # ------------------------------------------------------------------------------------

    def _capture(self, env: np.ndarray, cams: np.ndarray, times: np.ndarray,
                 counts: np.ndarray, t0: np.ndarray, span: np.ndarray, pb: np.ndarray,
                 cb: np.ndarray, pr: np.ndarray, cr: np.ndarray) -> FrameBatch:
        """The frames of cameras ``cams`` of fields ``env`` captured at ``times`` (each
        field's frames consecutive, camera-major as :meth:`OverheadVision.step` lists them),
        each frame with its field's number of frames this step ``counts``, its step's start
        ``t0`` and length ``span`` [s], ball ``x, y, z`` at its start and end ``pb``, ``cb``
        and robot poses ``pr``, ``cr``: :meth:`OverheadVision._capture` on arrays (frames that
        detected nothing included)."""
        spec, rs = self.spec, self._one.robot_spec
        F, N = len(env), self.n_robots
        r = self._one.ball_spec.radius
        with np.errstate(divide="ignore", invalid="ignore"):
            w = np.where(span > 0, (times - t0) / np.where(span > 0, span, 1.0), 1.0)
        # Robot poses at the capture times: positions on the line, headings on the short arc
        # (math.remainder for few frames of few robots, numpy's remainder otherwise, as the
        # single sensor picks them).
        delta = cr - pr
        small = counts * N <= 16
        turn = np.where(small[:, None], wrap_angles(delta[..., 2]),
                        np.remainder(delta[..., 2] + math.pi, 2.0 * math.pi) - math.pi)
        wc = w[:, None]
        X = pr[..., 0] + wc * delta[..., 0]
        Y = pr[..., 1] + wc * delta[..., 1]
        TH = pr[..., 2] + wc * turn
        # Each field's random numbers for all its frames of this step, in one block.
        nn, nu = 3 * (N + 2), 2 * N + 5
        first = np.ones(F, dtype=bool)
        first[1:] = env[1:] != env[:-1]
        starts = np.nonzero(first)[0]
        fields = env[starts]
        per_field = np.diff(np.append(starts, F))
        local = np.arange(F) - np.repeat(starts, per_field)
        nf = self._normals.take(fields, per_field * nn, self._rngs, local, nn, env)
        uf = self._uniforms.take(fields, per_field * nu, self._rngs, local, nu, env)
        cam = self._cams[cams]
        cx, cy, h, x0, x1, y0, y1 = (cam[:, j] for j in range(7))
        inside = ((x0[:, None] <= X) & (X <= x1[:, None]) & (y0[:, None] <= Y)
                  & (Y <= y1[:, None]))
        robot_seen = inside & (uf[:, :N] < spec.robot_detection)
        s, st = self.robot_model.sigma_xy, self.robot_model.sigma_theta
        poses = np.stack([X + s * nf[:, 0:3 * N:3], Y + s * nf[:, 1:3 * N:3],
                          wrap_angles(TH + st * nf[:, 2:3 * N:3])], axis=-1)
        poses[~robot_seen] = 0.0
        balls = np.zeros((F, N + 2, 2))
        ball_seen = np.zeros((F, N + 2), dtype=bool)
        sigma = self.ball_model.sigma
        period = self._period() or 0.0
        p_dribbler = 1.0 - math.exp(-spec.dribbler_false_rate * period)
        p_random = 1.0 - math.exp(-spec.random_false_rate * period)
        if p_dribbler > 0.0:  # rare: frame by frame, with the C library's cos and sin
            front = rs.front_distance + r
            for f, i in zip(*(a.tolist() for a in np.nonzero(inside & (uf[:, N:2 * N]
                                                                      < p_dribbler)))):
                x, y, th = float(X[f, i]), float(Y[f, i]), float(TH[f, i])
                balls[f, 1 + i] = self.ball_model.perturb(
                    x + front * math.cos(th), y + front * math.sin(th), nf[f, 3 * N],
                    nf[f, 3 * N + 1])
                ball_seen[f, 1 + i] = True
        # The ball, where the camera's ray through it meets the resting-ball plane.
        bx = pb[:, 0] + w * (cb[:, 0] - pb[:, 0])
        by = pb[:, 1] + w * (cb[:, 1] - pb[:, 1])
        zc = r + pb[:, 2] + w * (cb[:, 2] - pb[:, 2])
        kk = (h - r) / (h - zc)
        sx, sy = cx + (bx - cx) * kk, cy + (by - cy) * kk
        visible = ((x0 <= sx) & (sx <= x1) & (y0 <= sy) & (sy <= y1)
                   & (uf[:, 2 * N] < spec.ball_detection))
        if spec.occlusion_threshold <= 1.0 and visible.any():
            # The single sensor's test, for the frames where a robot may cover the ball (a
            # looser bound than its own first test, so that no such frame is skipped).
            H, R = rs.height, rs.radius
            low = zc < H
            with np.errstate(divide="ignore", invalid="ignore"):
                kh = (h - zc) / (h - H)
            near = (R * kh + r + 10.0 * (kh - 1.0) + 0.01) ** 2 * (1.0 + 1e-9) + 1e-12
            d2 = (X - sx[:, None]) ** 2 + (Y - sy[:, None]) ** 2
            for f in np.nonzero(visible & low & (d2 <= near[:, None]).any(axis=1))[0].tolist():
                robots = list(zip(X[f].tolist(), Y[f].tolist(), TH[f].tolist()))
                hidden = self._one._hidden(float(sx[f]), float(sy[f]), float(zc[f]), robots,
                                           float(cx[f]), float(cy[f]), float(h[f]))
                visible[f] = hidden < spec.occlusion_threshold
        balls[:, 0, 0] = sx + sigma * nf[:, 3 * N + 3]
        balls[:, 0, 1] = sy + sigma * nf[:, 3 * N + 4]
        ball_seen[:, 0] = visible
        spurious = uf[:, 2 * N + 1] < p_random
        balls[:, N + 1, 0] = x0 + (x1 - x0) * uf[:, 2 * N + 2]
        balls[:, N + 1, 1] = y0 + (y1 - y0) * uf[:, 2 * N + 3]
        ball_seen[:, N + 1] = spurious
        balls[~ball_seen] = 0.0
        delivered = times + (spec.latency + spec.latency_jitter * uf[:, 2 * N + 4])
        return FrameBatch(env.astype(np.int64), cams.astype(np.int64), times.copy(),
                          delivered, balls, ball_seen, poses, robot_seen)


class _BatchDraws:
    """``_Draws`` of many generators: each field's numbers drawn in the same blocks as a
    single sensor's ``_Draws`` and handed out in the same order, kept in one array."""

    def __init__(self, m: int, kind: str) -> None:
        self._kind = kind
        self._buf = np.zeros((m, _Draws.BLOCK))
        self._len = np.zeros(m, dtype=np.int64)
        self._pos = np.zeros(m, dtype=np.int64)

    def clear(self, k: int) -> None:
        """Field ``k`` starts afresh (a new ``_Draws``): nothing drawn yet."""
        self._len[k] = self._pos[k] = 0

    def take(self, fields: np.ndarray, need: np.ndarray, rngs: list, local: np.ndarray,
             width: int, env: np.ndarray) -> np.ndarray:
        """Hand each of ``fields`` its ``need`` numbers; returns ``(F, width)``: frame ``f``
        (of field ``env[f]``, its ``local[f]``-th frame) gets its field's numbers
        ``local * width .. + width`` of this request."""
        short = self._pos[fields] + need > self._len[fields]
        for k, n in zip(fields[short].tolist(), need[short].tolist()):
            rng, pos, length = rngs[k], int(self._pos[k]), int(self._len[k])
            fresh = (rng.standard_normal(max(n, _Draws.BLOCK)) if self._kind == "normal"
                     else rng.random(max(n, _Draws.BLOCK)))
            kept = length - pos
            size = kept + len(fresh)
            if size > self._buf.shape[1]:
                self._buf = np.pad(self._buf, ((0, 0), (0, size - self._buf.shape[1])))
            self._buf[k, :kept] = self._buf[k, pos:length]
            self._buf[k, kept:size] = fresh
            self._pos[k], self._len[k] = 0, size
        base = self._pos[env] + local * width
        out = self._buf[env[:, None], base[:, None] + np.arange(width)]
        self._pos[fields] += need
        return out
