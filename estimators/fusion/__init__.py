"""Geometric fusion of sightings (paper 000, Xu, Xie, Wang, Ni 2012).

* :mod:`~estimators.fusion.hough`: Hough-space fusion of several robots' sighting lines of one
  target (:func:`hough_fuse`, :func:`fusion_weights`), and of a team's timestamped sightings
  with an error covariance for a tracker (:func:`fuse_sightings`, and :func:`fuse_lines`
  without its checks);
* :mod:`~estimators.fusion.triangulation`: a robot's pose from the bearings of three known
  landmarks (:func:`triangulate`).
"""

from .hough import (
    FUSION_WEIGHTINGS,
    FusedSighting,
    fuse_lines,
    fuse_sightings,
    fusion_weights,
    hough_fuse,
    hough_lines,
)
from .triangulation import Fix, triangulate

__all__ = [
    "hough_lines",
    "hough_fuse",
    "fusion_weights",
    "fuse_sightings",
    "fuse_lines",
    "FusedSighting",
    "FUSION_WEIGHTINGS",
    "Fix",
    "triangulate",
]
