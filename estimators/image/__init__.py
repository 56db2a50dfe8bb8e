"""Trackers on weight images (a colour-probability image, i.e. the back-projection of a colour
table or a hue histogram, or a frame difference); numpy-only, whatever made the images.

* :mod:`~estimators.image.meanshift`: mean shift on a weight image (:func:`mean_shift`) and
  the batched window machinery the trackers share (:class:`MeanShiftWindows`);
* :mod:`~estimators.image.checks`: the image trackers' argument checks;
* :mod:`~estimators.image.window_kernels`: the window machinery as compiled kernels (the
  global search's window masses, the windows' pixels, the mean-shift step);
* :mod:`~estimators.image.mspf`: the feature-restricted mean-shift particle filter of Li,
  Wu and Kong (2010; :class:`MeanShiftParticleFilter`) and the plain particle filter it
  is compared with (:class:`ParticleFilterTracker`);
* :mod:`~estimators.image.following`: the Kalman-started mean shift with ego-motion
  compensation of Yu, Wei and Zhang (2010; :class:`KalmanMeanShift`), plain mean shift
  (:class:`PlainMeanShift`), and the pinhole helpers (:func:`ego_motion_shift`,
  :func:`depth_from_size`, :func:`apparent_height`, :func:`focal_length_px`).
"""

from .following import (
    KalmanMeanShift,
    PlainMeanShift,
    apparent_height,
    depth_from_size,
    ego_motion_shift,
    focal_length_px,
)
from .meanshift import MEAN_SHIFT_KERNELS, MeanShiftWindows, mean_shift
from .mspf import EmptyWindowError, MeanShiftParticleFilter, ParticleFilterTracker

__all__ = [
    "mean_shift",
    "MEAN_SHIFT_KERNELS",
    "MeanShiftWindows",
    "EmptyWindowError",
    "MeanShiftParticleFilter",
    "ParticleFilterTracker",
    "KalmanMeanShift",
    "PlainMeanShift",
    "depth_from_size",
    "focal_length_px",
    "apparent_height",
    "ego_motion_shift",
]
