"""Ball trackers for delayed overhead-camera detections: the EKF of Zhao, Wang and Li (2012)
and its baselines.

Both trackers follow the tracker protocol (:class:`~estimators.protocol.Tracker`): they take
detection frames ``update(t, detections, obstacles)`` (capture time ``t`` [s], detected ball
positions ``(k, 2)`` [m], robot positions ``(j, 2)`` seen in the same frame), answer
``estimate(t) -> (x, y, vx, vy)`` for any later time ``t`` (None before the first detection)
and forget everything on ``reset()``.

Latency compensation (Zhao et al. 2012): a measurement corrects the state *at its capture
time*, and the estimate is predicted from there to whatever time is asked, the present or the
present plus the actuation latency. Frames may arrive out of order (several cameras): the
tracker keeps a short history and replays it in capture-time order. A tracker given arrival
times instead of capture times is the "no latency compensation" baseline.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..exact import hypots
from ..models.measurement import PositionMeasurement
from ..models.motion import PAPER_CYCLE, FrictionBallMotion
from ..protocol import check_order, check_time

__all__ = ["BallFilterConfig", "BallTracker", "BallTrackerBatch", "LeastSquaresBall",
           "CHI2_2DOF_999"]

#: Largest change of the ball's velocity a kick or a bounce can make [m/s] (a 6.5 m/s ball
#: reversing off a robot moving towards it).
MAX_SPEED_CHANGE = 10.0

#: 99.9 % quantile of the chi-square distribution with 2 degrees of freedom.
CHI2_2DOF_999 = 13.815510557964274


@dataclass(frozen=True)
class BallFilterConfig:
    """Configuration of :class:`BallTracker`. Defaults are Zhao et al.'s (2012) parameters.

    Attributes:
        deceleration: carpet friction ``a_f`` [m/s^2] (paper: 0.23); 0 makes a
            constant-velocity Kalman filter.
        propagation: ``"jacobian"`` (basic EKF) or ``"rk"`` (improved EKF), see
            :class:`~estimators.models.FrictionBallMotion`.
        sigma_xy: measurement noise the filter assumes [m] (paper: ``delta_xy`` = 25 mm).
        tau: initial standard deviation of every state component [m, m/s] (paper: 100 mm,
            100 mm/s).
        sigma_r: velocity noise per 40 ms cycle far from robots [m/s] (paper:
            ``delta_R`` = 100 mm/s).
        collision_noise: use eq. 19, ``sigma_v = max(k (R + r) / d sigma_R, sigma_R)`` with
            ``d`` the distance from the ball to the nearest robot, so the filter trusts the
            model less where the ball may be hit.
        gain_k, robot_radius, ball_radius: ``k`` = 10, ``R`` = 75 mm, ``r`` = 20 mm of eq. 19.
        gate: reject detections whose squared Mahalanobis distance exceeds this (false
            detections, outliers); None fuses everything.
        reset_after: after this many consecutive gated-out detections that agree with each
            other (a kick or a collision moved the ball), restart the track from them with the
            finite-difference velocity; None never resets.
        maneuver_radius: a gated-out detection within this distance [m] of the predicted
            position is taken as the ball changing its motion where it is (a kick, a bounce):
            the velocity variance is raised by ``maneuver_speed^2`` and the detection fused at
            once, instead of waiting for ``reset_after`` detections. None disables this.
        maneuver_speed: standard deviation [m/s] of the velocity change assumed at a
            maneuver.
        two_phase: ``(sliding_deceleration, k_switch)``: after a reset faster than
            ``kick_speed`` the ball slides at the first deceleration until its speed falls to
            ``k_switch`` times the reset speed, then rolls at ``deceleration``. None: one
            phase, as in the paper.
        kick_speed: reset speed [m/s] above which a reset counts as a kick (two-phase model).
        history: seconds of frames kept to replay out-of-order arrivals.
    """

    deceleration: float = 0.23
    propagation: str = "jacobian"
    sigma_xy: float = 0.025
    tau: float = 0.1
    sigma_r: float = 0.1
    collision_noise: bool = True
    gain_k: float = 10.0
    robot_radius: float = 0.075
    ball_radius: float = 0.02
    gate: float | None = CHI2_2DOF_999
    reset_after: int | None = 2
    maneuver_radius: float | None = 0.15
    maneuver_speed: float = 3.0
    two_phase: tuple[float, float] | None = None
    kick_speed: float = 1.0
    history: float = 0.5

    def __post_init__(self) -> None:
        for name in ("sigma_xy", "tau", "sigma_r", "gain_k", "robot_radius", "ball_radius",
                     "kick_speed", "history", "maneuver_speed"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0.0):
                raise ValueError(f"{name} must be finite and > 0, got {v!r}")
        if self.gate is not None and not self.gate > 0:
            raise ValueError(f"gate must be > 0 or None, got {self.gate!r}")
        if self.reset_after is not None and (not isinstance(self.reset_after, int)
                                             or self.reset_after < 1):
            raise ValueError(f"reset_after must be a positive integer or None, got "
                             f"{self.reset_after!r}")
        if self.reset_after is not None and self.gate is None:
            raise ValueError("reset_after needs a gate: only gated-out detections trigger resets")
        if self.two_phase is not None:
            a_slide, k = self.two_phase
            if not (a_slide >= 0 and 0 < k < 1):
                raise ValueError(f"two_phase must be (sliding deceleration >= 0, 0 < k_switch "
                                 f"< 1), got {self.two_phase!r}")
        FrictionBallMotion(self.deceleration, self.propagation)  # validates both


def _points(name: str, value, exact: bool = True) -> list:
    """``value`` (``k`` points, k may be 0: an array ``(k, 2)`` or a sequence of ``(x, y)``
    sequences; with ``exact=False`` longer rows whose first two entries are ``x, y``, such as
    poses) as a list of rows; ``ValueError`` for other shapes or non-finite values."""
    if isinstance(value, np.ndarray):
        if value.size == 0:
            return []
        if value.ndim != 2 or value.shape[1] < 2 or (exact and value.shape[1] != 2):
            raise ValueError(f"{name} must have shape (k, 2), got {value.shape}")
        rows = value.tolist()
    elif isinstance(value, (list, tuple)):
        rows = value
    else:
        raise TypeError(f"{name} must be an array or a sequence of points, got "
                        f"{type(value).__name__}")
    total = 0.0
    for p in rows:
        n = len(p)
        if n < 2 or (exact and n != 2):
            raise ValueError(f"{name} must have shape (k, 2); got a point of length {n}")
        total += p[0] + p[1]
    if not math.isfinite(total):
        raise ValueError(f"{name} must be finite (NaN measurements are refused)")
    return rows


# --------------------------------------------------------------------------------------------
# The filter arithmetic in plain floats.
#
# The ball filter runs for every camera frame, often several times per environment step, and a
# 4-state filter is a few dozen multiply-adds: numpy's per-call overhead (about a microsecond
# per operation, some twenty operations per update) would cost ten times the arithmetic. So
# the state is a 4-tuple and the covariance three 2 x 2 row-major blocks
# ``P = [[P11, P12], [P12^T, P22]]``; with ``F = [[I, A], [0, B]]`` and ``H = [I 0]`` the
# equations of :class:`~estimators.kalman.KalmanFilter` reduce to the block forms below.
# tests/estimators/kalman/test_ball.py checks them against that class to 1e-10.
# --------------------------------------------------------------------------------------------

_Mat = tuple[float, float, float, float]


def _t(a: _Mat) -> _Mat:
    return (a[0], a[2], a[1], a[3])


def _predict(x, P, A: _Mat, B: _Mat, q: float):
    """``P = F P F^T + Q`` for ``F = [[I, A], [0, B]]``, ``Q = diag(0, 0, q, q)``.

    With ``P21 = P12^T``: ``P11' = P11 + A P21 + P12 A^T + A P22 A^T``,
    ``P12' = (P12 + A P22) B^T``, ``P22' = B P22 B^T + q I`` (written out element by element).
    """
    (p0, p1, _, p3), (m0, m1, m2, m3), (n0, n1, _, n3) = P
    a0, a1, a2, a3 = A
    b0, b1, b2, b3 = B
    # A P22 (P22 symmetric: n2 = n1)
    t0, t1 = a0 * n0 + a1 * n1, a0 * n1 + a1 * n3
    t2, t3 = a2 * n0 + a3 * n1, a2 * n1 + a3 * n3
    # A P21 with P21 = P12^T = (m0, m2, m1, m3)
    s0, s1 = a0 * m0 + a1 * m1, a0 * m2 + a1 * m3
    s2, s3 = a2 * m0 + a3 * m1, a2 * m2 + a3 * m3
    q00 = p0 + 2.0 * s0 + t0 * a0 + t1 * a1
    q01 = p1 + s1 + s2 + 0.5 * (t0 * a2 + t1 * a3 + t2 * a0 + t3 * a1)
    q11 = p3 + 2.0 * s3 + t2 * a2 + t3 * a3
    w0, w1, w2, w3 = m0 + t0, m1 + t1, m2 + t2, m3 + t3
    P12n = (w0 * b0 + w1 * b1, w0 * b2 + w1 * b3, w2 * b0 + w3 * b1, w2 * b2 + w3 * b3)
    u0, u1 = b0 * n0 + b1 * n1, b0 * n1 + b1 * n3
    u2, u3 = b2 * n0 + b3 * n1, b2 * n1 + b3 * n3
    r01 = 0.5 * (u0 * b2 + u1 * b3 + u2 * b0 + u3 * b1)
    return ((q00, q01, q01, q11), P12n,
            (u0 * b0 + u1 * b1 + q, r01, r01, u2 * b2 + u3 * b3 + q))


def _innovation(x, P, z, r: float) -> tuple[float, float, _Mat, float]:
    """``(y, S^-1, d^2)`` of a position measurement ``z`` with noise variance ``r``."""
    P11 = P[0]
    s0, s1, s3 = P11[0] + r, P11[1], P11[3] + r
    det = s0 * s3 - s1 * s1
    Si = (s3 / det, -s1 / det, -s1 / det, s0 / det)
    y0, y1 = z[0] - x[0], z[1] - x[1]
    d2 = y0 * (Si[0] * y0 + Si[1] * y1) + y1 * (Si[2] * y0 + Si[3] * y1)
    return (y0, y1), Si, d2


def _update(x, P, y, Si: _Mat, r: float):
    """Kalman gain, mean and Joseph-form covariance for ``H = [I 0]``, ``R = r I``.

    ``K1 = P11 S^-1``, ``K2 = P21 S^-1``; with ``M = I - K1``, ``N = -K2``:
    ``P11' = M P11 M^T + r K1 K1^T``, ``P12' = M P11 N^T + M P12 + r K1 K2^T``,
    ``P22' = (N P11 + P21) N^T + N P12 + P22 + r K2 K2^T`` (written out element by element;
    the symmetric blocks are stored with equal off-diagonals).
    """
    (p0, p1, _, p3), (m0, m1, m2, m3), (n0, n1, _, n3) = P
    i0, i1, _, i3 = Si
    y0, y1 = y
    # K1 = P11 S^-1, K2 = P21 S^-1 with P21 = (m0, m2, m1, m3).
    a0, a1, a2, a3 = p0 * i0 + p1 * i1, p0 * i1 + p1 * i3, p1 * i0 + p3 * i1, p1 * i1 + p3 * i3
    b0, b1, b2, b3 = m0 * i0 + m2 * i1, m0 * i1 + m2 * i3, m1 * i0 + m3 * i1, m1 * i1 + m3 * i3
    xn = (x[0] + a0 * y0 + a1 * y1, x[1] + a2 * y0 + a3 * y1,
          x[2] + b0 * y0 + b1 * y1, x[3] + b2 * y0 + b3 * y1)
    # M = I - K1 = (c0, c1, c2, c3); N = -K2.
    c0, c1, c2, c3 = 1.0 - a0, -a1, -a2, 1.0 - a3
    # M P11
    e0, e1 = c0 * p0 + c1 * p1, c0 * p1 + c1 * p3
    e2, e3 = c2 * p0 + c3 * p1, c2 * p1 + c3 * p3
    # P11' = (M P11) M^T + r K1 K1^T
    q00 = e0 * c0 + e1 * c1 + r * (a0 * a0 + a1 * a1)
    q01 = 0.5 * (e0 * c2 + e1 * c3 + e2 * c0 + e3 * c1) + r * (a0 * a2 + a1 * a3)
    q11 = e2 * c2 + e3 * c3 + r * (a2 * a2 + a3 * a3)
    # P12' = (M P11) N^T + M P12 + r K1 K2^T, N^T = -(b0, b2, b1, b3)
    f0 = -(e0 * b0 + e1 * b1) + c0 * m0 + c1 * m2 + r * (a0 * b0 + a1 * b1)
    f1 = -(e0 * b2 + e1 * b3) + c0 * m1 + c1 * m3 + r * (a0 * b2 + a1 * b3)
    f2 = -(e2 * b0 + e3 * b1) + c2 * m0 + c3 * m2 + r * (a2 * b0 + a3 * b1)
    f3 = -(e2 * b2 + e3 * b3) + c2 * m1 + c3 * m3 + r * (a2 * b2 + a3 * b3)
    # N P11 + P21, with N = -K2
    g0, g1 = -(b0 * p0 + b1 * p1) + m0, -(b0 * p1 + b1 * p3) + m2
    g2, g3 = -(b2 * p0 + b3 * p1) + m1, -(b2 * p1 + b3 * p3) + m3
    # P22' = (N P11 + P21) N^T + N P12 + P22 + r K2 K2^T
    h00 = -(g0 * b0 + g1 * b1) - (b0 * m0 + b1 * m2) + n0 + r * (b0 * b0 + b1 * b1)
    h01 = 0.5 * (-(g0 * b2 + g1 * b3) - (b0 * m1 + b1 * m3)
                 - (g2 * b0 + g3 * b1) - (b2 * m0 + b3 * m2)) + n1 + r * (b0 * b2 + b1 * b3)
    h11 = -(g2 * b2 + g3 * b3) - (b2 * m1 + b3 * m3) + n3 + r * (b2 * b2 + b3 * b3)
    return xn, ((q00, q01, q01, q11), (f0, f1, f2, f3), (h00, h01, h01, h11))


def _full(P) -> np.ndarray:
    P11, P12, P22 = P
    return np.block([[np.reshape(P11, (2, 2)), np.reshape(P12, (2, 2))],
                     [np.reshape(_t(P12), (2, 2)), np.reshape(P22, (2, 2))]])


class _Track(NamedTuple):
    """Everything a replay must restore (immutable, so snapshots need no copies): the filter
    at capture time ``t``, gated-out detections that may start a new track, and the two-phase
    switch speed."""

    t: float = -math.inf
    x: tuple | None = None
    P: tuple | None = None
    candidates: tuple = ()
    v_switch: float = 0.0
    fused_at: float = -math.inf  # capture time of the latest fused detection
    since_start: int = 0  # detections fused since the track's latest (re)start


class BallTracker:
    """Kalman / extended Kalman ball tracker with latency compensation (Zhao et al. 2012).

    Args:
        config: filter configuration (Zhao et al.'s 2012 EKF by default).
        measurement: the sensor's :class:`~estimators.models.PositionMeasurement` (the same
            object that simulates the detections); by default one with ``config.sigma_xy``.

    Attributes:
        fused, rejected, resets, maneuvers, late: counters of detections fused, gated out,
            track resets, maneuvers (see ``maneuver_radius``) and frames too old to replay
            (older than ``history``).
    """

    def __init__(self, config: BallFilterConfig | None = None,
                 measurement: PositionMeasurement | None = None) -> None:
        self.config = config or BallFilterConfig()
        c = self.config
        self.motion = FrictionBallMotion(c.deceleration, c.propagation)
        # The sensor's own measurement model when given (its R), else one from sigma_xy.
        self.measurement = measurement or PositionMeasurement(c.sigma_xy, 4)
        self._r = float(self.measurement.R[0, 0])
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._track = _Track()
        self._base = _Track()  # state before the oldest frame still in the log
        self._log: list[tuple[float, list, list, _Track]] = []
        self.fused = self.rejected = self.resets = self.maneuvers = self.late = 0

    @property
    def initialized(self) -> bool:
        return self._track.x is not None

    @property
    def time(self) -> float:
        """Capture time of the latest processed frame (``-inf`` before the first)."""
        return self._track.t

    @property
    def last_fused(self) -> float:
        """Capture time of the latest detection fused into the track, the one that started
        it included (``-inf`` before the first) [s]."""
        return self._track.fused_at

    @property
    def since_start(self) -> int:
        """Detections fused since the track's latest (re)start, the starting one included (0
        before the first)."""
        return self._track.since_start

    def covariance(self, t: float) -> np.ndarray | None:
        """The ``4 x 4`` covariance of ``(x, y, vx, vy)`` [m, m/s] predicted to ``t`` (None
        before the first detection)."""
        out = self.estimate_with_covariance(t)
        return None if out is None else out[1]

    # ------------------------------------------------------------------------------------

    def update(self, t: float, detections, obstacles=None) -> None:
        """Process one frame captured at ``t`` with ball detections ``(k, 2)`` (k may be 0)
        and robot positions seen in it (for eq. 19; ``(j, 2)``, or poses whose first two
        entries are the position)."""
        t = check_time(t)
        check_order(t, self._track.t)
        dets = _points("detections", detections)
        obs = _points("obstacles", obstacles, exact=False) if obstacles is not None else []
        self.update_frame(t, dets, obs)

    def update_frame(self, t: float, detections: Sequence[Sequence[float]],
                     obstacles: Sequence[Sequence[float]]) -> None:
        """:meth:`update` without its checks, for a pipeline whose frames are checked already
        (a sensor's own: ``t`` a finite float, ``detections`` a sequence of finite ``(x, y)``
        and ``obstacles`` of finite rows whose first two entries are a position, neither
        None, ``t`` no older than the latest frame by more than
        :data:`~estimators.protocol.MAX_REWIND`)."""
        dets, obs = detections, obstacles
        if t >= self._track.t:
            self._track = self._process(self._track, t, dets, obs)
            self._log.append((t, dets, obs, self._track))
        elif t < self._base.t:
            self.late += 1
            return
        else:  # out of order: rewind to the state before t and replay
            i = bisect.bisect_right([entry[0] for entry in self._log], t)
            track = self._log[i - 1][3] if i > 0 else self._base
            self._log.insert(i, (t, dets, obs, track))
            for j in range(i, len(self._log)):
                tj, dj, oj, _ = self._log[j]
                track = self._process(track, tj, dj, oj)
                self._log[j] = (tj, dj, oj, track)
            self._track = track
        # Drop what is older than the replay window.
        horizon = self._log[-1][0] - self.config.history
        while len(self._log) > 1 and self._log[0][0] < horizon:
            self._base = self._log.pop(0)[3]


    def estimate(self, t: float) -> np.ndarray | None:
        """State ``(x, y, vx, vy)`` predicted to time ``t`` (None before the first frame)."""
        t = check_time(t)
        tr = self._track
        if tr.x is None:
            return None
        dt = t - tr.t
        if dt <= 0.0:
            return np.array(tr.x)
        return np.array(self._step(tr, dt)[0])

    def estimate_with_covariance(self, t: float) -> tuple[np.ndarray, np.ndarray] | None:
        """``(x, P)`` predicted to time ``t`` without changing the tracker."""
        t = check_time(t)
        tr = self._track
        if tr.x is None:
            return None
        dt = t - tr.t
        if dt <= 0.0:
            return np.array(tr.x), _full(tr.P)
        x, A, B = self._step(tr, dt)
        q = self.motion.velocity_noise(dt, self.config.sigma_r)
        return np.array(x), _full(_predict(tr.x, tr.P, A, B, q))

    # ------------------------------------------------------------------------------------

    def _step(self, tr: _Track, dt: float):
        c = self.config
        decel = None
        if c.two_phase is not None and math.hypot(tr.x[2], tr.x[3]) > tr.v_switch:
            decel = c.two_phase[0]
        return self.motion.step(*tr.x, dt, decel)

    def velocity_sigma(self, position, obstacles=None) -> float:
        """The velocity noise ``sigma_v`` [m/s per paper cycle] of eq. 19 for a ball at
        ``position`` ``(x, y)`` [m] with robots at ``obstacles`` (``(j, 2)``, or poses whose
        first two entries are the position; None: no robots): ``sigma_r``, raised near a robot
        when ``collision_noise`` is on (what :meth:`update` uses between two frames)."""
        obs = _points("obstacles", obstacles, exact=False) if obstacles is not None else []
        return self._sigma_v(position, obs)

    def _sigma_v(self, position, obstacles: list) -> float:
        """Eq. 19 of Zhao et al. (2012) (:meth:`velocity_sigma` with the obstacles already a list of
        rows)."""
        c = self.config
        if not c.collision_noise or not obstacles:
            return c.sigma_r
        px, py = position[0], position[1]
        d = min(math.hypot(o[0] - px, o[1] - py) for o in obstacles)
        return max(c.gain_k * (c.robot_radius + c.ball_radius) / max(d, 1e-6) * c.sigma_r,
                   c.sigma_r)

    def _process(self, tr: _Track, t: float, dets: list, obstacles: list) -> _Track:
        c, r = self.config, self._r
        if tr.x is None:
            if not dets:
                return tr
            zx, zy = dets[0]
            var = c.tau**2
            return _Track(t, (zx, zy, 0.0, 0.0), ((var, 0.0, 0.0, var), (0.0,) * 4,
                                                   (var, 0.0, 0.0, var)), (), 0.0, t, 1)
        x, P = tr.x, tr.P
        dt = t - tr.t
        A = B = None
        if dt > 0.0:
            sigma_v = self._sigma_v(x, obstacles)
            x, A, B = self._step(tr, dt)
            q_step = self.motion.velocity_noise(dt, sigma_v)
            P = _predict(tr.x, P, A, B, q_step)
        if not dets:
            return _Track(t, x, P, tr.candidates, tr.v_switch, tr.fused_at, tr.since_start)
        # The detection nearest the prediction (Mahalanobis) is this frame's ball.
        best = None
        for z in dets:
            y, Si, d2 = _innovation(x, P, z, r)
            if best is None or d2 < best[3]:
                best = (z, y, Si, d2)
        z, y, Si, d2 = best
        if c.gate is None or d2 <= c.gate:
            self.fused += 1
            x, P = _update(x, P, y, Si, r)
            return _Track(t, x, P, (), tr.v_switch, t, tr.since_start + 1)
        # A maneuver must be near the prediction and reachable: a velocity change of at
        # most MAX_SPEED_CHANGE over the time since the last frame, plus noise.
        jump = math.hypot(*y)
        if (c.maneuver_radius is not None and jump <= c.maneuver_radius
                and jump <= MAX_SPEED_CHANGE * dt + 3.0 * c.sigma_xy):
            # The ball changed its motion where it is: redo the prediction with a velocity
            # change of maneuver_speed at the previous frame, so that the uncertainty reaches
            # the position through the motion, then fuse.
            self.maneuvers += 1
            m = c.maneuver_speed**2
            P11, P12, P22 = tr.P
            P = (P11, P12, (P22[0] + m, P22[1], P22[2], P22[3] + m))
            if A is not None:
                P = _predict(tr.x, P, A, B, q_step)
            y, Si, _ = _innovation(x, P, z, r)
            x, P = _update(x, P, y, Si, r)
            speed = math.hypot(x[2], x[3])
            v_switch = (c.two_phase[1] * speed if c.two_phase is not None
                        and speed > c.kick_speed else tr.v_switch)
            return _Track(t, x, P, (), v_switch, t, tr.since_start + 1)
        self.rejected += 1
        return self._outlier(_Track(t, x, P, tr.candidates, tr.v_switch, tr.fused_at,
                                    tr.since_start), t, z)

    def _outlier(self, tr: _Track, t: float, z: list[float]) -> _Track:
        """Keep gated-out detections; restart the track once enough of them agree."""
        c = self.config
        if c.reset_after is None:
            return tr
        candidates = tr.candidates
        if candidates:
            t0, z0 = candidates[-1]
            # Two detections belong to one moving ball if a ball at most 10 m/s could
            # connect them (plus noise); otherwise the older one was spurious.
            gap = math.hypot(z[0] - z0[0], z[1] - z0[1])
            if gap > MAX_SPEED_CHANGE * (t - t0) + 5.0 * c.sigma_xy:
                candidates = ()
            elif t <= t0:  # a second camera's view of the same instant: no new information
                return tr._replace(candidates=candidates)
        candidates = (*candidates, (t, tuple(z)))
        if len(candidates) < c.reset_after:
            return tr._replace(candidates=candidates)
        (t0, z0), (t1, z1) = candidates[0], candidates[-1]
        span = t1 - t0
        # The finite-difference velocity (z1 - z0) / span has variance 2 sigma^2 / span^2 per
        # axis, unbounded when two cameras see the ball a moment apart. Combine it with the
        # prior that a ball moves at most MAX_SPEED_CHANGE (v ~ N(0, s0^2), s0 = a third of
        # it): v = g v_fd and var = g var_fd with g = s0^2 / (s0^2 + var_fd).
        s0_2 = (MAX_SPEED_CHANGE / 3.0) ** 2
        if span > 1e-9:
            var_fd = 2.0 * c.sigma_xy**2 / span**2
            g = s0_2 / (s0_2 + var_fd)
            vx, vy = g * (z1[0] - z0[0]) / span, g * (z1[1] - z0[1]) / span
            var_v = g * var_fd + c.sigma_r**2
        else:
            vx = vy = 0.0
            var_v = s0_2 + c.sigma_r**2
        var_p = c.sigma_xy**2
        speed = math.hypot(vx, vy)
        v_switch = (c.two_phase[1] * speed if c.two_phase is not None and speed > c.kick_speed
                    else 0.0)
        self.resets += 1
        return _Track(tr.t, (z1[0], z1[1], vx, vy),
                      ((var_p, 0.0, 0.0, var_p), (0.0,) * 4, (var_v, 0.0, 0.0, var_v)), (),
                      v_switch, t, 1)


class LeastSquaresBall:
    """The least-squares trajectory predictor of Zhao et al.'s (2012) comparison.

    Fits ``p(t) = p0 + v (t - t_last)`` to the last ``window`` detections by least squares
    (separately in ``x`` and ``y``) and extrapolates to the requested time. Of several
    detections in one frame it keeps the one nearest to the extrapolation.
    """

    def __init__(self, window: int = 6, sigma_xy: float = 0.01) -> None:
        if not isinstance(window, int) or window < 2:
            raise ValueError(f"window must be an integer >= 2, got {window!r}")
        if not (math.isfinite(sigma_xy) and sigma_xy > 0.0):
            raise ValueError(f"sigma_xy must be a finite number > 0 [m], got {sigma_xy!r}")
        self.window = window
        #: The detections' noise [m] (per axis) that :meth:`covariance` assumes.
        self.sigma_xy = float(sigma_xy)
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._t: list[float] = []
        self._z: list[np.ndarray] = []

    @property
    def initialized(self) -> bool:
        return bool(self._t)

    @property
    def time(self) -> float:
        return self._t[-1] if self._t else -math.inf

    @property
    def last_fused(self) -> float:
        """Capture time of the latest detection in the fit (``-inf`` before the first) [s]."""
        return self.time

    @property
    def since_start(self) -> int:
        """Detections in the fit (at most ``window``; the predictor never restarts)."""
        return len(self._t)

    def covariance(self, t: float) -> np.ndarray | None:
        """The ``4 x 4`` covariance of ``(x, y, vx, vy)`` extrapolated to ``t``: ordinary
        least squares with independent noise ``sigma_xy`` per axis, so per axis
        ``var p(t) = s^2 (1/n + (t - tm)^2 / S)``, ``var v = s^2 / S`` and
        ``cov(p, v) = s^2 (t - tm) / S`` with ``tm`` the mean and ``S`` the sum of squared
        deviations of the ``n`` detection times. With one detection the velocity is unknown:
        its variance is that of a ball anywhere up to ``MAX_SPEED_CHANGE``. None before the
        first detection."""
        t = check_time(t)
        if not self._t:
            return None
        s2 = self.sigma_xy**2
        n = len(self._t)
        ts = np.asarray(self._t)
        tm = float(ts.mean())
        S = float(np.sum((ts - tm) ** 2))
        if n < 2 or S <= 0.0:
            var_v = (MAX_SPEED_CHANGE / 3.0) ** 2
            var_p, cov_pv = s2 + var_v * max(0.0, t - tm) ** 2, var_v * max(0.0, t - tm)
        else:
            d = t - tm
            var_p, cov_pv, var_v = s2 * (1.0 / n + d * d / S), s2 * d / S, s2 / S
        P = np.zeros((4, 4))
        for a in (0, 1):
            P[a, a], P[a, a + 2] = var_p, cov_pv
            P[a + 2, a], P[a + 2, a + 2] = cov_pv, var_v
        return P

    def update(self, t: float, detections, obstacles=None) -> None:
        """Process one frame captured at ``t`` with ball detections ``(k, 2)`` (k may be 0);
        ``obstacles`` is accepted for the protocol's sake and not used."""
        t = check_time(t)
        check_order(t, self._t[-1] if self._t else -math.inf)
        dets = np.asarray(detections, dtype=np.float64).reshape(-1, 2) if len(
            detections) else np.zeros((0, 2))
        if not np.isfinite(dets).all():
            raise ValueError("detections must be finite (NaN measurements are refused)")
        if not len(dets):
            return
        z = dets[0]
        if len(dets) > 1 and self._t:
            guess = self.estimate(t)[:2]
            z = dets[np.argmin(np.hypot(*(dets - guess).T))]
        i = bisect.bisect_right(self._t, t)
        self._t.insert(i, t)
        self._z.insert(i, z.copy())
        del self._t[: -self.window], self._z[: -self.window]


    def estimate(self, t: float) -> np.ndarray | None:
        """State ``(x, y, vx, vy)`` extrapolated to time ``t`` (None before the first
        detection)."""
        t = check_time(t)
        if not self._t:
            return None
        if len(self._t) == 1:
            z = self._z[0]
            return np.array([z[0], z[1], 0.0, 0.0])
        ts = np.asarray(self._t) - self._t[-1]
        zs = np.asarray(self._z)
        A = np.column_stack([np.ones_like(ts), ts])
        coef, *_ = np.linalg.lstsq(A, zs, rcond=None)  # rows: p0, v
        p0, v = coef
        dt = t - self._t[-1]
        return np.array([p0[0] + v[0] * dt, p0[1] + v[1] * dt, v[0], v[1]])


