"""The head-camera sensor: what is seen (field of view, range, occlusion), where it is projected
(believed head angles against the true, swaying ones), noise, timing, spurious balls, landmarks
and presets."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest

from estimators import HeadCamera
from soccer_env import presets
from soccer_env.presets.sensors import HEAD_CAMERAS, head_camera
from soccer_env.sensors.headcam import LANDMARK_KINDS, HeadCameraSensor, field_landmarks
from soccer_env.state import HeadState, WorldState

FIELD = presets.field("humanoid-2012")
BALL = presets.ball("ssl")
R = 0.1  # robot radius [m]
AWAY = (-10.0, -10.0, 0.0)  # a ball nobody looks at


def scene(poses, ball=AWAY, t=0.0, teams=None):
    robots = np.zeros((len(poses), 6))
    robots[:, 0:3] = poses
    teams = np.zeros(len(poses), dtype=int) if teams is None else np.asarray(teams)
    return WorldState(t, np.array([*ball, 0.0, 0.0, 0.0]), robots,
                      tuple(f"r{i}" for i in range(len(poses))), teams)


def make(spec, n, observers=(0,), teams=None):
    teams = [0] * n if teams is None else teams
    return HeadCameraSensor(spec, FIELD, BALL, [R] * n, teams, observers)


def heads(n, pan=0.0, tilt=0.0, sway_pan=0.0, sway_tilt=0.0, blind=False):
    full = np.broadcast_to
    return HeadState(full(np.asarray(pan, float), (n,)).copy(),
                     full(np.asarray(tilt, float), (n,)).copy(),
                     full(np.asarray(sway_pan, float), (n,)).copy(),
                     full(np.asarray(sway_tilt, float), (n,)).copy(),
                     full(np.asarray(blind, bool), (n,)).copy())


def to_robot(pose, point):
    """Field point -> robot frame of ``pose``."""
    x, y, th = pose
    dx, dy = point[0] - x, point[1] - y
    return np.array([math.cos(th) * dx + math.sin(th) * dy,
                     -math.sin(th) * dx + math.cos(th) * dy])


def one_frame(sensor, state, hs, seed=0):
    sensor.reset(state, hs, np.random.default_rng(seed))
    frames = sensor.step(state._replace(time=state.time + 0.02), hs)
    assert len(frames) == len(sensor.observers)
    return frames[0]


def landmark_points(frame):
    return [(k, np.array([x, y])) for k, _, _, x, y, _ in frame.landmarks]


# --------------------------------------------------------------------------------------------
# What is seen, and where
# --------------------------------------------------------------------------------------------


def test_landmark_straight_ahead_is_seen_at_its_true_position():
    # The front corner of the yellow goal area (2.4, 1.1), 1 m ahead, on the optical axis.
    pose = (1.4, 1.1, 0.0)
    tilt = math.atan(0.56 / 1.0)
    frame = one_frame(make(head_camera("ideal"), 1), scene([pose]), heads(1, 0.0, tilt))
    ahead = [d for d in frame.landmarks if abs(d[5]) < 1e-6]  # the corner, the T behind it
    assert [d[0] for d in ahead] == ["L", "T"]
    kind, u, v, x, y, bearing = ahead[0]
    np.testing.assert_allclose([x, y], [1.0, 0.0], atol=1e-9)
    np.testing.assert_allclose([u, v], HeadCamera().centre, atol=1e-6)
    assert frame.pan == 0.0 and frame.tilt == tilt


def test_ideal_detections_are_exactly_what_the_pinhole_model_sees():
    """For random poses and head angles, the landmarks reported are those whose projection
    (estimators.HeadCamera, the filters' model) lies in the image, at their true
    robot-frame positions; the ball likewise, projected onto its centre's plane."""
    rng = np.random.default_rng(5)
    spec = head_camera("ideal")
    cam = spec.camera
    lm, kinds = field_landmarks(FIELD, True)
    sensor = make(spec, 1)
    seen_total = 0
    for _ in range(30):
        pose = (rng.uniform(-2.5, 2.5), rng.uniform(-1.8, 1.8), rng.uniform(-math.pi, math.pi))
        pan, tilt = rng.uniform(-1.5, 1.5), rng.uniform(0.1, 0.9)
        ball = (rng.uniform(-3, 3), rng.uniform(-2, 2), 0.0)
        frame = one_frame(sensor, scene([pose], ball), heads(1, pan, tilt))
        rel = np.array([to_robot(pose, p) for p in lm])
        uv, inside = cam.project(rel, pan, tilt)
        assert [d[0] for d in frame.landmarks] == [kinds[i] for i in np.flatnonzero(inside)]
        for d, i in zip(frame.landmarks, np.flatnonzero(inside)):
            np.testing.assert_allclose(d[1:3], uv[i], atol=1e-6)
            np.testing.assert_allclose(d[3:5], rel[i], atol=1e-9)
            assert d[5] == pytest.approx(math.atan2(rel[i, 1], rel[i, 0]), abs=1e-9)
        b = to_robot(pose, ball)
        b_in = cam.project(np.array([[b[0], b[1], BALL.radius]]), pan, tilt)[1][0]
        assert len(frame.balls) == int(b_in)
        if b_in:
            np.testing.assert_allclose(frame.balls[0][2:4], b, atol=1e-9)
        seen_total += len(frame.landmarks) + len(frame.balls)
    assert seen_total > 20  # the test saw something


def test_outside_the_view_or_beyond_range_is_not_seen():
    corner = (2.4, 1.1)
    tilt = math.atan(0.56 / 1.0)

    def sees_corner(pose, pan=0.0, **overrides):
        frame = one_frame(make(head_camera("ideal", **overrides), 1), scene([pose]),
                          heads(1, pan, tilt))
        target = to_robot(pose, corner)
        return any(np.allclose(p, target, atol=1e-6) for _, p in landmark_points(frame))

    assert sees_corner((1.4, 1.1, 0.0))
    assert not sees_corner((3.4, 1.1, 0.0))  # behind the robot
    assert not sees_corner((1.4, 1.1, 0.0), pan=0.6)  # 0.6 rad to the side, fov +-0.45
    assert sees_corner((1.4, 1.1, 0.0), pan=0.4)
    assert not sees_corner((1.4, 1.1, 0.0), landmark_range=0.95)
    assert sees_corner((1.4, 1.1, 0.0), landmark_range=1.05)


def test_robots_hide_what_is_behind_them_and_are_seen_by_their_feet():
    ball = (2.0, 0.0, 0.0)  # 2 m ahead of the observer at the origin
    tilt = math.radians(23.5)  # the ball and a foot 0.9 m ahead both in the image

    def frame(blocker, **overrides):
        state = scene([(0.0, 0.0, 0.0), blocker], ball, teams=[0, 1])
        sensor = make(head_camera("ideal", **overrides), 2, teams=[0, 1])
        return one_frame(sensor, state, heads(2, 0.0, tilt))

    blocked = frame((1.0, 0.0, 2.0))
    assert blocked.balls == ()
    assert len(blocked.robots) == 1
    team, _, _, x, y, bearing = blocked.robots[0]
    assert team == 1  # team from markers
    np.testing.assert_allclose([x, y, bearing], [1.0 - R, 0.0, 0.0], atol=1e-9)
    clear = frame((1.0, 0.3, 2.0))  # 0.3 m aside: the line of sight passes 0.2 m from it
    assert len(clear.balls) == 1
    np.testing.assert_allclose(clear.balls[0][2:4], [2.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(clear.robots[0][3:5], to_robot((0, 0, 0), (1.0, 0.3))
                               * (1 - R / math.hypot(1.0, 0.3)), atol=1e-9)
    assert len(frame((1.0, 0.0, 2.0), occlusion=False).balls) == 1


@pytest.mark.parametrize("preset", ["kidsize", "ideal"])
def test_a_blind_robot_produces_no_frames(preset):
    state = scene([(0.0, 0.0, 0.0), (1.0, 1.0, 0.0)])
    sensor = make(head_camera(preset), 2, observers=(0, 1))
    hs = heads(2, 0.0, 0.4, blind=[True, False])
    warm = sensor.reset(state, hs, np.random.default_rng(0))
    frames = list(warm)
    for k in range(1, 61):
        frames += sensor.step(state._replace(time=k / 60), hs)
    assert {f.robot for f in frames} == {1}
    assert len(frames) > 25
    # Up again: it sees from its next frame on.
    frames = [f for k in range(61, 81)
              for f in sensor.step(state._replace(time=k / 60), heads(2, 0.0, 0.4))]
    assert {f.robot for f in frames} == {0, 1}


def test_a_raised_ball_is_projected_farther_and_pixels_above_the_horizon_have_no_range():
    spec = head_camera("ideal")
    tilt = math.atan(0.56 / 2.0)
    r = BALL.radius
    for z in (0.0, 0.2):
        frame = one_frame(make(spec, 1), scene([(0.0, 0.0, 0.0)], (2.0, 0.0, z)),
                          heads(1, 0.0, tilt))
        (_, _, x, y, bearing), = frame.balls
        # The ray through the centre (height z + r) meets the plane z = r farther away.
        assert x == pytest.approx(2.0 * (0.56 - r) / (0.56 - r - z), abs=1e-9)
        assert y == pytest.approx(0.0, abs=1e-9) and bearing == pytest.approx(0.0, abs=1e-9)
    # A landmark 5.6 m ahead (0.0997 rad below the horizon) seen with a true tilt of 0.02 rad,
    # while the robot believes -0.13 (a 0.15 rad sway): its pixel lies above the believed
    # horizon, so no ground point, but its bearing is still known.
    pose = (3.0 - 5.6, 0.775, 0.0)  # facing the left post of the yellow goal
    frame = one_frame(make(spec, 1), scene([pose]), heads(1, 0.0, -0.13, sway_tilt=0.15))
    post = [d for d in frame.landmarks if d[0] == "post_yellow" and abs(d[5]) < 1e-9]
    assert len(post) == 1 and math.isnan(post[0][3]) and math.isnan(post[0][4])


# --------------------------------------------------------------------------------------------
# Errors
# --------------------------------------------------------------------------------------------


def test_sway_makes_the_range_error_grow_with_distance():
    """Two robots look at the same ball, one from 1 m and one from 4 m, with the same unknown
    tilt sway: the ground projection's range error is many times larger far away."""
    poses = [(-1.0, 0.0, 0.0), (4.0, 0.0, math.pi)]
    state = scene(poses, (0.0, 0.0, 0.0))
    tilts = [math.atan(0.54 / 1.0), math.atan(0.54 / 4.0)]
    sensor = make(head_camera("ideal"), 2, observers=(0, 1))
    rng = np.random.default_rng(2)
    sensor.reset(state, heads(2, 0.0, tilts), np.random.default_rng(0))
    errors = {0: [], 1: []}
    for k in range(1, 201):
        sway = rng.normal(0.0, 0.01)
        for f in sensor.step(state._replace(time=k / 60), heads(2, 0.0, tilts, 0.0, sway)):
            (_, _, x, y, _), = f.balls
            assert f.tilt == tilts[f.robot]  # the frame carries the believed angle
            errors[f.robot].append(abs(math.hypot(x, y) - (1.0, 4.0)[f.robot]))
    near, far = np.mean(errors[0]), np.mean(errors[1])
    assert len(errors[0]) == len(errors[1]) == 200
    assert 0.005 < near < 0.05  # about 2.3 m/rad * 0.008 rad
    assert far > 6.0 * near  # about 29 m/rad: the error grows with d^2 / h


@pytest.mark.parametrize("distance", [0.8, 2.5, 3.8])
def test_a_standing_robots_ball_range_is_off_by_under_two_percent(distance):
    """Without sway, the ground projection's range errs only by the pixel noise: under 2 %
    standard deviation up to 4 m for ``kidsize-2012`` (the line tracker's least relative range
    error, ``soccer_env.perception.brain``)."""
    spec = head_camera("kidsize-2012", frame_rate=None, latency=0.0, ball_detection=1.0,
                       false_ball_rate=0.0)
    pose = (-distance, 0.0, 0.0)
    state = scene([pose], (0.0, 0.0, 0.0))
    hs = heads(1, 0.0, math.atan(spec.height / distance))
    sensor = make(spec, 1)
    sensor.reset(state, hs, np.random.default_rng(7))
    rel = []
    for k in range(1, 301):
        (frame,) = sensor.step(state._replace(time=k / 60), hs)
        (_, _, x, y, _), = frame.balls
        rel.append(math.hypot(x, y) / distance - 1.0)
    assert 0.0 < np.std(rel) < 0.02
    assert abs(np.mean(rel)) < 0.005


def test_pixel_noise_statistics():
    spec = head_camera("kidsize-2012", frame_rate=None, latency=0.0, landmark_detection=1.0,
                       ball_detection=1.0, false_ball_rate=0.0)
    pose, pan, tilt = (1.4, 1.1, 0.0), 0.0, math.atan(0.56 / 1.0)
    state = scene([pose])
    lm, _ = field_landmarks(FIELD, True)
    rel = np.array([to_robot(pose, p) for p in lm])
    uv_true, inside = spec.camera.project(rel, pan, tilt)
    sensor = make(spec, 1)
    hs = heads(1, pan, tilt)
    sensor.reset(state, hs, np.random.default_rng(4))
    err = []
    for k in range(1, 401):
        (frame,) = sensor.step(state._replace(time=k / 60), hs)
        got = np.array([d[1:3] for d in frame.landmarks])
        err.append(got - uv_true[inside])
    err = np.concatenate(err)
    assert len(err) >= 400
    assert np.std(err, axis=0) == pytest.approx([2.0, 2.0], rel=0.08)
    assert np.abs(np.mean(err, axis=0)).max() < 0.25
    assert abs(np.corrcoef(err.T)[0, 1]) < 0.1


def test_spurious_balls_appear_at_the_configured_rate_on_the_ground_in_view():
    spec = head_camera("kidsize-2012", latency=0.0, ball_detection=0.0, false_ball_rate=25.0)
    state = scene([(0.0, 0.0, 0.0)], (1.0, 0.0, 0.0))  # the true ball is never detected
    hs = heads(1, 0.3, 0.35)
    sensor = make(spec, 1)
    sensor.reset(state, hs, np.random.default_rng(6))
    frames = []
    for k in range(1, 1201):
        frames += sensor.step(state._replace(time=k / 60), hs)
    assert len(frames) == pytest.approx(20 * 25, abs=2)
    with_ball = [f for f in frames if f.balls]
    assert len(with_ball) / len(frames) == pytest.approx(1 - math.exp(-1.0), abs=0.05)
    reach = spec.ball_range / math.cos(spec.hfov / 2) + 1e-9
    for f in with_ball:
        (u, v, x, y, bearing), = f.balls
        assert 0 <= u <= spec.width and 0 <= v <= spec.height_px
        assert 0 < math.hypot(x, y) <= reach and bearing == pytest.approx(math.atan2(y, x))
        # A ball lying there would be seen at that pixel.
        uv, inside = spec.camera.project(np.array([[x, y, BALL.radius]]), 0.3, 0.35)
        assert inside[0] and np.allclose(uv[0], [u, v], atol=1e-6)
    assert max(math.hypot(*f.balls[0][2:4]) for f in with_ball) > 0.8 * spec.ball_range


# --------------------------------------------------------------------------------------------
# Timing and reproducibility
# --------------------------------------------------------------------------------------------


def run(sensor, state, hs, steps, dt=1 / 60):
    """All frames returned by ``steps`` steps, each with the time of the step returning it."""
    out = []
    for k in range(1, steps + 1):
        now = state.time + k * dt
        out += [(now, f) for f in sensor.step(state._replace(time=now), hs)]
    return out


def test_frame_rate_latency_and_delivery_order():
    spec = head_camera("kidsize-2012")  # 25 Hz, 40 ms
    state = scene([(0.0, 0.0, 0.0), (1.0, 1.0, 1.0)])
    hs = heads(2, 0.0, 0.4)
    sensor = make(spec, 2, observers=(0, 1))
    warm = sensor.reset(state, hs, np.random.default_rng(1))
    assert [f.robot for f in warm] == [0, 1]
    assert all(f.t_capture == pytest.approx(-0.04) and f.t_delivered == 0.0 for f in warm)
    got = run(sensor, state, hs, 240)  # 4 s at 60 Hz
    for robot in (0, 1):
        caps = np.array([f.t_capture for _, f in got if f.robot == robot])
        assert 98 <= len(caps) <= 100  # 25 frames/s, minus those still in flight
        steps = np.round(np.diff(caps) * 60).astype(int)  # captured at step times
        assert set(steps) <= {2, 3} and np.mean(np.diff(caps)) == pytest.approx(0.04, rel=0.02)
    for now, f in got:
        assert f.t_delivered == pytest.approx(f.t_capture + 0.04)
        assert f.t_delivered <= now + 1e-12 and f.t_delivered > now - 1 / 60 - 1e-12
    # With jitter, frames come out of order of capture but in order of delivery.
    jittery = make(head_camera("kidsize", latency_jitter=0.05), 2, observers=(0, 1))
    jittery.reset(state, hs, np.random.default_rng(1))
    got = run(jittery, state, hs, 240)
    delivered = [f.t_delivered for _, f in got]
    delays = np.array([f.t_delivered - f.t_capture for _, f in got])
    assert delivered == sorted(delivered)
    assert delays.min() >= 0.05 - 1e-12 and delays.max() <= 0.1 + 1e-12
    assert delays.std() > 0.01
    captures = [f.t_capture for _, f in got]
    assert captures != sorted(captures)


def test_detections_agree_with_the_filters_camera_model():
    """With noise and sway, every detection's ground point and bearing are what
    HeadCamera.ground_point gives for its pixel and the frame's (believed) head angles."""
    spec = head_camera("kidsize", false_ball_rate=10.0)
    cam = spec.camera
    poses = [(0.0, 0.0, 0.0), (1.5, 0.3, 2.0), (-1.0, -0.5, 0.3)]
    state = scene(poses, (1.0, 0.1, 0.0), teams=[0, 1, 1])
    hs = heads(3, [0.1, -0.2, 0.4], [0.45, 0.3, 0.5], 0.02, -0.03)
    sensor = make(spec, 3, observers=(0, 1, 2), teams=[0, 1, 1])
    sensor.reset(state, hs, np.random.default_rng(8))
    n = 0
    for _, f in run(sensor, state, hs, 60):
        for plane, dets in ((BALL.radius, f.balls), (0.0, [d[1:] for d in f.landmarks]),
                            (0.0, [d[1:] for d in f.robots])):
            for u, v, x, y, bearing in dets:
                g = cam.ground_point(np.array([[u, v]]), f.pan, f.tilt, plane_height=plane)
                np.testing.assert_allclose([x, y], g[0], atol=1e-9)
                assert bearing == pytest.approx(math.atan2(y, x), abs=1e-9)
                n += 1
    assert n > 50


def test_same_seed_same_frames():
    spec = head_camera("kidsize", false_ball_rate=5.0)
    poses = [(0.0, 0.0, 0.0), (1.0, 0.2, 3.0), (-1.0, 1.0, -0.5), (2.0, -1.0, 2.5)]
    state = scene(poses, (0.8, 0.1, 0.0), teams=[0, 0, 1, 1])
    hs = heads(4, [0.0, 0.3, -0.4, 0.1], [0.4, 0.5, 0.3, 0.6], 0.01, -0.01)

    def frames(seed):
        sensor = make(spec, 4, observers=(0, 1, 2, 3), teams=[0, 0, 1, 1])
        warm = sensor.reset(state, hs, np.random.default_rng(seed))
        return repr(warm + [f for _, f in run(sensor, state, hs, 60)])

    assert frames(3) == frames(3)
    assert frames(3) != frames(4)


# --------------------------------------------------------------------------------------------
# Landmarks and presets
# --------------------------------------------------------------------------------------------


def test_field_landmarks_of_the_2012_humanoid_field():
    pts, kinds = field_landmarks(FIELD, distinct_goals=True)
    assert pts.shape == (20, 2) and len(kinds) == 20 and set(kinds) <= set(LANDMARK_KINDS)
    assert Counter(kinds) == {"post_blue": 2, "post_yellow": 2, "L": 8, "T": 6, "X": 2}
    items = {(k, round(x, 9), round(y, 9)) for k, (x, y) in zip(kinds, pts.tolist())}
    assert len(items) == 20
    swap = {"post_blue": "post_yellow", "post_yellow": "post_blue"}
    assert {(swap.get(k, k), -x, y) for k, x, y in items} == items  # mirror in x (goals swap)
    assert {(k, x, -y) for k, x, y in items} == items  # mirror in y
    assert ("post_yellow", 3.0, 0.775) in items  # post centre: 1.5 / 2 + 0.05 / 2
    assert ("L", 2.4, 1.1) in items and ("L", -3.0, -2.0) in items
    assert ("T", 3.0, 1.1) in items and ("T", 0.0, 2.0) in items
    assert ("X", 0.0, 0.6) in items


def test_distinct_goals_changes_post_kinds():
    _, kinds = field_landmarks(FIELD, distinct_goals=False)
    assert Counter(kinds)["post"] == 4 and "post_blue" not in kinds
    pose = (1.0, 0.0, 0.0)  # facing the yellow goal 2 m away
    tilt = math.atan(0.56 / 2.0)
    for distinct, kind in ((True, "post_yellow"), (False, "post")):
        spec = head_camera("ideal", distinct_goals=distinct)
        frame = one_frame(make(spec, 1), scene([pose]), heads(1, 0.0, tilt))
        posts = [d[0] for d in frame.landmarks if d[0].startswith("post")]
        assert posts == [kind, kind]


def test_presets_match_their_sources():
    old = HEAD_CAMERAS["kidsize-2012"]
    assert (old.height, old.width, old.height_px, old.frame_rate) == (0.56, 720, 625, 25.0)
    assert old.hfov == pytest.approx(math.radians(51.0)) and old.distinct_goals
    assert old.landmark_range == 4.0  # Guo and Li (2013)
    assert not head_camera("kidsize").distinct_goals
    ideal = head_camera("ideal")
    assert ideal.occlusion and ideal.pixel_sigma == 0.0 and ideal.false_ball_rate == 0.0
    assert head_camera(old) is old


@pytest.mark.parametrize("name, value", [
    ("height", 0.0), ("hfov", 0.0), ("hfov", 4.0), ("width", 1), ("height_px", 2.5),
    ("frame_rate", 0.0), ("latency", -0.01), ("latency_jitter", 3.0), ("pixel_sigma", -1.0),
    ("ball_range", 0.0), ("landmark_range", math.inf), ("robot_range", -1.0),
    ("ball_detection", 1.5), ("landmark_detection", -0.1), ("robot_detection", math.nan),
    ("false_ball_rate", -1.0), ("occlusion", 1), ("distinct_goals", "yes"),
])
def test_bad_spec_values_raise_naming_the_field(name, value):
    with pytest.raises(ValueError, match=rf"head_camera\.{name} must"):
        head_camera("kidsize", **{name: value})


def test_bad_names_and_sensor_arguments():
    with pytest.raises(ValueError, match="unknown head_camera preset"):
        head_camera("kidsize-2099")
    with pytest.raises(TypeError, match="unknown head_camera parameter"):
        head_camera("kidsize", fov=1.0)
    spec = head_camera("ideal")
    with pytest.raises(ValueError, match="observers"):
        HeadCameraSensor(spec, FIELD, BALL, [R, R], [0, 1], [2])
    with pytest.raises(ValueError, match="teams"):
        HeadCameraSensor(spec, FIELD, BALL, [R, R], [0, 2], [0])
    with pytest.raises(ValueError, match="robot_radii"):
        HeadCameraSensor(spec, FIELD, BALL, [R, -R], [0, 1], [0])
    sensor = HeadCameraSensor(spec, FIELD, BALL, [R, R], [0, 1], [0])
    with pytest.raises(ValueError, match="heads.tilt"):
        sensor.reset(scene([(0, 0, 0), (1, 0, 0)]),
                     heads(2)._replace(tilt=np.zeros(3)), np.random.default_rng(0))
