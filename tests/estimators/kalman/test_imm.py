"""The interacting multiple model ball tracker: its equations against a numpy reference,
rest, kicks and rolling against known truth, gating and restarts, latency compensation,
out-of-order frames, numerical health and bad input."""

import math

import numpy as np
import pytest

from estimators.kalman import BallFilterConfig, BallTracker
from estimators.kalman.imm import DEFAULT_RATES, MIN_PROBABILITY, IMMBall
from estimators.models import FrictionBallMotion


def two_phase(t, p0, v0, t_kick, a_s=3.0, a_r=0.3, k=0.64):
    """True states ``(x, y, vx, vy)`` at times ``t`` of a ball at rest at ``p0`` kicked at
    ``t_kick`` with velocity ``v0``: it slides at ``a_s`` down to ``k`` times its kick speed,
    then rolls at ``a_r`` until it stops."""
    speed = math.hypot(*v0)
    u = np.asarray(v0, dtype=float) / speed
    tau1 = (1.0 - k) * speed / a_s
    out = []
    for tk in t:
        tau = tk - t_kick
        if tau <= 0.0:
            s = v = 0.0
        elif tau <= tau1:
            s, v = speed * tau - 0.5 * a_s * tau * tau, speed - a_s * tau
        else:
            r = min(tau - tau1, k * speed / a_r)
            s = speed * tau1 - 0.5 * a_s * tau1**2 + k * speed * r - 0.5 * a_r * r * r
            v = max(k * speed - a_r * r, 0.0)
        out.append((*(np.asarray(p0) + u * s), *(u * v)))
    return np.array(out)


