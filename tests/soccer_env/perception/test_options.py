"""Perception's option families are registries: a new option is one registration away from
every environment, and the error messages list what is registered."""

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401  (registers the environments)
from estimators import BallFilterConfig, BallTracker
from soccer_env.perception.base import PerceptionConfig
from soccer_env.perception.options import (
    BALL_FILTERS,
    BALL_TRACKERS,
    DETECTORS,
    FUSIONS,
    LOCALIZATIONS,
    BallFilter,
)


def test_a_registered_ball_filter_is_usable_everywhere():
    calls = []

    def slow_kf(ball, vision, measurement):
        calls.append(vision.name)
        cfg = BallFilterConfig(deceleration=0.0, sigma_xy=0.1, collision_noise=False,
                               gate=None, reset_after=None)
        return BallFilter(BallTracker(cfg, measurement), True)

    BALL_FILTERS.register("slow-kf", slow_kf, "a Kalman filter that trusts its sensor little")
    try:
        env = gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived",
                       perception={"vision": "ssl-2012", "ball_filter": "slow-kf"})
        env.reset(seed=0)
        _, _, _, _, info = env.step(np.zeros(6, np.float32))
        assert calls == ["ssl-2012"]
        assert np.all(np.isfinite(info["estimate"]["ball_position"]))
        assert env.unwrapped.pipelines[0].ball_tracker.config.sigma_xy == 0.1
    finally:
        BALL_FILTERS.unregister("slow-kf")
    with pytest.raises(ValueError, match="ball_filter must be one of"):
        PerceptionConfig(vision="ssl-2012", ball_filter="slow-kf")


def test_the_humanoid_families_follow_the_estimators_registries():
    from estimators import FUSION_WEIGHTINGS, INVERSE_VARIANCE, PARTICLE_FILTERS

    assert list(BALL_TRACKERS) == ["none", *PARTICLE_FILTERS, "kick"]
    assert list(FUSIONS) == ["own", *FUSION_WEIGHTINGS, INVERSE_VARIANCE]
    assert FUSIONS["own"] == "inverse"  # a lone own line, weighted as in the weighted fusion
    assert list(LOCALIZATIONS) == ["kld", "kld-triangulate", "odometry", "truth"]
    assert list(DETECTORS) == ["geometric", "pixels"]
    for family in (BALL_FILTERS, BALL_TRACKERS, FUSIONS, LOCALIZATIONS, DETECTORS):
        assert all(family.description(name) for name in family)


@pytest.mark.parametrize("key,family", [("ball_filter", BALL_FILTERS),
                                        ("ball_tracker", BALL_TRACKERS),
                                        ("fusion", FUSIONS), ("localization", LOCALIZATIONS),
                                        ("detector", DETECTORS)])
def test_errors_list_the_registered_options(key, family):
    with pytest.raises(ValueError, match=rf"{key} must be one of \[.*'{list(family)[-1]}'\]"):
        PerceptionConfig(vision="ideal", **{key: "nonsense"})
