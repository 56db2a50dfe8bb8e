"""A humanoid's ball sightings and what it knows of their errors: the sighting line a head
camera frame gives (:class:`SightingLine`), the error model of its bearing and range
(:func:`sighting_sigmas`), how much the robot's gait sways the camera (:func:`sway_scale`), and
the landmarks of a frame the localization weighs (:func:`landmark_sightings`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from soccer_env.presets import RobotSpec
from soccer_env.presets.sensors import HeadCameraSpec
from soccer_env.sensors.headcam import HeadFrame
from soccer_env.sim.walk import speed_norm, sway_share

__all__ = ["SightingLine", "sighting_sigmas", "sway_scale", "landmark_sightings"]


@dataclass
class SightingLine:
    """A sighting line: from ``origin`` at ``angle`` [rad], range [m] (NaN: bearing only),
    captured at ``stamp`` [s] while the observer swayed by ``sway`` (0 to 1, its
    :func:`sway_scale`)."""

    stamp: float
    origin: tuple[float, float]
    angle: float
    range: float
    sway: float = 1.0


def sighting_sigmas(camera: HeadCameraSpec, sway_pan: float, sway_tilt: float
                    ) -> tuple[float, float]:
    """``(bearing_sigma [rad], range_per_metre [1/m])``: the error model of a head camera's
    ball sightings with the torso swaying by ``sway_pan`` and ``sway_tilt`` [rad]: bearings off
    by the pixel noise and the yaw sway (at least half a degree); ranges (ground projections)
    off by about ``d^2 e / h`` for an angular error ``e`` of the tilt (pixel noise and pitch
    sway), i.e. relatively by ``d e / h`` (at least 0.1 % per metre)."""
    pixel = camera.pixel_sigma / camera.camera.focal_px
    return (max(math.radians(0.5), math.hypot(sway_pan, pixel)),
            max(1e-3, math.hypot(sway_tilt, pixel) / camera.height))


def sway_scale(spec: RobotSpec, gait: tuple[float, float, float]) -> float:
    """How much a humanoid walking at ``gait`` ``(vx, vy, omega)`` sways, 0 (standing) to 1,
    as its walk engine makes it (:func:`soccer_env.sim.walk.sway_share`). A robot knows its own
    gait, so its sightings carry it."""
    return sway_share(speed_norm(spec, *gait))


def landmark_sightings(frame: HeadFrame) -> tuple[tuple[str, ...], np.ndarray, np.ndarray]:
    """The landmarks of ``frame`` that have a ground point: their kinds, ranges [m] and
    bearings [rad] in the robot frame (what the localization weighs)."""
    kinds, ranges, bearings = [], [], []
    for kind, _u, _v, x, y, bearing in frame.landmarks:
        r = math.hypot(x, y)
        if math.isfinite(r):
            kinds.append(kind)
            ranges.append(r)
            bearings.append(bearing)
    return tuple(kinds), np.array(ranges), np.array(bearings)
