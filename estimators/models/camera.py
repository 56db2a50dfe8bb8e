"""Pinhole model of a humanoid's head camera, and the ground projection of a sighting
(Xu, Xie, Wang and Ni 2012).

Frames: the robot frame has its origin on the ground under the camera, ``x`` forward, ``y``
to the left, ``z`` up [m]. The paper's world frame at the robot is ``(x_w, y_w, z_w) =
(-y, x, z)`` (``y_w`` forward, ``x_w`` to the right); the camera frame ``(x_c, y_c, z_c)`` has
``y_c`` along the optical axis, ``x_c`` to the right and ``z_c`` up in the image. The head pans
by ``alpha`` about ``z`` (positive to the left) and then tilts by ``beta`` about the panned
``x`` axis (positive down), in that order:

    [x_c, y_c, z_c]^T = Rx(beta) Rz(alpha) [x_w, y_w, z_w - h]^T,

with ``Rz(a) = [[cos a, sin a, 0], [-sin a, cos a, 0], [0, 0, 1]]`` and
``Rx(b) = [[1, 0, 0], [0, cos b, -sin b], [0, sin b, cos b]]`` (the matrices that express a
world vector in the turned frames). Image: ``u - u0 = f_px x_c / y_c``, ``v - v0 = -f_px
z_c / y_c`` (pixels, ``v`` growing downwards as in image arrays; the paper writes ``v`` up),
``f_px = (width / 2) / tan(hfov / 2)``.

The ground projection inverts this for ``z_w = 0``: the pixel's ray from the camera at height
``h`` meets the ground at a unique point if it points below the horizon. A pixel error
``du`` therefore becomes a ground error that grows with distance (about ``d^2 / (h f_px)``
along the ray), which is why far sightings deserve less weight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import MAX_PIXELS, check_count, check_real

__all__ = ["HeadCamera", "MIN_HFOV"]

#: The narrowest horizontal field of view [rad]: the focal length in pixels stays finite.
MIN_HFOV = 1e-6


@dataclass(frozen=True)
class HeadCamera:
    """A pinhole head camera (see the module docstring).

    Attributes:
        height: camera height above the ground [m] (Xu et al. 2012: 0.56).
        hfov: horizontal field of view [rad] in [MIN_HFOV, pi) (Xu et al. 2012: 51 degrees).
        width, height_px: image size [pixels] (Xu et al. 2012: 720 x 625 at 25 frames/s).
    """

    height: float = 0.56
    hfov: float = math.radians(51.0)
    width: int = 720
    height_px: int = 625

    def __post_init__(self) -> None:
        for name in ("width", "height_px"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
                raise ValueError(f"{name} must be a whole number of pixels, got {value!r}")
            object.__setattr__(self, name, check_count(name, value, 2, MAX_PIXELS))
        object.__setattr__(self, "height", check_real(
            "height", self.height, 0.0, 10.0, low_open=True, high_open=True, unit=" m"))
        object.__setattr__(self, "hfov", check_real(
            "hfov", self.hfov, MIN_HFOV, math.pi, high_open=True, unit=" rad"))

    @property
    def focal_px(self) -> float:
        """Focal length in pixels."""
        return 0.5 * self.width / math.tan(0.5 * self.hfov)

    @property
    def centre(self) -> tuple[float, float]:
        """Principal point ``(u0, v0)`` [pixels]."""
        return 0.5 * self.width, 0.5 * self.height_px

    @property
    def vfov(self) -> float:
        """Vertical field of view [rad]."""
        return 2.0 * math.atan(0.5 * self.height_px / self.focal_px)

    @staticmethod
    def _rotation(pan: float, tilt: float) -> np.ndarray:
        """``Rx(tilt) Rz(pan)``: paper world frame to camera frame."""
        ca, sa, cb, sb = math.cos(pan), math.sin(pan), math.cos(tilt), math.sin(tilt)
        rz = np.array([[ca, sa, 0.0], [-sa, ca, 0.0], [0.0, 0.0, 1.0]])
        rx = np.array([[1.0, 0.0, 0.0], [0.0, cb, -sb], [0.0, sb, cb]])
        return rx @ rz

    def project(self, points: np.ndarray, pan: float, tilt: float
                ) -> tuple[np.ndarray, np.ndarray]:
        """Pixels ``(n, 2)`` of robot-frame points ``(n, 3)`` (or ``(n, 2)`` on the ground),
        and a mask of those in front of the camera and inside the image."""
        p = np.asarray(points, dtype=np.float64)
        if p.ndim != 2 or p.shape[1] not in (2, 3):
            raise ValueError(f"points must have shape (n, 2) or (n, 3), got {p.shape}")
        _check_angles(pan, tilt)
        z = p[:, 2] if p.shape[1] == 3 else np.zeros(len(p))
        world = np.column_stack([-p[:, 1], p[:, 0], z - self.height])
        cam = world @ self._rotation(pan, tilt).T
        u0, v0 = self.centre
        f = self.focal_px
        ahead = cam[:, 1] > 1e-9
        depth = np.where(ahead, cam[:, 1], np.nan)
        uv = np.column_stack([u0 + f * cam[:, 0] / depth, v0 - f * cam[:, 2] / depth])
        inside = ahead & (uv[:, 0] >= 0) & (uv[:, 0] <= self.width) & (uv[:, 1] >= 0) & \
            (uv[:, 1] <= self.height_px)
        return uv, inside

    def ground_point(self, pixels: np.ndarray, pan: float, tilt: float,
                     plane_height: float = 0.0) -> np.ndarray:
        """Robot-frame points ``(n, 2)`` [m] seen at ``pixels`` ((n, 2)) on the horizontal plane
        ``z = plane_height`` [m] (the ground by default; a resting ball's centre lies on
        ``z = ball radius``): the ray ``c + t d`` from the camera ``c`` meets it at
        ``t = (plane_height - height) / d_z``. NaN where the ray does not meet the plane ahead
        of the camera (``t <= 0``): for planes below the camera, pixels at or above the
        horizon."""
        uv = np.asarray(pixels, dtype=np.float64)
        if uv.ndim != 2 or uv.shape[1] != 2:
            raise ValueError(f"pixels must have shape (n, 2), got {uv.shape}")
        if not np.isfinite(uv).all():
            raise ValueError("pixels must be finite (NaN pixels are refused)")
        _check_angles(pan, tilt)
        if not math.isfinite(plane_height):
            raise ValueError(f"plane_height must be finite, got {plane_height!r}")
        u0, v0 = self.centre
        f = self.focal_px
        ray_cam = np.column_stack([(uv[:, 0] - u0) / f, np.ones(len(uv)), -(uv[:, 1] - v0) / f])
        ray = ray_cam @ self._rotation(pan, tilt)  # camera -> paper world (R^T applied)
        drop = plane_height - self.height  # [m], negative for planes below the camera
        meets = (ray[:, 2] * drop > 0.0) & (np.abs(ray[:, 2]) > 1e-12)
        t = np.where(meets, drop / np.where(meets, ray[:, 2], 1.0), np.nan)
        xw, yw = t * ray[:, 0], t * ray[:, 1]
        return np.column_stack([yw, -xw])  # paper world -> robot frame


def _check_angles(pan: float, tilt: float) -> None:
    """``ValueError`` unless the head's ``pan`` and ``tilt`` [rad] are finite numbers."""
    if not (math.isfinite(pan) and math.isfinite(tilt)):
        raise ValueError(f"pan and tilt must be finite angles in radians, got {pan!r}, "
                         f"{tilt!r}")
