"""The closed-form friction ball model: deceleration and stop, batches, the time to reach a
line, bad arguments (against the simulated ball: tests/test_ball_models.py)."""

import numpy as np
import pytest

from estimators import FrictionBallModel


def test_predict_decelerates_and_stops():
    m = FrictionBallModel(0.5)
    s = np.array([0.0, 0.0, 3.0, 4.0])  # speed 5 along (0.6, 0.8)
    out = m.predict(s, 2.0)
    np.testing.assert_allclose(out, [0.6 * 9.0, 0.8 * 9.0, 0.6 * 4.0, 0.8 * 4.0])
    stop = m.predict(s, 100.0)
    np.testing.assert_allclose(stop, [0.6 * 25.0, 0.8 * 25.0, 0.0, 0.0])
    assert m.stop_time(s) == pytest.approx(10.0)
    np.testing.assert_allclose(m.stop_position(s), stop[:2])


def test_predict_batched_and_at_rest():
    m = FrictionBallModel(0.3)
    states = np.array([[1.0, 2.0, 0.0, 0.0], [0.0, 0.0, -1.0, 0.0]])
    out = m.predict(states, np.array([1.0, 1.0]))
    np.testing.assert_allclose(out[0], states[0])
    np.testing.assert_allclose(out[1], [-0.85, 0.0, -0.7, 0.0])


def test_time_to_line():
    m = FrictionBallModel(0.5)
    s = np.array([0.0, 0.0, -2.0, 0.0])
    t = m.time_to_line(s, -3.0)  # 3 m at 2 m/s decelerating at 0.5: 2t - t^2/4 = 3 -> t=2
    assert t == pytest.approx(2.0)
    assert np.isinf(m.time_to_line(s, -5.0))  # stops at -4
    assert np.isinf(m.time_to_line(s, 1.0))  # behind it
    np.testing.assert_allclose(m.predict(s, t)[0], -3.0)
    assert FrictionBallModel(0.0).time_to_line(s, -3.0) == pytest.approx(1.5)


def test_bad_arguments():
    with pytest.raises(ValueError, match=r"deceleration must be a finite number in \[0"):
        FrictionBallModel(-0.1)
    with pytest.raises(ValueError, match="dt must be >= 0"):
        FrictionBallModel(0.1).predict(np.zeros(4), -1.0)
