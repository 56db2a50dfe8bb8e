"""Fuzzing the public entry points (hypothesis, derandomized in CI by ``tests/conftest.py``):
whatever a caller passes to an environment's constructor, ``reset`` or ``step``, or to an
estimator's methods, the outcome is either a result whose numbers are finite, or a
``ValueError`` / ``TypeError`` whose message names the argument. Never another exception,
never NaN, never a hang (each example is bounded by hypothesis' deadline)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from fuzzing import ANYTHING, FAST, NUMBERS, accepted, finite, named
from hypothesis import given
from hypothesis import strategies as st

import soccer_env
from estimators import (
    BallTracker,
    FrictionBallModel,
    KalmanFilter,
    KLDConfig,
    LeastSquaresBall,
    ParticleBallTracker,
    RobotTracker,
)
from soccer_env.envs.goalkeeper import GoalkeeperEnv
from soccer_env.envs.shootout import ShootoutEnv
from soccer_env.validation import keyword_names

# -- environments ----------------------------------------------------------------------------

ENV_CLASSES = {"goalkeeper": GoalkeeperEnv, "shootout": ShootoutEnv}


@pytest.mark.parametrize("kind", list(ENV_CLASSES))
@FAST
@given(data=st.data())
def test_environment_constructors(kind, data):
    """One keyword argument set to anything: the environment is built and plays, or the
    error names that argument."""
    cls = ENV_CLASSES[kind]
    name = data.draw(st.sampled_from([n for n in keyword_names(cls.__init__)
                                      if n != "render_mode"]), label="argument")
    value = data.draw(ANYTHING, label="value")
    try:
        env = cls(**{name: value})
    except (ValueError, TypeError) as err:
        assert named(err, name), f"{name}={value!r}: {err}"
        return
    obs, info = env.reset(seed=0)
    assert finite(obs)
    obs, reward, *_ = env.step(np.zeros(6, np.float32))
    assert accepted(finite(obs) and math.isfinite(reward))


@pytest.fixture(scope="module")
def keeper():
    return GoalkeeperEnv()


@FAST
@given(seed=ANYTHING, action=st.one_of(ANYTHING, st.lists(NUMBERS, min_size=6, max_size=6)))
def test_goalkeeper_reset_and_step(keeper, seed, action):
    try:
        keeper.reset(seed=seed)
    except (ValueError, TypeError) as err:
        assert named(err, "seed"), f"seed={seed!r}: {err}"
        keeper.reset(seed=0)
    try:
        obs, reward, term, trunc, info = keeper.step(action)
    except (ValueError, TypeError) as err:
        assert named(err, "action"), f"action={action!r}: {err}"
        return
    assert accepted(finite(obs) and math.isfinite(reward))


@pytest.fixture(scope="module")
def match():
    return soccer_env.parallel_env(blue=2, yellow=1)


@FAST
@given(seed=ANYTHING, actions=st.one_of(
    ANYTHING, st.dictionaries(st.sampled_from(["blue_0", "blue_1", "yellow_0", "red_0"]),
                              st.one_of(ANYTHING, st.lists(NUMBERS, min_size=6,
                                                           max_size=6)), max_size=4)))
def test_match_reset_and_step(match, seed, actions):
    try:
        match.reset(seed=seed)
    except (ValueError, TypeError) as err:
        assert named(err, "seed"), f"seed={seed!r}: {err}"
        match.reset(seed=0)
    try:
        obs, rewards, *_ = match.step(actions)
    except (ValueError, TypeError) as err:
        assert named(err, "action"), f"actions={actions!r}: {err}"
        return
    assert accepted(finite(obs) and finite(rewards))


# -- estimators ------------------------------------------------------------------------------

POINTS = st.one_of(ANYTHING, st.lists(st.lists(NUMBERS, min_size=2, max_size=2),
                                      max_size=3))


@pytest.mark.parametrize("make", [BallTracker, LeastSquaresBall], ids=["ekf", "least-squares"])
@FAST
@given(feed=st.lists(st.tuples(st.one_of(NUMBERS, ANYTHING), POINTS), max_size=4),
       ask=st.one_of(NUMBERS, ANYTHING))
def test_ball_trackers(make, feed, ask):
    tracker = make()
    for t, z in feed:
        try:
            tracker.update(t, z)
        except (ValueError, TypeError) as err:
            assert named(err, "t ", "t must", "detections", "obstacles"), f"{t!r}, {z!r}: {err}"
    try:
        est = tracker.estimate(ask)
    except (ValueError, TypeError) as err:
        assert named(err, "t must"), f"estimate({ask!r}): {err}"
        return
    assert accepted(est is None or finite(est))


@FAST
@given(feed=st.lists(st.tuples(st.one_of(NUMBERS, ANYTHING), POINTS,
                               st.one_of(NUMBERS, ANYTHING)), max_size=4),
       ask=st.one_of(NUMBERS, ANYTHING))
def test_particle_ball_tracker(feed, ask):
    tracker = ParticleBallTracker(np.random.default_rng(0), n_particles=50)
    for t, z, sigma in feed:
        try:
            tracker.update(t, z, sigma)
        except (ValueError, TypeError) as err:
            assert named(err, "t must", "z must", "sigma must"), f"{t!r}, {z!r}: {err}"
    for method in (tracker.predict_to, tracker.estimate, tracker.covariance):
        try:
            out = method(ask)
        except (ValueError, TypeError) as err:
            assert named(err, "t must"), f"{method.__name__}({ask!r}): {err}"
            continue
        assert accepted(out is None or finite(out))


@FAST
@given(n=ANYTHING, t=ANYTHING, z=ANYTHING, index=ANYTHING, ask=ANYTHING)
def test_robot_tracker(n, t, z, index, ask):
    try:
        tracker = RobotTracker(n)
    except (ValueError, TypeError) as err:
        assert named(err, "n must"), f"n={n!r}: {err}"
        tracker = RobotTracker(2)
    try:
        tracker.update(t, z, index)
    except (ValueError, TypeError) as err:
        assert named(err, "t must", "z must", "index must", "z "), f"{t!r} {z!r}: {err}"
    try:
        out = tracker.estimate(ask)
    except (ValueError, TypeError) as err:
        assert named(err, "t must"), f"estimate({ask!r}): {err}"
        return
    assert accepted(finite(out))


@FAST
@given(F=ANYTHING, Q=ANYTHING, z=ANYTHING, R=ANYTHING)
def test_kalman_filter(F, Q, z, R):
    kf = KalmanFilter(np.zeros(2), np.eye(2))
    for name, call in (("F", lambda: kf.predict(F, np.eye(2))),
                       ("Q", lambda: kf.predict(np.eye(2), Q)),
                       ("z", lambda: kf.update(z, np.eye(2), np.eye(2))),
                       ("R", lambda: kf.update(np.zeros(2), np.eye(2), R))):
        try:
            call()
        except (ValueError, TypeError) as err:
            assert named(err, f"{name} must", f"{name} "), f"{name}: {err}"
            continue
        assert accepted(finite(kf.x) and finite(kf.P))


@FAST
@given(a=ANYTHING, state=ANYTHING)
def test_friction_ball_model(a, state):
    try:
        model = FrictionBallModel(a)
    except (ValueError, TypeError) as err:
        assert named(err, "deceleration"), f"{a!r}: {err}"
        return
    try:
        stop = model.stop_position(state)
    except (ValueError, TypeError) as err:
        assert named(err, "state"), f"{state!r}: {err}"
        return
    assert accepted(not np.any(np.isnan(stop)))


@FAST
@given(name=st.sampled_from(list(KLDConfig.__dataclass_fields__)), value=ANYTHING)
def test_kld_config(name, value):
    try:
        KLDConfig(**{name: value})
    except (ValueError, TypeError) as err:
        assert named(err, name), f"{name}={value!r}: {err}"
        return
    accepted(True)
