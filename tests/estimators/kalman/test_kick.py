"""The kick-aware ball tracker against known truth: a ball at rest, a kick from rest, a
bounce, spurious detections, the kick hint, the two-phase law of motion and bad input."""

import math

import numpy as np
import pytest

from estimators import BallTracker, FrictionBallModel, KickAwareBall
from estimators.kalman.kick import travel

SIGMA = 0.025  # m, the ssl-2012 preset's ball noise
FPS = 25.0
SLIDE, ROLL, K = 3.0, 0.3, 0.64  # the SSL ball's two-phase model


def kicked(t, t_kick, start, velocity):
    """True positions and velocities ``(n, 4)`` at times ``t`` of a ball lying at ``start``
    and kicked at ``t_kick`` with ``velocity`` (two-phase friction)."""
    v0 = math.hypot(*velocity)
    u = np.asarray(velocity) / v0
    s, v = travel(np.asarray(t) - t_kick, v0, K * v0, SLIDE, ROLL)
    return np.column_stack([start[0] + u[0] * s, start[1] + u[1] * s, u[0] * v, u[1] * v])


def feed(tracker, t, truth, seed=0, sigma=SIGMA):
    rng = np.random.default_rng(seed)
    for tk, s in zip(t, truth):
        tracker.update(tk, (s[:2] + rng.normal(0.0, sigma, 2))[None])


def test_travel_is_the_two_phase_law():
    # Sliding: v0 tau - a_s tau^2 / 2 until the speed is k v0, then rolling until it stops.
    v0 = 5.0
    tau1 = (1 - K) * v0 / SLIDE
    s, v = travel(np.array([0.0, 0.5 * tau1, tau1]), v0, K * v0, SLIDE, ROLL)
    assert np.allclose(v, [v0, v0 - SLIDE * 0.5 * tau1, K * v0])
    assert math.isclose(s[2], v0 * tau1 - 0.5 * SLIDE * tau1**2)
    # Once rolling it is FrictionBallModel from the switch point, and it stops for good.
    rolled = FrictionBallModel(ROLL).predict(np.array([s[2], 0.0, K * v0, 0.0]), 1.3)
    s2, v2 = travel(np.array([tau1 + 1.3, tau1 + 100.0]), v0, K * v0, SLIDE, ROLL)
    assert math.isclose(s2[0], rolled[0]) and math.isclose(v2[0], rolled[2])
    assert math.isclose(s2[1], s[2] + (K * v0) ** 2 / (2 * ROLL)) and v2[1] == 0.0
    # Numerical integration of dv/dt = -a(v) agrees.
    dt, x, vel = 1e-5, 0.0, v0
    for _ in range(int(round(1.0 / dt))):
        a = SLIDE if vel > K * v0 else ROLL
        x += vel * dt - 0.5 * a * dt * dt
        vel = max(vel - a * dt, 0.0)
    assert math.isclose(travel(np.array(1.0), v0, K * v0, SLIDE, ROLL)[0], x, rel_tol=1e-4)
    # Before the start nothing moves.
    assert travel(np.array(-0.1), v0, K * v0, SLIDE, ROLL) == (0.0, 0.0)


def test_a_ball_at_rest_is_its_detections_mean_and_still():
    tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
    assert tracker.estimate(0.0) is None and tracker.covariance(0.0) is None
    assert not tracker.initialized
    t = np.arange(30) / FPS
    truth = np.tile([1.0, -0.5, 0.0, 0.0], (30, 1))
    rng = np.random.default_rng(3)
    z = truth[:, :2] + rng.normal(0.0, SIGMA, (30, 2))
    for tk, zk in zip(t, z):
        tracker.update(tk, zk[None])
    est = tracker.estimate(t[-1] + 0.12)
    assert tracker.at_rest
    assert np.allclose(est[:2], z.mean(axis=0), atol=1e-9)  # the mean, exactly
    assert est[2] == est[3] == 0.0
    assert np.hypot(*(est[:2] - truth[0, :2])) < 3 * SIGMA / math.sqrt(30)
    P = tracker.covariance(t[-1])
    assert math.isclose(P[0, 0], SIGMA**2 / 30) and P[2, 2] == 0.0
    assert tracker.since_start == 30 and tracker.segments == 0