# --------------------------------------------------------------------------------------------
# The same filter for many balls at once.
#
# Column-array transliterations of _predict, _innovation and _update above: the same
# operations in the same order, on arrays whose rows are independent filters, so that each row
# rounds exactly as the plain-float version does. ``P`` is ``(d, 12)``: the blocks P11, P12 and
# P22 row-major in columns 0-3, 4-7 and 8-11; ``A``, ``B`` are ``(d, 4)`` row-major 2 x 2.
# --------------------------------------------------------------------------------------------


def _predict_rows(P: np.ndarray, A: np.ndarray, B: np.ndarray, q: np.ndarray) -> np.ndarray:
    p0, p1, p3 = P[:, 0], P[:, 1], P[:, 3]
    m0, m1, m2, m3 = P[:, 4], P[:, 5], P[:, 6], P[:, 7]
    n0, n1, n3 = P[:, 8], P[:, 9], P[:, 11]
    a0, a1, a2, a3 = A.T
    b0, b1, b2, b3 = B.T
    t0, t1 = a0 * n0 + a1 * n1, a0 * n1 + a1 * n3
    t2, t3 = a2 * n0 + a3 * n1, a2 * n1 + a3 * n3
    s0, s1 = a0 * m0 + a1 * m1, a0 * m2 + a1 * m3
    s2, s3 = a2 * m0 + a3 * m1, a2 * m2 + a3 * m3
    out = np.empty_like(P)
    out[:, 0] = p0 + 2.0 * s0 + t0 * a0 + t1 * a1
    out[:, 1] = out[:, 2] = p1 + s1 + s2 + 0.5 * (t0 * a2 + t1 * a3 + t2 * a0 + t3 * a1)
    out[:, 3] = p3 + 2.0 * s3 + t2 * a2 + t3 * a3
    w0, w1, w2, w3 = m0 + t0, m1 + t1, m2 + t2, m3 + t3
    out[:, 4], out[:, 5] = w0 * b0 + w1 * b1, w0 * b2 + w1 * b3
    out[:, 6], out[:, 7] = w2 * b0 + w3 * b1, w2 * b2 + w3 * b3
    u0, u1 = b0 * n0 + b1 * n1, b0 * n1 + b1 * n3
    u2, u3 = b2 * n0 + b3 * n1, b2 * n1 + b3 * n3
    out[:, 8] = u0 * b0 + u1 * b1 + q
    out[:, 9] = out[:, 10] = 0.5 * (u0 * b2 + u1 * b3 + u2 * b0 + u3 * b1)
    out[:, 11] = u2 * b2 + u3 * b3 + q
    return out


