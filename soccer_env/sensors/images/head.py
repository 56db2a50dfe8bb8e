"""Head frames (:class:`HeadFrameRenderer`). The pinhole view of :class:`estimators.HeadCamera`
(geometry in :mod:`soccer_env.sensors.headcam`) from the observer's head with the TRUE
orientation (pan + sway_pan, tilt + sway_tilt): sky above the horizon, floor below it, the
carpet of the walled area, the field lines as ground polygons of their true width (so they thin
with distance), then in painter's order (farthest first, by ground distance from the camera) the
goal posts (vertical cylinders of ``goal_wall_thickness`` diameter and ``goal_height``), the
crossbars, the other robots (dark cylinders of their radius and height, the top fifth in team
colour) and the ball (a disc of radius ``f r / depth`` px). Polygons are clipped at 5 cm in
front of the camera. No motion blur in head frames; robots are drawn standing (the state does
not say who has fallen).

Lighting and noise as in :mod:`~soccer_env.sensors.images.common`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np

from estimators import HeadCamera
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.presets.images import COLOURS, RGB, HeadFrameSpec, head_frame
from soccer_env.presets.sensors import HeadCameraSpec
from soccer_env.sensors.images.common import (
    DRAW_ONE,
    DRAW_SHIFT,
    Photometry,
    check_robot_count,
    robot_markers,
)
from soccer_env.state import HeadState, WorldState

__all__ = ["HeadFrameRenderer"]

_NEAR = 0.05  # [m] polygons are clipped this far in front of the camera


def _clip_near(poly: np.ndarray) -> np.ndarray | None:
    """Sutherland-Hodgman clip of a camera-frame polygon ``(k, 3)`` (columns ``x_c, depth,
    z_c``) to ``depth >= _NEAR``; None if nothing is left."""
    out = []
    n = len(poly)
    for j in range(n):
        a, b = poly[j], poly[(j + 1) % n]
        ina, inb = a[1] >= _NEAR, b[1] >= _NEAR
        if ina:
            out.append(a)
        if ina != inb:
            t = (_NEAR - a[1]) / (b[1] - a[1])
            out.append(a + t * (b - a))
    return np.array(out) if len(out) >= 3 else None


class HeadFrameRenderer:
    """Head-camera images of the robots of a world (module docstring).

    Args:
        camera_spec: the head camera (height, field of view, image size, goal colours:
            ``distinct_goals`` draws the goal at ``x = -L/2`` blue and the other yellow, else
            both white).
        field, robot_specs, ball_spec, teams: as :class:`OverheadRenderer`.
        spec: image appearance (or a preset name of :data:`HEAD_FRAMES`).
        size: ``(width, height)`` [pixels] to render at instead of the camera's, keeping its
            horizontal field of view (the focal length in pixels scales with the width).

    :attr:`camera` is the :class:`estimators.HeadCamera` of the rendered image:
    ``camera.project(points, pan, tilt)`` gives the pixels of robot-frame points.
    """

    def __init__(self, camera_spec: HeadCameraSpec, field: FieldSpec,
                 robot_specs: RobotSpec | Sequence[RobotSpec], ball_spec: BallSpec,
                 teams: Sequence[int], spec: HeadFrameSpec | str = "clean",
                 size: tuple[int, int] | None = None) -> None:
        if isinstance(spec, str):
            spec = head_frame(spec)
        if size is None:
            size = (camera_spec.width, camera_spec.height_px)
        if not (len(size) == 2 and all(isinstance(s, (int, np.integer)) and 16 <= s <= 8192
                                       for s in size)):
            raise ValueError(f"size must be (width, height) in pixels, each in [16, 8192], "
                             f"got {size!r}")
        self.spec, self.camera_spec, self.field, self.ball_spec = spec, camera_spec, field, \
            ball_spec
        self.robot_specs, self.teams, _ = robot_markers(robot_specs, teams)
        self.n_robots = len(self.teams)
        self.camera = HeadCamera(height=camera_spec.height, hfov=camera_spec.hfov,
                                 width=int(size[0]), height_px=int(size[1]))
        self.width, self.height = int(size[0]), int(size[1])
        self._f = self.camera.focal_px
        self._u0, self._v0 = self.camera.centre
        self._line_type = cv2.LINE_AA if spec.antialias else cv2.LINE_8
        self._photo = Photometry(self.width, self.height, spec.gain_sigma, spec.gradient,
                                  spec.noise_sigma)
        self._quads = self._line_quads()
        self._sky_img = np.empty((self.height, self.width, 3), np.uint8)
        self._sky_img[:] = spec.sky
        self._floor_img = np.empty_like(self._sky_img)
        self._floor_img[:] = spec.floor
        f = field
        hl, wx, wy = f.half_length, f.half_length + f.boundary, f.half_width + f.boundary
        self._carpet = np.array([[-wx, wy, 0.0], [wx, wy, 0.0], [wx, -wy, 0.0], [-wx, -wy, 0.0]])
        py = 0.5 * (f.goal_width + f.goal_wall_thickness)
        # Posts (as headcam.field_landmarks): centres, colour per goal.
        if camera_spec.distinct_goals:
            goal_rgb = (COLOURS["blue"], COLOURS["yellow"])
        else:
            goal_rgb = (spec.line, spec.line)
        self._posts = [(sx * hl, sy * py, goal_rgb[g])
                       for g, sx in enumerate((-1.0, 1.0)) for sy in (-1.0, 1.0)]
        a = np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False)
        self._ring = np.column_stack([np.cos(a), np.sin(a)])

    def _line_quads(self) -> np.ndarray:
        """Field lines as ground quads ``(Q, 4, 3)`` of the line width."""
        f = self.field
        hx, hy = f.half_length, f.half_width
        segs = [((-hx, hy), (hx, hy)), ((hx, hy), (hx, -hy)), ((hx, -hy), (-hx, -hy)),
                ((-hx, -hy), (-hx, hy)), ((0.0, hy), (0.0, -hy))]
        dw, dd = 0.5 * f.defense_width, f.defense_depth
        if dw > 0.0 and dd > 0.0:
            for sgn in (-1.0, 1.0):
                xa, xb = sgn * hx, sgn * (hx - dd)
                segs += [((xa, dw), (xb, dw)), ((xb, dw), (xb, -dw)), ((xb, -dw), (xa, -dw))]
        r = f.center_circle_radius
        if r > 0.0:
            n = 48
            a = np.linspace(0.0, 2.0 * math.pi, n + 1)
            pts = r * np.column_stack([np.cos(a), np.sin(a)])
            segs += [(tuple(pts[j]), tuple(pts[j + 1])) for j in range(n)]
        w = max(0.5 * f.line_width, 1e-3)
        quads = []
        for (x1, y1), (x2, y2) in segs:
            dx, dy = x2 - x1, y2 - y1
            length = math.hypot(dx, dy)
            nx, ny = -dy / length * w, dx / length * w
            ex, ey = dx / length * w, dy / length * w  # extend the ends: closed corners
            quads.append([(x1 - ex + nx, y1 - ey + ny, 0.0), (x2 + ex + nx, y2 + ey + ny, 0.0),
                          (x2 + ex - nx, y2 + ey - ny, 0.0), (x1 - ex - nx, y1 - ey - ny, 0.0)])
        return np.array(quads, dtype=np.float64)

    # ---------------------------------------------------------------- geometry

    def _to_camera(self, p: np.ndarray) -> np.ndarray:
        """Camera coordinates ``(..., 3)`` (``x_c`` right, depth, ``z_c`` up) of field points
        ``(..., 3)`` for the current pose (headcam module docstring)."""
        return (p - self._origin) @ self._rot_t

    def _fixed(self, cam: np.ndarray) -> np.ndarray:
        """Fixed-point drawing coordinates of camera-frame points in front of the camera."""
        f = self._f * DRAW_ONE
        d = cam[..., 1]
        out = np.empty(cam.shape[:-1] + (2,), np.int32)
        out[..., 0] = np.rint((self._u0 - 0.5) * DRAW_ONE + f * cam[..., 0] / d)
        out[..., 1] = np.rint((self._v0 - 0.5) * DRAW_ONE - f * cam[..., 2] / d)
        return out

    def _polygons(self, cam: np.ndarray) -> list[np.ndarray]:
        """Drawable polygons of camera-frame polygons ``(Q, k, 3)``, clipped at the near
        plane."""
        front = cam[..., 1] >= _NEAR
        whole = front.all(axis=1)
        out = list(self._fixed(cam[whole])) if whole.any() else []
        for j in np.nonzero(front.any(axis=1) & ~whole)[0].tolist():
            poly = _clip_near(cam[j])
            if poly is not None:
                out.append(self._fixed(poly))
        return out

    def _fill(self, img: np.ndarray, cam_polys: np.ndarray, rgb: RGB) -> None:
        """Fill convex camera-frame polygons ``(Q, k, 3)`` one by one (``cv2.fillPoly`` fills
        several polygons with the even-odd rule: overlaps would become holes)."""
        lt = self._line_type
        for poly in self._polygons(cam_polys):
            cv2.fillConvexPoly(img, poly, rgb, lt, DRAW_SHIFT)

    def _cylinder(self, img: np.ndarray, x: float, y: float, radius: float, z0: float,
                  z1: float, rgb: RGB) -> None:
        """A vertical cylinder: the convex hull of its projected end circles, or (partly
        behind the camera) its clipped silhouette quad."""
        cx, cy = self._pose[0], self._pose[1]
        ring = self._ring * radius + (x, y)
        pts = np.empty((2 * len(ring), 3))
        pts[:len(ring), :2] = ring
        pts[len(ring):, :2] = ring
        pts[:len(ring), 2] = z0
        pts[len(ring):, 2] = z1
        cam = self._to_camera(pts)
        if (cam[:, 1] >= _NEAR).all():
            hull = cv2.convexHull(self._fixed(cam))
            cv2.fillConvexPoly(img, hull, rgb, self._line_type, DRAW_SHIFT)
            return
        dx, dy = x - cx, y - cy
        d = math.hypot(dx, dy)
        if d < 1e-9:
            return
        nx, ny = -dy / d * radius, dx / d * radius
        quad = np.array([[x + nx, y + ny, z0], [x - nx, y - ny, z0], [x - nx, y - ny, z1],
                         [x + nx, y + ny, z1]])
        self._fill(img, self._to_camera(quad)[None], rgb)

    # ---------------------------------------------------------------- render

    def horizon_row(self, tilt: float) -> float:
        """Continuous ``v`` [px] of the horizon for a true camera tilt [rad]."""
        return self._v0 - self._f * math.tan(tilt)

    def render(self, state: WorldState, heads: HeadState, observer: int,
               rng: np.random.Generator | None = None) -> np.ndarray:
        """The image seen by robot ``observer``'s head camera in ``state`` with the TRUE head
        orientation of ``heads`` (servo plus sway): ``(height, width, 3)`` uint8 RGB."""
        check_robot_count(state, self.n_robots)
        if not 0 <= observer < self.n_robots:
            raise ValueError(f"observer must be a robot index in [0, {self.n_robots - 1}], "
                             f"got {observer!r}")
        sp, f = self.spec, self.field
        x, y, th = state.robots[observer, 0:3].tolist()
        psi = th + float(heads.pan[observer]) + float(heads.sway_pan[observer])
        beta = float(heads.tilt[observer]) + float(heads.sway_tilt[observer])
        h = self.camera.height
        c, s, cb, sb = math.cos(psi), math.sin(psi), math.cos(beta), math.sin(beta)
        self._pose = (x, y)
        self._origin = np.array([x, y, h])
        # Rows: x_c (right), depth, z_c (up) of a field offset (dx, dy, dz).
        self._rot_t = np.array([[s, -c, 0.0], [cb * c, cb * s, -sb], [sb * c, sb * s, cb]]).T
        H = self.height
        # Sky above the horizon, floor below it (no roll: a horizontal line).
        if beta >= 0.5 * math.pi - 1e-9:
            row = -1
        elif beta <= -0.5 * math.pi + 1e-9:
            row = H
        else:
            row = int(min(H, max(-1, math.floor(self.horizon_row(beta) - 0.5) + 1)))
        row = max(0, row)
        img = self._floor_img.copy()
        img[:row] = self._sky_img[:row]
        self._fill(img, self._to_camera(self._carpet)[None], sp.carpet)
        self._fill(img, self._to_camera(self._quads), sp.line)
        # Objects, farthest first.
        objects: list[tuple[float, int, tuple]] = []
        gh, gt = f.goal_height, f.goal_wall_thickness
        post_d = []
        for px, py, rgb in self._posts:
            d = math.hypot(px - x, py - y)
            post_d.append(d)
            objects.append((d, 0, (px, py, 0.5 * gt, 0.0, gh, rgb)))
        for g in (0, 2):  # crossbars, behind their posts
            (ax, ay, rgb), (bx_, by_, _) = self._posts[g], self._posts[g + 1]
            objects.append((max(post_d[g], post_d[g + 1]) + 1e-3, 1,
                            (ax, ay, bx_, by_, gh - gt, gh, rgb)))
        for j, (rx, ry) in enumerate(state.robots[:, 0:2].tolist()):
            if j == observer:
                continue
            rs = self.robot_specs[j]
            objects.append((math.hypot(rx - x, ry - y), 2, (rx, ry, rs.radius, rs.height,
                                                            self.teams[j])))
        bx, by, bz = state.ball[0:3].tolist()
        objects.append((math.hypot(bx - x, by - y), 3, (bx, by, bz)))
        objects.sort(key=lambda o: -o[0])
        team_rgb = (COLOURS["blue"], COLOURS["yellow"])
        for _, kind, a in objects:
            if kind == 0:
                self._cylinder(img, a[0], a[1], a[2], a[3], a[4], a[5])
            elif kind == 1:
                ax, ay, bx_, by_, z0, z1, rgb = a
                bar = np.array([[ax, ay, z0], [bx_, by_, z0], [bx_, by_, z1], [ax, ay, z1]])
                self._fill(img, self._to_camera(bar)[None], rgb)
            elif kind == 2:
                rx, ry, rr, rh, team = a
                self._cylinder(img, rx, ry, rr, 0.0, 0.8 * rh, sp.body)
                self._cylinder(img, rx, ry, rr, 0.8 * rh, rh, team_rgb[team])
            else:
                self._draw_ball(img, *a)
        return self._photo.apply(img, rng)

    def _draw_ball(self, img: np.ndarray, bx: float, by: float, bz: float) -> None:
        r = self.ball_spec.radius
        cam = self._to_camera(np.array([bx, by, bz + r]))
        depth = float(cam[1])
        if depth < _NEAR + r:
            return
        radius = self._f * r / depth
        centre = self._fixed(cam)
        u, v = centre.tolist()
        lim = 4 * DRAW_ONE * (self.width + self.height)
        if abs(u) > lim or abs(v) > lim:
            return
        cv2.circle(img, (u, v), max(1, int(round(radius * DRAW_ONE))), COLOURS["orange"], -1,
                   self._line_type, DRAW_SHIFT)
