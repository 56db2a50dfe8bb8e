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


def test_robot_tracker_refuses_a_robot_it_does_not_have_and_nan_detections():
    tracker = RobotTracker(2)
    tracker.update_robot(0.0, (1.0, 0.5, 0.1), 0)
    before = tracker.covariance(0).copy()
    for i in (2, -1, True, 1.0):
        with pytest.raises(ValueError, match=r"robot index must be an integer in 0..1"):
            tracker.covariance(i)
    with pytest.raises(ValueError, match=r"robot index must be an integer in 0..1, got 99"):
        tracker.pose_sigma(99, 0.0)
    for t, z, i in ((0.1, (NAN, 0.0, 0.0), 0), (INF, (0.0, 0.0, 0.0), 0),
                    (0.1, (0.0, 0.0, 0.0), 5)):
        with pytest.raises(ValueError, match=r"update_robot needs a finite time and pose and "
                                             r"a robot in 0..1"):
            tracker.update_robot(t, z, i)
    assert np.array_equal(tracker.covariance(0), before)  # nothing changed
    assert np.isfinite(tracker.estimate(0.2)).all()


@pytest.mark.parametrize("weights", [[NAN, 1.0], [-1.0, 2.0], [0.0, 0.0], [[0.5, 0.5]],
                                     [INF, 1.0]])
def test_systematic_resampling_refuses_weights_that_are_no_distribution(weights):
    from estimators.particle import systematic_resample

    with pytest.raises(ValueError, match=r"weights must be a 1-D array of finite, "
                                         r"non-negative numbers with a positive sum"):
        systematic_resample(np.array(weights), np.random.default_rng(0))
    assert list(systematic_resample(np.array([0.0, 1.0]), np.random.default_rng(0))) == [1, 1]


def test_head_camera_refuses_fractional_sizes_and_non_finite_angles_and_pixels():
    from estimators import HeadCamera

    with pytest.raises(ValueError, match=r"width must be a whole number of pixels, got 2.5"):
        HeadCamera(width=2.5)
    camera = HeadCamera()
    with pytest.raises(ValueError, match=r"pan and tilt must be finite angles"):
        camera.project(np.array([[1.0, 0.0, 0.0]]), NAN, 0.3)
    with pytest.raises(ValueError, match=r"pixels must be finite"):
        camera.ground_point(np.array([[NAN, 100.0]]), 0.0, 0.3)
    assert np.isfinite(camera.ground_point(np.array([[360.0, 500.0]]), 0.0, 0.3)).all()


def test_trackers_take_unix_times_and_refuse_strings_and_far_detections():
    from estimators import BallTracker

    tracker = BallTracker()
    with pytest.raises(ValueError, match=r"t must be a time in seconds, a number, got '0.1'"):
        tracker.update("0.1", [(0.0, 0.0)])
    with pytest.raises(ValueError, match=r"detections must lie within 1e\+06 m"):
        tracker.update(0.0, [(1e300, 0.0)])
    assert tracker.estimate(0.0) is None  # nothing was fused
    tracker.update(1e12 - 1.0, [(1.0, 2.0)])  # a time stamp in milliseconds since 1970
    assert np.allclose(tracker.estimate(1e12)[:2], (1.0, 2.0), atol=0.1)


def test_ungm_simulate_refuses_a_negative_length():
    from estimators.particle import ungm_simulate

    with pytest.raises(ValueError, match=r"steps must be a whole number >= 0, got -1"):
        ungm_simulate(-1, np.random.default_rng(0))
    assert len(ungm_simulate(0, np.random.default_rng(0))[1]) == 0


@pytest.mark.parametrize("radius", [-1.0, 0.0, NAN, INF])
def test_ball_filter_config_refuses_a_maneuver_radius_that_is_no_distance(radius):
    from estimators import BallFilterConfig

    with pytest.raises(ValueError, match=r"maneuver_radius must be finite and > 0"):
        BallFilterConfig(maneuver_radius=radius)
    assert BallFilterConfig(maneuver_radius=None).maneuver_radius is None


