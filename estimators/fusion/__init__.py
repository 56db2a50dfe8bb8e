"""Geometric fusion of sightings (Xu, Xie, Wang and Ni 2012).

* :mod:`~estimators.fusion.hough`: Hough-space fusion of several robots' sighting lines of one
  target (:func:`hough_fuse`, :func:`fusion_weights`, :func:`line_offset_variance` for the
  inverse-variance weighting);
* :mod:`~estimators.fusion.sightings`: the fusion of a team's timestamped sightings with an
  error covariance for a tracker (:func:`fuse_sightings`, and :func:`fuse_lines` without its
  checks);
* :mod:`~estimators.fusion.line_kernels`: their maths as compiled kernels over the lines
  (:func:`~estimators.fusion.line_kernels.fuse_line_rows`);
* :mod:`~estimators.fusion.triangulation`: a robot's pose from the bearings of three known
  landmarks (:func:`triangulate`), and pose hypotheses from sightings of landmarks known by
  kind only, gathered over several frames (:func:`triangulate_sightings`,
  :class:`SightingMemory`).
"""

from .hough import (
    FUSION_WEIGHTINGS,
    INVERSE_VARIANCE,
    WEIGHTING_NAMES,
    fusion_weights,
    hough_fuse,
    hough_lines,
    line_offset_variance,
    weighting_power,
)
from .sightings import FusedSighting, fuse_lines, fuse_sightings
from .triangulation import (
    SEED_FAILURES,
    Fix,
    PoseHypotheses,
    SightingMemory,
    triangulate,
    triangulate_sightings,
)

__all__ = [
    "hough_lines",
    "hough_fuse",
    "fusion_weights",
    "fuse_sightings",
    "fuse_lines",
    "line_offset_variance",
    "weighting_power",
    "FusedSighting",
    "FUSION_WEIGHTINGS",
    "INVERSE_VARIANCE",
    "WEIGHTING_NAMES",
    "Fix",
    "PoseHypotheses",
    "SightingMemory",
    "SEED_FAILURES",
    "triangulate_sightings",
    "triangulate",
]
