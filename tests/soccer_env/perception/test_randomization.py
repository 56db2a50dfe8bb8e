"""Sensor randomisation (``perception={"randomize": {...}}``): the figures are drawn afresh each
episode, inside their ranges, from the seed; bad ranges are refused naming the figure."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401
from soccer_env.perception.base import PerceptionConfig
from soccer_env.perception.randomization import RANDOMIZABLE

GK = "soccer_env/Goalkeeper-v0"
RANGES = {"latency": (0.03, 0.12), "ball_sigma": (0.001, 0.03), "frame_rate": (25.0, 75.0),
          "ball_detection": (0.8, 1.0)}


def _draws(env, seeds):
    out = []
    for s in seeds:
        env.reset(seed=s)
        v = env.unwrapped.pipelines[0].vision_spec
        out.append(tuple(getattr(v, k) for k in sorted(RANGES)))
    return np.array(out)


@pytest.mark.parametrize("mode", ["raw", "perceived"])
def test_figures_are_drawn_each_episode_within_their_ranges(mode):
    env = gym.make(GK, obs_mode=mode, perception={"vision": "ssl-2012", "randomize": RANGES})
    draws = _draws(env, range(20))
    for col, key in enumerate(sorted(RANGES)):
        lo, hi = RANGES[key]
        assert np.all((lo <= draws[:, col]) & (draws[:, col] <= hi))
        assert np.ptp(draws[:, col]) > 0.3 * (hi - lo)  # they vary across episodes
    # The figures not named keep the preset's values.
    v = env.unwrapped.pipelines[0].vision_spec
    assert v.robot_sigma == PerceptionConfig.create("ssl-2012", mode).vision.robot_sigma


def test_same_seed_same_draws_and_episode():
    kw = dict(obs_mode="perceived", perception={"vision": "ssl-2012", "randomize": RANGES})
    a, b = gym.make(GK, **kw), gym.make(GK, **kw)
    np.testing.assert_array_equal(_draws(a, [4, 9, 4]), _draws(b, [4, 9, 4]))
    assert np.array_equal(_draws(a, [4])[0], _draws(a, [4])[0])
    oa, _ = a.reset(seed=2)
    ob, _ = b.reset(seed=2)
    for _ in range(60):
        oa, *_ = a.step(np.zeros(6, np.float32))
        ob, *_ = b.step(np.zeros(6, np.float32))
    np.testing.assert_array_equal(oa, ob)


def test_drawn_noise_reaches_the_detections():
    """Episodes drawn with large ball noise see noisier raw detections than those drawn with
    small noise: the sensor itself uses the draw."""
    env = gym.make(GK, obs_mode="raw", shots={"delay": (2.0, 2.0)},
                   perception={"vision": "ssl-2012", "randomize": {"ball_sigma": (0.001, 0.05)}})
    rows = []
    for seed in range(12):
        env.reset(seed=seed)
        sigma = env.unwrapped.pipelines[0].vision_spec.ball_sigma
        errs = []
        for _ in range(60):  # the ball lies still until the shot at 2 s
            _, _, _, _, info = env.step(np.zeros(6, np.float32))
            errs.append(np.hypot(*(info["estimate"]["ball_position"]
                                   - info["truth"]["ball_position"])))
        rows.append((sigma, np.median(errs)))
    rows = np.array(rows)
    assert np.corrcoef(rows[:, 0], rows[:, 1])[0, 1] > 0.8


def test_humanoid_camera_figures():
    env = gym.make(GK, robot="humanoid", obs_mode="perceived",
                   perception={"randomize": {"latency": (0.03, 0.12), "pixel_sigma": (0.5, 3)}})
    seen = set()
    for seed in range(3):
        env.reset(seed=seed)
        cam = env.unwrapped.pipelines[0].camera
        assert 0.03 <= cam.latency <= 0.12 and 0.5 <= cam.pixel_sigma <= 3
        seen.add(cam.latency)
        for _ in range(20):
            env.step(np.zeros(6, np.float32))
    assert len(seen) == 3


def test_drawn_actuation_latency_delays_the_commands():
    """The command latency is drawn per episode: the robot starts moving as many control
    steps after the first command as the drawn latency spans."""
    env = gym.make(GK, obs_mode="perceived",
                   perception={"vision": "ssl-2012", "randomize": {"actuation_latency": (0, 0.1)}})
    dt, delays = env.unwrapped.world.control_dt, set()
    forward = np.array([1, 0, 0, 0, 0, 0], np.float32)
    for seed in range(8):
        env.reset(seed=seed)
        delay = round(env.unwrapped.pipelines[0].vision_spec.actuation_latency / dt)
        moved = None
        for k in range(10):
            info = env.step(forward)[-1]
            if np.abs(info["truth"]["robot_velocity"]["blue_0"]).max() > 1e-3:
                moved = k
                break
        assert moved == delay
        delays.add(delay)
    assert len(delays) >= 3


def test_whole_presets_are_drawn_with_their_links():
    """``"preset"`` alternates whole presets, each with its own command latency and loss, and
    the figures named beside it replace the drawn preset's."""
    env = gym.make(GK, obs_mode="perceived", perception={"vision": "ssl-2012", "randomize": {
        "preset": ["ssl-2012", "realistic"], "ball_detection": (0.9, 0.9)}})
    u, names = env.unwrapped, []
    for seed in range(16):
        env.reset(seed=seed)
        v = u.pipelines[0].vision_spec
        names.append(v.name)
        assert v.ball_detection == 0.9
        assert u._channels[0].delay_steps == round(v.actuation_latency / u.world.control_dt)
        assert u._channels[0].loss == v.command_loss
        assert v.frame_rate == {"ssl-2012": 25.0, "realistic": 60.0}[v.name]
    assert 4 <= names.count("realistic") <= 12
    again = gym.make(GK, obs_mode="perceived", perception={"vision": "ssl-2012", "randomize": {
        "preset": ["ssl-2012", "realistic"], "ball_detection": (0.9, 0.9)}})
    for seed in (3, 11):
        again.reset(seed=seed)
        assert again.unwrapped.pipelines[0].vision_spec.name == names[seed]
    # Humanoid teams draw head-camera presets.
    hum = gym.make(GK, robot="humanoid", obs_mode="perceived",
                   perception={"randomize": {"preset": ["kidsize", "kidsize-2012"]}})
    seen = set()
    for seed in range(8):
        hum.reset(seed=seed)
        seen.add(hum.unwrapped.pipelines[0].camera.name)
    assert seen == {"kidsize", "kidsize-2012"}


