"""The head camera's compiled kernels, called directly: where an object is projected and
projected back (closed forms of the pinhole model), what hides it, what drops it, and the order
and layout of what they return."""

from __future__ import annotations

import math

import numpy as np
import pytest

from soccer_env.sensors.headcam_kernels import back_project, head_detections

H = 0.56  # camera height [m]
U0, V0 = 360.0, 312.5  # principal point [px] of a 720 x 625 image
F = U0 / math.tan(math.radians(25.5))  # focal length [px] for a 51 degree field of view
R_BALL = 0.043
LENS = (F, U0, V0)


def detect(poses, landmarks=(), ball=(-50.0, -50.0, 0.0), obs=(0,), pan=0.0, tilt=0.0,
           sway_pan=0.0, sway_tilt=0.0, radii=0.2, ranges=100.0, p_detect=1.0, U=None,
           Z=None, sigma=0.0, occlusion=True):
    """Run :func:`head_detections` on robots at ``poses`` and ``landmarks`` (field frame);
    per-robot or scalar head angles, radii; per-slot or scalar ranges and detection
    probabilities. Returns a list of ``(frame, slot, u, v, x, y, bearing)``."""
    n = len(poses)
    robots = np.zeros((n, 6))
    robots[:, :3] = poses
    lm = np.array(landmarks, dtype=np.float64).reshape(-1, 2)
    p = 1 + len(lm) + n
    per_robot = [np.broadcast_to(np.asarray(a, dtype=np.float64), (n,)).copy()
                 for a in (pan, tilt, sway_pan, sway_tilt, radii)]
    radii_a = per_robot[4]
    obs_a = np.array(obs, dtype=np.int64)
    U = np.zeros((len(obs), p + 4)) if U is None else np.asarray(U, dtype=np.float64)
    Z = np.zeros((len(obs), 2, p)) if Z is None else np.asarray(Z, dtype=np.float64)
    where, found = head_detections(
        robots, np.array([*ball, 0.0, 0.0, 0.0]), obs_a, *per_robot[:4], lm, radii_a,
        radii_a**2, np.broadcast_to(np.asarray(ranges, dtype=np.float64) ** 2, (p,)).copy(),
        np.broadcast_to(np.asarray(p_detect, dtype=np.float64), (p,)).copy(), U, Z,
        (H, F, U0, V0, R_BALL, sigma), occlusion)
    assert where.shape == (len(found), 2) and found.shape == (len(where), 5)
    return [(k, s, *d) for (k, s), d in zip(where.tolist(), found.tolist())]


# --------------------------------------------------------------------------------------------
# Projection and back-projection
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("d", [1.5, 2.0, 3.5])
def test_a_landmark_straight_ahead_projects_to_the_centre_column_and_back(d):
    """Level camera: a ground point d ahead lies f h / d below the principal point, on its
    column (in the image from 1.35 m on); projected back it is the point itself, at bearing
    0."""
    (k, slot, u, v, x, y, b), = detect([(1.0, 0.5, 0.0)], landmarks=[(1.0 + d, 0.5)])
    assert (k, slot) == (0, 1)
    assert u == pytest.approx(U0, abs=1e-9)
    assert v == pytest.approx(V0 + F * H / d, rel=1e-12)
    assert (x, y, b) == pytest.approx((d, 0.0, 0.0), abs=1e-12)


def test_tilted_so_the_landmark_is_on_the_optical_axis():
    d = 1.6
    (_, _, u, v, x, y, b), = detect([(0.0, 0.0, 0.0)], landmarks=[(d, 0.0)],
                                    tilt=math.atan2(H, d))
    assert (u, v) == pytest.approx((U0, V0), abs=1e-9)
    assert (x, y, b) == pytest.approx((d, 0.0, 0.0), abs=1e-12)


def test_heading_and_pan_turn_the_view_and_the_robot_frame():
    """Robot facing +y (theta = pi/2), head panned 0.3 rad left: a landmark 2 m away along
    the camera's axis is on the centre column, at (2 cos 0.3, 2 sin 0.3) in the robot
    frame."""
    a, d = 0.3, 2.0
    lm = (d * math.cos(math.pi / 2 + a), d * math.sin(math.pi / 2 + a))
    (_, _, u, v, x, y, b), = detect([(0.0, 0.0, math.pi / 2)], landmarks=[lm], pan=a)
    assert u == pytest.approx(U0, abs=1e-9) and v == pytest.approx(V0 + F * H / d, rel=1e-9)
    assert (x, y, b) == pytest.approx((d * math.cos(a), d * math.sin(a), a), abs=1e-12)


