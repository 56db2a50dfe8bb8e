"""The option families of perception, one registry each: a name, what builds the option, and a
one-line description (what ``soccer-env list``, the ablation and the error messages read).

* :data:`BALL_FILTERS` (SSL teams, ``ball_filter=``): name -> ``factory(ball, vision,
  measurement) -> BallFilter`` (the tracker and whether it is fed capture times);
* :data:`BALL_TRACKERS` (humanoids, ``ball_tracker=``): ``"none"``, one of the estimators'
  :data:`~estimators.PARTICLE_FILTERS` or ``"kick"`` (:class:`~estimators.LineBallTracker`),
  name -> ``factory(rng, ball, max_speed, noise, observers)`` (None for ``"none"``);
* :data:`FUSIONS` (humanoids, ``fusion=``): the robot's own sighting, or Hough-space fusion with
  one of the estimators' :data:`~estimators.FUSION_WEIGHTINGS` or the inverse variance of each
  line's offset; name -> the weighting of :func:`~estimators.fuse_sightings`;
* :data:`LOCALIZATIONS` (humanoids, ``localization=``): name -> ``factory(bounds, rng, config,
  pose)`` of the localization filter, or None for dead reckoning and the oracle, which the
  robot's :class:`~soccer_env.perception.brain.Brain` keeps itself;
* :data:`ROBOT_PREDICTIONS` (SSL teams, ``robot_prediction=``): how the team's own robots are
  predicted to when its commands take effect;
* :data:`DETECTORS` (``detector=``): name -> :class:`Detector`, the factories of the overhead
  sensor (and its detector), the head-camera sensor and a robot's ball finder.

A new option is one ``register`` call on its family.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from estimators import (
    FUSION_WEIGHTINGS,
    INVERSE_VARIANCE,
    MIN_SIGMA_XY,
    PARTICLE_FILTERS,
    BallFilterConfig,
    BallTracker,
    IMMBall,
    KickAwareBall,
    KLDConfig,
    KLDLocalizer,
    LeastSquaresBall,
    LineBallTracker,
    ParticleBallTracker,
    PositionMeasurement,
    SightingNoise,
)
from estimators.registry import Registry
from soccer_env.presets import BallSpec, FieldSpec, HeadCameraSpec, RobotSpec, VisionSpec
from soccer_env.sensors.headcam import HeadCameraSensor
from soccer_env.sensors.overhead import OverheadVision

__all__ = ["BallFilter", "BALL_FILTERS", "ROBOT_PREDICTIONS", "BALL_TRACKERS", "FUSIONS",
           "LOCALIZATIONS", "Detector", "DETECTORS", "PARTICLES", "line_tracker"]


# --------------------------------------------------------------------------------------------
# Ball filters of SSL teams
# --------------------------------------------------------------------------------------------


class BallFilter(NamedTuple):
    """A built ball filter: the tracker (``update(t, detections, robots)``,
    ``estimate(t)``) and whether it is fed capture times (latency compensation) rather than
    arrival times."""

    tracker: Any
    capture_times: bool


def _sigma(vision: VisionSpec) -> float:
    """The measurement noise the filters assume: the sensor's, at least 1 mm."""
    return max(vision.ball_sigma, MIN_SIGMA_XY)


def _kalman(compensated: bool, ball: BallSpec, vision: VisionSpec,
            measurement: PositionMeasurement) -> BallFilter:
    """The constant-velocity Kalman filter: no friction, no collision noise, no gating."""
    cfg = BallFilterConfig(deceleration=0.0, sigma_xy=_sigma(vision), collision_noise=False,
                           gate=None, reset_after=None)
    return BallFilter(BallTracker(cfg, measurement), compensated)


def _ekf(propagation: str, two_phase: bool, ball: BallSpec, vision: VisionSpec,
         measurement: PositionMeasurement) -> BallFilter:
    """Zhao et al.'s (2012) friction EKF with the ball's rolling deceleration (and, with
    ``two_phase``, its sliding phase after kicks); its other parameters are the paper's."""
    cfg = BallFilterConfig(deceleration=ball.rolling_deceleration, propagation=propagation,
                           sigma_xy=_sigma(vision),
                           two_phase=((ball.sliding_deceleration, ball.k_switch) if two_phase
                                      else None))
    return BallFilter(BallTracker(cfg, measurement), True)