def kicked_ball(seed, speed=4.0, fps=25.0, sigma=0.025, t_kick=1.01, duration=2.5):
    """Frame times, true states and detections of a ball kicked from rest in a random
    direction."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration, 1.0 / fps)
    angle = rng.uniform(0.0, 2.0 * math.pi)
    truth = two_phase(t, (0.5, -0.3), (speed * math.cos(angle), speed * math.sin(angle)),
                      t_kick)
    return t, truth, truth[:, :2] + rng.normal(0.0, sigma, (len(t), 2))


def game_frames(seed, steps=600, fps=60.0, sigma=0.01):
    """Frames of a ball kicked now and then, with misses, spurious detections, several
    detections per frame and a second camera seeing the same instant: ``(t, dets, robots)``."""
    rng = np.random.default_rng(seed)
    p, v = np.zeros(2), np.zeros(2)
    t, out = 0.0, []
    for _ in range(steps):
        dt = rng.choice([0.0, 1.0 / fps, 2.0 / fps]) if out else 0.0
        t += dt
        speed = math.hypot(*v)
        if speed > 0.0:
            v = v * max(0.0, speed - 0.3 * dt) / speed
        p = p + v * dt
        if rng.random() < 0.02:
            v = rng.uniform(-5.0, 5.0, 2)
        dets = [p + rng.normal(0.0, sigma, 2)] if rng.random() < 0.85 else []
        while rng.random() < 0.1:
            dets.append(rng.uniform(-4.0, 4.0, 2))
        robots = [p + rng.uniform(-0.5, 0.5, 2) for _ in range(rng.integers(0, 3))]
        out.append((t, np.reshape(dets, (-1, 2)), np.reshape(robots, (-1, 2))))
    return out


# --------------------------------------------------------------------------------------------
# The equations


class ReferenceIMM:
    """The IMM of the class docstring written with 4 x 4 numpy matrices (one-phase rolling
    model, every detection fused): the specification the plain-float filter must meet."""

    def __init__(self, f: IMMBall) -> None:
        self.f = f
        self.motion = FrictionBallMotion(f.rolling)
        r = f.sigma_xy**2
        self.R = r * np.eye(2)
        self.H = np.hstack([np.eye(2), np.zeros((2, 2))])
        rates = np.array(f.rates, dtype=float)
        self.leave = rates.sum(axis=1)
        self.jump = rates / np.where(self.leave > 0, self.leave, 1.0)[:, None]
        self.vr = (f.rest_noise / 0.04) ** 2
        self.t = None

    def start(self, t, z):
        r = self.f.sigma_xy**2
        x = np.array([z[0], z[1], 0.0, 0.0])
        big = (10.0 / 3.0) ** 2
        self.x = [x.copy(), x.copy(), x.copy()]
        self.P = [np.diag([r, r, self.vr, self.vr]), np.diag([r, r, big, big]),
                  np.diag([r, r, big, big])]
        self.mu = np.full(3, 1.0 / 3.0)
        self.t = t

    def transition(self, dt):
        stay = np.exp(-self.leave * dt)
        Pi = (1.0 - stay)[:, None] * self.jump
        Pi[np.diag_indices(3)] = stay
        return Pi

    def predict(self, dt):
        """Steps 1-3: predicted modes and ``c``."""
        Pi = self.transition(dt)
        c = Pi.T @ self.mu
        W = Pi * self.mu[:, None] / c[None, :]
        xs, Ps = [], []
        for j in range(3):
            x0 = sum(W[i, j] * self.x[i] for i in range(3))
            P0 = sum(W[i, j] * (self.P[i] + np.outer(self.x[i] - x0, self.x[i] - x0))
                     for i in range(3))
            if j == 0:
                F = np.diag([1.0, 1.0, 0.0, 0.0])
                q = self.f.rest_noise**2 * dt / 0.04
                Q = np.diag([q, q, self.vr, self.vr])
                x = F @ x0
            elif j == 1:
                x, F, Q = self.motion.transition(x0, dt, self.f.rolling_noise)
            else:
                F = np.eye(4)
                F[0, 2] = F[1, 3] = dt
                Q = self.f.maneuver_noise**2 * np.kron(
                    np.array([[dt * dt / 3.0, dt / 2.0], [dt / 2.0, 1.0]]), np.eye(2))
                x = F @ x0
            xs.append(x)
            Ps.append(F @ P0 @ F.T + Q)
        return xs, Ps, c

    def update(self, t, z):
        xs, Ps, c = self.predict(t - self.t)
        L = np.empty(3)
        for j in range(3):
            y = z - self.H @ xs[j]
            S = self.H @ Ps[j] @ self.H.T + self.R
            K = Ps[j] @ self.H.T @ np.linalg.inv(S)
            L[j] = math.exp(-0.5 * y @ np.linalg.solve(S, y)) / (
                2 * math.pi * math.sqrt(np.linalg.det(S)))
            IKH = np.eye(4) - K @ self.H
            xs[j] = xs[j] + K @ y
            Ps[j] = IKH @ Ps[j] @ IKH.T + K @ self.R @ K.T  # Joseph form
        mu = c * L / (c * L).sum()
        mu = np.maximum(mu, MIN_PROBABILITY)
        self.x, self.P, self.mu, self.t = xs, Ps, mu / mu.sum(), t

    @staticmethod
    def combine(xs, Ps, w):
        x = sum(wj * xj for wj, xj in zip(w, xs))
        return x, sum(wj * (Pj + np.outer(xj - x, xj - x)) for wj, xj, Pj in zip(w, xs, Ps))

    def estimate(self, t):
        if t <= self.t:
            return self.combine(self.x, self.P, self.mu) + (self.mu,)
        xs, Ps, c = self.predict(t - self.t)
        return self.combine(xs, Ps, c) + (c,)


@pytest.mark.parametrize("fps, sigma", [(25.0, 0.025), (60.0, 0.0014)])
def test_plain_float_filter_is_the_imm_of_its_docstring(fps, sigma):
    """Mixing, mode-matched prediction and update, mode probabilities and the combined
    estimate and covariance, at each frame and predicted ahead (latency compensation: the
    estimate at a later time is the model's prediction), equal the numpy reference."""
    f = IMMBall(sliding_deceleration=None, sigma_xy=sigma, gate=1e12)
    ref = ReferenceIMM(f)
    t, truth, z = kicked_ball(3, speed=3.0, fps=fps, sigma=sigma, duration=2.0)
    rng = np.random.default_rng(4)
    t = t + rng.uniform(0.0, 0.2 / fps, len(t))  # uneven frame intervals
    for k, tk in enumerate(t):
        f.update(tk, z[k][None])
        ref.update(tk, z[k]) if k else ref.start(tk, z[k])
        for ahead in (0.0, 0.045, 0.3):
            x, P, mu = ref.estimate(tk + ahead)
            np.testing.assert_allclose(f.estimate(tk + ahead), x, rtol=0, atol=1e-9)
            np.testing.assert_allclose(f.covariance(tk + ahead), P, rtol=1e-7, atol=1e-12)
            np.testing.assert_allclose(f.mode_probabilities(tk + ahead), mu, atol=1e-9)


def test_transition_probabilities_follow_the_rates():
    """Each row of ``Pi(T)`` sums to 1; ``Pi_ii = exp(-lambda_i T)``; over a long horizon
    the mode probabilities go where the first jump goes."""
    f = IMMBall()
    f.update(0.0, [(0.0, 0.0)])
    mu0 = f.mode_probabilities()
    np.testing.assert_allclose(mu0, 1.0 / 3.0)
    for T in (1e-4, 0.04, 1.0, 100.0):
        mu = f.mode_probabilities(T)
        assert mu.sum() == pytest.approx(1.0, abs=1e-12)
        leave = [sum(row) for row in DEFAULT_RATES]
        stay = [math.exp(-lam * T) for lam in leave]
        expected = [mu0[j] * stay[j] + sum(mu0[i] * (1 - stay[i]) * DEFAULT_RATES[i][j]
                                           / leave[i] for i in range(3) if i != j)
                    for j in range(3)]
        np.testing.assert_allclose(mu, expected, atol=1e-12)
    np.testing.assert_array_equal(f.mode_probabilities(0.0), mu0)  # not ahead: the latest


# --------------------------------------------------------------------------------------------
# Against known truth


def test_ball_at_rest_converges_below_the_noise():
    """25 mm noise at 25 Hz: after 30 frames the estimate is within 8 mm of the ball (the
    mean of 30 detections has 4.6 mm per axis), its speed is near zero and the rest mode
    dominates."""
    rng = np.random.default_rng(0)
    ball = np.array([1.2, -0.7])
    f = IMMBall()
    for k in range(30):
        f.update(k * 0.04, (ball + rng.normal(0.0, 0.025, 2))[None])
    est = f.estimate(29 * 0.04)
    assert np.hypot(*(est[:2] - ball)) < 0.008
    assert np.hypot(*est[2:]) < 0.05
    mu = f.mode_probabilities()
    assert mu[0] > 0.9 and mu.argmax() == 0


def _kick_errors(make, seeds, **kw):
    """Per seed and frame: velocity error in the first 0.3 s after the kick, position and
    velocity errors later, and the mode probabilities (IMM only)."""
    early, late_p, late_v, modes = [], [], [], []
    for seed in seeds:
        t, truth, z = kicked_ball(seed, **kw)
        f = make()
        e1, lp, lv, m = [], [], [], []
        for k, tk in enumerate(t):
            f.update(tk, z[k][None])
            est = f.estimate(tk)
            if 1.01 < tk <= 1.31:
                e1.append(np.hypot(*(est[2:] - truth[k, 2:])))
            elif tk > 1.31:
                lp.append(np.hypot(*(est[:2] - truth[k, :2])))
                lv.append(np.hypot(*(est[2:] - truth[k, 2:])))
            if isinstance(f, IMMBall):
                m.append(f.mode_probabilities())
        early.append(e1)
        late_p.append(lp)
        late_v.append(lv)
        modes.append(m)
    return np.array(early), np.array(late_p), np.array(late_v), np.array(modes)


def test_kick_from_rest_maneuver_takes_over_then_rolling():
    """A ball kicked from rest at 4 m/s (two-phase ball, 25 Hz, 25 mm noise, ten seeds).

    * In the first frame after the kick (30 ms of motion, about 12 cm, five times the noise)
      the maneuver mode becomes the most probable and the rest mode is all but dropped one
      frame later.
    * The velocity error (RMS over the seeds) is bounded by what the detections since the
      kick can tell: at the second frame after the kick by the two-point finite difference,
      ``sqrt(2) sigma / T`` = 0.88 m/s per axis, 1.25 m/s in 2-D; at the fourth frame by the
      least-squares slope of three detections, ``sigma / (T sqrt(2))`` = 0.44 m/s per axis,
      0.63 m/s in 2-D (the filter has four detections of the moving ball by then, the first
      of which showed it the kick).
    * From 0.3 s after the kick the rolling mode dominates, the position error (RMS) is below
      the noise of one detection per axis, and the velocity error below 0.2 m/s.
    """
    early, late_p, late_v, modes = _kick_errors(IMMBall, range(10))
    first = 26  # the first frame after the kick at 1.01 s
    assert (modes[:, first - 1, 0] > 0.9).all()
    assert (modes[:, first].argmax(axis=1) == 2).all() and (modes[:, first, 0] < 0.3).all()
    assert (modes[:, first + 1, 0] < 0.01).all()
    rms = np.sqrt(np.mean(early**2, axis=0))
    assert rms[1] < 1.25 and rms[3] < 0.63
    assert modes[:, first + 8:, 1].mean() > 0.9
    assert np.sqrt(np.mean(late_p**2)) < 0.025
    assert np.sqrt(np.mean(late_v**2)) < 0.2


def test_after_a_kick_the_velocity_is_no_worse_than_the_ekf():
    """The same detections into the default EKF (Zhao et al.'s, with the SSL ball's rolling
    deceleration): over the first 0.3 s after the kick the IMM's mean velocity error is not
    larger, at 2, 4 and 6 m/s."""
    for speed in (2.0, 4.0, 6.0):
        imm, _, _, _ = _kick_errors(IMMBall, range(8), speed=speed)
        ekf, _, _, _ = _kick_errors(lambda: BallTracker(BallFilterConfig(deceleration=0.3)),
                                    range(8), speed=speed)
        assert imm.mean() <= ekf.mean(), (speed, imm.mean(), ekf.mean())


def test_fast_kick_at_60_hz_is_followed_at_once():
    """A 6.5 m/s kick (the SSL limit) just after a frame, seen at 60 Hz with 1.4 mm noise: the
    first detection after the kick, over 10 cm (75 noise sigmas) from the resting ball, is
    fused (the maneuver mode's gate), the track is not restarted, and five frames later the
    velocity is right to 0.2 m/s."""
    t, truth, z = kicked_ball(1, speed=6.5, fps=60.0, sigma=0.0014, t_kick=1.0001,
                              duration=1.3)
    first = 61  # the first frame after the kick, 16.6 ms later: 10.6 cm away
    assert np.hypot(*(truth[first, :2] - truth[first - 1, :2])) > 0.1
    f = IMMBall(sigma_xy=0.0014)
    for k in range(first + 1):
        f.update(t[k], z[k][None])
    assert f.mode_probabilities()[2] > 0.5 and f.rejected == 0 and f.resets == 0
    for k in range(first + 1, first + 6):
        f.update(t[k], z[k][None])
    assert f.rejected == 0 and f.resets == 0
    assert np.hypot(*(f.estimate(t[k])[2:] - truth[k, 2:])) < 0.2


def test_latency_compensation_predicts_to_the_present():
    """Detections 80 ms old arrive stamped with their capture times; the estimate predicted
    to the present is closer to the ball than the latest detection (rolling ball, 25 mm
    noise, 25 Hz), and asking changes nothing."""
    t, truth, z = kicked_ball(5, speed=3.0, duration=3.0)
    lag = 2  # frames: 80 ms
    f = IMMBall()
    est_err, raw_err = [], []
    for k in range(lag, len(t)):
        f.update(t[k - lag], z[k - lag][None])
        est = f.estimate(t[k])
        np.testing.assert_array_equal(est, f.estimate(t[k]))
        if t[k] > 1.4:
            est_err.append(np.hypot(*(est[:2] - truth[k, :2])))
            raw_err.append(np.hypot(*(z[k - lag] - truth[k, :2])))
    assert np.sqrt(np.mean(np.square(est_err))) < 0.5 * np.sqrt(np.mean(np.square(raw_err)))


# --------------------------------------------------------------------------------------------
# Health


def test_probabilities_and_covariances_stay_valid():
    """Through kicks, misses, spurious detections, restarts and simultaneous views: the mode
    probabilities are in [0, 1] and sum to 1, the covariance is symmetric positive definite
    now and predicted ahead."""
    f = IMMBall(sigma_xy=0.01)
    for t, dets, robots in game_frames(7):
        f.update(t, dets, robots)
        if not f.initialized:
            continue
        for ahead in (None, 0.0, 0.05, 1.0):
            mu = f.mode_probabilities(None if ahead is None else t + ahead)
            assert ((mu >= 0.0) & (mu <= 1.0)).all() and mu.sum() == pytest.approx(1.0)
            P = f.covariance(t + (ahead or 0.0))
            np.testing.assert_array_equal(P, P.T)
            assert np.linalg.eigvalsh(P).min() > 0.0
            assert np.isfinite(f.estimate(t + (ahead or 0.0))).all()
    assert f.fused > 400 and f.rejected > 0 and f.resets > 0


# --------------------------------------------------------------------------------------------
# Gating, restarts, out-of-order frames


def _resting(f, n=20, point=(0.0, 0.0), sigma=0.0):
    rng = np.random.default_rng(0)
    for k in range(n):
        f.update(k * 0.04, (np.asarray(point) + rng.normal(0.0, sigma, 2))[None])
    return (n - 1) * 0.04


def test_spurious_detection_is_rejected_and_two_agreeing_restart():
    f = IMMBall()
    t = _resting(f, sigma=0.025)
    before = f.estimate(t + 0.08)
    f.update(t + 0.04, [(2.0, 1.0)])  # a spurious ball 2.2 m away, the real one missed
    assert f.rejected == 1 and f.resets == 0 and f.last_fused == t
    after = f.estimate(t + 0.08)
    assert np.hypot(*(after[:2] - before[:2])) < 1e-3 and np.hypot(*after[2:]) < 0.05
    f.update(t + 0.08, [(0.0, 0.0)])  # the ball again: the candidate is forgotten
    assert f.rejected == 1 and f.last_fused == t + 0.08
    f.update(t + 0.12, [(2.0, 1.0)])
    f.update(t + 0.16, [(2.12, 1.0)])  # two agreeing: the ball is there, moving at 3 m/s
    assert f.resets == 1 and f.since_start == 1 and f.last_fused == t + 0.16
    est = f.estimate(t + 0.16)
    np.testing.assert_allclose(est[:2], (2.12, 1.0), atol=1e-12)
    assert est[2] == pytest.approx(3.0, abs=0.5) and f.mode_probabilities()[0] < 0.1
    f.update(t + 0.2, [(2.24, 1.0)])  # and it follows from there
    assert f.rejected == 3 and f.estimate(t + 0.2)[2] == pytest.approx(3.0, abs=0.3)


def test_restart_on_a_still_ball_starts_at_rest():
    """The ball moved elsewhere and lies still (placed): the restart's two detections show
    no motion, so the rest mode takes most of the probability."""
    f = IMMBall()
    t = _resting(f, sigma=0.025)
    f.update(t + 0.04, [(1.0, 1.0)])
    f.update(t + 0.08, [(1.0, 1.0)])
    assert f.resets == 1 and f.mode_probabilities()[0] > 0.8
    np.testing.assert_allclose(f.estimate(t + 0.08), (1.0, 1.0, 0.0, 0.0), atol=1e-12)


def test_a_spurious_ball_near_the_real_one_is_no_kick():
    """A resting ball, 1.4 mm noise at 60 Hz. A second camera's frame 4 ms later shows only a
    ball 12 cm away (a spurious one at a robot's dribbler): no kick moves a ball that far in
    4 ms (at most 6.5 m/s), so it is gated out. After the ball went unseen for 0.3 s, one
    0.5 m away is not fused either (``max_jump``), although the gates then span metres: it
    takes a second detection that agrees to move the track there."""
    f = IMMBall(sigma_xy=0.0014)
    for k in range(30):
        f.update(k / 60, [(0.0, 0.0)])
    t = 29 / 60
    f.update(t + 0.004, [(0.12, 0.0)])
    assert f.rejected == 1 and np.hypot(*f.estimate(t + 0.1)[:2]) < 1e-3
    # The same after a frame that showed only a ball far away: the time that counts is the
    # time since the previous frame, not since the ball was last seen.
    f.update(t + 1 / 60, [(2.0, 2.0)])
    f.update(t + 1 / 60 + 0.004, [(0.12, 0.0)])
    assert f.rejected == 3 and np.hypot(*f.estimate(t + 0.1)[:2]) < 1e-3
    t += 2 / 60
    f.update(t, [(0.0, 0.0)])  # the ball again
    f.update(t + 0.3, [(0.5, 0.0)])
    assert f.rejected == 4 and f.resets == 0 and np.hypot(*f.estimate(t + 0.3)[:2]) < 1e-3
    f.update(t + 0.32, [(0.55, 0.0)])
    assert f.resets == 1 and f.estimate(t + 0.32)[0] == pytest.approx(0.55)
    g = IMMBall(sigma_xy=0.0014, max_jump=10.0)
    for k in range(32):
        g.update(k / 60, [(0.0, 0.0)])
    g.update(t + 0.3, [(0.5, 0.0)])  # without the bound: fused at once
    assert g.rejected == 0 and g.estimate(t + 0.3)[0] > 0.4


def test_nearest_of_several_detections_is_fused():
    """A spurious ball in the same frame as the real one is ignored."""
    f, g = IMMBall(), IMMBall()
    t = _resting(f)
    _resting(g)
    f.update(t + 0.04, [(0.3, 0.2), (0.001, 0.0)])
    g.update(t + 0.04, [(0.001, 0.0)])
    np.testing.assert_array_equal(f.estimate(t + 0.1), g.estimate(t + 0.1))
    assert f.rejected == 0


def test_out_of_order_frames_are_replayed():
    """Frames arriving out of capture order within ``history`` give the state of the frames
    in order; a frame older than the window is dropped and counted."""
    t, truth, z = kicked_ball(2, speed=3.0, duration=2.0)
    frames = [(tk, z[k][None]) for k, tk in enumerate(t)]
    rng = np.random.default_rng(1)
    order = np.arange(len(frames), dtype=float) + rng.uniform(0.0, 3.5, len(frames))
    ordered, shuffled = IMMBall(), IMMBall()
    for tk, zk in frames:
        ordered.update(tk, zk)
    for k in np.argsort(order):
        shuffled.update(*frames[k])
    assert shuffled.late == 0
    np.testing.assert_array_equal(shuffled.estimate(2.1), ordered.estimate(2.1))
    np.testing.assert_array_equal(shuffled.covariance(2.1), ordered.covariance(2.1))
    np.testing.assert_array_equal(shuffled.mode_probabilities(), ordered.mode_probabilities())
    shuffled.update(t[-1] - 0.6, z[0][None])  # older than the 0.5 s window
    assert shuffled.late == 1
    np.testing.assert_array_equal(shuffled.estimate(2.1), ordered.estimate(2.1))


def test_simultaneous_views_are_both_fused():
    """Two cameras seeing the same instant: the second view is fused too (no prediction over
    a zero interval) and makes the position surer."""
    f = IMMBall()
    t = _resting(f, sigma=0.0)
    f.update(t + 0.04, [(0.0, 0.0)])
    var = np.diag(f.covariance(t + 0.04))
    f.update(t + 0.04, [(0.001, 0.0)])
    assert f.time == t + 0.04 and f.fused == 21
    assert (np.diag(f.covariance(t + 0.04))[:2] < var[:2]).all()
    assert 0.0 < f.estimate(t + 0.04)[0] < 0.001


# --------------------------------------------------------------------------------------------
# Protocol and bad input


def test_protocol_and_reset():
    f = IMMBall()
    assert IMMBall.MODES == ("rest", "rolling", "maneuver")
    assert f.estimate(0.0) is None and f.covariance(0.0) is None and not f.initialized
    assert f.time == -math.inf and f.last_fused == -math.inf and f.since_start == 0
    f.update(0.0, np.zeros((0, 2)))  # an empty frame is fine
    assert f.estimate(0.0) is None
    t = _resting(f, sigma=0.01)
    f.update(t + 0.04, np.zeros((0, 2)), np.array([[0.1, 0.0, 0.5]]))  # robots as poses
    assert f.initialized and f.time == t + 0.04 and f.last_fused == t and f.since_start == 20
    est = f.estimate(t + 0.1)
    assert est.shape == (4,) and f.covariance(t + 0.1).shape == (4, 4)
    f.reset()
    assert f.estimate(1.0) is None and f.covariance(1.0) is None and not f.initialized
    assert f.time == -math.inf and f.last_fused == -math.inf and f.since_start == 0
    assert f.fused == f.rejected == f.resets == f.late == 0
    np.testing.assert_array_equal(f.mode_probabilities(), np.full(3, 1.0 / 3.0))
    f.update(0.0, [(5.0, 5.0)])  # a new episode starts from scratch
    np.testing.assert_array_equal(f.estimate(0.0), (5.0, 5.0, 0.0, 0.0))


def test_bad_frames_are_refused_without_changing_the_track():
    f = IMMBall()
    t = _resting(f, sigma=0.01)
    est = f.estimate(t + 0.1)
    with pytest.raises(ValueError, match="NaN measurements are refused"):
        f.update(t + 0.04, np.array([[np.nan, 0.0]]))
    with pytest.raises(ValueError, match="detections must have shape"):
        f.update(t + 0.04, np.zeros((1, 3)))
    with pytest.raises(ValueError, match="detections must have shape"):
        f.update(t + 0.04, [(0.0, 0.0, 0.0)])
    with pytest.raises(ValueError, match="obstacles"):
        f.update(t + 0.04, [(0.0, 0.0)], np.array([[np.inf, 0.0]]))
    with pytest.raises(ValueError, match="t must be a finite time"):
        f.update(math.nan, [(0.0, 0.0)])
    with pytest.raises(ValueError, match="before the latest measurement"):
        f.update(t - 20.0, [(0.0, 0.0)])
    with pytest.raises(ValueError, match="t must be a finite time"):
        f.estimate(math.inf)
    with pytest.raises(ValueError, match="t must be a finite time"):
        f.mode_probabilities(math.nan)
    np.testing.assert_array_equal(f.estimate(t + 0.1), est)
    assert f.fused == 19 and f.rejected == 0


@pytest.mark.parametrize("name, value", [
    ("rolling_deceleration", -0.1), ("rolling_deceleration", math.nan),
    ("sliding_deceleration", -1.0), ("sliding_deceleration", math.inf),
    ("k_switch", 0.0), ("k_switch", 1.5), ("sigma_xy", 0.0), ("sigma_xy", -0.01),
    ("rest_noise", 0.0), ("rolling_noise", -0.1), ("maneuver_noise", 0.0),
    ("maneuver_noise", "4"), ("gate", 0.0), ("gate", True), ("max_jump", 0.0),
    ("max_kick_speed", 11.0), ("history", -1.0), ("history", 11.0),
])
def test_bad_arguments_name_themselves(name, value):
    with pytest.raises(ValueError, match=f"^{name} must be"):
        IMMBall(**{name: value})


@pytest.mark.parametrize("rates, match", [
    ([[0, 1], [1, 0]], r"^rates must be a 3 x 3 matrix"),
    (5.0, r"^rates must be a 3 x 3 matrix"),
    ([[0, -1, 1], [1, 0, 1], [1, 1, 0]], r"^rates\[0\]\[1\] must be"),
    ([[0, 1, 1], [1, 0, 1], [1, math.nan, 0]], r"^rates\[2\]\[1\] must be"),
])
def test_bad_rates_name_the_entry(rates, match):
    with pytest.raises(ValueError, match=match):
        IMMBall(rates=rates)
