"""The EKF ball tracker of many environments as arrays (:class:`BallTrackerBatch`)."""

from __future__ import annotations

import math

import numpy as np

from ..exact import hypots
from ..models.measurement import PositionMeasurement
from ..models.motion import PAPER_CYCLE
from ..tracking import Candidates
from .ball import BallFilterConfig, BallTrack, BallTracker
from .blocks import blocks_from_row, innovation_rows, predict_covariance_rows, update_rows

__all__ = ["BallTrackerBatch"]


class BallTrackerBatch:
    """``m`` independent :class:`BallTracker` with one configuration, as arrays: the ball
    filters of ``m`` environments updated by one array operation per batch of frames.

    Tracker ``k`` gives what a :class:`BallTracker` fed the same frames gives, bit for bit
    (``tests/estimators/kalman/test_ball.py``): the prediction, the choice of the detection
    and its fusion are the plain-float arithmetic transliterated onto columns (``math.hypot``
    by :func:`~estimators.exact.hypots`), and what happens rarely (a detection outside the
    gate: a maneuver, an outlier, a track restart; the Runge-Kutta propagation of
    ``propagation="rk"``) runs row by row through :class:`BallTracker`'s own code.

    Frames must come in capture-time order per tracker (``update`` raises ``ValueError``
    otherwise): the single tracker's replay of out-of-order frames is not batched, so a sensor
    whose latency jitters needs :class:`BallTracker`.

    Args:
        m: trackers (environments).
        config: as :class:`BallTracker`'s.
        measurement: as :class:`BallTracker`'s.

    Attributes:
        fused, rejected, resets, maneuvers: ``(m,)`` counters, as :class:`BallTracker`'s.
    """

    def __init__(self, m: int, config: BallFilterConfig | None = None,
                 measurement: PositionMeasurement | None = None) -> None:
        if not isinstance(m, (int, np.integer)) or m < 1:
            raise ValueError(f"m must be a positive integer, got {m!r}")
        self._one = BallTracker(config, measurement)
        self.config, self.motion, self.r = self._one.config, self._one.motion, self._one.r
        self.m = m = int(m)
        self._t, self._x, self._P = np.empty(m), np.empty((m, 4)), np.empty((m, 12))
        self.initialized = np.empty(m, dtype=bool)
        self._pending = np.empty(m, dtype=bool)  # rows with candidates
        self._v_switch, self.last_fused = np.empty(m), np.empty(m)
        self.since_start = np.empty(m, dtype=np.int64)
        self._candidates: list[Candidates] = [()] * m
        self.fused, self.rejected, self.resets, self.maneuvers = (
            np.empty(m, dtype=np.int64) for _ in range(4))
        self.reset()

    def reset(self, rows=None) -> None:
        """Forget trackers ``rows`` (all by default)."""
        rows = np.arange(self.m) if rows is None else np.asarray(rows, dtype=np.int64)
        self._t[rows] = self.last_fused[rows] = -math.inf
        self._x[rows] = self._P[rows] = self._v_switch[rows] = 0.0
        self.initialized[rows] = self._pending[rows] = False
        for array in (self.since_start, self.fused, self.rejected, self.resets, self.maneuvers):
            array[rows] = 0
        for k in rows.tolist():
            self._candidates[k] = ()

    # ------------------------------------------------------------------------------------

    def _decelerations(self, x: np.ndarray, v_switch: np.ndarray) -> np.ndarray:
        """Each row's deceleration for its next prediction (``_step``'s choice)."""
        c = self.config
        a = np.full(len(x), self.motion.deceleration)
        if c.two_phase is not None:
            a[hypots(x[:, 2], x[:, 3]) > v_switch] = c.two_phase[0]
        return a

    def _motion(self, x: np.ndarray, T: np.ndarray, a: np.ndarray):
        """:meth:`FrictionBallMotion.step` of every row: ``(x', A, B)``."""
        d = len(x)
        A = np.zeros((d, 4))
        B = np.zeros((d, 4))
        out = np.empty_like(x)
        if self.motion.propagation == "rk":  # rare in practice: row by row
            for j, (row, Tj, aj) in enumerate(zip(x.tolist(), T.tolist(), a.tolist())):
                mean, Aj, Bj = self.motion.step(*row, Tj, aj)
                out[j], A[j], B[j] = mean, Aj, Bj
            return out, A, B
        px, py, vx, vy = x.T
        speed = hypots(vx, vy)
        plain = (a == 0.0) | (speed == 0.0)
        rolls = ~plain & (speed > a * T)
        stops = ~plain & ~rolls
        if plain.any():
            Tp = T[plain]
            out[plain] = np.stack([px[plain] + vx[plain] * Tp, py[plain] + vy[plain] * Tp,
                                   vx[plain], vy[plain]], axis=1)
            A[plain, 0] = A[plain, 3] = Tp
            B[plain, 0] = B[plain, 3] = 1.0
        if rolls.any():
            s, Tr, ar = speed[rolls], T[rolls], a[rolls]
            X, Y, VX, VY = px[rolls], py[rolls], vx[rolls], vy[rolls]
            ux, uy = VX / s, VY / s
            half = 0.5 * ar * Tr * Tr
            out[rolls] = np.stack([X + VX * Tr - half * ux, Y + VY * Tr - half * uy,
                                   VX - ar * Tr * ux, VY - ar * Tr * uy], axis=1)
            g00, g01, g11 = (1.0 - ux * ux) / s, -ux * uy / s, (1.0 - uy * uy) / s
            A[rolls] = np.stack([Tr - half * g00, -half * g01, -half * g01, Tr - half * g11],
                                axis=1)
            B[rolls] = np.stack([1.0 - ar * Tr * g00, -ar * Tr * g01, -ar * Tr * g01,
                                 1.0 - ar * Tr * g11], axis=1)
        if stops.any():
            Ts = T[stops]
            out[stops] = np.stack([px[stops] + 0.5 * vx[stops] * Ts,
                                   py[stops] + 0.5 * vy[stops] * Ts,
                                   np.zeros(len(Ts)), np.zeros(len(Ts))], axis=1)
            A[stops, 0] = A[stops, 3] = 0.5 * Ts
        return out, A, B

    def _sigma_v(self, x: np.ndarray, obstacles: np.ndarray, seen: np.ndarray) -> np.ndarray:
        """Eq. 19 for every row (:meth:`BallTracker.velocity_sigma`)."""
        c = self.config
        sigma = np.full(len(x), c.sigma_r)
        near = seen.any(axis=1) if c.collision_noise else np.zeros(len(x), dtype=bool)
        if near.any():
            o, xs = obstacles[near], x[near]
            d = hypots(o[..., 0] - xs[:, 0:1], o[..., 1] - xs[:, 1:2])
            d = np.where(seen[near], d, np.inf).min(axis=1)
            gain = c.gain_k * (c.robot_radius + c.ball_radius)
            sigma[near] = np.maximum(gain / np.maximum(d, 1e-6) * c.sigma_r, c.sigma_r)
        return sigma

    def update(self, rows, t, detections, detected, obstacles=None, obstacle_seen=None
               ) -> None:
        """Process one frame of each tracker in ``rows`` ``(d,)`` (distinct), captured at
        ``t`` ``(d,)`` [s]: ball detections ``detections`` ``(d, k, 2)`` [m] of which
        ``detected`` ``(d, k)`` are real (in their frame's order), and the robots seen in the
        frame ``obstacles`` ``(d, j, 2+)`` of which ``obstacle_seen`` ``(d, j)`` are real.
        Unchecked values (the batch's fast path), but times before a tracker's latest frame
        raise ``ValueError``.

        The steps of :meth:`BallTracker.process` on rows: start the tracks of rows without
        one (:meth:`_start`), predict (:meth:`_predict`), gate and fuse the nearest detection
        (:meth:`_fuse`), and hand a gated-out one to the single tracker
        (:meth:`_gated_out`)."""
        rows = np.asarray(rows, dtype=np.int64)
        t = np.asarray(t, dtype=np.float64)
        z = np.asarray(detections, dtype=np.float64)
        has = np.asarray(detected, dtype=bool)
        if obstacles is None:
            obstacles, obstacle_seen = np.zeros((len(rows), 0, 2)), np.zeros((len(rows), 0),
                                                                              dtype=bool)
        obstacles = np.asarray(obstacles, dtype=np.float64)[..., 0:2]
        obstacle_seen = np.asarray(obstacle_seen, dtype=bool)
        if not len(rows):
            return
        if (t < self._t[rows]).any():
            raise ValueError("frames must come in capture-time order per tracker "
                             "(BallTracker replays late frames; BallTrackerBatch does not)")
        any_det = has.any(axis=1)
        init = self.initialized[rows]
        start = ~init & any_det
        if start.any():
            self._start(rows, t, z, has, start)
        if not init.any():
            return
        rows, t, z, has, any_det = rows[init], t[init], z[init], has[init], any_det[init]
        obstacles, obstacle_seen = obstacles[init], obstacle_seen[init]
        x0, P0, t0 = self._x[rows], self._P[rows], self._t[rows]
        x, P = self._predict(rows, t - t0, x0, P0, obstacles, obstacle_seen)
        # No detection: the prediction is the track.
        self._t[rows] = t
        quiet = ~any_det
        if quiet.any():
            self._x[rows[quiet]], self._P[rows[quiet]] = x[quiet], P[quiet]
        if not any_det.any():
            return
        seen = np.nonzero(any_det)[0]
        inside = self._fuse(rows, t, seen, x, P, z, has)
        if not inside.all():
            for j in seen[~inside].tolist():
                self._gated_out(int(rows[j]), float(t0[j]), float(t[j]), x0[j], P0[j],
                                z[j][has[j]].tolist(),
                                obstacles[j][obstacle_seen[j]].tolist())

    def _start(self, rows: np.ndarray, t: np.ndarray, z: np.ndarray, has: np.ndarray,
               start: np.ndarray) -> None:
        """Start the tracks of ``rows[start]`` at their first detection, as
        :meth:`BallTracker.process` does: at rest, every component of standard deviation
        ``tau``."""
        k, ts = rows[start], t[start]
        first = z[start, has[start].argmax(axis=1)]
        var = self.config.tau ** 2
        self._t[k] = ts
        self._x[k] = 0.0
        self._x[k, 0:2] = first
        self._P[k] = 0.0
        self._P[k, 0] = self._P[k, 3] = self._P[k, 8] = self._P[k, 11] = var
        self._v_switch[k] = 0.0
        self.last_fused[k] = ts
        self.since_start[k] = 1
        self.initialized[k] = True

    def _predict(self, rows: np.ndarray, dt: np.ndarray, x0: np.ndarray, P0: np.ndarray,
                 obstacles: np.ndarray, seen: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(x, P)`` of trackers ``rows`` (states ``x0``, ``P0``) predicted over ``dt``
        ``(d,)`` [s] (unchanged where ``dt`` is 0) with eq. 19's noise from the robots
        ``obstacles`` of which ``seen`` are real."""
        x, P = x0.copy(), P0.copy()
        moved = dt > 0.0
        if moved.any():
            sigma_v = self._sigma_v(x0[moved], obstacles[moved], seen[moved])
            a = self._decelerations(x0[moved], self._v_switch[rows[moved]])
            xm, A, B = self._motion(x0[moved], dt[moved], a)
            q = sigma_v * sigma_v * dt[moved] / PAPER_CYCLE
            x[moved], P[moved] = xm, predict_covariance_rows(P0[moved], A, B, q)
        return x, P

    def _fuse(self, rows: np.ndarray, t: np.ndarray, seen: np.ndarray, x: np.ndarray,
              P: np.ndarray, z: np.ndarray, has: np.ndarray) -> np.ndarray:
        """Of the rows ``seen`` (indices into ``rows``, ``t``, ``x``, ``P``, ``z``, ``has``),
        take each frame's detection nearest the prediction (Mahalanobis; the first of equals)
        and fuse it where the gate admits it; returns which were inside, ``(len(seen),)``."""
        xs, Ps = x[seen], P[seen]
        y0, y1, Si, d2 = innovation_rows(xs, Ps, z[seen], self.r)
        d2 = np.where(has[seen], d2, np.inf)
        best = d2.argmin(axis=1)
        pick = np.arange(len(seen))
        d2b = d2[pick, best]
        gate = self.config.gate
        inside = np.ones(len(seen), dtype=bool) if gate is None else d2b <= gate
        if inside.any():
            j = seen[inside]
            k = rows[j]
            b = best[inside]
            Sj = tuple(s[inside, 0] for s in Si)
            xn, Pn = update_rows(xs[inside], Ps[inside], y0[inside, b], y1[inside, b], Sj,
                                 self.r)
            self._x[k], self._P[k] = xn, Pn
            self.fused[k] += 1
            self.last_fused[k] = t[j]
            self.since_start[k] += 1
            clear = self._pending[k]
            if clear.any():
                for kk in k[clear].tolist():
                    self._candidates[kk] = ()
                self._pending[k] = False
        return inside

    def _gated_out(self, k: int, t0: float, t: float, x0: np.ndarray, P0: np.ndarray,
                   detections: list, obstacles: list) -> None:
        """Tracker ``k``'s frame at ``t`` whose nearest detection the gate rejected (a
        maneuver, an outlier, a restart): :meth:`BallTracker.process` from its state
        ``x0``, ``P0`` at ``t0``, the counters carried over."""
        one = self._one
        before = BallTrack(t0, tuple(x0.tolist()), blocks_from_row(P0), self._candidates[k],
                           float(self._v_switch[k]), float(self.last_fused[k]),
                           int(self.since_start[k]))
        counts = (one.fused, one.rejected, one.resets, one.maneuvers)
        tr = one.process(before, t, detections, obstacles)
        self.fused[k] += one.fused - counts[0]
        self.rejected[k] += one.rejected - counts[1]
        self.resets[k] += one.resets - counts[2]
        self.maneuvers[k] += one.maneuvers - counts[3]
        self._t[k] = tr.t
        self._x[k] = tr.x
        self._P[k] = np.concatenate(tr.P)
        self._candidates[k] = tr.candidates
        self._pending[k] = bool(tr.candidates)
        self._v_switch[k] = tr.v_switch
        self.last_fused[k] = tr.fused_at
        self.since_start[k] = tr.since_start

    def estimate(self, t) -> tuple[np.ndarray, np.ndarray]:
        """``(x, known)``: ``(m, 4)`` states ``(x, y, vx, vy)`` of every tracker predicted to
        its time ``t`` (``(m,)`` [s], or one time for all; zeros where ``known`` is False,
        before a tracker's first frame)."""
        t = np.broadcast_to(np.asarray(t, dtype=np.float64), (self.m,))
        out = np.zeros((self.m, 4))
        known = self.initialized.copy()
        dt = np.where(known, t - np.where(known, self._t, 0.0), 0.0)
        ahead = known & (dt > 0.0)
        out[known & ~ahead] = self._x[known & ~ahead]
        if ahead.any():
            x = self._x[ahead]
            a = self._decelerations(x, self._v_switch[ahead])
            out[ahead] = self._motion(x, dt[ahead], a)[0]
        return out, known