def _least_squares(ball: BallSpec, vision: VisionSpec, measurement: PositionMeasurement
                   ) -> BallFilter:
    return BallFilter(LeastSquaresBall(sigma_xy=_sigma(vision)), True)


def _kick_aware(ball: BallSpec, vision: VisionSpec, measurement: PositionMeasurement
                ) -> BallFilter:
    """The kick-aware tracker with the ball's two-phase friction model."""
    return BallFilter(KickAwareBall(ball.sliding_deceleration, ball.rolling_deceleration,
                                    ball.k_switch, sigma_xy=_sigma(vision)), True)


def _imm(ball: BallSpec, vision: VisionSpec, measurement: PositionMeasurement) -> BallFilter:
    """The interacting multiple model tracker with the ball's two-phase friction model."""
    return BallFilter(IMMBall(ball.rolling_deceleration, ball.sliding_deceleration,
                              ball.k_switch, sigma_xy=_sigma(vision)), True)


#: Ball filters of ``obs_mode="perceived"`` for SSL teams.
BALL_FILTERS: Registry[Callable[..., BallFilter]] = Registry("ball filter", [
    ("kf", functools.partial(_kalman, False),
     "constant-velocity Kalman filter fed arrival times (no latency compensation), no gating"),
    ("kf-comp", functools.partial(_kalman, True), "the same with latency compensation"),
    ("ekf", functools.partial(_ekf, "jacobian", False),
     "Zhao et al.'s (2012) friction EKF (analytic Jacobian), latency compensation, eq. 19 "
     "collision-aware noise, gating and reset on kicks (default)"),
    ("ekf-improved", functools.partial(_ekf, "rk", False),
     "Zhao et al.'s (2012) improved EKF (Runge-Kutta propagation, F = M), otherwise as 'ekf'"),
    ("ekf-2phase", functools.partial(_ekf, "jacobian", True),
     "'ekf' with the two-phase sliding/rolling model after detected kicks"),
    ("ls", _least_squares,
     "Zhao et al.'s (2012) least-squares predictor (line fit to the last 6 detections)"),
    ("kick", _kick_aware,
     "kick-aware: each motion since a kick or collision fitted whole to the two-phase friction "
     "model, started at the kick point and time"),
    ("imm", _imm,
     "interacting multiple model: rest, rolling (two-phase friction) and maneuver Kalman "
     "filters mixed by their likelihoods; latency compensation, gating, restarts"),
])


#: How an SSL team's pipeline predicts its own robots to the time its commands take effect
#: (``robot_prediction=``); the value says whether the team's commands are read.
ROBOT_PREDICTIONS: Registry[bool] = Registry("robot prediction", [
    ("constant-velocity", False,
     "every robot at the constant velocity its pose filter estimates (default)"),
    ("commands", True,
     "the team's own robots driven through the commands it sent since their latest "
     "detection (a Smith predictor, estimators.CommandHistory); others at constant velocity"),
])


# --------------------------------------------------------------------------------------------
# Humanoid teams: ball trackers, fusion, localization
# --------------------------------------------------------------------------------------------

#: Particles of a humanoid's ball tracker (Xu et al. 2012: 100).
PARTICLES = 100


def _particle_tracker(name: str, rng: np.random.Generator, ball: BallSpec,
                      max_speed: float, noise: SightingNoise, observers: tuple[int, ...]
                      ) -> ParticleBallTracker:
    """A humanoid's ball tracker on the particle filter ``name`` (see
    :class:`~estimators.ParticleBallTracker`): 1 m/s^2 of acceleration noise, the ball's
    rolling deceleration, restarted after 2 s without a fused sighting or after two
    implausible ones in a row (``noise`` and ``observers`` are the fusion's business, not the
    tracker's)."""
    return ParticleBallTracker(rng, filter=name, n_particles=PARTICLES, accel_sigma=1.0,
                               deceleration=ball.rolling_deceleration, lost_after=2.0,
                               max_speed=max_speed,
                               reinit_after=2)


