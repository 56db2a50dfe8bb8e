"""Shootout-v0: an attacker against the scripted keeper, on the same core as the others."""

import math
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import soccer_env  # noqa: F401  (registers the environments)
from soccer_env.envs.shootout import ShootoutEnv, ShootoutStart

STILL = np.zeros(6, np.float32)


def test_registered_with_its_time_limit_and_passes_check_env():
    env = gym.make("soccer_env/Shootout-v0")
    assert env.spec.max_episode_steps == 600
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped)
        check_env(gym.make("soccer_env/Shootout-v0", robot="humanoid-2012",
                           obs_mode="perceived").unwrapped, skip_render_check=True)


def test_layout_shows_the_keeper_as_the_opponent():
    env = ShootoutEnv()
    obs, info = env.reset(seed=3)
    names = env.builder.names
    assert obs.shape == (25,) and len(names) == 25
    assert names[11:17] == tuple(f"opp0.{e}" for e in ("dx", "dy", "cos", "sin", "vx", "vy"))
    # Truth mode: the keeper's relative position in the attacker's body frame.
    me, keeper = info["truth"]["robot_pose"]["blue_0"], info["truth"]["robot_pose"]["yellow_0"]
    c, s = math.cos(me[2]), math.sin(me[2])
    dx, dy = keeper[0] - me[0], keeper[1] - me[1]
    assert obs[11:13] == pytest.approx([c * dx + s * dy, c * dy - s * dx], abs=1e-5)


def test_seeded_starts_in_front_of_the_goal():
    env = ShootoutEnv()
    starts = []
    for seed in range(20):
        _, info = env.reset(seed=seed)
        start = info["start"]
        starts.append(start["ball"])
        hx = env.field.half_length
        d = math.hypot(hx - start["ball"][0], start["ball"][1])
        assert env.start.distances(env.field)[0] <= d <= env.start.distances(env.field)[1]
        assert info["truth"]["robot_pose"]["yellow_0"][0] > hx - 0.2  # on its goal line
        # The attacker faces the ball.
        ax, ay, ath = info["truth"]["robot_pose"]["blue_0"]
        bx, by = start["ball"]
        assert math.remainder(math.atan2(by - ay, bx - ax) - ath, 2 * math.pi) == \
            pytest.approx(0.0, abs=1e-9)
    assert len(set(starts)) == 20
    _, again = env.reset(seed=7)
    _, first = ShootoutEnv().reset(seed=7)
    assert again["start"] == first["start"]


def roll(env, vx, vy, x=None, y=0.0, steps=300):
    """Send the ball from ``(x, y)`` with velocity ``(vx, vy)``; the attacker stands."""
    w = env.world
    w.set_robot(0, -1.0, -1.5, 0.0)  # out of the way
    w.set_ball(x if x is not None else env.field.half_length - 1.5, y, vx, vy, sliding=True)
    for _ in range(steps):
        obs, reward, term, trunc, info = env.step(STILL)
        if term:
            return reward, info
    return None, info


def test_a_goal_scores_and_ends_the_episode():
    env = ShootoutEnv()
    env.reset(seed=0)
    # A hard shot into the corner the keeper does not stand in.
    keeper_y = env.world.robot_array()[1, 1]
    side = -1.0 if keeper_y > 0 else 1.0
    hx, gw = env.field.half_length, env.field.goal_width
    target = (hx, side * (0.5 * gw - 0.05))
    x0 = hx - 0.6
    v = 6.0
    d = math.hypot(target[0] - x0, target[1])
    reward, info = roll(env, v * (target[0] - x0) / d, v * target[1] / d, x=x0)
    assert info["outcome"] == "goal" and info["is_success"]
    assert reward == 1.0 and info["reward_terms"]["outcome"] == 1.0


def test_the_keeper_saves_a_slow_shot_at_it():
    env = ShootoutEnv()
    env.reset(seed=0)
    ky = float(env.world.robot_array()[1, 1])
    reward, info = roll(env, 1.5, 0.0, y=ky)
    assert info["outcome"] == "saved" and not info["is_success"]
    assert info["keeper_touched"] and reward == -1.0


