"""The shared parts of the ball trackers (:mod:`estimators.tracking`) and the Kalman blocks
(:mod:`estimators.kalman.blocks`): each part's rule on its own, and one contract test over
every ball tracker built from them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators import (
    BallFilterConfig,
    BallTracker,
    IMMBall,
    KickAwareBall,
    LeastSquaresBall,
    ParticleBallTracker,
    TrackQuality,
)
from estimators.kalman import blocks
from estimators.tracking import (
    CHI2_2DOF_999,
    MAX_SPEED_CHANGE,
    Gate,
    ReplayBuffer,
    TrackInitiator,
    TrackQualityMixin,
    TrackTimes,
    prior_gain,
)


def _random_blocks(rng):
    """A random covariance as blocks and as a 4 x 4 array."""
    L = rng.normal(size=(4, 4))
    P = L @ L.T + 0.1 * np.eye(4)
    return (tuple(P[0:2, 0:2].ravel()), tuple(P[0:2, 2:4].ravel()),
            tuple(P[2:4, 2:4].ravel())), P


def test_blocks_are_the_matrix_equations():
    rng = np.random.default_rng(0)
    H = np.hstack([np.eye(2), np.zeros((2, 2))])
    for _ in range(20):
        Pb, P = _random_blocks(rng)
        x = tuple(rng.normal(size=4))
        A, B = tuple(rng.normal(size=4)), tuple(rng.normal(size=4))
        F = np.block([[np.eye(2), np.reshape(A, (2, 2))], [np.zeros((2, 2)),
                                                            np.reshape(B, (2, 2))]])
        q, r = 0.3, 0.05
        Q = np.diag([0.0, 0.0, q, q])
        np.testing.assert_allclose(blocks.full_covariance(blocks.predict_covariance(Pb, A, B, q)),
                                   F @ P @ F.T + Q, atol=1e-12)
        z = tuple(rng.normal(size=2))
        y, Si, d2 = blocks.innovation(x, Pb, z, r)
        S = H @ P @ H.T + r * np.eye(2)
        np.testing.assert_allclose(np.reshape(Si, (2, 2)), np.linalg.inv(S), atol=1e-10)
        yv = np.asarray(z) - np.asarray(x)[:2]
        assert d2 == pytest.approx(float(yv @ np.linalg.solve(S, yv)))
        K = P @ H.T @ np.linalg.inv(S)
        x_ref = np.asarray(x) + K @ yv
        P_ref = (np.eye(4) - K @ H) @ P
        for xn, Pn in (blocks.update(x, Pb, y, Si, r),
                       blocks.update_closed_form(x, Pb, z, y, Si, r)):
            np.testing.assert_allclose(xn, x_ref, atol=1e-10)
            np.testing.assert_allclose(blocks.full_covariance(Pn), P_ref, atol=1e-10)


def test_gate_takes_the_nearest_in_the_metric():
    gate = Gate(CHI2_2DOF_999)
    S = (1.0, 0.0, 100.0)  # y is ten times as uncertain as x
    z, d2, Si = gate.nearest(0.0, 0.0, S, [(2.0, 0.0), (0.0, 5.0), (0.0, 5.0)])
    assert z == (0.0, 5.0) and d2 == pytest.approx(0.25) and Si == (1.0, -0.0, -0.0, 0.01)
    assert gate.nearest(0.0, 0.0, S, [(1.0, 0.0), (-1.0, 0.0)])[0] == (1.0, 0.0)  # first
    assert gate.admits(CHI2_2DOF_999) and not gate.admits(CHI2_2DOF_999 + 1e-9)
    assert Gate(None).admits(1e300)
    # A kick reaches kick_speed dt + 3 sigma; no time, no speed.
    assert gate.reaches(MAX_SPEED_CHANGE * 0.1 + 0.03, 0.1, 0.01)
    assert not gate.reaches(MAX_SPEED_CHANGE * 0.1 + 0.031, 0.1, 0.01)
    assert gate.reaches(0.03, -1.0, 0.01) and not gate.reaches(0.031, -1.0, 0.01)


def test_initiator_restarts_on_agreeing_detections():
    init = TrackInitiator(0.01)
    c = init.offer((), 0.0, (1.0, 1.0))
    assert c == ((0.0, (1.0, 1.0)),) and not init.ready(c)
    # Too far for a ball at MAX_SPEED_CHANGE: the older one was spurious.
    c = init.offer(c, 0.1, (3.0, 1.0))
    assert c == ((0.1, (3.0, 1.0)),)
    # Another camera's view of the same instant adds nothing.
    assert init.offer(c, 0.1, (3.01, 1.0)) is c
    c = init.offer(c, 0.2, (3.5, 1.0))
    assert init.ready(c) and c[0] == (0.1, (3.0, 1.0)) and c[-1] == (0.2, (3.5, 1.0))
    assert not TrackInitiator(0.01, count=3).ready(c)
    # The prior: detections a moment apart give a velocity near zero.
    assert init.prior_var == pytest.approx((MAX_SPEED_CHANGE / 3.0) ** 2)
    assert prior_gain(init.prior_var, 1e12) < 1e-10
    assert prior_gain(init.prior_var, 0.0) == 1.0


class _Digits(ReplayBuffer):
    """A tracker whose state is the digits of the frames it processed, in order."""

    def __init__(self, history: float) -> None:
        self.history = history
        self._track = TrackTimes()
        self.reset_replay()

    def process(self, state, t, value, obstacles):
        return TrackTimes(t, t, state.since_start * 10 + value)


def test_replay_buffer_processes_late_frames_in_capture_order():
    in_order, shuffled = _Digits(0.15), _Digits(0.15)
    frames = [(0.1, 1), (0.2, 2), (0.3, 3), (0.4, 4)]
    for t, v in frames:
        in_order.update_frame(t, v, ())
    for t, v in (frames[0], frames[2], frames[3], frames[1]):
        shuffled.update_frame(t, v, ())
    assert in_order._track == shuffled._track == TrackTimes(0.4, 0.4, 1234)
    # Older than the window (0.15 s before the latest, 0.4 s): dropped, counted.
    shuffled.update_frame(0.15, 9, ())
    assert shuffled._track == TrackTimes(0.4, 0.4, 1234) and shuffled.late == 1
    shuffled._track = TrackTimes()
    shuffled.reset_replay()
    assert shuffled.late == 0


def _trackers():
    cfg = BallFilterConfig(sigma_xy=0.01)
    return {
        "ekf": lambda: BallTracker(cfg),
        "least-squares": lambda: LeastSquaresBall(6, sigma_xy=0.01),
        "kick": lambda: KickAwareBall(sigma_xy=0.01),
        "imm": lambda: IMMBall(sigma_xy=0.01),
        "particles": lambda: ParticleBallTracker(np.random.default_rng(0), n_particles=200),
    }


@pytest.mark.parametrize("name", list(_trackers()))
def test_every_ball_tracker_reports_its_quality_from_the_shared_part(name):
    tr = _trackers()[name]()
    assert isinstance(tr, TrackQualityMixin) and isinstance(tr, TrackQuality)
    assert not tr.initialized and tr.time == -math.inf and tr.last_fused == -math.inf
    assert tr.since_start == 0 and tr.covariance(0.0) is None and tr.estimate(0.0) is None
    for k in range(8):
        t = k / 60.0
        if name == "particles":
            tr.update(t, np.array([0.5 * t, 0.0]), 0.01)
        else:
            tr.update(t, [[0.5 * t, 0.0]])
        assert tr.initialized and tr.time == t and tr.last_fused == t
        assert tr.since_start >= 1
    P = tr.covariance(tr.time + 0.1)
    assert P.shape == (4, 4) and np.isfinite(P).all()
    np.testing.assert_allclose(P, P.T, atol=1e-12)
    with pytest.raises(ValueError):
        tr.covariance(math.nan)
    tr.reset()
    assert not tr.initialized and tr.covariance(0.0) is None