def line_tracker(rng: np.random.Generator, ball: BallSpec, max_speed: float,
                 noise: SightingNoise, observers: tuple[int, ...], *,
                 cls: type[LineBallTracker] = LineBallTracker, **overrides: Any
                 ) -> LineBallTracker:
    """The ``"kick"`` tracker: the kick-aware tracker of the sighting lines of the robots
    ``observers`` (indices) (:class:`~estimators.LineBallTracker`) with the ball's two-phase
    friction law, 1 m/s^2 of acceleration noise (as the particle trackers) and kicks of 3 m/s
    per axis, restarted after 2 s without an agreeing line; it draws nothing. ``cls`` and
    ``overrides`` (keyword arguments of the tracker) build variants for ablations."""
    kwargs: dict[str, Any] = dict(
        deceleration=ball.rolling_deceleration, sliding_deceleration=ball.sliding_deceleration,
        k_switch=ball.k_switch, accel_sigma=1.0, kick_sigma=3.0, lost_after=2.0,
        observers=observers)
    return cls(noise, **{**kwargs, **overrides})


#: A humanoid's ball trackers, ``factory(rng, ball, max_speed, noise, observers)`` with the
#: ball's :class:`~soccer_env.presets.BallSpec`, the team's sighting error model
#: (:class:`~estimators.SightingNoise`) and the robots (indices) whose sightings it may get:
#: none; one per particle filter of the estimators, fed the fused sightings; or the
#: kick-aware tracker fed each line.
BALL_TRACKERS: Registry[Callable[..., Any] | None] = Registry(
    "ball tracker",
    [("none", None, "no tracking: the latest fused point, velocity from the last two")]
    + [(name, functools.partial(_particle_tracker, name),
        f"{PARTICLE_FILTERS.description(name)}; {PARTICLES} particles")
       for name in PARTICLE_FILTERS]
    + [("kick", line_tracker,
        "kick-aware Kalman tracker fed each sighting line at its capture time (no fusion "
        "step); a kick hypothesis beside the track, its kick time searched")])

#: Ball fusion: the robot's own sighting only, or Xu et al.'s (2012) Hough-space fusion of the
#: team's sightings with one of the estimators' weightings (the value: the weighting
#: :func:`~estimators.fuse_sightings` applies; a lone own line is weighted as ``"inverse"``).
FUSIONS: Registry[str] = Registry(
    "fusion",
    [("own", "inverse", "the robot's own sighting only")]
    + [(name, name, f"Hough-space fusion of the team's sightings, "
                    f"{FUSION_WEIGHTINGS.description(name)}")
       for name in FUSION_WEIGHTINGS]
    + [(INVERSE_VARIANCE, INVERSE_VARIANCE,
        "Hough-space fusion of the team's sightings, each line weighted by the inverse "
        "variance of its offset at the ball (the camera's bearing noise and the observers' "
        "localization error)")])


def _kld(recovery: str, bounds: tuple[float, float, float, float], rng: np.random.Generator,
         config: KLDConfig, pose: np.ndarray) -> KLDLocalizer:
    """Guo and Li's (2013) KLD-sampling localization started at the known pose (5 cm, 0.05 rad),
    its recovery drawing particles as ``recovery`` says (one of
    :data:`~estimators.RECOVERIES`)."""
    return KLDLocalizer(bounds, rng, config, pose=pose, pose_sigma=(0.05, 0.05, 0.05),
                        recovery=recovery)


