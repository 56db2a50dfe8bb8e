"""The pinhole head camera (Xu et al. 2012): projection and ground projection invert each other,
the pan-then-tilt order, the field of view, error growing with distance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators.models import HeadCamera

CAM = HeadCamera()


def test_optical_axis_hits_the_image_centre():
    # Tilted down by beta, the axis meets the ground h / tan(beta) ahead.
    for pan, tilt in ((0.0, 0.4), (0.7, 0.3), (-1.2, 0.9)):
        d = CAM.height / math.tan(tilt)
        point = np.array([[d * math.cos(pan), d * math.sin(pan)]])
        uv, inside = CAM.project(point, pan, tilt)
        np.testing.assert_allclose(uv[0], CAM.centre, atol=1e-9)
        assert inside[0]


def test_ground_projection_inverts_projection():
    rng = np.random.default_rng(0)
    for _ in range(50):
        pan, tilt = rng.uniform(-1.5, 1.5), rng.uniform(0.1, 1.2)
        pts = rng.uniform(-4, 4, (30, 2))
        uv, inside = CAM.project(pts, pan, tilt)
        back = CAM.ground_point(uv[inside], pan, tilt)
        np.testing.assert_allclose(back, pts[inside], atol=1e-9)


def test_field_of_view_and_left_right():
    fov = CAM.hfov
    # Level camera: points just inside / outside half the field of view.
    d = 3.0
    inner = [[d, d * math.tan(0.49 * fov), 0.56]]
    outer = [[d, d * math.tan(0.51 * fov), 0.56]]
    assert CAM.project(np.array(inner), 0.0, 0.0)[1][0]
    assert not CAM.project(np.array(outer), 0.0, 0.0)[1][0]
    # A point to the left appears left of the centre (smaller u); behind: not seen.
    uv, inside = CAM.project(np.array([[2.0, 0.5], [-2.0, 0.0]]), 0.0, 0.3)
    assert uv[0, 0] < CAM.centre[0] and inside[0] and not inside[1]
    assert CAM.vfov < CAM.hfov  # 720 x 625


def test_pan_then_tilt_order_matters():
    p = np.array([[1.5, 1.0, 0.3]])
    a = CAM.project(p, 0.6, 0.5)[0]
    # Tilt first, then pan (the other order) gives another pixel.
    ca, sa, cb, sb = math.cos(0.6), math.sin(0.6), math.cos(0.5), math.sin(0.5)
    rz = np.array([[ca, sa, 0], [-sa, ca, 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, cb, -sb], [0, sb, cb]])
    world = np.array([-p[0, 1], p[0, 0], p[0, 2] - CAM.height])
    cam = rz @ rx @ world
    other = np.array([CAM.centre[0] + CAM.focal_px * cam[0] / cam[1],
                      CAM.centre[1] - CAM.focal_px * cam[2] / cam[1]])
    assert np.hypot(*(a[0] - other)) > 5.0


def test_pixel_error_grows_with_distance():
    errors = []
    for d in (1.0, 2.0, 4.0):
        tilt = math.atan(CAM.height / d)
        uv, _ = CAM.project(np.array([[d, 0.0]]), 0.0, tilt)
        moved = CAM.ground_point(uv + [0.0, -1.0], 0.0, tilt)  # one pixel up
        errors.append(np.hypot(*(moved[0] - [d, 0.0])))
    assert errors[0] < errors[1] < errors[2]
    assert errors[2] / errors[0] > 10  # about quadratic in distance


def test_horizon_and_bad_input():
    uv = np.array([[CAM.centre[0], CAM.centre[1]]])
    assert np.all(np.isnan(CAM.ground_point(uv, 0.0, 0.0)))  # level axis: the horizon
    assert np.all(np.isnan(CAM.ground_point(uv - [0, 50], 0.0, 0.0)))  # above it
    with pytest.raises(ValueError, match="pixels"):
        CAM.ground_point(np.zeros(2), 0.0, 0.0)
    with pytest.raises(ValueError, match="points"):
        CAM.project(np.zeros((2, 4)), 0.0, 0.0)
    with pytest.raises(ValueError, match="hfov"):
        HeadCamera(hfov=4.0)
    with pytest.raises(ValueError, match="height"):
        HeadCamera(height=0.0)


def test_ground_point_on_a_raised_plane():
    # A ball's centre at z = r: projecting it and intersecting the plane z = r gives it back;
    # the ground (z = 0) puts it farther along the same ray, by h / (h - r).
    r = 0.033
    rng = np.random.default_rng(1)
    pts = np.column_stack([rng.uniform(0.5, 4.0, 20), rng.uniform(-1.0, 1.0, 20),
                           np.full(20, r)])
    uv, inside = CAM.project(pts, 0.2, 0.4)
    assert inside.sum() > 5
    back = CAM.ground_point(uv[inside], 0.2, 0.4, plane_height=r)
    np.testing.assert_allclose(back, pts[inside, 0:2], atol=1e-9)
    ground = CAM.ground_point(uv[inside], 0.2, 0.4)
    np.testing.assert_allclose(ground, pts[inside, 0:2] * CAM.height / (CAM.height - r),
                               atol=1e-9)
    # A plane above the camera is met by rays pointing up, never by rays pointing down.
    up = CAM.ground_point(np.array([[360.0, 0.0], [360.0, 600.0]]), 0.0, 0.0, plane_height=1.0)
    assert np.all(np.isfinite(up[0])) and up[0, 0] > 0 and np.all(np.isnan(up[1]))
    with pytest.raises(ValueError, match="plane_height"):
        CAM.ground_point(uv, 0.0, 0.0, plane_height=math.nan)
