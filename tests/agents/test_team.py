"""The scripted team: it wins, plays both colours and every observation mode, keeps its roles."""

from __future__ import annotations

import math

import numpy as np
import pytest

import soccer_env
from agents.team import ScriptedTeam
from soccer_env.envs.keeper import ScriptedGoalkeeper

FIELD = soccer_env.presets.field("ssl-div-b")
HX = FIELD.half_length
R = soccer_env.presets.robot("ssl").radius


def idle_team(agents):
    return lambda obs: {a: np.zeros(6, np.float32) for a in agents}


def random_team(agents, seed):
    rng = np.random.default_rng(seed)
    return lambda obs: {a: rng.uniform(-1.0, 1.0, 6).astype(np.float32) for a in agents}


def make_team(kind, env, colour, seed):
    agents = [a for a in env.possible_agents if a.startswith(colour)]
    if kind == "scripted":
        return ScriptedTeam.for_env(env, colour)
    if kind == "idle":
        return idle_team(agents)
    return random_team(agents, seed + 1000)


def play(blue, yellow, kinds, seed, duration=20.0, **kwargs):
    """Play a whole match; return the score (blue, yellow). ``kinds`` = (blue's, yellow's)."""
    env = soccer_env.parallel_env(blue=blue, yellow=yellow, match_duration=duration, **kwargs)
    obs, _ = env.reset(seed=seed)
    teams = [make_team(k, env, c, seed) for k, c in zip(kinds, ("blue", "yellow"))]
    while env.agents:
        actions = {}
        for team in teams:
            actions.update(team(obs))
        obs, *_ = env.step(actions)
    return tuple(env.score)


def in_defense_area(x, y, sign=1.0):
    """Whether a field-frame point lies in the defense area of the team defending -sign x."""
    return sign * x < -HX + FIELD.defense_depth and abs(y) < 0.5 * FIELD.defense_width


# ----------------------------------------------------------------------------------------
# It wins
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("blue,yellow", [(1, 1), (3, 3),
                                         pytest.param(6, 6, marks=pytest.mark.slow)])
def test_scripted_team_beats_idle_and_random_teams_with_either_colour(blue, yellow):
    """Over 8 short matches (2 seeds x 2 colours x idle/random opponent) the scripted team
    wins every match, scores at least 1.5 goals per 20 s match and concedes almost nothing."""
    scored = conceded = 0
    for seed in (0, 1):
        for opponent in ("idle", "random"):
            for colour in ("blue", "yellow"):
                kinds = ("scripted", opponent) if colour == "blue" else (opponent, "scripted")
                b, y = play(blue, yellow, kinds, seed)
                gf, ga = (b, y) if colour == "blue" else (y, b)
                assert gf > ga, (opponent, colour, seed, (b, y))
                scored += gf
                conceded += ga
    assert scored >= 12
    assert conceded <= 2


def test_scripted_team_scores_on_perceived_observations():
    """The team reads only its observations: on the estimation stack's belief (noise,
    latency) it still beats idle and random teams."""
    b, y = play(3, 3, ("scripted", "idle"), seed=0, obs_mode="perceived")
    assert b >= 2 and y == 0
    b, y = play(3, 3, ("random", "scripted"), seed=1, obs_mode="perceived")
    assert y >= 2 and b == 0


def test_scripted_team_scores_on_raw_detections():
    """Raw detections (delayed, unfiltered, with very noisy ball velocities) make it weaker,
    but it still scores against an idle team."""
    scores = [play(1, 1, ("scripted", "idle"), seed=s, obs_mode="raw") for s in (0, 1)]
    assert sum(b for b, _ in scores) >= 2 and all(y == 0 for _, y in scores)


def test_same_seed_same_match_and_another_seed_another():
    def trajectory(seed):
        env = soccer_env.parallel_env(blue=2, yellow=2, match_duration=4.0,
                                      obs_mode="perceived")
        obs, _ = env.reset(seed=seed)
        blue, yellow = ScriptedTeam.for_env(env, "blue"), ScriptedTeam.for_env(env, "yellow")
        states, actions = [], []
        while env.agents:
            act = {**blue(obs), **yellow(obs)}
            actions.append(np.stack([act[a] for a in env.possible_agents]))
            obs, *_ = env.step(act)
            states.append(env.state())
        return np.array(states), np.array(actions)

    s1, a1 = trajectory(3)
    s2, a2 = trajectory(3)
    np.testing.assert_array_equal(s1, s2)
    np.testing.assert_array_equal(a1, a2)
    s3, _ = trajectory(4)
    assert not np.array_equal(s1, s3)


