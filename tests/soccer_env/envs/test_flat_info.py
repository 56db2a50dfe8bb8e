"""``info_mode="flat"``: numbers only, the same keys at every reset and step, and the same
facts as the full infos."""

import math
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from pettingzoo.test import api_test, parallel_api_test

import soccer_env
from soccer_env.envs.flat_info import COMMON_KEYS, EVENT_CODES, INFO_MODES, OUTCOME_CODES

GYM_CASES = [
    ("soccer_env/Goalkeeper-v0", {}),
    ("soccer_env/Goalkeeper-v0", {"obs_mode": "perceived", "perception": "harsh",
                                  "shaping": {"intercept": 1.0, "action_cost": 0.1}}),
    ("soccer_env/Goalkeeper-v0", {"robot": "humanoid", "obs_mode": "perceived", "mates": 1}),
    ("soccer_env/Shootout-v0", {"obs_mode": "raw", "perception": "realistic"}),
    ("soccer_env/Shootout-v0", {"robot": "humanoid"}),
]
MATCH_CASES = [
    {"blue": 2, "yellow": 2, "obs_mode": "perceived", "perception": "harsh",
     "shaping": {"ball_progress": 1.0}},
    {"blue": 1, "yellow": 1, "robot": {"blue": "ssl", "yellow": "humanoid"},
     "field": "humanoid-kid", "obs_mode": "perceived"},
]


def _check_flat(info, keys):
    assert list(info) == list(keys)
    for key, value in info.items():
        assert type(value) is np.float64 and isinstance(value, float), (key, value)
        assert math.isfinite(value), (key, value)


@pytest.mark.parametrize("env_id,kwargs", GYM_CASES)
def test_gym_flat_keys_fixed_over_episodes(env_id, kwargs):
    env = gym.make(env_id, info_mode="flat", **kwargs)
    keys = env.unwrapped.flat_info_keys
    assert keys[:len(COMMON_KEYS)] == COMMON_KEYS and len(set(keys)) == len(keys)
    rng = np.random.default_rng(0)
    for seed in range(2):
        obs, info = env.reset(seed=seed)
        _check_flat(info, keys)
        assert info["outcome"] == 0.0 and info["is_success"] == 0.0
        for _ in range(600):
            obs, reward, terminated, truncated, info = env.step(
                rng.uniform(-1, 1, 6).astype(np.float32))
            _check_flat(info, keys)
            total = sum(v for k, v in info.items() if k.startswith("reward_"))
            assert reward == pytest.approx(total)
            if terminated or truncated:
                break
        assert (info["outcome"] != 0.0) == terminated


@pytest.mark.parametrize("env_id,kwargs", GYM_CASES[:2] + GYM_CASES[3:4])
def test_gym_flat_matches_full_info(env_id, kwargs):
    """The same seed and actions give the same facts in both modes."""
    full = gym.make(env_id, **kwargs)
    flat = gym.make(env_id, info_mode="flat", **kwargs)
    actions = np.random.default_rng(1).uniform(-1, 1, (600, 6)).astype(np.float32)
    for seed in (3, 4):
        (o1, i1), (o2, i2) = full.reset(seed=seed), flat.reset(seed=seed)
        for action in actions:
            np.testing.assert_array_equal(o1, o2)
            truth, est = i1["truth"], i1["estimate"]
            assert i2["time"] == truth["time"]
            assert (i2["truth_ball_x"], i2["truth_ball_y"]) == tuple(truth["ball_position"])
            assert i2["truth_ball_z"] == truth["ball_height"]
            assert (i2["truth_robot_x"], i2["truth_robot_y"], i2["truth_robot_theta"]) == \
                tuple(truth["robot_pose"]["blue_0"])
            assert (i2["estimate_ball_vx"], i2["estimate_ball_vy"]) == \
                tuple(est["ball_velocity"])
            assert (i2["estimate_robot_x"], i2["estimate_robot_y"],
                    i2["estimate_robot_theta"]) == tuple(est["robot_pose"]["blue_0"])
            assert i2["ball_error"] == pytest.approx(
                np.hypot(*(est["ball_position"] - truth["ball_position"])))
            for term, value in i1["reward_terms"].items():
                assert i2[f"reward_{term}"] == value
            assert i2["outcome"] == OUTCOME_CODES[i1["outcome"]]
            assert i2["is_success"] == float(i1.get("is_success", False))
            assert i2["keeper_touched"] == float(i1["keeper_touched"])
            o1, r1, t1, u1, i1 = full.step(action)
            o2, r2, t2, u2, i2 = flat.step(action)
            assert (r1, t1, u1) == (r2, t2, u2)
            if t1 or u1:
                break
        assert i2["outcome"] == OUTCOME_CODES[i1["outcome"]]
        assert i2["is_success"] == float(i1.get("is_success", False))