def _innovation_rows(x: np.ndarray, P: np.ndarray, z: np.ndarray, r: float):
    """``(y0, y1, Si (4 columns), d2)`` of detections ``z`` ``(d, k, 2)`` against ``d``
    filters (broadcast over the ``k`` detections)."""
    s0, s1, s3 = P[:, 0] + r, P[:, 1], P[:, 3] + r
    det = s0 * s3 - s1 * s1
    i0, i1, i3 = s3 / det, -s1 / det, s0 / det
    i0, i1, i3 = i0[:, None], i1[:, None], i3[:, None]
    y0, y1 = z[..., 0] - x[:, 0:1], z[..., 1] - x[:, 1:2]
    d2 = y0 * (i0 * y0 + i1 * y1) + y1 * (i1 * y0 + i3 * y1)
    return y0, y1, (i0, i1, i3), d2


def _update_rows(x: np.ndarray, P: np.ndarray, y0: np.ndarray, y1: np.ndarray, Si,
                 r: float) -> tuple[np.ndarray, np.ndarray]:
    p0, p1, p3 = P[:, 0], P[:, 1], P[:, 3]
    m0, m1, m2, m3 = P[:, 4], P[:, 5], P[:, 6], P[:, 7]
    n0, n1, n3 = P[:, 8], P[:, 9], P[:, 11]
    i0, i1, i3 = Si
    a0, a1, a2, a3 = p0 * i0 + p1 * i1, p0 * i1 + p1 * i3, p1 * i0 + p3 * i1, p1 * i1 + p3 * i3
    b0, b1, b2, b3 = m0 * i0 + m2 * i1, m0 * i1 + m2 * i3, m1 * i0 + m3 * i1, m1 * i1 + m3 * i3
    xn = np.empty_like(x)
    xn[:, 0] = x[:, 0] + a0 * y0 + a1 * y1
    xn[:, 1] = x[:, 1] + a2 * y0 + a3 * y1
    xn[:, 2] = x[:, 2] + b0 * y0 + b1 * y1
    xn[:, 3] = x[:, 3] + b2 * y0 + b3 * y1
    c0, c1, c2, c3 = 1.0 - a0, -a1, -a2, 1.0 - a3
    e0, e1 = c0 * p0 + c1 * p1, c0 * p1 + c1 * p3
    e2, e3 = c2 * p0 + c3 * p1, c2 * p1 + c3 * p3
    out = np.empty_like(P)
    out[:, 0] = e0 * c0 + e1 * c1 + r * (a0 * a0 + a1 * a1)
    out[:, 1] = out[:, 2] = (0.5 * (e0 * c2 + e1 * c3 + e2 * c0 + e3 * c1)
                             + r * (a0 * a2 + a1 * a3))
    out[:, 3] = e2 * c2 + e3 * c3 + r * (a2 * a2 + a3 * a3)
    out[:, 4] = -(e0 * b0 + e1 * b1) + c0 * m0 + c1 * m2 + r * (a0 * b0 + a1 * b1)
    out[:, 5] = -(e0 * b2 + e1 * b3) + c0 * m1 + c1 * m3 + r * (a0 * b2 + a1 * b3)
    out[:, 6] = -(e2 * b0 + e3 * b1) + c2 * m0 + c3 * m2 + r * (a2 * b0 + a3 * b1)
    out[:, 7] = -(e2 * b2 + e3 * b3) + c2 * m1 + c3 * m3 + r * (a2 * b2 + a3 * b3)
    g0, g1 = -(b0 * p0 + b1 * p1) + m0, -(b0 * p1 + b1 * p3) + m2
    g2, g3 = -(b2 * p0 + b3 * p1) + m1, -(b2 * p1 + b3 * p3) + m3
    out[:, 8] = -(g0 * b0 + g1 * b1) - (b0 * m0 + b1 * m2) + n0 + r * (b0 * b0 + b1 * b1)
    out[:, 9] = out[:, 10] = (0.5 * (-(g0 * b2 + g1 * b3) - (b0 * m1 + b1 * m3)
                                     - (g2 * b0 + g3 * b1) - (b2 * m0 + b3 * m2))
                              + n1 + r * (b0 * b2 + b1 * b3))
    out[:, 11] = -(g2 * b2 + g3 * b3) - (b2 * m1 + b3 * m3) + n3 + r * (b2 * b2 + b3 * b3)
    return xn, out


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
        self.config, self.motion, self._r = self._one.config, self._one.motion, self._one._r
        self.m = m = int(m)
        self._t, self._x, self._P = np.empty(m), np.empty((m, 4)), np.empty((m, 12))
        self.initialized = np.empty(m, dtype=bool)
        self._pending = np.empty(m, dtype=bool)  # rows with candidates
        self._v_switch, self.last_fused = np.empty(m), np.empty(m)
        self.since_start = np.empty(m, dtype=np.int64)
        self._candidates: list[tuple] = [()] * m
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
        """Eq. 19 for every row (``BallTracker._sigma_v``)."""
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
        raise ``ValueError``."""
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
        if not init.any():
            return
        rows, t, z, has, any_det = rows[init], t[init], z[init], has[init], any_det[init]
        obstacles, obstacle_seen = obstacles[init], obstacle_seen[init]
        x0, P0, t0 = self._x[rows], self._P[rows], self._t[rows]
        dt = t - t0
        x, P = x0.copy(), P0.copy()
        moved = dt > 0.0
        if moved.any():
            sigma_v = self._sigma_v(x0[moved], obstacles[moved], obstacle_seen[moved])
            a = self._decelerations(x0[moved], self._v_switch[rows[moved]])
            xm, A, B = self._motion(x0[moved], dt[moved], a)
            q = sigma_v * sigma_v * dt[moved] / PAPER_CYCLE
            x[moved], P[moved] = xm, _predict_rows(P0[moved], A, B, q)
        # No detection: the prediction is the track.
        self._t[rows] = t
        quiet = ~any_det
        if quiet.any():
            self._x[rows[quiet]], self._P[rows[quiet]] = x[quiet], P[quiet]
        if not any_det.any():
            return
        # The detection nearest the prediction (Mahalanobis; the first of equals).
        seen_rows = np.nonzero(any_det)[0]
        xs, Ps = x[seen_rows], P[seen_rows]
        y0, y1, Si, d2 = _innovation_rows(xs, Ps, z[seen_rows], self._r)
        d2 = np.where(has[seen_rows], d2, np.inf)
        best = d2.argmin(axis=1)
        pick = np.arange(len(seen_rows))
        d2b = d2[pick, best]
        gate = self.config.gate
        inside = np.ones(len(seen_rows), dtype=bool) if gate is None else d2b <= gate
        if inside.any():
            j = seen_rows[inside]
            k = rows[j]
            b = best[inside]
            Sj = tuple(s[inside, 0] for s in Si)
            xn, Pn = _update_rows(xs[inside], Ps[inside], y0[inside, b], y1[inside, b], Sj,
                                  self._r)
            self._x[k], self._P[k] = xn, Pn
            self.fused[k] += 1
            self.last_fused[k] = t[j]
            self.since_start[k] += 1
            clear = self._pending[k]
            if clear.any():
                for kk in k[clear].tolist():
                    self._candidates[kk] = ()
                self._pending[k] = False
        if not inside.all():  # gated out: BallTracker's own code, row by row
            one = self._one
            for j in seen_rows[~inside].tolist():
                k = int(rows[j])
                before = _Track(float(t0[j]),
                                tuple(x0[j].tolist()), _blocks(P0[j]), self._candidates[k],
                                float(self._v_switch[k]), float(self.last_fused[k]),
                                int(self.since_start[k]))
                dets = z[j][has[j]].tolist()
                obs = obstacles[j][obstacle_seen[j]].tolist()
                counts = (one.fused, one.rejected, one.resets, one.maneuvers)
                tr = one._process(before, float(t[j]), dets, obs)
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


def _blocks(P: np.ndarray) -> tuple:
    """A ``(12,)`` covariance row as :class:`_Track`'s three 4-tuples."""
    v = P.tolist()
    return (tuple(v[0:4]), tuple(v[4:8]), tuple(v[8:12]))
