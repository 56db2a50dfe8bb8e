"""Estimators and models for robot soccer, usable without the environment.

Everything here takes and returns numpy arrays, depends on numpy and numba only (its hot paths
are compiled kernels; never on ``soccer_env`` or ``agents``), and draws random numbers from
explicit ``numpy.random.Generator`` arguments.

"Xu et al. (2012)" to "Yu et al. (2010)" are the five source papers, cited in full in the
README's "Source papers" section and on the documentation's "Source papers" page
(``docs/papers.md``): Xu, Xie, Wang and Ni (2012), target localization by cooperative soccer
robots in Hough space; Guo and Li (2013), mobile-robot localization from obstacle-ground
corners; Zhao, Wang and Li (2012), the extended Kalman filter in robot soccer; Li, Wu and Kong
(2010), the mean-shift, feature-restricted particle filter; Yu, Wei and Zhang (2010), person
following with a monocular camera.

Every public name is importable from here (``from estimators import BallTracker``); the
subpackages group them:

* :mod:`estimators.models`: motion and measurement models, the rolling ball, the head camera;
* :mod:`estimators.tracking`: the parts the ball trackers are built from (gate, track
  initiator, replay buffer for latency compensation, track quality);
* :mod:`estimators.kalman`: the Kalman filter core and its blocks, the ball trackers of Zhao
  et al. (2012) and others, the robot tracker;
* :mod:`estimators.particle`: the particle filters of Xu et al. (2012), the particle ball
  tracker, the KLD-sampling localization of Guo and Li (2013);
* :mod:`estimators.fusion`: Hough-space fusion and three-landmark triangulation (Xu et al.
  2012);
* :mod:`estimators.image`: mean shift and the trackers on weight images (Li et al. 2010 and
  Yu et al. 2010).

**Time-stamped trackers** follow one protocol (:class:`Tracker`, :mod:`estimators.protocol`):
``update(t, z, ...)`` fuses a measurement captured at time ``t`` [s], ``estimate(t)`` predicts
the state to any time ``t`` without changing the tracker (None before the first measurement),
``reset()`` forgets everything:

* :class:`BallTracker`, :class:`LeastSquaresBall`, :class:`KickAwareBall` and
  :class:`IMMBall`: ``update(t, detections, obstacles=None)``
  (one camera frame's ball detections ``(k, 2)`` and the robots seen in it), ``estimate(t)``
  -> ``(x, y, vx, vy)``;
* :class:`ParticleBallTracker`: ``update(t, z, sigma)`` (a fused position and its noise),
  ``estimate(t)`` -> ``(x, y, vx, vy)``;
* :class:`LineBallTracker`: ``update_line(t, origin, angle, range_, own)`` (one robot's
  sighting line, in any order within its replay window), ``estimate(t)`` ->
  ``(x, y, vx, vy)``;
* :class:`RobotTracker` (many robots): ``update(t, z, index)`` (a batch of poses ``(k, 3)`` and
  their robots, checked), ``update_robot(t, z, i)`` and ``update_many(t, index, z)`` (one
  pose or several, unchecked: the fast paths), ``estimate(t)`` -> ``(n, 6)`` rows
  ``x, y, theta, vx, vy, omega`` for all robots, never None (robots never seen read as
  zeros, see ``seen``), and ``estimate_driven(t, history)``: a team's own robots driven from
  their latest update through the commands of a :class:`CommandHistory` (a Smith predictor).

:class:`BallTrackerBatch` and :class:`RobotTrackerBatch` are ``m`` such trackers as arrays
(the filters of ``m`` environments), updated with one kernel call per batch of frames: the
same compiled kernels as the single trackers', which are batches of one.

The ball trackers also follow :class:`TrackQuality`: ``covariance(t)``, ``last_fused``
and ``since_start`` say how sure they are (the environments' belief features; one
implementation, :class:`~estimators.tracking.TrackQualityMixin`); the robot
tracker's ``pose_sigma(i, t)`` and the localization's ``pose_sigma()`` give the pose's spread.

**Frame-synchronous image trackers** step once per image, the frame being the time step:
``update(image, ...)`` returns the estimate [px, px/frame]. :class:`MeanShiftParticleFilter`
and :class:`ParticleFilterTracker`: ``update(colour_image, motion_image=None, ...)`` ->
``(x, y, vx, vy)``; :class:`KalmanMeanShift`: ``update(weight_image, rotation, advance,
distance)`` -> ``(x, y, vx, vy)``; :class:`PlainMeanShift`: ``update(weight_image)`` ->
``(x, y)``.

**Filter cores**, the building blocks the trackers are made of, keep their textbook verbs:
:class:`KalmanFilter` ``predict(F, Q)`` / ``update(z, H, R)``; :class:`BootstrapPF`,
:class:`FBPF`, :class:`MFBPF` ``predict()`` / ``correct(y)`` / ``step(y)``;
:class:`KLDLocalizer` ``predict(odometry)`` / ``update(landmarks, ranges, bearings)`` /
``update_kinds(...)`` / ``estimate()`` (the current pose: it keeps no clock).

**Option families** are registries (:class:`Registry`: name -> value and a one-line
description, errors that list the options): :data:`PARTICLE_FILTERS`,
:data:`FUSION_WEIGHTINGS`, :data:`MEAN_SHIFT_KERNELS`.
"""