def test_a_ball_over_the_touch_line_is_out():
    env = ShootoutEnv()
    env.reset(seed=0)
    reward, info = roll(env, 0.0, 3.0, x=0.5)
    assert info["outcome"] == "out" and reward == -1.0


def test_same_seed_same_episode_in_every_mode():
    for kwargs in ({}, {"obs_mode": "perceived"}, {"obs_mode": "raw", "perception": "harsh"},
                   {"robot": "humanoid-2012", "obs_mode": "perceived"}):
        runs = []
        for _ in range(2):
            env = gym.make("soccer_env/Shootout-v0", **kwargs)
            env.action_space.seed(0)
            obs, _ = env.reset(seed=11)
            seq = [obs]
            for _ in range(60):
                obs, r, term, trunc, _ = env.step(env.action_space.sample())
                seq.append(obs)
                if term:
                    break
            runs.append(np.array(seq))
        assert np.array_equal(*runs), kwargs


def test_the_keeper_plays_from_its_own_perception():
    """In perceived mode the keeper acts on its team's belief, not on the truth: its moves
    differ from those it makes in truth mode."""
    def keeper_path(mode):
        env = ShootoutEnv(obs_mode=mode, perception="harsh")
        env.reset(seed=2)
        env.world.set_ball(env.field.half_length - 2.0, 0.4, 2.0, -0.3, sliding=True)
        return np.array([env.step(STILL)[4]["truth"]["robot_pose"]["yellow_0"][1]
                         for _ in range(40)])

    assert not np.allclose(keeper_path("truth"), keeper_path("perceived"))


def test_shaping_terms_are_named_and_off_by_default():
    env = ShootoutEnv()
    env.reset(seed=0)
    _, reward, _, _, info = env.step(STILL)
    assert set(info["reward_terms"]) == {"outcome", "ball_progress", "ball_distance",
                                         "action_cost"}
    assert reward == 0.0
    env = ShootoutEnv(shaping={"ball_distance": 1.0})
    env.reset(seed=0)
    _, reward, _, _, info = env.step(STILL)
    assert reward == info["reward_terms"]["ball_distance"] < 0.0


def test_renders_both_robots():
    pytest.importorskip("pygame")
    env = ShootoutEnv(render_mode="rgb_array", render_width=320, robot="humanoid-2012",
                      obs_mode="perceived")
    env.reset(seed=0)
    frame = env.render()
    assert frame.ndim == 3 and frame.shape[1] == 320 and frame.dtype == np.uint8


@pytest.mark.parametrize("kwargs,match", [
    ({"start": {"ball_angle": (-1.4, 1.4)}}, "must stay inside"),
    ({"start": {"ball_distance": (0.0, 1.0)}}, r"start.ball_distance must be"),
    ({"start": {"angle": 1}}, r"unknown start key\(s\) \['angle'\]"),
    ({"start": 3}, "start must be a ShootoutStart or a mapping"),
    ({"shaping": {"goals": 1}}, r"unknown shaping term"),
    ({"head": "eyes"}, "head must be one of"),
    ({"obs_mode": "x"}, "obs_mode must be one of"),
])
def test_bad_arguments_name_what_is_allowed(kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        ShootoutEnv(**kwargs)


def test_unknown_keyword_arguments_are_refused():
    with pytest.raises(TypeError, match="unknown keyword argument"):
        ShootoutEnv(shots={})


def test_bad_actions_are_refused_before_the_world_moves():
    env = ShootoutEnv(out_of_range_actions="raise")
    env.reset(seed=0)
    before = env.world.snapshot()
    for bad in (np.full(6, np.nan), np.full(6, 2.0), np.zeros(5)):
        with pytest.raises(ValueError, match="action"):
            env.step(bad)
    assert np.array_equal(env.world.snapshot().robots, before.robots)


def test_start_defaults_follow_the_field():
    start = ShootoutStart()
    for name in ("ssl-div-b", "ssl-div-a", "ssl-2012", "humanoid-2012", "humanoid-kid"):
        fld = soccer_env.presets.field(name)
        lo, hi = start.distances(fld)
        assert lo > math.hypot(fld.defense_depth, 0.5 * fld.defense_width)
        start.check_field(fld, 0.1)
