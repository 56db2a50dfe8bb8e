"""The overhead vision's capture kernel (soccer_env.sensors.overhead_kernels) against
closed-form expectations: visibility per camera, detection against the drawn uniforms, noise
from the given normals, occlusion by robots, spurious balls, delivery times, interpolation."""

import math

import numpy as np
import pytest

from estimators.exact import floor_remainder, wrap_angle
from soccer_env.sensors.overhead_kernels import (
    PARAMS,
    RING,
    capture_frames,
    frame_columns,
    hidden_fraction,
    interpolate_poses,
)

R_BALL = 0.0215
SSL_BODY = (0.08 + R_BALL, 0.15, 0.09)  # dribbler reach [m], height [m], radius [m]
CAMERA = (0.0, 0.0, 4.0, -5.0, 5.0, -4.0, 4.0)


def figures(**overrides):
    """Kernel parameters: everything detected, no noise, no spurious balls, no occlusion."""
    base = {"ball_radius": R_BALL, "robot_detection": 1.0, "ball_detection": 1.0,
            "p_dribbler": 0.0, "p_random": 0.0, "robot_sigma": 0.0, "robot_sigma_theta": 0.0,
            "ball_sigma": 0.0, "occlusion_threshold": 2.0, "latency": 0.0,
            "latency_jitter": 0.0}
    base.update(overrides)
    return np.array([base[k] for k in PARAMS])


def capture(ball, robots, cams=(0,), times=None, cameras=(CAMERA,), bodies=None,
            normals=None, uniforms=None, clock=(0.0, 0.0), ball1=None, robots1=None, **kw):
    """One state's frames: ``ball`` ``(x, y, z)``, ``robots`` ``(N, 3)`` poses (the same at
    the step's end unless ``ball1``, ``robots1``); returns the decoded frames."""
    robots = np.asarray(robots, dtype=np.float64).reshape(-1, 3)
    n, F = len(robots), len(cams)
    times = np.zeros(F) if times is None else np.asarray(times, dtype=np.float64)
    bodies = np.array([SSL_BODY] * n).reshape(n, 3) if bodies is None else np.asarray(bodies)
    # Uniforms default to 0.5 (under every probability of 1, over every one of 0).
    normals = np.zeros(F * 3 * (n + 2)) if normals is None else np.asarray(normals, float)
    uniforms = np.full(F * (2 * n + 5), 0.5) if uniforms is None else np.asarray(uniforms, float)
    b0 = np.array([ball], dtype=np.float64)
    b1 = b0 if ball1 is None else np.array([ball1], dtype=np.float64)
    r1 = robots if robots1 is None else np.asarray(robots1, dtype=np.float64).reshape(-1, 3)
    out = np.full((F + 1, frame_columns(n)[4]), 7.0)  # a spare row the kernel must not touch
    capture_frames(np.zeros(F, dtype=np.int64), np.asarray(cams, dtype=np.int64), times,
                   np.array([clock]), b0, b1, robots[None], r1[None], normals, uniforms,
                   np.array(cameras, dtype=np.float64), bodies, figures(**kw), out)
    assert (out[F] == 7.0).all()
    _, b, r, p, width = frame_columns(n)
    assert width == 7 * n + 7
    return [{"delivered": row[0], "ball_seen": row[1:b] == 1.0,
             "balls": row[b:r].reshape(n + 2, 2), "robot_seen": row[r:p] == 1.0,
             "poses": row[p:].reshape(n, 3)} for row in out[:F]]


def test_a_ball_is_seen_by_the_cameras_whose_view_holds_it():
    left = (-2.0, 0.0, 4.0, -4.0, 0.25, -3.0, 3.0)
    right = (2.0, 0.0, 4.0, -0.25, 4.0, -3.0, 3.0)
    for x, seen in ((-1.0, [True, False]), (1.0, [False, True]), (0.0, [True, True])):
        frames = capture((x, 0.5, 0.0), np.zeros((0, 3)), cams=(0, 1), cameras=(left, right))
        assert [bool(f["ball_seen"][0]) for f in frames] == seen, x
        for f, s in zip(frames, seen):
            assert f["balls"][0].tolist() == ([x, 0.5] if s else [0.0, 0.0])
    # A robot is seen only inside the view too.
    frames = capture((9.0, 9.0, 0.0), [(-1.0, 0.0, 0.0)], cams=(0, 1), cameras=(left, right))
    assert [bool(f["robot_seen"][0]) for f in frames] == [True, False]


