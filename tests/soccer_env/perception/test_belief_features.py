"""Belief features (``belief_features=True``): the observation says how sure the belief is,
with one layout in every mode, named in the builder's ``names``."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import soccer_env
from soccer_env.observations import (
    BELIEF_FEATURES,
    HUMANOID_BELIEF_FEATURES,
    ObservationBuilder,
)
from soccer_env.presets import field
from soccer_env.state import Belief, BeliefQuality

GK = "soccer_env/Goalkeeper-v0"
SSL_NAMES = tuple(f"belief.{n}" for n in BELIEF_FEATURES)
HUMANOID_NAMES = SSL_NAMES + tuple(f"belief.{n}" for n in HUMANOID_BELIEF_FEATURES)


def _features(env, obs):
    names = env.unwrapped.builder.names
    start = names.index("belief.ball.sigma")
    return dict(zip(names[start:], obs[start:].tolist()))


def _episode(env, seed):
    obs, info = env.reset(seed=seed)
    rows = [(_features(env, obs), info)]
    while True:
        obs, _, term, trunc, info = env.step(np.zeros(6, np.float32))
        rows.append((_features(env, obs), info))
        if term or trunc:
            return rows


@pytest.mark.parametrize("robot,names", [("ssl", SSL_NAMES), ("humanoid", HUMANOID_NAMES)])
@pytest.mark.parametrize("mode", ["truth", "raw", "perceived"])
def test_same_layout_in_every_mode(robot, names, mode):
    plain = gym.make(GK, robot=robot, obs_mode=mode)
    env = gym.make(GK, robot=robot, obs_mode=mode, belief_features=True)
    builder = env.unwrapped.builder
    assert builder.names == plain.unwrapped.builder.names + names
    assert env.observation_space.shape == (plain.observation_space.shape[0] + len(names),)
    obs, _ = env.reset(seed=3)
    plain_obs, _ = plain.reset(seed=3)
    # The features are appended: everything before them is the plain observation.
    np.testing.assert_array_equal(obs[: len(plain_obs)], plain_obs)
    for _ in range(30):
        obs, *_ = env.step(np.zeros(6, np.float32))
        assert env.observation_space.contains(obs)


@pytest.mark.parametrize("robot", ["ssl", "humanoid"])
def test_truth_mode_reads_a_perfect_sensor(robot):
    env = gym.make(GK, robot=robot, belief_features=True)
    for f, _ in _episode(env, 0)[:50]:
        assert f["belief.ball.sigma"] == f["belief.ball.velocity_sigma"] == 0.0
        assert f["belief.ball.age"] == 0.0 and f["belief.ball.tracking"] == 1.0
        assert f["belief.ball.lost"] == f["belief.ball.reset"] == 0.0
        assert f["belief.self.sigma_xy"] == f["belief.self.sigma_theta"] == 0.0
        assert f["belief.ball.measured_dx"] == f["belief.ball.measured_dy"] == 0.0
        if robot == "humanoid":  # the keeper and its three team-mates all see it
            assert f["belief.ball.seen_by"] == 4.0 and f["belief.ball.fused_age"] == 0.0


def test_perceived_features_describe_the_error():
    """Over 20 shots under ssl-2012, against the error of the belief at the present time
    (the features describe the observation's belief, predicted ahead by the actuation
    latency): while tracking, the reported spread is the size of the errors (RMS ratio
    within a factor 3); coasting and freshly reset tracks, which the features flag, err
    more than tracking ones. (Step by step the EKF's spread hardly correlates with its
    error, r ~ 0.01: the flags and the age carry what the spread misses.)"""
    env = gym.make(GK, obs_mode="perceived", perception="ssl-2012", belief_features=True)
    sig, err, flagged = [], [], []
    for seed in range(20):
        for f, info in _episode(env, seed)[1:]:
            if f["belief.ball.lost"]:
                continue
            sig.append(f["belief.ball.sigma"])
            e = info["estimate"]["ball_position"] - info["truth"]["ball_position"]
            err.append(float(np.hypot(*e)) / np.sqrt(2.0))  # per axis
            flagged.append(f["belief.ball.tracking"] == 0.0)
    sig, err, flagged = np.array(sig), np.array(err), np.array(flagged)
    assert len(sig) > 500 and flagged.sum() > 20
    ratio = np.sqrt(np.mean(err[~flagged] ** 2) / np.mean(sig[~flagged] ** 2))
    assert 1 / 3 < ratio < 3, ratio
    assert err[flagged].mean() > err[~flagged].mean()
    assert 0.005 < np.median(sig) < 0.2  # the vision's noise and the motion, not a bound


def test_status_is_lost_until_the_ball_is_seen_and_reset_after():
    """Raw and perceived SSL: the first observation knows nothing of the ball's motion
    (reset or lost), later ones track it."""
    for mode in ("raw", "perceived"):
        env = gym.make(GK, obs_mode=mode, perception="ssl-2012", belief_features=True)
        rows = _episode(env, 1)
        first = rows[0][0]
        assert first["belief.ball.reset"] + first["belief.ball.lost"] == 1.0
        assert any(f["belief.ball.tracking"] == 1.0 for f, _ in rows[10:])
        for f, _ in rows:
            status = [f[f"belief.ball.{s}"] for s in ("tracking", "coasting", "reset", "lost")]
            assert sorted(status) == [0.0, 0.0, 0.0, 1.0]


def test_coasting_when_frames_stop():
    """With every ball detection missed after the start, the track coasts, then is lost."""
    from soccer_env.perception.base import PerceptionConfig
    from soccer_env.perception.overhead import make_perception
    from soccer_env.presets import ball, robot, vision
    from soccer_env.sensors.overhead import DetectionFrame
    from soccer_env.state import WorldState

    spec = vision("ssl-2012")
    fld = field("ssl-div-b")
    pipe = make_perception("perceived", PerceptionConfig(spec), fld, robot("ssl"),
                           ball("ssl"), 1, features=True)
    state = WorldState(0.0, np.zeros(6), np.zeros((1, 6)), ("blue_0",), np.zeros(1, int))
    pipe.reset(state, np.random.default_rng(0))
    period = 1.0 / spec.frame_rate
    statuses = []
    for k in range(1, 60):
        t = k * period
        balls = ((0.01 * k, 0.0),) if k <= 10 else ()
        pipe.consume([DetectionFrame(0, t - spec.latency, t, balls, (0,), ((0.0, 0.0, 0.0),))],
                     t)
        seen, _ = pipe.beliefs(t)
        statuses.append(seen.quality.ball_status)
    assert statuses[4:10] == [0] * 6  # tracking while it is seen
    assert 1 in statuses[11:20]  # coasting once frames miss it
    assert statuses[-1] == 3  # lost after a second without it


def _measured(env, obs):
    """Where the latest measurement puts the ball, field frame, read from the observation:
    the believed ball (``ball.dx, ball.dy`` from the believed pose) plus ``measured_dx,
    measured_dy``, both in the body frame."""
    o = dict(zip(env.unwrapped.builder.names, obs.tolist()))
    c, s = o["self.ax"], -o["self.ay"]
    dx = o["ball.dx"] + o["belief.ball.measured_dx"]
    dy = o["ball.dy"] + o["belief.ball.measured_dy"]
    return np.array([o["self.x"] + c * dx - s * dy, o["self.y"] + s * dx + c * dy])


def _steps(env, seed):
    """``(obs, info)`` of every step of the episode of ``seed`` (doing nothing)."""
    obs, info = env.reset(seed=seed)
    rows = [(obs, info)]
    while True:
        obs, _, term, trunc, info = env.step(np.zeros(6, np.float32))
        rows.append((obs, info))
        if term or trunc:
            return rows


def test_raw_measurement_is_the_belief():
    """Raw SSL observations are the latest detection: the measurement is on the belief."""
    env = gym.make(GK, obs_mode="raw", perception="ssl-2012", belief_features=True)
    for f, _ in _episode(env, 4):
        assert abs(f["belief.ball.measured_dx"]) < 1e-5
        assert abs(f["belief.ball.measured_dy"]) < 1e-5


def test_ssl_measurement_is_the_latest_detection():
    """Perceived SSL: the measurement the features point at is within the vision's noise of
    where the ball was at the capture of the latest detection (``ball.age`` ago)."""
    env = gym.make(GK, obs_mode="perceived", perception="ssl-2012", belief_features=True)
    names = env.unwrapped.builder.names
    times, history, errors = [], [], []
    for obs, info in _steps(env, 6):
        times.append(info["truth"]["time"] if "truth" in info else 0.0)
        history.append(info["truth"]["ball_position"].copy() if "truth" in info else None)
        f = dict(zip(names, obs.tolist()))
        if f["belief.ball.lost"] or np.hypot(*info["truth"]["ball_velocity"]) < 1.0:
            continue  # a moving ball: the belief, predicted ahead, is elsewhere
        captured = times[-1] - f["belief.ball.age"]
        k = int(np.argmin(np.abs(np.array(times) - captured)))
        errors.append(np.hypot(*(_measured(env, obs) - history[k])))
    assert len(errors) > 20
    assert np.median(errors) < 0.06  # 25 mm noise; the capture time rounded to a step


def test_humanoid_kick_shows_in_the_measurement_first():
    """With team fusion and MFBPF, a kicked ball's belief stays near the kick point for
    several frames; the keeper's own sightings run ahead of it at once. Over 10 shots, 0.1 s
    after the kick the measurement is nearer the true ball than the belief is."""
    env = gym.make(GK, robot="humanoid-2012", obs_mode="perceived",
                   perception="kidsize-2012", belief_features=True)
    closer = 0
    for seed in range(10):
        fired = None
        for obs, info in _steps(env, seed)[1:]:
            if info["shot_fired"] and fired is None:
                fired = info["truth"]["time"]
            if fired is not None and info["truth"]["time"] - fired >= 0.1:
                truth = info["truth"]["ball_position"]
                belief = info["estimate"]["ball_position"]
                closer += np.hypot(*(_measured(env, obs) - truth)) < np.hypot(*(belief - truth))
                break
    assert closer >= 8


def test_humanoid_team_counts_sightings():
    env = gym.make(GK, robot="humanoid", obs_mode="perceived", belief_features=True)
    rows = _episode(env, 2)
    seen_by = [f["belief.ball.seen_by"] for f, _ in rows]
    assert max(seen_by) >= 2  # team-mates' sightings were fused
    assert all(0 <= s <= 4 for s in seen_by)
    assert all(f["belief.ball.fused_age"] >= 0.0 for f, _ in rows)
    loc = [f["belief.self.sigma_xy"] for f, _ in rows]
    assert 0.0 < np.median(loc) < 0.5  # the localization's particles have a spread


@pytest.mark.parametrize("robot", ["ssl", "humanoid"])
def test_match_and_shootout_have_them(robot):
    penv = soccer_env.parallel_env(blue=2, yellow=2, robot=robot, obs_mode="perceived",
                                   belief_features=True)
    obs, _ = penv.reset(seed=0)
    names = penv.builder.names
    expected = HUMANOID_NAMES if robot == "humanoid" else SSL_NAMES
    assert names[-len(expected):] == expected
    for agent, o in obs.items():
        assert penv.observation_space(agent).contains(o)
    shoot = gym.make("soccer_env/Shootout-v0", robot=robot, obs_mode="perceived",
                     belief_features=True)
    assert shoot.unwrapped.builder.names[-len(expected):] == expected
    obs, _ = shoot.reset(seed=0)
    assert shoot.observation_space.contains(obs)


MODE_NAMES = ("belief.ball.p_rest", "belief.ball.p_rolling", "belief.ball.p_maneuver")


def test_imm_mode_probabilities_are_features():
    """With the interacting multiple model filter the features end with its mode
    probabilities: a distribution over rest, rolling and maneuver, resting before the shot
    and rolling half a second after it."""
    env = gym.make(GK, obs_mode="perceived",
                   perception={"vision": "ssl-2012", "ball_filter": "imm"}, belief_features=True)
    names = env.unwrapped.builder.names
    assert names[-3:] == MODE_NAMES and names[-14:-3] == SSL_NAMES
    for seed in (0, 1, 4):  # shots fired once the resting ball has been seen for a while
        obs, info = env.reset(seed=seed)
        before, after, fired = [], [], None
        for step in range(200):
            obs, _, term, trunc, info = env.step(np.zeros(6, np.float32))
            assert env.observation_space.contains(obs)
            p = obs[-3:].astype(np.float64)
            assert p.min() >= 0.0 and p.sum() == pytest.approx(1.0, abs=1e-5)
            if fired is None and info["shot_fired"]:
                fired = step
            (before if fired is None else after).append(p)
            if term or trunc:
                break
        assert fired is not None and fired >= 7
        assert before[-1][0] > 0.7  # at rest, well seen
        assert after[12][1] > 0.7  # rolling 0.5 s after the shot
    check_env(env.unwrapped)


def test_mode_features_need_a_filter_with_modes():
    """Teams whose ball filters differ get no mode features (one layout for every agent); a
    builder asked for them refuses the truth and a quality without them."""
    penv = soccer_env.parallel_env(blue=1, yellow=1, obs_mode="perceived", belief_features=True,
                                   perception={"blue": {"ball_filter": "imm"},
                                               "yellow": {"ball_filter": "ekf"}})
    assert penv.builder.names[-11:] == SSL_NAMES
    both = soccer_env.parallel_env(blue=1, yellow=1, obs_mode="perceived",
                                   belief_features=True, perception={"ball_filter": "imm"})
    assert both.builder.names[-3:] == MODE_NAMES
    obs, _ = both.reset(seed=0)
    for agent, o in obs.items():
        assert both.observation_space(agent).contains(o)
    builder = ObservationBuilder(field("ssl-div-b"), [0], [0], belief_features=True,
                                 ball_modes=("rest", "rolling", "maneuver"))
    quality = BeliefQuality(0.01, 0.1, 0.0, 0, np.zeros((1, 2)), 0.0, 1)
    with pytest.raises(ValueError, match="mode probabilities"):
        builder.build(Belief(0.0, np.zeros(6), np.zeros((1, 6)), quality))
    truth = gym.make(GK, belief_features=True).unwrapped
    truth.reset(seed=0)
    with pytest.raises(ValueError, match="mode probabilities"):
        builder.build(truth.world.snapshot())


def test_check_env_with_features():
    check_env(gym.make(GK, obs_mode="perceived", belief_features=True).unwrapped)


def test_determinism_with_features():
    a = gym.make(GK, obs_mode="perceived", perception="ssl-2012", belief_features=True)
    b = gym.make(GK, obs_mode="perceived", perception="ssl-2012", belief_features=True)
    for (fa, _), (fb, _) in zip(_episode(a, 5), _episode(b, 5)):
        assert fa == fb


def test_bad_input():
    with pytest.raises(TypeError, match="belief_features"):
        gym.make(GK, belief_features="yes")
    builder = ObservationBuilder(field("ssl-div-b"), [0], [0], belief_features=True)
    with pytest.raises(ValueError, match="quality"):
        builder.build(Belief(0.0, np.zeros(6), np.zeros((1, 6))))


def test_names_for_accepts_team_names():
    builder = ObservationBuilder(field("ssl-div-b"), [0, 0, 1], [0, 2])
    assert builder.names_for("blue") == builder.names_for(0)
    assert builder.names_for("yellow") == builder.names_for(1)
    assert builder.names_for("blue") != builder.names_for("yellow")
    for bad in ("green", 2, True):
        with pytest.raises(ValueError, match="team"):
            builder.names_for(bad)
