"""The Kalman filter core against FilterPy: predictions, updates, missed detections,
gating and bad input."""

import numpy as np
import pytest
from filterpy.kalman import KalmanFilter as FilterPyKF

from estimators import ConstantVelocityMotion, KalmanFilter


def cv_data(n=200, dt=0.04, seed=0):
    rng = np.random.default_rng(seed)
    p = np.array([0.0, 0.0])
    v = np.array([1.5, -0.7])
    out = []
    for _ in range(n):
        v = v + rng.normal(0, 0.05, 2)
        p = p + v * dt
        out.append(p + rng.normal(0, 0.02, 2))
    return np.array(out)


def test_matches_filterpy_on_constant_velocity_data():
    dt = 0.04
    motion = ConstantVelocityMotion(2, q=0.5)
    _, F, Q = motion.transition(np.zeros(4), dt)
    H = np.hstack([np.eye(2), np.zeros((2, 2))])
    R = 0.02**2 * np.eye(2)
    x0, P0 = np.zeros(4), np.eye(4)

    ours = KalmanFilter(x0, P0)
    ref = FilterPyKF(dim_x=4, dim_z=2)
    ref.x, ref.P, ref.F, ref.Q, ref.H, ref.R = x0.copy(), P0.copy(), F, Q, H, R
    for k, z in enumerate(cv_data()):
        ours.predict(F, Q)
        ref.predict()
        if k % 7 == 3:  # a missed detection now and then
            ours.update(None, H, R)
            ref.update(None)
        else:
            ours.update(z, H, R)
            ref.update(z)
            np.testing.assert_allclose(ours.y, ref.y.ravel(), atol=1e-9)
            np.testing.assert_allclose(ours.S, ref.S, atol=1e-9)
            assert ours.d2 == pytest.approx(float(ref.mahalanobis) ** 2, rel=1e-9)
        np.testing.assert_allclose(ours.x, ref.x.ravel(), rtol=0, atol=1e-9)
        np.testing.assert_allclose(ours.P, ref.P, rtol=0, atol=1e-9)


def test_gate_rejects_outliers_and_counts_misses():
    kf = KalmanFilter(np.zeros(4), np.eye(4) * 0.01)
    H = np.hstack([np.eye(2), np.zeros((2, 2))])
    R = 1e-4 * np.eye(2)
    assert not kf.update(np.array([5.0, 5.0]), H, R, gate=13.8)
    assert kf.rejected == 1 and np.all(kf.x == 0) and kf.d2 > 13.8
    assert not kf.update(None, H, R) and kf.missed == 1
    assert kf.update(np.array([0.01, 0.0]), H, R, gate=13.8)
    assert kf.rejected == 0 and kf.missed == 0


@pytest.mark.parametrize("bad,match", [
    (np.array([np.nan, 0.0]), "z must be finite"),
    (np.zeros(3), r"z must have shape \(2,\)"),
])
def test_bad_measurements_refused(bad, match):
    kf = KalmanFilter(np.zeros(4), np.eye(4))
    H = np.hstack([np.eye(2), np.zeros((2, 2))])
    with pytest.raises(ValueError, match=match):
        kf.update(bad, H, np.eye(2))
    np.testing.assert_array_equal(kf.x, np.zeros(4))


def test_bad_construction():
    with pytest.raises(ValueError, match="symmetric positive definite"):
        KalmanFilter(np.zeros(2), np.array([[1.0, 2.0], [2.0, 1.0]]))
    with pytest.raises(ValueError, match=r"P must have shape \(2, 2\)"):
        KalmanFilter(np.zeros(2), np.eye(3))
