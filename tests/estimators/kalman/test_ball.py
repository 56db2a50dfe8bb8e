"""Ball trackers: contract, FilterPy equivalence, latency compensation, gating, resets,
out-of-order replay and long-run numerical health."""

import math

import numpy as np
import pytest
from filterpy.kalman import KalmanFilter as FilterPyKF

from estimators import (
    BallFilterConfig,
    BallTracker,
    BallTrackerBatch,
    FrictionBallModel,
    FrictionBallMotion,
    LeastSquaresBall,
)

PAPER = BallFilterConfig()  # Zhao et al.'s (2012) EKF
CONFIGS = {
    "kf": BallFilterConfig(deceleration=0.0, collision_noise=False, gate=None, reset_after=None),
    "ekf": PAPER,
    "ekf-improved": BallFilterConfig(propagation="rk"),
    "ekf-2phase": BallFilterConfig(two_phase=(3.0, 0.64)),
}


def make(name):
    return LeastSquaresBall() if name == "ls" else BallTracker(CONFIGS[name])


def trajectory(duration=3.0, fps=25.0, a=0.23, v0=(2.0, 1.2), wall_y=None, e=0.6):
    """True ball states at the frame times: friction deceleration, optional bounce."""
    model = FrictionBallModel(a)
    t = np.arange(0.0, duration, 1.0 / fps)
    state = np.array([0.0, 0.0, *v0])
    out, last = [], 0.0
    for tk in t:
        state = model.predict(state, tk - last)
        last = tk
        if wall_y is not None and state[1] > wall_y and state[3] > 0:
            state[1] = 2 * wall_y - state[1]
            state[3] = -e * state[3]
            state[2] *= e
        out.append(state.copy())
    return t, np.array(out)


@pytest.mark.parametrize("name", ["kf", "ekf", "ekf-improved", "ekf-2phase", "ls"])
def test_tracker_contract(name):
    f = make(name)
    assert f.estimate(0.0) is None and not f.initialized
    f.update(0.0, np.zeros((0, 2)))  # an empty frame is fine
    assert f.estimate(0.0) is None
    t, truth = trajectory(1.0)
    rng = np.random.default_rng(0)
    for tk, s in zip(t, truth):
        f.update(tk, (s[:2] + rng.normal(0, 0.01, 2))[None])
    est = f.estimate(t[-1] + 0.1)
    assert est.shape == (4,) and np.isfinite(est).all()
    np.testing.assert_array_equal(est, f.estimate(t[-1] + 0.1))  # estimating changes nothing
    with pytest.raises(ValueError, match="NaN measurements are refused"):
        f.update(t[-1] + 0.04, np.array([[np.nan, 0.0]]))
    np.testing.assert_array_equal(est, f.estimate(t[-1] + 0.1))
    with pytest.raises(ValueError):
        f.update(t[-1] + 0.04, np.zeros((1, 3)))
    f.reset()
    assert f.estimate(1.0) is None


def test_constant_velocity_tracker_matches_filterpy():
    dt = 0.04
    cfg = CONFIGS["kf"]
    ours = BallTracker(cfg)
    _, F, Q = FrictionBallMotion(0.0).transition(np.zeros(4), dt, cfg.sigma_r)
    ref = FilterPyKF(dim_x=4, dim_z=2)
    ref.F, ref.Q = F, Q
    ref.H = np.hstack([np.eye(2), np.zeros((2, 2))])
    ref.R = cfg.sigma_xy**2 * np.eye(2)
    t, truth = trajectory(3.0, fps=1 / dt, a=0.0)
    rng = np.random.default_rng(3)
    for k, (tk, s) in enumerate(zip(t, truth)):
        z = s[:2] + rng.normal(0, cfg.sigma_xy, 2)
        ours.update(tk, z[None])
        if k == 0:
            ref.x = np.array([z[0], z[1], 0.0, 0.0])
            ref.P = np.eye(4) * cfg.tau**2
        else:
            ref.predict()
            ref.update(z)
        np.testing.assert_allclose(ours.estimate(tk), ref.x.ravel(), atol=1e-9)
        np.testing.assert_allclose(ours.estimate_with_covariance(tk)[1], ref.P, atol=1e-9)


