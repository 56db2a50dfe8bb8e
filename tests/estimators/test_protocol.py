"""The tracker protocol: every time-stamped tracker answers reset(), update(t, z, ...) and
estimate(t) alike. Each case feeds the same ball, rolling in a straight line, through the
tracker's own measurement form and reads the ball's ``(x, y, vx, vy)`` back from its
estimate."""

from __future__ import annotations

import numpy as np
import pytest

from estimators import (
    PARTICLE_FILTERS,
    BallFilterConfig,
    BallTracker,
    LeastSquaresBall,
    ParticleBallTracker,
    RobotTracker,
    Tracker,
)

P0 = np.array([-2.0, 1.0])  # the ball's start [m]
V = np.array([1.0, -0.5])  # its velocity [m/s]
SIGMA = 0.005  # measurement noise [m]
HEADING = 0.3  # the tracked robot's heading (RobotTracker) [rad]
ROBOT = 1  # the robot RobotTracker follows (of two)


def _ball(factory):
    return factory, lambda tr, t, z: tr.update(t, z[None]), lambda est: est


def _particle(name):
    return (lambda: ParticleBallTracker(np.random.default_rng(3), filter=name),
            lambda tr, t, z: tr.update(t, z, SIGMA), lambda est: est)


def _robots():
    def feed(tr, t, z):
        tr.update(t, [[z[0], z[1], HEADING]], [ROBOT])

    return (lambda: RobotTracker(2, q_xy=0.1, sigma_xy=SIGMA), feed,
            lambda est: est[ROBOT, [0, 1, 3, 4]])


# name -> (make a tracker, feed it one measurement of the ball, the ball's state in an estimate)
CASES = {
    "kf": _ball(lambda: BallTracker(BallFilterConfig(deceleration=0.0, collision_noise=False,
                                                     gate=None, reset_after=None))),
    "ekf": _ball(BallTracker),
    "ekf-improved": _ball(lambda: BallTracker(BallFilterConfig(propagation="rk"))),
    "least-squares": _ball(LeastSquaresBall),
    **{f"particle-{name}": _particle(name) for name in PARTICLE_FILTERS},
    "robots": _robots(),
}


def _roll(tracker, feed, steps=25, dt=0.04, seed=0):
    """Feed ``steps`` noisy positions of the rolling ball; returns the last time."""
    rng = np.random.default_rng(seed)
    t = 0.0
    for k in range(steps):
        t = k * dt
        feed(tracker, t, P0 + t * V + rng.normal(0.0, SIGMA, 2))
    return t


def _nothing_yet(tracker, t):
    """``estimate(t)`` before any measurement: None; for the multi-target RobotTracker, every
    robot unseen and its row zeros (it answers for all its robots at once)."""
    est = tracker.estimate(t)
    if isinstance(tracker, RobotTracker):
        return est.shape == (tracker.n, 6) and not tracker.seen.any() and not est.any()
    return est is None


@pytest.mark.parametrize("name", list(CASES))
def test_time_stamped_trackers_follow_the_protocol(name):
    make, feed, ball = CASES[name]
    tracker = make()
    assert isinstance(tracker, Tracker)
    assert _nothing_yet(tracker, 1.0)
    for episode in range(2):  # reset() starts a new episode
        tracker.reset()
        assert _nothing_yet(tracker, 1.0)
        t_last = _roll(tracker, feed, seed=episode)
        t = t_last + 0.2  # later than the last measurement: a prediction
        est = ball(tracker.estimate(t))
        truth = np.concatenate([P0 + t * V, V])
        assert est.shape == (4,) and np.all(np.isfinite(est))
        assert np.hypot(*(est[:2] - truth[:2])) < 0.05, (est, truth)
        assert np.hypot(*(est[2:] - truth[2:])) < 0.25, (est, truth)
        # Estimating changes nothing.
        np.testing.assert_array_equal(ball(tracker.estimate(t)), est)


def test_filter_cores_and_image_trackers_are_not_time_stamped_trackers():
    from estimators import KalmanFilter, KLDLocalizer, PlainMeanShift

    assert not isinstance(KalmanFilter(np.zeros(2), np.eye(2)), Tracker)
    assert not isinstance(KLDLocalizer((-1.0, 1.0, -1.0, 1.0), np.random.default_rng(0)),
                          Tracker)
    assert not isinstance(PlainMeanShift((5.0, 5.0), (3, 3)), Tracker)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf"), 1.3e155, "soon"])
@pytest.mark.parametrize("name", list(CASES))
def test_trackers_refuse_impossible_time_stamps_and_stay_as_they_were(name, bad):
    """A NaN, infinite, absurd (a frame stamped 1.3e155 s turned a track into NaN for the
    next 30 frames) or non-numeric time stamp raises ValueError naming ``t``, in update and
    in estimate, before changing anything."""
    make, feed, ball = CASES[name]
    tracker = make()
    t = _roll(tracker, feed)
    before = np.array(tracker.estimate(t + 0.1))
    with pytest.raises(ValueError, match=r"\bt must be"):
        feed(tracker, bad, P0 + t * V)
    with pytest.raises(ValueError, match=r"\bt must be"):
        tracker.estimate(bad)
    np.testing.assert_array_equal(tracker.estimate(t + 0.1), before)
    assert np.all(np.isfinite(before))


@pytest.mark.parametrize("name", list(CASES))
def test_a_clock_that_goes_back_is_refused_but_late_frames_are_not(name):
    """A measurement older than the latest by more than MAX_REWIND is no late frame but a
    clock that went back (a new episode fed without reset()): refused, naming reset().
    Ordinary late frames (tens of milliseconds) are taken as the tracker's own rules say."""
    from estimators.protocol import MAX_REWIND

    make, feed, ball = CASES[name]
    tracker = make()
    t = _roll(tracker, feed, steps=300)  # 12 s of frames
    assert t > MAX_REWIND
    feed(tracker, t - 0.05, P0 + (t - 0.05) * V)
    with pytest.raises(ValueError, match=r"before the latest measurement.*reset\(\)"):
        feed(tracker, t - MAX_REWIND - 1.0, P0)
    tracker.reset()
    feed(tracker, 0.0, P0)  # after a reset the clock may start again