def test_no_randomization_by_default():
    assert not PerceptionConfig.create("ssl-2012", "perceived").randomize


def test_bad_ranges():
    for bad, match in [({"latency": (0.2, 0.1)}, "low <= high"),
                       ({"latency": (0.1,)}, "latency"),
                       ({"warp": (0, 1)}, "unknown figure 'warp'"),
                       ({"ball_detection": (0.5, 1.5)}, "ball_detection"),
                       ({"latency": (float("nan"), 0.1)}, "finite"),
                       ({"preset": ["ssl-2012", "nowhere"]}, "unknown ssl sensor preset"),
                       ({"preset": []}, "non-empty list"),
                       ({"preset": ["harsh"], "command_loss": (0, 2)}, "command_loss")]:
        with pytest.raises(ValueError, match=match):
            gym.make(GK, obs_mode="perceived", perception={"vision": "ssl-2012",
                                                           "randomize": bad})
    with pytest.raises(ValueError, match="pixel_sigma"):  # a head camera's figure, not SSL's
        gym.make(GK, obs_mode="perceived", perception={"randomize": {"pixel_sigma": (1, 2)}})
    with pytest.raises(TypeError, match="randomize"):
        PerceptionConfig("ssl-2012", randomize=[("latency", 0.1)])
    assert set(RANDOMIZABLE) == {"ssl", "humanoid"}
