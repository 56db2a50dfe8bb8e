"""Trackers on weight images."""

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

__all__ = [
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
