"""Ball trackers for delayed overhead-camera detections: the EKF of paper 002 (Zhao, Wang, Li
2012) and its baselines.

Both trackers follow the tracker protocol (:class:`~estimators.protocol.Tracker`): they take
detection frames ``update(t, detections, obstacles)`` (capture time ``t`` [s], detected ball
positions ``(k, 2)`` [m], robot positions ``(j, 2)`` seen in the same frame), answer
``estimate(t) -> (x, y, vx, vy)`` for any later time ``t`` (None before the first detection)
and forget everything on ``reset()``.

Latency compensation (paper 002, SPEC 1.3): a measurement corrects the state *at its capture
time*, and the estimate is predicted from there to whatever time is asked, the present or the
present plus the actuation latency. Frames may arrive out of order (several cameras): the
tracker keeps a short history and replays it in capture-time order. A tracker given arrival
times instead of capture times is the "no latency compensation" baseline.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..models.measurement import PositionMeasurement
from ..models.motion import FrictionBallMotion
from ..protocol import check_order, check_time

__all__ = ["BallFilterConfig", "BallTracker", "LeastSquaresBall", "CHI2_2DOF_999"]

#: Largest change of the ball's velocity a kick or a bounce can make [m/s] (a 6.5 m/s ball
#: reversing off a robot moving towards it).
MAX_SPEED_CHANGE = 10.0

#: 99.9 % quantile of the chi-square distribution with 2 degrees of freedom.
CHI2_2DOF_999 = 13.815510557964274


@dataclass(frozen=True)
class BallFilterConfig:
    """Configuration of :class:`BallTracker`. Defaults are paper 002's parameters.

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
    """Kalman / extended Kalman ball tracker with latency compensation (paper 002).

    Args:
        config: filter configuration (paper 002's EKF by default).
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
        """Eq. 19 of paper 002 (:meth:`velocity_sigma` with the obstacles already a list of
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
    """The least-squares trajectory predictor of paper 002's comparison.

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
