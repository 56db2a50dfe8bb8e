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

from ..checks import (
    MAX_COORDINATE,
    MAX_SPEED,
    check_count,
    check_flag,
    check_points,
    check_positive,
    check_reals,
)
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
)
from .ball_kernels import (
    FUSED,
    MANEUVERS,
    REJECTED,
    RESETS,
    TRACK_WIDTH,
    as_points,
    ball_estimate,
    ball_frame,
    ball_parameters,
    ball_predicted,
    collision_sigma,
    track_width,
)
from .blocks import Blocks, State, blocks_from_row

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
        collision_noise: ``True`` or ``False`` (a bool, not a number): use eq. 19,
            ``sigma_v = max(k (R + r) / d sigma_R, sigma_R)`` with ``d`` the distance from the
            ball to the nearest robot, so the filter trusts the model less where the ball may
            be hit.
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

    Each field is checked when the configuration is made (``ValueError`` naming it): the
    lengths are at most :data:`~estimators.checks.MAX_COORDINATE` and the speeds at most
    :data:`~estimators.checks.MAX_SPEED` (:data:`POSITIVE_FIELDS`), so that their squares
    stay finite.
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
        """Check every field (``ValueError`` naming it, nothing built); numbers are stored
        as floats."""
        def put(name: str, value: object) -> None:
            object.__setattr__(self, name, value)

        for name, high, unit in POSITIVE_FIELDS:
            put(name, check_positive(name, getattr(self, name), unit=unit, high=high))
        put("collision_noise", check_flag("collision_noise", self.collision_noise,
                                          " (use eq. 19's collision noise)"))
        if self.gate is not None:
            put("gate", check_positive("gate", self.gate, unit=" or None (fuse everything)"))
        if self.maneuver_radius is not None:
            put("maneuver_radius", check_positive("maneuver_radius", self.maneuver_radius,
                                                  unit=" [m] or None (no maneuvers)",
                                                  high=MAX_COORDINATE))
        if self.reset_after is not None:
            put("reset_after", check_count("reset_after", self.reset_after, 1,
                                           MAX_RESET_AFTER))
        if self.reset_after is not None and self.gate is None:
            raise ValueError("reset_after needs a gate: only gated-out detections trigger resets")
        if self.two_phase is not None:
            what = "(sliding deceleration >= 0 [m/s^2], 0 < k_switch < 1) or None"
            a_slide, k = check_reals("two_phase", self.two_phase, 2, what=what)
            if not (a_slide >= 0 and 0 < k < 1):
                raise ValueError(f"two_phase must be {what}, got {self.two_phase!r}")
            put("two_phase", (float(a_slide), float(k)))
        FrictionBallMotion(self.deceleration, self.propagation)  # validates both
        put("deceleration", float(self.deceleration))


#: The largest gain ``k`` of eq. 19 (Zhao et al. 2012: 10).
MAX_GAIN_K = 1e6

#: The fields of :class:`BallFilterConfig` that are finite numbers > 0, their upper bounds
#: (lengths within :data:`~estimators.checks.MAX_COORDINATE`, speeds within
#: :data:`~estimators.checks.MAX_SPEED`: their squares and eq. 19's products stay finite)
#: and their units.
POSITIVE_FIELDS = (("sigma_xy", MAX_COORDINATE, " [m]"), ("tau", MAX_COORDINATE, " [m, m/s]"),
                   ("sigma_r", MAX_SPEED, " [m/s]"), ("gain_k", MAX_GAIN_K, ""),
                   ("robot_radius", MAX_COORDINATE, " [m]"),
                   ("ball_radius", MAX_COORDINATE, " [m]"), ("kick_speed", MAX_SPEED, " [m/s]"),
                   ("history", math.inf, " [s]"), ("maneuver_speed", MAX_SPEED, " [m/s]"))

#: The most gated-out detections :attr:`BallFilterConfig.reset_after` may wait for (each
#: takes three columns of a track row).
MAX_RESET_AFTER = 1000