def test_goalkeeper_flat_shot_entries():
    env = gym.make("soccer_env/Goalkeeper-v0", info_mode="flat")
    full = gym.make("soccer_env/Goalkeeper-v0")
    for seed in range(5):
        info = env.reset(seed=seed)[1]
        shot = full.reset(seed=seed)[1]["shot"]
        assert info["shot_speed"] == shot["speed"]
        assert info["shot_chip"] == float(shot["chip"])
        assert info["shot_fired"] == float(shot["delay"] <= 0.0)


def test_outcome_codes_cover_every_outcome():
    assert set(OUTCOME_CODES) == {"", "goal", "stopped", "cleared", "out", "saved"}
    assert set(EVENT_CODES) == {"", "goal", "touch", "goal_line", "over_bar", "invalid_goal"}
    assert OUTCOME_CODES[""] == 0 == EVENT_CODES[""]
    assert len(set(OUTCOME_CODES.values())) == len(OUTCOME_CODES)


@pytest.mark.parametrize("env_id,kwargs", [GYM_CASES[0], GYM_CASES[3]])
def test_gym_flat_passes_check_env(env_id, kwargs):
    env = gym.make(env_id, info_mode="flat", **kwargs)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped, skip_render_check=True)


@pytest.mark.parametrize("kwargs", MATCH_CASES)
def test_match_flat_keys_fixed_for_every_agent(kwargs):
    env = soccer_env.parallel_env(info_mode="flat", max_cycles=150, **kwargs)
    keys = env.flat_info_keys
    obs, infos = env.reset(seed=0)
    assert set(infos) == set(env.agents)
    for info in infos.values():
        _check_flat(info, keys)
    while env.agents:
        actions = {a: env.action_space(a).sample() for a in env.agents}
        obs, rewards, terminations, truncations, infos = env.step(actions)
        for a, info in infos.items():
            _check_flat(info, keys)
            assert rewards[a] == pytest.approx(
                sum(v for k, v in info.items() if k.startswith("reward_")))
        names = env.possible_agents
        assert all(infos[a]["score_blue"] == infos[names[0]]["score_blue"] for a in infos)


def test_match_flat_matches_full_info():
    kwargs = {"blue": 2, "yellow": 1, "obs_mode": "raw", "perception": "harsh",
              "max_cycles": 100}
    full = soccer_env.parallel_env(**kwargs)
    flat = soccer_env.parallel_env(info_mode="flat", **kwargs)
    (_, i1), (_, i2) = full.reset(seed=5), flat.reset(seed=5)
    rng = np.random.default_rng(2)
    while full.agents:
        for a in full.agents:
            truth, est = i1[a]["truth"], i1[a]["estimate"]
            assert (i2[a]["truth_robot_x"], i2[a]["truth_robot_y"],
                    i2[a]["truth_robot_theta"]) == tuple(truth["robot_pose"][a])
            assert (i2[a]["estimate_ball_x"], i2[a]["estimate_ball_y"]) == \
                tuple(est["ball_position"])
            assert (i2[a]["estimate_robot_x"], i2[a]["estimate_robot_y"]) == \
                tuple(est["robot_pose"][a][:2])
            assert i2[a]["event"] == EVENT_CODES[i1[a]["event"]]
            assert (i2[a]["score_blue"], i2[a]["score_yellow"]) == \
                (i1[a]["score"]["blue"], i1[a]["score"]["yellow"])
            for term, value in i1[a]["reward_terms"].items():
                assert i2[a][f"reward_{term}"] == value
        actions = {a: rng.uniform(-1, 1, 6) for a in full.agents}
        _, r1, _, _, i1 = full.step(actions)
        _, r2, _, _, i2 = flat.step(actions)
        assert r1 == r2


