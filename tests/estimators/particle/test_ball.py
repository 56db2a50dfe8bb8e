"""Particle-filter ball tracker (Xu et al.'s 2012 filters on the constant-velocity ball model):
tracking accuracy for every filter, prediction with and without deceleration, restarts after
a teleport or a long absence, late measurements, reproducibility and bad arguments."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators import PARTICLE_FILTERS, ParticleBallTracker

SIGMA = 0.1  # measurement noise [m]
V = np.array([1.0, -0.5])  # the rolling ball's velocity [m/s]
P0 = np.array([-2.0, 1.0])


def _roll(tracker, rng, steps=150, t0=0.0, p0=P0, v=V, sigma=SIGMA):
    """Feed noisy positions of a ball rolling in a straight line, at 25 Hz with jittered
    time steps; returns times, truths, measurements and estimates."""
    ts = t0 + np.cumsum(rng.uniform(0.03, 0.05, steps))
    truth = p0 + np.outer(ts - t0, v)
    zs = truth + rng.normal(0.0, sigma, (steps, 2))
    est = []
    for t, z in zip(ts, zs, strict=True):
        tracker.update(t, z, sigma)
        est.append(tracker.estimate(t))
    return ts, truth, zs, np.array(est)


@pytest.mark.parametrize("name", list(PARTICLE_FILTERS))
def test_tracks_a_rolling_ball_well_below_the_measurement_noise(name):
    ratios, speed_err = [], []
    for seed in range(4):
        rng = np.random.default_rng(seed)
        tr = ParticleBallTracker(np.random.default_rng(100 + seed), filter=name)
        _, truth, zs, est = _roll(tr, rng)
        err = np.hypot(*(est[50:, :2] - truth[50:]).T)
        raw = np.hypot(*(zs[50:] - truth[50:]).T)
        ratios.append(np.sqrt(np.mean(err**2)) / np.sqrt(np.mean(raw**2)))
        speed_err.append(np.sqrt(np.mean(np.sum((est[100:, 2:] - V) ** 2, axis=1))))
        assert tr.resets == 0 and tr.fused == 150
    assert np.mean(ratios) < 0.5
    assert np.mean(speed_err) < 0.25  # the velocity converges


def test_particles_alone_from_the_first_measurement():
    """kalman_start=1 (the paper's start: no Kalman filter) converges too with FBPF."""
    rng = np.random.default_rng(3)
    tr = ParticleBallTracker(np.random.default_rng(4), filter="fbpf", kalman_start=1,
                             init_speed_sigma=1.0)
    _, truth, _, est = _roll(tr, rng)
    assert np.sqrt(np.mean(np.sum((est[60:, :2] - truth[60:]) ** 2, axis=1))) < 0.08
    assert np.hypot(*(est[-1, 2:] - V)) < 0.4


def test_predict_to_extrapolates_linearly_with_constant_velocity():
    rng = np.random.default_rng(5)
    tr = ParticleBallTracker(np.random.default_rng(6))
    ts, *_ = _roll(tr, rng)
    t = ts[-1]
    x = tr.estimate(t)
    particles = tr.particles
    for dt in (0.1, 0.5, 2.0):  # estimate() predicts without changing the filter
        np.testing.assert_allclose(tr.estimate(t + dt), [*(x[:2] + dt * x[2:]), *x[2:]],
                                   atol=1e-12)
    np.testing.assert_array_equal(tr.particles, particles)
    spread = tr.spread
    tr.predict_to(t + 0.5)  # the time update moves the particles themselves
    assert tr.time == t + 0.5
    moved = tr.estimate(t + 0.5)
    np.testing.assert_allclose(moved[:2], x[:2] + 0.5 * x[2:], atol=0.05)
    assert tr.spread > spread  # and the uncertainty grows
    tr.predict_to(t)  # the past: nothing happens
    assert tr.time == t + 0.5


def test_predict_to_decelerates_and_stops_with_deceleration():
    a = 0.5
    rng = np.random.default_rng(7)
    tr = ParticleBallTracker(np.random.default_rng(8), deceleration=a)
    ts = np.arange(1, 60) * 0.04
    for t in ts:  # a ball rolling at 2 m/s along +x, slowing at a
        s = 2.0 - a * t
        tr.update(t, [2.0 * t - 0.5 * a * t * t, 0.0] + rng.normal(0, 0.02, 2), 0.02)
    x = tr.estimate(ts[-1])
    s = math.hypot(x[2], x[3])
    assert s == pytest.approx(2.0 - a * ts[-1], abs=0.15)
    u = x[2:] / s
    for dt in (0.5, 1.0):
        e = tr.estimate(ts[-1] + dt)  # uniform deceleration along the motion
        np.testing.assert_allclose(e[:2], x[:2] + u * (s * dt - 0.5 * a * dt * dt), atol=1e-9)
        assert math.hypot(e[2], e[3]) == pytest.approx(s - a * dt)
    stop = tr.estimate(ts[-1] + 10.0)  # it stops after s / a and does not roll back
    np.testing.assert_allclose(stop[:2], x[:2] + u * s * s / (2 * a), atol=1e-9)
    np.testing.assert_array_equal(stop[2:], [0.0, 0.0])
    tr.predict_to(ts[-1] + 1.0)
    assert math.hypot(*tr.estimate(ts[-1] + 1.0)[2:]) < s - 0.3


def test_restarts_after_a_teleport():
    """The ball was kicked or placed elsewhere: the first implausible measurement restarts
    the filter there, and it converges again."""
    rng = np.random.default_rng(9)
    tr = ParticleBallTracker(np.random.default_rng(10))
    ts, *_ = _roll(tr, rng, steps=80)
    new_p0, new_v = np.array([2.0, -1.0]), np.array([-0.5, 0.8])
    ts2, truth, _, est = _roll(tr, rng, steps=80, t0=ts[-1], p0=new_p0, v=new_v)
    assert tr.resets == 1 and tr.rejected == 1
    assert np.hypot(*(est[0, :2] - truth[0])) < 4 * SIGMA  # the measurement itself
    assert np.sqrt(np.mean(np.sum((est[40:, :2] - truth[40:]) ** 2, axis=1))) < 0.09
    # reinit_after=2: a single outlier is dropped instead.
    tr = ParticleBallTracker(np.random.default_rng(10), reinit_after=2)
    ts, *_ = _roll(tr, np.random.default_rng(9), steps=80)
    before = tr.estimate(ts[-1] + 0.04)
    tr.update(ts[-1] + 0.04, [2.5, 1.5], SIGMA)
    assert tr.rejected == 1 and tr.resets == 0
    np.testing.assert_allclose(tr.estimate(ts[-1] + 0.04), before, atol=0.02)
    # gate=None never restarts on a measurement.
    tr = ParticleBallTracker(np.random.default_rng(10), gate=None)
    ts, *_ = _roll(tr, np.random.default_rng(9), steps=80)
    tr.update(ts[-1] + 0.04, [2.5, 1.5], SIGMA)
    assert tr.resets == 0


def test_restarts_after_lost_after_seconds_without_measurements():
    rng = np.random.default_rng(11)
    tr = ParticleBallTracker(np.random.default_rng(12), lost_after=0.5)
    ts, *_ = _roll(tr, rng, steps=40)
    tr.predict_to(ts[-1] + 0.4)  # predictions alone do not count as measurements
    tr.update(ts[-1] + 0.6, [0.0, 0.0], SIGMA)
    assert tr.resets == 1
    np.testing.assert_array_equal(tr.estimate(ts[-1] + 0.6), [0.0, 0.0, 0.0, 0.0])


def test_late_measurements_are_fused_without_predicting_backwards():
    rng = np.random.default_rng(13)
    tr = ParticleBallTracker(np.random.default_rng(14), max_lag=0.1)
    ts, *_ = _roll(tr, rng, steps=60)
    t = ts[-1]
    x = tr.estimate(t)
    n_fused = tr.fused
    # 20 ms late, at the ball's true position then: fused, the filter's time unchanged.
    tr.update(t - 0.02, P0 + (t - ts[0] - 0.02) * V + [0.0, 0.05], SIGMA)
    assert tr.fused == n_fused + 1 and tr.time == t and tr.late == 0
    assert np.hypot(*(tr.estimate(t)[:2] - x[:2])) < 0.05
    tr.update(t - 0.5, [0.0, 0.0], SIGMA)  # beyond max_lag: ignored
    assert tr.late == 1 and tr.fused == n_fused + 1


def test_full_covariance_measurements():
    """A 2 x 2 covariance: precise across the motion, vague along it."""
    rng = np.random.default_rng(15)
    tr = ParticleBallTracker(np.random.default_rng(16))
    R = np.array([[0.04, 0.0], [0.0, 0.0004]])
    errs = []
    for k in range(1, 120):
        t = 0.04 * k
        truth = np.array([t, 0.5])
        tr.update(t, truth + rng.multivariate_normal([0, 0], R), R)
        errs.append(tr.estimate(t)[:2] - truth)
    errs = np.abs(np.array(errs[40:]))
    assert errs[:, 1].mean() < 0.02 < errs[:, 0].mean() < 0.2


@pytest.mark.parametrize("name", list(PARTICLE_FILTERS))
def test_same_seed_same_estimates(name):
    runs = []
    for _ in range(2):
        tr = ParticleBallTracker(np.random.default_rng(17), filter=name)
        _, _, _, est = _roll(tr, np.random.default_rng(18), steps=40)
        tr.predict_to(10.0)
        runs.append((est.tolist(), tr.particles.tolist()))
    assert runs[0] == runs[1]


def test_before_the_first_measurement_and_reset():
    tr = ParticleBallTracker(np.random.default_rng(0))
    assert tr.estimate(1.0) is None and tr.spread is None and not tr.initialized
    assert tr.particles.shape == (0, 4)
    tr.predict_to(1.0)  # nothing to predict
    tr.update(1.0, [0.5, -0.5], 0.1)
    assert tr.initialized and tr.particles.shape == (100, 4)
    np.testing.assert_array_equal(tr.estimate(1.0), [0.5, -0.5, 0.0, 0.0])
    assert 0.05 < tr.spread < 0.3  # about sqrt(2) sigma
    assert tr.weights.sum() == pytest.approx(1.0)
    tr.reset()
    assert tr.estimate(1.0) is None and tr.fused == 0


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"filter": "kalman"}, "filter"),
    ({"n_particles": 1}, "n_particles"),
    ({"n_particles": 10.5}, "n_particles"),
    ({"accel_sigma": 0.0}, "accel_sigma"),
    ({"deceleration": -0.1}, "deceleration"),
    ({"threshold": 0.0}, "threshold"),
    ({"fission_sigma": (0.1, 0.1)}, "fission_sigma"),
    ({"fission_sigma": (0.1, 0.1, -1.0, 0.1)}, "fission_sigma"),
    ({"sfn_when": "sometimes"}, "sfn_when"),
    ({"init_speed_sigma": math.nan}, "init_speed_sigma"),
    ({"gate": -1.0}, "gate"),
    ({"reinit_after": 0}, "reinit_after"),
    ({"lost_after": 0.0}, "lost_after"),
    ({"max_lag": -0.1}, "max_lag"),
    ({"kalman_start": 0}, "kalman_start"),
])
def test_bad_arguments_name_the_argument(kwargs, name):
    with pytest.raises(ValueError, match=name):
        ParticleBallTracker(np.random.default_rng(0), **kwargs)