def _kick_run(tracker, seed, t_kick=0.413, velocity=(-4.0, 1.5), frames=40):
    t = np.arange(frames) / FPS
    truth = kicked(t, t_kick, (0.5, 0.2), velocity)
    feed(tracker, t, truth, seed)
    return t, truth


def test_a_kick_is_found_and_fitted_from_the_kick_point():
    errors_v, errors_p, kicks = [], [], []
    for seed in range(20):
        tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
        t, truth = _kick_run(tracker, seed)
        kicks.append(tracker.kick_time - 0.413)
        est = tracker.estimate(t[-1])
        errors_v.append(np.hypot(*(est[2:] - truth[-1, 2:])))
        errors_p.append(np.hypot(*(est[:2] - truth[-1, :2])))
        assert tracker.segments == 1 and not tracker.at_rest
    # 30 frames of the motion and the kick point: velocity within a few cm/s, the position
    # below the detections' own noise, the kick time within a frame period.
    assert np.sqrt(np.mean(np.square(errors_v))) < 0.05
    assert np.sqrt(np.mean(np.square(errors_p))) < SIGMA / 2
    assert np.max(np.abs(kicks)) < 1.0 / FPS


def test_after_a_kick_it_knows_the_new_velocity_sooner_than_the_ekf():
    # The first 0.3 s after the first frame that shows the kick: velocity RMSE.
    t_kick = 0.413
    err = {"kick": [], "ekf": []}
    for seed in range(30):
        t = np.arange(40) / FPS
        truth = kicked(t, t_kick, (0.5, 0.2), (-4.0, 1.5))
        for name, tracker in (("kick", KickAwareBall(SLIDE, ROLL, K, SIGMA)),
                              ("ekf", BallTracker())):
            rng = np.random.default_rng(seed)
            for tk, s in zip(t, truth):
                tracker.update(tk, (s[:2] + rng.normal(0.0, SIGMA, 2))[None])
                if t_kick + 1 / FPS < tk <= t_kick + 0.3:
                    err[name].append(np.hypot(*(tracker.estimate(tk)[2:] - s[2:])))
    rms = {k: float(np.sqrt(np.mean(np.square(v)))) for k, v in err.items()}
    assert rms["kick"] < 0.5 * rms["ekf"], rms


def test_the_kick_hint_fixes_the_kick_time():
    tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
    tracker.kick(0.413)
    _kick_run(tracker, seed=1)
    assert tracker.kick_time == 0.413 and tracker.segments == 1


def test_covariance_is_symmetric_positive_definite_and_shrinks():
    tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
    t = np.arange(40) / FPS
    truth = kicked(t, 0.413, (0.5, 0.2), (-4.0, 1.5))
    rng = np.random.default_rng(5)
    spreads = []
    for tk, s in zip(t, truth):
        tracker.update(tk, (s[:2] + rng.normal(0.0, SIGMA, 2))[None])
        if tk > 0.5:
            P = tracker.covariance(tk)
            assert np.allclose(P, P.T) and np.all(np.linalg.eigvalsh(P) > 0)
            spreads.append(P[2, 2])
    assert spreads[-1] < 0.2 * spreads[0]


def test_a_spurious_detection_is_ignored_and_two_agreeing_ones_restart():
    tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
    t = np.arange(20) / FPS
    for tk in t:
        tracker.update(tk, [(0.0, 0.0)])
    before = tracker.estimate(0.8)
    tracker.update(0.8, [(3.0, 2.0)])  # far away: no kick could get it there
    assert np.array_equal(tracker.estimate(0.8), before) and tracker.rejected == 1
    tracker.update(0.84, [(0.0, 0.0)])  # the ball is still where it was
    assert np.allclose(tracker.estimate(0.84)[:2], 0.0)
    # Two detections far away that agree: the ball is there now.
    tracker.update(0.88, [(3.0, 2.0)])
    tracker.update(0.92, [(3.0, 2.0)])
    assert np.allclose(tracker.estimate(0.92)[:2], (3.0, 2.0), atol=1e-6)
    assert tracker.segments == 1