def test_match_flat_passes_pettingzoo_api_tests():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parallel_api_test(soccer_env.parallel_env(blue=2, yellow=2, info_mode="flat",
                                                  match_duration=3.0), num_cycles=200)
    aec = soccer_env.env(blue=1, yellow=2, info_mode="flat", max_cycles=60)
    api_test(aec, num_cycles=100)
    aec.reset(seed=0)
    keys = aec.unwrapped.flat_info_keys
    for agent in aec.agent_iter(max_iter=90):
        _, _, term, trunc, info = aec.last()
        _check_flat(info, keys)
        aec.step(None if term or trunc else aec.action_space(agent).sample())


@pytest.mark.parametrize("make", [
    lambda **kw: gym.make("soccer_env/Goalkeeper-v0", **kw),
    lambda **kw: gym.make("soccer_env/Shootout-v0", **kw),
    lambda **kw: soccer_env.parallel_env(blue=1, yellow=1, **kw),
    lambda **kw: soccer_env.env(blue=1, yellow=1, **kw),
])
@pytest.mark.parametrize("bad", ["nested", "FLAT", None, 1])
def test_info_mode_is_checked(make, bad):
    with pytest.raises(ValueError, match=r"info_mode must be one of \['full', 'flat'\]"):
        make(info_mode=bad)


def test_info_mode_default_is_full():
    assert INFO_MODES == ("full", "flat")
    env = gym.make("soccer_env/Goalkeeper-v0")
    assert env.unwrapped.info_mode == "full"
    assert isinstance(env.reset(seed=0)[1]["truth"], dict)


def _nones(value, path="info"):
    """The paths of every None in a (nested) info."""
    if value is None:
        return [path]
    if isinstance(value, dict):
        return [p for k, v in value.items() for p in _nones(v, f"{path}[{k!r}]")]
    if isinstance(value, (list, tuple)):
        return [p for k, v in enumerate(value) for p in _nones(v, f"{path}[{k}]")]
    return []


@pytest.mark.parametrize("env_id,kwargs", GYM_CASES[:3] + [GYM_CASES[4]])
def test_full_infos_hold_no_none(env_id, kwargs):
    """The full infos of every step hold no None (libraries that turn infos into arrays read
    it as NaN): ``outcome`` is ``""`` until the episode's end, the estimate has values from
    the first step (before any track)."""
    env = gym.make(env_id, max_episode_steps=60, **kwargs)
    info = env.reset(seed=1)[1]
    assert info["outcome"] == "" and not _nones(info)
    rng = np.random.default_rng(1)
    for _ in range(120):
        action = rng.uniform(-1, 1, 6).astype(np.float32)
        _, _, terminated, truncated, info = env.step(action)
        assert not _nones(info), _nones(info)
        assert bool(info["outcome"]) == terminated
        if terminated or truncated:
            info = env.reset()[1]
            assert not _nones(info)


@pytest.mark.parametrize("kwargs", [MATCH_CASES[1],
                                    {"blue": 3, "yellow": 3, "game": "ssl-2025-div-b"}])
def test_match_infos_hold_no_none(kwargs):
    """The match's per-agent infos: ``event`` is ``""`` at a step where nothing happened, and
    the game flow's state says "none" with ``""`` (no team) and ``()`` (no next command, no
    designated position)."""
    env = soccer_env.parallel_env(max_cycles=150, **kwargs)
    infos = env.reset(seed=2)[1]
    assert not _nones(infos) and infos["blue_0"]["event"] == ""
    rng = np.random.default_rng(2)
    seen = set()
    while env.agents:
        infos = env.step({a: rng.uniform(-1, 1, 6) for a in env.agents})[4]
        assert not _nones(infos), _nones(infos)
        seen.add(infos["blue_0"]["event"])
        if "game" in infos["blue_0"]:
            g = infos["blue_0"]["game"]
            seen.update((g["command_team"], g["next_command"], g["designated"]))
    assert "" in seen
    if "game" in kwargs:
        assert () in seen
