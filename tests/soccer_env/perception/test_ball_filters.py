"""The ball filter with the environment's ball: the two-phase model against the SSL ball
preset's sliding and rolling decelerations (the estimator's own tests are in
tests/estimators/kalman/test_ball.py)."""

import numpy as np

from estimators import BallFilterConfig, BallTracker


def test_two_phase_model_follows_a_kick():
    """After a kick the two-phase filter's prediction keeps up through the sliding phase."""
    from soccer_env.presets import ball as ball_preset

    bs = ball_preset("ssl")
    dt, v0 = 1 / 60, 5.0
    # True two-phase motion along x.
    x, v, truth = 0.0, v0, []
    for _ in range(90):
        a = bs.sliding_deceleration if v > bs.k_switch * v0 else bs.rolling_deceleration
        x, v = x + v * dt - 0.5 * a * dt * dt, max(v - a * dt, 0.0)
        truth.append((x, v))
    errors = {}
    for name, two in (("one", None), ("two", (bs.sliding_deceleration, bs.k_switch))):
        f = BallTracker(BallFilterConfig(deceleration=bs.rolling_deceleration, sigma_xy=0.002,
                                         two_phase=two))
        f.update(0.0, np.zeros((1, 2)))
        errs = []
        for k, (xt, vt) in enumerate(truth):
            f.update((k + 1) * dt, np.array([[xt, 0.0]]))
            ahead = f.estimate((k + 1) * dt + 0.1)  # 100 ms ahead
            errs.append(abs(ahead[2] - max(vt - 3.0 * 0.1, 0.0)))
        errors[name] = np.mean(errs[5:25])
    assert errors["two"] < errors["one"]