# ----------------------------------------------------------------------------------------
# Both colours: yellow reads its own team frame
# ----------------------------------------------------------------------------------------


def staged(blue, yellow, poses, ball, **kwargs):
    """A match reset, then every robot and the ball teleported (at rest); returns the env and
    fresh observations (after one idle step)."""
    env = soccer_env.parallel_env(blue=blue, yellow=yellow, match_duration=60.0,
                                  formation_jitter=0.0, **kwargs)
    env.reset(seed=0)
    env.world.place_all(np.array(poses, dtype=float), ball)
    env.restart_team = -1  # open play, not the kick-off drawn at reset
    obs, *_ = env.step({a: np.zeros(6, np.float32) for a in env.agents})
    return env, obs


def test_yellow_plays_the_mirror_image_of_blue():
    """In a point-symmetric position each yellow robot sees what its blue counterpart sees,
    and the yellow team does what the blue team does."""
    blue = [(-4.0, 0.3, 0.2), (-1.0, -0.8, 1.0), (-2.0, 1.5, -2.5)]
    yellow = [(-x, -y, math.remainder(h + math.pi, 2 * math.pi)) for x, y, h in blue]
    env, obs = staged(3, 3, blue + yellow, (0.0, 0.0))
    blue_team, yellow_team = ScriptedTeam.for_env(env, "blue"), ScriptedTeam.for_env(env, "yellow")
    ab, ay = blue_team(obs), yellow_team(obs)
    assert sorted(ab) == ["blue_0", "blue_1", "blue_2"]
    assert sorted(ay) == ["yellow_0", "yellow_1", "yellow_2"]
    for i in range(3):
        np.testing.assert_allclose(obs[f"yellow_{i}"], obs[f"blue_{i}"], atol=1e-4)
        np.testing.assert_allclose(ay[f"yellow_{i}"], ab[f"blue_{i}"], atol=1e-3)
    # Not trivially idle: someone drives and turns.
    assert np.abs(np.stack(list(ab.values()))[:, :3]).max() > 0.1


# ----------------------------------------------------------------------------------------
# Roles
# ----------------------------------------------------------------------------------------


def test_keeper_is_the_scripted_goalkeeper_outside_its_defense_area():
    """Robot 0 plays ScriptedGoalkeeper's action, bit for bit, whenever the ball is away
    from the defense area (blue and yellow)."""
    env = soccer_env.parallel_env(blue=3, yellow=3, match_duration=10.0)
    obs, _ = env.reset(seed=2)
    teams = {c: ScriptedTeam.for_env(env, c) for c in ("blue", "yellow")}
    keepers = {c: ScriptedGoalkeeper(env.field, env.ball_spec, env.robot_spec,
                                     env.builder.names_for(t))
               for t, c in enumerate(("blue", "yellow"))}
    compared = 0
    while env.agents:
        act = {**teams["blue"](obs), **teams["yellow"](obs)}
        bx = float(env.state()[0])
        for sign, colour in ((1.0, "blue"), (-1.0, "yellow")):
            if sign * bx > -HX + FIELD.defense_depth + 0.2:
                np.testing.assert_array_equal(act[f"{colour}_0"],
                                              keepers[colour](obs[f"{colour}_0"]))
                compared += 1
        obs, *_ = env.step(act)
    assert compared > 500


def test_formation_around_a_fixed_ball():
    """With the ball held in place (and kickers off), the keeper stands on its guard line on
    the ball's side, the nearest field player goes to the ball, and the four defenders walk
    round the ball to stand spread out between it and their goal, outside the defense
    area."""
    poses = [(-3.0, 1.0, 0.0), (1.0, 2.5, 0.0), (-1.0, 0.0, 0.0), (0.5, -2.0, 0.0),
             (-3.0, -2.5, 0.0), (0.0, 1.0, 0.0), (4.0, -2.8, math.pi)]
    ball = (-1.2, 0.8)
    env, obs = staged(6, 1, poses, ball)
    team = ScriptedTeam.for_env(env, "blue")
    idle = {"yellow_0": np.zeros(6, np.float32)}
    closest = np.full(6, np.inf)
    for _ in range(150):  # 2.5 s
        act = team(obs)
        for a in act.values():
            a[3] = 0.0
        obs, *_ = env.step({**act, **idle})
        robots = env.state()[6:].reshape(-1, 6)[:6]
        closest = np.minimum(closest, np.hypot(*(robots[:, :2] - ball).T))
        env.world.set_ball(*ball)
    guard_x = -HX + R + 0.05
    assert abs(robots[0, 0] - guard_x) < 0.05
    assert 0.0 < robots[0, 1] < 0.5 * FIELD.goal_width
    attacker = 2  # the nearest field player at the start
    assert closest[attacker] < 0.15
    defenders = [1, 3, 4, 5]
    assert closest[defenders].min() > 0.2  # they went round the ball, not through it
    d_ball = np.hypot(*(robots[:, :2] - ball).T)
    goal = np.array([-HX, 0.0])
    ball_to_goal = np.hypot(*(np.array(ball) - goal))
    for i in defenders:
        x, y = robots[i, :2]
        assert np.hypot(x - goal[0], y - goal[1]) < ball_to_goal - 0.3, i
        assert not in_defense_area(x, y), i
        assert d_ball[i] > 0.4, i
    gaps = [np.hypot(*(robots[i, :2] - robots[j, :2]))
            for i in defenders for j in defenders if i < j]
    assert min(gaps) > 0.3