#: Self-localization of a humanoid: a filter's factory, or None where the robot keeps its pose
#: itself (dead reckoning, the oracle).
LOCALIZATIONS: Registry[Callable[..., KLDLocalizer] | None] = Registry("localization", [
    ("kld", functools.partial(_kld, "uniform"),
     "Guo and Li's (2013) KLD-sampling particle filter on odometry and landmark sightings"),
    ("kld-triangulate", functools.partial(_kld, "triangulate"),
     "the default: 'kld' whose recovery draws half of its new particles around poses "
     "triangulated from the last 25 frames' landmarks (Xu et al. 2012) instead of all uniformly"),
    ("odometry", None, "dead reckoning from the known start pose (no landmarks)"),
    ("truth", None, "the true pose (oracle, for ablations)"),
])


# --------------------------------------------------------------------------------------------
# Detectors
# --------------------------------------------------------------------------------------------


class Detector(NamedTuple):
    """Where detections come from, as factories:

    * ``overhead(vision, field, robot, robots, ball, teams) -> (sensor, detector)``: an SSL
      team's overhead sensor and what turns its frames into detection frames (None: they are
      detections already);
    * ``head(camera, field, ball, robots, teams, observers) -> sensor``: the humanoids' head
      cameras;
    * ``ball_finder(camera, ball)``: what finds the ball in a humanoid's frame images (None:
      the frames carry ball detections).
    """

    overhead: Callable[..., tuple[Any, Any]]
    head: Callable[..., Any]
    ball_finder: Callable[..., Any] | None


def _geometric_overhead(vision: VisionSpec, field: FieldSpec, robot: RobotSpec,
                        robots: Sequence[RobotSpec], ball: BallSpec, teams: Sequence[int]
                        ) -> tuple[OverheadVision, None]:
    return OverheadVision(vision, field, robot, ball, len(robots), robots=robots), None


def _geometric_head(camera: HeadCameraSpec, field: FieldSpec, ball: BallSpec,
                    robots: Sequence[RobotSpec], teams: Sequence[int],
                    observers: Sequence[int]) -> HeadCameraSensor:
    return HeadCameraSensor(camera, field, ball, [s.radius for s in robots], teams, observers)


#: Why the pixels detector cannot be built without OpenCV.
_NEEDS_OPENCV = "detector='pixels' needs OpenCV; install it with: pip install 'soccer-env[pixels]'"


def _pixels_overhead(vision: VisionSpec, field: FieldSpec, robot: RobotSpec,
                     robots: Sequence[RobotSpec], ball: BallSpec, teams: Sequence[int]
                     ) -> tuple[Any, Any]:
    try:
        from soccer_env.perception.pixels import OverheadPixelDetector
        from soccer_env.sensors.images.cameras import OverheadImageCamera
    except ImportError as err:  # pragma: no cover - depends on the installation
        raise ImportError(_NEEDS_OPENCV) from err
    camera = OverheadImageCamera(vision, field, robots, ball, teams)
    return camera, OverheadPixelDetector(camera, vision)


def _pixels_head(camera: HeadCameraSpec, field: FieldSpec, ball: BallSpec,
                 robots: Sequence[RobotSpec], teams: Sequence[int],
                 observers: Sequence[int]) -> Any:
    try:
        from soccer_env.sensors.images.cameras import PixelHeadCamera
    except ImportError as err:  # pragma: no cover - depends on the installation
        raise ImportError(_NEEDS_OPENCV) from err
    return PixelHeadCamera(camera, field, ball, robots, teams, observers)


def _pixels_ball_finder(camera: HeadCameraSpec, ball: BallSpec) -> Any:
    from soccer_env.perception.pixels import BallImageTracker

    return BallImageTracker(camera, ball)


#: Where detections come from: the sensor models, or image trackers on rendered frames.
DETECTORS: Registry[Detector] = Registry("detector", [
    ("geometric", Detector(_geometric_overhead, _geometric_head, None),
     "the sensor model's noisy detections"),
    ("pixels", Detector(_pixels_overhead, _pixels_head, _pixels_ball_finder),
     "rendered camera images tracked by Li et al.'s (2010) mean-shift particle filters (overhead) "
     "and Yu et al.'s (2010) Kalman-started mean shift (head cameras); needs the pixels extra"),
])