def test_a_lone_kick_that_the_next_frame_contradicts_is_undone():
    tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
    for tk in np.arange(20) / FPS:
        tracker.update(tk, [(0.0, 0.0)])
    tracker.update(0.8, [(0.2, 0.0)])  # near enough to be a kick: taken at once
    assert not tracker.at_rest and tracker.segments == 1
    tracker.update(0.84, [(0.0, 0.0)])  # but the ball had not moved
    assert tracker.at_rest and tracker.reverted == 1
    assert np.allclose(tracker.estimate(0.9), (0.0, 0.0, 0.0, 0.0))


def test_a_bounce_starts_a_new_motion_from_where_the_ball_was():
    # A ball rolling at 2 m/s along +y bounces off a wall at y = 1 with restitution 0.6.
    t = np.arange(50) / FPS
    model = FrictionBallModel(ROLL)
    state, last, truth = np.array([0.0, 0.0, 0.3, 2.0]), 0.0, []
    for tk in t:
        state = model.predict(state, tk - last)
        last = tk
        if state[1] > 1.0 and state[3] > 0:
            state[1], state[3], state[2] = 2.0 - state[1], -0.6 * state[3], 0.6 * state[2]
        truth.append(state.copy())
    truth = np.array(truth)
    tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
    feed(tracker, t, truth, seed=2)
    est = tracker.estimate(t[-1])
    assert tracker.segments >= 1
    assert np.hypot(*(est[:2] - truth[-1, :2])) < 2 * SIGMA
    assert np.hypot(*(est[2:] - truth[-1, 2:])) < 0.15


def test_frames_out_of_order_within_a_motion_are_fused():
    tracker = KickAwareBall(SLIDE, ROLL, K, SIGMA)
    t = np.arange(30) / FPS
    truth = kicked(t, 0.2, (0.0, 0.0), (3.0, 0.0))
    order = list(range(30))
    order[20], order[21] = order[21], order[20]
    for i in order:
        tracker.update(t[i], [tuple(truth[i, :2])])
    assert tracker.fused == 30 and tracker.segments == 1
    # Exact detections: within the resolution of the kick-time search.
    assert np.allclose(tracker.estimate(t[-1])[:2], truth[-1, :2], atol=5e-3)


def test_reset_forgets_everything():
    tracker = KickAwareBall()
    _kick_run(tracker, seed=0)
    tracker.reset()
    assert tracker.estimate(1.0) is None and tracker.fused == 0 and tracker.kick_time is None


@pytest.mark.parametrize("kwargs, name", [
    ({"sigma_xy": 0.0}, "sigma_xy"), ({"sigma_xy": float("nan")}, "sigma_xy"),
    ({"k_switch": 0.0}, "k_switch"), ({"k_switch": 1.5}, "k_switch"),
    ({"sliding_deceleration": -1.0}, "sliding_deceleration"),
    ({"rolling_deceleration": float("inf")}, "rolling_deceleration"),
    ({"gate": 0.0}, "gate"), ({"search": 0}, "search"), ({"lock": 2.5}, "lock"),
    ({"kick_search": -0.1}, "kick_search"),
])
def test_bad_arguments_are_named(kwargs, name):
    with pytest.raises(ValueError, match=name):
        KickAwareBall(**kwargs)


def test_bad_detections_are_refused():
    tracker = KickAwareBall()
    with pytest.raises(ValueError, match="finite"):
        tracker.update(0.0, [(float("nan"), 0.0)])
    with pytest.raises(ValueError, match="shape"):
        tracker.update(0.0, np.zeros((2, 3)))
    with pytest.raises(ValueError, match="t must be"):
        tracker.update(float("inf"), [(0.0, 0.0)])
    assert tracker.estimate(0.0) is None