def test_kld_localizer_refuses_bad_spreads_odometry_and_ranges():
    from estimators import KLDLocalizer

    bounds = (-4.5, 4.5, -3.0, 3.0)
    for sigma in (-1.0, (0.1, NAN, 0.1), (0.1, 0.1)):
        with pytest.raises(ValueError, match=r"pose_sigma must be three finite numbers >= 0"):
            KLDLocalizer(bounds, np.random.default_rng(0), pose=np.zeros(3), pose_sigma=sigma)
    loc = KLDLocalizer(bounds, np.random.default_rng(0), pose=np.zeros(3))
    before = loc.particles.copy()
    with pytest.raises(ValueError, match=r"odometry must be a finite \(dx, dy, dtheta\), each "
                                         r"within 1000"):
        loc.predict((1e300, 0.0, 0.0))
    with pytest.raises(ValueError, match=r"ranges must be >= 0"):
        loc.update(np.array([[0.0, 0.0]]), np.array([-1.0]))
    assert np.array_equal(loc.particles, before)  # nothing changed
    loc.predict((0.1, 0.0, 0.0))
    assert np.isfinite(loc.estimate()).all()


@pytest.mark.parametrize("distances", [[1e308, 1.0], [1e-320, 1.0], [0.0, 1.0], [NAN, 1.0]])
def test_fusion_weights_refuse_distances_whose_weights_overflow(distances):
    from estimators import fusion_weights, line_offset_variance

    with pytest.raises(ValueError, match=r"distances must be a 1-d array of finite numbers in "
                                         r"\[1e-06, 1e\+06\] m"):
        fusion_weights(distances)
    with pytest.raises(ValueError, match=r"distances must be"):
        line_offset_variance(distances, 0.01)
    assert np.isfinite(fusion_weights([0.5, 3.0], "inverse_square")).all()


def test_kalman_filter_accepts_lists_and_an_exact_measurement_and_refuses_a_singular_one():
    """Array-likes are matrices; ``R = 0`` (an exact measurement) is fused exactly where
    ``H P H^T`` is positive definite; a singular innovation covariance names ``R``."""
    kf = _kf()
    kf.predict([[1.0, 0.0], [0.0, 1.0]], [[0.0, 0.0], [0.0, 0.0]])
    assert kf.update([0.5, -0.25], np.eye(2), np.zeros((2, 2)))
    np.testing.assert_allclose(kf.x, [0.5, -0.25])
    np.testing.assert_allclose(kf.P, np.zeros((2, 2)), atol=1e-12)
    kf = _kf()
    with pytest.raises(ValueError, match=r"R: the innovation covariance S = H P H\^T \+ R is "
                                         r"singular"):
        kf.update(np.ones(1), np.zeros((1, 2)), np.zeros((1, 1)))
    np.testing.assert_array_equal(kf.P, np.eye(2))
    assert kf.y is None and kf.missed == 0


@pytest.mark.parametrize("step", ["update", "predict"])
def test_kalman_filter_refuses_a_step_that_overflows_and_stays(step):
    kf = _kf()
    with pytest.raises(ValueError, match="small enough that the filter stays finite"):
        if step == "update":
            kf.update(np.full(2, 1e308), np.eye(2), np.eye(2))
        else:
            kf.predict(1e200 * np.eye(2), np.eye(2))
    np.testing.assert_array_equal(kf.x, np.zeros(2))
    np.testing.assert_array_equal(kf.P, np.eye(2))
    assert kf.d2 is None
    kf.update(np.ones(2), np.eye(2), np.eye(2))  # and it goes on
    np.testing.assert_allclose(kf.x, [0.5, 0.5])


@pytest.mark.parametrize("name", ["bootstrap", "fbpf", "mfbpf"])
@pytest.mark.parametrize("y,match", [(INF, "y must be finite"), (NAN, "y must be finite"),
                                     ("x", "y must be a real number"),
                                     ([1.0, 2.0], r"y of shape \(2,\): the likelihood")])
def test_particle_filters_refuse_a_measurement_that_weighs_nothing(name, y, match):
    """``step(inf)`` used to weigh every particle zero and return the prior in silence."""
    from estimators.particle.core import PARTICLE_FILTERS, ungm_model

    transition, likelihood = ungm_model()
    rng = np.random.default_rng(1)
    pf = PARTICLE_FILTERS.get(name)(rng.normal(size=(64, 1)), transition, likelihood, rng)
    pf.step(0.5)
    particles, k = pf.particles.copy(), pf.k
    with pytest.raises(ValueError, match=match):
        pf.step(y)
    if not match.startswith("y of shape"):  # refused before the particles move
        np.testing.assert_array_equal(pf.particles, particles)
        assert pf.k == k
    assert np.isfinite(pf.step(0.4)).all()