def test_an_offset_landmark_and_the_sway_the_robot_does_not_know():
    """A point (d, w) is f w / d left of the centre; an unknown pan sway delta turns what the
    robot computes by -delta about the camera foot."""
    d, w = 2.0, 0.4
    (_, _, u, _, x, y, b), = detect([(0.0, 0.0, 0.0)], landmarks=[(d, w)])
    assert u == pytest.approx(U0 - F * w / d, rel=1e-12)
    assert (x, y, b) == pytest.approx((d, w, math.atan2(w, d)), abs=1e-12)
    delta = 0.05
    (_, _, u, _, x, y, b), = detect([(0.0, 0.0, 0.0)], landmarks=[(d, 0.0)], sway_pan=delta)
    assert u == pytest.approx(U0 + F * math.tan(delta), rel=1e-12)
    assert (x, y, b) == pytest.approx((d * math.cos(delta), -d * math.sin(delta), -delta),
                                      abs=1e-12)


def test_the_ball_is_projected_onto_the_plane_of_its_centre():
    d = 1.5
    (k, slot, u, v, x, y, b), = detect([(0.0, 0.0, 0.0)], ball=(d, 0.0, 0.0))
    assert slot == 0
    assert v == pytest.approx(V0 + F * (H - R_BALL) / d, rel=1e-12)
    assert (x, y, b) == pytest.approx((d, 0.0, 0.0), abs=1e-12)


def test_another_robot_is_seen_by_its_foot_point_nearest_the_observer():
    """Robot 1 (radius 0.25) 2 m ahead and 0.5 m left: its foot point is its centre moved
    0.25 m towards the observer, in slot 1 + M + 1."""
    c = np.array([2.0, 0.5])
    foot = c * (1.0 - 0.25 / np.hypot(*c))
    (k, slot, u, v, x, y, b), = detect([(0.0, 0.0, 0.0), (*c, 1.0)], landmarks=[(-3.0, 0.0)],
                                       radii=[0.2, 0.25])
    assert slot == 1 + 1 + 1
    assert (x, y) == pytest.approx(tuple(foot), abs=1e-12)
    assert v == pytest.approx(V0 + F * H / foot[0], rel=1e-12)


def test_pixel_noise_is_added_before_the_back_projection():
    z = np.zeros((1, 2, 2))
    z[0, :, 1] = (0.5, -1.5)
    (_, _, u, v, x, y, b), = detect([(0.0, 0.0, 0.0)], landmarks=[(2.0, 0.0)], Z=z, sigma=2.0)
    assert u == U0 + 2.0 * 0.5
    assert v == pytest.approx(V0 + F * H / 2.0 + 2.0 * -1.5, rel=1e-15)
    assert (x, y, b) == back_project(u, v, (1.0, 0.0, 1.0, 0.0), LENS, H, 0.0)
    assert x > 2.0 and y < 0.0  # one pixel to the right and three up: farther and right


# --------------------------------------------------------------------------------------------
# What is hidden or dropped
# --------------------------------------------------------------------------------------------


def test_a_robot_in_the_line_of_sight_hides_what_is_behind_it():
    """(Tilted 0.5 rad down: the ground from 0.46 m to 5.8 m ahead is in the image.)"""
    observer, blocker = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)
    behind, aside = (2.0, 0.0), (2.0, 0.6)  # the segment to `aside` passes 0.29 m from it
    got = detect([observer, blocker], landmarks=[behind, aside], radii=[0.3, 0.2], tilt=0.5)
    assert [s for _, s, *_ in got] == [2, 4]  # `aside` and the blocker's own foot point
    got = detect([observer, blocker], landmarks=[behind, aside], radii=[0.3, 0.2], tilt=0.5,
                 occlusion=False)
    assert [s for _, s, *_ in got] == [1, 2, 4]
    # A wider robot hides `aside` too; the observer's own (wider still) disc hides nothing.
    got = detect([observer, blocker], landmarks=[behind, aside], radii=[0.5, 0.3], tilt=0.5)
    assert [s for _, s, *_ in got] == [4]
    # The ball behind it likewise (no landmarks: the blocker's foot point is slot 2).
    for occlusion, slots in ((True, [2]), (False, [0, 2])):
        got = detect([observer, blocker], ball=(2.0, 0.0, 0.0), tilt=0.5, occlusion=occlusion)
        assert [s for _, s, *_ in got] == slots