@pytest.mark.parametrize("propagation", ["jacobian", "rk"])
def test_tracker_arithmetic_equals_the_generic_filter(propagation):
    """The tracker's plain-float block equations are the KalmanFilter class's equations."""
    from estimators import KalmanFilter

    cfg = BallFilterConfig(propagation=propagation, gate=None, reset_after=None)
    ours = BallTracker(cfg)
    motion, meas = FrictionBallMotion(cfg.deceleration, propagation), ours.measurement
    t, truth = trajectory(2.0, v0=(3.0, -1.0), wall_y=None)
    rng = np.random.default_rng(8)
    ref, t_prev = None, None
    for tk, s in zip(t + rng.uniform(0, 0.01, len(t)), truth):
        z = s[:2] + rng.normal(0, 0.02, 2)
        robot = s[:2] + rng.normal(0, 0.3, 2)
        ours.update(tk, z[None], robot[None])
        if ref is None:
            ref = KalmanFilter([z[0], z[1], 0, 0], np.eye(4) * cfg.tau**2)
        else:
            sigma_v = ours.velocity_sigma(ref.x[:2], robot[None])
            x_pred, F, Q = motion.transition(ref.x, tk - t_prev, sigma_v)
            ref.predict(F, Q, x_pred)
            ref.update(z, meas.H, meas.R)
        t_prev = tk
        x, P = ours.estimate_with_covariance(tk)
        np.testing.assert_allclose(x, ref.x, atol=1e-10)
        np.testing.assert_allclose(P, ref.P, atol=1e-10)


def present_time_errors(tracker, latency, fps=25.0, noise=0.025, seed=0, **traj):
    """Errors at the present time of the tracker's estimate and of the raw detection."""
    t, truth = trajectory(fps=fps, **traj)
    rng = np.random.default_rng(seed)
    z = truth[:, :2] + rng.normal(0, noise, (len(t), 2))
    lag = int(round(latency * fps))
    est_err, raw_err = [], []
    for k in range(lag, len(t)):
        tracker.update(t[k - lag], z[k - lag][None])  # captured lag frames ago, arriving now
        est = tracker.estimate(t[k])
        est_err.append(np.hypot(*(est[:2] - truth[k, :2])))
        raw_err.append(np.hypot(*(z[k - lag] - truth[k, :2])))
    return np.array(est_err), np.array(raw_err)


def rmse(e):
    return float(np.sqrt(np.mean(np.square(e))))


@pytest.mark.parametrize("name", ["ekf", "ekf-improved"])
def test_latency_compensated_ekf_beats_raw_delayed_detections(name):
    """Zhao et al.'s (2012) setting: 25 Hz, 120 ms latency, 25 mm noise, a_f = 0.23 m/s^2."""
    est, raw = present_time_errors(make(name), latency=0.12, v0=(2.5, 1.0))
    settled = slice(10, None)
    assert rmse(est[settled]) * 5 <= rmse(raw[settled])


def test_no_compensation_lags_by_the_latency():
    """The same filter fed arrival times instead of capture times trails the ball."""
    t, truth = trajectory(v0=(2.5, 0.0))
    lag = 3
    comp, naive = make("ekf"), make("ekf")
    for k in range(lag, len(t)):
        comp.update(t[k - lag], truth[k - lag, :2][None])
        naive.update(t[k], truth[k - lag, :2][None])  # pretends the detection is fresh
    x_true = truth[-1, 0]
    assert abs(comp.estimate(t[-1])[0] - x_true) < 0.01
    assert abs(naive.estimate(t[-1])[0] - x_true) > 0.15  # ~ 120 ms at 2 m/s


def test_gate_ignores_false_detections():
    t, truth = trajectory(v0=(2.0, 0.5))
    rng = np.random.default_rng(4)
    f = make("ekf")
    errors = []
    for k, (tk, s) in enumerate(zip(t, truth)):
        dets = [s[:2] + rng.normal(0, 0.025, 2)]
        if k % 5 == 2:  # a spurious ball somewhere else on the field, in the same frame
            dets.append(rng.uniform(-4, 4, 2))
        if k % 11 == 7:  # or alone, with the ball missed
            dets = [rng.uniform(-4, 4, 2)]
        f.update(tk, np.array(dets))
        errors.append(np.hypot(*(f.estimate(tk)[:2] - s[:2])))
        if k == 10:
            locked = (f.resets, f.rejected)  # the first frames lock on with one reset
    assert max(errors[10:]) < 0.1
    assert f.rejected > locked[1] and f.resets == locked[0]