def _trackers():
    from estimators.image.following import KalmanMeanShift, PlainMeanShift
    from estimators.image.mspf import MeanShiftParticleFilter, ParticleFilterTracker

    rng = np.random.default_rng(3)
    return {
        "plain": PlainMeanShift((35, 25), (10, 10)),
        "kalman": KalmanMeanShift((35, 25), (10, 10), image_size=(80, 60), fov=(1.0, 0.8),
                                  camera_height=0.5),
        "kalman-paper": KalmanMeanShift((35, 25), (10, 10), image_size=(80, 60),
                                        fov=(1.0, 0.8), order="paper"),
        "mspf": MeanShiftParticleFilter((35, 25), (10, 10), rng, area=100.0),
        "pf": ParticleFilterTracker((35, 25), (10, 10), rng),
    }


def _state(tracker) -> dict:
    return {k: v.copy() if isinstance(v, np.ndarray) else v for k, v in vars(tracker).items()
            if k not in ("kf", "_win", "rng", "_source", "_motion_source")} | (
        {"kf": (tracker.kf.x.copy(), tracker.kf.P.copy())} if hasattr(tracker, "kf") else {})


WEIGHTS = r"(weight|colour)_image must hold finite, non-negative weights"
TOO_SMALL = (r"(weight|colour)_image must be at least 10 x 10 pixels \(w x h\) to hold the "
             r"window, got shape \(1, 1\)")


@pytest.mark.parametrize("kind", ["plain", "kalman", "kalman-paper", "mspf", "pf"])
@pytest.mark.parametrize("bad,match", [
    (np.full((60, 80), NAN), WEIGHTS), (np.full((60, 80), 1e308), WEIGHTS),
    (np.full((60, 80), -1.0), WEIGHTS), (np.ones((1, 1)), TOO_SMALL)])
def test_image_trackers_refuse_frames_that_are_no_weights_and_stay(kind, bad, match):
    """NaN, overflowing or negative weights where a window reads them, or a frame smaller
    than the window: ValueError naming the image, the tracker as it was (its next frame the
    same as an untouched copy's)."""
    import copy

    if kind.startswith("kalman") and bad.shape == (1, 1):
        match = r"weight_image must have shape \(60, 80\)"  # it knows its image size
    good = np.zeros((60, 80))
    good[20:30, 30:40] = 1.0
    tracker = _trackers()[kind]
    tracker.update(good)
    twin = copy.deepcopy(tracker)
    before = _state(tracker)
    with pytest.raises(ValueError, match=match):
        tracker.update(bad)
    after = _state(tracker)
    assert after.keys() == before.keys()
    for key, value_before in before.items():
        np.testing.assert_equal(after[key], value_before, err_msg=key)
    np.testing.assert_array_equal(tracker.update(good), twin.update(good))


def test_a_kalman_mean_shift_names_the_image_size_it_was_made_for():
    tracker = _trackers()["kalman"]
    with pytest.raises(ValueError, match=r"weight_image must have shape \(60, 80\), got "
                                         r"\(10, 10\)"):
        tracker.update(np.zeros((10, 10)))
    np.testing.assert_array_equal(tracker.state, [35.0, 25.0, 0.0, 0.0])


def test_ball_trackers_take_an_empty_frame_and_have_no_estimate_before_a_track():
    """Accepted by design: a frame without a detection is a frame in which the ball was not
    seen, and a tracker that has never seen the ball has no estimate (None)."""
    from estimators import BallTracker, LeastSquaresBall

    for make in (BallTracker, LeastSquaresBall):
        tracker = make()
        assert tracker.estimate(0.0) is None
        tracker.update(0.0, np.zeros((0, 2)))
        assert tracker.estimate(0.05) is None
        tracker.update(0.1, np.array([[1.0, 2.0]]))
        np.testing.assert_allclose(tracker.estimate(0.1)[:2], [1.0, 2.0], atol=1e-9)


@pytest.mark.parametrize("deceleration,state,dt,match", [
    (0.4, [0.0, 0.0, 0.0, 1.34e154], 0.0, r"state must be finite .* velocities within 10000"),
    (0.4, [2e6, 0.0, 1.0, 0.0], 1.0, r"state must be finite .* positions within 1e\+06 m"),
    (0.0, [0.0, 0.0, 1.0, 0.0], INF, r"state and dt must keep the prediction finite"),
])
def test_the_ball_model_refuses_a_prediction_that_overflows(deceleration, state, dt, match):
    """A speed whose square overflows made NaN out of ``predict``; so did a ball that never
    stops (no friction) predicted forever."""
    model = FrictionBallModel(deceleration)
    with pytest.raises(ValueError, match=match):
        model.predict(state, dt)
    assert np.isfinite(model.predict([0.0, 0.0, 1.0, 0.0], 1.0)).all()
