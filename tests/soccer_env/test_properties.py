"""Property-based tests (hypothesis) of contracts that must hold for any input."""

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import soccer_env  # noqa: F401
from estimators import FrictionBallModel

finite = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)
FIXTURE_OK = [HealthCheck.function_scoped_fixture]


@pytest.fixture(scope="module")
def keeper():
    return gym.make("soccer_env/Goalkeeper-v0").unwrapped


@settings(max_examples=60, deadline=None, suppress_health_check=FIXTURE_OK)
@given(actions=arrays(np.float64, (5, 6), elements=finite), seed=st.integers(0, 2**31 - 1))
def test_any_finite_action_keeps_observations_in_space(keeper, actions, seed):
    obs, _ = keeper.reset(seed=seed)
    assert keeper.observation_space.contains(obs)
    for a in actions:
        obs, reward, term, trunc, info = keeper.step(a)
        assert keeper.observation_space.contains(obs)
        assert np.isfinite(reward)
        if term:
            break


@settings(max_examples=40, deadline=None, suppress_health_check=FIXTURE_OK)
@given(action=arrays(np.float64, 6, elements=st.floats(allow_nan=True, allow_infinity=True)),
       seed=st.integers(0, 1000))
def test_bad_numbers_never_reach_the_world(keeper, action, seed):
    keeper.reset(seed=seed)
    before = keeper.world.snapshot()
    if np.isfinite(action).all():
        keeper.step(action)
    else:
        with pytest.raises(ValueError, match="blue_0"):
            keeper.step(action)
        after = keeper.world.snapshot()
        np.testing.assert_array_equal(before.robots, after.robots)
        np.testing.assert_array_equal(before.ball, after.ball)


state = st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-8, 8), st.floats(-8, 8))


@given(s=state, t1=st.floats(0, 5), t2=st.floats(0, 5), a=st.floats(0, 4))
def test_friction_model_composes_and_never_reverses(s, t1, t2, a):
    m = FrictionBallModel(a)
    s = np.array(s)
    once = m.predict(s, t1 + t2)
    twice = m.predict(m.predict(s, t1), t2)
    np.testing.assert_allclose(once, twice, atol=1e-6)
    v0, v1 = s[2:4], once[2:4]
    assert np.linalg.norm(v1) <= np.linalg.norm(v0) + 1e-9
    assert v1 @ v0 >= -1e-9  # never reverses