class BallTrack(NamedTuple):
    """The state of a :class:`BallTracker` after a frame: everything a replay must restore.

    The track itself is a row of :mod:`~estimators.kalman.ball_kernels` (``row``, never
    changed once the frame is processed, so snapshots need no copies); the times and the
    count the replay and the track quality read are fields, the rest properties.

    Attributes:
        t: capture time of the latest frame processed [s] (``-inf`` before the first).
        fused_at: capture time of the latest detection fused [s].
        since_start: detections fused since the track's latest (re)start (0: no track).
        row: the track row (see :mod:`~estimators.kalman.ball_kernels`).
    """

    t: float
    fused_at: float
    since_start: int
    row: np.ndarray

    @property
    def x(self) -> State | None:
        """The state ``(x, y, vx, vy)`` [m, m/s] at ``t`` (None before the first detection)."""
        return tuple(self.row[1:5].tolist()) if self.since_start else None

    @property
    def P(self) -> Blocks | None:
        """Its covariance as :data:`~estimators.kalman.blocks.Blocks` (None before the first
        detection)."""
        return blocks_from_row(self.row[5:17]) if self.since_start else None

    @property
    def v_switch(self) -> float:
        """The two-phase model's switch speed [m/s]: the ball slides while faster."""
        return float(self.row[17])

    @property
    def candidates(self) -> Candidates:
        """Gated-out detections that may start a new track
        (:class:`~estimators.tracking.TrackInitiator`)."""
        n = int(self.row[20])
        c = self.row[TRACK_WIDTH:TRACK_WIDTH + 3 * n].tolist()
        return tuple((c[3 * i], (c[3 * i + 1], c[3 * i + 2])) for i in range(n))


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
    :class:`~estimators.tracking.TrackInitiator` (``config.reset_after``). The frame is one
    call of the compiled :func:`~estimators.kalman.ball_kernels.ball_frame`, the kernel that
    :class:`~estimators.BallTrackerBatch` runs over many tracks: this tracker is a batch of
    one.

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
        gate = Gate(c.gate)
        initiator = (None if c.reset_after is None
                     else TrackInitiator(c.sigma_xy, c.reset_after))
        #: The kernels' parameters (:func:`~estimators.kalman.ball_kernels.ball_parameters`).
        self.parameters = ball_parameters(c, self.r, gate.kick_speed, initiator)
        #: Columns of a track row (:func:`~estimators.kalman.ball_kernels.track_width`).
        self.width = track_width(c)
        #: Seconds of frames kept to replay out-of-order arrivals (``config.history``).
        self.history = c.history
        self._counts = np.zeros(4, dtype=np.int64)
        self._real = np.ones(16, dtype=bool)  # "every row is real"
        self._no_robots = np.zeros((0, 2))
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new episode)."""
        self._track = self.empty_track()
        self.reset_replay()
        self._counts[:] = 0

    def empty_track(self) -> BallTrack:
        """The track before the first frame."""
        row = np.zeros(self.width)
        row[0] = row[18] = -math.inf
        return BallTrack(-math.inf, -math.inf, 0, row)

    @property
    def track(self) -> BallTrack:
        """The current track (read only)."""
        return self._track

    fused = property(lambda self: int(self._counts[FUSED]), doc="Detections fused.")
    rejected = property(lambda self: int(self._counts[REJECTED]), doc="Detections gated out.")
    resets = property(lambda self: int(self._counts[RESETS]), doc="Track restarts.")
    maneuvers = property(lambda self: int(self._counts[MANEUVERS]), doc="Maneuvers taken.")

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

    def update_frame(self, t: float, detections: Sequence[Sequence[float]],
                     obstacles: Sequence[Sequence[float]] = ()) -> None:
        """:meth:`ReplayBuffer.update_frame <estimators.tracking.ReplayBuffer.update_frame>`
        with the detections and robots as arrays
        (:func:`~estimators.kalman.ball_kernels.as_points`), converted once for the frame and
        its replays."""
        # Without eq. 19's collision noise the robots are not read.
        obs = as_points(obstacles) if self.config.collision_noise else self._no_robots
        ReplayBuffer.update_frame(self, float(t), as_points(detections), obs)

    def estimate(self, t: float) -> np.ndarray | None:
        """State ``(x, y, vx, vy)`` predicted to time ``t`` (None before the first frame)."""
        t = check_time(t)
        tr = self._track
        if not tr.since_start:
            return None
        out = np.empty(4)
        ball_estimate(tr.row, t, out, self.parameters)
        return out

    def estimate_with_covariance(self, t: float) -> tuple[np.ndarray, np.ndarray] | None:
        """``(x, P)`` predicted to time ``t`` without changing the tracker."""
        t = check_time(t)
        if not self._track.since_start:
            return None
        return self._predicted(t)

    def _covariance(self, t: float) -> np.ndarray:
        return self._predicted(t)[1]

    def _predicted(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """``(x, P)`` of a started track predicted to ``t`` (no process noise for eq. 19's
        robots: ``sigma_r``)."""
        x, P = np.empty(4), np.empty((4, 4))
        ball_predicted(self._track.row, t, x, P, self.parameters)
        return x, P

    def velocity_sigma(self, position, obstacles=None) -> float:
        """The velocity noise ``sigma_v`` [m/s per paper cycle] of eq. 19 for a ball at
        ``position`` ``(x, y)`` [m] with robots at ``obstacles`` (``(j, 2)``, or poses whose
        first two entries are the position; None: no robots): ``sigma_r``, raised near a robot
        when ``collision_noise`` is on (what :meth:`update` uses between two frames;
        :func:`~estimators.kalman.ball_kernels.collision_sigma`)."""
        obs = as_points(check_points("obstacles", obstacles, exact=False)
                        if obstacles is not None else [])
        return collision_sigma(float(position[0]), float(position[1]), obs,
                               self._mask(len(obs)), self.parameters)

    def _mask(self, n: int) -> np.ndarray:
        """At least ``n`` True flags (the rows of a single frame are all real; the kernels
        read as many as there are rows)."""
        if n > len(self._real):
            self._real = np.ones(2 * n, dtype=bool)
        return self._real

    # ------------------------------------------------------------------------------------
    # The update

    def process(self, track: BallTrack, t: float, detections: np.ndarray,
                obstacles: np.ndarray) -> BallTrack:
        """The track after one frame captured at ``t`` [s], no earlier than ``track.t``, with
        ball detections ``(k, 2)`` and robots ``(j, 2+)`` as
        :func:`~estimators.kalman.ball_kernels.as_points` gives them: predict, gate, then fuse
        the nearest detection, or take it as a maneuver, or offer it to the initiator
        (:func:`~estimators.kalman.ball_kernels.ball_frame`). The counters are updated;
        ``track`` is not changed. What :meth:`update_frame` replays."""
        row = np.empty(self.width)
        t, fused_at, since = ball_frame(track.row, row, self._counts, t, detections,
                                        self._mask(len(detections)), obstacles,
                                        self._mask(len(obstacles)), self.parameters)
        return BallTrack(t, fused_at, since, row)