def test_reset_after_a_bounce_locks_on_within_a_few_frames():
    t, truth = trajectory(v0=(1.0, 2.0), wall_y=1.0, e=0.6)
    bounce = int(np.argmax(truth[:, 3] < 0))
    f = make("ekf")
    errs = []
    for tk, s in zip(t, truth):
        f.update(tk, s[:2][None])
        errs.append(np.hypot(*(f.estimate(tk)[2:] - s[2:])))
    assert f.resets + f.maneuvers >= 1
    assert max(errs[bounce + 4:]) < 0.2  # velocity re-acquired within 4 frames


def test_out_of_order_frames_are_replayed():
    """Two unsynchronised cameras, frames delivered in a jumbled order, equal in-order."""
    rng = np.random.default_rng(5)
    t_a = np.arange(0, 2, 1 / 30)
    t_b = t_a + 0.013
    times = np.sort(np.concatenate([t_a, t_b]))
    model = FrictionBallModel(0.23)
    start = np.array([0.0, 0.0, 2.0, -1.0])
    frames = [(tk, model.predict(start, tk)[:2] + rng.normal(0, 0.01, 2)) for tk in times]
    in_order, jumbled = make("ekf"), make("ekf")
    for tk, z in frames:
        in_order.update(tk, z[None])
    order = np.arange(len(frames))
    for k in range(0, len(order) - 3, 4):  # swap neighbours within 0.1 s
        order[[k, k + 2]] = order[[k + 2, k]]
    for k in order:
        jumbled.update(frames[k][0], frames[k][1][None])
    np.testing.assert_allclose(jumbled.estimate(2.1), in_order.estimate(2.1), atol=1e-12)
    late = make("ekf")
    for tk, z in frames:
        late.update(tk, z[None])
    late.update(0.0, np.zeros((1, 2)))  # older than the replay window: dropped, counted
    assert late.late == 1


def test_collision_noise_follows_eq_19():
    f = BallTracker(PAPER)
    c = PAPER
    far = f.velocity_sigma((0.0, 0.0), [[5.0, 0.0]])
    near = f.velocity_sigma((0.0, 0.0), np.array([[0.2, 0.0], [3.0, 1.0]]))
    assert far == c.sigma_r and f.velocity_sigma((0.0, 0.0)) == c.sigma_r  # no robots
    assert near == pytest.approx(c.gain_k * (c.robot_radius + c.ball_radius) / 0.2 * c.sigma_r)


@pytest.mark.slow
def test_covariance_stays_symmetric_positive_definite():
    """10^5 frames with gaps, outliers, false detections, kicks and stops."""
    rng = np.random.default_rng(6)
    f = BallTracker(BallFilterConfig(two_phase=(3.0, 0.64)))
    state = np.array([0.0, 0.0, 1.0, 0.5])
    model = FrictionBallModel(0.3)
    t = 0.0
    for k in range(100_000):
        dt = rng.choice([1 / 60, 1 / 30, 0.2])  # regular frames and gaps
        t += dt
        state = model.predict(state, dt)
        if rng.random() < 0.01:  # kicks
            state[2:] = rng.uniform(-6, 6, 2)
        if abs(state[0]) > 4 or abs(state[1]) > 3:
            state = np.array([0.0, 0.0, *rng.uniform(-3, 3, 2)])
        r = rng.random()
        if r < 0.1:
            dets = np.zeros((0, 2))
        elif r < 0.15:
            dets = rng.uniform(-5, 5, (1, 2))
        else:
            dets = state[None, :2] + rng.normal(0, 0.01, (1, 2))
        obstacles = rng.uniform(-4, 4, (3, 2))
        f.update(t, dets, obstacles)
        if k % 97 == 0:
            _, P = f.estimate_with_covariance(t + 0.05)
            assert np.allclose(P, P.T) and np.linalg.eigvalsh(P).min() > 0
    _, P = f.estimate_with_covariance(t)
    assert np.allclose(P, P.T) and np.linalg.eigvalsh(P).min() > 0
    assert f.fused > 50_000 and f.resets > 100