def test_a_robot_behind_the_object_or_beside_the_line_hides_nothing():
    got = detect([(0.0, 0.0, 0.0), (2.5, 0.0, 0.0), (1.0, 0.45, 0.0)],
                 landmarks=[(2.0, 0.0)], radii=0.2, tilt=0.5)
    assert [s for _, s, *_ in got] == [1, 3, 4]


def test_out_of_range_outside_the_image_behind_or_missed_is_dropped():
    pose = [(0.0, 0.0, 0.0)]
    lms = [(2.0, 0.0), (1.0, 1.0), (-1.0, 0.0), (0.2, 0.0), (3.0, 0.1)]
    # (1, 1): 45 degrees left, outside the +-25.5 degree view; (-1, 0) behind; (0.2, 0) below
    # the image (its pixel 1568 rows below the centre).
    assert [s for _, s, *_ in detect(pose, landmarks=lms)] == [1, 5]
    ranges = [100.0, 2.5, 2.5, 2.5, 2.5, 2.5, 2.5]
    assert [s for _, s, *_ in detect(pose, landmarks=lms, ranges=ranges)] == [1]
    u = np.zeros((1, 7 + 4))
    u[0, 1] = 0.9  # the detection draw of (2, 0) at 0.9, probability 0.9: missed
    assert [s for _, s, *_ in detect(pose, landmarks=lms, U=u, p_detect=0.9)] == [5]
    # The tilt looking up: nothing on the ground is in the image.
    assert detect(pose, landmarks=lms, tilt=-0.6) == []


def test_rows_come_frame_by_frame_and_slot_by_slot_without_oneself():
    poses = [(0.0, 0.0, 0.0), (1.0, 0.0, math.pi), (4.0, 0.0, math.pi)]
    lms = [(0.5, 0.2), (0.5, -0.2)]
    got = detect(poses, landmarks=lms, obs=(2, 0), tilt=0.5, occlusion=False)
    rows = [(k, s) for k, s, *_ in got]
    assert rows == [(0, 1), (0, 2), (0, 3), (0, 4), (1, 1), (1, 2), (1, 4), (1, 5)]
    assert detect(poses, landmarks=lms, obs=()) == []
    # Looking down at its own feet (its foot point, under the camera, would be 290 px above
    # the centre at a 1.2 rad tilt), a robot does not see itself.
    assert detect([(0.0, 0.0, 0.0)], tilt=1.2) == []


# --------------------------------------------------------------------------------------------
# Back-projection alone
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("pan", [0.0, 0.7, -1.2])
def test_the_principal_point_meets_the_ground_at_h_over_tan_tilt(pan):
    tilt = 0.35
    head = (math.cos(pan), math.sin(pan), math.cos(tilt), math.sin(tilt))
    x, y, b = back_project(U0, V0, head, LENS, H, 0.0)
    d = H / math.tan(tilt)
    assert (x, y, b) == pytest.approx((d * math.cos(pan), d * math.sin(pan), pan), abs=1e-12)
    x, y, _ = back_project(U0, V0, head, LENS, H, R_BALL)  # the ball's plane: nearer
    assert math.hypot(x, y) == pytest.approx((H - R_BALL) / math.tan(tilt), rel=1e-12)


def test_at_and_above_the_horizon_there_is_no_ground_point_but_a_bearing():
    """The centre row with the camera level or looking up; a pixel left of the centre column
    by f tan(0.1) has the bearing pan + atan(tan(0.1) / cos(tilt))."""
    for tilt in (0.0, -0.2):
        head = (math.cos(0.4), math.sin(0.4), math.cos(tilt), math.sin(tilt))
        x, y, b = back_project(U0 - F * math.tan(0.1), V0, head, LENS, H, 0.0)
        assert math.isnan(x) and math.isnan(y)
        assert b == pytest.approx(0.4 + math.atan2(math.tan(0.1), math.cos(tilt)), abs=1e-12)
