"""The environments with humanoid robots: Gymnasium and PettingZoo API checks, seeding, spaces,
``info["robot_state"]``, per-robot beliefs, head control and rendering."""

from __future__ import annotations

import math
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from pettingzoo.test import parallel_api_test, parallel_seed_test

import soccer_env

#: The keys of ``info["robot_state"][name]`` (see ``World.humanoid_state``).
ROBOT_STATE_KEYS = {"fallen", "kicking", "pan", "tilt", "sway", "odometry", "falls", "kicks"}
MIXED = {"blue": "ssl", "yellow": "humanoid"}


def keeper(obs_mode="perceived", **kw):
    return gym.make("soccer_env/Goalkeeper-v0", robot="humanoid", obs_mode=obs_mode, **kw)


def humanoid_match(robot="humanoid", obs_mode="perceived", max_cycles=40, **kw):
    kw.setdefault("field", "humanoid-kid")
    return soccer_env.parallel_env(blue=2, yellow=2, robot=robot, obs_mode=obs_mode,
                                   max_cycles=max_cycles, **kw)


# ----------------------------------------------------------------------------------------
# API checkers
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("obs_mode", ["truth", "raw", "perceived"])
def test_humanoid_goalkeeper_passes_check_env(obs_mode):
    env = keeper(obs_mode)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped, skip_render_check=True)


@pytest.mark.parametrize("robot", ["humanoid", MIXED], ids=["humanoid", "mixed"])
def test_humanoid_and_mixed_matches_pass_the_pettingzoo_checks(robot):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parallel_api_test(humanoid_match(robot, max_cycles=60), num_cycles=60)
    parallel_seed_test(lambda: humanoid_match(robot, max_cycles=60), num_cycles=60)


# ----------------------------------------------------------------------------------------
# Seeding
# ----------------------------------------------------------------------------------------


def keeper_rollout(env, seed, steps=120):
    """Observations, rewards and the infos' truth and estimate of a seeded random episode
    (reset on its end), flattened into one array."""
    obs, info = env.reset(seed=seed)
    env.action_space.seed(seed)
    out = [obs, *_truth_and_estimate(info)]
    for _ in range(steps):
        obs, r, term, trunc, info = env.step(env.action_space.sample())
        out += [obs, [r], *_truth_and_estimate(info)]
        if term or trunc:
            obs, info = env.reset()
            out += [obs, *_truth_and_estimate(info)]
    return np.concatenate([np.ravel(np.asarray(x, dtype=np.float64)) for x in out])


def _truth_and_estimate(info):
    out = []
    for key in ("truth", "estimate"):
        d = info[key]
        out += [d["ball_position"], d["ball_velocity"], [d["ball_height"], d["time"]]]
        for name in sorted(d["robot_pose"]):
            out += [d["robot_pose"][name], d["robot_velocity"][name]]
    return out


def test_humanoid_goalkeeper_same_seed_same_perceived_episode():
    a, b = keeper(), keeper()
    first = keeper_rollout(a, 7)
    np.testing.assert_array_equal(first, keeper_rollout(b, 7))
    keeper_rollout(a, 3, steps=37)  # another history in between changes nothing
    np.testing.assert_array_equal(first, keeper_rollout(a, 7))
    other = keeper_rollout(a, 8)
    assert first.shape != other.shape or not np.array_equal(first, other)


def test_humanoid_shots_and_ball_do_not_depend_on_the_observation_mode():
    """Sensors, radio and estimators draw from their own streams: the seeded shots, and the
    ball's true path until the (standing) keeper touches it, are the same in every mode."""
    shots, paths = {}, {}
    for mode in ("truth", "raw", "perceived"):
        env = keeper(mode)
        shots[mode] = [env.reset(seed=s)[1]["shot"] for s in range(4)]
        _, info = env.reset(seed=1)
        path = [info["truth"]["ball_position"].copy()]
        for _ in range(150):
            _, _, term, _, info = env.step(np.zeros(6, np.float32))
            if term or info["keeper_touched"]:
                break
            path.append(info["truth"]["ball_position"].copy())
        paths[mode] = np.array(path)
    assert shots["truth"] == shots["raw"] == shots["perceived"]
    n = min(len(p) for p in paths.values())
    assert n > 30  # the ball has been shot and has rolled for a while
    for mode in ("raw", "perceived"):
        np.testing.assert_array_equal(paths[mode][:n], paths["truth"][:n])