def test_config_validation():
    with pytest.raises(ValueError, match="sigma_xy must be finite and > 0"):
        BallFilterConfig(sigma_xy=0.0)
    with pytest.raises(ValueError, match="reset_after needs a gate"):
        BallFilterConfig(gate=None)
    with pytest.raises(ValueError, match="two_phase must be"):
        BallFilterConfig(two_phase=(3.0, 1.5))
    with pytest.raises(ValueError, match="window must be an integer >= 2"):
        LeastSquaresBall(1)
    assert math.isclose(CONFIGS["ekf"].sigma_xy, 0.025)


def test_reset_from_simultaneous_camera_views_still_finds_the_velocity():
    """Overlapping cameras capturing at the same instant give two detections with one time
    stamp; a reset must not take a zero velocity from them."""
    f = BallTracker(BallFilterConfig(sigma_xy=0.0014, maneuver_radius=None))
    f.update(0.0, [(0.0, 0.0)])
    for k in range(1, 10):
        t = k / 60
        z = (3.0 * t, 0.0)
        f.update(t, [z])
        f.update(t, [z])  # the same ball seen by a second camera at the same capture time
    assert f.resets >= 1
    assert f.estimate(9 / 60)[2] == pytest.approx(3.0, abs=0.1)


def test_maneuver_follows_a_kick_at_once():
    """A ball at rest kicked at 5 m/s: the first moving detection opens up the velocity."""
    f = BallTracker(BallFilterConfig(sigma_xy=0.0014))
    for k in range(10):
        f.update(k / 60, [(0.0, 0.0)])
    for k in range(1, 6):
        f.update(9 / 60 + k / 60, [(5.0 * k / 60, 0.0)])
        if k == 1:
            assert f.maneuvers == 1 and f.resets == 0
            assert f.estimate(9 / 60 + k / 60)[2] > 2.0
    assert f.estimate(9 / 60 + 5 / 60)[2] == pytest.approx(5.0, abs=0.3)


def test_no_maneuver_from_a_detection_too_far_for_the_time_elapsed():
    """A spurious detection 10 cm away a millisecond later is not a kick."""
    f = BallTracker(BallFilterConfig(sigma_xy=0.0014))
    for k in range(10):
        f.update(k / 60, [(0.0, 0.0)])
    f.update(9 / 60 + 0.001, [(0.1, 0.0)])
    assert f.maneuvers == 0 and f.rejected == 1
    assert abs(f.estimate(0.2)[2]) < 0.1


def test_reset_from_views_a_moment_apart_keeps_a_physical_speed():
    """Two cameras seeing a ball that was knocked away, a fraction of a millisecond apart,
    with centimetre noise: the finite-difference velocity of the reset would be hundreds of
    m/s; the tracker must stay below the fastest ball (it takes the velocity from later
    frames instead)."""
    sigma = 0.025
    f = BallTracker(BallFilterConfig(sigma_xy=sigma, maneuver_radius=None))
    for k in range(10):
        f.update(k * 0.04, [(0.0, 0.0)])
    # Knocked 0.5 m away at 4 m/s along x; seen by two cameras 0.3 ms apart, noise 2 sigma
    # in opposite directions along y.
    t1 = 0.4
    f.update(t1, [(0.5, 2 * sigma)])
    f.update(t1 + 0.0003, [(0.5 + 4.0 * 0.0003, -2 * sigma)])
    assert f.resets == 1
    assert np.hypot(*f.estimate(t1 + 0.0003)[2:]) < 10.0
    for k in range(1, 6):
        t = t1 + k * 0.04
        f.update(t, [(0.5 + 4.0 * (t - t1), 0.0)])
    assert f.estimate(t1 + 0.2)[2] == pytest.approx(4.0, abs=0.5)


