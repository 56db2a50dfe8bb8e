"""The closed-form friction ball model against the simulated ball (the model's own tests are in
tests/estimators/models/test_ball.py)."""

import numpy as np
from worlds import make_world, park

from estimators import FrictionBallModel
from soccer_env.sim.world import idle_commands


def test_model_predicts_the_simulated_rolling_ball():
    w = park(make_world())
    a = w.ball_spec.rolling_deceleration
    w.set_ball(-3.0, -1.0, 1.2, 0.5)
    start = w.ball_array()[[0, 1, 3, 4]]
    for _ in range(120):
        w.step(idle_commands(1))
    predicted = FrictionBallModel(a).predict(start, w.time)
    np.testing.assert_allclose(w.ball_array()[[0, 1, 3, 4]], predicted, atol=0.01)
