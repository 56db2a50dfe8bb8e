"""The friction ball motion model: stops instead of reversing, and its two propagations
agree with each other and with the closed-form ball while it moves."""

import numpy as np
import pytest

from estimators import FrictionBallModel, FrictionBallMotion


def test_motion_models_stop_instead_of_reversing():
    for prop in ("jacobian", "rk"):
        m = FrictionBallMotion(0.5, prop)
        x, _, _ = m.transition(np.array([0.0, 0.0, 0.1, 0.0]), 1.0, 0.1)
        assert x[2] == 0.0 and x[3] == 0.0 and 0.0 < x[0] <= 0.05 + 1e-12
    with pytest.raises(ValueError, match="propagation must be one of"):
        FrictionBallMotion(0.2, "euler")


def test_rk_and_jacobian_means_agree_while_moving():
    x0 = np.array([0.0, 0.0, 2.0, -1.0])
    a, b = FrictionBallMotion(0.23, "jacobian"), FrictionBallMotion(0.23, "rk")
    np.testing.assert_allclose(a.transition(x0, 0.04, 0.1)[0], b.transition(x0, 0.04, 0.1)[0],
                               atol=1e-12)
    exact = FrictionBallModel(0.23).predict(x0, 0.04)
    np.testing.assert_allclose(a.transition(x0, 0.04, 0.1)[0], exact, atol=1e-12)