def _frames(rng, steps, kicks=True):
    """Frames of a ball rolling with friction and kicked now and then, seen by two cameras
    (sometimes at the same instant), with misses, noise, spurious detections and robots near
    the ball: ``(t, detections (k, 2), obstacles (j, 2))``."""
    p, v = rng.uniform(-2, 2, 2), rng.uniform(-3, 3, 2)
    t, out = 0.0, []
    for _ in range(steps):
        t += rng.choice([0.0, 1 / 60, 1 / 30]) if out else 0.0
        speed = math.hypot(*v)
        if speed > 0:
            v = v * max(0.0, speed - 0.4 * (1 / 60)) / speed
        p = p + v / 60
        if kicks and rng.random() < 0.04:
            v = rng.uniform(-6, 6, 2)
        dets = []
        if rng.random() < 0.9:
            dets.append(p + rng.normal(0, 0.01, 2))
        while rng.random() < 0.15:
            dets.append(rng.uniform(-4, 4, 2))
        obs = [p + rng.uniform(-0.3, 0.3, 2) for _ in range(rng.integers(0, 3))]
        out.append((t, np.reshape(dets, (-1, 2)), np.reshape(obs, (-1, 2))))
    return out


@pytest.mark.parametrize("name", ["ekf", "kf", "ekf-2phase", "ekf-improved"])
def test_batched_trackers_equal_single_trackers_bit_for_bit(name):
    """BallTrackerBatch, fed frame by frame with the frames of several balls (kicks,
    outliers, restarts, simultaneous views, no detection), holds exactly the single trackers'
    states and predictions, and counts what they count."""
    configs = {
        "ekf": BallFilterConfig(),
        "kf": BallFilterConfig(deceleration=0.0, collision_noise=False, gate=None,
                               reset_after=None),
        "ekf-2phase": BallFilterConfig(two_phase=(4.0, 0.7)),
        "ekf-improved": BallFilterConfig(propagation="rk"),
    }
    cfg = configs[name]
    m, steps = 6, 160
    rng = np.random.default_rng(7)
    streams = [_frames(rng, steps) for _ in range(m)]
    singles = [BallTracker(cfg) for _ in range(m)]
    batch = BallTrackerBatch(m, cfg)
    for s in range(steps):
        rows = [k for k in range(m) if (s + k) % 5]  # not every tracker every time
        k_max = max(len(streams[k][s][1]) for k in rows)
        j_max = max(len(streams[k][s][2]) for k in rows)
        z = np.zeros((len(rows), k_max, 2))
        has = np.zeros((len(rows), k_max), dtype=bool)
        obs = np.zeros((len(rows), j_max, 2))
        seen = np.zeros((len(rows), j_max), dtype=bool)
        for r, k in enumerate(rows):
            t, d, o = streams[k][s]
            z[r, :len(d)], has[r, :len(d)] = d, True
            obs[r, :len(o)], seen[r, :len(o)] = o, True
            singles[k].update(t, d, o)
        batch.update(rows, [streams[k][s][0] for k in rows], z, has, obs, seen)
        t_ask = np.array([tr.time + 0.07 for tr in singles])
        est, known = batch.estimate(t_ask)
        for k, tr in enumerate(singles):
            assert known[k] == tr.initialized
            if tr.initialized:
                assert est[k].tolist() == tr.estimate(t_ask[k]).tolist()
                assert batch._x[k].tolist() == list(tr._track.x)
                assert batch._P[k].tolist() == [v for block in tr._track.P for v in block]
    for k, tr in enumerate(singles):
        assert (batch.fused[k], batch.rejected[k], batch.resets[k], batch.maneuvers[k]) == (
            tr.fused, tr.rejected, tr.resets, tr.maneuvers)
        assert batch.last_fused[k] == tr.last_fused and batch.since_start[k] == tr.since_start
    if name != "kf":  # the streams exercised the rare paths
        assert batch.resets.sum() > 0 and batch.rejected.sum() > 0
        assert batch.maneuvers.sum() > 0 and batch.fused.sum() > 0
    batch.reset([0])
    assert not batch.initialized[0] and batch.fused[0] == 0


def test_batched_trackers_refuse_frames_out_of_order():
    batch = BallTrackerBatch(2)
    batch.update([0, 1], [1.0, 1.0], np.zeros((2, 1, 2)), np.ones((2, 1), dtype=bool))
    with pytest.raises(ValueError, match="capture-time order"):
        batch.update([1], [0.5], np.zeros((1, 1, 2)), np.ones((1, 1), dtype=bool))
