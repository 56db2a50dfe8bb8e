"""Overhead frames (:class:`OverheadRenderer`), the camera of SSL / MiroSot vision (Li et al.'s 2010
setting). An orthographic view of the field plane from a camera above the centre of the region
it sees (the whole walled area by default, scaled to fit the image with square pixels and
centred): carpet, field lines, defense areas, centre circle, goals and walls come from a
background image drawn once; every frame copies it and draws the robots (SSL: the flat-front
outline in a dark body colour; humanoids: a dark disc; both with their patch pattern) and the
orange ball. Robots are drawn at their ground position (an SSL-Vision-like calibration per
object height); a ball in the air is seen by the camera at ``camera_height`` above the region's
centre (or the given :class:`~soccer_env.sensors.overhead.Camera`) and is drawn where the
camera's ray through its centre meets the plane of a resting ball's centre, enlarged by the same
factor (``chip_parallax``; a ball on the carpet is drawn at its position with its true size). A
ball on the carpet is drawn before the robots (a robot over it hides it), a ball higher than the
tallest robot after them.

Motion blur: each object whose image moves by half a pixel or more during the exposure
(``exposure`` [s], centred on the frame's time; translation plus rotation at the body's radius)
is drawn at ``K`` poses spread evenly over the exposure, ``K = clip(ceil(smear) + 1, 2,
blur_samples)`` with ``smear`` its image displacement in pixels, each on a copy of the image
region it sweeps, and the copies are averaged: the object is smeared along its image velocity
and blended with what lies behind it.

Lighting and noise: :mod:`~soccer_env.sensors.images.common`; the top markers:
:mod:`~soccer_env.sensors.images.patterns`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np

try:
    import cv2
except ImportError as err:  # pragma: no cover - depends on the installation
    raise ImportError("soccer_env.sensors.images.overhead needs OpenCV; install it with: "
                      "pip install 'soccer-env[pixels]'") from err

from estimators.image.colour import ColourTable
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.presets.images import (
    CLASS_ALIASES,
    COLOURS,
    OVERHEAD_CLASSES,
    OverheadFrameSpec,
    overhead_frame,
)
from soccer_env.sensors.images.common import (
    DRAW_ONE,
    DRAW_SHIFT,
    Photometry,
    check_robot_count,
    robot_markers,
)
from soccer_env.sensors.images.patterns import PATTERN
from soccer_env.sensors.overhead import Camera
from soccer_env.sim.ssl import robot_outline
from soccer_env.state import WorldState

__all__ = ["OverheadRenderer"]


# --------------------------------------------------------------------------------------------
# Top markers
# --------------------------------------------------------------------------------------------


# --------------------------------------------------------------------------------------------
# Specs
# --------------------------------------------------------------------------------------------


# --------------------------------------------------------------------------------------------
# Shared: lighting and noise, robots' lists
# --------------------------------------------------------------------------------------------


# --------------------------------------------------------------------------------------------
# Overhead camera
# --------------------------------------------------------------------------------------------


class OverheadRenderer:
    """Overhead camera images of a field (module docstring).

    Args:
        spec: image characteristics (or a preset name of :data:`OVERHEAD_FRAMES`).
        field: the field.
        robot_specs: one spec for every robot or one per robot (world order).
        ball_spec: the ball.
        teams: ``(N,)`` team per robot, 0 blue, 1 yellow; a robot's number within its team
            (its patch pattern) is its rank among its team's robots in world order.
        camera: show this :class:`~soccer_env.sensors.overhead.Camera`'s area (overrides
            ``spec.region``) and take its position and height for the ball's parallax.

    :meth:`render` returns ``(spec.height, spec.width, 3)`` uint8 RGB.
    """

    def __init__(self, spec: OverheadFrameSpec | str, field: FieldSpec,
                 robot_specs: RobotSpec | Sequence[RobotSpec], ball_spec: BallSpec,
                 teams: Sequence[int], camera: Camera | None = None) -> None:
        if isinstance(spec, str):
            spec = overhead_frame(spec)
        self.spec, self.field, self.ball_spec = spec, field, ball_spec
        self.robot_specs, self.teams, self.numbers = robot_markers(robot_specs, teams)
        self.n_robots = len(self.teams)
        W, H = spec.width, spec.height
        if camera is not None:
            region = (camera.x_min, camera.x_max, camera.y_min, camera.y_max)
            self._cam = (camera.x, camera.y, camera.height)
        elif spec.region is not None:
            region = spec.region
            self._cam = (0.5 * (region[0] + region[1]), 0.5 * (region[2] + region[3]),
                         spec.camera_height)
        else:
            wx, wy = field.half_length + field.boundary, field.half_width + field.boundary
            region = (-wx, wx, -wy, wy)
            self._cam = (0.0, 0.0, spec.camera_height)
        self.region = tuple(float(c) for c in region)
        x0, x1, y0, y1 = self.region
        #: Metres per pixel (square pixels).
        self.metres_per_pixel = max((x1 - x0) / W, (y1 - y0) / H)
        self._cx, self._cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        self._k = 1.0 / self.metres_per_pixel
        self._line_type = cv2.LINE_AA if spec.antialias else cv2.LINE_8
        self._photo = Photometry(W, H, spec.gain_sigma, spec.gradient, spec.noise_sigma)
        # Per robot: body outline (body frame) and patches (centres, radii, colours).
        outlines, patches = [], []
        for rs, team, num in zip(self.robot_specs, self.teams, self.numbers):
            if rs.kind == "ssl":
                outline = np.array(robot_outline(rs, n_arc=16))
            else:
                a = np.linspace(0.0, 2.0 * math.pi, 24, endpoint=False)
                outline = rs.radius * np.column_stack([np.cos(a), np.sin(a)])
            outlines.append(outline)
            patches.append(PATTERN.patches(team, num, rs.radius))
        self._outlines = outlines
        self._patch_xy = [np.array([(p.x, p.y) for p in ps]) for ps in patches]
        self._patch_r = [[p.radius * self._k * DRAW_ONE for p in ps] for ps in patches]
        self._patch_rgb = [[p.rgb for p in ps] for ps in patches]
        self._radii = np.array([rs.radius for rs in self.robot_specs])
        self._max_height = max((rs.height for rs in self.robot_specs), default=0.0)
        self._background = self._draw_background()

    # ---------------------------------------------------------------- mapping

    def to_pixel(self, x: float | np.ndarray, y: float | np.ndarray
                 ) -> tuple[float | np.ndarray, float | np.ndarray]:
        """Continuous pixel ``(u, v)`` of the field point ``(x, y)`` [m] (module docstring:
        pixel ``[j, i]`` covers ``i <= u < i + 1``)."""
        k = self._k
        return (0.5 * self.spec.width + (x - self._cx) * k,
                0.5 * self.spec.height - (y - self._cy) * k)

    def to_field(self, u: float | np.ndarray, v: float | np.ndarray
                 ) -> tuple[float | np.ndarray, float | np.ndarray]:
        """Field point ``(x, y)`` [m] at continuous pixel ``(u, v)``; inverse of
        :meth:`to_pixel`."""
        m = self.metres_per_pixel
        return (self._cx + (u - 0.5 * self.spec.width) * m,
                self._cy - (v - 0.5 * self.spec.height) * m)

    def _fixed(self, x: np.ndarray, y: np.ndarray, ox: float = 0.0, oy: float = 0.0
               ) -> np.ndarray:
        """Fixed-point drawing coordinates (``shift = 4``) of field points, minus a pixel
        offset ``(ox, oy)``: cv2 puts integer coordinates at pixel centres."""
        u, v = self.to_pixel(x, y)
        return np.column_stack([np.rint((u - 0.5 - ox) * DRAW_ONE),
                                np.rint((v - 0.5 - oy) * DRAW_ONE)]).astype(np.int32)

    def colour_table(self, tolerance: float = 30.0, bits: int = 5) -> ColourTable:
        """A :class:`ColourTable` of this renderer's colours, with a gain range that covers its
        lighting variation (3 sigma of gain plus the largest ramp)."""
        s = self.spec
        spread = 3.0 * s.gain_sigma + s.gradient
        colours = {**OVERHEAD_CLASSES, "carpet": s.carpet}
        return ColourTable(colours, tolerance=max(tolerance, 3.0 * s.noise_sigma),
                           gain_range=(max(0.3, 1.0 - spread - 0.1), 1.0 + spread + 0.1),
                           bits=bits, aliases=CLASS_ALIASES)

    # ---------------------------------------------------------------- background

    def _draw_background(self) -> np.ndarray:
        s, f = self.spec, self.field
        img = np.empty((s.height, s.width, 3), np.uint8)
        img[:] = COLOURS["floor"]
        lt = self._line_type
        k = self._k

        def pt(x: float, y: float) -> tuple[int, int]:
            return tuple(self._fixed(np.array([x]), np.array([y]))[0].tolist())

        def thick(width_m: float) -> int:
            return max(1, int(round(width_m * k)))

        hx, hy = f.half_length, f.half_width
        wx, wy = hx + f.boundary, hy + f.boundary
        cv2.fillPoly(img, [np.array([pt(-wx, wy), pt(wx, wy), pt(wx, -wy), pt(-wx, -wy)])],
                     s.carpet, lt, DRAW_SHIFT)
        lw = thick(f.line_width)
        corners = np.array([pt(-hx, hy), pt(hx, hy), pt(hx, -hy), pt(-hx, -hy)])
        cv2.polylines(img, [corners], True, s.line, lw, lt, DRAW_SHIFT)
        cv2.line(img, pt(0.0, hy), pt(0.0, -hy), s.line, lw, lt, DRAW_SHIFT)
        if f.center_circle_radius > 0.0:
            cv2.circle(img, pt(0.0, 0.0), int(round(f.center_circle_radius * k * DRAW_ONE)), s.line,
                       lw, lt, DRAW_SHIFT)
        dw, dd = 0.5 * f.defense_width, f.defense_depth
        gw, gd = 0.5 * f.goal_width, f.goal_depth
        gt = thick(f.goal_wall_thickness)
        for sgn in (-1.0, 1.0):
            if dw > 0.0 and dd > 0.0:
                xa, xb = sgn * hx, sgn * (hx - dd)
                cv2.polylines(img, [np.array([pt(xa, dw), pt(xb, dw), pt(xb, -dw),
                                              pt(xa, -dw)])], False, s.line, lw, lt, DRAW_SHIFT)
            # Goal walls: outside the goal line, wall_thickness beyond the goal's inside.
            e = 0.5 * f.goal_wall_thickness
            gx = sgn * (hx + gd + e)
            cv2.polylines(img, [np.array([pt(sgn * hx, gw + e), pt(gx, gw + e), pt(gx, -gw - e),
                                          pt(sgn * hx, -gw - e)])], False, COLOURS["goal"], gt,
                          lt, DRAW_SHIFT)
        cv2.polylines(img, [np.array([pt(-wx, wy), pt(wx, wy), pt(wx, -wy), pt(-wx, -wy)])],
                      True, COLOURS["wall"], thick(0.02), lt, DRAW_SHIFT)
        img.flags.writeable = False
        return img

    # ---------------------------------------------------------------- objects

    def _draw_robot(self, img: np.ndarray, i: int, x: float, y: float, th: float,
                    ox: float = 0.0, oy: float = 0.0) -> None:
        c, s = math.cos(th), math.sin(th)
        lt = self._line_type
        o = self._outlines[i]
        pts = self._fixed(x + c * o[:, 0] - s * o[:, 1], y + s * o[:, 0] + c * o[:, 1], ox, oy)
        cv2.fillPoly(img, [pts], COLOURS["body"], lt, DRAW_SHIFT)
        p = self._patch_xy[i]
        centres = self._fixed(x + c * p[:, 0] - s * p[:, 1], y + s * p[:, 0] + c * p[:, 1],
                              ox, oy).tolist()
        for centre, r, rgb in zip(centres, self._patch_r[i], self._patch_rgb[i]):
            cv2.circle(img, centre, int(round(r)), rgb, -1, lt, DRAW_SHIFT)

    def _ball_view(self, bx: float, by: float, bz: float) -> tuple[float, float, float]:
        """Where the ball appears (as a point of the field plane) and its apparent radius [m]
        (module docstring: chip parallax)."""
        r = self.ball_spec.radius
        if bz <= 0.0 or not self.spec.chip_parallax:
            return bx, by, r
        cx, cy, h = self._cam
        zc = bz + r
        if zc >= h - 1e-3:
            zc = h - 1e-3
        k = (h - r) / (h - zc)
        return cx + (bx - cx) * k, cy + (by - cy) * k, r * k

    def _draw_ball(self, img: np.ndarray, bx: float, by: float, bz: float, ox: float = 0.0,
                   oy: float = 0.0) -> None:
        x, y, r = self._ball_view(bx, by, bz)
        centre = self._fixed(np.array([x]), np.array([y]), ox, oy)[0].tolist()
        cv2.circle(img, centre, max(1, int(round(r * self._k * DRAW_ONE))), COLOURS["orange"], -1,
                   self._line_type, DRAW_SHIFT)

    def _smeared(self, img: np.ndarray, draw, poses: list[tuple[float, ...]], reach: float
                 ) -> None:
        """Average ``draw(tile, *pose, ox, oy)`` over ``poses`` on the image region they sweep
        (``reach`` [m] around each pose's position)."""
        xs = np.array([p[0] for p in poses])
        ys = np.array([p[1] for p in poses])
        us, vs = self.to_pixel(xs, ys)
        rpx = reach * self._k + 2.0
        H, W = img.shape[:2]
        u0, u1 = max(0, int(math.floor(us.min() - rpx))), min(W, int(math.ceil(us.max() + rpx)))
        v0, v1 = max(0, int(math.floor(vs.min() - rpx))), min(H, int(math.ceil(vs.max() + rpx)))
        if u0 >= u1 or v0 >= v1:
            return
        base = img[v0:v1, u0:u1]
        acc = np.zeros(base.shape, np.float32)
        for pose in poses:
            tile = base.copy()
            draw(tile, *pose, u0, v0)
            acc += tile
        img[v0:v1, u0:u1] = np.rint(acc * (1.0 / len(poses))).astype(np.uint8)

    def _samples(self, smear_px: float) -> int:
        return min(self.spec.blur_samples, max(2, int(math.ceil(smear_px)) + 1))

    def render(self, state: WorldState, rng: np.random.Generator | None = None) -> np.ndarray:
        """The camera image of ``state``: ``(height, width, 3)`` uint8 RGB. ``rng`` draws the
        lighting and noise (needed only if the spec has any)."""
        check_robot_count(state, self.n_robots)
        img = self._background.copy()
        T = self.spec.exposure
        k = self._k
        bx, by, bz, bvx, bvy, bvz = state.ball.tolist()
        ball_first = bz < self._max_height
        if ball_first:
            self._ball(img, bx, by, bz, bvx, bvy, bvz, T)
        robots = state.robots.tolist()
        radii = self._radii.tolist()
        for i, (x, y, th, vx, vy, om) in enumerate(robots):
            smear = T * (math.hypot(vx, vy) + abs(om) * radii[i]) * k
            if smear < 0.5:
                self._draw_robot(img, i, x, y, th)
                continue
            poses = [(x + vx * t, y + vy * t, i, th + om * t)
                     for t in np.linspace(-0.5 * T, 0.5 * T, self._samples(smear)).tolist()]
            self._smeared(img, self._draw_robot_at, poses, radii[i])
        if not ball_first:
            self._ball(img, bx, by, bz, bvx, bvy, bvz, T)
        return self._photo.apply(img, rng)

    def _draw_robot_at(self, tile: np.ndarray, x: float, y: float, i: int, th: float,
                       ox: float, oy: float) -> None:
        self._draw_robot(tile, i, x, y, th, ox, oy)

    def _ball(self, img: np.ndarray, bx: float, by: float, bz: float, vx: float, vy: float,
              vz: float, T: float) -> None:
        smear = T * math.sqrt(vx * vx + vy * vy + vz * vz) * self._k
        if smear < 0.5:
            self._draw_ball(img, bx, by, bz)
            return
        poses = []
        for t in np.linspace(-0.5 * T, 0.5 * T, self._samples(smear)).tolist():
            x, y, _ = self._ball_view(bx + vx * t, by + vy * t, max(0.0, bz + vz * t))
            poses.append((x, y, bx + vx * t, by + vy * t, max(0.0, bz + vz * t)))
        _, _, r = self._ball_view(bx, by, bz)

        def draw(tile: np.ndarray, x: float, y: float, tx: float, ty: float, tz: float,
                 ox: float, oy: float) -> None:
            self._draw_ball(tile, tx, ty, tz, ox, oy)

        self._smeared(img, draw, poses, 1.5 * r + self.ball_spec.radius)


# --------------------------------------------------------------------------------------------
# Head camera
# --------------------------------------------------------------------------------------------


# --------------------------------------------------------------------------------------------
# Trackers' helpers
# --------------------------------------------------------------------------------------------


# --------------------------------------------------------------------------------------------
# Timing
# --------------------------------------------------------------------------------------------