def test_attacker_is_the_nearest_field_player_and_scores_past_an_idle_keeper():
    """The field player nearest the ball takes it and shoots past the keeper standing in the
    middle of the goal; its team-mates never touch the ball."""
    poses = [(-4.3, 0.0, 0.0), (-1.0, 2.0, 0.0), (1.0, -0.8, 0.0), (-2.0, -2.0, 0.0),
             (4.3, 0.0, math.pi), (3.5, 2.5, math.pi)]
    env, obs = staged(4, 2, poses, (1.6, -0.5))
    team = ScriptedTeam.for_env(env, "blue")
    idle = {a: np.zeros(6, np.float32) for a in ("yellow_0", "yellow_1")}
    touched = np.zeros(6, dtype=bool)
    for _ in range(240):
        obs, _, _, _, info = env.step({**team(obs), **idle})
        if info["blue_0"]["event"] is not None:
            break
        touched |= env.world.touched
    assert info["blue_0"]["event"] == "goal" and env.score == [1, 0]
    assert touched[2] and not touched[[0, 1, 3]].any()


def test_keeper_alone_clears_a_ball_resting_in_its_defense_area():
    poses = [(-4.3, 0.0, 0.0), (-2.5, 1.0, 0.0), (-2.0, -1.0, 0.0), (3.0, 2.5, math.pi)]
    env, obs = staged(3, 1, poses, (-4.0, 0.5))
    team = ScriptedTeam.for_env(env, "blue")
    idle = {"yellow_0": np.zeros(6, np.float32)}
    cleared = False
    for _ in range(240):
        obs, *_ = env.step({**team(obs), **idle})
        state = env.state()
        robots = state[6:].reshape(-1, 6)
        for i in (1, 2):
            assert not in_defense_area(*robots[i, :2]), (i, robots[i, :2])
        if not in_defense_area(*state[:2]):
            cleared = True
            break
    assert cleared
    assert env.world.last_touch == 0


# ----------------------------------------------------------------------------------------
# API
# ----------------------------------------------------------------------------------------


def test_call_and_batched_act_agree_and_stay_in_the_action_box():
    env = soccer_env.parallel_env(blue=3, yellow=2, match_duration=5.0)
    obs, _ = env.reset(seed=0)
    team = ScriptedTeam.for_env(env, "yellow")
    for _ in range(60):
        act = team(obs)
        assert sorted(act) == ["yellow_0", "yellow_1"]
        batch = team.act(np.stack([obs["yellow_0"], obs["yellow_1"]]))
        assert batch.dtype == np.float32 and batch.shape == (2, 6)
        np.testing.assert_array_equal(batch, np.stack([act["yellow_0"], act["yellow_1"]]))
        assert np.all(np.abs(batch) <= 1.0)
        obs, *_ = env.step({**act, **{f"blue_{i}": np.zeros(6, np.float32) for i in range(3)}})


def test_bad_input_raises_clear_errors():
    env = soccer_env.parallel_env(blue=2, yellow=0, match_duration=5.0)
    with pytest.raises(ValueError, match=r"team must be one of \['blue', 'yellow'\], got 'red'"):
        ScriptedTeam.for_env(env, "red")
    with pytest.raises(ValueError, match="yellow team of this match has no robots"):
        ScriptedTeam.for_env(env, "yellow")
    team = ScriptedTeam.for_env(env, "blue")
    obs, _ = env.reset(seed=0)
    with pytest.raises(ValueError, match=r"obs_batch must have shape \(2, "):
        team.act(obs["blue_0"][None])
    with pytest.raises(ValueError, match="team_size must be 1..11"):
        ScriptedTeam(env.field, env.ball_spec, env.robot_spec, env.builder.names, 0)
