"""Estimators and motion models for robot soccer, usable without the environment.

Everything here takes and returns numpy arrays, depends on numpy only, and never on
``soccer_env``. Random draws come from explicit ``numpy.random.Generator`` arguments.
"""

from .hough import FusedSighting, fuse_sightings, fusion_weights, hough_fuse, hough_lines
from .kalman import (
    CHI2_2DOF_999,
    BallFilterConfig,
    BallTracker,
    KalmanFilter,
    LeastSquaresBall,
    RobotTracker,
)
from .meanshift import (
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
    BootstrapPF,
    KLDConfig,
    KLDLocalizer,
    ParticleBallTracker,
    kld_sample_size,
    sfn,
    systematic_resample,
    ungm_model,
    ungm_simulate,
)
from .triangulation import Fix, triangulate

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
    "LeastSquaresBall",
    "ParticleBallTracker",
    "RobotTracker",
    "CHI2_2DOF_999",
    "hough_fuse",
    "fuse_sightings",
    "FusedSighting",
    "hough_lines",
    "fusion_weights",
    "BootstrapPF",
    "FBPF",
    "MFBPF",
    "sfn",
    "systematic_resample",
    "ungm_model",
    "ungm_simulate",
    "Fix",
    "triangulate",
    "KLDConfig",
    "KLDLocalizer",
    "kld_sample_size",
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
]
