"""Bad keywords to the estimators' constructors: None, strings, bools where numbers are meant,
and numbers whose squares or products overflow raise ValueError naming the keyword and what is
allowed, before anything is built (never a TypeError from deep inside Python or numpy, never
NaN in a later estimate)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from estimators import (
    BallFilterConfig,
    HeadCamera,
    KalmanMeanShift,
    KLDConfig,
    KLDLocalizer,
    LeastSquaresBall,
    MeanShiftParticleFilter,
    ParticleBallTracker,
    ParticleFilterTracker,
    PlainMeanShift,
    RobotTracker,
)
from estimators.checks import check_reals, real_value

BOUNDS = (-4.5, 4.5, -3.0, 3.0)


def _rng() -> np.random.Generator:
    return np.random.default_rng(0)


#: Name -> the constructor of ``**kwargs`` with the other arguments it needs.
MAKE: dict[str, Callable[..., Any]] = {
    "BallFilterConfig": BallFilterConfig,
    "HeadCamera": HeadCamera,
    "KLDConfig": lambda **kw: KLDLocalizer(BOUNDS, _rng(), KLDConfig(**kw)),
    "KLDLocalizer": lambda **kw: KLDLocalizer(**{"bounds": BOUNDS, "rng": _rng(), **kw}),
    "LeastSquaresBall": LeastSquaresBall,
    "ParticleBallTracker": lambda **kw: ParticleBallTracker(_rng(), **kw),
    "RobotTracker": lambda **kw: RobotTracker(**{"n": 2, **kw}),
    "PlainMeanShift": lambda **kw: PlainMeanShift(**{"position": (35, 25),
                                                      "window_size": (10, 10), **kw}),
    "KalmanMeanShift": lambda **kw: KalmanMeanShift(**{
        "position": (35, 25), "window_size": (10, 10), "image_size": (80, 60),
        "fov": (1.0, 0.8), **kw}),
    "MeanShiftParticleFilter": lambda **kw: MeanShiftParticleFilter(**{
        "position": (35, 25), "window_size": (10, 10), "rng": _rng(), **kw}),
    "ParticleFilterTracker": lambda **kw: ParticleFilterTracker(**{
        "position": (35, 25), "window_size": (10, 10), "rng": _rng(), **kw}),
}

BAD = [
    # Not numbers where numbers are meant.
    ("BallFilterConfig", "sigma_xy", None, r"sigma_xy must be finite and > 0 .*\[m\], got None"),
    ("BallFilterConfig", "deceleration", None, r"deceleration must be finite and >= 0"),
    ("BallFilterConfig", "gate", "", r"gate must be finite and > 0 or None"),
    ("BallFilterConfig", "maneuver_radius", "", r"maneuver_radius must be finite and > 0"),
    ("BallFilterConfig", "two_phase", "", r"two_phase must be two finite numbers"),
    ("BallFilterConfig", "reset_after", True, r"reset_after must be an integer in \[1, "),
    ("HeadCamera", "height", None, r"height must be a finite number in \(0, 10\) m"),
    ("HeadCamera", "hfov", None, r"hfov must be a finite number in \[1e-06, 3.14159\)"),
    ("KLDLocalizer", "bounds", "", r"bounds must be four finite numbers"),
    ("KLDLocalizer", "bounds", None, r"bounds must be four finite numbers"),
    ("KLDLocalizer", "pose", "", r"pose must be three finite numbers"),
    ("KLDLocalizer", "pose", {}, r"pose must be three finite numbers"),
    ("KLDLocalizer", "pose_sigma", "abc", r"pose_sigma must be three finite numbers >= 0"),
    ("LeastSquaresBall", "sigma_xy", None, r"sigma_xy must be finite and > 0"),
    ("ParticleBallTracker", "fission_sigma", "", r"fission_sigma must be four finite"),
    ("ParticleBallTracker", "fission_sigma", {}, r"fission_sigma must be four finite"),
    ("ParticleBallTracker", "threshold", "", r"threshold must be a finite number in \(0, 1\]"),
    ("RobotTracker", "q_xy", None, r"q_xy must be finite and >= 0"),
    ("PlainMeanShift", "position", "", r"position must be two finite numbers \(x, y\)"),
    ("KalmanMeanShift", "position", "", r"position must be two finite numbers"),
    ("KalmanMeanShift", "camera_height", "", r"camera_height must be finite, got ''"),
    ("KalmanMeanShift", "camera_height", None, r"camera_height must be finite, got None"),
    ("MeanShiftParticleFilter", "position", {}, r"position must be two finite numbers"),
    ("ParticleFilterTracker", "position", "", r"position must be two finite numbers"),
    ("PlainMeanShift", "eps", True, r"eps must be finite and >= 0"),
    # A flag is a bool: "no" or 0 would read as a choice never made.
    ("BallFilterConfig", "collision_noise", "", r"collision_noise must be True or False"),
    ("BallFilterConfig", "collision_noise", None, r"collision_noise must be True or False"),
    ("BallFilterConfig", "collision_noise", 1, r"collision_noise must be True or False"),
    # Numbers whose squares or products overflow, or whose squares underflow to zero.
    ("BallFilterConfig", "tau", 1.34e154, r"tau must be finite and > 0 and <= 1e\+06"),
    ("HeadCamera", "hfov", 1e-308, r"hfov must be a finite number in \[1e-06"),
    ("HeadCamera", "width", 0, r"width must be an integer in \[2, 100,000\]"),
    ("KLDLocalizer", "bounds", (-1e308, 1e308, -3.0, 3.0), r"bounds must be four finite"),
    ("KLDConfig", "delta", 1e-300, r"delta must be >= 1e-12"),
    ("ParticleBallTracker", "accel_sigma", 9.5e9, r"accel_sigma must be finite and > 0 and "
                                                  r"<= 10000"),
    ("ParticleBallTracker", "init_speed_sigma", 1e-300, r"init_speed_sigma must be a finite "
                                                        r"number in \[1e-06, 10000\]"),
    ("RobotTracker", "sigma_xy", 1.34e154, r"sigma_xy must be finite and >= 0 and <= 1e\+06"),
    ("KalmanMeanShift", "accel_sigma", 1e154, r"accel_sigma must be finite and >= 0.0, "
                                              r"<= 100000"),
    ("KalmanMeanShift", "init_sigma", (1e-300, 1.0), r"init_sigma must be two finite numbers "
                                                     r"in \[1e-06, 100000\]"),
    ("KalmanMeanShift", "window_scale", 7, r"image_size must be at least 70 x 70 pixels .* "
                                           r"\(window_size x window_scale\)"),
    ("MeanShiftParticleFilter", "likelihood_sigma", 1e300, r"likelihood_sigma must be finite"),
    ("ParticleFilterTracker", "process_sigma", 1.7e308, r"process_sigma must be finite and "),
]


@pytest.mark.parametrize("kind,keyword,value,match", BAD,
                         ids=[f"{k}-{n}-{v!r}" for k, n, v, _ in BAD])
def test_constructors_refuse_a_bad_keyword_naming_it(kind, keyword, value, match):
    with pytest.raises(ValueError, match=match):
        MAKE[kind](**{keyword: value})


def test_the_numbers_the_checks_take():
    """One rule: Python and numpy integers and floats (and 0-d arrays of them) are numbers;
    bools, strings and None are not; integers beyond float range read as infinite."""
    assert [real_value(v) for v in (3, 2.5, np.float32(1.5), np.int64(4), np.array(2.0))] == \
        [3.0, 2.5, 1.5, 4.0, 2.0]
    assert [real_value(v) for v in (True, np.bool_(False), "1", b"1", None, [1.0])] == \
        [None] * 6
    assert real_value(10**400) == float("inf") and real_value(-10**400) == -float("inf")
    np.testing.assert_array_equal(check_reals("p", np.array([1, 2]), 2), [1.0, 2.0])
    for bad in ("12", (1, True), (1.0, float("nan")), [1.0], np.ones((1, 2)), {"x": 1.0}):
        with pytest.raises(ValueError, match=r"p must be two finite numbers"):
            check_reals("p", bad, 2)


def test_a_config_stores_the_numbers_it_checked_as_floats():
    config = BallFilterConfig(sigma_xy=np.float32(0.05), gate=np.int64(9),
                              two_phase=[np.float64(0.6), 0.5])
    assert type(config.sigma_xy) is float and type(config.gate) is float
    assert config.two_phase == (0.6, 0.5)
    camera = HeadCamera(height=np.float64(0.5), width=np.int32(640))
    assert type(camera.height) is float and type(camera.width) is int
