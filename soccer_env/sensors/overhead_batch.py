"""The overhead vision of many fields at once: :class:`OverheadVisionBatch`, the cameras of
``m`` fields alike capturing in one array pass per step, and their frames as arrays
(:class:`FrameBatch`). Field ``k`` gets, bit for bit, the frames of a single
:class:`~soccer_env.sensors.overhead.OverheadVision` on that field.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec
from soccer_env.presets.sensors import VisionSpec
from soccer_env.sensors.draws import BatchDraws
from soccer_env.sensors.overhead import Camera, DetectionFrame, OverheadVision
from soccer_env.sensors.overhead_kernels import capture_frames

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
    (:class:`~soccer_env.sensors.draws.BatchDraws`), and the same capture kernel
    (:func:`~soccer_env.sensors.overhead_kernels.capture_frames`, every field's frames of a
    step in one call). ``tests/soccer_env/sensors/test_overhead.py`` compares them.

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
        # Parts: (frames (env, cams, times, state), states (clock, balls at the step's start
        # and end, robots at its start and end)).
        parts = []
        horizon = None  # each field's delivery horizon [s], when fields step
        if step is not None and len(step[0]):
            part, horizon = self._due(*step)
            if part is not None:
                parts.append(part)
        n_step = sum(len(p[0][0]) for p in parts)
        if start is not None and len(start[0]):
            parts.append(self._start(*start))
        if not parts:
            return self._empty, self._empty
        if len(parts) == 1:
            frames = self._capture(*parts[0][0], *parts[0][1])
        else:
            (first, s1), (second, s2) = parts
            second = (*second[:3], second[3] + len(s1[0]))  # the second part's states follow
            frames = self._capture(*(np.concatenate(col) for col in zip(first, second)),
                                   *(np.concatenate(col) for col in zip(s1, s2)))
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
        columns :meth:`_capture` takes, frames and states, None for none) and every field's
        delivery horizon [s]; the fields' truth is kept for their next step."""
        c = len(self.cameras)
        rows = np.asarray(rows, dtype=np.int64)
        now = np.asarray(now, dtype=np.float64)
        balls = np.ascontiguousarray(balls, dtype=np.float64)
        robots = np.ascontiguousarray(robots, dtype=np.float64)
        horizon = np.full(self.m, -math.inf)
        horizon[rows] = now + 1e-12
        if self.period is None:
            r = np.repeat(np.arange(len(rows)), c)
            cam = np.tile(np.arange(c), len(rows))
            t = now[r]
        else:
            r, cam, t = self._scheduled(rows, now)
        part = None
        if len(r):  # one state per stepped field
            t0 = self._prev_t[rows]
            part = ((rows[r], cam, t, r), (np.column_stack((t0, now - t0)),
                                           self._prev_ball[rows], balls,
                                           self._prev_robots[rows], robots))
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
        of their warm-up captures (every camera at once, of a scene standing still): frames
        and states, as :meth:`_due`'s."""
        c = len(self.cameras)
        period = self.period
        rows = np.asarray(rows, dtype=np.int64)
        times = np.asarray(times, dtype=np.float64)
        balls = np.ascontiguousarray(balls, dtype=np.float64)
        robots = np.ascontiguousarray(robots, dtype=np.float64)
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
        return ((rows[r], np.tile(np.arange(c), len(rows)), times[r], r),
                (np.column_stack((times, np.zeros(len(rows)))), balls, balls, robots, robots))

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
                 state: np.ndarray, clock: np.ndarray, ball0: np.ndarray, ball1: np.ndarray,
                 robots0: np.ndarray, robots1: np.ndarray) -> FrameBatch:
        """The frames of cameras ``cams`` of fields ``env`` captured at ``times`` (each
        field's frames consecutive, camera-major as :meth:`OverheadVision.step` lists them),
        frame ``f`` of the field's step ``state[f]``: its start and length ``clock`` ``(S,
        2)`` [s], the ball ``x, y, z`` at its start and end ``ball0``, ``ball1`` ``(S, 3)``
        and the robots' poses ``robots0``, ``robots1`` ``(S, N, 3)``: the capture kernel
        :func:`~soccer_env.sensors.overhead_kernels.capture_frames` on every frame at once,
        with each field's numbers (:meth:`_numbers`; frames that detected nothing
        included)."""
        one, F, N = self._one, len(env), self.n_robots
        normals, uniforms = self._numbers(env)
        _, b, r, p, width = one.columns
        out = np.empty((F, width))
        capture_frames(state, cams, times, clock, ball0, ball1, robots0, robots1,
                       normals.reshape(-1), uniforms.reshape(-1), one.camera_rows, one.bodies,
                       one.capture_params, out)
        return FrameBatch(env.astype(np.int64), cams.astype(np.int64), times.copy(),
                          out[:, 0].copy(), out[:, b:r].reshape(F, N + 2, 2), out[:, 1:b] != 0.0,
                          out[:, p:].reshape(F, N, 3), out[:, r:p] != 0.0)

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
