"""The kick-aware sighting-line tracker against known truth: a resting ball, kicks, outliers,
lines out of order, bearings alone, restarts and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from estimators import LineBallTracker, SightingNoise

BEARING = math.radians(1.5)
REL = 0.03  # relative range error per metre
NOISE = SightingNoise(bearing_sigma=BEARING, range_per_metre=REL, pose_sigma_xy=0.0,
                      pose_sigma_theta=0.0)
DECEL = 0.4
PERIOD = 0.04  # 25 frames/s
#: The keeper (own sightings) and three team-mates.
OBSERVERS = ((0.0, 0.0, True), (2.5, 2.0, False), (3.0, -1.5, False), (-1.0, 2.0, False))


def rolled(p0, v, t):
    """Position and velocity ``t`` [s] after a kick from ``p0`` at ``v``, rolling to a stop."""
    p0, v = np.asarray(p0, float), np.asarray(v, float)
    s = float(np.hypot(*v))
    if t <= 0.0 or s == 0.0:
        return p0, np.zeros(2)
    tau = min(t, s / DECEL)
    u = v / s
    return p0 + u * (s * tau - 0.5 * DECEL * tau * tau), u * (s - DECEL * tau)


def sightings(rng, truth, t_end, observers=OBSERVERS, bearing_only=False, pose_sigmas=None):
    """``(arrival, t, ox, oy, angle, range, own, observer)`` of every observer's frames up to
    ``t_end``, sorted by arrival: own frames 40 ms late, team-mates' 70-90 ms. With
    ``pose_sigmas = (position [m], heading [rad])`` each observer's pose estimate is off by
    an error drawn once (what a localization's slowly changing error does)."""
    errors = [(rng.normal(0.0, pose_sigmas[0], 2), rng.normal(0.0, pose_sigmas[1]))
              if pose_sigmas else (np.zeros(2), 0.0) for _ in observers]
    out = []
    for k in range(int(round(t_end / PERIOD))):
        for j, (ox, oy, own) in enumerate(observers):
            t = k * PERIOD + 0.007 * j
            p, _ = truth(t)
            d = p - (ox, oy)
            r = float(np.hypot(*d))
            angle = math.atan2(d[1], d[0]) + rng.normal(0.0, BEARING) + errors[j][1]
            rr = math.nan if bearing_only else r * (1.0 + rng.normal(0.0, REL * r))
            delay = 0.04 + (0.0 if own else 0.03 + 0.02 * rng.random())
            o = np.array([ox, oy]) + errors[j][0]
            out.append((t + delay, t, float(o[0]), float(o[1]), angle, rr, own, j))
    out.sort()
    return out


def feed(tracker, lines):
    for _, t, ox, oy, angle, r, own, j in lines:
        tracker.line(t, ox, oy, angle, r, own, j)


def test_a_resting_ball_is_found_and_held():
    rng = np.random.default_rng(0)
    tracker = LineBallTracker(NOISE, deceleration=DECEL)
    feed(tracker, sightings(rng, lambda t: rolled((1.5, 0.4), (0, 0), t), 2.0))
    est = tracker.estimate(2.0)
    assert np.hypot(est[0] - 1.5, est[1] - 0.4) < 0.03
    assert np.hypot(est[2], est[3]) < 0.1
    cov = tracker.covariance(2.0)
    assert 0.0 < cov[0, 0] < 0.01 and 0.0 < cov[1, 1] < 0.01
    assert tracker.kicks == 0 and tracker.resets == 0 and tracker.late == 0


def lock_on_frames(seed, noise=NOISE, pose_sigmas=None, **kwargs):
    """Own frames after the kick until the belief's velocity is within 25 % of the truth's
    speed and stays there for the next 0.3 s (the belief read at each own frame's arrival);
    ``pose_sigmas``: the observers' pose errors (see :func:`sightings`)."""
    rng = np.random.default_rng(seed)
    angle = rng.uniform(-math.pi, math.pi)
    speed = rng.uniform(2.0, 4.0)
    kick = 1.5 + rng.uniform(0.0, PERIOD)
    p0 = (rng.uniform(0.5, 2.5), rng.uniform(-1.0, 1.0))
    v = (speed * math.cos(angle), speed * math.sin(angle))

    def truth(t):
        return rolled(p0, v, t - kick)

    tracker = LineBallTracker(noise, deceleration=DECEL, observers=4, **kwargs)
    good = []
    for arrival, t, ox, oy, a, r, own, j in sightings(rng, truth, kick + 0.5,
                                                     pose_sigmas=pose_sigmas):
        tracker.line(t, ox, oy, a, r, own, j)
        if own and t > kick:
            est = tracker.estimate(arrival)
            _, vt = truth(arrival)
            good.append(np.hypot(*(est[2:] - vt)) <= 0.25 * np.hypot(*vt))
    for k in range(len(good)):
        if all(good[k:k + 8]):
            return k + 1
    return len(good) + 1


def test_a_kick_is_learnt_within_a_few_frames():
    frames = [lock_on_frames(seed) for seed in range(30)]
    assert np.median(frames) <= 4, frames
    assert np.percentile(frames, 90) <= 8, frames


def slid(p0, v, t, sliding=2.0, k_switch=0.7):
    """Position and velocity ``t`` [s] after a kick from ``p0`` at ``v`` under the two-phase
    friction law: sliding at ``sliding`` [m/s^2] down to ``k_switch`` of the kick speed, then
    rolling at ``DECEL``."""
    p0, v = np.asarray(p0, float), np.asarray(v, float)
    s = float(np.hypot(*v))
    if t <= 0.0:
        return p0, np.zeros(2)
    u = v / s
    t1 = (1.0 - k_switch) * s / sliding
    if t <= t1:
        return p0 + u * (s * t - 0.5 * sliding * t * t), u * (s - sliding * t)
    p1 = p0 + u * (s * t1 - 0.5 * sliding * t1 * t1)
    return rolled(p1, u * k_switch * s, t - t1)


@pytest.mark.parametrize("two_phase", [True, False])
def test_a_kicked_ball_slides_before_it_rolls(two_phase):
    """With the ball's sliding phase in the model the believed speed follows the truth; with
    rolling alone it lags the faster deceleration."""
    rng = np.random.default_rng(5)
    kick, v = 1.0, (3.5, -1.0)
    tracker = LineBallTracker(NOISE, deceleration=DECEL,
                              sliding_deceleration=2.0 if two_phase else 0.0, k_switch=0.7)
    feed(tracker, sightings(rng, lambda t: slid((1.0, 0.5), v, t - kick), kick + 0.5))
    _, vt = slid((1.0, 0.5), v, 0.5)
    ratio = np.hypot(*tracker.estimate(kick + 0.5)[2:]) / np.hypot(*vt)
    if two_phase:
        assert abs(ratio - 1.0) < 0.03, ratio
    else:
        assert ratio > 1.05, ratio


def test_observer_biases_let_a_kick_be_seen_through_localization_errors():
    """Each observer's pose error, drawn once per episode (5 cm, 2.5 degrees), is a bias its
    lines share: in the state, a line is compared with where that observer has been seeing
    the ball, and a kick is learnt sooner than with the errors taken as white noise."""
    noise = NOISE._replace(pose_sigma_xy=0.05, pose_sigma_theta=math.radians(2.5))
    pose = (0.05, math.radians(2.5))
    frames = {biases: [lock_on_frames(seed, noise, pose, biases=biases) for seed in range(40)]
              for biases in (True, False)}
    assert np.median(frames[True]) <= 3, frames
    assert np.mean(frames[True]) < np.mean(frames[False]) - 0.3, frames


def test_an_outlier_does_not_move_the_track():
    rng = np.random.default_rng(1)
    tracker = LineBallTracker(NOISE, deceleration=DECEL)
    lines = sightings(rng, lambda t: rolled((1.5, 0.4), (0, 0), t), 2.0)
    feed(tracker, lines[:-8])
    t_out = max(ln[1] for ln in lines[:-8]) + 0.001
    tracker.line(t_out, 0.0, 0.0, math.atan2(-1.0, 1.0), 1.4, True, 0)  # 1.4 m off
    assert tracker.kick_pending
    feed(tracker, lines[-8:])
    est = tracker.estimate(2.0)
    assert not tracker.kick_pending and tracker.kicks == 0
    assert np.hypot(est[0] - 1.5, est[1] - 0.4) < 0.05
    assert np.hypot(est[2], est[3]) < 0.2


def test_lines_out_of_order_give_the_state_of_lines_in_order():
    rng = np.random.default_rng(2)
    lines = sightings(rng, lambda t: rolled((1.0, 0.0), (2.0, 1.0), t - 0.8), 1.6)
    in_order = LineBallTracker(NOISE, deceleration=DECEL)
    feed(in_order, sorted(lines, key=lambda ln: ln[1]))
    shuffled = LineBallTracker(NOISE, deceleration=DECEL)
    feed(shuffled, lines)  # by arrival: team-mates' lines come after later own ones
    assert shuffled.late == 0
    np.testing.assert_array_equal(shuffled.estimate(1.7), in_order.estimate(1.7))
    np.testing.assert_array_equal(shuffled.covariance(1.7), in_order.covariance(1.7))


def test_bearings_alone_triangulate_a_started_track():
    rng = np.random.default_rng(3)
    tracker = LineBallTracker(NOISE, deceleration=DECEL)
    tracker.line(0.0, 0.0, 0.0, math.atan2(0.4, 1.5), 1.7, True, 0)  # a range 0.15 m long
    feed(tracker, sightings(rng, lambda t: rolled((1.5, 0.4), (0, 0), t), 1.0,
                            bearing_only=True))
    est = tracker.estimate(1.0)
    assert np.hypot(est[0] - 1.5, est[1] - 0.4) < 0.03
    # Bearing-only lines start nothing.
    fresh = LineBallTracker(NOISE)
    fresh.line(0.0, 0.0, 0.0, 0.3, math.nan, True)
    assert fresh.estimate(0.0) is None and fresh.covariance(0.0) is None
    assert fresh.rejected == 1


def test_a_lost_ball_restarts_and_old_lines_are_dropped():
    tracker = LineBallTracker(NOISE, lost_after=1.0, history=0.5)
    tracker.line(0.0, 0.0, 0.0, 0.0, 1.0, True)
    tracker.line(2.0, 0.0, 0.0, math.pi / 2, 2.0, True)  # 2 s later, elsewhere
    est = tracker.estimate(2.0)
    assert tracker.resets == 1 and np.allclose(est, (0.0, 2.0, 0.0, 0.0), atol=1e-9)
    tracker.line(1.2, 0.0, 0.0, 0.0, 1.0, True)  # 0.8 s late: beyond the replay window
    assert tracker.late == 1
    np.testing.assert_array_equal(tracker.estimate(2.0), est)


@pytest.mark.parametrize("kwargs, match", [
    ({"noise": (0.1,)}, "noise must be a SightingNoise"),
    ({"noise": SightingNoise(bearing_sigma=0.0)}, "noise.bearing_sigma"),
    ({"noise": SightingNoise(0.01, range_per_metre=-1.0)}, "noise.range_per_metre"),
    ({"deceleration": -0.1}, "deceleration"),
    ({"kick_sigma": 0.0}, "kick_sigma"),
    ({"gate": math.nan}, "gate"),
    ({"suspect": 20.0}, "suspect must be at most gate"),
    ({"kick_window": 1.0}, "kick_window must be at most history"),
    ({"sliding_deceleration": -1.0}, "sliding_deceleration"),
    ({"k_switch": 1.5}, r"k_switch must be in \(0, 1\]"),
    ({"observers": 0}, "observers must be a count"),
    ({"observers": (1, 1)}, "observers must be a count"),
    ({"observers": (1, "2")}, "observers must be a count"),
    ({"observers": None}, "observers must be a count"),
])
def test_bad_settings_are_named(kwargs, match):
    args = {"noise": NOISE, **kwargs}
    with pytest.raises((TypeError, ValueError), match=match):
        LineBallTracker(**args)


@pytest.mark.parametrize("args, match", [
    ((math.nan, (0, 0), 0.0, 1.0), "t must be a finite time"),
    ((0.0, (0, math.inf), 0.0, 1.0), "origin and angle must be finite"),
    ((0.0, (0, 0), "north", 1.0), "origin must be"),
    ((0.0, (0, 0), 0.0, 0.0), "range_ must be > 0"),
    ((0.0, (0, 0), 0.0, -2.0), "range_ must be > 0"),
    ((0.0, (0, 0), 0.0, 1.0, True, 7), r"observer must be one of the tracker's observers \[0, "),
])
def test_bad_lines_are_named_and_change_nothing(args, match):
    tracker = LineBallTracker(NOISE)
    tracker.update_line(0.0, (0.0, 0.0), 0.0, 1.0)
    before = tracker.estimate(0.5)
    with pytest.raises(ValueError, match=match):
        tracker.update_line(*args)
    np.testing.assert_array_equal(tracker.estimate(0.5), before)
