"""The perception of SSL teams, fed by the overhead vision (or, with ``detector="pixels"``, by
the trackers on its rendered images):

* :class:`TruthPerception` (``obs_mode="truth"``): the oracle, the true state itself;
* :class:`RawPerception` (``"raw"``): the latest delayed detections, unfiltered;
* :class:`FilteredPerception` (``"perceived"``): the ball filter chosen by ``ball_filter``
  (Zhao et al.'s 2012 EKF by default) and batched robot pose filters, fed with the frames by capture
  time and predicted to the present plus the actuation latency (with
  ``robot_prediction="commands"`` the team's own robots through the commands it sent).

:func:`make_perception` builds the pipeline of an observation mode.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from estimators import CommandHistory, RobotTracker
from soccer_env.perception.base import (
    OBS_MODES,
    SSL_LOST_AFTER,
    Perception,
    PerceptionConfig,
    ball_status,
    expected_age,
    sigmas,
)
from soccer_env.perception.options import BALL_FILTERS, DETECTORS
from soccer_env.presets import BallSpec, FieldSpec, SSLRobotSpec
from soccer_env.sensors.overhead import DetectionFrame
from soccer_env.state import Belief, BeliefQuality, BeliefSpread, WorldState

__all__ = ["TruthPerception", "VisionPerception", "RawPerception", "FilteredPerception",
           "make_perception"]


class TruthPerception:
    """The oracle of ``obs_mode="truth"``: the belief is the true state itself."""

    def __init__(self, config: PerceptionConfig) -> None:
        self.vision_spec = config.vision

    def reset(self, state: WorldState, rng: np.random.Generator):
        return state, state

    def update(self, state: WorldState):
        return state, state


class VisionPerception:
    """What the pipelines fed by the overhead vision share (the base of
    :class:`RawPerception` and :class:`FilteredPerception`): the sensor and its detector as
    the ``detector`` option builds them, the frames of each reset and update (taken from
    another team's pipeline instead when :attr:`frames_from` is set), and the step that feeds
    them to the estimation.

    A subclass supplies ``_clear`` (forget the episode), :meth:`consume` (take a step's
    frames) and :meth:`beliefs` (the beliefs at a time).
    """

    def __init__(self, config: PerceptionConfig, field: FieldSpec, robot: SSLRobotSpec,
                 ball: BallSpec, n_robots: int, teams: Sequence[int] | None = None,
                 robots: Sequence[Any] | None = None) -> None:
        self.config = config
        self.vision_spec = config.vision
        #: The overhead sensor, and what turns its frames into detection frames (None: they
        #: are detections already), as the detector option builds them.
        self.sensor, self.detector = DETECTORS[config.detector].overhead(
            config.vision, field, robot, robots or [robot] * n_robots, ball,
            teams if teams is not None else [0] * n_robots)
        #: The detections' measurement models (the filters weigh them with these).
        self.measurements = self.detector if self.detector is not None else self.sensor
        self.n_robots = n_robots
        #: Another team's pipeline whose camera frames this one takes instead of its own
        #: sensor's (:class:`~soccer_env.perception.match.MatchPerception` sets it for two SSL
        #: teams on the same vision; that pipeline is reset and updated first).
        self.frames_from: VisionPerception | None = None
        #: The frames of the latest reset or update.
        self.last_frames: list[DetectionFrame] = []
        #: Whether the beliefs carry their :class:`~soccer_env.state.BeliefQuality` (the
        #: environments' ``belief_features``).
        self.features = False
        v = config.vision
        self._expected_age = expected_age(v.frame_rate, v.latency, v.latency_jitter)

    def reset(self, state: WorldState, rng: np.random.Generator):
        """Start an episode at ``state``: the sensor's warm-up frames consumed; returns
        :meth:`beliefs` at its time."""
        self._clear()
        if self.frames_from is not None:
            frames = self.frames_from.last_frames
        elif self.detector is None:
            frames = self.sensor.reset(state, rng)
        else:
            # The images' lighting and noise, then the trackers, draw from streams seeded in
            # this order from the episode's sensor stream.
            image_rng = np.random.default_rng(rng.integers(2**63))
            self.detector.reset(state, np.random.default_rng(rng.integers(2**63)))
            frames = self.detector.detections(self.sensor.reset(state, rng, image_rng))
        self.last_frames = frames
        self.consume(frames, state.time)
        return self.beliefs(state.time)

    def update(self, state: WorldState):
        """Advance to ``state``: the frames delivered by its time consumed; returns
        :meth:`beliefs` at its time."""
        if self.frames_from is not None:
            frames = self.frames_from.last_frames
        else:
            frames = self.sensor.step(state)
            if self.detector is not None:
                frames = self.detector.detections(frames)
        self.last_frames = frames
        self.consume(frames, state.time)
        return self.beliefs(state.time)

    def restart(self, now: float) -> None:
        """Forget the episode and start afresh at ``now`` [s] with no frames: for frames that
        come from elsewhere through :meth:`consume` (a live team's SSL-Vision,
        :mod:`agents.live`) instead of this pipeline's sensor."""
        self._clear()
        self.last_frames = []

    def _clear(self) -> None:
        raise NotImplementedError

    def consume(self, frames: list[DetectionFrame], now: float) -> None:
        """The estimation of one step: take the detection frames delivered by ``now``."""
        raise NotImplementedError

    def beliefs(self, now: float):
        """``(belief for the observation, belief now)`` at ``now``."""
        raise NotImplementedError


class RawPerception(VisionPerception):
    """``obs_mode="raw"``: the latest delayed detections, no filtering.

    The ball is its most recent detection (of several in a frame, the one nearest the previous
    raw ball); a robot is its most recent detection. Velocities are the differences of the last
    two sightings at least half a frame period apart (overlapping cameras see an object a
    fraction of a millisecond apart; differencing those would turn centimetres of noise into
    metres per second). Objects never seen read as zeros.
    """

    def _clear(self) -> None:
        rate = self.vision_spec.frame_rate
        self._min_gap = 0.0 if rate is None else 0.5 / rate
        n = self.n_robots
        self._ball = [None, None]  # last two (t, x, y)
        self._robots = [[None, None] for _ in range(n)]

    def consume(self, frames: list[DetectionFrame], now: float) -> None:
        for f in sorted(frames, key=lambda f: f.t_capture):
            t = f.t_capture
            if f.balls:
                last = self._ball[1]
                bx, by = _nearest(f.balls, None if last is None else last[1:3])
                _push(self._ball, (t, bx, by), self._min_gap)
            for i, pose in zip(f.robot_ids, f.robots):
                _push(self._robots[i], (t, *pose), self._min_gap)

    def beliefs(self, now: float):
        ball = np.zeros(6)
        ball[0:2], ball[3:5] = _last_and_rate(self._ball, 2)
        robots = np.zeros((self.n_robots, 6))
        for i, hist in enumerate(self._robots):
            pose, rate = _last_and_rate(hist, 3)
            robots[i, 0:3], robots[i, 3:6] = pose, rate
        belief = Belief(now, ball, robots, self._quality(now) if self.features else None)
        return belief, belief

    def _quality(self, now: float) -> BeliefQuality:
        """The raw belief's quality: the sensor's noise on the latest sighting, the
        difference velocity's ``sqrt(2) sigma / gap`` (unknown from one sighting)."""
        v = self.vision_spec
        prev, last = self._ball
        age = math.inf if last is None else now - last[0]
        sigma = math.inf if last is None else v.ball_sigma
        sigma_v = (math.inf if prev is None else
                   math.sqrt(2.0) * v.ball_sigma / (last[0] - prev[0]))
        status = ball_status(age, self._expected_age, 3 if prev is not None else 1,
                             SSL_LOST_AFTER)
        known = [(v.robot_sigma, v.robot_sigma_theta) if h[1] is not None
                 else (math.inf, math.inf) for h in self._robots]
        return BeliefQuality(sigma, sigma_v, age, status,
                             np.array(known, dtype=np.float64).reshape(-1, 2), age,
                             0 if last is None else 1,
                             None if last is None else np.array(last[1:3]))


    def spread(self, t: float) -> BeliefSpread:
        """How the raw belief is spread, for drawing (reads, never changes, the pipeline):
        the sensor's noise on the latest sighting. The vision's noise is one standard
        deviation per axis, so the covariances are ``sigma^2 I`` (circles): ``ball_sigma``
        for the ball, ``robot_sigma`` for every robot seen; None for a ball never seen, NaN
        for robots never seen. ``t`` [s] is accepted for the pipelines' common signature
        (a raw sighting does not grow with time)."""
        v = self.vision_spec
        ball = None if self._ball[1] is None else circle_covariance(v.ball_sigma)
        robots = np.full((self.n_robots, 2, 2), np.nan)
        for i, hist in enumerate(self._robots):
            if hist[1] is not None:
                robots[i] = circle_covariance(v.robot_sigma)
        return BeliefSpread(ball, robots)


def circle_covariance(sigma: float) -> np.ndarray:
    """``sigma^2 I``, the ``2 x 2`` covariance of a position known to ``sigma`` [m] per axis
    (NaN for an infinite ``sigma``: unknown)."""
    if not math.isfinite(sigma):
        return np.full((2, 2), np.nan)
    return np.array([[sigma * sigma, 0.0], [0.0, sigma * sigma]])


def _push(hist: list, item: tuple, min_gap: float) -> None:
    """Keep the last two sightings, newest last, captured at least ``min_gap`` [s] apart."""
    last = hist[1]
    if last is not None and (item[0] <= last[0] or item[0] < last[0] + min_gap):
        if item[0] >= last[0]:
            hist[1] = item  # the same moment seen by another camera: keep the later report
        return
    hist[0], hist[1] = hist[1], item


def _last_and_rate(hist: list, dims: int) -> tuple[list, list]:
    prev, last = hist
    if last is None:
        return [0.0] * dims, [0.0] * dims
    if prev is None:
        return list(last[1:]), [0.0] * dims
    dt = last[0] - prev[0]
    rate = [(a - b) / dt for a, b in zip(last[1:], prev[1:])]
    if dims == 3:
        rate[2] = math.remainder(last[3] - prev[3], 2.0 * math.pi) / dt
    return list(last[1:]), rate


class FilteredPerception(VisionPerception):
    """``obs_mode="perceived"``: batched robot pose filters and a ball tracker.

    Frames are processed in capture-time order: the robots first (their detections in the same
    frame give the ball filter's eq. 19 its nearest-robot distance), then the ball. The belief
    for the observation is predicted to ``now + actuation_latency``.
    """

    def __init__(self, config: PerceptionConfig, field: FieldSpec, robot: SSLRobotSpec,
                 ball: BallSpec, n_robots: int, teams: Sequence[int] | None = None,
                 robots: Sequence[Any] | None = None) -> None:
        super().__init__(config, field, robot, ball, n_robots, teams, robots)
        spec = config.vision
        # The filters weigh detections with the sensor's own measurement models.
        self.robot_tracker = RobotTracker(n_robots, measurement=self.measurements.robot_model)
        built = BALL_FILTERS.create(config.ball_filter, ball, spec, self.measurements.ball_model)
        self.ball_tracker, self._capture_times = built.tracker, built.capture_times
        #: The ball filter's motion modes, whose probabilities the belief's quality carries
        #: (an interacting multiple model filter's; empty for a filter without modes).
        self.ball_modes: tuple[str, ...] = tuple(getattr(self.ball_tracker, "MODES", ()))
        # The frames are the sensor's own, checked data: a tracker with an unchecked path
        # (BallTracker.update_frame) is fed through it.
        self._feed = getattr(self.ball_tracker, "update_frame", self.ball_tracker.update)
        self.ahead = spec.actuation_latency
        #: The team's recent commands, with ``robot_prediction="commands"`` (set by
        #: :meth:`drive_own`); None: every robot at constant velocity.
        self.history: CommandHistory | None = None

    def drive_own(self, robots: Sequence[int], robot: SSLRobotSpec, control_dt: float
                  ) -> None:
        """Predict ``robots`` (the team's own, of model ``robot``) through the commands the
        team sends (:meth:`command`, one per control step of ``control_dt`` [s]) instead of
        at constant velocity (see :mod:`estimators.kalman.driven`). The history keeps enough
        commands to span the vision's delay, the prediction's lead and three frames."""
        v = self.vision_spec
        frame = control_dt if v.frame_rate is None else 1.0 / v.frame_rate
        span = v.latency + v.latency_jitter + self.ahead + 3.0 * frame
        self.history = CommandHistory(
            robots, control_dt, math.ceil(span / control_dt) + 2,
            (robot.max_speed, robot.max_acceleration, robot.max_angular_speed,
             robot.max_angular_acceleration))

    def command(self, start: float, commands: np.ndarray) -> None:
        """Record the team's physical commands ``(r, 6)`` (body-frame ``vx, vy, omega``
        first) that take effect at ``start`` [s] (nothing without :meth:`drive_own`)."""
        if self.history is not None:
            self.history.record(start, commands)

    def reset(self, state: WorldState, rng: np.random.Generator):
        if self.history is not None:  # the robots stand still until the first command
            self.history.reset(state.time)
        return super().reset(state, rng)

    def restart(self, now: float) -> None:
        if self.history is not None:
            self.history.reset(now)
        super().restart(now)

    def _clear(self) -> None:
        self.robot_tracker.reset()
        self.ball_tracker.reset()
        self._measured: np.ndarray | None = None  # the latest ball detection fed (x, y)

    def consume(self, frames: list[DetectionFrame], now: float) -> None:
        if not frames:
            return
        ball = self.ball_tracker
        if len(frames) > 1:
            frames = sorted(frames, key=lambda f: f.t_capture)
        self._update_robots(frames)
        for f in frames:
            t = f.t_capture
            if f.balls:
                # Without latency compensation a pipeline stamps frames when they arrive.
                stamp = t if self._capture_times else f.t_delivered
                self._feed(stamp, f.balls, f.robots)
                if self.features:  # of several detections, the one nearest the belief
                    self._measured = np.array(_nearest(f.balls, ball.estimate(stamp)))

    def _update_robots(self, frames: list[DetectionFrame]) -> None:
        """Fuse the robot detections of ``frames`` (in capture order). The robots' filters and
        the ball's are independent (the ball's takes a frame's robot detections, not the
        robots' estimates), so every robot detection of a step's frames goes in one kernel
        call: the same updates in the same order as frame by frame."""
        robots = self.robot_tracker
        if len(frames) == 1 and len(frames[0].robot_ids) <= 1:  # a keeper's step: no arrays
            f = frames[0]
            if f.robot_ids:
                robots.update_robot(f.t_capture, f.robots[0], f.robot_ids[0])
            return
        ids = [i for f in frames for i in f.robot_ids]
        if ids:
            robots.update_many([f.t_capture for f in frames for _ in f.robot_ids], ids,
                               [p for f in frames for p in f.robots])

    def beliefs(self, now: float):
        current = self._belief(now)
        seen = self._belief(now + self.ahead) if self.ahead else current
        if self.features:
            seen = seen._replace(quality=self._quality(seen.time, now))
        return seen, current

    def _belief(self, t: float) -> Belief:
        est = self.ball_tracker.estimate(t)
        ball = np.zeros(6) if est is None else np.array((est[0], est[1], 0.0, est[2], est[3],
                                                         0.0))
        tracker, history = self.robot_tracker, self.history
        robots = (tracker.estimate(t) if history is None
                  else tracker.estimate_driven(t, history))
        return Belief(t, ball, robots)

    def spread(self, t: float) -> BeliefSpread:
        """How the belief at ``t`` [s] is spread, for drawing (reads, never changes, the
        filters): the ball filter's covariance of ``(x, y)`` predicted to ``t`` (None before
        its first detection); for each robot ``sigma^2 I`` (a circle) with ``sigma`` the
        position standard deviation of :meth:`~estimators.RobotTracker.pose_sigma` predicted
        to ``t``: the robot filters run one per axis with the same noise, so the two axes'
        spreads are alike and uncorrelated (NaN for robots never seen)."""
        cov = self.ball_tracker.covariance(t)
        ball = None if cov is None else np.array(cov[0:2, 0:2], dtype=np.float64)
        robots = self.robot_tracker
        covs = np.array([circle_covariance(robots.pose_sigma(i, t)[0])
                         for i in range(self.n_robots)]).reshape(-1, 2, 2)
        return BeliefSpread(ball, covs)

    def _quality(self, t: float, now: float) -> BeliefQuality:
        """The filters' quality of the belief at ``t`` (ages at ``now``): the ball filter's
        covariance and track state, the robot filters' pose spreads."""
        ball = self.ball_tracker
        sigma, sigma_v = sigmas(ball.covariance(t))
        age = now - ball.last_fused
        status = ball_status(age, self._expected_age, ball.since_start, SSL_LOST_AFTER)
        robots = self.robot_tracker
        spread = np.array([robots.pose_sigma(i, t) for i in range(self.n_robots)],
                          dtype=np.float64).reshape(-1, 2)
        modes = ball.mode_probabilities(t) if self.ball_modes else None
        return BeliefQuality(sigma, sigma_v, age, status, spread, age,
                             int(status < 3 and age <= self._expected_age), self._measured,
                             modes)


def _nearest(balls: Sequence[Sequence[float]], est: Sequence[float] | None
             ) -> tuple[float, float]:
    """The ``(x, y)`` of the detection in ``balls`` nearest the point ``est`` (the first
    without one)."""
    if est is None or len(balls) == 1:
        return float(balls[0][0]), float(balls[0][1])
    b = min(balls, key=lambda b: (b[0] - est[0]) ** 2 + (b[1] - est[1]) ** 2)
    return float(b[0]), float(b[1])


def make_perception(obs_mode: str, config: PerceptionConfig, field: FieldSpec,
                    robot: SSLRobotSpec, ball: BallSpec, n_robots: int,
                    actuation_delay: float | None = None, teams: Sequence[int] | None = None,
                    robots: Sequence[Any] | None = None, features: bool = False
                    ) -> Perception:
    """The overhead-vision pipeline of ``obs_mode`` for SSL robots (humanoids:
    :class:`MatchPerception`); unknown modes raise ``ValueError``.

    ``actuation_delay`` [s] is how far ahead the perceived belief is predicted (default: the
    vision preset's actuation latency; environments pass the latency as they apply it, in
    whole control steps). ``teams`` and ``robots`` (every robot's team and spec) are what the
    ``pixels`` detector draws. With ``features`` the observation's belief carries its
    :class:`~soccer_env.state.BeliefQuality`.
    """
    if obs_mode == "truth":
        return TruthPerception(config)
    if obs_mode == "raw":
        p: VisionPerception = RawPerception(config, field, robot, ball, n_robots, teams,
                                             robots)
    elif obs_mode == "perceived":
        p = FilteredPerception(config, field, robot, ball, n_robots, teams, robots)
        if actuation_delay is not None:
            p.ahead = float(actuation_delay)
    else:
        raise ValueError(f"obs_mode must be one of {list(OBS_MODES)}, got {obs_mode!r}")
    p.features = features
    return p