def test_a_chipped_ball_is_seen_along_the_camera_ray():
    z = 1.0
    f, = capture((1.0, 0.0, z), np.zeros((0, 3)))
    k = (4.0 - R_BALL) / (4.0 - (R_BALL + z))
    assert f["balls"][0].tolist() == [0.0 + (1.0 - 0.0) * k, 0.0]


def test_a_detection_is_dropped_when_its_uniform_exceeds_the_probability():
    robots = [(0.5, 0.5, 0.0), (-0.5, 0.5, 0.0)]
    n = 2
    u = np.full(2 * n + 5, 0.5)
    u[0], u[1], u[2 * n] = 0.3, 0.7, 0.59  # robot 0 under 0.6, robot 1 over, the ball under
    f, = capture((1.0, 1.0, 0.0), robots, uniforms=u, robot_detection=0.6, ball_detection=0.6)
    assert f["robot_seen"].tolist() == [True, False] and f["ball_seen"][0]
    u[2 * n] = 0.61
    f, = capture((1.0, 1.0, 0.0), robots, uniforms=u, robot_detection=0.6, ball_detection=0.6)
    assert not f["ball_seen"].any() and f["balls"].tolist() == [[0.0, 0.0]] * (n + 2)
    assert f["poses"][1].tolist() == [0.0, 0.0, 0.0]


def test_noise_is_sigma_times_the_given_normals():
    n = 1
    normals = np.arange(1.0, 3 * (n + 2) + 1) / 10.0  # 0.1, 0.2, ... distinct
    x, y, th = 0.7, -0.3, 3.13
    s, st, sigma = 0.002, 0.05, 0.004
    f, = capture((1.25, -0.5, 0.0), [(x, y, th)], normals=normals, robot_sigma=s,
                 robot_sigma_theta=st, ball_sigma=sigma)
    assert f["poses"][0].tolist() == [x + s * 0.1, y + s * 0.2, wrap_angle(th + st * 0.3)]
    assert f["poses"][0][2] < 0  # 3.13 + 0.015 wrapped past pi
    assert f["balls"][0].tolist() == [1.25 + sigma * normals[3 * n + 3],
                                      -0.5 + sigma * normals[3 * n + 4]]


def test_spurious_balls_at_dribblers_and_anywhere_and_the_delivery_time():
    n = 2
    robots = [(1.0, 0.0, 0.0), (-1.0, 1.0, math.pi / 2)]
    u = np.full(2 * n + 5, 0.5)
    u[n], u[n + 1] = 0.01, 0.01  # both robots' dribbler draws under p_dribbler
    u[2 * n + 1], u[2 * n + 2], u[2 * n + 3], u[2 * n + 4] = 0.01, 0.25, 0.75, 0.5
    normals = np.zeros(3 * (n + 2))
    normals[3 * n], normals[3 * n + 1] = 1.0, -1.0
    sigma = 0.01
    bodies = [SSL_BODY, (math.nan, 0.6, 0.1)]  # robot 1 has no dribbler (a humanoid)
    f, = capture((9.0, 9.0, 0.0), robots, uniforms=u, normals=normals, bodies=bodies,
                 times=[2.0], p_dribbler=0.05, p_random=0.05, ball_sigma=sigma, latency=0.1,
                 latency_jitter=0.02)
    d = SSL_BODY[0]
    assert f["ball_seen"].tolist() == [False, True, False, True]
    assert f["balls"][1].tolist() == [1.0 + d * math.cos(0.0) + sigma * 1.0,
                                      0.0 + d * math.sin(0.0) + sigma * -1.0]
    x0, x1, y0, y1 = CAMERA[3:]
    assert f["balls"][n + 1].tolist() == [x0 + (x1 - x0) * 0.25, y0 + (y1 - y0) * 0.75]
    assert f["delivered"] == 2.0 + (0.1 + 0.02 * 0.5)


def test_a_ball_behind_a_robot_is_hidden_from_the_camera_and_not_in_front():
    """Camera 4 m above the origin, an SSL robot at x = 2 m: a ball just beyond it (seen from
    the camera) is hidden, one just before it is not."""
    gap = SSL_BODY[2] + R_BALL + 0.002
    robot = [(2.0, 0.0, 0.0)]
    seen = {x: bool(capture((x, 0.0, 0.0), robot, occlusion_threshold=0.4)[0]["ball_seen"][0])
            for x in (2.0 + gap, 2.0 - gap, 0.5)}
    assert seen == {2.0 + gap: False, 2.0 - gap: True, 0.5: True}
    # Occlusion off (threshold above 1): seen wherever it is.
    assert capture((2.0 + gap, 0.0, 0.0), robot)[0]["ball_seen"][0]


