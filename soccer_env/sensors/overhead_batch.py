"""The overhead vision of many fields at once: :class:`OverheadVisionBatch`, the cameras of
``m`` fields alike capturing in one array pass per step, and their frames as arrays
(:class:`FrameBatch`). Field ``k`` gets, bit for bit, the frames of a single
:class:`~soccer_env.sensors.overhead.OverheadVision` on that field.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from estimators.exact import wrap_angles
from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec
from soccer_env.presets.sensors import VisionSpec
from soccer_env.sensors.draws import BatchDraws
from soccer_env.sensors.overhead import Camera, DetectionFrame, OverheadVision

__all__ = ["FrameBatch", "OverheadVisionBatch"]


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
    (:class:`~soccer_env.sensors.draws.BatchDraws`), the same arithmetic (``math.remainder`` by
    :func:`~estimators.exact.wrap_angles`). What happens rarely runs frame by frame in the
    single sensor's code: the occlusion test of a ball near a robot, the spurious balls at
    dribblers (their sine and cosine from the C library, as the single sensor's).
    ``tests/soccer_env/sensors/test_overhead.py`` compares them.

    Args:
        spec: sensor characteristics, as :class:`OverheadVision`'s.
        field: the fields' geometry, as :class:`OverheadVision`'s.
        robot: the common robot model, as :class:`OverheadVision`'s.
        ball: the ball, as :class:`OverheadVision`'s.
        n_robots: number of robots on each field.
        m: fields.
        cameras: as :class:`OverheadVision`'s.
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
        self._normals = BatchDraws(self.m, "normal")
        self._uniforms = BatchDraws(self.m, "uniform")
        N = n_robots
        #: Frames in flight: the frames captured in each step, in the order of the steps.
        self._queue: list[FrameBatch] = []
        self._empty = FrameBatch(np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64),
                                 np.zeros(0), np.zeros(0), np.zeros((0, N + 2, 2)),
                                 np.zeros((0, N + 2), dtype=bool), np.zeros((0, N, 3)),
                                 np.zeros((0, N), dtype=bool))

    @property
    def period(self) -> float | None:
        """The cameras' frame period [s] (None: a frame at every step)."""
        return self._one.period

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
        started ones)``. The two sets of fields must not meet.

        The steps: the captures due on the stepped fields (:meth:`_due`) and the warm-up
        captures of the started ones (:meth:`_start`), captured together
        (:meth:`_capture`); the new frames queued, and the frames delivered by each stepped
        field's time taken from the queue (:meth:`_deliver`)."""
        parts = []  # (env, cams, times, counts, t0, span, prev ball, ball, prev robots, robots)
        horizon = None  # each field's delivery horizon [s], when fields step
        if step is not None and len(step[0]):
            part, horizon = self._due(*step)
            if part is not None:
                parts.append(part)
        n_step = sum(len(p[0]) for p in parts)
        if start is not None and len(start[0]):
            parts.append(self._start(*start))
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
        return self._deliver(horizon), warm

    def _due(self, rows, now, balls, robots) -> tuple[tuple | None, np.ndarray]:
        """The captures due on the stepped fields ``rows`` by their times ``now`` (the
        columns :meth:`_capture` takes, None for none) and every field's delivery horizon
        [s]; the fields' truth is kept for their next step."""
        c = len(self.cameras)
        rows = np.asarray(rows, dtype=np.int64)
        now = np.asarray(now, dtype=np.float64)
        balls = np.asarray(balls, dtype=np.float64)
        robots = np.asarray(robots, dtype=np.float64)
        horizon = np.full(self.m, -math.inf)
        horizon[rows] = now + 1e-12
        if self.period is None:
            r = np.repeat(np.arange(len(rows)), c)
            cam = np.tile(np.arange(c), len(rows))
            t = now[r]
        else:
            r, cam, t = self._scheduled(rows, now)
        part = None
        if len(r):
            env = rows[r]
            counts = np.bincount(r, minlength=len(rows))[r]
            t0 = self._prev_t[env]
            part = (env, cam, t, counts, t0, now[r] - t0, self._prev_ball[env], balls[r],
                    self._prev_robots[env], robots[r])
        self._prev_t[rows], self._prev_ball[rows] = now, balls
        self._prev_robots[rows] = robots
        return part, horizon

    def _scheduled(self, rows: np.ndarray, now: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The scheduled captures of fields ``rows`` up to their times ``now`` (every
        camera's frame times passed, each camera's schedule moved on): their positions in
        ``rows``, cameras and capture times, ordered by field, then camera, then time."""
        period = self.period
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
        return r, cam, t

    def _start(self, rows, times, balls, robots, rngs) -> tuple:
        """Start an episode on fields ``rows``: their frames in flight dropped, their
        generators, draws and capture schedules new, their truth kept; returns the columns
        of their warm-up captures (every camera at once, of a scene standing still)."""
        c = len(self.cameras)
        period = self.period
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
        return (rows[r], np.tile(np.arange(c), len(rows)), t, np.full(len(r), c), t,
                np.zeros(len(r)), balls[r], balls[r], robots[r], robots[r])

    def _deliver(self, horizon: np.ndarray) -> FrameBatch:
        """The queued frames delivered by each field's ``horizon`` [s], taken from the queue,
        ordered by field, then delivery time, capture time and camera."""
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
            return self._empty
        got = delivered[0] if len(delivered) == 1 else FrameBatch.join(delivered)
        order = np.lexsort((got.camera, got.t_capture, got.t_delivered, got.env))
        return got.take(order)

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
        w, X, Y, TH = self._interpolate(times, counts, t0, span, pr, cr)
        nf, uf = self._numbers(env)
        cam = self._cams[cams]
        x0, x1, y0, y1 = (cam[:, j] for j in range(3, 7))
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
        period = self.period or 0.0
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
        sx, sy, visible = self._true_ball(cam, w, pb, cb, X, Y, TH, uf[:, 2 * N])
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

    def _interpolate(self, times: np.ndarray, counts: np.ndarray, t0: np.ndarray,
                     span: np.ndarray, pr: np.ndarray, cr: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Each frame's interpolation weight ``(F,)`` and its robots' poses at the capture
        time, ``X, Y, TH`` ``(F, N)``: positions on the line, headings on the short arc
        (``math.remainder`` for few frames of few robots, numpy's remainder otherwise, as the
        single sensor picks them)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            w = np.where(span > 0, (times - t0) / np.where(span > 0, span, 1.0), 1.0)
        delta = cr - pr
        small = counts * self.n_robots <= 16
        turn = np.where(small[:, None], wrap_angles(delta[..., 2]),
                        np.remainder(delta[..., 2] + math.pi, 2.0 * math.pi) - math.pi)
        wc = w[:, None]
        X = pr[..., 0] + wc * delta[..., 0]
        Y = pr[..., 1] + wc * delta[..., 1]
        TH = pr[..., 2] + wc * turn
        return w, X, Y, TH

    def _numbers(self, env: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The normals ``(F, 3 (N + 2))`` and uniforms ``(F, 2 N + 5)`` of the frames of
        fields ``env``: each field's numbers for all its frames of this step in one block, as
        the single sensor takes them."""
        F, N = len(env), self.n_robots
        nn, nu = 3 * (N + 2), 2 * N + 5
        first = np.ones(F, dtype=bool)
        first[1:] = env[1:] != env[:-1]
        starts = np.nonzero(first)[0]
        fields = env[starts]
        per_field = np.diff(np.append(starts, F))
        local = np.arange(F) - np.repeat(starts, per_field)
        nf = self._normals.take(fields, per_field * nn, self._rngs, local, nn, env)
        uf = self._uniforms.take(fields, per_field * nu, self._rngs, local, nu, env)
        return nf, uf

    def _true_ball(self, cam: np.ndarray, w: np.ndarray, pb: np.ndarray, cb: np.ndarray,
                   X: np.ndarray, Y: np.ndarray, TH: np.ndarray, detect: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The true ball in each frame of cameras ``cam`` ``(F, 7)``: where the camera's ray
        through it meets the resting-ball plane ``sx, sy`` [m], and whether it is seen (in
        view, its detection uniform ``detect`` under the detection probability, not hidden
        by the robots at ``X, Y, TH``)."""
        spec, rs = self.spec, self._one.robot_spec
        r = self._one.ball_spec.radius
        cx, cy, h, x0, x1, y0, y1 = (cam[:, j] for j in range(7))
        bx = pb[:, 0] + w * (cb[:, 0] - pb[:, 0])
        by = pb[:, 1] + w * (cb[:, 1] - pb[:, 1])
        zc = r + pb[:, 2] + w * (cb[:, 2] - pb[:, 2])
        kk = (h - r) / (h - zc)
        sx, sy = cx + (bx - cx) * kk, cy + (by - cy) * kk
        visible = ((x0 <= sx) & (sx <= x1) & (y0 <= sy) & (sy <= y1)
                   & (detect < spec.ball_detection))
        if spec.occlusion_threshold <= 1.0 and visible.any():
            # The single sensor's test, for the frames where a robot may cover the ball (a
            # looser bound than its own first test, so that no such frame is skipped).
            H, R = rs.height, rs.radius
            low = zc < H
            with np.errstate(divide="ignore", invalid="ignore"):
                kh = (h - zc) / (h - H)
            near = (R * kh + r + 10.0 * (kh - 1.0) + 0.01) ** 2 * (1.0 + 1e-9) + 1e-12
            d2 = (X - sx[:, None]) ** 2 + (Y - sy[:, None]) ** 2
            hidden_by = self._one.occlusion.hidden
            for f in np.nonzero(visible & low & (d2 <= near[:, None]).any(axis=1))[0].tolist():
                robots = list(zip(X[f].tolist(), Y[f].tolist(), TH[f].tolist()))
                hidden = hidden_by(float(sx[f]), float(sy[f]), float(zc[f]), robots,
                                   float(cx[f]), float(cy[f]), float(h[f]))
                visible[f] = hidden < spec.occlusion_threshold
        return sx, sy, visible