def match_rollout(env, seed, steps=60):
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(steps):
        obs, rew, _, _, infos = env.step({a: rng.uniform(-1, 1, 6) for a in env.agents})
        for a in env.possible_agents:
            out += [obs[a], [rew[a]], *_truth_and_estimate(infos[a])]
        if not env.agents:
            break
    return np.concatenate([np.ravel(np.asarray(x, dtype=np.float64)) for x in out])


@pytest.mark.parametrize("robot", ["humanoid", MIXED], ids=["humanoid", "mixed"])
def test_match_same_seed_same_perceived_episode(robot):
    """PettingZoo's seed test stops after one step; this one compares whole episodes."""
    env = humanoid_match(robot, max_cycles=100)
    first = match_rollout(env, 11)
    match_rollout(env, 5, steps=20)
    np.testing.assert_array_equal(first, match_rollout(env, 11))
    np.testing.assert_array_equal(first, match_rollout(humanoid_match(robot, max_cycles=100), 11))
    assert not np.array_equal(first, match_rollout(env, 12))


# ----------------------------------------------------------------------------------------
# Spaces and info
# ----------------------------------------------------------------------------------------


def test_humanoid_spaces_have_the_ssl_shapes():
    hum, ssl = keeper(), gym.make("soccer_env/Goalkeeper-v0")
    assert hum.observation_space.shape == ssl.observation_space.shape == (19,)
    assert hum.action_space.shape == ssl.action_space.shape == (6,)
    obs, _ = hum.reset(seed=0)
    assert hum.observation_space.contains(obs)
    ssl_match = soccer_env.parallel_env(blue=2, yellow=2)
    for robot in ("humanoid", MIXED):
        env = humanoid_match(robot)
        obs, _ = env.reset(seed=0)
        for a in env.possible_agents:
            assert env.observation_space(a).shape == ssl_match.observation_space(a).shape
            assert env.action_space(a).shape == ssl_match.action_space(a).shape == (6,)
            assert env.observation_space(a).contains(obs[a])


def test_robot_state_reports_every_humanoid():
    env = keeper(mates=2)
    _, info = env.reset(seed=0)
    for _ in range(2):
        assert set(info["robot_state"]) == {"blue_0", "blue_1", "blue_2"}
        for state in info["robot_state"].values():
            assert set(state) == ROBOT_STATE_KEYS
            assert len(state["sway"]) == 2 and len(state["odometry"]) == 3
            assert state["fallen"] is False and state["falls"] == 0
        _, _, _, _, info = env.step(np.array([1, 0, 0, 0, 0, 0], np.float32))
    assert info["robot_state"]["blue_0"]["odometry"][0] > 0.0  # walking forward
    _, ssl_info = gym.make("soccer_env/Goalkeeper-v0").reset(seed=0)
    assert "robot_state" not in ssl_info
    env = humanoid_match(MIXED)
    _, infos = env.reset(seed=0)
    _, _, _, _, infos = env.step({a: np.zeros(6) for a in env.agents})
    for a in env.agents:
        assert set(infos[a]["robot_state"]) == {"yellow_0", "yellow_1"}
        for state in infos[a]["robot_state"].values():
            assert set(state) == ROBOT_STATE_KEYS


def test_a_humanoid_agent_sees_its_own_belief():
    """In perceived mode each humanoid has its own belief (its own localization, camera and
    the radio's news); SSL team-mates share the overhead vision's."""
    env = humanoid_match(max_cycles=100)
    obs, infos = env.reset(seed=3)
    names = env.builder.names
    for _ in range(60):
        obs, _, _, _, infos = env.step({a: np.r_[0.5, 0.0, 0.2, 0.0, 0.0, 0.0]
                                        for a in env.agents})
    b0, b1 = infos["blue_0"]["estimate"], infos["blue_1"]["estimate"]
    truth = infos["blue_0"]["truth"]
    assert not np.array_equal(b0["robot_pose"]["blue_0"], b1["robot_pose"]["blue_0"])
    assert not np.array_equal(b0["ball_position"], b1["ball_position"])
    for a in ("blue_0", "blue_1"):
        own = infos[a]["estimate"]["robot_pose"][a]
        assert np.hypot(*(own[:2] - truth["robot_pose"][a][:2])) < 0.3
        # The observation is built from the agent's own belief (blue plays in field frame).
        assert obs[a][names.index("self.x")] == pytest.approx(own[0], abs=1e-5)
        assert obs[a][names.index("self.y")] == pytest.approx(own[1], abs=1e-5)
    mixed = humanoid_match(MIXED)
    mixed.reset(seed=3)
    for _ in range(30):
        _, _, _, _, infos = mixed.step({a: np.zeros(6) for a in mixed.agents})
    assert infos["blue_0"]["estimate"] is infos["blue_1"]["estimate"]  # one vision
    assert not np.array_equal(infos["yellow_0"]["estimate"]["ball_position"],
                              infos["yellow_1"]["estimate"]["ball_position"])
    truth_match = humanoid_match(obs_mode="truth")
    truth_match.reset(seed=3)
    _, _, _, _, infos = truth_match.step({a: np.zeros(6) for a in truth_match.agents})
    for a in truth_match.agents:
        assert infos[a]["estimate"] is infos[a]["truth"]