def test_hidden_fraction_closed_form():
    cam = np.array(CAMERA)
    X, Y = np.array([2.0]), np.array([0.0])
    tall, radius = np.array([0.6]), np.array([0.1])
    # The humanoid's shadow on the ball's plane reaches 2 (4 - zc) / (4 - 0.6) = 2.34 m, its
    # capsule 0.117 m wide: a ball at 2.2 m is inside it whole.
    assert hidden_fraction(2.2, 0.0, R_BALL, X, Y, cam, R_BALL, tall, radius) == 1.0
    assert hidden_fraction(1.5, 0.0, R_BALL, X, Y, cam, R_BALL, tall, radius) == 0.0
    # Above the robot's top it cannot be hidden.
    assert hidden_fraction(2.2, 0.0, 0.7, X, Y, cam, R_BALL, tall, radius) == 0.0
    # Half covered: the ring points on the robot's side of the shadow's edge line.
    zc = R_BALL
    k = (4.0 - zc) / (4.0 - 0.6)
    edge = 0.1 * k
    by = edge  # the ball's centre on the capsule's edge (beside the shadow's axis)
    got = hidden_fraction(2.2, by, zc, X, Y, cam, R_BALL, tall, radius)
    expected = sum(oy * R_BALL + by <= edge for _, oy in RING) / len(RING)
    assert got == pytest.approx(expected, abs=1.5 / len(RING))
    assert 0.0 < got < 1.0


def test_interpolation_to_the_capture_time_on_the_short_arc():
    prev = np.array([[0.0, 0.0, 3.0]])
    cur = np.array([[1.0, -2.0, -3.0]])  # crossing pi: the short way is +0.28 rad
    X, Y, TH = np.empty(1), np.empty(1), np.empty(1)
    interpolate_poses(0.25, prev, cur, True, X, Y, TH)
    turn = math.remainder(-6.0, 2 * math.pi)
    assert (X[0], Y[0], TH[0]) == (0.25, -0.5, 3.0 + 0.25 * turn)
    # Through the kernel: capture at t = 0.25 of a step from 0 to 1 s, no noise.
    f, = capture((0.0, 0.0, 0.0), prev, times=[0.25], clock=(0.0, 1.0), ball1=(1.0, 1.0, 0.0),
                 robots1=cur)
    assert f["poses"][0].tolist() == [0.25, -0.5, wrap_angle(3.0 + 0.25 * turn)]
    assert f["balls"][0].tolist() == [0.25, 0.25]
    # A step of length 0 is at its end.
    f, = capture((0.0, 0.0, 0.0), prev, times=[5.0], clock=(5.0, 0.0), ball1=(1.0, 1.0, 0.0),
                 robots1=cur)
    assert f["balls"][0].tolist() == [1.0, 1.0] and f["poses"][0][0] == 1.0


def test_the_heading_wrap_follows_the_number_of_poses_captured():
    """A turn of exactly pi: ``math.remainder`` keeps +pi, numpy's floored remainder gives
    -pi. Few poses (frames times robots at most 16) take the first, more the second, as the
    Python and the numpy versions of the sensor did."""
    prev, cur = np.array([[0.0, 0.0, 0.0]]), np.array([[0.0, 0.0, math.pi]])
    X, Y, TH = np.empty(1), np.empty(1), np.empty(1)
    interpolate_poses(0.5, prev, cur, True, X, Y, TH)
    assert TH[0] == math.pi / 2
    interpolate_poses(0.5, prev, cur, False, X, Y, TH)
    assert TH[0] == -math.pi / 2
    for frames, sign in ((16, 1.0), (17, -1.0)):
        got = capture((9.0, 9.0, 0.0), prev, cams=(0,) * frames, times=[0.5] * frames,
                      clock=(0.0, 1.0), robots1=cur)
        assert [f["poses"][0][2] for f in got] == [sign * math.pi / 2] * frames


def test_floor_remainder_is_numpys():
    rng = np.random.default_rng(3)
    a = np.concatenate([rng.normal(0.0, 10.0, 2000), [0.0, -0.0, 2 * math.pi, -math.pi, 1e300]])
    for b in (2 * math.pi, -1.5):
        got = np.array([floor_remainder(x, b) for x in a])
        assert got.tobytes() == np.remainder(a, b).tobytes()
