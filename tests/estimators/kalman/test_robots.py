"""The batched robot tracker against the 6-state Kalman filter core, across the angle wrap,
and bad input."""

import math

import numpy as np
import pytest

from estimators import ConstantVelocityMotion, KalmanFilter, PoseMeasurement, RobotTracker
from estimators.models import wrap_angle


def test_robot_tracker_equals_six_state_filter():
    """The decoupled, batched equations are the 6-state Kalman filter exactly."""
    q_xy, q_th, s_xy, s_th, s_v0 = 4.0, 30.0, 0.01, 0.03, 2.0
    tracker = RobotTracker(2, q_xy, q_th, s_xy, s_th, s_v0)
    motion = ConstantVelocityMotion(3, q=[q_xy, q_xy, q_th], angle_axes=(2,))
    meas = PoseMeasurement(s_xy, s_th)
    rng = np.random.default_rng(1)
    filters = [None, None]
    t_last = [0.0, 0.0]
    t = 0.0
    for _ in range(300):
        t += rng.uniform(0.01, 0.03)
        who = [i for i in range(2) if rng.random() < 0.8]
        z = np.column_stack([rng.uniform(-1, 1, (len(who), 2)),
                             wrap_angle(rng.uniform(-4, 4, len(who)))])
        tracker.update(t, z, who)
        for k, i in enumerate(who):
            if filters[i] is None:
                filters[i] = KalmanFilter(np.concatenate([z[k], np.zeros(3)]),
                                          np.diag(list(meas.R.diagonal()) + [s_v0**2] * 3))
            else:
                x_pred, F, Q = motion.transition(filters[i].x, t - t_last[i])
                filters[i].predict(F, Q, x_pred)
                filters[i].update(z[k], meas.H, meas.R, z_pred=meas.expected(filters[i].x),
                                  residual=meas.residual)
                filters[i].x[2] = wrap_angle(filters[i].x[2])
            t_last[i] = t
        for i in range(2):
            if filters[i] is not None:
                np.testing.assert_allclose(tracker.p[i], filters[i].x[:3], atol=1e-9)
                np.testing.assert_allclose(tracker.v[i], filters[i].x[3:], atol=1e-9)
                np.testing.assert_allclose(tracker.covariance(i), filters[i].P, atol=1e-9)


def test_robot_tracker_follows_a_turning_robot_across_the_angle_wrap():
    tracker = RobotTracker(1, q_theta=5.0, sigma_xy=0.002, sigma_theta=0.01)
    rng = np.random.default_rng(2)
    errs, omegas = [], []
    for k in range(200):
        t = k / 60
        truth = np.array([math.cos(t), math.sin(t), wrap_angle(3.0 + 4.0 * t)])
        z = truth + rng.normal(0, [0.002, 0.002, 0.01])
        tracker.update(t, z[None], [0])
        est = tracker.estimate(t)
        errs.append(abs(wrap_angle(est[0, 2] - truth[2])))
        omegas.append(est[0, 5])
    assert max(errs[50:]) < 0.05
    assert np.mean(omegas[100:]) == pytest.approx(4.0, rel=0.05)


def test_robot_tracker_bad_input():
    tr = RobotTracker(2)
    with pytest.raises(ValueError, match=r"index must be in 0..1"):
        tr.update(0.0, np.zeros((1, 3)), [2])
    with pytest.raises(ValueError, match="NaN measurements are refused"):
        tr.update(0.0, np.array([[np.nan, 0, 0]]), [0])
    with pytest.raises(ValueError, match=r"z must have shape \(1, 3\)"):
        tr.update(0.0, np.zeros((1, 2)), [0])
    assert not tr.seen.any()
    tr.update([1.0, 0.5], np.zeros((2, 3)), [0, 0])  # the second is older: dropped
    assert tr.seen.tolist() == [True, False] and tr.dropped == 1


def test_batched_trackers_equal_single_trackers_bit_for_bit():
    """RobotTrackerBatch fed the detections of several trackers (robots seen for the first
    time, late detections, headings across +-pi) holds the single trackers' estimates
    exactly."""
    from estimators import RobotTrackerBatch

    m, n = 5, 4
    rng = np.random.default_rng(3)
    singles = [RobotTracker(n) for _ in range(m)]
    batch = RobotTrackerBatch(m, n)
    clock = np.zeros(m)
    for _ in range(120):
        ks, is_, ts, zs = [], [], [], []
        for k in range(m):
            clock[k] += rng.choice([0.0, 1 / 60, 1 / 25])
            for i in rng.permutation(n)[: rng.integers(0, n + 1)].tolist():
                t = clock[k] - (0.05 if rng.random() < 0.1 else 0.0)  # now and then late
                z = [rng.uniform(-3, 3), rng.uniform(-2, 2), rng.uniform(-3.2, 3.2)]
                singles[k].update_robot(t, z, i)
                ks.append(k), is_.append(i), ts.append(t), zs.append(z)
        batch.update(ks, is_, ts, np.reshape(zs, (-1, 3)))
        ask = clock + 0.04
        est = batch.estimate(ask)
        for k, tr in enumerate(singles):
            assert est[k].tolist() == tr.estimate(ask[k]).tolist()
            assert batch.seen[k].tolist() == tr.seen.tolist()
    assert batch.dropped.tolist() == [tr.dropped for tr in singles]
    assert batch.dropped.sum() > 0
    batch.reset([1])
    assert not batch.seen[1].any() and batch.estimate(0.0)[1].tolist() == [[0.0] * 6] * n


def test_update_many_is_update_robot_in_turn_bit_for_bit():
    """A step's detections in one call (new robots, late detections, headings across +-pi,
    one robot twice) leave the tracker as update_robot of each in turn does."""
    n = 5
    rng = np.random.default_rng(8)
    one, many = RobotTracker(n), RobotTracker(n)
    clock = 0.0
    for _ in range(100):
        clock += rng.choice([1 / 60, 1 / 25])
        d = int(rng.integers(0, 2 * n))
        ids = rng.integers(0, n, d).tolist()
        ts = [clock - (0.05 if rng.random() < 0.1 else 0.0) for _ in ids]
        zs = [(rng.uniform(-3, 3), rng.uniform(-2, 2), rng.uniform(-3.2, 3.2)) for _ in ids]
        for t, z, i in zip(ts, zs, ids):
            one.update_robot(t, z, i)
        many.update_many(ts, ids, zs)
        assert many.estimate(clock + 0.02).tolist() == one.estimate(clock + 0.02).tolist()
        assert many.p.tolist() == one.p.tolist() and many.v.tolist() == one.v.tolist()
    assert many.dropped == one.dropped > 0
    assert many.seen.tolist() == one.seen.tolist()