# ----------------------------------------------------------------------------------------
# The head
# ----------------------------------------------------------------------------------------


def test_head_action_moves_the_head_and_auto_ignores_it():
    spec = soccer_env.presets.robot("humanoid")
    pan = 0.5 * spec.head_pan_limit
    mid, half = (0.5 * (spec.head_tilt_max + spec.head_tilt_min),
                 0.5 * (spec.head_tilt_max - spec.head_tilt_min))
    tilt = mid + 0.25 * half
    action = np.array([0, 0, 0, 0, 0.5, 0.25], np.float32)
    env = keeper(head="action", shots={"delay": (3.0, 3.0)})
    _, info = env.reset(seed=0)
    pans = [info["robot_state"]["blue_0"]["pan"]]
    for _ in range(40):
        _, _, _, _, info = env.step(action)
        pans.append(info["robot_state"]["blue_0"]["pan"])
    # The servo turns at most at its speed, then holds the commanded angle.
    step = spec.head_speed * env.unwrapped.world.control_dt
    assert np.all(np.abs(np.diff(pans)) <= step + 1e-12)
    assert abs(pans[0] - pan) > 0.3
    assert pans[-1] == pytest.approx(pan)
    assert info["robot_state"]["blue_0"]["tilt"] == pytest.approx(tilt)
    auto = keeper(head="auto", shots={"delay": (3.0, 3.0)})
    auto.reset(seed=0)
    for _ in range(40):
        _, _, _, _, info = auto.step(action)
    assert abs(info["robot_state"]["blue_0"]["pan"] - pan) > 0.3
    # In a match, every agent's head follows its own action.
    match = humanoid_match(head="action")
    match.reset(seed=0)
    pans = dict(zip(match.possible_agents, (-0.6, -0.2, 0.2, 0.6)))
    for _ in range(40):
        _, _, _, _, infos = match.step({a: np.r_[0, 0, 0, 0, pans[a], 0.0] for a in match.agents})
    for a, p in pans.items():
        assert infos[a]["robot_state"][a]["pan"] == pytest.approx(p * spec.head_pan_limit)


@pytest.mark.parametrize("obs_mode", ["truth", "perceived"])
def test_auto_head_turns_towards_the_ball(obs_mode):
    """A static ball well to the keeper's left; the keeper's head, turned away to its right
    after the reset, pans back to the ball and stays on it."""
    shots = {"delay": (3.0, 3.0), "x_range": (-2.5, -2.5), "y_range": (2.0, 2.0)}
    env = keeper(obs_mode, head="auto", shots=shots)
    env.reset(seed=0)
    env.unwrapped.world.walk.pan[0] = -1.0
    errors = []
    for _ in range(120):
        _, _, _, _, info = env.step(np.zeros(6, np.float32))
        k = info["truth"]["robot_pose"]["blue_0"]
        b = info["truth"]["ball_position"]
        bearing = math.remainder(math.atan2(b[1] - k[1], b[0] - k[0]) - k[2], 2 * math.pi)
        errors.append(abs(info["robot_state"]["blue_0"]["pan"] - bearing))
    assert bearing > 0.6 and errors[0] > 1.5
    # On the ball within half a second, and after that bar short glances for landmarks.
    assert np.median(errors[30:]) < 0.05
    assert np.mean(np.array(errors[30:]) < 0.1) > 0.8


# ----------------------------------------------------------------------------------------
# Rendering
# ----------------------------------------------------------------------------------------


def test_rgb_array_rendering_of_humanoids():
    pytest.importorskip("pygame")
    env = keeper(render_mode="rgb_array", render_width=480)
    env.reset(seed=0)
    env.step(np.array([0, 0, 0, -1, 0, 0], np.float32))  # a dive: the lying body is drawn
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[1:] == (480, 3)
    assert frame.std() > 0
    for robot in ("humanoid", MIXED):
        match = humanoid_match(robot, render_mode="rgb_array", render_width=320)
        match.reset(seed=0)
        frame = match.render()
        assert frame.dtype == np.uint8 and frame.shape[1:] == (320, 3) and frame.std() > 0