def test_bad_measurements_name_the_argument():
    with pytest.raises(TypeError, match="Generator"):
        ParticleBallTracker(42)
    tr = ParticleBallTracker(np.random.default_rng(0))
    with pytest.raises(ValueError, match="^t "):
        tr.update(math.inf, [0.0, 0.0], 0.1)
    with pytest.raises(ValueError, match="^z "):
        tr.update(0.0, [0.0, math.nan], 0.1)
    with pytest.raises(ValueError, match="^z "):
        tr.update(0.0, [0.0, 0.0, 0.0], 0.1)
    with pytest.raises(ValueError, match="^sigma "):
        tr.update(0.0, [0.0, 0.0], 0.0)
    with pytest.raises(ValueError, match="^sigma "):
        tr.update(0.0, [0.0, 0.0], [[1.0, 2.0], [2.0, 1.0]])  # not positive definite
    with pytest.raises(ValueError, match="^sigma "):
        tr.update(0.0, [0.0, 0.0], [0.1, 0.1])
    assert not tr.initialized


def test_a_restart_on_a_kick_takes_the_new_motion_from_the_measurement_before_it():
    # A ball at rest, then kicked at 3 m/s along x: the measurement that fails the gate
    # restarts the filter with the finite-difference velocity (shrunk by the speed prior),
    # not with a ball at rest.
    rng = np.random.default_rng(0)
    tr = ParticleBallTracker(np.random.default_rng(1), filter="mfbpf")
    for k in range(20):
        tr.update(0.04 * k, rng.normal(0.0, 0.01, 2), 0.01)
    t = 0.04 * 20
    tr.update(t, np.array([0.12, 0.0]) + rng.normal(0.0, 0.01, 2), 0.01)  # kicked 40 ms ago
    assert tr.resets == 1
    vx, vy = tr.estimate(t)[2:4]
    assert vx == pytest.approx(3.0, abs=0.6) and abs(vy) < 0.5


