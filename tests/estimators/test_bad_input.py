"""Bad input to the estimators: NaN, infinite, negative-variance or absurdly large arguments
raise ValueError naming the argument and its range, never NaN later and never an
allocation the machine cannot hold."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators import FrictionBallModel, KalmanFilter, KLDConfig, ParticleBallTracker
from estimators.checks import MAX_PARTICLES
from estimators.kalman.robots import RobotTracker

NAN, INF = float("nan"), float("inf")


def _kf():
    return KalmanFilter(np.zeros(2), np.eye(2))


@pytest.mark.parametrize("F,Q,match", [
    (np.full((2, 2), NAN), np.eye(2), r"F must be finite"),
    (np.eye(2), np.full((2, 2), NAN), r"Q must be finite"),
    (np.eye(2), -np.eye(2), r"Q must be positive semi-definite"),
    (np.eye(2), np.array([[1.0, 0.5], [0.0, 1.0]]), r"Q must be symmetric"),
    (np.eye(3), np.eye(2), r"F must have shape \(2, 2\)"),
])
def test_kalman_predict_refuses_bad_models_and_stays(F, Q, match):
    kf = _kf()
    with pytest.raises(ValueError, match=match):
        kf.predict(F, Q)
    np.testing.assert_array_equal(kf.x, np.zeros(2))
    np.testing.assert_array_equal(kf.P, np.eye(2))


@pytest.mark.parametrize("z,H,R,match", [
    (np.zeros(1), np.array([[1.0, 0.0]]), np.array([[NAN]]), r"R must be finite"),
    (np.zeros(1), np.array([[1.0, 0.0]]), np.array([[-1.0]]), r"R must be positive semi"),
    (np.array([NAN]), np.array([[1.0, 0.0]]), np.eye(1), r"z must be finite"),
    (np.zeros(1), np.array([[INF, 0.0]]), np.eye(1), r"H must be finite"),
    (np.zeros(1), np.array([1.0, 0.0]), np.eye(1), r"H must have shape \(m, 2\)"),
])
def test_kalman_update_refuses_bad_measurements_and_stays(z, H, R, match):
    kf = _kf()
    with pytest.raises(ValueError, match=match):
        kf.update(z, H, R)
    np.testing.assert_array_equal(kf.x, np.zeros(2))
    np.testing.assert_array_equal(kf.P, np.eye(2))
    with pytest.raises(ValueError, match="gate must be"):
        kf.update(np.zeros(1), np.array([[1.0, 0.0]]), np.eye(1), gate=NAN)


def test_a_ball_without_friction_stops_nowhere_not_at_nan():
    model = FrictionBallModel(0.0)
    stop = model.stop_position(np.array([[1.0, 2.0, 3.0, 0.0], [1.0, 2.0, 0.0, -1.0],
                                         [1.0, 2.0, 0.0, 0.0]]))
    np.testing.assert_array_equal(stop, [[INF, 2.0], [1.0, -INF], [1.0, 2.0]])
    # With friction: the closed form, p + u v^2 / (2 a).
    np.testing.assert_allclose(FrictionBallModel(0.5).stop_position(
        np.array([0.0, 0.0, 1.0, 0.0])), [1.0, 0.0])


@pytest.mark.parametrize("field,value", [
    ("a_trans", INF), ("range_sigma", INF), ("a_rot", NAN), ("bearing_sigma", INF),
    ("bin_size", (0.2, NAN, 0.2)), ("bin_size", (0.2, 0.2)), ("epsilon", NAN),
    ("max_particles", 10**10), ("min_particles", 0), ("min_particles", 2.5),
])
def test_kld_config_refuses_non_finite_and_impossible_values(field, value):
    with pytest.raises(ValueError, match=field):
        KLDConfig(**{field: value})


def test_particle_counts_are_bounded_before_anything_is_allocated():
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match=rf"n_particles must be an integer in \[2, "
                                         rf"{MAX_PARTICLES:,}\], got 10000000000"):
        ParticleBallTracker(rng, n_particles=10**10)
    with pytest.raises(ValueError, match=r"n must be an integer in \[0, 10,000\]"):
        RobotTracker(10**10)
    assert math.isfinite(MAX_PARTICLES)
