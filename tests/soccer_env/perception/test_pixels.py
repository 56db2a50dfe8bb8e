"""The ``pixels`` detector: rendered images tracked by Li et al.'s (2010) and Yu et al.'s (2010)
trackers instead of geometric detections, the rest of the stack unchanged."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import soccer_env
from soccer_env.envs.goalkeeper import GoalkeeperEnv

pytest.importorskip("cv2", reason="the pixels detector needs the 'pixels' extra (OpenCV)")

SSL = dict(field="ssl-2012", robot="ssl-2012", obs_mode="perceived")


def ssl_keeper(detector="pixels", **kw):
    return GoalkeeperEnv(**SSL, perception={"vision": "ssl-2012", "detector": detector}, **kw)


def test_overhead_images_track_the_keeper_and_the_ball():
    env = ssl_keeper(shots={"delay": (1.0, 1.0)})
    env.reset(seed=3)
    pose_err, ball_err = [], []
    for _ in range(50):  # the ball lies still until the shot
        _, _, _, _, info = env.step(np.zeros(6, np.float32))
        est, tru = info["estimate"], info["truth"]
        pose_err.append(np.hypot(*(est["robot_pose"]["blue_0"][:2]
                                   - tru["robot_pose"]["blue_0"][:2])))
        ball_err.append(np.hypot(*(est["ball_position"] - tru["ball_position"])))
    assert np.median(pose_err[10:]) < 0.03  # a 640 px image of a 6.6 m field: 1 cm pixels
    assert np.median(ball_err[10:]) < 0.03
    # The camera delivers images, and their detections are weighed by the pixel size.
    pipeline = env.pipelines[0]
    assert type(pipeline.sensor).__name__ == "OverheadImageCamera"
    assert type(pipeline.detector).__name__ == "OverheadPixelDetector"
    assert (pipeline.measurements.ball_model.sigma
            >= pipeline.sensor.renderer.metres_per_pixel - 1e-12)


def test_headings_come_from_the_dot_layout():
    env = soccer_env.parallel_env(blue=2, yellow=2, max_cycles=60,
                                  perception={"vision": "ssl-2012", "detector": "pixels"}, **SSL)
    obs, infos = env.reset(seed=1)
    errors = []
    while env.agents:
        obs, _, _, _, infos = env.step({a: np.array([0.3, 0, 0.4, 0, 0, 0], np.float32)
                                        for a in env.agents})
        info = infos["blue_0"]
        for a in env.possible_agents:
            e, t = info["estimate"]["robot_pose"][a], info["truth"]["robot_pose"][a]
            errors.append(abs(math.remainder(float(e[2] - t[2]), 2 * math.pi)))
    assert np.median(errors) < math.radians(15)


def test_the_same_seed_gives_the_same_images_and_estimates():
    def run():
        env = ssl_keeper()
        env.reset(seed=5)
        return [env.step(np.zeros(6, np.float32))[0] for _ in range(30)]
    np.testing.assert_array_equal(run(), run())


def test_humanoids_find_the_ball_in_their_head_camera_images():
    env = GoalkeeperEnv(robot="humanoid-2012", obs_mode="perceived", mates=3,
                        shots={"delay": (2.0, 2.0)},
                        perception={"camera": "kidsize-2012", "detector": "pixels"})
    env.reset(seed=0)
    errors = []
    for _ in range(110):  # before the shot
        _, _, _, _, info = env.step(np.zeros(6, np.float32))
        errors.append(np.hypot(*(info["estimate"]["ball_position"]
                                 - info["truth"]["ball_position"])))
    assert np.median(errors[30:]) < 0.3
    sensor = env.pipelines[0].sensor
    assert type(sensor).__name__ == "PixelHeadCamera"


def test_pixels_on_four_cameras_hand_robots_over_across_the_quadrants():
    """Division B: four overlapping cameras, each rendering its quadrant with its own
    trackers. A robot driving from its own half into the other, across the cameras' borders,
    is found all the way: the camera it drives into takes it over where the others last saw
    it."""
    env = soccer_env.parallel_env(blue=1, yellow=1, field="ssl-div-b", robot="ssl",
                                  obs_mode="perceived", max_cycles=400,
                                  perception={"vision": "ssl-2012", "detector": "pixels"})
    env.reset(seed=2)
    pipeline = env.unwrapped.pipelines[0]
    assert len(pipeline.sensor.renderers) == 4
    errors, xs, cameras = [], [], set()
    for _ in range(240):
        actions = {a: np.zeros(6, np.float32) for a in env.agents}
        actions["blue_0"] = np.array([0.6, 0.0, 0.0, 0, 0, 0], np.float32)  # forward: +x
        _, _, _, _, infos = env.step(actions)
        info = infos["blue_0"]
        e, t = info["estimate"]["robot_pose"]["blue_0"], info["truth"]["robot_pose"]["blue_0"]
        errors.append(float(np.hypot(*(e[:2] - t[:2]))))
        xs.append(float(t[0]))
        trackers = pipeline.detector._trackers
        cameras |= {c for c in range(4) if trackers[c][0] is not None}
    assert xs[0] < -0.5 and xs[-1] > 0.5  # it crossed the halfway line, two cameras' border
    assert len(cameras) >= 2  # tracked by the cameras on both sides
    assert max(errors[20:]) < 0.1 and np.median(errors[20:]) < 0.03


def test_a_camera_whose_new_tracker_finds_nothing_drops_it_and_tries_again():
    """Division B: a camera starts tracking the ball where it was last found once that is in
    its view; where that start holds no orange (the ball hidden by a robot, or gone from that
    camera's view since), the camera drops the tracker and reports nothing, and starts again
    where the cameras that see the ball found it."""
    env = soccer_env.parallel_env(blue=1, yellow=1, field="ssl-div-b", robot="ssl",
                                  obs_mode="perceived", max_cycles=400,
                                  perception={"vision": "ssl-2012", "detector": "pixels"})
    env.reset(seed=2)
    detector = env.unwrapped.pipelines[0].detector
    frames = []
    detections = detector.detections

    def recorded(fs):
        frames.extend(fs)
        return detections(fs)

    detector.detections = recorded
    zero = {a: np.zeros(6, np.float32) for a in env.agents}
    for _ in range(20):  # every camera tracks the ball at the centre spot
        env.step(zero)
    image = [f for f in frames if f.camera == 0][-1]
    ball = detector._known_ball
    # Camera 0, without a tracker, told the ball was last found in a corner of its view.
    x0, _, y0, _ = detector.renderers[0].region
    detector._ball_trackers[0] = None
    detector._known_ball = (x0 + 0.5, y0 + 0.5)
    out = detector.detections([image])
    assert all(not f.balls for f in out) and detector._ball_trackers[0] is None
    # Found again (by the other cameras) at the centre: camera 0 starts there.
    detector._known_ball = ball
    out = detector.detections([image])
    assert np.hypot(*np.subtract(out[0].balls[0], ball)) < 0.02
    assert detector._ball_trackers[0] is not None


def test_an_unknown_detector_is_refused():
    with pytest.raises(ValueError, match=r"detector must be one of \['geometric', 'pixels'\]"):
        gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived",
                 perception={"detector": "camera"})


def test_a_ball_filling_the_head_image_is_tracked_not_refused():
    """A ball right below the camera fills more than half of the image: its search window
    (twice the blob) is kept inside the image, and the tracker follows it frame after frame."""
    from soccer_env import presets
    from soccer_env.perception.pixels import BallImageTracker
    from soccer_env.presets.images import COLOURS

    tracker = BallImageTracker(presets.head_camera("kidsize"), presets.ball("kidsize"))
    width, height = tracker.size
    image = np.zeros((height, width, 3), dtype=np.uint8)
    image[height // 8:, width // 10:] = COLOURS["orange"]
    for _ in range(3):
        found = tracker.detect(image, 0.0, 0.6, 0.0)
        assert len(found) == 1 and np.all(np.isfinite(found[0]))