def test_a_restart_does_not_believe_an_impossible_speed():
    # Two measurements 5 m apart in 40 ms (an outlier next to the ball): no ball moves at
    # 125 m/s, so the restart keeps the velocity prior (at rest).
    tr = ParticleBallTracker(np.random.default_rng(1), filter="mfbpf", max_speed=10.0)
    for k in range(20):
        tr.update(0.04 * k, np.zeros(2), 0.01)
    tr.update(0.8, np.array([5.0, 0.0]), 0.01)
    assert tr.resets == 1
    assert np.allclose(tr.estimate(0.8)[2:4], 0.0)
    with pytest.raises(ValueError, match="max_speed"):
        ParticleBallTracker(np.random.default_rng(1), max_speed=0.0)


def test_update_fused_is_update_without_the_checks():
    """The unchecked path (a pipeline's validated fused points) gives update()'s tracker bit
    for bit, through the Kalman start, the particles, gating and restarts."""
    runs = []
    for unchecked in (False, True):
        tracker = ParticleBallTracker(np.random.default_rng(4), deceleration=0.4)
        rng = np.random.default_rng(5)
        t = 0.0
        for k in range(120):
            t += 0.04
            z = P0 + V * t + rng.normal(0, SIGMA, 2) + (3.0 if k == 60 else 0.0)
            R = np.array([[0.01, 0.002], [0.002, 0.02]])
            if unchecked:
                tracker.update_fused(t, z, R)
            else:
                tracker.update(t, z, R)
        runs.append((tracker.particles, tracker.estimate(t + 0.05), tracker.resets))
    np.testing.assert_array_equal(runs[0][0], runs[1][0])
    np.testing.assert_array_equal(runs[0][1], runs[1][1])
    assert runs[0][2] == runs[1][2] >= 1


def test_an_estimate_kept_for_its_time_is_a_new_array_and_follows_the_filter():
    rng = np.random.default_rng(4)
    a = ParticleBallTracker(np.random.default_rng(1))
    b = ParticleBallTracker(np.random.default_rng(1))
    t = 0.0
    for k in range(40):
        t += 0.04
        z = np.array([0.5 * t, -0.2 * t]) + rng.normal(0.0, 0.01, 2)
        first = a.estimate(t + 0.02)  # asked for before and after each change of the filter
        if first is not None:
            first[:] = 99.0  # a caller's array: changing it changes nothing kept
        a.update(t, z, 0.01)
        b.update(t, z, 0.01)
        if k % 5 == 0:
            a.predict_to(t + 0.01)
            b.predict_to(t + 0.01)
        for q in (t + 0.02, t + 0.02, t - 0.01, t + 0.02):
            assert np.array_equal(a.estimate(q), b.estimate(q))
