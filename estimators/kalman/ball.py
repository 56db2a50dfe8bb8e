"""The EKF ball tracker of Zhao, Wang and Li (2012) for delayed overhead-camera detections.

:class:`BallTracker`, its baseline :class:`~estimators.LeastSquaresBall` and the batched
:class:`~estimators.BallTrackerBatch` follow the tracker protocol
(:class:`~estimators.protocol.Tracker`): they take detection frames
``update(t, detections, obstacles)`` (capture time ``t`` [s], detected ball positions
``(k, 2)`` [m], robot positions ``(j, 2)`` seen in the same frame), answer
``estimate(t) -> (x, y, vx, vy)`` for any later time ``t`` (None before the first detection)
and forget everything on ``reset()``.

Latency compensation (Zhao et al. 2012): a measurement corrects the state *at its capture
time*, and the estimate is predicted from there to whatever time is asked, the present or the
present plus the actuation latency. Frames may arrive out of order (several cameras): the
tracker keeps a short history and replays it in capture-time order
(:class:`~estimators.tracking.ReplayBuffer`). A tracker given arrival
times instead of capture times is the "no latency compensation" baseline.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..checks import check_points
from ..models.measurement import PositionMeasurement
from ..models.motion import FrictionBallMotion
from ..protocol import check_order, check_time
from ..tracking import (
    CHI2_2DOF_999,
    MAX_SPEED_CHANGE,
    Candidates,
    Gate,
    ReplayBuffer,
    TrackInitiator,
    TrackQualityMixin,
    prior_gain,
)
from .blocks import Blocks, State, full_covariance, innovation, predict_covariance, update

__all__ = ["BallFilterConfig", "BallTracker", "BallTrack", "CHI2_2DOF_999", "MAX_SPEED_CHANGE"]


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


class BallTrack(NamedTuple):
    """The state of a :class:`BallTracker` after a frame: everything a replay must restore
    (immutable, so snapshots need no copies).

    Attributes:
        t: capture time of the latest frame processed [s] (``-inf`` before the first).
        x: the state ``(x, y, vx, vy)`` [m, m/s] at ``t`` (None before the first detection).
        P: its covariance as :data:`~estimators.kalman.blocks.Blocks`.
        candidates: gated-out detections that may start a new track
            (:class:`~estimators.tracking.TrackInitiator`).
        v_switch: the two-phase model's switch speed [m/s]: the ball slides while faster.
        fused_at: capture time of the latest detection fused [s].
        since_start: detections fused since the track's latest (re)start.
    """

    t: float = -math.inf
    x: State | None = None
    P: Blocks | None = None
    candidates: Candidates = ()
    v_switch: float = 0.0
    fused_at: float = -math.inf
    since_start: int = 0


class BallTracker(ReplayBuffer, TrackQualityMixin):
    """Kalman / extended Kalman ball tracker with latency compensation (Zhao et al. 2012).

    Built from the shared parts of :mod:`estimators.tracking`: frames go through the
    :class:`~estimators.tracking.ReplayBuffer` (``config.history``) to :meth:`process`,
    which predicts with the friction model (:class:`~estimators.models.FrictionBallMotion`,
    eq. 19's collision-aware velocity noise, the optional two-phase model), takes the
    detection nearest the prediction through the :class:`~estimators.tracking.Gate`
    (``config.gate``) and fuses it with the Kalman blocks of
    :mod:`estimators.kalman.blocks`; a gated-out detection within ``maneuver_radius`` that
    the ball could have reached is a maneuver, any other goes to the
    :class:`~estimators.tracking.TrackInitiator` (``config.reset_after``).

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
        #: The measurement noise variance per axis the filter fuses with [m^2].
        self.r = float(self.measurement.R[0, 0])
        self._gate = Gate(c.gate)
        self._initiator = (None if c.reset_after is None
                           else TrackInitiator(c.sigma_xy, c.reset_after))
        #: Seconds of frames kept to replay out-of-order arrivals (``config.history``).
        self.history = c.history
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._track = BallTrack()
        self.reset_replay()
        self.fused = self.rejected = self.resets = self.maneuvers = 0

    # ------------------------------------------------------------------------------------

    def update(self, t: float, detections, obstacles=None) -> None:
        """Process one frame captured at ``t`` with ball detections ``(k, 2)`` (k may be 0)
        and robot positions seen in it (for eq. 19; ``(j, 2)``, or poses whose first two
        entries are the position)."""
        t = check_time(t)
        check_order(t, self._track.t)
        dets = check_points("detections", detections)
        obs = (check_points("obstacles", obstacles, exact=False) if obstacles is not None
               else [])
        self.update_frame(t, dets, obs)

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
        if self._track.x is None:
            return None
        return self._predicted(t)

    def _covariance(self, t: float) -> np.ndarray:
        return self._predicted(t)[1]

    def _predicted(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """``(x, P)`` of a started track predicted to ``t`` (no process noise for eq. 19's
        robots: ``sigma_r``)."""
        tr = self._track
        dt = t - tr.t
        if dt <= 0.0:
            return np.array(tr.x), full_covariance(tr.P)
        x, A, B = self._step(tr, dt)
        q = self.motion.velocity_noise(dt, self.config.sigma_r)
        return np.array(x), full_covariance(predict_covariance(tr.P, A, B, q))

    # ------------------------------------------------------------------------------------
    # The motion model

    def _step(self, tr: BallTrack, dt: float):
        """The friction model's ``(x', A, B)`` over ``dt`` from ``tr``: the sliding
        deceleration while the two-phase ball is faster than its switch speed."""
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
        obs = (check_points("obstacles", obstacles, exact=False) if obstacles is not None
               else [])
        return self._sigma_v(position, obs)

    def _sigma_v(self, position, obstacles: list) -> float:
        """Eq. 19 of Zhao et al. (2012) (:meth:`velocity_sigma` with the obstacles already a
        list of rows)."""
        c = self.config
        if not c.collision_noise or not obstacles:
            return c.sigma_r
        px, py = position[0], position[1]
        d = min(math.hypot(o[0] - px, o[1] - py) for o in obstacles)
        return max(c.gain_k * (c.robot_radius + c.ball_radius) / max(d, 1e-6) * c.sigma_r,
                   c.sigma_r)

    # ------------------------------------------------------------------------------------
    # The update

    def process(self, track: BallTrack, t: float, detections: Sequence[Sequence[float]],
                obstacles: Sequence[Sequence[float]]) -> BallTrack:
        """The track after one frame captured at ``t`` [s], no earlier than ``track.t``
        (detections and robots as :meth:`update_frame` takes them): predict, gate, then fuse
        the nearest detection, or take it as a maneuver, or offer it to the initiator. The
        counters are updated; ``track`` is not changed. What :meth:`update_frame` replays."""
        c, r = self.config, self.r
        if track.x is None:
            if not detections:
                return track
            zx, zy = detections[0]
            var = c.tau**2
            return BallTrack(t, (zx, zy, 0.0, 0.0), ((var, 0.0, 0.0, var), (0.0,) * 4,
                                                      (var, 0.0, 0.0, var)), (), 0.0, t, 1)
        x, P = track.x, track.P
        dt = t - track.t
        A = B = None
        q_step = 0.0
        if dt > 0.0:
            sigma_v = self._sigma_v(x, obstacles)
            x, A, B = self._step(track, dt)
            q_step = self.motion.velocity_noise(dt, sigma_v)
            P = predict_covariance(P, A, B, q_step)
        if not detections:
            return BallTrack(t, x, P, track.candidates, track.v_switch, track.fused_at,
                             track.since_start)
        # The detection nearest the prediction (Mahalanobis) is this frame's ball.
        gate = self._gate
        P11 = P[0]
        z, d2, Si = gate.nearest(x[0], x[1], (P11[0] + r, P11[1], P11[3] + r), detections)
        z = (float(z[0]), float(z[1]))  # (a float pair: the compiled blocks take one type)
        y = (z[0] - x[0], z[1] - x[1])
        if d2 <= gate.limit:
            self.fused += 1
            x, P = update(x, P, y, Si, r)
            return BallTrack(t, x, P, (), track.v_switch, t, track.since_start + 1)
        # A maneuver must be near the prediction and reachable: a velocity change of at
        # most MAX_SPEED_CHANGE over the time since the last frame, plus noise.
        jump = math.hypot(*y)
        if (c.maneuver_radius is not None and jump <= c.maneuver_radius
                and gate.reaches(jump, dt, c.sigma_xy)):
            return self._maneuver(track, t, x, P, A, B, q_step, z)
        self.rejected += 1
        return self._outlier(BallTrack(t, x, P, track.candidates, track.v_switch,
                                       track.fused_at, track.since_start), t, z)

    def _maneuver(self, track: BallTrack, t: float, x: State, P: Blocks, A, B, q_step: float,
                  z: Sequence[float]) -> BallTrack:
        """The ball changed its motion where it is: redo the prediction from ``track`` (by
        ``A``, ``B``, ``q_step``; none when the frame is another view of the same instant)
        with a velocity change of ``maneuver_speed`` at the previous frame, so that the
        uncertainty reaches the position through the motion, then fuse ``z``."""
        c, r = self.config, self.r
        self.maneuvers += 1
        m = c.maneuver_speed**2
        P11, P12, P22 = track.P
        P = (P11, P12, (P22[0] + m, P22[1], P22[2], P22[3] + m))
        if A is not None:
            P = predict_covariance(P, A, B, q_step)
        y, Si, _ = innovation(x, P, z, r)
        x, P = update(x, P, y, Si, r)
        speed = math.hypot(x[2], x[3])
        v_switch = (c.two_phase[1] * speed if c.two_phase is not None
                    and speed > c.kick_speed else track.v_switch)
        return BallTrack(t, x, P, (), v_switch, t, track.since_start + 1)

    def _outlier(self, tr: BallTrack, t: float, z: Sequence[float]) -> BallTrack:
        """Keep a gated-out detection; restart the track once ``reset_after`` agree."""
        initiator = self._initiator
        if initiator is None:
            return tr
        candidates = initiator.offer(tr.candidates, t, tuple(z))
        if not initiator.ready(candidates):
            return tr._replace(candidates=candidates)
        c = self.config
        (t0, z0), (t1, z1) = candidates[0], candidates[-1]
        span = t1 - t0
        # The finite-difference velocity (z1 - z0) / span has variance 2 sigma^2 / span^2 per
        # axis, unbounded when two cameras see the ball a moment apart: combined with the
        # initiator's prior that a ball moves at most MAX_SPEED_CHANGE.
        s0_2 = initiator.prior_var
        if span > 1e-9:
            var_fd = 2.0 * c.sigma_xy**2 / span**2
            g = prior_gain(s0_2, var_fd)
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
        return BallTrack(tr.t, (z1[0], z1[1], vx, vy),
                         ((var_p, 0.0, 0.0, var_p), (0.0,) * 4, (var_v, 0.0, 0.0, var_v)), (),
                         v_switch, t, 1)