from .fusion import (
    FUSION_WEIGHTINGS,
    INVERSE_VARIANCE,
    WEIGHTING_NAMES,
    Fix,
    FusedSighting,
    PoseHypotheses,
    SightingMemory,
    fuse_lines,
    fuse_sightings,
    fusion_weights,
    hough_fuse,
    hough_lines,
    line_offset_variance,
    triangulate,
    triangulate_sightings,
    weighting_power,
)
from .image import (
    MEAN_SHIFT_KERNELS,
    KalmanMeanShift,
    MeanShiftParticleFilter,
    ParticleFilterTracker,
    PlainMeanShift,
    apparent_height,
    depth_from_size,
    ego_motion_shift,
    focal_length_px,
    mean_shift,
)
from .kalman import (
    CHI2_2DOF_999,
    BallFilterConfig,
    BallTracker,
    BallTrackerBatch,
    CommandHistory,
    IMMBall,
    KalmanFilter,
    KickAwareBall,
    LeastSquaresBall,
    LineBallTracker,
    RobotTracker,
    RobotTrackerBatch,
    SightingNoise,
)
from .models import (
    MIN_SIGMA_XY,
    PAPER_CYCLE,
    ConstantVelocityMotion,
    FrictionBallModel,
    FrictionBallMotion,
    HeadCamera,
    PoseMeasurement,
    PositionMeasurement,
    wrap_angle,
)
from .particle import (
    FBPF,
    MFBPF,
    PARTICLE_FILTERS,
    RECOVERIES,
    BootstrapPF,
    KLDConfig,
    KLDLocalizer,
    LandmarkTable,
    ParticleBallTracker,
    kld_sample_size,
    seed_poses,
    sfn,
    systematic_resample,
    ungm_model,
    ungm_simulate,
)
from .protocol import Tracker, TrackQuality
from .registry import Registry

__all__ = [
    "KalmanFilter",
    "FrictionBallModel",
    "FrictionBallMotion",
    "ConstantVelocityMotion",
    "PositionMeasurement",
    "PoseMeasurement",
    "wrap_angle",
    "PAPER_CYCLE",
    "MIN_SIGMA_XY",
    "BallFilterConfig",
    "BallTracker",
    "BallTrackerBatch",
    "LeastSquaresBall",
    "KickAwareBall",
    "IMMBall",
    "LineBallTracker",
    "SightingNoise",
    "ParticleBallTracker",
    "RobotTracker",
    "RobotTrackerBatch",
    "CommandHistory",
    "CHI2_2DOF_999",
    "hough_fuse",
    "fuse_sightings",
    "fuse_lines",
    "FusedSighting",
    "hough_lines",
    "fusion_weights",
    "line_offset_variance",
    "weighting_power",
    "BootstrapPF",
    "FBPF",
    "MFBPF",
    "sfn",
    "systematic_resample",
    "ungm_model",
    "ungm_simulate",
    "Fix",
    "triangulate",
    "triangulate_sightings",
    "PoseHypotheses",
    "SightingMemory",
    "KLDConfig",
    "KLDLocalizer",
    "RECOVERIES",
    "LandmarkTable",
    "kld_sample_size",
    "seed_poses",
    "HeadCamera",
    "mean_shift",
    "MeanShiftParticleFilter",
    "ParticleFilterTracker",
    "KalmanMeanShift",
    "PlainMeanShift",
    "depth_from_size",
    "focal_length_px",
    "apparent_height",
    "ego_motion_shift",
    "Tracker",
    "TrackQuality",
    "Registry",
    "PARTICLE_FILTERS",
    "FUSION_WEIGHTINGS",
    "INVERSE_VARIANCE",
    "WEIGHTING_NAMES",
    "MEAN_SHIFT_KERNELS",
]
